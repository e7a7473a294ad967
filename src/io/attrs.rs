//! Attribute values read beside the polygons, kept in file order until the
//! mesh is built, then attached as mesh columns (which follow every later
//! edit by their rule). Kept apart from the parsers so that a format only
//! says what it read, and from the repairs, which only say where each
//! element came from ([`Provenance`]).
//!
//! | read as | column |
//! |---|---|
//! | `[f64; 2]`, `[f64; 3]`, `[f64; 4]`, `f64` | typed, with the [`Interpolate`](crate::attr::Interpolate) rule |
//! | `String` | typed, with `String`'s rule |
//! | a [`Value`] of a declared [`ValueType`] | dynamic (PLY properties, written back with their type) |

use std::collections::HashMap;

use crate::attr::{Value, ValueType};
use crate::keys::{ElementKind, FaceKey, HalfedgeKey, VertexKey};
use crate::mesh::Mesh;
use crate::repair::Provenance;

use super::error::{Error, Location};

/// The values of one attribute, one per element in file order.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Data {
    Scalar(Vec<f64>),
    Vec2(Vec<[f64; 2]>),
    Vec3(Vec<[f64; 3]>),
    Vec4(Vec<[f64; 4]>),
    Text(Vec<String>),
    Dynamic(ValueType, Vec<Value>),
}

impl Data {
    fn len(&self) -> usize {
        match self {
            Data::Scalar(v) => v.len(),
            Data::Vec2(v) => v.len(),
            Data::Vec3(v) => v.len(),
            Data::Vec4(v) => v.len(),
            Data::Text(v) => v.len(),
            Data::Dynamic(_, v) => v.len(),
        }
    }

    /// Exact bits of element `i`'s value, for welding.
    fn bits(&self, i: usize, out: &mut Vec<u64>) {
        match self {
            Data::Scalar(v) => out.push(v[i].to_bits()),
            Data::Vec2(v) => out.extend(v[i].iter().map(|x| x.to_bits())),
            Data::Vec3(v) => out.extend(v[i].iter().map(|x| x.to_bits())),
            Data::Vec4(v) => out.extend(v[i].iter().map(|x| x.to_bits())),
            Data::Text(v) => out.extend(v[i].bytes().map(u64::from)),
            Data::Dynamic(_, v) => {
                fn walk(v: &Value, out: &mut Vec<u64>) {
                    match v {
                        Value::List(items) => {
                            out.push(items.len() as u64);
                            items.iter().for_each(|x| walk(x, out));
                        }
                        Value::Text(s) => out.extend(s.bytes().map(u64::from)),
                        other => out.push(other.as_f64().map_or(0, f64::to_bits)),
                    }
                }
                walk(&v[i], out);
            }
        }
    }
}

/// One attribute: its name, values and which elements have one.
#[derive(Clone, Debug)]
pub(crate) struct SoupColumn {
    pub(crate) name: String,
    pub(crate) data: Data,
    /// `None`: every element has a value.
    pub(crate) present: Option<Vec<bool>>,
}

impl SoupColumn {
    pub(crate) fn dense(name: &str, data: Data) -> SoupColumn {
        SoupColumn {
            name: name.to_owned(),
            data,
            present: None,
        }
    }

    fn has(&self, i: usize) -> bool {
        i < self.data.len() && self.present.as_ref().is_none_or(|p| p[i])
    }
}

/// Named values for vertices, faces and corners (half-edges).
#[derive(Clone, Debug, Default)]
pub(crate) struct SoupAttrs {
    pub(crate) vertex: Vec<SoupColumn>,
    pub(crate) face: Vec<SoupColumn>,
    pub(crate) corner: Vec<SoupColumn>,
}

impl SoupAttrs {
    /// Whether no attribute was read.
    pub(crate) fn is_empty(&self) -> bool {
        self.vertex.is_empty() && self.face.is_empty() && self.corner.is_empty()
    }

    /// A weld class per vertex: vertices weld only within a class, so two
    /// vertices at one position with different attribute values stay apart.
    pub(crate) fn weld_classes(&self, n: usize) -> Vec<u32> {
        if self.vertex.is_empty() {
            return Vec::new();
        }
        let mut ids: HashMap<Vec<u64>, u32> = HashMap::new();
        let mut key = Vec::new();
        (0..n)
            .map(|v| {
                key.clear();
                for c in &self.vertex {
                    key.push(u64::from(c.has(v)));
                    if c.has(v) {
                        c.data.bits(v, &mut key);
                    }
                }
                let next = ids.len() as u32;
                *ids.entry(key.clone()).or_insert(next)
            })
            .collect()
    }

    /// Attach every attribute to the built mesh. Input vertex `i` of the
    /// build is `vertices[i]`, face `i` is `faces[i]`; `prov` maps them back
    /// to the file (empty maps when no repair ran). Corner `c` of face `f`
    /// is its `c`-th half-edge from the face's first.
    pub(crate) fn attach(
        &self,
        mesh: &mut Mesh,
        vertices: &[Option<VertexKey>],
        faces: &[FaceKey],
        offsets: &[u32],
        prov: &Provenance,
    ) -> Result<(), Error> {
        let src = |map: &[u32], i: usize| map.get(i).map_or(i, |&s| s as usize);
        for col in &self.vertex {
            let targets = vertices
                .iter()
                .enumerate()
                .filter_map(|(i, k)| k.map(|k| (k, src(&prov.vertex_source, i))));
            attach_column(mesh, col, targets.collect::<Vec<_>>())?;
        }
        for col in &self.face {
            let targets = faces
                .iter()
                .enumerate()
                .map(|(i, &k)| (k, src(&prov.face_source, i)));
            attach_column(mesh, col, targets.collect::<Vec<_>>())?;
        }
        if !self.corner.is_empty() {
            let mut targets: Vec<(HalfedgeKey, usize)> = Vec::new();
            for (i, &f) in faces.iter().enumerate() {
                let Ok(view) = mesh.face(f) else { continue };
                for (k, h) in view.halfedges().enumerate() {
                    let c = offsets[i] as usize + k;
                    targets.push((h, src(&prov.corner_source, c)));
                }
            }
            for col in &self.corner {
                attach_column(mesh, col, targets.clone())?;
            }
        }
        Ok(())
    }
}

fn clash(kind: ElementKind, name: &str) -> Error {
    Error::Header {
        at: Location::whole(),
        message: format!(
            "the {kind} attribute {name:?} is given twice (or clashes with positions)"
        ),
    }
}

fn failed(name: &str, e: crate::Error) -> Error {
    Error::Header {
        at: Location::whole(),
        message: format!("attribute {name:?}: {e}"),
    }
}

/// Add one column and fill it: `targets` pairs each element key with the
/// file element whose value it takes.
fn attach_column<K: crate::attr::Element>(
    mesh: &mut Mesh,
    col: &SoupColumn,
    targets: Vec<(K, usize)>,
) -> Result<(), Error> {
    macro_rules! typed {
        ($t:ty, $v:expr) => {{
            let h = mesh
                .add_attr::<K, $t>(&col.name)
                .map_err(|_| clash(K::KIND, &col.name))?;
            let mut view = mesh.attr_view_mut(&h).map_err(|e| failed(&col.name, e))?;
            for (k, i) in targets {
                if col.has(i) {
                    view.set(k, Some($v[i].clone()))
                        .map_err(|e| failed(&col.name, e))?;
                }
            }
        }};
    }
    match &col.data {
        Data::Scalar(v) => typed!(f64, v),
        Data::Vec2(v) => typed!([f64; 2], v),
        Data::Vec3(v) => typed!([f64; 3], v),
        Data::Vec4(v) => typed!([f64; 4], v),
        Data::Text(v) => typed!(String, v),
        Data::Dynamic(ty, v) => {
            let h = mesh
                .add_dynamic_attr::<K>(&col.name, *ty)
                .map_err(|_| clash(K::KIND, &col.name))?;
            let mut view = mesh.attr_view_mut(&h).map_err(|e| failed(&col.name, e))?;
            for (k, i) in targets {
                if col.has(i) {
                    view.set(k, Some(v[i].clone()))
                        .map_err(|e| failed(&col.name, e))?;
                }
            }
        }
    }
    Ok(())
}

/// Collects one attribute's values element by element, some maybe absent;
/// nothing is stored until the first value arrives.
pub(crate) struct Collector<T> {
    name: &'static str,
    values: Vec<T>,
    present: Vec<bool>,
    any: bool,
}

impl<T: Clone + Default> Collector<T> {
    pub(crate) fn new(name: &'static str) -> Collector<T> {
        Collector {
            name,
            values: Vec::new(),
            present: Vec::new(),
            any: false,
        }
    }

    /// The value of element `i` (elements must come in order, gaps absent).
    pub(crate) fn set(&mut self, i: usize, value: T) {
        self.values.resize(i, T::default());
        self.present.resize(i, false);
        self.values.push(value);
        self.present.push(true);
        self.any = true;
    }

    /// The column over `n` elements, if any had a value.
    pub(crate) fn finish(mut self, n: usize, wrap: impl Fn(Vec<T>) -> Data) -> Option<SoupColumn> {
        if !self.any {
            return None;
        }
        self.values.resize(n, T::default());
        self.present.resize(n, false);
        let all = self.present.iter().all(|&p| p);
        Some(SoupColumn {
            name: self.name.to_owned(),
            data: wrap(self.values),
            present: (!all).then_some(self.present),
        })
    }
}
