//! The PLY body, read value by value with bounds checks, into a soup.

use super::header::{header_error, parse_header, Property, Scalar};
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
    soup.nonstandard = header
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
        .collect();
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

            soup.polygons.indices.reserve(capped(
                element.count.saturating_mul(3),
                body.remaining(),
                2,
            ));
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
                                        what: "vertex",
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
