//! PLY (Polygon File Format), ascii and binary in both byte orders.
//!
//! The reader is written here rather than taken from `ply-rs-bw`: the
//! versions that build with this crate's minimum Rust read through a
//! generic property map per element (slow on the 871k-face dragon), and
//! what this module needs is bounded reads that never reserve by a
//! header's count and errors that name the header line or the body line
//! (ascii) or byte offset (binary) where the data is wrong. The header is
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

use super::error::{Error, Location};
use super::soup::Soup;
use super::text::{capped, parse_f64, Lines, Tokens};
use super::{emit, polygons_of, slurp, ReadOptions};
use crate::mesh::Mesh;
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
    parse(&bytes)?.finish(options)
}

/// Write a mesh as PLY: `vertex` with `double x y z`, `face` with a
/// `vertex_indices` list (holes are not written).
///
/// # Errors
/// [`Error::Unwritable`] without positions; [`Error::Io`].
pub fn write_ply(mesh: &Mesh, writer: impl Write, encoding: PlyEncoding) -> Result<(), Error> {
    let p = polygons_of(mesh)?;
    let wide = p.faces().any(|f| f.len() > 255);
    let mut out = Vec::with_capacity(24 * p.positions.len() + 5 * p.indices.len() + 256);
    let format = match encoding {
        PlyEncoding::Ascii => "ascii",
        PlyEncoding::BinaryLittleEndian => "binary_little_endian",
        PlyEncoding::BinaryBigEndian => "binary_big_endian",
    };
    write!(
        out,
        "ply\nformat {format} 1.0\ncomment written by meshloom\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\nelement face {}\n\
         property list {} int vertex_indices\nend_header\n",
        p.positions.len(),
        p.face_count(),
        if wide { "uint" } else { "uchar" }
    )
    .map_err(Error::io)?;
    let be = encoding == PlyEncoding::BinaryBigEndian;
    match encoding {
        PlyEncoding::Ascii => {
            for q in &p.positions {
                writeln!(out, "{} {} {}", q[0], q[1], q[2]).map_err(Error::io)?;
            }
            for f in p.faces() {
                write!(out, "{}", f.len()).map_err(Error::io)?;
                for i in f {
                    write!(out, " {i}").map_err(Error::io)?;
                }
                out.push(b'\n');
            }
        }
        _ => {
            for q in &p.positions {
                for x in q {
                    out.extend_from_slice(&if be { x.to_be_bytes() } else { x.to_le_bytes() });
                }
            }
            for f in p.faces() {
                if wide {
                    let n = f.len() as u32;
                    out.extend_from_slice(&if be { n.to_be_bytes() } else { n.to_le_bytes() });
                } else {
                    out.push(f.len() as u8);
                }
                for &i in f {
                    let i = i as i32;
                    out.extend_from_slice(&if be { i.to_be_bytes() } else { i.to_le_bytes() });
                }
            }
        }
    }
    emit(writer, &out)
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
pub(crate) fn parse(bytes: &[u8]) -> Result<Soup, Error> {
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
    let mut soup = Soup::new();
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
        let list = if element.name == "face" {
            element
                .props
                .iter()
                .position(|p| {
                    p.count.is_some() && (p.name == "vertex_indices" || p.name == "vertex_index")
                })
                .ok_or_else(|| {
                    header_error(element.line, "the face element has no vertex_indices list")
                })
                .map(Some)?
        } else {
            None
        };
        if is_vertex {
            soup.polygons.positions.reserve(room);
        }
        if list.is_some() {
            soup.polygons.offsets.reserve(room);
            soup.face_at.reserve(room);
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
            for (k, prop) in element.props.iter().enumerate() {
                let what = || format!("{} {} of {} {}", prop.name, i, element.name, element.count);
                match prop.count {
                    None => values.push(body.value(prop.item, &what)?),
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
                            for _ in 0..n {
                                body.value(prop.item, &what)?;
                            }
                        }
                    }
                }
            }
            if is_vertex {
                soup.polygons
                    .positions
                    .push([values[xyz[0]], values[xyz[1]], values[xyz[2]]]);
            }
            if list.is_some() {
                soup.end_face(start);
            }
        }
    }
    Ok(soup)
}
