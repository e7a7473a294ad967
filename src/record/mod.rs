//! The journal's storage part: the record of old values a mesh keeps while
//! undo history, a transaction or change tracking is on, and the step log
//! it seals them into.
//!
//! This layer sits under [`Mesh`](crate::Mesh), beside the slots and the
//! attribute columns it records: it knows the storage (link arrays,
//! [`Slots`], [`AttrStore`]), never the mesh. The mesh holds a
//! [`Recorder`] while a journal is on and lends it its storage
//! ([`Storage`]) to seal a step; the mesh's link mutators call the
//! recorder's save primitives before each write. Undo, redo, transactions
//! and change reports, which apply records back to a mesh, are the
//! [`journal`](crate::journal), one layer up.
//!
//! | file | holds |
//! |---|---|
//! | `recorder.rs` | [`Recorder`] (the open step, the undo and redo logs, change tracking), its side records, and the save primitives the mesh's mutators call |
//! | `seal.rs` | closing the open step: the changed links and column values onto the undo log, change tracking, the log's limits |
//! | `pages.rs` | copy-on-first-touch pages of a link array |
//! | `codec.rs` | the byte form of a sealed step |
//!
//! Whether an operator writes the record at all is chosen once per call,
//! by the [`Journaling`] mode it is compiled in (see `mesh/writer.rs`): with
//! no recorder, the operator runs a body in which every hook compiles
//! away.

mod codec;
mod pages;
mod recorder;
mod seal;

pub(crate) use codec::{decode, encode, last_step, SlotEvent, Step, FACE, NEXT, ORIGIN};
pub(crate) use recorder::{for_born, Recorder, Side};
pub(crate) use seal::step_touches;

use std::ops::{Index, IndexMut};

use crate::keys::ElementKind;
use crate::layout::{FaceLink, Fid, HalfedgeRecord, Hid, LinkVec, Vid};
use crate::slots::Slots;
use crate::store::AttrStore;

/// One of the three slot arenas a step records births and deaths in
/// (half-edges live in their edge's slot).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Arena {
    Vertex,
    Edge,
    Face,
}

impl Arena {
    /// The arenas, in the order of every per-arena record.
    pub(crate) const ALL: [Arena; 3] = [Arena::Vertex, Arena::Edge, Arena::Face];

    /// Its position in per-arena records (and its bit in the codec's masks).
    #[inline]
    pub(crate) const fn index(self) -> usize {
        self as usize
    }

    /// The arena whose slots a column set's slots live in, and the shift
    /// from a column slot to an arena slot (a half-edge's edge is half its
    /// slot).
    pub(crate) const fn of_set(set: ElementKind) -> (Arena, u32) {
        match set {
            ElementKind::Vertex => (Arena::Vertex, 0),
            ElementKind::Halfedge => (Arena::Edge, 1),
            ElementKind::Edge => (Arena::Edge, 0),
            ElementKind::Face => (Arena::Face, 0),
        }
    }
}

/// One value per [`Arena`], indexed by it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct PerArena<T>(pub(crate) [T; 3]);

impl<T> PerArena<T> {
    /// `f` of every arena, in [`Arena::ALL`] order.
    pub(crate) fn from_fn(mut f: impl FnMut(Arena) -> T) -> Self {
        PerArena(Arena::ALL.map(&mut f))
    }

    /// The values, in [`Arena::ALL`] order.
    pub(crate) fn iter(&self) -> std::slice::Iter<'_, T> {
        self.0.iter()
    }

    /// The values, mutably, in [`Arena::ALL`] order.
    pub(crate) fn iter_mut(&mut self) -> std::slice::IterMut<'_, T> {
        self.0.iter_mut()
    }
}

impl<T> Index<Arena> for PerArena<T> {
    type Output = T;
    #[inline]
    fn index(&self, a: Arena) -> &T {
        &self.0[a.index()]
    }
}

impl<T> IndexMut<Arena> for PerArena<T> {
    #[inline]
    fn index_mut(&mut self, a: Arena) -> &mut T {
        &mut self.0[a.index()]
    }
}

/// Whether an operator's writes are recorded: [`Recorded`] or
/// [`Unrecorded`], picked once per call (see `mesh/writer.rs`).
pub(crate) trait Journaling {
    /// Whether the hooks look for a recorder at all.
    const ON: bool;
}

/// Writes record their old values while a recorder exists (one test of
/// the mesh's recorder pointer per write).
pub(crate) enum Recorded {}

/// No recorder exists: the hooks compile to nothing.
pub(crate) enum Unrecorded {}

impl Journaling for Recorded {
    const ON: bool = true;
}

impl Journaling for Unrecorded {
    const ON: bool = false;
}

/// Run an operator body generic over [`Journaling`] in the mode the mesh
/// is in, the one place an operator's mode is chosen:
/// `journaled!(self.body(args..))` calls `self.body::<Recorded>` while a
/// recorder exists, `self.body::<Unrecorded>` otherwise. The body takes
/// the mesh's [`Writer`](crate::mesh::Writer) in that mode once and makes
/// every write through it. On a mesh with a column whose rule can fail,
/// the body runs as a transaction, so that a rule's failure refuses the
/// operator (its body returns a `Result`) and leaves the mesh unchanged.
/// `journaled!(unguarded self.body(args..))` leaves that to the caller.
macro_rules! journaled {
    ($m:ident . $body:ident ( $($arg:expr),* $(,)? )) => {
        if $m.attrs.may_fail() {
            $m.guarded(|m| m.$body::<$crate::record::Recorded>($($arg),*))
        } else {
            $crate::record::journaled!(unguarded $m.$body($($arg),*))
        }
    };
    (unguarded $m:ident . $body:ident ( $($arg:expr),* $(,)? )) => {
        if $m.rec.is_some() {
            $m.$body::<$crate::record::Recorded>($($arg),*)
        } else {
            $m.$body::<$crate::record::Unrecorded>($($arg),*)
        }
    };
}
pub(crate) use journaled;

/// A mesh's storage, lent to its [`Recorder`]: what opening and sealing a
/// step read (the link arrays, the hole count) and write (the slots' free
/// lists, the columns' saved values).
pub(crate) struct Storage<'a> {
    pub(crate) v_halfedge: &'a LinkVec<Vid, Hid>,
    pub(crate) he: &'a LinkVec<Hid, HalfedgeRecord>,
    pub(crate) f_halfedge: &'a LinkVec<Fid, FaceLink>,
    pub(crate) slots: PerArena<&'a mut Slots>,
    pub(crate) holes: usize,
    pub(crate) attrs: &'a mut AttrStore,
}

impl Storage<'_> {
    /// Slots allocated in each column set (vertex, half-edge, edge, face).
    pub(crate) fn slot_counts(&self) -> [usize; 4] {
        [
            self.slots[Arena::Vertex].slot_count(),
            self.he.len(),
            self.slots[Arena::Edge].slot_count(),
            self.slots[Arena::Face].slot_count(),
        ]
    }

    /// The generation of slot `i` of arena `a` (0: never allocated).
    pub(crate) fn generation(&self, a: Arena, i: u32) -> u32 {
        self.slots[a].generation(i as usize).unwrap_or(0)
    }
}

/// A whole mesh's storage, kept by a step that rebuilt the mesh wholesale
/// (applying the step swaps it with the mesh's; see
/// `Mesh::swap_storage`).
#[derive(Debug)]
pub(crate) struct Snapshot {
    pub(crate) v_halfedge: LinkVec<Vid, Hid>,
    pub(crate) v_slots: Slots,
    pub(crate) he: LinkVec<Hid, HalfedgeRecord>,
    pub(crate) e_slots: Slots,
    pub(crate) f_halfedge: LinkVec<Fid, FaceLink>,
    pub(crate) f_slots: Slots,
    pub(crate) holes: usize,
    pub(crate) attrs: AttrStore,
    /// Heap bytes it holds (the mesh's `heap_bytes` when it was taken).
    pub(crate) bytes: usize,
}
