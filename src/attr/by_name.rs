//! Attribute values by column name as dynamic [`Value`]s: how file
//! readers and writers move attributes whose types they learn at run time.

use super::handle::Element;
use super::view::check_dynamic;
use crate::error::{Error, Result};
use crate::keys::{AnyKey, EdgeKey, ElementKind, FaceKey, HalfedgeKey, VertexKey};
use crate::mesh::Mesh;
use crate::store::{Attribute, Value, ValueType};

impl Mesh {
    /// [`Mesh::add_dynamic_attr`] with the arena chosen at run time (a file
    /// reader that meets an element name).
    ///
    /// # Errors
    /// [`Error::AttributeExists`] if the name is taken.
    ///
    /// ```
    /// use meshloom::attr::{Value, ValueType};
    /// use meshloom::{AnyKey, ElementKind};
    /// let mut mesh = meshloom::shapes::cube();
    /// mesh.add_dynamic_attr_in(ElementKind::Face, "group", ValueType::Text)?;
    /// let f = AnyKey::Face(mesh.faces().next().unwrap());
    /// mesh.set_attr_value_at("group", f, Some(&Value::Text("lid".into())))?;
    /// assert_eq!(mesh.attr_value_at("group", f)?, Some(Value::Text("lid".into())));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn add_dynamic_attr_in(
        &mut self,
        kind: ElementKind,
        name: &str,
        ty: ValueType,
    ) -> Result<()> {
        match kind {
            ElementKind::Vertex => self.add_dynamic_attr::<VertexKey>(name, ty).map(drop),
            ElementKind::Halfedge => self.add_dynamic_attr::<HalfedgeKey>(name, ty).map(drop),
            ElementKind::Edge => self.add_dynamic_attr::<EdgeKey>(name, ty).map(drop),
            ElementKind::Face => self.add_dynamic_attr::<FaceKey>(name, ty).map(drop),
        }
    }

    /// [`Mesh::attr_value`] for a key of any kind.
    ///
    /// # Errors
    /// As [`Mesh::attr_value`].
    pub fn attr_value_at(&self, name: &str, key: AnyKey) -> Result<Option<Value>> {
        match key {
            AnyKey::Vertex(k) => self.attr_value(name, k),
            AnyKey::Halfedge(k) => self.attr_value(name, k),
            AnyKey::Edge(k) => self.attr_value(name, k),
            AnyKey::Face(k) => self.attr_value(name, k),
        }
    }

    /// [`Mesh::set_attr_value`] for a key of any kind.
    ///
    /// # Errors
    /// As [`Mesh::set_attr_value`].
    pub fn set_attr_value_at(
        &mut self,
        name: &str,
        key: AnyKey,
        value: Option<&Value>,
    ) -> Result<()> {
        match key {
            AnyKey::Vertex(k) => self.set_attr_value(name, k, value),
            AnyKey::Halfedge(k) => self.set_attr_value(name, k, value),
            AnyKey::Edge(k) => self.set_attr_value(name, k, value),
            AnyKey::Face(k) => self.set_attr_value(name, k, value),
        }
    }

    /// The value of `key`'s element in the column `name`, of any portable
    /// type, as a [`Value`]: how file writers read attributes.
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::AttributeMissing`].
    pub fn attr_value<K: Element>(&self, name: &str, key: K) -> Result<Option<Value>> {
        let i = self.element_slot(key)?;
        let cols = self.columns_of(K::KIND);
        let c = cols.find(name).ok_or_else(|| Error::AttributeMissing {
            kind: K::KIND,
            name: name.to_owned(),
        })?;
        Ok(cols.cols[c].1.value_at(i))
    }

    /// Set `key`'s value in the column `name` from a [`Value`] (`None`
    /// clears it): how file readers write attributes.
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::AttributeMissing`];
    /// [`Error::AttributeType`] if the value does not convert to the
    /// column's type.
    pub fn set_attr_value<K: Element>(
        &mut self,
        name: &str,
        key: K,
        value: Option<&Value>,
    ) -> Result<()> {
        let i = self.element_slot(key)?;
        let is_position_column = K::KIND == ElementKind::Vertex
            && self.attrs.position.is_some()
            && self.attrs.vertex.find(name) == self.attrs.position;
        if is_position_column {
            if let Some(v) = value {
                let p =
                    <[f64; 3]>::from_value(v).ok_or_else(|| mismatch::<K>(name, "[f64; 3]", v))?;
                return self.set_position(VertexKey::new(key.slot(), key.generation_of_key()), p);
            }
        }
        let cols = self.attrs.columns_mut(K::KIND);
        let c = cols.find(name).ok_or_else(|| Error::AttributeMissing {
            kind: K::KIND,
            name: name.to_owned(),
        })?;
        if let (Some(ty), Some(v)) = (cols.meta[c].value_type, value) {
            check_dynamic(K::KIND, name, ty, v)?;
        }
        self.journal_attr_write(K::KIND, c, i);
        let col = &mut self.attrs.columns_mut(K::KIND).cols[c].1;
        let ok = col.set_value(i, value);
        let type_name = col.type_name();
        self.end_edit();
        if ok {
            Ok(())
        } else {
            let v = value.cloned().unwrap_or_default();
            Err(mismatch::<K>(name, type_name, &v))
        }
    }
}

fn mismatch<K: Element>(name: &str, expected: &'static str, v: &Value) -> Error {
    Error::AttributeType {
        kind: K::KIND,
        name: name.to_owned(),
        expected,
        found: v.value_type().name(),
    }
}
