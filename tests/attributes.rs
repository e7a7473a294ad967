//! The attribute system: every stock rule through the operators, keys and
//! handles at the door, views, dynamic columns, and quickcheck properties
//! over random operation streams.

use meshloom::attr::{
    Conserved, Contagion, Discard, FaceAttr, Incompatible, Interpolate, KeepFirst, Value,
    ValueType, VertexAttr,
};
use meshloom::{EdgeKey, Error, FaceKey, HalfedgeKey, Mesh, VertexKey};
use quickcheck::{QuickCheck, TestResult};

/// An open 3×3-cell triangle grid: 16 vertices, boundary all round.
fn grid() -> Mesh {
    let n = 4;
    let mut p = Vec::new();
    for y in 0..n {
        for x in 0..n {
            p.push([x as f64, y as f64, 0.0]);
        }
    }
    let mut faces = Vec::new();
    for y in 0..n - 1 {
        for x in 0..n - 1 {
            let a = (y * n + x) as u32;
            let (b, c, d) = (a + 1, a + n as u32 + 1, a + n as u32);
            faces.push([a, b, c]);
            faces.push([a, c, d]);
        }
    }
    Mesh::from_polygons(&p, &faces).unwrap()
}

fn total<K: meshloom::attr::Element>(
    mesh: &Mesh,
    h: &meshloom::attr::Attr<K, f64, Conserved>,
) -> f64 {
    mesh.attr_view(h).unwrap().iter().map(|(_, v)| *v).sum()
}

// ----- rules through the operators ---------------------------------------------

#[test]
fn interpolate_positions_follow_split_edge() {
    let mut mesh = meshloom::shapes::cube();
    let e = mesh.edges().next().unwrap();
    let [a, b] = mesh.edge(e).unwrap().vertices();
    let (pa, pb) = (mesh.position(a).unwrap(), mesh.position(b).unwrap());
    let m = mesh.split_edge(e, 0.25).unwrap();
    let pm = mesh.position(m).unwrap();
    for k in 0..3 {
        assert!((pm[k] - (0.75 * pa[k] + 0.25 * pb[k])).abs() < 1e-12);
    }
}

#[test]
fn conserved_mass_sums_on_collapse_and_survives_splits() {
    let mut mesh = meshloom::shapes::icosahedron();
    let mass = mesh
        .add_attr_with_rule::<VertexKey, f64, Conserved>("mass")
        .unwrap();
    mesh.fill_attr(&mass, 1.0).unwrap();
    let h = mesh.halfedges().next().unwrap();
    let kept = mesh.collapse_edge(h).unwrap();
    assert_eq!(mesh.attr(&mass, kept).unwrap(), Some(&2.0));
    assert_eq!(total(&mesh, &mass), 12.0);
    let e = mesh.edges().next().unwrap();
    let m = mesh.split_edge(e, 0.5).unwrap();
    // The new vertex takes nothing: no mass is created.
    assert_eq!(mesh.attr(&mass, m).unwrap(), None);
    assert_eq!(total(&mesh, &mass), 12.0);
}

#[test]
fn conserved_face_area_shares_out_on_split_face() {
    let mut mesh = meshloom::shapes::cube();
    let area = mesh
        .add_attr_with_rule::<FaceKey, f64, Conserved>("area")
        .unwrap();
    mesh.fill_attr(&area, 1.0).unwrap();
    let f = mesh.faces().next().unwrap();
    let corners: Vec<_> = mesh.face(f).unwrap().vertices().collect();
    let h = mesh.split_face(f, corners[0], corners[2]).unwrap();
    let other = mesh.halfedge(h).unwrap().twin().face().key();
    let (a, b) = (
        mesh.attr(&area, f).unwrap().copied(),
        mesh.attr(&area, other).unwrap().copied(),
    );
    assert_eq!(a.unwrap() + b.unwrap(), 1.0);
    assert!((a.unwrap() - 0.5).abs() < 1e-12);
    // Holes count too: a face removed becomes a hole and its area goes.
    assert_eq!(total(&mesh, &area), 7.0 - 1.0);
}

#[test]
fn contagion_flag_spreads_through_collapse() {
    let mut mesh = meshloom::shapes::icosahedron();
    let sel = mesh.add_vertex_attr::<bool>("selected").unwrap();
    mesh.fill_attr(&sel, false).unwrap();
    let h = mesh.halfedges().next().unwrap();
    let a = mesh.halfedge(h).unwrap().origin().key();
    mesh.set_attr(&sel, a, true).unwrap();
    let b = mesh.collapse_edge(h).unwrap();
    assert!(!mesh.contains_vertex(a));
    assert_eq!(mesh.attr(&sel, b).unwrap(), Some(&true));
}

#[test]
fn incompatible_materials_never_mix() {
    let mut mesh = meshloom::shapes::cube();
    let mat = mesh.add_face_attr::<u32>("material").unwrap(); // Incompatible
    let f: Vec<_> = mesh.faces().collect();
    mesh.fill_attr(&mat, 1).unwrap();
    let g = mesh.face(f[0]).unwrap().neighbors().next().unwrap();
    let same = mesh.merge_faces(f[0], g).unwrap();
    assert_eq!(mesh.attr(&mat, same).unwrap(), Some(&1));
    let g = mesh
        .face(same)
        .unwrap()
        .neighbors()
        .find(|&g| mesh.check_merge_faces(same, g).is_ok())
        .unwrap();
    mesh.set_attr(&mat, g, 2).unwrap();
    let mixed = mesh.merge_faces(same, g).unwrap();
    assert_eq!(mesh.attr(&mat, mixed).unwrap(), None);
}

#[test]
fn keep_first_and_discard_on_merge() {
    let mut mesh = meshloom::shapes::cube();
    let first = mesh
        .add_attr_with_rule::<FaceKey, i64, KeepFirst>("first")
        .unwrap();
    let cache = mesh
        .add_attr_with_rule::<FaceKey, f64, Discard>("cache")
        .unwrap();
    let f: Vec<_> = mesh.faces().collect();
    for (i, &fk) in f.iter().enumerate() {
        mesh.set_attr(&first, fk, i as i64).unwrap();
        mesh.set_attr(&cache, fk, 9.0).unwrap();
    }
    let g = mesh.face(f[0]).unwrap().neighbors().next().unwrap();
    let kept = mesh.merge_faces(f[0], g).unwrap();
    assert_eq!(mesh.attr(&first, kept).unwrap(), Some(&0));
    assert_eq!(mesh.attr(&cache, kept).unwrap(), None);
    // Untouched faces keep their cache.
    let untouched = mesh.faces().find(|&x| x != kept).unwrap();
    assert_eq!(mesh.attr(&cache, untouched).unwrap(), Some(&9.0));
}

#[test]
fn corner_uvs_follow_split_edge() {
    let mut mesh = grid();
    let uv = mesh.add_halfedge_attr::<[f32; 2]>("uv").unwrap();
    let hs: Vec<HalfedgeKey> = mesh.halfedges().collect();
    for &h in &hs {
        let p = mesh
            .position(mesh.halfedge(h).unwrap().origin().key())
            .unwrap();
        mesh.set_attr(&uv, h, [p[0] as f32 / 3.0, p[1] as f32 / 3.0])
            .unwrap();
    }
    let e = mesh
        .edges()
        .find(|&e| !mesh.edge(e).unwrap().is_boundary())
        .unwrap();
    let m = mesh.split_edge(e, 0.5).unwrap();
    let pm = mesh.position(m).unwrap();
    for h in mesh.vertex(m).unwrap().outgoing().collect::<Vec<_>>() {
        let got = mesh.attr(&uv, h).unwrap().copied().unwrap();
        assert!(
            (got[0] - pm[0] as f32 / 3.0).abs() < 1e-6,
            "{got:?} at {pm:?}"
        );
        assert!((got[1] - pm[1] as f32 / 3.0).abs() < 1e-6);
    }
}

// ----- keys, handles, views ----------------------------------------------------

#[test]
fn stale_keys_and_handles_are_errors() {
    let mut mesh = meshloom::shapes::icosahedron();
    let w = mesh
        .add_attr_with_rule::<VertexKey, f64, Conserved>("w")
        .unwrap();
    let h = mesh.halfedges().next().unwrap();
    let a = mesh.halfedge(h).unwrap().origin().key();
    mesh.set_attr(&w, a, 1.0).unwrap();
    mesh.collapse_edge(h).unwrap();
    assert_eq!(mesh.attr(&w, a), Err(Error::StaleKey(a.into())));
    assert!(matches!(mesh.set_attr(&w, a, 2.0), Err(Error::StaleKey(_))));
    assert_eq!(mesh.attr_view(&w).unwrap().get(a), None);
    // The freed slot is reused without the old value.
    let e = mesh.edges().next().unwrap();
    let m = mesh.split_edge(e, 0.5).unwrap();
    assert_eq!(m.index(), a.index());
    assert_ne!(m, a);
    assert_eq!(mesh.attr(&w, m).unwrap(), None); // conserved: new vertices take nothing
                                                 // Removed columns make stale handles.
    let v = mesh.vertices().next().unwrap();
    mesh.remove_attr(&w).unwrap();
    assert!(matches!(
        mesh.attr(&w, v),
        Err(Error::AttributeHandle { .. })
    ));
    assert!(mesh.remove_attr(&w).is_err());
    // Lookups by name check the type and rule.
    mesh.add_vertex_attr::<f64>("w").unwrap();
    assert!(matches!(
        mesh.attr_handle::<VertexKey, f32, Interpolate>("w"),
        Err(Error::AttributeType { .. })
    ));
    assert!(matches!(
        mesh.attr_handle::<VertexKey, f64, Conserved>("w"),
        Err(Error::AttributeType { .. })
    ));
    assert!(matches!(
        mesh.attr_handle::<FaceKey, f64, Interpolate>("w"),
        Err(Error::AttributeMissing { .. })
    ));
    assert!(matches!(
        mesh.add_vertex_attr::<u8>("w"),
        Err(Error::AttributeExists { .. })
    ));
}

#[test]
fn removing_a_column_before_positions_keeps_positions() {
    let mut mesh = meshloom::shapes::cube();
    let pos = mesh.position_attr().unwrap();
    let v = mesh.vertices().next().unwrap();
    let p = mesh.position(v).unwrap();
    let extra = mesh.add_vertex_attr::<f64>("extra").unwrap();
    mesh.remove_attr(&extra).unwrap();
    assert_eq!(mesh.attr(&pos, v).unwrap(), Some(&p));
    assert!(matches!(
        mesh.set_attr(&pos, v, [f64::NAN, 0.0, 0.0]),
        Err(Error::NonFinitePosition { .. })
    ));
    mesh.remove_attr(&pos).unwrap();
    assert!(!mesh.has_positions());
    assert_eq!(mesh.position(v), Err(Error::NoPositions));
}

#[test]
fn views_iterate_live_elements_with_values() {
    let mut mesh = meshloom::shapes::cube();
    let c: FaceAttr<[f32; 3]> = mesh.add_face_attr("colour").unwrap();
    let f: Vec<_> = mesh.faces().collect();
    for (i, &fk) in f.iter().enumerate().step_by(2) {
        mesh.set_attr(&c, fk, [i as f32, 0.0, 0.0]).unwrap();
    }
    let seen: Vec<FaceKey> = mesh.attr_view(&c).unwrap().iter().map(|(k, _)| k).collect();
    assert_eq!(seen, [f[0], f[2], f[4]]);
    let mut view = mesh.attr_view_mut(&c).unwrap();
    for (_, v) in view.iter_mut() {
        v[1] = 1.0;
    }
    view.set(f[0], None).unwrap();
    assert_eq!(view.get(f[0]), None);
    assert_eq!(view.get(f[2]), Some(&[2.0, 1.0, 0.0]));
    assert_eq!(mesh.clear_attr(&c, f[2]).unwrap(), Some([2.0, 1.0, 0.0]));
    assert_eq!(mesh.attr_view(&c).unwrap().iter().count(), 1);
}

#[test]
fn hole_faces_carry_face_attributes() {
    let mut mesh = grid();
    let tag = mesh.add_face_attr::<String>("tag").unwrap();
    let hole = mesh.holes().next().unwrap();
    mesh.set_attr(&tag, hole, "outside".to_owned()).unwrap();
    assert_eq!(
        mesh.attr(&tag, hole).unwrap().map(String::as_str),
        Some("outside")
    );
    mesh.fill_attr(&tag, "all".to_owned()).unwrap();
    assert_eq!(
        mesh.attr_view(&tag).unwrap().iter().count(),
        mesh.face_count() + 1
    );
}

#[test]
fn dynamic_columns_carry_runtime_types() {
    let mut mesh = meshloom::shapes::icosahedron();
    let q = mesh
        .add_dynamic_attr::<VertexKey>("quality", ValueType::F32)
        .unwrap();
    mesh.fill_attr(&q, Value::F32(1.0)).unwrap();
    let v = mesh.vertices().next().unwrap();
    mesh.set_attr(&q, v, Value::F32(3.0)).unwrap();
    assert!(matches!(
        mesh.set_attr(&q, v, Value::Text("x".into())),
        Err(Error::AttributeType { .. })
    ));
    // Interpolated like a float along a split edge.
    let h = mesh.vertex(v).unwrap().outgoing().next().unwrap();
    let m = mesh.split_edge(h.edge_key(), 0.5).unwrap();
    let got = mesh.attr(&q, m).unwrap().cloned();
    assert!(
        matches!(got, Some(Value::F32(x)) if (x - 2.0).abs() < 1e-6),
        "{got:?}"
    );
    // Any portable column reads and writes by name.
    let w = mesh.add_vertex_attr::<f64>("w").unwrap();
    mesh.set_attr_value("w", v, Some(&Value::F64(0.5))).unwrap();
    assert_eq!(mesh.attr(&w, v).unwrap(), Some(&0.5));
    assert!(mesh.set_attr_value("w", v, Some(&Value::U8(1))).is_err());
    assert!(mesh.set_attr_value("nope", v, None).is_err());
    mesh.set_attr_value("position", v, Some(&[1.0f64, 2.0, 3.0].to_value_list()))
        .unwrap();
    assert_eq!(mesh.position(v).unwrap(), [1.0, 2.0, 3.0]);
    let info = mesh.attr_info(meshloom::ElementKind::Vertex);
    assert_eq!(info[1].value_type, Some(ValueType::F32));
    assert!(info[1].dynamic);
}

trait ToValueList {
    fn to_value_list(&self) -> Value;
}

impl ToValueList for [f64; 3] {
    fn to_value_list(&self) -> Value {
        Value::List(self.iter().map(|&x| Value::F64(x)).collect())
    }
}

// ----- random operation streams ---------------------------------------------------

/// One operation, chosen from raw numbers so that quickcheck can shrink it.
#[derive(Clone, Copy, Debug)]
struct Step(u8, u16, u16);

impl quickcheck::Arbitrary for Step {
    fn arbitrary(g: &mut quickcheck::Gen) -> Self {
        Step(u8::arbitrary(g), u16::arbitrary(g), u16::arbitrary(g))
    }
    fn shrink(&self) -> Box<dyn Iterator<Item = Self>> {
        let s = *self;
        Box::new((0..s.1).rev().take(3).map(move |i| Step(s.0, i, s.2)))
    }
}

/// Which totals an operation keeps (the operators' docs say which merge,
/// which split, and which delete).
struct Keeps {
    vertex_total: bool,
    face_total: bool,
    /// Whether the operation ran (was not refused).
    ran: bool,
}

fn pick<T: Copy>(items: &[T], i: u16) -> Option<T> {
    (!items.is_empty()).then(|| items[i as usize % items.len()])
}

/// Apply one step; refused operations change nothing. Returns what the
/// operation keeps.
fn apply(mesh: &mut Mesh, s: Step) -> Keeps {
    let v: Vec<VertexKey> = mesh.vertices().collect();
    let e: Vec<EdgeKey> = mesh.edges().collect();
    let h: Vec<HalfedgeKey> = mesh.halfedges().collect();
    let f: Vec<FaceKey> = mesh.faces().collect();
    let t = f64::from(s.2 % 101) / 100.0;
    let mut ran = false;
    let (mut vertex_total, mut face_total) = (true, true);
    match s.0 % 8 {
        0 => {
            if let Some(e) = pick(&e, s.1) {
                ran = mesh.split_edge(e, t).is_ok();
            }
        }
        1 => {
            if let Some(f) = pick(&f, s.1) {
                let c: Vec<_> = mesh.face(f).unwrap().vertices().collect();
                let (a, b) = (c[0], c[(s.2 as usize % (c.len() - 1)) + 1]);
                ran = mesh.split_face(f, a, b).is_ok();
            }
        }
        2 => {
            if let Some(f) = pick(&f, s.1) {
                ran = mesh.poke_face(f).is_ok();
            }
        }
        3 | 4 => {
            if let Some(h) = pick(&h, s.1) {
                if mesh.vertex_count() > 5 {
                    ran = mesh.collapse_edge_at(h, t).is_ok();
                }
            }
        }
        5 => {
            if let Some(e) = pick(&e, s.1) {
                ran = mesh.flip_edge(e).is_ok();
            }
        }
        6 => {
            // A face that joins a hole is deleted, like remove_face.
            let mut interior = true;
            if let Some(e) = pick(&e, s.1) {
                interior = !mesh.edge(e).unwrap().is_boundary();
                ran = mesh.remove_edge(e).is_ok();
            }
            vertex_total = false;
            face_total = interior;
        }
        _ => {
            let mut interior = true;
            if let Some(v) = pick(&v, s.1) {
                interior = !mesh.vertex(v).unwrap().is_boundary();
                ran = mesh.remove_vertex(v).is_ok();
            }
            vertex_total = false;
            face_total = interior;
        }
    }
    Keeps {
        vertex_total,
        face_total,
        ran,
    }
}

/// A mesh with a conserved vertex mass, a conserved face area, a contagious
/// vertex flag and an incompatible face material (an f64, so mixing would
/// show as a new number).
struct Decorated {
    mesh: Mesh,
    mass: VertexAttr<f64, Conserved>,
    area: FaceAttr<f64, Conserved>,
    flag: VertexAttr<bool, Contagion>,
    material: FaceAttr<f64, Incompatible>,
}

fn decorated(base: Mesh, seed: u16) -> Decorated {
    let mut mesh = base;
    let mass = mesh
        .add_attr_with_rule::<VertexKey, f64, Conserved>("mass")
        .unwrap();
    let area = mesh
        .add_attr_with_rule::<FaceKey, f64, Conserved>("area")
        .unwrap();
    let flag = mesh.add_vertex_attr::<bool>("flag").unwrap();
    let material = mesh
        .add_attr_with_rule::<FaceKey, f64, Incompatible>("material")
        .unwrap();
    for (i, v) in mesh.vertices().collect::<Vec<_>>().into_iter().enumerate() {
        mesh.set_attr(&mass, v, 1.0 + (i % 3) as f64).unwrap();
        mesh.set_attr(&flag, v, (i + seed as usize) % 4 == 0)
            .unwrap();
    }
    for (i, f) in mesh.faces().collect::<Vec<_>>().into_iter().enumerate() {
        mesh.set_attr(&area, f, 0.5 + (i % 2) as f64).unwrap();
        mesh.set_attr(&material, f, ((i + seed as usize) % 3) as f64)
            .unwrap();
    }
    Decorated {
        mesh,
        mass,
        area,
        flag,
        material,
    }
}

fn base(which: u8) -> Mesh {
    match which % 3 {
        0 => meshloom::shapes::icosahedron(),
        1 => grid(),
        _ => meshloom::shapes::cube(),
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(1.0)
}

fn rules_hold(which: u8, seed: u16, steps: Vec<Step>) -> TestResult {
    let mut d = decorated(base(which), seed);
    for s in steps.into_iter().take(40) {
        let (vt, ft) = (total(&d.mesh, &d.mass), total(&d.mesh, &d.area));
        let flagged: Vec<VertexKey> = d
            .mesh
            .attr_view(&d.flag)
            .unwrap()
            .iter()
            .filter(|(_, f)| **f)
            .map(|(k, _)| k)
            .collect();
        let keeps = apply(&mut d.mesh, s);
        if let Err(e) = d.mesh.validate() {
            return TestResult::error(format!("{s:?}: {e}"));
        }
        if keeps.vertex_total && !close(vt, total(&d.mesh, &d.mass)) {
            return TestResult::error(format!("{s:?} changed the vertex mass {vt}"));
        }
        if keeps.face_total && !close(ft, total(&d.mesh, &d.area)) {
            return TestResult::error(format!("{s:?} changed the face area {ft}"));
        }
        for v in flagged {
            if d.mesh.contains_vertex(v) && d.mesh.attr(&d.flag, v).unwrap() != Some(&true) {
                return TestResult::error(format!("{s:?} unflagged {v:?}"));
            }
        }
        if let Some((f, m)) = d
            .mesh
            .attr_view(&d.material)
            .unwrap()
            .iter()
            .find(|(_, m)| ![0.0, 1.0, 2.0].contains(*m))
        {
            return TestResult::error(format!("{s:?} mixed materials into {m} on {f:?}"));
        }
    }
    TestResult::passed()
}

#[test]
fn random_streams_mostly_edit() {
    // The properties below mean something only if most steps do run.
    let mut d = decorated(base(0), 1);
    let mut x: u32 = 12345;
    let mut ran = 0;
    for _ in 0..200 {
        x = x.wrapping_mul(1_103_515_245).wrapping_add(12_345);
        let s = Step((x >> 8) as u8, (x >> 12) as u16, (x >> 3) as u16);
        ran += usize::from(apply(&mut d.mesh, s).ran);
    }
    assert!(ran >= 80, "only {ran} of 200 steps ran");
}

#[test]
fn rules_hold_over_random_operation_streams() {
    QuickCheck::new()
        .tests(150)
        .quickcheck(rules_hold as fn(u8, u16, Vec<Step>) -> TestResult);
}

#[cfg(feature = "serde")]
fn deterministic(which: u8, seed: u16, steps: Vec<Step>) -> bool {
    let run = || {
        let mut d = decorated(base(which), seed);
        let uv = d.mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
        d.mesh.fill_attr(&uv, [0.25, 0.75]).unwrap();
        for &s in steps.iter().take(30) {
            apply(&mut d.mesh, s);
        }
        serde_json::to_string(&d.mesh).unwrap()
    };
    run() == run()
}

#[cfg(feature = "serde")]
#[test]
fn same_operations_give_same_values() {
    QuickCheck::new()
        .tests(60)
        .quickcheck(deterministic as fn(u8, u16, Vec<Step>) -> bool);
}

// ----- one test per remaining operator ------------------------------------------

/// The cube with a conserved face area of 1 per face, a face colour and a
/// conserved vertex mass of 1 per vertex.
type Weighed = (
    Mesh,
    FaceAttr<f64, Conserved>,
    FaceAttr<[f32; 3]>,
    VertexAttr<f64, Conserved>,
);

fn weighed_cube() -> Weighed {
    let mut mesh = meshloom::shapes::cube();
    let area = mesh
        .add_attr_with_rule::<FaceKey, f64, Conserved>("area")
        .unwrap();
    let colour = mesh.add_face_attr::<[f32; 3]>("colour").unwrap();
    let mass = mesh
        .add_attr_with_rule::<VertexKey, f64, Conserved>("mass")
        .unwrap();
    for (i, f) in mesh.faces().collect::<Vec<_>>().into_iter().enumerate() {
        mesh.set_attr(&area, f, 1.0).unwrap();
        mesh.set_attr(&colour, f, [i as f32, 0.0, 0.0]).unwrap();
    }
    mesh.fill_attr(&mass, 1.0).unwrap();
    (mesh, area, colour, mass)
}

#[test]
fn poke_face_centre_is_the_centroid_and_pieces_share_the_area() {
    let (mut mesh, area, colour, mass) = weighed_cube();
    let f = mesh.faces().next().unwrap();
    let centroid = mesh.face_centroid(f).unwrap();
    let c = mesh.poke_face(f).unwrap();
    assert_eq!(mesh.position(c).unwrap(), centroid);
    assert_eq!(mesh.attr(&mass, c).unwrap(), None);
    let pieces: Vec<FaceKey> = mesh.vertex(c).unwrap().faces().collect();
    assert_eq!(pieces.len(), 4);
    let shared: f64 = pieces
        .iter()
        .map(|&p| mesh.attr(&area, p).unwrap().unwrap())
        .sum();
    assert!((shared - 1.0).abs() < 1e-12);
    for p in pieces {
        assert_eq!(mesh.attr(&colour, p).unwrap(), Some(&[0.0, 0.0, 0.0]));
    }
    assert!((total(&mesh, &area) - 6.0).abs() < 1e-12);
}

#[test]
fn triangulate_shares_out_and_copies() {
    let (mut mesh, area, colour, _) = weighed_cube();
    let f = mesh.faces().nth(1).unwrap();
    let tris = mesh.triangulate(f).unwrap();
    assert_eq!(tris.len(), 2);
    for &t in &tris {
        assert!((mesh.attr(&area, t).unwrap().unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(mesh.attr(&colour, t).unwrap(), Some(&[1.0, 0.0, 0.0]));
    }
}

#[test]
fn flip_edge_keeps_totals_and_edge_values() {
    let mut mesh = meshloom::shapes::icosahedron();
    let area = mesh
        .add_attr_with_rule::<FaceKey, f64, Conserved>("area")
        .unwrap();
    let crease = mesh.add_edge_attr::<f32>("crease").unwrap();
    let faces: Vec<FaceKey> = mesh.faces().collect();
    for (i, &f) in faces.iter().enumerate() {
        mesh.set_attr(&area, f, i as f64).unwrap();
    }
    let e = mesh.edges().next().unwrap();
    mesh.set_attr(&crease, e, 0.75).unwrap();
    let before = total(&mesh, &area);
    let e = mesh.flip_edge(e).unwrap();
    assert_eq!(total(&mesh, &area), before);
    assert_eq!(mesh.attr(&crease, e).unwrap(), Some(&0.75));
}

#[test]
fn remove_vertex_merges_its_ring() {
    let (mut mesh, area, colour, mass) = weighed_cube();
    let v = mesh.vertices().next().unwrap();
    let f = mesh.remove_vertex(v).unwrap();
    assert_eq!(mesh.attr(&area, f).unwrap(), Some(&3.0));
    // Three different colours average.
    assert!(mesh.attr(&colour, f).unwrap().is_some());
    // The removed vertex's value goes with it.
    assert!(mesh.attr(&mass, v).is_err());
    assert_eq!(total(&mesh, &mass), 7.0);
}

#[test]
fn remove_face_drops_and_fill_hole_starts_empty() {
    let (mut mesh, area, colour, _) = weighed_cube();
    let f = mesh.faces().next().unwrap();
    let holes = mesh.remove_face(f).unwrap();
    assert_eq!(total(&mesh, &area), 5.0);
    let filled = mesh.fill_hole(holes[0]).unwrap();
    assert_eq!(mesh.attr(&area, filled).unwrap(), None);
    assert_eq!(mesh.attr(&colour, filled).unwrap(), None);
    // Interpolated values can be inferred from the neighbours on demand.
    assert!(mesh.infer_attr(&colour, filled).unwrap().is_some());
}

#[test]
fn compact_moves_values_with_their_elements() {
    let (mut mesh, area, colour, mass) = weighed_cube();
    let uv = mesh.add_halfedge_attr::<[f32; 2]>("uv").unwrap();
    for (i, h) in mesh.halfedges().collect::<Vec<_>>().into_iter().enumerate() {
        mesh.set_attr(&uv, h, [i as f32, 0.0]).unwrap();
    }
    let h = mesh.halfedges().nth(5).unwrap();
    mesh.collapse_edge(h).unwrap();
    let before: Vec<(VertexKey, Option<f64>, [f64; 3])> = mesh
        .vertices()
        .map(|v| {
            (
                v,
                mesh.attr(&mass, v).unwrap().copied(),
                mesh.position(v).unwrap(),
            )
        })
        .collect();
    let corner_before: Vec<(HalfedgeKey, Option<[f32; 2]>)> = mesh
        .halfedges()
        .map(|h| (h, mesh.attr(&uv, h).unwrap().copied()))
        .collect();
    let face_before: Vec<(FaceKey, Option<f64>, Option<[f32; 3]>)> = mesh
        .faces()
        .map(|f| {
            (
                f,
                mesh.attr(&area, f).unwrap().copied(),
                mesh.attr(&colour, f).unwrap().copied(),
            )
        })
        .collect();
    let maps = mesh.compact();
    for (v, m, p) in before {
        let w = maps.vertex(v).unwrap();
        assert_eq!(mesh.attr(&mass, w).unwrap().copied(), m);
        assert_eq!(mesh.position(w).unwrap(), p);
    }
    for (h, x) in corner_before {
        assert_eq!(
            mesh.attr(&uv, maps.halfedge(h).unwrap()).unwrap().copied(),
            x
        );
    }
    for (f, a, c) in face_before {
        let g = maps.face(f).unwrap();
        assert_eq!(mesh.attr(&area, g).unwrap().copied(), a);
        assert_eq!(mesh.attr(&colour, g).unwrap().copied(), c);
    }
    mesh.validate().unwrap();
}

#[test]
fn reads_by_key_agree_on_fresh_and_edited_meshes() {
    // A fresh mesh reads through the fast path (no slot ever freed, every
    // value present); a collapse frees slots and a cleared value adds
    // presence bits, which switch to the checked path. Both must agree.
    let mut mesh = meshloom::shapes::icosphere(2);
    let pos = mesh.position_attr().expect("positions");
    let keys: Vec<VertexKey> = mesh.vertices().collect();
    {
        let view = mesh.attr_view(&pos).unwrap();
        for &v in &keys {
            assert_eq!(view.get(v).copied(), Some(mesh.position(v).unwrap()));
        }
        // A key of a larger mesh names no slot here.
        let far = meshloom::shapes::icosphere(3).vertices().last().unwrap();
        assert_eq!(view.get(far), None);
    }
    let h = mesh.vertex(keys[0]).unwrap().halfedge().key();
    let gone = mesh.halfedge(h).unwrap().origin().key();
    mesh.collapse_edge(h).unwrap();
    let weight = mesh.add_vertex_attr::<f64>("weight").unwrap();
    let view = mesh.attr_view(&pos).unwrap();
    assert_eq!(view.get(gone), None, "the collapsed vertex's key is stale");
    for &v in keys.iter().filter(|&&v| v != gone) {
        assert_eq!(view.get(v).copied(), Some(mesh.position(v).unwrap()));
    }
    let wview = mesh.attr_view(&weight).unwrap();
    assert!(keys.iter().all(|&v| wview.get(v).is_none()));
}

#[test]
fn reads_by_key_on_columns_with_gaps_before_and_after_compact() {
    // An intact arena stores no generations; a column with gaps on it (and
    // a half-edge column, two values per edge slot) reads through the
    // checked path, which must take the base for the generation, refuse a
    // key of a larger mesh, and refuse every key from before `compact()`;
    // the same path reads the written-out generations of an edited arena.
    let mut mesh = grid();
    {
        // A first pass on the intact arenas, before any edit.
        let w = mesh.add_vertex_attr::<f64>("w").unwrap();
        let vs: Vec<VertexKey> = mesh.vertices().collect();
        mesh.set_attr(&w, vs[5], 2.0).unwrap();
        let view = mesh.attr_view(&w).unwrap();
        for &v in &vs {
            assert_eq!(view.get(v).copied(), (v == vs[5]).then_some(2.0));
        }
        let big = meshloom::shapes::icosphere(3);
        assert_eq!(view.get(big.vertices().last().unwrap()), None);
    }
    // A collapse frees a slot in every arena (generations written out),
    // so that `compact()` moves elements and raises every base.
    let inner = mesh.vertices().nth(5).unwrap();
    let h = mesh.vertex(inner).unwrap().halfedge().key();
    mesh.collapse_edge(h).unwrap();
    let tag = mesh.add_halfedge_attr::<u32>("tag").unwrap();
    let weight = mesh.add_vertex_attr::<f64>("weight").unwrap();
    let hs: Vec<HalfedgeKey> = mesh.halfedges().collect();
    let vs: Vec<VertexKey> = mesh.vertices().collect();
    for (i, &h) in hs.iter().enumerate().filter(|(i, _)| i % 3 == 0) {
        mesh.set_attr(&tag, h, i as u32).unwrap();
    }
    for (i, &v) in vs.iter().enumerate().filter(|(i, _)| i % 2 == 1) {
        mesh.set_attr(&weight, v, i as f64).unwrap();
    }
    let check = |mesh: &Mesh, hs: &[HalfedgeKey], vs: &[VertexKey]| {
        let tview = mesh.attr_view(&tag).unwrap();
        for (i, &h) in hs.iter().enumerate() {
            let want = (i % 3 == 0).then_some(i as u32);
            assert_eq!(tview.get(h).copied(), want, "half-edge {i}");
        }
        let wview = mesh.attr_view(&weight).unwrap();
        for (i, &v) in vs.iter().enumerate() {
            let want = (i % 2 == 1).then_some(i as f64);
            assert_eq!(wview.get(v).copied(), want, "vertex {i}");
        }
        let big = meshloom::shapes::icosphere(3);
        assert_eq!(wview.get(big.vertices().last().unwrap()), None);
        assert_eq!(tview.get(big.halfedges().last().unwrap()), None);
    };
    check(&mesh, &hs, &vs);
    let maps = mesh.compact();
    let new_hs: Vec<HalfedgeKey> = hs.iter().map(|&h| maps.halfedge(h).unwrap()).collect();
    let new_vs: Vec<VertexKey> = vs.iter().map(|&v| maps.vertex(v).unwrap()).collect();
    check(&mesh, &new_hs, &new_vs);
    let (tview, wview) = (
        mesh.attr_view(&tag).unwrap(),
        mesh.attr_view(&weight).unwrap(),
    );
    assert!(
        hs.iter().all(|&h| tview.get(h).is_none()),
        "stale half-edge keys"
    );
    assert!(
        vs.iter().all(|&v| wview.get(v).is_none()),
        "stale vertex keys"
    );
}
