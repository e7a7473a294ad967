//! The [`Mesh`]: three arenas, their attribute columns, counts and element
//! iterators.
//!
//! # Storage
//!
//! | arena | per slot | notes |
//! |---|---|---|
//! | vertices | outgoing half-edge `u32`, generation `u32` | position in the `position` column (`[f64; 3]`) |
//! | edges | generation `u32`; two half-edge records of `origin`, `next`, `face` (`u32` each) | half-edges `2e` and `2e + 1` are twins |
//! | faces | one half-edge `u32` (top bit: hole flag), generation `u32` | holes are faces |
//!
//! There is no `prev` link: `prev(h)` is found by turning around `origin(h)`
//! (O(vertex degree), not O(face degree)), which keeps a triangle mesh with
//! f64 positions at about 132 heap bytes per vertex, generations included.
//! Internal links are typed slot indices ([`Vid`], [`Hid`], [`Eid`],
//! [`Fid`]; the layout they follow is in [`layout`](crate::layout));
//! generations are checked once, at the public door.

use crate::error::{Error, Result};
use crate::iter::{Edges, Faces, Halfedges, Vertices};
use crate::journal::{Journaling, Recorded, Recorder};
use crate::keys::{AnyKey, EdgeKey, FaceKey, HalfedgeKey, VertexKey};
pub(crate) use crate::layout::HalfedgeRecord;
use crate::layout::{Eid, FaceLink, Fid, Hid, LinkVec, Vid};
use crate::slots::Slots;
use crate::store::rules::Interpolate;
use crate::store::{AttrStore, Column, POSITION};

/// A polygon mesh stored as a half-edge graph.
///
/// Build one with [`Mesh::from_polygons`], [`Mesh::from_faces`], a shape
/// from [`shapes`](crate::shapes) or a reader from [`io`](crate::io);
/// navigate with the borrowed views [`Mesh::vertex`], [`Mesh::halfedge`],
/// [`Mesh::face`], [`Mesh::edge`].
///
/// ```
/// use meshloom::Mesh;
/// let square = Mesh::from_polygons(
///     &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     &[[0u32, 1, 2, 3]],
/// )?;
/// assert_eq!((square.vertex_count(), square.edge_count(), square.face_count()), (4, 4, 1));
/// assert_eq!(square.hole_count(), 1); // the outside of the boundary
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Debug, Default)]
pub struct Mesh {
    /// Per vertex slot: an outgoing half-edge.
    pub(crate) v_halfedge: LinkVec<Vid, Hid>,
    pub(crate) v_slots: Slots,
    /// Per half-edge slot: its links (edge `e` owns `2e` and `2e + 1`).
    pub(crate) he: LinkVec<Hid, HalfedgeRecord>,
    pub(crate) e_slots: Slots,
    /// Per face slot: a half-edge and the hole flag.
    pub(crate) f_halfedge: LinkVec<Fid, FaceLink>,
    pub(crate) f_slots: Slots,
    pub(crate) holes: usize,
    pub(crate) attrs: AttrStore,
    /// The journal's recorder while undo history, a transaction or change
    /// tracking is on ([`journal`](crate::journal)); `None` otherwise, and
    /// then every mutator's journal check is one test of this pointer.
    pub(crate) rec: Option<Box<Recorder>>,
}

impl Clone for Mesh {
    /// A copy of the mesh without its journal: no undo history, no open
    /// transaction, no change tracking. Slots an undo left vacant for a
    /// redo are free again in the copy.
    fn clone(&self) -> Mesh {
        let mut m = Mesh {
            v_halfedge: self.v_halfedge.clone(),
            v_slots: self.v_slots.clone(),
            he: self.he.clone(),
            e_slots: self.e_slots.clone(),
            f_halfedge: self.f_halfedge.clone(),
            f_slots: self.f_slots.clone(),
            holes: self.holes,
            attrs: self.attrs.clone(),
            rec: None,
        };
        if let Some(r) = &self.rec {
            r.release_held_into(&mut m);
        }
        m
    }
}

impl Mesh {
    /// An empty mesh with a position column.
    pub fn new() -> Mesh {
        let mut m = Mesh::default();
        m.attrs.position = Some(m.attrs.vertex.push(
            POSITION,
            Box::new(Column::<[f64; 3], Interpolate>::dense(Vec::new())),
        ));
        m
    }

    // ----- counts ---------------------------------------------------------

    /// Number of vertices.
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.v_slots.live()
    }

    /// Number of half-edges (twice the edges).
    #[inline]
    pub fn halfedge_count(&self) -> usize {
        Eid::halfedge_slots(self.e_slots.live())
    }

    /// Number of edges.
    #[inline]
    pub fn edge_count(&self) -> usize {
        self.e_slots.live()
    }

    /// Number of faces, holes excluded.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.f_slots.live() - self.holes
    }

    /// Number of hole faces: one per boundary loop.
    #[inline]
    pub fn hole_count(&self) -> usize {
        self.holes
    }

    /// Whether the mesh has no elements.
    pub fn is_empty(&self) -> bool {
        self.e_slots.live() == 0
    }

    /// V − E + F over faces that are not holes. For a mesh without boundary
    /// this is 2 − 2·genus per component.
    pub fn euler_characteristic(&self) -> i64 {
        self.vertex_count() as i64 - self.edge_count() as i64 + self.face_count() as i64
    }

    /// Whether the mesh has no boundary (no holes).
    pub fn is_closed(&self) -> bool {
        self.holes == 0
    }

    /// Heap bytes held by the connectivity, generations, free lists and
    /// every attribute column (capacities, not lengths).
    pub fn heap_bytes(&self) -> usize {
        self.v_halfedge.capacity() * std::mem::size_of::<Hid>()
            + self.v_slots.heap_bytes()
            + self.he.capacity() * std::mem::size_of::<HalfedgeRecord>()
            + self.e_slots.heap_bytes()
            + self.f_halfedge.capacity() * std::mem::size_of::<FaceLink>()
            + self.f_slots.heap_bytes()
            + self.attrs.heap_bytes()
    }

    // ----- element iterators (keys, in slot order) -------------------------

    /// Every vertex key, in slot order; `len()` is exact.
    #[inline]
    pub fn vertices(&self) -> Vertices<'_> {
        Vertices::new(self)
    }

    /// Every half-edge key, in slot order (twins adjacent); `len()` is
    /// exact.
    #[inline]
    pub fn halfedges(&self) -> Halfedges<'_> {
        Halfedges::new(self)
    }

    /// Every edge key, in slot order; `len()` is exact.
    #[inline]
    pub fn edges(&self) -> Edges<'_> {
        Edges::new(self)
    }

    /// Every face key, holes excluded, in slot order; `len()` is exact.
    ///
    /// ```
    /// let cube = meshloom::shapes::cube();
    /// let faces = cube.faces();
    /// assert_eq!(faces.len(), cube.face_count());
    /// ```
    #[inline]
    pub fn faces(&self) -> Faces<'_> {
        Faces::not_holes(self)
    }

    /// Every hole face key, in slot order; `len()` is exact.
    #[inline]
    pub fn holes(&self) -> Faces<'_> {
        Faces::holes(self)
    }

    /// Every face key, holes included, in slot order; `len()` is exact.
    #[inline]
    pub fn faces_and_holes(&self) -> Faces<'_> {
        Faces::both(self)
    }

    // ----- keys by slot (for walking while editing) --------------------------

    /// The vertex living in slot `i`, if any (`i` from 0 to
    /// [`slot_counts`](Mesh::slot_counts)`()[0]`).
    ///
    /// The element iterators borrow the mesh; walking slots instead lets a
    /// loop edit the mesh as it goes without first collecting every key
    /// (which costs 2 ms and 4 MB for the edges of a 164k-vertex sphere). A
    /// new element takes a vacant slot or the next one after the last.
    #[inline]
    pub fn vertex_at(&self, i: usize) -> Option<VertexKey> {
        let (i, g) = self.v_slots.live_at(i)?;
        Some(Vid::new(i).key(g))
    }

    /// The edge living in slot `i`, if any (`i` from 0 to
    /// [`slot_counts`](Mesh::slot_counts)`()[2]`); see
    /// [`vertex_at`](Mesh::vertex_at).
    ///
    /// ```
    /// // Flip every edge once, editing while walking the slots.
    /// let mut mesh = meshloom::shapes::icosphere(2);
    /// let mut flipped = 0;
    /// for i in 0..mesh.slot_counts()[2] {
    ///     if let Some(e) = mesh.edge_at(i) {
    ///         flipped += usize::from(mesh.flip_edge(e).is_ok());
    ///     }
    /// }
    /// assert!(flipped > 0);
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn edge_at(&self, i: usize) -> Option<EdgeKey> {
        let (i, g) = self.e_slots.live_at(i)?;
        Some(Eid::new(i).key(g))
    }

    /// The face (not a hole) living in slot `i`, if any (`i` from 0 to
    /// [`slot_counts`](Mesh::slot_counts)`()[3]`); see
    /// [`vertex_at`](Mesh::vertex_at).
    #[inline]
    pub fn face_at(&self, i: usize) -> Option<FaceKey> {
        let (i, g) = self.f_slots.live_at(i)?;
        let f = Fid::new(i);
        (!self.is_hole(f)).then(|| f.key(g))
    }

    // ----- key checks at the door -------------------------------------------

    /// Whether the key names a live vertex of this mesh.
    #[inline]
    pub fn contains_vertex(&self, v: VertexKey) -> bool {
        self.v_slots.is_current(v.index, v.generation)
    }

    /// Whether the key names a live half-edge of this mesh.
    #[inline]
    pub fn contains_halfedge(&self, h: HalfedgeKey) -> bool {
        self.e_slots.is_current(h.id().edge().raw(), h.generation)
    }

    /// Whether the key names a live edge of this mesh.
    #[inline]
    pub fn contains_edge(&self, e: EdgeKey) -> bool {
        self.e_slots.is_current(e.index, e.generation)
    }

    /// Whether the key names a live face or hole of this mesh.
    #[inline]
    pub fn contains_face(&self, f: FaceKey) -> bool {
        self.f_slots.is_current(f.index, f.generation)
    }

    #[inline]
    pub(crate) fn check_vertex(&self, v: VertexKey) -> Result<Vid> {
        if self.contains_vertex(v) {
            Ok(v.id())
        } else {
            Err(Error::StaleKey(AnyKey::Vertex(v)))
        }
    }

    #[inline]
    pub(crate) fn check_halfedge(&self, h: HalfedgeKey) -> Result<Hid> {
        if self.contains_halfedge(h) {
            Ok(h.id())
        } else {
            Err(Error::StaleKey(AnyKey::Halfedge(h)))
        }
    }

    #[inline]
    pub(crate) fn check_edge(&self, e: EdgeKey) -> Result<Eid> {
        if self.contains_edge(e) {
            Ok(e.id())
        } else {
            Err(Error::StaleKey(AnyKey::Edge(e)))
        }
    }

    #[inline]
    pub(crate) fn check_face(&self, f: FaceKey) -> Result<Fid> {
        if self.contains_face(f) {
            Ok(f.id())
        } else {
            Err(Error::StaleKey(AnyKey::Face(f)))
        }
    }

    // ----- typed slot -> key ---------------------------------------------------

    #[inline]
    pub(crate) fn vkey(&self, v: Vid) -> VertexKey {
        v.key(self.v_slots.generation_of(v.raw()))
    }

    #[inline]
    pub(crate) fn hkey(&self, h: Hid) -> HalfedgeKey {
        h.key(self.e_slots.generation_of(h.edge().raw()))
    }

    #[inline]
    pub(crate) fn ekey(&self, e: Eid) -> EdgeKey {
        e.key(self.e_slots.generation_of(e.raw()))
    }

    #[inline]
    pub(crate) fn fkey(&self, f: Fid) -> FaceKey {
        f.key(self.f_slots.generation_of(f.raw()))
    }

    // ----- live slots, typed, in slot order -----------------------------------

    /// The live vertex slots.
    #[inline]
    pub(crate) fn vids(&self) -> impl Iterator<Item = Vid> + '_ {
        self.v_slots.live_indices().map(Vid::new)
    }

    /// The live edge slots.
    #[inline]
    pub(crate) fn eids(&self) -> impl Iterator<Item = Eid> + '_ {
        self.e_slots.live_indices().map(Eid::new)
    }

    /// The live half-edge slots (twins adjacent).
    #[inline]
    pub(crate) fn hids(&self) -> impl Iterator<Item = Hid> + '_ {
        self.eids().flat_map(Eid::halfedges)
    }

    /// The live face slots, holes included.
    #[inline]
    pub(crate) fn fids(&self) -> impl Iterator<Item = Fid> + '_ {
        self.f_slots.live_indices().map(Fid::new)
    }

    // ----- navigation (no checks; internal links are trusted) -----------------

    /// The vertex `h` leaves.
    #[inline]
    pub(crate) fn origin(&self, h: Hid) -> Vid {
        self.he[h].origin
    }

    /// The vertex `h` enters.
    #[inline]
    pub(crate) fn dest(&self, h: Hid) -> Vid {
        self.he[h.twin()].origin
    }

    /// The half-edge after `h` in its face.
    #[inline]
    pub(crate) fn next(&self, h: Hid) -> Hid {
        self.he[h].next
    }

    /// The face (or hole) left of `h`.
    #[inline]
    pub(crate) fn face_of(&self, h: Hid) -> Fid {
        self.he[h].face
    }

    /// The half-edge before `h` in its face, found by turning around
    /// `origin(h)`: O(degree of that vertex). [`Hid::NONE`] if a corrupted
    /// ring never comes back.
    #[inline]
    pub(crate) fn prev(&self, h: Hid) -> Hid {
        let mut o = h;
        // Bounded: the ring around a vertex has at most 2E half-edges.
        let mut budget = self.he.len();
        loop {
            let t = o.twin();
            let n = self.he[t].next;
            if n == h {
                return t;
            }
            o = n;
            budget -= 1;
            if budget == 0 {
                return Hid::NONE;
            }
        }
    }

    /// Whether face slot `f` is a hole.
    #[inline]
    pub(crate) fn is_hole(&self, f: Fid) -> bool {
        self.f_halfedge[f].is_hole()
    }

    /// The half-edge face slot `f` names.
    #[inline]
    pub(crate) fn face_halfedge(&self, f: Fid) -> Hid {
        self.f_halfedge[f].halfedge()
    }

    /// Whether half-edge `h` lies in a hole.
    #[inline]
    pub(crate) fn in_hole(&self, h: Hid) -> bool {
        self.is_hole(self.he[h].face)
    }

    /// Whether a hole touches vertex `v`: O(1), by rule 11 (a vertex that
    /// touches a hole names an outgoing half-edge that lies in one).
    #[inline]
    pub(crate) fn on_boundary(&self, v: Vid) -> bool {
        self.in_hole(self.v_halfedge[v])
    }

    /// Re-establish rule 11 at `v` after an edit that may have changed which
    /// of its half-edges lie in holes: keep its half-edge if that lies in a
    /// hole, else turn around `v` for one that does. O(1) when it already
    /// points into a hole, else O(degree of `v`).
    pub(crate) fn point_at_hole<J: Journaling>(&mut self, v: Vid) {
        if self.on_boundary(v) {
            return;
        }
        if let Some(h) = self.outgoing(v).find(|&h| self.in_hole(h)) {
            self.set_vertex_halfedge::<J>(v, h);
        }
    }

    /// Re-establish rule 11 for every vertex: O(half-edges). Robust to any
    /// links (a mesh being deserialized or raw-edited, not yet validated):
    /// it reads only in-range slots, and moves a vertex's half-edge only
    /// from one that leaves the vertex but lies in no hole to one that
    /// leaves it and lies in a hole, so every other broken rule is left for
    /// [`validate`](Mesh::validate) to report.
    pub(crate) fn point_all_at_holes(&mut self) {
        for h in self.hids().collect::<Vec<_>>() {
            let r = self.he[h];
            let hole = self.f_halfedge.get(r.face).is_some_and(|l| l.is_hole())
                && self.f_slots.is_live(r.face.index());
            if !hole || !self.v_slots.is_live(r.origin.index()) {
                continue;
            }
            let Some(&cur) = self.v_halfedge.get(r.origin) else {
                continue;
            };
            let cur_ok = self.he.get(cur).is_some_and(|c| {
                c.origin == r.origin
                    && self.e_slots.is_live(cur.edge().index())
                    && !self.f_halfedge.get(c.face).is_some_and(|l| l.is_hole())
            });
            if cur_ok {
                self.set_vertex_halfedge::<Recorded>(r.origin, h);
            }
        }
    }

    // ----- allocation (internal; columns follow every slot) -------------------

    /// A new vertex slot with no links yet. Columns grow; values are set by
    /// the caller's rule.
    // Inlined: measured (instruction counts of poke_face) to matter.
    #[inline(always)]
    pub(crate) fn alloc_vertex<J: Journaling>(&mut self) -> Vid {
        let (i, g, is_new) = self.v_slots.alloc();
        let v = Vid::new(i);
        if is_new {
            self.v_halfedge.push(Hid::NONE);
        } else {
            self.set_vertex_halfedge::<J>(v, Hid::NONE);
            if let Some(r) = self.recorder::<J>() {
                r.reused(0, i, g);
                self.attrs.vertex.reset(v.index());
            }
        }
        self.attrs.vertex.ensure_len(self.v_slots.slot_count());
        v
    }

    /// A new edge slot (two half-edges) with no links yet.
    pub(crate) fn alloc_edge<J: Journaling>(&mut self) -> Eid {
        let (i, g, is_new) = self.e_slots.alloc();
        let e = Eid::new(i);
        if is_new {
            self.he.push(HalfedgeRecord::VACANT);
            self.he.push(HalfedgeRecord::VACANT);
        } else {
            for h in e.halfedges() {
                self.set_he::<J>(h, HalfedgeRecord::VACANT);
            }
            if let Some(r) = self.recorder::<J>() {
                r.reused(1, i, g);
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

    /// A new face slot (a hole if `hole`) with no links yet.
    // Inlined: measured (instruction counts of poke_face) to matter.
    #[inline(always)]
    pub(crate) fn alloc_face<J: Journaling>(&mut self, hole: bool) -> Fid {
        let (i, g, is_new) = self.f_slots.alloc();
        let f = Fid::new(i);
        let link = FaceLink::unset(hole);
        if is_new {
            self.f_halfedge.push(link);
        } else {
            self.set_face_link_raw::<J>(f, link);
            if let Some(r) = self.recorder::<J>() {
                r.reused(2, i, g);
                self.attrs.face.reset(f.index());
            }
        }
        if hole {
            self.holes += 1;
        }
        self.attrs.face.ensure_len(self.f_slots.slot_count());
        f
    }

    /// Remove a vertex slot and its attribute values. While a journal
    /// records, the slot keeps its links and values (undoing the removal
    /// then only revives the slot; a reuse clears them, recorded).
    pub(crate) fn free_vertex<J: Journaling>(&mut self, v: Vid) {
        let generation = self.v_slots.generation_of(v.raw());
        if let Some(r) = self.recorder::<J>() {
            r.died(0, v.raw(), generation);
        } else {
            self.attrs.vertex.clear(v.index());
            *self.v_halfedge.unlogged_mut(v) = Hid::NONE;
        }
        self.v_slots.free(v.raw());
    }

    /// Remove an edge slot, both half-edges and their attribute values
    /// (kept while a journal records, as in [`free_vertex`](Mesh::free_vertex)).
    pub(crate) fn free_edge<J: Journaling>(&mut self, e: Eid) {
        let generation = self.e_slots.generation_of(e.raw());
        if let Some(r) = self.recorder::<J>() {
            r.died(1, e.raw(), generation);
        } else {
            self.attrs.edge.clear(e.index());
            for h in e.halfedges() {
                self.attrs.halfedge.clear(h.index());
                *self.he.unlogged_mut(h) = HalfedgeRecord::VACANT;
            }
        }
        self.e_slots.free(e.raw());
    }

    /// Remove a face slot and its attribute values (kept while a journal
    /// records, as in [`free_vertex`](Mesh::free_vertex)).
    pub(crate) fn free_face<J: Journaling>(&mut self, f: Fid) {
        if self.is_hole(f) {
            self.holes -= 1;
        }
        let generation = self.f_slots.generation_of(f.raw());
        if let Some(r) = self.recorder::<J>() {
            r.died(2, f.raw(), generation);
        } else {
            self.attrs.face.clear(f.index());
            *self.f_halfedge.unlogged_mut(f) = FaceLink::unset(false);
        }
        self.f_slots.free(f.raw());
    }

    /// Set or clear a face's hole flag.
    pub(crate) fn set_hole<J: Journaling>(&mut self, f: Fid, hole: bool) {
        let link = self.f_halfedge[f];
        if link.is_hole() != hole {
            self.set_face_link_raw::<J>(f, link.with_hole(hole));
            if hole {
                self.holes += 1;
            } else {
                self.holes -= 1;
            }
        }
    }

    // ----- positions -----------------------------------------------------------

    /// Whether the mesh carries vertex positions.
    pub fn has_positions(&self) -> bool {
        self.attrs.positions().is_some()
    }

    /// A vertex's position.
    ///
    /// # Errors
    /// [`Error::StaleKey`] for a removed vertex; [`Error::NoPositions`] for
    /// a topology-only mesh.
    pub fn position(&self, v: VertexKey) -> Result<[f64; 3]> {
        let i = self.check_vertex(v)?;
        self.attrs
            .positions()
            .and_then(|c| c.get(i.index()).copied())
            .ok_or_else(|| Error::NoPositions)
    }

    /// Set a vertex's position. NaN and infinite coordinates are refused.
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::NoPositions`],
    /// [`Error::NonFinitePosition`].
    pub fn set_position(&mut self, v: VertexKey, p: [f64; 3]) -> Result<()> {
        let i = self.check_vertex(v)?;
        if !p.iter().all(|c| c.is_finite()) {
            return Err(Error::NonFinitePosition {
                key: v.into(),
                position: p,
            });
        }
        self.attrs
            .set_position_saved(i.index(), p)
            .ok_or_else(|| Error::NoPositions)?;
        self.end_edit();
        Ok(())
    }

    /// The position column indexed by vertex slot ([`VertexKey::index`]);
    /// vacant slots hold zeros (while a [journal](crate::journal) records,
    /// the last position of the vertex that lived there). For fast
    /// whole-mesh geometry passes.
    pub fn position_slots(&self) -> Option<&[[f64; 3]]> {
        self.attrs.positions().map(|c| c.raw())
    }

    /// The position column indexed by vertex slot, mutably. Callers must
    /// keep coordinates finite.
    ///
    /// While a [journal](crate::journal) records, this saves the whole
    /// column first (O(slots)), and the writes become one undo step of
    /// their own, holding only the positions that changed.
    pub fn position_slots_mut(&mut self) -> Option<&mut [[f64; 3]]> {
        let n = self.v_slots.slot_count();
        self.bulk_positions_mut(0..n)
    }

    /// Slots allocated in each arena (live or vacant): the length of the
    /// attribute columns of vertices, half-edges, edges and faces.
    pub fn slot_counts(&self) -> [usize; 4] {
        [
            self.v_slots.slot_count(),
            self.he.len(),
            self.e_slots.slot_count(),
            self.f_slots.slot_count(),
        ]
    }

    /// Replace the whole mesh by `result`, an algorithm's output built
    /// wholesale (subdivision, remeshing, ...) instead of through the
    /// operators.
    ///
    /// This is the one door for such rebuilds, so that whatever watches
    /// edits (the journal for undo and change tracking) sees them as one
    /// step: while a [journal](crate::journal) records, the whole prior
    /// mesh is kept as that step (memory: one copy of the mesh), undo
    /// brings it back, and every key the result issued stays stale after
    /// that undo. `result` must carry the caller's attribute columns with
    /// the same ids (build it from a clone of `self`, or move the column
    /// sets over), so handles taken before the rebuild keep working.
    #[allow(dead_code)]
    pub(crate) fn replace_with(&mut self, result: Mesh) {
        let mut result = result;
        result.rec = None;
        self.wholesale(move |m| {
            let rec = m.rec.take();
            *m = result;
            m.rec = rec;
        });
    }
}
