//! Attribute storage: the typed columns that sit beside each arena, and the
//! vocabulary they are typed over.
//!
//! This is the layer under [`Mesh`](crate::Mesh): the mesh owns an
//! [`AttrStore`] and every operator runs the rules of its columns through
//! it. The user-facing attribute API ([`attr`](crate::attr): handles,
//! views, access by name, inference) is built on top and re-exports the
//! public items below; nothing here imports from it.
//!
//! | file | holds |
//! |---|---|
//! | `column.rs` | [`Column`] (a `Vec` per slot plus lazy presence bits) and the type-erased `ErasedColumn` every edit calls |
//! | `rule.rs`, `rules.rs` | the [`Rule`](rule::Rule) trait and the stock rules |
//! | `attribute.rs` | [`Attribute`]: a value type that names its rule |
//! | `plan.rs` | `ColumnPlan`: the sources of every slot of a column rebuilt wholesale (subdivision) |
//! | `value.rs` | [`Value`] and [`ValueType`], the portable form of a value (file formats, serde, dynamic columns) |
//! | `float_serde.rs` | serde for a `Value`'s floats, NaN and the infinities included |
//! | this file | `Columns` (one arena's columns) and `AttrStore` (the four arenas) |

mod attribute;
mod column;
#[cfg(feature = "serde")]
mod float_serde;
pub(crate) mod plan;
pub mod rule;
pub mod rules;
mod value;

pub use attribute::Attribute;
pub(crate) use column::mark;
pub use column::Column;
pub(crate) use column::{ErasedColumn, Record};
pub use value::{Dynamic, Value, ValueType};

use rules::Interpolate;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::Error;
use crate::keys::ElementKind;

/// Column ids are unique in the process, so a handle never names a column
/// of another mesh by accident (a clone shares its original's ids).
static NEXT_COLUMN_ID: AtomicU64 = AtomicU64::new(1);

/// What a column set knows about a column beside its values.
#[derive(Clone, Debug)]
pub(crate) struct ColumnMeta {
    /// Unique id, checked by handles.
    pub(crate) id: u64,
    /// The declared type of a dynamic column.
    pub(crate) value_type: Option<ValueType>,
}

/// The name of the position column.
pub const POSITION: &str = "position";

/// The columns of one arena, in the order they were added.
#[derive(Default)]
pub(crate) struct Columns {
    pub(crate) cols: Vec<(String, Box<dyn ErasedColumn>)>,
    /// One entry per column, in the same order.
    pub(crate) meta: Vec<ColumnMeta>,
    /// While a journal records: the arena's slot count when the open step
    /// began. A write to a slot below it saves the old value first; slots
    /// at or past it were born in the step (undo needs nothing of them).
    /// 0 with no journal, so the check is one compare that never passes.
    pub(crate) log_below: usize,
    /// Whether a column saved a value in the open step.
    pub(crate) dirty: bool,
    /// Whether a column's rule can fail ([`Rule::FALLIBLE`](rule::Rule::FALLIBLE)),
    /// kept by every change of the columns (see [`Columns::recount`]).
    pub(crate) fallible: bool,
}

impl Clone for Columns {
    /// The columns and values; nothing of a journal.
    fn clone(&self) -> Self {
        Columns {
            cols: self
                .cols
                .iter()
                .map(|(n, c)| (n.clone(), c.clone_box()))
                .collect(),
            meta: self.meta.clone(),
            log_below: 0,
            dirty: false,
            fallible: self.fallible,
        }
    }
}

impl std::fmt::Debug for Columns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list()
            .entries(self.cols.iter().map(|(n, c)| (n, c.type_name())))
            .finish()
    }
}

impl Columns {
    /// Column index by name.
    pub(crate) fn find(&self, name: &str) -> Option<usize> {
        self.cols.iter().position(|(n, _)| n == name)
    }

    /// Add a column (the caller checked the name is free).
    pub(crate) fn push(&mut self, name: &str, col: Box<dyn ErasedColumn>) -> usize {
        self.push_dynamic(name, col, None)
    }

    /// Add a column with its declared dynamic type.
    pub(crate) fn push_dynamic(
        &mut self,
        name: &str,
        col: Box<dyn ErasedColumn>,
        value_type: Option<ValueType>,
    ) -> usize {
        self.fallible |= col.may_fail();
        self.cols.push((name.to_owned(), col));
        self.meta.push(ColumnMeta {
            id: NEXT_COLUMN_ID.fetch_add(1, Ordering::Relaxed),
            value_type,
        });
        self.cols.len() - 1
    }

    /// Remove column `i`; later columns move down by one.
    pub(crate) fn remove(&mut self, i: usize) {
        self.cols.remove(i);
        self.meta.remove(i);
        self.recount();
    }

    /// Set [`fallible`](Columns::fallible) from the columns, after they
    /// changed.
    pub(crate) fn recount(&mut self) {
        self.fallible = self.cols.iter().any(|(_, c)| c.may_fail());
    }

    /// The index of the column with this id.
    #[inline]
    pub(crate) fn find_id(&self, index: usize, id: u64) -> Option<usize> {
        if self.meta.get(index).is_some_and(|m| m.id == id) {
            Some(index)
        } else {
            self.meta.iter().position(|m| m.id == id)
        }
    }

    /// Typed access to column `i`.
    pub(crate) fn typed<T: 'static, R: 'static>(&self, i: usize) -> Option<&Column<T, R>> {
        self.cols.get(i)?.1.as_any().downcast_ref()
    }

    /// Typed mutable access to column `i`.
    pub(crate) fn typed_mut<T: 'static, R: 'static>(
        &mut self,
        i: usize,
    ) -> Option<&mut Column<T, R>> {
        self.cols.get_mut(i)?.1.as_any_mut().downcast_mut()
    }

    /// Before a write to slot `i` of every column: save the old values
    /// while a journal records (one compare otherwise).
    #[inline(always)]
    pub(crate) fn save(&mut self, i: usize) {
        if i < self.log_below {
            self.save_all_columns(i);
        }
    }

    #[inline(never)]
    fn save_all_columns(&mut self, i: usize) {
        self.dirty = true;
        for (_, c) in &mut self.cols {
            c.save(i);
        }
    }

    /// Before a write to slot `i` of column `col` alone.
    #[inline]
    pub(crate) fn save_one(&mut self, col: usize, i: usize) {
        if i < self.log_below {
            self.dirty = true;
            self.cols[col].1.save(i);
        }
    }

    /// A reused slot starts as a freed one would have been left (values
    /// dropped), with the old values saved: while a journal records, a
    /// freed slot keeps its values (so undoing its death needs nothing),
    /// and they go only when the slot is reused.
    #[inline]
    pub(crate) fn reset(&mut self, i: usize) {
        self.save(i);
        self.clear(i);
    }

    /// Every column grows to `len` slots.
    #[inline]
    pub(crate) fn ensure_len(&mut self, len: usize) {
        for (_, c) in &mut self.cols {
            c.ensure_len(len);
        }
    }

    /// Slot `i`'s element was removed.
    #[inline]
    pub(crate) fn clear(&mut self, i: usize) {
        for (_, c) in &mut self.cols {
            c.clear(i);
        }
    }

    /// Merge rule on every column (nothing to do, and nothing to save,
    /// when the arena has no columns: that check is inlined).
    #[inline]
    pub(crate) fn merge(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        if !self.cols.is_empty() {
            self.merge_columns(dst, inputs);
        }
    }

    fn merge_columns(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        if dst < self.log_below {
            // A journal records: save only what the merge changes (a
            // collapse merging the survivor with weight 1 keeps its value).
            for (_, c) in &mut self.cols {
                self.dirty |= c.merge_saving(dst, inputs);
            }
        } else {
            for (_, c) in &mut self.cols {
                c.merge(dst, inputs);
            }
        }
    }

    /// Merge rule on column `col` alone, saving the old value first while
    /// a journal records (only if the merge changes it).
    #[inline]
    pub(crate) fn merge_one(&mut self, col: usize, dst: usize, inputs: &[(usize, f64)]) {
        let c = &mut self.cols[col].1;
        if dst < self.log_below {
            self.dirty |= c.merge_saving(dst, inputs);
        } else {
            c.merge(dst, inputs);
        }
    }

    /// Copy slot `from` to `to` in column `col` alone, saving `to`'s old
    /// value first while a journal records.
    #[inline]
    pub(crate) fn copy_one(&mut self, col: usize, from: usize, to: usize) {
        self.save_one(col, to);
        self.cols[col].1.copy(from, to);
    }

    /// Interpolate rule on every column.
    #[inline]
    pub(crate) fn interpolate(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        if !self.cols.is_empty() {
            self.interpolate_columns(dst, inputs);
        }
    }

    fn interpolate_columns(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        self.save(dst);
        for (_, c) in &mut self.cols {
            c.interpolate(dst, inputs);
        }
    }

    /// Interpolate rule on every column for every `(dst, start, end)` job
    /// (of `inputs[start..end]`), all read before any is written.
    pub(crate) fn interpolate_all(&mut self, jobs: &[(usize, u32, u32)], inputs: &[(usize, f64)]) {
        if self.cols.is_empty() {
            return;
        }
        for &(dst, _, _) in jobs {
            self.save(dst);
        }
        for (_, c) in &mut self.cols {
            c.interpolate_all(jobs, inputs);
        }
    }

    /// Split rule on every column.
    #[inline]
    pub(crate) fn split(&mut self, src: usize, pieces: &[(usize, f64)]) {
        if !self.cols.is_empty() {
            self.split_columns(src, pieces);
        }
    }

    fn split_columns(&mut self, src: usize, pieces: &[(usize, f64)]) {
        for &(dst, _) in pieces {
            self.save(dst);
        }
        for (_, c) in &mut self.cols {
            c.split(src, pieces);
        }
    }

    /// Copy slot `from` to `to` in every column.
    #[inline]
    pub(crate) fn copy(&mut self, from: usize, to: usize) {
        if !self.cols.is_empty() {
            self.copy_columns(from, to);
        }
    }

    fn copy_columns(&mut self, from: usize, to: usize) {
        self.save(to);
        for (_, c) in &mut self.cols {
            c.copy(from, to);
        }
    }

    /// Reorder every column: new slot `i` holds old slot `order[i]`.
    pub(crate) fn permute(&mut self, order: &[u32]) {
        for (_, c) in &mut self.cols {
            c.permute(order);
        }
    }

    /// The earliest rule failure kept by a column: its order and the
    /// column's index.
    fn first_failure(&self) -> Option<(u64, usize)> {
        if !self.fallible {
            return None;
        }
        self.cols
            .iter()
            .enumerate()
            .filter_map(|(i, (_, c))| Some((c.failure()?.seq, i)))
            .min()
    }

    /// Heap bytes of every column.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.cols.iter().map(|(_, c)| c.heap_bytes()).sum::<usize>()
            + self.cols.capacity() * std::mem::size_of::<(String, Box<dyn ErasedColumn>)>()
    }
}

/// The column sets of the four arenas.
#[derive(Clone, Debug, Default)]
pub(crate) struct AttrStore {
    pub(crate) vertex: Columns,
    pub(crate) halfedge: Columns,
    pub(crate) edge: Columns,
    pub(crate) face: Columns,
    /// Index of the position column in `vertex`, if any.
    pub(crate) position: Option<usize>,
}

/// The position column's concrete type.
pub(crate) type PositionColumn = Column<[f64; 3], Interpolate>;

impl AttrStore {
    /// The columns of one arena.
    pub(crate) fn columns(&self, kind: ElementKind) -> &Columns {
        match kind {
            ElementKind::Vertex => &self.vertex,
            ElementKind::Halfedge => &self.halfedge,
            ElementKind::Edge => &self.edge,
            ElementKind::Face => &self.face,
        }
    }

    /// The columns of one arena, mutably.
    pub(crate) fn columns_mut(&mut self, kind: ElementKind) -> &mut Columns {
        match kind {
            ElementKind::Vertex => &mut self.vertex,
            ElementKind::Halfedge => &mut self.halfedge,
            ElementKind::Edge => &mut self.edge,
            ElementKind::Face => &mut self.face,
        }
    }

    /// Whether a column's rule can fail ([`Rule::FALLIBLE`](rule::Rule::FALLIBLE)):
    /// then every edit runs all or nothing, as a transaction.
    #[inline]
    pub(crate) fn may_fail(&self) -> bool {
        self.vertex.fallible | self.halfedge.fallible | self.edge.fallible | self.face.fallible
    }

    /// The first rule failure the columns kept, as the error of the edit
    /// that ran it. With `take`, every column's kept failure is taken (their
    /// rules run again); otherwise they stay, for the edits around.
    pub(crate) fn rule_failure(&mut self, take: bool) -> Option<Error> {
        if !self.may_fail() {
            return None;
        }
        let kinds = [
            ElementKind::Vertex,
            ElementKind::Halfedge,
            ElementKind::Edge,
            ElementKind::Face,
        ];
        let (_, kind, col) = kinds
            .iter()
            .zip(self.all_mut())
            .filter_map(|(&kind, set)| set.first_failure().map(|(seq, i)| (seq, kind, i)))
            .min_by_key(|&(seq, ..)| seq)?;
        let (column, c) = &self.columns(kind).cols[col];
        let error = Error::Rule(c.failure()?.error.of_column(kind, column));
        if take {
            for set in self.all_mut() {
                for (_, c) in &mut set.cols {
                    c.take_failure();
                }
            }
        }
        Some(error)
    }

    /// Heap bytes of every column.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.vertex.heap_bytes()
            + self.halfedge.heap_bytes()
            + self.edge.heap_bytes()
            + self.face.heap_bytes()
    }

    /// The position column.
    #[inline]
    pub(crate) fn positions(&self) -> Option<&PositionColumn> {
        self.vertex.typed(self.position?)
    }

    /// The position column, mutably.
    #[inline]
    pub(crate) fn positions_mut(&mut self) -> Option<&mut PositionColumn> {
        let i = self.position?;
        self.vertex.typed_mut(i)
    }

    /// Set vertex slot `i`'s position, its old one saved first for a
    /// journal. `None` when the mesh has no positions.
    #[inline]
    pub(crate) fn set_position_saved(&mut self, i: usize, p: [f64; 3]) -> Option<()> {
        let col = self.position?;
        self.vertex.save_one(col, i);
        self.positions_mut()?.set(i, Some(p));
        Some(())
    }

    /// Take column `col` out of set `set` (a journal keeps it), keeping
    /// the position index right. Returns `(name, column, meta)`.
    pub(crate) fn take_column(
        &mut self,
        set: usize,
        col: usize,
    ) -> (String, Box<dyn ErasedColumn>, ColumnMeta) {
        let c = &mut self.all_mut()[set];
        let (name, column) = c.cols.remove(col);
        let meta = c.meta.remove(col);
        c.recount();
        if set == 0 {
            self.position = match self.position {
                Some(p) if p == col => None,
                Some(p) if p > col => Some(p - 1),
                p => p,
            };
        }
        (name, column, meta)
    }

    /// Put back a column [`take_column`](AttrStore::take_column) took, at
    /// `col`, grown to `len` slots.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn insert_column(
        &mut self,
        set: usize,
        col: usize,
        name: String,
        mut column: Box<dyn ErasedColumn>,
        meta: ColumnMeta,
        position: bool,
        len: usize,
    ) {
        column.ensure_len(len);
        let c = &mut self.all_mut()[set];
        c.cols.insert(col, (name, column));
        c.meta.insert(col, meta);
        c.recount();
        if set == 0 {
            self.position = match self.position {
                Some(p) if p >= col => Some(p + 1),
                p => p,
            };
            if position {
                self.position = Some(col);
            }
        }
    }

    /// The four column sets, in arena order (vertex, half-edge, edge,
    /// face: [`ElementKind`] order).
    pub(crate) fn all_mut(&mut self) -> [&mut Columns; 4] {
        [
            &mut self.vertex,
            &mut self.halfedge,
            &mut self.edge,
            &mut self.face,
        ]
    }
}
