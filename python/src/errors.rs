//! Rust errors as the Python exceptions of `meshloom.errors`, carrying what
//! the Rust errors carry (operator, reason and element; file and line).

use meshloom::attr::RuleError;
use meshloom::error::{BuildError, Refusal};
use meshloom::io::Position;
use meshloom::{AnyKey, Error};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyModule;
use pyo3::IntoPyObjectExt;

use crate::elements::key_object;
use crate::mesh::PyMesh;

static ERRORS: PyOnceLock<Py<PyModule>> = PyOnceLock::new();

/// An instance of the exception class `name` of `meshloom.errors` with the
/// message and the attributes given. If the class cannot be found (the
/// Python package is broken), a `RuntimeError` says so.
pub fn raise(py: Python<'_>, name: &str, msg: String, attrs: &[(&str, Py<PyAny>)]) -> PyErr {
    let made = (|| -> PyResult<PyErr> {
        let module =
            ERRORS.get_or_try_init(py, || py.import("meshloom.errors").map(Bound::unbind))?;
        let class = module.bind(py).getattr(name)?;
        let value = class.call1((msg.clone(),))?;
        for (k, v) in attrs {
            value.setattr(*k, v)?;
        }
        Ok(PyErr::from_value(value))
    })();
    made.unwrap_or_else(|e| e)
}

/// The error of using a mesh from inside one of its own Python attribute
/// rules while meshloom edits it (the edit holds the mesh): a
/// `ReentrantError`, which the edit then rolls back and raises.
pub fn busy(e: impl std::fmt::Display) -> PyErr {
    Python::attach(|py| {
        raise(
            py,
            "ReentrantError",
            format!(
                "the mesh is being edited: an attribute rule called during an edit of this mesh cannot use the mesh ({e})"
            ),
            &[],
        )
    })
}

/// The snake_case name of a refusal: `LinkCondition` → `link_condition`.
fn refusal_name(reason: &Refusal) -> String {
    let debug = format!("{reason:?}");
    let head = debug.split('(').next().unwrap_or(&debug);
    snake(head)
}

fn snake(camel: &str) -> String {
    let mut out = String::with_capacity(camel.len() + 4);
    for (i, c) in camel.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                out.push('_');
            }
            out.push(c.to_ascii_lowercase());
        } else {
            out.push(c);
        }
    }
    out
}

fn build_face(e: &BuildError) -> Option<usize> {
    // Every build error that names one face says "face N" first.
    let text = e.to_string();
    let rest = text.strip_prefix("face ")?;
    rest.split(|c: char| !c.is_ascii_digit())
        .next()?
        .parse()
        .ok()
}

/// A Python object of a Rust value.
fn obj<'py, T: IntoPyObject<'py>>(py: Python<'py>, v: T) -> Py<PyAny> {
    v.into_py_any(py).unwrap_or_else(|_| py.None())
}

/// A meshloom error as a Python exception; keys it names become key objects
/// of `mesh`.
pub fn mesh_err(py: Python<'_>, mesh: &Py<PyMesh>, e: Error) -> PyErr {
    let key = |k: AnyKey| key_object(py, mesh, k);
    let msg = e.to_string();
    match e {
        Error::StaleKey(k) => raise(py, "StaleKeyError", msg, &[("element", key(k))]),
        Error::Refused { op, key: k, reason } => raise(
            py,
            "RefusedError",
            msg,
            &[
                ("op", obj(py, op)),
                ("reason", obj(py, refusal_name(&reason))),
                ("element", key(k)),
            ],
        ),
        Error::Build(b) => build_err(py, b),
        Error::Invalid(v) => {
            let element = v.key.map(key).unwrap_or_else(|| py.None());
            raise(
                py,
                "ValidationError",
                msg,
                &[("rule", obj(py, v.rule)), ("element", element)],
            )
        }
        Error::AttributeExists { .. }
        | Error::AttributeMissing { .. }
        | Error::AttributeType { .. }
        | Error::AttributeHandle { .. } => raise(py, "ColumnError", msg, &[]),
        Error::Rule(error) => rule_err(py, &error, msg),
        e => algorithm_err(py, mesh, e, msg),
    }
}

/// The errors an algorithm stops with, each as its exception
/// (`MeshloomError` for any other).
fn algorithm_err(py: Python<'_>, mesh: &Py<PyMesh>, e: Error, msg: String) -> PyErr {
    let key = |k: AnyKey| key_object(py, mesh, k);
    match e {
        Error::Cancelled { algorithm } => raise(
            py,
            "CancelledError",
            msg,
            &[("algorithm", obj(py, algorithm))],
        ),
        Error::Unsuitable {
            algorithm,
            key: k,
            reason,
        } => raise(
            py,
            "UnsuitableError",
            msg,
            &[
                ("algorithm", obj(py, algorithm)),
                ("reason", obj(py, reason)),
                ("element", k.map(key).unwrap_or_else(|| py.None())),
            ],
        ),
        Error::TooLarge {
            algorithm,
            estimate,
            limit,
            option,
        } => raise(
            py,
            "TooLargeError",
            msg,
            &[
                ("algorithm", obj(py, algorithm)),
                ("estimate", obj(py, estimate)),
                ("limit", obj(py, limit)),
                ("option", obj(py, option)),
            ],
        ),
        Error::NonFiniteResult {
            algorithm, key: k, ..
        } => raise(
            py,
            "NonFiniteError",
            msg,
            &[("algorithm", obj(py, algorithm)), ("element", key(k))],
        ),
        _ => raise(py, "MeshloomError", msg, &[]),
    }
}

/// A column's rule failed: the exception a Python rule raised, itself (with
/// a note that the mesh is unchanged); for a rule of another kind, a
/// `MeshloomError` naming the column.
fn rule_err(py: Python<'_>, error: &RuleError, msg: String) -> PyErr {
    let column = error.column();
    if let Some(raised) = error.cause().and_then(|c| c.downcast_ref::<PyErr>()) {
        let raised = raised.clone_ref(py);
        let rule = match column {
            Some((kind, name)) => format!("the Python rule of the {kind} column {name:?}"),
            None => "a Python rule".to_owned(),
        };
        let note = format!("raised by {rule} inside a meshloom edit; the mesh is unchanged");
        let _ = raised.value(py).call_method1("add_note", (note,));
        return raised;
    }
    raise(
        py,
        "MeshloomError",
        msg,
        &[
            ("column", obj(py, column.map(|(_, name)| name))),
            ("kind", obj(py, column.map(|(kind, _)| kind.to_string()))),
        ],
    )
}

/// A build error (bad input polygons) as `BuildError`.
pub fn build_err(py: Python<'_>, b: BuildError) -> PyErr {
    let face = build_face(&b)
        .map(|f| f.into_pyobject(py).unwrap().into_any().unbind())
        .unwrap_or_else(|| py.None());
    let debug = format!("{b:?}");
    let kind = snake(debug.split([' ', '{', '(']).next().unwrap_or(""));
    let kind = kind.into_pyobject(py).unwrap().into_any().unbind();
    raise(
        py,
        "BuildError",
        b.to_string(),
        &[("face", face), ("kind", kind)],
    )
}

/// A reader or writer error as `ReadError` with file, line and byte.
pub fn io_err(py: Python<'_>, e: meshloom::io::Error) -> PyErr {
    let at = e.location();
    let file = at
        .path
        .as_ref()
        .map(|p| {
            p.display()
                .to_string()
                .into_pyobject(py)
                .unwrap()
                .into_any()
                .unbind()
        })
        .unwrap_or_else(|| py.None());
    let (line, byte) = match at.position {
        Position::Line(l) => (Some(l), None),
        Position::Byte(b) => (None, Some(b)),
        _ => (None, None),
    };
    let num = |n: Option<u64>| {
        n.map(|n| n.into_pyobject(py).unwrap().into_any().unbind())
            .unwrap_or_else(|| py.None())
    };
    raise(
        py,
        "ReadError",
        e.to_string(),
        &[("file", file), ("line", num(line)), ("byte", num(byte))],
    )
}
