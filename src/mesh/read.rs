//! The algorithms' read API: raw-index reads of the arenas for the code
//! outside the core (algorithms, exchange, traversal, statistics, repair,
//! shapes), so the storage fields of [`Mesh`] stay private to the core,
//! the operators and the journal (`tests/layers.rs` checks who touches
//! them).
//!
//! Everything here is an `#[inline(always)]` read of one field: a hot loop
//! over `halfedge_record(h)` compiles to the same loads as `mesh.he[h]`.
//! Navigation that already exists is not repeated here: `origin`, `dest`,
//! `next`, `prev`, `face_of`, `is_hole`, `face_halfedge`, `in_hole`,
//! `on_boundary` and the live-slot iterators `vids`/`eids`/`hids`/`fids`
//! are in `mesh.rs`; the circulators (`outgoing`, `face_halfedges`,
//! `face_halfedges_from`) in [`circulate`](crate::circulate). The raw indices
//! are the typed slots of [`layout`](crate::layout).
//!
//! Slot counts include vacant slots (arrays indexed by slot are that long);
//! the `*_live` tests say whether a slot is occupied.

use super::{HalfedgeRecord, Mesh};
use crate::layout::{FaceLink, Fid, Hid, Vid};
use crate::slots::Slots;
use crate::store::AttrStore;

impl Mesh {
    // ----- links -------------------------------------------------------------

    /// The links of half-edge `h` (origin, next, face), copied.
    #[inline(always)]
    pub(crate) fn halfedge_record(&self, h: Hid) -> HalfedgeRecord {
        self.he[h]
    }

    /// The links of half-edge `h`, or `None` past the last half-edge slot.
    #[inline(always)]
    pub(crate) fn try_halfedge_record(&self, h: Hid) -> Option<HalfedgeRecord> {
        self.he.get(h).copied()
    }

    /// The outgoing half-edge vertex slot `v` names.
    #[inline(always)]
    pub(crate) fn vertex_halfedge(&self, v: Vid) -> Hid {
        self.v_halfedge[v]
    }

    /// The outgoing half-edge of `v`, or `None` past the last vertex slot.
    #[inline(always)]
    pub(crate) fn try_vertex_halfedge(&self, v: Vid) -> Option<Hid> {
        self.v_halfedge.get(v).copied()
    }

    /// Face slot `f`'s link: one of its half-edges and the hole flag.
    #[inline(always)]
    pub(crate) fn face_link(&self, f: Fid) -> FaceLink {
        self.f_halfedge[f]
    }

    /// Face slot `f`'s link, or `None` past the last face slot.
    #[inline(always)]
    pub(crate) fn try_face_link(&self, f: Fid) -> Option<FaceLink> {
        self.f_halfedge.get(f).copied()
    }

    // ----- slot counts and liveness ------------------------------------------

    /// Vertex slots, vacant ones included.
    #[inline(always)]
    pub(crate) fn vertex_slots(&self) -> usize {
        self.v_slots.slot_count()
    }

    /// Half-edge slots, vacant ones included (twice the edge slots).
    #[inline(always)]
    pub(crate) fn halfedge_slots(&self) -> usize {
        self.he.len()
    }

    /// Edge slots, vacant ones included.
    #[inline(always)]
    pub(crate) fn edge_slots(&self) -> usize {
        self.e_slots.slot_count()
    }

    /// Face slots, holes and vacant ones included.
    #[inline(always)]
    pub(crate) fn face_slots(&self) -> usize {
        self.f_slots.slot_count()
    }

    /// Whether vertex slot `i` is occupied.
    #[inline(always)]
    pub(crate) fn vertex_live(&self, i: usize) -> bool {
        self.v_slots.is_live(i)
    }

    /// Whether edge slot `i` is occupied.
    #[inline(always)]
    pub(crate) fn edge_live(&self, i: usize) -> bool {
        self.e_slots.is_live(i)
    }

    /// Whether face slot `i` (a face or a hole) is occupied.
    #[inline(always)]
    pub(crate) fn face_live(&self, i: usize) -> bool {
        self.f_slots.is_live(i)
    }

    /// The vertex arena's slots and generations, for code that derives a
    /// new arena or ranks from it (subdivision levels).
    #[inline(always)]
    pub(crate) fn vertex_arena(&self) -> &Slots {
        &self.v_slots
    }

    /// The edge arena's slots and generations.
    #[inline(always)]
    pub(crate) fn edge_arena(&self) -> &Slots {
        &self.e_slots
    }

    /// The face arena's slots and generations.
    #[inline(always)]
    pub(crate) fn face_arena(&self) -> &Slots {
        &self.f_slots
    }

    // ----- attribute columns -------------------------------------------------

    /// The attribute columns, for reading.
    #[inline(always)]
    pub(crate) fn attrs(&self) -> &AttrStore {
        &self.attrs
    }

    /// The attribute columns, for writing. The columns' own writers (`copy`,
    /// `interpolate`, `merge`, ...) save the old value while a journal
    /// records; a raw slice (`raw_mut`) does not, so take one only of a mesh
    /// no journal records (one an algorithm is building, or one it replaces
    /// wholesale).
    #[inline(always)]
    pub(crate) fn attrs_mut(&mut self) -> &mut AttrStore {
        &mut self.attrs
    }

    /// The vertex arena with the attribute columns for writing (see
    /// [`attrs_mut`](Self::attrs_mut)), borrowed together: a pass that
    /// moves the live vertices' positions.
    #[inline(always)]
    pub(crate) fn vertex_arena_and_attrs_mut(&mut self) -> (&Slots, &mut AttrStore) {
        (&self.v_slots, &mut self.attrs)
    }
}
