//! Semi-sharp creases, boundaries and corners, shared by Loop and
//! Catmull-Clark (Pixar's scheme, DeRose, Kass and Truong 1998; the
//! vocabulary is OpenSubdiv's `Sdc::Crease`).
//!
//! - An edge's **sharpness** `s` comes from the crease column (absent, zero
//!   or negative: smooth); boundary edges are infinitely sharp. Its edge
//!   point follows the sharp rule (the midpoint) when `s ≥ 1`, the scheme's
//!   smooth rule when `s ≤ 0`, and the blend `s · sharp + (1 − s) · smooth`
//!   in between; its two children get `s − 1`.
//! - A vertex's **rule** comes from the number of sharp edges (`s > 0`)
//!   around it: fewer than two, *smooth* (a single one is a dart); two,
//!   *crease* (`¾ v + ⅛ (a + b)`, `a` and `b` the far ends of the two
//!   sharp edges); more, or a vertex marked as a corner, *corner* (it stays
//!   put).
//! - Where the rule of a vertex's children differs from its own (a
//!   sharpness at most 1 decays to zero), both rules apply, blended by the
//!   mean sharpness of the edges that decay (OpenSubdiv's transitional
//!   "fractional weight").
//!
//! Every rule is written once, against a [`Sink`] that receives `(vertex,
//! weight)` contributions: a [`PointSink`] sums positions, a [`PlanSink`]
//! records the stencil for the vertex columns interpolated like positions.

use crate::algo::subdivision::{corner_column_index, crease_column_index, unsuitable, Boundary};
use crate::error::Result;
use crate::layout::{Eid, Fid, Hid, Vid};
use crate::mesh::Mesh;
use crate::store::plan::ColumnPlan;

/// Where a stencil's contributions go.
pub(crate) trait Sink {
    /// Parent vertex `v` contributes with weight `w`.
    fn vertex(&mut self, v: Vid, w: f64);
    /// The face point of parent face `f` (the mean of its corners)
    /// contributes with weight `w`.
    fn face(&mut self, f: Fid, w: f64);
}

/// Sums positions.
pub(crate) struct PointSink<'a> {
    /// The parent's positions, by vertex slot.
    pub(crate) p: &'a [[f64; 3]],
    /// Face points by parent face slot's rank (`face_rank`).
    pub(crate) face_points: &'a [[f64; 3]],
    /// The rank of each parent face slot.
    pub(crate) face_rank: &'a [u32],
    /// The sum so far.
    pub(crate) acc: [f64; 3],
}

impl<'a> PointSink<'a> {
    /// An empty sum over `p` (for schemes without face points).
    pub(crate) fn new(p: &'a [[f64; 3]]) -> PointSink<'a> {
        PointSink {
            p,
            face_points: &[],
            face_rank: &[],
            acc: [0.0; 3],
        }
    }

    /// Start a new sum.
    #[inline]
    pub(crate) fn take(&mut self) -> [f64; 3] {
        std::mem::replace(&mut self.acc, [0.0; 3])
    }

    /// The face point of parent face `f`.
    #[inline(always)]
    pub(crate) fn face_point(&self, f: Fid) -> [f64; 3] {
        self.face_points[self.face_rank[f.index()] as usize]
    }
}

impl Sink for PointSink<'_> {
    #[inline(always)]
    fn vertex(&mut self, v: Vid, w: f64) {
        let q = self.p[v.index()];
        self.acc[0] += w * q[0];
        self.acc[1] += w * q[1];
        self.acc[2] += w * q[2];
    }

    #[inline(always)]
    fn face(&mut self, f: Fid, w: f64) {
        let q = self.face_point(f);
        self.acc[0] += w * q[0];
        self.acc[1] += w * q[1];
        self.acc[2] += w * q[2];
    }
}

/// Records stencils as interpolation entries of a [`ColumnPlan`] (face
/// points expanded to the face's corners).
pub(crate) struct PlanSink<'a> {
    pub(crate) mesh: &'a Mesh,
    pub(crate) plan: &'a mut ColumnPlan,
}

impl Sink for PlanSink<'_> {
    #[inline]
    fn vertex(&mut self, v: Vid, w: f64) {
        self.plan.push_input(v.raw(), w);
    }

    fn face(&mut self, f: Fid, w: f64) {
        let n = self.mesh.face_halfedges(f).count().max(1) as f64;
        for h in self.mesh.face_halfedges(f) {
            self.plan.push_input(self.mesh.origin(h).raw(), w / n);
        }
    }
}

/// The smooth rules of a scheme.
pub(crate) trait Mask {
    /// The smooth vertex rule at `v`, with weight `w`.
    fn smooth_vertex<S: Sink>(&self, mesh: &Mesh, v: Vid, ring: &[Spoke], w: f64, sink: &mut S);
    /// The smooth rule of the edge point of `h`'s edge (not a boundary
    /// edge), with weight `w`.
    fn smooth_edge<S: Sink>(&self, mesh: &Mesh, h: Hid, w: f64, sink: &mut S);
}

/// One edge around a vertex.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Spoke {
    /// The half-edge leaving the vertex.
    pub(crate) h: Hid,
    /// Its far end.
    pub(crate) u: Vid,
    /// The edge's sharpness (infinite on the boundary).
    pub(crate) s: f64,
}

/// What a vertex does at one level.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Rule {
    Smooth,
    /// Along the two sharp edges to these vertices.
    Crease(Vid, Vid),
    Corner,
}

/// A vertex's rules at this level and the next, and the weight of its own.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct VertexRule {
    pub(crate) parent: Rule,
    pub(crate) child: Rule,
    /// Weight of `parent` (1 when the two agree).
    pub(crate) weight: f64,
}

/// Sharpness, boundary and corners of one level.
pub(crate) struct Features {
    /// Per parent edge slot, without the boundary (0: smooth); `None`
    /// without a crease column.
    sharpness: Option<Vec<f64>>,
    /// Per parent vertex slot: a corner by the corner column.
    pinned: Option<Vec<bool>>,
    /// Boundary vertices of valence 2 are corners.
    boundary_corners: bool,
    /// Per parent vertex slot: pinned, or on an edge of positive sharpness
    /// (these take the general rule; so does every boundary vertex).
    special: Option<Vec<bool>>,
    /// Interior edges of positive sharpness.
    pub(crate) sharp_edges: usize,
}

impl Features {
    /// Read the columns named by the options.
    ///
    /// # Errors
    /// A missing or mistyped column; a NaN sharpness
    /// ([`Error::Unsuitable`](crate::Error::Unsuitable) at its edge).
    pub(crate) fn read(
        mesh: &Mesh,
        algorithm: &'static str,
        boundary: Boundary,
        corner_column: Option<&str>,
        crease_column: Option<&str>,
    ) -> Result<Features> {
        let mut sharp_edges = 0;
        let sharpness = match crease_column {
            None => None,
            Some(name) => {
                let i = crease_column_index(mesh, name)?;
                let col = &mesh.attrs().edge.cols[i].1;
                let mut s = vec![0.0f64; mesh.edge_slots()];
                for e in mesh.eids() {
                    let Some(x) = col.value_at(e.index()).and_then(|v| v.as_f64()) else {
                        continue;
                    };
                    if x.is_nan() {
                        return Err(unsuitable(
                            algorithm,
                            Some(mesh.ekey(e).into()),
                            format!("its sharpness in {name:?} is NaN"),
                        ));
                    }
                    let [h, t] = e.halfedges();
                    if x > 0.0 && !mesh.in_hole(h) && !mesh.in_hole(t) {
                        s[e.index()] = x;
                        sharp_edges += 1;
                    }
                }
                Some(s)
            }
        };
        let pinned = match corner_column {
            None => None,
            Some(name) => {
                let i = corner_column_index(mesh, name)?;
                let col = &mesh.attrs().vertex.cols[i].1;
                let flags: Vec<bool> = (0..mesh.vertex_slots())
                    .map(|v| {
                        mesh.vertex_live(v)
                            && col.value_at(v) == Some(crate::attr::Value::Bool(true))
                    })
                    .collect();
                Some(flags)
            }
        };
        let special = if sharp_edges > 0 || pinned.is_some() {
            let mut special = pinned
                .clone()
                .unwrap_or_else(|| vec![false; mesh.vertex_slots()]);
            if let Some(s) = &sharpness {
                for e in mesh.eids() {
                    if s[e.index()] > 0.0 {
                        for h in e.halfedges() {
                            special[mesh.origin(h).index()] = true;
                        }
                    }
                }
            }
            Some(special)
        } else {
            None
        };
        Ok(Features {
            sharpness,
            pinned,
            boundary_corners: boundary == Boundary::CreaseAndCorners,
            special,
            sharp_edges,
        })
    }

    /// Whether boundary vertices of valence 2 are corners
    /// ([`Boundary::CreaseAndCorners`]).
    #[inline]
    pub(crate) fn boundary_corners(&self) -> bool {
        self.boundary_corners
    }

    /// Whether `v` needs the general rule (boundary vertices always do).
    #[inline(always)]
    pub(crate) fn is_special(&self, v: Vid) -> bool {
        self.special.as_ref().is_some_and(|s| s[v.index()])
    }

    /// Sharpness of interior edge `e` (0 when smooth).
    #[inline(always)]
    pub(crate) fn sharpness(&self, e: Eid) -> f64 {
        self.sharpness.as_ref().map_or(0.0, |s| s[e.index()])
    }

    /// Sharpness of `e` with the boundary: infinite there.
    #[inline]
    pub(crate) fn edge_sharpness(&self, mesh: &Mesh, e: Eid) -> f64 {
        let [h, t] = e.halfedges();
        if mesh.in_hole(h) || mesh.in_hole(t) {
            f64::INFINITY
        } else {
            self.sharpness(e)
        }
    }

    /// The edges around `v` into `ring`; returns whether `v` is on the
    /// boundary.
    pub(crate) fn gather(&self, mesh: &Mesh, v: Vid, ring: &mut Vec<Spoke>) -> bool {
        ring.clear();
        let mut boundary = false;
        for h in mesh.outgoing(v) {
            let t = h.twin();
            let on_boundary = mesh.in_hole(h) || mesh.in_hole(t);
            boundary |= on_boundary;
            ring.push(Spoke {
                h,
                u: mesh.origin(t),
                s: if on_boundary {
                    f64::INFINITY
                } else {
                    self.sharpness(h.edge())
                },
            });
        }
        boundary
    }

    /// The rules of `v`, whose edges are `ring`.
    pub(crate) fn rule(&self, v: Vid, ring: &[Spoke], boundary: bool) -> VertexRule {
        let pinned = self.pinned.as_ref().is_some_and(|p| p[v.index()])
            || (self.boundary_corners && boundary && ring.len() == 2);
        let parent = rule_above(ring, pinned, 0.0);
        let child = rule_above(ring, pinned, 1.0);
        let weight = if parent == child {
            1.0
        } else {
            let (mut sum, mut n) = (0.0, 0usize);
            for sp in ring {
                if sp.s > 0.0 && sp.s <= 1.0 {
                    sum += sp.s;
                    n += 1;
                }
            }
            if n == 0 {
                1.0
            } else {
                (sum / n as f64).clamp(0.0, 1.0)
            }
        };
        VertexRule {
            parent,
            child,
            weight,
        }
    }
}

/// The rule from the edges sharper than `above`.
fn rule_above(ring: &[Spoke], pinned: bool, above: f64) -> Rule {
    if pinned {
        return Rule::Corner;
    }
    let mut ends = [Vid::NONE; 2];
    let mut n = 0usize;
    for sp in ring {
        if sp.s > above {
            if n < 2 {
                ends[n] = sp.u;
            }
            n += 1;
        }
    }
    match n {
        0 | 1 => Rule::Smooth,
        2 => Rule::Crease(ends[0], ends[1]),
        _ => Rule::Corner,
    }
}

/// Emit rule `rule` at `v` with weight `w`.
#[inline]
fn emit_rule<M: Mask, S: Sink>(
    mask: &M,
    mesh: &Mesh,
    v: Vid,
    ring: &[Spoke],
    rule: Rule,
    w: f64,
    sink: &mut S,
) {
    match rule {
        Rule::Smooth => mask.smooth_vertex(mesh, v, ring, w, sink),
        Rule::Crease(a, b) => {
            sink.vertex(v, 0.75 * w);
            sink.vertex(a, 0.125 * w);
            sink.vertex(b, 0.125 * w);
        }
        Rule::Corner => sink.vertex(v, w),
    }
}

/// The stencil of parent vertex `v`'s new position.
pub(crate) fn emit_vertex<M: Mask, S: Sink>(
    mask: &M,
    mesh: &Mesh,
    v: Vid,
    ring: &[Spoke],
    rule: VertexRule,
    sink: &mut S,
) {
    if rule.weight >= 1.0 {
        emit_rule(mask, mesh, v, ring, rule.parent, 1.0, sink);
    } else {
        emit_rule(mask, mesh, v, ring, rule.parent, rule.weight, sink);
        emit_rule(mask, mesh, v, ring, rule.child, 1.0 - rule.weight, sink);
    }
}

/// The stencil of the edge point of `e`, of sharpness `s` (infinite on the
/// boundary).
pub(crate) fn emit_edge<M: Mask, S: Sink>(mask: &M, mesh: &Mesh, e: Eid, s: f64, sink: &mut S) {
    let [h, t] = e.halfedges();
    let (a, b) = (mesh.origin(h), mesh.origin(t));
    if s >= 1.0 {
        sink.vertex(a, 0.5);
        sink.vertex(b, 0.5);
    } else if s <= 0.0 {
        mask.smooth_edge(mesh, h, 1.0, sink);
    } else {
        sink.vertex(a, 0.5 * s);
        sink.vertex(b, 0.5 * s);
        mask.smooth_edge(mesh, h, 1.0 - s, sink);
    }
}

/// Counts of the rules used at one level, for the report.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct RuleCounts {
    pub(crate) crease: usize,
    pub(crate) corner: usize,
    pub(crate) blended: usize,
}

impl RuleCounts {
    #[inline]
    pub(crate) fn count(&mut self, rule: &VertexRule) {
        if rule.weight < 1.0 {
            self.blended += 1;
        }
        match rule.parent {
            Rule::Smooth => {}
            Rule::Crease(..) => self.crease += 1,
            Rule::Corner => self.corner += 1,
        }
    }
}
