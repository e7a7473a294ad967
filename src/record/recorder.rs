//! The recorder: the open step, the undo and redo logs, change tracking.
//!
//! A forward edit writes through the mesh's hooks (`mesh/writer.rs`,
//! `Columns::save`, `Mesh::alloc_*` and `free_*`), which call the save
//! primitives here. A link write to a slot that existed when the open step
//! began copies that slot's page of the link array on the first write to
//! the page ([`pages`](super::pages)); column writes push the old values
//! onto the column's list. Closing the step ([`seal`](super::seal)) walks
//! the copied pages in slot order, keeps the fields that differ from the
//! live arrays, and encodes them ([`codec`](super::codec)) onto the undo
//! log; column values go beside it as side records (the oldest value per
//! slot). Undo (in the journal) decodes the top step, swaps every stored
//! value with the mesh's (so the step now holds the values redo puts
//! back), reverses the slot events, and encodes the swapped step onto the
//! redo log. Redo is the same the other way.

use std::collections::{HashMap, VecDeque};

use super::codec::{SlotEvent, Step, FACE, NEXT, ORIGIN};
use super::pages::PageLog;
use super::{Arena, PerArena, Snapshot};
use crate::keys::ElementKind;
use crate::layout::{FaceLink, Fid, HalfedgeRecord, Hid, Vid};
use crate::slots::State;
use crate::store::{ColumnMeta, ErasedColumn, Record};

/// A record kept beside a step's bytes.
pub(crate) enum Side {
    /// Values of column `col` of set `set`.
    Col {
        set: ElementKind,
        col: u32,
        rec: Box<dyn Record>,
    },
    /// A column was added at `col` (applying it removes the column).
    Added { set: ElementKind, col: u32 },
    /// A column was removed from `col` (applying it puts it back).
    Removed {
        set: ElementKind,
        col: u32,
        name: String,
        column: Box<dyn ErasedColumn>,
        meta: ColumnMeta,
        position: bool,
    },
    /// The whole mesh's storage as it was (applying it swaps it in).
    Whole(Box<Snapshot>),
}

impl Side {
    pub(super) fn heap_bytes(&self) -> usize {
        std::mem::size_of::<Side>()
            + match self {
                Side::Col { rec, .. } => rec.heap_bytes(),
                Side::Added { .. } => 0,
                Side::Removed { column, name, .. } => column.heap_bytes() + name.len(),
                Side::Whole(m) => m.bytes,
            }
    }
}

/// One log of steps (undo or redo).
#[derive(Default)]
pub(crate) struct Log {
    /// Framed steps, bottom first; bytes before `floor` were trimmed.
    pub(crate) bytes: Vec<u8>,
    pub(crate) floor: usize,
    pub(crate) side: VecDeque<Side>,
    /// Units (what one undo takes back) in the log.
    pub(crate) units: usize,
    /// Units trimmed from the bottom so far (unit ids stay stable).
    pub(crate) trimmed: usize,
    /// Names of named units: `(unit id, name)`, ascending.
    pub(crate) names: Vec<(usize, String)>,
    /// Heap bytes of the side records.
    pub(crate) side_bytes: usize,
}

impl Log {
    pub(crate) fn is_empty(&self) -> bool {
        self.units == 0
    }

    /// The id the next unit pushed gets.
    pub(crate) fn next_id(&self) -> usize {
        self.trimmed + self.units
    }

    pub(crate) fn top_name(&self) -> Option<&str> {
        let top = self.next_id().checked_sub(1)?;
        match self.names.last() {
            Some((id, n)) if *id == top && self.units > 0 => Some(n),
            _ => None,
        }
    }

    pub(crate) fn memory(&self) -> usize {
        self.bytes.capacity()
            + self.side_bytes
            + self.names.iter().map(|n| n.1.len() + 32).sum::<usize>()
    }

    pub(crate) fn push_side(&mut self, s: Side) {
        self.side_bytes += s.heap_bytes();
        self.side.push_back(s);
    }

    pub(crate) fn pop_side(&mut self) -> Side {
        let s = self
            .side
            .pop_back()
            .expect("a step's side record is missing");
        self.side_bytes -= s.heap_bytes();
        s
    }
}

/// Open-step bookkeeping and the logs. See the module docs.
#[derive(Default)]
pub(crate) struct Recorder {
    // ----- who needs it
    /// Undo history is on.
    pub(crate) history: bool,
    /// Depth limit (units) and byte limit of the undo log.
    pub(crate) max_units: Option<usize>,
    pub(crate) max_bytes: Option<usize>,
    /// Change tracking is on.
    pub(crate) tracking: bool,
    /// Open transactions and steps (`begin_step`), nested.
    pub(crate) tx_depth: u32,
    pub(crate) group_depth: u32,
    /// A step of the open group was sealed (later ones continue its unit).
    pub(crate) group_started: bool,
    pub(crate) group_name: Option<String>,
    // ----- the open step
    /// Slot counts (vertex, edge, face) when it began.
    pub(crate) start: PerArena<u32>,
    /// Old links of the pages the open step wrote (half-edge, vertex,
    /// face arrays), copied on the first write to each page; slots born in
    /// the open step are never saved (undo makes them vacant).
    pub(crate) he: PageLog<HalfedgeRecord>,
    pub(crate) vh: PageLog<Hid>,
    pub(crate) fl: PageLog<FaceLink>,
    pub(crate) events: PerArena<Vec<SlotEvent>>,
    /// Per arena: deaths of slots born in the open step (0: all of them
    /// are live, the seal need not look).
    pub(crate) born_deaths: PerArena<u32>,
    pub(crate) holes0: usize,
    pub(crate) states0: PerArena<State>,
    pub(crate) side: Vec<Side>,
    /// Bulk writers saved column values (sealed as a step of their own).
    pub(crate) bulk: bool,
    // ----- logs
    pub(crate) undo: Log,
    pub(crate) redo: Log,
    // ----- tracking
    /// Per arena: slot -> generation at the last `take_changes` (even:
    /// vacant or not yet allocated).
    pub(crate) touched: PerArena<HashMap<u32, u32>>,
    /// `(set, column id) -> (existed at the last take, name)`.
    pub(crate) cols: HashMap<(ElementKind, u64), (bool, String)>,
    pub(crate) rebuilt: bool,
    /// The mesh revision at the last `take_changes` (or when tracking
    /// was turned on): the start of the next change set's span.
    pub(crate) taken_at: u64,
    // ----- scratch
    pub(crate) step: Step,
}

impl std::fmt::Debug for Recorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Recorder")
            .field("history", &self.history)
            .field("tracking", &self.tracking)
            .field("undo_units", &self.undo.units)
            .field("redo_units", &self.redo.units)
            .finish_non_exhaustive()
    }
}

impl Recorder {
    /// Record `h`'s links before a write to them: the first write to each
    /// page of slots that existed when the open step began copies the page
    /// (the oldest values are the ones to put back).
    #[inline(always)]
    pub(crate) fn save_he(&mut self, h: Hid, live: &[HalfedgeRecord]) {
        self.he.save(h.raw(), self.start[Arena::Edge] * 2, live);
    }

    /// Record `v`'s half-edge before a write (first write per page).
    #[inline(always)]
    pub(crate) fn save_vh(&mut self, v: Vid, live: &[Hid]) {
        self.vh.save(v.raw(), self.start[Arena::Vertex], live);
    }

    /// Record `f`'s link before a write (first write per page).
    #[inline(always)]
    pub(crate) fn save_fl(&mut self, f: Fid, live: &[FaceLink]) {
        self.fl.save(f.raw(), self.start[Arena::Face], live);
    }

    /// A vacant slot of arena `a` was taken from the free list. A slot
    /// born in the open step records nothing: the seal reads whether it is
    /// live from the arena (see [`Step::born_live`]).
    #[inline]
    pub(crate) fn reused(&mut self, a: Arena, slot: u32, generation: u32) {
        if slot < self.start[a] {
            self.events[a].push(SlotEvent::Reuse { slot, generation });
        }
    }

    /// The element at `generation` in slot `slot` of arena `a` was removed.
    /// For a slot born in the open step only a count goes up (the seal
    /// then looks at which new slots are vacant).
    #[inline]
    pub(crate) fn died(&mut self, a: Arena, slot: u32, generation: u32) {
        if slot < self.start[a] {
            self.events[a].push(SlotEvent::Death { slot, generation });
        } else {
            self.born_deaths[a] += 1;
        }
    }

    /// Whether steps are kept (history or an open transaction).
    pub(crate) fn keeps_steps(&self) -> bool {
        self.history || self.tx_depth > 0
    }

    pub(crate) fn touch(&mut self, a: Arena, slot: u32, baseline: u32) {
        if self.tracking {
            self.touched[a].entry(slot).or_insert(baseline);
        }
    }

    pub(crate) fn touch_col(&mut self, set: ElementKind, id: u64, existed: bool, name: &str) {
        if self.tracking {
            self.cols
                .entry((set, id))
                .or_insert_with(|| (existed, name.to_owned()));
        }
    }
}

/// The fields of a half-edge record that differ between `cur` and `old`
/// (a mask of `ORIGIN`, `NEXT`, `FACE`), if any.
#[inline]
pub(super) fn changed_fields(cur: HalfedgeRecord, old: HalfedgeRecord) -> Option<u8> {
    let mask = (u8::from(cur.origin != old.origin) * ORIGIN)
        | (u8::from(cur.next != old.next) * NEXT)
        | (u8::from(cur.face != old.face) * FACE);
    (mask != 0).then_some(mask)
}

/// Call `f(slot, live at the seal)` for every new slot of a step, in
/// slot order (`runs`: [`Step::born_live`]).
#[inline]
pub(crate) fn for_born(start: u32, count: u32, runs: &[u32], mut f: impl FnMut(u32, bool)) {
    if runs.is_empty() {
        (start..start + count).for_each(|i| f(i, true));
        return;
    }
    let mut i = start;
    for (k, &len) in runs.iter().enumerate() {
        let live = k % 2 == 0;
        (i..i + len).for_each(|j| f(j, live));
        i += len;
    }
}

impl Recorder {
    /// The undo name of the unit on top, if named.
    pub(crate) fn undo_name(&self) -> Option<&str> {
        self.undo.top_name()
    }

    /// The redo name of the unit on top, if named.
    pub(crate) fn redo_name(&self) -> Option<&str> {
        self.redo.top_name()
    }
}
