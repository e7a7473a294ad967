//! The [`Attribute`] trait: a value type that states its rule, and the
//! stock types that implement it.

use super::rule::Rule;
use super::rules::{Contagion, Incompatible, Interpolate};
use super::value::{Dynamic, Value};

/// A type that can live in an attribute column, with the rule its values
/// follow when elements merge and split.
///
/// Implement it for your own types (also for foreign types: the trait is
/// meshloom's). `to_value` and `from_value` are optional: they let file
/// formats and serde carry the values; a column whose type returns `None`
/// is refused by serialization with an error naming it.
///
/// ```
/// use meshloom::attr::{Attribute, Conserved, Linear};
///
/// /// Mass in kilograms: sums when vertices merge, shares out on split.
/// #[derive(Clone, Copy, Default, Debug, PartialEq)]
/// struct Mass(f64);
///
/// impl Linear for Mass {
///     fn zero() -> Self { Mass(0.0) }
///     fn add_scaled(&mut self, other: &Self, w: f64) { self.0 += other.0 * w }
/// }
///
/// impl Attribute for Mass {
///     type Rule = Conserved;
/// }
///
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let mass = mesh.add_vertex_attr::<Mass>("mass")?;
/// let v = mesh.vertices().next().unwrap();
/// mesh.set_attr(&mass, v, Mass(2.0))?;
/// assert_eq!(mesh.attr(&mass, v)?, Some(&Mass(2.0)));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub trait Attribute: Clone + Default + Send + Sync + 'static {
    /// The rule the values follow when elements merge and split.
    type Rule: Rule<Self>;

    /// The value as a dynamic [`Value`], for file formats and serde.
    /// Defaults to `None`: not portable.
    fn to_value(&self) -> Option<Value> {
        None
    }

    /// The value back from a dynamic [`Value`]; `None` if it does not fit.
    fn from_value(value: &Value) -> Option<Self> {
        let _ = value;
        None
    }
}

macro_rules! scalar_attribute {
    ($rule:ty: $($t:ty => $variant:ident),*) => {$(
        impl Attribute for $t {
            type Rule = $rule;
            fn to_value(&self) -> Option<Value> {
                Some(Value::$variant(self.clone()))
            }
            fn from_value(value: &Value) -> Option<Self> {
                match value {
                    Value::$variant(x) => Some(x.clone()),
                    _ => None,
                }
            }
        }
    )*};
}

scalar_attribute!(Interpolate: f32 => F32, f64 => F64);
scalar_attribute!(Incompatible: i8 => I8, u8 => U8, i16 => I16, u16 => U16, i32 => I32,
    u32 => U32, i64 => I64, u64 => U64, String => Text);
scalar_attribute!(Contagion: bool => Bool);

macro_rules! array_attribute {
    ($($t:ty => $variant:ident),*) => {$(
        impl<const N: usize> Attribute for [$t; N]
        where
            [$t; N]: Default,
        {
            type Rule = Interpolate;
            fn to_value(&self) -> Option<Value> {
                Some(Value::List(self.iter().map(|&x| Value::$variant(x)).collect()))
            }
            fn from_value(value: &Value) -> Option<Self> {
                let Value::List(items) = value else { return None };
                if items.len() != N {
                    return None;
                }
                let mut out = [<$t>::default(); N];
                for (o, item) in out.iter_mut().zip(items) {
                    match item {
                        Value::$variant(x) => *o = *x,
                        _ => return None,
                    }
                }
                Some(out)
            }
        }
    )*};
}

array_attribute!(f32 => F32, f64 => F64);

impl Attribute for Value {
    type Rule = Dynamic;
    fn to_value(&self) -> Option<Value> {
        Some(self.clone())
    }
    fn from_value(value: &Value) -> Option<Self> {
        Some(value.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_round_trip() {
        assert_eq!(f64::from_value(&2.5f64.to_value().unwrap()), Some(2.5));
        assert_eq!(u8::from_value(&Value::U16(3)), None);
        let a = [1.0f32, 2.0, 3.0];
        assert_eq!(<[f32; 3]>::from_value(&a.to_value().unwrap()), Some(a));
        assert_eq!(<[f32; 2]>::from_value(&a.to_value().unwrap()), None);
        assert_eq!(
            String::from_value(&Value::Text("x".into())),
            Some("x".into())
        );
    }
}
