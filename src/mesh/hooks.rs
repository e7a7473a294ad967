//! The mutators every link write goes through, and how an operator
//! chooses whether they record.
//!
//! The mesh keeps its links in [`LinkVec`](crate::layout::LinkVec)s, which
//! have no `IndexMut`: a write is one of the calls below. Each is generic
//! over a [`Journaling`] mode, chosen **once per operator call**: a public
//! operator looks at [`Mesh::rec`] once and runs its body either as
//! `body::<Unrecorded>` (no journal: every hook below compiles away, the
//! write is the plain store and nothing else, as if the journal did not
//! exist) or as `body::<Recorded>` (the hooks record the old value of
//! every slot that existed when the open step began, once per slot per
//! step, through the [`Recorder`]'s save primitives). Code outside the
//! operators (raw edits, setters) uses `Recorded`, whose hooks check the
//! recorder themselves.
//!
//! Slot births and deaths are recorded in [`Mesh::alloc_vertex`] and its
//! siblings (generic the same way), attribute writes in
//! [`Columns`](crate::store::Columns) (`save`, one compare with a bound
//! that is 0 with no journal).
//!
//! [`Unrecorded`]: crate::record::Unrecorded

use crate::layout::{FaceLink, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::Mesh;
use crate::record::{Journaling, Recorder};

impl Mesh {
    /// The recorder, if `J` records and one exists (with `Unrecorded`, a
    /// constant `None`: the caller's recording code is dead).
    #[inline(always)]
    pub(crate) fn recorder<J: Journaling>(&mut self) -> Option<&mut Recorder> {
        if J::ON {
            self.rec.as_deref_mut()
        } else {
            None
        }
    }

    /// Record half-edge `h`'s links before a write.
    #[inline(always)]
    fn log_he<J: Journaling>(&mut self, h: Hid) {
        // Read as before the page log existed (callgrind, `poke_face` with
        // no journal on the 40k grid: 2.8 % more instructions than before
        // the page log without these reads, 1.8 % with them).
        let _current = self.he[h];
        if J::ON {
            if let Some(r) = self.rec.as_deref_mut() {
                r.save_he(h, self.he.as_slice());
            }
        }
    }

    /// Set all three links of half-edge `h`.
    #[inline(always)]
    pub(crate) fn set_he<J: Journaling>(&mut self, h: Hid, record: HalfedgeRecord) {
        self.log_he::<J>(h);
        *self.he.unlogged_mut(h) = record;
    }

    /// Half-edge `h`'s links, mutably (recorded first).
    #[inline(always)]
    pub(crate) fn he_mut<J: Journaling>(&mut self, h: Hid) -> &mut HalfedgeRecord {
        self.log_he::<J>(h);
        self.he.unlogged_mut(h)
    }

    /// Half-edge `h`'s links, mutably, for a slot the running operator
    /// allocated: nothing to record in either mode. A slot born in the
    /// open step is never saved, and an older one taken from the free list
    /// had its page saved when `alloc_edge` cleared it (through
    /// [`set_he`](Mesh::set_he)); the step cannot close in between.
    #[inline(always)]
    pub(crate) fn fresh_he_mut(&mut self, h: Hid) -> &mut HalfedgeRecord {
        // The same read as `log_he`'s (the code with no journal is alike).
        let _current = self.he[h];
        self.he.unlogged_mut(h)
    }

    /// [`v_halfedge_mut`](Mesh::v_halfedge_mut) for a vertex the running
    /// operator allocated (see [`fresh_he_mut`](Mesh::fresh_he_mut)).
    #[inline(always)]
    pub(crate) fn fresh_v_halfedge_mut(&mut self, v: Vid) -> &mut Hid {
        let _current = self.v_halfedge[v];
        self.v_halfedge.unlogged_mut(v)
    }

    /// Record face `f`'s link before writes to it, without writing (the
    /// writes then go through [`fresh_face_link`](Mesh::fresh_face_link)).
    #[inline(always)]
    pub(crate) fn log_face<J: Journaling>(&mut self, f: Fid) {
        if J::ON {
            if let Some(r) = self.rec.as_deref_mut() {
                r.save_fl(f, self.f_halfedge.as_slice());
            }
        }
    }

    /// Point face `f` at half-edge `h`, keeping its hole flag, with nothing
    /// to record: `f` was allocated by the running operator (see
    /// [`fresh_he_mut`](Mesh::fresh_he_mut)) or logged by
    /// [`log_face`](Mesh::log_face) in it.
    #[inline(always)]
    pub(crate) fn fresh_face_link(&mut self, f: Fid, h: Hid) {
        let link = self.f_halfedge[f].with_halfedge(h);
        *self.f_halfedge.unlogged_mut(f) = link;
    }

    /// Set `next(h)`.
    #[inline(always)]
    pub(crate) fn set_next<J: Journaling>(&mut self, h: Hid, n: Hid) {
        self.he_mut::<J>(h).next = n;
    }

    /// Point vertex `v` at half-edge `h`.
    #[inline(always)]
    pub(crate) fn set_vertex_halfedge<J: Journaling>(&mut self, v: Vid, h: Hid) {
        *self.v_halfedge_mut::<J>(v) = h;
    }

    /// Vertex `v`'s half-edge, mutably (recorded first).
    #[inline(always)]
    pub(crate) fn v_halfedge_mut<J: Journaling>(&mut self, v: Vid) -> &mut Hid {
        let _current = self.v_halfedge[v];
        if J::ON {
            if let Some(r) = self.rec.as_deref_mut() {
                r.save_vh(v, self.v_halfedge.as_slice());
            }
        }
        self.v_halfedge.unlogged_mut(v)
    }

    /// Face `f`'s link, mutably (recorded first).
    #[inline(always)]
    pub(crate) fn f_halfedge_mut<J: Journaling>(&mut self, f: Fid) -> &mut FaceLink {
        let _current = self.f_halfedge[f];
        if J::ON {
            if let Some(r) = self.rec.as_deref_mut() {
                r.save_fl(f, self.f_halfedge.as_slice());
            }
        }
        self.f_halfedge.unlogged_mut(f)
    }

    /// Set face `f`'s link (half-edge and hole flag).
    #[inline(always)]
    pub(crate) fn set_face_link_raw<J: Journaling>(&mut self, f: Fid, link: FaceLink) {
        *self.f_halfedge_mut::<J>(f) = link;
    }

    /// Point face `f` at half-edge `h`, keeping its hole flag.
    #[inline(always)]
    pub(crate) fn set_face_link<J: Journaling>(&mut self, f: Fid, h: Hid) {
        let link = self.f_halfedge[f].with_halfedge(h);
        self.set_face_link_raw::<J>(f, link);
    }

    /// The end of one public edit (an operator, a setter): validate in
    /// debug builds, then close the journal's open step, if a journal
    /// records and no step group or transaction is open.
    #[inline(always)]
    pub(crate) fn end_op<J: Journaling>(&mut self) {
        self.bump_revision();
        self.debug_validate();
        if J::ON {
            self.end_edit();
        }
    }

    /// Close the journal's open step, if a journal records (no validation:
    /// attribute setters). Inside a step group or a transaction the step
    /// stays open: the group is one undo unit anyway, and one step for the
    /// whole group saves each slot once (its oldest value) and seals once,
    /// where a step per edit would save and encode every edit's writes.
    /// Whatever needs the step closed (undo, a bulk view, a column change,
    /// `take_changes`, the group's end) seals it first.
    #[inline]
    pub(crate) fn end_edit(&mut self) {
        self.bump_revision();
        if let Some(r) = self.rec.as_deref() {
            if r.group_depth == 0 {
                self.seal();
            }
        }
    }
}
