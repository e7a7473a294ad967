use super::*;
use crate::attr::{Conserved, FaceAttr, HalfedgeAttr};
use crate::journal::HistoryLimits;
use crate::model::testing::{field, fingerprint, mixed_meshes, random_faces};
use crate::shapes::{self, GridFaces};
use crate::Error;

fn opts(thickness: f64, individual: bool) -> InsetOptions {
    InsetOptions {
        thickness,
        individual,
        ..Default::default()
    }
}

/// A planar grid: corner UVs from a linear field, a material per column
/// of quads, a conserved face quantity of 1 a face.
fn textured_grid(n: usize) -> (Mesh, HalfedgeAttr<[f64; 2]>, FaceAttr<u32>) {
    let mut mesh = shapes::grid(n, n, GridFaces::Quads);
    let uv = mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let material = mesh.add_face_attr::<u32>("material").unwrap();
    let mass = mesh
        .add_attr_with_rule::<FaceKey, f64, Conserved>("mass")
        .unwrap();
    for h in mesh.halfedges().collect::<Vec<_>>() {
        let view = mesh.halfedge(h).unwrap();
        if !view.is_boundary() {
            let p = view.origin().position().unwrap();
            mesh.set_attr(&uv, h, field(p)).unwrap();
        }
    }
    for f in mesh.faces().collect::<Vec<_>>() {
        let x = mesh
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| mesh.position(v).unwrap()[0])
            .sum::<f64>()
            / 4.0;
        mesh.set_attr(&material, f, x as u32).unwrap();
        mesh.set_attr(&mass, f, 1.0).unwrap();
    }
    (mesh, uv, material)
}

/// Every corner carries the field at its vertex; the masses sum to `total`.
fn check_fields(mesh: &Mesh, uv: &HalfedgeAttr<[f64; 2]>, total: f64) {
    for h in mesh
        .halfedges()
        .filter(|&h| !mesh.halfedge(h).unwrap().is_boundary())
    {
        let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
        let got = *mesh.attr(uv, h).unwrap().unwrap();
        let want = field(p);
        assert!(
            (got[0] - want[0]).abs() < 1e-12 && (got[1] - want[1]).abs() < 1e-12,
            "{got:?} at {p:?}"
        );
    }
    let sum: f64 = mesh
        .faces()
        .map(|f| {
            mesh.attr_value("mass", f)
                .unwrap()
                .unwrap()
                .as_f64()
                .unwrap()
        })
        .sum();
    assert!((sum - total).abs() < 1e-9, "{sum}");
}

#[test]
fn every_face_of_a_cube_inset_on_its_own() {
    let mut cube = shapes::cube();
    let all: Vec<FaceKey> = cube.faces().collect();
    let made = cube.inset_faces(&all, &opts(0.2, true)).unwrap();
    cube.validate().unwrap();
    assert_eq!(
        (cube.vertex_count(), cube.edge_count(), cube.face_count()),
        (32, 60, 30)
    );
    assert_eq!(
        (made.inner.len(), made.rim.len(), made.vertices.len()),
        (6, 24, 24)
    );
    // Each inner face is its face shrunk by 0.2 on every side: 0.6 wide.
    for &f in &made.inner {
        let ps: Vec<V3> = cube
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| cube.position(v).unwrap())
            .collect();
        for k in 0..4 {
            let d = vec3::norm(vec3::sub(ps[(k + 1) % 4], ps[k]));
            assert!((d - 0.6).abs() < 1e-12, "{d}");
        }
    }
}

#[test]
fn individual_insets_keep_a_linear_uv_field_materials_and_conserved_totals() {
    let (mut mesh, uv, material) = textured_grid(4);
    let all: Vec<FaceKey> = mesh.faces().collect();
    let made = mesh.inset_faces(&all, &opts(0.2, true)).unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.face_count(), 16 * 5);
    check_fields(&mesh, &uv, 16.0);
    // The rim quads are pieces of their face: its material.
    for (k, &f) in made.inner.iter().enumerate() {
        let m = mesh.attr(&material, f).unwrap().copied();
        for &r in &made.rim[4 * k..4 * k + 4] {
            assert_eq!(mesh.attr(&material, r).unwrap().copied(), m);
        }
    }
}

#[test]
fn a_region_inset_moves_its_outline_in_by_the_thickness_and_keeps_the_fields() {
    let (mut mesh, uv, _) = textured_grid(6);
    // The 4 × 4 block of inner quads.
    let block: Vec<FaceKey> = mesh
        .faces()
        .filter(|&f| {
            mesh.face(f).unwrap().vertices().all(|v| {
                let p = mesh.position(v).unwrap();
                (1.0..=5.0).contains(&p[0]) && (1.0..=5.0).contains(&p[1])
            })
        })
        .collect();
    assert_eq!(block.len(), 16);
    let made = mesh
        .inset_faces(
            &block,
            &InsetOptions {
                thickness: 0.25,
                depth: -0.5,
                ..Default::default()
            },
        )
        .unwrap();
    mesh.validate().unwrap();
    assert_eq!((made.rim.len(), made.vertices.len()), (16, 16));
    check_fields_planar_xy(&mesh, &uv);
    // The new outline: the square [1.25, 4.75]², sunk to z = −0.5 (even
    // offset keeps the corners 0.25 from both sides).
    for v in made.vertices {
        let p = mesh.position(v).unwrap();
        let on = |x: f64| (x - 1.25).abs() < 1e-12 || (x - 4.75).abs() < 1e-12;
        assert!(
            (on(p[0]) || on(p[1])) && (1.25 - 1e-12..=4.75 + 1e-12).contains(&p[0]),
            "{p:?}"
        );
        assert!((p[2] + 0.5).abs() < 1e-12);
    }
    let sum: f64 = mesh
        .faces()
        .map(|f| {
            mesh.attr_value("mass", f)
                .unwrap()
                .unwrap()
                .as_f64()
                .unwrap()
        })
        .sum();
    assert!((sum - 36.0).abs() < 1e-9);
}

/// The field at each corner's (x, y): the depth moved z only.
fn check_fields_planar_xy(mesh: &Mesh, uv: &HalfedgeAttr<[f64; 2]>) {
    for h in mesh
        .halfedges()
        .filter(|&h| !mesh.halfedge(h).unwrap().is_boundary())
    {
        let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
        let got = *mesh.attr(uv, h).unwrap().unwrap();
        let want = field([p[0], p[1], 0.0]);
        assert!(
            (got[0] - want[0]).abs() < 1e-12 && (got[1] - want[1]).abs() < 1e-12,
            "{got:?} at {p:?}"
        );
    }
}

#[test]
fn refusals_change_nothing_and_an_inset_is_one_undo_step() {
    let (mut mesh, _, _) = textured_grid(3);
    mesh.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&mesh);
    let f = mesh.faces().next().unwrap();
    let hole = mesh.holes().next().unwrap();
    for (faces, o) in [
        (vec![], opts(0.1, false)),
        (vec![f, hole], opts(0.1, false)),
        (vec![f, hole], opts(0.1, true)),
        (vec![f], opts(f64::NAN, false)),
        (
            vec![f],
            InsetOptions {
                depth: f64::INFINITY,
                ..opts(0.1, true)
            },
        ),
    ] {
        assert!(mesh.inset_faces(&faces, &o).is_err());
        assert!(mesh.check_inset_faces(&faces, &o).is_err());
        assert_eq!(fingerprint(&mesh), before);
    }
    let undo = mesh.history().undo_len();
    let all: Vec<FaceKey> = mesh.faces().collect();
    mesh.inset_faces(&all, &opts(0.1, true)).unwrap();
    assert_eq!(mesh.history().undo_len(), undo + 1);
    assert!(mesh.undo());
    assert_eq!(fingerprint(&mesh), before);
    let err = mesh.inset_faces(&[hole], &opts(0.1, false)).unwrap_err();
    assert!(matches!(
        err,
        Error::Refused {
            reason: Refusal::Hole,
            ..
        }
    ));
}

#[test]
fn random_selections_on_mixed_meshes_inset_and_validate() {
    let meshes = mixed_meshes();
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    for mesh in meshes {
        for round in 0..40 {
            let faces = random_faces(&mesh, &mut seed);
            if faces.is_empty() {
                continue;
            }
            let mut m = mesh.clone();
            let o = InsetOptions {
                thickness: 0.02,
                depth: 0.01,
                even: round % 2 == 0,
                individual: round % 3 == 0,
            };
            let made = m.inset_faces(&faces, &o).unwrap();
            m.validate().unwrap();
            assert_eq!(m.euler_characteristic(), mesh.euler_characteristic());
            assert_eq!(m.face_count(), mesh.face_count() + made.rim.len());
        }
    }
}
