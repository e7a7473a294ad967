//! The geometry algorithms from Python: normals, curvature, subdivision,
//! smoothing, fairing, decimation and level-of-detail chains. Keyword
//! options mirror the Rust options structs (angles in radians, as there);
//! results are numpy arrays in element order (`mesh.vertices`,
//! `mesh.halfedges`, `mesh.faces`) and reports are dicts. Every algorithm
//! that changes the mesh runs through the same all-or-nothing door as the
//! operators (`mesh::edit`): an error, a cancellation or a Python rule that
//! raised leaves the mesh as it was, and attribute columns follow by rule.

use crate::errors::busy;
use std::cell::RefCell;

use meshloom::algo::curvature::{add_curvature, curvature, BoundaryCurvature, CurvatureOptions};
use meshloom::algo::decimate::{decimate, lod_chain, Keep, LodOptions, Target};
use meshloom::algo::fair::{fair, FairOptions, FairRegion};
use meshloom::algo::fill_hole::{fill_holes, FillHoleOptions};
use meshloom::algo::laplacian::LaplaceWeights;
use meshloom::algo::remesh::{remesh, RemeshOptions, Resample, Sizing};
use meshloom::algo::smooth::{smooth, SmoothMethod, SmoothOptions};
use meshloom::algo::subdivision::SubdivisionReport;
use meshloom::algo::{
    add_corner_normals, add_face_normals, add_vertex_normals, corner_normals, face_normals,
    subdivide, vertex_normals, CornerNormalOptions, DecimateOptions, DecimateReport, Flow,
    NormalWeight, Progress, ProgressInfo, Scheme, SubdivisionOptions, VertexInterpolation,
    VertexNormalOptions,
};
use meshloom::algo::{Constraints, DEFAULT_MAX_FACES};
use meshloom::attr::{Attr, Contagion, Element, VertexAttr};
use meshloom::choice::UnknownChoice;
use meshloom::{Mesh, VertexKey};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::elements::PyVertex;
use crate::mesh::{edit, PyMesh};

/// A dict of a report's named fields: `fields_dict!(py, r; moved, fixed)`
/// is `{"moved": r.moved, "fixed": r.fixed}` (returns early on an error).
macro_rules! fields_dict {
    ($py:expr, $r:expr; $($field:ident),* $(,)?) => {{
        let d = PyDict::new($py);
        $(d.set_item(stringify!($field), $r.$field)?;)*
        d
    }};
}

/// A temporary boolean vertex column made from a numpy mask, removed again
/// inside the same edit.
const TEMP_MASK: &str = "__meshloom_mask";

/// A progress callback from Python: called with a dict (`algorithm`,
/// `stage`, `done`, `total`); returning `False` cancels. An exception it
/// raises cancels too and is kept here to be raised instead of
/// `CancelledError`.
struct Callback<'py> {
    f: Option<Bound<'py, PyAny>>,
    raised: RefCell<Option<PyErr>>,
}

impl<'py> Callback<'py> {
    fn new(f: Option<Bound<'py, PyAny>>) -> PyResult<Self> {
        if let Some(f) = &f {
            if !f.is_callable() {
                return Err(PyTypeError::new_err(
                    "progress must be a callable taking a dict and returning False to cancel",
                ));
            }
        }
        Ok(Callback {
            f,
            raised: RefCell::new(None),
        })
    }

    fn call(&self, info: &ProgressInfo<'_>) -> Flow {
        let Some(f) = &self.f else {
            return Flow::Continue;
        };
        let py = f.py();
        let answer = (|| -> PyResult<bool> {
            let d = fields_dict!(py, info; algorithm, stage, done, total);
            let r = f.call1((d,))?;
            Ok(!r.is_instance_of::<pyo3::types::PyBool>() || r.is_truthy()?)
        })();
        match answer {
            Ok(true) => Flow::Continue,
            Ok(false) => Flow::Cancel,
            Err(e) => {
                self.raised.borrow_mut().get_or_insert(e);
                Flow::Cancel
            }
        }
    }

    /// Run `f` with a `Progress` that calls back (or none).
    fn run<R>(&self, f: impl FnOnce(Progress<'_>) -> meshloom::Result<R>) -> meshloom::Result<R> {
        if self.f.is_none() {
            return f(Progress::none());
        }
        let mut cb = |info: &ProgressInfo<'_>| self.call(info);
        f(Progress::new(&mut cb))
    }

    /// The callback's own exception, if it raised, in place of `result`'s.
    fn finish<R>(&self, result: PyResult<R>) -> PyResult<R> {
        match (result, self.raised.borrow_mut().take()) {
            (Err(_), Some(e)) => Err(e),
            (r, _) => r,
        }
    }
}

/// An option enum read from its library words (`FromStr`); an unknown
/// word raises `ValueError` listing the words.
pub(crate) fn parse_word<T: std::str::FromStr<Err = UnknownChoice>>(s: &str) -> PyResult<T> {
    s.parse()
        .map_err(|e: UnknownChoice| PyValueError::new_err(e.to_string()))
}

/// `(n, 3)` float64 array of `values[slot]` for each element's slot.
fn rows_by_slot<'py>(
    py: Python<'py>,
    values: &[[f64; 3]],
    slots: impl Iterator<Item = u32>,
) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f64> = slots
        .flat_map(|s| values.get(s as usize).copied().unwrap_or([f64::NAN; 3]))
        .collect();
    let n = flat.len() / 3;
    Ok(PyArray1::from_vec(py, flat).reshape([n, 3])?.into_any())
}

fn by_slot<'py>(
    py: Python<'py>,
    values: &[f64],
    slots: impl Iterator<Item = u32>,
) -> Bound<'py, PyAny> {
    let v: Vec<f64> = slots
        .map(|s| values.get(s as usize).copied().unwrap_or(f64::NAN))
        .collect();
    PyArray1::from_vec(py, v).into_any()
}

/// A bool vertex column named by `mask`: a column name, or a numpy bool
/// array in vertex order (written to a temporary column).
enum Mask {
    None,
    Column(String),
    Array(Vec<bool>),
}

fn mask_of(mask: Option<&Bound<'_, PyAny>>) -> PyResult<Mask> {
    let Some(m) = mask else {
        return Ok(Mask::None);
    };
    if m.is_none() {
        return Ok(Mask::None);
    }
    if let Ok(s) = m.extract::<String>() {
        return Ok(Mask::Column(s));
    }
    let np = m.py().import("numpy")?;
    let arr = np.call_method1("asarray", (m, "bool"))?;
    let v: Vec<bool> = arr.call_method0("tolist")?.extract()?;
    Ok(Mask::Array(v))
}

/// The handle of the boolean column (a vertex mask, locked vertices, hard
/// or feature edges) a keyword names, or `None` when the keyword was not
/// given. One lookup for every algorithm keyword that names a flag column.
pub(crate) fn flag_column<K: Element>(
    mesh: &Mesh,
    name: Option<&str>,
) -> meshloom::Result<Option<Attr<K, bool, Contagion>>> {
    name.map(|n| mesh.attr_handle::<K, bool, Contagion>(n))
        .transpose()
}

/// The mask's column handle, adding the temporary column `temp` for an
/// array.
fn mask_handle(
    mesh: &mut Mesh,
    mask: &Mask,
    temp: &str,
) -> meshloom::Result<Option<VertexAttr<bool>>> {
    match mask {
        Mask::None => Ok(None),
        Mask::Column(name) => flag_column::<VertexKey>(mesh, Some(name)),
        Mask::Array(values) => {
            let keys: Vec<VertexKey> = mesh.vertices().collect();
            if values.len() != keys.len() {
                return Err(meshloom::Error::Unsuitable {
                    algorithm: "mask",
                    key: None,
                    reason: format!(
                        "a mask of {} values for {} vertices",
                        values.len(),
                        keys.len()
                    ),
                });
            }
            let h = mesh.add_vertex_attr::<bool>(temp)?;
            let mut view = mesh.attr_view_mut(&h)?;
            for (k, &b) in keys.iter().zip(values) {
                view.set(*k, Some(b))?;
            }
            Ok(Some(h))
        }
    }
}

fn drop_mask(mesh: &mut Mesh, h: Option<VertexAttr<bool>>, mask: &Mask) {
    if let (Some(h), Mask::Array(_)) = (h, mask) {
        let _ = mesh.remove_attr(&h);
    }
}

/// The complement of a mask, as an array in vertex order (a column is read
/// from `mesh`).
fn complement(mesh: &Mesh, mask: &Mask) -> meshloom::Result<Mask> {
    Ok(match mask {
        Mask::None => Mask::None,
        Mask::Array(values) => Mask::Array(values.iter().map(|b| !b).collect()),
        Mask::Column(name) => {
            let h = mesh.attr_handle::<VertexKey, bool, Contagion>(name)?;
            let view = mesh.attr_view(&h)?;
            Mask::Array(
                mesh.vertices()
                    .map(|v| view.get(v) != Some(&true))
                    .collect(),
            )
        }
    })
}

/// A temporary bool vertex column holding an array given for `pinned`.
const TEMP_PINNED: &str = "__meshloom_pinned";

/// Warn (`DeprecationWarning`) that the keyword `old` is replaced by `new`.
fn deprecated(py: Python<'_>, old: &str, new: &str) -> PyResult<()> {
    let message = std::ffi::CString::new(format!("{old} is deprecated; use {new}"))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let category = py.get_type::<pyo3::exceptions::PyDeprecationWarning>();
    PyErr::warn(py, &category, &message, 1)
}

/// A word of `Keep` ("free", "slide", "lock"), read by the library's own
/// parser; `None` when the keyword was not given.
fn keep_word(ob: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<Keep>> {
    let Some(ob) = ob.filter(|o| !o.is_none()) else {
        return Ok(None);
    };
    let word: String = ob.extract().map_err(|_| {
        PyTypeError::new_err(format!("{what} is one of {}", Keep::WORDS.join(", ")))
    })?;
    word.parse::<Keep>()
        .map(Some)
        .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))
}

/// An old keyword that took `True`/`False` or a word: a word passes
/// through, `True` is `if_true`, `False` is free; with a warning naming
/// the new keyword.
fn old_keep(
    py: Python<'_>,
    ob: Option<&Bound<'_, PyAny>>,
    old: &str,
    new: &str,
    if_true: Keep,
) -> PyResult<Option<Keep>> {
    let Some(ob) = ob.filter(|o| !o.is_none()) else {
        return Ok(None);
    };
    let k = match ob.extract::<bool>() {
        Ok(b) => Some(if b { if_true } else { Keep::Free }),
        Err(_) => keep_word(Some(ob), old)?,
    };
    let shown = k.map_or(String::new(), |k| k.word().to_owned());
    deprecated(py, old, &format!("{new}=\"{shown}\""))?;
    Ok(k)
}

/// The constraint keywords every algorithm takes, in the words of
/// `meshloom::algo::Constraints`: `boundary` and `seams` (`"free"`,
/// `"slide"`, `"lock"`), `feature_angle` (radians), `features` (a bool
/// edge column name), `pinned` (a bool vertex column name or array: true =
/// never moves). `None` leaves the algorithm's default.
struct KeepKw {
    boundary: Option<Keep>,
    seams: Option<Keep>,
    feature_angle: Option<f64>,
    features: Option<String>,
    pinned: Mask,
}

impl KeepKw {
    fn new(
        boundary: Option<&Bound<'_, PyAny>>,
        seams: Option<&Bound<'_, PyAny>>,
        feature_angle: Option<f64>,
        features: Option<String>,
        pinned: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<KeepKw> {
        Ok(KeepKw {
            boundary: keep_word(boundary, "boundary")?,
            seams: keep_word(seams, "seams")?,
            feature_angle,
            features,
            pinned: mask_of(pinned)?,
        })
    }

    /// Take an old keyword naming a column (`locked`, `feature_edges`) in
    /// place of the new one, with a warning.
    fn old_column(
        py: Python<'_>,
        new: &mut Option<String>,
        old: Option<String>,
        old_name: &str,
        new_name: &str,
    ) -> PyResult<()> {
        if let Some(name) = old {
            deprecated(py, old_name, new_name)?;
            new.get_or_insert(name);
        }
        Ok(())
    }

    /// `c` with these keywords over it, the columns looked up on `mesh` by
    /// name (an array given for `pinned` is left to [`KeepKw::apply`]).
    fn apply_named(&self, mesh: &Mesh, mut c: Constraints) -> meshloom::Result<Constraints> {
        if let Some(k) = self.boundary {
            c.boundary = k;
        }
        if let Some(k) = self.seams {
            c.seams = k;
        }
        if self.feature_angle.is_some() {
            c.feature_angle = self.feature_angle;
        }
        if self.features.is_some() {
            c.features = flag_column(mesh, self.features.as_deref())?;
        }
        if let Mask::Column(name) = &self.pinned {
            c.pinned = flag_column(mesh, Some(name))?;
        }
        Ok(c)
    }

    /// As [`KeepKw::apply_named`], an array given for `pinned` written to
    /// a temporary column, whose handle comes back to be dropped with
    /// [`drop_mask`].
    fn apply(
        &self,
        mesh: &mut Mesh,
        c: Constraints,
    ) -> meshloom::Result<(Constraints, Option<VertexAttr<bool>>)> {
        let mut c = self.apply_named(mesh, c)?;
        let mut temp = None;
        if let Mask::Array(_) = self.pinned {
            temp = mask_handle(mesh, &self.pinned, TEMP_PINNED)?;
            c.pinned = temp.clone();
        }
        Ok((c, temp))
    }
}

fn counts_dict<'py>(py: Python<'py>, c: &meshloom::algo::Counts) -> PyResult<Bound<'py, PyDict>> {
    let d = fields_dict!(py, c; vertices, edges, faces, holes);
    Ok(d)
}

fn subdivision_report<'py>(py: Python<'py>, r: &SubdivisionReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("scheme", r.scheme.word())?;
    d.set_item("input", counts_dict(py, &r.input)?)?;
    d.set_item("output", counts_dict(py, &r.output)?)?;
    let levels = PyList::empty(py);
    for l in &r.levels {
        let ld = counts_dict(py, &l.output)?;
        ld.set_item("sharp_edges", l.sharp_edges)?;
        ld.set_item("crease_vertices", l.crease_vertices)?;
        ld.set_item("corner_vertices", l.corner_vertices)?;
        ld.set_item("blended_vertices", l.blended_vertices)?;
        levels.append(ld)?;
    }
    d.set_item("levels", levels)?;
    Ok(d)
}

fn decimate_report<'py>(py: Python<'py>, r: &DecimateReport) -> PyResult<Bound<'py, PyDict>> {
    // Python's words use `_` where the library's use `-`.
    let stopped = r.stopped_by.word().replace('-', "_");
    let d = fields_dict!(py, r; error, collapses, passes, fixed);
    d.set_item("input", counts_dict(py, &r.input)?)?;
    d.set_item("output", counts_dict(py, &r.output)?)?;
    d.set_item("stopped_by", stopped)?;
    d.set_item(
        "refused",
        fields_dict!(py, r.refused; topology, normal, quality, valence),
    )?;
    Ok(d)
}

/// A decimation target: one of `ratio`, `vertices`, `faces`, or none
/// (then `max_error` alone stops).
fn target_of(
    ratio: Option<f64>,
    vertices: Option<usize>,
    faces: Option<usize>,
    max_error: Option<f64>,
) -> PyResult<Target> {
    match (ratio, vertices, faces) {
        (Some(r), None, None) => Ok(Target::Ratio(r)),
        (None, Some(v), None) => Ok(Target::Vertices(v)),
        (None, None, Some(f)) => Ok(Target::Faces(f)),
        (None, None, None) if max_error.is_some() => Ok(Target::None),
        (None, None, None) => Ok(Target::Ratio(0.5)),
        _ => Err(PyValueError::new_err(
            "give at most one of ratio, vertices and faces",
        )),
    }
}

/// Decimation options from the keywords shared by `decimate` and
/// `lod_chain` (columns by name; their handles are looked up on the mesh).
struct DecimateKw {
    max_error: Option<f64>,
    max_normal_deviation: Option<f64>,
    min_quality: Option<f64>,
    max_valence: Option<usize>,
    keep: KeepKw,
    material: Option<String>,
    attributes: Vec<(String, f64)>,
}

impl DecimateKw {
    /// The options but the constraints.
    fn base(&self, target: Target) -> DecimateOptions {
        DecimateOptions::default()
            .target(target)
            .max_error(self.max_error)
            .max_normal_deviation(self.max_normal_deviation)
            .min_quality(self.min_quality)
            .max_valence(self.max_valence)
            .material(self.material.clone())
            .attributes(
                self.attributes
                    .iter()
                    .map(|(name, weight)| meshloom::algo::decimate::AttributeWeight {
                        name: name.clone(),
                        weight: *weight,
                    })
                    .collect(),
            )
    }

    /// The options, and the temporary pinned column to drop (an array).
    fn options(
        &self,
        mesh: &mut Mesh,
        target: Target,
    ) -> meshloom::Result<(DecimateOptions, Option<VertexAttr<bool>>)> {
        let o = self.base(target);
        let (c, temp) = self.keep.apply(mesh, o.constraints())?;
        Ok((o.with_constraints(c), temp))
    }

    /// The options of a chain over `mesh`, which is not changed (columns
    /// by name only).
    fn lod_options(&self, mesh: &Mesh) -> meshloom::Result<DecimateOptions> {
        let o = self.base(Target::Ratio(0.5));
        let c = self.keep.apply_named(mesh, o.constraints())?;
        Ok(o.with_constraints(c))
    }
}

/// The old constraint keywords of `decimate` and `lod_chain`, each mapped
/// to the new one with a `DeprecationWarning`: `keep_boundary` and
/// `keep_seams` (`True` = lock), `locked`, `feature_edges`.
struct OldDecimateKw<'a, 'py> {
    keep_boundary: Option<&'a Bound<'py, PyAny>>,
    keep_seams: Option<&'a Bound<'py, PyAny>>,
    locked: Option<String>,
    feature_edges: Option<String>,
}

impl OldDecimateKw<'_, '_> {
    fn onto(self, py: Python<'_>, keep: &mut KeepKw) -> PyResult<()> {
        let b = old_keep(
            py,
            self.keep_boundary,
            "keep_boundary",
            "boundary",
            Keep::Lock,
        )?;
        keep.boundary = keep.boundary.or(b);
        let s = old_keep(py, self.keep_seams, "keep_seams", "seams", Keep::Lock)?;
        keep.seams = keep.seams.or(s);
        if let Some(name) = self.locked {
            deprecated(py, "locked", "pinned")?;
            if matches!(keep.pinned, Mask::None) {
                keep.pinned = Mask::Column(name);
            }
        }
        KeepKw::old_column(
            py,
            &mut keep.features,
            self.feature_edges,
            "feature_edges",
            "features",
        )
    }
}

#[allow(clippy::too_many_arguments)]
fn decimate_kw(
    max_error: Option<f64>,
    max_normal_deviation: Option<f64>,
    min_quality: Option<f64>,
    max_valence: Option<usize>,
    keep: KeepKw,
    material: Option<String>,
    attributes: Option<&Bound<'_, PyDict>>,
) -> PyResult<DecimateKw> {
    let attributes = match attributes {
        Some(d) => d
            .iter()
            .map(|(k, v)| Ok((k.extract::<String>()?, v.extract::<f64>()?)))
            .collect::<PyResult<Vec<_>>>()?,
        None => Vec::new(),
    };
    Ok(DecimateKw {
        max_error,
        max_normal_deviation,
        min_quality,
        max_valence,
        keep,
        material,
        attributes,
    })
}

/// The targets of `lod_chain`: ratios or dicts `{"vertices": n}`,
/// `{"faces": n}`, `{"ratio": r}` (default: `LodOptions`').
fn lod_targets(targets: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<Target>> {
    let Some(t) = targets else {
        return Ok(LodOptions::default().targets);
    };
    t.try_iter()?
        .map(|item| {
            let item = item?;
            if let Ok(r) = item.extract::<f64>() {
                return Ok(Target::Ratio(r));
            }
            let d = item.cast::<PyDict>().map_err(|_| {
                PyTypeError::new_err(
                    "a target is a ratio or a dict {\"vertices\": n} or {\"faces\": n}",
                )
            })?;
            if let Some(v) = d.get_item("vertices")? {
                return Ok(Target::Vertices(v.extract()?));
            }
            if let Some(f) = d.get_item("faces")? {
                return Ok(Target::Faces(f.extract()?));
            }
            if let Some(r) = d.get_item("ratio")? {
                return Ok(Target::Ratio(r.extract()?));
            }
            Err(PyValueError::new_err(
                "a target dict has \"vertices\", \"faces\" or \"ratio\"",
            ))
        })
        .collect()
}

/// Which columns `remesh` resamples: `"linear"` (or None), `"off"`, or a
/// list of column names.
fn resample_of(resample: Option<&Bound<'_, PyAny>>) -> PyResult<Resample> {
    let Some(r) = resample.filter(|r| !r.is_none()) else {
        return Ok(Resample::Linear);
    };
    if let Ok(s) = r.extract::<String>() {
        return match s.as_str() {
            "linear" => Ok(Resample::Linear),
            "off" => Ok(Resample::Off),
            other => Err(PyValueError::new_err(format!(
                "resample is \"linear\", \"off\" or a list of column names, not {other:?}"
            ))),
        };
    }
    Ok(Resample::Columns(r.extract::<Vec<String>>().map_err(
        |_| PyTypeError::new_err("resample is \"linear\", \"off\" or a list of column names"),
    )?))
}

/// A fair region given as a list (or tuple) of `Vertex` keys of this
/// mesh; `None` for anything else (a column name, an array, None).
fn region_keys(
    slf: &Bound<'_, PyMesh>,
    region: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<Vec<VertexKey>>> {
    let Some(r) = region else {
        return Ok(None);
    };
    if r.cast::<PyList>().is_err() && !r.is_instance_of::<pyo3::types::PyTuple>() {
        return Ok(None);
    }
    let mut out = Vec::new();
    for item in r.try_iter()? {
        let item = item?;
        match item.cast::<PyVertex>() {
            Ok(v) => {
                let v = v.get();
                if !v.mesh.is(slf) {
                    return Err(PyValueError::new_err(format!(
                        "{:?} belongs to another mesh",
                        v.key
                    )));
                }
                out.push(v.key);
            }
            Err(_) => return Ok(None),
        }
    }
    Ok((!out.is_empty()).then_some(out))
}

const DEFAULT_NORMAL_DEVIATION: f64 = 75.0 * std::f64::consts::PI / 180.0;
const DEFAULT_CREASE: f64 = 30.0 * std::f64::consts::PI / 180.0;

#[pymethods]
impl PyMesh {
    /// Normals as an (n, 3) float64 array. `kind`: `"face"` (one per face,
    /// in the order of `faces`), `"vertex"` (in the order of `vertices`,
    /// faces weighted by `weight`: `"angle"`, `"area"` or `"uniform"`) or
    /// `"corner"` (one per half-edge, in the order of `halfedges`, split
    /// at feature edges: where faces meet at more than `feature_angle`
    /// radians (None: never) or where the bool edge column `features` is
    /// true). `store=True` also writes them to the column `"normal"` of
    /// that kind (half-edges for corners), which then follows edits by
    /// interpolation. `crease_angle` and `hard_edges` are the deprecated
    /// names of `feature_angle` and `features`.
    #[pyo3(signature = (kind = "vertex", *, weight = "angle", feature_angle = Some(DEFAULT_CREASE), features = None, store = false, crease_angle = None, hard_edges = None))]
    #[allow(clippy::too_many_arguments)]
    fn normals(
        slf: &Bound<'_, Self>,
        kind: &str,
        weight: &str,
        feature_angle: Option<f64>,
        features: Option<String>,
        store: bool,
        crease_angle: Option<&Bound<'_, PyAny>>,
        hard_edges: Option<String>,
    ) -> PyResult<Py<PyAny>> {
        let py = slf.py();
        let weight: NormalWeight = parse_word(weight)?;
        let mut feature_angle = feature_angle;
        if let Some(a) = crease_angle {
            deprecated(py, "crease_angle", "feature_angle")?;
            feature_angle = a.extract()?;
        }
        let mut features = features;
        KeepKw::old_column(py, &mut features, hard_edges, "hard_edges", "features")?;
        let corner = |m: &Mesh| -> meshloom::Result<CornerNormalOptions> {
            Ok(CornerNormalOptions::default()
                .weight(weight)
                .feature_angle(feature_angle)
                .features(flag_column(m, features.as_deref())?))
        };
        let vertex = VertexNormalOptions::default().weight(weight);
        if store {
            match kind {
                "face" => edit(slf, |m| add_face_normals(m).map(drop))?,
                "vertex" => edit(slf, |m| add_vertex_normals(m, &vertex).map(drop))?,
                "corner" | "halfedge" => edit(slf, |m| {
                    let o = corner(m)?;
                    add_corner_normals(m, &o).map(drop)
                })?,
                _ => {}
            }
        }
        let this = slf.try_borrow().map_err(busy)?;
        let m = &this.mesh;
        let err = |e| crate::errors::mesh_err(py, &slf.clone().unbind(), e);
        let out = match kind {
            "face" => {
                let n = face_normals(m).map_err(err)?;
                rows_by_slot(py, &n, m.faces().map(|k| k.slot()))?
            }
            "vertex" => {
                let n = vertex_normals(m, &vertex).map_err(err)?;
                rows_by_slot(py, &n, m.vertices().map(|k| k.slot()))?
            }
            "corner" | "halfedge" => {
                let o = corner(m).map_err(err)?;
                let n = corner_normals(m, &o).map_err(err)?;
                rows_by_slot(py, &n, m.halfedges().map(|k| k.slot()))?
            }
            other => {
                return Err(PyValueError::new_err(format!(
                    "kind is \"face\", \"vertex\" or \"corner\", not {other:?}"
                )))
            }
        };
        Ok(out.unbind())
    }

    /// Mean, Gaussian and principal curvatures of every vertex (cotangent
    /// Laplacian and angle defect): a dict of (n,) float64 arrays `mean`,
    /// `gaussian`, `min`, `max` and `area` (the mixed Voronoi area), in the
    /// order of `vertices`. `boundary`: `"from_interior"` (boundary vertices
    /// get their interior neighbours' average) or `"one_sided"`.
    /// `store=True` also writes the vertex columns `mean_curvature`,
    /// `gaussian_curvature`, `min_curvature` and `max_curvature`.
    #[pyo3(signature = (*, boundary = "from_interior", store = false))]
    fn curvature(slf: &Bound<'_, Self>, boundary: &str, store: bool) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let options =
            CurvatureOptions::default().boundary(parse_word::<BoundaryCurvature>(boundary)?);
        if store {
            edit(slf, |m| add_curvature(m, &options).map(drop))?;
        }
        let this = slf.try_borrow().map_err(busy)?;
        let m = &this.mesh;
        let c = curvature(m, &options)
            .map_err(|e| crate::errors::mesh_err(py, &slf.clone().unbind(), e))?;
        let slots: Vec<u32> = m.vertices().map(|k| k.slot()).collect();
        let d = PyDict::new(py);
        d.set_item("mean", by_slot(py, &c.mean, slots.iter().copied()))?;
        d.set_item("gaussian", by_slot(py, &c.gaussian, slots.iter().copied()))?;
        d.set_item("min", by_slot(py, &c.min, slots.iter().copied()))?;
        d.set_item("max", by_slot(py, &c.max, slots.iter().copied()))?;
        d.set_item("area", by_slot(py, &c.area, slots.iter().copied()))?;
        Ok(d.unbind())
    }

    /// Subdivide in place; returns the report (a dict: `scheme`, `input`
    /// and `output` counts, one dict per level). `scheme`: `"loop"`
    /// (triangles), `"catmull_clark"` (or `"catmull-clark"`; any polygons),
    /// `"sqrt3"` (triangles) or `"midpoint"` (linear: triangles 1-to-4,
    /// else quads; `faces` = `"auto"`, `"quads"` or `"triangles"`).
    /// `boundary`: `"crease"` or `"crease_and_corners"`; `corner_column`
    /// (bool vertex column of fixed vertices) and `crease_column` (float
    /// edge column of crease sharpness; loop and catmull_clark only, the
    /// others raise `UnsuitableError`); `linear_columns`: vertex columns
    /// refined linearly instead of with the scheme's stencil. `progress`: a
    /// callable taking a dict and returning False to cancel
    /// (`CancelledError`; the mesh is unchanged). `max_faces`: a request
    /// estimated to make more faces is refused before any work
    /// (`TooLargeError`; default ten million).
    #[pyo3(signature = (scheme = "loop", levels = 1, *, boundary = "crease", corner_column = None, crease_column = None, linear_columns = Vec::new(), faces = "auto", progress = None, max_faces = DEFAULT_MAX_FACES))]
    #[allow(clippy::too_many_arguments)]
    fn subdivide(
        slf: &Bound<'_, Self>,
        scheme: &str,
        levels: u32,
        boundary: &str,
        corner_column: Option<String>,
        crease_column: Option<String>,
        linear_columns: Vec<String>,
        faces: &str,
        progress: Option<Bound<'_, PyAny>>,
        max_faces: usize,
    ) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let word = |e: UnknownChoice| PyValueError::new_err(e.to_string());
        let scheme: Scheme = scheme.parse().map_err(word)?;
        let mut options = SubdivisionOptions::default()
            .levels(levels)
            .boundary(boundary.parse().map_err(word)?)
            .corner_column(corner_column)
            .crease_column(crease_column)
            .midpoint_faces(faces.parse().map_err(word)?)
            .max_faces(max_faces);
        for c in &linear_columns {
            options.vertex_data = options
                .vertex_data
                .clone()
                .with(c, VertexInterpolation::Linear);
        }
        let cb = Callback::new(progress)?;
        let report = cb.finish(edit(slf, |m| cb.run(|p| subdivide(m, scheme, &options, p))))?;
        Ok(subdivision_report(py, &report)?.unbind())
    }

    /// Smooth the positions in place; returns the report (a dict: `moved`,
    /// `fixed`, `iterations`, `max_displacement`, `stale`: the columns,
    /// such as stored normals, that no longer match). `method`:
    /// `"uniform"`, `"cotan"`, `"taubin"` or `"implicit"` (backward Euler
    /// mean-curvature flow). `iterations` (default 10, implicit 1); `step`
    /// (explicit and Taubin: lambda in (0, 1], default 0.5; implicit: the
    /// time step, default 0.001); `taubin_mu`; `rescale` (implicit: keep
    /// area and centroid). What stays: `boundary` (`"lock"`, the default;
    /// `"slide"`: on the input's boundary; `"free"`), `seams` (default
    /// `"free"`), `feature_angle` (radians) and `features` (a bool edge
    /// column: lines that slide), `pinned` (a bool vertex column name or a
    /// bool array in vertex order: true = never moves). `fix_boundary`
    /// (True = `boundary="lock"`, False = `"free"`) and `mask` (the
    /// vertices that may move: `pinned` is its complement) are deprecated.
    #[pyo3(signature = (method = "uniform", *, iterations = None, step = None, taubin_mu = None, boundary = None, seams = None, feature_angle = None, features = None, pinned = None, rescale = false, progress = None, fix_boundary = None, mask = None))]
    #[allow(clippy::too_many_arguments)]
    fn smooth(
        slf: &Bound<'_, Self>,
        method: &str,
        iterations: Option<u32>,
        step: Option<f64>,
        taubin_mu: Option<f64>,
        boundary: Option<&Bound<'_, PyAny>>,
        seams: Option<&Bound<'_, PyAny>>,
        feature_angle: Option<f64>,
        features: Option<String>,
        pinned: Option<&Bound<'_, PyAny>>,
        rescale: bool,
        progress: Option<Bound<'_, PyAny>>,
        fix_boundary: Option<&Bound<'_, PyAny>>,
        mask: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let method: SmoothMethod = parse_word(method)?;
        let mut options = SmoothOptions::with_method(method);
        if let Some(i) = iterations {
            options.iterations = i;
        }
        options.step = step;
        options.taubin_mu = taubin_mu;
        options.rescale = rescale;
        let mut keep = KeepKw::new(boundary, seams, feature_angle, features, pinned)?;
        let fixed = old_keep(py, fix_boundary, "fix_boundary", "boundary", Keep::Lock)?;
        keep.boundary = keep.boundary.or(fixed);
        let mask = mask_of(mask)?;
        if !matches!(mask, Mask::None) {
            deprecated(py, "mask", "pinned (its complement)")?;
        }
        let cb = Callback::new(progress)?;
        let r = cb.finish(edit(slf, |m| {
            if matches!(keep.pinned, Mask::None) {
                keep.pinned = complement(m, &mask)?;
            }
            let (c, temp) = keep.apply(m, options.constraints())?;
            let o = options.clone().with_constraints(c);
            let out = cb.run(|p| smooth(m, &o, p));
            drop_mask(m, temp, &keep.pinned);
            out
        }))?;
        let d = fields_dict!(py, r; moved, fixed, iterations, max_displacement, stale);
        Ok(d.unbind())
    }

    /// Fair a region in place: the smoothest surface (k-harmonic, `order`
    /// 1 to 3, default 2) over the region with its surroundings fixed.
    /// `region`: None (every vertex), a bool vertex column name, a bool
    /// array in vertex order, or a list of `Vertex` keys. `weights`:
    /// `"cotan"` or `"uniform"`. What stays: `boundary` (`"lock"`, the
    /// default: the boundary and its order − 1 rings; `"slide"`: boundary
    /// vertices are spread along the input's boundary; `"free"`), `seams`
    /// (default `"free"`), `feature_angle` (radians), `features` (a bool
    /// edge column), `pinned` (a bool vertex column name or array: true =
    /// never moves). Returns the report (a dict: `moved`, `fixed`,
    /// `max_displacement`).
    #[pyo3(signature = (region = None, *, order = 2, weights = "cotan", boundary = None, seams = None, feature_angle = None, features = None, pinned = None, progress = None))]
    #[allow(clippy::too_many_arguments)]
    fn fair(
        slf: &Bound<'_, Self>,
        region: Option<&Bound<'_, PyAny>>,
        order: u32,
        weights: &str,
        boundary: Option<&Bound<'_, PyAny>>,
        seams: Option<&Bound<'_, PyAny>>,
        feature_angle: Option<f64>,
        features: Option<String>,
        pinned: Option<&Bound<'_, PyAny>>,
        progress: Option<Bound<'_, PyAny>>,
    ) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let weights: LaplaceWeights = parse_word(weights)?;
        let keys = region_keys(slf, region)?;
        let mask = if keys.is_some() {
            Mask::None
        } else {
            mask_of(region)?
        };
        let keep = KeepKw::new(boundary, seams, feature_angle, features, pinned)?;
        let cb = Callback::new(progress)?;
        let r = cb.finish(edit(slf, |m| {
            let h = mask_handle(m, &mask, TEMP_MASK)?;
            let region = match (&keys, &h) {
                (Some(k), _) => FairRegion::Vertices(k.clone()),
                (None, Some(h)) => FairRegion::Mask(h.clone()),
                (None, None) => FairRegion::All,
            };
            let o = FairOptions::default()
                .region(region)
                .order(order)
                .weights(weights);
            let out = keep.apply(m, o.constraints()).and_then(|(c, temp)| {
                let o = o.with_constraints(c);
                let out = cb.run(|p| fair(m, &o, p));
                drop_mask(m, temp, &keep.pinned);
                out
            });
            drop_mask(m, h, &mask);
            out
        }))?;
        let d = fields_dict!(py, r; moved, fixed, max_displacement);
        Ok(d.unbind())
    }

    /// Isotropic remeshing (Botsch-Kobbelt) of a triangle mesh in place:
    /// split long edges, collapse short ones, flip towards valence 6,
    /// relax tangentially, project back onto the input. The target is
    /// `edge_length` (default: the input's mean edge length) or `adaptive`
    /// (an approximation tolerance in mesh units; edges follow the
    /// curvature, clamped to `min_length`..`max_length`). `iterations`
    /// (default 10), `smoothing_steps` per round (default 5), `project`.
    /// What stays: `boundary` (`"slide"`, the default: boundary vertices
    /// slide along the input's boundary; `"lock"`: boundaries stay exactly
    /// as they are; `"free"`), `seams` (UV seams of the resampled corner
    /// columns, default `"slide"`), `feature_angle` (radians) and
    /// `features` (a bool edge column): lines that slide; `pinned` (a bool
    /// vertex column name or array: vertices that never move).
    /// `resample`: `"linear"` (every linear vertex and corner column, the
    /// default), `"off"`, or a list of column names, resampled from the
    /// input surface so UVs do not drift. Returns the report (a dict:
    /// `iterations`, `splits`, `collapses`, `flips`, `target_length`,
    /// `fixed`, and the `input` and `output` counts). `max_faces`: a target
    /// estimated to make more faces is refused before any work
    /// (`TooLargeError`). One undo unit; a cancelled or failed run leaves
    /// the mesh as it was. Deprecated: `keep_boundary` (True =
    /// `boundary="lock"`), `feature_edges`, `locked`, and a bool `seams`.
    #[pyo3(signature = (edge_length = None, *, adaptive = None, min_length = None, max_length = None, iterations = 10, smoothing_steps = 5, project = true, boundary = None, seams = None, feature_angle = None, features = None, pinned = None, resample = None, progress = None, max_faces = DEFAULT_MAX_FACES, keep_boundary = None, feature_edges = None, locked = None))]
    #[allow(clippy::too_many_arguments)]
    fn remesh(
        slf: &Bound<'_, Self>,
        edge_length: Option<f64>,
        adaptive: Option<f64>,
        min_length: Option<f64>,
        max_length: Option<f64>,
        iterations: usize,
        smoothing_steps: usize,
        project: bool,
        boundary: Option<&Bound<'_, PyAny>>,
        seams: Option<&Bound<'_, PyAny>>,
        feature_angle: Option<f64>,
        features: Option<String>,
        pinned: Option<&Bound<'_, PyAny>>,
        resample: Option<&Bound<'_, PyAny>>,
        progress: Option<Bound<'_, PyAny>>,
        max_faces: usize,
        keep_boundary: Option<&Bound<'_, PyAny>>,
        feature_edges: Option<String>,
        locked: Option<String>,
    ) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let sizing = match (edge_length, adaptive) {
            (Some(_), Some(_)) => {
                return Err(PyValueError::new_err(
                    "give edge_length or adaptive, not both",
                ))
            }
            (Some(l), None) => Sizing::Uniform(l),
            (None, Some(tolerance)) => Sizing::Adaptive {
                tolerance,
                min_length,
                max_length,
            },
            (None, None) => Sizing::MeanEdgeLength,
        };
        let resample = resample_of(resample)?;
        let old_seams = seams.filter(|s| s.is_instance_of::<pyo3::types::PyBool>());
        let seams = seams.filter(|s| !s.is_instance_of::<pyo3::types::PyBool>());
        let mut keep = KeepKw::new(boundary, seams, feature_angle, features, pinned)?;
        let b = old_keep(py, keep_boundary, "keep_boundary", "boundary", Keep::Lock)?;
        keep.boundary = keep.boundary.or(b);
        let s = old_keep(py, old_seams, "seams=True/False", "seams", Keep::Slide)?;
        keep.seams = keep.seams.or(s);
        OldDecimateKw {
            keep_boundary: None,
            keep_seams: None,
            locked,
            feature_edges,
        }
        .onto(py, &mut keep)?;
        let cb = Callback::new(progress)?;
        let r = cb.finish(edit(slf, |m| {
            let o = RemeshOptions::default()
                .sizing(sizing)
                .iterations(iterations)
                .smoothing_steps(smoothing_steps)
                .project(project)
                .resample(resample.clone())
                .max_faces(max_faces);
            let (c, temp) = keep.apply(m, o.constraints())?;
            let o = o.with_constraints(c);
            let out = cb.run(|p| remesh(m, &o, p));
            drop_mask(m, temp, &keep.pinned);
            out
        }))?;
        let d = fields_dict!(py, r; iterations, splits, collapses, flips, target_length, fixed, feature_edges);
        d.set_item("input", counts_dict(py, &r.input)?)?;
        d.set_item("output", counts_dict(py, &r.output)?)?;
        Ok(d.unbind())
    }

    /// Fill every hole in place by Liepa's method: the least-weight
    /// triangulation of the rim (dihedral angle, then area), refined to the
    /// rim's edge length (`refine`), its new vertices faired (`fair`,
    /// k-harmonic of `fair_order` 1 to 3, default 2). Holes with more than
    /// `max_rim` rim edges are left open; rims over `max_refined_rim`
    /// (default 2000) are triangulated but not refined or faired (the
    /// patch grows as the rim's square). Attributes come from the rim:
    /// face values from the neighbouring face, rim corners (UVs) continue
    /// the outer corners, new vertices interpolate. Returns the report (a
    /// dict: `holes_filled`, `faces_added`, `vertices_added`,
    /// `ear_clipped`, `unrefined`, `skipped`, the `input` and `output`
    /// counts). One undo unit; a cancelled
    /// or failed run leaves the mesh as it was.
    #[pyo3(signature = (*, refine = true, fair = true, fair_order = 2, max_rim = None, progress = None, max_refined_rim = None))]
    #[allow(clippy::too_many_arguments)]
    fn fill_holes(
        slf: &Bound<'_, Self>,
        refine: bool,
        fair: bool,
        fair_order: u32,
        max_rim: Option<usize>,
        progress: Option<Bound<'_, PyAny>>,
        max_refined_rim: Option<usize>,
    ) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let defaults = FillHoleOptions::default();
        let max_refined_rim = max_refined_rim.unwrap_or(defaults.max_refined_rim);
        let o = defaults
            .max_rim(max_rim)
            .refine(refine)
            .fair(fair)
            .fair_order(fair_order)
            .max_refined_rim(max_refined_rim);
        let cb = Callback::new(progress)?;
        let r = cb.finish(edit(slf, |m| cb.run(|p| fill_holes(m, &o, p))))?;
        let d =
            fields_dict!(py, r; holes_filled, faces_added, vertices_added, ear_clipped, unrefined);
        d.set_item("skipped", r.skipped.len())?;
        d.set_item("input", counts_dict(py, &r.input)?)?;
        d.set_item("output", counts_dict(py, &r.output)?)?;
        Ok(d.unbind())
    }

    /// Decimate a triangle mesh in place by quadric error edge collapse;
    /// returns the report (a dict: `stopped_by` (`"target"`, `"max_error"`,
    /// `"no_collapses"`), `error`, the `input` and `output` counts,
    /// `collapses`, `passes`, `refused` by guard, `fixed`). The target is
    /// one of `ratio` (share of the vertices; default 0.5), `vertices`,
    /// `faces`, or none with `max_error` (a distance in mesh units).
    /// Guards: `max_normal_deviation` (radians, default 75 degrees; None:
    /// off), `min_quality`, `max_valence`. What stays: `boundary` and
    /// `seams` (UV seams and every other corner-column discontinuity):
    /// `"slide"` (the default), `"free"` or `"lock"`; `material`: a face
    /// column whose borders are kept like seams; `pinned`: a bool vertex
    /// column (name or array) of vertices that never move;
    /// `feature_angle` (radians) and `features` (a bool edge column):
    /// edges whose vertices never move; `attributes`: {column name:
    /// weight} of vertex or corner float columns taking part in the error.
    /// Attribute columns follow every collapse by rule. Deprecated:
    /// `keep_boundary` and `keep_seams` (True = `"lock"`), `locked`,
    /// `feature_edges`.
    #[pyo3(signature = (ratio = None, *, vertices = None, faces = None, max_error = None, max_normal_deviation = Some(DEFAULT_NORMAL_DEVIATION), min_quality = None, max_valence = None, boundary = None, seams = None, feature_angle = None, features = None, pinned = None, material = None, attributes = None, progress = None, keep_boundary = None, keep_seams = None, locked = None, feature_edges = None))]
    #[allow(clippy::too_many_arguments)]
    fn decimate(
        slf: &Bound<'_, Self>,
        ratio: Option<f64>,
        vertices: Option<usize>,
        faces: Option<usize>,
        max_error: Option<f64>,
        max_normal_deviation: Option<f64>,
        min_quality: Option<f64>,
        max_valence: Option<usize>,
        boundary: Option<&Bound<'_, PyAny>>,
        seams: Option<&Bound<'_, PyAny>>,
        feature_angle: Option<f64>,
        features: Option<String>,
        pinned: Option<&Bound<'_, PyAny>>,
        material: Option<String>,
        attributes: Option<&Bound<'_, PyDict>>,
        progress: Option<Bound<'_, PyAny>>,
        keep_boundary: Option<&Bound<'_, PyAny>>,
        keep_seams: Option<&Bound<'_, PyAny>>,
        locked: Option<String>,
        feature_edges: Option<String>,
    ) -> PyResult<Py<PyDict>> {
        let py = slf.py();
        let target = target_of(ratio, vertices, faces, max_error)?;
        let mut keep = KeepKw::new(boundary, seams, feature_angle, features, pinned)?;
        OldDecimateKw {
            keep_boundary,
            keep_seams,
            locked,
            feature_edges,
        }
        .onto(py, &mut keep)?;
        let kw = decimate_kw(
            max_error,
            max_normal_deviation,
            min_quality,
            max_valence,
            keep,
            material,
            attributes,
        )?;
        let cb = Callback::new(progress)?;
        let r = cb.finish(edit(slf, |m| {
            let (o, temp) = kw.options(m, target)?;
            let out = cb.run(|p| decimate(m, &o, p));
            drop_mask(m, temp, &kw.keep.pinned);
            out
        }))?;
        Ok(decimate_report(py, &r)?.unbind())
    }

    /// A level-of-detail chain: one decimation through several targets,
    /// coarser and coarser; the mesh itself is not changed. `targets`: a
    /// list of ratios (floats) or dicts `{"vertices": n}` / `{"faces": n}`
    /// (default `[0.5, 0.25, 0.1]`). The other keywords are `decimate`'s
    /// (`pinned` by column name only).
    /// Returns one dict per level: `mesh` (a new `Mesh`, with the
    /// attribute columns, Python-rule columns included) and `report`.
    #[pyo3(signature = (targets = None, *, max_error = None, max_normal_deviation = Some(DEFAULT_NORMAL_DEVIATION), min_quality = None, max_valence = None, boundary = None, seams = None, feature_angle = None, features = None, pinned = None, material = None, attributes = None, progress = None, keep_boundary = None, keep_seams = None, locked = None, feature_edges = None))]
    #[allow(clippy::too_many_arguments)]
    fn lod_chain(
        slf: &Bound<'_, Self>,
        targets: Option<&Bound<'_, PyAny>>,
        max_error: Option<f64>,
        max_normal_deviation: Option<f64>,
        min_quality: Option<f64>,
        max_valence: Option<usize>,
        boundary: Option<&Bound<'_, PyAny>>,
        seams: Option<&Bound<'_, PyAny>>,
        feature_angle: Option<f64>,
        features: Option<String>,
        pinned: Option<String>,
        material: Option<String>,
        attributes: Option<&Bound<'_, PyDict>>,
        progress: Option<Bound<'_, PyAny>>,
        keep_boundary: Option<&Bound<'_, PyAny>>,
        keep_seams: Option<&Bound<'_, PyAny>>,
        locked: Option<String>,
        feature_edges: Option<String>,
    ) -> PyResult<Py<PyList>> {
        let py = slf.py();
        let targets = lod_targets(targets)?;
        let mut keep = KeepKw::new(boundary, seams, feature_angle, features, None)?;
        keep.pinned = pinned.map_or(Mask::None, Mask::Column);
        OldDecimateKw {
            keep_boundary,
            keep_seams,
            locked,
            feature_edges,
        }
        .onto(py, &mut keep)?;
        let kw = decimate_kw(
            max_error,
            max_normal_deviation,
            min_quality,
            max_valence,
            keep,
            material,
            attributes,
        )?;
        let cb = Callback::new(progress)?;
        let chain = {
            let this = slf.try_borrow().map_err(busy)?;
            let m = &this.mesh;
            let result = kw.lod_options(m).and_then(|decimate| {
                let o = LodOptions::default()
                    .targets(targets)
                    .decimate(decimate)
                    .meshes(true)
                    .record(false);
                cb.run(|p| lod_chain(m, &o, p))
            });
            let result = result.map_err(|e| crate::errors::mesh_err(py, &slf.clone().unbind(), e));
            cb.finish(result)?
        };
        let out = PyList::empty(py);
        let this = slf.try_borrow().map_err(busy)?;
        for level in chain.levels {
            let d = PyDict::new(py);
            match level.mesh {
                Some(m) => d.set_item("mesh", Py::new(py, this.wrap_like(py, m))?)?,
                None => d.set_item("mesh", py.None())?,
            }
            d.set_item("report", decimate_report(py, &level.report)?)?;
            out.append(d)?;
        }
        Ok(out.unbind())
    }
}
