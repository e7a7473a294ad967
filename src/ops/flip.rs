//! `flip_edge`: turn the diagonal of two triangles.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::keys::EdgeKey;
use crate::mesh::Mesh;

impl Mesh {
    fn plan_flip(&self, ek: EdgeKey) -> Result<u32> {
        const OP: &str = "flip_edge";
        let e = self.check_edge(ek)?;
        let (h, t) = (2 * e, 2 * e + 1);
        let h1 = self.next_of(h);
        let t1 = self.next_of(t);
        let h2 = self.next_of(h1);
        let t2 = self.next_of(t1);
        // (A closed mesh has no holes: skip two random reads.)
        if self.holes > 0 && (self.in_hole_raw(h) || self.in_hole_raw(t)) {
            return Err(refuse(OP, ek, Refusal::Boundary));
        }
        if self.next_of(h2) != h || self.next_of(t2) != t {
            return Err(refuse(OP, ek, Refusal::NotTriangles));
        }
        let c = self.origin_of(h2);
        let d = self.origin_of(t2);
        if c == d || self.joined_from(h2, d) {
            return Err(refuse(OP, ek, Refusal::EdgeExists));
        }
        Ok(e)
    }

    /// Whether an edge joins `origin(start)` and `b` (a plain loop over
    /// the ring, starting at a half-edge already in cache).
    #[inline]
    fn joined_from(&self, start: u32, b: u32) -> bool {
        let mut o = start;
        for _ in 0..self.he.len() {
            if self.dest_of(o) == b {
                return true;
            }
            o = self.next_of(o ^ 1);
            if o == start {
                return false;
            }
        }
        false
    }

    /// Whether [`flip_edge`](Mesh::flip_edge) would succeed; changes nothing.
    ///
    /// # Errors
    /// As [`flip_edge`](Mesh::flip_edge).
    pub fn check_flip_edge(&self, e: EdgeKey) -> Result<()> {
        self.plan_flip(e).map(|_| ())
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
        let e = self.plan_flip(ek)?;
        let (h, t) = (2 * e, 2 * e + 1);
        let (h1, t1) = (self.next_of(h), self.next_of(t));
        let (h2, t2) = (self.next_of(h1), self.next_of(t1));
        let (a, b) = (self.origin_of(h), self.origin_of(t));
        let (c, d) = (self.origin_of(h2), self.origin_of(t2));
        let (f0, f1) = (self.face_of(h), self.face_of(t));
        // f0 = (h: c -> d, t2: d -> b, h1: b -> c);
        // f1 = (t: d -> c, h2: c -> a, t1: a -> d).
        self.he[h as usize].origin = c;
        self.he[t as usize].origin = d;
        self.set_next(h, t2);
        self.set_next(t2, h1);
        self.set_next(h1, h);
        self.set_next(t, h2);
        self.set_next(h2, t1);
        self.set_next(t1, t);
        self.he[t2 as usize].face = f0;
        self.he[h2 as usize].face = f1;
        self.set_face_link(f0, h);
        self.set_face_link(f1, t);
        // a and b may have named h and t; t1 and h1 surely leave them.
        self.v_halfedge[a as usize] = t1;
        self.v_halfedge[b as usize] = h1;
        if !self.attrs.face.cols.is_empty() {
            let pair = [(f0 as usize, 0.5), (f1 as usize, 0.5)];
            self.attrs.face.merge(f0 as usize, &pair);
            self.attrs.face.split(f0 as usize, &pair);
        }
        self.attrs.halfedge.copy(h2 as usize, h as usize);
        self.attrs.halfedge.copy(t2 as usize, t as usize);
        self.debug_validate();
        Ok(ek)
    }
}
