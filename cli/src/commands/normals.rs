//! `--normals`: angle-weighted vertex normals (`meshloom::algo::normals`),
//! stored the way the output format carries them, and stale normal columns
//! dropped after a command that moved vertices.

use std::path::Path;

use meshloom::algo::normals::{
    add_corner_normals, add_vertex_normals, vertex_normals, CornerNormalOptions,
    VertexNormalOptions, NORMAL,
};
use meshloom::attr::{Interpolate, Value};
use meshloom::io::Format;
use meshloom::{ElementKind, FaceKey, HalfedgeKey, Mesh, VertexKey};

use crate::Failure;

/// [`add_for`] the format of the file `output`.
pub fn add_for_path(mesh: &mut Mesh, output: &Path) -> Result<&'static str, Failure> {
    add_for(mesh, Format::from_path(output).map(|(f, _gz)| f))
}

/// Compute angle-weighted vertex normals and store them for `format`: OBJ
/// `vn` (a corner column, one value per vertex), OFF `NOFF` and glTF
/// `NORMAL` (a vertex column; `None` is glTF), PLY `nx ny nz` (three vertex
/// properties). Returns what was written, or why nothing was (STL).
pub fn add_for(mesh: &mut Mesh, format: Option<Format>) -> Result<&'static str, Failure> {
    let fail = |e: meshloom::Error| Failure::input(format!("cannot compute normals: {e}"));
    match format {
        Some(Format::Stl) => Ok("none: STL carries only facet normals, which it always writes"),
        Some(Format::Obj) => {
            add_corner_normals(mesh, &CornerNormalOptions::smooth()).map_err(fail)?;
            Ok("OBJ vn, angle-weighted vertex normals")
        }
        Some(Format::Ply) => {
            let n = vertex_normals(mesh, &VertexNormalOptions::default()).map_err(fail)?;
            let keys: Vec<VertexKey> = mesh.vertices().collect();
            for (k, name) in ["nx", "ny", "nz"].into_iter().enumerate() {
                // A column of that name (read from a PLY file, of any
                // number type) is written through by name.
                let exists = mesh
                    .attr_info(ElementKind::Vertex)
                    .iter()
                    .any(|a| a.name == name);
                if !exists {
                    mesh.add_vertex_attr::<f64>(name).map_err(fail)?;
                }
                for &v in &keys {
                    mesh.set_attr_value(name, v, Some(&Value::F64(n[v.index()][k])))
                        .map_err(fail)?;
                }
            }
            Ok("PLY nx ny nz, angle-weighted vertex normals")
        }
        // OFF and glTF.
        _ => {
            add_vertex_normals(mesh, &VertexNormalOptions::default()).map_err(fail)?;
            Ok("vertex normals (OFF NOFF, glTF NORMAL), angle-weighted")
        }
    }
}

/// Remove the `normal` columns (`[f64; 3]`, as read from OBJ, OFF and
/// glTF files) that moving the vertices made stale; their names, as
/// `"vertex normal"`.
pub fn drop_stale(mesh: &mut Mesh) -> Vec<String> {
    let mut dropped = Vec::new();
    if let Ok(h) = mesh.attr_handle::<VertexKey, [f64; 3], Interpolate>(NORMAL) {
        if mesh.remove_attr(&h).is_ok() {
            dropped.push(format!("vertex {NORMAL}"));
        }
    }
    if let Ok(h) = mesh.attr_handle::<HalfedgeKey, [f64; 3], Interpolate>(NORMAL) {
        if mesh.remove_attr(&h).is_ok() {
            dropped.push(format!("halfedge {NORMAL}"));
        }
    }
    if let Ok(h) = mesh.attr_handle::<FaceKey, [f64; 3], Interpolate>(NORMAL) {
        if mesh.remove_attr(&h).is_ok() {
            dropped.push(format!("face {NORMAL}"));
        }
    }
    dropped
}
