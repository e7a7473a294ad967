//! PLY (Polygon File Format), ascii and binary in both byte orders.
//!
//! The reader is written here rather than taken from `ply-rs-bw`: its
//! current version needs a newer Rust than this crate's minimum (1.80), its
//! reader builds a map of named properties for every element (slow on the
//! 871k-face dragon), and what this module needs is bounded reads that
//! never reserve by a header's count and errors that name the header line,
//! or the body line (ascii) or byte offset (binary), where the data is
//! wrong. The header is
//! parsed into elements and typed properties; the body is read element by
//! element, every element the header declares (unknown ones are read and
//! skipped, so what follows them is found).
//!
//! Read: `vertex` with `x y z` (any numeric type), `face` with a list named
//! `vertex_indices` or `vertex_index`. Writing puts positions as `double`
//! so they read back exactly.
//!
//! ```
//! use meshloom::io::{read_ply, write_ply, PlyEncoding};
//! let mut bytes = Vec::new();
//! write_ply(&meshloom::shapes::cube(), &mut bytes, PlyEncoding::BinaryBigEndian)?;
//! let cube = read_ply(&bytes[..])?;
//! assert_eq!((cube.vertex_count(), cube.face_count()), (8, 6));
//! # Ok::<(), meshloom::io::Error>(())
//! ```

use std::io::{Read, Write};

use super::attrs::{Data, SoupColumn};
use super::error::{Error, Location};
use super::soup::Soup;
use super::text::{capped, parse_f64, Lines, Tokens};
use super::{emit, polygons_of, slurp, ReadOptions};
use crate::attr::{Value, ValueType};
use crate::mesh::Mesh;

const FORMAT: super::Format = super::Format::Ply;
use crate::repair::RepairReport;

/// How a PLY body is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlyEncoding {
    /// Text.
    Ascii,
    /// Binary, least significant byte first.
    BinaryLittleEndian,
    /// Binary, most significant byte first.
    BinaryBigEndian,
}

/// Read a PLY mesh, strictly.
///
/// # Errors
/// [`Error`] with the line (header, ascii body) or byte offset (binary
/// body): a malformed header, missing `x y z` or face list, a malformed or
/// truncated body, an index out of range, polygons that need repair.
pub fn read_ply(reader: impl Read) -> Result<Mesh, Error> {
    read_ply_with(reader, &ReadOptions::strict()).map(|(m, _)| m)
}

/// Read a PLY mesh with repair policies.
///
/// # Errors
/// As [`read_ply`], less what the policies repair.
pub fn read_ply_with(
    reader: impl Read,
    options: &ReadOptions,
) -> Result<(Mesh, RepairReport), Error> {
    let bytes = slurp(reader, options)?;
    super::read_soup(FORMAT, &bytes, options)
}

/// Write a mesh as PLY: `vertex` with `double x y z`, `face` with a
/// `vertex_indices` list (holes are not written), and every vertex and face
/// attribute with a PLY type as a property of that type: dynamic columns
/// keep their declared type, `f64` columns are `double`, arrays and lists
/// are list properties, `i64`/`u64` go as `double` and `bool` as `uchar`.
/// Text columns and half-edge and edge attributes have no place in PLY and
/// are left out. An element without a value writes 0 (an empty list).
///
/// # Errors
/// [`Error::Unwritable`] without positions; [`Error::Io`].
pub fn write_ply(mesh: &Mesh, writer: impl Write, encoding: PlyEncoding) -> Result<(), Error> {
    let (p, maps) = polygons_of(mesh)?;
    let vcols = out_columns(mesh, &maps.vertices);
    let fcols = out_columns(mesh, &maps.faces);
    let wide = p.faces().any(|f| f.len() > 255);
    let mut out = Vec::with_capacity(24 * p.positions.len() + 5 * p.indices.len() + 256);
    let format = match encoding {
        PlyEncoding::Ascii => "ascii",
        PlyEncoding::BinaryLittleEndian => "binary_little_endian",
        PlyEncoding::BinaryBigEndian => "binary_big_endian",
    };
    let io = Error::io;
    write!(
        out,
        "ply\nformat {format} 1.0\ncomment written by meshloom\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\n",
        p.positions.len()
    )
    .map_err(io)?;
    for c in &vcols {
        c.declare(&mut out).map_err(io)?;
    }
    writeln!(
        out,
        "element face {}\nproperty list {} int vertex_indices",
        p.face_count(),
        if wide { "uint" } else { "uchar" }
    )
    .map_err(io)?;
    for c in &fcols {
        c.declare(&mut out).map_err(io)?;
    }
    out.extend_from_slice(b"end_header\n");
    let ascii = encoding == PlyEncoding::Ascii;
    let sep = |out: &mut Vec<u8>| {
        if ascii {
            out.push(b' ');
        }
    };
    for (i, q) in p.positions.iter().enumerate() {
        for (k, &x) in q.iter().enumerate() {
            if k > 0 {
                sep(&mut out);
            }
            Scalar::F64.put(&mut out, x, encoding);
        }
        for c in &vcols {
            sep(&mut out);
            c.put(&mut out, i, encoding);
        }
        if ascii {
            out.push(b'\n');
        }
    }
    let count = if wide { Scalar::U32 } else { Scalar::U8 };
    for (i, f) in p.faces().enumerate() {
        count.put(&mut out, f.len() as f64, encoding);
        for &v in f {
            sep(&mut out);
            Scalar::I32.put(&mut out, f64::from(v), encoding);
        }
        for c in &fcols {
            sep(&mut out);
            c.put(&mut out, i, encoding);
        }
        if ascii {
            out.push(b'\n');
        }
    }
    emit(writer, &out)
}

/// One attribute column on its way out: its PLY type and every element's
/// value in dense order.
struct OutColumn {
    name: String,
    item: Scalar,
    /// `Some(count type)` for a list property.
    list: Option<Scalar>,
    values: Vec<Option<Value>>,
}

impl OutColumn {
    fn declare(&self, out: &mut Vec<u8>) -> std::io::Result<()> {
        match self.list {
            Some(c) => writeln!(
                out,
                "property list {} {} {}",
                c.name(),
                self.item.name(),
                self.name
            ),
            None => writeln!(out, "property {} {}", self.item.name(), self.name),
        }
    }

    fn put(&self, out: &mut Vec<u8>, i: usize, encoding: PlyEncoding) {
        let v = self.values[i].as_ref();
        match self.list {
            None => self
                .item
                .put(out, v.and_then(Value::as_f64).unwrap_or(0.0), encoding),
            Some(c) => {
                let items: &[Value] = match v {
                    Some(Value::List(items)) => items,
                    _ => &[],
                };
                c.put(out, items.len() as f64, encoding);
                for x in items {
                    if encoding == PlyEncoding::Ascii {
                        out.push(b' ');
                    }
                    self.item.put(out, x.as_f64().unwrap_or(0.0), encoding);
                }
            }
        }
    }
}

/// The columns of `keys`' arena that PLY can hold (positions excepted).
fn out_columns<K: crate::attr::Element>(mesh: &Mesh, keys: &[K]) -> Vec<OutColumn> {
    let mut cols = Vec::new();
    for info in mesh.attr_info(K::KIND) {
        if K::KIND == crate::ElementKind::Vertex && info.name == crate::attr::POSITION {
            continue;
        }
        let Some(ty) = info.value_type else { continue };
        let values: Vec<Option<Value>> = keys
            .iter()
            .map(|&k| mesh.attr_value(&info.name, k).ok().flatten())
            .collect();
        let name: String = info
            .name
            .chars()
            .map(|c| if c.is_whitespace() { '_' } else { c })
            .collect();
        let (item, list) = if ty == ValueType::List {
            let first = values.iter().flatten().find_map(|v| match v {
                Value::List(items) => items.first().map(Value::value_type),
                _ => None,
            });
            let item = first.and_then(Scalar::of).unwrap_or(Scalar::F64);
            let long = values
                .iter()
                .flatten()
                .any(|v| matches!(v, Value::List(items) if items.len() > 255));
            (item, Some(if long { Scalar::U32 } else { Scalar::U8 }))
        } else {
            match Scalar::of(ty) {
                Some(item) => (item, None),
                None => continue,
            }
        };
        cols.push(OutColumn {
            name,
            item,
            list,
            values,
        });
    }
    cols
}

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
    fn parse(name: &[u8]) -> Option<Scalar> {
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

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// A value read as `f64` (exact for every PLY type) in its own type.
    fn value(self, v: f64) -> Value {
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

    fn value_type(self) -> ValueType {
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
    fn of(ty: ValueType) -> Option<Scalar> {
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

    fn name(self) -> &'static str {
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
    fn put(self, out: &mut Vec<u8>, v: f64, encoding: PlyEncoding) {
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
    fn min_size(&self, ascii: bool) -> usize {
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
}

fn header_error(line: u64, message: impl Into<String>) -> Error {
    Error::Header {
        at: Location::line(line),
        message: message.into(),
    }
}

pub(crate) fn parse_header(bytes: &[u8]) -> Result<Header, Error> {
    let mut lines = Lines::new(bytes);
    match lines.next() {
        Some(l) if l.trim_ascii() == b"ply" => {}
        Some(l) => {
            return Err(Error::syntax(
                Location::line(1),
                "the magic line \"ply\"",
                l,
            ))
        }
        None => {
            return Err(Error::Empty {
                at: Location::whole(),
            })
        }
    }
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
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
            b"format" => {
                encoding = Some(match t.next().unwrap_or_default() {
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
                });
            }
            b"element" => {
                let name = t.next().unwrap_or_default();
                let tok = t.next().unwrap_or_default();
                let count = super::text::parse_i64(tok)
                    .and_then(|c| usize::try_from(c).ok())
                    .ok_or_else(|| Error::syntax(Location::line(n), "an element count", tok))?;
                elements.push(Element {
                    name: String::from_utf8_lossy(name).into_owned(),
                    count,
                    props: Vec::new(),
                    line: n,
                });
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(header_error(n, "a property before any element"));
                };
                let ty = t.next().unwrap_or_default();
                let prop = if ty == b"list" {
                    let (c, i) = (t.next().unwrap_or_default(), t.next().unwrap_or_default());
                    let count = Scalar::parse(c).filter(|s| s.is_integer()).ok_or_else(|| {
                        Error::syntax(Location::line(n), "an integer list count type", c)
                    })?;
                    let item = Scalar::parse(i)
                        .ok_or_else(|| Error::syntax(Location::line(n), "a list item type", i))?;
                    (count, item, t.next()).2.map(|name| Property {
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
                let prop =
                    prop.ok_or_else(|| Error::syntax(Location::line(n), "a property name", b""))?;
                element.props.push(prop);
            }
            b"end_header" => break,
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
    })
}

/// The body, read value by value.
enum Body<'a> {
    Ascii {
        lines: Lines<'a>,
        tokens: Tokens<'a>,
    },
    Binary {
        data: &'a [u8],
        pos: usize,
        base: usize,
        be: bool,
    },
}

impl<'a> Body<'a> {
    fn at(&self) -> Location {
        match self {
            Body::Ascii { lines, .. } => lines.here(),
            Body::Binary { pos, base, .. } => Location::byte((base + pos) as u64),
        }
    }

    fn remaining(&self) -> usize {
        match self {
            Body::Ascii { lines, .. } => lines.remaining(),
            Body::Binary { data, pos, .. } => data.len() - pos,
        }
    }

    /// The next value, as `f64` (exact for every PLY integer type).
    #[inline]
    fn value(&mut self, s: Scalar, what: &dyn Fn() -> String) -> Result<f64, Error> {
        match self {
            Body::Ascii { lines, tokens } => {
                let tok = loop {
                    if let Some(t) = tokens.next() {
                        break t;
                    }
                    match lines.next() {
                        Some(l) => *tokens = Tokens::new(l),
                        None => {
                            return Err(Error::Truncated {
                                at: lines.end(),
                                expected: what(),
                            })
                        }
                    }
                };
                let v = parse_f64(tok).ok_or_else(|| Error::syntax(lines.here(), what(), tok))?;
                if s.is_integer() && v.fract() != 0.0 {
                    return Err(Error::syntax(lines.here(), what(), tok));
                }
                Ok(v)
            }
            Body::Binary {
                data,
                pos,
                base,
                be,
            } => {
                let n = s.size();
                let Some(b) = data.get(*pos..*pos + n) else {
                    return Err(Error::Truncated {
                        at: Location::byte((*base + *pos) as u64),
                        expected: what(),
                    });
                };
                *pos += n;
                let mut a = [0u8; 8];
                a[..n].copy_from_slice(b);
                if *be {
                    a[..n].reverse();
                }
                Ok(match s {
                    Scalar::I8 => f64::from(a[0] as i8),
                    Scalar::U8 => f64::from(a[0]),
                    Scalar::I16 => f64::from(i16::from_le_bytes([a[0], a[1]])),
                    Scalar::U16 => f64::from(u16::from_le_bytes([a[0], a[1]])),
                    Scalar::I32 => f64::from(i32::from_le_bytes([a[0], a[1], a[2], a[3]])),
                    Scalar::U32 => f64::from(u32::from_le_bytes([a[0], a[1], a[2], a[3]])),
                    Scalar::F32 => f64::from(f32::from_le_bytes([a[0], a[1], a[2], a[3]])),
                    Scalar::F64 => f64::from_le_bytes(a),
                })
            }
        }
    }
}

/// Parse PLY bytes into a soup.
pub(crate) fn parse(bytes: &[u8], record: bool) -> Result<Soup, Error> {
    let header = parse_header(bytes)?;
    let ascii = header.encoding == PlyEncoding::Ascii;
    let data = &bytes[header.body..];
    let mut body = if ascii {
        let mut lines = Lines::new(data);
        lines.line = header.body_line;
        Body::Ascii {
            lines,
            tokens: Tokens::new(b""),
        }
    } else {
        Body::Binary {
            data,
            pos: 0,
            base: header.body,
            be: header.encoding == PlyEncoding::BinaryBigEndian,
        }
    };
    let vertex = header.elements.iter().find(|e| e.name == "vertex");
    let Some(vertex) = vertex else {
        return Err(header_error(2, "no vertex element"));
    };
    let nv = vertex.count;
    let mut xyz = [usize::MAX; 3];
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        xyz[k] = vertex
            .props
            .iter()
            .filter(|p| p.count.is_none())
            .position(|p| p.name == *axis)
            .ok_or_else(|| {
                header_error(
                    vertex.line,
                    format!("the vertex element has no scalar property {axis}"),
                )
            })?;
    }
    let mut soup = Soup::new(record);
    soup.binary = !ascii;
    let mut values: Vec<f64> = Vec::new();
    for element in &header.elements {
        let room = capped(element.count, body.remaining(), element.min_size(ascii));
        let least = element.count as u128 * element.min_size(ascii) as u128;
        if least > body.remaining() as u128 + 1 {
            return Err(Error::Truncated {
                at: body.at(),
                expected: format!(
                    "{} {} elements (header line {}), but only {} bytes follow",
                    element.count,
                    element.name,
                    element.line,
                    body.remaining()
                ),
            });
        }
        let is_vertex = element.name == "vertex";
        let is_face = element.name == "face";
        let list = if is_face {
            let i = element
                .props
                .iter()
                .position(|p| {
                    p.count.is_some() && (p.name == "vertex_indices" || p.name == "vertex_index")
                })
                .ok_or_else(|| {
                    header_error(element.line, "the face element has no vertex_indices list")
                })?;
            Some(i)
        } else {
            None
        };
        // Where each property goes: positions, the face list, a kept
        // attribute column, or nowhere (elements other than vertex and face).
        let keep = |k: usize, p: &Property| {
            (is_vertex && !(p.count.is_none() && ["x", "y", "z"].contains(&p.name.as_str())))
                || (is_face && Some(k) != list)
        };
        let mut extra: Vec<(usize, Vec<Value>)> = element
            .props
            .iter()
            .enumerate()
            .filter(|&(k, p)| keep(k, p))
            .map(|(k, _)| (k, Vec::with_capacity(room)))
            .collect();
        if is_vertex {
            soup.polygons.positions.reserve(room);
        }
        if is_face {
            soup.polygons.offsets.reserve(room);

            soup.polygons
                .indices
                .reserve(capped(3 * element.count, body.remaining(), 2));
        }
        for i in 0..element.count {
            let start = match &body {
                Body::Ascii { lines, .. } => lines.line + 1,
                Body::Binary { pos, base, .. } => (base + pos) as u64,
            };
            values.clear();
            let mut next_extra = 0;
            for (k, prop) in element.props.iter().enumerate() {
                let what = || {
                    format!(
                        "{} of {} {i} (of {})",
                        prop.name, element.name, element.count
                    )
                };
                let kept = extra.get(next_extra).is_some_and(|e| e.0 == k);
                match prop.count {
                    None => {
                        let v = body.value(prop.item, &what)?;
                        values.push(v);
                        if kept {
                            extra[next_extra].1.push(prop.item.value(v));
                        }
                    }
                    Some(cs) => {
                        let at = body.at();
                        let n = body.value(cs, &what)?;
                        if n < 0.0 {
                            return Err(Error::Syntax {
                                at,
                                expected: format!("a list length for {}", prop.name),
                                found: n.to_string(),
                            });
                        }
                        let n = n as usize;
                        if Some(k) == list {
                            for _ in 0..n {
                                let at = body.at();
                                let v = body.value(prop.item, &what)?;
                                if v < 0.0 || v >= nv as f64 || v.fract() != 0.0 {
                                    return Err(Error::IndexOutOfRange {
                                        at,
                                        index: v as i64,
                                        count: nv,
                                    });
                                }
                                soup.polygons.indices.push(v as u32);
                            }
                        } else {
                            let mut items = Vec::new();
                            for _ in 0..n {
                                let v = body.value(prop.item, &what)?;
                                if kept {
                                    items.push(prop.item.value(v));
                                }
                            }
                            if kept {
                                extra[next_extra].1.push(Value::List(items));
                            }
                        }
                    }
                }
                if kept {
                    next_extra += 1;
                }
            }
            if is_vertex {
                soup.polygons
                    .positions
                    .push([values[xyz[0]], values[xyz[1]], values[xyz[2]]]);
                soup.vertex_read_at(start);
            }
            if is_face {
                soup.end_face(start);
            }
        }
        for (k, column) in extra {
            let prop = &element.props[k];
            let ty = if prop.count.is_some() {
                ValueType::List
            } else {
                prop.item.value_type()
            };
            let col = SoupColumn::dense(&prop.name, Data::Dynamic(ty, column));
            if is_vertex {
                soup.attrs.vertex.push(col);
            } else {
                soup.attrs.face.push(col);
            }
        }
    }
    Ok(soup)
}
