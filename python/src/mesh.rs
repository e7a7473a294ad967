//! `meshloom.Mesh`: construction from numpy arrays or index lists, export
//! to arrays and triangle buffers, navigation, attributes, operators and
//! their check twins, validation and pickling.

use std::collections::HashMap;

use meshloom::attr::Rule;
use meshloom::buffers::{ColumnChoice, TriangleBufferOptions};
use meshloom::keys::ElementKind;
use meshloom::{AnyKey, EdgeKey, FaceKey, HalfedgeKey, Mesh, Polygons, VertexKey};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyTuple};

use crate::attrs::{
    add, column_type, get_all, get_one, parse_kind, remove, set_all, set_one, Dtype, FromAny,
    PyAttr, RuleName,
};
use crate::dispatch;
use crate::elements::{self, key_object, PyEdge, PyFace, PyHalfedge, PyVertex};
use crate::errors::{build_err, busy, mesh_err};

/// The element kinds, by `ElementKind as usize`.
pub const KINDS: [ElementKind; 4] = [
    ElementKind::Vertex,
    ElementKind::Halfedge,
    ElementKind::Edge,
    ElementKind::Face,
];

/// A Python-rule column's values by slot, as pickled.
type SlotValues = Vec<(u32, Py<PyAny>)>;
/// A pickled Python-rule column: kind, name, rule object, values.
type PickledColumn = (String, String, Py<PyAny>, SlotValues);

/// A polygon mesh as a half-edge graph whose attributes follow every edit.
#[pyclass(module = "meshloom", name = "Mesh", weakref)]
pub struct PyMesh {
    /// The Rust mesh.
    pub mesh: Mesh,
    /// The rule object of each Python-rule column, by (kind, name).
    pub py_rules: HashMap<(usize, String), Py<PyAny>>,
}

impl PyMesh {
    /// A Python mesh of a Rust one.
    pub fn wrap(mesh: Mesh) -> PyMesh {
        PyMesh {
            mesh,
            py_rules: HashMap::new(),
        }
    }

    /// Whether a key (of any kind) names a live element.
    pub fn alive(&self, key: AnyKey) -> bool {
        match key {
            AnyKey::Vertex(k) => self.mesh.contains_vertex(k),
            AnyKey::Halfedge(k) => self.mesh.contains_halfedge(k),
            AnyKey::Edge(k) => self.mesh.contains_edge(k),
            AnyKey::Face(k) => self.mesh.contains_face(k),
        }
    }

    /// Whether the mesh has a Python-rule column (whose rules may raise).
    pub fn has_python_rules(&self) -> bool {
        !self.py_rules.is_empty()
    }

    /// A mesh made from this one (a copy, an LOD level): the Python-rule
    /// columns it holds keep their rule objects.
    pub fn wrap_like(&self, py: Python<'_>, mesh: Mesh) -> PyMesh {
        let py_rules = self
            .py_rules
            .iter()
            .filter(|((kind, name), _)| {
                mesh.attr_info(KINDS[*kind]).iter().any(|i| &i.name == name)
            })
            .map(|(k, v)| (k.clone(), v.clone_ref(py)))
            .collect();
        PyMesh { mesh, py_rules }
    }
}

/// Run an edit all-or-nothing: the Rust operators refuse before changing
/// anything, and a Python rule that raises fails the edit with
/// `Error::Rule`, which leaves the mesh as it was (meshloom runs every edit
/// of a mesh with a fallible column as a transaction: the cost is the size
/// of the edit, not of the mesh); `mesh_err` raises the rule's exception.
/// On such a mesh the whole call is one transaction too, so that an edit of
/// several steps is undone whole.
pub(crate) fn edit<T>(
    slf: &Bound<'_, PyMesh>,
    op: impl FnOnce(&mut Mesh) -> meshloom::Result<T>,
) -> PyResult<T> {
    let py = slf.py();
    let mut this = slf.try_borrow_mut().map_err(busy)?;
    let result = if this.has_python_rules() {
        this.mesh.transaction(op)
    } else {
        op(&mut this.mesh)
    };
    drop(this);
    result.map_err(|e| mesh_err(py, &slf.clone().unbind(), e))
}

/// A read-only query that may fail with a meshloom error.
fn query<T>(slf: &Bound<'_, PyMesh>, op: impl FnOnce(&Mesh) -> meshloom::Result<T>) -> PyResult<T> {
    let this = slf.try_borrow().map_err(busy)?;
    op(&this.mesh).map_err(|e| mesh_err(slf.py(), &slf.clone().unbind(), e))
}

macro_rules! own_key {
    ($fn:ident, $class:ty, $key:ty) => {
        pub(crate) fn $fn(slf: &Bound<'_, PyMesh>, k: &Bound<'_, $class>) -> PyResult<$key> {
            let k = k.get();
            if !k.mesh.is(slf) {
                return Err(PyValueError::new_err(format!(
                    "{:?} belongs to another mesh",
                    k.key
                )));
            }
            Ok(k.key)
        }
    };
}
own_key!(vkey, PyVertex, VertexKey);
own_key!(hkey, PyHalfedge, HalfedgeKey);
own_key!(ekey, PyEdge, EdgeKey);
own_key!(fkey, PyFace, FaceKey);

/// Any key object of this mesh as an `AnyKey`.
fn any_key(slf: &Bound<'_, PyMesh>, ob: &Bound<'_, PyAny>) -> PyResult<AnyKey> {
    if let Ok(k) = ob.cast::<PyVertex>() {
        return vkey(slf, k).map(AnyKey::from);
    }
    if let Ok(k) = ob.cast::<PyHalfedge>() {
        return hkey(slf, k).map(AnyKey::from);
    }
    if let Ok(k) = ob.cast::<PyEdge>() {
        return ekey(slf, k).map(AnyKey::from);
    }
    if let Ok(k) = ob.cast::<PyFace>() {
        return fkey(slf, k).map(AnyKey::from);
    }
    Err(PyTypeError::new_err(
        "expected a Vertex, Halfedge, Edge or Face key",
    ))
}

/// The keys of `faces`, or every face of the mesh.
fn face_list(
    slf: &Bound<'_, PyMesh>,
    faces: Option<Vec<Bound<'_, PyFace>>>,
) -> PyResult<Vec<FaceKey>> {
    match faces {
        Some(fs) => fs.iter().map(|f| fkey(slf, f)).collect(),
        None => Ok(slf.try_borrow().map_err(busy)?.mesh.faces().collect()),
    }
}

fn kind_of(key: AnyKey) -> ElementKind {
    match key {
        AnyKey::Vertex(_) => ElementKind::Vertex,
        AnyKey::Halfedge(_) => ElementKind::Halfedge,
        AnyKey::Edge(_) => ElementKind::Edge,
        AnyKey::Face(_) => ElementKind::Face,
    }
}

fn kind_name(kind: ElementKind) -> &'static str {
    match kind {
        ElementKind::Vertex => "vertex",
        ElementKind::Halfedge => "halfedge",
        ElementKind::Edge => "edge",
        _ => "face",
    }
}

fn missing(kind: ElementKind, name: &str) -> meshloom::Error {
    meshloom::Error::AttributeMissing {
        kind,
        name: name.to_owned(),
    }
}

/// Positions from an (n, 3) float array or a sequence of triples.
fn positions_of(ob: &Bound<'_, PyAny>) -> PyResult<Vec<[f64; 3]>> {
    let py = ob.py();
    let arr = if let Ok(a) = ob.cast::<PyArray2<f64>>() {
        a.clone()
    } else {
        let np = py.import("numpy")?;
        let a = np.call_method1("asarray", (ob, numpy::dtype::<f64>(py)))?;
        if a.getattr("size")?.extract::<usize>()? == 0 {
            return Ok(Vec::new());
        }
        a.cast_into::<PyArray2<f64>>()
            .map_err(|_| PyValueError::new_err("positions must be an (n, 3) array of floats"))?
    };
    let ro: PyReadonlyArray2<f64> = arr.readonly();
    if ro.shape()[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "positions must have shape (n, 3), not {:?}",
            ro.shape()
        )));
    }
    match ro.as_slice() {
        Ok(s) => Ok(s.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()),
        Err(_) => {
            let a = ro.as_array();
            Ok(a.rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect())
        }
    }
}

/// Faces as offsets and indices, from an (m, k) integer array or a sequence
/// of index sequences (n-gons of any degree).
fn faces_of(ob: &Bound<'_, PyAny>) -> PyResult<(Vec<u32>, Vec<i64>)> {
    let py = ob.py();
    let np = py.import("numpy")?;
    let is_array = ob.is_instance(&np.getattr("ndarray")?)?;
    if is_array {
        let kind: String = ob.getattr("dtype")?.getattr("kind")?.extract()?;
        if ob.getattr("ndim")?.extract::<usize>()? == 2 && (kind == "i" || kind == "u") {
            let a = np.call_method1("ascontiguousarray", (ob, numpy::dtype::<i64>(py)))?;
            let a = a
                .cast_into::<PyArray2<i64>>()
                .map_err(|_| PyValueError::new_err("faces"))?;
            let ro = a.readonly();
            let k = ro.shape()[1];
            let m = ro.shape()[0];
            let offsets = (0..=m).map(|i| (i * k) as u32).collect();
            return Ok((offsets, ro.as_slice()?.to_vec()));
        }
    }
    let mut offsets = vec![0u32];
    let mut indices = Vec::new();
    for face in ob.try_iter()? {
        let face = face?;
        for i in face.try_iter()? {
            indices.push(i?.extract::<i64>()?);
        }
        offsets.push(indices.len() as u32);
    }
    Ok((offsets, indices))
}

fn build(
    py: Python<'_>,
    positions: Vec<[f64; 3]>,
    vertex_count: Option<usize>,
    offsets: Vec<u32>,
    indices: Vec<i64>,
) -> PyResult<Mesh> {
    let n = vertex_count.unwrap_or(positions.len());
    if indices.iter().all(|&i| i >= 0 && (i as u64) < n as u64) && positions.len() == n {
        let polygons = Polygons {
            positions,
            offsets,
            indices: indices.into_iter().map(|i| i as u32).collect(),
        };
        return py
            .detach(|| Mesh::from_buffers(&polygons))
            .map_err(|e| match e {
                meshloom::Error::Build(b) => build_err(py, b),
                other => PyValueError::new_err(other.to_string()),
            });
    }
    // Out-of-range indices or no positions: the list builder names the face.
    let faces: Vec<&[i64]> = offsets
        .windows(2)
        .map(|w| &indices[w[0] as usize..w[1] as usize])
        .collect();
    let built = if positions.is_empty() {
        Mesh::from_faces(n, &faces)
    } else {
        Mesh::from_polygons(&positions, &faces)
    };
    built.map_err(|e| match e {
        meshloom::Error::Build(b) => build_err(py, b),
        other => PyValueError::new_err(other.to_string()),
    })
}

fn u32s<'py>(py: Python<'py>, v: Vec<u32>) -> Bound<'py, PyArray1<u32>> {
    PyArray1::from_vec(py, v)
}

#[pymethods]
impl PyMesh {
    /// A bounding-volume hierarchy over the faces for ray casts, closest
    /// points, inside tests, winding numbers and radius queries. It answers
    /// for the mesh as it is now; after an edit, refit or rebuild it.
    fn tree(slf: &Bound<'_, Self>) -> PyResult<crate::tree::PyFaceTree> {
        crate::tree::PyFaceTree::build(slf)
    }

    /// An empty mesh.
    #[new]
    fn new() -> Self {
        PyMesh {
            mesh: Mesh::new(),
            py_rules: HashMap::new(),
        }
    }

    /// Build a mesh from positions and faces.
    ///
    /// `positions`: an (n, 3) float array (or any sequence of triples, as the
    /// halfedge package's vertex list). `faces`: an (m, k) integer array, or
    /// a sequence of index sequences of any degrees (the halfedge package's
    /// face-index list). Holes get hole faces. Raises `BuildError` naming the
    /// face for input a half-edge mesh cannot hold.
    #[staticmethod]
    fn from_arrays(
        py: Python<'_>,
        positions: &Bound<'_, PyAny>,
        faces: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let positions = positions_of(positions)?;
        let (offsets, indices) = faces_of(faces)?;
        Ok(PyMesh::wrap(build(py, positions, None, offsets, indices)?))
    }

    /// Build a topology-only mesh (no positions) of `vertex_count` vertices.
    #[staticmethod]
    fn from_faces(py: Python<'_>, vertex_count: usize, faces: &Bound<'_, PyAny>) -> PyResult<Self> {
        let (offsets, indices) = faces_of(faces)?;
        Ok(PyMesh::wrap(build(
            py,
            Vec::new(),
            Some(vertex_count),
            offsets,
            indices,
        )?))
    }

    /// `(positions, faces)`: an (n, 3) float64 array in the order of
    /// `vertices`, and faces in the order of `faces` as an (m, k) int64 array
    /// when every face has k corners, else a list of lists. A mesh built by
    /// `from_arrays` comes back exactly as given.
    fn to_arrays(&self, py: Python<'_>) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
        let (p, _) = self.mesh.to_polygons();
        let n = p.positions.len();
        let pos = PyArray1::from_slice(py, p.positions.as_flattened()).reshape([n, 3])?;
        let m = p.face_count();
        let k = if m > 0 { p.offsets[1] as usize } else { 3 };
        let uniform = p.offsets.windows(2).all(|w| (w[1] - w[0]) as usize == k);
        let faces = if uniform {
            let idx: Vec<i64> = p.indices.iter().map(|&i| i64::from(i)).collect();
            PyArray1::from_vec(py, idx)
                .reshape([m, k])?
                .into_any()
                .unbind()
        } else {
            let rows: Vec<Vec<u32>> = p.faces().map(|f| f.to_vec()).collect();
            PyList::new(py, rows)?.into_any().unbind()
        };
        Ok((pos.into_any().unbind(), faces))
    }

    /// `(positions, indices, offsets)`: faces as one flat uint32 index array
    /// cut by offsets (face i is `indices[offsets[i]:offsets[i+1]]`).
    fn to_buffers(&self, py: Python<'_>) -> PyResult<(Py<PyAny>, Py<PyAny>, Py<PyAny>)> {
        let (p, _) = self.mesh.to_polygons();
        let n = p.positions.len();
        let pos = PyArray1::from_slice(py, p.positions.as_flattened()).reshape([n, 3])?;
        Ok((
            pos.into_any().unbind(),
            u32s(py, p.indices).into_any().unbind(),
            u32s(py, p.offsets).into_any().unbind(),
        ))
    }

    /// Triangle buffers for a renderer or game engine: a dict with
    /// `positions` (v, 3) float32, `normals` (v, 3) float32 (when `normals`),
    /// `indices` (t, 3) uint32, `triangle_faces` (t,) int64 slot indices, and
    /// one (v, c) float32 array per column named in `corner_columns` or
    /// `vertex_columns`. Vertices are split where corner values differ.
    #[pyo3(signature = (normals = true, corner_columns = Vec::new(), vertex_columns = Vec::new()))]
    fn triangle_buffers(
        slf: &Bound<'_, Self>,
        normals: bool,
        corner_columns: Vec<String>,
        vertex_columns: Vec<String>,
    ) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let mut options = TriangleBufferOptions::default();
        if !normals {
            options.normals = None;
        }
        options.columns = corner_columns
            .iter()
            .map(|c| ColumnChoice::corner(c))
            .chain(vertex_columns.iter().map(|c| ColumnChoice::vertex(c)))
            .collect();
        let b = slf
            .try_borrow()
            .map_err(busy)?
            .mesh
            .to_triangle_buffers(&options)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let out = PyDict::new(py);
        let n = b.positions.len();
        out.set_item(
            "positions",
            PyArray1::from_slice(py, b.positions.as_flattened()).reshape([n, 3])?,
        )?;
        if normals {
            let nn = b.normals.len();
            out.set_item(
                "normals",
                PyArray1::from_slice(py, b.normals.as_flattened()).reshape([nn, 3])?,
            )?;
        }
        let t = b.triangle_count();
        out.set_item("indices", u32s(py, b.indices.to_u32()).reshape([t, 3])?)?;
        let tf: Vec<i64> = b.triangle_faces.iter().map(|f| f.index() as i64).collect();
        out.set_item("triangle_faces", PyArray1::from_vec(py, tf))?;
        for c in &b.columns {
            let rows = c.data.len() / c.components.max(1);
            out.set_item(
                &c.name,
                PyArray1::from_slice(py, &c.data).reshape([rows, c.components])?,
            )?;
        }
        Ok(out.unbind())
    }

    // ----- counts and elements -------------------------------------------------

    /// Number of vertices.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.mesh.vertex_count()
    }
    /// Number of half-edges (twice the edges).
    #[getter]
    fn halfedge_count(&self) -> usize {
        self.mesh.halfedge_count()
    }
    /// Number of edges.
    #[getter]
    fn edge_count(&self) -> usize {
        self.mesh.edge_count()
    }
    /// Number of faces, holes not counted.
    #[getter]
    fn face_count(&self) -> usize {
        self.mesh.face_count()
    }
    /// Number of hole faces (boundary loops).
    #[getter]
    fn hole_count(&self) -> usize {
        self.mesh.hole_count()
    }
    /// V - E + F, holes not counted as faces.
    #[getter]
    fn euler_characteristic(&self) -> i64 {
        self.mesh.euler_characteristic()
    }
    /// Whether the mesh has no boundary.
    #[getter]
    fn is_closed(&self) -> bool {
        self.mesh.is_closed()
    }

    /// Every vertex, in slot order.
    #[getter]
    fn vertices(slf: &Bound<'_, Self>) -> PyResult<Vec<Py<PyVertex>>> {
        let keys: Vec<_> = slf.try_borrow().map_err(busy)?.mesh.vertices().collect();
        elements::vertices(slf.py(), &slf.clone().unbind(), keys)
    }
    /// Every half-edge, in slot order.
    #[getter]
    fn halfedges(slf: &Bound<'_, Self>) -> PyResult<Vec<Py<PyHalfedge>>> {
        let keys: Vec<_> = slf.try_borrow().map_err(busy)?.mesh.halfedges().collect();
        elements::halfedges(slf.py(), &slf.clone().unbind(), keys)
    }
    /// Every edge, in slot order.
    #[getter]
    fn edges(slf: &Bound<'_, Self>) -> PyResult<Vec<Py<PyEdge>>> {
        let keys: Vec<_> = slf.try_borrow().map_err(busy)?.mesh.edges().collect();
        elements::edges(slf.py(), &slf.clone().unbind(), keys)
    }
    /// Every face that is not a hole, in slot order.
    #[getter]
    fn faces(slf: &Bound<'_, Self>) -> PyResult<Vec<Py<PyFace>>> {
        let keys: Vec<_> = slf.try_borrow().map_err(busy)?.mesh.faces().collect();
        elements::faces(slf.py(), &slf.clone().unbind(), keys)
    }
    /// Every hole face (one per boundary loop), in slot order.
    #[getter]
    fn holes(slf: &Bound<'_, Self>) -> PyResult<Vec<Py<PyFace>>> {
        let keys: Vec<_> = slf.try_borrow().map_err(busy)?.mesh.holes().collect();
        elements::faces(slf.py(), &slf.clone().unbind(), keys)
    }
    /// Faces and holes, in slot order.
    #[getter]
    fn faces_and_holes(slf: &Bound<'_, Self>) -> PyResult<Vec<Py<PyFace>>> {
        let keys: Vec<_> = slf
            .try_borrow()
            .map_err(busy)?
            .mesh
            .faces_and_holes()
            .collect();
        elements::faces(slf.py(), &slf.clone().unbind(), keys)
    }

    /// The half-edge from `a` to `b`, or None.
    fn find_halfedge(
        slf: &Bound<'_, Self>,
        a: &Bound<'_, PyVertex>,
        b: &Bound<'_, PyVertex>,
    ) -> PyResult<Option<Py<PyHalfedge>>> {
        let (a, b) = (vkey(slf, a)?, vkey(slf, b)?);
        let h = query(slf, |m| m.find_halfedge(a, b))?;
        h.map(|h| PyHalfedge::make(slf.py(), &slf.clone().unbind(), h))
            .transpose()
    }

    /// Whether the key names a live element of this mesh.
    fn __contains__(slf: &Bound<'_, Self>, key: &Bound<'_, PyAny>) -> PyResult<bool> {
        match any_key(slf, key) {
            Ok(k) => Ok(slf.try_borrow().map_err(busy)?.alive(k)),
            Err(_) => Ok(false),
        }
    }

    /// Check every structural rule; raises `ValidationError` (with `rule`
    /// and `element`) on the first broken one.
    fn validate(slf: &Bound<'_, Self>) -> PyResult<()> {
        query(slf, |m| m.validate().map_err(meshloom::Error::from))
    }

    /// Make every arena dense. Returns a dict from each live old key to its
    /// new key; every old key is stale afterwards.
    fn compact(slf: &Bound<'_, Self>) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let me = slf.clone().unbind();
        let (vs, hs, es, fs) = {
            let m = &slf.try_borrow().map_err(busy)?.mesh;
            (
                m.vertices().collect::<Vec<_>>(),
                m.halfedges().collect::<Vec<_>>(),
                m.edges().collect::<Vec<_>>(),
                m.faces_and_holes().collect::<Vec<_>>(),
            )
        };
        let maps = edit(slf, |m| Ok(m.compact()))?;
        let out = PyDict::new(py);
        for v in vs {
            if let Some(n) = maps.vertex(v) {
                out.set_item(key_object(py, &me, v.into()), key_object(py, &me, n.into()))?;
            }
        }
        for h in hs {
            if let Some(n) = maps.halfedge(h) {
                out.set_item(key_object(py, &me, h.into()), key_object(py, &me, n.into()))?;
            }
        }
        for e in es {
            if let Some(n) = maps.edge(e) {
                out.set_item(key_object(py, &me, e.into()), key_object(py, &me, n.into()))?;
            }
        }
        for f in fs {
            if let Some(n) = maps.face(f) {
                out.set_item(key_object(py, &me, f.into()), key_object(py, &me, n.into()))?;
            }
        }
        Ok(out.unbind())
    }

    /// A deep copy (keys of the copy are new objects of the same slots).
    fn copy(&self, py: Python<'_>) -> Self {
        PyMesh {
            mesh: self.mesh.clone(),
            py_rules: self
                .py_rules
                .iter()
                .map(|(k, v)| (k.clone(), v.clone_ref(py)))
                .collect(),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "Mesh(vertices={}, edges={}, faces={}, holes={})",
            self.mesh.vertex_count(),
            self.mesh.edge_count(),
            self.mesh.face_count(),
            self.mesh.hole_count()
        )
    }

    // ----- attributes ------------------------------------------------------------

    /// Add an attribute column on `kind` ("vertex", "halfedge" (corners),
    /// "edge" or "face"). `dtype`: float, int, bool, str, "vec2", "vec3", or
    /// object. `rule`: "interpolate", "conserved", "contagion",
    /// "incompatible", "keep_first", "discard" (default by dtype:
    /// interpolate for floats and vectors, incompatible for int and str,
    /// contagion for bool), or a Python rule object with `merge(values,
    /// weights)` and `split(value, share)` methods (and optionally
    /// `interpolate(values, weights)`), which makes an object column.
    #[pyo3(signature = (name, kind = "vertex", dtype = None, rule = None))]
    fn add_attr(
        slf: &Bound<'_, Self>,
        name: &str,
        kind: &str,
        dtype: Option<&Bound<'_, PyAny>>,
        rule: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let kind = parse_kind(kind)?;
        let rule_obj = rule.cloned();
        let (dtype, rule) = match rule {
            Some(r) if !r.is_instance_of::<pyo3::types::PyString>() => {
                if !(r.hasattr("merge")? && r.hasattr("split")?) {
                    return Err(PyTypeError::new_err(
                        "a rule object needs merge and split methods",
                    ));
                }
                (Dtype::Object, RuleName::PyRule)
            }
            r => {
                let dtype = match dtype {
                    Some(d) => Dtype::parse(d)?,
                    None => Dtype::Float,
                };
                let rule = match r {
                    Some(r) => RuleName::parse(&r.extract::<String>()?)?,
                    None => dtype.default_rule(),
                };
                if dtype == Dtype::Object {
                    return Err(PyTypeError::new_err(
                        "an object column needs a rule object with merge and split methods",
                    ));
                }
                (dtype, rule)
            }
        };
        let py = slf.py();
        let result = {
            let mut this = slf.try_borrow_mut().map_err(busy)?;
            dispatch!(kind, dtype, rule, add(&mut this.mesh, name))?
        };
        result.map_err(|e| mesh_err(py, &slf.clone().unbind(), e))?;
        if dtype == Dtype::Object {
            if let Some(r) = rule_obj {
                slf.try_borrow_mut()
                    .map_err(busy)?
                    .py_rules
                    .insert((kind as usize, name.to_owned()), r.unbind());
            }
        }
        Ok(())
    }

    /// Add a vertex attribute (see `add_attr`).
    #[pyo3(signature = (name, dtype = None, rule = None))]
    fn add_vertex_attr(
        slf: &Bound<'_, Self>,
        name: &str,
        dtype: Option<&Bound<'_, PyAny>>,
        rule: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        Self::add_attr(slf, name, "vertex", dtype, rule)
    }
    /// Add a half-edge (corner) attribute (see `add_attr`).
    #[pyo3(signature = (name, dtype = None, rule = None))]
    fn add_halfedge_attr(
        slf: &Bound<'_, Self>,
        name: &str,
        dtype: Option<&Bound<'_, PyAny>>,
        rule: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        Self::add_attr(slf, name, "halfedge", dtype, rule)
    }
    /// Add an edge attribute (see `add_attr`).
    #[pyo3(signature = (name, dtype = None, rule = None))]
    fn add_edge_attr(
        slf: &Bound<'_, Self>,
        name: &str,
        dtype: Option<&Bound<'_, PyAny>>,
        rule: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        Self::add_attr(slf, name, "edge", dtype, rule)
    }
    /// Add a face attribute (see `add_attr`).
    #[pyo3(signature = (name, dtype = None, rule = None))]
    fn add_face_attr(
        slf: &Bound<'_, Self>,
        name: &str,
        dtype: Option<&Bound<'_, PyAny>>,
        rule: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        Self::add_attr(slf, name, "face", dtype, rule)
    }

    /// Remove the column `name` of `kind`.
    #[pyo3(signature = (name, kind = "vertex"))]
    fn remove_attr(slf: &Bound<'_, Self>, name: &str, kind: &str) -> PyResult<()> {
        let kind = parse_kind(kind)?;
        let py = slf.py();
        let mut this = slf.try_borrow_mut().map_err(busy)?;
        let (d, r) = column_type(&this.mesh, kind, name)
            .ok_or_else(|| mesh_err(py, &slf.clone().unbind(), missing(kind, name)))?;
        let result = dispatch!(kind, d, r, remove(&mut this.mesh, name))?;
        this.py_rules.remove(&(kind as usize, name.to_owned()));
        drop(this);
        result.map_err(|e| mesh_err(py, &slf.clone().unbind(), e))
    }

    /// The columns of `kind`: a dict from name to `(dtype, rule)` names.
    #[pyo3(signature = (kind = "vertex"))]
    fn attrs(&self, py: Python<'_>, kind: &str) -> PyResult<Py<PyDict>> {
        let kind = parse_kind(kind)?;
        let out = PyDict::new(py);
        for info in self.mesh.attr_info(kind) {
            let t = column_type(&self.mesh, kind, &info.name)
                .map(|(d, r)| (d.name().to_owned(), r.name().to_owned()))
                .unwrap_or_else(|| (info.type_name.to_owned(), "?".to_owned()));
            out.set_item(info.name, t)?;
        }
        Ok(out.unbind())
    }

    /// The value of column `name` at `key` (the key's kind picks the
    /// arena), or None where it has none. Raises `StaleKeyError` for a
    /// removed element, `ColumnError` for an unknown column.
    fn attr(slf: &Bound<'_, Self>, name: &str, key: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let py = slf.py();
        let k = any_key(slf, key)?;
        let kind = kind_of(k);
        let this = slf.try_borrow().map_err(busy)?;
        let (d, r) = column_type(&this.mesh, kind, name)
            .ok_or_else(|| mesh_err(py, &slf.clone().unbind(), missing(kind, name)))?;
        let result = dispatch!(kind, d, r, get_one(py, &this.mesh, name, k))?;
        drop(this);
        result.map_err(|e| mesh_err(py, &slf.clone().unbind(), e))
    }

    /// Set the value of column `name` at `key`; None clears it.
    fn set_attr(
        slf: &Bound<'_, Self>,
        name: &str,
        key: &Bound<'_, PyAny>,
        value: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let py = slf.py();
        let k = any_key(slf, key)?;
        let kind = kind_of(k);
        let mut this = slf.try_borrow_mut().map_err(busy)?;
        let (d, r) = column_type(&this.mesh, kind, name)
            .ok_or_else(|| mesh_err(py, &slf.clone().unbind(), missing(kind, name)))?;
        let rule = this
            .py_rules
            .get(&(kind as usize, name.to_owned()))
            .map(|r| r.clone_ref(py));
        let result = dispatch!(
            kind,
            d,
            r,
            set_one(&mut this.mesh, name, k, value, rule.as_ref())
        )?;
        drop(this);
        result.map_err(|e| mesh_err(py, &slf.clone().unbind(), e))
    }

    /// The whole column as a numpy array in element order (`vertices`,
    /// `halfedges`, `edges`, `faces`): (n,) for float, int and bool,
    /// (n, 2) / (n, 3) for vectors, a list for str and object columns.
    /// Elements without a value read as NaN in float columns, as `fill`
    /// elsewhere (an int or bool column with gaps and no `fill` raises).
    #[pyo3(signature = (name, kind = "vertex", fill = None))]
    fn attr_array(
        slf: &Bound<'_, Self>,
        name: &str,
        kind: &str,
        fill: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Py<PyAny>> {
        let py = slf.py();
        let kind = parse_kind(kind)?;
        let this = slf.try_borrow().map_err(busy)?;
        let (d, r) = column_type(&this.mesh, kind, name)
            .ok_or_else(|| mesh_err(py, &slf.clone().unbind(), missing(kind, name)))?;
        let result = dispatch!(kind, d, r, get_all(py, &this.mesh, name, fill))?;
        drop(this);
        result.map_err(|e| mesh_err(py, &slf.clone().unbind(), e))
    }

    /// Set the whole column from an array in element order (as `attr_array`
    /// returns it); NaN (or None in lists) leaves an element without value.
    #[pyo3(signature = (name, values, kind = "vertex"))]
    fn set_attr_array(
        slf: &Bound<'_, Self>,
        name: &str,
        values: &Bound<'_, PyAny>,
        kind: &str,
    ) -> PyResult<()> {
        let py = slf.py();
        let kind = parse_kind(kind)?;
        let mut this = slf.try_borrow_mut().map_err(busy)?;
        let (d, r) = column_type(&this.mesh, kind, name)
            .ok_or_else(|| mesh_err(py, &slf.clone().unbind(), missing(kind, name)))?;
        let rule = this
            .py_rules
            .get(&(kind as usize, name.to_owned()))
            .map(|r| r.clone_ref(py));
        let result = dispatch!(
            kind,
            d,
            r,
            set_all(&mut this.mesh, name, values, rule.as_ref())
        )?;
        drop(this);
        result.map_err(|e| mesh_err(py, &slf.clone().unbind(), e))
    }

    /// Positions as an (n, 3) float64 array in the order of `vertices`;
    /// settable with an array of the same shape (as
    /// `set_attr_array("position", ...)`: one undo step, non-finite
    /// values refused).
    #[getter]
    fn positions(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let (p, _) = self.mesh.to_polygons();
        let n = p.positions.len();
        Ok(PyArray1::from_slice(py, p.positions.as_flattened())
            .reshape([n, 3])?
            .into_any()
            .unbind())
    }

    #[setter]
    fn set_positions(slf: &Bound<'_, Self>, values: &Bound<'_, PyAny>) -> PyResult<()> {
        Self::set_attr_array(slf, "position", values, "vertex")
    }

    // ----- loops and rings -----------------------------------------------------------

    /// The edge loop through edge `e`: on through vertices of degree 4,
    /// stopping at poles and the boundary (along the boundary for a
    /// boundary edge). End to end; a closed loop starts with `e`.
    fn edge_loop(slf: &Bound<'_, Self>, e: &Bound<'_, PyEdge>) -> PyResult<Vec<Py<PyEdge>>> {
        let e = ekey(slf, e)?;
        let run = query(slf, |m| m.edge_loop(e))?;
        elements::edges(slf.py(), &slf.clone().unbind(), run.keys)
    }

    /// The edge ring through edge `e`: across quads, stopping at other
    /// faces and holes. End to end; a closed ring starts with `e`.
    fn edge_ring(slf: &Bound<'_, Self>, e: &Bound<'_, PyEdge>) -> PyResult<Vec<Py<PyEdge>>> {
        let e = ekey(slf, e)?;
        let run = query(slf, |m| m.edge_ring(e))?;
        elements::edges(slf.py(), &slf.clone().unbind(), run.keys)
    }

    /// The face loop across edge `e`: the quads its edge ring crosses, in
    /// order.
    fn face_loop(slf: &Bound<'_, Self>, e: &Bound<'_, PyEdge>) -> PyResult<Vec<Py<PyFace>>> {
        let e = ekey(slf, e)?;
        let run = query(slf, |m| m.face_loop(e))?;
        elements::faces(slf.py(), &slf.clone().unbind(), run.keys)
    }

    // ----- modelling tools -------------------------------------------------------------

    /// Cut the quads of the edge ring through `e` with `cuts` new edge
    /// loops at `factor` (in (0, 1); evenly spaced at 0.5), bulging by
    /// `smoothness` towards the surface; one undo step. Returns a dict:
    /// "vertices" (ring edge by ring edge, `cuts` each), "edges" (quad by
    /// quad, `cuts` each), "closed".
    #[pyo3(signature = (e, *, cuts = 1, factor = 0.5, smoothness = 0.0))]
    fn loop_cut<'py>(
        slf: &Bound<'py, Self>,
        e: &Bound<'py, PyEdge>,
        cuts: usize,
        factor: f64,
        smoothness: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let e = ekey(slf, e)?;
        let options = meshloom::model::LoopCutOptions {
            cuts,
            factor,
            smoothness,
        };
        let cut = edit(slf, |m| m.loop_cut(e, &options))?;
        let (py, mesh) = (slf.py(), slf.clone().unbind());
        let out = PyDict::new(py);
        out.set_item("vertices", elements::vertices(py, &mesh, cut.vertices)?)?;
        out.set_item("edges", elements::edges(py, &mesh, cut.edges)?)?;
        out.set_item("closed", cut.closed)?;
        Ok(out)
    }

    /// Extrude `faces` by `distance`: faces sharing an edge move together
    /// with walls along their region's boundary (`individual`: each face on
    /// its own), along the region's mean normal or `direction`; one undo
    /// step. Returns a dict: "top" (the faces, on top), "sides" (the
    /// walls), "vertices" (the new vertices).
    #[pyo3(signature = (faces, distance = 0.0, *, individual = false, direction = None))]
    fn extrude_faces<'py>(
        slf: &Bound<'py, Self>,
        faces: Vec<Bound<'py, PyFace>>,
        distance: f64,
        individual: bool,
        direction: Option<[f64; 3]>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let faces: Vec<FaceKey> = faces
            .iter()
            .map(|f| fkey(slf, f))
            .collect::<PyResult<_>>()?;
        let options = meshloom::model::ExtrudeOptions {
            distance,
            direction,
            individual,
        };
        let made = edit(slf, |m| m.extrude_faces(&faces, &options))?;
        let (py, mesh) = (slf.py(), slf.clone().unbind());
        let out = PyDict::new(py);
        out.set_item("top", elements::faces(py, &mesh, made.top)?)?;
        out.set_item("sides", elements::faces(py, &mesh, made.sides)?)?;
        out.set_item("vertices", elements::vertices(py, &mesh, made.vertices)?)?;
        Ok(out)
    }

    /// Inset `faces` by `thickness` (negative: outset): each region of
    /// faces sharing an edge (`individual`: each face) gets a copy of its
    /// outline moved inwards and `depth` along its mean normal, joined by
    /// a rim of quads; `even` keeps the thickness at sharp corners; one
    /// undo step. Returns a dict: "inner" (the faces), "rim" (the quads),
    /// "vertices" (the new vertices).
    #[pyo3(signature = (faces, thickness, *, depth = 0.0, individual = false, even = true))]
    fn inset_faces<'py>(
        slf: &Bound<'py, Self>,
        faces: Vec<Bound<'py, PyFace>>,
        thickness: f64,
        depth: f64,
        individual: bool,
        even: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let faces: Vec<FaceKey> = faces
            .iter()
            .map(|f| fkey(slf, f))
            .collect::<PyResult<_>>()?;
        let options = meshloom::model::InsetOptions {
            thickness,
            depth,
            even,
            individual,
        };
        let made = edit(slf, |m| m.inset_faces(&faces, &options))?;
        let (py, mesh) = (slf.py(), slf.clone().unbind());
        let out = PyDict::new(py);
        out.set_item("inner", elements::faces(py, &mesh, made.inner)?)?;
        out.set_item("rim", elements::faces(py, &mesh, made.rim)?)?;
        out.set_item("vertices", elements::vertices(py, &mesh, made.vertices)?)?;
        Ok(out)
    }

    /// Scale, rotate and translate `elements` (vertices, edges, faces: their
    /// vertices) about `pivot` ("centroid", "origin" or a point), as one
    /// undo step: `p -> pivot + rotate @ (scale * (p - pivot)) + translate`.
    /// `rotate` is a 3x3 matrix or `(axis, angle)`; `scale` a number or
    /// three. `individual` (faces only): each region of faces sharing an
    /// edge about its own centroid.
    #[pyo3(signature = (elements, *, translate = None, rotate = None, scale = None, pivot = None, individual = false))]
    fn transform(
        slf: &Bound<'_, Self>,
        elements: Vec<Bound<'_, PyAny>>,
        translate: Option<[f64; 3]>,
        rotate: Option<Bound<'_, PyAny>>,
        scale: Option<Bound<'_, PyAny>>,
        pivot: Option<Bound<'_, PyAny>>,
        individual: bool,
    ) -> PyResult<()> {
        use meshloom::model::{Pivot, Transform};
        let mut t = Transform {
            individual,
            ..Default::default()
        };
        if let Some(v) = translate {
            t.translate = v;
        }
        if let Some(r) = rotate {
            t.rotate = if let Ok(m) = r.extract::<[[f64; 3]; 3]>() {
                m
            } else {
                let (axis, angle): ([f64; 3], f64) = r.extract().map_err(|_| {
                    PyTypeError::new_err("rotate must be a 3x3 matrix or (axis, angle)")
                })?;
                Transform::rotation(axis, angle).ok_or_else(|| {
                    PyValueError::new_err("rotate: the axis must be finite and not zero")
                })?
            };
        }
        if let Some(sc) = scale {
            t.scale = match sc.extract::<f64>() {
                Ok(x) => [x; 3],
                Err(_) => sc
                    .extract::<[f64; 3]>()
                    .map_err(|_| PyTypeError::new_err("scale must be a number or three"))?,
            };
        }
        if let Some(pv) = pivot {
            t.pivot = match pv.extract::<String>() {
                Ok(w) if w == "centroid" => Pivot::Centroid,
                Ok(w) if w == "origin" => Pivot::Point([0.0; 3]),
                Ok(w) => {
                    return Err(PyValueError::new_err(format!(
                        "unknown pivot {w:?}: centroid, origin or a point"
                    )))
                }
                Err(_) => Pivot::Point(pv.extract::<[f64; 3]>().map_err(|_| {
                    PyTypeError::new_err("pivot must be \"centroid\", \"origin\" or a point")
                })?),
            };
        }
        let keys: Vec<AnyKey> = elements
            .iter()
            .map(|e| any_key(slf, e))
            .collect::<PyResult<_>>()?;
        let faces: Vec<FaceKey> = keys
            .iter()
            .filter_map(|k| {
                if let AnyKey::Face(f) = k {
                    Some(*f)
                } else {
                    None
                }
            })
            .collect();
        if !keys.is_empty() && faces.len() == keys.len() {
            return edit(slf, |m| m.transform_faces(&faces, &t));
        }
        edit(slf, |m| {
            let mut vs = Vec::new();
            for k in &keys {
                match *k {
                    AnyKey::Vertex(v) => vs.push(v),
                    AnyKey::Edge(e) => vs.extend(m.edge(e)?.vertices()),
                    AnyKey::Halfedge(h) => vs.push(m.halfedge(h)?.origin().key()),
                    AnyKey::Face(f) => vs.extend(m.face(f)?.vertices()),
                }
            }
            m.transform_vertices(&vs, &t)
        })
    }

    /// The centroids (mean of the corners) of `faces` (default: every
    /// face, in `faces` order), as an (n, 3) array.
    #[pyo3(signature = (faces = None))]
    fn face_centroids<'py>(
        slf: &Bound<'py, Self>,
        faces: Option<Vec<Bound<'py, PyFace>>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let keys = face_list(slf, faces)?;
        let rows = query(slf, |m| {
            keys.iter()
                .map(|&f| m.face_centroid(f))
                .collect::<meshloom::Result<Vec<_>>>()
        })?;
        let n = rows.len();
        Ok(PyArray1::from_slice(slf.py(), rows.as_flattened())
            .reshape([n, 3])?
            .into_any())
    }

    /// The areas of `faces` (default: every face, in `faces` order).
    #[pyo3(signature = (faces = None))]
    fn face_areas<'py>(
        slf: &Bound<'py, Self>,
        faces: Option<Vec<Bound<'py, PyFace>>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let keys = face_list(slf, faces)?;
        let areas = query(slf, |m| {
            keys.iter()
                .map(|&f| m.face_area(f))
                .collect::<meshloom::Result<Vec<_>>>()
        })?;
        Ok(PyArray1::from_vec(slf.py(), areas))
    }

    // ----- operators ---------------------------------------------------------------

    /// Split edge `e` at parameter `t` (0 at side 0's origin); returns the
    /// new vertex. Vertex columns interpolate, edge columns split.
    #[pyo3(signature = (e, t = 0.5))]
    fn split_edge(slf: &Bound<'_, Self>, e: &Bound<'_, PyEdge>, t: f64) -> PyResult<Py<PyVertex>> {
        let e = ekey(slf, e)?;
        let v = edit(slf, |m| m.split_edge(e, t))?;
        PyVertex::make(slf.py(), &slf.clone().unbind(), v)
    }
    /// Raise `RefusedError` if `split_edge(e, t)` would refuse; else None.
    #[pyo3(signature = (e, t = 0.5))]
    fn check_split_edge(slf: &Bound<'_, Self>, e: &Bound<'_, PyEdge>, t: f64) -> PyResult<()> {
        let e = ekey(slf, e)?;
        query(slf, |m| m.check_split_edge(e, t))
    }

    /// Split face `f` by a new edge from corner `a` to corner `b`; returns
    /// the new half-edge from a to b.
    fn split_face(
        slf: &Bound<'_, Self>,
        f: &Bound<'_, PyFace>,
        a: &Bound<'_, PyVertex>,
        b: &Bound<'_, PyVertex>,
    ) -> PyResult<Py<PyHalfedge>> {
        let (f, a, b) = (fkey(slf, f)?, vkey(slf, a)?, vkey(slf, b)?);
        let h = edit(slf, |m| m.split_face(f, a, b))?;
        PyHalfedge::make(slf.py(), &slf.clone().unbind(), h)
    }
    /// Raise `RefusedError` if `split_face(f, a, b)` would refuse.
    fn check_split_face(
        slf: &Bound<'_, Self>,
        f: &Bound<'_, PyFace>,
        a: &Bound<'_, PyVertex>,
        b: &Bound<'_, PyVertex>,
    ) -> PyResult<()> {
        let (f, a, b) = (fkey(slf, f)?, vkey(slf, a)?, vkey(slf, b)?);
        query(slf, |m| m.check_split_face(f, a, b))
    }

    /// Join two corners of a common face by a new edge; returns a to b.
    fn insert_edge(
        slf: &Bound<'_, Self>,
        a: &Bound<'_, PyVertex>,
        b: &Bound<'_, PyVertex>,
    ) -> PyResult<Py<PyHalfedge>> {
        let (a, b) = (vkey(slf, a)?, vkey(slf, b)?);
        let h = edit(slf, |m| m.insert_edge(a, b))?;
        PyHalfedge::make(slf.py(), &slf.clone().unbind(), h)
    }
    /// Raise `RefusedError` if `insert_edge(a, b)` would refuse.
    fn check_insert_edge(
        slf: &Bound<'_, Self>,
        a: &Bound<'_, PyVertex>,
        b: &Bound<'_, PyVertex>,
    ) -> PyResult<()> {
        let (a, b) = (vkey(slf, a)?, vkey(slf, b)?);
        query(slf, |m| m.check_insert_edge(a, b))
    }

    /// Put a vertex at the centre of face `f`, joined to every corner;
    /// returns it.
    fn poke_face(slf: &Bound<'_, Self>, f: &Bound<'_, PyFace>) -> PyResult<Py<PyVertex>> {
        let f = fkey(slf, f)?;
        let v = edit(slf, |m| m.poke_face(f))?;
        PyVertex::make(slf.py(), &slf.clone().unbind(), v)
    }
    /// Raise `RefusedError` if `poke_face(f)` would refuse.
    fn check_poke_face(slf: &Bound<'_, Self>, f: &Bound<'_, PyFace>) -> PyResult<()> {
        let f = fkey(slf, f)?;
        query(slf, |m| m.check_poke_face(f))
    }

    /// Collapse half-edge `h`: its origin merges into its destination (or,
    /// with `t`, both move to the point at parameter t). Returns the
    /// surviving vertex; vertex columns merge, survivor first.
    #[pyo3(signature = (h, t = None))]
    fn collapse_edge(
        slf: &Bound<'_, Self>,
        h: &Bound<'_, PyHalfedge>,
        t: Option<f64>,
    ) -> PyResult<Py<PyVertex>> {
        let h = hkey(slf, h)?;
        let v = edit(slf, |m| match t {
            Some(t) => m.collapse_edge_at(h, t),
            None => m.collapse_edge(h),
        })?;
        PyVertex::make(slf.py(), &slf.clone().unbind(), v)
    }
    /// Raise `RefusedError` if `collapse_edge(h, t)` would refuse.
    #[pyo3(signature = (h, t = None))]
    fn check_collapse_edge(
        slf: &Bound<'_, Self>,
        h: &Bound<'_, PyHalfedge>,
        t: Option<f64>,
    ) -> PyResult<()> {
        let h = hkey(slf, h)?;
        query(slf, |m| match t {
            Some(t) => m.check_collapse_edge_at(h, t),
            None => m.check_collapse_edge(h),
        })
    }

    /// Flip the diagonal of the two triangles beside edge `e`; returns the
    /// new edge.
    fn flip_edge(slf: &Bound<'_, Self>, e: &Bound<'_, PyEdge>) -> PyResult<Py<PyEdge>> {
        let e = ekey(slf, e)?;
        let n = edit(slf, |m| m.flip_edge(e))?;
        PyEdge::make(slf.py(), &slf.clone().unbind(), n)
    }
    /// Raise `RefusedError` if `flip_edge(e)` would refuse.
    fn check_flip_edge(slf: &Bound<'_, Self>, e: &Bound<'_, PyEdge>) -> PyResult<()> {
        let e = ekey(slf, e)?;
        query(slf, |m| m.check_flip_edge(e))
    }

    /// Remove edge `e`, merging the faces on its sides (a boundary edge
    /// merges its face into the hole); returns the surviving face.
    fn remove_edge(slf: &Bound<'_, Self>, e: &Bound<'_, PyEdge>) -> PyResult<Py<PyFace>> {
        let e = ekey(slf, e)?;
        let f = edit(slf, |m| m.remove_edge(e))?;
        PyFace::make(slf.py(), &slf.clone().unbind(), f)
    }
    /// Raise `RefusedError` if `remove_edge(e)` would refuse.
    fn check_remove_edge(slf: &Bound<'_, Self>, e: &Bound<'_, PyEdge>) -> PyResult<()> {
        let e = ekey(slf, e)?;
        query(slf, |m| m.check_remove_edge(e))
    }

    /// `remove_edge` that may also remove a bridge (splitting the mesh in
    /// two); returns the faces left where it was.
    fn remove_edge_allowing_bridge(
        slf: &Bound<'_, Self>,
        e: &Bound<'_, PyEdge>,
    ) -> PyResult<Vec<Py<PyFace>>> {
        let e = ekey(slf, e)?;
        let fs = edit(slf, |m| m.remove_edge_allowing_bridge(e))?;
        elements::faces(slf.py(), &slf.clone().unbind(), fs)
    }
    /// Raise `RefusedError` if `remove_edge_allowing_bridge(e)` would refuse.
    fn check_remove_edge_allowing_bridge(
        slf: &Bound<'_, Self>,
        e: &Bound<'_, PyEdge>,
    ) -> PyResult<()> {
        let e = ekey(slf, e)?;
        query(slf, |m| m.check_remove_edge_allowing_bridge(e))
    }

    /// Merge two adjacent faces into `f`; returns it.
    fn merge_faces(
        slf: &Bound<'_, Self>,
        f: &Bound<'_, PyFace>,
        g: &Bound<'_, PyFace>,
    ) -> PyResult<Py<PyFace>> {
        let (f, g) = (fkey(slf, f)?, fkey(slf, g)?);
        let k = edit(slf, |m| m.merge_faces(f, g))?;
        PyFace::make(slf.py(), &slf.clone().unbind(), k)
    }
    /// Raise `RefusedError` if `merge_faces(f, g)` would refuse.
    fn check_merge_faces(
        slf: &Bound<'_, Self>,
        f: &Bound<'_, PyFace>,
        g: &Bound<'_, PyFace>,
    ) -> PyResult<()> {
        let (f, g) = (fkey(slf, f)?, fkey(slf, g)?);
        query(slf, |m| m.check_merge_faces(f, g))
    }

    /// Remove vertex `v` and its edges; its faces become one; returns it.
    fn remove_vertex(slf: &Bound<'_, Self>, v: &Bound<'_, PyVertex>) -> PyResult<Py<PyFace>> {
        let v = vkey(slf, v)?;
        let f = edit(slf, |m| m.remove_vertex(v))?;
        PyFace::make(slf.py(), &slf.clone().unbind(), f)
    }
    /// Raise `RefusedError` if `remove_vertex(v)` would refuse.
    fn check_remove_vertex(slf: &Bound<'_, Self>, v: &Bound<'_, PyVertex>) -> PyResult<()> {
        let v = vkey(slf, v)?;
        query(slf, |m| m.check_remove_vertex(v))
    }

    /// Turn face `f` into (part of) a hole; returns the hole faces left.
    fn remove_face(slf: &Bound<'_, Self>, f: &Bound<'_, PyFace>) -> PyResult<Vec<Py<PyFace>>> {
        let f = fkey(slf, f)?;
        let fs = edit(slf, |m| m.remove_face(f))?;
        elements::faces(slf.py(), &slf.clone().unbind(), fs)
    }
    /// Raise `RefusedError` if `remove_face(f)` would refuse.
    fn check_remove_face(slf: &Bound<'_, Self>, f: &Bound<'_, PyFace>) -> PyResult<()> {
        let f = fkey(slf, f)?;
        query(slf, |m| m.check_remove_face(f))
    }

    /// Close a hole with one face; returns it.
    fn fill_hole(slf: &Bound<'_, Self>, hole: &Bound<'_, PyFace>) -> PyResult<Py<PyFace>> {
        let h = fkey(slf, hole)?;
        let f = edit(slf, |m| m.fill_hole(h))?;
        PyFace::make(slf.py(), &slf.clone().unbind(), f)
    }
    /// Raise `RefusedError` if `fill_hole(hole)` would refuse.
    fn check_fill_hole(slf: &Bound<'_, Self>, hole: &Bound<'_, PyFace>) -> PyResult<()> {
        let h = fkey(slf, hole)?;
        query(slf, |m| m.check_fill_hole(h))
    }

    /// Close a hole with triangles; returns them.
    fn fill_hole_triangulated(
        slf: &Bound<'_, Self>,
        hole: &Bound<'_, PyFace>,
    ) -> PyResult<Vec<Py<PyFace>>> {
        let h = fkey(slf, hole)?;
        let fs = edit(slf, |m| m.fill_hole_triangulated(h))?;
        elements::faces(slf.py(), &slf.clone().unbind(), fs)
    }
    /// Raise `RefusedError` if `fill_hole_triangulated(hole)` would refuse.
    fn check_fill_hole_triangulated(
        slf: &Bound<'_, Self>,
        hole: &Bound<'_, PyFace>,
    ) -> PyResult<()> {
        let h = fkey(slf, hole)?;
        query(slf, |m| m.check_fill_hole_triangulated(h))
    }

    /// Cut face `f` into triangles (ear clipping); returns them.
    fn triangulate(slf: &Bound<'_, Self>, f: &Bound<'_, PyFace>) -> PyResult<Vec<Py<PyFace>>> {
        let f = fkey(slf, f)?;
        let fs = edit(slf, |m| m.triangulate(f))?;
        elements::faces(slf.py(), &slf.clone().unbind(), fs)
    }
    /// Raise `RefusedError` if `triangulate(f)` would refuse.
    fn check_triangulate(slf: &Bound<'_, Self>, f: &Bound<'_, PyFace>) -> PyResult<()> {
        let f = fkey(slf, f)?;
        query(slf, |m| m.check_triangulate(f))
    }
    /// Triangulate every face; returns the faces that could not be cut
    /// (every way needed an existing edge), left as they were.
    fn triangulate_all(slf: &Bound<'_, Self>) -> PyResult<Vec<Py<PyFace>>> {
        let fs = edit(slf, |m| Ok(m.triangulate_all()))?;
        elements::faces(slf.py(), &slf.clone().unbind(), fs)
    }

    /// Extrude face `f` by `distance` along its normal; returns the side
    /// faces.
    fn extrude_face(
        slf: &Bound<'_, Self>,
        f: &Bound<'_, PyFace>,
        distance: f64,
    ) -> PyResult<Vec<Py<PyFace>>> {
        let f = fkey(slf, f)?;
        let fs = edit(slf, |m| m.extrude_face(f, distance))?;
        elements::faces(slf.py(), &slf.clone().unbind(), fs)
    }
    /// Raise `RefusedError` if `extrude_face(f, distance)` would refuse.
    fn check_extrude_face(
        slf: &Bound<'_, Self>,
        f: &Bound<'_, PyFace>,
        distance: f64,
    ) -> PyResult<()> {
        let f = fkey(slf, f)?;
        query(slf, |m| m.check_extrude_face(f, distance))
    }

    /// Split the origin of two outgoing half-edges `hc`, `hd` into two
    /// vertices joined by a new edge; returns the new half-edge.
    fn split_vertex(
        slf: &Bound<'_, Self>,
        hc: &Bound<'_, PyHalfedge>,
        hd: &Bound<'_, PyHalfedge>,
    ) -> PyResult<Py<PyHalfedge>> {
        let (c, d) = (hkey(slf, hc)?, hkey(slf, hd)?);
        let h = edit(slf, |m| m.split_vertex(c, d))?;
        PyHalfedge::make(slf.py(), &slf.clone().unbind(), h)
    }
    /// Raise `RefusedError` if `split_vertex(hc, hd)` would refuse.
    fn check_split_vertex(
        slf: &Bound<'_, Self>,
        hc: &Bound<'_, PyHalfedge>,
        hd: &Bound<'_, PyHalfedge>,
    ) -> PyResult<()> {
        let (c, d) = (hkey(slf, hc)?, hkey(slf, hd)?);
        query(slf, |m| m.check_split_vertex(c, d))
    }

    /// Cut the mesh open along a path of vertices joined by edges; returns
    /// the new hole faces.
    fn cut_path(
        slf: &Bound<'_, Self>,
        path: Vec<Bound<'_, PyVertex>>,
    ) -> PyResult<Vec<Py<PyFace>>> {
        let path: Vec<VertexKey> = path.iter().map(|v| vkey(slf, v)).collect::<PyResult<_>>()?;
        let fs = edit(slf, |m| m.cut_path(&path))?;
        elements::faces(slf.py(), &slf.clone().unbind(), fs)
    }
    /// Raise `RefusedError` if `cut_path(path)` would refuse.
    fn check_cut_path(slf: &Bound<'_, Self>, path: Vec<Bound<'_, PyVertex>>) -> PyResult<()> {
        let path: Vec<VertexKey> = path.iter().map(|v| vkey(slf, v)).collect::<PyResult<_>>()?;
        query(slf, |m| m.check_cut_path(&path))
    }

    /// For the benchmark script: the seconds `Mesh::from_buffers` (the Rust
    /// builder) takes to rebuild this mesh's polygons, timed in Rust once
    /// per repeat, with no Python on the clock.
    fn _rust_build_seconds(&self, py: Python<'_>, repeats: usize) -> PyResult<Vec<f64>> {
        let (polygons, _) = self.mesh.to_polygons();
        py.detach(|| {
            (0..repeats)
                .map(|_| {
                    let start = std::time::Instant::now();
                    let built = Mesh::from_buffers(&polygons);
                    let secs = start.elapsed().as_secs_f64();
                    built.map(|m| {
                        drop(m);
                        secs
                    })
                })
                .collect::<meshloom::Result<Vec<f64>>>()
        })
        .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    // ----- pickling ------------------------------------------------------------------

    /// The pickled state: the validated serde form (JSON) of the mesh
    /// without its Python-rule columns, and those columns as
    /// `(kind, name, rule, [(slot, value), ...])`.
    fn __getstate__(&self, py: Python<'_>) -> PyResult<Py<PyTuple>> {
        let mut plain = self.mesh.clone();
        let mut columns = Vec::new();
        for ((kind, name), rule) in &self.py_rules {
            let kind = [
                ElementKind::Vertex,
                ElementKind::Halfedge,
                ElementKind::Edge,
                ElementKind::Face,
            ][*kind];
            let values = dispatch!(
                kind,
                Dtype::Object,
                RuleName::PyRule,
                slot_values(py, &plain, name)
            )?;
            dispatch!(
                kind,
                Dtype::Object,
                RuleName::PyRule,
                remove(&mut plain, name)
            )?
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
            columns.push((kind_name(kind), name.clone(), rule.clone_ref(py), values));
        }
        let json = serde_json::to_vec(&plain)
            .map_err(|e| PyValueError::new_err(format!("cannot pickle the mesh: {e}")))?;
        Ok(PyTuple::new(
            py,
            [
                PyBytes::new(py, &json).into_any(),
                columns.into_pyobject(py)?.into_any(),
            ],
        )?
        .unbind())
    }

    /// Restore a pickled state (validated: a corrupt state raises).
    fn __setstate__(&mut self, py: Python<'_>, state: &Bound<'_, PyTuple>) -> PyResult<()> {
        let json: Vec<u8> = state.get_item(0)?.extract()?;
        let mut mesh: Mesh = serde_json::from_slice(&json)
            .map_err(|e| PyValueError::new_err(format!("cannot unpickle the mesh: {e}")))?;
        let mut rules = HashMap::new();
        for col in state.get_item(1)?.try_iter()? {
            let col = col?;
            let (kind, name, rule, values): PickledColumn = col.extract()?;
            let kind = parse_kind(&kind)?;
            dispatch!(kind, Dtype::Object, RuleName::PyRule, add(&mut mesh, &name))?
                .map_err(|e| PyValueError::new_err(e.to_string()))?;
            dispatch!(
                kind,
                Dtype::Object,
                RuleName::PyRule,
                restore_slots(py, &mut mesh, &name, &rule, &values)
            )?;
            rules.insert((kind as usize, name), rule);
        }
        self.mesh = mesh;
        self.py_rules = rules;
        Ok(())
    }

    /// Whether both meshes have the same elements under the same keys and
    /// the same attribute values (Python values compared with ==).
    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        let Ok(other) = other.cast::<PyMesh>() else {
            return Ok(false);
        };
        let other = other.try_borrow().map_err(busy)?;
        let a = self.__getstate__(py)?;
        let b = other.__getstate__(py)?;
        let (a, b) = (a.bind(py), b.bind(py));
        let ja: serde_json::Value = serde_json::from_slice(&a.get_item(0)?.extract::<Vec<u8>>()?)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let jb: serde_json::Value = serde_json::from_slice(&b.get_item(0)?.extract::<Vec<u8>>()?)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        if canonical(ja) != canonical(jb) {
            return Ok(false);
        }
        let sort = py.import("builtins")?.getattr("sorted")?;
        let ca = sort.call1((a.get_item(1)?,))?;
        let cb = sort.call1((b.get_item(1)?,))?;
        // Rules are compared by type: two instances of one rule class are
        // the same rule.
        let strip = |c: &Bound<'_, PyAny>| -> PyResult<Vec<(String, String, String, SlotValues)>> {
            let mut out = Vec::new();
            for item in c.try_iter()? {
                let (k, n, r, v): (String, String, Bound<'_, PyAny>, SlotValues) =
                    item?.extract()?;
                out.push((k, n, r.get_type().qualname()?.to_string(), v));
            }
            Ok(out)
        };
        let (sa, sb) = (strip(&ca)?, strip(&cb)?);
        if sa.len() != sb.len() {
            return Ok(false);
        }
        for (x, y) in sa.iter().zip(&sb) {
            if (&x.0, &x.1, &x.2) != (&y.0, &y.1, &y.2) || x.3.len() != y.3.len() {
                return Ok(false);
            }
            for ((i, u), (j, w)) in x.3.iter().zip(&y.3) {
                if i != j || !u.bind(py).eq(w.bind(py))? {
                    return Ok(false);
                }
            }
        }
        Ok(true)
    }
}

/// The serde form without what no key can reach: the content and
/// generation of vacant slots, and vacant slots past the last live one. Two
/// meshes equal in this form have the same elements under the same keys,
/// the same links and the same values; they may differ in slots left
/// vacant (an undone or rolled-back birth leaves its slot vacant at a
/// higher generation).
fn canonical(mut j: serde_json::Value) -> serde_json::Value {
    use serde_json::Value as J;
    fn live(j: &J, field: &str) -> Vec<bool> {
        j[field]
            .as_array()
            .map(|g| {
                g.iter()
                    .map(|g| g.as_u64().is_some_and(|g| g & 1 == 1))
                    .collect()
            })
            .unwrap_or_default()
    }
    /// Null the entries of vacant slots (`per` entries per slot), then cut
    /// the array after the last live slot.
    fn scrub(a: &mut J, live: &[bool], per: usize) {
        let Some(a) = a.as_array_mut() else { return };
        for (i, x) in a.iter_mut().enumerate() {
            if !live.get(i / per).copied().unwrap_or(false) {
                *x = J::Null;
            }
        }
        let keep = live.iter().rposition(|&l| l).map_or(0, |i| (i + 1) * per);
        a.truncate(keep);
    }
    fn scrub_attrs(j: &mut J, field: &str, live: &[bool], per: usize) {
        if let Some(cols) = j[field].as_array_mut() {
            for c in cols {
                scrub(&mut c["values"], live, per);
            }
        }
    }
    let (v, e, f) = (
        live(&j, "vertex_generations"),
        live(&j, "edge_generations"),
        live(&j, "face_generations"),
    );
    for (field, live, per) in [
        ("vertex_halfedge", &v, 1),
        ("vertex_generations", &v, 1),
        ("halfedges", &e, 2),
        ("edge_generations", &e, 1),
        ("face_halfedge", &f, 1),
        ("face_generations", &f, 1),
    ] {
        scrub(&mut j[field], live, per);
    }
    scrub_attrs(&mut j, "vertex_attrs", &v, 1);
    scrub_attrs(&mut j, "halfedge_attrs", &e, 2);
    scrub_attrs(&mut j, "edge_attrs", &e, 1);
    scrub_attrs(&mut j, "face_attrs", &f, 1);
    j
}

/// The present values of a Python-rule column by slot.
fn slot_values<K: FromAny, T: PyAttr, R: Rule<T>>(
    py: Python<'_>,
    mesh: &Mesh,
    name: &str,
) -> PyResult<Vec<(u32, Py<PyAny>)>> {
    let h = mesh
        .attr_handle::<K, T, R>(name)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let view = mesh
        .attr_view(&h)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    view.iter()
        .map(|(k, v)| Ok((k.slot(), v.to_py(py)?)))
        .collect()
}

/// Put values back by slot into a Python-rule column.
fn restore_slots<K: FromAny, T: PyAttr, R: Rule<T>>(
    py: Python<'_>,
    mesh: &mut Mesh,
    name: &str,
    rule: &Py<PyAny>,
    values: &[(u32, Py<PyAny>)],
) -> PyResult<()> {
    let by_slot: HashMap<u32, K> = K::all_with_holes(mesh)
        .into_iter()
        .map(|k| (k.slot(), k))
        .collect();
    let h = mesh
        .attr_handle::<K, T, R>(name)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    for (slot, v) in values {
        let k = by_slot.get(slot).ok_or_else(|| {
            PyValueError::new_err(format!(
                "pickled value for slot {slot} of {name:?}, which holds no element"
            ))
        })?;
        let v = T::from_py(v.bind(py), Some(rule))?;
        mesh.set_attr(&h, *k, v)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
    }
    Ok(())
}
