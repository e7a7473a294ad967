//! Quadric error decimation (Garland & Heckbert 1997): collapse edges of a
//! triangle mesh, cheapest first, until a vertex or face count, a ratio or
//! an error is reached.
//!
//! **What it does.** Every vertex carries the quadric of the planes of its
//! faces, weighted by area (boundary, seam and material lines add planes
//! across them). An edge costs the quadric error of its collapse at the
//! best point: the minimiser of the two quadrics summed (*optimal
//! placement*), or, when that 3×3 system is singular (a flat or straight
//! neighbourhood), the best of the two ends and the midpoint. Each collapse
//! goes through [`Mesh::collapse_edge_to`]'s checks (the link condition,
//! no non-manifold result) and its rules: every attribute column of every
//! arena follows its [`Rule`](crate::attr::Rule), with the weights of the
//! new point's projection on the edge, and corner columns per wedge, so UVs,
//! colours and material ids come out right without user code.
//!
//! **Constraints** (the shared vocabulary of
//! [`constraints`](super::constraints): [`DecimateOptions::boundary`],
//! `seams`, `feature_angle`, `features`, `pinned`). Boundary edges, UV
//! seams (corners whose values differ across an edge, in any half-edge
//! column) and material borders (a face column, where asked) are *lines*.
//! With [`Keep::Slide`] (the default) a vertex on exactly two line edges
//! may only collapse along one of them, into the neighbour there (whose
//! position stays), so a line keeps the input's polyline and its ends do
//! not slide off it (meshoptimizer's "border" and "seam" vertex kinds); a
//! vertex at the end or crossing of lines, or where a line turns by more
//! than the feature angle (45° without one: the corner of a square), never
//! moves. With [`Keep::Lock`] every vertex of the line stays and so do its
//! edges; with [`Keep::Free`] its edges are like any other. Feature edges
//! (by dihedral angle or an edge column) are locked: their vertices never
//! move; nor do pinned vertices. A kept boundary never loses a loop (an
//! edge of a triangular hole is not collapsed; counted as a topology
//! refusal). A free vertex collapsing into a constrained one takes its
//! position.
//!
//! **Guards**, each an option of [`DecimateOptions`]: the largest turn of a
//! face normal (flips are refused by default), the smallest triangle
//! quality, the largest valence. The report counts the collapses each
//! refused.
//!
//! **Attribute error.** Vertex and corner columns of floats (`f32`, `f64`
//! and arrays of them) named in [`DecimateOptions::attributes`] take part in
//! the error as in Hoppe 1999's quadric: per face, the linear function
//! that interpolates the column over the face; an attribute quadric per
//! vertex, each column scaled by its weight; the value at the new vertex is
//! what the column's rule gives there (interpolation at the projection), so
//! the error measures the result the mesh will hold.
//!
//! **How, and how fast.** As meshoptimizer's simplifier rather than pmp's
//! global heap: in passes. Each pass scores every edge, keeps each vertex's
//! cheapest edge, sorts those (one `u64` key each: error bits above the
//! half-edge), and collapses in that order, skipping any edge whose ends
//! were touched earlier in the pass (their quadrics changed) and stopping
//! the pass when errors climb past 1.5× the error at the rank the target
//! needs. Quadrics are `f32` over positions scaled into the unit box.
//! Memory: 40 bytes of quadric, 8 bytes of candidate and one byte of flags
//! a vertex, and a bit an edge (about 49.5 bytes a vertex on a triangle
//! mesh); attribute columns add `4 × (1 + 4·dims)` bytes a vertex each.
//! `BENCHMARKS.md` times it beside pmp-library, OpenMesh, CGAL and
//! meshoptimizer's `simplify`.
//!
//! **All or nothing.** Without a progress callback
//! ([`Progress::none`]) the decimator edits the mesh in place: every input
//! check comes before the first collapse and nothing after it can fail. With
//! one (which may cancel), it works on a copy and hands the result over at
//! the end, so a cancelled run leaves the mesh exactly as it was; the copy
//! costs the mesh's own size again for the duration (about 132 bytes a
//! vertex plus the attribute columns).
//!
//! ```
//! use meshloom::algo::decimate::{decimate, DecimateOptions, StopReason, Target};
//! use meshloom::algo::Progress;
//! let mut mesh = meshloom::shapes::icosphere(4); // 2562 vertices
//! let report = decimate(&mut mesh, &DecimateOptions::to(Target::Ratio(0.1)), Progress::none())?;
//! assert_eq!(report.stopped_by, StopReason::Target);
//! assert_eq!(mesh.vertex_count(), 257);
//! assert_eq!(mesh.euler_characteristic(), 2);
//! assert!(report.error < 0.05); // a unit sphere, within 5 % of its radius
//! mesh.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

mod attributes;
mod lod;
mod passes;
mod quadric;
mod setup;
#[cfg(test)]
mod tests;

use super::constraints::{Constraints, EdgeBits, FIXED, FREE, LINE};
use super::subdivision::Counts;
use crate::attr::{EdgeAttr, VertexAttr};
use crate::error::{Error, Result};
use crate::layout::{Eid, Hid, Vid};
use crate::mesh::Mesh;
use crate::vec3::{self, cross, dot, sub, V3};
use attributes::AttrError;
pub use lod::{lod_chain, replay, LodChain, LodLevel, LodOptions};
use quadric::{Quadric, Q64};

/// The line rule, shared by every algorithm: see [`Constraints`].
pub use super::constraints::Keep;
use super::progress::Progress;

const ALGORITHM: &str = "decimate";

/// When to stop, by count.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Target {
    /// At this many vertices.
    Vertices(usize),
    /// At this many faces (or one fewer: most collapses remove two).
    Faces(usize),
    /// At this share of the vertices, rounded up (`0.1`: a tenth).
    Ratio(f64),
    /// No count: only [`DecimateOptions::max_error`] stops.
    None,
}

/// A vertex or corner column that takes part in the error, with its weight
/// (error per unit of value, against distance in mesh units).
#[derive(Clone, Debug, PartialEq)]
pub struct AttributeWeight {
    /// The column's name; a vertex column is looked up first, then a
    /// half-edge (corner) column.
    pub name: String,
    /// Its weight.
    pub weight: f64,
}

/// Options of [`decimate`]. `DecimateOptions::default()` decimates to half
/// the vertices; [`DecimateOptions::to`] names the target.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct DecimateOptions {
    /// When to stop by count (default: half the vertices).
    pub target: Target,
    /// Stop before a collapse whose error (a distance in mesh units: the
    /// root of the area-weighted mean squared distance to the planes of the
    /// faces merged into the vertex) would pass this. Default: none.
    pub max_error: Option<f64>,
    /// Refuse a collapse that turns a face's normal by more than this
    /// angle (radians), or leaves a face without area. Default: 75°, which
    /// refuses flips; `None` checks nothing.
    pub max_normal_deviation: Option<f64>,
    /// Refuse a collapse that makes a triangle of lower quality than this
    /// (`4√3·area / Σ edge²`: 1 for an equilateral triangle, 0 for a
    /// sliver), unless the worst triangle around it was worse before.
    /// Default: none.
    pub min_quality: Option<f64>,
    /// Refuse a collapse that leaves a vertex with more neighbours than
    /// this. Default: none.
    pub max_valence: Option<usize>,
    /// Boundary loops (default [`Keep::Slide`]; see [`Constraints`]).
    pub boundary: Keep,
    /// UV seams and every other discontinuity of a half-edge column, and
    /// the borders of [`DecimateOptions::material`] (default
    /// [`Keep::Slide`]).
    pub seams: Keep,
    /// Edges whose faces meet at more than this dihedral angle (radians)
    /// are feature edges: their vertices never move. Also the turn that
    /// makes a line's vertex a corner (45° without it). Default: none.
    pub feature_angle: Option<f64>,
    /// An edge column: edges whose value is `true` are feature edges.
    pub features: Option<EdgeAttr<bool>>,
    /// A vertex column: vertices whose value is `true` are pinned (never
    /// move).
    pub pinned: Option<VertexAttr<bool>>,
    /// A face column whose borders (edges between faces with different
    /// values, such as a material id) are kept as seams are. Default: none.
    pub material: Option<String>,
    /// Columns in the error (default: none, positions only).
    pub attributes: Vec<AttributeWeight>,
}

crate::algo::constraints::constrained!(DecimateOptions);

crate::choice::setters!(DecimateOptions {
    target: Target,
    max_error: Option<f64>,
    max_normal_deviation: Option<f64>,
    min_quality: Option<f64>,
    max_valence: Option<usize>,
    boundary: Keep,
    seams: Keep,
    feature_angle: Option<f64>,
    features: Option<EdgeAttr<bool>>,
    pinned: Option<VertexAttr<bool>>,
    material: Option<String>,
    attributes: Vec<AttributeWeight>,
});

impl Default for DecimateOptions {
    fn default() -> Self {
        DecimateOptions {
            target: Target::Ratio(0.5),
            max_error: None,
            max_normal_deviation: Some(75f64.to_radians()),
            min_quality: None,
            max_valence: None,
            boundary: Keep::Slide,
            seams: Keep::Slide,
            feature_angle: None,
            features: None,
            pinned: None,
            material: None,
            attributes: Vec::new(),
        }
    }
}

impl DecimateOptions {
    /// The defaults with another target.
    pub fn to(target: Target) -> DecimateOptions {
        DecimateOptions {
            target,
            ..DecimateOptions::default()
        }
    }
}

/// Why decimation stopped.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum StopReason {
    /// The target count was reached.
    Target,
    /// The next collapse would have passed [`DecimateOptions::max_error`].
    MaxError,
    /// No edge could be collapsed any more: every one left is constrained or
    /// refused (the counts in [`Refused`] say by what).
    NoCollapses,
}

crate::choice::choices!(StopReason {
    Target = "target",
    MaxError = "max-error",
    NoCollapses = "no-collapses",
});

/// Collapses refused, by what refused them. A candidate refused in one
/// pass is counted again if it is tried again in a later one.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct Refused {
    /// By the operator (the link condition, a non-manifold result), or
    /// because the collapse would close a kept boundary's triangular hole.
    pub topology: usize,
    /// By [`DecimateOptions::max_normal_deviation`].
    pub normal: usize,
    /// By [`DecimateOptions::min_quality`].
    pub quality: usize,
    /// By [`DecimateOptions::max_valence`].
    pub valence: usize,
}

/// What [`decimate`] did.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct DecimateReport {
    /// What stopped it.
    pub stopped_by: StopReason,
    /// The largest error of a collapse made (a distance in mesh units; see
    /// [`DecimateOptions::max_error`]).
    pub error: f64,
    /// Counts of the input.
    pub input: Counts,
    /// Counts of the result (at a level of a chain: of that level).
    pub output: Counts,
    /// Collapses made.
    pub collapses: usize,
    /// Passes over the candidates.
    pub passes: usize,
    /// Collapses refused, by guard.
    pub refused: Refused,
    /// Vertices that could not move at the start (pinned, on a feature or
    /// a locked line, the corners, ends and crossings of sliding lines).
    pub fixed: usize,
    /// Whether the run worked on a copy (a progress callback was given).
    pub on_copy: bool,
}

/// Decimate a triangle mesh by quadric error edge collapse (see the
/// [module](self) for the method, the constraints and the costs).
///
/// # Arguments
/// `options` say when to stop and what to keep; `progress` is told the
/// collapses made against those needed (stage `"collapses"`), and may
/// cancel.
///
/// # Returns
/// A [`DecimateReport`]: what stopped it, the largest error, the counts and
/// the refusals.
///
/// # Errors
/// [`Error::NoPositions`]; [`Error::Unsuitable`] for a face that is not a
/// triangle (naming it), a target ratio outside `0..=1`, no target and no
/// `max_error`, an attribute that is not a column of floats; the attribute
/// errors of a column handle or name ([`Error::AttributeHandle`],
/// [`Error::AttributeMissing`]); [`Error::Cancelled`]. On every error the
/// mesh is unchanged.
///
/// # Complexity
/// O(E log E) a pass over the E live edges, O(degree) a collapse; the
/// passes shrink with the mesh (a dozen or so to reach 10 %).
///
/// # Examples
/// ```
/// use meshloom::algo::decimate::{decimate, DecimateOptions, Target};
/// use meshloom::algo::Progress;
/// use meshloom::shapes::{grid, GridFaces};
/// let mut mesh = grid(40, 40, GridFaces::Triangles); // flat: every collapse is free
/// let report = decimate(&mut mesh, &DecimateOptions::to(Target::Faces(100)), Progress::none())?;
/// assert!(mesh.face_count() <= 100 && mesh.face_count() >= 99);
/// assert!(report.error < 1e-9);
/// assert_eq!(mesh.hole_count(), 1); // the boundary is kept
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn decimate(
    mesh: &mut Mesh,
    options: &DecimateOptions,
    progress: Progress<'_>,
) -> Result<DecimateReport> {
    mesh.as_one_step("Decimate", |mesh| decimate_run(mesh, options, progress))
}

/// [`decimate`] itself, outside the journal's step.
fn decimate_run(
    mesh: &mut Mesh,
    options: &DecimateOptions,
    mut progress: Progress<'_>,
) -> Result<DecimateReport> {
    let stops = [Stop::from_target(mesh, options)?];
    run(
        mesh,
        options,
        &stops,
        &mut progress,
        &mut |_, _, _| {},
        None,
    )
}

/// A resolved stop: a vertex or face count (or none) and an error.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Stop {
    pub(crate) vertices: usize,
    pub(crate) faces: usize,
}

impl Stop {
    pub(crate) fn from_target(mesh: &Mesh, options: &DecimateOptions) -> Result<Stop> {
        let unsuitable = |reason: String| Error::Unsuitable {
            algorithm: ALGORITHM,
            key: None,
            reason,
        };
        let nv = mesh.vertex_count();
        Ok(match options.target {
            Target::Vertices(n) => Stop {
                vertices: n,
                faces: 0,
            },
            Target::Faces(n) => Stop {
                vertices: 0,
                faces: n,
            },
            Target::Ratio(r) => {
                if !(0.0..=1.0).contains(&r) {
                    return Err(unsuitable(format!(
                        "the target ratio {r} is not between 0 and 1"
                    )));
                }
                Stop {
                    vertices: (r * nv as f64).ceil() as usize,
                    faces: 0,
                }
            }
            Target::None => {
                if options.max_error.is_none() {
                    return Err(unsuitable(
                        "no target count and no max_error: nothing would stop it".into(),
                    ));
                }
                Stop {
                    vertices: 0,
                    faces: 0,
                }
            }
        })
    }

    fn reached(&self, mesh: &Mesh) -> bool {
        mesh.vertex_count() <= self.vertices || mesh.face_count() <= self.faces
    }

    /// Vertices still to remove (a face target needs about one per two).
    fn remaining(&self, mesh: &Mesh) -> usize {
        let by_v = mesh.vertex_count().saturating_sub(self.vertices);
        let by_f = mesh.face_count().saturating_sub(self.faces).div_ceil(2);
        by_v.min(by_f)
    }
}

/// One collapse as made: the half-edge (its origin merged into its
/// destination) and the new position. Replaying these on the mesh they were
/// made on repeats the decimation without its search.
#[derive(Copy, Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Collapse {
    /// The half-edge collapsed: `origin` merges into `dest`.
    pub halfedge: crate::HalfedgeKey,
    /// Where the merged vertex went.
    pub position: [f64; 3],
}

/// Called when a stop is reached: the mesh, the stop's index and the report
/// so far.
pub(crate) type LevelHook<'h> = dyn FnMut(&Mesh, usize, &DecimateReport) + 'h;

/// The driver behind [`decimate`] and the level-of-detail chain: decimate
/// through `stops` in order (each at most as many vertices and faces as
/// the one before), calling `on_level` at each, recording collapses when
/// asked. Works on a copy when `progress` can cancel.
pub(crate) fn run(
    mesh: &mut Mesh,
    options: &DecimateOptions,
    stops: &[Stop],
    progress: &mut Progress<'_>,
    on_level: &mut LevelHook<'_>,
    record: Option<&mut Vec<Collapse>>,
) -> Result<DecimateReport> {
    // Every check that can fail comes before the first change.
    let engine = setup::prepare(mesh, options)?;
    if progress.is_active() {
        let mut work = mesh.clone();
        let report = engine.run(&mut work, options, stops, progress, on_level, record, true)?;
        mesh.replace_with(work);
        Ok(report)
    } else {
        engine.run(mesh, options, stops, progress, on_level, record, false)
    }
}

/// The vertex kind's bits of the flag byte ([`FREE`], [`LINE`],
/// [`FIXED`]: the classifier's kinds).
const KIND: u8 = 3;
/// Set on a vertex whose quadric changed in this pass.
const TOUCHED: u8 = 0x80;

/// A chosen collapse: `origin(h)` into `dest(h)` at `p` (mesh units), with
/// `t` its projection's weight and `err` its cost (squared, unit box).
#[derive(Copy, Clone, Debug)]
struct Choice {
    h: Hid,
    p: V3,
    t: f64,
    err: f64,
}

/// Why a guard refused.
#[derive(Copy, Clone)]
enum Guard {
    Normal,
    Quality,
    Valence,
}

/// The decimator's state: everything it keeps per vertex and edge.
pub(crate) struct Engine {
    /// Per vertex slot.
    quadrics: Vec<Quadric>,
    /// Per vertex slot: kind and the touched bit.
    flags: Vec<u8>,
    /// Per edge slot, one bit: the edge lies on a sliding line.
    lines: EdgeBits,
    /// Positions to the unit box: `(x − centre) · inv_scale`.
    centre: V3,
    inv_scale: f64,
    scale: f64,
    /// The attribute part of the error, when columns are named.
    attrs: Option<AttrError>,
    fixed: usize,
}

impl Engine {
    #[inline(always)]
    fn kind(&self, v: Vid) -> u8 {
        self.flags[v.index()] & KIND
    }

    #[inline(always)]
    fn on_line(&self, e: Eid) -> bool {
        self.lines.get(e)
    }

    #[inline(always)]
    fn unit(&self, p: V3) -> V3 {
        vec3::scale(sub(p, self.centre), self.inv_scale)
    }

    /// The cost of collapsing into `p` (unit box, squared).
    #[inline(always)]
    fn cost(&self, mesh: &Mesh, q: &Q64, h: Hid, p: V3, t: f64) -> f64 {
        let w = q.weight();
        let geo = if w > 0.0 {
            q.eval(self.unit(p)) / w
        } else {
            0.0
        };
        match &self.attrs {
            None => geo,
            Some(at) => geo + at.cost(mesh, h, self.unit(p), t),
        }
    }

    /// The collapse of edge `e` this decimator would make, if any.
    #[inline]
    fn evaluate(&self, mesh: &Mesh, pos: &[[f64; 3]], e: Eid) -> Option<Choice> {
        let [h0, h1] = e.halfedges();
        let a = mesh.origin(h0);
        let b = mesh.origin(h1);
        let (ka, kb) = (self.kind(a), self.kind(b));
        let (pa, pb) = (pos[a.index()], pos[b.index()]);
        let q = self.quadrics[a.index()]
            .wide()
            .sum(self.quadrics[b.index()].wide());
        // (survivor-side half-edge, position, t)
        let (h, p, t) = match (ka, kb) {
            (FREE, FREE) => {
                let best = q.minimiser().map(|x| {
                    let p = vec3::add(vec3::scale(x, self.scale), self.centre);
                    (p, projection(pa, pb, p))
                });
                match best {
                    Some((p, t)) if p.iter().all(|c| c.is_finite()) => (h0, p, t),
                    _ => {
                        // Singular: the best of a, b and the midpoint.
                        let mid = vec3::scale(vec3::add(pa, pb), 0.5);
                        let mut out = (h0, pb, 1.0);
                        let mut best = f64::INFINITY;
                        for (p, t) in [(pb, 1.0), (pa, 0.0), (mid, 0.5)] {
                            let c = q.eval(self.unit(p));
                            if c < best {
                                best = c;
                                out = (h0, p, t);
                            }
                        }
                        out
                    }
                }
            }
            (FREE, _) => (h0, pb, 1.0),
            (_, FREE) => (h1, pa, 1.0),
            (LINE, LINE) if self.on_line(e) => {
                // Along the line, onto the cheaper end: the survivor keeps
                // a position of the input's line, so the line never leaves
                // the input's polyline (a point between the ends would cut
                // across a bend).
                if q.eval(self.unit(pb)) <= q.eval(self.unit(pa)) {
                    (h0, pb, 1.0)
                } else {
                    (h1, pa, 1.0)
                }
            }
            (LINE, FIXED) if self.on_line(e) => (h0, pb, 1.0),
            (FIXED, LINE) if self.on_line(e) => (h1, pa, 1.0),
            _ => return None,
        };
        let err = self.cost(mesh, &q, h, p, t);
        Some(Choice { h, p, t, err })
    }

    /// The guards of a collapse of `c.h` to `c.p`.
    fn guards(
        &self,
        mesh: &Mesh,
        pos: &[[f64; 3]],
        c: &Choice,
        options: &DecimateOptions,
    ) -> Option<Guard> {
        let cos_max = options.max_normal_deviation.map(f64::cos);
        let min_q = options.min_quality;
        if cos_max.is_none() && min_q.is_none() && options.max_valence.is_none() {
            return None;
        }
        let h = c.h;
        let t = h.twin();
        let (fl, fr) = (mesh.face_of(h), mesh.face_of(t));
        let p = c.p;
        let (mut old_q, mut new_q) = (f64::INFINITY, f64::INFINITY);
        let mut degree = 0usize;
        for start in [h, t] {
            let v = mesh.origin(start);
            let pv = pos[v.index()];
            let mut o = start;
            let mut budget = mesh.halfedge_slots();
            loop {
                degree += 1;
                let f = mesh.face_of(o);
                if !mesh.is_hole(f) {
                    let n1 = mesh.next(o);
                    let v1 = pos[mesh.origin(n1).index()];
                    let v2 = pos[mesh.origin(mesh.next(n1)).index()];
                    if min_q.is_some() {
                        old_q = old_q.min(quality(pv, v1, v2));
                    }
                    if f != fl && f != fr {
                        let before = cross(sub(v1, pv), sub(v2, pv));
                        let after = cross(sub(v1, p), sub(v2, p));
                        if let Some(cm) = cos_max {
                            let (lb, la) = (dot(before, before), dot(after, after));
                            if lb > 0.0
                                && (la.is_nan()
                                    || la <= 1e-24 * lb
                                    || dot(before, after) < cm * (lb * la).sqrt())
                            {
                                return Some(Guard::Normal);
                            }
                        }
                        if min_q.is_some() {
                            new_q = new_q.min(quality(p, v1, v2));
                        }
                    }
                }
                o = mesh.next(o.twin());
                budget -= 1;
                if o == start || budget == 0 {
                    break;
                }
            }
        }
        if let Some(m) = min_q {
            if new_q < m && new_q < old_q {
                return Some(Guard::Quality);
            }
        }
        if let Some(max) = options.max_valence {
            let tri = |x: Hid| mesh.next(mesh.next(mesh.next(x))) == x;
            // The ends' neighbours, less each other, less the apexes they
            // share (one per triangle that disappears).
            let shared = usize::from(tri(h)) + usize::from(tri(t));
            if (degree - 2).saturating_sub(shared) > max {
                return Some(Guard::Valence);
            }
        }
        None
    }
}

/// Whether collapsing `h` would close a triangular hole beside it.
#[inline(always)]
fn closes_hole(mesh: &Mesh, h: Hid) -> bool {
    [h, h.twin()]
        .into_iter()
        .any(|x| mesh.in_hole(x) && mesh.next(mesh.next(mesh.next(x))) == x)
}

/// The parameter of `p`'s projection on `a → b`, clamped to `0..=1`.
#[inline(always)]
fn projection(a: V3, b: V3, p: V3) -> f64 {
    let d = sub(b, a);
    let l = dot(d, d);
    if l.is_nan() || l <= 0.0 {
        return 1.0;
    }
    (dot(sub(p, a), d) / l).clamp(0.0, 1.0)
}

/// `4√3·area / Σ edge²`: 1 for an equilateral triangle.
#[inline(always)]
fn quality(a: V3, b: V3, c: V3) -> f64 {
    let (ab, bc, ca) = (sub(b, a), sub(c, b), sub(a, c));
    let n = cross(ab, sub(c, a));
    let s = dot(ab, ab) + dot(bc, bc) + dot(ca, ca);
    if s > 0.0 {
        2.0 * 3f64.sqrt() * dot(n, n).sqrt() / s
    } else {
        0.0
    }
}
