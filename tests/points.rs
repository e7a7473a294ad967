//! The builders take the caller's own point types as they are: `[f64; 3]`,
//! `[f32; 3]`, and with the features `glam`, `nalgebra` and `mint` their
//! points and vectors. Each build must give the same mesh as the `[f64; 3]`
//! one, with the coordinates rounded as the type holds them.

use meshloom::geometry::Point;
use meshloom::{BuildError, Error, Mesh, Polygons, PolygonsRef};

/// An octahedron: positions that are exact in `f32`, and its faces.
fn octahedron() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let p = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.5],
        [0.0, 0.0, -0.25],
    ];
    let f = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    (p, f)
}

/// The octahedron's faces as flat offsets and indices.
fn flat_faces() -> (Vec<u32>, Vec<u32>) {
    let (_, f) = octahedron();
    let offsets = (0..=f.len() as u32).map(|i| 3 * i).collect();
    (offsets, f.concat())
}

/// Build from `points` (face lists, and flat buffers borrowed as they are)
/// and compare with the `[f64; 3]` build.
fn same_as_f64<P: Point + std::fmt::Debug>(points: &[P]) {
    let (p, f) = octahedron();
    let want = Mesh::from_polygons(&p, &f).unwrap();
    let (offsets, indices) = flat_faces();
    let by_ref = Mesh::from_buffers(PolygonsRef::new(points, &offsets, &indices)).unwrap();
    let built = Mesh::build_buffers(PolygonsRef::new(points, &offsets, &indices)).unwrap();
    #[allow(deprecated)] // the 0.1 name still builds the same mesh
    let flat = Mesh::from_flat_faces(points, &offsets, &indices).unwrap();
    assert_eq!(built.faces.len(), 8);
    assert!(built.vertices.iter().all(Option::is_some));
    for got in [
        Mesh::from_polygons(points, &f).unwrap(),
        flat,
        by_ref,
        built.mesh,
    ] {
        assert_eq!(got.to_polygons().0, want.to_polygons().0);
        assert!(got.is_closed());
        assert_eq!(got.euler_characteristic(), 2);
    }
}

/// The error `from_buffers` gives for `[f64; 3]` buffers, and the one the
/// flat builder gives for the same buffers in `f32`.
fn both_errors(positions: &[[f64; 3]], offsets: &[u32], indices: &[u32]) -> (Error, Error) {
    let poly = Polygons {
        positions: positions.to_vec(),
        offsets: offsets.to_vec(),
        indices: indices.to_vec(),
    };
    let want = Mesh::from_buffers(&poly).unwrap_err();
    let p32: Vec<[f32; 3]> = positions.iter().map(|q| q.map(|c| c as f32)).collect();
    let got = Mesh::from_buffers(PolygonsRef::new(&p32, offsets, indices)).unwrap_err();
    (want, got)
}

#[test]
fn flat_buffers_of_f32_give_the_errors_of_from_buffers() {
    let (p, _) = octahedron();
    let (offsets, indices) = flat_faces();
    // An index past the positions, in face 2.
    let mut bad = indices.clone();
    bad[7] = 6;
    let (want, got) = both_errors(&p, &offsets, &bad);
    assert_eq!(got, want);
    assert!(
        matches!(
            got,
            Error::Build(BuildError::IndexOutOfRange {
                face: 2,
                index: 6,
                vertex_count: 6
            })
        ),
        "{got:?}"
    );
    // Offsets that go back, that do not start at 0, that miss the end.
    for bent in [
        vec![0, 3, 2, 9, 12, 15, 18, 21, 24],
        vec![3, 6, 9, 12, 15, 18, 21, 24],
        vec![0, 3, 6, 9, 12, 15, 18, 21],
    ] {
        let (want, got) = both_errors(&p, &bent, &indices);
        assert_eq!(got, want);
        assert!(
            matches!(got, Error::Build(BuildError::MalformedOffsets { .. })),
            "{got:?}"
        );
    }
    // A NaN in a used vertex; in an unused one it is dropped with it.
    let mut nan = p.clone();
    nan[4][1] = f64::NAN;
    let (want, got) = both_errors(&nan, &offsets, &indices);
    assert!(
        matches!(
            got,
            Error::Build(BuildError::NonFinitePosition { vertex: 4, .. })
        ),
        "{got:?}"
    );
    assert_eq!(got.to_string(), want.to_string());
    let mut unused = p.iter().map(|q| q.map(|c| c as f32)).collect::<Vec<_>>();
    unused.push([f32::NAN; 3]);
    let m = Mesh::from_buffers(PolygonsRef::new(&unused, &offsets, &indices)).unwrap();
    assert_eq!(m.vertex_count(), 6);
    // Topological errors too: a face with a repeated vertex.
    let (want, got) = both_errors(&p, &[0, 3], &[0, 1, 0]);
    assert_eq!(got, want);
    assert!(
        matches!(
            got,
            Error::Build(BuildError::RepeatedVertex { face: 0, vertex: 0 })
        ),
        "{got:?}"
    );
}

#[test]
fn flat_buffers_borrowed_from_polygons_build_the_same() {
    let (p, f) = octahedron();
    let poly = Mesh::from_polygons(&p, &f).unwrap().to_polygons().0;
    let a = Mesh::from_buffers(&poly).unwrap();
    let b = Mesh::from_buffers(poly.borrowed()).unwrap();
    assert_eq!(a.to_polygons().0, b.to_polygons().0);
    // Empty positions: topology only, as from_buffers.
    let topo = PolygonsRef::<[f32; 3]>::new(&[], &poly.offsets, &poly.indices);
    let t = Mesh::from_buffers(topo).unwrap();
    assert!(!t.has_positions());
    assert_eq!(t.face_count(), 8);
}

#[test]
fn f64_and_f32_arrays() {
    let (p, _) = octahedron();
    same_as_f64(&p);
    let p32: Vec<[f32; 3]> = p.iter().map(|q| q.map(|c| c as f32)).collect();
    same_as_f64(&p32);
    // Borrowed, not copied, for the builders' own type.
    assert!(matches!(
        Point::slice_xyz(&p[..]),
        std::borrow::Cow::Borrowed(_)
    ));
}

#[test]
fn f32_rounding_is_kept_not_hidden() {
    // 0.1 is not exact in f32: the mesh holds the f32 value, widened.
    let p = [[0.1f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let m = Mesh::from_polygons(&p, &[[0u8, 1, 2]]).unwrap();
    let v = m.vertices().next().unwrap();
    assert_eq!(m.position(v).unwrap()[0], f64::from(0.1f32));
    assert_ne!(m.position(v).unwrap()[0], 0.1);
}

#[test]
fn non_finite_points_are_refused_whatever_the_type() {
    let p = [[f32::NAN, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let err = Mesh::from_polygons(&p, &[[0u32, 1, 2]]).unwrap_err();
    assert!(err.to_string().contains("vertex 0"), "{err}");
}

#[cfg(feature = "glam")]
#[test]
fn glam_points() {
    let (p, _) = octahedron();
    let v: Vec<glam::Vec3> = p.iter().map(|q| glam::Vec3::from_xyz(*q)).collect();
    same_as_f64(&v);
    let d: Vec<glam::DVec3> = p.iter().map(|q| glam::DVec3::from(*q)).collect();
    same_as_f64(&d);
}

#[cfg(feature = "nalgebra")]
#[test]
fn nalgebra_points() {
    let (p, _) = octahedron();
    let a: Vec<nalgebra::Point3<f64>> = p.iter().map(|q| nalgebra::Point3::from(*q)).collect();
    same_as_f64(&a);
    let b: Vec<nalgebra::Point3<f32>> = p.iter().map(|q| nalgebra::Point3::from_xyz(*q)).collect();
    same_as_f64(&b);
    let c: Vec<nalgebra::Vector3<f64>> = p.iter().map(|q| nalgebra::Vector3::from(*q)).collect();
    same_as_f64(&c);
}

#[cfg(feature = "mint")]
#[test]
fn mint_points() {
    let (p, _) = octahedron();
    let a: Vec<mint::Point3<f64>> = p.iter().map(|q| mint::Point3::from(*q)).collect();
    same_as_f64(&a);
    let b: Vec<mint::Vector3<f32>> = p.iter().map(|q| mint::Vector3::from_xyz(*q)).collect();
    same_as_f64(&b);
}
