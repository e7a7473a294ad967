//! serde for [`Mesh`]: connectivity, generations, holes and every
//! attribute column. Deserializing checks everything: lengths, column types,
//! finite positions, then [`Mesh::validate`]; a structurally invalid mesh is
//! an error, never a broken mesh.
//!
//! Column values travel as [`Value`]s, absent ones as `null`. Every value
//! an attribute accepts comes back: NaN and the infinities (NaN often marks
//! "no data") travel as the strings `"NaN"`, `"inf"` and `"-inf"` in
//! human-readable formats such as JSON, which has no such numbers, and as
//! plain floats in binary ones. A float written as `null` (what JSON
//! writers make of NaN, and what meshloom 0.1 saved) reads back as NaN. Typed columns
//! come back typed when their value type and rule are registered
//! ([`attr::register`](crate::attr::register); the stock ones are), and as
//! dynamic columns otherwise. Keys stay valid across a round trip: slots and
//! generations are kept.
//!
//! ```
//! let mut mesh = meshloom::shapes::cube();
//! let mass = mesh.add_vertex_attr::<f64>("mass")?;
//! mesh.fill_attr(&mass, 2.0)?;
//! let json = serde_json::to_string(&mesh).unwrap();
//! let back: meshloom::Mesh = serde_json::from_str(&json).unwrap();
//! let v = mesh.vertices().next().unwrap();
//! let mass = back.attr_handle::<meshloom::VertexKey, f64, meshloom::attr::Interpolate>("mass")?;
//! assert_eq!(back.attr(&mass, v)?, Some(&2.0));
//! assert_eq!(back.position(v)?, mesh.position(v)?);
//! # Ok::<(), meshloom::Error>(())
//! ```

use serde::de::Error as _;
use serde::ser::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::attr::registry::{column_type_key, make_column};
use crate::keys::ElementKind;
use crate::layout::{Eid, FaceLink, HalfedgeRecord, Hid, IdVec, MAX_HALFEDGE_SLOTS};
use crate::mesh::Mesh;
use crate::slots::Slots;
use crate::store::{Column, Columns, Dynamic, ErasedColumn, Value, ValueType, POSITION};

/// One attribute column as serialized.
#[derive(Serialize, Deserialize)]
struct ColumnData {
    name: String,
    /// `value type/rule` of a typed column; absent for a dynamic one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    rust_type: Option<String>,
    /// The declared type of a dynamic column.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    dynamic: Option<ValueType>,
    /// One entry per slot; `None` for absent values and vacant slots.
    values: Vec<Option<Value>>,
}

/// The serialized form of a mesh.
#[derive(Serialize, Deserialize)]
struct MeshData {
    vertex_halfedge: Vec<Hid>,
    vertex_generations: Vec<u32>,
    halfedges: Vec<HalfedgeRecord>,
    edge_generations: Vec<u32>,
    /// A face's half-edge, top bit set for holes.
    face_halfedge: Vec<FaceLink>,
    face_generations: Vec<u32>,
    /// Each arena's base generation (absent in meshes saved before it
    /// existed: 1).
    #[serde(default = "first_base")]
    vertex_base: u32,
    #[serde(default = "first_base")]
    edge_base: u32,
    #[serde(default = "first_base")]
    face_base: u32,
    /// Each arena's fresh floor where an undo raised it above the base
    /// (see `slots.rs`): no generation below it is issued again, so keys
    /// of elements an undo took back stay stale in the copy too. Absent:
    /// the base.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    vertex_fresh: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    edge_fresh: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    face_fresh: Option<u32>,
    /// Index of the position column among the vertex columns.
    position: Option<usize>,
    vertex_attrs: Vec<ColumnData>,
    halfedge_attrs: Vec<ColumnData>,
    edge_attrs: Vec<ColumnData>,
    face_attrs: Vec<ColumnData>,
}

fn first_base() -> u32 {
    Slots::FIRST_BASE
}

fn columns_out(
    mesh: &Mesh,
    kind: ElementKind,
    live: impl Fn(usize) -> bool,
) -> Result<Vec<ColumnData>, String> {
    let cols = mesh.columns_of(kind);
    cols.cols
        .iter()
        .zip(&cols.meta)
        .map(|((name, c), meta)| {
            if c.portable_type().is_none() {
                return Err(format!(
                    "the {kind} attribute {name:?} holds {}, whose Attribute::to_value is not implemented",
                    c.type_name()
                ));
            }
            let values = (0..c.len())
                .map(|i| if live(i) { c.value_at(i) } else { None })
                .collect();
            Ok(ColumnData {
                name: name.clone(),
                rust_type: meta.value_type.is_none().then(|| column_type_key(&**c)),
                dynamic: meta.value_type,
                values,
            })
        })
        .collect()
}

impl Serialize for Mesh {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let v_live = |i: usize| self.v_slots.is_live(i);
        let h_live = |i: usize| self.e_slots.is_live(Hid::new(i as u32).edge().index());
        let e_live = |i: usize| self.e_slots.is_live(i);
        let f_live = |i: usize| self.f_slots.is_live(i);
        let data = MeshData {
            vertex_halfedge: self.v_halfedge.as_slice().to_vec(),
            vertex_generations: self.v_slots.generations().into_owned(),
            halfedges: self.he.as_slice().to_vec(),
            edge_generations: self.e_slots.generations().into_owned(),
            face_halfedge: self.f_halfedge.as_slice().to_vec(),
            face_generations: self.f_slots.generations().into_owned(),
            vertex_base: self.v_slots.base(),
            edge_base: self.e_slots.base(),
            face_base: self.f_slots.base(),
            vertex_fresh: self.v_slots.raised_fresh(),
            edge_fresh: self.e_slots.raised_fresh(),
            face_fresh: self.f_slots.raised_fresh(),
            position: self.attrs.position,
            vertex_attrs: columns_out(self, ElementKind::Vertex, v_live)
                .map_err(S::Error::custom)?,
            halfedge_attrs: columns_out(self, ElementKind::Halfedge, h_live)
                .map_err(S::Error::custom)?,
            edge_attrs: columns_out(self, ElementKind::Edge, e_live).map_err(S::Error::custom)?,
            face_attrs: columns_out(self, ElementKind::Face, f_live).map_err(S::Error::custom)?,
        };
        data.serialize(serializer)
    }
}

/// Rebuild one arena's columns.
fn columns_in(kind: ElementKind, data: Vec<ColumnData>, len: usize) -> Result<Columns, String> {
    let mut cols = Columns::default();
    for c in data {
        if cols.find(&c.name).is_some() {
            return Err(format!("the {kind} attribute {:?} appears twice", c.name));
        }
        if c.values.len() != len {
            return Err(format!(
                "the {kind} attribute {:?} has {} values for {len} slots",
                c.name,
                c.values.len()
            ));
        }
        let (mut col, declared): (Box<dyn ErasedColumn>, Option<ValueType>) =
            match (&c.dynamic, &c.rust_type) {
                (None, Some(key)) => match make_column(key, len) {
                    Some(col) => (col, None),
                    None => (
                        Box::new(Column::<Value, Dynamic>::absent(len)),
                        common_type(&c.values),
                    ),
                },
                (declared, _) => (Box::new(Column::<Value, Dynamic>::absent(len)), *declared),
            };
        for (i, v) in c.values.iter().enumerate() {
            if let (Some(ty), Some(v)) = (declared, v) {
                if v.value_type() != ty {
                    return Err(format!(
                        "the {kind} attribute {:?} declares {ty} but slot {i} holds {}",
                        c.name,
                        v.value_type()
                    ));
                }
            }
            if !col.set_value(i, v.as_ref()) {
                return Err(format!(
                    "the {kind} attribute {:?}: slot {i} does not fit {}",
                    c.name,
                    col.type_name()
                ));
            }
        }
        cols.push_dynamic(&c.name, col, declared);
    }
    Ok(cols)
}

/// The one type every present value has, if they agree.
fn common_type(values: &[Option<Value>]) -> Option<ValueType> {
    let mut types = values.iter().flatten().map(Value::value_type);
    let first = types.next()?;
    types.all(|t| t == first).then_some(first)
}

fn mesh_from(data: MeshData) -> Result<Mesh, String> {
    let (nv, ne, nf) = (
        data.vertex_generations.len(),
        data.edge_generations.len(),
        data.face_generations.len(),
    );
    if data.vertex_halfedge.len() != nv
        || data.halfedges.len() != Eid::halfedge_slots(ne)
        || data.face_halfedge.len() != nf
    {
        return Err("link arrays and generations disagree in length".into());
    }
    if nv > MAX_HALFEDGE_SLOTS
        || Eid::halfedge_slots(ne) > MAX_HALFEDGE_SLOTS
        || nf > MAX_HALFEDGE_SLOTS
    {
        return Err("too many slots for 32-bit links".into());
    }
    let slots = |kind: &str, generations: Vec<u32>, base: u32, fresh: Option<u32>| {
        Slots::from_generations(generations, base, fresh.unwrap_or(base))
            .map_err(|e| format!("{kind} {e}"))
    };
    let v_slots = slots(
        "vertex",
        data.vertex_generations,
        data.vertex_base,
        data.vertex_fresh,
    )?;
    let e_slots = slots(
        "edge",
        data.edge_generations,
        data.edge_base,
        data.edge_fresh,
    )?;
    let f_slots = slots(
        "face",
        data.face_generations,
        data.face_base,
        data.face_fresh,
    )?;
    let holes = (0..nf)
        .filter(|&f| f_slots.is_live(f) && data.face_halfedge[f].is_hole())
        .count();
    let mut mesh = Mesh {
        v_halfedge: IdVec::from_vec(data.vertex_halfedge).into(),
        v_slots,
        he: IdVec::from_vec(data.halfedges).into(),
        e_slots,
        f_halfedge: IdVec::from_vec(data.face_halfedge).into(),
        f_slots,
        holes,
        attrs: Default::default(),
        rec: None,
        stamp: crate::mesh::Stamp::fresh(),
    };
    mesh.attrs.vertex = columns_in(ElementKind::Vertex, data.vertex_attrs, nv)?;
    mesh.attrs.halfedge = columns_in(
        ElementKind::Halfedge,
        data.halfedge_attrs,
        Eid::halfedge_slots(ne),
    )?;
    mesh.attrs.edge = columns_in(ElementKind::Edge, data.edge_attrs, ne)?;
    mesh.attrs.face = columns_in(ElementKind::Face, data.face_attrs, nf)?;
    if let Some(p) = data.position {
        let col = mesh
            .attrs
            .vertex
            .typed::<[f64; 3], crate::store::rules::Interpolate>(p)
            .ok_or("the position column is missing or not [f64; 3] with Interpolate")?;
        if mesh.attrs.vertex.cols[p].0 != POSITION {
            return Err(format!("the position column must be named {POSITION:?}"));
        }
        for v in mesh.vids() {
            if let Some(x) = col.get(v.index()) {
                if !x.iter().all(|c| c.is_finite()) {
                    let v = v.raw();
                    return Err(format!("vertex slot {v} has the non-finite position {x:?}"));
                }
            }
        }
        mesh.attrs.position = Some(p);
    }
    // Meshes saved before rule 11 existed (or by hand) may name an interior
    // half-edge at a boundary vertex: point them into the hole first.
    mesh.point_all_at_holes();
    mesh.validate().map_err(|e| e.to_string())?;
    Ok(mesh)
}

impl<'de> Deserialize<'de> for Mesh {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let data = MeshData::deserialize(deserializer)?;
        mesh_from(data).map_err(D::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use crate::attr::{Conserved, Value, ValueType};
    use crate::{FaceKey, Mesh, VertexKey};

    fn round_trip(mesh: &Mesh) -> Result<Mesh, serde_json::Error> {
        serde_json::from_str(&serde_json::to_string(mesh)?)
    }

    #[test]
    fn attributes_and_holes_round_trip() {
        let mut mesh = Mesh::from_polygons(
            &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            &[[0u32, 1, 2]],
        )
        .unwrap();
        let mass = mesh
            .add_attr_with_rule::<VertexKey, f64, Conserved>("mass")
            .unwrap();
        let colour = mesh.add_face_attr::<[f32; 3]>("colour").unwrap();
        let q = mesh
            .add_dynamic_attr::<VertexKey>("quality", ValueType::F32)
            .unwrap();
        let v: Vec<_> = mesh.vertices().collect();
        mesh.set_attr(&mass, v[0], 1.5).unwrap();
        mesh.set_attr(&q, v[2], Value::F32(0.25)).unwrap();
        let hole: FaceKey = mesh.holes().next().unwrap();
        mesh.set_attr(&colour, hole, [0.0, 0.0, 1.0]).unwrap();
        let back = round_trip(&mesh).unwrap();
        // The handle belongs to the original mesh's column.
        assert!(matches!(
            back.attr(&mass, v[0]),
            Err(crate::Error::AttributeHandle { .. })
        ));
        let mass2 = back
            .attr_handle::<VertexKey, f64, Conserved>("mass")
            .unwrap();
        assert_eq!(back.attr(&mass2, v[0]).unwrap(), Some(&1.5));
        assert_eq!(back.attr(&mass2, v[1]).unwrap(), None);
        let c2 = back
            .attr_handle::<FaceKey, [f32; 3], crate::attr::Interpolate>("colour")
            .unwrap();
        assert_eq!(back.attr(&c2, hole).unwrap(), Some(&[0.0, 0.0, 1.0]));
        assert_eq!(
            back.attr_value("quality", v[2]).unwrap(),
            Some(Value::F32(0.25))
        );
        assert_eq!(back.hole_count(), 1);
        // Serializing again gives the same text: nothing was lost or reordered.
        assert_eq!(
            serde_json::to_string(&back).unwrap(),
            serde_json::to_string(&mesh).unwrap()
        );
    }

    #[test]
    fn broken_meshes_are_refused() {
        let mesh = crate::shapes::tetrahedron();
        let json = serde_json::to_value(&mesh).unwrap();
        let mut bad = json.clone();
        bad["halfedges"][0]["next"] = serde_json::json!(0);
        assert!(serde_json::from_value::<Mesh>(bad).is_err());
        let mut bad = json.clone();
        bad["vertex_generations"].as_array_mut().unwrap().pop();
        assert!(serde_json::from_value::<Mesh>(bad).is_err());
        let mut bad = json.clone();
        bad["vertex_attrs"][0]["values"][0] = serde_json::json!({"List": [{"F64": 1.0}]});
        assert!(serde_json::from_value::<Mesh>(bad).is_err());
        let mut bad = json.clone();
        bad["halfedges"][3]["origin"] = serde_json::json!(99);
        assert!(serde_json::from_value::<Mesh>(bad).is_err());
        let mut bad = json;
        bad["position"] = serde_json::json!(5);
        assert!(serde_json::from_value::<Mesh>(bad).is_err());
    }

    /// A mesh saved before rule 11 (a boundary vertex naming an interior
    /// half-edge) loads, and comes back pointing into its hole.
    #[test]
    fn boundary_vertices_are_pointed_into_holes_on_load() {
        let mesh = Mesh::from_faces(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
        let v = mesh.vertices().next().unwrap();
        let inner = mesh
            .vertex(v)
            .unwrap()
            .outgoing()
            .find(|&h| !mesh.halfedge(h).unwrap().is_boundary())
            .unwrap();
        let mut json = serde_json::to_value(&mesh).unwrap();
        json["vertex_halfedge"][v.index()] = serde_json::json!(inner.index());
        let back: Mesh = serde_json::from_value(json).unwrap();
        back.validate().unwrap();
        assert!(back.vertex(v).unwrap().halfedge().is_boundary());
    }

    #[test]
    fn unregistered_types_come_back_dynamic() {
        let mesh = crate::shapes::tetrahedron();
        let mut json = serde_json::to_value(&mesh).unwrap();
        json["vertex_attrs"][0]["rust_type"] = serde_json::json!("Elsewhere/Rule");
        json["position"] = serde_json::Value::Null;
        let back: Mesh = serde_json::from_value(json).unwrap();
        assert!(!back.has_positions());
        let v = back.vertices().next().unwrap();
        assert!(matches!(
            back.attr_value("position", v).unwrap(),
            Some(Value::List(_))
        ));
    }

    /// Issue 10, defect 6: every float value `set_attr` accepts, NaN and
    /// the infinities included, comes back from JSON, in every float
    /// column kind (scalars, arrays, dynamic values and lists).
    #[test]
    fn non_finite_floats_round_trip() {
        let odd = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -0.0, 1.5];
        let mut mesh = crate::shapes::cube();
        let vs: Vec<_> = mesh.vertices().collect();
        let fs: Vec<_> = mesh.faces().collect();
        let a = mesh.add_vertex_attr::<f64>("a").unwrap();
        let b = mesh.add_vertex_attr::<f32>("b").unwrap();
        let c = mesh.add_face_attr::<[f64; 3]>("c").unwrap();
        let d = mesh.add_face_attr::<[f32; 2]>("d").unwrap();
        let e = mesh
            .add_dynamic_attr::<VertexKey>("e", ValueType::F64)
            .unwrap();
        let l = mesh
            .add_dynamic_attr::<VertexKey>("l", ValueType::List)
            .unwrap();
        for (i, &x) in odd.iter().enumerate() {
            mesh.set_attr(&a, vs[i], x).unwrap();
            mesh.set_attr(&b, vs[i], x as f32).unwrap();
            mesh.set_attr(&c, fs[i], [x, 0.0, x]).unwrap();
            mesh.set_attr(&d, fs[i], [x as f32, 2.0]).unwrap();
            mesh.set_attr(&e, vs[i], Value::F64(x)).unwrap();
            let list = Value::List(vec![Value::F32(x as f32), Value::F64(x)]);
            mesh.set_attr(&l, vs[i], list).unwrap();
        }
        let json = serde_json::to_string(&mesh).unwrap();
        assert!(json.contains("\"NaN\"") && json.contains("\"-inf\""));
        let back = round_trip(&mesh).unwrap();
        // Every float of a value, in order.
        fn floats(v: &Value, out: &mut Vec<u64>) {
            match v {
                Value::List(items) => items.iter().for_each(|x| floats(x, out)),
                Value::F32(x) => out.push(f64::from(*x).to_bits()),
                Value::F64(x) => out.push(x.to_bits()),
                _ => panic!("not a float: {v:?}"),
            }
        }
        let all = |m: &Mesh| {
            let mut out = Vec::new();
            for n in ["a", "b", "e", "l"] {
                for &v in &vs {
                    if let Some(x) = m.attr_value(n, v).unwrap() {
                        floats(&x, &mut out);
                    }
                }
            }
            for n in ["c", "d"] {
                for &f in &fs {
                    if let Some(x) = m.attr_value(n, f).unwrap() {
                        floats(&x, &mut out);
                    }
                }
            }
            out
        };
        let (was, now) = (all(&mesh), all(&back));
        assert_eq!(was.len(), 5 * (1 + 1 + 1 + 2 + 3 + 2));
        // Bit for bit (a NaN's payload aside: JSON keeps no payload).
        let canon = |b: &u64| {
            let x = f64::from_bits(*b);
            if x.is_nan() {
                f64::NAN.to_bits()
            } else {
                *b
            }
        };
        assert_eq!(
            was.iter().map(canon).collect::<Vec<_>>(),
            now.iter().map(canon).collect::<Vec<_>>()
        );
        let a_back = back
            .attr_handle::<VertexKey, f64, crate::attr::Interpolate>("a")
            .unwrap();
        assert!(back.attr(&a_back, vs[0]).unwrap().unwrap().is_nan());
        // A mesh saved before: NaN written as `null` reads back as NaN.
        let old = json.replace("\"NaN\"", "null");
        let back: Mesh = serde_json::from_str(&old).unwrap();
        assert!(matches!(back.attr_value("a", vs[0]).unwrap(), Some(Value::F64(x)) if x.is_nan()));
    }
}
