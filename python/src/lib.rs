//! Python bindings of meshloom (`import meshloom`): half-edge meshes whose
//! attributes follow every edit, with numpy arrays, Python attribute rules
//! and pickling.
//!
//! The native module is `meshloom._meshloom`; the Python package
//! `meshloom` (in `meshloom/`) re-exports it with the exception classes
//! and type stubs. Nothing here panics into Python: every Rust error becomes
//! an exception of `meshloom.errors`.
#![deny(missing_docs)]
#![forbid(unsafe_code)]

use pyo3::prelude::*;

pub mod algo;
pub mod attrs;
pub mod buffers;
pub mod elements;
pub mod errors;
pub mod gc;
pub mod intersect;
pub mod io;
pub mod mesh;
pub mod model_bridge;
pub mod model_dissolve;
pub mod model_quads;
pub mod model_shapes;
pub mod model_split;
pub mod tree;

/// The native module.
#[pymodule]
fn _meshloom(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<mesh::PyMesh>()?;
    m.add_class::<elements::PyVertex>()?;
    m.add_class::<elements::PyHalfedge>()?;
    m.add_class::<elements::PyEdge>()?;
    m.add_class::<elements::PyFace>()?;
    m.add_class::<tree::PyFaceTree>()?;
    m.add_function(wrap_pyfunction!(io::read, m)?)?;
    m.add_function(wrap_pyfunction!(io::read_with, m)?)?;
    m.add_function(wrap_pyfunction!(io::write, m)?)?;
    model_shapes::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
