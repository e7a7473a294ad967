//! Dynamic attribute values: data whose type is known only at run time (a
//! PLY property `quality: f32`, an OBJ group name).

use std::fmt;

use super::rule::Rule;

/// One dynamic attribute value.
///
/// ```
/// use meshloom::attr::{Value, ValueType};
/// let q = Value::F32(0.5);
/// assert_eq!(q.value_type(), ValueType::F32);
/// assert_eq!(q.as_f64(), Some(0.5));
/// ```
#[derive(Clone, Debug, PartialEq, PartialOrd)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Value {
    /// A flag.
    Bool(bool),
    /// 8-bit signed integer.
    I8(i8),
    /// 8-bit unsigned integer.
    U8(u8),
    /// 16-bit signed integer.
    I16(i16),
    /// 16-bit unsigned integer.
    U16(u16),
    /// 32-bit signed integer.
    I32(i32),
    /// 32-bit unsigned integer.
    U32(u32),
    /// 64-bit signed integer.
    I64(i64),
    /// 64-bit unsigned integer.
    U64(u64),
    /// 32-bit float. NaN and the infinities are values like any other;
    /// serde carries them as the strings `"NaN"`, `"inf"` and `"-inf"` in
    /// human-readable formats (JSON has no such numbers).
    F32(#[cfg_attr(feature = "serde", serde(with = "crate::store::float_serde::float32"))] f32),
    /// 64-bit float; non-finite values as for [`Value::F32`].
    F64(#[cfg_attr(feature = "serde", serde(with = "crate::store::float_serde::float64"))] f64),
    /// Text.
    Text(String),
    /// A list (a PLY list property, a fixed-size vector).
    List(Vec<Value>),
}

impl Default for Value {
    fn default() -> Self {
        Value::Bool(false)
    }
}

/// The type of a [`Value`], declared when a dynamic column is added.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[allow(missing_docs)]
pub enum ValueType {
    Bool,
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
    Text,
    /// A list of any values.
    List,
}

impl ValueType {
    /// The type's name, as in a PLY header where one exists (`float`,
    /// `uchar`, ...) and `bool`, `text`, `list` otherwise.
    pub fn name(self) -> &'static str {
        match self {
            ValueType::Bool => "bool",
            ValueType::I8 => "char",
            ValueType::U8 => "uchar",
            ValueType::I16 => "short",
            ValueType::U16 => "ushort",
            ValueType::I32 => "int",
            ValueType::U32 => "uint",
            ValueType::I64 => "long",
            ValueType::U64 => "ulong",
            ValueType::F32 => "float",
            ValueType::F64 => "double",
            ValueType::Text => "text",
            ValueType::List => "list",
        }
    }
}

impl fmt::Display for ValueType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Value {
    /// The value's type.
    pub fn value_type(&self) -> ValueType {
        match self {
            Value::Bool(_) => ValueType::Bool,
            Value::I8(_) => ValueType::I8,
            Value::U8(_) => ValueType::U8,
            Value::I16(_) => ValueType::I16,
            Value::U16(_) => ValueType::U16,
            Value::I32(_) => ValueType::I32,
            Value::U32(_) => ValueType::U32,
            Value::I64(_) => ValueType::I64,
            Value::U64(_) => ValueType::U64,
            Value::F32(_) => ValueType::F32,
            Value::F64(_) => ValueType::F64,
            Value::Text(_) => ValueType::Text,
            Value::List(_) => ValueType::List,
        }
    }

    /// The value as `f64`, for any number (integers converted, possibly
    /// rounded for 64-bit ones); `None` for flags, text and lists.
    pub fn as_f64(&self) -> Option<f64> {
        Some(match *self {
            Value::I8(x) => x.into(),
            Value::U8(x) => x.into(),
            Value::I16(x) => x.into(),
            Value::U16(x) => x.into(),
            Value::I32(x) => x.into(),
            Value::U32(x) => x.into(),
            Value::I64(x) => x as f64,
            Value::U64(x) => x as f64,
            Value::F32(x) => x.into(),
            Value::F64(x) => x,
            _ => return None,
        })
    }

    /// Whether this is a float or a non-empty list of floats: the values
    /// [`Dynamic`] interpolates.
    fn is_float_like(&self) -> bool {
        match self {
            Value::F32(_) | Value::F64(_) => true,
            Value::List(l) => {
                !l.is_empty() && l.iter().all(|x| matches!(x, Value::F32(_) | Value::F64(_)))
            }
            _ => false,
        }
    }

    /// Weighted mean of values of one shape (the first's), or `None` when
    /// the shapes differ.
    fn mean(values: &[(&Value, f64)]) -> Option<Value> {
        let (first, _) = values.first()?;
        match first {
            Value::F32(_) | Value::F64(_) => {
                let mut sum = 0.0;
                for (v, w) in values {
                    if v.value_type() != first.value_type() {
                        return None;
                    }
                    sum += v.as_f64()? * w;
                }
                Some(match first {
                    Value::F32(_) => Value::F32(sum as f32),
                    _ => Value::F64(sum),
                })
            }
            Value::List(l) => {
                let mut out = Vec::with_capacity(l.len());
                for i in 0..l.len() {
                    let column: Option<Vec<(&Value, f64)>> = values
                        .iter()
                        .map(|(v, w)| match v {
                            Value::List(m) if m.len() == l.len() => Some((&m[i], *w)),
                            _ => None,
                        })
                        .collect();
                    out.push(Value::mean(&column?)?);
                }
                Some(Value::List(out))
            }
            _ => None,
        }
    }
}

/// The rule of dynamic columns: floats (and lists of floats of one length)
/// interpolate like [`Interpolate`](super::rules::Interpolate); every other value
/// is [`Incompatible`](super::rules::Incompatible) (kept only when all
/// contributors agree). Split pieces keep the source value.
///
/// ```
/// use meshloom::attr::{Dynamic, Rule, Value};
/// let (a, b) = (Value::F32(1.0), Value::F32(3.0));
/// assert_eq!(Dynamic::merge(&[(Some(&a), 0.5), (Some(&b), 0.5)]), Some(Value::F32(2.0)));
/// let (x, y) = (Value::U8(1), Value::U8(2));
/// assert_eq!(Dynamic::merge(&[(Some(&x), 0.5), (Some(&y), 0.5)]), None);
/// assert_eq!(Dynamic::merge(&[(Some(&x), 0.5), (Some(&x), 0.5)]), Some(Value::U8(1)));
/// ```
#[derive(Copy, Clone, Debug, Default)]
pub struct Dynamic;

impl Rule<Value> for Dynamic {
    /// Floats (and lists of floats) are averaged like [`Interpolate`](super::rules::Interpolate);
    /// other values are kept only where every contributor agrees.
    const LINEAR: bool = true;

    fn name() -> &'static str {
        "Dynamic"
    }

    fn merge(inputs: &[(Option<&Value>, f64)]) -> Option<Value> {
        let present: Vec<(&Value, f64)> = inputs
            .iter()
            .filter_map(|(v, w)| Some(((*v)?, *w)))
            .collect();
        let first = present.first()?.0;
        if first.is_float_like() {
            let total: f64 = present.iter().map(|(_, w)| w).sum();
            let n = present.len() as f64;
            let weighted: Vec<(&Value, f64)> = present
                .iter()
                .map(|(v, w)| (*v, if total > 0.0 { w / total } else { 1.0 / n }))
                .collect();
            Value::mean(&weighted)
        } else if present.len() == inputs.len() && present.iter().all(|(v, _)| *v == first) {
            Some(first.clone())
        } else {
            None
        }
    }

    fn split(source: Option<&Value>, _share: f64) -> Option<Value> {
        source.cloned()
    }

    fn infer(neighbours: &[(Option<&Value>, f64)]) -> Option<Value> {
        let first = neighbours.iter().find_map(|(v, _)| *v)?;
        if first.is_float_like() {
            Self::merge(neighbours)
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_of_floats_interpolate() {
        let a = Value::List(vec![Value::F64(0.0), Value::F64(2.0)]);
        let b = Value::List(vec![Value::F64(2.0), Value::F64(4.0)]);
        let m = Dynamic::merge(&[(Some(&a), 0.5), (Some(&b), 0.5), (None, 0.0)]);
        assert_eq!(m, Some(Value::List(vec![Value::F64(1.0), Value::F64(3.0)])));
        let c = Value::List(vec![Value::F64(2.0)]);
        assert_eq!(Dynamic::merge(&[(Some(&a), 0.5), (Some(&c), 0.5)]), None);
    }

    #[test]
    fn mixed_float_types_do_not_mix() {
        let a = Value::F32(1.0);
        let b = Value::F64(1.0);
        assert_eq!(Dynamic::merge(&[(Some(&a), 0.5), (Some(&b), 0.5)]), None);
    }

    #[test]
    fn text_is_incompatible_with_absence() {
        let a = Value::Text("steel".into());
        assert_eq!(Dynamic::merge(&[(Some(&a), 0.5), (None, 0.5)]), None);
        assert_eq!(Dynamic::infer(&[(Some(&a), 1.0)]), None);
    }
}
