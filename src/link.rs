//! Low-level reflecting setters, for people writing their own operators.
//!
//! [`Mesh::raw_edit`] hands out a [`RawEdit`] guard. Its setters write one
//! link each and *reflect* it where the mesh keeps a back link:
//! [`set_origin`](RawEdit::set_origin) also points the vertex at the
//! half-edge, [`set_face`](RawEdit::set_face) also points the face at it.
//! `next` is the only face-order link (there is no `prev`);
//! [`link(a, b)`](RawEdit::link) sets `next(a) = b`. Between setters the
//! mesh may break its rules; call [`RawEdit::finish`] when done, and do not
//! use views on a mesh that does not validate.
//!
//! Rule 11 of [`validate`](crate::validate) (a vertex that touches a hole
//! names an outgoing half-edge in a hole) is the one rule the setters need
//! not keep by hand: [`finish`](RawEdit::finish) re-establishes it for
//! every vertex (pointing each vertex that touches a hole, and names a
//! half-edge leaving it that lies in none, at one that lies in a hole)
//! before it validates. [`RawEdit::validate`] checks the mesh as it is, so
//! in the middle of an edit it may report rule 11 where `finish` would
//! not. Attribute columns follow new and removed elements (new
//! elements hold default values), but no merge or split rule runs: that is
//! the operator writer's choice.
//!
//! ```
//! use meshloom::Mesh;
//! // Flip the diagonal of a square by hand.
//! let mut mesh = Mesh::from_faces(4, &[[0u32, 1, 2], [0, 2, 3]])?;
//! let v: Vec<_> = mesh.vertices().collect();
//! let h = mesh.find_halfedge(v[0], v[2])?.unwrap(); // 0 -> 2, in face (0, 2, 3)
//! let t = mesh.halfedge(h)?.twin().key();            // 2 -> 0, in face (0, 1, 2)
//! let (h1, t1) = (mesh.halfedge(h)?.next().key(), mesh.halfedge(t)?.next().key());
//! let (h2, t2) = (mesh.halfedge(h1)?.next().key(), mesh.halfedge(t1)?.next().key());
//! let (f0, f1) = (mesh.halfedge(h)?.face().key(), mesh.halfedge(t)?.face().key());
//! let mut edit = mesh.raw_edit();
//! edit.set_origin(h, v[3])?;      // h: 3 -> 1
//! edit.set_origin(t, v[1])?;      // t: 1 -> 3
//! edit.set_origin(t1, v[0])?;     // 0 and 2 point at half-edges they keep
//! edit.set_origin(h1, v[2])?;
//! edit.link(h, t2)?; edit.link(t2, h1)?; edit.link(h1, h)?; // (3, 1, 2)
//! edit.link(t, h2)?; edit.link(h2, t1)?; edit.link(t1, t)?; // (1, 3, 0)
//! edit.set_face(t2, f0)?; edit.set_face(h1, f0)?; edit.set_face(h, f0)?;
//! edit.set_face(h2, f1)?; edit.set_face(t1, f1)?; edit.set_face(t, f1)?;
//! edit.finish()?;
//! assert!(mesh.find_halfedge(v[1], v[3])?.is_some());
//! # Ok::<(), meshloom::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::keys::{EdgeKey, FaceKey, HalfedgeKey, VertexKey};
use crate::layout::Vid;
use crate::mesh::Mesh;
use crate::record::Recorded;

/// A guard for raw link edits; see the [module docs](self).
///
/// While the guard lives the mesh may break its rules; [`RawEdit::finish`]
/// checks them all. A triangle from nothing:
///
/// ```
/// let mut mesh = meshloom::Mesh::new();
/// let mut edit = mesh.raw_edit();
/// let v = [edit.new_vertex(), edit.new_vertex(), edit.new_vertex()];
/// let e = [edit.new_edge(), edit.new_edge(), edit.new_edge()];
/// let (face, hole) = (edit.new_face(false), edit.new_face(true));
/// for i in 0..3 {
///     let j = (i + 1) % 3;
///     // Side 0 of edge i runs v[i] -> v[j] in the face, side 1 back in the hole.
///     let (h, t) = (e[i].halfedge_key(0), e[i].halfedge_key(1));
///     edit.set_origin(h, v[i])?;
///     edit.set_origin(t, v[j])?;
///     edit.set_face(h, face)?;
///     edit.set_face(t, hole)?;
///     edit.link(h, e[j].halfedge_key(0))?;
///     edit.link(e[j].halfedge_key(1), t)?;
/// }
/// edit.finish()?;
/// assert_eq!((mesh.vertex_count(), mesh.face_count(), mesh.hole_count()), (3, 1, 1));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub struct RawEdit<'m> {
    mesh: &'m mut Mesh,
}

impl Mesh {
    /// Start raw link edits (see [`link`](crate::link)).
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let f = mesh.faces().next().unwrap();
    /// let mut edit = mesh.raw_edit();
    /// edit.set_hole(f, true)?; // the face becomes the outside of a boundary loop
    /// edit.finish()?;
    /// assert_eq!((mesh.face_count(), mesh.hole_count()), (3, 1));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn raw_edit(&mut self) -> RawEdit<'_> {
        RawEdit { mesh: self }
    }
}

impl RawEdit<'_> {
    /// The origin link of `h`, if set.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let a = mesh.halfedge(h)?.origin().key();
    /// let mut edit = mesh.raw_edit();
    /// assert_eq!(edit.origin(h)?, Some(a));
    /// let e = edit.new_edge();
    /// assert_eq!(edit.origin(e.halfedge_key(0))?, None); // not linked yet
    /// edit.remove_edge(e)?;
    /// edit.finish()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn origin(&self, h: HalfedgeKey) -> Result<Option<VertexKey>> {
        let h = self.mesh.check_halfedge(h)?;
        let o = self.mesh.origin(h);
        Ok(self.live_vertex(o))
    }

    /// The next link of `h`, if set.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let n = mesh.halfedge(h)?.next().key();
    /// let mut edit = mesh.raw_edit();
    /// assert_eq!(edit.next(h)?, Some(n));
    /// let e = edit.new_edge();
    /// assert_eq!(edit.next(e.halfedge_key(0))?, None);
    /// edit.remove_edge(e)?;
    /// edit.finish()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn next(&self, h: HalfedgeKey) -> Result<Option<HalfedgeKey>> {
        let h = self.mesh.check_halfedge(h)?;
        let n = self.mesh.next(h);
        Ok((!n.is_none() && self.mesh.edge_live(n.edge().index())).then(|| self.mesh.hkey(n)))
    }

    /// The face link of `h`, if set.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let f = mesh.halfedge(h)?.face().key();
    /// let mut edit = mesh.raw_edit();
    /// assert_eq!(edit.face(h)?, Some(f));
    /// let e = edit.new_edge();
    /// assert_eq!(edit.face(e.halfedge_key(1))?, None);
    /// edit.remove_edge(e)?;
    /// edit.finish()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn face(&self, h: HalfedgeKey) -> Result<Option<FaceKey>> {
        let h = self.mesh.check_halfedge(h)?;
        let f = self.mesh.face_of(h);
        Ok((!f.is_none() && self.mesh.face_live(f.index())).then(|| self.mesh.fkey(f)))
    }

    fn live_vertex(&self, v: Vid) -> Option<VertexKey> {
        (!v.is_none() && self.mesh.vertex_live(v.index())).then(|| self.mesh.vkey(v))
    }

    /// Set `origin(h) = v` and reflect it: `v`'s half-edge becomes `h`.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let v = mesh.vertices().next().unwrap();
    /// let h = mesh.vertex(v)?.outgoing().nth(1).unwrap();
    /// let mut edit = mesh.raw_edit();
    /// edit.set_origin(h, v)?; // the same origin, and v now names h
    /// edit.finish()?;
    /// assert_eq!(mesh.vertex(v)?.halfedge().key(), h);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn set_origin(&mut self, h: HalfedgeKey, v: VertexKey) -> Result<()> {
        let h = self.mesh.check_halfedge(h)?;
        let v = self.mesh.check_vertex(v)?;
        let mut w = self.mesh.writer::<Recorded>();
        w.he_mut(h).origin = v;
        *w.v_halfedge_mut(v) = h;
        Ok(())
    }

    /// Set `face(h) = f` and reflect it: `f`'s half-edge becomes `h` (its
    /// hole flag is kept).
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let h = mesh.face(f)?.halfedges().nth(2).unwrap();
    /// let mut edit = mesh.raw_edit();
    /// edit.set_face(h, f)?; // the same face, and f now names h
    /// edit.finish()?;
    /// assert_eq!(mesh.face(f)?.halfedge().key(), h);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn set_face(&mut self, h: HalfedgeKey, f: FaceKey) -> Result<()> {
        let h = self.mesh.check_halfedge(h)?;
        let f = self.mesh.check_face(f)?;
        let mut w = self.mesh.writer::<Recorded>();
        w.he_mut(h).face = f;
        w.set_face_link(f, h);
        Ok(())
    }

    /// Set `next(a) = b`.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let n = mesh.halfedge(h)?.next().key();
    /// let mut edit = mesh.raw_edit();
    /// edit.link(h, n)?;
    /// assert_eq!(edit.next(h)?, Some(n));
    /// edit.finish()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn link(&mut self, a: HalfedgeKey, b: HalfedgeKey) -> Result<()> {
        let a = self.mesh.check_halfedge(a)?;
        let b = self.mesh.check_halfedge(b)?;
        self.mesh.writer::<Recorded>().set_next(a, b);
        Ok(())
    }

    /// Point vertex `v` at half-edge `h` (which should leave it), without
    /// touching `h`.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let v = mesh.vertices().next().unwrap();
    /// let third = mesh.vertex(v)?.outgoing().nth(2).unwrap();
    /// let mut edit = mesh.raw_edit();
    /// edit.set_vertex_halfedge(v, third)?;
    /// edit.finish()?;
    /// assert_eq!(mesh.vertex(v)?.outgoing().next(), Some(third)); // circulation starts there
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn set_vertex_halfedge(&mut self, v: VertexKey, h: HalfedgeKey) -> Result<()> {
        let h = self.mesh.check_halfedge(h)?;
        let v = self.mesh.check_vertex(v)?;
        *self.mesh.writer::<Recorded>().v_halfedge_mut(v) = h;
        Ok(())
    }

    /// Point face `f` at half-edge `h` (which should be in it), without
    /// touching `h`.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let second = mesh.face(f)?.halfedges().nth(1).unwrap();
    /// let mut edit = mesh.raw_edit();
    /// edit.set_face_halfedge(f, second)?;
    /// edit.finish()?;
    /// assert_eq!(mesh.face(f)?.halfedges().next(), Some(second)); // the face's corners start there
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn set_face_halfedge(&mut self, f: FaceKey, h: HalfedgeKey) -> Result<()> {
        let h = self.mesh.check_halfedge(h)?;
        let f = self.mesh.check_face(f)?;
        self.mesh.writer::<Recorded>().set_face_link(f, h);
        Ok(())
    }

    /// Flag face `f` as a hole, or not.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let mut edit = mesh.raw_edit();
    /// edit.set_hole(f, true)?; // open the box
    /// edit.finish()?;
    /// assert!(mesh.face(f)?.is_hole());
    /// assert_eq!((mesh.face_count(), mesh.hole_count()), (5, 1));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn set_hole(&mut self, f: FaceKey, hole: bool) -> Result<()> {
        let f = self.mesh.check_face(f)?;
        self.mesh.writer::<Recorded>().set_hole(f, hole);
        Ok(())
    }

    /// A new vertex with no links yet.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let mut edit = mesh.raw_edit();
    /// let v = edit.new_vertex();
    /// assert!(edit.validate().is_err()); // a vertex no half-edge leaves
    /// edit.remove_vertex(v)?;
    /// edit.finish()?;
    /// assert_eq!(mesh.vertex_count(), 4);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn new_vertex(&mut self) -> VertexKey {
        let v = self.mesh.writer::<Recorded>().alloc_vertex();
        self.mesh.vkey(v)
    }

    /// A new edge (two half-edges, [`EdgeKey::halfedge_key`]) with no links
    /// yet.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let mut edit = mesh.raw_edit();
    /// let e = edit.new_edge();
    /// assert_eq!(e.halfedge_key(0).twin_key(), e.halfedge_key(1));
    /// edit.remove_edge(e)?;
    /// edit.finish()?;
    /// assert_eq!(mesh.edge_count(), 6);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn new_edge(&mut self) -> EdgeKey {
        let e = self.mesh.writer::<Recorded>().alloc_edge();
        self.mesh.ekey(e)
    }

    /// A new face (a hole if `hole`) with no links yet.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let mut edit = mesh.raw_edit();
    /// let f = edit.new_face(false);
    /// assert!(edit.validate().is_err()); // a face without half-edges
    /// edit.remove_face(f)?;
    /// edit.finish()?;
    /// assert_eq!(mesh.face_count(), 4);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn new_face(&mut self, hole: bool) -> FaceKey {
        let f = self.mesh.writer::<Recorded>().alloc_face(hole);
        self.mesh.fkey(f)
    }

    /// Remove a vertex slot (links to it are the caller's to fix).
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let v = mesh.vertices().next().unwrap();
    /// let mut edit = mesh.raw_edit();
    /// edit.remove_vertex(v)?;
    /// assert!(edit.validate().is_err()); // half-edges still leave it
    /// assert!(edit.remove_vertex(v).is_err()); // its key is stale now
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn remove_vertex(&mut self, v: VertexKey) -> Result<()> {
        let v = self.mesh.check_vertex(v)?;
        self.mesh.writer::<Recorded>().free_vertex(v);
        Ok(())
    }

    /// Remove an edge and both its half-edges.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let mut edit = mesh.raw_edit();
    /// let e = edit.new_edge();
    /// edit.remove_edge(e)?;
    /// assert!(edit.origin(e.halfedge_key(0)).is_err()); // both half-edges went
    /// edit.finish()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn remove_edge(&mut self, e: EdgeKey) -> Result<()> {
        let e = self.mesh.check_edge(e)?;
        self.mesh.writer::<Recorded>().free_edge(e);
        Ok(())
    }

    /// Remove a face or hole.
    ///
    /// # Errors
    /// [`Error::StaleKey`].
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let mut edit = mesh.raw_edit();
    /// let hole = edit.new_face(true);
    /// edit.remove_face(hole)?;
    /// edit.finish()?;
    /// assert_eq!(mesh.hole_count(), 0);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn remove_face(&mut self, f: FaceKey) -> Result<()> {
        let f = self.mesh.check_face(f)?;
        self.mesh.writer::<Recorded>().free_face(f);
        Ok(())
    }

    /// Check every structural rule on the edited mesh.
    ///
    /// # Errors
    /// [`Error::Invalid`] with the first broken rule.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let mut edit = mesh.raw_edit();
    /// assert!(edit.validate().is_ok());
    /// let v = edit.new_vertex();
    /// assert!(edit.validate().is_err()); // mid-edit, the rules may break
    /// edit.remove_vertex(v)?;
    /// edit.finish()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn validate(&self) -> Result<()> {
        self.mesh.validate().map_err(Error::Invalid)
    }

    /// End the edit: re-establish rule 11 (boundary vertices name a
    /// half-edge in a hole; see the [module docs](self)), then
    /// [`validate`](RawEdit::validate), consuming the guard.
    ///
    /// # Errors
    /// As `validate`.
    ///
    /// # Complexity
    /// O(half-edges) for rule 11, plus `validate`.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let mut edit = mesh.raw_edit();
    /// let v = edit.new_vertex();
    /// assert!(edit.finish().is_err()); // the stray vertex breaks a rule
    /// // The mesh stays as the setters left it; a new session mends it.
    /// let mut edit = mesh.raw_edit();
    /// edit.remove_vertex(v)?;
    /// edit.finish()?;
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn finish(self) -> Result<()> {
        self.mesh.point_all_at_holes();
        let out = self.validate();
        // One journal step for the whole session (see [`journal`](crate::journal)).
        self.mesh.end_edit();
        out
    }
}
