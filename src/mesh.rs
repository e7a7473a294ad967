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
use crate::keys::{AnyKey, EdgeKey, FaceKey, HalfedgeKey, VertexKey};
pub(crate) use crate::layout::HalfedgeRecord;
use crate::layout::{Eid, FaceLink, Fid, Hid, LinkVec, Vid};
use crate::record::{PerArena, Recorded, Recorder};
use crate::slots::Slots;
use crate::store::rules::Interpolate;
use crate::store::{AttrStore, Column, POSITION};

mod read;
mod topology;
pub(crate) use topology::Topology;
mod recording;
mod writer;

pub(crate) use writer::Writer;

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
    /// Which mesh value this is and how many edits it has had (see
    /// [`Stamp`]).
    pub(crate) stamp: Stamp,
}

/// A mesh value's identity and edit count: what a derived structure (a
/// [`FaceTree`](crate::query::FaceTree)) records to refuse a mesh that
/// changed since, or another mesh.
///
/// `mesh` is drawn from a process-wide counter when a mesh value is made
/// (built, read, cloned, compacted), so two mesh values never share it;
/// `edits` counts the edits of that value. The mesh bumps it at the narrow
/// doors every change passes: the end of every operator and setter
/// (`end_op`, `end_edit`), mutable position and attribute views, the
/// journal's undo, redo and rollback (`open_step`) and wholesale rebuilds
/// (`wholesale`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Stamp {
    /// Unique per mesh value.
    pub(crate) mesh: u64,
    /// Edits since the value was made.
    pub(crate) edits: u64,
}

impl Default for Stamp {
    /// A fresh stamp: a default mesh is a new mesh value.
    fn default() -> Stamp {
        Stamp::fresh()
    }
}

impl Stamp {
    /// A new mesh value's stamp.
    pub(crate) fn fresh() -> Stamp {
        use std::sync::atomic::{AtomicU64, Ordering};
        static NEXT: AtomicU64 = AtomicU64::new(1);
        Stamp {
            mesh: NEXT.fetch_add(1, Ordering::Relaxed),
            edits: 0,
        }
    }
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
            // Another mesh value: trees built for the original refuse it.
            stamp: Stamp::fresh(),
        };
        if let Some(r) = &self.rec {
            r.release_held_into(PerArena([&mut m.v_slots, &mut m.e_slots, &mut m.f_slots]));
        }
        m
    }
}

impl Mesh {
    /// An empty mesh with a position column.
    ///
    /// ```
    /// let mesh = meshloom::Mesh::new();
    /// assert!(mesh.is_empty() && mesh.has_positions());
    /// assert_eq!((mesh.vertex_count(), mesh.face_count()), (0, 0));
    /// ```
    pub fn new() -> Mesh {
        let mut m = Mesh::default();
        m.attrs.position = Some(m.attrs.vertex.push(
            POSITION,
            Box::new(Column::<[f64; 3], Interpolate>::dense(Vec::new())),
        ));
        m
    }

    /// The edit count of this mesh value: 0 when made (built, cloned,
    /// read), then changed by every edit — an operator, a setter, a mutable
    /// position or attribute view, an undo, a redo, a rolled-back
    /// transaction, a wholesale rebuild. Equal revisions of one mesh mean
    /// nothing changed in between (a view taken but not written counts as
    /// an edit: the count errs towards "changed").
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let before = mesh.revision();
    /// let v = mesh.vertices().next().unwrap();
    /// mesh.set_position(v, [0.0, 0.0, 2.0])?;
    /// assert_ne!(mesh.revision(), before);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn revision(&self) -> u64 {
        self.stamp.edits
    }

    /// Which mesh value this is and its edit count (see [`Stamp`]).
    #[inline]
    pub(crate) fn stamp(&self) -> Stamp {
        self.stamp
    }

    /// Note an edit (see [`Stamp`]).
    #[inline(always)]
    pub(crate) fn bump_revision(&mut self) {
        let s = &mut self.stamp;
        s.edits = s.edits.wrapping_add(1);
    }

    // ----- counts ---------------------------------------------------------

    /// Number of vertices.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mesh = grid(3, 2, GridFaces::Quads); // 3 × 2 cells
    /// assert_eq!(mesh.vertex_count(), 4 * 3);
    /// ```
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.v_slots.live()
    }

    /// Number of half-edges (twice the edges).
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// assert_eq!(mesh.halfedge_count(), 2 * mesh.edge_count());
    /// ```
    #[inline]
    pub fn halfedge_count(&self) -> usize {
        Eid::halfedge_slots(self.e_slots.live())
    }

    /// Number of edges.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mesh = grid(3, 2, GridFaces::Quads);
    /// assert_eq!(mesh.edge_count(), 3 * 3 + 2 * 4); // horizontal + vertical
    /// ```
    #[inline]
    pub fn edge_count(&self) -> usize {
        self.e_slots.live()
    }

    /// Number of faces, holes excluded.
    ///
    /// ```
    /// let mesh = meshloom::shapes::disk(6);
    /// assert_eq!((mesh.face_count(), mesh.hole_count()), (6, 1)); // the hole is not counted
    /// ```
    #[inline]
    pub fn face_count(&self) -> usize {
        self.f_slots.live() - self.holes
    }

    /// Number of hole faces: one per boundary loop.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mut mesh = grid(3, 3, GridFaces::Quads);
    /// assert_eq!(mesh.hole_count(), 1); // outside the border
    /// let centre = mesh.faces().nth(4).unwrap();
    /// mesh.remove_face(centre)?;
    /// assert_eq!(mesh.hole_count(), 2); // and where the centre cell was
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn hole_count(&self) -> usize {
        self.holes
    }

    /// Whether the mesh has no elements.
    ///
    /// ```
    /// assert!(meshloom::Mesh::new().is_empty());
    /// assert!(!meshloom::shapes::tetrahedron().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.e_slots.live() == 0
    }

    /// V − E + F over faces that are not holes. For a mesh without boundary
    /// this is 2 − 2·genus per component.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// assert_eq!(meshloom::shapes::icosphere(2).euler_characteristic(), 2); // a sphere
    /// assert_eq!(grid(4, 4, GridFaces::Triangles).euler_characteristic(), 1); // a disk
    /// ```
    pub fn euler_characteristic(&self) -> i64 {
        self.vertex_count() as i64 - self.edge_count() as i64 + self.face_count() as i64
    }

    /// Whether the mesh has no boundary (no holes).
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// assert!(mesh.is_closed());
    /// let f = mesh.faces().next().unwrap();
    /// mesh.remove_face(f)?;
    /// assert!(!mesh.is_closed());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn is_closed(&self) -> bool {
        self.holes == 0
    }

    /// Heap bytes held by the connectivity, generations, free lists and
    /// every attribute column (capacities, not lengths).
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::icosphere(3);
    /// let before = mesh.heap_bytes();
    /// let t = mesh.add_vertex_attr::<f64>("temperature")?;
    /// mesh.fill_attr(&t, 20.0)?;
    /// assert!(mesh.heap_bytes() >= before + 8 * mesh.vertex_count());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn heap_bytes(&self) -> usize {
        self.v_halfedge.capacity() * std::mem::size_of::<Hid>()
            + self.v_slots.heap_bytes()
            + self.he.capacity() * std::mem::size_of::<HalfedgeRecord>()
            + self.e_slots.heap_bytes()
            + self.f_halfedge.capacity() * std::mem::size_of::<FaceLink>()
            + self.f_slots.heap_bytes()
            + self.attrs.heap_bytes()
    }

    // ----- keys by slot (for walking while editing) --------------------------

    /// The vertex living in slot `i`, if any (`i` from 0 to
    /// [`slot_counts`](Mesh::slot_counts)`()[0]`).
    ///
    /// The element iterators borrow the mesh; walking slots instead lets a
    /// loop edit the mesh as it goes without first collecting every key
    /// (a vector of 8 bytes a key). A new element takes a vacant slot or
    /// the next one after the last.
    ///
    /// ```
    /// // Move every vertex while walking the slots.
    /// let mut mesh = meshloom::shapes::cube();
    /// for i in 0..mesh.slot_counts()[0] {
    ///     if let Some(v) = mesh.vertex_at(i) {
    ///         let p = mesh.position(v)?;
    ///         mesh.set_position(v, [2.0 * p[0], p[1], p[2]])?;
    ///     }
    /// }
    /// assert_eq!(mesh.vertex_at(mesh.slot_counts()[0]), None); // past the end
    /// # Ok::<(), meshloom::Error>(())
    /// ```
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
    ///
    /// ```
    /// // Poke every face once: the new faces take slots after the last one.
    /// let mut mesh = meshloom::shapes::cube();
    /// for i in 0..mesh.slot_counts()[3] {
    ///     if let Some(f) = mesh.face_at(i) {
    ///         mesh.poke_face(f)?;
    ///     }
    /// }
    /// assert_eq!(mesh.face_count(), 6 * 4);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn face_at(&self, i: usize) -> Option<FaceKey> {
        let (i, g) = self.f_slots.live_at(i)?;
        let f = Fid::new(i);
        (!self.is_hole(f)).then(|| f.key(g))
    }

    // ----- key checks at the door -------------------------------------------

    /// Whether the key names a live vertex of this mesh.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let gone = mesh.halfedge(h)?.origin().key();
    /// mesh.collapse_edge(h)?;
    /// assert!(!mesh.contains_vertex(gone));
    /// assert_eq!(mesh.vertices().filter(|&v| mesh.contains_vertex(v)).count(), 11);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn contains_vertex(&self, v: VertexKey) -> bool {
        self.v_slots.is_current(v.index, v.generation)
    }

    /// Whether the key names a live half-edge of this mesh.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// mesh.collapse_edge(h)?;
    /// assert!(!mesh.contains_halfedge(h) && !mesh.contains_halfedge(h.twin_key()));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn contains_halfedge(&self, h: HalfedgeKey) -> bool {
        self.e_slots.is_current(h.id().edge().raw(), h.generation)
    }

    /// Whether the key names a live edge of this mesh.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let e = mesh.edges().next().unwrap();
    /// assert!(mesh.contains_edge(e));
    /// mesh.collapse_edge(e.halfedge_key(0))?;
    /// assert!(!mesh.contains_edge(e));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn contains_edge(&self, e: EdgeKey) -> bool {
        self.e_slots.is_current(e.index, e.generation)
    }

    /// Whether the key names a live face or hole of this mesh.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let f = mesh.halfedge(h)?.face().key();
    /// mesh.collapse_edge(h)?; // the triangle beside h goes
    /// assert!(!mesh.contains_face(f));
    /// let disk = meshloom::shapes::disk(6);
    /// assert!(disk.holes().all(|hole| disk.contains_face(hole))); // holes count
    /// # Ok::<(), meshloom::Error>(())
    /// ```
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
                self.writer::<Recorded>().set_vertex_halfedge(r.origin, h);
            }
        }
    }

    // ----- positions -----------------------------------------------------------

    /// Whether the mesh carries vertex positions.
    ///
    /// ```
    /// assert!(meshloom::shapes::cube().has_positions());
    /// let topology = meshloom::Mesh::from_faces(4, &[[0u32, 1, 2], [0, 2, 3]])?;
    /// assert!(!topology.has_positions());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn has_positions(&self) -> bool {
        self.attrs.positions().is_some()
    }

    /// A vertex's position.
    ///
    /// # Errors
    /// [`Error::StaleKey`] for a removed vertex; [`Error::NoPositions`] for
    /// a topology-only mesh.
    ///
    /// ```
    /// use meshloom::{Error, Mesh};
    /// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let mesh = Mesh::from_polygons(&p, &[[0u32, 1, 2]])?;
    /// let v: Vec<_> = mesh.vertices().collect();
    /// assert_eq!(mesh.position(v[1])?, [1.0, 0.0, 0.0]);
    /// let topology = Mesh::from_faces(3, &[[0u32, 1, 2]])?;
    /// let w = topology.vertices().next().unwrap();
    /// assert!(matches!(topology.position(w), Err(Error::NoPositions)));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
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
    ///
    /// ```
    /// use meshloom::Error;
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let v = mesh.vertices().next().unwrap();
    /// mesh.set_position(v, [0.0, 0.0, 2.0])?;
    /// assert_eq!(mesh.position(v)?, [0.0, 0.0, 2.0]);
    /// let refused = mesh.set_position(v, [f64::NAN, 0.0, 0.0]);
    /// assert!(matches!(refused, Err(Error::NonFinitePosition { .. })));
    /// assert_eq!(mesh.position(v)?, [0.0, 0.0, 2.0]); // unchanged
    /// # Ok::<(), meshloom::Error>(())
    /// ```
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
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// let slots = mesh.position_slots().expect("the cube has positions");
    /// assert_eq!(slots.len(), mesh.slot_counts()[0]);
    /// for v in mesh.vertices() {
    ///     assert_eq!(slots[v.index()], mesh.position(v)?);
    /// }
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn position_slots(&self) -> Option<&[[f64; 3]]> {
        self.attrs.positions().map(|c| c.raw())
    }

    /// The position column indexed by vertex slot, mutably. Callers must
    /// keep coordinates finite.
    ///
    /// While a [journal](crate::journal) records, this saves the whole
    /// column first (O(slots)), and the writes become one undo step of
    /// their own, holding only the positions that changed.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let v = mesh.vertices().last().unwrap();
    /// for p in mesh.position_slots_mut().unwrap() {
    ///     p[2] *= 3.0; // stretch along z, one pass
    /// }
    /// assert_eq!(mesh.position(v)?[2], 3.0);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn position_slots_mut(&mut self) -> Option<&mut [[f64; 3]]> {
        let n = self.v_slots.slot_count();
        self.bulk_positions_mut(0..n)
    }

    /// Slots allocated in each arena (live or vacant): the length of the
    /// attribute columns of vertices, half-edges, edges and faces.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// assert_eq!(mesh.slot_counts(), [12, 60, 30, 20]); // vertices, half-edges, edges, faces
    /// mesh.collapse_edge(mesh.halfedges().next().unwrap())?;
    /// assert_eq!(mesh.face_count(), 18);
    /// assert_eq!(mesh.slot_counts(), [12, 60, 30, 20]); // vacant slots stay
    /// mesh.compact();
    /// assert_eq!(mesh.slot_counts(), [11, 54, 27, 18]);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
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
            let stamp = m.stamp();
            *m = result;
            m.rec = rec;
            m.stamp = stamp;
        });
    }
}
