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
mod by_name;
mod handle;
mod infer;
#[cfg(feature = "serde")]
pub(crate) mod registry;
mod view;

pub use crate::error::RuleError;
pub use crate::store::{rule, rules};
pub use crate::store::{Attribute, Column, POSITION};
pub use crate::store::{Dynamic, Value, ValueType};
pub use api::AttrInfo;
pub use handle::{Attr, EdgeAttr, Element, FaceAttr, HalfedgeAttr, VertexAttr};
#[cfg(feature = "serde")]
pub use registry::register;
pub use rule::{Linear, Rule};
pub use rules::{Conserved, Contagion, Discard, Incompatible, Interpolate, KeepFirst};
pub use view::{AttrView, AttrViewMut, ElementView};

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
        let slot = mesh.writer::<crate::record::Recorded>().alloc_vertex();
        assert_eq!(slot.index(), 4);
        for (_, c) in &mesh.attrs.vertex.cols {
            assert_eq!(c.len(), 5);
        }
        mesh.writer::<crate::record::Recorded>().free_vertex(v.id());
        // The value is gone (and its heap memory with it), not just hidden.
        let col = mesh
            .attrs
            .vertex
            .typed::<String, crate::attr::Incompatible>(1)
            .unwrap();
        assert!(col.raw()[v.index()].is_empty());
        assert!(!col.has(v.index()));
        // The slot comes back under a new generation, without a value.
        let again = mesh.writer::<crate::record::Recorded>().alloc_vertex();
        assert_eq!(again, v.id());
        let k = mesh.vkey(again);
        assert_eq!(mesh.attr(&name, k).unwrap(), None);
        assert_eq!(mesh.attr(&w, k).unwrap(), None);
        assert!(mesh.attr(&name, v).is_err());
    }

    #[test]
    fn a_column_written_key_by_key_is_dense_again() {
        let mut mesh = crate::shapes::icosahedron();
        let w = mesh.add_vertex_attr::<f64>("w").unwrap();
        let keys: Vec<_> = mesh.vertices().collect();
        assert!(mesh.attr_view(&w).unwrap().dense_slice().is_none());
        for (i, &v) in keys.iter().enumerate() {
            mesh.set_attr(&w, v, i as f64).unwrap();
        }
        let want: Vec<f64> = (0..12).map(f64::from).collect();
        assert_eq!(mesh.attr_view(&w).unwrap().dense_slice(), Some(&want[..]));
        // A gap makes it sparse; filling the gap makes it dense again.
        mesh.clear_attr(&w, keys[3]).unwrap();
        assert!(mesh.attr_view(&w).unwrap().dense_slice().is_none());
        mesh.set_attr(&w, keys[3], 3.0).unwrap();
        assert_eq!(mesh.attr_view(&w).unwrap().dense_slice(), Some(&want[..]));
        // Through a mutable view, as bulk writers do.
        {
            let mut view = mesh.attr_view_mut(&w).unwrap();
            view.set(keys[0], None).unwrap();
            view.set(keys[0], Some(0.0)).unwrap();
        }
        assert_eq!(mesh.attr_view(&w).unwrap().dense_slice(), Some(&want[..]));
        // A rolled-back clear leaves it dense.
        let r = mesh.transaction(|m| {
            m.clear_attr(&w, keys[5])?;
            Err::<(), _>(crate::Error::Cancelled { algorithm: "test" })
        });
        assert!(r.is_err());
        assert_eq!(mesh.attr_view(&w).unwrap().dense_slice(), Some(&want[..]));
    }
}
