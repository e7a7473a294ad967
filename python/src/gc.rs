//! Garbage collection: a Python-rule column holds Python objects (the
//! values and the rule), which may refer back to the mesh (a value that is
//! a key object, a rule that keeps its mesh). `Mesh.__traverse__` shows
//! Python's collector every such reference, `Mesh.__clear__` drops them to
//! break a cycle, and the key classes show the mesh they hold.

use meshloom::attr::Element;
use meshloom::keys::ElementKind;
use meshloom::{EdgeKey, FaceKey, HalfedgeKey, Mesh, VertexKey};
use pyo3::gc::PyVisit;
use pyo3::prelude::*;
use pyo3::PyTraverseError;

use crate::attrs::{PyRule, PyValue};
use crate::mesh::{PyMesh, KINDS};

/// Visit every value of the Python-rule column `name` on `K`'s arena. Each
/// `PyValue` owns its references, so no object is visited more often than
/// the column holds it. (Values saved by an open journal transaction are
/// not visited: the collector then sees them as held from outside, which
/// keeps them alive, never frees them early.)
fn visit_column<K: Element>(
    mesh: &Mesh,
    name: &str,
    visit: &PyVisit<'_>,
) -> Result<(), PyTraverseError> {
    let Ok(h) = mesh.attr_handle::<K, PyValue, PyRule>(name) else {
        return Ok(());
    };
    let Ok(view) = mesh.attr_view(&h) else {
        return Ok(());
    };
    for (_, v) in view.iter() {
        if let Some(c) = &v.0 {
            visit.call(&c.rule)?;
            visit.call(&c.value)?;
        }
    }
    Ok(())
}

fn remove_column<K: Element>(mesh: &mut Mesh, name: &str) {
    if let Ok(h) = mesh.attr_handle::<K, PyValue, PyRule>(name) {
        let _ = mesh.remove_attr(&h);
    }
}

#[pymethods]
impl PyMesh {
    fn __traverse__(&self, visit: PyVisit<'_>) -> Result<(), PyTraverseError> {
        for ((kind, name), rule) in &self.py_rules {
            visit.call(rule)?;
            match KINDS[*kind] {
                ElementKind::Vertex => visit_column::<VertexKey>(&self.mesh, name, &visit)?,
                ElementKind::Halfedge => visit_column::<HalfedgeKey>(&self.mesh, name, &visit)?,
                ElementKind::Edge => visit_column::<EdgeKey>(&self.mesh, name, &visit)?,
                _ => visit_column::<FaceKey>(&self.mesh, name, &visit)?,
            }
        }
        Ok(())
    }

    fn __clear__(&mut self) {
        let rules = std::mem::take(&mut self.py_rules);
        for (kind, name) in rules.keys() {
            match KINDS[*kind] {
                ElementKind::Vertex => remove_column::<VertexKey>(&mut self.mesh, name),
                ElementKind::Halfedge => remove_column::<HalfedgeKey>(&mut self.mesh, name),
                ElementKind::Edge => remove_column::<EdgeKey>(&mut self.mesh, name),
                _ => remove_column::<FaceKey>(&mut self.mesh, name),
            }
        }
    }
}
