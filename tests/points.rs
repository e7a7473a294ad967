//! The builders take the caller's own point types as they are: `[f64; 3]`,
//! `[f32; 3]`, and with the features `glam`, `nalgebra` and `mint` their
//! points and vectors. Each build must give the same mesh as the `[f64; 3]`
//! one, with the coordinates rounded as the type holds them.

use meshloom::geometry::Point;
use meshloom::Mesh;

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

/// Build from `points` and compare with the `[f64; 3]` build.
fn same_as_f64<P: Point>(points: &[P]) {
    let (p, f) = octahedron();
    let want = Mesh::from_polygons(&p, &f).unwrap();
    let got = Mesh::from_polygons(points, &f).unwrap();
    assert_eq!(got.to_polygons().0, want.to_polygons().0);
    assert!(got.is_closed());
    assert_eq!(got.euler_characteristic(), 2);
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
