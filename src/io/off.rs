//! OFF (Object File Format, as geomview and CGAL write it).
//!
//! The parser is hand-written rather than taken from a crate: it keeps
//! n-gons as they are, reads the header variants real files use
//! (`[ST][C][N][4][n]OFF`, comments before and after the keyword, counts on
//! the keyword line, an optional edge count), takes the optional colour at
//! the end of a face line, and reports the line of every error. It is one
//! pass over the bytes with the exact fast float path of the text scanner,
//! and it never reserves space by the header's counts beyond what the
//! remaining bytes could hold.
//!
//! Read: the first three coordinates of each vertex are its position (a
//! `4OFF` file's fourth is dropped); a face line is `k i1 .. ik` followed by
//! nothing, a colour map index, or an RGB(A) colour. Binary OFF is refused
//! with [`Error::UnsupportedFormat`].
//!
//! ```
//! let off = "OFF\n# a square\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
//! let mesh = meshloom::io::read_off(off.as_bytes())?;
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (4, 1));
//! let mut out = Vec::new();
//! meshloom::io::write_off(&mesh, &mut out)?;
//! assert!(out.starts_with(b"OFF\n4 1 0\n"));
//! # Ok::<(), meshloom::io::Error>(())
//! ```

use std::io::{Read, Write};

use super::attrs::{Collector, Data};
use super::error::{Error, Location};
use super::soup::Soup;
use super::text::{
    capped, next_count, next_f64, parse_f64, parse_i64, strip_comment, Lines, Tokens,
};
use super::{emit, polygons_of, slurp, ReadOptions};
use crate::attr::Value;
use crate::mesh::Mesh;

const FORMAT: super::Format = super::Format::Off;
use crate::repair::RepairReport;
use crate::ElementKind;

/// Read an OFF mesh, strictly.
///
/// # Errors
/// [`Error`] with the line: malformed header or numbers, too few vertices
/// or faces, an index out of range, polygons that need repair.
pub fn read_off(reader: impl Read) -> Result<Mesh, Error> {
    read_off_with(reader, &ReadOptions::strict()).map(|(m, _)| m)
}

/// Read an OFF mesh with repair policies.
///
/// # Errors
/// As [`read_off`], less what the policies repair.
pub fn read_off_with(
    reader: impl Read,
    options: &ReadOptions,
) -> Result<(Mesh, RepairReport), Error> {
    let bytes = slurp(reader, options)?;
    super::read_soup(FORMAT, &bytes, options)
}

/// Write a mesh as ascii OFF: positions with every digit needed to read
/// them back exactly, faces as index lists (holes are not written). Vertex
/// attributes `w` (a number), `normal`, `color` (RGBA) and `texcoord` make
/// a `[ST][C][N][4]OFF` header with those on every vertex line; a face
/// attribute `color` (RGBA) is written after each face's indices, and
/// `color_index` where there is no colour.
///
/// # Errors
/// [`Error::Unwritable`] without positions; [`Error::Io`].
pub fn write_off(mesh: &Mesh, writer: impl Write) -> Result<(), Error> {
    let (p, maps) = polygons_of(mesh)?;
    let io = Error::io;
    let vertex_cols = |name: &str, len: usize| -> Option<Vec<Vec<f64>>> {
        let has = mesh
            .attr_info(ElementKind::Vertex)
            .iter()
            .any(|a| a.name == name);
        has.then(|| {
            maps.vertices
                .iter()
                .map(|&v| {
                    numbers(mesh.attr_value(name, v), len).unwrap_or_else(|| {
                        // No value: zeros (an opaque black colour).
                        let mut z = vec![0.0; len];
                        if len == 4 {
                            z[3] = 1.0;
                        }
                        z
                    })
                })
                .collect()
        })
    };
    let w = vertex_cols("w", 1);
    let normal = vertex_cols("normal", 3);
    let color = vertex_cols("color", 4);
    let texcoord = vertex_cols("texcoord", 2);
    let face_has = |name: &str| {
        mesh.attr_info(ElementKind::Face)
            .iter()
            .any(|a| a.name == name)
    };
    let (fcolor, findex) = (face_has("color"), face_has("color_index"));
    let mut out = Vec::with_capacity(32 * (p.positions.len() + p.indices.len()));
    let keyword = format!(
        "{}{}{}{}OFF",
        if texcoord.is_some() { "ST" } else { "" },
        if color.is_some() { "C" } else { "" },
        if normal.is_some() { "N" } else { "" },
        if w.is_some() { "4" } else { "" },
    );
    writeln!(out, "{keyword}\n{} {} 0", p.positions.len(), p.face_count()).map_err(io)?;
    for (i, q) in p.positions.iter().enumerate() {
        write!(out, "{} {} {}", q[0], q[1], q[2]).map_err(io)?;
        for col in [&w, &normal, &color, &texcoord].into_iter().flatten() {
            for x in &col[i] {
                write!(out, " {x}").map_err(io)?;
            }
        }
        out.push(b'\n');
    }
    for (i, f) in p.faces().enumerate() {
        write!(out, "{}", f.len()).map_err(io)?;
        for v in f {
            write!(out, " {v}").map_err(io)?;
        }
        let key = maps.faces[i];
        let colour = fcolor
            .then(|| numbers(mesh.attr_value("color", key), 4))
            .flatten()
            .or_else(|| {
                findex
                    .then(|| numbers(mesh.attr_value("color_index", key), 1))
                    .flatten()
            });
        for x in colour.unwrap_or_default() {
            write!(out, " {x}").map_err(io)?;
        }
        out.push(b'\n');
    }
    emit(writer, &out)
}

/// `len` numbers from an attribute value (a number or a list), padded
/// with zeros; `None` where the element has no value.
fn numbers(value: crate::Result<Option<Value>>, len: usize) -> Option<Vec<f64>> {
    let mut xs: Vec<f64> = match value {
        Ok(Some(Value::List(items))) => items.iter().map(|x| x.as_f64().unwrap_or(0.0)).collect(),
        Ok(Some(v)) => v.as_f64().into_iter().collect(),
        _ => return None,
    };
    xs.resize(len, 0.0);
    Some(xs)
}

/// The header keyword's flags.
struct Keyword {
    dim: usize,
    has_dim_token: bool,
    colors: bool,
    normals: bool,
    texcoords: bool,
}

fn keyword(tok: &[u8]) -> Option<Keyword> {
    let mut k = Keyword {
        dim: 3,
        has_dim_token: false,
        colors: false,
        normals: false,
        texcoords: false,
    };
    let mut s = tok.strip_suffix(b"OFF")?;
    if let Some(r) = s.strip_prefix(b"ST") {
        k.texcoords = true;
        s = r;
    }
    if let Some(r) = s.strip_prefix(b"C") {
        k.colors = true;
        s = r;
    }
    if let Some(r) = s.strip_prefix(b"N") {
        k.normals = true;
        s = r;
    }
    if let Some(r) = s.strip_prefix(b"4") {
        k.dim = 4;
        s = r;
    }
    if let Some(r) = s.strip_prefix(b"n") {
        k.has_dim_token = true;
        s = r;
    }
    s.is_empty().then_some(k)
}

/// The next line with something other than a comment, and its tokens.
fn content<'a>(lines: &mut Lines<'a>) -> Option<&'a [u8]> {
    for line in lines.by_ref() {
        let s = strip_comment(line);
        if !s.is_empty() {
            return Some(s);
        }
    }
    None
}

/// The first `N` numbers of `rest`, taken off it.
fn take<const N: usize>(rest: &mut &[f64]) -> Option<[f64; N]> {
    let (head, tail) = rest.split_first_chunk::<N>()?;
    *rest = tail;
    Some(*head)
}

/// An RGB or RGBA colour in 0..=1; integer components (any above 1) are
/// read as 0..=255. `None` for other lengths.
fn colour(c: &[f64]) -> Option<[f64; 4]> {
    let scale = if c.iter().any(|&x| x > 1.0) && c.iter().all(|x| x.fract() == 0.0) {
        255.0
    } else {
        1.0
    };
    match *c {
        [r, g, b] => Some([r / scale, g / scale, b / scale, 1.0]),
        [r, g, b, a] => Some([r / scale, g / scale, b / scale, a / scale]),
        _ => None,
    }
}

/// Make sure `tokens` has one more token, taking the next content line if
/// it is used up.
fn refill<'a>(lines: &mut Lines<'a>, tokens: &mut Tokens<'a>) -> Result<(), Error> {
    if tokens.clone().next().is_none() {
        let line = content(lines).ok_or_else(|| Error::Truncated {
            at: lines.end(),
            expected: "the vertex and face counts".into(),
        })?;
        *tokens = Tokens::new(line);
    }
    Ok(())
}

/// Parse OFF bytes into a soup.
pub(crate) fn parse(bytes: &[u8], record: bool) -> Result<Soup, Error> {
    let mut lines = Lines::new(bytes);
    let header = read_header(&mut lines)?;
    let (nv, nf) = (header.vertices, header.faces);
    let mut soup = Soup::new(record);
    let rest = lines.remaining();
    soup.polygons
        .positions
        .reserve(capped(nv, rest, 2 * header.dim));
    soup.polygons.offsets.reserve(capped(nf, rest, 4));
    soup.polygons.indices.reserve(capped(3 * nf, rest, 2));
    let mut read = Reading {
        soup,
        columns: Columns::new(),
        extra: Vec::new(),
    };
    read.vertices(&mut lines, &header)?;
    read.faces(&mut lines, &header)?;
    let mut soup = read.soup;
    read.columns.finish(&mut soup, nv, nf);
    Ok(soup)
}

/// What the header says: the keyword, the numbers per vertex line before
/// the optional ones, and the counts.
struct Header {
    kw: Keyword,
    dim: usize,
    vertices: usize,
    faces: usize,
}

/// The keyword (or none, when the counts come first) and the counts after
/// it, checked against the bytes that follow.
fn read_header(lines: &mut Lines<'_>) -> Result<Header, Error> {
    let Some(first) = content(lines) else {
        return Err(Error::Empty {
            at: Location::whole(),
        });
    };
    let mut tokens = Tokens::new(first);
    let kw = read_keyword(&mut tokens, lines)?;
    // Counts may follow the keyword on its line, or come on later lines.
    let mut dim = kw.dim;
    if kw.has_dim_token {
        refill(lines, &mut tokens)?;
        let n = next_count(&mut tokens, || lines.here(), "the dimension of nOFF")?;
        if !(1..=16).contains(&n) {
            return Err(Error::Header {
                at: lines.here(),
                message: format!("dimension {n} is not between 1 and 16"),
            });
        }
        dim = n + usize::from(kw.dim == 4);
    }
    refill(lines, &mut tokens)?;
    let nv = next_count(&mut tokens, || lines.here(), "the vertex count")?;
    refill(lines, &mut tokens)?;
    let nf = next_count(&mut tokens, || lines.here(), "the face count")?;
    // A vertex takes at least `dim` one-digit numbers and separators; a
    // face at least "1 0\n".
    let least = (nv as u128) * (2 * dim as u128) + (nf as u128) * 4;
    if least > lines.remaining() as u128 + 1 {
        return Err(Error::Header {
            at: Location::line(lines.line),
            message: format!(
                "it announces {nv} vertices and {nf} faces, but only {} bytes follow",
                lines.remaining()
            ),
        });
    }
    Ok(Header {
        kw,
        dim,
        vertices: nv,
        faces: nf,
    })
}

/// The keyword at the start of `tokens` (taken off them), or plain `OFF`
/// when the line starts with a count; binary OFF is refused.
fn read_keyword(tokens: &mut Tokens<'_>, lines: &Lines<'_>) -> Result<Keyword, Error> {
    let head = tokens.clone().next().unwrap_or_default();
    let kw = match keyword(head) {
        Some(k) => {
            tokens.next();
            k
        }
        None if parse_i64(head).is_some() => {
            keyword(b"OFF").ok_or_else(|| Error::syntax(lines.here(), "an OFF keyword", head))?
        }
        None => {
            return Err(Error::syntax(
                lines.here(),
                "an OFF keyword such as OFF, COFF, NOFF or 4OFF",
                head,
            ))
        }
    };
    if tokens.clone().next() == Some(b"BINARY") {
        return Err(Error::UnsupportedFormat {
            at: lines.here(),
            what: "binary OFF".into(),
        });
    }
    Ok(kw)
}

/// The attribute columns an OFF file may carry.
struct Columns {
    w: Collector<f64>,
    normal: Collector<[f64; 3]>,
    vertex_color: Collector<[f64; 4]>,
    texcoord: Collector<[f64; 2]>,
    face_color: Collector<[f64; 4]>,
    face_index: Collector<f64>,
}

impl Columns {
    fn new() -> Columns {
        Columns {
            w: Collector::new("w"),
            normal: Collector::new("normal"),
            vertex_color: Collector::new("color"),
            texcoord: Collector::new("texcoord"),
            face_color: Collector::new("color"),
            face_index: Collector::new("color_index"),
        }
    }

    /// Hand the columns read to the soup.
    fn finish(self, soup: &mut Soup, nv: usize, nf: usize) {
        let a = &mut soup.attrs;
        a.vertex.extend(self.w.finish(nv, Data::Scalar));
        a.vertex.extend(self.normal.finish(nv, Data::Vec3));
        a.vertex.extend(self.vertex_color.finish(nv, Data::Vec4));
        a.vertex.extend(self.texcoord.finish(nv, Data::Vec2));
        a.face.extend(self.face_color.finish(nf, Data::Vec4));
        a.face.extend(self.face_index.finish(nf, Data::Scalar));
    }
}

/// The body being read: the soup, its columns, and the numbers at the end
/// of the line at hand.
struct Reading {
    soup: Soup,
    columns: Columns,
    extra: Vec<f64>,
}

/// The content line of element `i` of `n` (`what`: vertex or face).
#[inline]
fn element_line<'a>(
    lines: &mut Lines<'a>,
    what: &str,
    i: usize,
    n: usize,
) -> Result<&'a [u8], Error> {
    content(lines).ok_or_else(|| Error::Truncated {
        at: lines.end(),
        expected: format!("{what} {} of {n}", i + 1),
    })
}

impl Reading {
    /// The vertex lines: a position, a fourth coordinate (`w`), then the
    /// normal, colour and texture coordinates the keyword announces.
    fn vertices(&mut self, lines: &mut Lines<'_>, header: &Header) -> Result<(), Error> {
        let (kw, dim, nv) = (&header.kw, header.dim, header.vertices);
        let (soup, columns, extra) = (&mut self.soup, &mut self.columns, &mut self.extra);
        for i in 0..nv {
            let line = element_line(lines, "vertex", i, nv)?;
            let mut t = Tokens::new(line);
            let at = || lines.here();
            let mut p = [0.0; 3];
            for c in p.iter_mut().take(dim) {
                *c = next_f64(&mut t, at, "a vertex coordinate")?;
            }
            for k in 3..dim {
                let x = next_f64(&mut t, at, "a vertex coordinate")?;
                if k == 3 {
                    columns.w.set(i, x);
                }
            }
            soup.polygons.positions.push(p);
            soup.vertex_read_at(lines.line);
            if kw.normals || kw.colors || kw.texcoords {
                rest_numbers(t, at, "a number", extra)?;
                vertex_extras(kw, i, line, extra, at, columns)?;
            }
        }
        Ok(())
    }

    /// The face lines: `k i1 .. ik` and an optional colour.
    fn faces(&mut self, lines: &mut Lines<'_>, header: &Header) -> Result<(), Error> {
        let (nv, nf) = (header.vertices, header.faces);
        let (soup, columns, extra) = (&mut self.soup, &mut self.columns, &mut self.extra);
        for i in 0..nf {
            let line = element_line(lines, "face", i, nf)?;
            let mut t = Tokens::new(line);
            let at = || lines.here();
            let k_tok = t.next().unwrap_or_default();
            let k = match parse_i64(k_tok) {
                Some(k) if k >= 1 => k as usize,
                _ => {
                    return Err(Error::syntax(
                        at(),
                        "a face's corner count (at least 1)",
                        k_tok,
                    ))
                }
            };
            for _ in 0..k {
                let tok = t.next().ok_or_else(|| {
                    Error::syntax(at(), format!("{k} vertex indices after the count"), b"")
                })?;
                let index =
                    parse_i64(tok).ok_or_else(|| Error::syntax(at(), "a vertex index", tok))?;
                if index < 0 || index as u64 >= nv as u64 {
                    return Err(Error::IndexOutOfRange {
                        what: "vertex",
                        at: at(),
                        index,
                        count: nv,
                    });
                }
                soup.polygons.indices.push(index as u32);
            }
            // An optional colour: a map index, RGB or RGBA, ints or floats.
            rest_numbers(t, at, "a colour component or the end of the line", extra)?;
            face_colour(i, k, line, extra, at, columns)?;
            soup.end_face(lines.line);
        }
        Ok(())
    }
}

/// The numbers that end a line (its tokens `t`) into `extra`; a token that
/// is not a number is an error expecting `what`.
#[inline]
fn rest_numbers(
    t: Tokens<'_>,
    at: impl Fn() -> Location,
    what: &str,
    extra: &mut Vec<f64>,
) -> Result<(), Error> {
    extra.clear();
    for tok in t {
        extra.push(parse_f64(tok).ok_or_else(|| Error::syntax(at(), what, tok))?);
    }
    Ok(())
}

/// The numbers after vertex `i`'s coordinates on its line `line`: normal,
/// colour, texture coordinates.
#[inline]
fn vertex_extras(
    kw: &Keyword,
    i: usize,
    line: &[u8],
    extra: &[f64],
    at: impl Fn() -> Location,
    columns: &mut Columns,
) -> Result<(), Error> {
    let mut rest = extra;
    if kw.normals {
        let [x, y, z] = take::<3>(&mut rest)
            .ok_or_else(|| Error::syntax(at(), "three normal coordinates (NOFF)", line))?;
        columns.normal.set(i, [x, y, z]);
    }
    if kw.colors {
        let n = rest.len().saturating_sub(if kw.texcoords { 2 } else { 0 });
        if let Some(c) = colour(&rest[..n]) {
            columns.vertex_color.set(i, c);
        }
        rest = &rest[n..];
    }
    if kw.texcoords {
        let [s_, t_] = take::<2>(&mut rest)
            .ok_or_else(|| Error::syntax(at(), "two texture coordinates (STOFF)", line))?;
        columns.texcoord.set(i, [s_, t_]);
    }
    Ok(())
}

/// The numbers after face `i`'s `k` corners on its line `line`: none, a
/// colour map index, or an RGB(A) colour.
#[inline]
fn face_colour(
    i: usize,
    k: usize,
    line: &[u8],
    extra: &[f64],
    at: impl Fn() -> Location,
    columns: &mut Columns,
) -> Result<(), Error> {
    match extra.len() {
        0 => {}
        1 => columns.face_index.set(i, extra[0]),
        3 | 4 => {
            if let Some(c) = colour(extra) {
                columns.face_color.set(i, c);
            }
        }
        _ => {
            return Err(Error::syntax(
                at(),
                format!("{k} vertex indices and a colour of 1, 3 or 4 components"),
                line,
            ))
        }
    }
    Ok(())
}
