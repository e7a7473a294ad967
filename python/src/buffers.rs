//! Triangle buffers for renderers and game engines, both ways:
//! `Mesh.to_triangle_buffers` (vertices split where corner values or
//! normals differ) and `Mesh.from_triangle_buffers` (welded back by
//! position; corner columns come back as half-edge columns, so UV seams
//! survive the round trip).

use crate::errors::busy;
use meshloom::buffers::{
    BufferColumn, ColumnChoice, ColumnSource, FromBuffersOptions, Indices, TriangleBufferOptions,
    TriangleBuffers, Weld,
};
use meshloom::keys::ElementKind;
use meshloom::Mesh;
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::mesh::PyMesh;

/// A buffer error (bad lengths, an index out of range, triangles that do
/// not form a half-edge mesh) as `ValueError`, or `BuildError` when the
/// builder names the triangle.
fn buffer_err(py: Python<'_>, e: meshloom::buffers::BufferError) -> PyErr {
    match e {
        meshloom::buffers::BufferError::Build { source, .. } => {
            crate::errors::build_err(py, source)
        }
        other => PyValueError::new_err(other.to_string()),
    }
}

/// Rows of `n` components as an (len / n, n) array.
fn rows<'py, T: numpy::Element + Copy>(
    py: Python<'py>,
    data: &[T],
    n: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let n = n.max(1);
    Ok(PyArray1::from_slice(py, data)
        .reshape([data.len() / n, n])?
        .into_any())
}

/// An (n, k) float64 array (or sequence) flattened, with n and k.
fn flat_rows(ob: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<f64>, usize, usize)> {
    let py = ob.py();
    let np = py.import("numpy")?;
    let arr = np.call_method1("ascontiguousarray", (ob, numpy::dtype::<f64>(py)))?;
    let ndim: usize = arr.getattr("ndim")?.extract()?;
    let arr = match ndim {
        1 => arr.call_method1("reshape", ((-1i64, 1i64),))?,
        2 => arr,
        _ => {
            return Err(PyValueError::new_err(format!(
                "{what} must be an (n,) or (n, k) array"
            )))
        }
    };
    let arr = arr
        .cast_into::<numpy::PyArray2<f64>>()
        .map_err(|_| PyValueError::new_err(format!("{what} must be an array of numbers")))?;
    let ro = arr.readonly();
    let (n, k) = (ro.shape()[0], ro.shape()[1]);
    Ok((ro.as_slice()?.to_vec(), n, k))
}

fn source_of(s: &str) -> PyResult<ColumnSource> {
    // "halfedge" is Python's older name of a corner column.
    if s == "halfedge" {
        return Ok(ColumnSource::Corner);
    }
    crate::algo::parse_word(s)
}

/// A column choice: a name (a half-edge column of that name if there is
/// one, else the vertex column) or a `(name, "vertex" | "corner")` pair.
fn choice_of(mesh: &Mesh, ob: &Bound<'_, PyAny>) -> PyResult<ColumnChoice> {
    if let Ok(name) = ob.extract::<String>() {
        let corner = mesh
            .attr_info(ElementKind::Halfedge)
            .iter()
            .any(|i| i.name == name);
        return Ok(if corner {
            ColumnChoice::corner(&name)
        } else {
            ColumnChoice::vertex(&name)
        });
    }
    let (name, source): (String, String) = ob.extract().map_err(|_| {
        PyTypeError::new_err("a column is a name or a (name, \"vertex\" | \"corner\") pair")
    })?;
    Ok(ColumnChoice {
        name,
        source: source_of(&source)?,
    })
}

/// The corner normals `to_triangle_buffers` asks for: `weight` by name.
fn normal_options(
    weight: &str,
    crease_angle: Option<f64>,
    hard_edges: Option<meshloom::attr::EdgeAttr<bool>>,
) -> PyResult<meshloom::algo::CornerNormalOptions> {
    let weight: meshloom::algo::NormalWeight = crate::algo::parse_word(weight)?;
    Ok(meshloom::algo::CornerNormalOptions::default()
        .weight(weight)
        .feature_angle(crease_angle)
        .features(hard_edges))
}

/// The index width `index_type` names, set in `options`; whether uint16
/// indices are required (an error when they do not fit).
fn index_width(index_type: &str, options: &mut TriangleBufferOptions) -> PyResult<bool> {
    // numpy's names: "uint32" is the library's `u32`; "uint16" is `auto`
    // that must come out as 16 bits.
    let word = match index_type {
        "uint16" => return Ok(true),
        "uint32" => "u32",
        other => other,
    };
    options.index_width = word.parse().map_err(|e: meshloom::choice::UnknownChoice| {
        PyValueError::new_err(format!("index_type: {e}, uint16 or uint32"))
    })?;
    Ok(false)
}

/// What `to_triangle_buffers` takes from the buffers after the vertex
/// arrays: the columns (a dict), indices, triangle faces, vertex sources.
type BufferParts<'py> = (
    Bound<'py, PyDict>,
    Indices,
    Vec<meshloom::FaceKey>,
    Vec<meshloom::VertexKey>,
);

/// Put `b`'s positions (and its normals, when asked for) into `out`, and
/// its columns into a dict; hand back the rest.
fn put_vertices<'py, S: numpy::Element + Copy>(
    out: &Bound<'py, PyDict>,
    b: meshloom::buffers::TriangleBuffers<S>,
    normals: bool,
) -> PyResult<BufferParts<'py>> {
    let py = out.py();
    out.set_item("positions", rows(py, b.positions.as_flattened(), 3)?)?;
    if normals {
        out.set_item("normals", rows(py, b.normals.as_flattened(), 3)?)?;
    }
    let cols = PyDict::new(py);
    for c in &b.columns {
        cols.set_item(&c.name, rows(py, &c.data, c.components)?)?;
    }
    Ok((cols, b.indices, b.triangle_faces, b.vertex_sources))
}

#[pymethods]
impl PyMesh {
    /// Triangle buffers for a renderer or game engine, as a dict of numpy
    /// arrays: `positions` (v, 3), `normals` (v, 3) (when `normals`),
    /// `indices` (t, 3), `columns` (a dict from name to a (v, c) array),
    /// `triangle_faces` (t,) (the slot index of each triangle's face) and
    /// `vertex_sources` (v,) (the slot index of each buffer vertex's mesh
    /// vertex). Faces are fanned into triangles; a mesh vertex is split
    /// where its corners' normals or corner-column values differ (UV
    /// seams, creases). `crease_angle` (radians, default 30 degrees; None:
    /// smooth everywhere), `weight` ("angle", "area", "uniform") and
    /// `hard_edges` (a bool edge column) choose the normals. `columns`:
    /// names (a corner column if there is one of that name, else a vertex
    /// column) or `(name, "vertex" | "corner")` pairs, of float or float
    /// vector values. `index_type`: "auto" (uint16 when it fits), "uint16"
    /// (an error past 65,535 vertices) or "uint32". `dtype`: "float32"
    /// (default) or "float64" (positions come out exactly).
    #[pyo3(signature = (*, normals = true, crease_angle = Some(30f64.to_radians()), weight = "angle", hard_edges = None, columns = None, index_type = "auto", dtype = "float32"))]
    #[allow(clippy::too_many_arguments)]
    fn to_triangle_buffers(
        slf: &Bound<'_, Self>,
        normals: bool,
        crease_angle: Option<f64>,
        weight: &str,
        hard_edges: Option<String>,
        columns: Option<&Bound<'_, PyAny>>,
        index_type: &str,
        dtype: &str,
    ) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let this = slf.try_borrow().map_err(busy)?;
        let mesh = &this.mesh;
        let mut options = TriangleBufferOptions::default();
        if normals {
            let hard = crate::algo::flag_column(mesh, hard_edges.as_deref())
                .map_err(|e| crate::errors::mesh_err(py, &slf.clone().unbind(), e))?;
            options.normals = Some(normal_options(weight, crease_angle, hard)?);
        } else {
            options.normals = None;
        }
        if let Some(cols) = columns {
            for c in cols.try_iter()? {
                options.columns.push(choice_of(mesh, &c?)?);
            }
        }
        let force16 = index_width(index_type, &mut options)?;
        let out = PyDict::new(py);
        let (cols, indices, tf, vs) = match dtype {
            "float32" => {
                let b = mesh
                    .to_triangle_buffers(&options)
                    .map_err(|e| buffer_err(py, e))?;
                put_vertices(&out, b, normals)?
            }
            "float64" => {
                let b = mesh
                    .to_triangle_buffers_f64(&options)
                    .map_err(|e| buffer_err(py, e))?;
                put_vertices(&out, b, normals)?
            }
            other => {
                return Err(PyValueError::new_err(format!(
                    "dtype is \"float32\" or \"float64\", not {other:?}"
                )))
            }
        };
        let indices = match indices {
            Indices::U16(i) => rows(py, &i, 3)?,
            Indices::U32(i) if force16 => {
                return Err(PyValueError::new_err(format!(
                    "{} buffer vertices do not fit uint16 indices",
                    i.iter().max().map_or(0, |m| m + 1)
                )))
            }
            Indices::U32(i) => rows(py, &i, 3)?,
        };
        out.set_item("indices", indices)?;
        out.set_item("columns", cols)?;
        let tf: Vec<i64> = tf.iter().map(|f| f.index() as i64).collect();
        let vs: Vec<i64> = vs.iter().map(|v| v.index() as i64).collect();
        out.set_item("triangle_faces", PyArray1::from_vec(py, tf))?;
        out.set_item("vertex_sources", PyArray1::from_vec(py, vs))?;
        Ok(out.unbind())
    }

    /// Build a mesh from triangle buffers (as `to_triangle_buffers` makes
    /// them, or an engine's): `positions` (v, 3), `indices` (t, 3) or
    /// (3t,); buffer vertices weld by exact position, or within `weld` (a
    /// distance) when given. `normals` (v, 3) become the half-edge column
    /// `"normal"`. `columns`: a dict from name to an (v,) or (v, c) array
    /// (a vertex column) or to `(array, "vertex" | "corner")`; a corner
    /// column becomes a half-edge column (a UV seam comes back as corner
    /// values that differ across an edge), a vertex column stays one where
    /// every copy of a welded vertex agrees. Raises `BuildError` (naming
    /// the triangle) when the welded triangles cannot form a half-edge
    /// mesh, `ValueError` for bad lengths or indices.
    #[staticmethod]
    #[pyo3(signature = (positions, indices, *, normals = None, columns = None, weld = None))]
    fn from_triangle_buffers(
        py: Python<'_>,
        positions: &Bound<'_, PyAny>,
        indices: &Bound<'_, PyAny>,
        normals: Option<&Bound<'_, PyAny>>,
        columns: Option<&Bound<'_, PyDict>>,
        weld: Option<f64>,
    ) -> PyResult<PyMesh> {
        let (p, n, k) = flat_rows(positions, "positions")?;
        if k != 3 && n > 0 {
            return Err(PyValueError::new_err(format!(
                "positions must have shape (n, 3), not ({n}, {k})"
            )));
        }
        let np = py.import("numpy")?;
        let idx = np.call_method1("ascontiguousarray", (indices, numpy::dtype::<i64>(py)))?;
        let idx = idx.call_method1("reshape", (-1i64,))?;
        let idx: Vec<i64> = idx.call_method0("tolist")?.extract()?;
        let idx: Vec<u32> = idx
            .iter()
            .enumerate()
            .map(|(at, &i)| {
                u32::try_from(i).map_err(|_| {
                    PyValueError::new_err(format!("index {i} at {at} is out of range"))
                })
            })
            .collect::<PyResult<_>>()?;
        let mut b = TriangleBuffers::<f64> {
            positions: p.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
            normals: Vec::new(),
            columns: Vec::new(),
            indices: Indices::U32(idx),
            triangle_faces: Vec::new(),
            vertex_sources: Vec::new(),
        };
        if let Some(nr) = normals.filter(|x| !x.is_none()) {
            let (d, _, k) = flat_rows(nr, "normals")?;
            if k != 3 {
                return Err(PyValueError::new_err("normals must have shape (n, 3)"));
            }
            b.normals = d.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        }
        if let Some(cols) = columns {
            for (name, value) in cols.iter() {
                let name: String = name.extract()?;
                let (arr, source) = match value.cast::<PyTuple>() {
                    Ok(t) if t.len() == 2 => {
                        let s: String = t.get_item(1)?.extract()?;
                        (t.get_item(0)?, source_of(&s)?)
                    }
                    _ => (value.clone(), ColumnSource::Vertex),
                };
                let (data, _, components) = flat_rows(&arr, &format!("column {name:?}"))?;
                b.columns.push(BufferColumn {
                    name,
                    source,
                    components,
                    data,
                });
            }
        }
        let options = FromBuffersOptions::default().weld(match weld {
            Some(t) => Weld::Tolerance(t),
            None => Weld::Exact,
        });
        let mesh = Mesh::from_triangle_buffers(&b, &options).map_err(|e| buffer_err(py, e))?;
        Ok(PyMesh::wrap(mesh))
    }
}
