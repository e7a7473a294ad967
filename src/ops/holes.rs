//! Faces into holes and back: `remove_face`, `fill_hole`.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::FaceKey;
use crate::layout::{Fid, Hid, Vid};
use crate::mesh::{Mesh, Writer};

impl Mesh {
    fn plan_remove_face(&self, fk: FaceKey) -> Result<Fid> {
        let f = self.check_face(fk)?;
        if self.is_hole(f) {
            return Err(refuse("remove_face", fk, Refusal::Hole));
        }
        Ok(f)
    }

    /// Whether [`remove_face`](Mesh::remove_face) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`remove_face`](Mesh::remove_face).
    pub fn check_remove_face(&self, f: FaceKey) -> Result<()> {
        self.plan_remove_face(f).map(|_| ())
    }

    /// Turn face `f` into (part of) a hole. Its edges on a boundary would
    /// have holes on both sides, so they go, and with them vertices left
    /// without edges; where `f` touched the same hole twice the hole splits
    /// in two (the mesh comes apart there, or a handle is cut).
    ///
    /// ```text
    ///   x ---- a ---- y        x ---- a ---- y
    ///   |      |      |        |      |
    ///   |      |  f   |   =>   |      |   (hole)
    ///   |      |      |        |      |
    ///   z ---- b ---- w        z ---- b
    /// ```
    ///
    /// Returns the holes that now cover `f`'s place (none when nothing
    /// around it remains, as for a lone triangle). Attributes: the face's
    /// values, and those of removed edges and vertices, are dropped. χ
    /// changes by −1 + (edges removed) − (vertices removed).
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Hole`] on a
    /// hole.
    ///
    /// # Complexity
    /// O(degree of `f` · degree of its corners).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let holes = mesh.remove_face(f)?;
    /// assert_eq!(holes, vec![f]);
    /// assert_eq!((mesh.face_count(), mesh.hole_count()), (5, 1));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn remove_face(&mut self, fk: FaceKey) -> Result<Vec<FaceKey>> {
        journaled!(self.remove_face_with(fk))
    }

    fn plan_fill_hole(&self, hk: FaceKey) -> Result<Fid> {
        const OP: &str = "fill_hole";
        let h = self.check_face(hk)?;
        if !self.is_hole(h) {
            return Err(refuse(OP, hk, Refusal::NotHole));
        }
        let mut corners: Vec<Vid> = self.face_halfedges(h).map(|x| self.origin(x)).collect();
        if corners.len() < 3 {
            return Err(refuse(OP, hk, Refusal::Degenerate));
        }
        corners.sort_unstable();
        if corners.windows(2).any(|w| w[0] == w[1]) {
            return Err(refuse(OP, hk, Refusal::NonManifold));
        }
        Ok(h)
    }

    /// Whether [`fill_hole`](Mesh::fill_hole) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`fill_hole`](Mesh::fill_hole).
    pub fn check_fill_hole(&self, hole: FaceKey) -> Result<()> {
        self.plan_fill_hole(hole).map(|_| ())
    }

    /// Make hole `hole` a face: one polygon over the whole boundary loop.
    /// Follow with [`triangulate`](Mesh::triangulate) for triangles.
    ///
    /// ```text
    ///   a ---- b        a ---- b
    ///   | hole |   =>   |  f   |
    ///   d ---- c        d ---- c
    /// ```
    ///
    /// Returns the face; it keeps the hole's key. Attributes: the face gets
    /// `interpolate` of nothing (absent for interpolated columns). χ grows
    /// by 1.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::NotHole`];
    /// [`Refusal::NonManifold`] when the loop passes a vertex twice (holes
    /// meeting at a bowtie vertex).
    ///
    /// # Complexity
    /// O(degree of the hole · log degree).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let hole = mesh.remove_face(f)?[0];
    /// let g = mesh.fill_hole(hole)?;
    /// assert_eq!(mesh.face(g)?.degree(), 4);
    /// assert!(mesh.is_closed());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn fill_hole(&mut self, hole: FaceKey) -> Result<FaceKey> {
        journaled!(self.fill_hole_with(hole))
    }
}

impl Mesh {
    /// [`remove_face`](Mesh::remove_face)'s body, in journaling mode `J`.
    fn remove_face_with<J: Journaling>(&mut self, fk: FaceKey) -> Result<Vec<FaceKey>> {
        let mut w = self.writer::<J>();
        let f = w.plan_remove_face(fk)?;
        let sides: Vec<Hid> = w.face_halfedges(f).collect();
        w.set_hole(f, true);
        w.attrs.face.interpolate(f.index(), &[]);
        // Rule 11: every corner is now on the boundary.
        for &x in &sides {
            let v = w.origin(x);
            *w.v_halfedge_mut(v) = x;
        }
        let mut kept = Vec::new();
        let mut dangling = Vec::new();
        for &x in &sides {
            if w.in_hole(x.twin()) {
                dangling.push(x);
            } else {
                kept.push(x);
            }
        }
        for x in dangling {
            let survivor = w.face_of(x.twin());
            w.remove_edge_raw(x.edge(), survivor);
        }
        let mut holes: Vec<Fid> = kept.iter().map(|&x| w.face_of(x)).collect();
        holes.sort_unstable();
        holes.dedup();
        w.end_op();
        Ok(holes.into_iter().map(|h| w.fkey(h)).collect())
    }

    /// [`fill_hole`](Mesh::fill_hole)'s body, in journaling mode `J`.
    fn fill_hole_with<J: Journaling>(&mut self, hole: FaceKey) -> Result<FaceKey> {
        let mut w = self.writer::<J>();
        w.fill_hole_open(hole)?;
        w.end_op();
        Ok(hole)
    }
}

impl<J: Journaling> Writer<'_, J> {
    /// [`fill_hole`](Mesh::fill_hole) without ending the edit: for
    /// composite operators, which end theirs once (one journal step).
    pub(crate) fn fill_hole_open(&mut self, hole: FaceKey) -> Result<()> {
        let h = self.plan_fill_hole(hole)?;
        self.set_hole(h, false);
        self.attrs.face.interpolate(h.index(), &[]);
        // Rule 11: a corner that named a half-edge of the hole names another
        // hole's, if one still touches it.
        let corners: Vec<Vid> = self.face_halfedges(h).map(|x| self.origin(x)).collect();
        for v in corners {
            self.point_at_hole(v);
        }
        Ok(())
    }
}
