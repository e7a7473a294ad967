//! The PLY body, read value by value with bounds checks, into a soup.

use super::header::{header_error, parse_header, Element, Header, Property, Scalar};
use super::PlyEncoding;
use crate::attr::{Value, ValueType};
use crate::io::attrs::{Data, SoupColumn};
use crate::io::error::{Error, Location};
use crate::io::soup::Soup;
use crate::io::text::{capped, parse_f64, Lines, Tokens};

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
    /// The body after `header`, read as its encoding says.
    fn open(header: &Header, bytes: &'a [u8]) -> Body<'a> {
        let data = &bytes[header.body..];
        if header.encoding == PlyEncoding::Ascii {
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
        }
    }

    /// Where the next element starts: its line (ascii) or byte offset.
    #[inline]
    fn start(&self) -> u64 {
        match self {
            Body::Ascii { lines, .. } => lines.line + 1,
            Body::Binary { pos, base, .. } => (base + pos) as u64,
        }
    }
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
    let mut body = Body::open(&header, bytes);
    let vertices = Vertices::of(&header)?;
    let mut soup = Soup::new(record);
    soup.binary = !ascii;
    soup.nonstandard = nonstandard_lines(&header);
    let mut values: Vec<f64> = Vec::new();
    for element in &header.elements {
        read_element(&mut body, element, ascii, &vertices, &mut soup, &mut values)?;
    }
    Ok(soup)
}

/// The vertex element's count and where its `x`, `y` and `z` are among its
/// scalar properties.
struct Vertices {
    count: usize,
    xyz: [usize; 3],
}

impl Vertices {
    fn of(header: &Header) -> Result<Vertices, Error> {
        let vertex = header.elements.iter().find(|e| e.name == "vertex");
        let Some(vertex) = vertex else {
            return Err(header_error(2, "no vertex element"));
        };
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
        Ok(Vertices {
            count: vertex.count,
            xyz,
        })
    }
}

/// The header's lines that are not PLY keywords, as the soup reports them.
fn nonstandard_lines(header: &Header) -> Vec<(Location, String)> {
    header
        .nonstandard
        .iter()
        .map(|(line, text)| {
            (
                Location::line(*line),
                format!(
                    "{} is not a PLY header line (format, element, property, comment, obj_info or end_header)",
                    crate::io::error::quote(text.as_bytes())
                ),
            )
        })
        .collect()
}

/// Refuse an element count the remaining bytes cannot hold.
fn check_room(body: &Body<'_>, element: &Element, ascii: bool) -> Result<(), Error> {
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
    Ok(())
}

/// The face element's list of vertex indices.
fn face_list(element: &Element) -> Result<usize, Error> {
    element
        .props
        .iter()
        .position(|p| p.count.is_some() && (p.name == "vertex_indices" || p.name == "vertex_index"))
        .ok_or_else(|| header_error(element.line, "the face element has no vertex_indices list"))
}

/// What one element's properties become.
struct ElementPlan {
    is_vertex: bool,
    is_face: bool,
    /// The face list among the properties.
    list: Option<usize>,
    /// The properties kept as attribute columns, with their values.
    extra: Vec<(usize, Vec<Value>)>,
}

impl ElementPlan {
    /// Where each property goes: positions, the face list, a kept attribute
    /// column, or nowhere (elements other than vertex and face); `room`
    /// values reserved per column.
    fn of(element: &Element, room: usize) -> Result<ElementPlan, Error> {
        let is_vertex = element.name == "vertex";
        let is_face = element.name == "face";
        let list = if is_face {
            Some(face_list(element)?)
        } else {
            None
        };
        let keep = |k: usize, p: &Property| {
            (is_vertex && !(p.count.is_none() && ["x", "y", "z"].contains(&p.name.as_str())))
                || (is_face && Some(k) != list)
        };
        let extra = element
            .props
            .iter()
            .enumerate()
            .filter(|&(k, p)| keep(k, p))
            .map(|(k, _)| (k, Vec::with_capacity(room)))
            .collect();
        Ok(ElementPlan {
            is_vertex,
            is_face,
            list,
            extra,
        })
    }

    /// Reserve the soup's buffers for the element's `room` instances.
    fn reserve(&self, soup: &mut Soup, element: &Element, body: &Body<'_>, room: usize) {
        if self.is_vertex {
            soup.polygons.positions.reserve(room);
        }
        if self.is_face {
            soup.polygons.offsets.reserve(room);
            soup.polygons.indices.reserve(capped(
                element.count.saturating_mul(3),
                body.remaining(),
                2,
            ));
        }
    }

    /// Hand the kept columns to the soup.
    fn store_columns(self, element: &Element, soup: &mut Soup) {
        for (k, column) in self.extra {
            let prop = &element.props[k];
            let ty = if prop.count.is_some() {
                ValueType::List
            } else {
                prop.item.value_type()
            };
            let col = SoupColumn::dense(&prop.name, Data::Dynamic(ty, column));
            if self.is_vertex {
                soup.attrs.vertex.push(col);
            } else {
                soup.attrs.face.push(col);
            }
        }
    }
}

/// Read every instance of `element` into the soup.
fn read_element(
    body: &mut Body<'_>,
    element: &Element,
    ascii: bool,
    vertices: &Vertices,
    soup: &mut Soup,
    values: &mut Vec<f64>,
) -> Result<(), Error> {
    let room = capped(element.count, body.remaining(), element.min_size(ascii));
    check_room(body, element, ascii)?;
    let mut plan = ElementPlan::of(element, room)?;
    plan.reserve(soup, element, body, room);
    let xyz = vertices.xyz;
    for i in 0..element.count {
        let start = body.start();
        values.clear();
        let mut next_extra = 0;
        for (k, prop) in element.props.iter().enumerate() {
            let what = || {
                format!(
                    "{} of {} {i} (of {})",
                    prop.name, element.name, element.count
                )
            };
            let kept = plan.extra.get(next_extra).is_some_and(|e| e.0 == k);
            match prop.count {
                None => {
                    let v = body.value(prop.item, &what)?;
                    values.push(v);
                    if kept {
                        plan.extra[next_extra].1.push(prop.item.value(v));
                    }
                }
                Some(cs) => {
                    let n = list_length(body, cs, prop, &what)?;
                    if Some(k) == plan.list {
                        read_face_indices(body, prop.item, n, vertices.count, &what, soup)?;
                    } else {
                        let items = read_list(body, prop.item, n, kept, &what)?;
                        if kept {
                            plan.extra[next_extra].1.push(Value::List(items));
                        }
                    }
                }
            }
            if kept {
                next_extra += 1;
            }
        }
        if plan.is_vertex {
            soup.polygons
                .positions
                .push([values[xyz[0]], values[xyz[1]], values[xyz[2]]]);
            soup.vertex_read_at(start);
        }
        if plan.is_face {
            soup.end_face(start);
        }
    }
    plan.store_columns(element, soup);
    Ok(())
}

/// A list's length, of count type `cs`.
#[inline]
fn list_length(
    body: &mut Body<'_>,
    cs: Scalar,
    prop: &Property,
    what: &dyn Fn() -> String,
) -> Result<usize, Error> {
    let at = body.at();
    let n = body.value(cs, what)?;
    if n < 0.0 {
        return Err(Error::Syntax {
            at,
            expected: format!("a list length for {}", prop.name),
            found: n.to_string(),
        });
    }
    Ok(n as usize)
}

/// A face's `n` vertex indices, each checked against the `nv` vertices,
/// pushed to the soup's corners.
#[inline]
fn read_face_indices(
    body: &mut Body<'_>,
    item: Scalar,
    n: usize,
    nv: usize,
    what: &dyn Fn() -> String,
    soup: &mut Soup,
) -> Result<(), Error> {
    for _ in 0..n {
        let at = body.at();
        let v = body.value(item, what)?;
        if v < 0.0 || v >= nv as f64 || v.fract() != 0.0 {
            return Err(Error::IndexOutOfRange {
                what: "vertex",
                at,
                index: v as i64,
                count: nv,
            });
        }
        soup.polygons.indices.push(v as u32);
    }
    Ok(())
}

/// Another list's `n` items: its values when `kept`, else read past.
#[inline]
fn read_list(
    body: &mut Body<'_>,
    item: Scalar,
    n: usize,
    kept: bool,
    what: &dyn Fn() -> String,
) -> Result<Vec<Value>, Error> {
    let mut items = Vec::new();
    for _ in 0..n {
        let v = body.value(item, what)?;
        if kept {
            items.push(item.value(v));
        }
    }
    Ok(items)
}
