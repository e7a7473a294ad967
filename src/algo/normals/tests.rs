//! Normals against values computed by hand.

use super::*;
use crate::shapes::{self, GridFaces};

fn close(a: V3, b: V3) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)
}

fn normalized(a: V3) -> V3 {
    crate::vec3::normalize_or_zero(a)
}

/// Two unit squares sharing the edge x = 1; the second turned up by
/// `theta` about it. Returns the mesh and the key of the shared edge.
fn folded_strip(theta: f64) -> (Mesh, crate::EdgeKey) {
    let (c, s) = (theta.cos(), theta.sin());
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0 + c, 0.0, s],
        [1.0 + c, 1.0, s],
    ];
    let mesh = Mesh::from_polygons(&p, &[[0u32, 1, 2, 3], [1, 4, 5, 2]]).unwrap();
    let v: Vec<_> = mesh.vertices().collect();
    let h = mesh.find_halfedge(v[1], v[2]).unwrap().unwrap();
    (mesh, h.edge_key())
}

/// The corner normals of the two faces at vertex 1 of the strip.
fn strip_corners(mesh: &Mesh, n: &[V3]) -> (V3, V3) {
    let v1 = mesh.vertices().nth(1).unwrap();
    let faces: Vec<_> = mesh.faces().collect();
    let corner = |f: FaceKey| {
        let h = mesh
            .face(f)
            .unwrap()
            .halfedges()
            .find(|&h| mesh.halfedge(h).unwrap().origin().key() == v1)
            .unwrap();
        n[h.index()]
    };
    (corner(faces[0]), corner(faces[1]))
}

#[test]
fn cube_vertex_normals_point_along_the_diagonals_for_every_weight() {
    let cube = shapes::cube();
    let k = 1.0 / 3f64.sqrt();
    for weight in [
        NormalWeight::Angle,
        NormalWeight::Area,
        NormalWeight::Uniform,
    ] {
        let n = vertex_normals(&cube, &VertexNormalOptions { weight }).unwrap();
        for v in cube.vertices() {
            let p = cube.position(v).unwrap();
            let expected = p.map(|c| if c > 0.5 { k } else { -k });
            assert!(close(n[v.index()], expected), "{weight:?} {v}");
        }
    }
}

#[test]
fn cube_corners_split_at_right_angles_and_not_without_crease() {
    let cube = shapes::cube();
    let flat = corner_normals(&cube, &CornerNormalOptions::default()).unwrap();
    let smooth = corner_normals(&cube, &CornerNormalOptions::smooth()).unwrap();
    let vn = vertex_normals(&cube, &VertexNormalOptions::default()).unwrap();
    let mut corners = 0;
    for f in cube.faces() {
        let fnormal = cube.face_normal(f).unwrap();
        for h in cube.face(f).unwrap().halfedges() {
            let v = cube.halfedge(h).unwrap().origin().key();
            assert_eq!(flat[h.index()], fnormal);
            assert!(close(smooth[h.index()], vn[v.index()]));
            corners += 1;
        }
    }
    assert_eq!(corners, 24);
    // A crease angle just above 90° keeps the cube smooth.
    let wide = CornerNormalOptions {
        feature_angle: Some(91f64.to_radians()),
        ..CornerNormalOptions::default()
    };
    let n = corner_normals(&cube, &wide).unwrap();
    assert_eq!(n, smooth);
}

#[test]
fn a_fold_sharper_than_the_crease_splits_and_a_gentle_one_does_not() {
    // 60° fold, 30° crease: each side keeps its face's normal.
    let theta = 60f64.to_radians();
    let (mesh, _) = folded_strip(theta);
    let n = corner_normals(&mesh, &CornerNormalOptions::default()).unwrap();
    let (a, b) = strip_corners(&mesh, &n);
    assert!(close(a, [0.0, 0.0, 1.0]));
    assert!(close(b, [-theta.sin(), 0.0, theta.cos()]));

    // 20° fold: both corners (90° each) share the normalised sum.
    let theta = 20f64.to_radians();
    let (mesh, _) = folded_strip(theta);
    let n = corner_normals(&mesh, &CornerNormalOptions::default()).unwrap();
    let (a, b) = strip_corners(&mesh, &n);
    let expected = normalized([-theta.sin(), 0.0, 1.0 + theta.cos()]);
    assert!(close(a, expected) && close(b, expected), "{a:?} {b:?}");
    // ... which is also the vertex normal there.
    let vn = vertex_normals(&mesh, &VertexNormalOptions::default()).unwrap();
    assert!(close(vn[1], expected));
}

#[test]
fn a_hard_edge_splits_whatever_the_angle() {
    let theta = 20f64.to_radians();
    let (mut mesh, shared) = folded_strip(theta);
    let hard = mesh.add_edge_attr::<bool>("hard").unwrap();
    mesh.fill_attr(&hard, false).unwrap();
    mesh.set_attr(&hard, shared, true).unwrap();
    let opts = CornerNormalOptions {
        features: Some(hard.clone()),
        ..CornerNormalOptions::default()
    };
    let n = corner_normals(&mesh, &opts).unwrap();
    let (a, b) = strip_corners(&mesh, &n);
    assert!(close(a, [0.0, 0.0, 1.0]));
    assert!(close(b, [-theta.sin(), 0.0, theta.cos()]));
    // The far corners of each face are alone in their fans anyway.
    mesh.set_attr(&hard, shared, false).unwrap();
    let n = corner_normals(&mesh, &opts).unwrap();
    let (a, b) = strip_corners(&mesh, &n);
    assert!(close(a, b));
    // A removed column is an error, not a silent default.
    mesh.remove_attr(&hard).unwrap();
    assert!(matches!(
        corner_normals(&mesh, &opts),
        Err(Error::AttributeHandle { .. })
    ));
}

#[test]
fn tetrahedron_angle_weights_match_acos() {
    let mesh = shapes::tetrahedron();
    let n = vertex_normals(&mesh, &VertexNormalOptions::default()).unwrap();
    for v in mesh.vertices() {
        let q = mesh.position(v).unwrap();
        let mut sum = [0.0; 3];
        for f in mesh.vertex(v).unwrap().faces() {
            let fnormal = mesh.face_normal(f).unwrap();
            let corners: Vec<_> = mesh.face(f).unwrap().vertices().collect();
            let i = corners.iter().position(|&c| c == v).unwrap();
            let a = sub(mesh.position(corners[(i + 1) % 3]).unwrap(), q);
            let b = sub(mesh.position(corners[(i + 2) % 3]).unwrap(), q);
            let cos = dot(a, b) / (norm(a) * norm(b));
            add_scaled(&mut sum, fnormal, cos.acos());
        }
        assert!(close(n[v.index()], normalized(sum)));
    }
}

#[test]
fn degenerate_faces_give_finite_normals_or_zero() {
    // Face 0 has no area (three corners on a line); face 1 is a proper
    // triangle in z = 0. Vertex 1 lies only on the degenerate face.
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [1.0, -1.0, 0.0],
    ];
    let mesh = Mesh::from_polygons(&p, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    let fnormals = face_normals(&mesh).unwrap();
    let faces: Vec<_> = mesh.faces().collect();
    assert_eq!(fnormals[faces[0].index()], [0.0; 3]);
    for weight in [
        NormalWeight::Angle,
        NormalWeight::Area,
        NormalWeight::Uniform,
    ] {
        let vn = vertex_normals(&mesh, &VertexNormalOptions { weight }).unwrap();
        assert_eq!(vn[1], [0.0; 3]);
        for v in [0, 2, 3] {
            assert!(close(vn[v], fnormals[faces[1].index()]), "{weight:?}");
        }
        let opts = CornerNormalOptions {
            weight,
            ..CornerNormalOptions::default()
        };
        let cn = corner_normals(&mesh, &opts).unwrap();
        assert!(cn.iter().flatten().all(|c| c.is_finite()));
        // The degenerate face's corner at vertex 0 joins the proper face's
        // fan: a face without area is no crease.
        let h = mesh.face(faces[0]).unwrap().halfedges().next().unwrap();
        assert!(close(cn[h.index()], fnormals[faces[1].index()]));
    }
}

#[test]
fn polygons_use_newell_normals() {
    // An L-shaped hexagon in z = 0 and a bent quad.
    let l = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 2.0, 0.0],
        [0.0, 2.0, 0.0],
    ];
    let mesh = Mesh::from_polygons(&l, &[[0u32, 1, 2, 3, 4, 5]]).unwrap();
    let vn = vertex_normals(&mesh, &VertexNormalOptions::default()).unwrap();
    assert!(vn.iter().all(|&n| n == [0.0, 0.0, 1.0]));
    let q = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.5],
        [0.0, 1.0, 0.0],
    ];
    let mesh = Mesh::from_polygons(&q, &[[0u32, 1, 2, 3]]).unwrap();
    let f = mesh.faces().next().unwrap();
    assert_eq!(
        face_normals(&mesh).unwrap()[f.index()],
        mesh.face_normal(f).unwrap()
    );
    let vn = vertex_normals(&mesh, &VertexNormalOptions::default()).unwrap();
    assert!(vn.iter().all(|&n| close(n, mesh.face_normal(f).unwrap())));
}

#[test]
fn large_meshes_match_a_plain_reference() {
    // 20,480 faces: the parallel path with the `parallel` feature.
    let mesh = shapes::icosphere(5);
    for weight in [
        NormalWeight::Angle,
        NormalWeight::Area,
        NormalWeight::Uniform,
    ] {
        let n = vertex_normals(&mesh, &VertexNormalOptions { weight }).unwrap();
        let fnormals = face_normals(&mesh).unwrap();
        for v in mesh.vertices() {
            let q = mesh.position(v).unwrap();
            let mut sum = [0.0; 3];
            for f in mesh.vertex(v).unwrap().faces() {
                let corners: Vec<_> = mesh.face(f).unwrap().vertices().collect();
                let i = corners.iter().position(|&c| c == v).unwrap();
                let a = sub(mesh.position(corners[(i + 1) % 3]).unwrap(), q);
                let b = sub(mesh.position(corners[(i + 2) % 3]).unwrap(), q);
                let w = match weight {
                    NormalWeight::Angle => angle(a, b),
                    NormalWeight::Area => mesh.face_area(f).unwrap(),
                    NormalWeight::Uniform => 1.0,
                };
                add_scaled(&mut sum, fnormals[f.index()], w);
            }
            let r = normalized(sum);
            assert!((0..3).all(|i| (n[v.index()][i] - r[i]).abs() < 1e-9));
        }
        // Smooth corner normals are the vertex normals.
        let opts = CornerNormalOptions {
            weight,
            ..CornerNormalOptions::smooth()
        };
        let cn = corner_normals(&mesh, &opts).unwrap();
        for h in mesh.halfedges() {
            let v = mesh.halfedge(h).unwrap().origin().key();
            assert!((0..3).all(|i| (cn[h.index()][i] - n[v.index()][i]).abs() < 1e-9));
        }
    }
}

#[test]
fn columns_are_written_and_follow_edits() {
    let mut mesh = shapes::grid(2, 2, GridFaces::Quads);
    let vn = add_vertex_normals(&mut mesh, &VertexNormalOptions::default()).unwrap();
    let cn = add_corner_normals(&mut mesh, &CornerNormalOptions::default()).unwrap();
    let fcol = add_face_normals(&mut mesh).unwrap();
    for v in mesh.vertices() {
        assert_eq!(mesh.attr(&vn, v).unwrap(), Some(&[0.0, 0.0, 1.0]));
    }
    for h in mesh.halfedges() {
        let in_hole = mesh.halfedge(h).unwrap().is_boundary();
        let value = mesh.attr(&cn, h).unwrap();
        assert_eq!(value.is_none(), in_hole);
    }
    let hole = mesh.holes().next().unwrap();
    assert_eq!(mesh.attr(&fcol, hole).unwrap(), None);
    // Adding again overwrites the same columns.
    let again = add_vertex_normals(&mut mesh, &VertexNormalOptions::default()).unwrap();
    assert_eq!(again, vn);
    // A column of another type under the name is an error.
    let mut other = shapes::cube();
    other.add_vertex_attr::<f64>(NORMAL).unwrap();
    assert!(matches!(
        add_vertex_normals(&mut other, &VertexNormalOptions::default()),
        Err(Error::AttributeType { .. })
    ));
    // Without positions there is nothing to compute.
    let bare = Mesh::from_faces(3, &[[0u32, 1, 2]]).unwrap();
    assert_eq!(face_normals(&bare), Err(Error::NoPositions));
}

#[test]
fn corner_angle_matches_atan2() {
    // Deterministic samples over every branch: steep and flat, below and
    // above tan 15°, acute and obtuse, and values far apart in size.
    // The stated accuracy: 3·10⁻⁹ rad absolute, 1.1·10⁻⁸ relative (six
    // series terms; four or five would fail here).
    let (mut worst, mut worst_rel): (f64, f64) = (0.0, 0.0);
    let mut check = |y: f64, x: f64| {
        let (got, want) = (super::corner_angle(y, x), f64::atan2(y, x));
        worst = worst.max((got - want).abs());
        worst_rel = worst_rel.max((got - want).abs() / want);
    };
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for i in 0..200_000 {
        let y = (next() + 1e-9) * 10f64.powi(i % 7 - 3);
        let x = (next() - 0.5) * 10f64.powi(i / 7 % 7 - 3);
        check(y, x);
    }
    // Near tan 15° (the fold's edge) and near 0, where the series is least
    // and most accurate.
    for i in 0..=1000 {
        let t = 0.26 + 0.016 * i as f64 / 1000.0;
        check(t, 1.0);
        check(1.0, -t);
        check(1e-3 * i as f64, 1.0);
    }
    for (y, x) in [
        (1.0, 0.0),
        (1.0, 1.0),
        (1.0, -1.0),
        (1e-300, 1.0),
        (1.0, -1e-300),
        (1.5e308, 1e308),
        (1e308, -1.7e308),
        (f64::MAX, -f64::MAX),
    ] {
        check(y, x);
    }
    assert!(worst <= 3e-9, "worst error {worst:e}");
    assert!(worst_rel <= 1.1e-8, "worst relative error {worst_rel:e}");
}
