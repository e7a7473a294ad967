//! Bridge edge loops and grid fill: `Mesh.bridge_loops`, `Mesh.grid_fill`.

use meshloom::{EdgeKey, FaceKey};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::elements::{self, PyEdge, PyFace};
use crate::mesh::{edit, PyMesh};

/// The key of an edge of this mesh.
fn edge_key(slf: &Bound<'_, PyMesh>, e: &Bound<'_, PyEdge>) -> PyResult<EdgeKey> {
    let e = e.get();
    if !e.mesh.is(slf) {
        return Err(PyValueError::new_err(format!(
            "{:?} belongs to another mesh",
            e.key
        )));
    }
    Ok(e.key)
}

/// The key of a face (or hole) of this mesh.
fn face_key(slf: &Bound<'_, PyMesh>, f: &Bound<'_, PyFace>) -> PyResult<FaceKey> {
    let f = f.get();
    if !f.mesh.is(slf) {
        return Err(PyValueError::new_err(format!(
            "{:?} belongs to another mesh",
            f.key
        )));
    }
    Ok(f.key)
}

#[pymethods]
impl PyMesh {
    /// Join two loops (or chains) of boundary edges by a band of quads,
    /// with `cuts` loops of new vertices inside and closed loops' pairing
    /// offset by `twist`; one undo step. Returns a dict: "faces" (column
    /// by column, `cuts + 1` each), "vertices", "edges", "holes" (beside
    /// the band, for open chains), "closed".
    #[pyo3(signature = (edges_a, edges_b, *, cuts = 0, twist = 0))]
    fn bridge_loops<'py>(
        slf: &Bound<'py, Self>,
        edges_a: Vec<Bound<'py, PyEdge>>,
        edges_b: Vec<Bound<'py, PyEdge>>,
        cuts: usize,
        twist: isize,
    ) -> PyResult<Bound<'py, PyDict>> {
        let a = edges_a
            .iter()
            .map(|e| edge_key(slf, e))
            .collect::<PyResult<Vec<_>>>()?;
        let b = edges_b
            .iter()
            .map(|e| edge_key(slf, e))
            .collect::<PyResult<Vec<_>>>()?;
        let options = meshloom::model::BridgeOptions { cuts, twist };
        let made = edit(slf, |m| m.bridge_loops(&a, &b, &options))?;
        let (py, mesh) = (slf.py(), slf.clone().unbind());
        let out = PyDict::new(py);
        out.set_item("faces", elements::faces(py, &mesh, made.faces)?)?;
        out.set_item("vertices", elements::vertices(py, &mesh, made.vertices)?)?;
        out.set_item("edges", elements::edges(py, &mesh, made.edges)?)?;
        out.set_item("holes", elements::faces(py, &mesh, made.holes)?)?;
        out.set_item("closed", made.closed)?;
        Ok(out)
    }

    /// Fill `hole` (an even number of edges, at least 4) with a grid of
    /// quads, `span` edges on its first side (chosen with the corners when
    /// None); one undo step. Returns a dict: "faces" (row by row),
    /// "vertices", "edges", "span", "offset".
    #[pyo3(signature = (hole, *, span = None, offset = None))]
    fn grid_fill<'py>(
        slf: &Bound<'py, Self>,
        hole: &Bound<'py, PyFace>,
        span: Option<usize>,
        offset: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let h = face_key(slf, hole)?;
        let options = meshloom::model::GridFillOptions { span, offset };
        let made = edit(slf, |m| m.grid_fill(h, &options))?;
        let (py, mesh) = (slf.py(), slf.clone().unbind());
        let out = PyDict::new(py);
        out.set_item("faces", elements::faces(py, &mesh, made.faces)?)?;
        out.set_item("vertices", elements::vertices(py, &mesh, made.vertices)?)?;
        out.set_item("edges", elements::edges(py, &mesh, made.edges)?)?;
        out.set_item("span", made.span)?;
        out.set_item("offset", made.offset)?;
        Ok(out)
    }
}
