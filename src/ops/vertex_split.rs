//! `split_vertex`: the inverse of `collapse_edge`.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::HalfedgeKey;
use crate::layout::{HalfedgeRecord, Hid};
use crate::mesh::Mesh;

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

    /// [`split_vertex`](Mesh::split_vertex)'s body, in journaling mode `J`.
    fn split_vertex_with<J: Journaling>(
        &mut self,
        hck: HalfedgeKey,
        hdk: HalfedgeKey,
    ) -> Result<HalfedgeKey> {
        let VertexSplitPlan { hc, hd, moved, pd } = self.plan_split_vertex(hck, hdk)?;
        let b = self.origin(hc);
        let c = self.dest(hc);
        let d = self.dest(hd);
        let tdb = hd.twin(); // d -> b
        let f_c = self.face_of(hc);
        let f_d = self.face_of(tdb);
        let after_hc = self.next(hc);
        // Rule 11: only a boundary b can leave holes at b or at a.
        let b_on_boundary = self.holes > 0 && self.on_boundary(b);
        let a = self.alloc_vertex::<J>();
        let (e_ab, e_ac, e_ad) = (
            self.alloc_edge::<J>(),
            self.alloc_edge::<J>(),
            self.alloc_edge::<J>(),
        );
        let [h, t] = e_ab.halfedges(); // a -> b, b -> a
        let [ac, ca] = e_ac.halfedges();
        let [ad, da] = e_ad.halfedges();
        let left = self.alloc_face::<J>(false);
        let right = self.alloc_face::<J>(false);
        let prev_c = moved.last().map_or(da, |&o| o.twin());
        let next_d = moved.first().copied().unwrap_or(ac);
        for &o in &moved {
            self.he_mut::<J>(o).origin = a;
        }
        // The faces beside the wedge: ac takes hc's place, da takes d -> b's.
        *self.he_mut::<J>(ac) = HalfedgeRecord {
            origin: a,
            next: after_hc,
            face: f_c,
        };
        *self.he_mut::<J>(da) = HalfedgeRecord {
            origin: d,
            next: next_d,
            face: f_d,
        };
        self.set_next::<J>(prev_c, ac);
        self.set_next::<J>(pd, da);
        if self.face_halfedge(f_c) == hc {
            self.set_face_link::<J>(f_c, ac);
        }
        if self.face_halfedge(f_d) == tdb {
            self.set_face_link::<J>(f_d, da);
        }
        // Triangles (a, b, c) and (b, a, d).
        *self.he_mut::<J>(h) = HalfedgeRecord {
            origin: a,
            next: hc,
            face: left,
        };
        self.he_mut::<J>(hc).next = ca;
        self.he_mut::<J>(hc).face = left;
        *self.he_mut::<J>(ca) = HalfedgeRecord {
            origin: c,
            next: h,
            face: left,
        };
        *self.he_mut::<J>(t) = HalfedgeRecord {
            origin: b,
            next: ad,
            face: right,
        };
        *self.he_mut::<J>(ad) = HalfedgeRecord {
            origin: a,
            next: tdb,
            face: right,
        };
        self.he_mut::<J>(tdb).next = t;
        self.he_mut::<J>(tdb).face = right;
        self.set_face_link::<J>(left, h);
        self.set_face_link::<J>(right, t);
        *self.v_halfedge_mut::<J>(a) = h;
        *self.v_halfedge_mut::<J>(b) = hc;
        // da took d -> b's place in f_d (a hole, maybe): d keeps a half-edge
        // in that face.
        if self.v_halfedge[d] == tdb {
            *self.v_halfedge_mut::<J>(d) = da;
        }
        if b_on_boundary {
            self.point_at_hole::<J>(a);
            self.point_at_hole::<J>(b);
        }
        // Attributes.
        self.attrs
            .vertex
            .interpolate(a.index(), &[(b.index(), 1.0)]);
        for e in [e_ab, e_ac, e_ad] {
            self.attrs.edge.interpolate(e.index(), &[]);
        }
        self.attrs.halfedge.copy(hc.index(), ac.index());
        self.attrs.halfedge.copy(tdb.index(), da.index());
        for x in [h, ca, t, ad] {
            self.attrs.halfedge.interpolate(x.index(), &[]);
        }
        self.attrs.face.interpolate(left.index(), &[]);
        self.attrs.face.interpolate(right.index(), &[]);
        self.end_op::<J>();
        Ok(self.hkey(h))
    }
}
