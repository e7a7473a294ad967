//! Attribute columns of a new level: which plan each column follows, the
//! plans of the face-splitting schemes, and the assembly of the new
//! [`AttrStore`].

use crate::algo::subdivision::creases::{emit_edge, emit_vertex, Features, Mask, PlanSink};
use crate::algo::subdivision::refine::{face_ring, Cut, Refinement};
use crate::algo::subdivision::{VertexData, VertexInterpolation};
use crate::attr::{Interpolate, Value, ValueType};
use crate::layout::{Eid, Hid, Vid};
use crate::mesh::Mesh;
use crate::store::plan::ColumnPlan;
use crate::store::{AttrStore, Column, Columns, ErasedColumn};
use crate::vec3::{cross, norm, sub};

/// The plans of one level, built on first use.
pub(crate) trait ColumnPlans {
    /// Vertices: old ones keep their values, new ones interpolate their
    /// linear contributors.
    fn vertex_linear(&self) -> ColumnPlan;
    /// Vertices: every vertex interpolates the scheme's stencil.
    fn vertex_smooth(&self) -> ColumnPlan;
    /// Half-edges (corners).
    fn halfedge(&self) -> ColumnPlan;
    /// Edges.
    fn edge(&self) -> ColumnPlan;
    /// Faces and holes.
    fn face(&self) -> ColumnPlan;
}

/// Whether vertex column `i` is interpolated with the stencil.
fn smooth_column(cols: &Columns, i: usize, data: &VertexData) -> bool {
    let (name, col) = &cols.cols[i];
    let linear_type = cols.meta[i]
        .value_type
        .is_none_or(|t| matches!(t, ValueType::F32 | ValueType::F64 | ValueType::List));
    col.interpolates_linearly() && linear_type && data.of(name) == VertexInterpolation::Smooth
}

/// A lazily built plan.
struct Lazy<'a> {
    build: &'a dyn Fn() -> ColumnPlan,
    plan: Option<ColumnPlan>,
}

impl<'a> Lazy<'a> {
    fn new(build: &'a dyn Fn() -> ColumnPlan) -> Lazy<'a> {
        Lazy { build, plan: None }
    }

    fn get(&mut self) -> &ColumnPlan {
        self.plan.get_or_insert_with(self.build)
    }
}

/// Every column of `cols` rebuilt, column `i` from `pick(i)`.
fn rebuild(
    cols: &Columns,
    mut pick: impl FnMut(usize, &dyn ErasedColumn) -> Box<dyn ErasedColumn>,
) -> Columns {
    Columns {
        cols: cols
            .cols
            .iter()
            .enumerate()
            .map(|(i, (name, col))| (name.clone(), pick(i, col.as_ref())))
            .collect(),
        meta: cols.meta.clone(),
        log_below: 0,
        dirty: false,
        fallible: cols.fallible,
    }
}

/// The columns of the new level: positions from `positions` (when the
/// parent's are dense), every other column rebuilt from its plan; the
/// crease column's children get the sharpness in `crease` (new edge slot,
/// value).
pub(crate) fn finish_columns(
    parent: &Mesh,
    plans: &impl ColumnPlans,
    positions: Option<Vec<[f64; 3]>>,
    data: &VertexData,
    crease: Option<(&str, Vec<(u32, f64)>)>,
) -> AttrStore {
    let a = &parent.attrs();
    let (linear, smooth) = (|| plans.vertex_linear(), || plans.vertex_smooth());
    let (mut linear, mut smooth) = (Lazy::new(&linear), Lazy::new(&smooth));
    let mut positions = positions;
    let vertex = rebuild(&a.vertex, |i, col| {
        if Some(i) == a.position {
            if let Some(p) = positions.take() {
                return Box::new(Column::<[f64; 3], Interpolate>::dense(p));
            }
            return col.rebuilt(smooth.get());
        }
        if smooth_column(&a.vertex, i, data) {
            col.rebuilt(smooth.get())
        } else {
            col.rebuilt(linear.get())
        }
    });
    let build_h = || plans.halfedge();
    let mut hplan = Lazy::new(&build_h);
    let halfedge = rebuild(&a.halfedge, |_, col| col.rebuilt(hplan.get()));
    let build_e = || plans.edge();
    let mut eplan = Lazy::new(&build_e);
    let mut edge = rebuild(&a.edge, |_, col| col.rebuilt(eplan.get()));
    let build_f = || plans.face();
    let mut fplan = Lazy::new(&build_f);
    let face = rebuild(&a.face, |_, col| col.rebuilt(fplan.get()));
    if let Some((name, values)) = crease {
        if let Some(i) = edge.find(name) {
            let ty = edge.meta[i]
                .value_type
                .or_else(|| edge.cols[i].1.portable_type());
            let col = &mut edge.cols[i].1;
            for (slot, s) in values {
                let v = match ty {
                    Some(ValueType::F32) => Value::F32(s as f32),
                    _ => Value::F64(s),
                };
                col.set_value(slot as usize, Some(&v));
            }
        }
    }
    AttrStore {
        vertex,
        halfedge,
        edge,
        face,
        position: a.position,
    }
}

/// The sharpness of a child of an edge of sharpness `s`.
#[inline]
pub(crate) fn decayed(s: f64) -> f64 {
    if s.is_infinite() && s > 0.0 {
        s
    } else {
        (s - 1.0).max(0.0)
    }
}

/// The crease column's values for the children of every parent edge that
/// has one: `children(e)` names the new edge slots.
pub(crate) fn crease_children(
    parent: &Mesh,
    name: &str,
    mut children: impl FnMut(Eid, &mut dyn FnMut(u32)),
) -> Vec<(u32, f64)> {
    let Some(i) = parent.attrs().edge.find(name) else {
        return Vec::new();
    };
    let col = &parent.attrs().edge.cols[i].1;
    let mut out = Vec::new();
    for e in parent.eids() {
        if let Some(s) = col.value_at(e.index()).and_then(|v| v.as_f64()) {
            let s = decayed(s);
            children(e, &mut |slot| out.push((slot, s)));
        }
    }
    out
}

// ----- the plans of the face-splitting schemes ----------------------------------

/// Vertices, linearly: old ones kept, edge points the mean of the edge's
/// ends, face points the mean of the face's corners.
pub(crate) fn vertex_linear_plan_refine(mesh: &Mesh, r: &Refinement) -> ColumnPlan {
    let mut plan =
        ColumnPlan::with_capacity(r.vertex_slots(), 2 * r.edges as usize + r.corners as usize);
    for v in 0..r.nv {
        plan.copy(v);
    }
    for e in mesh.eids() {
        let [h, t] = e.halfedges();
        plan.interpolate([(mesh.origin(h).raw(), 0.5), (mesh.origin(t).raw(), 0.5)]);
    }
    face_points(mesh, r, &mut plan);
    debug_assert_eq!(plan.len(), r.vertex_slots());
    plan
}

/// The face points, in face order: each the mean of its face's corners.
fn face_points(mesh: &Mesh, r: &Refinement, plan: &mut ColumnPlan) {
    let mut ring = Vec::new();
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        face_ring(mesh, mesh.face_halfedge(f), &mut ring);
        if r.rule.cut(ring.len()) == Some(Cut::Quads) {
            let w = 1.0 / ring.len() as f64;
            plan.interpolate(ring.iter().map(|&h| (mesh.origin(h).raw(), w)));
        }
    }
}

/// Corners, face-varying and linear: each child corner interpolates the
/// corners of its parent face only (a seam stays a seam).
pub(crate) fn halfedge_plan_refine(mesh: &Mesh, r: &Refinement) -> ColumnPlan {
    let slots = Eid::halfedge_slots((r.corners + 2 * r.edges) as usize);
    let mut plan = ColumnPlan::with_capacity(slots, 2 * slots);
    let mut ring = Vec::new();
    let half = |a: Hid, b: Hid| [(a.raw(), 0.5), (b.raw(), 0.5)];
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        face_ring(mesh, mesh.face_halfedge(f), &mut ring);
        let n = ring.len();
        let cut = r.rule.cut(n).unwrap_or(Cut::Quads);
        for i in 0..n {
            let (hp, hi, hn) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            // Both kinds: the inside edge's side 0 leaves the edge point m_i.
            plan.interpolate(half(hi, hn));
            match cut {
                // Side 1 leaves m_{i-1}.
                Cut::Triangle => plan.interpolate(half(hp, hi)),
                // Side 1 leaves the face point.
                Cut::Quads => {
                    let w = 1.0 / n as f64;
                    plan.interpolate(ring.iter().map(|&h| (h.raw(), w)));
                }
            }
        }
    }
    for e in mesh.eids() {
        let [h, t] = e.halfedges();
        // In slot order: h's first child, t's second, h's second, t's first.
        plan.copy(h.raw());
        plan.interpolate(half(t, mesh.next(t)));
        plan.interpolate(half(h, mesh.next(h)));
        plan.copy(t.raw());
    }
    debug_assert_eq!(plan.len(), slots);
    plan
}

/// Edges: inside edges get `interpolate` of nothing, the two children of a
/// parent edge `split(value, ½)` each.
pub(crate) fn edge_plan_refine(mesh: &Mesh, r: &Refinement) -> ColumnPlan {
    let slots = (r.corners + 2 * r.edges) as usize;
    let mut plan = ColumnPlan::with_capacity(slots, 2 * r.edges as usize);
    for _ in 0..r.corners {
        plan.interpolate([]);
    }
    for e in mesh.eids() {
        plan.split(e.raw(), 0.5);
        plan.split(e.raw(), 0.5);
    }
    plan
}

/// Faces: each child gets `split(value, share)`, shares by area in the
/// parent's plane (¼ for the four triangles of a triangle); holes keep
/// their values.
pub(crate) fn face_column_plan_refine(mesh: &Mesh, r: &Refinement) -> ColumnPlan {
    let slots = (r.corners + r.tris + r.holes) as usize;
    let mut plan = ColumnPlan::with_capacity(slots, slots);
    let positions = mesh.position_slots();
    let mut ring = Vec::new();
    let mut shares = Vec::new();
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        face_ring(mesh, mesh.face_halfedge(f), &mut ring);
        match r.rule.cut(ring.len()).unwrap_or(Cut::Quads) {
            Cut::Triangle => {
                for _ in 0..3 {
                    plan.split(f.raw(), 0.25);
                }
            }
            Cut::Quads => {
                quad_shares(mesh, positions, &ring, &mut shares);
                for &s in &shares {
                    plan.split(f.raw(), s);
                }
            }
        }
    }
    for f in mesh.fids() {
        if !mesh.is_hole(f) && r.rule.cut(mesh.face_halfedges(f).count()) == Some(Cut::Triangle) {
            plan.split(f.raw(), 0.25);
        }
    }
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            plan.copy(f.raw());
        }
    }
    debug_assert_eq!(plan.len(), slots);
    plan
}

/// The shares of the quads of a face cut around its centroid: their areas
/// in the parent's geometry over the sum, or equal without positions or
/// area.
fn quad_shares(mesh: &Mesh, positions: Option<&[[f64; 3]]>, ring: &[Hid], out: &mut Vec<f64>) {
    let n = ring.len();
    out.clear();
    out.resize(n, 1.0 / n as f64);
    let Some(p) = positions else { return };
    let at = |h: Hid| p[mesh.origin(h).index()];
    let mut c = [0.0; 3];
    for &h in ring {
        let q = at(h);
        for k in 0..3 {
            c[k] += q[k] / n as f64;
        }
    }
    let mid = |a: [f64; 3], b: [f64; 3]| {
        [
            (a[0] + b[0]) / 2.0,
            (a[1] + b[1]) / 2.0,
            (a[2] + b[2]) / 2.0,
        ]
    };
    let mut total = 0.0;
    let mut areas = Vec::with_capacity(n);
    for i in 0..n {
        let (vp, vi, vn) = (
            at(ring[(i + n - 1) % n]),
            at(ring[i]),
            at(ring[(i + 1) % n]),
        );
        let (m_prev, m_next) = (mid(vp, vi), mid(vi, vn));
        // The quad (v_i, m_i, c, m_{i-1}): half the cross product of its
        // diagonals.
        let a = 0.5 * norm(cross(sub(c, vi), sub(m_prev, m_next)));
        total += a;
        areas.push(a);
    }
    if total > 0.0 && total.is_finite() {
        for (o, a) in out.iter_mut().zip(areas) {
            *o = a / total;
        }
    }
}

/// The plans of a face-splitting scheme whose smooth rules are `mask`
/// (`None`: a linear scheme, whose stencil is the linear plan).
pub(crate) struct RefinePlans<'a, M> {
    pub(crate) mesh: &'a Mesh,
    pub(crate) r: &'a Refinement,
    pub(crate) smooth: Option<(&'a M, &'a Features)>,
}

impl<M: Mask> ColumnPlans for RefinePlans<'_, M> {
    fn vertex_linear(&self) -> ColumnPlan {
        vertex_linear_plan_refine(self.mesh, self.r)
    }

    fn vertex_smooth(&self) -> ColumnPlan {
        let Some((mask, features)) = self.smooth else {
            return self.vertex_linear();
        };
        let (mesh, r) = (self.mesh, self.r);
        let mut plan = ColumnPlan::with_capacity(r.vertex_slots(), 8 * r.vertex_slots());
        let mut ring = Vec::new();
        for vi in 0..r.nv {
            let v = Vid::new(vi);
            if !mesh.vertex_live(vi as usize) {
                plan.copy(vi);
                continue;
            }
            let boundary = features.gather(mesh, v, &mut ring);
            let rule = features.rule(v, &ring, boundary);
            let start = plan.begin_interpolate();
            emit_vertex(
                mask,
                mesh,
                v,
                &ring,
                rule,
                &mut PlanSink {
                    mesh,
                    plan: &mut plan,
                },
            );
            plan.end_interpolate(start);
        }
        for e in mesh.eids() {
            let s = features.edge_sharpness(mesh, e);
            let start = plan.begin_interpolate();
            emit_edge(
                mask,
                mesh,
                e,
                s,
                &mut PlanSink {
                    mesh,
                    plan: &mut plan,
                },
            );
            plan.end_interpolate(start);
        }
        face_points(mesh, r, &mut plan);
        debug_assert_eq!(plan.len(), r.vertex_slots());
        plan
    }

    fn halfedge(&self) -> ColumnPlan {
        halfedge_plan_refine(self.mesh, self.r)
    }

    fn edge(&self) -> ColumnPlan {
        edge_plan_refine(self.mesh, self.r)
    }

    fn face(&self) -> ColumnPlan {
        face_column_plan_refine(self.mesh, self.r)
    }
}
