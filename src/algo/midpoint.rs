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
//! **Built wholesale**, sharing Loop's and Catmull-Clark's topology pass
//! (see [`subdivision`](crate::algo::subdivision)).
//!
//! ```
//! use meshloom::algo::{midpoint_subdivide, MidpointOptions, Progress};
//! let mut cube = meshloom::shapes::cube();
//! midpoint_subdivide(&mut cube, &MidpointOptions::levels(2), Progress::none())?;
//! assert_eq!(cube.face_count(), 6 * 16);
//! // Nothing moved off the cube.
//! for v in cube.vertices() {
//!     let p = cube.position(v)?;
//!     assert!(p.iter().any(|&c| c == 0.0 || c == 1.0));
//! }
//! # Ok::<(), meshloom::Error>(())
//! ```

use crate::algo::loop_subdivision::LoopMask;
use crate::algo::progress::Progress;
use crate::algo::subdivision::refine::{check_valence_two, refine, CutRule};
use crate::algo::subdivision::{
    finish_columns, run_levels, Growth, LevelReport, Levels, RefinePlans, SubdivisionReport,
    VertexData,
};
use crate::error::Result;
use crate::mesh::Mesh;

const ALGORITHM: &str = "midpoint_subdivide";

/// How [`midpoint_subdivide`] cuts the faces.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum MidpointFaces {
    /// Triangles 1-to-4 when every face is a triangle, quads otherwise.
    #[default]
    Auto,
    /// Every face into one quad per corner, around its centroid.
    Quads,
    /// Every triangle into four (other faces are refused).
    Triangles,
}

/// Options of [`midpoint_subdivide`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MidpointOptions {
    /// Levels to apply (default 1).
    pub levels: u32,
    /// How faces are cut (default: by the mesh).
    pub faces: MidpointFaces,
    /// The most faces the result may have (as
    /// [`SubdivisionOptions::max_faces`](crate::algo::SubdivisionOptions::max_faces);
    /// default [`DEFAULT_MAX_FACES`](crate::algo::DEFAULT_MAX_FACES)).
    pub max_faces: usize,
}

impl Default for MidpointOptions {
    fn default() -> Self {
        MidpointOptions {
            levels: 1,
            faces: MidpointFaces::Auto,
            max_faces: super::DEFAULT_MAX_FACES,
        }
    }
}

impl MidpointOptions {
    /// `levels` levels, faces cut by the mesh.
    pub fn levels(levels: u32) -> MidpointOptions {
        MidpointOptions {
            levels,
            ..MidpointOptions::default()
        }
    }
}

/// Apply `options.levels` levels of linear subdivision.
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
/// let opts = MidpointOptions { faces: MidpointFaces::Quads, ..MidpointOptions::levels(1) };
/// midpoint_subdivide(&mut mesh, &opts, Progress::none())?;
/// assert_eq!((mesh.vertex_count(), mesh.face_count()), (4 + 6 + 4, 12));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn midpoint_subdivide(
    mesh: &mut Mesh,
    options: &MidpointOptions,
    progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    mesh.as_one_step("Midpoint subdivision", |mesh| {
        midpoint_subdivide_run(mesh, options, progress)
    })
}

/// [`midpoint_subdivide`] itself, outside the journal's step.
fn midpoint_subdivide_run(
    mesh: &mut Mesh,
    options: &MidpointOptions,
    mut progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    let rule = match options.faces {
        MidpointFaces::Quads => CutRule::Quads,
        MidpointFaces::Triangles => CutRule::Triangles,
        MidpointFaces::Auto => {
            let all_triangles = mesh
                .fids()
                .all(|f| mesh.is_hole(f) || mesh.face_loop(f).count() == 3);
            if all_triangles {
                CutRule::Triangles
            } else {
                CutRule::Quads
            }
        }
    };
    let data = VertexData::default();
    run_levels(
        mesh,
        ALGORITHM,
        Levels {
            count: options.levels,
            growth: match rule {
                CutRule::Triangles => Growth::Four,
                _ => Growth::Corners,
            },
            max_faces: options.max_faces,
        },
        &mut progress,
        |parent, level, progress| {
            check_valence_two(parent, rule, ALGORITHM)?;
            let (r, topology) = refine(parent, rule, ALGORITHM, level, progress)?;
            // No smooth rules: the "smooth" plan is the linear one.
            let plans = RefinePlans::<LoopMask> {
                mesh: parent,
                r: &r,
                smooth: None,
            };
            let attrs = finish_columns(parent, &plans, None, &data, None);
            Ok((topology.into_mesh(attrs), LevelReport::default()))
        },
    )
}
