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
//! | `value.rs` | [`Value`] and [`ValueType`], the portable form of a value (file formats, serde, dynamic columns) |
//! | this file | `Columns` (one arena's columns) and `AttrStore` (the four arenas) |

mod attribute;
mod column;
pub mod rule;
pub mod rules;
mod value;

pub use attribute::Attribute;
pub use column::Column;
pub(crate) use column::ErasedColumn;
pub use value::{Dynamic, Value, ValueType};

use rules::Interpolate;
use std::sync::atomic::{AtomicU64, Ordering};

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
}

impl Clone for Columns {
    fn clone(&self) -> Self {
        Columns {
            cols: self
                .cols
                .iter()
                .map(|(n, c)| (n.clone(), c.clone_box()))
                .collect(),
            meta: self.meta.clone(),
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

    /// Merge rule on every column.
    pub(crate) fn merge(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        for (_, c) in &mut self.cols {
            c.merge(dst, inputs);
        }
    }

    /// Interpolate rule on every column.
    pub(crate) fn interpolate(&mut self, dst: usize, inputs: &[(usize, f64)]) {
        for (_, c) in &mut self.cols {
            c.interpolate(dst, inputs);
        }
    }

    /// Split rule on every column.
    pub(crate) fn split(&mut self, src: usize, pieces: &[(usize, f64)]) {
        for (_, c) in &mut self.cols {
            c.split(src, pieces);
        }
    }

    /// Copy slot `from` to `to` in every column.
    pub(crate) fn copy(&mut self, from: usize, to: usize) {
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
}
