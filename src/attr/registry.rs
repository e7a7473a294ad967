//! The registry of typed columns that deserialization can rebuild.
//!
//! A serialized column names its value type and rule by their short Rust
//! names (`f64/Conserved`, `[f32; 3]/Interpolate`, `Mass/Conserved`:
//! module paths dropped, so moving a type between modules keeps files
//! readable). Deserializing rebuilds a typed column only when that key is
//! registered; the stock types with the stock rules are, and
//! [`register`] adds others. A column of an unregistered type comes back as
//! a dynamic [`Value`] column of the same name, so no data is lost.

use std::collections::HashMap;
use std::sync::{OnceLock, RwLock};

use crate::store::rule::Rule;
use crate::store::rules::{Conserved, Contagion, Discard, Incompatible, Interpolate, KeepFirst};
use crate::store::{Attribute, Column, Dynamic, ErasedColumn, Value};

type Make = fn(usize) -> Box<dyn ErasedColumn>;

fn make<T: Attribute, R: Rule<T>>(len: usize) -> Box<dyn ErasedColumn> {
    Box::new(Column::<T, R>::absent(len))
}

/// A Rust type name without module paths: `alloc::string::String` becomes
/// `String`, `[f64; 3]` stays.
pub(crate) fn short_type_name(full: &str) -> String {
    let mut out = String::with_capacity(full.len());
    let mut ident = String::new();
    for c in full.chars() {
        if c.is_alphanumeric() || c == '_' {
            ident.push(c);
        } else if c == ':' {
            ident.clear();
        } else {
            out.push_str(&ident);
            ident.clear();
            out.push(c);
        }
    }
    out.push_str(&ident);
    out
}

/// The registry key of column type `Column<T, R>`.
pub(crate) fn type_key<T, R>() -> String {
    key_of_names(std::any::type_name::<T>(), std::any::type_name::<R>())
}

/// The registry key of a stored column: `"value type/rule type"`.
pub(crate) fn column_type_key(c: &dyn ErasedColumn) -> String {
    let (value, rule) = c.type_names();
    key_of_names(value, rule)
}

fn key_of_names(value: &str, rule: &str) -> String {
    format!("{}/{}", short_type_name(value), short_type_name(rule))
}

fn registry() -> &'static RwLock<HashMap<String, Make>> {
    static REGISTRY: OnceLock<RwLock<HashMap<String, Make>>> = OnceLock::new();
    REGISTRY.get_or_init(|| {
        let mut map: HashMap<String, Make> = HashMap::new();
        macro_rules! reg {
            ($rules:tt: $($t:ty),*) => {$( reg!(@rules $t, $rules); )*};
            (@rules $t:ty, [$($r:ty),*]) => {$(
                map.insert(type_key::<$t, $r>(), make::<$t, $r>);
            )*};
        }
        reg!([Interpolate, Conserved, Contagion, Incompatible, KeepFirst, Discard]: f32, f64);
        reg!([Contagion, Incompatible, KeepFirst, Discard]:
            i8, u8, i16, u16, i32, u32, i64, u64, bool, String);
        reg!([Interpolate, Conserved, Incompatible, KeepFirst, Discard]:
            [f32; 2], [f32; 3], [f32; 4], [f64; 2], [f64; 3], [f64; 4]);
        reg!([Dynamic, KeepFirst, Discard]: Value);
        RwLock::new(map)
    })
}

/// Register `Column<T, R>` so that deserialization rebuilds it as a typed
/// column (the stock types with the stock rules are registered already).
/// Registering twice is harmless.
///
/// ```
/// use meshloom::attr::{register, Attribute, Value};
///
/// #[derive(Clone, Default, PartialEq, PartialOrd, Debug)]
/// struct Tag(u8);
/// impl Attribute for Tag {
///     type Rule = meshloom::attr::Contagion;
///     fn to_value(&self) -> Option<Value> { Some(Value::U8(self.0)) }
///     fn from_value(v: &Value) -> Option<Self> {
///         if let Value::U8(x) = v { Some(Tag(*x)) } else { None }
///     }
/// }
///
/// register::<Tag, meshloom::attr::Contagion>();
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let tag = mesh.add_vertex_attr::<Tag>("tag")?;
/// mesh.fill_attr(&tag, Tag(7))?;
/// let json = serde_json::to_string(&mesh).unwrap();
/// let back: meshloom::Mesh = serde_json::from_str(&json).unwrap();
/// let tag = back.attr_handle::<meshloom::VertexKey, Tag, meshloom::attr::Contagion>("tag")?;
/// assert_eq!(back.attr(&tag, back.vertices().next().unwrap())?, Some(&Tag(7)));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn register<T: Attribute, R: Rule<T>>() {
    let mut map = registry().write().unwrap_or_else(|e| e.into_inner());
    map.insert(type_key::<T, R>(), make::<T, R>);
}

/// A fresh column of `len` absent values for a registered key.
pub(crate) fn make_column(key: &str, len: usize) -> Option<Box<dyn ErasedColumn>> {
    let map = registry().read().unwrap_or_else(|e| e.into_inner());
    map.get(key).map(|m| m(len))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_names() {
        assert_eq!(short_type_name("alloc::string::String"), "String");
        assert_eq!(short_type_name("[f64; 3]"), "[f64; 3]");
        assert_eq!(type_key::<[f64; 3], Interpolate>(), "[f64; 3]/Interpolate");
        assert_eq!(short_type_name("a::B<c::D, [e::F; 2]>"), "B<D, [F; 2]>");
    }

    #[test]
    fn stock_columns_are_registered() {
        let c = make_column("f64/Conserved", 3).unwrap();
        assert_eq!(c.len(), 3);
        assert_eq!(column_type_key(&*c), "f64/Conserved");
        assert!(make_column("Unknown/Rule", 1).is_none());
    }
}
