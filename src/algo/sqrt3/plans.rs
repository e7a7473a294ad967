//! The attribute plans of a √3 level (see the module doc of
//! [`sqrt3`](super) for what each arena's columns get).

use crate::algo::subdivision::creases::PlanSink;
use crate::algo::subdivision::ColumnPlans;
use crate::layout::{Eid, Hid, Vid};
use crate::mesh::Mesh;
use crate::store::plan::ColumnPlan;

use super::topology::Layout;
use super::{alpha, curve_vertex, VertexMove, VertexRules};

/// The attribute plans of a √3 level.
pub(super) struct Plans<'a> {
    pub(super) mesh: &'a Mesh,
    pub(super) l: &'a Layout,
    pub(super) rules: &'a VertexRules<'a>,
}

impl Plans<'_> {
    /// Face points: the mean of the corners' vertices.
    fn face_points(&self, plan: &mut ColumnPlan) {
        let m = self.mesh;
        for f in m.fids() {
            if m.is_hole(f) {
                continue;
            }
            let h = m.face_halfedge(f);
            let third = 1.0 / 3.0;
            plan.interpolate([
                (m.origin(h).raw(), third),
                (m.origin(m.next(h)).raw(), third),
                (m.origin(m.next(m.next(h))).raw(), third),
            ]);
        }
    }

    /// The inner half-edges of the trisected edges, in rank order.
    fn trisected(&self) -> impl Iterator<Item = Hid> + '_ {
        self.l.trisected_edges(self.mesh).map(|(_, h)| h)
    }

    /// The mean of the three corners of `h`'s face.
    ///
    /// Always summed from the face's own half-edge, whichever corner `h`
    /// is: the corners around one face point then get bit-identical values
    /// (a sum in another order may differ in the last bit, which would
    /// count as a seam at every face point).
    fn face_corners(&self, h: Hid, plan: &mut ColumnPlan) {
        let m = self.mesh;
        let third = 1.0 / 3.0;
        let first = m.face_halfedge(m.face_of(h));
        let (a, b) = (m.next(first), m.next(m.next(first)));
        plan.interpolate([(first.raw(), third), (a.raw(), third), (b.raw(), third)]);
    }
}

/// The corner value `k` thirds along `from` towards `to` (`k` 1 or 2).
fn thirds(from: Hid, to: Hid, k: u32) -> [(u32, f64); 2] {
    let t = f64::from(k) / 3.0;
    [(from.raw(), 1.0 - t), (to.raw(), t)]
}

impl ColumnPlans for Plans<'_> {
    fn vertex_linear(&self) -> ColumnPlan {
        let m = self.mesh;
        let nv = self.l.nv;
        let b = 2 * self.l.boundary as usize;
        let mut plan = ColumnPlan::with_capacity(nv as usize + m.face_count() + b, 2 * b);
        for v in 0..nv {
            plan.copy(v);
        }
        self.face_points(&mut plan);
        for h in self.trisected() {
            let (a, b) = (m.origin(h).raw(), m.origin(h.twin()).raw());
            plan.interpolate([(a, 2.0 / 3.0), (b, 1.0 / 3.0)]);
            plan.interpolate([(a, 1.0 / 3.0), (b, 2.0 / 3.0)]);
        }
        plan
    }

    fn vertex_smooth(&self) -> ColumnPlan {
        let m = self.mesh;
        let nv = self.l.nv;
        let b = 2 * self.l.boundary as usize;
        let mut plan =
            ColumnPlan::with_capacity(nv as usize + m.face_count() + b, 8 * nv as usize + 3 * b);
        for vi in 0..nv {
            let v = Vid::new(vi);
            if !m.vertex_live(vi as usize) {
                plan.copy(vi);
                continue;
            }
            match self.rules.of_vertex(v) {
                VertexMove::Stay => plan.copy(vi),
                VertexMove::Curve(a, b) => {
                    let start = plan.begin_interpolate();
                    curve_vertex(
                        v,
                        a,
                        b,
                        &mut PlanSink {
                            mesh: m,
                            plan: &mut plan,
                        },
                    );
                    plan.end_interpolate(start);
                }
                VertexMove::Smooth => {
                    let n = m.outgoing(v).count();
                    let a = alpha(n);
                    let start = plan.begin_interpolate();
                    plan.push_input(vi, 1.0 - a);
                    for h in m.outgoing(v) {
                        plan.push_input(m.origin(h.twin()).raw(), a / n as f64);
                    }
                    plan.end_interpolate(start);
                }
            }
        }
        self.face_points(&mut plan);
        for h in self.trisected() {
            for k in 0..2 {
                let start = plan.begin_interpolate();
                self.rules.boundary_point(
                    h,
                    k,
                    &mut PlanSink {
                        mesh: m,
                        plan: &mut plan,
                    },
                );
                plan.end_interpolate(start);
            }
        }
        plan
    }

    fn halfedge(&self) -> ColumnPlan {
        let m = self.mesh;
        let (c, e) = (self.l.corners as usize, m.edge_count());
        let b = self.l.boundary as usize;
        let mut plan =
            ColumnPlan::with_capacity(Eid::halfedge_slots(c + e + 4 * b), 8 * c + 16 * b);
        for edge in m.eids() {
            for h in edge.halfedges() {
                if m.in_hole(h) {
                    continue;
                }
                // Side 0 leaves origin(h), in a triangle over face(h) and
                // the face across prev(h): the mean of the two corners
                // (only h's own where prev(h) is on the boundary).
                let p = m.next(m.next(h));
                if self.l.kept(p.edge()) {
                    plan.copy(h.raw());
                } else {
                    plan.interpolate([(h.raw(), 0.5), (p.twin().raw(), 0.5)]);
                }
                // Side 1 leaves the face point of face(h).
                self.face_corners(h, &mut plan);
            }
        }
        for edge in m.eids() {
            let kept = self.l.kept(edge);
            let trisected = self.l.trisected(edge).is_some();
            for h in edge.halfedges() {
                if trisected && m.in_hole(h) {
                    // From the first boundary point, a third along the
                    // inner half-edge, on the hole's side.
                    plan.interpolate(thirds(m.next(h), h, 1));
                } else if kept {
                    plan.copy(h.raw());
                } else {
                    self.face_corners(h, &mut plan);
                }
            }
        }
        // Per trisected edge: the middle third (inner side from a', hole
        // side from b'), the last third (inner from b', hole from b), the
        // spokes from a' and b' (their face-point sides).
        for h in self.trisected() {
            let (t, hn) = (h.twin(), m.next(h));
            let tn = m.next(t);
            plan.interpolate(thirds(h, hn, 1));
            plan.interpolate(thirds(tn, t, 2));
            plan.interpolate(thirds(h, hn, 2));
            plan.copy(t.raw());
            plan.interpolate(thirds(h, hn, 1));
            self.face_corners(h, &mut plan);
            plan.interpolate(thirds(h, hn, 2));
            self.face_corners(h, &mut plan);
        }
        plan
    }

    fn edge(&self) -> ColumnPlan {
        let m = self.mesh;
        let c = self.l.corners as usize;
        let b = self.l.boundary as usize;
        let mut plan = ColumnPlan::with_capacity(c + m.edge_count() + 4 * b, 3 * b);
        for _ in 0..c {
            plan.interpolate([]);
        }
        let third = 1.0 / 3.0;
        for edge in m.eids() {
            if self.l.trisected(edge).is_some() {
                plan.split(edge.raw(), third);
            } else if self.l.kept(edge) {
                plan.copy(edge.raw());
            } else {
                plan.interpolate([]);
            }
        }
        for h in self.trisected() {
            let e = h.edge().raw();
            plan.split(e, third);
            plan.split(e, third);
            plan.interpolate([]);
            plan.interpolate([]);
        }
        plan
    }

    fn face(&self) -> ColumnPlan {
        let m = self.mesh;
        let c = self.l.corners as usize;
        let b = self.l.boundary as usize;
        let mut plan = ColumnPlan::with_capacity(c + 2 * b + m.hole_count(), 2 * c + 2 * b);
        let third = 1.0 / 3.0;
        let ninth = 1.0 / 9.0;
        for edge in m.eids() {
            for h in edge.halfedges() {
                if m.in_hole(h) {
                    continue;
                }
                let (own, other) = (m.face_of(h).raw(), m.face_of(h.twin()));
                if self.l.trisected(edge).is_some() {
                    // The first of three triangles on the kept piece.
                    plan.split(own, ninth);
                } else if self.l.kept(edge) {
                    // The kept piece beside a boundary or seam edge.
                    plan.split(own, third);
                } else {
                    // Half of each piece beside the flipped edge, this
                    // side's first.
                    plan.flip_piece(own, third, other.raw(), third);
                }
            }
        }
        for h in self.trisected() {
            let own = m.face_of(h).raw();
            plan.split(own, ninth);
            plan.split(own, ninth);
        }
        for f in m.fids() {
            if m.is_hole(f) {
                plan.copy(f.raw());
            }
        }
        plan
    }
}
