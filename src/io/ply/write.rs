//! Writing PLY: positions as `double`, the face list, and every vertex and
//! face attribute PLY can hold.

use std::io::Write;

use super::header::Scalar;
use super::PlyEncoding;
use crate::attr::{Value, ValueType};
use crate::io::error::Error;
use crate::io::{emit, polygons_of};
use crate::mesh::Mesh;

/// Write a mesh as PLY: `vertex` with `double x y z`, `face` with a
/// `vertex_indices` list (holes are not written), and every vertex and face
/// attribute with a PLY type as a property of that type: dynamic columns
/// keep their declared type, `f64` columns are `double`, arrays and lists
/// are list properties, `i64`/`u64` go as `double` and `bool` as `uchar`.
/// An element without a value writes 0 (an empty list).
///
/// Half-edge (corner) attributes with a PLY type go on the vertices where
/// every corner of a vertex holds the same value (no seams): `texcoord` as
/// `s t`, `normal` as `nx ny nz`, others as `name` or `name_0 name_1 ...`.
/// A `texcoord` column with seams goes on the faces as a list property
/// `texcoord` (two numbers per corner, in the face's corner order), as
/// MeshLab and Assimp write it. Text columns, edge attributes and other
/// corner columns with seams have no place in PLY and are left out
/// ([`dropped_columns`](crate::io::dropped_columns) names them).
///
/// # Errors
/// [`Error::Unwritable`] without positions; [`Error::Io`].
pub fn write_ply(mesh: &Mesh, writer: impl Write, encoding: PlyEncoding) -> Result<(), Error> {
    let (p, maps) = polygons_of(mesh)?;
    let mut vcols = out_columns(mesh, &maps.vertices);
    let mut fcols = out_columns(mesh, &maps.faces);
    let corners = corner_columns(mesh, &maps);
    vcols.extend(corners.vertex);
    fcols.extend(corners.face);
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

/// Half-edge columns as PLY holds them: per-vertex properties where they
/// have no seams, a face list for a seamed `texcoord`, and the names of
/// what PLY cannot hold.
pub(crate) struct CornerColumns {
    vertex: Vec<OutColumn>,
    face: Vec<OutColumn>,
    pub(crate) dropped: Vec<String>,
}

/// Split half-edge columns as [`write_ply`] documents.
pub(crate) fn corner_columns(mesh: &Mesh, maps: &crate::build::IndexMaps) -> CornerColumns {
    let mut out = CornerColumns {
        vertex: Vec::new(),
        face: Vec::new(),
        dropped: Vec::new(),
    };
    for info in mesh.attr_info(crate::ElementKind::Halfedge) {
        let portable = info.value_type.is_some_and(|t| t != ValueType::Text);
        if !portable {
            out.dropped
                .push(format!("half-edge attribute {:?} (no PLY type)", info.name));
            continue;
        }
        // Each face's corner values, in the face's corner order, and each
        // vertex's value if all its corners agree.
        let mut per_face: Vec<Vec<Option<Value>>> = Vec::with_capacity(maps.faces.len());
        let mut per_vertex: Vec<Option<Value>> = vec![None; maps.vertices.len()];
        let mut seen = vec![false; maps.vertices.len()];
        let mut seamless = true;
        for &f in &maps.faces {
            let Ok(view) = mesh.face(f) else { continue };
            let mut corners = Vec::new();
            for h in view.halfedges() {
                let value = mesh.attr_value(&info.name, h).ok().flatten();
                let origin = mesh.halfedge(h).ok().map(|v| v.origin().key());
                if let Some(i) = origin.and_then(|v| maps.vertex_index(v)) {
                    if !seen[i] {
                        seen[i] = true;
                        per_vertex[i] = value.clone();
                    } else if per_vertex[i] != value {
                        seamless = false;
                    }
                }
                corners.push(value);
            }
            per_face.push(corners);
        }
        let numbers = |v: &Option<Value>| -> Option<Vec<f64>> {
            match v.as_ref()? {
                Value::List(items) => items.iter().map(Value::as_f64).collect(),
                other => other.as_f64().map(|x| vec![x]),
            }
        };
        let width = per_vertex.iter().find_map(|v| numbers(v).map(|n| n.len()));
        let same_width = per_vertex
            .iter()
            .all(|v| v.is_none() || numbers(v).map(|n| n.len()) == width);
        let names: Vec<String> = match (info.name.as_str(), width) {
            ("texcoord", Some(2)) => vec!["s".into(), "t".into()],
            ("normal", Some(3)) => vec!["nx".into(), "ny".into(), "nz".into()],
            (name, Some(1)) => vec![name.into()],
            (name, Some(n)) => (0..n).map(|k| format!("{name}_{k}")).collect(),
            (_, None) => Vec::new(),
        };
        if seamless && same_width && !names.is_empty() {
            for (k, name) in names.into_iter().enumerate() {
                out.vertex.push(OutColumn {
                    name,
                    item: Scalar::F32,
                    list: None,
                    values: per_vertex
                        .iter()
                        .map(|v| numbers(v).map(|n| Value::F64(n[k])))
                        .collect(),
                });
            }
        } else if info.name == "texcoord" {
            out.face.push(OutColumn {
                name: "texcoord".into(),
                item: Scalar::F32,
                list: Some(Scalar::U8),
                values: per_face
                    .iter()
                    .map(|corners| {
                        let flat: Vec<Value> = corners
                            .iter()
                            .flat_map(|c| {
                                let n = numbers(c).unwrap_or_default();
                                (0..2).map(move |k| Value::F64(n.get(k).copied().unwrap_or(0.0)))
                            })
                            .collect();
                        Some(Value::List(flat))
                    })
                    .collect(),
            });
        } else {
            out.dropped.push(format!(
                "half-edge attribute {:?} (differs between the corners of a vertex; PLY holds it per vertex only)",
                info.name
            ));
        }
    }
    out
}
