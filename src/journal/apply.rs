//! Undo and redo: applying a logged step back to the mesh.
//!
//! Undo decodes the top step of the undo log ([`record`](crate::record)),
//! swaps every stored value with the mesh's (so the step now holds the
//! values redo puts back), reverses the slot events, and encodes the
//! swapped step onto the redo log. Redo is the same the other way. A
//! transaction rolls back by undoing to a mark and dropping what it undid.

use crate::keys::ElementKind;
use crate::mesh::Mesh;
use crate::record::{self, for_born, Arena, Recorder, Side, SlotEvent, Step, FACE, NEXT, ORIGIN};
use crate::slots::Slots;

/// Direction of an application.
#[derive(Copy, Clone, PartialEq, Eq)]
pub(crate) enum Dir {
    Undo,
    Redo,
}

fn slots_of_mut(m: &mut Mesh, a: Arena) -> &mut Slots {
    match a {
        Arena::Vertex => &mut m.v_slots,
        Arena::Edge => &mut m.e_slots,
        Arena::Face => &mut m.f_slots,
    }
}

impl Mesh {
    /// The recorder, which the caller knows is on.
    pub(super) fn r(&mut self) -> &mut Recorder {
        self.rec.as_deref_mut().expect("no recorder")
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

    /// Tracking before applying a decoded step (undo or redo): every slot
    /// it touches, at its generation now.
    fn track_apply(&mut self, step: &Step, side: &[Side]) {
        let mut touches = record::step_touches(step);
        for s in side {
            match s {
                Side::Col { set, col, rec } => {
                    let (a, shift) = Arena::of_set(*set);
                    touches.extend(rec.slots().map(|i| (a, i >> shift)));
                    let c = self.attrs.columns(*set);
                    let (id, name) = (c.meta[*col as usize].id, c.cols[*col as usize].0.clone());
                    self.r().touch_col(*set, id, true, &name);
                }
                Side::Added { set, col } => {
                    let c = self.attrs.columns(*set);
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
            let g = slots_of_mut(self, a).generation(slot as usize).unwrap_or(0);
            self.r().touch(a, slot, g);
        }
    }

    /// Pop one step from the `dir` source log (undo log for `Undo`), apply
    /// it, and push the swapped step onto the other log (or drop it, with
    /// `discard`: a rolled-back transaction). Returns whether the popped
    /// step ended its unit.
    fn apply_top(&mut self, dir: Dir, first_of_unit: bool, discard: bool) -> bool {
        let r = self.r();
        let mut step = std::mem::take(&mut r.step);
        let src = match dir {
            Dir::Undo => &mut r.undo,
            Dir::Redo => &mut r.redo,
        };
        let (start, body) = record::last_step(&src.bytes, src.bytes.len());
        record::decode(&src.bytes[body], &mut step);
        src.bytes.truncate(start);
        let mut side: Vec<Side> = (0..step.side).map(|_| src.pop_side()).collect();
        let ended = !step.more;
        if r.tracking {
            self.track_apply(&step, &side);
        }
        self.apply_step(&mut step, &mut side, dir);
        if discard {
            // The births this undo took back will never be redone.
            for a in Arena::ALL {
                let (s, c) = step.births[a];
                for i in (s..s + c).rev() {
                    slots_of_mut(self, a).release(i);
                }
            }
        } else {
            let r = self.r();
            let dst = match dir {
                Dir::Undo => &mut r.redo,
                Dir::Redo => &mut r.undo,
            };
            step.more = !first_of_unit;
            record::encode(&step, &mut dst.bytes);
            for s in side {
                dst.push_side(s);
            }
        }
        self.r().step = step;
        ended
    }

    /// Swap a decoded step into the mesh.
    fn apply_step(&mut self, step: &mut Step, side: &mut [Side], dir: Dir) {
        self.swap_links(step);
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
        for a in Arena::ALL {
            let slots = slots_of_mut(self, a);
            match dir {
                Dir::Undo => undo_slots(slots, step, a),
                Dir::Redo => redo_slots(slots, step, a),
            }
        }
        match dir {
            Dir::Undo => self.holes = (self.holes as i64 - step.holes) as usize,
            Dir::Redo => self.holes = (self.holes as i64 + step.holes) as usize,
        }
    }

    /// Swap the step's links with the mesh's.
    fn swap_links(&mut self, step: &mut Step) {
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
    }

    /// Apply one side record, turning it into its inverse.
    fn apply_side(&mut self, s: &mut Side) {
        match s {
            Side::Col { set, col, rec } => {
                let set = self.attrs.columns_mut(*set);
                let ok = set.cols[*col as usize].1.apply_record(rec.as_mut());
                debug_assert!(ok, "a column record of another type");
            }
            Side::Added { set, col } => {
                let (set_i, col_i) = (*set, *col);
                let position =
                    set_i == ElementKind::Vertex && self.attrs.position == Some(col_i as usize);
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
                } = std::mem::replace(
                    s,
                    Side::Added {
                        set: ElementKind::Vertex,
                        col: 0,
                    },
                )
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
                // Keys the mesh being swapped out issued stay stale in the
                // one swapped in: raise its fresh floors above them.
                let highs = [
                    self.v_slots.highest_issued(),
                    self.e_slots.highest_issued(),
                    self.f_slots.highest_issued(),
                ];
                self.swap_storage(m);
                for (a, h) in Arena::ALL.into_iter().zip(highs) {
                    let slots = slots_of_mut(self, a);
                    if h >= slots.base() {
                        slots.raise_fresh(h.saturating_add(2));
                    }
                }
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
}

/// Undo arena `a`'s slot events of `step`.
fn undo_slots(slots: &mut Slots, step: &Step, a: Arena) {
    let (start, count) = step.births[a];
    let runs = &step.born_live[a];
    if !runs.is_empty() {
        // New slots that died in the step are vacant at a generation
        // above every key they had: they only leave the free list (held
        // for a redo).
        slots.hold_from(start);
    }
    for e in step.events[a].iter().rev() {
        match *e {
            SlotEvent::Reuse { slot, .. } => slots.unbirth(slot, true),
            SlotEvent::Death { slot, generation } => slots.undeath(slot, generation),
        }
    }
    for_born(start, count, runs, |i, live| {
        if live {
            slots.unbirth(i, false);
        }
    });
    let state = step.states[a].map_or(slots.state(), |(before, _)| before);
    slots.restore_state(state);
}

/// Redo arena `a`'s slot events of `step`.
fn redo_slots(slots: &mut Slots, step: &Step, a: Arena) {
    let (start, count) = step.births[a];
    let runs = &step.born_live[a];
    for_born(start, count, runs, |i, live| {
        if live {
            slots.rebirth(i, false);
        }
    });
    for e in &step.events[a] {
        match *e {
            SlotEvent::Reuse { slot, generation } => slots.rebirth_at(slot, generation),
            SlotEvent::Death { slot, .. } => slots.free(slot),
        }
    }
    // New slots vacant at the seal go back on the free list, at the
    // generation the step left them (undo did not move it).
    for_born(start, count, runs, |i, live| {
        if !live {
            slots.release(i);
        }
    });
    let state = step.states[a].map_or(slots.state(), |(_, after)| after);
    slots.restore_state(state);
}
