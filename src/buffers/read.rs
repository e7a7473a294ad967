//! Reading a column of any numeric type as `f64`s: typed views for the
//! common types (one slice read per value), dynamic values for the rest.

use crate::attr::{AttrView, Element, Interpolate, Value};
use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// A column being read, with its values per element.
pub(crate) enum Reader<'m, K: Element> {
    F32(AttrView<'m, K, f32>),
    F64(AttrView<'m, K, f64>),
    A2f32(AttrView<'m, K, [f32; 2]>),
    A3f32(AttrView<'m, K, [f32; 3]>),
    A4f32(AttrView<'m, K, [f32; 4]>),
    A2f64(AttrView<'m, K, [f64; 2]>),
    A3f64(AttrView<'m, K, [f64; 3]>),
    A4f64(AttrView<'m, K, [f64; 4]>),
    /// Any other portable column, through [`Value`]s.
    Dynamic {
        mesh: &'m Mesh,
        name: String,
        components: usize,
    },
}

impl<'m, K: Element> Reader<'m, K> {
    /// A reader of column `name` on `K`'s arena.
    ///
    /// # Errors
    /// [`Error::AttributeMissing`]; [`Error::AttributeType`] for values
    /// that are not numbers or lists of numbers.
    pub(crate) fn new(
        mesh: &'m Mesh,
        name: &str,
        keys: impl Iterator<Item = K>,
    ) -> Result<Reader<'m, K>> {
        macro_rules! typed {
            ($t:ty, $variant:ident) => {
                if let Ok(h) = mesh.attr_handle::<K, $t, Interpolate>(name) {
                    return Ok(Reader::$variant(mesh.attr_view(&h)?));
                }
            };
        }
        typed!([f32; 2], A2f32);
        typed!([f32; 3], A3f32);
        typed!([f32; 4], A4f32);
        typed!([f64; 2], A2f64);
        typed!([f64; 3], A3f64);
        typed!([f64; 4], A4f64);
        typed!(f32, F32);
        typed!(f64, F64);
        let info = mesh
            .attr_info(K::KIND)
            .into_iter()
            .find(|a| a.name == name)
            .ok_or_else(|| Error::AttributeMissing {
                kind: K::KIND,
                name: name.to_owned(),
            })?;
        let not_numbers = |found: &'static str| Error::AttributeType {
            kind: K::KIND,
            name: name.to_owned(),
            expected: "numbers or lists of numbers",
            found,
        };
        // The first value present tells the width.
        let mut components = None;
        for k in keys {
            if let Some(v) = mesh.attr_value(name, k)? {
                components = Some(width(&v).ok_or_else(|| not_numbers(v.value_type().name()))?);
                break;
            }
        }
        Ok(Reader::Dynamic {
            mesh,
            name: name.to_owned(),
            components: match components {
                Some(c) => c,
                // No value at all: one zero per vertex.
                None if info.value_type.is_some() => 1,
                None => return Err(not_numbers(info.type_name)),
            },
        })
    }

    /// Values per element.
    pub(crate) fn components(&self) -> usize {
        match self {
            Reader::F32(_) | Reader::F64(_) => 1,
            Reader::A2f32(_) | Reader::A2f64(_) => 2,
            Reader::A3f32(_) | Reader::A3f64(_) => 3,
            Reader::A4f32(_) | Reader::A4f64(_) => 4,
            Reader::Dynamic { components, .. } => *components,
        }
    }

    /// `key`'s values into `out` (`components` long); zeros if absent.
    #[inline]
    pub(crate) fn read(&self, key: K, out: &mut [f64]) {
        fn put<const N: usize, T: Copy + Into<f64>>(v: Option<&[T; N]>, out: &mut [f64]) {
            match v {
                Some(v) => out.iter_mut().zip(v).for_each(|(o, &x)| *o = x.into()),
                None => out.fill(0.0),
            }
        }
        match self {
            Reader::F32(a) => out[0] = a.get(key).map_or(0.0, |&x| x.into()),
            Reader::F64(a) => out[0] = a.get(key).copied().unwrap_or(0.0),
            Reader::A2f32(a) => put(a.get(key), out),
            Reader::A3f32(a) => put(a.get(key), out),
            Reader::A4f32(a) => put(a.get(key), out),
            Reader::A2f64(a) => put(a.get(key), out),
            Reader::A3f64(a) => put(a.get(key), out),
            Reader::A4f64(a) => put(a.get(key), out),
            Reader::Dynamic { mesh, name, .. } => {
                out.fill(0.0);
                match mesh.attr_value(name, key).ok().flatten() {
                    Some(Value::List(items)) => {
                        for (o, x) in out.iter_mut().zip(&items) {
                            *o = x.as_f64().unwrap_or(0.0);
                        }
                    }
                    Some(v) => out[0] = v.as_f64().unwrap_or(0.0),
                    None => {}
                }
            }
        }
    }
}

/// How many numbers a value holds, if it holds only numbers.
fn width(v: &Value) -> Option<usize> {
    match v {
        Value::List(items) => items
            .iter()
            .all(|x| x.as_f64().is_some())
            .then_some(items.len()),
        other => other.as_f64().map(|_| 1),
    }
}
