//! serde for the floats of a [`Value`](super::Value): NaN and the
//! infinities are values like any other, and JSON has no numbers for them.
//! Lives beside `Value` (not with the mesh's serde in `serde_impl`), so the
//! storage layer does not depend on the serde of the layers above it.

/// serde for floats that may be NaN or infinite: finite ones as numbers,
/// the others as `"NaN"`, `"inf"` or `"-inf"` where the format is human
/// readable (JSON cannot hold them as numbers). Reading takes a number, one
/// of those strings (also `"nan"`, `"+inf"`, `"infinity"`, any case), or
/// `null` as NaN.
macro_rules! nonfinite_float {
    ($name:ident, $t:ty, $visit_float:ident, $deserialize_float:ident) => {
        pub(crate) mod $name {
            use serde::de::{self, Visitor};
            use serde::{Deserializer, Serializer};
            use std::fmt;

            pub(crate) fn serialize<S: Serializer>(x: &$t, s: S) -> Result<S::Ok, S::Error> {
                if x.is_finite() || !s.is_human_readable() {
                    return s.$visit_float(*x);
                }
                s.serialize_str(if x.is_nan() {
                    "NaN"
                } else if *x > 0.0 {
                    "inf"
                } else {
                    "-inf"
                })
            }

            struct Float;

            impl Visitor<'_> for Float {
                type Value = $t;
                fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                    f.write_str("a number, or \"NaN\", \"inf\" or \"-inf\"")
                }
                fn visit_f64<E: de::Error>(self, v: f64) -> Result<$t, E> {
                    Ok(v as $t)
                }
                fn visit_f32<E: de::Error>(self, v: f32) -> Result<$t, E> {
                    Ok(v as $t)
                }
                fn visit_i64<E: de::Error>(self, v: i64) -> Result<$t, E> {
                    Ok(v as $t)
                }
                fn visit_u64<E: de::Error>(self, v: u64) -> Result<$t, E> {
                    Ok(v as $t)
                }
                fn visit_unit<E: de::Error>(self) -> Result<$t, E> {
                    Ok(<$t>::NAN)
                }
                fn visit_none<E: de::Error>(self) -> Result<$t, E> {
                    Ok(<$t>::NAN)
                }
                fn visit_str<E: de::Error>(self, v: &str) -> Result<$t, E> {
                    match v.to_ascii_lowercase().as_str() {
                        "nan" => Ok(<$t>::NAN),
                        "inf" | "+inf" | "infinity" | "+infinity" => Ok(<$t>::INFINITY),
                        "-inf" | "-infinity" => Ok(<$t>::NEG_INFINITY),
                        _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
                    }
                }
            }

            pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<$t, D::Error> {
                if d.is_human_readable() {
                    d.deserialize_any(Float)
                } else {
                    d.$deserialize_float(Float)
                }
            }
        }
    };
}

nonfinite_float!(float32, f32, serialize_f32, deserialize_f32);
nonfinite_float!(float64, f64, serialize_f64, deserialize_f64);
