//! The core's bulk-build primitive: the whole connectivity of a new mesh,
//! written by an algorithm that produces a new level in one pass (
//! subdivision's edge and face passes, √3's spokes) into plain arrays in
//! slot order, and turned into a [`Mesh`] here, so the storage fields are
//! assigned in the core only.
//!
//! The builder is trusted: the arrays must describe a valid half-edge
//! graph (the algorithms' tests validate their results).

use super::Mesh;
use crate::layout::{FaceLink, Fid, HalfedgeRecord, Hid, IdVec, Vid};
use crate::slots::Slots;
use crate::store::AttrStore;

/// The connectivity of a new mesh, without attribute columns.
pub(crate) struct Topology {
    /// Per vertex slot: an outgoing half-edge (rule 11: one in a hole for a
    /// boundary vertex).
    pub(crate) vertex_links: IdVec<Vid, Hid>,
    /// The vertex arena (one slot per entry of `vertex_links`).
    pub(crate) vertex_arena: Slots,
    /// Per half-edge slot: its links (edge `e` owns `2e` and `2e + 1`).
    pub(crate) records: IdVec<Hid, HalfedgeRecord>,
    /// The edge arena (one slot per two records).
    pub(crate) edge_arena: Slots,
    /// Per face slot: a half-edge and the hole flag.
    pub(crate) face_links: IdVec<Fid, FaceLink>,
    /// The face arena (one slot per entry of `face_links`).
    pub(crate) face_arena: Slots,
    /// How many of the face links are holes.
    pub(crate) hole_count: usize,
}

impl Topology {
    /// A mesh of this connectivity with the given attribute columns, and no
    /// journal.
    pub(crate) fn into_mesh(self, attrs: AttrStore) -> Mesh {
        debug_assert_eq!(self.vertex_links.len(), self.vertex_arena.slot_count());
        debug_assert_eq!(self.records.len(), 2 * self.edge_arena.slot_count());
        debug_assert_eq!(self.face_links.len(), self.face_arena.slot_count());
        Mesh {
            v_halfedge: self.vertex_links.into(),
            v_slots: self.vertex_arena,
            he: self.records.into(),
            e_slots: self.edge_arena,
            f_halfedge: self.face_links.into(),
            f_slots: self.face_arena,
            holes: self.hole_count,
            attrs,
            rec: None,
            stamp: crate::mesh::Stamp::fresh(),
        }
    }
}
