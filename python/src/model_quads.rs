//! `Mesh.join_triangles`: pairs of triangles into quads
//! ([`meshloom::model::JoinTrianglesOptions`]).

use meshloom::model::{Delimit, JoinTrianglesOptions};
use meshloom::{EdgeKey, FaceKey};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::algo::flag_column;
use crate::elements::{self, PyFace};
use crate::mesh::{edit, fkey, PyMesh};

#[pymethods]
impl PyMesh {
    /// Join pairs of adjacent triangles into quads (Blender's Tris to
    /// Quads): two triangles join when their normals differ by at most
    /// `angle` (radians), every corner of the quad is within `shape_angle`
    /// of a right angle and the quad is convex; best pairs first, each
    /// triangle once; one undo step. Edges are kept between faces whose
    /// `material` face column differs, across seams of the `seams` corner
    /// column and where the boolean `sharp` edge column is true. `faces`:
    /// the faces to join among (default every face). A quad keeps its first
    /// triangle's key and face values (merged by their rules: a conserved
    /// column sums) and its corners' values. Returns a dict: "quads",
    /// "triangles_left".
    #[pyo3(signature = (*, angle = 40f64.to_radians(), shape_angle = 40f64.to_radians(), material = None, seams = None, sharp = None, faces = None))]
    #[allow(clippy::too_many_arguments)]
    fn join_triangles<'py>(
        slf: &Bound<'py, Self>,
        angle: f64,
        shape_angle: f64,
        material: Option<String>,
        seams: Option<String>,
        sharp: Option<String>,
        faces: Option<Vec<Bound<'py, PyFace>>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let faces: Option<Vec<FaceKey>> = faces
            .map(|fs| fs.iter().map(|f| fkey(slf, f)).collect::<PyResult<_>>())
            .transpose()?;
        let joined = edit(slf, |m| {
            let delimit = Delimit {
                material,
                seams,
                sharp: flag_column::<EdgeKey>(m, sharp.as_deref())?,
            };
            let options = JoinTrianglesOptions {
                face_angle: angle,
                shape_angle,
                delimit,
                faces,
            };
            m.join_triangles(&options)
        })?;
        let (py, mesh) = (slf.py(), slf.clone().unbind());
        let out = PyDict::new(py);
        out.set_item("quads", elements::faces(py, &mesh, joined.quads)?)?;
        out.set_item("triangles_left", joined.triangles_left)?;
        Ok(out)
    }
}
