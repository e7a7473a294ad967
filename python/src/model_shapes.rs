//! The native side of `meshloom.shapes`: the textured primitives (a corner
//! `"uv"` column laid out as Blender's, a face `"material"` column per side
//! when asked, as an integer column like Python's). `meshloom/shapes.py`
//! gives them their Python signatures.

use meshloom::attr::Incompatible;
use meshloom::shapes::{self, ShapeOptions};
use meshloom::{Error, FaceKey, Mesh};
use pyo3::prelude::*;
use pyo3::IntoPyObjectExt;

use crate::errors::{build_err, raise};
use crate::mesh::PyMesh;

/// A shape's error as the exception of `meshloom.errors`: a parameter out
/// of range is an `UnsuitableError` (with `algorithm` and `reason`).
fn shape_err(py: Python<'_>, e: Error) -> PyErr {
    let msg = e.to_string();
    match e {
        Error::Unsuitable {
            algorithm, reason, ..
        } => raise(
            py,
            "UnsuitableError",
            msg,
            &[
                ("algorithm", algorithm.into_py_any(py).unwrap_or(py.None())),
                ("reason", reason.into_py_any(py).unwrap_or(py.None())),
                ("element", py.None()),
            ],
        ),
        Error::Build(b) => build_err(py, b),
        _ => raise(py, "MeshloomError", msg, &[]),
    }
}

/// A count from Python: a negative one is out of range like any other.
fn count(py: Python<'_>, shape: &'static str, name: &str, n: i64) -> PyResult<usize> {
    usize::try_from(n).map_err(|_| {
        shape_err(
            py,
            Error::Unsuitable {
                algorithm: shape,
                key: None,
                reason: format!("{name} must not be negative (got {n})"),
            },
        )
    })
}

/// The `u32` material column as Python's integer columns are (`i64`,
/// incompatible), so that `attr_array` and the tools' `material=` read it.
fn int_materials(mut mesh: Mesh) -> meshloom::Result<Mesh> {
    let Ok(old) = mesh.attr_handle::<FaceKey, u32, Incompatible>(shapes::MATERIAL) else {
        return Ok(mesh);
    };
    let values: Vec<(FaceKey, u32)> = mesh
        .faces()
        .filter_map(|f| Some((f, *mesh.attr(&old, f).ok()??)))
        .collect();
    mesh.remove_attr(&old)?;
    let new = mesh.add_face_attr::<i64>(shapes::MATERIAL)?;
    for (f, m) in values {
        mesh.set_attr(&new, f, i64::from(m))?;
    }
    Ok(mesh)
}

/// Build a shape without the GIL; errors as exceptions.
fn made(py: Python<'_>, build: impl FnOnce() -> meshloom::Result<Mesh> + Send) -> PyResult<PyMesh> {
    py.detach(|| build().and_then(int_materials))
        .map(PyMesh::wrap)
        .map_err(|e| shape_err(py, e))
}

fn options(uv: bool, materials: bool, caps: bool) -> ShapeOptions {
    ShapeOptions {
        uv,
        materials,
        caps,
    }
}

/// `meshloom.shapes.box`: a box of sizes `(x, y, z)` centred on the origin.
#[pyfunction]
#[pyo3(signature = (size, uv, materials))]
pub fn _shape_box(py: Python<'_>, size: [f64; 3], uv: bool, materials: bool) -> PyResult<PyMesh> {
    let o = options(uv, materials, true);
    made(py, || shapes::box_mesh(size, &o))
}

/// `meshloom.shapes.cylinder` and `cone` (radii at the bottom and the top).
#[pyfunction]
#[pyo3(signature = (radius_bottom, radius_top, height, segments, caps, uv, materials, cylinder))]
#[allow(clippy::too_many_arguments)]
pub fn _shape_cone(
    py: Python<'_>,
    radius_bottom: f64,
    radius_top: f64,
    height: f64,
    segments: i64,
    caps: bool,
    uv: bool,
    materials: bool,
    cylinder: bool,
) -> PyResult<PyMesh> {
    let shape = if cylinder { "cylinder" } else { "cone" };
    let s = count(py, shape, "segments", segments)?;
    let o = options(uv, materials, caps);
    if cylinder {
        made(py, || shapes::cylinder(radius_bottom, height, s, &o))
    } else {
        made(py, || {
            shapes::cone(radius_bottom, radius_top, height, s, &o)
        })
    }
}

/// `meshloom.shapes.grid`: `cols × rows` quads of sizes `(x, y)`.
#[pyfunction]
#[pyo3(signature = (size, cols, rows, uv, materials))]
pub fn _shape_grid(
    py: Python<'_>,
    size: [f64; 2],
    cols: i64,
    rows: i64,
    uv: bool,
    materials: bool,
) -> PyResult<PyMesh> {
    let (c, r) = (
        count(py, "grid", "cols", cols)?,
        count(py, "grid", "rows", rows)?,
    );
    let o = options(uv, materials, true);
    made(py, || shapes::textured_grid(size, c, r, &o))
}

/// `meshloom.shapes.uv_sphere`.
#[pyfunction]
#[pyo3(signature = (radius, segments, rings, uv, materials))]
pub fn _shape_uv_sphere(
    py: Python<'_>,
    radius: f64,
    segments: i64,
    rings: i64,
    uv: bool,
    materials: bool,
) -> PyResult<PyMesh> {
    let s = count(py, "uv_sphere", "segments", segments)?;
    let r = count(py, "uv_sphere", "rings", rings)?;
    let o = options(uv, materials, true);
    made(py, || shapes::textured_uv_sphere(radius, s, r, &o))
}

/// `meshloom.shapes.icosphere`.
#[pyfunction]
#[pyo3(signature = (radius, subdivisions, uv, materials))]
pub fn _shape_icosphere(
    py: Python<'_>,
    radius: f64,
    subdivisions: i64,
    uv: bool,
    materials: bool,
) -> PyResult<PyMesh> {
    let n = count(py, "icosphere", "subdivisions", subdivisions)?;
    let n = u32::try_from(n).unwrap_or(u32::MAX);
    let o = options(uv, materials, true);
    made(py, || shapes::textured_icosphere(radius, n, &o))
}

/// `meshloom.shapes.torus`.
#[pyfunction]
#[pyo3(signature = (major_radius, minor_radius, major_segments, minor_segments, uv, materials))]
pub fn _shape_torus(
    py: Python<'_>,
    major_radius: f64,
    minor_radius: f64,
    major_segments: i64,
    minor_segments: i64,
    uv: bool,
    materials: bool,
) -> PyResult<PyMesh> {
    let big = count(py, "torus", "major_segments", major_segments)?;
    let small = count(py, "torus", "minor_segments", minor_segments)?;
    let o = options(uv, materials, true);
    made(py, || {
        shapes::textured_torus(major_radius, minor_radius, big, small, &o)
    })
}

/// Register the shape functions on the native module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_shape_box, m)?)?;
    m.add_function(wrap_pyfunction!(_shape_cone, m)?)?;
    m.add_function(wrap_pyfunction!(_shape_grid, m)?)?;
    m.add_function(wrap_pyfunction!(_shape_uv_sphere, m)?)?;
    m.add_function(wrap_pyfunction!(_shape_icosphere, m)?)?;
    m.add_function(wrap_pyfunction!(_shape_torus, m)?)?;
    Ok(())
}
