//! Attribute columns from Python: stock rules by name, numpy bulk reads and
//! writes, and custom rules written in Python.
//!
//! A column's value type and rule are read from `Mesh::attr_info` (the
//! value type's name and [`Rule::name`]), so columns read from files or
//! restored by pickling are found the same way as columns added from
//! Python.
//!
//! # Python rules
//!
//! `meshloom::attr::Rule` is a trait of associated functions: a rule has no
//! state. A Python rule is an object, so each value of a Python-rule column
//! carries its rule object beside the value ([`PyValue`]); [`PyRule`] finds
//! the rule in the first present contributor and calls its `merge`,
//! `interpolate` (falling back to `merge`) or `split` method. [`PyRule`] is
//! a fallible rule (`Rule::FALLIBLE`): an exception a Python rule raises
//! becomes its `RuleError`, holding the exception, and meshloom fails the
//! edit with `Error::Rule`, leaving the mesh as it was (every edit of a
//! mesh with such a column runs as a transaction: all or nothing, at the
//! cost of the edit). `crate::errors::mesh_err` raises the original
//! exception again. The values hold Python objects, so `Mesh` takes part in
//! Python's garbage collection (`crate::gc`).

use meshloom::attr::Attribute;
use meshloom::attr::{Element, Rule, RuleError, Value};
use meshloom::keys::ElementKind;
use meshloom::{AnyKey, EdgeKey, FaceKey, HalfedgeKey, Mesh, VertexKey};
use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyString, PyType};

/// The value types the bindings expose.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dtype {
    /// `f64`.
    Float,
    /// `i64`.
    Int,
    /// `bool`.
    Bool,
    /// `[f64; 2]`.
    Vec2,
    /// `[f64; 3]`.
    Vec3,
    /// `[f64; 4]` (colours read from files).
    Vec4,
    /// `String`.
    Text,
    /// Any Python object, with a Python rule.
    Object,
    /// A dynamic value (columns read from files).
    Dynamic,
}

/// The rules, named as their Rust types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(clippy::enum_variant_names)]
pub enum RuleName {
    /// Weighted mean.
    Interpolate,
    /// Sum on merge, shared out on split.
    Conserved,
    /// Greatest value wins.
    Contagion,
    /// Kept only where all agree.
    Incompatible,
    /// The survivor's value.
    KeepFirst,
    /// Dropped.
    Discard,
    /// A Python rule object.
    PyRule,
    /// The dynamic rule of file columns.
    Dynamic,
}

impl RuleName {
    /// The Python name (`"keep_first"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            RuleName::Interpolate => "interpolate",
            RuleName::Conserved => "conserved",
            RuleName::Contagion => "contagion",
            RuleName::Incompatible => "incompatible",
            RuleName::KeepFirst => "keep_first",
            RuleName::Discard => "discard",
            RuleName::PyRule => "python",
            RuleName::Dynamic => "dynamic",
        }
    }

    /// The rule a column reports (`meshloom::attr::Rule::name`), if the
    /// bindings know it.
    pub fn of_rule_name(name: &str) -> Option<RuleName> {
        Some(match name {
            "Interpolate" => RuleName::Interpolate,
            "Conserved" => RuleName::Conserved,
            "Contagion" => RuleName::Contagion,
            "Incompatible" => RuleName::Incompatible,
            "KeepFirst" => RuleName::KeepFirst,
            "Discard" => RuleName::Discard,
            "Dynamic" => RuleName::Dynamic,
            n if n == <PyRule as Rule<PyValue>>::name() => RuleName::PyRule,
            _ => return None,
        })
    }

    /// A rule from its Python name.
    pub fn parse(s: &str) -> PyResult<RuleName> {
        Ok(match s {
            "interpolate" => RuleName::Interpolate,
            "conserved" => RuleName::Conserved,
            "contagion" => RuleName::Contagion,
            "incompatible" => RuleName::Incompatible,
            "keep_first" => RuleName::KeepFirst,
            "discard" => RuleName::Discard,
            other => {
                return Err(PyValueError::new_err(format!(
                    "unknown rule {other:?}: use interpolate, conserved, contagion, incompatible, keep_first, discard, or an object with merge and split methods"
                )))
            }
        })
    }
}

impl Dtype {
    /// The Python name.
    pub fn name(self) -> &'static str {
        match self {
            Dtype::Float => "float",
            Dtype::Int => "int",
            Dtype::Bool => "bool",
            Dtype::Vec2 => "vec2",
            Dtype::Vec3 => "vec3",
            Dtype::Vec4 => "vec4",
            Dtype::Text => "str",
            Dtype::Object => "object",
            Dtype::Dynamic => "dynamic",
        }
    }

    /// A dtype from `float`, `int`, `bool`, `str`, `object` (the types) or
    /// their names, `"vec2"`, `"vec3"`.
    pub fn parse(ob: &Bound<'_, PyAny>) -> PyResult<Dtype> {
        let name: String = if let Ok(t) = ob.cast::<PyType>() {
            t.name()?.to_string()
        } else if let Ok(s) = ob.cast::<PyString>() {
            s.to_string()
        } else {
            return Err(PyTypeError::new_err(
                "dtype is a type (float, int, bool, str, object) or a name (\"vec2\", \"vec3\")",
            ));
        };
        Ok(match name.as_str() {
            "float" | "f64" | "float64" => Dtype::Float,
            "int" | "i64" | "int64" => Dtype::Int,
            "bool" => Dtype::Bool,
            "vec2" => Dtype::Vec2,
            "vec3" => Dtype::Vec3,
            "vec4" => Dtype::Vec4,
            "str" => Dtype::Text,
            "object" => Dtype::Object,
            other => return Err(PyValueError::new_err(format!("unsupported dtype {other:?}: use float, int, bool, str, \"vec2\", \"vec3\", \"vec4\", or object with a Python rule"))),
        })
    }

    /// The dtype of a column whose values are of the Rust type named
    /// `type_name` (`std::any::type_name`, as `Mesh::attr_info` reports
    /// it), if the bindings offer it.
    pub fn of_type_name(type_name: &str) -> Option<Dtype> {
        use std::any::type_name as name;
        let dtypes = [
            (name::<f64>(), Dtype::Float),
            (name::<i64>(), Dtype::Int),
            (name::<bool>(), Dtype::Bool),
            (name::<[f64; 2]>(), Dtype::Vec2),
            (name::<[f64; 3]>(), Dtype::Vec3),
            (name::<[f64; 4]>(), Dtype::Vec4),
            (name::<String>(), Dtype::Text),
            (name::<PyValue>(), Dtype::Object),
            (name::<Value>(), Dtype::Dynamic),
        ];
        dtypes
            .into_iter()
            .find_map(|(n, d)| (n == type_name).then_some(d))
    }

    /// The rule a column of this type gets when none is named.
    pub fn default_rule(self) -> RuleName {
        match self {
            Dtype::Float | Dtype::Vec2 | Dtype::Vec3 | Dtype::Vec4 => RuleName::Interpolate,
            Dtype::Int | Dtype::Text => RuleName::Incompatible,
            Dtype::Bool => RuleName::Contagion,
            Dtype::Object => RuleName::PyRule,
            Dtype::Dynamic => RuleName::Dynamic,
        }
    }
}

/// An element kind from its Python name.
pub fn parse_kind(s: &str) -> PyResult<ElementKind> {
    Ok(match s {
        "vertex" => ElementKind::Vertex,
        "halfedge" | "corner" => ElementKind::Halfedge,
        "edge" => ElementKind::Edge,
        "face" => ElementKind::Face,
        other => {
            return Err(PyValueError::new_err(format!(
                "unknown element kind {other:?}: use vertex, halfedge, edge or face"
            )))
        }
    })
}

/// A Python value with the Python rule its column follows.
///
/// Each `PyValue` owns its references (a clone takes new ones), so a mesh's
/// `__traverse__` visits exactly the references its columns hold, even when
/// a copy of the mesh holds the same objects.
#[derive(Default)]
pub struct PyValue(pub Option<Box<Carried>>);

impl Clone for PyValue {
    fn clone(&self) -> Self {
        match &self.0 {
            None => PyValue(None),
            Some(c) => {
                Python::attach(|py| PyValue::new(c.rule.clone_ref(py), c.value.clone_ref(py)))
            }
        }
    }
}

/// What a [`PyValue`] holds.
pub struct Carried {
    /// The rule object (with `merge` and `split` methods).
    pub rule: Py<PyAny>,
    /// The value.
    pub value: Py<PyAny>,
}

impl PyValue {
    /// A value of a column with rule `rule`.
    pub fn new(rule: Py<PyAny>, value: Py<PyAny>) -> PyValue {
        PyValue(Some(Box::new(Carried { rule, value })))
    }
}

impl Attribute for PyValue {
    type Rule = PyRule;
}

/// The rule of Python-rule columns: calls the Python rule object; an
/// exception it raises fails the edit (see the module docs).
pub struct PyRule;

/// An exception a Python rule raised, as the rule's error. PyO3's own
/// refusal to lend a mesh an edit holds (a rule calling a method of its
/// mesh) becomes the package's `ReentrantError`.
fn rule_error(py: Python<'_>, err: PyErr) -> RuleError {
    let text = err.value(py).to_string();
    let err = if err.is_instance_of::<pyo3::exceptions::PyRuntimeError>(py)
        && text.starts_with("Already")
        && text.contains("borrowed")
    {
        let reentrant = crate::errors::busy(text);
        reentrant.set_cause(py, Some(err));
        reentrant
    } else {
        err
    };
    RuleError::from_source(err)
}

/// The value the rule object's `method` gives for `inputs`.
fn call_rule(
    method: &str,
    inputs: &[(Option<&PyValue>, f64)],
) -> Result<Option<PyValue>, RuleError> {
    let Some(carried) = inputs
        .iter()
        .find_map(|(v, _)| v.and_then(|v| v.0.as_ref()))
    else {
        return Ok(None);
    };
    Python::attach(|py| {
        let rule = carried.rule.bind(py);
        let values: Vec<Py<PyAny>> = inputs
            .iter()
            .map(|(v, _)| match v.and_then(|v| v.0.as_ref()) {
                Some(c) => c.value.clone_ref(py),
                None => py.None(),
            })
            .collect();
        let weights: Vec<f64> = inputs.iter().map(|(_, w)| *w).collect();
        let method = if method == "interpolate" && !rule.hasattr("interpolate").unwrap_or(false) {
            "merge"
        } else {
            method
        };
        match rule.call_method1(method, (values, weights)) {
            Ok(r) if r.is_none() => Ok(None),
            Ok(r) => Ok(Some(PyValue::new(carried.rule.clone_ref(py), r.unbind()))),
            Err(e) => Err(rule_error(py, e)),
        }
    })
}

impl Rule<PyValue> for PyRule {
    const FALLIBLE: bool = true;

    fn name() -> &'static str {
        "PyRule"
    }

    fn merge(inputs: &[(Option<&PyValue>, f64)]) -> Option<PyValue> {
        Self::try_merge(inputs).ok().flatten()
    }

    fn interpolate(inputs: &[(Option<&PyValue>, f64)]) -> Option<PyValue> {
        Self::try_interpolate(inputs).ok().flatten()
    }

    fn split(source: Option<&PyValue>, share: f64) -> Option<PyValue> {
        Self::try_split(source, share).ok().flatten()
    }

    fn try_merge(inputs: &[(Option<&PyValue>, f64)]) -> Result<Option<PyValue>, RuleError> {
        call_rule("merge", inputs)
    }

    fn try_interpolate(inputs: &[(Option<&PyValue>, f64)]) -> Result<Option<PyValue>, RuleError> {
        call_rule("interpolate", inputs)
    }

    fn try_split(source: Option<&PyValue>, share: f64) -> Result<Option<PyValue>, RuleError> {
        let Some(carried) = source.and_then(|s| s.0.as_ref()) else {
            return Ok(None);
        };
        Python::attach(|py| {
            match carried
                .rule
                .bind(py)
                .call_method1("split", (carried.value.clone_ref(py), share))
            {
                Ok(r) if r.is_none() => Ok(None),
                Ok(r) => Ok(Some(PyValue::new(carried.rule.clone_ref(py), r.unbind()))),
                Err(e) => Err(rule_error(py, e)),
            }
        })
    }
}

/// A key of kind `Self` from any key.
pub trait FromAny: Element {
    /// `None` if `key` is of another kind.
    fn from_any(key: AnyKey) -> Option<Self>;
    /// Every live element of the kind, in the order of `mesh.vertices`,
    /// `mesh.halfedges`, `mesh.edges`, `mesh.faces` (holes excluded).
    fn all(mesh: &Mesh) -> Vec<Self>;
    /// Every live element of the kind, holes included.
    fn all_with_holes(mesh: &Mesh) -> Vec<Self> {
        Self::all(mesh)
    }
}

macro_rules! from_any {
    ($($k:ident => $variant:ident, $all:ident);*) => {$(
        impl FromAny for $k {
            fn from_any(key: AnyKey) -> Option<Self> {
                match key {
                    AnyKey::$variant(k) => Some(k),
                    _ => None,
                }
            }
            fn all(mesh: &Mesh) -> Vec<Self> {
                mesh.$all().collect()
            }
        }
    )*};
}
from_any!(VertexKey => Vertex, vertices; HalfedgeKey => Halfedge, halfedges; EdgeKey => Edge, edges);

impl FromAny for FaceKey {
    fn from_any(key: AnyKey) -> Option<Self> {
        match key {
            AnyKey::Face(k) => Some(k),
            _ => None,
        }
    }
    fn all(mesh: &Mesh) -> Vec<Self> {
        mesh.faces().collect()
    }
    fn all_with_holes(mesh: &Mesh) -> Vec<Self> {
        mesh.faces_and_holes().collect()
    }
}

/// A value type that converts to and from Python.
pub trait PyAttr: Attribute {
    /// To a Python object.
    fn to_py(&self, py: Python<'_>) -> PyResult<Py<PyAny>>;
    /// From a Python object (`rule` is the column's rule for Python-rule
    /// columns).
    fn from_py(ob: &Bound<'_, PyAny>, rule: Option<&Py<PyAny>>) -> PyResult<Self>;
    /// A `fill=` value from a Python object: it only stands in for absent
    /// values in the array handed out, never enters the mesh.
    fn fill_from_py(ob: &Bound<'_, PyAny>) -> PyResult<Self> {
        Self::from_py(ob, None)
    }
    /// A whole column, in element order, as numpy (or a list).
    fn to_array(
        py: Python<'_>,
        values: Vec<Option<Self>>,
        fill: Option<Self>,
        name: &str,
    ) -> PyResult<Py<PyAny>> {
        let mut out = Vec::with_capacity(values.len());
        for v in values {
            match v.or_else(|| fill.clone()) {
                Some(v) => out.push(v.to_py(py)?),
                None => out.push(py.None()),
            }
        }
        let _ = name;
        Ok(PyList::new(py, out)?.into_any().unbind())
    }
    /// A whole column with every value present, as numpy (or a list).
    fn dense_to_array(py: Python<'_>, values: &[Self]) -> PyResult<Py<PyAny>> {
        Self::to_array(py, values.iter().cloned().map(Some).collect(), None, "")
    }
    /// A whole column from numpy with every value present, in element
    /// order, when the type has a quick path (numbers); `None` otherwise.
    fn dense_from_array(_ob: &Bound<'_, PyAny>, _n: usize) -> PyResult<Option<Vec<Self>>> {
        Ok(None)
    }
    /// A whole column from numpy (or a sequence), in element order.
    fn from_array(
        ob: &Bound<'_, PyAny>,
        n: usize,
        rule: Option<&Py<PyAny>>,
    ) -> PyResult<Vec<Option<Self>>> {
        let mut out = Vec::with_capacity(n);
        for item in ob.try_iter()? {
            let item = item?;
            out.push(if item.is_none() {
                None
            } else {
                Some(Self::from_py(&item, rule)?)
            });
        }
        Ok(out)
    }
}

fn absent_err(name: &str) -> PyErr {
    PyValueError::new_err(format!(
        "column {name:?} has elements without a value; pass fill= to stand in for them"
    ))
}

fn numeric_from<T: numpy::Element + Copy>(ob: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<T>> {
    let np = ob.py().import("numpy")?;
    let dtype = numpy::dtype::<T>(ob.py());
    let arr = np.call_method1("ascontiguousarray", (ob, dtype))?;
    let arr = arr
        .cast::<PyArray1<T>>()
        .map_err(|_| PyValueError::new_err("expected a 1-D array"))?;
    let ro: PyReadonlyArray1<T> = arr.readonly();
    let s = ro.as_slice()?;
    if s.len() != n {
        return Err(PyValueError::new_err(format!(
            "expected {n} values, got {}",
            s.len()
        )));
    }
    Ok(s.to_vec())
}

impl PyAttr for f64 {
    fn dense_from_array(ob: &Bound<'_, PyAny>, n: usize) -> PyResult<Option<Vec<Self>>> {
        let v = numeric_from::<f64>(ob, n)?;
        Ok((!v.iter().any(|x| x.is_nan())).then_some(v))
    }
    fn dense_to_array(py: Python<'_>, values: &[Self]) -> PyResult<Py<PyAny>> {
        Ok(PyArray1::from_slice(py, values).into_any().unbind())
    }
    fn to_py(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(self.into_pyobject(py)?.into_any().unbind())
    }
    fn from_py(ob: &Bound<'_, PyAny>, _: Option<&Py<PyAny>>) -> PyResult<Self> {
        ob.extract()
    }
    fn to_array(
        py: Python<'_>,
        values: Vec<Option<Self>>,
        fill: Option<Self>,
        _: &str,
    ) -> PyResult<Py<PyAny>> {
        let fill = fill.unwrap_or(f64::NAN);
        let v: Vec<f64> = values.into_iter().map(|x| x.unwrap_or(fill)).collect();
        Ok(PyArray1::from_vec(py, v).into_any().unbind())
    }
    fn from_array(
        ob: &Bound<'_, PyAny>,
        n: usize,
        _: Option<&Py<PyAny>>,
    ) -> PyResult<Vec<Option<Self>>> {
        Ok(numeric_from::<f64>(ob, n)?
            .into_iter()
            .map(|x| (!x.is_nan()).then_some(x))
            .collect())
    }
}

impl PyAttr for i64 {
    fn dense_from_array(ob: &Bound<'_, PyAny>, n: usize) -> PyResult<Option<Vec<Self>>> {
        numeric_from::<i64>(ob, n).map(Some)
    }
    fn dense_to_array(py: Python<'_>, values: &[Self]) -> PyResult<Py<PyAny>> {
        Ok(PyArray1::from_slice(py, values).into_any().unbind())
    }
    fn to_py(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(self.into_pyobject(py)?.into_any().unbind())
    }
    fn from_py(ob: &Bound<'_, PyAny>, _: Option<&Py<PyAny>>) -> PyResult<Self> {
        ob.extract()
    }
    fn to_array(
        py: Python<'_>,
        values: Vec<Option<Self>>,
        fill: Option<Self>,
        name: &str,
    ) -> PyResult<Py<PyAny>> {
        let v: Option<Vec<i64>> = values.into_iter().map(|x| x.or(fill)).collect();
        Ok(PyArray1::from_vec(py, v.ok_or_else(|| absent_err(name))?)
            .into_any()
            .unbind())
    }
    fn from_array(
        ob: &Bound<'_, PyAny>,
        n: usize,
        _: Option<&Py<PyAny>>,
    ) -> PyResult<Vec<Option<Self>>> {
        Ok(numeric_from::<i64>(ob, n)?.into_iter().map(Some).collect())
    }
}

impl PyAttr for bool {
    fn dense_from_array(ob: &Bound<'_, PyAny>, n: usize) -> PyResult<Option<Vec<Self>>> {
        numeric_from::<bool>(ob, n).map(Some)
    }
    fn dense_to_array(py: Python<'_>, values: &[Self]) -> PyResult<Py<PyAny>> {
        Ok(PyArray1::from_slice(py, values).into_any().unbind())
    }
    fn to_py(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(pyo3::types::PyBool::new(py, *self)
            .to_owned()
            .into_any()
            .unbind())
    }
    fn from_py(ob: &Bound<'_, PyAny>, _: Option<&Py<PyAny>>) -> PyResult<Self> {
        ob.extract()
    }
    fn to_array(
        py: Python<'_>,
        values: Vec<Option<Self>>,
        fill: Option<Self>,
        name: &str,
    ) -> PyResult<Py<PyAny>> {
        let v: Option<Vec<bool>> = values.into_iter().map(|x| x.or(fill)).collect();
        Ok(PyArray1::from_vec(py, v.ok_or_else(|| absent_err(name))?)
            .into_any()
            .unbind())
    }
    fn from_array(
        ob: &Bound<'_, PyAny>,
        n: usize,
        _: Option<&Py<PyAny>>,
    ) -> PyResult<Vec<Option<Self>>> {
        Ok(numeric_from::<bool>(ob, n)?.into_iter().map(Some).collect())
    }
}

macro_rules! vec_attr {
    ($n:literal) => {
        impl PyAttr for [f64; $n] {
            fn dense_from_array(ob: &Bound<'_, PyAny>, n: usize) -> PyResult<Option<Vec<Self>>> {
                Ok(Self::from_array(ob, n, None)?.into_iter().collect())
            }
            fn dense_to_array(py: Python<'_>, values: &[Self]) -> PyResult<Py<PyAny>> {
                let flat: &[f64] = values.as_flattened();
                Ok(PyArray1::from_slice(py, flat)
                    .reshape([values.len(), $n])?
                    .into_any()
                    .unbind())
            }
            fn to_py(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
                Ok(pyo3::types::PyTuple::new(py, self)?.into_any().unbind())
            }
            fn from_py(ob: &Bound<'_, PyAny>, _: Option<&Py<PyAny>>) -> PyResult<Self> {
                ob.extract()
            }
            fn to_array(
                py: Python<'_>,
                values: Vec<Option<Self>>,
                fill: Option<Self>,
                _: &str,
            ) -> PyResult<Py<PyAny>> {
                let fill = fill.unwrap_or([f64::NAN; $n]);
                let n = values.len();
                let flat: Vec<f64> = values.into_iter().flat_map(|x| x.unwrap_or(fill)).collect();
                let arr = PyArray1::from_vec(py, flat);
                Ok(arr.reshape([n, $n])?.into_any().unbind())
            }
            fn from_array(
                ob: &Bound<'_, PyAny>,
                n: usize,
                _: Option<&Py<PyAny>>,
            ) -> PyResult<Vec<Option<Self>>> {
                let np = ob.py().import("numpy")?;
                let arr =
                    np.call_method1("ascontiguousarray", (ob, numpy::dtype::<f64>(ob.py())))?;
                let arr = arr.cast::<PyArray2<f64>>().map_err(|_| {
                    PyValueError::new_err(concat!("expected an (n, ", $n, ") array"))
                })?;
                let ro: PyReadonlyArray2<f64> = arr.readonly();
                if ro.shape() != [n, $n] {
                    return Err(PyValueError::new_err(format!(
                        "expected shape ({n}, {}), got {:?}",
                        $n,
                        ro.shape()
                    )));
                }
                Ok(ro
                    .as_slice()?
                    .chunks_exact($n)
                    .map(|c| {
                        let v: [f64; $n] = std::array::from_fn(|i| c[i]);
                        (!v.iter().any(|x| x.is_nan())).then_some(v)
                    })
                    .collect())
            }
        }
    };
}
vec_attr!(2);
vec_attr!(3);
vec_attr!(4);

impl PyAttr for String {
    fn to_py(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(self.into_pyobject(py)?.into_any().unbind())
    }
    fn from_py(ob: &Bound<'_, PyAny>, _: Option<&Py<PyAny>>) -> PyResult<Self> {
        ob.extract()
    }
}

impl PyAttr for PyValue {
    fn to_py(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(match &self.0 {
            Some(c) => c.value.clone_ref(py),
            None => py.None(),
        })
    }
    fn from_py(ob: &Bound<'_, PyAny>, rule: Option<&Py<PyAny>>) -> PyResult<Self> {
        let rule =
            rule.ok_or_else(|| PyValueError::new_err("a Python-rule column without its rule"))?;
        Ok(PyValue::new(rule.clone_ref(ob.py()), ob.clone().unbind()))
    }
    fn fill_from_py(ob: &Bound<'_, PyAny>) -> PyResult<Self> {
        // Never merged or split: no rule needed.
        Ok(PyValue::new(ob.py().None(), ob.clone().unbind()))
    }
}

/// Dynamic values (from files) as Python numbers, strings and lists.
pub fn value_to_py(py: Python<'_>, v: &Value) -> PyResult<Py<PyAny>> {
    Ok(match v {
        Value::Bool(b) => b.to_py(py)?,
        Value::Text(s) => s.to_py(py)?,
        Value::List(items) => {
            let items: PyResult<Vec<Py<PyAny>>> =
                items.iter().map(|x| value_to_py(py, x)).collect();
            PyList::new(py, items?)?.into_any().unbind()
        }
        Value::F32(x) => f64::from(*x).to_py(py)?,
        Value::F64(x) => x.to_py(py)?,
        other => match other.as_f64() {
            Some(_) => {
                let i: i128 = match *other {
                    Value::I8(x) => x.into(),
                    Value::U8(x) => x.into(),
                    Value::I16(x) => x.into(),
                    Value::U16(x) => x.into(),
                    Value::I32(x) => x.into(),
                    Value::U32(x) => x.into(),
                    Value::I64(x) => x.into(),
                    Value::U64(x) => x.into(),
                    _ => 0,
                };
                i.into_pyobject(py)?.into_any().unbind()
            }
            None => py.None(),
        },
    })
}

impl PyAttr for Value {
    fn to_py(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        value_to_py(py, self)
    }
    fn from_py(ob: &Bound<'_, PyAny>, _: Option<&Py<PyAny>>) -> PyResult<Self> {
        if let Ok(b) = ob.extract::<bool>() {
            if ob.is_instance_of::<pyo3::types::PyBool>() {
                return Ok(Value::Bool(b));
            }
        }
        if let Ok(i) = ob.extract::<i64>() {
            return Ok(Value::I64(i));
        }
        if let Ok(x) = ob.extract::<f64>() {
            return Ok(Value::F64(x));
        }
        if let Ok(s) = ob.extract::<String>() {
            return Ok(Value::Text(s));
        }
        Err(PyTypeError::new_err(
            "a dynamic column takes bool, int, float or str values",
        ))
    }
}

/// Run `$f::<K, T, R>($args)` for the column type `($dtype, $rule)` of kind
/// `$kind`; a combination the bindings do not offer is a `TypeError`.
#[macro_export]
macro_rules! dispatch {
    ($kind:expr, $dtype:expr, $rule:expr, $f:ident $args:tt) => {{
        use meshloom::keys::ElementKind as EK;
        match $kind {
            EK::Vertex => $crate::dispatch_types!($dtype, $rule, $f, $args, meshloom::VertexKey),
            EK::Halfedge => {
                $crate::dispatch_types!($dtype, $rule, $f, $args, meshloom::HalfedgeKey)
            }
            EK::Edge => $crate::dispatch_types!($dtype, $rule, $f, $args, meshloom::EdgeKey),
            EK::Face => $crate::dispatch_types!($dtype, $rule, $f, $args, meshloom::FaceKey),
            #[allow(unreachable_patterns)]
            _ => Err(pyo3::exceptions::PyValueError::new_err(
                "unknown element kind",
            )),
        }
    }};
}

/// The value-type level of [`dispatch!`].
#[macro_export]
macro_rules! dispatch_types {
    ($dtype:expr, $rule:expr, $f:ident, $args:tt, $K:ty) => {{
        use $crate::attrs::Dtype as D;
        match $dtype {
            D::Float => $crate::dispatch_rules!(
                $dtype,
                $rule,
                $f,
                $args,
                $K,
                f64,
                [
                    Interpolate,
                    Conserved,
                    Contagion,
                    Incompatible,
                    KeepFirst,
                    Discard
                ]
            ),
            D::Vec2 => $crate::dispatch_rules!(
                $dtype,
                $rule,
                $f,
                $args,
                $K,
                [f64; 2],
                [Interpolate, Conserved, Incompatible, KeepFirst, Discard]
            ),
            D::Vec3 => $crate::dispatch_rules!(
                $dtype,
                $rule,
                $f,
                $args,
                $K,
                [f64; 3],
                [Interpolate, Conserved, Incompatible, KeepFirst, Discard]
            ),
            D::Vec4 => $crate::dispatch_rules!(
                $dtype,
                $rule,
                $f,
                $args,
                $K,
                [f64; 4],
                [Interpolate, Conserved, Incompatible, KeepFirst, Discard]
            ),
            D::Int => $crate::dispatch_rules!(
                $dtype,
                $rule,
                $f,
                $args,
                $K,
                i64,
                [Contagion, Incompatible, KeepFirst, Discard]
            ),
            D::Bool => $crate::dispatch_rules!(
                $dtype,
                $rule,
                $f,
                $args,
                $K,
                bool,
                [Contagion, Incompatible, KeepFirst, Discard]
            ),
            D::Text => $crate::dispatch_rules!(
                $dtype,
                $rule,
                $f,
                $args,
                $K,
                String,
                [Contagion, Incompatible, KeepFirst, Discard]
            ),
            D::Object => $crate::dispatch_rules!(
                $dtype,
                $rule,
                $f,
                $args,
                $K,
                $crate::attrs::PyValue,
                [PyRule]
            ),
            D::Dynamic => $crate::dispatch_rules!(
                $dtype,
                $rule,
                $f,
                $args,
                $K,
                meshloom::attr::Value,
                [Dynamic, KeepFirst, Discard]
            ),
        }
    }};
}

/// The rule level of [`dispatch!`].
#[macro_export]
macro_rules! dispatch_rules {
    ($dtype:expr, $rule:expr, $f:ident, $args:tt, $K:ty, $T:ty, [$($R:ident),*]) => {{
        #[allow(unused_imports)]
        use meshloom::attr::{Conserved, Contagion, Discard, Dynamic, Incompatible, Interpolate, KeepFirst};
        #[allow(unused_imports)]
        use $crate::attrs::PyRule;
        use $crate::attrs::RuleName as RN;
        match $rule {
            $(RN::$R => $f::<$K, $T, $R> $args,)*
            #[allow(unreachable_patterns)]
            other => Err($crate::attrs::combo_err($dtype, other)),
        }
    }};
}

/// The error for a type and rule the bindings do not combine.
pub fn combo_err(dtype: Dtype, rule: RuleName) -> PyErr {
    PyTypeError::new_err(format!(
        "a {} column cannot follow the rule {} (interpolate and conserved need float or vector values; vectors cannot be contagion)",
        dtype.name(),
        rule.name()
    ))
}

/// Whether [`dispatch!`] reached the column type of arena `kind` under the
/// rule named `rule` (a combination it does not offer is its `TypeError`).
fn offered<K: Element, T: Attribute, R: Rule<T>>(kind: ElementKind, rule: &str) -> PyResult<bool> {
    Ok(K::KIND == kind && R::name() == rule)
}

/// The dtype and rule of column `name` on arena `kind`, as
/// `Mesh::attr_info` names them, if it exists and the bindings offer that
/// combination.
pub fn column_type(mesh: &Mesh, kind: ElementKind, name: &str) -> Option<(Dtype, RuleName)> {
    let info = mesh.attr_info(kind).into_iter().find(|i| i.name == name)?;
    let dtype = Dtype::of_type_name(info.type_name)?;
    let rule = RuleName::of_rule_name(info.rule)?;
    dispatch!(kind, dtype, rule, offered(kind, info.rule))
        .unwrap_or(false)
        .then_some((dtype, rule))
}

/// Add a column.
pub fn add<K: Element, T: Attribute, R: Rule<T>>(
    mesh: &mut Mesh,
    name: &str,
) -> PyResult<meshloom::Result<()>> {
    Ok(mesh.add_attr_with_rule::<K, T, R>(name).map(|_| ()))
}

/// Remove a column.
pub fn remove<K: Element, T: Attribute, R: Rule<T>>(
    mesh: &mut Mesh,
    name: &str,
) -> PyResult<meshloom::Result<()>> {
    Ok(mesh
        .attr_handle::<K, T, R>(name)
        .and_then(|h| mesh.remove_attr(&h)))
}

/// One value, or None.
pub fn get_one<K: FromAny, T: PyAttr, R: Rule<T>>(
    py: Python<'_>,
    mesh: &Mesh,
    name: &str,
    key: AnyKey,
) -> PyResult<Result<Py<PyAny>, meshloom::Error>> {
    let k = K::from_any(key).ok_or_else(|| PyTypeError::new_err("key of another element kind"))?;
    let h = match mesh.attr_handle::<K, T, R>(name) {
        Ok(h) => h,
        Err(e) => return Ok(Err(e)),
    };
    Ok(match mesh.attr(&h, k) {
        Ok(Some(v)) => Ok(v.to_py(py)?),
        Ok(None) => Ok(py.None()),
        Err(e) => Err(e),
    })
}

/// Set (or with None clear) one value.
pub fn set_one<K: FromAny, T: PyAttr, R: Rule<T>>(
    mesh: &mut Mesh,
    name: &str,
    key: AnyKey,
    value: &Bound<'_, PyAny>,
    rule: Option<&Py<PyAny>>,
) -> PyResult<Result<(), meshloom::Error>> {
    let k = K::from_any(key).ok_or_else(|| PyTypeError::new_err("key of another element kind"))?;
    let h = match mesh.attr_handle::<K, T, R>(name) {
        Ok(h) => h,
        Err(e) => return Ok(Err(e)),
    };
    if value.is_none() {
        return Ok(mesh.clear_attr(&h, k).map(|_| ()));
    }
    let v = T::from_py(value, rule)?;
    Ok(mesh.set_attr(&h, k, v))
}

/// The whole column in element order (the order of `mesh.vertices`, ...;
/// faces without holes).
pub fn get_all<K: FromAny, T: PyAttr, R: Rule<T>>(
    py: Python<'_>,
    mesh: &Mesh,
    name: &str,
    fill: Option<&Bound<'_, PyAny>>,
) -> PyResult<Result<Py<PyAny>, meshloom::Error>> {
    let h = match mesh.attr_handle::<K, T, R>(name) {
        Ok(h) => h,
        Err(e) => return Ok(Err(e)),
    };
    let view = match mesh.attr_view(&h) {
        Ok(v) => v,
        Err(e) => return Ok(Err(e)),
    };
    let count = element_count::<K>(mesh);
    // Every slot live and valued, and no hole among them: one copy.
    if let Some(s) = view.dense_slice().filter(|s| s.len() == count) {
        return Ok(Ok(T::dense_to_array(py, s)?));
    }
    let fill = fill.map(|f| T::fill_from_py(f)).transpose()?;
    let values: Vec<Option<T>> = K::all(mesh)
        .into_iter()
        .map(|k| view.get(k).cloned())
        .collect();
    Ok(Ok(T::to_array(py, values, fill, name)?))
}

/// Set the whole column from an array in element order.
pub fn set_all<K: FromAny, T: PyAttr, R: Rule<T>>(
    mesh: &mut Mesh,
    name: &str,
    values: &Bound<'_, PyAny>,
    rule: Option<&Py<PyAny>>,
) -> PyResult<Result<(), meshloom::Error>> {
    let h = match mesh.attr_handle::<K, T, R>(name) {
        Ok(h) => h,
        Err(e) => return Ok(Err(e)),
    };
    let count = element_count::<K>(mesh);
    // Numbers with every value present: converted once, written with one
    // copy when no slot is vacant.
    if let Some(dense) = T::dense_from_array(values, count)? {
        let mut view = match mesh.attr_view_mut(&h) {
            Ok(v) => v,
            Err(e) => return Ok(Err(e)),
        };
        match view.set_slots(&dense) {
            Ok(true) => return Ok(Ok(())),
            Ok(false) => {}
            Err(e) => return Ok(Err(e)),
        }
    }
    let vals = T::from_array(values, count, rule)?;
    if vals.len() != count {
        return Err(PyValueError::new_err(format!(
            "expected {count} values, got {}",
            vals.len()
        )));
    }
    let mut view = match mesh.attr_view_mut(&h) {
        Ok(v) => v,
        Err(e) => return Ok(Err(e)),
    };
    // Every value present, one per slot, no vacant slot: one copy.
    if vals.iter().all(Option::is_some) {
        let dense: Vec<T> = vals.iter().flatten().cloned().collect();
        match view.set_slots(&dense) {
            Ok(true) => return Ok(Ok(())),
            Ok(false) => {}
            Err(e) => return Ok(Err(e)),
        }
    }
    let keys = K::all(mesh);
    let mut view = match mesh.attr_view_mut(&h) {
        Ok(v) => v,
        Err(e) => return Ok(Err(e)),
    };
    for (k, v) in keys.into_iter().zip(vals) {
        if let Err(e) = view.set(k, v) {
            return Ok(Err(e));
        }
    }
    Ok(Ok(()))
}

/// The number of elements `attr_array` reads for `K` (faces: holes not
/// counted).
fn element_count<K: Element>(mesh: &Mesh) -> usize {
    match K::KIND {
        ElementKind::Vertex => mesh.vertex_count(),
        ElementKind::Halfedge => mesh.halfedge_count(),
        ElementKind::Edge => mesh.edge_count(),
        _ => mesh.face_count(),
    }
}

/// The rule object of a Python-rule column, from any of its values.
pub fn find_rule<K: FromAny>(py: Python<'_>, mesh: &Mesh, name: &str) -> Option<Py<PyAny>> {
    let h = mesh.attr_handle::<K, PyValue, PyRule>(name).ok()?;
    let view = mesh.attr_view(&h).ok()?;
    let found = view
        .iter()
        .find_map(|(_, v)| v.0.as_ref().map(|c| c.rule.clone_ref(py)));
    found
}
