//! The one writer the operators use: every link write, slot birth and slot
//! death goes through a [`Writer`], and the writer decides whether it is
//! recorded.
//!
//! The mesh keeps its links in [`LinkVec`](crate::layout::LinkVec)s, which
//! have no `IndexMut`: a write is one of the writer's calls. A writer is
//! made by [`Mesh::writer`] in a [`Journaling`] mode chosen **once per
//! operator call**: a public operator looks at [`Mesh::rec`] once (the
//! `journaled!` macro of [`record`](crate::record)) and runs its body in
//! `Unrecorded` or [`Recorded`](crate::record::Recorded) mode; the body
//! takes one writer and every call after that is plain (`w.set_next(h,
//! n)`), so the mode is named in one place, not at every write.
//!
//! - With `Unrecorded` (no journal) every hook below compiles away: a
//!   write is the plain store and nothing else, as if the journal did not
//!   exist.
//! - With `Recorded` the hooks record the old value of every slot that
//!   existed when the open step began, once per slot per step, through
//!   the [`Recorder`]'s save primitives. Code outside the operators (raw
//!   edits, setters) uses `Recorded`, whose hooks check the recorder
//!   themselves.
//!
//! Slot births and deaths ([`Writer::alloc_vertex`] and its siblings) are
//! recorded here too; attribute writes are recorded in
//! [`Columns`](crate::store::Columns) (`save`, one compare with a bound
//! that is 0 with no journal). A writer dereferences to its [`Mesh`], so
//! an operator reads through it and runs attribute rules on it as on the
//! mesh; a link write that bypassed it would need `unlogged_mut`, which
//! only this module and the recorder's own bookkeeping call.

use std::marker::PhantomData;
use std::ops::{Deref, DerefMut};

use crate::layout::{Eid, FaceLink, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::Mesh;
use crate::record::{Arena, Journaling, Recorder};

/// A mesh borrowed for writing in journaling mode `J` (see the module
/// docs): the link mutators, slot births and deaths.
pub(crate) struct Writer<'m, J: Journaling> {
    mesh: &'m mut Mesh,
    mode: PhantomData<J>,
}

impl Mesh {
    /// The writer an operator body uses, recording as `J` says.
    #[inline(always)]
    pub(crate) fn writer<J: Journaling>(&mut self) -> Writer<'_, J> {
        Writer {
            mesh: self,
            mode: PhantomData,
        }
    }
}

impl<J: Journaling> Deref for Writer<'_, J> {
    type Target = Mesh;

    #[inline(always)]
    fn deref(&self) -> &Mesh {
        self.mesh
    }
}

impl<J: Journaling> DerefMut for Writer<'_, J> {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut Mesh {
        self.mesh
    }
}

impl<J: Journaling> Writer<'_, J> {
    /// The same writer for a shorter borrow, to hand by value to a helper
    /// that is not inlined (by value, it reads the mesh through one
    /// pointer, not two).
    #[inline(always)]
    pub(crate) fn reborrow(&mut self) -> Writer<'_, J> {
        Writer {
            mesh: self.mesh,
            mode: PhantomData,
        }
    }

    /// The recorder, if `J` records and one exists (with `Unrecorded`, a
    /// constant `None`: the caller's recording code is dead).
    #[inline(always)]
    fn recorder(&mut self) -> Option<&mut Recorder> {
        if J::ON {
            self.mesh.rec.as_deref_mut()
        } else {
            None
        }
    }

    /// Record half-edge `h`'s links before a write.
    #[inline(always)]
    fn log_he(&mut self, h: Hid) {
        // Read as before the page log existed (callgrind, `poke_face` with
        // no journal on the 40k grid: 2.8 % more instructions than before
        // the page log without these reads, 1.8 % with them).
        let m = &mut *self.mesh;
        let _current = m.he[h];
        if J::ON {
            if let Some(r) = m.rec.as_deref_mut() {
                r.save_he(h, m.he.as_slice());
            }
        }
    }

    /// Set all three links of half-edge `h`.
    #[inline(always)]
    pub(crate) fn set_he(&mut self, h: Hid, record: HalfedgeRecord) {
        self.log_he(h);
        *self.mesh.he.unlogged_mut(h) = record;
    }

    /// Half-edge `h`'s links, mutably (recorded first).
    #[inline(always)]
    pub(crate) fn he_mut(&mut self, h: Hid) -> &mut HalfedgeRecord {
        self.log_he(h);
        self.mesh.he.unlogged_mut(h)
    }

    /// Half-edge `h`'s links, mutably, for a slot the running operator
    /// allocated: nothing to record in either mode. A slot born in the
    /// open step is never saved, and an older one taken from the free list
    /// had its page saved when `alloc_edge` cleared it (through
    /// [`set_he`](Writer::set_he)); the step cannot close in between.
    #[inline(always)]
    pub(crate) fn fresh_he_mut(&mut self, h: Hid) -> &mut HalfedgeRecord {
        // The same read as `log_he`'s (the code with no journal is alike).
        let _current = self.mesh.he[h];
        self.mesh.he.unlogged_mut(h)
    }

    /// [`v_halfedge_mut`](Writer::v_halfedge_mut) for a vertex the running
    /// operator allocated (see [`fresh_he_mut`](Writer::fresh_he_mut)).
    #[inline(always)]
    pub(crate) fn fresh_v_halfedge_mut(&mut self, v: Vid) -> &mut Hid {
        let _current = self.mesh.v_halfedge[v];
        self.mesh.v_halfedge.unlogged_mut(v)
    }

    /// Record face `f`'s link before writes to it, without writing (the
    /// writes then go through [`fresh_face_link`](Writer::fresh_face_link)).
    #[inline(always)]
    pub(crate) fn log_face(&mut self, f: Fid) {
        if J::ON {
            let m = &mut *self.mesh;
            if let Some(r) = m.rec.as_deref_mut() {
                r.save_fl(f, m.f_halfedge.as_slice());
            }
        }
    }

    /// Point face `f` at half-edge `h`, keeping its hole flag, with nothing
    /// to record: `f` was allocated by the running operator (see
    /// [`fresh_he_mut`](Writer::fresh_he_mut)) or logged by
    /// [`log_face`](Writer::log_face) in it.
    #[inline(always)]
    pub(crate) fn fresh_face_link(&mut self, f: Fid, h: Hid) {
        let link = self.mesh.f_halfedge[f].with_halfedge(h);
        *self.mesh.f_halfedge.unlogged_mut(f) = link;
    }

    /// Set `next(h)`.
    #[inline(always)]
    pub(crate) fn set_next(&mut self, h: Hid, n: Hid) {
        self.he_mut(h).next = n;
    }

    /// Point vertex `v` at half-edge `h`.
    #[inline(always)]
    pub(crate) fn set_vertex_halfedge(&mut self, v: Vid, h: Hid) {
        *self.v_halfedge_mut(v) = h;
    }

    /// Vertex `v`'s half-edge, mutably (recorded first).
    #[inline(always)]
    pub(crate) fn v_halfedge_mut(&mut self, v: Vid) -> &mut Hid {
        let m = &mut *self.mesh;
        let _current = m.v_halfedge[v];
        if J::ON {
            if let Some(r) = m.rec.as_deref_mut() {
                r.save_vh(v, m.v_halfedge.as_slice());
            }
        }
        m.v_halfedge.unlogged_mut(v)
    }

    /// Face `f`'s link, mutably (recorded first).
    #[inline(always)]
    pub(crate) fn f_halfedge_mut(&mut self, f: Fid) -> &mut FaceLink {
        let m = &mut *self.mesh;
        let _current = m.f_halfedge[f];
        if J::ON {
            if let Some(r) = m.rec.as_deref_mut() {
                r.save_fl(f, m.f_halfedge.as_slice());
            }
        }
        m.f_halfedge.unlogged_mut(f)
    }

    /// Set face `f`'s link (half-edge and hole flag).
    #[inline(always)]
    pub(crate) fn set_face_link_raw(&mut self, f: Fid, link: FaceLink) {
        *self.f_halfedge_mut(f) = link;
    }

    /// Point face `f` at half-edge `h`, keeping its hole flag.
    #[inline(always)]
    pub(crate) fn set_face_link(&mut self, f: Fid, h: Hid) {
        let link = self.mesh.f_halfedge[f].with_halfedge(h);
        self.set_face_link_raw(f, link);
    }

    /// Re-establish rule 11 at `v` after an edit that may have changed which
    /// of its half-edges lie in holes: keep its half-edge if that lies in a
    /// hole, else turn around `v` (clockwise, `h -> twin(h).next`, as
    /// [`Mesh::outgoing`] does) for one that does. O(1) when it already
    /// points into a hole, else O(degree of `v`).
    #[inline(always)]
    pub(crate) fn point_at_hole(&mut self, v: Vid) {
        self.mesh.point_at_hole::<J>(v)
    }
    // ----- allocation (internal; columns follow every slot) -------------------

    /// A new vertex slot with no links yet. Columns grow; values are set by
    /// the caller's rule.
    // Inlined: measured (instruction counts of poke_face) to matter.
    #[inline(always)]
    pub(crate) fn alloc_vertex(&mut self) -> Vid {
        let (i, g, is_new) = self.mesh.v_slots.alloc();
        let v = Vid::new(i);
        if is_new {
            self.mesh.v_halfedge.push(Hid::NONE);
        } else {
            self.set_vertex_halfedge(v, Hid::NONE);
            if let Some(r) = self.recorder() {
                r.reused(Arena::Vertex, i, g);
                self.mesh.attrs.vertex.reset(v.index());
            }
        }
        self.mesh
            .attrs
            .vertex
            .ensure_len(self.mesh.v_slots.slot_count());
        v
    }

    /// A new edge slot (two half-edges) with no links yet.
    #[inline(always)]
    pub(crate) fn alloc_edge(&mut self) -> Eid {
        self.mesh.alloc_edge::<J>()
    }

    /// A new face slot (a hole if `hole`) with no links yet.
    // Inlined: measured (instruction counts of poke_face) to matter.
    #[inline(always)]
    pub(crate) fn alloc_face(&mut self, hole: bool) -> Fid {
        let (i, g, is_new) = self.mesh.f_slots.alloc();
        let f = Fid::new(i);
        let link = FaceLink::unset(hole);
        if is_new {
            self.mesh.f_halfedge.push(link);
        } else {
            self.set_face_link_raw(f, link);
            if let Some(r) = self.recorder() {
                r.reused(Arena::Face, i, g);
                self.mesh.attrs.face.reset(f.index());
            }
        }
        if hole {
            self.mesh.holes += 1;
        }
        self.mesh
            .attrs
            .face
            .ensure_len(self.mesh.f_slots.slot_count());
        f
    }

    /// Remove a vertex slot and its attribute values. While a journal
    /// records, the slot keeps its links and values (undoing the removal
    /// then only revives the slot; a reuse clears them, recorded).
    #[inline(always)]
    pub(crate) fn free_vertex(&mut self, v: Vid) {
        self.mesh.free_vertex::<J>(v)
    }

    /// Remove an edge slot, both half-edges and their attribute values
    /// (kept while a journal records, as in [`free_vertex`](Writer::free_vertex)).
    #[inline(always)]
    pub(crate) fn free_edge(&mut self, e: Eid) {
        self.mesh.free_edge::<J>(e)
    }

    /// Remove a face slot and its attribute values (kept while a journal
    /// records, as in [`free_vertex`](Writer::free_vertex)).
    #[inline(always)]
    pub(crate) fn free_face(&mut self, f: Fid) {
        self.mesh.free_face::<J>(f)
    }

    /// Set or clear a face's hole flag.
    #[inline(always)]
    pub(crate) fn set_hole(&mut self, f: Fid, hole: bool) {
        self.mesh.set_hole::<J>(f, hole)
    }
}

/// The recorder in `rec`, if `J` records and one exists (a constant `None`
/// with `Unrecorded`).
#[inline(always)]
fn recorder<J: Journaling>(rec: &mut Option<Box<Recorder>>) -> Option<&mut Recorder> {
    if J::ON {
        rec.as_deref_mut()
    } else {
        None
    }
}

// The bodies of the writer's calls that are not inlined, on the mesh
// itself: passed the mesh, not the writer, they read its arrays through
// one pointer.
impl Mesh {
    /// [`Writer::point_at_hole`]'s body.
    fn point_at_hole<J: Journaling>(&mut self, v: Vid) {
        let m = &*self;
        if m.on_boundary(v) {
            return;
        }
        let start = m.v_halfedge[v];
        let mut h = start;
        // Bounded: a ring has fewer than 2E half-edges.
        for _ in 0..m.he.len() {
            if h.is_none() {
                return;
            }
            if m.in_hole(h) {
                self.writer::<J>().set_vertex_halfedge(v, h);
                return;
            }
            let n = m.he[h.twin()].next;
            h = if n == start { Hid::NONE } else { n };
        }
    }

    /// [`Writer::alloc_edge`]'s body.
    fn alloc_edge<J: Journaling>(&mut self) -> Eid {
        let (i, g, is_new) = self.e_slots.alloc();
        let e = Eid::new(i);
        if is_new {
            self.he.push(HalfedgeRecord::VACANT);
            self.he.push(HalfedgeRecord::VACANT);
        } else {
            for h in e.halfedges() {
                self.writer::<J>().set_he(h, HalfedgeRecord::VACANT);
            }
            if let Some(r) = recorder::<J>(&mut self.rec) {
                r.reused(Arena::Edge, i, g);
                self.attrs.edge.reset(e.index());
                for h in e.halfedges() {
                    self.attrs.halfedge.reset(h.index());
                }
            }
        }
        let slots = self.e_slots.slot_count();
        self.attrs.edge.ensure_len(slots);
        self.attrs.halfedge.ensure_len(Eid::halfedge_slots(slots));
        e
    }

    /// [`Writer::free_vertex`]'s body.
    fn free_vertex<J: Journaling>(&mut self, v: Vid) {
        let generation = self.v_slots.generation_of(v.raw());
        if let Some(r) = recorder::<J>(&mut self.rec) {
            r.died(Arena::Vertex, v.raw(), generation);
        } else {
            self.attrs.vertex.clear(v.index());
            *self.v_halfedge.unlogged_mut(v) = Hid::NONE;
        }
        self.v_slots.free(v.raw());
    }

    /// [`Writer::free_edge`]'s body.
    fn free_edge<J: Journaling>(&mut self, e: Eid) {
        let generation = self.e_slots.generation_of(e.raw());
        if let Some(r) = recorder::<J>(&mut self.rec) {
            r.died(Arena::Edge, e.raw(), generation);
        } else {
            self.attrs.edge.clear(e.index());
            for h in e.halfedges() {
                self.attrs.halfedge.clear(h.index());
                *self.he.unlogged_mut(h) = HalfedgeRecord::VACANT;
            }
        }
        self.e_slots.free(e.raw());
    }

    /// [`Writer::free_face`]'s body.
    fn free_face<J: Journaling>(&mut self, f: Fid) {
        if self.is_hole(f) {
            self.holes -= 1;
        }
        let generation = self.f_slots.generation_of(f.raw());
        if let Some(r) = recorder::<J>(&mut self.rec) {
            r.died(Arena::Face, f.raw(), generation);
        } else {
            self.attrs.face.clear(f.index());
            *self.f_halfedge.unlogged_mut(f) = FaceLink::unset(false);
        }
        self.f_slots.free(f.raw());
    }

    /// [`Writer::set_hole`]'s body.
    fn set_hole<J: Journaling>(&mut self, f: Fid, hole: bool) {
        let link = self.f_halfedge[f];
        if link.is_hole() != hole {
            self.writer::<J>()
                .set_face_link_raw(f, link.with_hole(hole));
            if hole {
                self.holes += 1;
            } else {
                self.holes -= 1;
            }
        }
    }
}
