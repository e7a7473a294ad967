//! The OBJ statements, one after the other, with every feature and error;
//! large plain files go to [`halves`](super::halves) first.

use super::halves::{next_corner, next_line, parse_halves, plain_index, PARALLEL_MIN};
use crate::io::attrs::{Data, SoupColumn};
use crate::io::error::{Error, Location};
use crate::io::soup::Soup;
use crate::io::text::{is_space, parse_f64, parse_f64_at, parse_i64, Tokens};

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

/// Parse OBJ bytes into a soup.
pub(crate) fn parse(bytes: &[u8], record: bool) -> Result<Soup, Error> {
    if !record && bytes.len() >= PARALLEL_MIN {
        if let Some(soup) = parse_halves(bytes) {
            return Ok(soup);
        }
    }
    parse_serial(bytes, record)
}

/// Parse OBJ bytes into a soup, one statement after the other.
pub(super) fn parse_serial(bytes: &[u8], record: bool) -> Result<Soup, Error> {
    let mut read = Statements::new(record, bytes.len());
    let n = bytes.len();
    let mut pos = 0;
    let mut line_no = 0u64;
    while pos < n {
        line_no += 1;
        // The hot statements, `v x y z` and `f` with plain indices, are
        // parsed in place in one pass; everything else goes by tokens.
        let head = &bytes[pos..n.min(pos + 2)];
        if head.len() == 2
            && (head[1] == b' ' || head[1] == b'\t')
            && (head[0] == b'v' || head[0] == b'f')
        {
            let i = if head[0] == b'v' {
                read.vertex_in_place(bytes, pos + 2, line_no)?
            } else {
                read.face_in_place(bytes, pos + 2, line_no)?
            };
            // The rest of the line (a `w`, vertex colours, a comment).
            pos = next_line(bytes, i);
            continue;
        }
        let end = bytes[pos..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(n, |k| pos + k);
        let line = &bytes[pos..end];
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        pos = end + 1;
        read.statement(line, line_no)?;
    }
    Ok(read.finish())
}

/// What the statements build: the polygons, the corners' references and
/// the names of groups, objects and materials per face.
struct Statements {
    soup: Soup,
    refs: CornerRefs,
    groups: Names,
    objects: Names,
    materials: Names,
}

impl Statements {
    /// Ready for `len` bytes of statements.
    fn new(record: bool, len: usize) -> Statements {
        let mut soup = Soup::new(record);
        // Reserve by the input's size only: about 30 bytes per statement.
        soup.polygons.positions.reserve(len / 48);
        soup.polygons.indices.reserve(len / 8);
        soup.polygons.offsets.reserve(len / 24);
        Statements {
            soup,
            refs: CornerRefs::default(),
            groups: Names::new("group"),
            objects: Names::new("object"),
            materials: Names::new("material"),
        }
    }

    /// A `v x y z` statement from `bytes[i..]` (after `v `), parsed in
    /// place; returns where the coordinates end.
    #[inline]
    fn vertex_in_place(
        &mut self,
        bytes: &[u8],
        mut i: usize,
        line_no: u64,
    ) -> Result<usize, Error> {
        let n = bytes.len();
        let mut p = [0.0; 3];
        for c in &mut p {
            while i < n && is_space(bytes[i]) {
                i += 1;
            }
            *c = parse_f64_at(bytes, &mut i).ok_or_else(|| {
                Error::syntax(
                    Location::line(line_no),
                    "a vertex coordinate",
                    token_at(bytes, i),
                )
            })?;
        }
        self.soup.polygons.positions.push(p);
        self.soup.vertex_read_at(line_no);
        Ok(i)
    }

    /// An `f` statement from `bytes[i..]` (after `f `), plain indices
    /// parsed in place; returns where its corners end.
    #[inline]
    fn face_in_place(&mut self, bytes: &[u8], mut i: usize, line_no: u64) -> Result<usize, Error> {
        let at = || Location::line(line_no);
        let (soup, refs) = (&mut self.soup, &mut self.refs);
        let start = soup.polygons.indices.len();
        while let Some(st) = next_corner(bytes, i) {
            // A plain index, parsed in place.
            let plain = plain_index(bytes, st).filter(|&(v, _)| {
                v as usize <= soup.polygons.positions.len()
                    && refs.texcoord_of.is_empty()
                    && refs.normal_of.is_empty()
            });
            if let Some((v, end)) = plain {
                i = end;
                soup.polygons.indices.push(v - 1);
                continue;
            }
            let tok = token_at(bytes, st);
            i = st + tok.len();
            face_corner(tok, soup, refs, at)?;
        }
        if soup.polygons.indices.len() == start {
            return Err(Error::syntax(at(), "vertex indices after f", b""));
        }
        soup.end_face(line_no);
        Ok(i)
    }

    /// Any statement, by its tokens: `line` is the line without its end.
    fn statement(&mut self, line: &[u8], line_no: u64) -> Result<(), Error> {
        let at = || Location::line(line_no);
        let mut t = Tokens::new(line);
        let Some(key) = t.next() else {
            return Ok(());
        };
        match key {
            b"v" => {
                let p = numbers::<3>(&mut t, at, "a vertex coordinate")?;
                self.soup.polygons.positions.push(p);
                self.soup.vertex_read_at(line_no);
            }
            b"f" => {
                let start = self.soup.polygons.indices.len();
                for corner in t {
                    face_corner(corner, &mut self.soup, &mut self.refs, at)?;
                }
                if self.soup.polygons.indices.len() == start {
                    return Err(Error::syntax(at(), "vertex indices after f", b""));
                }
                self.soup.end_face(line_no);
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
                self.refs.texcoords.push([u, v]);
            }
            b"vn" => {
                let n = numbers::<3>(&mut t, at, "a normal coordinate")?;
                self.refs.normals.push(n);
            }
            b"g" | b"o" | b"usemtl" => {
                let rest = line.trim_ascii();
                let name = rest[key.len()..].trim_ascii();
                let name = String::from_utf8_lossy(name).into_owned();
                let face = self.soup.face_count();
                match key {
                    b"g" => self.groups.name(face, name),
                    b"o" => self.objects.name(face, name),
                    _ => self.materials.name(face, name),
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// The soup, with the name and corner columns.
    fn finish(self) -> Soup {
        let mut soup = self.soup;
        let refs = self.refs;
        let nf = soup.face_count();
        let nc = soup.polygons.indices.len();
        let a = &mut soup.attrs;
        a.face.extend(self.objects.finish(nf));
        a.face.extend(self.groups.finish(nf));
        a.face.extend(self.materials.finish(nf));
        let texcoord = corner_column(
            "texcoord",
            &refs.texcoord_of,
            &refs.texcoords,
            nc,
            Data::Vec2,
        );
        a.corner.extend(texcoord);
        let normal = corner_column("normal", &refs.normal_of, &refs.normals, nc, Data::Vec3);
        a.corner.extend(normal);
        soup
    }
}

/// `N` numbers, the next tokens; a missing one is an empty token.
#[inline]
fn numbers<const N: usize>(
    t: &mut Tokens<'_>,
    at: impl Fn() -> Location,
    what: &str,
) -> Result<[f64; N], Error> {
    let mut p = [0.0; N];
    for c in &mut p {
        let tok = t.next().unwrap_or_default();
        *c = parse_f64(tok).ok_or_else(|| Error::syntax(at(), what, tok))?;
    }
    Ok(p)
}

/// A corner column from per-corner references into `values`; `None`
/// where no corner has a reference.
fn corner_column<T: Copy + Default>(
    name: &str,
    of: &[u32],
    values: &[T],
    corners: usize,
    wrap: fn(Vec<T>) -> Data,
) -> Option<SoupColumn> {
    if of.is_empty() {
        return None;
    }
    let mut present = vec![false; corners];
    let mut data = vec![T::default(); corners];
    for (c, &i) in of.iter().enumerate() {
        if let Some(v) = values.get(i as usize) {
            data[c] = *v;
            present[c] = true;
        }
    }
    let all = present.iter().all(|&p| p);
    Some(SoupColumn {
        name: name.to_owned(),
        data: wrap(data),
        present: (!all).then_some(present),
    })
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
    at: impl Fn() -> Location,
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
                what: "vertex",
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
    let reference = |tok: &[u8], kind: &'static str, count: usize| -> Result<u32, Error> {
        let index =
            parse_i64(tok).ok_or_else(|| Error::syntax(at(), format!("a {kind} index"), corner))?;
        resolve(index, count).ok_or_else(|| Error::IndexOutOfRange {
            at: at(),
            what: kind,
            index,
            count,
        })
    };
    let v = reference(v_tok, "vertex", soup.polygons.positions.len())?;
    soup.polygons.indices.push(v);
    let vt = match parts.next() {
        Some(tok) if !tok.is_empty() => reference(tok, "texture coordinate", refs.texcoords.len())?,
        _ => u32::MAX,
    };
    let vn = match parts.next() {
        Some(tok) if !tok.is_empty() => reference(tok, "normal", refs.normals.len())?,
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
