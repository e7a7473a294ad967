//! The modelling tools that cut and copy a selection: `split_edges`,
//! `duplicate_faces`, `separate`, and the delimiters' edges.

use meshloom::model::Delimit;
use meshloom::{EdgeKey, FaceKey};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::algo::flag_column;
use crate::elements::{self, PyEdge, PyFace};
use crate::mesh::{edit, ekey, fkey, query, PyMesh};

fn face_keys(slf: &Bound<'_, PyMesh>, faces: &[Bound<'_, PyFace>]) -> PyResult<Vec<FaceKey>> {
    faces.iter().map(|f| fkey(slf, f)).collect()
}

#[pymethods]
impl PyMesh {
    /// Disconnect the faces along `edges` (rip): each edge inside the
    /// surface becomes two on a hole, and vertices where the cut separates
    /// their faces split; edges already on a hole are left alone. Corner
    /// values stay (a UV seam becomes the rim of two islands); one undo
    /// step. Returns a dict: "holes", "vertices" (the copies), "edges"
    /// (the copies).
    fn split_edges<'py>(
        slf: &Bound<'py, Self>,
        edges: Vec<Bound<'py, PyEdge>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let edges: Vec<EdgeKey> = edges
            .iter()
            .map(|e| ekey(slf, e))
            .collect::<PyResult<_>>()?;
        let made = edit(slf, |m| m.split_edges(&edges))?;
        let (py, mesh) = (slf.py(), slf.clone().unbind());
        let out = PyDict::new(py);
        out.set_item("holes", elements::faces(py, &mesh, made.holes)?)?;
        out.set_item("vertices", elements::vertices(py, &mesh, made.vertices)?)?;
        out.set_item("edges", elements::edges(py, &mesh, made.edges)?)?;
        Ok(out)
    }

    /// The edges a merge would keep: the boundary, the borders of the face
    /// column `material`, the seams of the corner column `seams`, the edges
    /// where the boolean edge column `sharp` is true. With `split_edges` it
    /// rips a mesh along its UV seams.
    #[pyo3(signature = (*, material = None, seams = None, sharp = None))]
    fn delimited_edges(
        slf: &Bound<'_, Self>,
        material: Option<String>,
        seams: Option<String>,
        sharp: Option<String>,
    ) -> PyResult<Vec<Py<PyEdge>>> {
        let keys = query(slf, |m| {
            let sharp = flag_column::<EdgeKey>(m, sharp.as_deref())?;
            Delimit {
                material,
                seams,
                sharp,
            }
            .edges(m)
        })?;
        elements::edges(slf.py(), &slf.clone().unbind(), keys)
    }

    /// Copy `faces` in place, joined to each other where they share edges
    /// and to nothing else; every copy has its source's values; one undo
    /// step. Returns a dict: "faces" (the copies, in the order of `faces`
    /// without repeats), "vertices", "edges" (the copies) with
    /// "vertex_sources", "edge_sources" (their sources, in the same
    /// order), "holes".
    fn duplicate_faces<'py>(
        slf: &Bound<'py, Self>,
        faces: Vec<Bound<'py, PyFace>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let faces = face_keys(slf, &faces)?;
        let made = edit(slf, |m| m.duplicate_faces(&faces))?;
        let (py, mesh) = (slf.py(), slf.clone().unbind());
        let out = PyDict::new(py);
        let (_, fs): (Vec<_>, Vec<_>) = made.faces.into_iter().unzip();
        let (vsrc, vs): (Vec<_>, Vec<_>) = made.vertices.into_iter().unzip();
        let (esrc, es): (Vec<_>, Vec<_>) = made.edges.into_iter().unzip();
        out.set_item("faces", elements::faces(py, &mesh, fs)?)?;
        out.set_item("vertices", elements::vertices(py, &mesh, vs)?)?;
        out.set_item("vertex_sources", elements::vertices(py, &mesh, vsrc)?)?;
        out.set_item("edges", elements::edges(py, &mesh, es)?)?;
        out.set_item("edge_sources", elements::edges(py, &mesh, esrc)?)?;
        out.set_item("holes", elements::faces(py, &mesh, made.holes)?)?;
        Ok(out)
    }

    /// Move `faces` into a new mesh with every column (its elements keep
    /// this mesh's indices, so it maps back; `compact()` it for dense
    /// ones); here they become holes. One undo step here.
    fn separate(slf: &Bound<'_, Self>, faces: Vec<Bound<'_, PyFace>>) -> PyResult<Py<PyMesh>> {
        let faces = face_keys(slf, &faces)?;
        let part = edit(slf, |m| m.separate(&faces))?;
        let py = slf.py();
        let wrapped = slf.borrow().wrap_like(py, part);
        Py::new(py, wrapped)
    }
}
