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
//!    closest point on the input triangles, found through a bounding-volume
//!    hierarchy built once from a copy of the input taken before any edit
//!    (our own, `remesh/bvh.rs`: median split, warm-started with the
//!    triangle each vertex was last projected onto).
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

mod bvh;

/// The line rule, shared by every algorithm: see [`Constraints`].
pub use super::constraints::Keep;
use super::constraints::{Classifier, Constraints, LineSources, FIXED, FREE, LINE};
use super::subdivision::Counts;
use crate::attr::{EdgeAttr, VertexAttr};
use crate::error::{Error, Result};
use crate::layout::{Eid, Fid, Hid, Vid};
// The remesher edits a working copy (a clone records nothing), so its
// crate-private doors run unrecorded; the run is one unit through replace_with.
use crate::journal::Unrecorded;
use crate::mesh::Mesh;
use crate::vec3::{cross, dist2, dot, sub, V3};
use bvh::{Bvh, Segment, Triangle};

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

impl RemeshOptions {
    /// The constraints these options name.
    pub fn constraints(&self) -> Constraints {
        Constraints {
            boundary: self.boundary,
            seams: self.seams,
            feature_angle: self.feature_angle,
            features: self.features.clone(),
            pinned: self.pinned.clone(),
        }
    }

    /// These options with the five fields of `c` (the setters
    /// `boundary`, `seams`, `feature_angle`, `features` and `pinned` in
    /// one): the inverse of [`constraints`](Self::constraints).
    #[must_use]
    pub fn with_constraints(self, c: Constraints) -> Self {
        self.boundary(c.boundary)
            .seams(c.seams)
            .feature_angle(c.feature_angle)
            .features(c.features)
            .pinned(c.pinned)
    }
}

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
    let mut engine = Engine::new(mesh, &work, setup);
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

/// Edge flags.
const E_LINE: u8 = 1;
const E_LOCKED: u8 = 2;

/// A column to resample: its arena and index (the same in the input and
/// the copy).
struct ResampleColumn {
    name: String,
    corner: bool,
    index: usize,
}

/// Everything checked and classified before the first change.
struct Setup {
    /// Per vertex slot of the input: target length.
    sizing: Vec<f64>,
    uniform: bool,
    target_length: f64,
    /// Per vertex slot of the input: kind.
    kinds: Vec<u8>,
    /// Per edge slot of the input: flags.
    edges: Vec<u8>,
    feature_edges: usize,
    fixed: usize,
    resample: Vec<ResampleColumn>,
}

impl Setup {
    /// Refuse a target that would make more than `max_faces` faces: each
    /// input triangle's area over that of an equilateral triangle whose
    /// side is its corners' shortest target length.
    fn check_size(&self, mesh: &Mesh, max_faces: usize) -> Result<()> {
        let Some(pos) = mesh.position_slots() else {
            return Ok(());
        };
        let equilateral = 3f64.sqrt() / 4.0;
        let mut estimate = 0.0;
        for f in mesh.fids() {
            if mesh.is_hole(f) {
                continue;
            }
            let h = mesh.face_halfedge(f);
            let l = [h, mesh.next(h), mesh.prev_fast(h)]
                .map(|h| self.sizing[mesh.origin(h).index()])
                .into_iter()
                .fold(f64::INFINITY, f64::min);
            let n = triangle_normal(mesh, pos, h);
            let area = 0.5 * dot(n, n).sqrt();
            estimate += (area / (equilateral * l * l)).max(1.0);
        }
        if estimate > max_faces as f64 {
            return Err(Error::TooLarge {
                algorithm: ALGORITHM,
                estimate: estimate.min(u64::MAX as f64) as u64,
                limit: max_faces as u64,
                option: "max_faces",
            });
        }
        Ok(())
    }

    fn new(mesh: &Mesh, options: &RemeshOptions) -> Result<Setup> {
        let pos = mesh.position_slots().ok_or(Error::NoPositions)?;
        crate::algo::check_triangles(mesh, ALGORITHM, "remeshing")?;
        let constraints = options.constraints();
        constraints.check(ALGORITHM)?;
        let resample = resample_columns(mesh, &options.resample)?;
        // The seams are those of the corner columns being resampled.
        let sources = LineSources {
            seam_columns: resample
                .iter()
                .filter(|c| c.corner)
                .map(|c| &*mesh.attrs().halfedge.cols[c.index].1)
                .collect(),
            material: None,
            features: Keep::Slide,
            edge_bits: true,
        };
        let classified = Classifier::new(mesh, pos, &constraints, sources)?.classify();
        let mut edges = vec![0u8; mesh.slot_counts()[2]];
        for e in mesh.eids() {
            let line = if classified.lines.get(e) { E_LINE } else { 0 };
            let locked = if classified.locked.get(e) {
                E_LOCKED
            } else {
                0
            };
            edges[e.index()] = line | locked;
        }
        let (sizing, uniform, target_length) =
            sizing(mesh, pos, options.sizing, &classified.kinds)?;
        Ok(Setup {
            sizing,
            uniform,
            target_length,
            kinds: classified.kinds,
            edges,
            feature_edges: classified.feature_edges,
            fixed: classified.fixed,
            resample,
        })
    }
}

/// Per input vertex slot, the target length; whether it is uniform; the
/// uniform length or the mean of the adaptive ones.
fn sizing(mesh: &Mesh, pos: &[V3], sizing: Sizing, kinds: &[u8]) -> Result<(Vec<f64>, bool, f64)> {
    let positive = |name: &str, x: f64| {
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(unsuitable(
                None,
                format!("{name} {x} is not a positive finite number"),
            ))
        }
    };
    let nv = mesh.slot_counts()[0];
    let mean = mean_edge_length(mesh, pos);
    let need_mean = |what: &str| {
        if mean > 0.0 && mean.is_finite() {
            Ok(mean)
        } else {
            Err(unsuitable(
                None,
                format!("the input has no edge of positive length to take the {what} from"),
            ))
        }
    };
    Ok(match sizing {
        Sizing::MeanEdgeLength => {
            let l = need_mean("mean edge length")?;
            (vec![l; nv], true, l)
        }
        Sizing::Uniform(l) => {
            let l = positive("the target edge length", l)?;
            (vec![l; nv], true, l)
        }
        Sizing::Adaptive {
            tolerance,
            min_length,
            max_length,
        } => {
            let tol = positive("the tolerance", tolerance)?;
            let lo = match min_length {
                Some(x) => positive("min_length", x)?,
                None => 0.25 * need_mean("default min_length")?,
            };
            let hi = match max_length {
                Some(x) => positive("max_length", x)?,
                None => 4.0 * need_mean("default max_length")?,
            };
            if lo > hi {
                return Err(unsuitable(
                    None,
                    format!("min_length {lo} is greater than max_length {hi}"),
                ));
            }
            let s = adaptive_sizing(mesh, kinds, tol, lo, hi)?;
            let n = mesh.vertex_count().max(1) as f64;
            let avg = mesh.vids().map(|v| s[v.index()]).sum::<f64>() / n;
            (s, false, avg)
        }
    })
}

/// The columns `what` names, checked.
fn resample_columns(mesh: &Mesh, what: &Resample) -> Result<Vec<ResampleColumn>> {
    let position = mesh.attrs().position;
    let vertex = &mesh.attrs().vertex.cols;
    let corner = &mesh.attrs().halfedge.cols;
    let mut out = Vec::new();
    match what {
        Resample::Off => {}
        Resample::Linear => {
            for (i, (name, col)) in vertex.iter().enumerate() {
                if Some(i) != position && col.interpolates_linearly() {
                    out.push(ResampleColumn {
                        name: name.clone(),
                        corner: false,
                        index: i,
                    });
                }
            }
            for (i, (name, col)) in corner.iter().enumerate() {
                if col.interpolates_linearly() {
                    out.push(ResampleColumn {
                        name: name.clone(),
                        corner: true,
                        index: i,
                    });
                }
            }
        }
        Resample::Columns(names) => {
            for name in names {
                let (corner_col, index) = match mesh.attrs().vertex.find(name) {
                    Some(i) if Some(i) != position => (false, i),
                    Some(_) => {
                        return Err(unsuitable(
                            None,
                            "positions are projected, not resampled".into(),
                        ))
                    }
                    None => match mesh.attrs().halfedge.find(name) {
                        Some(i) => (true, i),
                        None => {
                            return Err(unsuitable(
                                None,
                                format!("no vertex or corner column named {name:?} to resample"),
                            ))
                        }
                    },
                };
                let col = if corner_col {
                    &corner[index].1
                } else {
                    &vertex[index].1
                };
                if !col.interpolates_linearly() {
                    return Err(unsuitable(
                        None,
                        format!(
                            "column {name:?} does not interpolate linearly; it cannot be resampled"
                        ),
                    ));
                }
                out.push(ResampleColumn {
                    name: name.clone(),
                    corner: corner_col,
                    index,
                });
            }
        }
    }
    Ok(out)
}

/// Whether the two triangles beside `h`'s edge have the same third
/// vertex (two triangles on the same three vertices, as in a closed
/// two-triangle "pillow"): splitting the edge would join the new vertex to
/// that apex twice.
fn same_apex(mesh: &Mesh, h: Hid) -> bool {
    let t = h.twin();
    !mesh.is_hole(mesh.face_of(h))
        && !mesh.is_hole(mesh.face_of(t))
        && mesh.origin(mesh.prev_fast(h)) == mesh.origin(mesh.prev_fast(t))
}

/// Twice the area vector of the face of `h` (a triangle).
fn triangle_normal(mesh: &Mesh, pos: &[V3], h: Hid) -> V3 {
    let n = mesh.next(h);
    let a = pos[mesh.origin(h).index()];
    let b = pos[mesh.origin(n).index()];
    let c = pos[mesh.origin(mesh.next(n)).index()];
    cross(sub(b, a), sub(c, a))
}

/// The mean length of the live edges.
fn mean_edge_length(mesh: &Mesh, pos: &[V3]) -> f64 {
    let mut sum = 0.0;
    let mut n = 0usize;
    for e in mesh.eids() {
        let [h, t] = e.halfedges();
        sum += dist2(pos[mesh.origin(h).index()], pos[mesh.origin(t).index()]).sqrt();
        n += 1;
    }
    if n == 0 {
        0.0
    } else {
        sum / n as f64
    }
}

/// Target lengths from curvature (see the module docs).
fn adaptive_sizing(mesh: &Mesh, kinds: &[u8], tol: f64, lo: f64, hi: f64) -> Result<Vec<f64>> {
    use super::curvature::{curvature, CurvatureOptions};
    let c = curvature(mesh, &CurvatureOptions::default())?;
    let nv = mesh.slot_counts()[0];
    // Curvature of lines and corners is not the surface's: leave it out.
    let mut k = vec![-1.0f64; nv];
    for v in mesh.vids() {
        let i = v.index();
        if kinds[i] == FREE && !mesh.on_boundary(v) {
            k[i] = c.max[i].abs().max(c.min[i].abs());
        }
    }
    // Two rounds of neighbour averaging (noise; and to give line vertices
    // the curvature of the surface beside them).
    for _ in 0..2 {
        let mut next = k.clone();
        for v in mesh.vids() {
            let (mut sum, mut n) = (0.0, 0.0);
            if k[v.index()] >= 0.0 {
                sum += k[v.index()];
                n += 1.0;
            }
            for o in mesh.outgoing(v) {
                let w = k[mesh.dest(o).index()];
                if w >= 0.0 {
                    sum += w;
                    n += 1.0;
                }
            }
            next[v.index()] = if n > 0.0 { sum / n } else { k[v.index()] };
        }
        k = next;
    }
    Ok(k.into_iter()
        .map(|c| {
            let h = if c <= 0.0 {
                hi
            } else {
                let r = 1.0 / c;
                if tol < r {
                    (6.0 * tol * r - 3.0 * tol * tol).sqrt()
                } else {
                    tol * 3f64.sqrt()
                }
            };
            h.clamp(lo, hi)
        })
        .collect())
}

/// The input surface: triangles and lines in hierarchies, with what
/// resampling needs.
struct Reference {
    tris: Bvh<Triangle>,
    /// Per triangle: its three corners (half-edges, origin = vertex) in the
    /// input.
    corners: Vec<[Hid; 3]>,
    /// Per triangle: its three input vertex slots.
    tri_vertices: Vec<[u32; 3]>,
    /// Per input face slot: its triangle (u32::MAX for holes).
    tri_of_face: Vec<u32>,
    lines: Bvh<Segment>,
    /// Per input vertex slot: target length (adaptive).
    sizing: Vec<f64>,
}

/// The remesher's state over the working copy.
struct Engine {
    reference: Reference,
    uniform: Option<f64>,
    /// Per vertex slot.
    kind: Vec<u8>,
    sizing: Vec<f64>,
    hint: Vec<u32>,
    line_hint: Vec<u32>,
    /// Per edge slot.
    eflags: Vec<u8>,
    /// Scratch, per vertex slot.
    update: Vec<V3>,
    valence: Vec<u32>,
    resample: Vec<ResampleColumn>,
}

impl Engine {
    fn new(input: &Mesh, work: &Mesh, setup: Setup) -> Engine {
        let pos = input.position_slots().unwrap_or(&[]);
        let nf = input.slot_counts()[3];
        let mut tri_of_face = vec![u32::MAX; nf];
        let mut tris = Vec::with_capacity(input.face_count());
        let mut corners = Vec::with_capacity(input.face_count());
        let mut tri_vertices = Vec::with_capacity(input.face_count());
        for f in input.fids() {
            if input.is_hole(f) {
                continue;
            }
            let h0 = input.face_halfedge(f);
            let h1 = input.next(h0);
            let h2 = input.next(h1);
            tri_of_face[f.index()] = tris.len() as u32;
            tris.push([h0, h1, h2].map(|h| pos[input.origin(h).index()]));
            corners.push([h0, h1, h2]);
            tri_vertices.push([h0, h1, h2].map(|h| input.origin(h).raw()));
        }
        let mut segs = Vec::new();
        for e in input.eids() {
            if setup.edges[e.index()] & E_LINE != 0 {
                let [h, t] = e.halfedges();
                segs.push([pos[input.origin(h).index()], pos[input.origin(t).index()]]);
            }
        }
        let nv = work.slot_counts()[0];
        let mut hint = vec![0u32; nv];
        for v in input.vids() {
            let h = input.vertex_halfedge(v);
            // A vertex on a boundary names a half-edge in a hole: its twin's
            // next leaves v in a face.
            let h = if input.in_hole(h) {
                input.next(h.twin())
            } else {
                h
            };
            let t = tri_of_face[input.face_of(h).index()];
            hint[v.index()] = if t == u32::MAX { 0 } else { t };
        }
        let uniform = setup.uniform.then_some(setup.target_length);
        Engine {
            reference: Reference {
                tris: Bvh::new(tris),
                corners,
                tri_vertices,
                tri_of_face,
                lines: Bvh::new(segs),
                sizing: setup.sizing.clone(),
            },
            uniform,
            kind: setup.kinds,
            sizing: setup.sizing,
            hint,
            line_hint: vec![0; nv],
            eflags: setup.edges,
            update: Vec::new(),
            valence: Vec::new(),
            resample: setup.resample,
        }
    }

    /// Grow the per-slot arrays to the mesh's slot counts.
    fn fit(&mut self, mesh: &Mesh) {
        let [nv, _, ne, _] = mesh.slot_counts();
        if self.kind.len() < nv {
            self.kind.resize(nv, FREE);
            self.sizing.resize(nv, self.uniform.unwrap_or(0.0));
            self.hint.resize(nv, 0);
            self.line_hint.resize(nv, 0);
        }
        if self.eflags.len() < ne {
            self.eflags.resize(ne, 0);
        }
    }

    #[inline(always)]
    fn target(&self, a: Vid, b: Vid) -> f64 {
        match self.uniform {
            Some(l) => l,
            None => self.sizing[a.index()].min(self.sizing[b.index()]),
        }
    }

    /// Split every edge longer than 4/3 of its target, until none is (at
    /// most 10 passes). Returns the splits made.
    fn split_long_edges(&mut self, mesh: &mut Mesh) -> usize {
        let mut splits = 0;
        for _ in 0..10 {
            let mut any = false;
            // The edges there are now: one level of splits a pass (edges
            // made by this pass wait for the next, as in pmp-library;
            // splitting the new ones at once can run away).
            for i in 0..mesh.edge_slots() {
                let e = Eid::new(i as u32);
                if !mesh.edge_live(e.index()) || self.eflags[e.index()] & E_LOCKED != 0 {
                    continue;
                }
                let [h, t] = e.halfedges();
                let (a, b) = (mesh.origin(h), mesh.origin(t));
                let pos = positions(mesh);
                let l = self.target(a, b) * (4.0 / 3.0);
                let d = dist2(pos[a.index()], pos[b.index()]);
                // (Not `d <= l²`: a NaN must not split forever.)
                if d.is_nan() || d <= l * l || !d.is_finite() || same_apex(mesh, h) {
                    continue;
                }
                self.split(mesh, e, a, b);
                splits += 1;
                any = true;
            }
            if !any {
                break;
            }
        }
        splits
    }

    /// Split edge `e` (a–b) at its midpoint and the triangles beside it.
    /// The two triangles must not share their apex (see [`same_apex`]).
    fn split(&mut self, mesh: &mut Mesh, e: Eid, a: Vid, b: Vid) {
        let [h, t] = e.halfedges();
        let (fh, ft) = (mesh.face_of(h), mesh.face_of(t));
        let (hole_h, hole_t) = (mesh.is_hole(fh), mesh.is_hole(ft));
        let m = mesh.split_edge_unvalidated(e, 0.5);
        // h: m -> b now; n0 = a -> m before it; n1 = m -> a after t.
        let n1 = mesh.next(t);
        let ne = n1.edge();
        let mut spokes = [Eid::NONE; 2];
        if !hole_h {
            let nh = mesh.next(h);
            let c = mesh.next(nh);
            let n0 = mesh.next(c);
            let (x, g) = mesh.split_face_raw::<Unrecorded>(n0, h, nh, c);
            mesh.split_face_values(fh, &[fh, g]);
            spokes[0] = x.edge();
        }
        if !hole_t {
            let nt = mesh.next(n1);
            let d = mesh.next(nt);
            let (x, g) = mesh.split_face_raw::<Unrecorded>(t, n1, nt, d);
            mesh.split_face_values(ft, &[ft, g]);
            spokes[1] = x.edge();
        }
        self.fit(mesh);
        let line = self.eflags[e.index()] & E_LINE;
        self.eflags[ne.index()] = line;
        for s in spokes {
            if !s.is_none() {
                self.eflags[s.index()] = 0;
            }
        }
        let (ia, ib, im) = (a.index(), b.index(), m.index());
        self.kind[im] = if line != 0 { LINE } else { FREE };
        self.sizing[im] = 0.5 * (self.sizing[ia] + self.sizing[ib]);
        self.hint[im] = self.hint[ia];
        self.line_hint[im] = self.line_hint[ia];
    }

    /// Collapse every edge shorter than 4/5 of its target where allowed
    /// (at most 10 passes). Returns the collapses made.
    fn collapse_short_edges(&mut self, mesh: &mut Mesh) -> usize {
        let mut collapses = 0;
        for _ in 0..10 {
            let mut any = false;
            for i in 0..mesh.edge_slots() {
                let e = Eid::new(i as u32);
                if !mesh.edge_live(i) || self.eflags[i] & E_LOCKED != 0 {
                    continue;
                }
                let [h0, h1] = e.halfedges();
                let (v0, v1) = (mesh.origin(h0), mesh.origin(h1));
                let pos = positions(mesh);
                let l = self.target(v0, v1) * 0.8;
                if dist2(pos[v0.index()], pos[v1.index()]) >= l * l {
                    continue;
                }
                let c01 = self.may_remove(mesh, h0);
                let c10 = self.may_remove(mesh, h1);
                // The vertex of lower valence goes first; the other way if
                // that would make an edge too long or is refused.
                let order = if c01 && c10 && valence(mesh, v0) >= valence(mesh, v1) {
                    [h1, h0]
                } else {
                    [h0, h1]
                };
                // Two free vertices meet at the midpoint (Botsch and
                // Kobbelt): its new edges are shorter than at either end,
                // so fewer collapses are refused for making an edge too long.
                if c01 && c10 && self.kind[v0.index()] == FREE && self.kind[v1.index()] == FREE {
                    let (p0, p1) = (pos[v0.index()], pos[v1.index()]);
                    let mid = [0, 1, 2].map(|k| 0.5 * (p0[k] + p1[k]));
                    if self.ring_fits(mesh, order[0], mid)
                        && self.ring_fits(mesh, order[0].twin(), mid)
                        && mesh
                            .collapse_unvalidated::<Unrecorded>(order[0], 0.5, None)
                            .is_ok()
                    {
                        collapses += 1;
                        any = true;
                        continue;
                    }
                }
                for h in order {
                    let allowed = if h == h0 { c01 } else { c10 };
                    if allowed
                        && self.short_enough_after(mesh, h)
                        && mesh
                            .collapse_unvalidated::<Unrecorded>(h, 1.0, None)
                            .is_ok()
                    {
                        collapses += 1;
                        any = true;
                        break;
                    }
                }
            }
            if !any {
                break;
            }
        }
        collapses
    }

    /// Whether `origin(h)` may merge into `dest(h)` as far as kinds and
    /// lines go (the operator checks the topology).
    fn may_remove(&self, mesh: &Mesh, h: Hid) -> bool {
        let a = mesh.origin(h);
        match self.kind[a.index()] {
            FIXED => false,
            LINE => {
                if self.eflags[h.edge().index()] & E_LINE == 0 {
                    return false;
                }
                // The sides at `a` of the triangles that disappear must not
                // be lines (a line would fold onto itself).
                let t = h.twin();
                let before = mesh.prev_fast(h);
                let after = mesh.next(t);
                let side_line =
                    |x: Hid| !mesh.in_hole(x) && self.eflags[x.edge().index()] & E_LINE != 0;
                (!side_line(before) || mesh.in_hole(h)) && (!side_line(after) || mesh.in_hole(t))
            }
            _ => {
                // A free vertex: off any line, unless the mesh has a
                // boundary it is not told of (never with Slide).
                !mesh.on_boundary(a)
            }
        }
    }

    /// Whether merging `origin(h)` into `dest(h)` keeps every new edge within
    /// 4/3 of its target.
    fn short_enough_after(&self, mesh: &Mesh, h: Hid) -> bool {
        let pb = positions(mesh)[mesh.dest(h).index()];
        self.ring_fits(mesh, h, pb)
    }

    /// Whether every neighbour of `origin(h)` but `dest(h)` is within 4/3
    /// of its target (with `dest(h)`) of `pb`: the edges `origin(h)`'s
    /// ring would have after a collapse of `h` to `pb`.
    fn ring_fits(&self, mesh: &Mesh, h: Hid, pb: V3) -> bool {
        let (a, b) = (mesh.origin(h), mesh.dest(h));
        let pos = positions(mesh);
        let mut o = mesh.vertex_halfedge(a);
        let start = o;
        loop {
            let w = mesh.dest(o);
            if w != b {
                let l = self.target(b, w) * (4.0 / 3.0);
                if dist2(pb, pos[w.index()]) > l * l {
                    return false;
                }
            }
            o = mesh.next(o.twin());
            if o == start {
                return true;
            }
        }
    }

    /// Flip edges towards valence 6 (4 on a boundary), at most 10 passes.
    fn flip_edges(&mut self, mesh: &mut Mesh) -> usize {
        let nv = mesh.slot_counts()[0];
        self.valence.clear();
        self.valence.resize(nv, 0);
        for e in mesh.eids() {
            let [h, t] = e.halfedges();
            self.valence[mesh.origin(h).index()] += 1;
            self.valence[mesh.origin(t).index()] += 1;
        }
        let mut flips = 0;
        for _ in 0..10 {
            let mut any = false;
            for i in 0..mesh.edge_slots() {
                let Some((e, vs)) = self.flip_candidate(mesh, i) else {
                    continue;
                };
                let [a, b, c, d] = vs;
                let target = |v: Vid| if mesh.on_boundary(v) { 4i32 } else { 6 };
                let val = vs.map(|v| self.valence[v.index()] as i32);
                let dev = |delta: [i32; 4]| -> i32 {
                    (0..4)
                        .map(|k| {
                            let x = val[k] + delta[k] - target(vs[k]);
                            x * x
                        })
                        .sum()
                };
                if dev([-1, -1, 1, 1]) >= dev([0; 4]) {
                    continue;
                }
                if !flip_keeps_orientation(positions(mesh), [a, b, c, d]) {
                    continue;
                }
                if mesh.flip_unvalidated(e).is_ok() {
                    self.valence[a.index()] -= 1;
                    self.valence[b.index()] -= 1;
                    self.valence[c.index()] += 1;
                    self.valence[d.index()] += 1;
                    flips += 1;
                    any = true;
                }
            }
            if !any {
                break;
            }
        }
        flips
    }

    /// Edge slot `i` as a flip candidate of [`Self::flip_edges`] and
    /// [`Self::remove_caps`]: a live edge that is no feature or boundary
    /// (no flag), between two triangles, none of whose four vertices is
    /// fixed; with its vertices `[a, b, c, d]` (the edge `a–b`, `c` and `d`
    /// opposite it in the faces of `a → b` and `b → a`).
    fn flip_candidate(&self, mesh: &Mesh, i: usize) -> Option<(Eid, [Vid; 4])> {
        if !mesh.edge_live(i) || self.eflags[i] != 0 {
            return None;
        }
        let e = Eid::new(i as u32);
        let [h, t] = e.halfedges();
        if mesh.in_hole(h) || mesh.in_hole(t) {
            return None;
        }
        let (hn, tn) = (mesh.next(h), mesh.next(t));
        if mesh.next(mesh.next(hn)) != h || mesh.next(mesh.next(tn)) != t {
            return None;
        }
        let vs = [mesh.origin(h), mesh.origin(t), mesh.dest(hn), mesh.dest(tn)];
        if vs.iter().any(|v| self.kind[v.index()] == FIXED) {
            return None;
        }
        Some((e, vs))
    }

    /// Flip the edges opposite an angle over 170° where that lowers the
    /// largest angle of the two triangles (pmp-library's `remove_caps`),
    /// one pass. Returns the flips made.
    fn remove_caps(&mut self, mesh: &mut Mesh) -> usize {
        self.fit(mesh);
        let mut flips = 0;
        for i in 0..mesh.edge_slots() {
            let Some((e, [a, b, c, d])) = self.flip_candidate(mesh, i) else {
                continue;
            };
            let pos = positions(mesh);
            let p = |v: Vid| pos[v.index()];
            let before =
                largest_angle_cos(p(a), p(b), p(c)).min(largest_angle_cos(p(b), p(a), p(d)));
            if before >= CAP_COS {
                continue;
            }
            let after =
                largest_angle_cos(p(c), p(d), p(b)).min(largest_angle_cos(p(d), p(c), p(a)));
            if after <= before || !flip_keeps_orientation(pos, [a, b, c, d]) {
                continue;
            }
            if mesh.flip_unvalidated(e).is_ok() {
                flips += 1;
            }
        }
        flips
    }

    /// One Jacobi step of tangential relaxation.
    fn relax(&mut self, mesh: &mut Mesh) {
        let nv = mesh.slot_counts()[0];
        self.fit(mesh);
        self.update.clear();
        self.update.resize(nv, [0.0; 3]);
        {
            let pos = positions(mesh);
            for i in 0..nv {
                let kind = self.kind[i];
                if kind == FIXED || !mesh.vertex_live(i) {
                    continue;
                }
                let v = Vid::new(i as u32);
                self.update[i] = if kind == LINE {
                    self.line_step(mesh, pos, v)
                } else {
                    self.surface_step(mesh, pos, v)
                };
            }
        }
        let Some(pos) = mesh.position_slots_mut() else {
            return;
        };
        for (i, u) in self.update.iter().enumerate() {
            if u[0] != 0.0 || u[1] != 0.0 || u[2] != 0.0 {
                let p = &mut pos[i];
                p[0] += u[0];
                p[1] += u[1];
                p[2] += u[2];
            }
        }
    }

    /// A free vertex's move: towards the area-weighted centroid of its
    /// triangles (weights divided by the squared target length when
    /// adaptive), in its tangent plane.
    #[inline]
    fn surface_step(&self, mesh: &Mesh, pos: &[V3], v: Vid) -> V3 {
        let p = pos[v.index()];
        let mut n = [0.0; 3];
        let mut c = [0.0; 3];
        let mut ww = 0.0;
        let start = mesh.vertex_halfedge(v);
        let mut o = start;
        loop {
            let r = mesh.halfedge_record(o);
            let tw = mesh.halfedge_record(o.twin());
            if !mesh.is_hole(r.face) {
                let w1 = tw.origin;
                let w2 = mesh.origin(mesh.next(r.next));
                let (p1, p2) = (pos[w1.index()], pos[w2.index()]);
                let x = cross(sub(p1, p), sub(p2, p));
                let mut area = dot(x, x).sqrt();
                if area == 0.0 {
                    area = 1e-300;
                }
                if self.uniform.is_none() {
                    let s = (self.sizing[v.index()]
                        + self.sizing[w1.index()]
                        + self.sizing[w2.index()])
                        / 3.0;
                    if s > 0.0 {
                        area /= s * s;
                    }
                }
                for k in 0..3 {
                    n[k] += x[k];
                    c[k] += area * (p[k] + p1[k] + p2[k]);
                }
                ww += area;
            }
            o = tw.next;
            if o == start {
                break;
            }
        }
        if ww <= 0.0 {
            return [0.0; 3];
        }
        let s = 1.0 / (3.0 * ww);
        let mut u = [c[0] * s - p[0], c[1] * s - p[1], c[2] * s - p[2]];
        let nn = dot(n, n);
        if nn > 0.0 {
            let k = dot(u, n) / nn;
            for i in 0..3 {
                u[i] -= k * n[i];
            }
        }
        if u.iter().all(|x| x.is_finite()) {
            u
        } else {
            [0.0; 3]
        }
    }

    /// A line vertex's move: towards the weighted mean of its two line
    /// edges' midpoints, along the line.
    fn line_step(&self, mesh: &Mesh, pos: &[V3], v: Vid) -> V3 {
        let p = pos[v.index()];
        let mut ends = [Vid::NONE; 2];
        let mut n = 0;
        for o in mesh.outgoing(v) {
            if self.eflags[o.edge().index()] & E_LINE != 0 {
                if n == 2 {
                    return [0.0; 3];
                }
                ends[n] = mesh.dest(o);
                n += 1;
            }
        }
        if n != 2 {
            return [0.0; 3];
        }
        let mut u = [0.0; 3];
        let mut ww = 0.0;
        let mut t = [0.0; 3];
        for (k, w) in ends.into_iter().enumerate() {
            let q = pos[w.index()];
            let l = dist2(p, q).sqrt();
            let s = 0.5 * (self.sizing[v.index()] + self.sizing[w.index()]);
            let weight = if s > 0.0 { l / s } else { l };
            for i in 0..3 {
                u[i] += weight * 0.5 * (p[i] + q[i]);
            }
            ww += weight;
            if l > 0.0 {
                let sign = if k == 0 { 1.0 } else { -1.0 };
                for i in 0..3 {
                    t[i] += sign * (q[i] - p[i]) / l;
                }
            }
        }
        let tt = dot(t, t);
        if ww <= 0.0 || tt <= 0.0 {
            return [0.0; 3];
        }
        let d = [u[0] / ww - p[0], u[1] / ww - p[1], u[2] / ww - p[2]];
        let k = dot(d, t) / tt;
        let out = [k * t[0], k * t[1], k * t[2]];
        if out.iter().all(|x| x.is_finite()) {
            out
        } else {
            [0.0; 3]
        }
    }

    /// Move every free vertex to its closest point on the input triangles
    /// and every line vertex to its closest point on the input's lines.
    fn project(&mut self, mesh: &mut Mesh) {
        self.fit(mesh);
        let nv = mesh.slot_counts()[0];
        let adaptive = self.uniform.is_none();
        let reference = &self.reference;
        let (live, attrs) = mesh.vertex_arena_and_attrs_mut();
        let Some(pos) = attrs.positions_mut().map(|c| c.raw_mut()) else {
            return;
        };
        for (i, p) in pos.iter_mut().enumerate().take(nv) {
            if self.kind[i] == FIXED || !live.is_live(i) {
                continue;
            }
            match self.kind[i] {
                FREE => {
                    if let Some(hit) = reference.tris.closest(*p, Some(self.hint[i])) {
                        *p = hit.point;
                        self.hint[i] = hit.prim;
                        if adaptive {
                            self.sizing[i] = reference.interpolate_sizing(hit.prim, hit.bary);
                        }
                    }
                }
                LINE => {
                    if let Some(hit) = reference.lines.closest(*p, Some(self.line_hint[i])) {
                        *p = hit.point;
                        self.line_hint[i] = hit.prim;
                    }
                }
                _ => {}
            }
        }
    }

    /// Resample the chosen vertex and corner columns of `work` from
    /// `input` (see the module docs).
    fn resample(&mut self, input: &Mesh, work: &mut Mesh) {
        if self.resample.is_empty() || self.reference.tris.is_empty() {
            return;
        }
        self.fit(work);
        let pos = positions(work).to_vec();
        // Each vertex's triangle and barycentric coordinates.
        let nv = work.slot_counts()[0];
        let mut at: Vec<(u32, [f64; 3])> = vec![(u32::MAX, [0.0; 3]); nv];
        for v in work.vids() {
            let i = v.index();
            if let Some(hit) = self.reference.tris.closest(pos[i], Some(self.hint[i])) {
                at[i] = (hit.prim, hit.bary);
            }
        }
        self.resample_vertex_columns(input, work, &at);
        let corner_cols: Vec<usize> = self
            .resample
            .iter()
            .filter(|c| c.corner)
            .map(|c| c.index)
            .collect();
        if !corner_cols.is_empty() {
            self.resample_corner_columns(input, work, &pos, &at, &corner_cols);
        }
    }

    /// The vertex columns: each vertex's value interpolated on the input
    /// triangle under it (`at`).
    fn resample_vertex_columns(&self, input: &Mesh, work: &mut Mesh, at: &[(u32, [f64; 3])]) {
        let reference = &self.reference;
        let tri_vertices = |t: u32| reference.corners[t as usize].map(|h| input.origin(h));
        for col in &self.resample {
            if col.corner {
                continue;
            }
            let src = &*input.attrs().vertex.cols[col.index].1;
            let (live, attrs) = work.vertex_arena_and_attrs_mut();
            let dst = &mut attrs.vertex.cols[col.index].1;
            for v in live.live_indices() {
                let (t, b) = at[v as usize];
                if t == u32::MAX {
                    continue;
                }
                let vs = tri_vertices(t);
                let inputs = [
                    (vs[0].index(), b[0]),
                    (vs[1].index(), b[1]),
                    (vs[2].index(), b[2]),
                ];
                dst.interpolate_from(src, v as usize, &inputs);
            }
        }
    }

    /// The corner columns `cols`: each corner's value interpolated on the
    /// input triangle under its vertex, on its own face's side of the
    /// column's seams.
    fn resample_corner_columns(
        &self,
        input: &Mesh,
        work: &mut Mesh,
        pos: &[V3],
        at: &[(u32, [f64; 3])],
        cols: &[usize],
    ) {
        let reference = &self.reference;
        // Per face of the result: the triangle under its centroid.
        let faces: Vec<(Fid, [Hid; 3])> = work
            .fids()
            .filter(|&f| !work.is_hole(f))
            .map(|f| {
                let h0 = work.face_halfedge(f);
                let h1 = work.next(h0);
                (f, [h0, h1, work.next(h1)])
            })
            .collect();
        let under_face: Vec<u32> = faces
            .iter()
            .map(|(_, hs)| {
                let ps = hs.map(|h| pos[work.origin(h).index()]);
                let c = [0, 1, 2].map(|k| (ps[0][k] + ps[1][k] + ps[2][k]) / 3.0);
                let hint = at[work.origin(hs[0]).index()].0;
                reference
                    .tris
                    .closest(c, (hint != u32::MAX).then_some(hint))
                    .map_or(u32::MAX, |hit| hit.prim)
            })
            .collect();
        for &ci in cols {
            let islands = reference.islands(input, ci);
            let mut writes: Vec<(Hid, u32, [f64; 3])> = Vec::with_capacity(3 * faces.len());
            for ((_, hs), &tf) in faces.iter().zip(&under_face) {
                if tf == u32::MAX {
                    continue;
                }
                let island = islands[tf as usize];
                for &h in hs {
                    let v = work.origin(h);
                    let (tv, bv) = at[v.index()];
                    let (t, b) = if tv != u32::MAX && islands[tv as usize] == island {
                        (tv, bv)
                    } else {
                        let keep = |t: u32| islands[t as usize] == island;
                        match reference
                            .tris
                            .closest_filtered(pos[v.index()], Some(tf), &keep)
                        {
                            Some(hit) => (hit.prim, hit.bary),
                            None => continue,
                        }
                    };
                    writes.push((h, t, b));
                }
            }
            let src = &*input.attrs().halfedge.cols[ci].1;
            let dst = &mut work.attrs_mut().halfedge.cols[ci].1;
            for (h, t, b) in writes {
                let cs = reference.corners[t as usize];
                let inputs = [
                    (cs[0].index(), b[0]),
                    (cs[1].index(), b[1]),
                    (cs[2].index(), b[2]),
                ];
                dst.interpolate_from(src, h.index(), &inputs);
            }
        }
    }

    /// Lengths of the result's edges against their targets.
    fn edge_lengths(&self, mesh: &Mesh) -> EdgeLengthStats {
        let pos = positions(mesh);
        let mut s = EdgeLengthStats {
            min: f64::INFINITY,
            max: 0.0,
            mean: 0.0,
            within: 0.0,
        };
        let mut n = 0usize;
        let mut ok = 0usize;
        for e in mesh.eids() {
            let [h, t] = e.halfedges();
            let (a, b) = (mesh.origin(h), mesh.origin(t));
            let l = dist2(pos[a.index()], pos[b.index()]).sqrt();
            let target = match self.uniform {
                Some(l) => l,
                None => 0.5 * (self.sizing[a.index()] + self.sizing[b.index()]),
            };
            s.min = s.min.min(l);
            s.max = s.max.max(l);
            s.mean += l;
            n += 1;
            if l >= 0.8 * target * (1.0 - 1e-9) && l <= target * (4.0 / 3.0) * (1.0 + 1e-9) {
                ok += 1;
            }
        }
        if n == 0 {
            return EdgeLengthStats::default();
        }
        s.mean /= n as f64;
        s.within = ok as f64 / n as f64;
        s
    }
}

impl Reference {
    /// The target length at barycentric `b` of triangle `t`.
    fn interpolate_sizing(&self, t: u32, b: [f64; 3]) -> f64 {
        let vs = self.tri_vertices[t as usize];
        b[0] * self.sizing[vs[0] as usize]
            + b[1] * self.sizing[vs[1] as usize]
            + b[2] * self.sizing[vs[2] as usize]
    }

    /// Per triangle, the island (a representative triangle) of corner
    /// column `ci`: triangles joined by edges across which the corner
    /// values agree at both ends.
    fn islands(&self, input: &Mesh, ci: usize) -> Vec<u32> {
        let col = &*input.attrs().halfedge.cols[ci].1;
        let n = self.corners.len();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        fn find(parent: &mut [u32], mut x: u32) -> u32 {
            while parent[x as usize] != x {
                let p = parent[parent[x as usize] as usize];
                parent[x as usize] = p;
                x = p;
            }
            x
        }
        for e in input.eids() {
            let [h, t] = e.halfedges();
            if input.in_hole(h) || input.in_hole(t) {
                continue;
            }
            // Corner at a in h's face is h; in t's face it is next(t).
            if !col.same(h.index(), input.next(t).index())
                || !col.same(input.next(h).index(), t.index())
            {
                continue;
            }
            let (x, y) = (
                self.tri_of_face[input.face_of(h).index()],
                self.tri_of_face[input.face_of(t).index()],
            );
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            if rx != ry {
                parent[rx as usize] = ry;
            }
        }
        (0..n as u32).map(|x| find(&mut parent, x)).collect()
    }
}

/// The position column by vertex slot.
#[inline(always)]
fn positions(mesh: &Mesh) -> &[V3] {
    mesh.position_slots().unwrap_or(&[])
}

/// The number of edges at `v`.
fn valence(mesh: &Mesh, v: Vid) -> usize {
    mesh.outgoing(v).count()
}

/// The cosine of 170°: an angle over it makes a cap.
const CAP_COS: f64 = -0.984_807_753_012_208;

/// The cosine of the largest angle of triangle (a, b, c) (the smallest of
/// its three cosines); 1 for a degenerate one.
fn largest_angle_cos(a: V3, b: V3, c: V3) -> f64 {
    let corner = |p: V3, q: V3, r: V3| {
        let (u, v) = (sub(q, p), sub(r, p));
        let l = (dot(u, u) * dot(v, v)).sqrt();
        if l > 0.0 {
            dot(u, v) / l
        } else {
            1.0
        }
    };
    corner(a, b, c).min(corner(b, c, a)).min(corner(c, a, b))
}

/// Whether flipping the edge a–b of triangles (a, b, c) and (b, a, d) to
/// c–d gives two triangles that face the way the two old ones did.
fn flip_keeps_orientation(pos: &[V3], [a, b, c, d]: [Vid; 4]) -> bool {
    let p = |v: Vid| pos[v.index()];
    let (pa, pb, pc, pd) = (p(a), p(b), p(c), p(d));
    let n_old = {
        let x = cross(sub(pb, pa), sub(pc, pa));
        let y = cross(sub(pa, pb), sub(pd, pb));
        [x[0] + y[0], x[1] + y[1], x[2] + y[2]]
    };
    // New faces: (c, d, b) and (d, c, a).
    let n1 = cross(sub(pd, pc), sub(pb, pc));
    let n2 = cross(sub(pc, pd), sub(pa, pd));
    dot(n1, n_old) > 0.0 && dot(n2, n_old) > 0.0
}
