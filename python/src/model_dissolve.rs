//! The dissolve tools: `dissolve_vertices`, `dissolve_edges`,
//! `dissolve_faces` and `dissolve_limited`
//! ([`meshloom::model::DissolveLimitedOptions`]).

use meshloom::model::{Delimit, DissolveEdgesOptions, DissolveLimitedOptions, Dissolved};
use meshloom::{EdgeKey, FaceKey, VertexKey};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::algo::flag_column;
use crate::elements::{self, PyEdge, PyFace, PyVertex};
use crate::mesh::{edit, ekey, fkey, vkey, PyMesh};

/// A dissolve's account as a dict: "faces" (the merged faces), "edges"
/// (the joined edges), "removed_vertices", "removed_edges",
/// "removed_faces" (counts).
fn report<'py>(slf: &Bound<'py, PyMesh>, d: Dissolved) -> PyResult<Bound<'py, PyDict>> {
    let (py, mesh) = (slf.py(), slf.clone().unbind());
    let out = PyDict::new(py);
    out.set_item("faces", elements::faces(py, &mesh, d.faces)?)?;
    out.set_item("edges", elements::edges(py, &mesh, d.edges)?)?;
    out.set_item("removed_vertices", d.removed_vertices)?;
    out.set_item("removed_edges", d.removed_edges)?;
    out.set_item("removed_faces", d.removed_faces)?;
    Ok(out)
}

#[pymethods]
impl PyMesh {
    /// Remove `vertices`, merging the faces round each into one (a vertex
    /// between two edges joins them); one undo step. Returns the dissolve's
    /// dict ("faces", "edges", "removed_vertices", "removed_edges",
    /// "removed_faces").
    fn dissolve_vertices<'py>(
        slf: &Bound<'py, Self>,
        vertices: Vec<Bound<'py, PyVertex>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let vs: Vec<VertexKey> = vertices
            .iter()
            .map(|v| vkey(slf, v))
            .collect::<PyResult<_>>()?;
        let d = edit(slf, |m| m.dissolve_vertices(&vs))?;
        report(slf, d)
    }

    /// Remove `edges`, merging the faces on their two sides (edges on a
    /// hole are skipped); `vertices`: also take out vertices left between
    /// two edges (as Blender's menu does). One undo step; returns the
    /// dissolve's dict.
    #[pyo3(signature = (edges, *, vertices = true))]
    fn dissolve_edges<'py>(
        slf: &Bound<'py, Self>,
        edges: Vec<Bound<'py, PyEdge>>,
        vertices: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let es: Vec<EdgeKey> = edges
            .iter()
            .map(|e| ekey(slf, e))
            .collect::<PyResult<_>>()?;
        let options = DissolveEdgesOptions { vertices };
        let d = edit(slf, |m| m.dissolve_edges(&es, &options))?;
        report(slf, d)
    }

    /// Merge each region of `faces` (faces sharing edges; each a disk)
    /// into one face, face values merged by area. One undo step; returns
    /// the dissolve's dict.
    fn dissolve_faces<'py>(
        slf: &Bound<'py, Self>,
        faces: Vec<Bound<'py, PyFace>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let fs: Vec<FaceKey> = faces
            .iter()
            .map(|f| fkey(slf, f))
            .collect::<PyResult<_>>()?;
        let d = edit(slf, |m| m.dissolve_faces(&fs))?;
        report(slf, d)
    }

    /// Limited dissolve (Blender's): merge faces whose normals differ by
    /// less than `angle` (radians), smallest angle first, then take out
    /// vertices on chains that bend by less; edges are kept between faces
    /// whose `material` face column differs (and any incompatible face
    /// column), across seams of the `seams` corner column, where the
    /// boolean `sharp` edge column is true, and on the boundary;
    /// `boundaries`: take out every vertex left between two edges. One undo
    /// step; returns the dissolve's dict.
    #[pyo3(signature = (angle = 5f64.to_radians(), *, material = None, seams = None, sharp = None, boundaries = false))]
    fn dissolve_limited<'py>(
        slf: &Bound<'py, Self>,
        angle: f64,
        material: Option<String>,
        seams: Option<String>,
        sharp: Option<String>,
        boundaries: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let d = edit(slf, |m| {
            let options = DissolveLimitedOptions {
                angle,
                delimit: Delimit {
                    material,
                    seams,
                    sharp: flag_column::<EdgeKey>(m, sharp.as_deref())?,
                },
                boundaries,
                ..DissolveLimitedOptions::default()
            };
            m.dissolve_limited(&options)
        })?;
        report(slf, d)
    }
}
