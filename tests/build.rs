//! Construction: counts, holes (bowties included), errors naming faces.

use meshloom::{BuildError, Error, Mesh};

fn counts(m: &Mesh) -> (usize, usize, usize, usize) {
    (
        m.vertex_count(),
        m.edge_count(),
        m.face_count(),
        m.hole_count(),
    )
}

fn build_err<F: AsRef<[u32]>>(n: usize, faces: &[F]) -> BuildError {
    match Mesh::from_faces(n, faces) {
        Err(Error::Build(e)) => e,
        other => panic!("expected a build error, got {other:?}"),
    }
}

#[test]
fn closed_tetrahedron() {
    let m = Mesh::from_faces(4, &[[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]]).unwrap();
    assert_eq!(counts(&m), (4, 6, 4, 0));
    m.validate().unwrap();
    for v in m.vertices() {
        assert_eq!(m.vertex(v).unwrap().degree(), 3);
        assert!(!m.vertex(v).unwrap().is_boundary());
    }
}

#[test]
fn single_triangle_has_one_hole() {
    let m = Mesh::from_faces(3, &[[0u32, 1, 2]]).unwrap();
    assert_eq!(counts(&m), (3, 3, 1, 1));
    m.validate().unwrap();
    let hole = m.holes().next().unwrap();
    let hv = m.face(hole).unwrap();
    assert!(hv.is_hole());
    assert_eq!(hv.degree(), 3);
    // The hole runs the other way round.
    let face: Vec<_> = m
        .face(m.faces().next().unwrap())
        .unwrap()
        .vertices()
        .collect();
    let mut hole_v: Vec<_> = hv.vertices().collect();
    hole_v.reverse();
    let k = hole_v.iter().position(|v| *v == face[0]).unwrap();
    hole_v.rotate_left(k);
    assert_eq!(face, hole_v);
    for h in m.halfedges() {
        let hv = m.halfedge(h).unwrap();
        assert_eq!(hv.prev().next().key(), h);
        assert_eq!(hv.next().prev().key(), h);
    }
}

#[test]
fn bowtie_vertex_is_one_ring() {
    // Two triangles sharing only vertex 0.
    let m = Mesh::from_faces(5, &[[0u32, 1, 2], [0, 3, 4]]).unwrap();
    m.validate().unwrap();
    let v0 = m.vertices().next().unwrap();
    assert_eq!(m.vertex(v0).unwrap().degree(), 4);
    assert_eq!(m.vertex(v0).unwrap().faces().count(), 2);
    // One hole passing vertex 0 twice.
    assert_eq!(m.hole_count(), 1);
    let hole = m.holes().next().unwrap();
    assert_eq!(m.face(hole).unwrap().degree(), 6);
}

#[test]
fn triple_bowtie() {
    let m = Mesh::from_faces(7, &[[0u32, 1, 2], [0, 3, 4], [0, 5, 6]]).unwrap();
    m.validate().unwrap();
    let v0 = m.vertices().next().unwrap();
    assert_eq!(m.vertex(v0).unwrap().degree(), 6);
}

#[test]
fn bowtie_of_fans_with_two_loops() {
    // Two quads fans meeting at 0, each fan two triangles.
    let m = Mesh::from_faces(7, &[[0u32, 1, 2], [0, 2, 3], [0, 4, 5], [0, 5, 6]]).unwrap();
    m.validate().unwrap();
    assert_eq!(m.vertex(m.vertices().next().unwrap()).unwrap().degree(), 6);
}

#[test]
fn unreferenced_vertices_are_dropped_and_counted() {
    let b = Mesh::build(None, 6, &[[0u32, 2, 4]]).unwrap();
    assert_eq!(b.unreferenced, 3);
    assert_eq!(b.mesh.vertex_count(), 3);
    assert!(b.vertices[1].is_none() && b.vertices[2].is_some());
}

#[test]
fn errors_name_faces_and_vertices() {
    assert_eq!(
        build_err(3, &[[0u32, 1, 7]]),
        BuildError::IndexOutOfRange {
            face: 0,
            index: 7,
            vertex_count: 3
        }
    );
    assert_eq!(
        build_err(3, &[vec![0u32, 1]]),
        BuildError::TooFewVertices { face: 0, degree: 2 }
    );
    assert_eq!(
        build_err(4, &[[0u32, 1, 2], [1, 3, 1]]),
        BuildError::RepeatedVertex { face: 1, vertex: 1 }
    );
    assert!(matches!(
        build_err(5, &[[0u32, 1, 2], [1, 0, 3], [0, 1, 4]]),
        BuildError::NonManifoldEdge {
            a: 0,
            b: 1,
            faces: [0, 1, 2]
        } | BuildError::InconsistentOrientation { .. }
    ));
    assert_eq!(
        build_err(5, &[[0u32, 1, 2], [0, 1, 3]]),
        BuildError::InconsistentOrientation {
            a: 0,
            b: 1,
            faces: [0, 1]
        }
    );
    // A duplicate face is an orientation conflict too.
    assert!(matches!(
        build_err(3, &[[0u32, 1, 2], [1, 2, 0]]),
        BuildError::InconsistentOrientation { .. }
    ));
    let neg = Mesh::from_faces(3, &[[0i32, 1, -1]]).unwrap_err();
    assert!(neg.to_string().contains("-1"), "{neg}");
    let nan = Mesh::from_polygons(
        &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [f64::NAN, 0.0, 0.0]],
        &[[0u32, 1, 2]],
    );
    assert!(matches!(
        nan,
        Err(Error::Build(BuildError::NonFinitePosition {
            vertex: 2,
            ..
        }))
    ));
}

#[test]
fn two_closed_cones_at_one_vertex_are_refused() {
    // Two tetrahedra sharing one vertex (0): two closed fans.
    let tet = |o: u32| {
        [
            [0u32, o + 2, o + 1],
            [0, o + 1, o + 3],
            [o + 1, o + 2, o + 3],
            [o + 2, 0, o + 3],
        ]
    };
    let mut faces = tet(0).to_vec();
    faces.extend(tet(3));
    let e = build_err(7, &faces);
    assert!(
        matches!(e, BuildError::NonManifoldVertex { vertex: 0, .. }),
        "{e:?}"
    );
}

#[test]
fn round_trip_through_buffers() {
    let m = meshloom::shapes::icosahedron();
    let (poly, maps) = m.to_polygons();
    let again = Mesh::from_buffers(&poly).unwrap();
    assert_eq!(counts(&again), counts(&m));
    assert_eq!(again.to_polygons().0, poly);
    for (i, v) in maps.vertices.iter().enumerate() {
        assert_eq!(maps.vertex_index(*v), Some(i));
    }
}

#[test]
fn stale_keys_are_errors() {
    let m = meshloom::shapes::cube();
    let v = m.vertices().next().unwrap();
    let other = meshloom::shapes::tetrahedron();
    // A key from another, smaller mesh can be out of range: an error.
    let far = meshloom::shapes::icosahedron().vertices().last().unwrap();
    assert!(other.vertex(far).is_err());
    assert!(m.vertex(v).is_ok());
}

/// The same faces, built as given (triangles only: the builder's leaner
/// triangle path) and with one separate quad after them (the general
/// path): the same error, or meshes that differ only by the quad.
fn same_on_both_paths(n: u32, tris: &[[u32; 3]]) {
    let faces: Vec<Vec<u32>> = tris.iter().map(|t| t.to_vec()).collect();
    let mut with_quad = faces.clone();
    with_quad.push(vec![n, n + 1, n + 2, n + 3]);
    let tri = Mesh::from_faces(n as usize, &faces);
    let general = Mesh::from_faces(n as usize + 4, &with_quad);
    match (tri, general) {
        (Ok(a), Ok(b)) => {
            a.validate().unwrap();
            let (v, e, f, h) = counts(&b);
            assert_eq!(counts(&a), (v - 4, e - 4, f - 1, h - 1), "{tris:?}");
        }
        (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{tris:?}"),
        (a, b) => panic!("{tris:?}: triangles {a:?}, general {b:?}"),
    }
}

#[test]
fn triangle_path_reports_as_the_general_path() {
    let cases: &[&[[u32; 3]]] = &[
        &[[0, 1, 2], [1, 0, 3], [0, 1, 4]],
        &[[0, 1, 2], [0, 1, 3]],
        &[[0, 1, 2], [1, 2, 0]],
        &[[0, 1, 2], [1, 0, 3], [1, 0, 4]],
        &[[0, 1, 2], [2, 1, 3], [1, 0, 4], [3, 1, 4]],
        &[[0, 1, 2], [0, 3, 4]],
        &[[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]],
        &[
            [0, 2, 1],
            [0, 1, 3],
            [1, 2, 3],
            [2, 0, 3],
            [0, 5, 4],
            [0, 4, 6],
        ],
    ];
    for tris in cases {
        same_on_both_paths(7, tris);
    }
    // Small random soups over few vertices: every defect the builder
    // knows, in many arrangements.
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = |m: u32| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 33) % u64::from(m)) as u32
    };
    for _ in 0..3000 {
        let n = 3 + next(6);
        let k = 1 + next(8) as usize;
        let mut tris = Vec::with_capacity(k);
        while tris.len() < k {
            let t = [next(n), next(n), next(n)];
            if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                tris.push(t);
            }
        }
        same_on_both_paths(n, &tris);
    }
}

/// A fan of many triangles around one vertex (the shape whose read was
/// quadratic in the valence): every side paired, the centre's ring whole,
/// one hole along the rim; closed, the rim edges pair too. The cost is
/// checked by the builder's own unit test
/// (`build::tests::triangle_pairing_is_linear_in_valence`), not by a clock.
#[test]
fn a_fan_of_high_valence_builds_whole() {
    let n = 60_000u32;
    let open: Vec<[u32; 3]> = (0..n - 1).map(|k| [0, 1 + k, 2 + k]).collect();
    let closed: Vec<[u32; 3]> = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
    let m = Mesh::from_faces(n as usize + 1, &open).unwrap();
    m.validate().unwrap();
    let n = n as usize;
    assert_eq!(counts(&m), (n + 1, 2 * n - 1, n - 1, 1));
    let centre = m
        .vertices()
        .max_by_key(|&v| m.vertex(v).unwrap().degree())
        .unwrap();
    assert_eq!(m.vertex(centre).unwrap().degree(), n);
    let hole = m.holes().next().unwrap();
    assert_eq!(m.face(hole).unwrap().degree(), n + 1);
    let m = Mesh::from_faces(n + 1, &closed).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (n + 1, 2 * n, n, 1));
    let hole = m.holes().next().unwrap();
    assert_eq!(m.face(hole).unwrap().degree(), n);
}
