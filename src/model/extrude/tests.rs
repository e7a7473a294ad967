use super::*;
use crate::attr::{FaceAttr, HalfedgeAttr};
use crate::journal::HistoryLimits;
use crate::model::testing::{fingerprint, mixed_meshes, random_faces};
use crate::shapes::{self, GridFaces};
use crate::Error;

fn opts(distance: f64) -> ExtrudeOptions {
    ExtrudeOptions {
        distance,
        ..Default::default()
    }
}

/// A grid with corner UVs `(x, y)` and a material per column of quads.
fn textured_grid(n: usize) -> (Mesh, HalfedgeAttr<[f64; 2]>, FaceAttr<u32>) {
    let mut mesh = shapes::grid(n, n, GridFaces::Quads);
    let uv = mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let material = mesh.add_face_attr::<u32>("material").unwrap();
    for h in mesh.halfedges().collect::<Vec<_>>() {
        let view = mesh.halfedge(h).unwrap();
        if !view.is_boundary() {
            let p = view.origin().position().unwrap();
            mesh.set_attr(&uv, h, [p[0], p[1]]).unwrap();
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
        mesh.set_attr(&material, f, x as u32 + 1).unwrap();
    }
    (mesh, uv, material)
}

#[test]
fn a_cube_face_extruded_and_every_face_on_its_own() {
    let mut cube = shapes::cube();
    let f = cube.faces().next().unwrap();
    let made = cube.extrude_faces(&[f], &opts(0.5)).unwrap();
    cube.validate().unwrap();
    assert_eq!(
        (cube.vertex_count(), cube.edge_count(), cube.face_count()),
        (12, 20, 10)
    );
    assert_eq!(
        (made.top, made.sides.len(), made.vertices.len()),
        (vec![f], 4, 4)
    );
    assert_eq!(cube.euler_characteristic(), 2);
    // The top moved along its normal by 0.5, out of the unit cube.
    let out: Vec<V3> = cube
        .face(f)
        .unwrap()
        .vertices()
        .map(|v| cube.position(v).unwrap())
        .collect();
    let normal = vec3::normalize(crate::vec3::newell(&out)).unwrap();
    let level = |p: V3| vec3::dot(p, normal);
    let was = level(out[0]) - 0.5;
    assert!(out
        .iter()
        .all(|&p| (level(p) - level(out[0])).abs() < 1e-12));
    assert!((was - 0.0).abs() < 1e-12 || (was - 1.0).abs() < 1e-12 || (was + 1.0).abs() < 1e-12);
    // Every face on its own: 4 walls each.
    let mut cube = shapes::cube();
    let all: Vec<FaceKey> = cube.faces().collect();
    let made = cube
        .extrude_faces(
            &all,
            &ExtrudeOptions {
                distance: 0.25,
                individual: true,
                ..Default::default()
            },
        )
        .unwrap();
    cube.validate().unwrap();
    assert_eq!(made.sides.len(), 24);
    assert_eq!(
        (cube.vertex_count(), cube.edge_count(), cube.face_count()),
        (32, 60, 30)
    );
}

#[test]
fn a_region_moves_together_with_walls_on_its_boundary_only() {
    let n = 6;
    let (mut mesh, uv, material) = textured_grid(n);
    // The faces left of x = 3: a 3 × 6 region touching the grid's boundary
    // on three sides.
    let left: Vec<FaceKey> = mesh
        .faces()
        .filter(|&f| *mesh.attr(&material, f).unwrap().unwrap() <= 3)
        .collect();
    assert_eq!(left.len(), 18);
    let (v0, e0, f0) = (mesh.vertex_count(), mesh.edge_count(), mesh.face_count());
    let made = mesh.extrude_faces(&left, &opts(2.0)).unwrap();
    mesh.validate().unwrap();
    // Its boundary: 3 + 6 + 3 + 6 = 18 edges, 18 vertices (a closed loop).
    assert_eq!(made.sides.len(), 18);
    assert_eq!(made.vertices.len(), 18);
    assert_eq!(mesh.vertex_count(), v0 + 18);
    assert_eq!(mesh.edge_count(), e0 + 36);
    assert_eq!(mesh.face_count(), f0 + 18);
    assert_eq!(mesh.euler_characteristic(), 1);
    // The region is up at z = 2 (the grid's normal is +z), the rest at 0.
    for &f in &left {
        for v in mesh.face(f).unwrap().vertices() {
            assert_eq!(mesh.position(v).unwrap()[2], 2.0);
        }
    }
    // UVs: every corner of a top face keeps (x, y); a wall's corners copy
    // the top face's corners at the same vertices (bottom and top alike),
    // and a wall takes its top face's material.
    for h in mesh
        .halfedges()
        .filter(|&h| !mesh.halfedge(h).unwrap().is_boundary())
    {
        let view = mesh.halfedge(h).unwrap();
        let p = view.origin().position().unwrap();
        let got = *mesh.attr(&uv, h).unwrap().unwrap();
        assert_eq!(got, [p[0], p[1]], "{p:?}");
    }
    for &s in &made.sides {
        let m = *mesh.attr(&material, s).unwrap().unwrap();
        assert!((1..=3).contains(&m));
    }
}

#[test]
fn faces_meeting_at_a_corner_get_one_copy_per_fan() {
    // Two diagonal quads of a 2 × 2 grid share only the centre vertex.
    let mut mesh = shapes::grid(2, 2, GridFaces::Quads);
    let centre = mesh
        .vertices()
        .find(|&v| !mesh.vertex(v).unwrap().is_boundary())
        .unwrap();
    let diagonal: Vec<FaceKey> = {
        let all: Vec<FaceKey> = mesh.vertex(centre).unwrap().faces().collect();
        vec![all[0], all[2]]
    };
    let made = mesh.extrude_faces(&diagonal, &opts(1.0)).unwrap();
    mesh.validate().unwrap();
    assert_eq!(made.vertices.len(), 8); // the centre twice
    assert_eq!(made.sides.len(), 8);
}

#[test]
fn a_closed_surface_selected_whole_moves_along_a_given_direction_or_is_refused() {
    let mut sphere = shapes::icosphere(1);
    let all: Vec<FaceKey> = sphere.faces().collect();
    let before = fingerprint(&sphere);
    let err = sphere.extrude_faces(&all, &opts(1.0)).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Refused {
                reason: Refusal::ZeroArea,
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(fingerprint(&sphere), before);
    let p0 = sphere.position(sphere.vertices().next().unwrap()).unwrap();
    let made = sphere
        .extrude_faces(
            &all,
            &ExtrudeOptions {
                distance: 2.0,
                direction: Some([0.0, 0.0, 5.0]),
                ..Default::default()
            },
        )
        .unwrap();
    sphere.validate().unwrap();
    assert!(made.sides.is_empty() && made.vertices.is_empty());
    let p1 = sphere.position(sphere.vertices().next().unwrap()).unwrap();
    assert_eq!(vec3::sub(p1, p0), [0.0, 0.0, 2.0]);
}

#[test]
fn refusals_change_nothing_and_an_extrusion_is_one_undo_step() {
    let (mut mesh, _, _) = textured_grid(3);
    mesh.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&mesh);
    let f = mesh.faces().next().unwrap();
    let hole = mesh.holes().next().unwrap();
    for (faces, o) in [
        (vec![], opts(1.0)),
        (vec![f, hole], opts(1.0)),
        (vec![f], opts(f64::NAN)),
        (
            vec![f],
            ExtrudeOptions {
                direction: Some([0.0; 3]),
                ..opts(1.0)
            },
        ),
        (
            vec![f],
            ExtrudeOptions {
                direction: Some([f64::INFINITY, 0.0, 0.0]),
                ..opts(1.0)
            },
        ),
        (
            vec![f, hole],
            ExtrudeOptions {
                individual: true,
                ..opts(1.0)
            },
        ),
    ] {
        assert!(mesh.extrude_faces(&faces, &o).is_err());
        assert!(mesh.check_extrude_faces(&faces, &o).is_err());
        assert_eq!(fingerprint(&mesh), before);
    }
    let undo = mesh.history().undo_len();
    let all: Vec<FaceKey> = mesh.faces().collect();
    mesh.extrude_faces(&all[..4], &opts(1.5)).unwrap();
    mesh.extrude_faces(
        &all[4..],
        &ExtrudeOptions {
            individual: true,
            ..opts(0.5)
        },
    )
    .unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.history().undo_len(), undo + 2);
    assert!(mesh.undo());
    assert!(mesh.undo());
    assert_eq!(fingerprint(&mesh), before);
    // A stale face.
    let mut m2 = shapes::grid(2, 2, GridFaces::Quads);
    let g = m2.faces().next().unwrap();
    m2.remove_face(g).unwrap();
    assert!(matches!(
        m2.extrude_faces(&[g], &opts(1.0)),
        Err(Error::StaleKey { .. })
    ));
}

#[test]
fn random_selections_on_mixed_meshes_extrude_and_validate() {
    let meshes = mixed_meshes();
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    for mesh in meshes {
        for round in 0..40 {
            let faces = random_faces(&mesh, &mut seed);
            if faces.is_empty() {
                continue;
            }
            let mut m = mesh.clone();
            let individual = round % 4 == 0;
            let o = ExtrudeOptions {
                distance: 0.1,
                individual,
                ..Default::default()
            };
            match m.extrude_faces(&faces, &o) {
                Ok(made) => {
                    m.validate().unwrap();
                    assert_eq!(m.euler_characteristic(), mesh.euler_characteristic());
                    assert_eq!(m.face_count(), mesh.face_count() + made.sides.len());
                }
                Err(e) => {
                    assert!(
                        matches!(
                            e,
                            Error::Refused {
                                reason: Refusal::ZeroArea,
                                ..
                            }
                        ),
                        "{e:?}"
                    );
                    assert_eq!(fingerprint(&m), fingerprint(&mesh));
                }
            }
        }
    }
}
