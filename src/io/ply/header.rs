//! The PLY header: elements, typed properties, the encoding.

use std::io::Write;

use super::PlyEncoding;
use crate::attr::{Value, ValueType};
use crate::io::error::{Error, Location};
use crate::io::text::{Lines, Tokens};

/// A scalar type of the PLY header.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    pub(super) fn parse(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    pub(super) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    pub(super) fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// A value read as `f64` (exact for every PLY type) in its own type.
    pub(super) fn value(self, v: f64) -> Value {
        match self {
            Scalar::I8 => Value::I8(v as i8),
            Scalar::U8 => Value::U8(v as u8),
            Scalar::I16 => Value::I16(v as i16),
            Scalar::U16 => Value::U16(v as u16),
            Scalar::I32 => Value::I32(v as i32),
            Scalar::U32 => Value::U32(v as u32),
            Scalar::F32 => Value::F32(v as f32),
            Scalar::F64 => Value::F64(v),
        }
    }

    pub(super) fn value_type(self) -> ValueType {
        match self {
            Scalar::I8 => ValueType::I8,
            Scalar::U8 => ValueType::U8,
            Scalar::I16 => ValueType::I16,
            Scalar::U16 => ValueType::U16,
            Scalar::I32 => ValueType::I32,
            Scalar::U32 => ValueType::U32,
            Scalar::F32 => ValueType::F32,
            Scalar::F64 => ValueType::F64,
        }
    }

    /// The PLY type that holds values of `ty` (`None`: none does).
    pub(super) fn of(ty: ValueType) -> Option<Scalar> {
        Some(match ty {
            ValueType::Bool | ValueType::U8 => Scalar::U8,
            ValueType::I8 => Scalar::I8,
            ValueType::I16 => Scalar::I16,
            ValueType::U16 => Scalar::U16,
            ValueType::I32 => Scalar::I32,
            ValueType::U32 => Scalar::U32,
            ValueType::F32 => Scalar::F32,
            ValueType::F64 | ValueType::I64 | ValueType::U64 => Scalar::F64,
            ValueType::Text | ValueType::List => return None,
        })
    }

    pub(super) fn name(self) -> &'static str {
        match self {
            Scalar::I8 => "char",
            Scalar::U8 => "uchar",
            Scalar::I16 => "short",
            Scalar::U16 => "ushort",
            Scalar::I32 => "int",
            Scalar::U32 => "uint",
            Scalar::F32 => "float",
            Scalar::F64 => "double",
        }
    }

    /// Append `v` in this type.
    pub(super) fn put(self, out: &mut Vec<u8>, v: f64, encoding: PlyEncoding) {
        let be = encoding == PlyEncoding::BinaryBigEndian;
        macro_rules! bin {
            ($x:expr) => {
                out.extend_from_slice(&if be {
                    $x.to_be_bytes()
                } else {
                    $x.to_le_bytes()
                })
            };
        }
        match (encoding, self) {
            (PlyEncoding::Ascii, Scalar::F32) => {
                let _ = write!(out, "{}", v as f32);
            }
            (PlyEncoding::Ascii, Scalar::F64) => {
                let _ = write!(out, "{v}");
            }
            (PlyEncoding::Ascii, _) => {
                let _ = write!(out, "{}", v as i64);
            }
            (_, Scalar::I8) => bin!(v as i8),
            (_, Scalar::U8) => bin!(v as u8),
            (_, Scalar::I16) => bin!(v as i16),
            (_, Scalar::U16) => bin!(v as u16),
            (_, Scalar::I32) => bin!(v as i32),
            (_, Scalar::U32) => bin!(v as u32),
            (_, Scalar::F32) => bin!(v as f32),
            (_, Scalar::F64) => bin!(v),
        }
    }
}

/// A property: a scalar, or a list with its count and item types.
#[derive(Clone, Debug)]
pub(crate) struct Property {
    pub(crate) name: String,
    pub(crate) item: Scalar,
    pub(crate) count: Option<Scalar>,
}

/// An element of the header.
#[derive(Clone, Debug)]
pub(crate) struct Element {
    pub(crate) name: String,
    pub(crate) count: usize,
    pub(crate) props: Vec<Property>,
    pub(crate) line: u64,
}

impl Element {
    /// The fewest bytes one instance takes (binary), or tokens (ascii).
    pub(super) fn min_size(&self, ascii: bool) -> usize {
        self.props
            .iter()
            .map(|p| match (ascii, p.count) {
                (true, _) => 2,
                (false, Some(c)) => c.size(),
                (false, None) => p.item.size(),
            })
            .sum::<usize>()
            .max(1)
    }
}

/// The parsed header and where the body starts.
pub(crate) struct Header {
    pub(crate) encoding: PlyEncoding,
    pub(crate) elements: Vec<Element>,
    pub(crate) body: usize,
    pub(crate) body_line: u64,
    /// Lines that are not PLY header lines (Blender writes `Created by
    /// Blender ...` without `comment`), skipped as comments: the line and
    /// what it held.
    pub(crate) nonstandard: Vec<(u64, String)>,
}

/// The elements the reader takes a meaning from; each may appear once.
const KNOWN: [&str; 2] = ["vertex", "face"];

pub(super) fn header_error(line: u64, message: impl Into<String>) -> Error {
    Error::Header {
        at: Location::line(line),
        message: message.into(),
    }
}

pub(crate) fn parse_header(bytes: &[u8]) -> Result<Header, Error> {
    let mut lines = Lines::new(bytes);
    check_magic(&mut lines)?;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut nonstandard = Vec::new();
    loop {
        let Some(line) = lines.next() else {
            return Err(Error::Truncated {
                at: lines.end(),
                expected: "\"end_header\"".into(),
            });
        };
        let n = lines.line;
        let mut t = Tokens::new(line);
        match t.next().unwrap_or_default() {
            b"" | b"comment" | b"obj_info" => {}
            b"format" => encoding = Some(parse_format(&mut t, n)?),
            b"element" => {
                let element = parse_element(&mut t, n, &elements)?;
                elements.push(element);
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(header_error(n, "a property before any element"));
                };
                element.props.push(parse_property(&mut t, n)?);
            }
            b"end_header" => break,
            _ if encoding.is_some() && line.is_ascii() => {
                // Not a header keyword: other readers skip such lines (Blender
                // writes "Created by Blender ..." without "comment"). Kept so
                // that a strict read can refuse it and a repairing read can
                // report it.
                nonstandard.push((n, String::from_utf8_lossy(line.trim_ascii()).into_owned()));
            }
            other => {
                return Err(Error::syntax(
                    Location::line(n),
                    "format, element, property, comment or end_header",
                    other,
                ))
            }
        }
    }
    let encoding = encoding.ok_or_else(|| header_error(2, "no format line"))?;
    Ok(Header {
        encoding,
        elements,
        body: lines.offset(),
        body_line: lines.line,
        nonstandard,
    })
}

/// The first line: `ply`.
fn check_magic(lines: &mut Lines<'_>) -> Result<(), Error> {
    match lines.next() {
        Some(l) if l.trim_ascii() == b"ply" => Ok(()),
        Some(l) => Err(Error::syntax(
            Location::line(1),
            "the magic line \"ply\"",
            l,
        )),
        None => Err(Error::Empty {
            at: Location::whole(),
        }),
    }
}

/// The rest of a `format` line (line `n`): the encoding.
fn parse_format(t: &mut Tokens<'_>, n: u64) -> Result<PlyEncoding, Error> {
    Ok(match t.next().unwrap_or_default() {
        b"ascii" => PlyEncoding::Ascii,
        b"binary_little_endian" => PlyEncoding::BinaryLittleEndian,
        b"binary_big_endian" => PlyEncoding::BinaryBigEndian,
        other => {
            return Err(Error::syntax(
                Location::line(n),
                "ascii, binary_little_endian or binary_big_endian",
                other,
            ))
        }
    })
}

/// The rest of an `element` line (line `n`), after `elements`.
fn parse_element(t: &mut Tokens<'_>, n: u64, elements: &[Element]) -> Result<Element, Error> {
    let name = t.next().unwrap_or_default();
    let tok = t.next().unwrap_or_default();
    let count = crate::io::text::parse_i64(tok)
        .and_then(|c| usize::try_from(c).ok())
        .ok_or_else(|| Error::syntax(Location::line(n), "an element count", tok))?;
    let name = String::from_utf8_lossy(name).into_owned();
    if name.is_empty() {
        return Err(Error::syntax(Location::line(n), "an element name", b""));
    }
    if let Some(first) = elements
        .iter()
        .find(|e| e.name == name && KNOWN.contains(&name.as_str()))
    {
        return Err(header_error(
            n,
            format!(
                "a second {name} element (the first is on line {}); a PLY file has one",
                first.line
            ),
        ));
    }
    Ok(Element {
        name,
        count,
        props: Vec::new(),
        line: n,
    })
}

/// The rest of a `property` line (line `n`): a scalar or a list.
fn parse_property(t: &mut Tokens<'_>, n: u64) -> Result<Property, Error> {
    let ty = t.next().unwrap_or_default();
    let prop = if ty == b"list" {
        let (c, i) = (t.next().unwrap_or_default(), t.next().unwrap_or_default());
        let count = Scalar::parse(c)
            .filter(|s| s.is_integer())
            .ok_or_else(|| Error::syntax(Location::line(n), "an integer list count type", c))?;
        let item = Scalar::parse(i)
            .ok_or_else(|| Error::syntax(Location::line(n), "a list item type", i))?;
        t.next().map(|name| Property {
            name: String::from_utf8_lossy(name).into_owned(),
            item,
            count: Some(count),
        })
    } else {
        let item = Scalar::parse(ty)
            .ok_or_else(|| Error::syntax(Location::line(n), "a property type", ty))?;
        t.next().map(|name| Property {
            name: String::from_utf8_lossy(name).into_owned(),
            item,
            count: None,
        })
    };
    prop.ok_or_else(|| Error::syntax(Location::line(n), "a property name", b""))
}
