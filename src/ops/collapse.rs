//! `collapse_edge`: merge a half-edge's origin into its destination.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::keys::{HalfedgeKey, VertexKey};
use crate::layout::{Fid, Hid, Vid};
use crate::mesh::Mesh;

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

impl Mesh {
    // Inlined into both callers so that the commit reuses what the plan
    // read.
    #[inline(always)]
    fn plan_collapse(&self, hk: HalfedgeKey) -> Result<CollapsePlan> {
        const OP: &str = "collapse_edge";
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
        let mut small = [Vid::NONE; 16];
        let mut large = Vec::new();
        let mut others = 0;
        let (mut degree, mut last_a) = (0usize, h);
        let mut before_last_a;
        let mut o = h;
        // Bounded: a ring has fewer than 2E half-edges. (A countdown at the
        // end of the body: `for _ in 0..len` here measured 10% slower.)
        let mut budget = self.he.len();
        loop {
            let twin = self.he[o.twin()];
            let w = twin.origin;
            if w != b && !is_apex(w) {
                if others < small.len() {
                    small[others] = w;
                } else {
                    if large.is_empty() {
                        large.extend_from_slice(&small);
                    }
                    large.push(w);
                }
                others += 1;
            }
            degree += 1;
            (before_last_a, last_a) = (last_a, o);
            o = twin.next;
            budget -= 1;
            if o == h || budget == 0 {
                break;
            }
        }
        let pt = if others == 0 {
            if right_goes {
                right_prev
            } else {
                self.prev_fast(t)
            }
        } else {
            let around_a: &[Vid] = if others <= small.len() {
                &small[..others]
            } else {
                large.sort_unstable();
                &large
            };
            let mut last_b;
            let mut o = t;
            let mut budget = self.he.len();
            loop {
                let twin = self.he[o.twin()];
                let w = twin.origin;
                let common = if others > small.len() {
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
            last_b.twin()
        };
        let rule11 = if self.holes > 0 {
            let apexes = [(left_goes, c), (right_goes, d)];
            self.check_collapse_boundary(hk, h, f_left, f_right, apexes)?
        } else {
            Rule11::NOTHING
        };
        // No other face may hold both a and b. Triangles around a cannot
        // (their third corner would be a common neighbour).
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
        Ok(CollapsePlan {
            h,
            a,
            b,
            f_left,
            f_right,
            nh,
            nt,
            ph: last_a.twin(),
            // The half-edge before twin(ph) = last_a once h is gone: the
            // twin of the one before it in a's ring, unless that is h.
            before_tph: (degree >= 3).then_some(before_last_a.twin()),
            pt,
            left_goes,
            right_goes,
            rule11,
        })
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
        const OP: &str = "collapse_edge";
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
            return Err(refuse(
                "collapse_edge",
                h,
                Refusal::Parameter("t must lie in 0..=1"),
            ));
        }
        self.check_collapse_edge(h)
    }

    /// [`collapse_edge`](Mesh::collapse_edge) with the merged vertex at
    /// parameter `t` from `a` to `b`: `b = merge(b: t, a: 1−t)`, the
    /// surviving `b` first (t = 0.5 puts it at the midpoint).
    ///
    /// # Errors
    /// As `collapse_edge`, and [`Refusal::Parameter`] when `t` is not in
    /// `0..=1`.
    ///
    /// # Complexity
    /// As `collapse_edge`.
    pub fn collapse_edge_at(&mut self, hk: HalfedgeKey, t: f64) -> Result<VertexKey> {
        if !(0.0..=1.0).contains(&t) {
            return Err(refuse(
                "collapse_edge",
                hk,
                Refusal::Parameter("t must lie in 0..=1"),
            ));
        }
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
        } = self.plan_collapse(hk)?;
        // Rule 11: which of b, c and d touched a hole before (a's holes
        // become b's). Only they can need another half-edge afterwards.
        // The surviving vertex first (the documented order KeepFirst reads).
        self.attrs
            .vertex
            .merge(b.index(), &[(b.index(), t), (a.index(), 1.0 - t)]);
        // Every half-edge leaving a now leaves b (the ring of a is walked by
        // next/twin, which the origins do not affect).
        let mut o = h;
        let mut budget = self.he.len();
        loop {
            self.he[o].origin = b;
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
        self.v_halfedge[b] = nh;
        self.free_edge(h.edge());
        self.free_vertex(a);
        if left_goes {
            // Two-sided loop (ph: c -> b, nh: b -> c): keep nh.
            self.dissolve_two_gon(ph, nh, before_tph);
        }
        if right_goes {
            // Two-sided loop (pt: d -> b, nt: b -> d): keep pt.
            self.dissolve_two_gon(nt, pt, None);
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
        self.debug_validate();
        Ok(self.vkey(b))
    }

    /// A face (or hole) left with the two half-edges `p` and `n` (parallel
    /// edges between the same vertices) disappears: `n` takes the place of
    /// `twin(p)` in its face and `p`'s edge goes. The mesh must be consistent
    /// apart from this two-sided loop. `before_tp`, when known, is the
    /// half-edge before `twin(p)` (else it is found by turning).
    fn dissolve_two_gon(&mut self, p: Hid, n: Hid, before_tp: Option<Hid>) {
        let f = self.face_of(p);
        let tp = p.twin();
        let g = self.face_of(tp);
        let q = before_tp.unwrap_or_else(|| self.prev_fast(tp));
        debug_assert_eq!(q, self.prev(tp));
        let r = self.next(tp);
        self.set_next(q, n);
        self.set_next(n, r);
        self.he[n].face = g;
        if self.face_halfedge(g) == tp {
            self.set_face_link(g, n);
        }
        let u = self.origin(p);
        let w = self.origin(tp);
        if self.v_halfedge[u] == p {
            self.v_halfedge[u] = n.twin();
        }
        if self.v_halfedge[w] == tp {
            self.v_halfedge[w] = n;
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
