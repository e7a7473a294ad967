//! Linear (midpoint) subdivision: the faces are cut as Loop or
//! Catmull-Clark cut them, and nothing moves. Every new vertex is the
//! midpoint of its edge or the centroid of its face; the old vertices stay
//! where they are, so the shape is kept exactly (a refinement, not a
//! smoothing: for more faces to edit, or a finer mesh to smooth later).
//!
//! **Counts** per level: [`MidpointFaces::Quads`] as Catmull-Clark
//! (V' = V + E + F, F' = Σ degrees), [`MidpointFaces::Triangles`] as Loop
//! (V' = V + E, F' = 4F).
//!
//! **Attributes** as in [`subdivision`](crate::algo::subdivision), with
//! every vertex column linear (there is no smooth stencil): corners
//! face-varying, face values split among the children, edge values to
//! both halves.
//!
//! **Built wholesale** by the face-splitting level Loop and Catmull-Clark
//! run on, without their smooth rules: the positions, like every vertex
//! column, follow the linear plan (see
//! [`subdivision`](crate::algo::subdivision)). Through [`subdivide`]
//! with [`Scheme::Midpoint`], the faces are cut as
//! [`SubdivisionOptions::midpoint_faces`] says; the boundary and corner
//! options change nothing (nothing moves), and a crease column is refused.
//!
//! ```
//! use meshloom::algo::{midpoint_subdivide, MidpointOptions, Progress};
//! let mut cube = meshloom::shapes::cube();
//! midpoint_subdivide(&mut cube, &MidpointOptions::default().levels(2), Progress::none())?;
//! assert_eq!(cube.face_count(), 6 * 16);
//! // Nothing moved off the cube.
//! for v in cube.vertices() {
//!     let p = cube.position(v)?;
//!     assert!(p.iter().any(|&c| c == 0.0 || c == 1.0));
//! }
//! # Ok::<(), meshloom::Error>(())
//! ```

use crate::algo::progress::Progress;
use crate::algo::subdivision::refine::CutRule;
use crate::algo::subdivision::split::{FaceSplit, Linear};
use crate::algo::subdivision::{subdivide, Scheme, SubdivisionOptions, SubdivisionReport};
use crate::error::Result;
use crate::mesh::Mesh;

pub use crate::algo::subdivision::MidpointFaces;

/// Options of [`midpoint_subdivide`]: the part of [`SubdivisionOptions`]
/// midpoint subdivision reads.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct MidpointOptions {
    /// Levels to apply (default 1).
    pub levels: u32,
    /// How faces are cut (default: by the mesh).
    pub faces: MidpointFaces,
    /// The most faces the result may have (as
    /// [`SubdivisionOptions::max_faces`];
    /// default [`DEFAULT_MAX_FACES`](crate::algo::DEFAULT_MAX_FACES)).
    pub max_faces: usize,
}

crate::choice::setters!(MidpointOptions {
    levels: u32,
    faces: MidpointFaces,
    max_faces: usize,
});

impl Default for MidpointOptions {
    fn default() -> Self {
        MidpointOptions {
            levels: 1,
            faces: MidpointFaces::Auto,
            max_faces: super::DEFAULT_MAX_FACES,
        }
    }
}

impl From<&MidpointOptions> for SubdivisionOptions {
    fn from(o: &MidpointOptions) -> SubdivisionOptions {
        SubdivisionOptions {
            levels: o.levels,
            midpoint_faces: o.faces,
            max_faces: o.max_faces,
            ..SubdivisionOptions::default()
        }
    }
}

/// Apply `options.levels` levels of linear subdivision: [`subdivide`]
/// with [`Scheme::Midpoint`].
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a face that is not a
/// triangle with [`MidpointFaces::Triangles`], or an interior vertex of
/// valence 2 between two triangles cut 1-to-4;
/// [`Error::Cancelled`](crate::Error::Cancelled). On any error the mesh is
/// exactly as it was.
///
/// ```
/// use meshloom::algo::{midpoint_subdivide, MidpointFaces, MidpointOptions, Progress};
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let opts = MidpointOptions::default().levels(1).faces(MidpointFaces::Quads);
/// midpoint_subdivide(&mut mesh, &opts, Progress::none())?;
/// assert_eq!((mesh.vertex_count(), mesh.face_count()), (4 + 6 + 4, 12));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn midpoint_subdivide(
    mesh: &mut Mesh,
    options: &MidpointOptions,
    progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    subdivide(mesh, Scheme::Midpoint, &options.into(), progress)
}

/// Midpoint subdivision with its cut rule decided.
pub(crate) struct Midpoint {
    rule: CutRule,
}

impl Midpoint {
    /// The cut of `faces` for `mesh`: `Auto` cuts triangles 1-to-4 when
    /// every face is one, everything else into quads (the first level
    /// decides: its result is all triangles or all quads).
    pub(crate) fn for_mesh(mesh: &Mesh, faces: MidpointFaces) -> Midpoint {
        let rule = match faces {
            MidpointFaces::Quads => CutRule::Quads,
            MidpointFaces::Triangles => CutRule::Triangles,
            MidpointFaces::Auto => {
                let all_triangles = mesh
                    .fids()
                    .all(|f| mesh.is_hole(f) || mesh.face_halfedges(f).count() == 3);
                if all_triangles {
                    CutRule::Triangles
                } else {
                    CutRule::Quads
                }
            }
        };
        Midpoint { rule }
    }
}

impl FaceSplit for Midpoint {
    const SCHEME: Scheme = Scheme::Midpoint;
    type Rules = Linear;

    fn cut(&self) -> CutRule {
        self.rule
    }

    fn rules(&self) -> Option<&Linear> {
        None
    }
}
