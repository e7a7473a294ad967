//! One attribute column: a value per slot of one arena, plus presence.

use std::any::Any;
use std::marker::PhantomData;

use super::attribute::Attribute;
use super::rule::Rule;
use super::value::Value;

/// A rule's merge or interpolate, as a function.
type RuleFn<T> = fn(&[(Option<&T>, f64)]) -> Option<T>;

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
    rule: PhantomData<fn() -> R>,
}

impl<T: Clone, R> Clone for Column<T, R> {
    fn clone(&self) -> Self {
        Column {
            values: self.values.clone(),
            present: self.present.clone(),
            rule: PhantomData,
        }
    }
}

impl<T: Default + Clone, R> Column<T, R> {
    /// A column of `len` absent values.
    pub(crate) fn absent(len: usize) -> Self {
        Column {
            values: vec![T::default(); len],
            present: Some(vec![0; len.div_ceil(64)]),
            rule: PhantomData,
        }
    }

    /// A column whose every slot has the given value.
    pub(crate) fn dense(values: Vec<T>) -> Self {
        Column {
            values,
            present: None,
            rule: PhantomData,
        }
    }

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
        match value {
            Some(v) => {
                self.values[i] = v;
                if let Some(bits) = &mut self.present {
                    bits[i / 64] |= 1 << (i % 64);
                }
            }
            None => {
                self.values[i] = T::default();
                let len = self.values.len();
                let bits = self
                    .present
                    .get_or_insert_with(|| vec![u64::MAX; len.div_ceil(64)]);
                bits[i / 64] &= !(1 << (i % 64));
            }
        }
    }

    /// The raw values, indexed by slot (vacant and absent slots hold
    /// defaults).
    pub(crate) fn raw(&self) -> &[T] {
        &self.values
    }

    /// Run `rule` on the values of `inputs` (slot, weight), in order. Up to
    /// eight contributors (every operator but the merges of whole rings)
    /// need no allocation.
    #[inline]
    fn with_inputs(&self, inputs: &[(usize, f64)], rule: RuleFn<T>) -> Option<T> {
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

    /// The presence bits (`None`: every slot has a value).
    #[inline]
    pub(crate) fn present_bits(&self) -> Option<&[u64]> {
        self.present.as_deref()
    }

    /// The raw values, mutably.
    pub(crate) fn raw_mut(&mut self) -> &mut [T] {
        &mut self.values
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
    /// Run the rule's interpolate: `dst` is made from `inputs`.
    fn interpolate(&mut self, dst: usize, inputs: &[(usize, f64)]);
    /// Run the rule's split: each `(slot, share)` piece from `src`. `src`
    /// may be among the pieces; its old value is read first.
    fn split(&mut self, src: usize, pieces: &[(usize, f64)]);
    /// Copy slot `from`'s value (or absence) to slot `to`.
    fn copy(&mut self, from: usize, to: usize);
    /// Reorder: slot `i` of the result holds old slot `order[i]`.
    fn permute(&mut self, order: &[u32]);
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
            if let Some(bits) = &mut self.present {
                bits[i / 64] &= !(1 << (i % 64));
            }
        }
    }

    fn merge(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        let result = self.with_inputs(inputs, R::merge);
        self.set(dst, result);
    }

    fn interpolate(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        let result = self.with_inputs(inputs, R::interpolate);
        self.set(dst, result);
    }

    fn split(&mut self, src: usize, pieces: &[(usize, f64)]) {
        let source = self.get(src).cloned();
        for &(dst, share) in pieces {
            let v = R::split(source.as_ref(), share);
            self.set(dst, v);
        }
    }

    fn copy(&mut self, from: usize, to: usize) {
        let v = self.get(from).cloned();
        self.set(to, v);
    }

    fn permute(&mut self, order: &[u32]) {
        let values: Vec<T> = order
            .iter()
            .map(|&i| self.values[i as usize].clone())
            .collect();
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
        self.present = present;
    }

    fn heap_bytes(&self) -> usize {
        self.values.capacity() * std::mem::size_of::<T>()
            + self.present.as_ref().map_or(0, |b| b.capacity() * 8)
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
