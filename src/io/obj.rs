//! Wavefront OBJ.
//!
//! The parser is hand-written rather than taken from a crate, for three
//! reasons: speed (`v` and `f` statements are parsed in place in one pass
//! over their bytes, without strings; a large file of only those is read
//! in two halves on two threads; `examples/bench_peers/io.rs` times it
//! beside pmp-library's reader), n-gons (faces keep every corner; nothing
//! is triangulated) and error quality (every error names the line and what
//! was expected there).
//!
//! Read: `v` (first three numbers; a `w` or vertex colour after them is
//! ignored), `vt`, `vn`, `f` with `v`, `v/vt`, `v//vn` and `v/vt/vn`
//! corners, positive (1-based) and negative (relative) indices, `g`, `o`,
//! `usemtl`. Texture coordinates and normals become half-edge (corner)
//! attributes `texcoord` and `normal`; groups and materials become face
//! attributes. `l`, `p`, `s`, `mtllib` and other statements are skipped.
//!
//! ```
//! let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n";
//! let mesh = meshloom::io::read_obj(obj.as_bytes())?;
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (4, 1));
//! # Ok::<(), meshloom::io::Error>(())
//! ```

use std::collections::HashMap;
use std::io::{Read, Write};

use super::attrs::{Data, SoupColumn};
use super::error::Error;
use super::error::Location;
use super::soup::Soup;
use super::text::{is_space, parse_f64, parse_f64_at, parse_i64, Lines, Tokens};
use super::{emit, polygons_of, slurp, ReadOptions};
use crate::attr::Value;
use crate::mesh::Mesh;

const FORMAT: super::Format = super::Format::Obj;
use crate::repair::RepairReport;

/// Read an OBJ mesh, strictly.
///
/// # Errors
/// [`Error`] with the line: a malformed number or corner, an index out of
/// range (or 0), no faces, polygons that need repair.
pub fn read_obj(reader: impl Read) -> Result<Mesh, Error> {
    read_obj_with(reader, &ReadOptions::strict()).map(|(m, _)| m)
}

/// Read an OBJ mesh with repair policies.
///
/// # Errors
/// As [`read_obj`], less what the policies repair.
pub fn read_obj_with(
    reader: impl Read,
    options: &ReadOptions,
) -> Result<(Mesh, RepairReport), Error> {
    let bytes = slurp(reader, options)?;
    super::read_soup(FORMAT, &bytes, options)
}

/// Write a mesh as OBJ: `v` lines with every digit needed to read the
/// positions back exactly, `f` lines with 1-based indices (holes are not
/// written). Half-edge attributes `texcoord` and `normal` (two and three
/// numbers) become `vt` and `vn` lines, shared between corners with equal
/// values; face attributes `object`, `group` and `material` (text) become
/// `o`, `g` and `usemtl` statements where they change.
///
/// # Errors
/// [`Error::Unwritable`] without positions; [`Error::Io`].
pub fn write_obj(mesh: &Mesh, writer: impl Write) -> Result<(), Error> {
    let (p, maps) = polygons_of(mesh)?;
    let io = Error::io;
    let mut out = Vec::with_capacity(32 * (p.positions.len() + p.indices.len()));
    for q in &p.positions {
        writeln!(out, "v {} {} {}", q[0], q[1], q[2]).map_err(io)?;
    }
    let names = |name: &str| -> Vec<Option<String>> {
        maps.faces
            .iter()
            .map(|&f| match mesh.attr_value(name, f) {
                Ok(Some(Value::Text(s))) => Some(s),
                _ => None,
            })
            .collect()
    };
    let statements = [
        ("o", names("object")),
        ("g", names("group")),
        ("usemtl", names("material")),
    ];
    // Corner attributes, numbered by distinct value.
    let has = |name: &str| {
        mesh.attr_info(crate::ElementKind::Halfedge)
            .iter()
            .any(|a| a.name == name)
    };
    let (with_uv, with_n) = (has("texcoord"), has("normal"));
    let mut uv = Numbering::default();
    let mut nr = Numbering::default();
    let mut corners: Vec<(u32, u32, u32)> = Vec::with_capacity(p.indices.len());
    for &f in &maps.faces {
        let Ok(view) = mesh.face(f) else { continue };
        for h in view.halfedges() {
            let v = mesh
                .halfedge(h)
                .ok()
                .and_then(|h| maps.vertex_index(h.origin().key()))
                .unwrap_or(0) as u32;
            let t = if with_uv {
                uv.number(mesh.attr_value("texcoord", h).ok().flatten(), 2)
            } else {
                0
            };
            let n = if with_n {
                nr.number(mesh.attr_value("normal", h).ok().flatten(), 3)
            } else {
                0
            };
            corners.push((v, t, n));
        }
    }
    for t in &uv.values {
        writeln!(out, "vt {} {}", t[0], t[1]).map_err(io)?;
    }
    for n in &nr.values {
        writeln!(out, "vn {} {} {}", n[0], n[1], n[2]).map_err(io)?;
    }
    let mut current: [Option<&String>; 3] = [None; 3];
    let mut c = 0;
    for (i, f) in p.faces().enumerate() {
        for (k, (word, values)) in statements.iter().enumerate() {
            let name = values[i].as_ref();
            if name.is_some() && name != current[k] {
                writeln!(out, "{word} {}", name.map_or("", |s| s.as_str())).map_err(io)?;
                current[k] = name;
            }
        }
        out.push(b'f');
        for &index in f {
            let (v, t, n) = corners.get(c).copied().unwrap_or((index, 0, 0));
            c += 1;
            match (t, n) {
                (0, 0) => write!(out, " {}", v + 1),
                (t, 0) => write!(out, " {}/{t}", v + 1),
                (0, n) => write!(out, " {}//{n}", v + 1),
                (t, n) => write!(out, " {}/{t}/{n}", v + 1),
            }
            .map_err(io)?;
        }
        out.push(b'\n');
    }
    emit(writer, &out)
}

/// Distinct corner values, numbered from 1 (0: the corner has none).
#[derive(Default)]
struct Numbering {
    values: Vec<Vec<f64>>,
    index: HashMap<Vec<u64>, u32>,
}

impl Numbering {
    fn number(&mut self, value: Option<Value>, len: usize) -> u32 {
        let Some(Value::List(items)) = value else {
            return 0;
        };
        let xs: Vec<f64> = items.iter().filter_map(Value::as_f64).collect();
        if xs.len() != len {
            return 0;
        }
        let key: Vec<u64> = xs.iter().map(|x| x.to_bits()).collect();
        let next = self.values.len() as u32 + 1;
        let i = *self.index.entry(key).or_insert(next);
        if i == next {
            self.values.push(xs);
        }
        i
    }
}

/// Resolve a 1-based or negative OBJ index against `count` elements.
#[inline]
fn resolve(index: i64, count: usize) -> Option<u32> {
    let i = if index > 0 {
        index - 1
    } else {
        count as i64 + index
    };
    (index != 0 && i >= 0 && (i as u64) < count as u64).then_some(i as u32)
}

/// Corner references to texture coordinates and normals (`NONE` = absent).
#[derive(Default)]
struct CornerRefs {
    texcoords: Vec<[f64; 2]>,
    normals: Vec<[f64; 3]>,
    texcoord_of: Vec<u32>,
    normal_of: Vec<u32>,
}

/// Inputs at least this large are parsed in two halves at once when both
/// are plain (see [`plain`]).
const PARALLEL_MIN: usize = 4 << 20;

/// Parse OBJ bytes into a soup.
pub(crate) fn parse(bytes: &[u8], record: bool) -> Result<Soup, Error> {
    if !record && bytes.len() >= PARALLEL_MIN {
        if let Some(soup) = parse_halves(bytes) {
            return Ok(soup);
        }
    }
    parse_serial(bytes, record)
}

/// A chunk of plain OBJ: `v` and `f` statements with positive indices
/// only (and statements every reader skips).
struct Plain {
    positions: Vec<[f64; 3]>,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    /// The most vertices any index needed from before the chunk.
    needs: usize,
}

/// The two halves of a large file, split at a line end, parsed on two
/// threads and joined. `None` (the caller then parses serially, with full
/// error reporting) if either half holds anything but plain statements or
/// anything wrong.
fn parse_halves(bytes: &[u8]) -> Option<Soup> {
    let mid = bytes.len() / 2;
    let cut = mid + bytes[mid..].iter().position(|&b| b == b'\n')? + 1;
    let (first, second) = bytes.split_at(cut);
    let (a, b) = std::thread::scope(|scope| {
        let other = std::thread::Builder::new()
            .spawn_scoped(scope, || plain(second))
            .ok()?;
        let a = plain(first);
        let b = other.join().ok()?;
        Some((a?, b?))
    })?;
    if a.needs > 0 || b.needs > a.positions.len() {
        return None;
    }
    let mut soup = Soup::new(false);
    let base = a.indices.len() as u32;
    let p = &mut soup.polygons;
    p.positions = a.positions;
    p.positions.extend_from_slice(&b.positions);
    p.indices = a.indices;
    p.indices.extend_from_slice(&b.indices);
    p.offsets = a.offsets;
    p.offsets.extend(b.offsets[1..].iter().map(|&o| o + base));
    Some(soup)
}

/// Parse a chunk of plain OBJ; `None` at anything else.
fn plain(bytes: &[u8]) -> Option<Plain> {
    let n = bytes.len();
    let mut out = Plain {
        positions: Vec::with_capacity(n / 96),
        offsets: Vec::with_capacity(n / 48),
        indices: Vec::with_capacity(n / 16),
        needs: 0,
    };
    out.offsets.push(0);
    let mut pos = 0;
    while pos < n {
        let mut i = pos;
        while i < n && is_space(bytes[i]) {
            i += 1;
        }
        let key_end = i + bytes[i..]
            .iter()
            .position(|&b| is_space(b) || b == b'\n')
            .unwrap_or(n - i);
        match &bytes[i..key_end] {
            b"v" => {
                i = key_end;
                let mut p = [0.0; 3];
                for c in &mut p {
                    while i < n && is_space(bytes[i]) {
                        i += 1;
                    }
                    *c = parse_f64_at(bytes, &mut i)?;
                }
                out.positions.push(p);
            }
            b"f" => {
                i = key_end;
                let start = out.indices.len();
                loop {
                    while i < n && is_space(bytes[i]) {
                        i += 1;
                    }
                    if i >= n || bytes[i] == b'\n' || bytes[i] == b'#' {
                        break;
                    }
                    let st = i;
                    let mut v: u32 = 0;
                    while i < n && i - st < 9 && bytes[i].is_ascii_digit() {
                        v = v * 10 + u32::from(bytes[i] - b'0');
                        i += 1;
                    }
                    if i == st || v == 0 || !(i == n || is_space(bytes[i]) || bytes[i] == b'\n') {
                        return None;
                    }
                    out.needs = out
                        .needs
                        .max((v as usize).saturating_sub(out.positions.len()));
                    out.indices.push(v - 1);
                }
                if out.indices.len() == start {
                    return None;
                }
                out.offsets.push(out.indices.len() as u32);
            }
            b"" | b"s" | b"l" | b"p" | b"mtllib" => {}
            k if k.first() == Some(&b'#') => {}
            _ => return None,
        }
        pos = match bytes[i.min(n)..].iter().position(|&b| b == b'\n') {
            Some(k) => i + k + 1,
            None => n,
        };
    }
    Some(out)
}

/// Parse OBJ bytes into a soup, one statement after the other.
fn parse_serial(bytes: &[u8], record: bool) -> Result<Soup, Error> {
    let mut soup = Soup::new(record);
    let mut refs = CornerRefs::default();
    let mut lines = Lines::new(bytes);
    let mut groups = Names::new("group");
    let mut objects = Names::new("object");
    let mut materials = Names::new("material");
    // Reserve by the input's size only: about 30 bytes per statement.
    soup.polygons.positions.reserve(bytes.len() / 96);
    soup.polygons.indices.reserve(bytes.len() / 16);
    soup.polygons.offsets.reserve(bytes.len() / 48);
    let n = bytes.len();
    let mut pos = 0;
    while pos < n {
        lines.line += 1;
        // The hot statements, `v x y z` and `f` with plain indices, are
        // parsed in place in one pass; everything else goes by tokens.
        let line_no = lines.line;
        let at = || Location::line(line_no);
        let head = &bytes[pos..n.min(pos + 2)];
        if head.len() == 2
            && (head[1] == b' ' || head[1] == b'\t')
            && (head[0] == b'v' || head[0] == b'f')
        {
            let mut i = pos + 2;
            if head[0] == b'v' {
                let mut p = [0.0; 3];
                for c in &mut p {
                    while i < n && is_space(bytes[i]) {
                        i += 1;
                    }
                    *c = parse_f64_at(bytes, &mut i).ok_or_else(|| {
                        Error::syntax(at(), "a vertex coordinate", token_at(bytes, i))
                    })?;
                }
                soup.polygons.positions.push(p);
                soup.vertex_read_at(line_no);
            } else {
                let start = soup.polygons.indices.len();
                loop {
                    while i < n && is_space(bytes[i]) {
                        i += 1;
                    }
                    if i >= n || bytes[i] == b'\n' || bytes[i] == b'#' {
                        break;
                    }
                    // A plain index, parsed in place.
                    let st = i;
                    let mut v: u32 = 0;
                    while i < n && i - st < 9 && bytes[i].is_ascii_digit() {
                        v = v * 10 + u32::from(bytes[i] - b'0');
                        i += 1;
                    }
                    let plain = i > st
                        && v > 0
                        && v as usize <= soup.polygons.positions.len()
                        && refs.texcoord_of.is_empty()
                        && refs.normal_of.is_empty()
                        && (i == n || is_space(bytes[i]) || bytes[i] == b'\n');
                    if plain {
                        soup.polygons.indices.push(v - 1);
                        continue;
                    }
                    let tok = token_at(bytes, st);
                    i = st + tok.len();
                    face_corner(tok, &mut soup, &mut refs, at)?;
                }
                if soup.polygons.indices.len() == start {
                    return Err(Error::syntax(at(), "vertex indices after f", b""));
                }
                soup.end_face(line_no);
            }
            // The rest of the line (a `w`, vertex colours, a comment).
            pos = match bytes[i.min(n)..].iter().position(|&b| b == b'\n') {
                Some(k) => i + k + 1,
                None => n,
            };
            continue;
        }
        let end = bytes[pos..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(n, |k| pos + k);
        let line = &bytes[pos..end];
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        pos = end + 1;
        let mut t = Tokens::new(line);
        let Some(key) = t.next() else { continue };
        match key {
            b"v" => {
                let mut p = [0.0; 3];
                for c in &mut p {
                    let tok = t.next().unwrap_or_default();
                    *c = parse_f64(tok)
                        .ok_or_else(|| Error::syntax(at(), "a vertex coordinate", tok))?;
                }
                soup.polygons.positions.push(p);
                soup.vertex_read_at(line_no);
            }
            b"f" => {
                let start = soup.polygons.indices.len();
                for corner in t {
                    face_corner(corner, &mut soup, &mut refs, at)?;
                }
                if soup.polygons.indices.len() == start {
                    return Err(Error::syntax(at(), "vertex indices after f", b""));
                }
                soup.end_face(line_no);
            }
            b"vt" => {
                let tok = t.next().unwrap_or_default();
                let u = parse_f64(tok)
                    .ok_or_else(|| Error::syntax(at(), "a texture coordinate", tok))?;
                let v = match t.next() {
                    Some(tok) => parse_f64(tok)
                        .ok_or_else(|| Error::syntax(at(), "a texture coordinate", tok))?,
                    None => 0.0,
                };
                refs.texcoords.push([u, v]);
            }
            b"vn" => {
                let mut n = [0.0; 3];
                for c in &mut n {
                    let tok = t.next().unwrap_or_default();
                    *c = parse_f64(tok)
                        .ok_or_else(|| Error::syntax(at(), "a normal coordinate", tok))?;
                }
                refs.normals.push(n);
            }
            b"g" | b"o" | b"usemtl" => {
                let rest = line.trim_ascii();
                let name = rest[key.len()..].trim_ascii();
                let name = String::from_utf8_lossy(name).into_owned();
                let face = soup.face_count();
                match key {
                    b"g" => groups.name(face, name),
                    b"o" => objects.name(face, name),
                    _ => materials.name(face, name),
                }
            }
            _ => {}
        }
    }
    let nf = soup.face_count();
    let nc = soup.polygons.indices.len();
    let a = &mut soup.attrs;
    a.face.extend(objects.finish(nf));
    a.face.extend(groups.finish(nf));
    a.face.extend(materials.finish(nf));
    if !refs.texcoord_of.is_empty() {
        a.corner.push(corner_column(
            "texcoord",
            &refs.texcoord_of,
            &refs.texcoords,
            nc,
            Data::Vec2,
        ));
    }
    if !refs.normal_of.is_empty() {
        a.corner.push(corner_column(
            "normal",
            &refs.normal_of,
            &refs.normals,
            nc,
            Data::Vec3,
        ));
    }
    Ok(soup)
}

/// A corner column from per-corner references into `values`.
fn corner_column<T: Copy + Default>(
    name: &str,
    of: &[u32],
    values: &[T],
    corners: usize,
    wrap: fn(Vec<T>) -> Data,
) -> SoupColumn {
    let mut present = vec![false; corners];
    let mut data = vec![T::default(); corners];
    for (c, &i) in of.iter().enumerate() {
        if let Some(v) = values.get(i as usize) {
            data[c] = *v;
            present[c] = true;
        }
    }
    let all = present.iter().all(|&p| p);
    SoupColumn {
        name: name.to_owned(),
        data: wrap(data),
        present: (!all).then_some(present),
    }
}

/// The current name of a `g`, `o` or `usemtl` statement, per face.
struct Names {
    column: &'static str,
    current: Option<String>,
    values: Vec<String>,
    present: Vec<bool>,
    any: bool,
}

impl Names {
    fn new(column: &'static str) -> Names {
        Names {
            column,
            current: None,
            values: Vec::new(),
            present: Vec::new(),
            any: false,
        }
    }

    /// From face `face` on, the name is `name`.
    fn name(&mut self, face: usize, name: String) {
        self.fill(face);
        self.current = Some(name);
        self.any = true;
    }

    fn fill(&mut self, upto: usize) {
        let current = self.current.clone();
        while self.values.len() < upto {
            self.present.push(current.is_some());
            self.values.push(current.clone().unwrap_or_default());
        }
    }

    fn finish(mut self, faces: usize) -> Option<SoupColumn> {
        if !self.any {
            return None;
        }
        self.fill(faces);
        let all = self.present.iter().all(|&p| p);
        Some(SoupColumn {
            name: self.column.to_owned(),
            data: Data::Text(self.values),
            present: (!all).then_some(self.present),
        })
    }
}

/// The token that starts at `s[i]`: up to whitespace or the line end.
fn token_at(s: &[u8], i: usize) -> &[u8] {
    let rest = s.get(i..).unwrap_or_default();
    let len = rest
        .iter()
        .position(|&b| is_space(b) || b == b'\n')
        .unwrap_or(rest.len());
    &rest[..len]
}

/// One `v[/vt][/vn]` corner of an `f` statement.
#[inline]
fn face_corner(
    corner: &[u8],
    soup: &mut Soup,
    refs: &mut CornerRefs,
    at: impl Fn() -> super::error::Location,
) -> Result<(), Error> {
    // The common case: a plain positive index.
    if corner.len() <= 9 && corner.iter().all(u8::is_ascii_digit) {
        let index = corner
            .iter()
            .fold(0u32, |a, &d| a * 10 + u32::from(d - b'0'));
        let count = soup.polygons.positions.len();
        if index == 0 || index as usize > count {
            return Err(Error::IndexOutOfRange {
                at: at(),
                index: i64::from(index),
                count,
            });
        }
        soup.polygons.indices.push(index - 1);
        if !refs.texcoord_of.is_empty() {
            refs.texcoord_of.push(u32::MAX);
        }
        if !refs.normal_of.is_empty() {
            refs.normal_of.push(u32::MAX);
        }
        return Ok(());
    }
    let mut parts = corner.splitn(3, |&b| b == b'/');
    let v_tok = parts.next().unwrap_or_default();
    let index = parse_i64(v_tok).ok_or_else(|| Error::syntax(at(), "a vertex index", corner))?;
    let count = soup.polygons.positions.len();
    let v = resolve(index, count).ok_or_else(|| Error::IndexOutOfRange {
        at: at(),
        index,
        count,
    })?;
    soup.polygons.indices.push(v);
    let vt = match parts.next() {
        Some(tok) if !tok.is_empty() => {
            let index = parse_i64(tok)
                .ok_or_else(|| Error::syntax(at(), "a texture coordinate index", corner))?;
            let count = refs.texcoords.len();
            resolve(index, count).ok_or_else(|| Error::IndexOutOfRange {
                at: at(),
                index,
                count,
            })?
        }
        _ => u32::MAX,
    };
    let vn = match parts.next() {
        Some(tok) if !tok.is_empty() => {
            let index =
                parse_i64(tok).ok_or_else(|| Error::syntax(at(), "a normal index", corner))?;
            let count = refs.normals.len();
            resolve(index, count).ok_or_else(|| Error::IndexOutOfRange {
                at: at(),
                index,
                count,
            })?
        }
        _ => u32::MAX,
    };
    if vt != u32::MAX || !refs.texcoord_of.is_empty() {
        let c = soup.polygons.indices.len() - 1;
        refs.texcoord_of.resize(c, u32::MAX);
        refs.texcoord_of.push(vt);
    }
    if vn != u32::MAX || !refs.normal_of.is_empty() {
        let c = soup.polygons.indices.len() - 1;
        refs.normal_of.resize(c, u32::MAX);
        refs.normal_of.push(vn);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A plain grid OBJ of at least `PARALLEL_MIN` bytes.
    fn big_grid(n: usize) -> Vec<u8> {
        let mut out = Vec::new();
        for j in 0..n {
            for i in 0..n {
                writeln!(out, "v {} {} 0.{}", i as f64 / 7.0, j as f64 / 3.0, i * j).unwrap();
            }
        }
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let a = j * n + i + 1;
                writeln!(
                    out,
                    "f {a} {} {}\nf {a} {} {}",
                    a + 1,
                    a + n + 1,
                    a + n + 1,
                    a + n
                )
                .unwrap();
            }
        }
        assert!(out.len() >= PARALLEL_MIN);
        out
    }

    #[test]
    fn halves_read_the_same_as_one_pass() {
        let bytes = big_grid(260);
        let both = parse_halves(&bytes).expect("a plain file is read in halves");
        let one = parse_serial(&bytes, false).unwrap();
        assert_eq!(both.polygons, one.polygons);
    }

    #[test]
    fn anything_unusual_in_a_half_falls_back_to_one_pass() {
        let mut bytes = big_grid(260);
        // A negative index near the end, a group name, an out-of-range index.
        for tail in ["f -1 -2 -3\n", "g late\nf 1 2 3\n", "f 1 2 99999999\n"] {
            let mut b = bytes.clone();
            b.extend_from_slice(tail.as_bytes());
            assert!(parse_halves(&b).is_none(), "{tail}");
        }
        bytes.extend_from_slice(b"f 1 2 99999999\n");
        let lines = bytes.iter().filter(|&&b| b == b'\n').count() as u64;
        let err = parse(&bytes, false).err().expect("an index out of range");
        assert_eq!(err.line(), Some(lines));
    }
}
