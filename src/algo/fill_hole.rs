//! Hole filling with fairing (Liepa, "Filling holes in meshes", 2003; as
//! pmp-library's `fill_hole` and CGAL's `triangulate_refine_and_fair_hole`):
//! close a hole with triangles that continue the surface around it.
//!
//! **Three steps.**
//! 1. *Triangulate.* The triangulation of the hole's polygon (its rim, the
//!    corners in loop order) of least weight, by dynamic programming over
//!    the rim: a triangle's weight is the pair (the largest dihedral angle
//!    with its neighbours, as `1 − cos`, including the faces across the
//!    rim; the sum of squared triangle areas), compared lexicographically.
//!    The area term is squared, as in pmp-library: on a planar hole every
//!    triangulation has the same plain area, and the squares prefer even
//!    triangles to long fans. Where both tie (angles within 1e-12, areas
//!    within a relative 1e-9: a flat strip, where every triangle has the
//!    same area), the sum of the squared diagonal lengths decides, so a
//!    strip is cut into a zigzag, not a fan. A diagonal that is already an
//!    edge of the mesh (joining two rim corners round the outside) is never
//!    used. A split corner whose two sub-polygons already lose to the best
//!    so far (every term only grows) is skipped before its triangle is
//!    computed. Cost O(n³) time and `52 n²` bytes for a rim of n edges
//!    (the tables are kept between the holes of one call); above
//!    [`FillHoleOptions::max_optimal_rim`] (default 300 edges, under 5 MB
//!    of tables), or when every triangulation needs an existing edge, the
//!    hole is cut by ear clipping instead ([`Mesh::triangulate`], near
//!    O(n log n) on large rims; counted in
//!    [`FillHoleReport::ear_clipped`]).
//! 2. *Refine* ([`FillHoleOptions::refine`]; not for rims over
//!    [`FillHoleOptions::max_refined_rim`], default 2000 edges, whose
//!    patch would grow as the square of the rim: those are filled by the
//!    triangulation alone and counted in [`FillHoleReport::unrefined`]),
//!    inside the patch only, when
//!    some triangle fails Liepa's density test (as CGAL's: α = √2 times
//!    the distance from its centroid to each corner exceeds the local edge
//!    length σ there and the triangle's mean σ, σ of a rim corner being the
//!    mean length of the mesh's edges at it) and some edge is longer than
//!    1.5 l (a patch whose triangles fit is left as it is, as CGAL leaves
//!    it), up to ten rounds as pmp-library: split edges longer than 1.5 l at their
//!    midpoint (then the two quads beside the new vertex into triangles),
//!    collapse new vertices along edges shorter than 0.7 l (unless an edge
//!    would grow past 1.5 l or a triangle turn over), flip edges that bring
//!    the four valences nearer 6, and relax the new vertices (a few sweeps
//!    of the uniform Laplacian). `l` is the mean length of the rim's edges.
//! 3. *Fair* ([`FillHoleOptions::fair`]): the new vertices solve the
//!    `k`-harmonic equation of [`fair`](super::fair) (`k` =
//!    [`FillHoleOptions::fair_order`], default 2: bi-Laplacian, cotangent
//!    weights clamped at zero, mixed-Voronoi masses), with every other
//!    vertex fixed, so the patch meets the surface around it with the same
//!    tangent plane (`k = 2`) or curvature too (`k = 3`). The system is
//!    [`fair`](super::fair)'s region-local one, built over the patch and
//!    its `k` rings only (as [`fair`](super::fair::fair) builds it for a
//!    region), so the cost does not grow with the mesh. With the `sparse`
//!    feature it is solved by faer's sparse
//!    Cholesky factorisation; without it by conjugate gradients on the same
//!    system (the same surface to solver precision; slower on large
//!    patches). New vertices within `k − 1` rings of another hole keep
//!    their refined positions (their Laplacian would be one-sided).
//!
//! **Attributes.** Everything runs through the operators
//! ([`Mesh::fill_hole`], [`Mesh::split_face`], [`Mesh::split_edge`],
//! [`Mesh::collapse_edge`], [`Mesh::flip_edge`], [`Mesh::set_position`]),
//! so every column follows its rule. Before the first split, the new face
//! takes its values from the face across the most rim edges by that
//! column's rule (`interpolate` from that one face: a copy for
//! interpolated colours and for material ids, nothing for conserved
//! quantities), and each of its corners copies the corner of the same rim
//! vertex in the face across the rim edge leaving that vertex: a UV map
//! continues into the patch with no new seam (where the rim crosses a seam,
//! the patch takes one side's values). New vertices and their corners get
//! their values where they are born: the midpoint of the edge they split
//! (`split_edge` at ½), so every value in the patch is a convex combination
//! of rim values, within the rim's range. They are not re-interpolated when
//! relaxation and fairing move the vertex (the values follow the
//! triangulation, not the final positions).
//!
//! **All or nothing.** Each call runs in a [transaction](Mesh::transaction)
//! (one undo step, for all the holes of [`fill_holes`] and
//! [`fill_holes_at`]): a refused hole, a failed solve or a cancelled
//! [`fill_holes`] leaves the mesh exactly as it was. Holes [`fill_holes`] does not fill (a rim longer
//! than [`FillHoleOptions::max_rim`], a rim that passes a vertex twice) are
//! listed in [`FillHoleReport::skipped`]; [`fill_hole`] refuses them.
//!
//! ```
//! use meshloom::algo::fill_hole::{fill_hole, FillHoleOptions};
//! // A sphere with a cap cut out: the patch follows the sphere.
//! let mut mesh = meshloom::shapes::icosphere(3);
//! let cap: Vec<_> = mesh
//!     .faces()
//!     .filter(|&f| mesh.face_centroid(f).unwrap()[2] > 0.8)
//!     .collect();
//! for f in cap {
//!     mesh.remove_face(f)?;
//! }
//! let hole = mesh.holes().next().unwrap();
//! let report = fill_hole(&mut mesh, hole, &FillHoleOptions::default())?;
//! assert!(mesh.is_closed());
//! assert!(report.vertices_added > 0);
//! for &v in &report.vertices {
//!     let p = mesh.position(v)?;
//!     let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
//!     assert!((r - 1.0).abs() < 0.1, "radius {r}");
//! }
//! mesh.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::collections::{BTreeSet, HashMap, HashSet};

use super::laplacian::LaplaceWeights;
use super::progress::Progress;
use super::subdivision::Counts;
use crate::error::{Error, Refusal, Result};
use crate::keys::{FaceKey, HalfedgeKey, VertexKey};
use crate::layout::{Eid, Fid, Hid, Vid};
use crate::mesh::Mesh;
use crate::ops::refuse;
use crate::vec3::{add, cross, dot, norm, normalize_or_zero, sub, V3};

const ALGORITHM: &str = "fill_hole";
const ALGORITHM_ALL: &str = "fill_holes";

/// Refinement rounds (as pmp-library).
const ROUNDS: usize = 10;
/// Split edges longer than this times the rim's mean edge length.
const LONG: f64 = 1.5;
/// Liepa's density factor α (√2, as CGAL's default): a triangle is too
/// large when α times its centroid's distance to each corner exceeds the
/// local edge length there.
const DENSITY: f64 = std::f64::consts::SQRT_2;
/// Collapse edges shorter than this times the rim's mean edge length.
const SHORT: f64 = 0.7;
/// Sweeps of uniform Laplacian relaxation per round.
const RELAX_SWEEPS: usize = 3;
/// Dihedral terms closer than this count as equal (rounding on flat holes).
const ANGLE_TIE: f64 = 1e-12;
/// Area sums closer than this fraction count as equal (rounding: on a flat
/// strip every triangulation has the same area).
const AREA_TIE: f64 = 1e-9;

/// Options of [`fill_hole`] and [`fill_holes`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct FillHoleOptions {
    /// Holes whose rim has more edges than this are not filled:
    /// [`fill_holes`] skips them (listed in the report), [`fill_hole`]
    /// refuses. Default: none (every hole).
    pub max_rim: Option<usize>,
    /// Refine the patch to the rim's edge length (default `true`). Without
    /// it the patch is the triangulation alone and has no new vertices.
    pub refine: bool,
    /// Fair the new vertices (default `true`; needs `refine` to have made
    /// any).
    pub fair: bool,
    /// The power `k` of the Laplacian in fairing, 1 to 3 (default 2).
    pub fair_order: u32,
    /// The largest rim (in edges) triangulated by the O(n³) optimal
    /// triangulation; longer rims are cut by ear clipping, near
    /// O(n log n) (default 300; raise it for the optimal triangulation of
    /// larger holes, at O(n³) time: 1000 edges take about 8 s).
    pub max_optimal_rim: usize,
    /// The largest rim (in edges) whose patch is refined and faired;
    /// longer rims are filled by the triangulation alone (counted in
    /// [`FillHoleReport::unrefined`]). The refined patch grows with the
    /// hole's area, as n² for a round rim of n edges (1000 edges: about
    /// 90,000 new vertices, 1.5 s; 100,000 edges would need about 10⁹).
    /// Default 2000.
    pub max_refined_rim: usize,
}

crate::choice::setters!(FillHoleOptions {
    max_rim: Option<usize>,
    refine: bool,
    fair: bool,
    fair_order: u32,
    max_optimal_rim: usize,
    max_refined_rim: usize,
});

impl Default for FillHoleOptions {
    fn default() -> Self {
        FillHoleOptions {
            max_rim: None,
            refine: true,
            fair: true,
            fair_order: 2,
            max_optimal_rim: 300,
            max_refined_rim: 2000,
        }
    }
}

/// What [`fill_hole`] or [`fill_holes`] did.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct FillHoleReport {
    /// Counts of the input.
    pub input: Counts,
    /// Counts of the result.
    pub output: Counts,
    /// Holes closed.
    pub holes_filled: usize,
    /// Faces the mesh gained (every face of every patch).
    pub faces_added: usize,
    /// Vertices the mesh gained (refinement).
    pub vertices_added: usize,
    /// Holes triangulated by ear clipping instead of the optimal
    /// triangulation (rim over [`FillHoleOptions::max_optimal_rim`], or no
    /// triangulation without an existing edge).
    pub ear_clipped: usize,
    /// Holes filled by the triangulation alone, with no refinement or
    /// fairing, because their rim is over
    /// [`FillHoleOptions::max_refined_rim`].
    pub unrefined: usize,
    /// The patches' faces.
    pub faces: Vec<FaceKey>,
    /// The new vertices.
    pub vertices: Vec<VertexKey>,
    /// Holes left open by [`fill_holes`]: a rim longer than
    /// [`FillHoleOptions::max_rim`], or one that passes a vertex twice.
    pub skipped: Vec<FaceKey>,
}

fn unsuitable(key: Option<crate::keys::AnyKey>, reason: impl Into<String>) -> Error {
    Error::Unsuitable {
        algorithm: ALGORITHM,
        key,
        reason: reason.into(),
    }
}

fn check_options(options: &FillHoleOptions) -> Result<()> {
    let k = options.fair_order;
    if !(1..=3).contains(&k) {
        return Err(unsuitable(None, format!("fair order {k} is not 1, 2 or 3")));
    }
    Ok(())
}

/// Fill hole `hole` (see the module docs), its rim starting at the hole's
/// own half-edge.
///
/// # Errors
/// [`Error::StaleKey`]; [`Error::NoPositions`]; as
/// [`Mesh::check_fill_hole`] ([`Refusal::NotHole`], [`Refusal::Degenerate`]
/// below three rim edges, [`Refusal::NonManifold`] for a rim that passes a
/// vertex twice); [`Error::Unsuitable`] for a fair order outside 1..=3, a
/// rim longer than [`FillHoleOptions::max_rim`], or a fairing system that
/// cannot be solved; a refusal of [`Mesh::triangulate`] when even ear
/// clipping needs an existing edge. The mesh is unchanged after any error.
///
/// # Complexity
/// O(n³) for a rim of n ≤ [`FillHoleOptions::max_optimal_rim`] edges (the
/// triangulation), near O(n log n) above it (ear clipping), plus the
/// refinement and one sparse factorisation over the patch (which grows
/// with the hole's area); nothing over the whole mesh.
///
/// ```
/// use meshloom::algo::fill_hole::{fill_hole, FillHoleOptions};
/// let mut mesh = meshloom::shapes::grid(6, 6, meshloom::shapes::GridFaces::Triangles);
/// let middle: Vec<_> = mesh
///     .faces()
///     .filter(|&f| {
///         let c = mesh.face_centroid(f).unwrap();
///         (c[0] - 3.0).abs() < 1.2 && (c[1] - 3.0).abs() < 1.2
///     })
///     .collect();
/// for f in middle {
///     mesh.remove_face(f)?;
/// }
/// assert_eq!(mesh.hole_count(), 2); // the grid's outline and the new hole
/// let hole = mesh.holes().min_by_key(|&h| mesh.face(h).unwrap().degree()).unwrap();
/// let report = fill_hole(&mut mesh, hole, &FillHoleOptions::default())?;
/// assert_eq!((report.holes_filled, mesh.hole_count()), (1, 1));
/// // A flat hole is filled flat.
/// assert!(report.vertices.iter().all(|&v| mesh.position(v).unwrap()[2].abs() < 1e-9));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn fill_hole(
    mesh: &mut Mesh,
    hole: FaceKey,
    options: &FillHoleOptions,
) -> Result<FillHoleReport> {
    let h = mesh.check_face(hole)?;
    if !mesh.is_hole(h) {
        return Err(refuse(ALGORITHM, hole, Refusal::NotHole));
    }
    let start = mesh.face_halfedge(h);
    fill_from(mesh, start, options)
}

/// As [`fill_hole`], for the hole on the side of `border` (a half-edge
/// in a hole), with the rim starting at `border`: the triangulation's ties
/// are broken in rim order, so the start can matter (pmp-library and CGAL
/// take a border half-edge too).
///
/// # Errors
/// As [`fill_hole`]; [`Refusal::NotHole`] when `border` is not in a hole.
pub fn fill_hole_at(
    mesh: &mut Mesh,
    border: HalfedgeKey,
    options: &FillHoleOptions,
) -> Result<FillHoleReport> {
    let h = mesh.check_halfedge(border)?;
    if !mesh.in_hole(h) {
        return Err(refuse(ALGORITHM, border, Refusal::NotHole));
    }
    fill_from(mesh, h, options)
}

/// As [`fill_hole_at`] for several holes, each from its border
/// half-edge, in order, in one transaction (one undo step for the call):
/// what a caller filling chosen holes should use instead of a loop of
/// [`fill_hole_at`] (one step, and one set of triangulation tables, for all
/// of them).
///
/// # Errors
/// As [`fill_hole_at`] for any of the half-edges (two in the same hole:
/// the second is no longer in a hole, [`Refusal::NotHole`]). The mesh is
/// unchanged after any error (the holes filled before it are undone).
///
/// # Complexity
/// The sum of [`fill_hole_at`]'s over the holes.
///
/// ```
/// use meshloom::algo::fill_hole::{fill_holes_at, FillHoleOptions};
/// let mut mesh = meshloom::shapes::icosphere(2);
/// let faces: Vec<_> = mesh.faces().step_by(40).collect();
/// for f in faces {
///     mesh.remove_face(f)?;
/// }
/// let holes: Vec<_> = mesh.holes().collect();
/// let borders: Vec<_> = holes
///     .iter()
///     .map(|&h| mesh.face(h).unwrap().halfedge().key())
///     .collect();
/// let report = fill_holes_at(&mut mesh, &borders, &FillHoleOptions::default())?;
/// assert_eq!(report.holes_filled, holes.len());
/// assert!(mesh.is_closed());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn fill_holes_at(
    mesh: &mut Mesh,
    borders: &[HalfedgeKey],
    options: &FillHoleOptions,
) -> Result<FillHoleReport> {
    check_options(options)?;
    if !mesh.has_positions() {
        return Err(Error::NoPositions);
    }
    mesh.transaction(|m| {
        let mut report = FillHoleReport::starting(m);
        let mut tables = Tables::default();
        for &border in borders {
            let h = m.check_halfedge(border)?;
            if !m.in_hole(h) {
                return Err(refuse(ALGORITHM, border, Refusal::NotHole));
            }
            let start = checked_start(m, h, options)?;
            report.add(fill_one(m, start, options, &mut tables)?);
        }
        Ok(report.finished(m))
    })
}

/// `start` (a half-edge in a hole) after the checks of [`fill_hole_at`]:
/// the hole can be filled and its rim is not over
/// [`FillHoleOptions::max_rim`].
fn checked_start(mesh: &Mesh, start: Hid, options: &FillHoleOptions) -> Result<Hid> {
    let hole = mesh.fkey(mesh.face_of(start));
    mesh.check_fill_hole(hole)?;
    let n = mesh.face_halfedges_from(start).count();
    if options.max_rim.is_some_and(|max| n > max) {
        return Err(unsuitable(
            Some(hole.into()),
            format!("the rim has {n} edges, more than max_rim"),
        ));
    }
    Ok(start)
}

fn fill_from(mesh: &mut Mesh, start: Hid, options: &FillHoleOptions) -> Result<FillHoleReport> {
    check_options(options)?;
    if !mesh.has_positions() {
        return Err(Error::NoPositions);
    }
    let start = checked_start(mesh, start, options)?;
    mesh.transaction(|m| {
        let mut report = FillHoleReport::starting(m);
        let patch = fill_one(m, start, options, &mut Tables::default())?;
        report.add(patch);
        Ok(report.finished(m))
    })
}

/// Fill every hole of `mesh` (see the module docs) but those over
/// [`FillHoleOptions::max_rim`] and those whose rim passes a vertex twice
/// (listed in [`FillHoleReport::skipped`]). `progress` hears of each hole
/// and may cancel.
///
/// # Errors
/// [`Error::NoPositions`]; [`Error::Unsuitable`] for a fair order outside
/// 1..=3 or a hole whose fairing system cannot be solved; a refusal of
/// [`Mesh::triangulate`] when even ear clipping needs an existing edge;
/// [`Error::Cancelled`]. The mesh is unchanged after any error (every hole
/// filled so far is undone).
///
/// # Complexity
/// The sum of [`fill_hole`]'s over the holes.
///
/// ```
/// use meshloom::algo::fill_hole::{fill_holes, FillHoleOptions};
/// use meshloom::algo::Progress;
/// let mut mesh = meshloom::shapes::icosphere(2);
/// let faces: Vec<_> = mesh.faces().step_by(40).collect();
/// for f in faces {
///     mesh.remove_face(f)?;
/// }
/// let holes = mesh.hole_count();
/// let report = fill_holes(&mut mesh, &FillHoleOptions::default(), Progress::none())?;
/// assert_eq!(report.holes_filled, holes);
/// assert!(mesh.is_closed());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn fill_holes(
    mesh: &mut Mesh,
    options: &FillHoleOptions,
    mut progress: Progress<'_>,
) -> Result<FillHoleReport> {
    check_options(options)?;
    if !mesh.has_positions() {
        return Err(Error::NoPositions);
    }
    let holes: Vec<FaceKey> = mesh.holes().collect();
    let total = holes.len() as u64;
    mesh.transaction(|m| {
        let mut report = FillHoleReport::starting(m);
        let mut tables = Tables::default();
        for (i, &hole) in holes.iter().enumerate() {
            progress.report(ALGORITHM_ALL, "holes", i as u64, total)?;
            let h = m.check_face(hole)?;
            let n = m.face_halfedges(h).count();
            if options.max_rim.is_some_and(|max| n > max) || m.check_fill_hole(hole).is_err() {
                report.skipped.push(hole);
                continue;
            }
            let start = m.face_halfedge(h);
            let patch = fill_one(m, start, options, &mut tables)?;
            report.add(patch);
        }
        progress.report(ALGORITHM_ALL, "holes", total, total)?;
        Ok(report.finished(m))
    })
}

impl FillHoleReport {
    /// An empty report with the counts of `mesh` as both input and output.
    fn starting(mesh: &Mesh) -> FillHoleReport {
        let counts = Counts::of(mesh);
        FillHoleReport {
            input: counts,
            output: counts,
            ..FillHoleReport::default()
        }
    }

    /// The report with the output counts of `mesh`.
    fn finished(mut self, mesh: &Mesh) -> FillHoleReport {
        self.output = Counts::of(mesh);
        self
    }

    fn add(&mut self, patch: Patch) {
        self.holes_filled += 1;
        self.faces_added += patch.faces.len();
        self.vertices_added += patch.vertices.len();
        self.ear_clipped += usize::from(patch.ear_clipped);
        self.unrefined += usize::from(patch.unrefined);
        self.faces.extend(patch.faces);
        self.vertices.extend(patch.vertices);
    }
}

/// One filled hole.
struct Patch {
    faces: Vec<FaceKey>,
    vertices: Vec<VertexKey>,
    ear_clipped: bool,
    unrefined: bool,
}

/// The elements of a patch while it is refined.
struct Work {
    /// Edges inside the patch (not the rim).
    edges: BTreeSet<Eid>,
    /// Vertices made by refinement.
    new: BTreeSet<Vid>,
}

/// Fill the hole through `start` (checked fillable); inside a transaction.
fn fill_one(
    mesh: &mut Mesh,
    start: Hid,
    options: &FillHoleOptions,
    tables: &mut Tables,
) -> Result<Patch> {
    let rim: Vec<Hid> = mesh.face_halfedges_from(start).collect();
    let corners: Vec<Vid> = rim.iter().map(|&h| mesh.origin(h)).collect();
    let n = rim.len();
    let p = mesh.position_slots().ok_or(Error::NoPositions)?;
    let mean_length = rim
        .iter()
        .map(|&h| norm(sub(p[mesh.dest(h).index()], p[mesh.origin(h).index()])))
        .sum::<f64>()
        / n as f64;
    let plan = if n == 3 {
        Some(Vec::new())
    } else if n <= options.max_optimal_rim {
        optimal_triangulation(mesh, &rim, p, tables)
    } else {
        None
    };
    // Liepa's density test on the planned triangles (CGAL's too): the
    // patch is refined only when some triangle is too large for the
    // density of the mesh around the rim.
    // Rims over max_refined_rim are filled by the triangulation alone:
    // their refined patch would grow as n².
    let unrefined = options.refine && n > options.max_refined_rim;
    let wants_refinement = options.refine
        && !unrefined
        && match &plan {
            Some(plan) => plan_fails_density(mesh, &corners, plan, p),
            None => true,
        };
    let neighbour = most_common_outer_face(mesh, &rim);

    // Commit: the hole becomes a face with its neighbours' values.
    let hole = mesh.fkey(mesh.face_of(start));
    mesh.fill_hole(hole)?;
    let f = hole.id();
    for &h in &rim {
        let across = mesh.next(h.twin());
        mesh.attrs_mut().halfedge.copy(across.index(), h.index());
    }
    mesh.attrs_mut()
        .face
        .interpolate(f.index(), &[(neighbour.index(), 1.0)]);

    let mut work = Work {
        edges: BTreeSet::new(),
        new: BTreeSet::new(),
    };
    let ear_clipped = plan.is_none();
    match plan {
        Some(diagonals) => cut_by_plan(mesh, hole, &corners, &diagonals, &mut work)?,
        None => {
            let rim_edges: HashSet<Eid> = rim.iter().map(|h| h.edge()).collect();
            for g in mesh.triangulate(hole)? {
                for h in mesh.face_halfedges(g.id()) {
                    if !rim_edges.contains(&h.edge()) {
                        work.edges.insert(h.edge());
                    }
                }
            }
        }
    }
    // Refine only a patch that fails the density test and has an edge to
    // split: a triangulation whose triangles already fit gains nothing
    // from the rounds.
    if wants_refinement
        && work
            .edges
            .iter()
            .any(|&e| length(mesh, e) > LONG * mean_length)
    {
        refine(mesh, &mut work, mean_length)?;
    }
    if options.fair && !work.new.is_empty() {
        fair_patch(mesh, &work.new, options.fair_order)?;
    }
    let mut faces: BTreeSet<Fid> = BTreeSet::new();
    for &e in &work.edges {
        for h in e.halfedges() {
            faces.insert(mesh.face_of(h));
        }
    }
    if faces.is_empty() {
        faces.insert(f);
    }
    Ok(Patch {
        faces: faces.into_iter().map(|f| mesh.fkey(f)).collect(),
        vertices: work.new.iter().map(|&v| mesh.vkey(v)).collect(),
        ear_clipped,
        unrefined,
    })
}

/// Liepa's density test over the planned triangles (`plan` as
/// [`optimal_triangulation`] returns it; empty for a triangle): whether
/// some triangle `(a, b, c)` with centroid `m` has, at every corner `x`,
/// `DENSITY * |m - x|` above both the corner's scale `σ(x)` (the mean
/// length of the mesh's edges at `x`, before the fill) and the mean scale
/// `σ(m)` of the three corners: the test by which Liepa (and CGAL's
/// `triangulate_refine_and_fair_hole`) decide to split a triangle at its
/// centroid. A triangle that passes it nowhere fits the mesh's density.
fn plan_fails_density(mesh: &Mesh, corners: &[Vid], plan: &[(u32, u32, u32)], p: &[V3]) -> bool {
    let scale: Vec<f64> = corners
        .iter()
        .map(|&v| {
            let (sum, count) = mesh.outgoing(v).fold((0.0, 0.0), |(s, c), g| {
                (
                    s + norm(sub(p[mesh.dest(g).index()], p[v.index()])),
                    c + 1.0,
                )
            });
            if count > 0.0 {
                sum / count
            } else {
                0.0
            }
        })
        .collect();
    let too_large = |t: [u32; 3]| {
        let q = t.map(|i| p[corners[i as usize].index()]);
        let s = t.map(|i| scale[i as usize]);
        let centroid = [0, 1, 2].map(|c| (q[0][c] + q[1][c] + q[2][c]) / 3.0);
        let mean_scale = (s[0] + s[1] + s[2]) / 3.0;
        (0..3).all(|x| {
            let d = DENSITY * norm(sub(centroid, q[x]));
            d > mean_scale && d > s[x]
        })
    };
    if plan.is_empty() {
        return corners.len() == 3 && too_large([0, 1, 2]);
    }
    plan.iter().any(|&(i, m, k)| too_large([i, m, k]))
}

/// The face across the most rim edges (the first such in rim order).
fn most_common_outer_face(mesh: &Mesh, rim: &[Hid]) -> Fid {
    let mut count: HashMap<Fid, usize> = HashMap::new();
    let mut best = (0, mesh.face_of(rim[0].twin()));
    for &h in rim {
        let g = mesh.face_of(h.twin());
        let c = count.entry(g).or_insert(0);
        *c += 1;
        if *c > best.0 {
            best = (*c, g);
        }
    }
    best.1
}

// ---------------------------------------------------------------------------
// 1. The optimal triangulation
// ---------------------------------------------------------------------------

/// `(largest dihedral term, sum of squared areas, sum of squared diagonal
/// lengths)`, compared lexicographically; the angle within
/// [`ANGLE_TIE`], the area within [`AREA_TIE`] of the incumbent's.
#[derive(Clone, Copy)]
struct Weight {
    angle: f64,
    area: f64,
    /// The tie-break: on a flat strip every triangulation has the same
    /// angles and areas, and the shortest diagonals avoid long fans that
    /// refinement would have to split.
    len: f64,
}

impl Weight {
    const NONE: Weight = Weight {
        angle: f64::INFINITY,
        area: f64::INFINITY,
        len: f64::INFINITY,
    };

    fn is_none(self) -> bool {
        self.angle == f64::INFINITY
    }

    fn better_than(self, other: Weight) -> bool {
        if other.is_none() {
            return !self.is_none();
        }
        if self.angle < other.angle - ANGLE_TIE {
            return true;
        }
        if self.angle > other.angle + ANGLE_TIE {
            return false;
        }
        let tol = AREA_TIE * other.area;
        self.area < other.area - tol || (self.area <= other.area + tol && self.len < other.len)
    }

    /// Whether no candidate at least as heavy as `self` in every term
    /// (angle and area) with the same `len` can beat `best`: the test that
    /// skips a split corner before its triangle is computed.
    fn cannot_beat(self, best: Weight) -> bool {
        if best.is_none() {
            return false;
        }
        if self.angle > best.angle + ANGLE_TIE {
            return true;
        }
        if self.angle < best.angle - ANGLE_TIE {
            return false;
        }
        let tol = AREA_TIE * best.area;
        self.area > best.area + tol || (self.area >= best.area - tol && self.len >= best.len)
    }
}

/// The dynamic programme's tables, kept between the holes of one call. Entry
/// `(i, k)` (at `i * n + k`) is the sub-polygon of rim corners `i..=k`: its
/// least weight, the corner its last triangle `(i, m, k)` splits it at, and
/// that triangle's unit normal.
#[derive(Default)]
struct Tables {
    /// The number of rim corners.
    n: usize,
    weight: Vec<Weight>,
    split: Vec<u32>,
    normal: Vec<V3>,
    /// The rim corners' positions.
    pos: Vec<V3>,
    /// The unit normals of the faces across the rim edges.
    outer: Vec<V3>,
}

impl Tables {
    /// Empties the tables for the rim `rim` and reads its corners and the
    /// faces across it.
    fn load(&mut self, mesh: &Mesh, rim: &[Hid], p: &[V3]) {
        let n = rim.len();
        self.n = n;
        self.weight.clear();
        self.weight.resize(n * n, Weight::NONE);
        self.split.clear();
        self.split.resize(n * n, u32::MAX);
        self.normal.clear();
        self.normal.resize(n * n, [0.0; 3]);
        self.pos.clear();
        self.pos
            .extend(rim.iter().map(|&h| p[mesh.origin(h).index()]));
        self.outer.clear();
        self.outer.extend(
            rim.iter()
                .map(|&h| normalize_or_zero(mesh.loop_normal(h.twin()).unwrap_or([0.0; 3]))),
        );
        // A rim edge is a sub-polygon of two corners: weightless.
        for i in 0..n - 1 {
            self.weight[i * n + i + 1] = Weight {
                angle: 0.0,
                area: 0.0,
                len: 0.0,
            };
        }
    }

    /// Fills entry `(i, k)` from the entries of the shorter sub-polygons,
    /// trying every split corner `m` between them; `closing` when `(i, k)`
    /// is the whole rim (its diagonal is the rim edge `n − 1 → 0`).
    #[inline]
    fn fill(&mut self, i: usize, k: usize, closing: bool) {
        let n = self.n;
        let at = |i: usize, k: usize| i * n + k;
        let Tables {
            weight,
            split,
            normal,
            pos,
            outer,
            ..
        } = self;
        let d = sub(pos[k], pos[i]);
        let diagonal = if closing { 0.0 } else { dot(d, d) };
        let mut best = Weight::NONE;
        let (mut best_m, mut best_n) = (u32::MAX, [0.0; 3]);
        for m in i + 1..k {
            let (left, right) = (weight[at(i, m)], weight[at(m, k)]);
            if left.is_none() || right.is_none() {
                continue;
            }
            // Every term only grows from here: skip the triangle when
            // even this bound loses.
            let bound = Weight {
                angle: left.angle.max(right.angle),
                area: left.area + right.area,
                len: left.len + right.len + diagonal,
            };
            if bound.cannot_beat(best) {
                continue;
            }
            let c = cross(sub(pos[m], pos[i]), d);
            let area2 = dot(c, c);
            // The area is known before the angles (a square root and
            // a division): the bound with it may lose already.
            let bound = Weight {
                area: bound.area + area2,
                ..bound
            };
            if bound.cannot_beat(best) {
                continue;
            }
            let tri = normalize_or_zero(c);
            let n_left = if m == i + 1 {
                outer[i]
            } else {
                normal[at(i, m)]
            };
            let n_right = if k == m + 1 {
                outer[m]
            } else {
                normal[at(m, k)]
            };
            let mut angle = bound
                .angle
                .max(1.0 - dot(tri, n_left))
                .max(1.0 - dot(tri, n_right));
            if closing {
                angle = angle.max(1.0 - dot(tri, outer[n - 1]));
            }
            let w = Weight { angle, ..bound };
            if w.better_than(best) {
                best = w;
                best_m = m as u32;
                best_n = tri;
            }
        }
        weight[at(i, k)] = best;
        split[at(i, k)] = best_m;
        normal[at(i, k)] = best_n;
    }

    /// The triangles `(i, m, k)` of the whole rim's best triangulation, read
    /// back from the split corners, each before the two it splits off.
    fn triangles(&self) -> Vec<(u32, u32, u32)> {
        let n = self.n;
        let mut out = Vec::with_capacity(n - 2);
        let mut stack = vec![(0usize, n - 1)];
        while let Some((i, k)) = stack.pop() {
            if k < i + 2 {
                continue;
            }
            let m = self.split[i * n + k];
            out.push((i as u32, m, k as u32));
            stack.push((i, m as usize));
            stack.push((m as usize, k));
        }
        out
    }
}

/// The diagonals of the least-weight triangulation of the rim, as pairs of
/// rim indices `(i, k)` with the split corner `m` (`(i, m, k)` a triangle),
/// in the order to cut them; `None` when every triangulation needs an edge
/// the mesh has already.
fn optimal_triangulation(
    mesh: &Mesh,
    rim: &[Hid],
    p: &[V3],
    tables: &mut Tables,
) -> Option<Vec<(u32, u32, u32)>> {
    let n = rim.len();
    tables.load(mesh, rim, p);
    let blocked = existing_diagonals(mesh, rim);
    for len in 2..n {
        for i in 0..n - len {
            let k = i + len;
            let closing = i == 0 && k == n - 1;
            if !closing && blocked.contains(&(i as u32, k as u32)) {
                continue;
            }
            tables.fill(i, k, closing);
        }
    }
    // Entry (0, n − 1), the whole rim.
    if tables.weight[n - 1].is_none() {
        return None;
    }
    Some(tables.triangles())
}

/// Pairs of rim indices `(i, j)`, `i < j`, not neighbours on the rim, that
/// an edge of the mesh joins already.
fn existing_diagonals(mesh: &Mesh, rim: &[Hid]) -> HashSet<(u32, u32)> {
    let n = rim.len();
    let index: HashMap<Vid, u32> = rim
        .iter()
        .enumerate()
        .map(|(i, &h)| (mesh.origin(h), i as u32))
        .collect();
    let mut out = HashSet::new();
    for (i, &h) in rim.iter().enumerate() {
        for g in mesh.outgoing(mesh.origin(h)) {
            if let Some(&j) = index.get(&mesh.dest(g)) {
                let (a, b) = (i.min(j as usize), i.max(j as usize));
                let neighbours = b == a + 1 || (a == 0 && b == n - 1);
                if !neighbours {
                    out.insert((a as u32, b as u32));
                }
            }
        }
    }
    out
}

/// Cut the new face `face` (the rim `corners`, in loop order) into the
/// planned triangles `(i, m, k)`: each cuts `[i..=k]` into `[i..=m]`,
/// `[m..=k]` and the triangle.
fn cut_by_plan(
    mesh: &mut Mesh,
    face: FaceKey,
    corners: &[Vid],
    plan: &[(u32, u32, u32)],
    work: &mut Work,
) -> Result<()> {
    // The face holding polygon [i..=k], by (i, k).
    let n = corners.len();
    let mut holder: HashMap<(u32, u32), FaceKey> = HashMap::new();
    holder.insert((0, n as u32 - 1), face);
    for &(i, m, k) in plan {
        let f = holder[&(i, k)];
        let [vi, vm, vk] = [i, m, k].map(|x| mesh.vkey(corners[x as usize]));
        if m > i + 1 {
            // The new half-edge v_m -> v_i lies in the part from v_i to v_m.
            let h = mesh.split_face(f, vm, vi)?;
            let h = mesh.check_halfedge(h)?;
            work.edges.insert(h.edge());
            holder.insert((i, m), mesh.fkey(mesh.face_of(h)));
        }
        if k > m + 1 {
            let h = mesh.split_face(f, vk, vm)?;
            let h = mesh.check_halfedge(h)?;
            work.edges.insert(h.edge());
            holder.insert((m, k), mesh.fkey(mesh.face_of(h)));
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// 2. Refinement
// ---------------------------------------------------------------------------

fn live_edge(mesh: &Mesh, e: Eid) -> bool {
    mesh.edge_live(e.index())
}

fn point(mesh: &Mesh, v: Vid) -> V3 {
    mesh.position_slots().map_or([0.0; 3], |p| p[v.index()])
}

fn length(mesh: &Mesh, e: Eid) -> f64 {
    let h = e.halfedge(0);
    norm(sub(point(mesh, mesh.dest(h)), point(mesh, mesh.origin(h))))
}

fn refine(mesh: &mut Mesh, work: &mut Work, l: f64) -> Result<()> {
    let (lmin, lmax) = (SHORT * l, LONG * l);
    for _ in 0..ROUNDS {
        let mut changed = split_long_edges(mesh, work, lmax)?;
        changed += collapse_short_edges(mesh, work, lmin, lmax);
        changed += flip_edges(mesh, work);
        relax(mesh, work)?;
        if changed == 0 {
            break;
        }
    }
    Ok(())
}

fn split_long_edges(mesh: &mut Mesh, work: &mut Work, lmax: f64) -> Result<usize> {
    let mut count = 0;
    let list: Vec<Eid> = work.edges.iter().copied().collect();
    for e in list {
        if !live_edge(mesh, e) || length(mesh, e) <= lmax {
            continue;
        }
        let m = mesh.split_edge(mesh.ekey(e), 0.5)?;
        let mv = m.id();
        work.new.insert(mv);
        count += 1;
        let out: Vec<Hid> = mesh.outgoing(mv).collect();
        for h in out {
            work.edges.insert(h.edge());
            let f = mesh.face_of(h);
            if mesh.is_hole(f) || mesh.face_degree(f) <= 3 {
                continue;
            }
            let opposite = mesh.origin(mesh.next(mesh.next(h)));
            let cut = mesh.split_face(mesh.fkey(f), m, mesh.vkey(opposite))?;
            work.edges.insert(mesh.check_halfedge(cut)?.edge());
        }
    }
    Ok(count)
}

fn collapse_short_edges(mesh: &mut Mesh, work: &mut Work, lmin: f64, lmax: f64) -> usize {
    let mut count = 0;
    let list: Vec<Eid> = work.edges.iter().copied().collect();
    for e in list {
        if !live_edge(mesh, e) || length(mesh, e) >= lmin {
            continue;
        }
        let [h, t] = e.halfedges();
        // Remove a new vertex: h runs from the removed vertex to the kept.
        let h = if work.new.contains(&mesh.origin(h)) {
            h
        } else if work.new.contains(&mesh.origin(t)) {
            t
        } else {
            continue;
        };
        if !collapse_keeps_shape(mesh, h, lmax) {
            continue;
        }
        let gone = mesh.origin(h);
        if mesh.collapse_edge(mesh.hkey(h)).is_ok() {
            work.new.remove(&gone);
            count += 1;
        }
    }
    work.edges.retain(|&e| live_edge(mesh, e));
    count
}

/// Whether collapsing `origin(h)` into `dest(h)` keeps every new edge at
/// most `lmax` long and turns no triangle over.
fn collapse_keeps_shape(mesh: &Mesh, h: Hid, lmax: f64) -> bool {
    let (a, b) = (mesh.origin(h), mesh.dest(h));
    let pb = point(mesh, b);
    let pa = point(mesh, a);
    for g in mesh.outgoing(a) {
        let x = mesh.dest(g);
        if x != b && norm(sub(point(mesh, x), pb)) > lmax {
            return false;
        }
        let f = mesh.face_of(g);
        if mesh.is_hole(f) {
            continue;
        }
        let y = mesh.dest(mesh.next(g));
        if x == b || y == b {
            continue;
        }
        let (px, py) = (point(mesh, x), point(mesh, y));
        let before = cross(sub(px, pa), sub(py, pa));
        let after = cross(sub(px, pb), sub(py, pb));
        if dot(before, after) <= 0.0 {
            return false;
        }
    }
    true
}

fn valence(mesh: &Mesh, v: Vid) -> i64 {
    mesh.outgoing(v).count() as i64
}

fn flip_edges(mesh: &mut Mesh, work: &mut Work) -> usize {
    let mut count = 0;
    let list: Vec<Eid> = work.edges.iter().copied().collect();
    for e in list {
        if !live_edge(mesh, e) {
            continue;
        }
        let [h, t] = e.halfedges();
        let (fh, ft) = (mesh.face_of(h), mesh.face_of(t));
        if mesh.is_hole(fh) || mesh.is_hole(ft) {
            continue;
        }
        if mesh.face_degree(fh) != 3 || mesh.face_degree(ft) != 3 {
            continue;
        }
        let (a, b) = (mesh.origin(h), mesh.dest(h));
        let c = mesh.dest(mesh.next(h));
        let d = mesh.dest(mesh.next(t));
        let target = |v: Vid| if mesh.on_boundary(v) { 4 } else { 6 };
        let dev = |v: Vid, change: i64| {
            let x = valence(mesh, v) + change - target(v);
            x * x
        };
        let before = dev(a, 0) + dev(b, 0) + dev(c, 0) + dev(d, 0);
        let after = dev(a, -1) + dev(b, -1) + dev(c, 1) + dev(d, 1);
        if after >= before || !flip_keeps_shape(mesh, [a, b, c, d]) {
            continue;
        }
        if mesh.flip_edge(mesh.ekey(e)).is_ok() {
            count += 1;
        }
    }
    count
}

/// Whether flipping the edge `a–b` of triangles `(a, b, c)` and `(b, a, d)`
/// to `c–d` gives triangles `(c, a, d)` and `(d, b, c)` facing the same way
/// as before.
fn flip_keeps_shape(mesh: &Mesh, [a, b, c, d]: [Vid; 4]) -> bool {
    let [pa, pb, pc, pd] = [a, b, c, d].map(|v| point(mesh, v));
    let n1 = cross(sub(pb, pa), sub(pc, pa));
    let n2 = cross(sub(pa, pb), sub(pd, pb));
    let old = add(n1, n2);
    let m1 = cross(sub(pa, pc), sub(pd, pc));
    let m2 = cross(sub(pb, pd), sub(pc, pd));
    dot(m1, old) > 0.0 && dot(m2, old) > 0.0 && dot(m1, m2) > 0.0
}

/// Move each new vertex to the mean of its neighbours, a few sweeps.
fn relax(mesh: &mut Mesh, work: &Work) -> Result<()> {
    for _ in 0..RELAX_SWEEPS {
        for &v in &work.new {
            let mut sum = [0.0; 3];
            let mut count = 0.0;
            for g in mesh.outgoing(v) {
                let q = point(mesh, mesh.dest(g));
                sum = add(sum, q);
                count += 1.0;
            }
            if count > 0.0 {
                let key = mesh.vkey(v);
                mesh.set_position(key, sum.map(|c| c / count))?;
            }
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// 3. Fairing over the patch
// ---------------------------------------------------------------------------

/// Solve the `k`-harmonic equation for the vertices `new` (those not
/// within `k − 1` rings of a boundary), everything else fixed, and move
/// them there: [`fair`](super::fair)'s region-local system.
fn fair_patch(mesh: &mut Mesh, new: &BTreeSet<Vid>, k: u32) -> Result<()> {
    let free: Vec<Vid> = new
        .iter()
        .copied()
        .filter(|&v| !super::fair::near_boundary(mesh, v, k - 1))
        .collect();
    if free.is_empty() {
        return Ok(());
    }
    let p = mesh.position_slots().ok_or(Error::NoPositions)?;
    let solution =
        super::fair::solve_local(mesh, p, &free, k, LaplaceWeights::Cotan).map_err(|reason| {
            unsuitable(
                Some(mesh.vkey(free[0]).into()),
                format!("fairing the patch: {reason}"),
            )
        })?;
    if let Some(i) = solution
        .positions
        .iter()
        .position(|q| !q.iter().all(|c| c.is_finite()))
    {
        return Err(unsuitable(
            Some(mesh.vkey(free[i]).into()),
            "the faired position is not finite",
        ));
    }
    for (&v, &q) in free.iter().zip(&solution.positions) {
        let key = mesh.vkey(v);
        mesh.set_position(key, q)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_compare_angle_first() {
        let a = Weight {
            angle: 0.1,
            area: 5.0,
            len: 9.0,
        };
        let b = Weight {
            angle: 0.2,
            area: 1.0,
            len: 1.0,
        };
        assert!(a.better_than(b));
        assert!(!b.better_than(a));
        assert!(a.better_than(Weight::NONE));
        assert!(!Weight::NONE.better_than(a));
    }

    #[test]
    fn weights_break_area_ties_by_diagonal_length() {
        let a = Weight {
            angle: 0.0,
            area: 1.0,
            len: 2.0,
        };
        let b = Weight {
            angle: 0.0,
            area: 1.0 + 1e-13,
            len: 3.0,
        };
        assert!(a.better_than(b));
        assert!(!b.better_than(a));
        // A bound that cannot beat: same angle and area, longer diagonals.
        assert!(b.cannot_beat(a));
        assert!(!a.cannot_beat(b));
        let c = Weight {
            angle: 0.0,
            area: 0.5,
            len: 30.0,
        };
        // A smaller area wins over shorter diagonals.
        assert!(c.better_than(a));
        assert!(!a.cannot_beat(Weight { area: 2.0, ..c }));
    }
}
