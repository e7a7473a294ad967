//! The storage layout of the arenas, owned in one place: typed slot
//! indices, the twin arithmetic, the "no element" value and the hole bit.
//!
//! Inside the crate every link is one of four index types, each a
//! `#[repr(transparent)]` `u32`:
//!
//! | type | a slot of | indexes |
//! |---|---|---|
//! | [`Vid`] | the vertex arena | `Mesh::v_halfedge`, the vertex columns |
//! | [`Hid`] | the half-edge records | `Mesh::he`, the half-edge columns |
//! | [`Eid`] | the edge arena | the edge generations and columns |
//! | [`Fid`] | the face arena (holes included) | `Mesh::f_halfedge`, the face columns |
//!
//! The layout, stated once:
//!
//! - Edge `e` owns half-edges `2e` and `2e + 1`. Twins sit side by side, so
//!   [`Hid::twin`] and [`Hid::edge`] are arithmetic and cost no storage, and
//!   a half-edge shares its edge's generation ([`Hid::EDGE_SHIFT`]).
//! - `u32::MAX` means "no element" ([`Hid::NONE`] and its siblings).
//! - A face's link ([`FaceLink`]) keeps its half-edge in the low 31 bits and
//!   the hole flag in the top bit: at most 2^31 − 1 half-edge slots.
//!
//! The conversions to the public keys (which add a generation) live here
//! too. [`IdVec`] is a `Vec` indexed by one id type, so a vertex id cannot
//! index the half-edge records by mistake. [`LinkVec`] is the same without
//! `IndexMut`: the mesh keeps its links in it, so every write goes through
//! the mutators of [`journal`](crate::journal) (which record the old value
//! while a journal is on) or through the explicitly named
//! [`LinkVec::unlogged_mut`].
//!
//! Every method is a one-line `#[inline]` function over the `u32`; the
//! types compile to the bare arithmetic they replace.

use std::fmt;
use std::marker::PhantomData;
use std::ops::{Index, IndexMut};

use crate::keys::{EdgeKey, FaceKey, HalfedgeKey, VertexKey};

/// The raw "no element" value.
const NONE_RAW: u32 = u32::MAX;

/// What the typed index vectors need of an index type.
pub(crate) trait Id: Copy {
    /// The id of slot `i`.
    fn from_index(i: usize) -> Self;
    /// The slot number, for indexing.
    fn index(self) -> usize;
}

macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident, $key:ident, $prefix:literal) => {
        $(#[$doc])*
        #[derive(Copy, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[repr(transparent)]
        #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize), serde(transparent))]
        pub(crate) struct $name(u32);

        impl $name {
            /// No element.
            pub(crate) const NONE: $name = $name(NONE_RAW);

            /// The id of slot `raw`.
            #[inline(always)]
            pub(crate) const fn new(raw: u32) -> $name {
                $name(raw)
            }

            /// The slot number as stored.
            #[inline(always)]
            pub(crate) const fn raw(self) -> u32 {
                self.0
            }

            /// The slot number, for indexing.
            #[inline(always)]
            pub(crate) const fn index(self) -> usize {
                self.0 as usize
            }

            /// Whether this is [`NONE`](Self::NONE).
            #[inline(always)]
            pub(crate) const fn is_none(self) -> bool {
                self.0 == NONE_RAW
            }

            /// The public key of this slot at `generation`.
            #[inline(always)]
            pub(crate) const fn key(self, generation: u32) -> $key {
                $key::new(self.0, generation)
            }
        }

        impl Id for $name {
            #[inline(always)]
            fn from_index(i: usize) -> $name {
                debug_assert!(i < NONE_RAW as usize, "slot index past 32 bits");
                $name(i as u32)
            }

            #[inline(always)]
            fn index(self) -> usize {
                self.0 as usize
            }
        }

        impl $key {
            /// The slot this key names (its generation is not checked).
            #[inline(always)]
            pub(crate) const fn id(self) -> $name {
                $name(self.index)
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                if self.is_none() {
                    write!(f, concat!($prefix, "NONE"))
                } else {
                    write!(f, concat!($prefix, "{}"), self.0)
                }
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Debug::fmt(self, f)
            }
        }
    };
}

id_type!(
    /// A vertex slot.
    Vid,
    VertexKey,
    "v"
);
id_type!(
    /// A half-edge slot: side `h & 1` of edge `h >> 1`.
    Hid,
    HalfedgeKey,
    "h"
);
id_type!(
    /// An edge slot: the twin half-edges `2e` and `2e + 1`.
    Eid,
    EdgeKey,
    "e"
);
id_type!(
    /// A face slot (a face or a hole).
    Fid,
    FaceKey,
    "f"
);

impl Hid {
    /// A half-edge's generation is its edge's: the edge slot is the
    /// half-edge slot shifted right by this much.
    pub(crate) const EDGE_SHIFT: u32 = 1;

    /// The other half-edge of the same edge.
    #[inline(always)]
    pub(crate) const fn twin(self) -> Hid {
        Hid(self.0 ^ 1)
    }

    /// The edge it belongs to.
    #[inline(always)]
    pub(crate) const fn edge(self) -> Eid {
        Eid(self.0 >> Self::EDGE_SHIFT)
    }

    /// Which of its edge's two half-edges it is: 0 or 1.
    #[inline(always)]
    pub(crate) const fn side(self) -> u32 {
        self.0 & 1
    }
}

impl Eid {
    /// Half-edge `side` (0 or 1; taken modulo 2).
    #[inline(always)]
    pub(crate) const fn halfedge(self, side: u32) -> Hid {
        Hid(2 * self.0 + (side & 1))
    }

    /// Both half-edges, side 0 first.
    #[inline(always)]
    pub(crate) const fn halfedges(self) -> [Hid; 2] {
        [Hid(2 * self.0), Hid(2 * self.0 + 1)]
    }

    /// The number of half-edge slots that `edges` edge slots hold.
    #[inline(always)]
    pub(crate) const fn halfedge_slots(edges: usize) -> usize {
        2 * edges
    }
}

/// The most half-edge slots a mesh can hold: a face link has 31 bits for its
/// half-edge.
#[cfg(feature = "serde")]
pub(crate) const MAX_HALFEDGE_SLOTS: usize = (FaceLink::HOLE_BIT - 1) as usize;

/// One half-edge's links.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct HalfedgeRecord {
    /// The vertex it leaves.
    pub(crate) origin: Vid,
    /// The next half-edge around its face.
    pub(crate) next: Hid,
    /// The face (or hole) on its left.
    pub(crate) face: Fid,
}

impl HalfedgeRecord {
    /// A record with no links (a new or freed slot).
    pub(crate) const VACANT: HalfedgeRecord = HalfedgeRecord {
        origin: Vid::NONE,
        next: Hid::NONE,
        face: Fid::NONE,
    };
}

/// A face's link: one of its half-edges, and whether it is a hole.
#[derive(Copy, Clone, PartialEq, Eq)]
#[repr(transparent)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(transparent)
)]
pub(crate) struct FaceLink(u32);

impl FaceLink {
    /// The hole flag's bit.
    const HOLE_BIT: u32 = 1 << 31;

    /// A face (or hole) that names no half-edge yet: its half-edge is the
    /// largest 31-bit value, past every half-edge slot.
    #[inline(always)]
    pub(crate) const fn unset(hole: bool) -> FaceLink {
        let bit = if hole { Self::HOLE_BIT } else { 0 };
        FaceLink(bit | !Self::HOLE_BIT)
    }

    /// Half-edge `h` (a slot below 2^31), flagged as a hole or not.
    #[inline(always)]
    pub(crate) const fn new(h: Hid, hole: bool) -> FaceLink {
        debug_assert!(h.0 < Self::HOLE_BIT, "half-edge slot past 31 bits");
        let bit = if hole { Self::HOLE_BIT } else { 0 };
        FaceLink(bit | h.0)
    }

    /// The face's half-edge (out of range while [`unset`](Self::unset)).
    #[inline(always)]
    pub(crate) const fn halfedge(self) -> Hid {
        Hid(self.0 & !Self::HOLE_BIT)
    }

    /// Whether the face is a hole.
    #[inline(always)]
    pub(crate) const fn is_hole(self) -> bool {
        self.0 & Self::HOLE_BIT != 0
    }

    /// The same flag, another half-edge (a slot below 2^31).
    #[inline(always)]
    pub(crate) const fn with_halfedge(self, h: Hid) -> FaceLink {
        debug_assert!(h.0 < Self::HOLE_BIT, "half-edge slot past 31 bits");
        FaceLink((self.0 & Self::HOLE_BIT) | h.0)
    }

    /// The same half-edge, flagged as a hole or not.
    #[inline(always)]
    pub(crate) const fn with_hole(self, hole: bool) -> FaceLink {
        let bit = if hole { Self::HOLE_BIT } else { 0 };
        FaceLink(bit | (self.0 & !Self::HOLE_BIT))
    }
}

impl fmt::Debug for FaceLink {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = if self.is_hole() { "hole" } else { "face" };
        write!(f, "{kind}({:?})", self.halfedge())
    }
}

/// Spare slots an arena array keeps beyond its length when it is built,
/// read, cloned, compacted or rebuilt by a subdivision (links, written-out
/// generations, attribute columns): about 3 % (and at least 16), so that
/// a small edit of a large mesh (a few holes filled, a local remesh) adds
/// its elements without reallocating, copying and page-faulting every
/// array. Capacity never
/// written is never touched, so it costs address space, not resident
/// memory; [`Mesh::heap_bytes`](crate::Mesh::heap_bytes) counts it.
/// Measured on icosphere(7) with the peers kit's 8 holes (`fill_holes`,
/// which needs 3 vertex, 9 edge and 6 face slots more than the holes
/// freed): the arrays' growth made the fill 17-23 ms where the fill
/// itself takes about 3 ms. The first `poke_face` after `compact()` of
/// icosphere(7) with every 50th face removed took 11-15 ms before
/// `compact` kept headroom, 6-9 µs after; after `loop_subdivide` of it,
/// 0.9-1.6 ms before, 8-10 µs after (2026-11-27, release build).
#[inline]
pub(crate) const fn headroom(len: usize) -> usize {
    len / 32 + 16
}

/// An empty `Vec` with room for `len` entries and [`headroom`] to spare.
pub(crate) fn with_headroom<T>(len: usize) -> Vec<T> {
    Vec::with_capacity(len + headroom(len))
}

/// A copy of `items` with [`headroom`] to spare.
pub(crate) fn to_vec_with_headroom<T: Clone>(items: &[T]) -> Vec<T> {
    let mut v = with_headroom(items.len());
    v.extend_from_slice(items);
    v
}

/// `n` copies of `value` with [`headroom`] to spare.
pub(crate) fn filled_with_headroom<T: Clone>(value: T, n: usize) -> Vec<T> {
    let mut v = with_headroom(n);
    v.resize(n, value);
    v
}

/// A `Vec` indexed by one id type.
#[derive(PartialEq, Eq)]
#[repr(transparent)]
pub(crate) struct IdVec<I, T> {
    raw: Vec<T>,
    id: PhantomData<fn(I) -> I>,
}

impl<I, T: Clone> Clone for IdVec<I, T> {
    /// A copy with [`headroom`] to spare.
    fn clone(&self) -> Self {
        IdVec::from_vec(to_vec_with_headroom(&self.raw))
    }
}

impl<I, T> Default for IdVec<I, T> {
    fn default() -> Self {
        IdVec::from_vec(Vec::new())
    }
}

impl<I, T: fmt::Debug> fmt::Debug for IdVec<I, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.raw.fmt(f)
    }
}

impl<I, T> IdVec<I, T> {
    /// Wrap a `Vec` whose entry `i` belongs to slot `i`.
    #[inline]
    pub(crate) const fn from_vec(raw: Vec<T>) -> Self {
        IdVec {
            raw,
            id: PhantomData,
        }
    }

    /// `n` copies of `value`.
    #[inline]
    pub(crate) fn filled(value: T, n: usize) -> Self
    where
        T: Clone,
    {
        IdVec::from_vec(vec![value; n])
    }

    /// `n` copies of `value`, with [`headroom`] to spare.
    #[inline]
    pub(crate) fn filled_with_headroom(value: T, n: usize) -> Self
    where
        T: Clone,
    {
        IdVec::from_vec(filled_with_headroom(value, n))
    }

    /// Entries held.
    #[inline(always)]
    pub(crate) fn len(&self) -> usize {
        self.raw.len()
    }

    /// Entries there is room for.
    #[inline]
    pub(crate) fn capacity(&self) -> usize {
        self.raw.capacity()
    }

    /// Append an entry.
    #[inline]
    pub(crate) fn push(&mut self, value: T) {
        self.raw.push(value);
    }

    /// Append copies of `values`.
    #[inline]
    pub(crate) fn extend_from(&mut self, values: &[T])
    where
        T: Clone,
    {
        self.raw.extend_from_slice(values);
    }

    /// The entries, in slot order.
    #[inline(always)]
    pub(crate) fn as_slice(&self) -> &[T] {
        &self.raw
    }
}

impl<I: Id, T> IdVec<I, T> {
    /// The entry of `i`, if in range.
    #[inline(always)]
    pub(crate) fn get(&self, i: I) -> Option<&T> {
        self.raw.get(i.index())
    }

    /// Whether `i` is in range.
    #[inline(always)]
    pub(crate) fn contains(&self, i: I) -> bool {
        i.index() < self.raw.len()
    }

    /// The ids of every entry, in order.
    #[inline]
    pub(crate) fn ids(&self) -> impl Iterator<Item = I> + use<I, T> {
        (0..self.raw.len()).map(I::from_index)
    }
}

/// The mesh's link arrays: an [`IdVec`] that can be read like one (it
/// derefs to it) but not written through indexing. Writes go through the
/// mesh's journaled mutators (`set_he`, `he_mut`, `set_vertex_halfedge`,
/// `set_face_link_raw` in `mesh/writer.rs`), which call
/// [`unlogged_mut`](LinkVec::unlogged_mut) after recording the old value; a
/// stray `mesh.he[h] = ..` does not compile.
#[derive(Clone, PartialEq, Eq)]
#[repr(transparent)]
pub(crate) struct LinkVec<I, T>(IdVec<I, T>);

impl<I, T: fmt::Debug> fmt::Debug for LinkVec<I, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl<I, T> Default for LinkVec<I, T> {
    fn default() -> Self {
        LinkVec(IdVec::from_vec(Vec::new()))
    }
}

impl<I, T> From<IdVec<I, T>> for LinkVec<I, T> {
    #[inline]
    fn from(v: IdVec<I, T>) -> Self {
        LinkVec(v)
    }
}

impl<I, T> std::ops::Deref for LinkVec<I, T> {
    type Target = IdVec<I, T>;
    #[inline(always)]
    fn deref(&self) -> &IdVec<I, T> {
        &self.0
    }
}

impl<I: Id, T> Index<I> for LinkVec<I, T> {
    type Output = T;

    #[inline(always)]
    fn index(&self, i: I) -> &T {
        &self.0[i]
    }
}

impl<I: Id, T> LinkVec<I, T> {
    /// Entry `i`, mutably, with nothing recorded: only for the journal's own
    /// mutators (which record first) and for arrays no journal can see.
    #[inline(always)]
    pub(crate) fn unlogged_mut(&mut self, i: I) -> &mut T {
        &mut self.0[i]
    }

    /// Append an entry (a new slot: the journal records births as ranges).
    #[inline]
    pub(crate) fn push(&mut self, value: T) {
        self.0.push(value);
    }
}

impl<I: Id, T> Index<I> for IdVec<I, T> {
    type Output = T;

    #[inline(always)]
    fn index(&self, i: I) -> &T {
        &self.raw[i.index()]
    }
}

impl<I: Id, T> IndexMut<I> for IdVec<I, T> {
    #[inline(always)]
    fn index_mut(&mut self, i: I) -> &mut T {
        &mut self.raw[i.index()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The capacities of `m`'s link arrays and position column.
    fn capacities(m: &crate::Mesh) -> [usize; 4] {
        [
            m.he.capacity(),
            m.v_halfedge.capacity(),
            m.f_halfedge.capacity(),
            m.attrs.positions().map_or(0, |p| p.values.capacity()),
        ]
    }

    /// The first edits after a build or a rebuild fit in the headroom:
    /// no array regrows (which copies and faults in the whole mesh).
    fn first_edits_fit(mut m: crate::Mesh, what: &str) {
        let before = capacities(&m);
        assert!(
            m.he.capacity() >= m.he.len() + headroom(m.he.len()),
            "{what}: half-edges {} for {}",
            m.he.capacity(),
            m.he.len()
        );
        let f = m.faces().next().expect("a face");
        m.poke_face(f).expect("poke");
        let e = m.edges().next().expect("an edge");
        m.split_edge(e, 0.5).expect("split");
        assert_eq!(capacities(&m), before, "{what}: an array regrew");
    }

    #[test]
    fn built_compacted_and_subdivided_meshes_keep_headroom() {
        use crate::algo::{self, Progress, SubdivisionOptions};
        let opts = SubdivisionOptions::default();
        first_edits_fit(crate::shapes::icosphere(2), "built");
        first_edits_fit(crate::shapes::icosphere(2).clone(), "cloned");
        let mut m = crate::shapes::icosphere(2);
        let gone: Vec<_> = m.faces().step_by(7).collect();
        for f in gone {
            m.remove_face(f).expect("remove");
        }
        m.compact();
        first_edits_fit(m, "compacted");
        type Scheme = fn(
            &mut crate::Mesh,
            &SubdivisionOptions,
            Progress<'_>,
        ) -> crate::Result<algo::SubdivisionReport>;
        let schemes: [(&str, Scheme); 3] = [
            ("loop", algo::loop_subdivide),
            ("catmull-clark", algo::catmull_clark),
            ("sqrt3", algo::sqrt3_subdivide),
        ];
        for (name, scheme) in schemes {
            let mut m = crate::shapes::icosphere(2);
            scheme(&mut m, &opts, Progress::none()).expect("subdivide");
            first_edits_fit(m, name);
        }
    }

    #[test]
    fn twins_and_edges() {
        let e = Eid::new(7);
        let [h, t] = e.halfedges();
        assert_eq!((h.raw(), t.raw()), (14, 15));
        assert_eq!((h.twin(), t.twin()), (t, h));
        assert_eq!((h.edge(), t.edge()), (e, e));
        assert_eq!((h.side(), t.side()), (0, 1));
        assert_eq!((e.halfedge(0), e.halfedge(1), e.halfedge(3)), (h, t, t));
        assert!(Hid::NONE.is_none() && !h.is_none());
    }

    #[test]
    fn face_links_keep_the_hole_bit() {
        let h = Hid::new(12);
        let f = FaceLink::new(h, true);
        assert!(f.is_hole());
        assert_eq!(f.halfedge(), h);
        let g = f.with_halfedge(Hid::new(3));
        assert!(g.is_hole());
        assert_eq!(g.halfedge(), Hid::new(3));
        assert!(!g.with_hole(false).is_hole());
        assert!(FaceLink::unset(false).halfedge().index() >= (1 << 31) - 1);
    }

    #[test]
    fn keys_round_trip() {
        let h = Hid::new(9);
        let k = h.key(5);
        assert_eq!((k.index(), k.generation()), (9, 5));
        assert_eq!(k.id(), h);
        assert_eq!(k.twin_key().id(), h.twin());
        assert_eq!(k.edge_key().id(), h.edge());
    }

    #[test]
    fn id_vec_indexes_by_id() {
        let mut v: IdVec<Vid, u8> = IdVec::filled(0, 3);
        v[Vid::new(2)] = 9;
        assert_eq!((v[Vid::new(0)], v[Vid::new(2)], v.len()), (0, 9, 3));
        assert_eq!(v.get(Vid::new(3)), None);
        assert_eq!(
            v.ids().collect::<Vec<_>>(),
            [Vid::new(0), Vid::new(1), Vid::new(2)]
        );
    }
}
