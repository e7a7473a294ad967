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

    /// Whether two values are the same, bit for bit where floats are
    /// concerned (`0.0` and `-0.0` differ, a NaN equals itself). One
    /// comparison serves everything that asks:
    ///
    /// - operators: corners whose values are the same on both sides of an
    ///   edge belong to one *wedge* (no UV seam there), so a collapse
    ///   interpolates them together;
    /// - the [journal](crate::journal), which leaves out writes that put
    ///   back the same value (a collapse that keeps `b`'s position writes
    ///   it unchanged).
    ///
    /// So it must be `true` only for values that are interchangeable in
    /// every respect the type cares about. Defaults to comparing
    /// [`to_value`](Attribute::to_value) the same way, bit for bit;
    /// `false` when the type is not portable (such a column counts as a
    /// seam everywhere, its corners keep their values, and the journal
    /// records every write to it: always correct, only larger). The stock
    /// types implement it directly.
    ///
    /// ```
    /// use meshloom::attr::Attribute;
    /// assert!([0.5f32, 0.25].same_value(&[0.5, 0.25]));
    /// assert!(!1.0f64.same_value(&2.0));
    /// assert!(!0.0f64.same_value(&-0.0));
    /// assert!(f64::NAN.same_value(&f64::NAN));
    /// ```
    fn same_value(&self, other: &Self) -> bool {
        matches!((self.to_value(), other.to_value()), (Some(a), Some(b)) if bitwise_equal(&a, &b))
    }
}

macro_rules! scalar_attribute {
    ($rule:ty, $same:expr; $($t:ty => $variant:ident),*) => {$(
        impl Attribute for $t {
            type Rule = $rule;
            #[inline]
            fn same_value(&self, other: &Self) -> bool {
                $same(self, other)
            }
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

scalar_attribute!(Interpolate, |a: &f32, b: &f32| a.to_bits() == b.to_bits(); f32 => F32);
scalar_attribute!(Interpolate, |a: &f64, b: &f64| a.to_bits() == b.to_bits(); f64 => F64);
scalar_attribute!(Incompatible, PartialEq::eq; i8 => I8, u8 => U8, i16 => I16, u16 => U16, i32 => I32,
    u32 => U32, i64 => I64, u64 => U64, String => Text);
scalar_attribute!(Contagion, PartialEq::eq; bool => Bool);

macro_rules! array_attribute {
    ($($t:ty => $variant:ident),*) => {$(
        impl<const N: usize> Attribute for [$t; N]
        where
            [$t; N]: Default,
        {
            type Rule = Interpolate;
            #[inline]
            fn same_value(&self, other: &Self) -> bool {
                self.iter().zip(other).all(|(a, b)| a.to_bits() == b.to_bits())
            }
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
    fn same_value(&self, other: &Self) -> bool {
        bitwise_equal(self, other)
    }
    fn to_value(&self) -> Option<Value> {
        Some(self.clone())
    }
    fn from_value(value: &Value) -> Option<Self> {
        Some(value.clone())
    }
}

/// Values equal bit for bit (floats by their bits, lists item by item).
fn bitwise_equal(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::F32(x), Value::F32(y)) => x.to_bits() == y.to_bits(),
        (Value::F64(x), Value::F64(y)) => x.to_bits() == y.to_bits(),
        (Value::List(x), Value::List(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(p, q)| bitwise_equal(p, q))
        }
        (Value::F32(_) | Value::F64(_) | Value::List(_), _) => false,
        _ => a == b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_value_is_bitwise() {
        assert!(1.5f64.same_value(&1.5));
        assert!(!0.0f64.same_value(&-0.0));
        assert!(f64::NAN.same_value(&f64::NAN));
        assert!([1.0f32, -0.0].same_value(&[1.0, -0.0]));
        assert!(![1.0f32, -0.0].same_value(&[1.0, 0.0]));
        assert!(7u8.same_value(&7) && !7u8.same_value(&8));
        let l = Value::List(vec![Value::F64(-0.0), Value::Text("a".into())]);
        assert!(l.same_value(&l.clone()));
        assert!(!l.same_value(&Value::List(vec![Value::F64(0.0), Value::Text("a".into())])));
        assert!(!Value::F32(1.0).same_value(&Value::F64(1.0)));
        assert!(Value::U8(3).same_value(&Value::U8(3)));
    }

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
