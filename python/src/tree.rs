//! `Mesh.tree()`: a bounding-volume hierarchy over a mesh's faces for ray
//! casts, closest points, inside tests, winding numbers and radius queries,
//! answering whole numpy batches through the Rust batch calls.
//!
//! `update()` applies the mesh's tracked changes (the tree turns tracking
//! on), `pick` finds the vertex or edge under a cursor.
//!
//! Face and vertex indices in arrays are slot indices, as in
//! `to_triangle_buffers`'s `triangle_faces`; -1 marks "none". Calls that
//! answer for one point return key objects.

use meshloom::query::{
    Closest, Cone, FaceTree, Hit, Occlusion, Pick, QueryError, Ray, UpdateReport, WindingMode,
};
use meshloom::{AnyKey, Mesh};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::elements::key_object;
use crate::errors::{busy, raise};
use crate::mesh::PyMesh;

/// A query error as a `meshloom.errors.QueryError` carrying the Rust
/// message (`StaleTreeError` for a tree the mesh moved on from).
pub fn query_err(py: Python<'_>, e: QueryError) -> PyErr {
    let class = match e {
        QueryError::StaleTree { .. }
        | QueryError::TopologyChanged { .. }
        | QueryError::FaceCountChanged { .. } => "StaleTreeError",
        _ => "QueryError",
    };
    raise(py, class, e.to_string(), &[])
}

/// `ob` as n rows of 3 float64 coordinates.
fn points_of(ob: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f64; 3]>> {
    let py = ob.py();
    let np = py.import("numpy")?;
    let arr = np.call_method1("ascontiguousarray", (ob, numpy::dtype::<f64>(py)))?;
    let arr = arr.call_method1("reshape", ((-1i64, 3i64),)).map_err(|_| {
        PyValueError::new_err(format!("{what} must be an (n, 3) array or a 3-vector"))
    })?;
    let arr = arr
        .cast_into::<numpy::PyArray2<f64>>()
        .map_err(|_| PyValueError::new_err(format!("{what} must be an array of numbers")))?;
    let ro = arr.readonly();
    Ok(ro
        .as_slice()?
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect())
}

/// `(n, 3)` float64 array of rows.
fn rows<'py>(py: Python<'py>, v: Vec<[f64; 3]>) -> PyResult<Bound<'py, PyAny>> {
    let n = v.len();
    let flat: Vec<f64> = v.into_iter().flatten().collect();
    Ok(PyArray1::from_vec(py, flat).reshape([n, 3])?.into_any())
}

/// `(n, 3)` int64 array of rows.
fn int_rows<'py>(py: Python<'py>, v: Vec<[i64; 3]>) -> PyResult<Bound<'py, PyAny>> {
    let n = v.len();
    let flat: Vec<i64> = v.into_iter().flatten().collect();
    Ok(PyArray1::from_vec(py, flat).reshape([n, 3])?.into_any())
}

/// The point each answer gives, NaN where there is none.
fn hit_dict<'py>(py: Python<'py>, hits: &[Option<Hit>]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let nan = [f64::NAN; 3];
    let face: Vec<i64> = hits
        .iter()
        .map(|h| h.map_or(-1, |h| h.face.index() as i64))
        .collect();
    let t: Vec<f64> = hits
        .iter()
        .map(|h| h.map_or(f64::INFINITY, |h| h.t))
        .collect();
    d.set_item("face", PyArray1::from_vec(py, face))?;
    d.set_item("t", PyArray1::from_vec(py, t))?;
    d.set_item(
        "point",
        rows(
            py,
            hits.iter().map(|h| h.map_or(nan, |h| h.point)).collect(),
        )?,
    )?;
    let w = hits.iter().map(|h| h.map_or(nan, |h| h.coords.weights));
    d.set_item("weights", rows(py, w.collect())?)?;
    let c = hits
        .iter()
        .map(|h| h.map_or([-1; 3], |h| h.coords.corners.map(|c| c as i64)));
    d.set_item("corners", int_rows(py, c.collect())?)?;
    Ok(d)
}

fn closest_dict<'py>(py: Python<'py>, found: &[Option<Closest>]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let nan = [f64::NAN; 3];
    let face: Vec<i64> = found
        .iter()
        .map(|c| c.map_or(-1, |c| c.face.index() as i64))
        .collect();
    let dist: Vec<f64> = found
        .iter()
        .map(|c| c.map_or(f64::INFINITY, |c| c.distance))
        .collect();
    d.set_item("face", PyArray1::from_vec(py, face))?;
    d.set_item(
        "point",
        rows(
            py,
            found.iter().map(|c| c.map_or(nan, |c| c.point)).collect(),
        )?,
    )?;
    d.set_item("distance", PyArray1::from_vec(py, dist))?;
    let w = found.iter().map(|c| c.map_or(nan, |c| c.coords.weights));
    d.set_item("weights", rows(py, w.collect())?)?;
    let c = found
        .iter()
        .map(|c| c.map_or([-1; 3], |c| c.coords.corners.map(|i| i as i64)));
    d.set_item("corners", int_rows(py, c.collect())?)?;
    Ok(d)
}

/// `nearest_edge`'s answer: the edge, its distance, its nearest point.
type EdgeNear = (Py<PyAny>, f64, [f64; 3]);

/// `pick`'s answer: the key, the point, its depth `t`, its offset.
type Picked = (Py<PyAny>, [f64; 3], f64, f64);

/// A bounding-volume hierarchy over a mesh's faces (polygons as fans of
/// triangles), made by `Mesh.tree()`. It answers for the mesh as it was
/// when built or last refitted: after an edit, queries raise
/// `StaleTreeError` until `update()` (any edit), `refit()` (positions moved) or a new `tree()`.
#[pyclass(module = "meshloom", name = "FaceTree")]
pub struct PyFaceTree {
    mesh: Py<PyMesh>,
    tree: FaceTree,
}

impl PyFaceTree {
    /// A tree over `mesh`'s faces.
    pub fn build(mesh: &Bound<'_, PyMesh>) -> PyResult<PyFaceTree> {
        let mut this = mesh.try_borrow_mut().map_err(busy)?;
        // Changes from here on are what `update` applies.
        this.mesh.history_mut().track_changes(true);
        this.mesh.history_mut().take_changes();
        let tree = FaceTree::build(&this.mesh).map_err(|e| query_err(mesh.py(), e))?;
        Ok(PyFaceTree {
            mesh: mesh.clone().unbind(),
            tree,
        })
    }

    /// `op` on the tree and its mesh, its error as an exception.
    fn with<T>(
        &self,
        py: Python<'_>,
        op: impl FnOnce(&FaceTree, &Mesh) -> Result<T, QueryError>,
    ) -> PyResult<T> {
        let this = self.mesh.bind(py).try_borrow().map_err(busy)?;
        op(&self.tree, &this.mesh).map_err(|e| query_err(py, e))
    }
}

#[pymethods]
impl PyFaceTree {
    /// The first hit of each ray: a dict of `face` (n,) (slot index, -1 for
    /// a miss), `t` (n,) (inf for a miss), `point` (n, 3), and `corners`
    /// (n, 3) / `weights` (n, 3): three of the face's corners (indices into
    /// its vertices) and their barycentric weights.
    fn ray_cast<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'py, PyAny>,
        directions: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let o = points_of(origins, "origins")?;
        let d = points_of(directions, "directions")?;
        if o.len() != d.len() {
            return Err(PyValueError::new_err(format!(
                "{} origins but {} directions",
                o.len(),
                d.len()
            )));
        }
        let rays: Vec<Ray> = o.into_iter().zip(d).map(|(o, d)| Ray::new(o, d)).collect();
        let hits = self.with(py, |t, m| t.ray_cast_batch(m, &rays))?;
        hit_dict(py, &hits)
    }

    /// The closest surface point to each point: a dict of `face` (n,)
    /// (slot index; -1 when nothing is within `max_distance`), `point`
    /// (n, 3), `distance` (n,), `corners` and `weights` (n, 3).
    #[pyo3(signature = (points, max_distance = None))]
    fn closest_points<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        max_distance: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let p = points_of(points, "points")?;
        let found = self.with(py, |t, m| t.closest_points(m, &p, max_distance))?;
        closest_dict(py, &found)
    }

    /// Whether each point is inside the surface (winding number > 1/2):
    /// a bool array (n,).
    fn contains<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let p = points_of(points, "points")?;
        let inside = self.with(py, |t, m| t.contains_batch(m, &p))?;
        Ok(PyArray1::from_vec(py, inside).into_any())
    }

    /// The generalized winding number of the surface at each point: a
    /// float array (n,). `mode` "fast" sums far nodes by their field's
    /// first three Taylor terms (`accuracy` their far-field factor, at
    /// least 1), "exact" every triangle.
    #[pyo3(signature = (points, mode = "fast", accuracy = 2.0))]
    fn winding_number<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        mode: &str,
        accuracy: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let mode = match mode {
            "fast" => WindingMode::Approximate { accuracy },
            "exact" => WindingMode::Exact,
            other => {
                return Err(PyValueError::new_err(format!(
                    "mode: unknown {other:?}, fast or exact"
                )))
            }
        };
        let p = points_of(points, "points")?;
        let w = self.with(py, |t, m| t.winding_numbers(m, &p, mode))?;
        Ok(PyArray1::from_vec(py, w).into_any())
    }

    /// The faces (`kind` "face"), vertices ("vertex") or edges ("edge")
    /// within `radius` of `point`, as key objects.
    #[pyo3(signature = (point, radius, kind = "face"))]
    fn within(
        &self,
        py: Python<'_>,
        point: &Bound<'_, PyAny>,
        radius: f64,
        kind: &str,
    ) -> PyResult<Vec<Py<PyAny>>> {
        let p = one_point(point)?;
        let keys: Vec<AnyKey> = match kind {
            "face" => self
                .with(py, |t, m| t.faces_within(m, p, radius))?
                .into_iter()
                .map(AnyKey::from)
                .collect(),
            "vertex" => self
                .with(py, |t, m| t.vertices_within(m, p, radius))?
                .into_iter()
                .map(AnyKey::from)
                .collect(),
            "edge" => self
                .with(py, |t, m| t.edges_within(m, p, radius))?
                .into_iter()
                .map(AnyKey::from)
                .collect(),
            other => {
                return Err(PyValueError::new_err(format!(
                    "kind: unknown {other:?}, face, vertex or edge"
                )))
            }
        };
        Ok(keys
            .into_iter()
            .map(|k| key_object(py, &self.mesh, k))
            .collect())
    }

    /// The vertex nearest to `point` and its distance, or None for a mesh
    /// without vertices.
    fn nearest_vertex(
        &self,
        py: Python<'_>,
        point: &Bound<'_, PyAny>,
    ) -> PyResult<Option<(Py<PyAny>, f64)>> {
        let p = one_point(point)?;
        let n = self.with(py, |t, m| t.nearest_vertex(m, p))?;
        Ok(n.map(|n| (key_object(py, &self.mesh, n.vertex.into()), n.distance)))
    }

    /// The edge nearest to `point`, its distance and its nearest point, or
    /// None for a mesh without faces.
    fn nearest_edge(&self, py: Python<'_>, point: &Bound<'_, PyAny>) -> PyResult<Option<EdgeNear>> {
        let p = one_point(point)?;
        let n = self.with(py, |t, m| t.nearest_edge(m, p))?;
        Ok(n.map(|n| {
            (
                key_object(py, &self.mesh, n.edge.into()),
                n.distance,
                n.point,
            )
        }))
    }

    /// The vertex (`kind` "vertex") or edge ("edge") under a cursor: the one
    /// nearest the axis of the cone around the ray `origin` + t·`direction`
    /// as the screen shows it. The cone: `angle` (radians) its half-angle,
    /// for a perspective view; `radius` its width at the origin, for an
    /// orthographic view (a cylinder); both for a cone with a rounded
    /// apex. `occlusion` "visible" passes over elements the surface hides,
    /// "xray" sees through. Returns `(key, point, t, offset)` (`offset`
    /// 0..1, the distance from the axis over the cone's width there) or
    /// None.
    #[pyo3(signature = (origin, direction, *, angle = None, radius = None, kind = "vertex", occlusion = "visible"))]
    #[allow(clippy::too_many_arguments)]
    fn pick(
        &self,
        py: Python<'_>,
        origin: &Bound<'_, PyAny>,
        direction: &Bound<'_, PyAny>,
        angle: Option<f64>,
        radius: Option<f64>,
        kind: &str,
        occlusion: &str,
    ) -> PyResult<Option<Picked>> {
        let ray = Ray::new(one_point(origin)?, one_point(direction)?);
        let cone = match (angle, radius) {
            (None, None) => {
                return Err(PyValueError::new_err(
                    "give the cone's angle (perspective) or radius (orthographic)",
                ))
            }
            (a, r) => Cone {
                ray,
                radius: r.unwrap_or(0.0),
                spread: a.map_or(0.0, f64::tan),
            },
        };
        let occlusion = match occlusion {
            "visible" => Occlusion::Visible,
            "xray" => Occlusion::XRay,
            other => {
                return Err(PyValueError::new_err(format!(
                    "occlusion: unknown {other:?}, visible or xray"
                )))
            }
        };
        fn out<K: Into<AnyKey>>(
            py: Python<'_>,
            mesh: &Py<PyMesh>,
            p: Option<Pick<K>>,
        ) -> Option<Picked> {
            p.map(|p| (key_object(py, mesh, p.key.into()), p.point, p.t, p.offset))
        }
        match kind {
            "vertex" => Ok(out(
                py,
                &self.mesh,
                self.with(py, |t, m| t.pick_vertex(m, cone, occlusion))?,
            )),
            "edge" => Ok(out(
                py,
                &self.mesh,
                self.with(py, |t, m| t.pick_edge(m, cone, occlusion))?,
            )),
            other => Err(PyValueError::new_err(format!(
                "kind: unknown {other:?}, vertex or edge"
            ))),
        }
    }

    /// Bring the tree up to date with the mesh's edits since it was built
    /// or last updated (the mesh tracks its changes from `Mesh.tree()` on),
    /// paying for what changed; a full rebuild when the edits are too many
    /// or another tree of the same mesh took the changes. Returns a dict:
    /// `removed_triangles`, `inserted_triangles`, `split_leaves`,
    /// `full_rebuild`.
    fn update<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let mesh = self.mesh.bind(py).clone();
        let mut this = mesh.try_borrow_mut().map_err(busy)?;
        this.mesh.history_mut().track_changes(true);
        let changes = this.mesh.history_mut().take_changes();
        let report = match self.tree.update(&this.mesh, &changes) {
            Ok(r) => r,
            Err(QueryError::ChangesMismatch { .. } | QueryError::StaleTree { .. }) => {
                self.tree = FaceTree::build(&this.mesh).map_err(|e| query_err(py, e))?;
                UpdateReport {
                    inserted_triangles: self.tree.triangle_count(),
                    full_rebuild: true,
                    ..UpdateReport::default()
                }
            }
            Err(e) => return Err(query_err(py, e)),
        };
        let d = PyDict::new(py);
        d.set_item("removed_triangles", report.removed_triangles)?;
        d.set_item("inserted_triangles", report.inserted_triangles)?;
        d.set_item("split_leaves", report.split_leaves)?;
        d.set_item("full_rebuild", report.full_rebuild)?;
        Ok(d)
    }

    /// Recompute the boxes after the mesh's positions moved (the faces
    /// unchanged). Raises `StaleTreeError` when the faces changed.
    fn refit(&mut self, py: Python<'_>) -> PyResult<()> {
        let this = self.mesh.bind(py).try_borrow().map_err(busy)?;
        self.tree.refit(&this.mesh).map_err(|e| query_err(py, e))
    }

    /// Whether the tree answers for the mesh as it is now.
    fn is_current(&self, py: Python<'_>) -> PyResult<bool> {
        let this = self.mesh.bind(py).try_borrow().map_err(busy)?;
        Ok(self.tree.is_current(&this.mesh))
    }

    /// The number of fan triangles.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.tree.triangle_count()
    }

    /// The bytes the tree holds on the heap.
    #[getter]
    fn heap_bytes(&self) -> usize {
        self.tree.heap_bytes()
    }

    fn __repr__(&self) -> String {
        format!("FaceTree({} triangles)", self.tree.triangle_count())
    }
}

/// One 3-vector.
fn one_point(ob: &Bound<'_, PyAny>) -> PyResult<[f64; 3]> {
    let p = points_of(ob, "point")?;
    match p.as_slice() {
        [p] => Ok(*p),
        _ => Err(PyValueError::new_err("point must be a 3-vector")),
    }
}
