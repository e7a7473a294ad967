use super::*;
use crate::attr::{Attr, Conserved};
use crate::journal::HistoryLimits;
use crate::model::testing::{field, fingerprint, mixed_meshes, next_random};
use crate::shapes::{self, GridFaces};
use crate::{Error, FaceKey, HalfedgeKey};

type Mass = Attr<FaceKey, f64, Conserved>;

/// A cube whose sides are finely triangulated: every edge split at its
/// middle, every side poked (a fan of 8 triangles), every triangle poked:
/// 144 flat triangles, 74 vertices.
fn fine_cube() -> Mesh {
    let mut mesh = shapes::cube();
    for e in mesh.edges().collect::<Vec<_>>() {
        mesh.split_edge(e, 0.5).unwrap();
    }
    for _ in 0..2 {
        for f in mesh.faces().collect::<Vec<_>>() {
            mesh.poke_face(f).unwrap();
        }
    }
    mesh
}

fn centre(mesh: &Mesh, f: FaceKey) -> V3 {
    let vs: Vec<V3> = mesh
        .face(f)
        .unwrap()
        .vertices()
        .map(|v| mesh.position(v).unwrap())
        .collect();
    let n = vs.len() as f64;
    std::array::from_fn(|k| vs.iter().map(|p| p[k]).sum::<f64>() / n)
}

fn with_mass(mesh: &mut Mesh) -> Mass {
    let mass = mesh
        .add_attr_with_rule::<FaceKey, f64, Conserved>("mass")
        .unwrap();
    for (i, f) in mesh.faces().collect::<Vec<_>>().into_iter().enumerate() {
        mesh.set_attr(&mass, f, 1.0 + (i % 7) as f64).unwrap();
    }
    mass
}

fn total(mesh: &Mesh, mass: &Mass) -> f64 {
    mesh.faces()
        .filter_map(|f| mesh.attr(mass, f).unwrap().copied())
        .sum()
}

/// Validate, and every face has an area.
fn sound(mesh: &Mesh) {
    mesh.validate().unwrap();
    for f in mesh.faces() {
        assert!(mesh.face_area(f).unwrap() > 1e-12, "a face without area");
    }
}

#[test]
fn a_finely_triangulated_cube_becomes_its_six_sides() {
    let mut mesh = fine_cube();
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (74, 144));
    let mass = with_mass(&mut mesh);
    let before = total(&mesh, &mass);
    let d = mesh
        .dissolve_limited(&DissolveLimitedOptions::default())
        .unwrap();
    sound(&mesh);
    assert_eq!(
        (mesh.vertex_count(), mesh.edge_count(), mesh.face_count()),
        (8, 12, 6)
    );
    assert_eq!(d.faces.len(), 6);
    assert!(mesh.faces().all(|f| mesh.face(f).unwrap().degree() == 4));
    assert!((total(&mesh, &mass) - before).abs() < 1e-9);
}

#[test]
fn a_material_column_splits_the_sides() {
    let mut mesh = fine_cube();
    let material = mesh.add_face_attr::<u32>("material").unwrap();
    // The top side's half with x below the middle gets material 1.
    let top = mesh
        .faces()
        .map(|f| centre(&mesh, f)[2])
        .fold(f64::MIN, f64::max);
    let mid = mesh.faces().map(|f| centre(&mesh, f)[0]).sum::<f64>() / mesh.face_count() as f64;
    for f in mesh.faces().collect::<Vec<_>>() {
        let c = centre(&mesh, f);
        let m = u32::from((c[2] - top).abs() < 1e-9 && c[0] < mid);
        mesh.set_attr(&material, f, m).unwrap();
    }
    let mut named = mesh.clone();
    mesh.dissolve_limited(&DissolveLimitedOptions::default())
        .unwrap();
    sound(&mesh);
    // An incompatible column delimits by itself: the top splits in two.
    assert_eq!(mesh.face_count(), 7);
    let ones = mesh
        .faces()
        .filter(|&f| mesh.attr(&material, f).unwrap() == Some(&1))
        .count();
    assert_eq!(ones, 1);
    assert!(mesh
        .faces()
        .all(|f| mesh.attr(&material, f).unwrap().is_some()));
    // Named as a delimiter, the same.
    let o = DissolveLimitedOptions {
        delimit: Delimit {
            material: Some("material".into()),
            ..Delimit::default()
        },
        ..Default::default()
    };
    named.dissolve_limited(&o).unwrap();
    assert_eq!(named.face_count(), 7);
}

#[test]
fn uv_seams_delimit_and_corners_keep_their_values() {
    let mut mesh = shapes::grid(6, 4, GridFaces::Triangles);
    let uv = mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let uv_of = |p: V3, right: bool| {
        let [u, v] = field(p);
        [u + if right { 10.0 } else { 0.0 }, v]
    };
    for f in mesh.faces().collect::<Vec<_>>() {
        let right = centre(&mesh, f)[0] > 3.0;
        for h in mesh
            .face(f)
            .unwrap()
            .halfedges()
            .collect::<Vec<HalfedgeKey>>()
        {
            let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
            mesh.set_attr(&uv, h, uv_of(p, right)).unwrap();
        }
    }
    let mut plain = mesh.clone();
    plain
        .dissolve_limited(&DissolveLimitedOptions::default())
        .unwrap();
    sound(&plain);
    assert_eq!((plain.face_count(), plain.vertex_count()), (1, 4));
    let o = DissolveLimitedOptions {
        delimit: Delimit {
            seams: Some("uv".into()),
            ..Delimit::default()
        },
        ..Default::default()
    };
    mesh.dissolve_limited(&o).unwrap();
    sound(&mesh);
    // Two rectangles either side of x = 3 (the seam's inner vertices
    // are left between two collinear edges and go).
    assert_eq!((mesh.face_count(), mesh.vertex_count()), (2, 6));
    for f in mesh.faces() {
        let right = centre(&mesh, f)[0] > 3.0;
        for h in mesh.face(f).unwrap().halfedges() {
            let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
            assert_eq!(*mesh.attr(&uv, h).unwrap().unwrap(), uv_of(p, right));
        }
    }
}

#[test]
fn an_angle_limit_keeps_the_bends_and_a_selection_keeps_the_rest() {
    // A triangulated grid folded along x = 2 by 20°.
    let mut mesh = shapes::grid(4, 3, GridFaces::Triangles);
    let (s, c) = 20f64.to_radians().sin_cos();
    let ps = mesh.position_slots_mut().unwrap();
    for p in ps.iter_mut() {
        if p[0] > 2.0 {
            let d = p[0] - 2.0;
            *p = [2.0 + d * c, p[1], d * s];
        }
    }
    let mut wide = mesh.clone();
    let mut some = mesh.clone();
    mesh.dissolve_limited(&DissolveLimitedOptions::default())
        .unwrap();
    sound(&mesh);
    assert_eq!((mesh.face_count(), mesh.vertex_count()), (2, 6));
    wide.dissolve_limited(&DissolveLimitedOptions {
        angle: 30f64.to_radians(),
        ..Default::default()
    })
    .unwrap();
    sound(&wide);
    assert_eq!(wide.face_count(), 1);
    // Only the edges whose middle is left of x = 1 may merge, no vertex
    // may go.
    let edges: Vec<EdgeKey> = some
        .edges()
        .filter(|&e| {
            let [a, b] = some.edge(e).unwrap().vertices();
            some.position(a).unwrap()[0] + some.position(b).unwrap()[0] < 2.0
        })
        .collect();
    let faces = some.face_count();
    some.dissolve_limited(&DissolveLimitedOptions {
        edges: Some(edges),
        vertices: Some(Vec::new()),
        ..Default::default()
    })
    .unwrap();
    sound(&some);
    // The column of 6 triangles left of x = 1 becomes one face.
    assert_eq!(some.face_count(), faces - 5);
}

#[test]
fn refusals_change_nothing_and_a_dissolve_is_one_undo_step() {
    let mut mesh = fine_cube();
    mesh.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&mesh);
    for angle in [f64::NAN, -1.0, f64::INFINITY] {
        let o = DissolveLimitedOptions {
            angle,
            ..Default::default()
        };
        let err = mesh.dissolve_limited(&o).unwrap_err();
        assert!(
            matches!(
                err,
                Error::Refused {
                    reason: Refusal::Parameter(_),
                    ..
                }
            ),
            "{err:?}"
        );
        assert!(mesh.check_dissolve_limited(&o).is_err());
        assert_eq!(fingerprint(&mesh), before);
    }
    let missing = DissolveLimitedOptions {
        delimit: Delimit {
            seams: Some("nope".into()),
            ..Delimit::default()
        },
        ..Default::default()
    };
    assert!(matches!(
        mesh.dissolve_limited(&missing),
        Err(Error::AttributeMissing { .. })
    ));
    assert_eq!(fingerprint(&mesh), before);
    let undo = mesh.history().undo_len();
    mesh.dissolve_limited(&DissolveLimitedOptions::default())
        .unwrap();
    assert_eq!(mesh.history().undo_len(), undo + 1);
    assert_eq!(mesh.face_count(), 6);
    assert!(mesh.undo());
    assert_eq!(fingerprint(&mesh), before);
}

#[test]
fn random_meshes_and_angles_dissolve_into_sound_faces() {
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    for mesh in mixed_meshes() {
        for round in 0..6 {
            let mut m = mesh.clone();
            let mass = with_mass(&mut m);
            let before = total(&m, &mass);
            let angle = (5.0 + (next_random(&mut seed) % 60) as f64).to_radians();
            let o = DissolveLimitedOptions {
                angle,
                boundaries: round % 2 == 1,
                ..Default::default()
            };
            m.dissolve_limited(&o).unwrap();
            sound(&m);
            assert!((total(&m, &mass) - before).abs() < 1e-9 * before);
        }
    }
}
