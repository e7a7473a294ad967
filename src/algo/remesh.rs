//! Isotropic remeshing (Botsch & Kobbelt 2004): make a triangle mesh's
//! edges all about one length (or a length that follows the curvature),
//! with valences near 6, while staying on the input surface.
//!
//! **What it does**, each of [`RemeshOptions::iterations`] times (default
//! 10), as pmp-library's `uniform_remeshing` / `adaptive_remeshing` and
//! CGAL's `isotropic_remeshing`:
//!
//! 1. *split* every edge longer than 4/3 of its target length `L` at its
//!    midpoint (both triangles beside it split in two);
//! 2. *collapse* every edge shorter than 4/5 `L` through the checked
//!    collapse operator (the link condition, no non-manifold result): two
//!    free vertices meet at the edge's midpoint (Botsch and Kobbelt), else
//!    (or when the midpoint would make an edge too long) the vertex of
//!    lower valence goes into the other; never when that would make an
//!    edge longer than 4/3 `L`;
//! 3. *flip* edges where that brings the four valences nearer their
//!    targets (6 inside, 4 on a boundary), unless a new triangle would
//!    turn over;
//! 4. *relax* each free vertex [`RemeshOptions::smoothing_steps`] times
//!    (default 5) towards the area-weighted centroid of its triangles,
//!    moved in its tangent plane only;
//! 5. *project* every vertex that moved back onto the input surface: the
//!    closest point on the input triangles, found through the shared
//!    [`FaceTree`](crate::query::FaceTree) built once over the input (the
//!    working copy is edited, the input is not), warm-started with the
//!    triangle each vertex was last projected onto.
//!
//! After the rounds, [`RemeshOptions::remove_caps`] (default on) flips
//! each edge opposite an angle over 170° where that lowers the largest
//! angle of its two triangles, as pmp-library does.
//!
//! **Quality.** With the default options at the mean edge length, 95 % or
//! more of the edges end within [4/5, 4/3] L on smooth shapes and on most
//! real meshes (`tests/remesh.rs` holds seven of them to it;
//! `BENCHMARKS.md` lists the share per mesh). The misses are edges
//! shorter than 4/5 L whose collapse would make an edge longer than
//! 4/3 L, or would collapse a tiny closed component.
//!
//! **Target length** ([`Sizing`]): uniform (a length, or by default the
//! input's mean edge length), or adaptive: from the largest absolute
//! principal curvature `κ` at each input vertex (smoothed over its
//! neighbours), the length `√(6εr − 3ε²)` (`r = 1/κ`, ε the tolerance) of
//! an equilateral triangle whose chord error on a circle of radius `r` is
//! ε, clamped to `[min, max]`; new vertices take the mean of their edge's
//! ends and projected vertices the value interpolated on the input.
//!
//! **Kept lines** (the shared vocabulary of
//! [`constraints`](super::constraints)). Boundaries, feature edges (faces
//! meeting at more than [`RemeshOptions::feature_angle`], or `true` in
//! [`RemeshOptions::features`]) and the seams of the corner columns being
//! resampled ([`RemeshOptions::seams`], UV seams) are *lines*. A sliding
//! line ([`Keep::Slide`], the default; feature lines always) is never
//! flipped, split only into line edges, and collapsed only along itself; a
//! vertex on exactly two line edges slides along its line (relaxed along
//! it, then projected onto the input's lines), and a vertex where lines
//! meet, end, or turn by more than the feature angle (45° without one),
//! the corner of a cube or a square, never moves. A locked line
//! ([`Keep::Lock`]) keeps every vertex and edge as it is; a free one
//! ([`Keep::Free`]) is like any other edge. A pinned vertex
//! ([`RemeshOptions::pinned`]) never moves and its edges are neither split
//! nor collapsed.
//!
//! **Attributes.** Every column follows the operators' rules (splits
//! interpolate, collapses merge into the survivor, flips copy corners), so
//! face and edge values such as material ids come out right. Vertex and
//! corner columns are then *resampled* from the input (by default every
//! one whose rule interpolates linearly, positions aside; see
//! [`Resample`]): each vertex's final position has a closest input
//! triangle and barycentric coordinates there, and the column's value is
//! interpolated from that triangle's three values, so UVs and colours do
//! not drift with the relaxation. A corner takes its value from the input
//! triangle under its vertex *on its own side of the seams*: the input
//! faces are grouped into islands per corner column (faces joined by edges
//! across which the column's corner values agree); when the triangle under
//! the vertex lies in another island than the triangle under the corner's
//! own face (at its centroid), the closest triangle of the face's island is
//! used instead. A seam therefore stays a seam and every UV stays within
//! its island's range.
//!
//! **All or nothing.** The remesher works on a copy of the mesh and hands
//! the result over at the end through the one door for wholesale rebuilds
//! (undo takes it back in one step); a cancelled ([`Progress`]) or failed
//! run leaves the mesh exactly as it was. Every input check comes first.
//!
//! **Cost.** O(n) per iteration for n vertices plus one closest-point
//! query per moved vertex (O(log n), a few box tests with the warm start);
//! memory: the copy of the mesh, the hierarchy (about 100 bytes an input
//! triangle) and about 60 bytes a vertex of working state.
//!
//! **Files.** `remesh.rs` holds the options, the report and the run;
//! `remesh/setup.rs` the checks and classification before any change;
//! `remesh/reference.rs` the input surface; `remesh/engine.rs` the working
//! state and the split, collapse, flip and cap passes; `remesh/relax.rs`
//! relaxation and projection; `remesh/resample.rs` the columns' resampling.
//! `BENCHMARKS.md` times it beside pmp-library and CGAL
//! (`uniform_remeshing`).
//!
//! ```
//! use meshloom::algo::remesh::{remesh, RemeshOptions, Sizing};
//! use meshloom::algo::Progress;
//! let mut mesh = meshloom::shapes::icosphere(3); // 642 vertices, unit radius
//! let options = RemeshOptions::default().sizing(Sizing::Uniform(0.1));
//! let report = remesh(&mut mesh, &options, Progress::none())?;
//! assert_eq!(report.iterations, 10);
//! assert!(report.edge_lengths.within > 0.8); // 84 % here within [4/5, 4/3] of 0.1
//! assert!(mesh.vertex_count() > 1000);
//! for v in mesh.vertices() {
//!     let p = mesh.position(v)?;
//!     let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
//!     assert!((r - 1.0).abs() < 0.01); // on the input's surface
//! }
//! assert_eq!(mesh.euler_characteristic(), 2);
//! mesh.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

mod engine;
mod reference;
mod relax;
mod resample;
mod setup;

use super::constraints::Constraints;
/// The line rule, shared by every algorithm: see [`Constraints`].
pub use super::constraints::Keep;
use super::subdivision::Counts;
use crate::attr::{EdgeAttr, VertexAttr};
use crate::error::{Error, Result};
// The remesher edits a working copy (a clone records nothing), so its
// crate-private doors run unrecorded; the run is one unit through replace_with.
use crate::mesh::Mesh;
use engine::Engine;
use setup::Setup;

use super::progress::Progress;

const ALGORITHM: &str = "remesh";

/// The target edge length.
#[derive(Copy, Clone, Debug, PartialEq, Default)]
pub enum Sizing {
    /// The mean length of the input's edges (default).
    #[default]
    MeanEdgeLength,
    /// This length everywhere.
    Uniform(f64),
    /// A length that follows the curvature: the largest an equilateral
    /// triangle can be while staying within `tolerance` of a circle of the
    /// surface's tightest curvature there, clamped to `[min_length,
    /// max_length]` (defaults: a quarter of and four times the input's mean
    /// edge length).
    Adaptive {
        /// The approximation error allowed (mesh units).
        tolerance: f64,
        /// The shortest target length.
        min_length: Option<f64>,
        /// The longest target length.
        max_length: Option<f64>,
    },
}

/// Which vertex and corner columns are resampled from the input at the end.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub enum Resample {
    /// Every vertex and corner (half-edge) column whose rule interpolates
    /// linearly (UVs, colours, normals), the positions aside (default).
    #[default]
    Linear,
    /// Only the columns of these names (vertex columns first, then corner
    /// columns); each must interpolate linearly.
    Columns(Vec<String>),
    /// None: the columns keep what the operators' rules gave them.
    Off,
}

/// Options of [`remesh`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct RemeshOptions {
    /// The target edge length (default: the input's mean edge length).
    pub sizing: Sizing,
    /// Split-collapse-flip-relax rounds (default 10).
    pub iterations: usize,
    /// Relaxation steps per round (default 5).
    pub smoothing_steps: usize,
    /// Project moved vertices back onto the input surface (default true).
    pub project: bool,
    /// Boundary loops (default [`Keep::Slide`]: boundary edges are split
    /// and collapsed along the boundary, boundary vertices slide along the
    /// input's boundary and corners stay; [`Keep::Lock`]: boundary vertices
    /// and edges stay as they are; [`Keep::Free`]: no constraint). See
    /// [`Constraints`].
    pub boundary: Keep,
    /// The seams of the corner columns being resampled (edges across which
    /// their values differ: UV seams), default [`Keep::Slide`]: each seam
    /// keeps its place and its polyline.
    pub seams: Keep,
    /// Edges whose faces meet at more than this dihedral angle (radians)
    /// are feature edges, kept as sliding lines; also the turn that makes a
    /// line's vertex a corner (45° without it). Default: none.
    pub feature_angle: Option<f64>,
    /// An edge column: edges whose value is `true` are feature edges.
    pub features: Option<EdgeAttr<bool>>,
    /// A vertex column: vertices whose value is `true` are pinned: they
    /// never move, and their edges are never split or collapsed.
    pub pinned: Option<VertexAttr<bool>>,
    /// Which columns are resampled from the input (default: every linear
    /// vertex and corner column).
    pub resample: Resample,
    /// After the rounds, flip each edge opposite an angle over 170° (a
    /// *cap*: a flat triangle whose third corner nearly lies on its long
    /// edge) where the flip lowers the largest angle of the two triangles,
    /// as pmp-library's `remove_caps` (default true). Lines and edges at
    /// fixed vertices are never flipped.
    pub remove_caps: bool,
    /// The most faces the result may have: a target length whose estimate
    /// (each input triangle's area over that of an equilateral triangle
    /// of its corners' shortest target) is past it is refused before any
    /// work with [`Error::TooLarge`] (default
    /// [`DEFAULT_MAX_FACES`](crate::algo::DEFAULT_MAX_FACES)).
    pub max_faces: usize,
}

crate::algo::constraints::constrained!(RemeshOptions);

crate::choice::setters!(RemeshOptions {
    sizing: Sizing,
    iterations: usize,
    smoothing_steps: usize,
    project: bool,
    boundary: Keep,
    seams: Keep,
    feature_angle: Option<f64>,
    features: Option<EdgeAttr<bool>>,
    pinned: Option<VertexAttr<bool>>,
    resample: Resample,
    remove_caps: bool,
    max_faces: usize,
});

impl Default for RemeshOptions {
    fn default() -> Self {
        RemeshOptions {
            sizing: Sizing::MeanEdgeLength,
            iterations: 10,
            smoothing_steps: 5,
            project: true,
            boundary: Keep::Slide,
            seams: Keep::Slide,
            feature_angle: None,
            features: None,
            pinned: None,
            resample: Resample::Linear,
            remove_caps: true,
            max_faces: crate::algo::DEFAULT_MAX_FACES,
        }
    }
}

/// Edge lengths of the result.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct EdgeLengthStats {
    /// The shortest edge.
    pub min: f64,
    /// The longest edge.
    pub max: f64,
    /// The mean length.
    pub mean: f64,
    /// The share of edges (0..=1) within [4/5, 4/3] of their target length
    /// (the mean of their ends' targets).
    pub within: f64,
}

/// What [`remesh`] did.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct RemeshReport {
    /// Rounds run.
    pub iterations: usize,
    /// Edges split.
    pub splits: usize,
    /// Edges collapsed.
    pub collapses: usize,
    /// Edges flipped (valence flips in the rounds).
    pub flips: usize,
    /// Caps removed by [`RemeshOptions::remove_caps`] (edge flips after
    /// the rounds).
    pub caps_removed: usize,
    /// The uniform target length, or the mean of the adaptive targets over
    /// the input's vertices.
    pub target_length: f64,
    /// Counts of the input.
    pub input: Counts,
    /// Counts of the result.
    pub output: Counts,
    /// Feature edges found in the input (by angle or column).
    pub feature_edges: usize,
    /// Input vertices that could not move (pinned, corners, a locked
    /// boundary or seam).
    pub fixed: usize,
    /// The columns resampled from the input.
    pub resampled: Vec<String>,
    /// Edge lengths of the result.
    pub edge_lengths: EdgeLengthStats,
}

/// Remesh a triangle mesh isotropically (see the [module](self) for the
/// method, what is kept and the costs).
///
/// # Arguments
/// `options` give the target length, the rounds and what to keep;
/// `progress` is told the rounds done (stage `"iterations"`) and may
/// cancel.
///
/// # Returns
/// A [`RemeshReport`]: the operations made and the edge lengths reached.
///
/// # Errors
/// [`Error::NoPositions`]; [`Error::Unsuitable`] for a face that is not a
/// triangle (naming it), a target length or tolerance that is not a
/// positive finite number, a feature angle that is not finite, a column to
/// resample that is missing or does not interpolate linearly; the errors
/// of a column handle ([`Error::AttributeHandle`]); [`Error::TooLarge`]
/// for a target length that would make more than `max_faces` faces
/// (a unit cube at 1e-6); [`Error::NonFiniteResult`]; [`Error::Cancelled`].
/// On every error the mesh is unchanged.
///
/// # Complexity
/// O(iterations · (n + m log n)) for n vertices of which m move.
///
/// # Examples
/// ```
/// use meshloom::algo::remesh::{remesh, RemeshOptions, Sizing};
/// use meshloom::algo::Progress;
/// use meshloom::shapes::{grid, GridFaces};
/// let mut mesh = grid(4, 4, GridFaces::Triangles); // cells of 1 × 1
/// let options = RemeshOptions::default().sizing(Sizing::Uniform(0.5));
/// let report = remesh(&mut mesh, &options, Progress::none())?;
/// assert!(report.splits > 0 && mesh.face_count() > 100);
/// assert_eq!(mesh.hole_count(), 1); // the boundary is kept
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn remesh(
    mesh: &mut Mesh,
    options: &RemeshOptions,
    progress: Progress<'_>,
) -> Result<RemeshReport> {
    mesh.as_one_step("Remesh", |mesh| remesh_run(mesh, options, progress))
}

/// [`remesh`] itself, inside its step.
fn remesh_run(
    mesh: &mut Mesh,
    options: &RemeshOptions,
    mut progress: Progress<'_>,
) -> Result<RemeshReport> {
    let setup = Setup::new(mesh, options)?;
    setup.check_size(mesh, options.max_faces)?;
    let mut report = RemeshReport {
        input: Counts::of(mesh),
        output: Counts::of(mesh),
        target_length: setup.target_length,
        feature_edges: setup.feature_edges,
        fixed: setup.fixed,
        resampled: setup.resample.iter().map(|c| c.name.clone()).collect(),
        ..RemeshReport::default()
    };
    if mesh.face_count() == 0 {
        return Ok(report);
    }
    let mut work = mesh.clone();
    let mut engine = Engine::new(mesh, &work, setup)?;
    for i in 0..options.iterations {
        progress.report(ALGORITHM, "iterations", i as u64, options.iterations as u64)?;
        report.splits += engine.split_long_edges(&mut work);
        report.collapses += engine.collapse_short_edges(&mut work);
        report.flips += engine.flip_edges(&mut work);
        for _ in 0..options.smoothing_steps {
            engine.relax(&mut work);
        }
        if options.project {
            engine.project(&mut work);
        }
        report.iterations += 1;
    }
    if options.remove_caps {
        report.caps_removed = engine.remove_caps(&mut work);
    }
    progress.report(
        ALGORITHM,
        "iterations",
        options.iterations as u64,
        options.iterations as u64,
    )?;
    engine.resample(mesh, &mut work);
    work.debug_validate();
    report.output = Counts::of(&work);
    report.edge_lengths = engine.edge_lengths(&work);
    crate::algo::check_finite(&work, ALGORITHM)?;
    mesh.replace_with(work);
    Ok(report)
}

fn unsuitable(key: Option<crate::keys::AnyKey>, reason: String) -> Error {
    Error::Unsuitable {
        algorithm: ALGORITHM,
        key,
        reason,
    }
}
