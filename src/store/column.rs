//! One attribute column: a value per slot of one arena, plus presence.

use std::any::Any;
use std::marker::PhantomData;
use std::sync::atomic::{AtomicU64, Ordering};

use super::attribute::Attribute;
use super::plan::{ColumnPlan, Source};
use super::rule::Rule;
use super::value::Value;
use crate::error::RuleError;

/// A rule's merge or interpolate, as a function (`U`: `Option<T>`, or a
/// fallible rule's `Result`).
type RuleFn<T, U = Option<T>> = fn(&[(Option<&T>, f64)]) -> U;

/// What a [fallible](Rule::FALLIBLE) rule's `try_` function gives.
type Tried<T> = Result<Option<T>, RuleError>;

/// Failures are numbered in the order they happen (in the whole process),
/// so the edit around several failed columns reports the first.
static NEXT_FAILURE: AtomicU64 = AtomicU64::new(0);

/// A fallible rule's failure, kept by its column until the edit around it
/// takes it ([`ErasedColumn::take_failure`]).
#[derive(Clone, Debug)]
pub(crate) struct Failure {
    /// When it happened, in the order of [`NEXT_FAILURE`].
    pub(crate) seq: u64,
    /// What the rule said.
    pub(crate) error: RuleError,
}

impl Failure {
    fn new(error: RuleError) -> Box<Failure> {
        Box::new(Failure {
            seq: NEXT_FAILURE.fetch_add(1, Ordering::Relaxed),
            error,
        })
    }
}

/// The values of one attribute for every slot of one arena.
///
/// Values sit in a plain `Vec<T>` indexed by slot. Presence is a bitset that
/// exists only once some live slot lacks a value: a column where every
/// element has a value (positions, usually) costs exactly `size_of::<T>()`
/// per slot. New slots hold `T::default()` and count as present until the
/// operation that made them runs the rule, which every operation does
/// before it returns.
#[derive(Debug)]
pub struct Column<T, R> {
    pub(crate) values: Vec<T>,
    /// Bit `i` set = slot `i` has a value. `None` = every slot has one.
    pub(crate) present: Option<Vec<u64>>,
    /// While `present` exists: how many of slots `0..len` have their bit
    /// clear. The bits are dropped when it reaches zero, so a column whose
    /// every slot got a value again (key by key, in bulk or by undo) is
    /// dense again and bulk reads take it whole.
    pub(crate) absent: usize,
    /// While a journal records: the old values of the open step's writes,
    /// oldest first, one entry per write ([`journal`](crate::journal)).
    pub(crate) saved: Vec<Saved<T>>,
    /// Old values saved by bulk writers (mutable views, raw slices), sealed
    /// as a step of their own before the next edit's.
    pub(crate) bulk: Vec<Saved<T>>,
    /// A [fallible](Rule::FALLIBLE) rule's first failure in the running
    /// edit; while it is kept, the rule is not called again (results are
    /// absent: the edit is rolled back).
    failure: Option<Box<Failure>>,
    rule: PhantomData<fn() -> R>,
}

/// One slot's value (or absence) as it was before a write.
#[derive(Clone, Debug)]
pub(crate) struct Saved<T> {
    pub(crate) slot: u32,
    pub(crate) present: bool,
    pub(crate) value: T,
}

/// A sealed record of one column in one step: unique slots, ascending, each
/// with the value to put back. Applying it swaps every value with the
/// column's, so the same record then holds what applying it again restores:
/// undo turns it into the redo record and back, with no allocation.
pub(crate) struct ColumnRecord<T> {
    pub(crate) entries: Vec<Saved<T>>,
}

impl<T: Clone, R> Clone for Column<T, R> {
    /// A copy of the values; whatever a journal saved stays behind.
    fn clone(&self) -> Self {
        Column {
            values: crate::layout::to_vec_with_headroom(&self.values),
            present: self.present.clone(),
            absent: self.absent,
            saved: Vec::new(),
            bulk: Vec::new(),
            failure: None,
            rule: PhantomData,
        }
    }
}

impl<T: Default + Clone, R> Column<T, R> {
    /// A column of `len` absent values.
    pub(crate) fn absent(len: usize) -> Self {
        Column {
            values: vec![T::default(); len],
            present: (len > 0).then(|| vec![0; len.div_ceil(64)]),
            absent: len,
            saved: Vec::new(),
            bulk: Vec::new(),
            failure: None,
            rule: PhantomData,
        }
    }

    /// A column whose every slot has the given value.
    pub(crate) fn dense(values: Vec<T>) -> Self {
        Column {
            values,
            present: None,
            absent: 0,
            saved: Vec::new(),
            bulk: Vec::new(),
            failure: None,
            rule: PhantomData,
        }
    }

    /// Slot `i` as it is now, for a journal.
    #[inline]
    pub(crate) fn saved_of(&self, i: usize) -> Saved<T> {
        Saved {
            slot: i as u32,
            present: self.has(i),
            value: self.values[i].clone(),
        }
    }

    /// Save slot `i`'s value before a write (the open step's journal).
    #[inline]
    pub(crate) fn save(&mut self, i: usize) {
        let s = self.saved_of(i);
        self.saved.push(s);
    }

    /// Save slots `range` for a bulk writer (mutable view, raw slice).
    pub(crate) fn save_bulk(&mut self, range: std::ops::Range<usize>) {
        let range = range.start.min(self.values.len())..range.end.min(self.values.len());
        self.bulk.reserve(range.len());
        for i in range {
            let s = self.saved_of(i);
            self.bulk.push(s);
        }
    }

    /// Put slot `i` back to `(present, value)`, handing back what it held.
    #[inline]
    fn swap_in(&mut self, e: &mut Saved<T>) {
        let i = e.slot as usize;
        let was = self.has(i);
        std::mem::swap(&mut self.values[i], &mut e.value);
        let len = self.values.len();
        mark(&mut self.present, &mut self.absent, len, i, e.present);
        e.present = was;
    }
}

/// Set (`present`) or clear slot `i`'s presence bit in a column of `len`
/// slots, keeping `absent` (the count of clear bits) exact: clearing a bit
/// of a dense column makes its bits (all set but `i`); setting the last
/// clear bit drops them (every slot has a value: dense again).
#[inline]
pub(crate) fn mark(
    bits: &mut Option<Vec<u64>>,
    absent: &mut usize,
    len: usize,
    i: usize,
    present: bool,
) {
    let (word, bit) = (i / 64, 1u64 << (i % 64));
    match bits {
        Some(b) => {
            let was = b[word] & bit != 0;
            if present && !was {
                b[word] |= bit;
                *absent -= 1;
                if *absent == 0 {
                    *bits = None;
                }
            } else if !present && was {
                b[word] &= !bit;
                *absent += 1;
            }
        }
        None if !present => {
            let mut b = vec![u64::MAX; len.div_ceil(64)];
            b[word] &= !bit;
            *bits = Some(b);
            *absent = 1;
        }
        None => {}
    }
}

/// Sort saved entries by slot, keeping the first (oldest) of each slot.
fn first_per_slot<T>(entries: &mut Vec<Saved<T>>) {
    // Stable: of equal slots the oldest stays first.
    entries.sort_by_key(|e| e.slot);
    entries.dedup_by_key(|e| e.slot);
}

impl<T: Default + Clone, R> Column<T, R> {
    /// The value of slot `i`, if it has one. The caller checked liveness.
    #[inline]
    pub(crate) fn get(&self, i: usize) -> Option<&T> {
        match &self.present {
            None => self.values.get(i),
            Some(bits) => {
                if bits.get(i / 64).is_some_and(|w| w >> (i % 64) & 1 == 1) {
                    self.values.get(i)
                } else {
                    None
                }
            }
        }
    }

    /// Whether slot `i` holds a value.
    #[inline]
    pub(crate) fn has(&self, i: usize) -> bool {
        match &self.present {
            None => i < self.values.len(),
            Some(bits) => bits.get(i / 64).is_some_and(|w| w >> (i % 64) & 1 == 1),
        }
    }

    /// Set or clear slot `i`'s value.
    #[inline]
    pub(crate) fn set(&mut self, i: usize, value: Option<T>) {
        let has = value.is_some();
        match value {
            Some(v) => self.values[i] = v,
            None => self.values[i] = T::default(),
        }
        let len = self.values.len();
        mark(&mut self.present, &mut self.absent, len, i, has);
    }

    /// The raw values, indexed by slot (vacant and absent slots hold
    /// defaults).
    pub(crate) fn raw(&self) -> &[T] {
        &self.values
    }

    /// Run `rule` on the values of `inputs` (slot, weight), in order. Up to
    /// eight contributors (every operator but the merges of whole rings)
    /// need no allocation.
    #[inline(always)]
    fn with_inputs<U>(&self, inputs: &[(usize, f64)], rule: RuleFn<T, U>) -> U {
        const SMALL: usize = 8;
        if inputs.len() <= SMALL {
            let mut args: [(Option<&T>, f64); SMALL] = [(None, 0.0); SMALL];
            for (a, &(s, w)) in args.iter_mut().zip(inputs) {
                *a = (self.get(s), w);
            }
            rule(&args[..inputs.len()])
        } else {
            let args: Vec<(Option<&T>, f64)> =
                inputs.iter().map(|&(s, w)| (self.get(s), w)).collect();
            rule(&args)
        }
    }

    /// As [`with_inputs`](Self::with_inputs), for `(u32 slot, weight)`
    /// pairs (a [`ColumnPlan`]'s entries).
    #[inline]
    fn with_u32_inputs<U>(&self, inputs: &[(u32, f64)], rule: RuleFn<T, U>) -> U {
        const SMALL: usize = 16;
        if inputs.len() <= SMALL {
            let mut args: [(Option<&T>, f64); SMALL] = [(None, 0.0); SMALL];
            for (a, &(s, w)) in args.iter_mut().zip(inputs) {
                *a = (self.get(s as usize), w);
            }
            rule(&args[..inputs.len()])
        } else {
            let args: Vec<(Option<&T>, f64)> = inputs
                .iter()
                .map(|&(s, w)| (self.get(s as usize), w))
                .collect();
            rule(&args)
        }
    }

    /// A [fallible](Rule::FALLIBLE) rule's result: what `run` gives, or
    /// absent when it fails (the failure kept, the first only) or when an
    /// earlier failure is kept (`run` is not called).
    #[cold]
    fn tried(&mut self, run: impl FnOnce(&Self) -> Tried<T>) -> Option<T> {
        if self.failure.is_some() {
            return None;
        }
        run(self).unwrap_or_else(|e| {
            self.failure = Some(Failure::new(e));
            None
        })
    }

    /// The presence bits (`None`: every slot has a value).
    #[inline]
    pub(crate) fn present_bits(&self) -> Option<&[u64]> {
        self.present.as_deref()
    }

    /// The raw values, mutably. Writes through it are not journaled: use
    /// it only after [`save_bulk`](Column::save_bulk) on the range written,
    /// or on a column no journal watches.
    pub(crate) fn raw_mut(&mut self) -> &mut [T] {
        &mut self.values
    }
}

impl<T: Attribute, R> Column<T, R> {
    /// Whether slot `i` holds what `e` saved.
    #[inline]
    fn unchanged(&self, e: &Saved<T>) -> bool {
        self.holds(e.slot as usize, e.present.then_some(&e.value))
    }

    /// Whether slot `i` holds `value` (`None`: no value), by
    /// [`Attribute::same_value`]: the test the seal drops saved values by.
    fn holds(&self, i: usize, value: Option<&T>) -> bool {
        match value {
            None => !self.has(i),
            Some(v) => self.has(i) && self.values[i].same_value(v),
        }
    }

    /// Seal the open step's saved values: the oldest per slot, left out
    /// where the slot holds the same again. `None`: nothing changed.
    pub(crate) fn seal_saved(&mut self) -> Option<ColumnRecord<T>> {
        if self.saved.is_empty() {
            return None;
        }
        let mut entries = std::mem::take(&mut self.saved);
        first_per_slot(&mut entries);
        entries.retain(|e| !self.unchanged(e));
        // A record is kept until its step leaves the history, and its
        // capacity counts in the history's memory: no slack from growth.
        if entries.capacity() > entries.len() + entries.len() / 8 {
            entries.shrink_to_fit();
        }
        // The scratch keeps its capacity for the next step.
        self.saved = Vec::with_capacity(entries.capacity().min(64));
        (!entries.is_empty()).then_some(ColumnRecord { entries })
    }

    /// Seal the bulk writers' saved values as a record of their own. A
    /// slot that the open step saved since is compared with that saved
    /// value (what the bulk write left), not with the current one.
    pub(crate) fn seal_bulk(&mut self) -> Option<ColumnRecord<T>> {
        if self.bulk.is_empty() {
            return None;
        }
        let mut entries = std::mem::take(&mut self.bulk);
        first_per_slot(&mut entries);
        if !self.saved.is_empty() {
            first_per_slot(&mut self.saved);
        }
        let saved = &self.saved;
        entries.retain(|e| match saved.binary_search_by_key(&e.slot, |s| s.slot) {
            Ok(k) => {
                let s = &saved[k];
                !(s.present == e.present && (!e.present || s.value.same_value(&e.value)))
            }
            Err(_) => !self.unchanged(e),
        });
        (!entries.is_empty()).then_some(ColumnRecord { entries })
    }

    /// Apply a record (undo or redo): every slot gets the record's value,
    /// and the record gets the slot's.
    pub(crate) fn apply_record(&mut self, record: &mut ColumnRecord<T>) {
        for e in &mut record.entries {
            self.swap_in(e);
        }
    }
}

/// A sealed column record with its value type erased, as the journal keeps
/// it.
pub(crate) trait Record: Any + Send + Sync {
    /// The slots it holds, ascending.
    fn slots(&self) -> Box<dyn Iterator<Item = u32> + '_>;
    /// Heap bytes held.
    fn heap_bytes(&self) -> usize;
    /// Upcast for the typed column.
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

impl<T: Send + Sync + 'static> Record for ColumnRecord<T> {
    fn slots(&self) -> Box<dyn Iterator<Item = u32> + '_> {
        Box::new(self.entries.iter().map(|e| e.slot))
    }

    fn heap_bytes(&self) -> usize {
        self.entries.capacity() * std::mem::size_of::<Saved<T>>()
    }

    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// A column with its type erased, as the mesh stores it: the operations
/// every topological edit runs on every column.
pub(crate) trait ErasedColumn: Any + Send + Sync {
    /// Slots held.
    fn len(&self) -> usize;
    /// Grow to `len` slots; new slots hold the default value.
    fn ensure_len(&mut self, len: usize);
    /// Slot `i`'s element was removed: drop its value.
    fn clear(&mut self, i: usize);
    /// Run the rule's merge: `dst` gets the merge of `inputs` (slot, weight).
    fn merge(&mut self, dst: usize, inputs: &[(usize, f64)]);
    /// [`merge`](ErasedColumn::merge) while a journal records: `dst`'s
    /// value is saved first unless the merge leaves the same value (by
    /// [`Attribute::same_value`], as the seal compares). Whether it saved.
    fn merge_saving(&mut self, dst: usize, inputs: &[(usize, f64)]) -> bool;
    /// Run the rule's interpolate: `dst` is made from `inputs`.
    fn interpolate(&mut self, dst: usize, inputs: &[(usize, f64)]);
    /// Run the rule's interpolate for every `(dst, start, end)` job, of
    /// `inputs[start..end]`, all read before any is written (a job may read
    /// another's destination).
    fn interpolate_all(&mut self, jobs: &[(usize, u32, u32)], inputs: &[(usize, f64)]);
    /// Run the rule's split: each `(slot, share)` piece from `src`. `src`
    /// may be among the pieces; its old value is read first.
    fn split(&mut self, src: usize, pieces: &[(usize, f64)]);
    /// Copy slot `from`'s value (or absence) to slot `to`.
    fn copy(&mut self, from: usize, to: usize);
    /// Whether slots `i` and `j` hold the same value (both absent counts as
    /// the same), by [`Attribute::same_value`].
    fn same(&self, i: usize, j: usize) -> bool;
    /// Reorder: slot `i` of the result holds old slot `order[i]`.
    fn permute(&mut self, order: &[u32]);
    /// A new column of the same type and rule, one slot per source of
    /// `plan`, each computed from this column as it is (see
    /// [`Source`]). Dense (no presence bits) when every slot gets a value.
    fn rebuilt(&self, plan: &ColumnPlan) -> Box<dyn ErasedColumn>;
    /// Whether the rule's interpolation is a weighted mean
    /// ([`Rule::LINEAR`]).
    fn interpolates_linearly(&self) -> bool;
    /// Whether the rule can fail ([`Rule::FALLIBLE`]).
    fn may_fail(&self) -> bool;
    /// The rule's name ([`Rule::name`]).
    fn rule_name(&self) -> &'static str;
    /// The failure of the rule kept since the running edit began, if any.
    fn failure(&self) -> Option<&Failure>;
    /// Take the kept failure: the rule runs again.
    fn take_failure(&mut self) -> Option<Box<Failure>>;
    /// Set slot `dst` to the rule's `interpolate` of `inputs` (slot,
    /// weight) read from `src`, a column of the same type and rule (of
    /// another mesh); `false`, changing nothing, when `src` is not.
    fn interpolate_from(
        &mut self,
        src: &dyn ErasedColumn,
        dst: usize,
        inputs: &[(usize, f64)],
    ) -> bool;
    /// Save slot `i`'s value before a write (the journal's open step).
    fn save(&mut self, i: usize);
    /// Save slots `range` for a bulk writer.
    fn save_bulk(&mut self, range: std::ops::Range<usize>);
    /// Seal the open step's saved values (see [`Column::seal_saved`]).
    fn seal_saved(&mut self) -> Option<Box<dyn Record>>;
    /// Seal the bulk writers' saved values (see [`Column::seal_bulk`]).
    fn seal_bulk(&mut self) -> Option<Box<dyn Record>>;
    /// Forget whatever was saved (the journal stopped).
    fn discard_saved(&mut self);
    /// Apply a record sealed from a column of this type: `false` if it is
    /// of another type (nothing changes).
    fn apply_record(&mut self, record: &mut dyn Record) -> bool;
    /// Heap bytes held.
    fn heap_bytes(&self) -> usize;
    /// Slot `i`'s value as a dynamic [`Value`] (`None`: absent, or the type
    /// is not portable).
    fn value_at(&self, i: usize) -> Option<Value>;
    /// Set slot `i` from a dynamic value (`None` clears it). `false` if the
    /// value does not convert to the column's type (nothing changes).
    fn set_value(&mut self, i: usize, value: Option<&Value>) -> bool;
    /// The [`ValueType`](super::ValueType) values convert to (for serde
    /// and file formats); `None` if they do not convert.
    fn portable_type(&self) -> Option<super::ValueType>;
    /// The full names of the value type and the rule type, from which the
    /// registry makes the key typed columns are registered under for
    /// deserialization.
    #[cfg(feature = "serde")]
    fn type_names(&self) -> (&'static str, &'static str);
    /// A boxed deep copy.
    fn clone_box(&self) -> Box<dyn ErasedColumn>;
    /// The value type's name, for errors and listings.
    fn type_name(&self) -> &'static str;
    /// Upcast for typed access.
    fn as_any(&self) -> &dyn Any;
    /// Upcast for typed access.
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

impl<T: Attribute, R: Rule<T>> Column<T, R> {
    /// [`ErasedColumn::rebuilt`]'s value of one new slot for a
    /// [fallible](Rule::FALLIBLE) rule: absent once `failure` holds one (the
    /// first failure is kept there).
    #[cold]
    fn rebuilt_tried(
        &self,
        source: Source,
        entries: &[(u32, f64)],
        failure: &mut Option<Box<Failure>>,
    ) -> Option<T> {
        if failure.is_some() {
            return None;
        }
        let value = match source {
            Source::Copy(from) => Ok(self.get(from as usize).cloned()),
            Source::Split(at) => {
                let (from, share) = entries[at as usize];
                R::try_split(self.get(from as usize), share)
            }
            Source::Interpolate { start, len } => {
                let inputs = &entries[start as usize..(start + len) as usize];
                self.with_u32_inputs(inputs, R::try_interpolate)
            }
            Source::FlipPiece(at) => (|| {
                let (a, sa) = entries[at as usize];
                let (b, sb) = entries[at as usize + 1];
                let pa = R::try_split(self.get(a as usize), sa)?;
                let pb = R::try_split(self.get(b as usize), sb)?;
                let merged = R::try_merge(&[(pa.as_ref(), 0.5), (pb.as_ref(), 0.5)])?;
                R::try_split(merged.as_ref(), 0.5)
            })(),
        };
        value.unwrap_or_else(|e| {
            *failure = Some(Failure::new(e));
            None
        })
    }
}

impl<T, R> ErasedColumn for Column<T, R>
where
    T: Attribute,
    R: Rule<T>,
{
    fn len(&self) -> usize {
        self.values.len()
    }

    fn ensure_len(&mut self, len: usize) {
        if self.values.len() < len {
            let old_len = self.values.len();
            self.values.resize(len, T::default());
            if let Some(bits) = &mut self.present {
                // New slots count as present until their rule runs.
                bits.resize(len.div_ceil(64), 0);
                for i in old_len..len {
                    bits[i / 64] |= 1 << (i % 64);
                }
            }
        }
    }

    fn clear(&mut self, i: usize) {
        if i < self.values.len() {
            self.values[i] = T::default();
            // A dense column stays dense: a vacant slot's presence is never
            // read (keys to it are stale), and every operation that reuses
            // the slot runs the rule on it.
            if self.present.is_some() {
                let len = self.values.len();
                mark(&mut self.present, &mut self.absent, len, i, false);
            }
        }
    }

    fn merge(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        let result = if R::FALLIBLE {
            self.tried(|c| c.with_inputs(inputs, R::try_merge))
        } else {
            self.with_inputs(inputs, R::merge)
        };
        self.set(dst, result);
    }

    fn merge_saving(&mut self, dst: usize, inputs: &[(usize, f64)]) -> bool {
        let result = if R::FALLIBLE {
            self.tried(|c| c.with_inputs(inputs, R::try_merge))
        } else {
            self.with_inputs(inputs, R::merge)
        };
        // The seal drops a saved value that the slot holds again (see
        // `unchanged`): a write of the same value needs no saving at all.
        let same = self.holds(dst, result.as_ref());
        if !same {
            Column::save(self, dst);
        }
        self.set(dst, result);
        !same
    }

    fn interpolate(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        let result = if R::FALLIBLE {
            self.tried(|c| c.with_inputs(inputs, R::try_interpolate))
        } else {
            self.with_inputs(inputs, R::interpolate)
        };
        self.set(dst, result);
    }

    fn interpolate_all(&mut self, jobs: &[(usize, u32, u32)], all: &[(usize, f64)]) {
        let results: Vec<Option<T>> = jobs
            .iter()
            .map(|&(_, start, end)| {
                let inputs = &all[start as usize..end as usize];
                if R::FALLIBLE {
                    self.tried(|c| c.with_inputs(inputs, R::try_interpolate))
                } else {
                    self.with_inputs(inputs, R::interpolate)
                }
            })
            .collect();
        for (&(dst, _, _), r) in jobs.iter().zip(results) {
            self.set(dst, r);
        }
    }

    fn split(&mut self, src: usize, pieces: &[(usize, f64)]) {
        let source = self.get(src).cloned();
        for &(dst, share) in pieces {
            let v = if R::FALLIBLE {
                self.tried(|_| R::try_split(source.as_ref(), share))
            } else {
                R::split(source.as_ref(), share)
            };
            self.set(dst, v);
        }
    }

    fn copy(&mut self, from: usize, to: usize) {
        let v = self.get(from).cloned();
        self.set(to, v);
    }

    #[inline]
    fn same(&self, i: usize, j: usize) -> bool {
        match (self.get(i), self.get(j)) {
            (None, None) => true,
            (Some(x), Some(y)) => x.same_value(y),
            _ => false,
        }
    }

    fn permute(&mut self, order: &[u32]) {
        // With the arena's headroom, as the arrays `compact` rebuilds.
        let mut values = crate::layout::with_headroom(order.len());
        values.extend(order.iter().map(|&i| self.values[i as usize].clone()));
        let present = self.present.as_ref().map(|_| {
            let mut bits = vec![0u64; order.len().div_ceil(64)];
            for (new, &old) in order.iter().enumerate() {
                if self.has(old as usize) {
                    bits[new / 64] |= 1 << (new % 64);
                }
            }
            bits
        });
        self.values = values;
        self.absent = present.as_ref().map_or(0, |bits| {
            (0..order.len())
                .filter(|&i| bits[i / 64] >> (i % 64) & 1 == 0)
                .count()
        });
        self.present = present.filter(|_| self.absent > 0);
    }

    fn rebuilt(&self, plan: &ColumnPlan) -> Box<dyn ErasedColumn> {
        let n = plan.sources.len();
        // With the arena's headroom, as the arrays the rebuild makes.
        let mut values = crate::layout::with_headroom(n);
        let mut bits = vec![0u64; n.div_ceil(64)];
        let mut absent = 0usize;
        let entries = &plan.entries;
        // A failure kept already stays with the column that replaces this.
        let mut failure = self.failure.clone();
        for (i, source) in plan.sources.iter().enumerate() {
            let value = if R::FALLIBLE {
                self.rebuilt_tried(*source, entries, &mut failure)
            } else {
                match *source {
                    Source::Copy(from) => self.get(from as usize).cloned(),
                    Source::Split(at) => {
                        let (from, share) = entries[at as usize];
                        R::split(self.get(from as usize), share)
                    }
                    Source::Interpolate { start, len } => {
                        let inputs = &entries[start as usize..(start + len) as usize];
                        self.with_u32_inputs(inputs, R::interpolate)
                    }
                    Source::FlipPiece(at) => {
                        let (a, sa) = entries[at as usize];
                        let (b, sb) = entries[at as usize + 1];
                        let pa = R::split(self.get(a as usize), sa);
                        let pb = R::split(self.get(b as usize), sb);
                        let merged = R::merge(&[(pa.as_ref(), 0.5), (pb.as_ref(), 0.5)]);
                        R::split(merged.as_ref(), 0.5)
                    }
                }
            };
            match value {
                Some(v) => {
                    values.push(v);
                    bits[i / 64] |= 1 << (i % 64);
                }
                None => {
                    values.push(T::default());
                    absent += 1;
                }
            }
        }
        Box::new(Column::<T, R> {
            values,
            present: (absent > 0).then_some(bits),
            absent,
            failure,
            rule: PhantomData,
            saved: Vec::new(),
            bulk: Vec::new(),
        })
    }

    fn interpolates_linearly(&self) -> bool {
        R::LINEAR
    }

    fn may_fail(&self) -> bool {
        R::FALLIBLE
    }

    fn rule_name(&self) -> &'static str {
        R::name()
    }

    fn failure(&self) -> Option<&Failure> {
        self.failure.as_deref()
    }

    fn take_failure(&mut self) -> Option<Box<Failure>> {
        self.failure.take()
    }

    fn interpolate_from(
        &mut self,
        src: &dyn ErasedColumn,
        dst: usize,
        inputs: &[(usize, f64)],
    ) -> bool {
        let Some(src) = src.as_any().downcast_ref::<Self>() else {
            return false;
        };
        let result = if R::FALLIBLE {
            self.tried(|_| src.with_inputs(inputs, R::try_interpolate))
        } else {
            src.with_inputs(inputs, R::interpolate)
        };
        self.set(dst, result);
        true
    }

    fn save(&mut self, i: usize) {
        Column::save(self, i);
    }

    fn save_bulk(&mut self, range: std::ops::Range<usize>) {
        Column::save_bulk(self, range);
    }

    fn seal_saved(&mut self) -> Option<Box<dyn Record>> {
        Column::seal_saved(self).map(|r| Box::new(r) as Box<dyn Record>)
    }

    fn seal_bulk(&mut self) -> Option<Box<dyn Record>> {
        Column::seal_bulk(self).map(|r| Box::new(r) as Box<dyn Record>)
    }

    fn discard_saved(&mut self) {
        self.saved = Vec::new();
        self.bulk = Vec::new();
    }

    fn apply_record(&mut self, record: &mut dyn Record) -> bool {
        match record.as_any_mut().downcast_mut::<ColumnRecord<T>>() {
            Some(r) => {
                Column::apply_record(self, r);
                true
            }
            None => false,
        }
    }

    fn heap_bytes(&self) -> usize {
        self.values.capacity() * std::mem::size_of::<T>()
            + self.present.as_ref().map_or(0, |b| b.capacity() * 8)
            + (self.saved.capacity() + self.bulk.capacity()) * std::mem::size_of::<Saved<T>>()
    }

    fn value_at(&self, i: usize) -> Option<Value> {
        self.get(i)?.to_value()
    }

    fn set_value(&mut self, i: usize, value: Option<&Value>) -> bool {
        if i >= self.values.len() {
            return false;
        }
        match value {
            None => {
                self.set(i, None);
                true
            }
            Some(v) => match T::from_value(v) {
                Some(t) => {
                    self.set(i, Some(t));
                    true
                }
                None => false,
            },
        }
    }

    fn portable_type(&self) -> Option<super::ValueType> {
        T::default().to_value().map(|v| v.value_type())
    }

    #[cfg(feature = "serde")]
    fn type_names(&self) -> (&'static str, &'static str) {
        (std::any::type_name::<T>(), std::any::type_name::<R>())
    }

    fn clone_box(&self) -> Box<dyn ErasedColumn> {
        Box::new(self.clone())
    }

    fn type_name(&self) -> &'static str {
        std::any::type_name::<T>()
    }

    fn as_any(&self) -> &dyn Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::rule::Interpolate;

    #[test]
    fn presence_is_lazy() {
        let mut c: Column<f64, Interpolate> = Column::dense(vec![1.0, 2.0]);
        assert!(c.present.is_none());
        c.set(1, None);
        assert_eq!(c.get(0), Some(&1.0));
        assert_eq!(c.get(1), None);
        c.set(1, Some(5.0));
        assert_eq!(c.get(1), Some(&5.0));
    }

    #[test]
    fn presence_bits_go_when_every_slot_has_a_value_again() {
        let mut c: Column<f64, Interpolate> = Column::absent(130);
        assert_eq!(c.absent, 130);
        for i in 0..130 {
            assert!(c.present.is_some(), "slot {i}");
            c.set(i, Some(i as f64));
        }
        assert!(c.present.is_none());
        assert_eq!(c.absent, 0);
        c.set(7, None);
        c.set(7, None); // clearing twice counts once
        c.clear(9);
        assert_eq!(c.absent, 2);
        assert_eq!((c.get(7), c.get(9), c.get(8)), (None, None, Some(&8.0)));
        c.set(7, Some(1.0));
        assert!(c.present.is_some());
        c.copy(8, 9);
        assert!(c.present.is_none());
        // Undoing a clear through a saved value is a write like any other.
        let mut saved = c.saved_of(3);
        c.set(3, None);
        c.swap_in(&mut saved);
        assert_eq!((c.get(3), c.absent), (Some(&3.0), 0));
        assert!(c.present.is_none());
        // Permuting and growing keep the count.
        c.set(0, None);
        c.permute(&[1, 0, 2]);
        assert_eq!((c.absent, c.get(1)), (1, None));
        c.ensure_len(200);
        assert_eq!(c.absent, 1);
        c.set(1, Some(0.5));
        assert!(c.present.is_none());
    }

    #[test]
    fn merge_split_permute() {
        let mut c: Column<f64, Interpolate> = Column::dense(vec![0.0, 4.0, 0.0]);
        c.merge(2, &[(0, 0.5), (1, 0.5)]);
        assert_eq!(c.get(2), Some(&2.0));
        c.split(1, &[(0, 0.5), (1, 0.5)]);
        assert_eq!(c.get(0), Some(&4.0));
        c.permute(&[2, 0]);
        assert_eq!(c.raw(), &[2.0, 4.0]);
    }
}
