//! The journal's primitives on an arena: undoing and redoing births,
//! deaths and reuses without ever reissuing a key, the fresh floor that
//! guarantees it, and the fast-path state an undo puts back (see the
//! parent module's docs, "Undo and the fresh floor").

use super::{Slots, State, MAX_LIVE_GENERATION};

impl Slots {
    /// The fast-path state, for the journal to restore.
    #[inline]
    pub(crate) fn state(&self) -> State {
        self.state
    }

    /// The fresh floor where an undo raised it above the base (`None`:
    /// it is the base), for serde.
    #[cfg(feature = "serde")]
    pub(crate) fn raised_fresh(&self) -> Option<u32> {
        (self.fresh != self.base).then_some(self.fresh)
    }

    /// The fresh floor (odd, at least the base).
    #[cfg(test)]
    pub(crate) fn fresh(&self) -> u32 {
        self.fresh
    }

    /// Set the fast-path state back to `state` after an undo or redo,
    /// weakened where the arena no longer allows it: vacant slots rule out
    /// `Intact`, a fresh floor above the base rules out `Pristine`.
    pub(crate) fn restore_state(&mut self, state: State) {
        let mut s = state;
        if s == State::Intact && self.live < self.slots {
            s = State::Pristine;
        }
        if self.fresh != self.base {
            s = State::Mixed;
        }
        if s != State::Intact {
            self.generations_mut();
        }
        self.state = s;
    }

    /// Raise the fresh floor to at least `g` (made odd), so that no
    /// generation below it is issued again. Capped at
    /// [`MAX_LIVE_GENERATION`]: only generations within two of 2^32, which
    /// only deserialized input carries, could then come back.
    pub(crate) fn raise_fresh(&mut self, g: u32) {
        let g = (g | 1).min(MAX_LIVE_GENERATION);
        if g > self.fresh {
            self.generations_mut();
            self.fresh = g;
            self.state = State::Mixed;
        }
    }

    /// Undo the birth of the element in slot `i`: the slot becomes vacant
    /// one generation above it (so its key stays stale even after a new
    /// edit reuses the slot). A slot that came from the free list goes
    /// back on it (`push`); a slot that was new is held vacant off the
    /// list, for a redo to revive ([`release`](Slots::release) lets it go).
    pub(crate) fn unbirth(&mut self, i: u32, push: bool) {
        self.generations_mut();
        let g = &mut self.generations[i as usize];
        debug_assert!(*g & 1 == 1, "undoing the birth of a vacant slot");
        *g += 1;
        self.live -= 1;
        if push && Self::reusable(*g) {
            self.free.push(i);
        }
    }

    /// Redo the birth [`unbirth`](Slots::unbirth) undid: the slot is live
    /// again at the same generation as before. `pop`: it was put back on
    /// the free list (and is on top of it).
    pub(crate) fn rebirth(&mut self, i: u32, pop: bool) {
        let g = &mut self.generations_mut()[i as usize];
        debug_assert!(*g & 1 == 0, "redoing the birth of a live slot");
        let reusable = Self::reusable(*g);
        *g -= 1;
        if pop && reusable {
            self.take_from_free(i);
        }
        self.live += 1;
    }

    /// Redo a reuse [`unbirth`](Slots::unbirth) undid: slot `i` is live
    /// again at `g`, the generation the reuse gave it (set, not derived:
    /// undoing an earlier death may have moved the slot's generation).
    pub(crate) fn rebirth_at(&mut self, i: u32, g: u32) {
        self.generations_mut();
        debug_assert!(
            self.generations[i as usize] & 1 == 0,
            "redoing the reuse of a live slot"
        );
        if Self::reusable(self.generations[i as usize]) {
            self.take_from_free(i);
        }
        self.generations[i as usize] = g;
        self.live += 1;
    }

    /// Take slot `i` off the free list: it is on top unless slots an
    /// undo held for a redo were released onto the list since.
    fn take_from_free(&mut self, i: u32) {
        if let Some(k) = self.free.iter().rposition(|&x| x == i) {
            self.free.remove(k);
        } else {
            debug_assert!(false, "slot {i} is not on the free list");
        }
    }

    /// Undo the death of the element that lived in slot `i` at generation
    /// `g`: it lives again with the same key. Its slot leaves the free list
    /// (it is on top, if its death put it there). When later elements in
    /// this slot were undone, the fresh floor rises above them.
    pub(crate) fn undeath(&mut self, i: u32, g: u32) {
        let current = self.generations_mut()[i as usize];
        debug_assert!(
            current & 1 == 0 && current > g,
            "undoing a death that did not happen"
        );
        if Self::reusable(g + 1) {
            self.take_from_free(i);
        }
        if current > g + 1 {
            self.raise_fresh(current + 1);
        }
        self.generations[i as usize] = g;
        self.live += 1;
    }

    /// The highest generation any slot holds (live or vacant), at least
    /// the fresh floor: every key this arena issued is at or below it.
    pub(crate) fn highest_issued(&self) -> u32 {
        self.highest_stored().max(self.fresh)
    }

    /// Take every slot from `start` on off the free list (an undo holds
    /// the slots its step created, vacant, for a redo). O(free list).
    #[inline]
    pub(crate) fn hold_from(&mut self, start: u32) {
        self.free.retain(|&i| i < start);
    }

    /// Put a vacant slot that [`unbirth`](Slots::unbirth) held for a redo
    /// back on the free list (the redo was dropped).
    pub(crate) fn release(&mut self, i: u32) {
        if let Some(g) = self.generation(i as usize) {
            if g & 1 == 0 && Self::reusable(g) {
                self.free.push(i);
            }
        }
    }
}
