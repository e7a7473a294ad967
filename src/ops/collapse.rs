//! `collapse_edge`: merge a half-edge's origin into its destination.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::{HalfedgeKey, VertexKey};
use crate::layout::{Fid, Hid, Vid};
use crate::mesh::{Mesh, Writer};
use crate::store::ErasedColumn;
use crate::vec3::{norm2, sub};

/// The operator's name in its refusals.
const OP: &str = "collapse_edge";

/// The corners around one end of a collapsing edge, in ring order from the
/// corner beside the edge on one side (index 0) to the one on the other
/// side (index 1) and on around, with whether each lies in a hole.
struct CornerRing {
    corners: Vec<(Hid, bool)>,
}

impl CornerRing {
    /// The ring of `origin(start)`, from `start`.
    fn gather(mesh: &Mesh, start: Hid) -> CornerRing {
        let corners = crate::circulate::VertexOutgoing::from_halfedge(mesh, start)
            .map(|o| (o, mesh.in_hole(o)))
            .collect();
        CornerRing { corners }
    }

    /// The wedges of the corners beside the edge, for one column: run 0
    /// (from index 0 away from the edge, backwards) when `side0` is a face,
    /// run 1 (from index 1 forwards, stopping before run 0) when `side1`
    /// is. Pushed as `(corner, is_left)`, where run 0 is the left side
    /// unless `swapped`.
    fn runs(
        &self,
        col: &dyn ErasedColumn,
        side0: bool,
        side1: bool,
        out: &mut Vec<(Hid, bool)>,
        swapped: bool,
    ) {
        let r = &self.corners;
        let d = r.len();
        if d < 2 {
            return;
        }
        // Backwards from 0: d-1, d-2, ..., 2 while the value carries over.
        let mut stop0 = d; // run 0 covers indices stop0..d and 0
        if side0 {
            out.push((r[0].0, !swapped));
            let mut i = d - 1;
            while i >= 2 {
                let (c, hole) = r[i];
                let next = r[(i + 1) % d].0;
                if hole || !col.same(c.index(), next.index()) {
                    break;
                }
                out.push((c, !swapped));
                stop0 = i;
                i -= 1;
            }
        }
        if side1 {
            out.push((r[1].0, swapped));
            for i in 2..stop0 {
                let (c, hole) = r[i];
                if hole || !col.same(r[i - 1].0.index(), c.index()) {
                    break;
                }
                out.push((c, swapped));
            }
        }
    }
}

struct CollapsePlan {
    h: Hid,
    a: Vid,
    b: Vid,
    f_left: Fid,
    f_right: Fid,
    /// The half-edges after `h` and after its twin.
    nh: Hid,
    nt: Hid,
    /// The half-edges before `h` and before its twin.
    ph: Hid,
    pt: Hid,
    before_tph: Option<Hid>,
    /// Whether the face of `h` (resp. its twin) is a triangle (or a
    /// triangular hole) that disappears.
    left_goes: bool,
    right_goes: bool,
    /// Who may need another half-edge for rule 11 afterwards.
    rule11: Rule11,
}

/// The vertices a collapse may leave naming a half-edge that no longer lies
/// in a hole (rule 11), found while planning: `b` when a hole touched `a`
/// or `b` (b gets a's ring), an apex `c` or `d` when its triangle is a hole
/// that closes. Nothing on a closed mesh.
#[derive(Copy, Clone)]
struct Rule11 {
    b: bool,
    c: Vid,
    d: Vid,
}

impl Rule11 {
    const NOTHING: Rule11 = Rule11 {
        b: false,
        c: Vid::NONE,
        d: Vid::NONE,
    };
}

/// The ring of `a`, the collapsing edge's origin, as the link condition
/// reads it: its neighbours other than `b` and the apexes of the triangles
/// that disappear (the first 16 in place, all of them in `large` past
/// that), its degree, and its last two outgoing half-edges.
struct RingOfA {
    small: [Vid; 16],
    large: Vec<Vid>,
    others: usize,
    degree: usize,
    last: Hid,
    before_last: Hid,
}

impl Mesh {
    // Inlined into both callers so that the commit reuses what the plan
    // read.
    #[inline(always)]
    fn plan_collapse(&self, hk: HalfedgeKey) -> Result<CollapsePlan> {
        let h = self.check_halfedge(hk)?;
        let t = h.twin();
        let (rh, rt) = (self.he[h], self.he[t]);
        let (a, b) = (rh.origin, rt.origin);
        let (f_left, f_right) = (rh.face, rt.face);
        let (nh, nt) = (rh.next, rt.next);
        // In a triangle the half-edge after `next` is the one before, and
        // leaves the apex.
        let (left_prev, right_prev) = (self.he[nh].next, self.he[nt].next);
        let (left, right) = (self.he[left_prev], self.he[right_prev]);
        let left_goes = nh != h && left.next == h;
        let right_goes = nt != t && right.next == t;
        let (c, d) = (left.origin, right.origin);
        if left_goes && right_goes && c == d {
            return Err(refuse(OP, hk, Refusal::LinkCondition));
        }
        // Link condition: the common neighbours of a and b are exactly the
        // apexes of the triangles that disappear. Gather a's neighbours
        // other than b and those apexes; when there are none (a poked
        // centre, a valence-3 vertex) b's ring need not be walked at all.
        let is_apex = |w: Vid| (left_goes && w == c) || (right_goes && w == d);
        let mut ring = self.ring_of_a(h, b, is_apex);
        let pt = if ring.others == 0 {
            if right_goes {
                right_prev
            } else {
                self.prev_fast(t)
            }
        } else {
            self.check_common_neighbours(hk, t, &mut ring)?
        };
        let rule11 = if self.holes > 0 {
            let apexes = [(left_goes, c), (right_goes, d)];
            self.check_collapse_boundary(hk, h, f_left, f_right, apexes)?
        } else {
            Rule11::NOTHING
        };
        self.check_no_face_holds_both(hk, a, b, f_left, f_right)?;
        Ok(CollapsePlan {
            h,
            a,
            b,
            f_left,
            f_right,
            nh,
            nt,
            ph: ring.last.twin(),
            // The half-edge before twin(ph) = last once h is gone: the
            // twin of the one before it in a's ring, unless that is h.
            before_tph: (ring.degree >= 3).then_some(ring.before_last.twin()),
            pt,
            left_goes,
            right_goes,
            rule11,
        })
    }

    /// Walk the ring of `a = origin(h)` from `h`: its neighbours other than
    /// `b` and the apexes, its degree and its last two half-edges.
    #[inline(always)]
    fn ring_of_a(&self, h: Hid, b: Vid, is_apex: impl Fn(Vid) -> bool) -> RingOfA {
        let mut ring = RingOfA {
            small: [Vid::NONE; 16],
            large: Vec::new(),
            others: 0,
            degree: 0,
            last: h,
            before_last: h,
        };
        let mut o = h;
        // Bounded: a ring has fewer than 2E half-edges. (A countdown at the
        // end of the body: `for _ in 0..len` here measured 10% slower.)
        let mut budget = self.he.len();
        loop {
            let twin = self.he[o.twin()];
            let w = twin.origin;
            if w != b && !is_apex(w) {
                if ring.others < ring.small.len() {
                    ring.small[ring.others] = w;
                } else {
                    if ring.large.is_empty() {
                        ring.large.extend_from_slice(&ring.small);
                    }
                    ring.large.push(w);
                }
                ring.others += 1;
            }
            ring.degree += 1;
            (ring.before_last, ring.last) = (ring.last, o);
            o = twin.next;
            budget -= 1;
            if o == h || budget == 0 {
                break;
            }
        }
        ring
    }

    /// Link condition, `b`'s side: walk the ring of `b = origin(t)` and
    /// refuse a neighbour `a`'s ring holds too. Returns the twin of the
    /// last half-edge of `b`'s ring (the one before `t`).
    #[inline(always)]
    fn check_common_neighbours(&self, hk: HalfedgeKey, t: Hid, ring: &mut RingOfA) -> Result<Hid> {
        let others = ring.others;
        let around_a: &[Vid] = if others <= ring.small.len() {
            &ring.small[..others]
        } else {
            ring.large.sort_unstable();
            &ring.large
        };
        let mut last_b;
        let mut o = t;
        let mut budget = self.he.len();
        loop {
            let twin = self.he[o.twin()];
            let w = twin.origin;
            let common = if others > ring.small.len() {
                around_a.binary_search(&w).is_ok()
            } else {
                around_a.contains(&w)
            };
            if common {
                return Err(refuse(OP, hk, Refusal::LinkCondition));
            }
            last_b = o;
            o = twin.next;
            budget -= 1;
            if o == t || budget == 0 {
                break;
            }
        }
        Ok(last_b.twin())
    }

    /// No face other than the two beside the edge may hold both `a` and
    /// `b`. Triangles around `a` cannot (their third corner would be a
    /// common neighbour).
    #[inline(always)]
    fn check_no_face_holds_both(
        &self,
        hk: HalfedgeKey,
        a: Vid,
        b: Vid,
        f_left: Fid,
        f_right: Fid,
    ) -> Result<()> {
        for o in self.outgoing(a) {
            let f = self.face_of(o);
            if f == f_left || f == f_right {
                continue;
            }
            let n = self.next(o);
            if self.next(self.next(n)) == o {
                continue;
            }
            if crate::circulate::FaceHalfedges::from_halfedge(self, n).any(|x| self.origin(x) == b)
            {
                return Err(refuse(OP, hk, Refusal::NonManifold));
            }
        }
        Ok(())
    }

    /// The checks that only a mesh with holes needs.
    fn check_collapse_boundary(
        &self,
        hk: HalfedgeKey,
        h: Hid,
        f_left: Fid,
        f_right: Fid,
        apexes: [(bool, Vid); 2],
    ) -> Result<Rule11> {
        let t = h.twin();
        let (hole_left, hole_right) = (self.is_hole(f_left), self.is_hole(f_right));
        // An interior edge between two boundary vertices would pinch.
        // (Rule 11 makes each test one look-up.)
        let (a_bnd, b_bnd) = (
            self.on_boundary(self.origin(h)),
            self.on_boundary(self.origin(t)),
        );
        if !hole_left && !hole_right && a_bnd && b_bnd {
            return Err(refuse(OP, hk, Refusal::NonManifold));
        }
        // A disappearing triangle must not leave an edge with holes on both
        // sides.
        for ((goes, _), x) in apexes.into_iter().zip([h, t]) {
            if goes && !self.in_hole(x) {
                let n = self.next(x);
                let p = self.next(n);
                if self.in_hole(n.twin()) && self.in_hole(p.twin()) {
                    return Err(refuse(OP, hk, Refusal::NonManifold));
                }
            }
        }
        let apex = |(goes, v): (bool, Vid), hole: bool| if goes && hole { v } else { Vid::NONE };
        Ok(Rule11 {
            b: a_bnd || b_bnd,
            c: apex(apexes[0], hole_left),
            d: apex(apexes[1], hole_right),
        })
    }

    /// Whether [`collapse_edge`](Mesh::collapse_edge) would succeed;
    /// changes nothing.
    ///
    /// # Errors
    /// As [`collapse_edge`](Mesh::collapse_edge).
    pub fn check_collapse_edge(&self, h: HalfedgeKey) -> Result<()> {
        self.plan_collapse(h).map(drop)
    }

    /// Merge `a = origin(h)` into `b = dest(h)`: the edge disappears, every
    /// edge of `a` now ends at `b`. A triangle beside the edge (face or
    /// hole) disappears and its two other edges become one; a larger face
    /// loses one side.
    ///
    /// ```text
    ///        c                  c
    ///      / | \                |
    ///     x  |  \               |
    ///      \ |   \      =>      |
    ///        a -h-> b      x -- b
    ///      /   \   /            |
    ///           \ /             |
    ///            d              d
    /// ```
    ///
    /// Returns `b`, which keeps its key. Attributes (the surviving element
    /// is always the first contributor): `b = merge(b: 1, a: 0)` (positions:
    /// `b` stays where it was; see [`collapse_edge_at`](Mesh::collapse_edge_at));
    /// where a triangle disappears, its side at `b` (`b–c`, resp. `b–d`) is
    /// kept and `merge(kept: ½, other: ½)` with its side at `a`; the
    /// triangle's values merge (weight 0) into the face that receives the
    /// kept side, that face first. χ is unchanged, except that it grows by 1
    /// when a triangular hole closes.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey);
    /// [`Refusal::LinkCondition`] when `a` and `b` have a common neighbour
    /// other than the apex of a disappearing triangle (the result would have
    /// two edges between the same vertices), or both sides are triangles on
    /// the same apex; [`Refusal::NonManifold`] when the edge is interior but
    /// both ends lie on a boundary, when another face holds both ends, or a
    /// triangle would leave an edge with holes on both sides.
    ///
    /// # Complexity
    /// O(Σ degree of the faces around `a` + degree of `b` · log degree of
    /// `a`). `b`'s ring is walked only when `a` has a neighbour other than
    /// `b` and the apexes of the disappearing triangles: collapsing a
    /// valence-3 vertex (a poked centre) costs O(1).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let b = mesh.halfedge(h)?.dest().key();
    /// assert_eq!(mesh.collapse_edge(h)?, b);
    /// assert_eq!((mesh.vertex_count(), mesh.face_count()), (11, 18));
    /// assert_eq!(mesh.euler_characteristic(), 2);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn collapse_edge(&mut self, h: HalfedgeKey) -> Result<VertexKey> {
        self.collapse_edge_at(h, 1.0)
    }

    /// Whether [`collapse_edge_at`](Mesh::collapse_edge_at) would succeed.
    ///
    /// # Errors
    /// As [`collapse_edge_at`](Mesh::collapse_edge_at).
    pub fn check_collapse_edge_at(&self, h: HalfedgeKey, t: f64) -> Result<()> {
        if !(0.0..=1.0).contains(&t) {
            return Err(refuse(OP, h, Refusal::Parameter("t must lie in 0..=1")));
        }
        self.check_collapse_edge(h)
    }

    /// [`collapse_edge`](Mesh::collapse_edge) with the merged vertex at
    /// parameter `t` from `a` to `b`: `b = merge(b: t, a: 1−t)`, the
    /// surviving `b` first (t = 0.5 puts it at the midpoint). Corner values
    /// follow the same weights (see [`collapse_edge_to`](Mesh::collapse_edge_to)).
    ///
    /// # Errors
    /// As `collapse_edge`, and [`Refusal::Parameter`] when `t` is not in
    /// `0..=1`.
    ///
    /// # Complexity
    /// As `collapse_edge`.
    pub fn collapse_edge_at(&mut self, hk: HalfedgeKey, t: f64) -> Result<VertexKey> {
        journaled!(self.collapse_edge_at_with(hk, t))
    }

    /// Whether [`collapse_edge_to`](Mesh::collapse_edge_to) would succeed;
    /// changes nothing.
    ///
    /// # Errors
    /// As [`collapse_edge_to`](Mesh::collapse_edge_to).
    pub fn check_collapse_edge_to(&self, h: HalfedgeKey, position: [f64; 3]) -> Result<()> {
        self.check_collapse_edge(h)?;
        self.collapse_weight(h.id(), position, h).map(drop)
    }

    /// [`collapse_edge`](Mesh::collapse_edge) with the merged vertex at any
    /// `position` (an optimal point of a quadric, off the edge): the
    /// position column gets `position` exactly; every other column's rule
    /// runs with the weights of the point's projection on the edge,
    /// `t = clamp((p − a)·(b − a) / |b − a|², 0, 1)`: `b = merge(b: t,
    /// a: 1−t)`, the survivor first (a zero-length edge takes t = 1).
    ///
    /// **Corners** (half-edge columns) follow the same weights, per column
    /// and per *wedge* (a fan of corners around a vertex whose values are
    /// the same across the edges between them, by
    /// [`Attribute::same_value`](crate::attr::Attribute::same_value)): on
    /// each side of the edge that
    /// is a face, the corners at `a` and `b` in that face give
    /// `merge(b's: t, a's: 1−t)`, and every corner of the wedges they
    /// belong to, at `a` and at `b`, takes that value. A UV seam along the
    /// edge therefore stays a seam (each side interpolates its own values)
    /// and a seam that crosses `a` or `b` elsewhere is not blurred (the
    /// other wedges keep their values). This holds for `collapse_edge` and
    /// `collapse_edge_at` as well (`t` = 1 and the given `t`).
    ///
    /// Returns `b`, which keeps its key.
    ///
    /// # Errors
    /// As [`collapse_edge`](Mesh::collapse_edge), and
    /// [`Error::NonFinitePosition`](crate::Error::NonFinitePosition) for a
    /// NaN or infinite `position`; [`Error::NoPositions`](crate::Error::NoPositions)
    /// for a mesh without positions.
    ///
    /// # Complexity
    /// As `collapse_edge`, plus the rings of `a` and `b` once per corner
    /// column when the mesh has any.
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let (a, b) = (mesh.halfedge(h)?.origin().key(), mesh.halfedge(h)?.dest().key());
    /// let (pa, pb) = (mesh.position(a)?, mesh.position(b)?);
    /// // The midpoint, pushed outwards: the projection on the edge is still t = 0.5.
    /// let mid: Vec<f64> = (0..3).map(|i| 0.5 * (pa[i] + pb[i]) * 1.1).collect();
    /// let p = [mid[0], mid[1], mid[2]];
    /// mesh.check_collapse_edge_to(h, p)?;
    /// assert_eq!(mesh.collapse_edge_to(h, p)?, b);
    /// assert_eq!(mesh.position(b)?, p);
    /// assert_eq!(mesh.vertex_count(), 11);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn collapse_edge_to(&mut self, hk: HalfedgeKey, position: [f64; 3]) -> Result<VertexKey> {
        journaled!(self.collapse_edge_to_with(hk, position))
    }

    /// The projection parameter of `position` on `h`'s edge, checked.
    fn collapse_weight(&self, h: Hid, position: [f64; 3], hk: HalfedgeKey) -> Result<f64> {
        if !position.iter().all(|c| c.is_finite()) {
            return Err(crate::Error::NonFinitePosition {
                key: hk.into(),
                position,
            });
        }
        let p = self.position_slots().ok_or(crate::Error::NoPositions)?;
        let (a, b) = (p[self.origin(h).index()], p[self.dest(h).index()]);
        let d = sub(b, a);
        let len2 = norm2(d);
        if len2 <= 0.0 || !len2.is_finite() {
            return Ok(1.0);
        }
        let s =
            (position[0] - a[0]) * d[0] + (position[1] - a[1]) * d[1] + (position[2] - a[2]) * d[2];
        Ok((s / len2).clamp(0.0, 1.0))
    }

    /// The corner rule of a collapse of `h` (a → b) at weight `t` (b's),
    /// run before the links change. Per half-edge column: on each side that
    /// is a face, `merge(b's corner: t, a's corner: 1−t)` goes to every
    /// corner of the two wedges (at a and at b) that hold that side's
    /// corners. All comparisons are made before any value is written.
    fn merge_corner_wedges(&mut self, h: Hid, t: f64) {
        let tw = h.twin();
        // Rings: at a from h (L side corner), then next(tw) (R side);
        // at b from tw (R side corner), then next(h) (L side).
        let ring_a = CornerRing::gather(self, h);
        let ring_b = CornerRing::gather(self, tw);
        let left = !self.in_hole(h);
        let right = !self.in_hole(tw);
        let (a_left, a_right) = (h, self.next(tw));
        let (b_left, b_right) = (self.next(h), tw);
        let mut runs: Vec<(Hid, bool)> = Vec::new();
        // Every write goes through the column set, which saves the old
        // value while a journal records (undo and rollback restore it).
        let cols = &mut self.attrs.halfedge;
        for ci in 0..cols.cols.len() {
            runs.clear();
            // At a: index 0 is the L corner, index 1 the R corner; at b:
            // index 0 is the R corner, index 1 the L corner.
            let col = &*cols.cols[ci].1;
            ring_a.runs(col, left, right, &mut runs, false);
            ring_b.runs(col, right, left, &mut runs, true);
            // The merged values go to the slots of a's corners beside the
            // edge (h is freed by the commit; a's R corner, when it lives
            // on, belongs to the R wedge anyway).
            if left {
                cols.merge_one(
                    ci,
                    a_left.index(),
                    &[(b_left.index(), t), (a_left.index(), 1.0 - t)],
                );
            }
            if right {
                cols.merge_one(
                    ci,
                    a_right.index(),
                    &[(b_right.index(), t), (a_right.index(), 1.0 - t)],
                );
            }
            for &(c, is_left) in &runs {
                let src = if is_left { a_left } else { a_right };
                if c != src {
                    cols.copy_one(ci, src.index(), c.index());
                }
            }
        }
    }
}

impl Mesh {
    /// [`Writer::collapse_unvalidated`] in journaling mode `J`, for code
    /// that holds no writer (the remesher, with no journal).
    #[inline]
    pub(crate) fn collapse_unvalidated<J: Journaling>(
        &mut self,
        h: Hid,
        t: f64,
        position: Option<[f64; 3]>,
    ) -> Result<Vid> {
        self.writer::<J>().collapse_unvalidated(h, t, position)
    }
}

impl Mesh {
    /// [`collapse_edge_at`](Mesh::collapse_edge_at)'s body, in journaling mode `J`.
    fn collapse_edge_at_with<J: Journaling>(
        &mut self,
        hk: HalfedgeKey,
        t: f64,
    ) -> Result<VertexKey> {
        let mut w = self.writer::<J>();
        if !(0.0..=1.0).contains(&t) {
            return Err(refuse(OP, hk, Refusal::Parameter("t must lie in 0..=1")));
        }
        let plan = w.plan_collapse(hk)?;
        let b = w.commit_collapse(plan, t, None);
        w.end_op();
        Ok(w.vkey(b))
    }

    /// [`collapse_edge_to`](Mesh::collapse_edge_to)'s body, in journaling mode `J`.
    fn collapse_edge_to_with<J: Journaling>(
        &mut self,
        hk: HalfedgeKey,
        position: [f64; 3],
    ) -> Result<VertexKey> {
        let mut w = self.writer::<J>();
        let plan = w.plan_collapse(hk)?;
        let t = w.collapse_weight(plan.h, position, hk)?;
        let b = w.commit_collapse(plan, t, Some(position));
        w.end_op();
        Ok(w.vkey(b))
    }
}

impl<J: Journaling> Writer<'_, J> {
    /// The decimator's and the remesher's door: collapse `h` with weight `t` and, if given,
    /// the exact position, without the per-call debug validation (the
    /// caller validates once at the end; validating after each of
    /// thousands of collapses would make debug builds quadratic). The
    /// caller checked that `position` is finite and `t` in `0..=1`.
    #[inline(always)]
    pub(crate) fn collapse_unvalidated(
        &mut self,
        h: Hid,
        t: f64,
        position: Option<[f64; 3]>,
    ) -> Result<Vid> {
        let plan = self.plan_collapse(self.hkey(h))?;
        Ok(self.commit_collapse(plan, t, position))
    }

    /// The commit and rules of a planned collapse; cannot fail.
    #[inline(always)]
    fn commit_collapse(&mut self, plan: CollapsePlan, t: f64, position: Option<[f64; 3]>) -> Vid {
        let CollapsePlan {
            h,
            a,
            b,
            f_left,
            f_right,
            nh,
            nt,
            ph,
            pt,
            before_tph,
            left_goes,
            right_goes,
            rule11,
        } = plan;
        // Corners first, while the rings are intact.
        if !self.attrs.halfedge.cols.is_empty() {
            self.merge_corner_wedges(h, t);
        }
        // Rule 11: which of b, c and d touched a hole before (a's holes
        // become b's). Only they can need another half-edge afterwards.
        // The surviving vertex first (the documented order KeepFirst reads).
        self.attrs
            .vertex
            .merge(b.index(), &[(b.index(), t), (a.index(), 1.0 - t)]);
        if let Some(p) = position {
            // The merge saved b's position only if it changed it.
            self.attrs.set_position_saved(b.index(), p);
        }
        // Every half-edge leaving a now leaves b (the ring of a is walked by
        // next/twin, which the origins do not affect).
        let mut o = h;
        let mut budget = self.he.len();
        loop {
            self.he_mut(o).origin = b;
            o = self.next(o.twin());
            budget -= 1;
            if o == h || budget == 0 {
                break;
            }
        }
        self.set_next(ph, nh);
        self.set_next(pt, nt);
        if self.face_halfedge(f_left) == h {
            self.set_face_link(f_left, nh);
        }
        if self.face_halfedge(f_right) == h.twin() {
            self.set_face_link(f_right, nt);
        }
        *self.v_halfedge_mut(b) = nh;
        self.free_edge(h.edge());
        self.free_vertex(a);
        if left_goes {
            // Two-sided loop (ph: c -> b, nh: b -> c): keep nh.
            self.reborrow().dissolve_two_gon(ph, nh, before_tph);
        }
        if right_goes {
            // Two-sided loop (pt: d -> b, nt: b -> d): keep pt.
            self.reborrow().dissolve_two_gon(nt, pt, None);
        }
        // Rule 11: b has a's holes now; a closed triangular hole may have
        // held its apex's half-edge.
        if rule11.b {
            self.point_at_hole(b);
        }
        for v in [rule11.c, rule11.d] {
            if !v.is_none() {
                self.point_at_hole(v);
            }
        }
        b
    }

    /// A face (or hole) left with the two half-edges `p` and `n` (parallel
    /// edges between the same vertices) disappears: `n` takes the place of
    /// `twin(p)` in its face and `p`'s edge goes. The mesh must be consistent
    /// apart from this two-sided loop. `before_tp`, when known, is the
    /// half-edge before `twin(p)` (else it is found by turning).
    fn dissolve_two_gon(mut self, p: Hid, n: Hid, before_tp: Option<Hid>) {
        let f = self.face_of(p);
        let tp = p.twin();
        let g = self.face_of(tp);
        let q = before_tp.unwrap_or_else(|| self.prev_fast(tp));
        debug_assert_eq!(q, self.prev(tp));
        let r = self.next(tp);
        self.set_next(q, n);
        self.set_next(n, r);
        self.he_mut(n).face = g;
        if self.face_halfedge(g) == tp {
            self.set_face_link(g, n);
        }
        let u = self.origin(p);
        let w = self.origin(tp);
        if self.v_halfedge[u] == p {
            *self.v_halfedge_mut(u) = n.twin();
        }
        if self.v_halfedge[w] == tp {
            *self.v_halfedge_mut(w) = n;
        }
        let (kept, gone) = (n.edge().index(), p.edge().index());
        self.attrs.edge.merge(kept, &[(kept, 0.5), (gone, 0.5)]);
        if !self.attrs.face.cols.is_empty() && !self.is_hole(f) {
            // The triangle's values go to a real face beside the kept edge.
            let k = if self.is_hole(g) {
                self.face_of(n.twin())
            } else {
                g
            };
            self.attrs
                .face
                .merge(k.index(), &[(k.index(), 1.0), (f.index(), 0.0)]);
        }
        self.attrs.halfedge.copy(tp.index(), n.index());
        self.free_face(f);
        self.free_edge(p.edge());
    }
}
