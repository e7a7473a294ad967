//! The attribute API of [`Mesh`]: add, find and remove typed and dynamic
//! columns; read and write values by key; views for whole-column passes.

use std::marker::PhantomData;

use super::handle::{Attr, EdgeAttr, Element, FaceAttr, HalfedgeAttr, VertexAttr};
use super::view::{AttrView, AttrViewMut};
use crate::error::{Error, Result};
use crate::keys::ElementKind;
use crate::mesh::Mesh;
use crate::slots::Slots;
use crate::store::rule::Rule;
use crate::store::rules::Interpolate;
use crate::store::{Attribute, Column, Columns, Dynamic, Value, ValueType};

/// What [`Mesh::attr_info`] tells about one column: enough to pick the
/// typed handle ([`Mesh::attr_handle`]) that reads it, without trying each.
///
/// ```
/// use meshloom::attr::{Conserved, Rule};
/// use meshloom::{ElementKind, VertexKey};
/// let mut mesh = meshloom::shapes::cube();
/// mesh.add_attr_with_rule::<VertexKey, f64, Conserved>("mass")?;
/// let info = mesh.attr_info(ElementKind::Vertex);
/// assert_eq!((info[0].name.as_str(), info[0].rule), ("position", "Interpolate"));
/// assert_eq!((info[1].name.as_str(), info[1].type_name, info[1].rule), ("mass", "f64", "Conserved"));
/// assert_eq!(info[1].rule, <Conserved as Rule<f64>>::name());
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct AttrInfo {
    /// The column's name.
    pub name: String,
    /// The Rust value type's name (`f64`, `meshloom::attr::Value`, ...:
    /// [`std::any::type_name`] of it).
    pub type_name: &'static str,
    /// The name of the column's rule ([`Rule::name`]): `"Interpolate"`,
    /// `"Conserved"`, `"Contagion"`, `"Incompatible"`, `"KeepFirst"`,
    /// `"Discard"`, `"Dynamic"` for the stock rules; a custom rule's own.
    pub rule: &'static str,
    /// The dynamic type its values convert to, if they do (the declared
    /// type of a dynamic column).
    pub value_type: Option<ValueType>,
    /// Whether it is a dynamic column.
    pub dynamic: bool,
}

impl Mesh {
    pub(crate) fn columns_of(&self, kind: ElementKind) -> &Columns {
        self.attrs.columns(kind)
    }

    /// The generations of an arena and the shift from a slot to its
    /// generation's index (half-edges share their edge's).
    #[inline]
    fn arena_slots(&self, kind: ElementKind) -> (&Slots, u32) {
        match kind {
            ElementKind::Vertex => (&self.v_slots, 0),
            ElementKind::Halfedge => (&self.e_slots, 1),
            ElementKind::Edge => (&self.e_slots, 0),
            ElementKind::Face => (&self.f_slots, 0),
        }
    }

    fn arena_len(&self, kind: ElementKind) -> usize {
        self.slot_counts()[kind as usize]
    }

    #[inline]
    pub(super) fn element_slot<K: Element>(&self, key: K) -> Result<usize> {
        let (slots, shift) = self.arena_slots(K::KIND);
        if slots.is_current(key.slot() >> shift, key.generation_of_key()) {
            Ok(key.slot() as usize)
        } else {
            Err(Error::StaleKey(key.any_key()))
        }
    }

    #[inline]
    fn resolve<K: Element, T: Attribute, R>(&self, h: &Attr<K, T, R>) -> Result<usize> {
        self.columns_of(K::KIND)
            .find_id(h.index, h.id)
            .ok_or_else(|| Error::AttributeHandle {
                kind: K::KIND,
                name: h.name.clone(),
            })
    }

    fn typed_column<K: Element, T: Attribute, R: Rule<T>>(
        &self,
        h: &Attr<K, T, R>,
    ) -> Result<&Column<T, R>> {
        let i = self.resolve(h)?;
        self.columns_of(K::KIND)
            .typed(i)
            .ok_or_else(|| stale_handle(h))
    }

    // ----- adding, finding, removing -----------------------------------------

    /// Add a column of `T` on the arena of `K`, with rule `R` instead of
    /// `T`'s own. Every element starts without a value.
    ///
    /// # Errors
    /// [`Error::AttributeExists`] if the name is taken on that arena.
    ///
    /// ```
    /// use meshloom::attr::{Conserved, FaceAttr};
    /// use meshloom::FaceKey;
    /// let mut mesh = meshloom::shapes::cube();
    /// let area: FaceAttr<f64, Conserved> = mesh.add_attr_with_rule::<FaceKey, f64, Conserved>("area")?;
    /// assert!(mesh.add_face_attr::<f64>("area").is_err());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn add_attr_with_rule<K: Element, T: Attribute, R: Rule<T>>(
        &mut self,
        name: &str,
    ) -> Result<Attr<K, T, R>> {
        self.add_column::<K, T, R>(name, None)
    }

    fn add_column<K: Element, T: Attribute, R: Rule<T>>(
        &mut self,
        name: &str,
        value_type: Option<ValueType>,
    ) -> Result<Attr<K, T, R>> {
        if self.columns_of(K::KIND).find(name).is_some() {
            return Err(Error::AttributeExists {
                kind: K::KIND,
                name: name.to_owned(),
            });
        }
        let len = self.arena_len(K::KIND);
        let cols = self.attrs.columns_mut(K::KIND);
        let i = cols.push_dynamic(name, Box::new(Column::<T, R>::absent(len)), value_type);
        let id = cols.meta[i].id;
        self.journal_column_added(K::KIND, i);
        Ok(Attr::new(i, id, name))
    }

    /// Add a column of `T` with `T`'s own rule on the arena of `K`.
    ///
    /// # Errors
    /// [`Error::AttributeExists`] if the name is taken on that arena.
    pub fn add_attr<K: Element, T: Attribute>(&mut self, name: &str) -> Result<Attr<K, T>> {
        self.add_column::<K, T, T::Rule>(name, None)
    }

    /// Add a vertex attribute (every vertex starts without a value).
    ///
    /// # Errors
    /// [`Error::AttributeExists`] if the name is taken.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let sel = mesh.add_vertex_attr::<bool>("selected")?; // rule: Contagion
    /// let v = mesh.vertices().next().unwrap();
    /// assert_eq!(mesh.attr(&sel, v)?, None);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn add_vertex_attr<T: Attribute>(&mut self, name: &str) -> Result<VertexAttr<T>> {
        self.add_attr(name)
    }

    /// Add a half-edge attribute: corner data such as UVs and split
    /// normals (the corner of half-edge `h` is at `origin(h)` in
    /// `face(h)`).
    ///
    /// # Errors
    /// [`Error::AttributeExists`] if the name is taken.
    pub fn add_halfedge_attr<T: Attribute>(&mut self, name: &str) -> Result<HalfedgeAttr<T>> {
        self.add_attr(name)
    }

    /// Add an edge attribute (crease weights, seams).
    ///
    /// # Errors
    /// [`Error::AttributeExists`] if the name is taken.
    pub fn add_edge_attr<T: Attribute>(&mut self, name: &str) -> Result<EdgeAttr<T>> {
        self.add_attr(name)
    }

    /// Add a face attribute; hole faces carry it too.
    ///
    /// # Errors
    /// [`Error::AttributeExists`] if the name is taken.
    pub fn add_face_attr<T: Attribute>(&mut self, name: &str) -> Result<FaceAttr<T>> {
        self.add_attr(name)
    }

    /// Add a dynamic column whose values must all be of type `ty` (a PLY
    /// property read from a file), with the [`Dynamic`] rule.
    ///
    /// # Errors
    /// [`Error::AttributeExists`] if the name is taken.
    ///
    /// ```
    /// use meshloom::attr::{Value, ValueType};
    /// use meshloom::VertexKey;
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let q = mesh.add_dynamic_attr::<VertexKey>("quality", ValueType::F32)?;
    /// let v = mesh.vertices().next().unwrap();
    /// mesh.set_attr(&q, v, Value::F32(0.9))?;
    /// assert!(mesh.set_attr(&q, v, Value::U8(1)).is_err());
    /// assert_eq!(mesh.attr_value("quality", v)?, Some(Value::F32(0.9)));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn add_dynamic_attr<K: Element>(
        &mut self,
        name: &str,
        ty: ValueType,
    ) -> Result<Attr<K, Value, Dynamic>> {
        self.add_column::<K, Value, Dynamic>(name, Some(ty))
    }

    /// The handle of an existing column.
    ///
    /// # Errors
    /// [`Error::AttributeMissing`] if there is none of that name;
    /// [`Error::AttributeType`] if it holds another type or rule.
    pub fn attr_handle<K: Element, T: Attribute, R: Rule<T>>(
        &self,
        name: &str,
    ) -> Result<Attr<K, T, R>> {
        let cols = self.columns_of(K::KIND);
        let i = cols.find(name).ok_or_else(|| Error::AttributeMissing {
            kind: K::KIND,
            name: name.to_owned(),
        })?;
        if cols.typed::<T, R>(i).is_none() {
            return Err(Error::AttributeType {
                kind: K::KIND,
                name: name.to_owned(),
                expected: std::any::type_name::<Column<T, R>>(),
                found: cols.cols[i].1.type_name(),
            });
        }
        Ok(Attr::new(i, cols.meta[i].id, name))
    }

    /// The position column's handle, if the mesh has positions. Writing
    /// through it refuses non-finite coordinates like
    /// [`Mesh::set_position`].
    pub fn position_attr(&self) -> Option<VertexAttr<[f64; 3], Interpolate>> {
        let i = self.attrs.position?;
        Some(Attr::new(
            i,
            self.attrs.vertex.meta[i].id,
            crate::store::POSITION,
        ))
    }

    /// Remove a column and every value in it. Removing the position column
    /// leaves a mesh without positions.
    ///
    /// # Errors
    /// [`Error::AttributeHandle`] if it was removed already.
    pub fn remove_attr<K: Element, T: Attribute, R>(&mut self, h: &Attr<K, T, R>) -> Result<()> {
        let i = self.resolve(h)?;
        if self.journal_column_removed(K::KIND, i) {
            // The journal took the column (kept for undo).
            return Ok(());
        }
        self.attrs.columns_mut(K::KIND).remove(i);
        if K::KIND == ElementKind::Vertex {
            self.attrs.position = match self.attrs.position {
                Some(p) if p == i => None,
                Some(p) if p > i => Some(p - 1),
                p => p,
            };
        }
        Ok(())
    }

    /// The columns of one arena, in the order they were added.
    ///
    /// ```
    /// use meshloom::ElementKind;
    /// let mesh = meshloom::shapes::cube();
    /// let names: Vec<_> = mesh.attr_info(ElementKind::Vertex).into_iter().map(|a| a.name).collect();
    /// assert_eq!(names, ["position"]);
    /// ```
    pub fn attr_info(&self, kind: ElementKind) -> Vec<AttrInfo> {
        let cols = self.columns_of(kind);
        cols.cols
            .iter()
            .zip(&cols.meta)
            .map(|((name, c), m)| {
                // A dynamic column without a declared type (one read back
                // from a file with mixed values) has no single value type.
                let dynamic = c.as_any().is::<Column<Value, Dynamic>>();
                AttrInfo {
                    name: name.clone(),
                    type_name: c.type_name(),
                    rule: c.rule_name(),
                    value_type: if dynamic {
                        m.value_type
                    } else {
                        c.portable_type()
                    },
                    dynamic,
                }
            })
            .collect()
    }

    // ----- values by key ---------------------------------------------------------

    /// The value of `key`'s element (`None`: it has none).
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::AttributeHandle`].
    #[inline]
    pub fn attr<K: Element, T: Attribute, R: Rule<T>>(
        &self,
        h: &Attr<K, T, R>,
        key: K,
    ) -> Result<Option<&T>> {
        let i = self.element_slot(key)?;
        Ok(self.typed_column(h)?.get(i))
    }

    /// Set the value of `key`'s element.
    ///
    /// Every value of an attribute type is accepted, NaN and the infinities
    /// included (a NaN often marks "no data"; only positions must be
    /// finite), and every accepted value survives serde: JSON, which has no
    /// such numbers, carries them as the strings `"NaN"`, `"inf"` and
    /// `"-inf"` (with the `serde` feature).
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::AttributeHandle`];
    /// [`Error::AttributeType`] for a [`Value`] of another type than a
    /// dynamic column declares; [`Error::NonFinitePosition`] through the
    /// position handle.
    pub fn set_attr<K: Element, T: Attribute, R: Rule<T>>(
        &mut self,
        h: &Attr<K, T, R>,
        key: K,
        value: T,
    ) -> Result<()> {
        self.journal_one(h, key)?;
        let out = self.attr_view_mut_unjournaled(h)?.set(key, Some(value));
        self.end_edit();
        out
    }

    /// Save `key`'s value in `h`'s column before a single write, while a
    /// journal records.
    fn journal_one<K: Element, T: Attribute, R: Rule<T>>(
        &mut self,
        h: &Attr<K, T, R>,
        key: K,
    ) -> Result<()> {
        if self.rec.is_some() {
            let col = self.resolve(h)?;
            if let Ok(i) = self.element_slot(key) {
                self.journal_attr_write(K::KIND, col, i);
            }
        }
        Ok(())
    }

    /// Remove the value of `key`'s element; returns what it was.
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::AttributeHandle`].
    pub fn clear_attr<K: Element, T: Attribute, R: Rule<T>>(
        &mut self,
        h: &Attr<K, T, R>,
        key: K,
    ) -> Result<Option<T>> {
        self.journal_one(h, key)?;
        let mut view = self.attr_view_mut_unjournaled(h)?;
        let old = view.get(key).cloned();
        let out = view.set(key, None);
        self.end_edit();
        out.map(|()| old)
    }

    /// Give every live element of the arena (holes included) `value`.
    ///
    /// # Errors
    /// As [`Mesh::set_attr`].
    pub fn fill_attr<K: Element, T: Attribute, R: Rule<T>>(
        &mut self,
        h: &Attr<K, T, R>,
        value: T,
    ) -> Result<()> {
        let (slots, shift) = self.arena_slots(K::KIND);
        let keys: Vec<K> = (0..self.arena_len(K::KIND) as u32)
            .filter_map(|i| {
                let g = slots.generation((i >> shift) as usize)?;
                (g & 1 == 1).then(|| K::from_parts(i, g))
            })
            .collect();
        let mut view = self.attr_view_mut(h)?;
        let mut out = Ok(());
        for k in keys {
            if let Err(e) = view.set(k, Some(value.clone())) {
                out = Err(e);
                break;
            }
        }
        view.drop_full_presence();
        self.end_edit();
        out
    }

    /// A read-only view of a column: O(1) `get` by key without the handle
    /// check, and iteration over the elements that have a value.
    ///
    /// # Errors
    /// [`Error::AttributeHandle`].
    #[inline]
    pub fn attr_view<K: Element, T: Attribute, R: Rule<T>>(
        &self,
        h: &Attr<K, T, R>,
    ) -> Result<AttrView<'_, K, T>> {
        let col = self.typed_column(h)?;
        let (slots, _) = self.arena_slots(K::KIND);
        // A column has one value per slot; the cut makes `AttrView::get`'s
        // slot bound a consequence of its value bound, whatever happens.
        let values = col.raw();
        let values = &values[..values.len().min(slots.slot_count() << K::SHIFT)];
        Ok(AttrView {
            mesh: self,
            values,
            present: col.present_bits(),
            generations: slots.stored_generations(),
            slot_count: slots.slot_count(),
            base: slots.base(),
            dense_intact: slots.intact() && col.present_bits().is_none(),
            marker: PhantomData,
        })
    }

    /// A mutable view of a column.
    ///
    /// # Errors
    /// [`Error::AttributeHandle`].
    pub fn attr_view_mut<K: Element, T: Attribute, R: Rule<T>>(
        &mut self,
        h: &Attr<K, T, R>,
    ) -> Result<AttrViewMut<'_, K, T>> {
        if self.rec.is_some() {
            let i = self.resolve(h)?;
            self.journal_bulk(K::KIND, i);
        }
        self.attr_view_mut_unjournaled(h)
    }

    /// [`Mesh::attr_view_mut`] without saving the column (the caller saved
    /// what it writes).
    fn attr_view_mut_unjournaled<K: Element, T: Attribute, R: Rule<T>>(
        &mut self,
        h: &Attr<K, T, R>,
    ) -> Result<AttrViewMut<'_, K, T>> {
        let i = self.resolve(h)?;
        // The view may write anything (positions included).
        self.bump_revision();
        let is_position = K::KIND == ElementKind::Vertex && self.attrs.position == Some(i);
        let (slots, shift) = match K::KIND {
            ElementKind::Vertex => (&self.v_slots, 0),
            ElementKind::Halfedge => (&self.e_slots, 1),
            ElementKind::Edge => (&self.e_slots, 0),
            ElementKind::Face => (&self.f_slots, 0),
        };
        let cols = self.attrs.columns_mut(K::KIND);
        let value_type = cols.meta[i].value_type;
        let (name, col) = &mut cols.cols[i];
        let col: &mut Column<T, R> = col
            .as_any_mut()
            .downcast_mut()
            .ok_or_else(|| stale_handle(h))?;
        Ok(AttrViewMut {
            values: &mut col.values,
            present: &mut col.present,
            absent: &mut col.absent,
            slots,
            shift,
            value_type,
            name,
            finite: is_position,
            marker: PhantomData,
        })
    }
}

fn stale_handle<K: Element, T: Attribute, R>(h: &Attr<K, T, R>) -> Error {
    Error::AttributeHandle {
        kind: K::KIND,
        name: h.name.clone(),
    }
}
