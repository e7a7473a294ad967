use super::*;
use crate::attr::{Conserved, FaceAttr, HalfedgeAttr, KeepFirst};
use crate::journal::HistoryLimits;
use crate::model::testing::{field, fingerprint, mixed_meshes, random_faces};
use crate::shapes::{self, GridFaces};
use crate::FaceKey;

/// Whether triangle `f` of a unit grid is the upper-left one of its cell
/// (its centroid above the cell's diagonal), and the centroid's x.
fn upper_left(mesh: &Mesh, f: FaceKey) -> (bool, f64) {
    let ps: Vec<_> = mesh
        .face(f)
        .unwrap()
        .vertices()
        .map(|v| mesh.position(v).unwrap())
        .collect();
    let (x, y) = (
        ps.iter().map(|p| p[0]).sum::<f64>() / 3.0,
        ps.iter().map(|p| p[1]).sum::<f64>() / 3.0,
    );
    (x.fract() < y.fract(), x)
}

/// An n × n triangle grid with the UV field on its corners, except that
/// the upper-left triangles of the first column of cells sit on their own
/// island (shifted by 10), and a material id that differs across the
/// diagonals of the second column.
fn textured_grid(n: usize) -> (Mesh, HalfedgeAttr<[f64; 2]>, FaceAttr<u32>) {
    let mut mesh = shapes::grid(n, n, GridFaces::Triangles);
    let uv = mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let material = mesh.add_face_attr::<u32>("material").unwrap();
    for f in mesh.faces().collect::<Vec<_>>() {
        let (ul, x) = upper_left(&mesh, f);
        let shift = if ul && x < 1.0 { 10.0 } else { 0.0 };
        let m = u32::from(ul && (1.0..2.0).contains(&x));
        mesh.set_attr(&material, f, m).unwrap();
        for h in mesh.face(f).unwrap().halfedges().collect::<Vec<_>>() {
            let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
            let [u, v] = field(p);
            mesh.set_attr(&uv, h, [u + shift, v]).unwrap();
        }
    }
    (mesh, uv, material)
}

fn degrees(mesh: &Mesh) -> (usize, usize) {
    let d: Vec<usize> = mesh
        .faces()
        .map(|f| mesh.face(f).unwrap().degree())
        .collect();
    (
        d.iter().filter(|&&k| k == 3).count(),
        d.iter().filter(|&&k| k == 4).count(),
    )
}

#[test]
fn a_triangle_grid_joins_back_to_its_quads() {
    for n in [1, 2, 5, 8] {
        let mut mesh = shapes::grid(n, n, GridFaces::Triangles);
        let chi = mesh.euler_characteristic();
        let joined = mesh
            .join_triangles(&JoinTrianglesOptions::default())
            .unwrap();
        mesh.validate().unwrap();
        assert_eq!(joined.quads.len(), n * n);
        assert_eq!(joined.triangles_left, 0);
        assert_eq!(degrees(&mesh), (0, n * n));
        assert_eq!(mesh.edge_count(), 2 * n * (n + 1));
        assert_eq!(mesh.euler_characteristic(), chi);
        // Every quad is a unit square.
        for f in mesh.faces() {
            assert!((mesh.face_area(f).unwrap() - 1.0).abs() < 1e-12);
        }
    }
}

#[test]
fn a_triangulated_cube_joins_to_six_quads() {
    let mut cube = shapes::cube();
    cube.triangulate_all();
    assert_eq!(cube.face_count(), 12);
    let joined = cube
        .join_triangles(&JoinTrianglesOptions::default())
        .unwrap();
    cube.validate().unwrap();
    assert_eq!(joined.quads.len(), 6);
    assert_eq!(
        (cube.vertex_count(), cube.edge_count(), cube.face_count()),
        (8, 12, 6)
    );
    // With no angle limits the pairs are still the faces' (best first).
    let mut cube = shapes::cube();
    cube.triangulate_all();
    let free = JoinTrianglesOptions {
        face_angle: PI,
        shape_angle: PI,
        ..Default::default()
    };
    assert_eq!(cube.join_triangles(&free).unwrap().quads.len(), 6);
    cube.validate().unwrap();
}

#[test]
fn a_pair_bent_beyond_the_face_angle_stays_apart() {
    // Two triangles on the diagonal (0,0)–(1,1), the second folded up by
    // lifting (0,1) to height z.
    let fold = |z: f64| {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, z],
        ];
        Mesh::from_polygons(&p, &[vec![0u32, 1, 2], vec![0, 2, 3]]).unwrap()
    };
    // Bent by atan(z·√2 / 1): 30° joins, 50° does not.
    for (deg, joins) in [(0.0f64, true), (30.0, true), (50.0, false)] {
        let z = deg.to_radians().tan() / 2f64.sqrt();
        let mut m = fold(z);
        let joined = m.join_triangles(&JoinTrianglesOptions::default()).unwrap();
        assert_eq!(joined.quads.len() == 1, joins, "{deg}°");
        m.validate().unwrap();
        // A wider face angle lets the 50° pair join.
        let mut m = fold(z);
        let wide = JoinTrianglesOptions {
            face_angle: 60f64.to_radians(),
            ..Default::default()
        };
        assert_eq!(m.join_triangles(&wide).unwrap().quads.len(), 1);
    }
}

#[test]
fn concave_and_badly_shaped_pairs_stay_apart() {
    // A dart: (0,0), (2,0), (0.5,0.5) reflex, (0,2): split at the reflex
    // corner into two triangles.
    let p = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.5, 0.5, 0.0],
        [0.0, 2.0, 0.0],
    ];
    let free = JoinTrianglesOptions {
        face_angle: PI,
        shape_angle: PI,
        ..Default::default()
    };
    let mut dart = Mesh::from_polygons(&p, &[vec![0u32, 1, 2], vec![0, 2, 3]]).unwrap();
    assert!(dart.join_triangles(&free).unwrap().quads.is_empty());
    // A rhombus with 60° corners: joined only past a 30° shape angle.
    let s = 3f64.sqrt() / 2.0;
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.5, s, 0.0],
        [0.5, s, 0.0],
    ];
    let rhombus = Mesh::from_polygons(&p, &[vec![0u32, 1, 2], vec![0, 2, 3]]).unwrap();
    for (deg, n) in [(25.0f64, 0), (35.0, 1)] {
        let mut m = rhombus.clone();
        let o = JoinTrianglesOptions {
            shape_angle: deg.to_radians(),
            ..Default::default()
        };
        assert_eq!(m.join_triangles(&o).unwrap().quads.len(), n, "{deg}°");
    }
}

#[test]
fn delimiters_stop_joins_and_attributes_follow() {
    let n = 4;
    let (mesh, uv, material) = textured_grid(n);
    // No delimiter: everything joins; corners keep their values.
    let mut all = mesh.clone();
    let joined = all
        .join_triangles(&JoinTrianglesOptions::default())
        .unwrap();
    assert_eq!(joined.quads.len(), n * n);
    // A seam delimiter keeps the first column's diagonals.
    let seams = JoinTrianglesOptions {
        delimit: Delimit {
            seams: Some("uv".into()),
            ..Delimit::default()
        },
        ..Default::default()
    };
    let mut m = mesh.clone();
    let joined = m.join_triangles(&seams).unwrap();
    m.validate().unwrap();
    assert_eq!(
        (joined.quads.len(), joined.triangles_left),
        (n * n - n, 2 * n)
    );
    // Every corner still holds the field (shifted on the island).
    for f in m.faces() {
        let shifted = m.face(f).unwrap().degree() == 3 && upper_left(&m, f).0;
        for h in m.face(f).unwrap().halfedges() {
            let p = m.halfedge(h).unwrap().origin().position().unwrap();
            let [u, v] = field(p);
            let want = [u + if shifted { 10.0 } else { 0.0 }, v];
            assert_eq!(*m.attr(&uv, h).unwrap().unwrap(), want);
        }
    }
    // The material delimiter keeps the second column's diagonals.
    let by_material = JoinTrianglesOptions {
        delimit: Delimit {
            material: Some("material".into()),
            ..Delimit::default()
        },
        ..Default::default()
    };
    let mut m = mesh.clone();
    let joined = m.join_triangles(&by_material).unwrap();
    m.validate().unwrap();
    assert_eq!(joined.quads.len(), n * n - n);
    for f in m.faces() {
        let tri = m.face(f).unwrap().degree() == 3;
        let want = u32::from(tri && upper_left(&m, f).0);
        assert_eq!(*m.attr(&material, f).unwrap().unwrap(), want);
    }
    // A sharp edge column: one diagonal kept.
    let mut m = mesh.clone();
    let sharp = m.add_edge_attr::<bool>("sharp").unwrap();
    let diagonal = m
        .edges()
        .find(|&e| {
            let [a, b] = m.edge(e).unwrap().vertices();
            let (p, q) = (m.position(a).unwrap(), m.position(b).unwrap());
            p[0] != q[0] && p[1] != q[1]
        })
        .unwrap();
    m.set_attr(&sharp, diagonal, true).unwrap();
    let o = JoinTrianglesOptions {
        delimit: Delimit {
            sharp: Some(sharp),
            ..Delimit::default()
        },
        ..Default::default()
    };
    assert_eq!(m.join_triangles(&o).unwrap().quads.len(), n * n - 1);
    assert!(m.edge(diagonal).is_ok());
}

#[test]
fn a_quad_keeps_its_first_triangles_values_and_conserved_totals() {
    let mut mesh = shapes::grid(3, 3, GridFaces::Triangles);
    let id = mesh
        .add_attr_with_rule::<FaceKey, u32, KeepFirst>("id")
        .unwrap();
    let mass = mesh
        .add_attr_with_rule::<FaceKey, f64, Conserved>("mass")
        .unwrap();
    let faces: Vec<FaceKey> = mesh.faces().collect();
    for (i, &f) in faces.iter().enumerate() {
        mesh.set_attr(&id, f, i as u32).unwrap();
        mesh.set_attr(&mass, f, 1.0 + i as f64).unwrap();
    }
    let total = |m: &Mesh| -> f64 { m.faces().map(|f| *m.attr(&mass, f).unwrap().unwrap()).sum() };
    let before = total(&mesh);
    let joined = mesh
        .join_triangles(&JoinTrianglesOptions::default())
        .unwrap();
    assert_eq!(total(&mesh), before);
    for q in joined.quads {
        // The quad is its first triangle: same key, same id; its mass is
        // its two triangles' (consecutive in the grid's order).
        let i = *mesh.attr(&id, q).unwrap().unwrap() as usize;
        assert_eq!(faces[i], q);
        let other = if i % 2 == 0 { i + 1 } else { i - 1 };
        let want = (1.0 + i as f64) + (1.0 + other as f64);
        assert_eq!(*mesh.attr(&mass, q).unwrap().unwrap(), want);
    }
}

#[test]
fn a_selection_joins_only_among_its_triangles() {
    let mut mesh = shapes::grid(3, 3, GridFaces::Triangles);
    let faces: Vec<FaceKey> = mesh.faces().collect();
    // The first two cells' triangles and one of the third's.
    let o = JoinTrianglesOptions {
        faces: Some(faces[..5].to_vec()),
        ..Default::default()
    };
    let joined = mesh.join_triangles(&o).unwrap();
    mesh.validate().unwrap();
    assert_eq!((joined.quads.len(), joined.triangles_left), (2, 1));
    assert_eq!(degrees(&mesh), (14, 2));
    // Quads among the selection are left alone.
    let o = JoinTrianglesOptions {
        faces: Some(mesh.faces().collect()),
        ..Default::default()
    };
    assert_eq!(mesh.join_triangles(&o).unwrap().quads.len(), 7);
}

#[test]
fn refusals_change_nothing_and_a_join_is_one_undo_step() {
    let (mut mesh, _, _) = textured_grid(3);
    mesh.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&mesh);
    let hole = mesh.holes().next().unwrap();
    let f = mesh.faces().next().unwrap();
    let bad = [
        JoinTrianglesOptions {
            face_angle: f64::NAN,
            ..Default::default()
        },
        JoinTrianglesOptions {
            shape_angle: -1.0,
            ..Default::default()
        },
        JoinTrianglesOptions {
            faces: Some(vec![f, hole]),
            ..Default::default()
        },
        JoinTrianglesOptions {
            delimit: Delimit {
                material: Some("nope".into()),
                ..Delimit::default()
            },
            ..Default::default()
        },
    ];
    for o in &bad {
        assert!(mesh.check_join_triangles(o).is_err());
        assert!(mesh.join_triangles(o).is_err());
        assert_eq!(fingerprint(&mesh), before);
    }
    let undo = mesh.history().undo_len();
    mesh.join_triangles(&JoinTrianglesOptions::default())
        .unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.history().undo_len(), undo + 1);
    assert!(mesh.undo());
    assert_eq!(fingerprint(&mesh), before);
    // A stale face.
    let mut m2 = shapes::grid(2, 2, GridFaces::Triangles);
    let g = m2.faces().next().unwrap();
    m2.remove_face(g).unwrap();
    let before = fingerprint(&m2);
    let o = JoinTrianglesOptions {
        faces: Some(vec![g]),
        ..Default::default()
    };
    assert!(matches!(m2.join_triangles(&o), Err(Error::StaleKey { .. })));
    assert_eq!(fingerprint(&m2), before);
}

#[test]
fn random_selections_on_mixed_meshes_join_and_validate() {
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    for mesh in mixed_meshes() {
        for round in 0..30 {
            let mut m = mesh.clone();
            let mut faces = random_faces(&mesh, &mut seed);
            // Now and then a hole among the faces: refused.
            let hole = mesh.holes().next().filter(|_| round % 7 == 6);
            faces.extend(hole);
            let deg = 10.0 + 7.0 * (round % 25) as f64;
            let o = JoinTrianglesOptions {
                face_angle: deg.to_radians(),
                shape_angle: (200.0 - deg).to_radians(),
                faces: (round % 3 != 0 || hole.is_some()).then_some(faces),
                ..Default::default()
            };
            match m.join_triangles(&o) {
                Ok(joined) => {
                    m.validate().unwrap();
                    assert_eq!(m.euler_characteristic(), mesh.euler_characteristic());
                    assert_eq!(m.face_count(), mesh.face_count() - joined.quads.len());
                    for &q in &joined.quads {
                        assert_eq!(m.face(q).unwrap().degree(), 4);
                    }
                }
                Err(e) => {
                    assert!(hole.is_some(), "{e:?}");
                    assert_eq!(fingerprint(&m), fingerprint(&mesh));
                }
            }
        }
    }
}
