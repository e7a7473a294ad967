//! Operators that merge faces: `remove_edge`, `merge_faces`,
//! `remove_vertex`.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::{EdgeKey, FaceKey, VertexKey};
use crate::layout::{Eid, Hid, Vid};
use crate::mesh::Mesh;

impl Mesh {
    fn plan_remove_edge(&self, ek: EdgeKey) -> Result<Eid> {
        const OP: &str = "remove_edge";
        let e = self.check_edge(ek)?;
        let [h, t] = e.halfedges();
        let (f_left, f_right) = (self.face_of(h), self.face_of(t));
        match (self.is_hole(f_left), self.is_hole(f_right)) {
            (false, false) => {
                // The merged face must not meet a vertex twice.
                let (a, b) = (self.origin(h), self.origin(t));
                let mut corners: Vec<Vid> = self
                    .face_halfedges(f_left)
                    .map(|x| self.origin(x))
                    .collect();
                corners.sort_unstable();
                for x in self.face_halfedges(f_right) {
                    let v = self.origin(x);
                    if v != a && v != b && corners.binary_search(&v).is_ok() {
                        return Err(refuse(OP, ek, Refusal::NonManifold));
                    }
                }
            }
            (hole_left, _) => {
                // The face beside the hole joins it; none of its other
                // edges may be on a boundary too (they would dangle).
                let x = if hole_left { t } else { h };
                if crate::circulate::FaceHalfedges::from_halfedge(self, x)
                    .any(|y| y != x && self.in_hole(y.twin()))
                {
                    return Err(refuse(OP, ek, Refusal::Bridge));
                }
            }
        }
        Ok(e)
    }

    /// Whether [`remove_edge`](Mesh::remove_edge) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`remove_edge`](Mesh::remove_edge).
    pub fn check_remove_edge(&self, e: EdgeKey) -> Result<()> {
        self.plan_remove_edge(e).map(|_| ())
    }

    /// Remove edge `e`; the faces on its two sides become one. On a
    /// boundary edge the face joins the hole, which grows.
    ///
    /// ```text
    ///   x ---- a ---- y        x ---- a ---- y
    ///   |      |      |        |             |
    ///   |  fl  e  fr  |   =>   |     fl      |
    ///   |      |      |        |             |
    ///   z ---- b ---- w        z ---- b ---- w
    /// ```
    ///
    /// Returns the merged face: the face of `e`'s first half-edge, or the
    /// hole when one side is a hole. Attributes: the kept face = `merge` of
    /// both, equal weights (a face that joins a hole loses its values). χ is
    /// unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey);
    /// [`Refusal::NonManifold`] when the two faces share a corner other than
    /// the edge's ends (the merged face would meet it twice);
    /// [`Refusal::Bridge`] on a boundary edge whose face has another
    /// boundary edge: removing it would leave a dangling edge or cut the
    /// mesh apart (ask for that with
    /// [`remove_edge_allowing_bridge`](Mesh::remove_edge_allowing_bridge)).
    ///
    /// # Complexity
    /// O(degree of both faces · log degree + degree of `a` and `b`).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let e = mesh.edges().next().unwrap();
    /// let f = mesh.remove_edge(e)?;
    /// assert_eq!(mesh.face(f)?.degree(), 6);
    /// assert_eq!(mesh.euler_characteristic(), 2);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn remove_edge(&mut self, ek: EdgeKey) -> Result<FaceKey> {
        journaled!(self.remove_edge_with(ek))
    }

    /// Whether [`remove_edge_allowing_bridge`](Mesh::remove_edge_allowing_bridge)
    /// would succeed; changes nothing.
    ///
    /// # Errors
    /// As [`remove_edge_allowing_bridge`](Mesh::remove_edge_allowing_bridge).
    pub fn check_remove_edge_allowing_bridge(&self, ek: EdgeKey) -> Result<()> {
        let [h, t] = self.check_edge(ek)?.halfedges();
        if self.in_hole(h) || self.in_hole(t) {
            Ok(())
        } else {
            self.check_remove_edge(ek)
        }
    }

    /// [`remove_edge`](Mesh::remove_edge), also where the edge is a bridge:
    /// on a boundary edge the face beside it joins the hole together with
    /// every other boundary edge of that face (they would dangle) and any
    /// vertex left without edges, which may cut the mesh apart; this is
    /// [`remove_face`](Mesh::remove_face) of that face.
    ///
    /// Returns the faces or holes now covering the edge's place: the merged
    /// face for an interior edge, else the holes `remove_face` returns.
    /// χ as for `remove_edge` or `remove_face`.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); for an interior edge,
    /// as `remove_edge`.
    ///
    /// # Complexity
    /// As `remove_edge` or `remove_face`.
    ///
    /// # Examples
    /// ```
    /// use meshloom::Mesh;
    /// // A strip of three quads: the middle quad's top edge is a bridge.
    /// let mut m = Mesh::from_faces(8, &[[0u32, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6]])?;
    /// let v: Vec<_> = m.vertices().collect();
    /// let top = m.find_halfedge(v[1], v[2])?.unwrap();
    /// let e = m.halfedge(top)?.edge().key();
    /// assert!(m.remove_edge(e).is_err());
    /// let holes = m.remove_edge_allowing_bridge(e)?;
    /// assert_eq!((holes.len(), m.face_count()), (2, 2));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn remove_edge_allowing_bridge(&mut self, ek: EdgeKey) -> Result<Vec<FaceKey>> {
        let [h, t] = self.check_edge(ek)?.halfedges();
        if self.in_hole(t) {
            let f = self.fkey(self.face_of(h));
            self.remove_face(f)
        } else if self.in_hole(h) {
            let f = self.fkey(self.face_of(t));
            self.remove_face(f)
        } else {
            self.remove_edge(ek).map(|f| vec![f])
        }
    }

    fn plan_merge_faces(&self, f: FaceKey, g: FaceKey) -> Result<Hid> {
        const OP: &str = "merge_faces";
        let fi = self.check_face(f)?;
        let gi = self.check_face(g)?;
        if self.is_hole(fi) {
            return Err(refuse(OP, f, Refusal::Hole));
        }
        if self.is_hole(gi) {
            return Err(refuse(OP, g, Refusal::Hole));
        }
        if fi == gi {
            return Err(refuse(OP, f, Refusal::Adjacent));
        }
        let mut shared = self
            .face_halfedges(fi)
            .filter(|&x| self.face_of(x.twin()) == gi);
        let Some(x) = shared.next() else {
            return Err(refuse(OP, f, Refusal::NotAdjacent));
        };
        if shared.next().is_some() {
            return Err(refuse(OP, f, Refusal::NonManifold));
        }
        let e = self.ekey(x.edge());
        self.plan_remove_edge(e)
            .map_err(|_| refuse(OP, f, Refusal::NonManifold))?;
        Ok(x)
    }

    /// Whether [`merge_faces`](Mesh::merge_faces) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`merge_faces`](Mesh::merge_faces).
    pub fn check_merge_faces(&self, f: FaceKey, g: FaceKey) -> Result<()> {
        self.plan_merge_faces(f, g).map(|_| ())
    }

    /// Merge two faces that share exactly one edge, by removing it (see
    /// [`remove_edge`](Mesh::remove_edge) for the diagram).
    ///
    /// Returns `f`, now the merged face. Attributes: `f = merge(f, g)`,
    /// equal weights. χ is unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Hole`];
    /// [`Refusal::Adjacent`] when `f == g`; [`Refusal::NotAdjacent`] when
    /// they share no edge; [`Refusal::NonManifold`] when they share more
    /// than one edge or another corner.
    ///
    /// # Complexity
    /// O(degree of both faces · log degree).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f: Vec<_> = mesh.faces().collect();
    /// let g = mesh.face(f[0])?.neighbors().next().unwrap();
    /// assert_eq!(mesh.merge_faces(f[0], g)?, f[0]);
    /// assert_eq!(mesh.face_count(), 5);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn merge_faces(&mut self, f: FaceKey, g: FaceKey) -> Result<FaceKey> {
        journaled!(self.merge_faces_with(f, g))
    }

    /// The ring of an interior vertex and the last half-edge of each face's
    /// segment, checked for `remove_vertex`.
    fn plan_remove_vertex(&self, vk: VertexKey) -> Result<(Vec<Hid>, Vec<Hid>)> {
        const OP: &str = "remove_vertex";
        let v = self.check_vertex(vk)?;
        if self.on_boundary(v) {
            return Err(refuse(OP, vk, Refusal::Boundary));
        }
        let outs: Vec<Hid> = self.outgoing(v).collect();
        let k = outs.len();
        let mut lasts = Vec::with_capacity(k);
        let mut corners = Vec::new();
        for i in 0..k {
            let stop = outs[(i + k - 1) % k].twin();
            let mut x = outs[i];
            for _ in 0..self.he.len() {
                let n = self.next(x);
                if n == stop {
                    break;
                }
                x = n;
                corners.push(self.origin(x));
            }
            lasts.push(x);
        }
        if corners.len() < 3 {
            return Err(refuse(OP, vk, Refusal::Degenerate));
        }
        corners.sort_unstable();
        if corners.windows(2).any(|w| w[0] == w[1]) {
            return Err(refuse(OP, vk, Refusal::NonManifold));
        }
        Ok((outs, lasts))
    }

    /// Whether [`remove_vertex`](Mesh::remove_vertex) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`remove_vertex`](Mesh::remove_vertex).
    pub fn check_remove_vertex(&self, v: VertexKey) -> Result<()> {
        self.plan_remove_vertex(v).map(|_| ())
    }

    /// Remove an interior vertex and its edges; the faces around it merge
    /// into one.
    ///
    /// ```text
    ///   x ---- y        x ---- y
    ///   | \  / |        |      |
    ///   |  v   |   =>   |  f   |
    ///   | /  \ |        |      |
    ///   w ---- z        w ---- z
    /// ```
    ///
    /// Returns the merged face (the face of `v`'s first outgoing
    /// half-edge). Attributes: it is the `merge` of all the faces, equal
    /// weights; `v` and its edges lose their values. χ is unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Boundary`]
    /// when a hole touches `v`; [`Refusal::NonManifold`] when the merged face
    /// would meet a vertex twice; [`Refusal::Degenerate`] when it would have
    /// fewer than three sides.
    ///
    /// # Complexity
    /// O(Σ degree of the faces around `v`).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let c = mesh.poke_face(f)?;
    /// let merged = mesh.remove_vertex(c)?;
    /// assert_eq!(mesh.face(merged)?.degree(), 4);
    /// assert_eq!(mesh.face_count(), 6);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn remove_vertex(&mut self, vk: VertexKey) -> Result<FaceKey> {
        journaled!(self.remove_vertex_with(vk))
    }
}

impl Mesh {
    /// [`remove_edge`](Mesh::remove_edge)'s body, in journaling mode `J`.
    fn remove_edge_with<J: Journaling>(&mut self, ek: EdgeKey) -> Result<FaceKey> {
        let mut w = self.writer::<J>();
        let e = w.plan_remove_edge(ek)?;
        let [h, t] = e.halfedges();
        let (f_left, f_right) = (w.face_of(h), w.face_of(t));
        let survivor = if w.is_hole(f_right) {
            f_right
        } else if w.is_hole(f_left) {
            f_left
        } else {
            let pair = [(f_left.index(), 0.5), (f_right.index(), 0.5)];
            w.attrs.face.merge(f_left.index(), &pair);
            f_left
        };
        w.remove_edge_raw(e, survivor);
        w.end_op();
        Ok(w.fkey(survivor))
    }

    /// [`merge_faces`](Mesh::merge_faces)'s body, in journaling mode `J`.
    fn merge_faces_with<J: Journaling>(&mut self, f: FaceKey, g: FaceKey) -> Result<FaceKey> {
        let mut w = self.writer::<J>();
        let x = w.plan_merge_faces(f, g)?;
        let (fi, gi) = (w.face_of(x), w.face_of(x.twin()));
        let pair = [(fi.index(), 0.5), (gi.index(), 0.5)];
        w.attrs.face.merge(fi.index(), &pair);
        w.remove_edge_raw(x.edge(), fi);
        w.end_op();
        Ok(f)
    }

    /// [`remove_vertex`](Mesh::remove_vertex)'s body, in journaling mode `J`.
    fn remove_vertex_with<J: Journaling>(&mut self, vk: VertexKey) -> Result<FaceKey> {
        let mut w = self.writer::<J>();
        let (outs, lasts) = w.plan_remove_vertex(vk)?;
        let v = w.origin(outs[0]);
        let k = outs.len();
        let faces: Vec<_> = outs.iter().map(|&o| w.face_of(o)).collect();
        let firsts: Vec<Hid> = outs.iter().map(|&o| w.next(o)).collect();
        let keep = faces[0];
        let share = 1.0 / k as f64;
        let inputs: Vec<(usize, f64)> = faces.iter().map(|&f| (f.index(), share)).collect();
        w.attrs.face.merge(keep.index(), &inputs);
        for i in 0..k {
            w.set_next(lasts[i], firsts[(i + k - 1) % k]);
            let u = w.dest(outs[i]);
            if w.v_halfedge[u] == outs[i].twin() {
                *w.v_halfedge_mut(u) = firsts[i];
            }
        }
        w.relabel_loop(firsts[0], keep);
        for &f in &faces[1..] {
            w.free_face(f);
        }
        for &o in &outs {
            w.free_edge(o.edge());
        }
        w.free_vertex(v);
        w.end_op();
        Ok(w.fkey(keep))
    }
}
