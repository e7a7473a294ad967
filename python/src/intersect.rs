//! `Mesh.self_intersections()`: the pairs of faces that intersect, as a
//! numpy array of face indices.

use meshloom::query::FaceTree;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

use crate::errors::busy;
use crate::mesh::PyMesh;
use crate::tree::query_err;

#[pymethods]
impl PyMesh {
    /// The pairs of faces that intersect, as a (k, 2) int64 array of face
    /// (slot) indices, each row `(lower, higher)`, sorted. Faces sharing a
    /// vertex or an edge count only when they meet beyond it; faces with
    /// nothing in common count when they touch. Decided with exact
    /// predicates; n-gons through their fan triangles.
    fn self_intersections<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let this = slf.try_borrow().map_err(busy)?;
        let tree = FaceTree::build(&this.mesh).map_err(|e| query_err(py, e))?;
        let pairs = tree
            .self_intersections(&this.mesh)
            .map_err(|e| query_err(py, e))?;
        let n = pairs.len();
        let flat: Vec<i64> = pairs
            .iter()
            .flat_map(|p| [p.0.index() as i64, p.1.index() as i64])
            .collect();
        Ok(PyArray1::from_vec(py, flat).reshape([n, 2])?.into_any())
    }
}
