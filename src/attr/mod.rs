//! Attributes: typed values on vertices, half-edges, edges and faces that
//! follow every topological edit by rule.
//!
//! Each arena has a set of columns ([`Columns`]); a column holds one value
//! per slot, so a value is found by the element's slot index in O(1) and no
//! per-element map exists. When an operation creates, merges, splits or
//! removes elements it calls the column set of that arena, which runs every
//! column's [`Rule`]. Positions are the vertex column named
//! [`POSITION`], with the [`Interpolate`] rule.

pub(crate) mod column;
pub mod rule;

pub use column::Column;
pub use rule::{Interpolate, Linear, Rule};

use column::ErasedColumn;

/// The name of the position column.
pub const POSITION: &str = "position";

/// The columns of one arena, in the order they were added.
#[derive(Default)]
pub(crate) struct Columns {
    pub(crate) cols: Vec<(String, Box<dyn ErasedColumn>)>,
}

impl Clone for Columns {
    fn clone(&self) -> Self {
        Columns {
            cols: self
                .cols
                .iter()
                .map(|(n, c)| (n.clone(), c.clone_box()))
                .collect(),
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
        self.cols.push((name.to_owned(), col));
        self.cols.len() - 1
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
