//! Keys as small hashable Python objects: `Vertex`, `Halfedge`, `Edge`,
//! `Face`. Each holds its mesh and a generational key; every property checks
//! the key first and raises `StaleKeyError` once its element is gone.
//! Navigation is named as in the Rust API (`v.outgoing`, `h.twin`, ...) and
//! returns key objects (circulators as lists, in the Rust order).

use meshloom::{AnyKey, EdgeKey, FaceKey, HalfedgeKey, VertexKey};
use pyo3::prelude::*;
use pyo3::types::PyAny;

use crate::errors::{busy, mesh_err};
use crate::mesh::PyMesh;

macro_rules! key_class {
    ($(#[$doc:meta])* $name:ident, $pyname:literal, $key:ty, $tag:literal) => {
        $(#[$doc])*
        #[pyclass(frozen, module = "meshloom", name = $pyname)]
        pub struct $name {
            /// The mesh the key belongs to.
            pub mesh: Py<PyMesh>,
            /// The Rust key.
            pub key: $key,
        }

        impl $name {
            /// A key object of `mesh`.
            pub fn make(py: Python<'_>, mesh: &Py<PyMesh>, key: $key) -> PyResult<Py<$name>> {
                Py::new(py, $name { mesh: mesh.clone_ref(py), key })
            }
        }

        #[pymethods]
        impl $name {
            /// The key holds its mesh: the garbage collector must see it (a
            /// key stored in a Python-rule column of its own mesh is a cycle).
            fn __traverse__(
                &self,
                visit: pyo3::gc::PyVisit<'_>,
            ) -> Result<(), pyo3::PyTraverseError> {
                visit.call(&self.mesh)
            }

            /// The slot index (dense after `Mesh.compact()`, reused after removal).
            #[getter]
            fn index(&self) -> usize {
                self.key.index()
            }

            /// The slot generation the key was issued for.
            #[getter]
            fn generation(&self) -> u32 {
                self.key.generation()
            }

            /// The mesh this key belongs to.
            #[getter]
            fn mesh(&self, py: Python<'_>) -> Py<PyMesh> {
                self.mesh.clone_ref(py)
            }

            /// Whether the element still exists (the key is not stale).
            #[getter]
            fn is_alive(&self, py: Python<'_>) -> bool {
                self.mesh.bind(py).try_borrow().is_ok_and(|m| m.alive(AnyKey::from(self.key)))
            }

            fn __hash__(&self) -> u64 {
                ((self.key.index() as u64) << 34) ^ (u64::from(self.key.generation()) << 2) ^ $tag
            }

            fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
                match other.cast::<$name>() {
                    Ok(o) => {
                        let o = o.get();
                        o.key == self.key && o.mesh.is(&self.mesh)
                    }
                    Err(_) => false,
                }
            }

            fn __lt__(&self, other: &Self) -> bool {
                self.key < other.key
            }

            fn __repr__(&self) -> String {
                format!(concat!($pyname, "({:?})"), self.key)
            }
        }
    };
}

key_class!(
    /// A vertex key.
    PyVertex, "Vertex", VertexKey, 0
);
key_class!(
    /// A half-edge key: one direction of an edge.
    PyHalfedge, "Halfedge", HalfedgeKey, 1
);
key_class!(
    /// An edge key: the unordered pair of twin half-edges.
    PyEdge, "Edge", EdgeKey, 2
);
key_class!(
    /// A face key; hole faces are faces too.
    PyFace, "Face", FaceKey, 3
);

/// A key object of `mesh` for any kind of key.
pub fn key_object(py: Python<'_>, mesh: &Py<PyMesh>, key: AnyKey) -> Py<PyAny> {
    let made = match key {
        AnyKey::Vertex(k) => PyVertex::make(py, mesh, k).map(Py::into_any),
        AnyKey::Halfedge(k) => PyHalfedge::make(py, mesh, k).map(Py::into_any),
        AnyKey::Edge(k) => PyEdge::make(py, mesh, k).map(Py::into_any),
        AnyKey::Face(k) => PyFace::make(py, mesh, k).map(Py::into_any),
    };
    made.unwrap_or_else(|_| py.None())
}

/// Key objects of `mesh` for a sequence of keys.
pub fn vertices(
    py: Python<'_>,
    mesh: &Py<PyMesh>,
    keys: impl IntoIterator<Item = VertexKey>,
) -> PyResult<Vec<Py<PyVertex>>> {
    keys.into_iter()
        .map(|k| PyVertex::make(py, mesh, k))
        .collect()
}
/// Half-edge key objects.
pub fn halfedges(
    py: Python<'_>,
    mesh: &Py<PyMesh>,
    keys: impl IntoIterator<Item = HalfedgeKey>,
) -> PyResult<Vec<Py<PyHalfedge>>> {
    keys.into_iter()
        .map(|k| PyHalfedge::make(py, mesh, k))
        .collect()
}
/// Edge key objects.
pub fn edges(
    py: Python<'_>,
    mesh: &Py<PyMesh>,
    keys: impl IntoIterator<Item = EdgeKey>,
) -> PyResult<Vec<Py<PyEdge>>> {
    keys.into_iter()
        .map(|k| PyEdge::make(py, mesh, k))
        .collect()
}
/// Face key objects.
pub fn faces(
    py: Python<'_>,
    mesh: &Py<PyMesh>,
    keys: impl IntoIterator<Item = FaceKey>,
) -> PyResult<Vec<Py<PyFace>>> {
    keys.into_iter()
        .map(|k| PyFace::make(py, mesh, k))
        .collect()
}

/// Borrow the mesh of a key object and run `f` on the checked view.
macro_rules! view {
    ($self:ident, $py:ident, $method:ident, |$m:ident, $v:ident| $body:expr) => {{
        let cell = $self.mesh.bind($py).try_borrow().map_err(busy)?;
        let $m = &$self.mesh;
        let $v = cell
            .mesh
            .$method($self.key)
            .map_err(|e| mesh_err($py, $m, e))?;
        $body
    }};
}

#[pymethods]
impl PyVertex {
    /// The position `(x, y, z)`, or None for a topology-only mesh.
    #[getter]
    fn position(&self, py: Python<'_>) -> PyResult<Option<[f64; 3]>> {
        view!(self, py, vertex, |_m, v| Ok(v.position()))
    }

    /// Set the position (a non-finite one raises `MeshloomError`).
    #[setter]
    fn set_position(&self, py: Python<'_>, p: [f64; 3]) -> PyResult<()> {
        let mut cell = self.mesh.bind(py).try_borrow_mut().map_err(busy)?;
        cell.mesh
            .set_position(self.key, p)
            .map_err(|e| mesh_err(py, &self.mesh, e))
    }

    /// One outgoing half-edge (the first of `outgoing`).
    #[getter]
    fn halfedge(&self, py: Python<'_>) -> PyResult<Py<PyHalfedge>> {
        view!(self, py, vertex, |m, v| PyHalfedge::make(
            py,
            m,
            v.halfedge().key()
        ))
    }

    /// The outgoing half-edges, counter-clockwise, holes' sides included.
    #[getter]
    fn outgoing(&self, py: Python<'_>) -> PyResult<Vec<Py<PyHalfedge>>> {
        view!(self, py, vertex, |m, v| halfedges(py, m, v.outgoing()))
    }

    /// The incoming half-edges, counter-clockwise (the twins of `outgoing`).
    #[getter]
    fn incoming(&self, py: Python<'_>) -> PyResult<Vec<Py<PyHalfedge>>> {
        view!(self, py, vertex, |m, v| halfedges(py, m, v.incoming()))
    }

    /// The neighbouring vertices, counter-clockwise.
    #[getter]
    fn neighbors(&self, py: Python<'_>) -> PyResult<Vec<Py<PyVertex>>> {
        view!(self, py, vertex, |m, v| vertices(py, m, v.neighbors()))
    }

    /// The faces around the vertex, counter-clockwise, holes skipped.
    #[getter]
    fn faces(&self, py: Python<'_>) -> PyResult<Vec<Py<PyFace>>> {
        view!(self, py, vertex, |m, v| faces(py, m, v.faces()))
    }

    /// The edges around the vertex, counter-clockwise.
    #[getter]
    fn edges(&self, py: Python<'_>) -> PyResult<Vec<Py<PyEdge>>> {
        view!(self, py, vertex, |m, v| edges(py, m, v.edges()))
    }

    /// The number of edges at the vertex.
    #[getter]
    fn degree(&self, py: Python<'_>) -> PyResult<usize> {
        view!(self, py, vertex, |_m, v| Ok(v.degree()))
    }

    /// Whether the vertex lies on a boundary (touches a hole).
    #[getter]
    fn is_boundary(&self, py: Python<'_>) -> PyResult<bool> {
        view!(self, py, vertex, |_m, v| Ok(v.is_boundary()))
    }
}

#[pymethods]
impl PyHalfedge {
    /// The opposite half-edge of the same edge.
    #[getter]
    fn twin(&self, py: Python<'_>) -> PyResult<Py<PyHalfedge>> {
        view!(self, py, halfedge, |m, h| PyHalfedge::make(
            py,
            m,
            h.twin().key()
        ))
    }
    /// The next half-edge around the face (counter-clockwise).
    #[getter]
    fn next(&self, py: Python<'_>) -> PyResult<Py<PyHalfedge>> {
        view!(self, py, halfedge, |m, h| PyHalfedge::make(
            py,
            m,
            h.next().key()
        ))
    }
    /// The previous half-edge around the face.
    #[getter]
    fn prev(&self, py: Python<'_>) -> PyResult<Py<PyHalfedge>> {
        view!(self, py, halfedge, |m, h| PyHalfedge::make(
            py,
            m,
            h.prev().key()
        ))
    }
    /// The vertex it starts at.
    #[getter]
    fn origin(&self, py: Python<'_>) -> PyResult<Py<PyVertex>> {
        view!(self, py, halfedge, |m, h| PyVertex::make(
            py,
            m,
            h.origin().key()
        ))
    }
    /// The vertex it ends at.
    #[getter]
    fn dest(&self, py: Python<'_>) -> PyResult<Py<PyVertex>> {
        view!(self, py, halfedge, |m, h| PyVertex::make(
            py,
            m,
            h.dest().key()
        ))
    }
    /// The face on its left (possibly a hole).
    #[getter]
    fn face(&self, py: Python<'_>) -> PyResult<Py<PyFace>> {
        view!(self, py, halfedge, |m, h| PyFace::make(
            py,
            m,
            h.face().key()
        ))
    }
    /// Its edge.
    #[getter]
    fn edge(&self, py: Python<'_>) -> PyResult<Py<PyEdge>> {
        view!(self, py, halfedge, |m, h| PyEdge::make(
            py,
            m,
            h.edge().key()
        ))
    }
    /// Whether its face is a hole.
    #[getter]
    fn is_boundary(&self, py: Python<'_>) -> PyResult<bool> {
        view!(self, py, halfedge, |_m, h| Ok(h.is_boundary()))
    }
    /// The next outgoing half-edge of the origin, clockwise.
    #[getter]
    fn rotate_cw(&self, py: Python<'_>) -> PyResult<Py<PyHalfedge>> {
        view!(self, py, halfedge, |m, h| PyHalfedge::make(
            py,
            m,
            h.rotate_cw().key()
        ))
    }
    /// The next outgoing half-edge of the origin, counter-clockwise.
    #[getter]
    fn rotate_ccw(&self, py: Python<'_>) -> PyResult<Py<PyHalfedge>> {
        view!(self, py, halfedge, |m, h| PyHalfedge::make(
            py,
            m,
            h.rotate_ccw().key()
        ))
    }
}

#[pymethods]
impl PyEdge {
    /// One of its half-edges: side 0 or 1.
    #[pyo3(signature = (side = 0))]
    fn halfedge(&self, py: Python<'_>, side: u32) -> PyResult<Py<PyHalfedge>> {
        if side > 1 {
            return Err(pyo3::exceptions::PyValueError::new_err("side is 0 or 1"));
        }
        view!(self, py, edge, |m, e| PyHalfedge::make(
            py,
            m,
            e.halfedge(side).key()
        ))
    }
    /// Both half-edges, side 0 first.
    #[getter]
    fn halfedges(&self, py: Python<'_>) -> PyResult<Vec<Py<PyHalfedge>>> {
        view!(self, py, edge, |m, e| halfedges(
            py,
            m,
            [e.halfedge(0).key(), e.halfedge(1).key()]
        ))
    }
    /// Its two vertices (origin of side 0 first).
    #[getter]
    fn vertices(&self, py: Python<'_>) -> PyResult<Vec<Py<PyVertex>>> {
        view!(self, py, edge, |m, e| vertices(py, m, e.vertices()))
    }
    /// The faces on either side; None where the side is a hole.
    #[getter]
    fn faces(&self, py: Python<'_>) -> PyResult<Vec<Option<Py<PyFace>>>> {
        view!(self, py, edge, |m, e| e
            .faces()
            .into_iter()
            .map(|f| f.map(|f| PyFace::make(py, m, f)).transpose())
            .collect())
    }
    /// Whether one side is a hole.
    #[getter]
    fn is_boundary(&self, py: Python<'_>) -> PyResult<bool> {
        view!(self, py, edge, |_m, e| Ok(e.is_boundary()))
    }
}

#[pymethods]
impl PyFace {
    /// One half-edge of the face (the first of `halfedges`).
    #[getter]
    fn halfedge(&self, py: Python<'_>) -> PyResult<Py<PyHalfedge>> {
        view!(self, py, face, |m, f| PyHalfedge::make(
            py,
            m,
            f.halfedge().key()
        ))
    }
    /// Whether the face is a hole (the outside of a boundary loop).
    #[getter]
    fn is_hole(&self, py: Python<'_>) -> PyResult<bool> {
        view!(self, py, face, |_m, f| Ok(f.is_hole()))
    }
    /// Its half-edges, counter-clockwise.
    #[getter]
    fn halfedges(&self, py: Python<'_>) -> PyResult<Vec<Py<PyHalfedge>>> {
        view!(self, py, face, |m, f| halfedges(py, m, f.halfedges()))
    }
    /// Its corners, counter-clockwise.
    #[getter]
    fn vertices(&self, py: Python<'_>) -> PyResult<Vec<Py<PyVertex>>> {
        view!(self, py, face, |m, f| vertices(py, m, f.vertices()))
    }
    /// Its edges, counter-clockwise.
    #[getter]
    fn edges(&self, py: Python<'_>) -> PyResult<Vec<Py<PyEdge>>> {
        view!(self, py, face, |m, f| edges(py, m, f.edges()))
    }
    /// The faces across its edges, holes skipped.
    #[getter]
    fn neighbors(&self, py: Python<'_>) -> PyResult<Vec<Py<PyFace>>> {
        view!(self, py, face, |m, f| faces(py, m, f.neighbors()))
    }
    /// The number of sides.
    #[getter]
    fn degree(&self, py: Python<'_>) -> PyResult<usize> {
        view!(self, py, face, |_m, f| Ok(f.degree()))
    }
}
