//! Attributes: typed values on vertices, half-edges, edges and faces that
//! follow every topological edit by rule.
//!
//! Each arena has a set of columns; a column holds one value per slot
//! (`Vec<T>` plus a presence bitset that exists only once some element lacks
//! a value), so a value is found by the element's slot index in O(1) and no
//! per-element map exists. When an operation creates, merges, splits or
//! removes elements it calls the column set of that arena, which runs every
//! column's [`Rule`]; the operators' docs ([`ops`](crate::ops)) say which
//! elements merge and which split. Positions are the vertex column named
//! [`POSITION`], with the [`Interpolate`] rule.
//!
//! # Tour
//!
//! | want | use |
//! |---|---|
//! | a value type that states its rule | [`Attribute`] (stock: floats and float arrays interpolate, integers and `String` are [`Incompatible`], `bool` is [`Contagion`]) |
//! | a column | [`Mesh::add_vertex_attr`](crate::Mesh::add_vertex_attr) and siblings; [`Mesh::add_attr_with_rule`](crate::Mesh::add_attr_with_rule) for another rule |
//! | a typed handle by name | [`Mesh::attr_handle`](crate::Mesh::attr_handle) ([`VertexAttr`], [`FaceAttr`], ...) |
//! | one value | [`Mesh::attr`](crate::Mesh::attr), [`Mesh::set_attr`](crate::Mesh::set_attr), [`Mesh::clear_attr`](crate::Mesh::clear_attr) |
//! | a hot loop or a whole column | [`Mesh::attr_view`](crate::Mesh::attr_view) ([`AttrView::get`], [`AttrView::at`], [`AttrView::iter`]), [`Mesh::attr_view_mut`](crate::Mesh::attr_view_mut) |
//! | data typed at run time (PLY properties) | [`Mesh::add_dynamic_attr`](crate::Mesh::add_dynamic_attr) with [`Value`] and the [`Dynamic`] rule; any portable column by name with [`Mesh::attr_value`](crate::Mesh::attr_value) |
//! | a missing value guessed from neighbours | [`Mesh::infer_attr`](crate::Mesh::infer_attr) |
//! | a new rule | implement [`Rule`] |
//!
//! ```
//! use meshloom::attr::{Conserved, FaceAttr};
//! use meshloom::VertexKey;
//!
//! let mut mesh = meshloom::shapes::icosahedron();
//! let colour: FaceAttr<[f32; 3]> = mesh.add_face_attr("colour")?;
//! let mass = mesh.add_attr_with_rule::<VertexKey, f64, Conserved>("mass")?;
//! mesh.fill_attr(&colour, [1.0, 0.5, 0.0])?;
//! mesh.fill_attr(&mass, 1.0)?;
//!
//! let h = mesh.halfedges().next().unwrap();
//! let kept = mesh.collapse_edge(h)?; // two vertices merge: masses add up
//! assert_eq!(mesh.attr(&mass, kept)?, Some(&2.0));
//! let total: f64 = mesh.attr_view(&mass)?.iter().map(|(_, m)| m).sum();
//! assert_eq!(total, 12.0);
//! let f = mesh.faces().next().unwrap();
//! assert_eq!(mesh.attr(&colour, f)?, Some(&[1.0, 0.5, 0.0]));
//! # Ok::<(), meshloom::Error>(())
//! ```
//!
//! # Costs
//!
//! [`AttrView::get`] compares the key's generation with the arena's (one
//! extra `u32` read from a separate array) before it reads the value; a
//! scan in slot order costs about as much as indexing a `Vec`, while random
//! access pays a second cache miss. [`AttrView::at`] takes a checked element
//! view instead and reads with no generation check, and [`AttrView::iter`]
//! walks the column in slot order.

mod api;
mod attribute;
mod by_name;
pub(crate) mod column;
mod handle;
mod infer;
#[cfg(feature = "serde")]
pub(crate) mod registry;
pub mod rule;
pub mod rules;
mod value;
mod view;

pub use api::AttrInfo;
pub use attribute::Attribute;
pub use column::Column;
pub use handle::{Attr, EdgeAttr, Element, FaceAttr, HalfedgeAttr, VertexAttr};
#[cfg(feature = "serde")]
pub use registry::register;
pub use rule::{Linear, Rule};
pub use rules::{Conserved, Contagion, Discard, Incompatible, Interpolate, KeepFirst};
pub use value::{Dynamic, Value, ValueType};
pub use view::{AttrView, AttrViewMut, ElementView};

pub(crate) use column::ErasedColumn;

use std::sync::atomic::{AtomicU64, Ordering};

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

#[cfg(test)]
mod tests {
    #[test]
    fn columns_follow_alloc_and_free() {
        let mut mesh = crate::shapes::tetrahedron();
        let name = mesh.add_vertex_attr::<String>("name").unwrap();
        let w = mesh.add_vertex_attr::<f64>("w").unwrap();
        let v = mesh.vertices().next().unwrap();
        mesh.set_attr(&name, v, "apex".into()).unwrap();
        mesh.set_attr(&w, v, 2.0).unwrap();
        let slot = mesh.alloc_vertex();
        assert_eq!(slot.index(), 4);
        for (_, c) in &mesh.attrs.vertex.cols {
            assert_eq!(c.len(), 5);
        }
        mesh.free_vertex(v.id());
        // The value is gone (and its heap memory with it), not just hidden.
        let col = mesh
            .attrs
            .vertex
            .typed::<String, crate::attr::Incompatible>(1)
            .unwrap();
        assert!(col.raw()[v.index()].is_empty());
        assert!(!col.has(v.index()));
        // The slot comes back under a new generation, without a value.
        let again = mesh.alloc_vertex();
        assert_eq!(again, v.id());
        let k = mesh.vkey(again);
        assert_eq!(mesh.attr(&name, k).unwrap(), None);
        assert_eq!(mesh.attr(&w, k).unwrap(), None);
        assert!(mesh.attr(&name, v).is_err());
    }
}
