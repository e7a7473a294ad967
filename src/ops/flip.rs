//! `flip_edge`: turn the diagonal of two triangles.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling, Unrecorded};
use crate::keys::EdgeKey;
use crate::layout::{Eid, FaceLink, Hid, Vid};
use crate::mesh::{Mesh, Writer};

/// The elements of a flip, named after the diagram on
/// [`Mesh::flip_edge`]: `h = a → b`, `t = b → a`, `h1 = b → c`,
/// `h2 = c → a`, `t1 = a → d`, `t2 = d → b`.
struct FlipPlan {
    e: Eid,
    h1: Hid,
    h2: Hid,
    t1: Hid,
    t2: Hid,
    c: Vid,
    d: Vid,
}

impl Mesh {
    // Inlined into both callers so that `flip_edge` reuses what the plan
    // read instead of reading it again.
    #[inline(always)]
    fn plan_flip(&self, ek: EdgeKey) -> Result<FlipPlan> {
        const OP: &str = "flip_edge";
        let e = self.check_edge(ek)?;
        let [h, t] = e.halfedges();
        let h1 = self.next(h);
        let t1 = self.next(t);
        let h2 = self.next(h1);
        let t2 = self.next(t1);
        // (A closed mesh has no holes: skip two random reads.)
        if self.holes > 0 && (self.in_hole(h) || self.in_hole(t)) {
            return Err(refuse(OP, ek, Refusal::Boundary));
        }
        let (r2, s2) = (self.he[h2], self.he[t2]);
        if r2.next != h || s2.next != t {
            return Err(refuse(OP, ek, Refusal::NotTriangles));
        }
        let (c, d) = (r2.origin, s2.origin);
        if c == d || self.joined_between(h2, h1.twin(), d) {
            return Err(refuse(OP, ek, Refusal::EdgeExists));
        }
        Ok(FlipPlan {
            e,
            h1,
            h2,
            t1,
            t2,
            c,
            d,
        })
    }

    /// Whether an edge joins `c = origin(first)` and `d`, looking only at
    /// the half-edges strictly between `first` and `last` in `c`'s ring
    /// (the two ends lead to `a` and `b`, which are not `d`).
    #[inline]
    fn joined_between(&self, first: Hid, last: Hid, d: Vid) -> bool {
        let mut o = self.next(first.twin());
        // Bounded: a ring has fewer than 2E half-edges.
        let mut budget = self.he.len();
        loop {
            if o == last {
                return false;
            }
            let twin = self.he[o.twin()];
            if twin.origin == d {
                return true;
            }
            o = twin.next;
            budget -= 1;
            if budget == 0 {
                return false;
            }
        }
    }

    /// Whether [`flip_edge`](Mesh::flip_edge) would succeed; changes nothing.
    ///
    /// # Errors
    /// As [`flip_edge`](Mesh::flip_edge).
    pub fn check_flip_edge(&self, e: EdgeKey) -> Result<()> {
        self.plan_flip(e).map(drop)
    }

    /// Replace the edge `a–b` shared by triangles `(a, b, c)` and
    /// `(b, a, d)` with the edge `c–d`.
    ///
    /// ```text
    ///        c                 c
    ///      /   \             / | \
    ///     a --h-> b   =>    a  h  b
    ///      \   /             \ | /
    ///        d                 d
    /// ```
    ///
    /// Returns the same edge key, now joining `c` and `d`; its first
    /// half-edge `h` runs `c → d` in face `(c, d, b)`, its twin `d → c` in
    /// `(d, c, a)`. Attributes: the two faces merge and split in equal shares;
    /// the edge keeps its values; the new corners copy the corners at `c`
    /// and `d` they replace. χ is unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Boundary`]
    /// when a hole lies beside the edge; [`Refusal::NotTriangles`];
    /// [`Refusal::EdgeExists`] when `c–d` is an edge already (or `c == d`).
    ///
    /// # Complexity
    /// O(degree of `c`).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let e = mesh.edges().next().unwrap();
    /// let before = mesh.edge(e)?.vertices();
    /// mesh.flip_edge(e)?;
    /// assert_ne!(mesh.edge(e)?.vertices(), before);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn flip_edge(&mut self, ek: EdgeKey) -> Result<EdgeKey> {
        journaled!(self.flip_edge_with(ek))
    }

    /// The remesher's door: [`flip_edge`](Mesh::flip_edge) of a live edge
    /// slot, checked as it is, without the per-call debug validation (the
    /// caller validates once at the end). A recording mesh takes the full
    /// operator, so every step is sealed as usual.
    pub(crate) fn flip_unvalidated(&mut self, e: Eid) -> Result<()> {
        let ek = self.ekey(e);
        if self.rec.is_some() {
            return self.flip_edge(ek).map(|_| ());
        }
        let plan = self.plan_flip(ek)?;
        self.writer::<Unrecorded>().commit_flip(plan);
        Ok(())
    }
}

impl Mesh {
    /// [`flip_edge`](Mesh::flip_edge)'s body, in journaling mode `J`.
    fn flip_edge_with<J: Journaling>(&mut self, ek: EdgeKey) -> Result<EdgeKey> {
        let mut w = self.writer::<J>();
        let plan = w.plan_flip(ek)?;
        w.commit_flip(plan);
        w.end_op();
        Ok(ek)
    }
}

impl<J: Journaling> Writer<'_, J> {
    /// The commit and rules of a planned flip; cannot fail.
    #[inline(always)]
    fn commit_flip(&mut self, plan: FlipPlan) {
        let FlipPlan {
            e,
            h1,
            h2,
            t1,
            t2,
            c,
            d,
        } = plan;
        let [h, t] = e.halfedges();
        let (a, b) = (self.origin(h), self.origin(t));
        let (f0, f1) = (self.face_of(h), self.face_of(t));
        // f0 = (h: c -> d, t2: d -> b, h1: b -> c);
        // f1 = (t: d -> c, h2: c -> a, t1: a -> d).
        self.he_mut(h).origin = c;
        self.he_mut(t).origin = d;
        self.set_next(h, t2);
        self.set_next(t2, h1);
        self.set_next(h1, h);
        self.set_next(t, h2);
        self.set_next(h2, t1);
        self.set_next(t1, t);
        self.he_mut(t2).face = f0;
        self.he_mut(h2).face = f1;
        // Neither face is a hole (refused above): no flag to keep.
        *self.f_halfedge_mut(f0) = FaceLink::new(h, false);
        *self.f_halfedge_mut(f1) = FaceLink::new(t, false);
        // a and b may have named h and t; t1 and h1 surely leave them. A
        // vertex that named another half-edge keeps it: a boundary vertex
        // names one in a hole (rule 11), which h and t are not.
        if self.v_halfedge[a] == h {
            *self.v_halfedge_mut(a) = t1;
        }
        if self.v_halfedge[b] == t {
            *self.v_halfedge_mut(b) = h1;
        }
        if !self.attrs.face.cols.is_empty() {
            let pair = [(f0.index(), 0.5), (f1.index(), 0.5)];
            self.attrs.face.merge(f0.index(), &pair);
            self.attrs.face.split(f0.index(), &pair);
        }
        self.attrs.halfedge.copy(h2.index(), h.index());
        self.attrs.halfedge.copy(t2.index(), t.index());
    }
}
