//! The mutators every link write goes through.
//!
//! The mesh keeps its links in [`LinkVec`](crate::layout::LinkVec)s, which
//! have no `IndexMut`: a write is one of the calls below. Each records the
//! old value first while a journal is on ([`Mesh::rec`] is `Some`) and the
//! slot existed when the open step began; with no journal the check is one
//! test of a pointer that is null, and the write is the plain store it
//! replaced. Slot births and deaths are recorded in
//! [`Mesh::alloc_vertex`] and its siblings, attribute writes in
//! [`Columns`](crate::store::Columns) (`save`, one compare).

use crate::layout::{FaceLink, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::Mesh;

impl Mesh {
    /// Record half-edge `h`'s links before a write.
    #[inline(always)]
    fn log_he(&mut self, h: Hid) {
        if let Some(r) = self.rec.as_deref_mut() {
            r.save_he(h, self.he[h]);
        }
    }

    /// Set all three links of half-edge `h`.
    #[inline(always)]
    pub(crate) fn set_he(&mut self, h: Hid, record: HalfedgeRecord) {
        self.log_he(h);
        *self.he.unlogged_mut(h) = record;
    }

    /// Half-edge `h`'s links, mutably (recorded first).
    #[inline(always)]
    pub(crate) fn he_mut(&mut self, h: Hid) -> &mut HalfedgeRecord {
        self.log_he(h);
        self.he.unlogged_mut(h)
    }

    /// Set `next(h)`.
    pub(crate) fn set_next(&mut self, h: Hid, n: Hid) {
        self.he_mut(h).next = n;
    }

    /// Point vertex `v` at half-edge `h`.
    pub(crate) fn set_vertex_halfedge(&mut self, v: Vid, h: Hid) {
        if let Some(r) = self.rec.as_deref_mut() {
            r.save_vh(v, self.v_halfedge[v]);
        }
        *self.v_halfedge.unlogged_mut(v) = h;
    }

    /// Vertex `v`'s half-edge, mutably (recorded first).
    #[inline(always)]
    pub(crate) fn v_halfedge_mut(&mut self, v: Vid) -> &mut Hid {
        if let Some(r) = self.rec.as_deref_mut() {
            r.save_vh(v, self.v_halfedge[v]);
        }
        self.v_halfedge.unlogged_mut(v)
    }

    /// Face `f`'s link, mutably (recorded first).
    #[inline(always)]
    pub(crate) fn f_halfedge_mut(&mut self, f: Fid) -> &mut FaceLink {
        if let Some(r) = self.rec.as_deref_mut() {
            r.save_fl(f, self.f_halfedge[f]);
        }
        self.f_halfedge.unlogged_mut(f)
    }

    /// Set face `f`'s link (half-edge and hole flag).
    #[inline(always)]
    pub(crate) fn set_face_link_raw(&mut self, f: Fid, link: FaceLink) {
        if let Some(r) = self.rec.as_deref_mut() {
            r.save_fl(f, self.f_halfedge[f]);
        }
        *self.f_halfedge.unlogged_mut(f) = link;
    }

    /// Point face `f` at half-edge `h`, keeping its hole flag.
    #[inline(always)]
    pub(crate) fn set_face_link(&mut self, f: Fid, h: Hid) {
        let link = self.f_halfedge[f].with_halfedge(h);
        self.set_face_link_raw(f, link);
    }

    /// The end of one public edit (an operator, a setter): validate in
    /// debug builds, then close the journal's open step, if a journal
    /// records.
    #[inline]
    pub(crate) fn end_op(&mut self) {
        self.debug_validate();
        self.end_edit();
    }

    /// Close the journal's open step, if a journal records (no validation:
    /// attribute setters).
    #[inline]
    pub(crate) fn end_edit(&mut self) {
        if self.rec.is_some() {
            self.seal();
        }
    }
}
