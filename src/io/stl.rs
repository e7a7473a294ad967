//! STL (stereolithography), ascii and binary.
//!
//! STL stores every triangle with its own three corner positions; reading
//! welds corners whose positions are bit-identical as `f32` (the precision
//! STL is defined in), so a closed solid reads as a closed mesh. Nothing
//! closer than identical is merged. The ascii parser is hand-written (speed,
//! and errors that name the line and the keyword expected there); the
//! binary one reads the 84-byte header and 50-byte records with bounds
//! checks and names the byte offset where data is missing.
//!
//! A file is binary when its size is exactly `84 + 50 × count` for the
//! count in its header (so a binary file whose header starts with `solid`
//! still reads as binary); otherwise it is ascii if it starts with `solid`
//! (a bare `solid` first line, without a name, is fine).
//!
//! Facet normals are not kept (they follow from the positions). Writing
//! splits polygons into triangle fans from their first corner.
//!
//! ```
//! let stl = "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n";
//! let mesh = meshloom::io::read_stl(stl.as_bytes())?;
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (3, 1));
//! # Ok::<(), meshloom::io::Error>(())
//! ```

use std::collections::HashMap;
use std::io::{Read, Write};

use super::error::{quote, Error, Location};
use super::soup::Soup;
use super::text::{capped, parse_f64, Lines, Tokens};
use super::{emit, polygons_of, slurp, ReadOptions};
use crate::mesh::Mesh;
use crate::vec3::{cross, normalize_or_zero, sub};

const FORMAT: super::Format = super::Format::Stl;
use crate::repair::RepairReport;

/// Which kind of STL to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StlEncoding {
    /// Text (`solid` ... `endsolid`).
    Ascii,
    /// Binary: 80-byte header, triangle count, 50 bytes per triangle.
    Binary,
}

crate::choice::choices!(StlEncoding {
    Ascii = "ascii",
    Binary = "binary",
});

/// Read an STL mesh (ascii or binary, detected), strictly.
///
/// # Errors
/// [`Error`] with the line (ascii) or byte offset (binary): a malformed
/// keyword or number, a truncated record, no triangles, polygons that need
/// repair.
pub fn read_stl(reader: impl Read) -> Result<Mesh, Error> {
    read_stl_with(reader, &ReadOptions::strict()).map(|(m, _)| m)
}

/// Read an STL mesh with repair policies.
///
/// # Errors
/// As [`read_stl`], less what the policies repair.
pub fn read_stl_with(
    reader: impl Read,
    options: &ReadOptions,
) -> Result<(Mesh, RepairReport), Error> {
    let bytes = slurp(reader, options)?;
    super::read_soup(FORMAT, &bytes, options)
}

/// Write a mesh as STL; polygons are cut as [`Mesh::triangulate`] cuts
/// them (ear clipping in their plane), positions `f32`.
///
/// # Errors
/// [`Error::Unwritable`] without positions, with more than 2^32
/// triangles, or with a coordinate that `f32` cannot hold (beyond
/// ±3.4e38, or so small that it would become 0 or subnormal: the message
/// names the vertex); [`Error::Io`].
pub fn write_stl(mesh: &Mesh, writer: impl Write, encoding: StlEncoding) -> Result<(), Error> {
    super::check_f32_positions(mesh, "STL", false, None)?;
    let (p, maps) = polygons_of(mesh)?;
    let positions: Vec<[f32; 3]> = p.positions.iter().map(|q| q.map(|x| x as f32)).collect();
    let tris = triangle_indices(mesh, &maps);
    let normal = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|i| positions[i as usize].map(f64::from));
        normalize_or_zero(cross(sub(b, a), sub(c, a))).map(|x| x as f32)
    };
    let mut out = Vec::new();
    match encoding {
        StlEncoding::Binary => {
            let count = u32::try_from(tris.len()).map_err(|_| Error::Unwritable {
                at: Location::whole(),
                what: "more than 2^32 triangles".into(),
            })?;
            out.reserve(84 + 50 * tris.len());
            let mut header = [b' '; 80];
            header[..16].copy_from_slice(b"meshloom binary ");
            out.extend_from_slice(&header);
            out.extend_from_slice(&count.to_le_bytes());
            for t in &tris {
                for x in normal(t) {
                    out.extend_from_slice(&x.to_le_bytes());
                }
                for &i in t {
                    for x in positions[i as usize] {
                        out.extend_from_slice(&x.to_le_bytes());
                    }
                }
                out.extend_from_slice(&[0, 0]);
            }
        }
        StlEncoding::Ascii => {
            out.extend_from_slice(b"solid meshloom\n");
            for t in &tris {
                let n = normal(t);
                writeln!(out, "facet normal {} {} {}\nouter loop", n[0], n[1], n[2])
                    .map_err(Error::io)?;
                for &i in t {
                    let q = positions[i as usize];
                    writeln!(out, "vertex {} {} {}", q[0], q[1], q[2]).map_err(Error::io)?;
                }
                out.extend_from_slice(b"endloop\nendfacet\n");
            }
            out.extend_from_slice(b"endsolid meshloom\n");
        }
    }
    emit(writer, &out)
}

/// The triangles of every face as indices of `maps`' vertices.
fn triangle_indices(mesh: &Mesh, maps: &crate::build::IndexMaps) -> Vec<[u32; 3]> {
    let mut tris = Vec::with_capacity(mesh.face_count() * 2);
    let mut sides = Vec::new();
    let mut cuts = Vec::new();
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        cuts.clear();
        mesh.triangles_of(f, &mut sides, &mut cuts);
        let index = |c: u32| {
            let v = mesh.vkey(mesh.origin(sides[c as usize]));
            maps.vertex_index(v).map_or(0, |i| i as u32)
        };
        tris.extend(cuts.iter().map(|t| t.map(index)));
    }
    tris
}

/// Welds corners by exact `f32` bits.
struct Welder {
    index: HashMap<[u32; 3], u32>,
}

impl Welder {
    fn new(capacity: usize) -> Welder {
        Welder {
            index: HashMap::with_capacity(capacity),
        }
    }

    #[inline]
    fn corner(&mut self, soup: &mut Soup, p: [f32; 3]) {
        let key = p.map(f32::to_bits);
        let next = soup.polygons.positions.len() as u32;
        let i = *self.index.entry(key).or_insert(next);
        if i == next {
            soup.polygons.positions.push(p.map(f64::from));
        }
        soup.polygons.indices.push(i);
    }
}

/// Parse STL bytes (ascii or binary) into a soup.
pub(crate) fn parse(bytes: &[u8], record: bool) -> Result<Soup, Error> {
    if bytes.is_empty() {
        return Err(Error::Empty {
            at: Location::whole(),
        });
    }
    let exact_binary = bytes.len() >= 84 && {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
        84 + 50 * n as u64 == bytes.len() as u64
    };
    // Ascii STL has no NUL bytes; binary STL nearly always has some early
    // (small floats, the zero attribute count), even when its 80-byte
    // header starts with "solid".
    let ascii = bytes.trim_ascii_start().starts_with(b"solid")
        && !bytes[..bytes.len().min(1024)].contains(&0);
    if !exact_binary && ascii {
        parse_ascii(bytes, record)
    } else {
        parse_binary(bytes, record)
    }
}

fn parse_binary(bytes: &[u8], record: bool) -> Result<Soup, Error> {
    if bytes.len() < 84 {
        return Err(Error::Truncated {
            at: Location::byte(bytes.len() as u64),
            expected: "the 84-byte header of a binary STL file".into(),
        });
    }
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let mut soup = Soup::new(record);
    soup.binary = true;
    let room = (bytes.len() - 84) / 50;
    if n > room {
        return Err(Error::Truncated {
            at: Location::byte((84 + 50 * room) as u64),
            expected: format!(
                "triangle {} of the {n} the header (byte 80) announces; the file holds {room}",
                room + 1
            ),
        });
    }
    let mut weld = Welder::new(n / 2);
    soup.polygons.indices.reserve(3 * n);
    soup.polygons.offsets.reserve(n);

    let f32_at =
        |o: usize| f32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]);
    for t in 0..n {
        let base = 84 + 50 * t;
        for c in 0..3 {
            let o = base + 12 + 12 * c;
            weld.corner(&mut soup, [f32_at(o), f32_at(o + 4), f32_at(o + 8)]);
        }
        soup.end_face(base as u64);
    }
    Ok(soup)
}

/// The ascii tokens with the line each is on.
struct Words<'a> {
    lines: Lines<'a>,
    tokens: Tokens<'a>,
}

impl<'a> Words<'a> {
    fn next(&mut self) -> Option<&'a [u8]> {
        loop {
            if let Some(t) = self.tokens.next() {
                return Some(t);
            }
            self.tokens = Tokens::new(self.lines.next()?);
        }
    }

    fn here(&self) -> Location {
        self.lines.here()
    }

    fn expect(&mut self, word: &str) -> Result<(), Error> {
        match self.next() {
            Some(t) if t.eq_ignore_ascii_case(word.as_bytes()) => Ok(()),
            Some(t) => Err(Error::syntax(self.here(), format!("\"{word}\""), t)),
            None => Err(Error::Truncated {
                at: self.lines.end(),
                expected: format!("\"{word}\""),
            }),
        }
    }

    fn number(&mut self) -> Result<f64, Error> {
        match self.next() {
            Some(t) => parse_f64(t).ok_or_else(|| Error::syntax(self.here(), "a number", t)),
            None => Err(Error::Truncated {
                at: self.lines.end(),
                expected: "a number".into(),
            }),
        }
    }
}

fn parse_ascii(bytes: &[u8], record: bool) -> Result<Soup, Error> {
    let mut w = Words {
        lines: Lines::new(bytes),
        tokens: Tokens::new(b""),
    };
    let mut soup = Soup::new(record);
    // A facet is at least ~60 bytes of text.
    let mut weld = Welder::new(capped(bytes.len() / 60, bytes.len(), 1));
    w.expect("solid")?;
    // The rest of the `solid` line is the name (maybe empty).
    w.tokens = Tokens::new(b"");
    loop {
        let Some(word) = w.next() else {
            return Err(Error::Truncated {
                at: w.lines.end(),
                expected: "\"facet\" or \"endsolid\"".into(),
            });
        };
        if word.eq_ignore_ascii_case(b"endsolid") {
            w.tokens = Tokens::new(b"");
            // Another solid may follow.
            match w.next() {
                None => break,
                Some(t) if t.eq_ignore_ascii_case(b"solid") => {
                    w.tokens = Tokens::new(b"");
                    continue;
                }
                Some(t) => {
                    return Err(Error::syntax(
                        w.here(),
                        "\"solid\" or the end of the file",
                        t,
                    ))
                }
            }
        }
        if !word.eq_ignore_ascii_case(b"facet") {
            return Err(Error::Syntax {
                at: w.here(),
                expected: "\"facet\" or \"endsolid\"".into(),
                found: quote(word),
            });
        }
        let line = w.lines.line;
        w.expect("normal")?;
        for _ in 0..3 {
            w.number()?;
        }
        w.expect("outer")?;
        w.expect("loop")?;
        for _ in 0..3 {
            w.expect("vertex")?;
            let p = [w.number()?, w.number()?, w.number()?];
            weld.corner(&mut soup, p.map(|x| x as f32));
        }
        w.expect("endloop")?;
        w.expect("endfacet")?;
        soup.end_face(line);
    }
    Ok(soup)
}
