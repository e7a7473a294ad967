//! The recorder: the open step, the undo and redo logs, change tracking.
//!
//! A forward edit writes through the hooks (`hooks.rs`, `Columns::save`,
//! `Mesh::alloc_*` and `free_*`). A link write to a slot that existed when
//! the open step began copies that slot's page of the link array on the
//! first write to the page ([`pages`](super::pages)); column writes push
//! the old values onto the column's list. Closing the step ([`Mesh::seal`])
//! walks the copied pages in slot order, keeps the fields that differ from
//! the live arrays, and encodes them ([`codec`]) onto the undo log; column
//! values go beside it as side records (the oldest value per slot). Undo decodes the
//! top step, swaps every stored value with the mesh's (so the step now
//! holds the values redo puts back), reverses the slot events, and encodes
//! the swapped step onto the redo log. Redo is the same the other way.

use std::collections::{HashMap, VecDeque};

use super::codec::{self, SlotEvent, Step, FACE, NEXT, ORIGIN};
use super::pages::PageLog;
use crate::layout::{FaceLink, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::Mesh;
use crate::slots::{Slots, State};
use crate::store::{ColumnMeta, ErasedColumn, Record};

/// A record kept beside a step's bytes.
pub(crate) enum Side {
    /// Values of one column: `set` in [`ElementKind`] order, column index.
    Col {
        set: u8,
        col: u32,
        rec: Box<dyn Record>,
    },
    /// A column was added at `col` (applying it removes the column).
    Added { set: u8, col: u32 },
    /// A column was removed from `col` (applying it puts it back).
    Removed {
        set: u8,
        col: u32,
        name: String,
        column: Box<dyn ErasedColumn>,
        meta: ColumnMeta,
        position: bool,
    },
    /// The whole mesh as it was (applying it swaps it in).
    Whole(Box<Mesh>),
}

impl Side {
    fn heap_bytes(&self) -> usize {
        std::mem::size_of::<Side>()
            + match self {
                Side::Col { rec, .. } => rec.heap_bytes(),
                Side::Added { .. } => 0,
                Side::Removed { column, name, .. } => column.heap_bytes() + name.len(),
                Side::Whole(m) => m.heap_bytes(),
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
    fn next_id(&self) -> usize {
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

    fn push_side(&mut self, s: Side) {
        self.side_bytes += s.heap_bytes();
        self.side.push_back(s);
    }

    fn pop_side(&mut self) -> Side {
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
    pub(crate) start: [u32; 3],
    /// Old links of the pages the open step wrote (half-edge, vertex,
    /// face arrays), copied on the first write to each page; slots born in
    /// the open step are never saved (undo makes them vacant).
    pub(crate) he: PageLog<HalfedgeRecord>,
    pub(crate) vh: PageLog<Hid>,
    pub(crate) fl: PageLog<FaceLink>,
    pub(crate) events: [Vec<SlotEvent>; 3],
    /// Per arena: deaths of slots born in the open step (0: all of them
    /// are live, the seal need not look).
    pub(crate) born_deaths: [u32; 3],
    pub(crate) holes0: usize,
    pub(crate) states0: [State; 3],
    pub(crate) side: Vec<Side>,
    /// Bulk writers saved column values (sealed as a step of their own).
    pub(crate) bulk: bool,
    // ----- logs
    pub(crate) undo: Log,
    pub(crate) redo: Log,
    // ----- tracking
    /// Per arena: slot -> generation at the last `take_changes` (even:
    /// vacant or not yet allocated).
    pub(crate) touched: [HashMap<u32, u32>; 3],
    /// `(set, column id) -> (existed at the last take, name)`.
    pub(crate) cols: HashMap<(u8, u64), (bool, String)>,
    pub(crate) rebuilt: bool,
    // ----- scratch
    step: Step,
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

/// Which arena a column set's slots belong to, and the shift from slot to
/// arena slot (half-edge columns share their edge's arena).
const SET_ARENA: [(usize, u32); 4] = [(0, 0), (1, 1), (1, 0), (2, 0)];

impl Recorder {
    /// Record `h`'s links before a write to them: the first write to each
    /// page of slots that existed when the open step began copies the page
    /// (the oldest values are the ones to put back).
    #[inline(always)]
    pub(crate) fn save_he(&mut self, h: Hid, live: &[HalfedgeRecord]) {
        self.he.save(h.raw(), self.start[1] * 2, live);
    }

    /// Record `v`'s half-edge before a write (first write per page).
    #[inline(always)]
    pub(crate) fn save_vh(&mut self, v: Vid, live: &[Hid]) {
        self.vh.save(v.raw(), self.start[0], live);
    }

    /// Record `f`'s link before a write (first write per page).
    #[inline(always)]
    pub(crate) fn save_fl(&mut self, f: Fid, live: &[FaceLink]) {
        self.fl.save(f.raw(), self.start[2], live);
    }

    /// A vacant slot of arena `a` was taken from the free list. A slot
    /// born in the open step records nothing: the seal reads whether it is
    /// live from the arena (see [`Step::born_live`]).
    #[inline]
    pub(crate) fn reused(&mut self, a: usize, slot: u32, generation: u32) {
        if slot < self.start[a] {
            self.events[a].push(SlotEvent::Reuse { slot, generation });
        }
    }

    /// The element at `generation` in slot `slot` of arena `a` was removed.
    /// For a slot born in the open step only a count goes up (the seal
    /// then looks at which new slots are vacant).
    #[inline]
    pub(crate) fn died(&mut self, a: usize, slot: u32, generation: u32) {
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

    fn touch(&mut self, a: usize, slot: u32, baseline: u32) {
        if self.tracking {
            self.touched[a].entry(slot).or_insert(baseline);
        }
    }

    fn touch_col(&mut self, set: u8, id: u64, existed: bool, name: &str) {
        if self.tracking {
            self.cols
                .entry((set, id))
                .or_insert_with(|| (existed, name.to_owned()));
        }
    }
}

fn slots_of(m: &Mesh, a: usize) -> &Slots {
    match a {
        0 => &m.v_slots,
        1 => &m.e_slots,
        _ => &m.f_slots,
    }
}

fn slots_of_mut(m: &mut Mesh, a: usize) -> &mut Slots {
    match a {
        0 => &mut m.v_slots,
        1 => &mut m.e_slots,
        _ => &mut m.f_slots,
    }
}

/// The fields of a half-edge record that differ between `cur` and `old`
/// (a mask of `ORIGIN`, `NEXT`, `FACE`), if any.
#[inline]
fn changed_fields(cur: HalfedgeRecord, old: HalfedgeRecord) -> Option<u8> {
    let mask = (u8::from(cur.origin != old.origin) * ORIGIN)
        | (u8::from(cur.next != old.next) * NEXT)
        | (u8::from(cur.face != old.face) * FACE);
    (mask != 0).then_some(mask)
}

fn slots_of_arena<'a>(v: &'a Slots, e: &'a Slots, f: &'a Slots, a: usize) -> &'a Slots {
    match a {
        0 => v,
        1 => e,
        _ => f,
    }
}

/// The generation of slot `i` (0: never allocated).
fn gen(m: &Mesh, a: usize, i: u32) -> u32 {
    slots_of(m, a).generation(i as usize).unwrap_or(0)
}

/// Call `f(slot, live at the seal)` for every new slot of a step, in
/// slot order (`runs`: [`Step::born_live`]).
#[inline]
fn for_born(start: u32, count: u32, runs: &[u32], mut f: impl FnMut(u32, bool)) {
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

/// Direction of an application.
#[derive(Copy, Clone, PartialEq, Eq)]
pub(crate) enum Dir {
    Undo,
    Redo,
}

impl Mesh {
    /// The recorder, which the caller knows is on.
    fn r(&mut self) -> &mut Recorder {
        self.rec.as_deref_mut().expect("no recorder")
    }

    /// Begin a new open step at the mesh as it is.
    pub(crate) fn open_step(&mut self) {
        let counts = [
            self.v_slots.slot_count() as u32,
            self.e_slots.slot_count() as u32,
            self.f_slots.slot_count() as u32,
        ];
        let holes = self.holes;
        let states = [
            self.v_slots.state(),
            self.e_slots.state(),
            self.f_slots.state(),
        ];
        let sc = self.slot_counts();
        self.attrs.vertex.log_below = sc[0];
        self.attrs.halfedge.log_below = sc[1];
        self.attrs.edge.log_below = sc[2];
        self.attrs.face.log_below = sc[3];
        let r = self.r();
        r.start = counts;
        r.holes0 = holes;
        r.states0 = states;
    }

    /// Start recording (a no-op if a recorder is on).
    pub(crate) fn ensure_recorder(&mut self) -> &mut Recorder {
        if self.rec.is_none() {
            self.rec = Some(Box::default());
            self.open_step();
        }
        self.r()
    }

    /// Stop recording if nothing needs it any more: no history, tracking,
    /// transaction or open step group. Held slots go back on the free lists.
    pub(crate) fn maybe_stop(&mut self) {
        let Some(r) = self.rec.as_deref() else { return };
        if r.history || r.tracking || r.tx_depth > 0 || r.group_depth > 0 {
            return;
        }
        self.seal();
        self.drop_redo();
        self.rec = None;
        for set in self.attrs.all_mut() {
            set.log_below = 0;
            set.dirty = false;
            for (_, c) in &mut set.cols {
                c.discard_saved();
            }
        }
    }

    /// Close the open step: encode it onto the undo log (while steps are
    /// kept), feed change tracking, and open the next.
    #[inline(never)]
    pub(crate) fn seal(&mut self) {
        if self.r().bulk {
            self.seal_bulk();
        }
        let mut step = std::mem::take(&mut self.r().step);
        step.clear();
        let mut side = std::mem::take(&mut self.r().side);
        // Column values.
        for (set_i, set) in self.attrs.all_mut().into_iter().enumerate() {
            if !set.dirty {
                continue;
            }
            set.dirty = false;
            for (ci, (_, c)) in set.cols.iter_mut().enumerate() {
                if let Some(rec) = c.seal_saved() {
                    side.push(Side::Col {
                        set: set_i as u8,
                        col: ci as u32,
                        rec,
                    });
                }
            }
        }
        // Links: the saved pages' old values that changed, ascending by
        // slot.
        {
            let r = self.rec.as_deref_mut().expect("no recorder");
            let [v0, _, f0] = r.start;
            // Room for every saved slot at once (no regrowth of a large step).
            step.vh.reserve(r.vh.saved_slots());
            step.fl.reserve(r.fl.saved_slots());
            r.vh.drain_changed(v0, self.v_halfedge.as_slice(), |v, old| {
                step.vh.push((Vid::new(v), old));
            });
            r.fl.drain_changed(f0, self.f_halfedge.as_slice(), |f, old| {
                step.fl.push((Fid::new(f), old));
            });
        }
        let counts = [
            self.v_slots.slot_count() as u32,
            self.e_slots.slot_count() as u32,
            self.f_slots.slot_count() as u32,
        ];
        let states = [
            self.v_slots.state(),
            self.e_slots.state(),
            self.f_slots.state(),
        ];
        let holes = self.holes;
        {
            let r = self.rec.as_deref_mut().expect("no recorder");
            for a in 0..3 {
                if counts[a] > r.start[a] {
                    step.births[a] = (r.start[a], counts[a] - r.start[a]);
                    if r.born_deaths[a] > 0 {
                        slots_of_arena(&self.v_slots, &self.e_slots, &self.f_slots, a)
                            .live_runs(r.start[a]..counts[a], &mut step.born_live[a]);
                    }
                }
                r.born_deaths[a] = 0;
                std::mem::swap(&mut step.events[a], &mut r.events[a]);
                if states[a] != r.states0[a] {
                    step.states[a] = Some((r.states0[a], states[a]));
                }
            }
            step.holes = holes as i64 - r.holes0 as i64;
            step.side = side.len() as u32;
        }
        // The half-edge records: straight from the saved pages into the
        // undo log when nothing else reads them (no tracking) and the step
        // is kept anyway; otherwise into `step.he` first.
        let direct = {
            let r = self.r();
            !r.tracking && r.keeps_steps() && r.he.saved_slots() > 0 && !step.is_empty()
        };
        if !direct {
            let r = self.rec.as_deref_mut().expect("no recorder");
            step.he.reserve(r.he.saved_slots());
            let live = &self.he;
            r.he.drain_changed(r.start[1] * 2, live.as_slice(), |h, old| {
                let h = Hid::new(h);
                if let Some(mask) = changed_fields(live[h], old) {
                    step.he.push((h, mask, old));
                }
            });
        }
        if !step.is_empty() || direct {
            if self.r().tracking {
                self.track_forward(&step, &side);
            }
            if self.r().keeps_steps() {
                self.push_forward(&mut step, side, direct);
            }
        }
        // Give the event lists back (their capacity) and open the next step.
        let r = self.r();
        for a in 0..3 {
            std::mem::swap(&mut step.events[a], &mut r.events[a]);
            r.events[a].clear();
        }
        r.step = step;
        self.open_step();
    }

    /// Bulk writers' saved values, as a step of their own.
    fn seal_bulk(&mut self) {
        self.r().bulk = false;
        let mut side = Vec::new();
        for (set_i, set) in self.attrs.all_mut().into_iter().enumerate() {
            for (ci, (_, c)) in set.cols.iter_mut().enumerate() {
                if let Some(rec) = c.seal_bulk() {
                    side.push(Side::Col {
                        set: set_i as u8,
                        col: ci as u32,
                        rec,
                    });
                }
            }
        }
        if side.is_empty() {
            return;
        }
        let mut step = Step {
            side: side.len() as u32,
            ..Step::default()
        };
        if self.r().tracking {
            self.track_forward(&step, &side);
        }
        if self.r().keeps_steps() {
            self.push_forward(&mut step, side, false);
        }
    }

    /// A forward step onto the undo log: the redo branch goes, the step
    /// joins the open group's unit or starts one.
    ///
    /// `direct`: the half-edge records are still in the page log and go
    /// straight from it into the undo log.
    fn push_forward(&mut self, step: &mut Step, side: Vec<Side>, direct: bool) {
        if !self.r().redo.is_empty() {
            self.drop_redo();
        }
        let r = self.rec.as_deref_mut().expect("no recorder");
        step.more = r.group_depth > 0 && r.group_started;
        if !step.more {
            if let Some(name) = r.group_name.clone().filter(|_| r.group_depth > 0) {
                let id = r.undo.next_id();
                r.undo.names.push((id, name));
            }
            r.undo.units += 1;
        }
        if r.group_depth > 0 {
            r.group_started = true;
        }
        if direct {
            let e0 = r.start[1] * 2;
            let pages = &mut r.he;
            let live = &self.he;
            let max = pages.saved_slots();
            codec::encode_with(
                step,
                &mut r.undo.bytes,
                Some((max, &mut |body: &mut Vec<u8>, w: &mut codec::HeWriter| {
                    pages.drain_changed(e0, live.as_slice(), |h, old| {
                        let h = Hid::new(h);
                        if let Some(mask) = changed_fields(live[h], old) {
                            w.push(body, h, mask, old);
                        }
                    });
                })),
            );
        } else {
            codec::encode(step, &mut r.undo.bytes);
        }
        for s in side {
            r.undo.push_side(s);
        }
        if r.group_depth == 0 {
            self.trim();
        }
    }

    /// Enforce the limits of the undo log (units from the bottom).
    pub(crate) fn trim(&mut self) {
        let r = self.rec.as_deref_mut().expect("no recorder");
        if r.tx_depth > 0 || r.group_depth > 0 {
            return;
        }
        let over = |r: &Recorder| {
            r.undo.units > 0
                && (r.max_units.is_some_and(|m| r.undo.units > m)
                    || r.max_bytes.is_some_and(|m| {
                        r.undo.units > 1
                            && r.undo.bytes.len() - r.undo.floor + r.undo.side_bytes > m
                    }))
        };
        let mut d = Step::default();
        while over(r) {
            // Drop the bottom unit: its first step and those that go on it.
            let mut pos = r.undo.floor;
            let mut first = true;
            while pos < r.undo.bytes.len() {
                let (end, body) = codec::first_step(&r.undo.bytes, pos);
                codec::decode(&r.undo.bytes[body], &mut d);
                if !first && !d.more {
                    break;
                }
                first = false;
                for _ in 0..d.side {
                    let s = r.undo.side.pop_front().expect("side record");
                    r.undo.side_bytes -= s.heap_bytes();
                }
                pos = end;
            }
            r.undo.floor = pos;
            r.undo.units -= 1;
            r.undo.trimmed += 1;
            let t = r.undo.trimmed;
            r.undo.names.retain(|(id, _)| *id >= t);
        }
        if r.undo.floor > 4096 && r.undo.floor * 2 > r.undo.bytes.len() {
            let f = r.undo.floor;
            r.undo.bytes.drain(..f);
            r.undo.floor = 0;
        }
    }

    /// Drop the redo branch: slots its births hold vacant go back on the
    /// free lists.
    pub(crate) fn drop_redo(&mut self) {
        let Some(r) = self.rec.as_deref_mut() else {
            return;
        };
        if r.redo.is_empty() {
            return;
        }
        let redo = std::mem::take(&mut r.redo);
        for (a, i) in held_births(&redo) {
            slots_of_mut(self, a).release(i);
        }
    }

    /// Tracking for a forward step (already applied).
    fn track_forward(&mut self, step: &Step, side: &[Side]) {
        let mut touches: Vec<(usize, u32)> = Vec::new();
        touches.extend(step.he.iter().map(|e| (1, e.0.edge().raw())));
        touches.extend(step.vh.iter().map(|e| (0, e.0.raw())));
        touches.extend(step.fl.iter().map(|e| (2, e.0.raw())));
        for a in 0..3 {
            let (s, c) = step.births[a];
            touches.extend((s..s + c).map(|i| (a, i)));
            touches.extend(step.events[a].iter().map(|e| match *e {
                SlotEvent::Death { slot, .. } | SlotEvent::Reuse { slot, .. } => (a, slot),
            }));
        }
        let mut col_touch = Vec::new();
        for s in side {
            match s {
                Side::Col { set, col, rec } => {
                    let (a, shift) = SET_ARENA[*set as usize];
                    touches.extend(rec.slots().map(|i| (a, i >> shift)));
                    let cols = self.attrs.all_mut();
                    let c = &cols[*set as usize];
                    if let Some(m) = c.meta.get(*col as usize) {
                        col_touch.push((*set, m.id, true, c.cols[*col as usize].0.clone()));
                    }
                }
                Side::Added { set, col } => {
                    let cols = self.attrs.all_mut();
                    let c = &cols[*set as usize];
                    col_touch.push((
                        *set,
                        c.meta[*col as usize].id,
                        false,
                        c.cols[*col as usize].0.clone(),
                    ));
                }
                Side::Removed {
                    set, meta, name, ..
                } => {
                    col_touch.push((*set, meta.id, true, name.clone()));
                }
                Side::Whole(_) => {}
            }
        }
        for (a, slot) in touches {
            if self.r().touched[a].contains_key(&slot) {
                continue;
            }
            // The generation at the start of the step.
            let baseline = if slot >= self.r().start[a] {
                0
            } else {
                match step.events[a].iter().find(|e| match **e {
                    SlotEvent::Death { slot: s, .. } | SlotEvent::Reuse { slot: s, .. } => {
                        s == slot
                    }
                }) {
                    Some(SlotEvent::Death { generation, .. }) => *generation,
                    Some(SlotEvent::Reuse { .. }) => 0,
                    None => gen(self, a, slot),
                }
            };
            self.r().touch(a, slot, baseline);
        }
        for (set, id, existed, name) in col_touch {
            self.r().touch_col(set, id, existed, &name);
        }
    }

    /// Tracking before applying a decoded step (undo or redo): every slot
    /// it touches, at its generation now.
    fn track_apply(&mut self, step: &Step, side: &[Side]) {
        let mut touches: Vec<(usize, u32)> = Vec::new();
        touches.extend(step.he.iter().map(|e| (1, e.0.edge().raw())));
        touches.extend(step.vh.iter().map(|e| (0, e.0.raw())));
        touches.extend(step.fl.iter().map(|e| (2, e.0.raw())));
        for a in 0..3 {
            let (s, c) = step.births[a];
            touches.extend((s..s + c).map(|i| (a, i)));
            touches.extend(step.events[a].iter().map(|e| match *e {
                SlotEvent::Death { slot, .. } | SlotEvent::Reuse { slot, .. } => (a, slot),
            }));
        }
        for s in side {
            match s {
                Side::Col { set, col, rec } => {
                    let (a, shift) = SET_ARENA[*set as usize];
                    touches.extend(rec.slots().map(|i| (a, i >> shift)));
                    let cols = self.attrs.all_mut();
                    let c = &cols[*set as usize];
                    let (id, name) = (c.meta[*col as usize].id, c.cols[*col as usize].0.clone());
                    self.r().touch_col(*set, id, true, &name);
                }
                Side::Added { set, col } => {
                    let cols = self.attrs.all_mut();
                    let c = &cols[*set as usize];
                    let (id, name) = (c.meta[*col as usize].id, c.cols[*col as usize].0.clone());
                    self.r().touch_col(*set, id, true, &name);
                }
                Side::Removed {
                    set, meta, name, ..
                } => {
                    let (set, id, name) = (*set, meta.id, name.clone());
                    self.r().touch_col(set, id, false, &name);
                }
                Side::Whole(_) => self.r().rebuilt = true,
            }
        }
        for (a, slot) in touches {
            let g = gen(self, a, slot);
            self.r().touch(a, slot, g);
        }
    }

    /// Pop one step from the `dir` source log (undo log for `Undo`), apply
    /// it, and push the swapped step onto the other log (or drop it, with
    /// `discard`: a rolled-back transaction). Returns whether the popped
    /// step ended its unit.
    fn apply_top(&mut self, dir: Dir, first_of_unit: bool, discard: bool) -> bool {
        let r = self.rec.as_deref_mut().expect("no recorder");
        let src = match dir {
            Dir::Undo => &mut r.undo,
            Dir::Redo => &mut r.redo,
        };
        let end = src.bytes.len();
        let (start, body) = codec::last_step(&src.bytes, end);
        let mut step = std::mem::take(&mut r.step);
        let src = match dir {
            Dir::Undo => &mut r.undo,
            Dir::Redo => &mut r.redo,
        };
        codec::decode(&src.bytes[body], &mut step);
        src.bytes.truncate(start);
        let mut side: Vec<Side> = (0..step.side).map(|_| src.pop_side()).collect();
        let ended = !step.more;
        if r.tracking {
            self.track_apply(&step, &side);
        }
        self.apply_step(&mut step, &mut side, dir);
        let r = self.rec.as_deref_mut().expect("no recorder");
        if discard {
            // The births this undo took back will never be redone.
            for a in 0..3 {
                let (s, c) = step.births[a];
                for i in (s..s + c).rev() {
                    slots_of_mut(self, a).release(i);
                }
            }
        } else {
            let r2 = &mut *r;
            let dst = match dir {
                Dir::Undo => &mut r2.redo,
                Dir::Redo => &mut r2.undo,
            };
            step.more = !first_of_unit;
            codec::encode(&step, &mut dst.bytes);
            for s in side {
                dst.push_side(s);
            }
        }
        let r = self.rec.as_deref_mut().expect("no recorder");
        r.step = step;
        ended
    }

    /// Swap a decoded step into the mesh.
    fn apply_step(&mut self, step: &mut Step, side: &mut [Side], dir: Dir) {
        for (h, mask, rec) in &mut step.he {
            let cur = self.he.unlogged_mut(*h);
            if *mask & ORIGIN != 0 {
                std::mem::swap(&mut cur.origin, &mut rec.origin);
            }
            if *mask & NEXT != 0 {
                std::mem::swap(&mut cur.next, &mut rec.next);
            }
            if *mask & FACE != 0 {
                std::mem::swap(&mut cur.face, &mut rec.face);
            }
        }
        for (v, h) in &mut step.vh {
            std::mem::swap(self.v_halfedge.unlogged_mut(*v), h);
        }
        for (f, l) in &mut step.fl {
            std::mem::swap(self.f_halfedge.unlogged_mut(*f), l);
        }
        // Side records were popped last first: that is undo order; redo
        // applies them the other way.
        match dir {
            Dir::Undo => {
                for s in side.iter_mut() {
                    self.apply_side(s);
                }
            }
            Dir::Redo => {
                for s in side.iter_mut().rev() {
                    self.apply_side(s);
                }
            }
        }
        for a in 0..3 {
            let (start, count) = step.births[a];
            let runs = &step.born_live[a];
            let slots = slots_of_mut(self, a);
            match dir {
                Dir::Undo => {
                    if !runs.is_empty() {
                        // New slots that died in the step are vacant at a
                        // generation above every key they had: they only
                        // leave the free list (held for a redo).
                        slots.hold_from(start);
                    }
                    for e in step.events[a].iter().rev() {
                        match *e {
                            SlotEvent::Reuse { slot, .. } => slots.unbirth(slot, true),
                            SlotEvent::Death { slot, generation } => {
                                slots.undeath(slot, generation)
                            }
                        }
                    }
                    for_born(start, count, runs, |i, live| {
                        if live {
                            slots.unbirth(i, false);
                        }
                    });
                    if let Some((before, _)) = step.states[a] {
                        slots.restore_state(before);
                    } else {
                        let s = slots.state();
                        slots.restore_state(s);
                    }
                }
                Dir::Redo => {
                    for_born(start, count, runs, |i, live| {
                        if live {
                            slots.rebirth(i, false);
                        }
                    });
                    for e in &step.events[a] {
                        match *e {
                            SlotEvent::Reuse { slot, generation } => {
                                slots.rebirth_at(slot, generation)
                            }
                            SlotEvent::Death { slot, .. } => slots.free(slot),
                        }
                    }
                    // New slots vacant at the seal go back on the free
                    // list, at the generation the step left them (undo
                    // did not move it).
                    for_born(start, count, runs, |i, live| {
                        if !live {
                            slots.release(i);
                        }
                    });
                    if let Some((_, after)) = step.states[a] {
                        slots.restore_state(after);
                    } else {
                        let s = slots.state();
                        slots.restore_state(s);
                    }
                }
            }
        }
        match dir {
            Dir::Undo => self.holes = (self.holes as i64 - step.holes) as usize,
            Dir::Redo => self.holes = (self.holes as i64 + step.holes) as usize,
        }
    }

    /// Apply one side record, turning it into its inverse.
    fn apply_side(&mut self, s: &mut Side) {
        match s {
            Side::Col { set, col, rec } => {
                let set = &mut self.attrs.all_mut()[*set as usize];
                let ok = set.cols[*col as usize].1.apply_record(rec.as_mut());
                debug_assert!(ok, "a column record of another type");
            }
            Side::Added { set, col } => {
                let (set_i, col_i) = (*set, *col);
                let position = set_i == 0 && self.attrs.position == Some(col_i as usize);
                let (name, column, meta) = self.attrs.take_column(set_i as usize, col_i as usize);
                *s = Side::Removed {
                    set: set_i,
                    col: col_i,
                    name,
                    column,
                    meta,
                    position,
                };
            }
            Side::Removed { .. } => {
                let Side::Removed {
                    set,
                    col,
                    name,
                    column,
                    meta,
                    position,
                } = std::mem::replace(s, Side::Added { set: 0, col: 0 })
                else {
                    unreachable!()
                };
                let len = self.slot_counts()[set as usize];
                self.attrs.insert_column(
                    set as usize,
                    col as usize,
                    name,
                    column,
                    meta,
                    position,
                    len,
                );
                *s = Side::Added { set, col };
            }
            Side::Whole(m) => {
                let rec = self.rec.take();
                // Keys the mesh being swapped out issued stay stale in the
                // one swapped in: raise its fresh floors above them.
                let highs = [
                    self.v_slots.highest_issued(),
                    self.e_slots.highest_issued(),
                    self.f_slots.highest_issued(),
                ];
                std::mem::swap(self, m.as_mut());
                for (a, h) in highs.into_iter().enumerate() {
                    let slots = slots_of_mut(self, a);
                    if h >= slots.base() {
                        slots.raise_fresh(h.saturating_add(2));
                    }
                }
                self.rec = rec;
            }
        }
    }

    /// Undo (or redo, by `dir`) one unit. `false`: the log was empty.
    pub(crate) fn move_unit(&mut self, dir: Dir) -> bool {
        self.seal();
        let r = self.r();
        let (src, dst) = match dir {
            Dir::Undo => (&mut r.undo, &mut r.redo),
            Dir::Redo => (&mut r.redo, &mut r.undo),
        };
        if src.is_empty() {
            return false;
        }
        let name = src.top_name().map(str::to_owned);
        if name.is_some() {
            src.names.pop();
        }
        src.units -= 1;
        if let Some(n) = name {
            let id = dst.next_id();
            dst.names.push((id, n));
        }
        dst.units += 1;
        let mut first = true;
        loop {
            let ended = self.apply_top(dir, first, false);
            first = false;
            if ended {
                break;
            }
        }
        self.open_step();
        true
    }

    /// Undo steps until the undo log is `len` bytes long, dropping what
    /// they undid (a transaction rolling back).
    pub(crate) fn roll_back_to(&mut self, len: usize) {
        self.seal();
        while self.r().undo.bytes.len() > len {
            self.apply_top(Dir::Undo, true, true);
        }
        self.open_step();
    }

    /// Record a wholesale rebuild `f` as one step holding the prior mesh.
    pub(crate) fn wholesale(&mut self, f: impl FnOnce(&mut Mesh)) {
        if self.rec.is_none() {
            f(self);
            return;
        }
        self.seal();
        let keeps = self.r().keeps_steps();
        if keeps {
            self.drop_redo();
        }
        let prior = keeps.then(|| Box::new(self.clone()));
        // The rebuild itself records nothing (its operators' ends would
        // seal steps of their own).
        let rec = self.rec.take();
        f(self);
        self.rec = rec;
        let r = self.r();
        if r.tracking {
            r.rebuilt = true;
            for t in &mut r.touched {
                t.clear();
            }
            r.cols.clear();
        }
        if let Some(prior) = prior {
            let mut step = Step {
                side: 1,
                ..Step::default()
            };
            self.push_forward(&mut step, vec![Side::Whole(prior)], false);
        }
        self.open_step();
    }

    /// Save a column's values in `range` for a bulk writer (a raw mutable
    /// view): the open step closes first, the writes become a step of
    /// their own at the next edit.
    pub(crate) fn save_bulk(&mut self, set: usize, col: usize, range: std::ops::Range<usize>) {
        if self.rec.is_none() {
            return;
        }
        self.seal();
        self.attrs.all_mut()[set].cols[col].1.save_bulk(range);
        self.r().bulk = true;
    }
}

impl Recorder {
    /// See [`Mesh::release_held_into`].
    pub(crate) fn release_held_into(&self, m: &mut Mesh) {
        if !self.redo.is_empty() {
            Mesh::release_held_into_impl(self, m);
        }
    }

    /// The undo name of the unit on top, if named.
    pub(crate) fn undo_name(&self) -> Option<&str> {
        self.undo.top_name()
    }

    /// The redo name of the unit on top, if named.
    pub(crate) fn redo_name(&self) -> Option<&str> {
        self.redo.top_name()
    }
}

impl Mesh {
    fn release_held_into_impl(r: &Recorder, m: &mut Mesh) {
        for (a, i) in held_births(&r.redo) {
            slots_of_mut(m, a).release(i);
        }
    }
}

/// The slots a redo log holds vacant in the mesh as it is: births of the
/// steps it would redo first, down to the first wholesale step (those
/// below it are slots of another mesh, which that step holds).
fn held_births(log: &Log) -> Vec<(usize, u32)> {
    let mut out = Vec::new();
    let mut d = Step::default();
    let mut end = log.bytes.len();
    let mut side = log.side.len();
    while end > log.floor {
        let (start, body) = codec::last_step(&log.bytes, end);
        codec::decode(&log.bytes[body], &mut d);
        let n = d.side as usize;
        if log
            .side
            .range(side - n..side)
            .any(|s| matches!(s, Side::Whole(_)))
        {
            break;
        }
        side -= n;
        for a in 0..3 {
            let (s0, count) = d.births[a];
            out.extend((s0..s0 + count).rev().map(|i| (a, i)));
        }
        end = start;
    }
    out
}
