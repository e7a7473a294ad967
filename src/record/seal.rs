//! Closing the open step: what changed since it opened goes onto the undo
//! log (while steps are kept) and into change tracking, and the next step
//! opens. Also the log's limits, and dropping the redo branch.
//!
//! Everything here works on the mesh's [`Storage`], lent by the mesh
//! (`Mesh::seal` and its siblings in `mesh/recording.rs`).

use super::codec::{self, SlotEvent, Step};
use super::recorder::{changed_fields, Log, Recorder, Side};
use super::{Arena, PerArena, Storage};
use crate::keys::ElementKind;
use crate::layout::{Fid, Hid, Vid};
use crate::slots::Slots;
use crate::store::AttrStore;

impl Recorder {
    /// Begin a new open step at the storage as it is.
    pub(crate) fn open_step(&mut self, s: &mut Storage<'_>) {
        let sc = s.slot_counts();
        s.attrs.vertex.log_below = sc[0];
        s.attrs.halfedge.log_below = sc[1];
        s.attrs.edge.log_below = sc[2];
        s.attrs.face.log_below = sc[3];
        self.start = PerArena::from_fn(|a| s.slots[a].slot_count() as u32);
        self.holes0 = s.holes;
        self.states0 = PerArena::from_fn(|a| s.slots[a].state());
    }

    /// Close the open step: encode it onto the undo log (while steps are
    /// kept), feed change tracking, and open the next.
    #[inline(never)]
    pub(crate) fn seal(&mut self, s: &mut Storage<'_>) {
        if self.bulk {
            self.seal_bulk(s);
        }
        let mut step = std::mem::take(&mut self.step);
        step.clear();
        let mut side = std::mem::take(&mut self.side);
        seal_columns(s.attrs, &mut side);
        self.seal_links(s, &mut step);
        self.seal_slots(s, &mut step);
        step.side = side.len() as u32;
        // The half-edge records: straight from the saved pages into the
        // undo log when nothing else reads them (no tracking) and the step
        // is kept anyway; otherwise into `step.he` first.
        let direct =
            !self.tracking && self.keeps_steps() && self.he.saved_slots() > 0 && !step.is_empty();
        if !direct {
            self.seal_halfedges(s, &mut step);
        }
        if !step.is_empty() || direct {
            if self.tracking {
                self.track_forward(s, &step, &side);
            }
            if self.keeps_steps() {
                self.push_forward(s, &mut step, side, direct);
            }
        }
        // Give the event lists back (their capacity) and open the next step.
        for a in Arena::ALL {
            std::mem::swap(&mut step.events[a], &mut self.events[a]);
            self.events[a].clear();
        }
        self.step = step;
        self.open_step(s);
    }

    /// The vertex and face links the open step saved and changed, in
    /// `step`, ascending by slot.
    fn seal_links(&mut self, s: &Storage<'_>, step: &mut Step) {
        let (v0, f0) = (self.start[Arena::Vertex], self.start[Arena::Face]);
        // Room for every saved slot at once (no regrowth of a large step).
        step.vh.reserve(self.vh.saved_slots());
        step.fl.reserve(self.fl.saved_slots());
        self.vh
            .drain_changed(v0, s.v_halfedge.as_slice(), |v, old| {
                step.vh.push((Vid::new(v), old));
            });
        self.fl
            .drain_changed(f0, s.f_halfedge.as_slice(), |f, old| {
                step.fl.push((Fid::new(f), old));
            });
    }

    /// The half-edge links the open step saved and changed (the fields
    /// that differ), in `step`, ascending by slot.
    fn seal_halfedges(&mut self, s: &Storage<'_>, step: &mut Step) {
        step.he.reserve(self.he.saved_slots());
        let live = s.he;
        self.he
            .drain_changed(self.start[Arena::Edge] * 2, live.as_slice(), |h, old| {
                let h = Hid::new(h);
                if let Some(mask) = changed_fields(live[h], old) {
                    step.he.push((h, mask, old));
                }
            });
    }

    /// Per arena: the new slots (and which of them are live), the deaths
    /// and reuses of older ones, the fast-path state; and the hole count.
    fn seal_slots(&mut self, s: &Storage<'_>, step: &mut Step) {
        for a in Arena::ALL {
            let slots = &*s.slots[a];
            let count = slots.slot_count() as u32;
            if count > self.start[a] {
                step.births[a] = (self.start[a], count - self.start[a]);
                if self.born_deaths[a] > 0 {
                    slots.live_runs(self.start[a]..count, &mut step.born_live[a]);
                }
            }
            self.born_deaths[a] = 0;
            std::mem::swap(&mut step.events[a], &mut self.events[a]);
            let state = slots.state();
            if state != self.states0[a] {
                step.states[a] = Some((self.states0[a], state));
            }
        }
        step.holes = s.holes as i64 - self.holes0 as i64;
    }

    /// Bulk writers' saved values, as a step of their own.
    fn seal_bulk(&mut self, s: &mut Storage<'_>) {
        self.bulk = false;
        let mut side = Vec::new();
        for (kind, set) in KINDS.into_iter().zip(s.attrs.all_mut()) {
            for (ci, (_, c)) in set.cols.iter_mut().enumerate() {
                if let Some(rec) = c.seal_bulk() {
                    side.push(Side::Col {
                        set: kind,
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
        if self.tracking {
            self.track_forward(s, &step, &side);
        }
        if self.keeps_steps() {
            self.push_forward(s, &mut step, side, false);
        }
    }

    /// A forward step onto the undo log: the redo branch goes, the step
    /// joins the open group's unit or starts one.
    ///
    /// `direct`: the half-edge records are still in the page log and go
    /// straight from it into the undo log.
    pub(crate) fn push_forward(
        &mut self,
        s: &mut Storage<'_>,
        step: &mut Step,
        side: Vec<Side>,
        direct: bool,
    ) {
        if !self.redo.is_empty() {
            self.drop_redo(s);
        }
        step.more = self.group_depth > 0 && self.group_started;
        if !step.more {
            if let Some(name) = self.group_name.clone().filter(|_| self.group_depth > 0) {
                let id = self.undo.next_id();
                self.undo.names.push((id, name));
            }
            self.undo.units += 1;
        }
        if self.group_depth > 0 {
            self.group_started = true;
        }
        if direct {
            let e0 = self.start[Arena::Edge] * 2;
            let pages = &mut self.he;
            let live = s.he;
            let max = pages.saved_slots();
            codec::encode_with(
                step,
                &mut self.undo.bytes,
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
            codec::encode(step, &mut self.undo.bytes);
        }
        for s in side {
            self.undo.push_side(s);
        }
        if self.group_depth == 0 {
            self.trim();
        }
    }

    /// Enforce the limits of the undo log (units from the bottom).
    pub(crate) fn trim(&mut self) {
        if self.tx_depth > 0 || self.group_depth > 0 {
            return;
        }
        let mut d = Step::default();
        while self.over_limits() {
            // Drop the bottom unit: its first step and those that go on it.
            let log = &mut self.undo;
            let mut pos = log.floor;
            let mut first = true;
            while pos < log.bytes.len() {
                let (end, body) = codec::first_step(&log.bytes, pos);
                codec::decode(&log.bytes[body], &mut d);
                if !first && !d.more {
                    break;
                }
                first = false;
                for _ in 0..d.side {
                    let s = log.side.pop_front().expect("side record");
                    log.side_bytes -= s.heap_bytes();
                }
                pos = end;
            }
            log.floor = pos;
            log.units -= 1;
            log.trimmed += 1;
            let t = log.trimmed;
            log.names.retain(|(id, _)| *id >= t);
        }
        let log = &mut self.undo;
        if log.floor > 4096 && log.floor * 2 > log.bytes.len() {
            let f = log.floor;
            log.bytes.drain(..f);
            log.floor = 0;
        }
    }

    /// Whether the undo log is past a limit (it keeps its last unit).
    fn over_limits(&self) -> bool {
        let u = &self.undo;
        u.units > 0
            && (self.max_units.is_some_and(|m| u.units > m)
                || self
                    .max_bytes
                    .is_some_and(|m| u.units > 1 && u.bytes.len() - u.floor + u.side_bytes > m))
    }

    /// Drop the redo branch: slots its births hold vacant go back on the
    /// free lists.
    pub(crate) fn drop_redo(&mut self, s: &mut Storage<'_>) {
        if self.redo.is_empty() {
            return;
        }
        let redo = std::mem::take(&mut self.redo);
        for (a, i) in held_births(&redo) {
            s.slots[a].release(i);
        }
    }

    /// Put the slots the redo log holds vacant back on the free lists of
    /// `slots`: a copy of the mesh has no redo log.
    pub(crate) fn release_held_into(&self, mut slots: PerArena<&mut Slots>) {
        if self.redo.is_empty() {
            return;
        }
        for (a, i) in held_births(&self.redo) {
            slots[a].release(i);
        }
    }

    /// Save a column's values in `range` for a bulk writer (a raw mutable
    /// view): the open step closes first, the writes become a step of
    /// their own at the next edit.
    pub(crate) fn save_bulk(
        &mut self,
        s: &mut Storage<'_>,
        set: ElementKind,
        col: usize,
        range: std::ops::Range<usize>,
    ) {
        self.seal(s);
        s.attrs.columns_mut(set).cols[col].1.save_bulk(range);
        self.bulk = true;
    }

    /// Tracking for a forward step (already applied).
    fn track_forward(&mut self, s: &mut Storage<'_>, step: &Step, side: &[Side]) {
        let mut touches = step_touches(step);
        let col_touch = side_touches(s.attrs, side, &mut touches);
        for (a, slot) in touches {
            if self.touched[a].contains_key(&slot) {
                continue;
            }
            // The generation at the start of the step.
            let baseline = if slot >= self.start[a] {
                0
            } else {
                match step.events[a].iter().find(|e| match **e {
                    SlotEvent::Death { slot: x, .. } | SlotEvent::Reuse { slot: x, .. } => {
                        x == slot
                    }
                }) {
                    Some(SlotEvent::Death { generation, .. }) => *generation,
                    Some(SlotEvent::Reuse { .. }) => 0,
                    None => s.generation(a, slot),
                }
            };
            self.touch(a, slot, baseline);
        }
        for (set, id, existed, name) in col_touch {
            self.touch_col(set, id, existed, &name);
        }
    }
}

/// The column sets in [`AttrStore::all_mut`] order.
const KINDS: [ElementKind; 4] = [
    ElementKind::Vertex,
    ElementKind::Halfedge,
    ElementKind::Edge,
    ElementKind::Face,
];

/// Every column's saved values (a set whose columns saved nothing is
/// passed over), as side records.
fn seal_columns(attrs: &mut AttrStore, side: &mut Vec<Side>) {
    for (kind, set) in KINDS.into_iter().zip(attrs.all_mut()) {
        if !set.dirty {
            continue;
        }
        set.dirty = false;
        for (ci, (_, c)) in set.cols.iter_mut().enumerate() {
            if let Some(rec) = c.seal_saved() {
                side.push(Side::Col {
                    set: kind,
                    col: ci as u32,
                    rec,
                });
            }
        }
    }
}

/// The `(arena, slot)`s whose links or slot a step touched.
pub(crate) fn step_touches(step: &Step) -> Vec<(Arena, u32)> {
    let mut touches: Vec<(Arena, u32)> = Vec::new();
    touches.extend(step.he.iter().map(|e| (Arena::Edge, e.0.edge().raw())));
    touches.extend(step.vh.iter().map(|e| (Arena::Vertex, e.0.raw())));
    touches.extend(step.fl.iter().map(|e| (Arena::Face, e.0.raw())));
    for a in Arena::ALL {
        let (s, c) = step.births[a];
        touches.extend((s..s + c).map(|i| (a, i)));
        touches.extend(step.events[a].iter().map(|e| match *e {
            SlotEvent::Death { slot, .. } | SlotEvent::Reuse { slot, .. } => (a, slot),
        }));
    }
    touches
}

/// The slots a forward step's side records wrote (added to `touches`), and
/// the columns they touched: `(set, column id, existed before, name)`.
fn side_touches(
    attrs: &AttrStore,
    side: &[Side],
    touches: &mut Vec<(Arena, u32)>,
) -> Vec<(ElementKind, u64, bool, String)> {
    let mut col_touch = Vec::new();
    for s in side {
        match s {
            Side::Col { set, col, rec } => {
                let (a, shift) = Arena::of_set(*set);
                touches.extend(rec.slots().map(|i| (a, i >> shift)));
                let c = attrs.columns(*set);
                if let Some(m) = c.meta.get(*col as usize) {
                    col_touch.push((*set, m.id, true, c.cols[*col as usize].0.clone()));
                }
            }
            Side::Added { set, col } => {
                let c = attrs.columns(*set);
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
    col_touch
}

/// The slots a redo log holds vacant in the mesh as it is: births of the
/// steps it would redo first, down to the first wholesale step (those
/// below it are slots of another mesh, which that step holds).
fn held_births(log: &Log) -> Vec<(Arena, u32)> {
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
        for a in Arena::ALL {
            let (s0, count) = d.births[a];
            out.extend((s0..s0 + count).rev().map(|i| (a, i)));
        }
        end = start;
    }
    out
}
