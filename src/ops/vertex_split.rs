//! `split_vertex`: the inverse of `collapse_edge`.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::HalfedgeKey;
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::{Mesh, Writer};

struct VertexSplitPlan {
    hc: Hid,
    hd: Hid,
    /// The half-edges strictly between `hd` and `hc` turning around `b`:
    /// they move to the new vertex.
    moved: Vec<Hid>,
    /// The half-edge before `twin(hd)` in its face.
    pd: Hid,
}

impl Mesh {
    fn plan_split_vertex(&self, hck: HalfedgeKey, hdk: HalfedgeKey) -> Result<VertexSplitPlan> {
        const OP: &str = "split_vertex";
        let hc = self.check_halfedge(hck)?;
        let hd = self.check_halfedge(hdk)?;
        let b = self.origin(hc);
        if self.origin(hd) != b {
            return Err(refuse(OP, hdk, Refusal::NotAdjacent));
        }
        if hc == hd || self.dest(hc) == self.dest(hd) {
            return Err(refuse(OP, hdk, Refusal::Adjacent));
        }
        let mut moved = Vec::new();
        let mut o = self.next(hd.twin());
        for _ in 0..self.he.len() {
            if o == hc {
                break;
            }
            moved.push(o);
            o = self.next(o.twin());
        }
        Ok(VertexSplitPlan {
            hc,
            hd,
            moved,
            pd: self.prev(hd.twin()),
        })
    }

    /// Whether [`split_vertex`](Mesh::split_vertex) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`split_vertex`](Mesh::split_vertex).
    pub fn check_split_vertex(&self, hc: HalfedgeKey, hd: HalfedgeKey) -> Result<()> {
        self.plan_split_vertex(hc, hd).map(|_| ())
    }

    /// Split vertex `b` in two, undoing [`collapse_edge`](Mesh::collapse_edge):
    /// `hc = b → c` and `hd = b → d` leave `b`; the half-edges turning
    /// clockwise from `hd` to `hc` (both excluded) move to a new vertex `a`,
    /// which is joined to `b`, `c` and `d`, with triangles `(a, b, c)` and
    /// `(b, a, d)` on both sides of the new edge.
    ///
    /// ```text
    ///        c                  c
    ///        |                / | \
    ///        |               /  |  \
    ///   x -- b      =>      x - a -h-> b
    ///        |               \  |  /
    ///        |                \ | /
    ///        d                  d
    /// ```
    ///
    /// Returns `h = a → b`. After `collapse_edge(h0)` returned `b`, the
    /// half-edges `b → c` and `b → d` towards the apexes of the triangles
    /// that disappeared give back the same connectivity. Attributes: `a =
    /// interpolate(b: 1)` (it starts at `b`'s position: move it with
    /// [`set_position`](Mesh::set_position)); new edges, faces and corners
    /// get `interpolate` of nothing. χ is unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::NotAdjacent`]
    /// when the two half-edges do not leave the same vertex;
    /// [`Refusal::Adjacent`] when they are the same or end at the same
    /// vertex.
    ///
    /// # Complexity
    /// O(degree of `b`).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let h0 = mesh.halfedges().next().unwrap();
    /// let hv = mesh.halfedge(h0)?;
    /// let (c, d) = (hv.next().dest().key(), hv.twin().next().dest().key());
    /// let b = mesh.collapse_edge(h0)?;
    /// let hc = mesh.find_halfedge(b, c)?.unwrap();
    /// let hd = mesh.find_halfedge(b, d)?.unwrap();
    /// let h = mesh.split_vertex(hc, hd)?;
    /// assert_eq!((mesh.vertex_count(), mesh.edge_count(), mesh.face_count()), (12, 30, 20));
    /// assert!(mesh.vertices().all(|v| mesh.vertex(v).unwrap().degree() == 5));
    /// assert_eq!(mesh.halfedge(h)?.dest().key(), b);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn split_vertex(&mut self, hck: HalfedgeKey, hdk: HalfedgeKey) -> Result<HalfedgeKey> {
        journaled!(self.split_vertex_with(hck, hdk))
    }

    /// What the split reads before it changes anything.
    fn read_split(&self, plan: VertexSplitPlan) -> VertexSplit {
        let (hc, hd) = (plan.hc, plan.hd);
        let b = self.origin(hc);
        let tdb = hd.twin(); // d -> b
        VertexSplit {
            b,
            c: self.dest(hc),
            d: self.dest(hd),
            tdb,
            f_c: self.face_of(hc),
            f_d: self.face_of(tdb),
            after_hc: self.next(hc),
            // Rule 11: only a boundary b can leave holes at b or at a.
            b_on_boundary: self.holes > 0 && self.on_boundary(b),
            plan,
        }
    }

    /// Attributes: `a = interpolate(b: 1)`, `ac` and `da` copy the corners
    /// they replace, everything else new interpolates nothing.
    fn split_vertex_attributes(&mut self, s: &VertexSplit, new: &NewElements) {
        let [h, t] = new.edges[0].halfedges();
        let [ac, ca] = new.edges[1].halfedges();
        let [ad, da] = new.edges[2].halfedges();
        self.attrs
            .vertex
            .interpolate(new.a.index(), &[(s.b.index(), 1.0)]);
        for e in new.edges {
            self.attrs.edge.interpolate(e.index(), &[]);
        }
        self.attrs.halfedge.copy(s.plan.hc.index(), ac.index());
        self.attrs.halfedge.copy(s.tdb.index(), da.index());
        for x in [h, ca, t, ad] {
            self.attrs.halfedge.interpolate(x.index(), &[]);
        }
        self.attrs.face.interpolate(new.left.index(), &[]);
        self.attrs.face.interpolate(new.right.index(), &[]);
    }
}

/// A planned vertex split with what it read before editing: `hc = b → c`,
/// `hd = b → d`, `tdb = d → b`, the faces of `hc` and `tdb`.
struct VertexSplit {
    plan: VertexSplitPlan,
    b: Vid,
    c: Vid,
    d: Vid,
    tdb: Hid,
    f_c: Fid,
    f_d: Fid,
    after_hc: Hid,
    b_on_boundary: bool,
}

/// The new vertex `a`, edges `ab`, `ac`, `ad` and triangles `(a, b, c)`
/// (left) and `(b, a, d)` (right).
struct NewElements {
    a: Vid,
    edges: [Eid; 3],
    left: Fid,
    right: Fid,
}

impl NewElements {
    /// `h = a → b`.
    fn h(&self) -> Hid {
        self.edges[0].halfedge(0)
    }
}

impl Mesh {
    /// [`split_vertex`](Mesh::split_vertex)'s body, in journaling mode `J`.
    fn split_vertex_with<J: Journaling>(
        &mut self,
        hck: HalfedgeKey,
        hdk: HalfedgeKey,
    ) -> Result<HalfedgeKey> {
        let mut w = self.writer::<J>();
        let plan = w.plan_split_vertex(hck, hdk)?;
        let s = w.read_split(plan);
        let a = w.alloc_vertex();
        let (e_ab, e_ac, e_ad) = (w.alloc_edge(), w.alloc_edge(), w.alloc_edge());
        let new = NewElements {
            a,
            edges: [e_ab, e_ac, e_ad],
            left: w.alloc_face(false),
            right: w.alloc_face(false),
        };
        w.move_split_wedge(&s, &new);
        w.link_split_triangles(&s, &new);
        w.point_split_vertices(&s, &new);
        w.split_vertex_attributes(&s, &new);
        w.end_op();
        Ok(w.hkey(new.h()))
    }
}

impl<J: Journaling> Writer<'_, J> {
    /// The moved half-edges leave `a`; in the faces beside the wedge `ac`
    /// takes `hc`'s place and `da` takes `d -> b`'s.
    fn move_split_wedge(&mut self, s: &VertexSplit, new: &NewElements) {
        let [ac, _] = new.edges[1].halfedges();
        let [_, da] = new.edges[2].halfedges();
        let moved = &s.plan.moved;
        let prev_c = moved.last().map_or(da, |&o| o.twin());
        let next_d = moved.first().copied().unwrap_or(ac);
        for &o in moved {
            self.he_mut(o).origin = new.a;
        }
        *self.he_mut(ac) = HalfedgeRecord {
            origin: new.a,
            next: s.after_hc,
            face: s.f_c,
        };
        *self.he_mut(da) = HalfedgeRecord {
            origin: s.d,
            next: next_d,
            face: s.f_d,
        };
        self.set_next(prev_c, ac);
        self.set_next(s.plan.pd, da);
        if self.face_halfedge(s.f_c) == s.plan.hc {
            self.set_face_link(s.f_c, ac);
        }
        if self.face_halfedge(s.f_d) == s.tdb {
            self.set_face_link(s.f_d, da);
        }
    }

    /// Triangles `(a, b, c)` and `(b, a, d)`.
    fn link_split_triangles(&mut self, s: &VertexSplit, new: &NewElements) {
        let (a, hc, tdb, left, right) = (new.a, s.plan.hc, s.tdb, new.left, new.right);
        let [h, t] = new.edges[0].halfedges(); // a -> b, b -> a
        let [_, ca] = new.edges[1].halfedges();
        let [ad, _] = new.edges[2].halfedges();
        *self.he_mut(h) = HalfedgeRecord {
            origin: a,
            next: hc,
            face: left,
        };
        self.he_mut(hc).next = ca;
        self.he_mut(hc).face = left;
        *self.he_mut(ca) = HalfedgeRecord {
            origin: s.c,
            next: h,
            face: left,
        };
        *self.he_mut(t) = HalfedgeRecord {
            origin: s.b,
            next: ad,
            face: right,
        };
        *self.he_mut(ad) = HalfedgeRecord {
            origin: a,
            next: tdb,
            face: right,
        };
        self.he_mut(tdb).next = t;
        self.he_mut(tdb).face = right;
        self.set_face_link(left, h);
        self.set_face_link(right, t);
    }

    /// The half-edges `a`, `b` and `d` name afterwards (rule 11 at a
    /// boundary `b`).
    fn point_split_vertices(&mut self, s: &VertexSplit, new: &NewElements) {
        let [_, da] = new.edges[2].halfedges();
        *self.v_halfedge_mut(new.a) = new.h();
        *self.v_halfedge_mut(s.b) = s.plan.hc;
        // da took d -> b's place in f_d (a hole, maybe): d keeps a half-edge
        // in that face.
        if self.v_halfedge[s.d] == s.tdb {
            *self.v_halfedge_mut(s.d) = da;
        }
        if s.b_on_boundary {
            self.point_at_hole(new.a);
            self.point_at_hole(s.b);
        }
    }
}
