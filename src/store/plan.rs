//! Rebuild plans: where every slot of a column rebuilt wholesale takes its
//! value from, in terms of the column as it was.
//!
//! Algorithms that build their result wholesale (subdivision) instead of
//! through the operators describe, for every slot of the new arena, which
//! old slots contribute and through which part of the column's
//! [`Rule`](super::rule::Rule). Every read sees the old column, so a plan
//! may read a slot that a later entry overwrites.

/// Where one new slot's value comes from. Slot numbers are the old
/// column's; weights and shares live in [`ColumnPlan::entries`].
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Source {
    /// The old slot's value, or its absence, unchanged.
    Copy(u32),
    /// `split(old[a], share)` where `entries[i] = (a, share)`: one piece of
    /// an element that split.
    Split(u32),
    /// `interpolate` over `entries[start..start + len]` (`(slot, weight)`):
    /// a new element made from others. `len == 0` is "interpolate of
    /// nothing" (what the operators give new edges).
    Interpolate {
        /// First entry.
        start: u32,
        /// Number of entries.
        len: u32,
    },
    /// Two pieces merged and split again, as `flip_edge` does with the faces
    /// beside the flipped edge: with `entries[i] = (a, sa)` and
    /// `entries[i + 1] = (b, sb)`, the value is
    /// `split(merge([(split(old[a], sa), ½), (split(old[b], sb), ½)]), ½)`.
    FlipPiece(u32),
}

/// The sources of every slot of a rebuilt column, in slot order.
#[derive(Clone, Debug, Default)]
pub(crate) struct ColumnPlan {
    /// One per slot of the new arena.
    pub(crate) sources: Vec<Source>,
    /// The `(old slot, weight or share)` pairs the sources point into.
    pub(crate) entries: Vec<(u32, f64)>,
}

impl ColumnPlan {
    /// An empty plan with room for `slots` sources.
    pub(crate) fn with_capacity(slots: usize, entries: usize) -> ColumnPlan {
        ColumnPlan {
            sources: Vec::with_capacity(slots),
            entries: Vec::with_capacity(entries),
        }
    }

    /// Append a slot that keeps old slot `i`.
    #[inline]
    pub(crate) fn copy(&mut self, i: u32) {
        self.sources.push(Source::Copy(i));
    }

    /// Append a slot that gets `split(old[i], share)`.
    #[inline]
    pub(crate) fn split(&mut self, i: u32, share: f64) {
        let at = self.entries.len() as u32;
        self.entries.push((i, share));
        self.sources.push(Source::Split(at));
    }

    /// Append a slot that gets `interpolate` of `inputs`.
    #[inline]
    pub(crate) fn interpolate(&mut self, inputs: impl IntoIterator<Item = (u32, f64)>) {
        let start = self.entries.len() as u32;
        self.entries.extend(inputs);
        let len = self.entries.len() as u32 - start;
        self.sources.push(Source::Interpolate { start, len });
    }

    /// Start a slot whose interpolation inputs are pushed one by one with
    /// [`push_input`](Self::push_input) and closed with
    /// [`end_interpolate`](Self::end_interpolate).
    #[inline]
    pub(crate) fn begin_interpolate(&mut self) -> u32 {
        self.entries.len() as u32
    }

    /// One more input of the slot begun with
    /// [`begin_interpolate`](Self::begin_interpolate).
    #[inline]
    pub(crate) fn push_input(&mut self, i: u32, w: f64) {
        self.entries.push((i, w));
    }

    /// Close the slot begun at `start`.
    #[inline]
    pub(crate) fn end_interpolate(&mut self, start: u32) {
        let len = self.entries.len() as u32 - start;
        self.sources.push(Source::Interpolate { start, len });
    }

    /// Append a slot that gets the flipped piece of `(a, sa)` and `(b, sb)`
    /// (see [`Source::FlipPiece`]).
    #[inline]
    pub(crate) fn flip_piece(&mut self, a: u32, sa: f64, b: u32, sb: f64) {
        let at = self.entries.len() as u32;
        self.entries.push((a, sa));
        self.entries.push((b, sb));
        self.sources.push(Source::FlipPiece(at));
    }

    /// Slots planned so far.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.sources.len()
    }
}
