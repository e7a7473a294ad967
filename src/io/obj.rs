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

use super::error::Error;
use super::{emit, polygons_of, slurp, ReadOptions};
use crate::attr::Value;
use crate::mesh::Mesh;

mod halves;
mod parse;

pub(crate) use parse::parse;

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
