//! `meshloom.read`, `read_with` and `write`: the Rust readers and writers
//! with their repair policies; errors as `ReadError` with file and line.

use meshloom::io::{ReadOptions, RepairOptions, WriteOptions};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::io_err;
use crate::mesh::PyMesh;

/// Read a mesh file strictly: OBJ, OFF, PLY, STL (optionally `.gz`) or
/// glTF 2.0 (`.gltf`, `.glb`; every mesh of the scene, texture coordinates
/// as the corner column `texcoord`). Raises `ReadError` naming the
/// file and line (or byte) for anything a half-edge mesh cannot hold.
#[pyfunction]
pub fn read(py: Python<'_>, path: std::path::PathBuf) -> PyResult<PyMesh> {
    let mesh = py
        .detach(|| meshloom::io::read(&path))
        .map_err(|e| io_err(py, e))?;
    Ok(PyMesh::wrap(mesh))
}

const POLICIES: &[&str] = &[
    "weld_vertices",
    "drop_degenerate_faces",
    "drop_duplicate_faces",
    "orient_faces",
    "split_nonmanifold_edges",
    "split_nonmanifold_vertices",
    "drop_unreferenced_vertices",
];

fn policies(repair: &Bound<'_, PyAny>) -> PyResult<RepairOptions> {
    if repair.is_none() {
        return Ok(RepairOptions::none());
    }
    if let Ok(s) = repair.extract::<String>() {
        return match s.as_str() {
            "all" => Ok(RepairOptions::all()),
            "none" => Ok(RepairOptions::none()),
            other => Err(PyValueError::new_err(format!(
                "repair is \"all\", \"none\" or a list of policies, not {other:?}"
            ))),
        };
    }
    let mut o = RepairOptions::none();
    for name in repair.try_iter()? {
        let name: String = name?.extract()?;
        let flag = match name.as_str() {
            "weld_vertices" => &mut o.weld_vertices,
            "drop_degenerate_faces" => &mut o.drop_degenerate_faces,
            "drop_duplicate_faces" => &mut o.drop_duplicate_faces,
            "orient_faces" => &mut o.orient_faces,
            "split_nonmanifold_edges" => &mut o.split_nonmanifold_edges,
            "split_nonmanifold_vertices" => &mut o.split_nonmanifold_vertices,
            "drop_unreferenced_vertices" => &mut o.drop_unreferenced_vertices,
            other => {
                return Err(PyValueError::new_err(format!(
                    "unknown repair policy {other:?}; the policies are {POLICIES:?}"
                )))
            }
        };
        *flag = true;
    }
    Ok(o)
}

/// Read a mesh file with repair policies: `repair` is "all" (every policy
/// but welding), "none", or a list of policy names; `weld=True` adds
/// welding of bit-identical positions. Returns `(mesh, report)`, the report
/// a dict of what the repairs did (counts and `warnings`).
#[pyfunction]
#[pyo3(signature = (path, repair = None, weld = false, max_bytes = None))]
pub fn read_with(
    py: Python<'_>,
    path: std::path::PathBuf,
    repair: Option<&Bound<'_, PyAny>>,
    weld: bool,
    max_bytes: Option<u64>,
) -> PyResult<(PyMesh, Py<PyAny>)> {
    let mut options = ReadOptions::strict();
    if let Some(r) = repair {
        options.repair = policies(r)?;
    } else {
        options.repair = RepairOptions::all();
    }
    options.repair.weld_vertices |= weld;
    if let Some(m) = max_bytes {
        options.max_bytes = m;
    }
    let (mesh, report) = py
        .detach(|| meshloom::io::read_with(&path, &options))
        .map_err(|e| io_err(py, e))?;
    let json = serde_json::to_string(&report).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let report = py.import("json")?.call_method1("loads", (json,))?;
    Ok((PyMesh::wrap(mesh), report.unbind()))
}

/// Write a mesh; the format comes from the extension (`.obj`, `.off`,
/// `.ply`, `.stl`, optionally `.gz`; `.gltf` (JSON with the buffer inside)
/// or `.glb`). PLY and STL are binary unless
/// `ascii=True`. Raises `ReadError` (with `file`) when it cannot.
#[pyfunction]
#[pyo3(signature = (mesh, path, ascii = false))]
pub fn write(
    py: Python<'_>,
    mesh: PyRef<'_, PyMesh>,
    path: std::path::PathBuf,
    ascii: bool,
) -> PyResult<()> {
    let options = if ascii {
        WriteOptions::ascii()
    } else {
        WriteOptions::default()
    };
    meshloom::io::write_with(&mesh.mesh, &path, &options).map_err(|e| io_err(py, e))
}
