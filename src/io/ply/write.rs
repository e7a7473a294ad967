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
