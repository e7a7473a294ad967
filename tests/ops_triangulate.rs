//! triangulate and triangulate_all: ear clipping with positions, fans
//! without.

mod common;
use common::*;
use meshloom::{shapes, Mesh};

/// Signed area of a triangle in the xy-plane.
fn signed_area(m: &Mesh, f: meshloom::FaceKey) -> f64 {
    let p: Vec<_> = m
        .face(f)
        .unwrap()
        .vertices()
        .map(|v| m.position(v).unwrap())
        .collect();
    0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]))
}

#[test]
fn non_convex_polygons_give_valid_triangles() {
    // A comb: a polygon with several reflex corners, in the xy-plane.
    let p = [
        [0.0, 0.0, 0.0],
        [5.0, 0.0, 0.0],
        [5.0, 3.0, 0.0],
        [4.0, 3.0, 0.0],
        [4.0, 1.0, 0.0],
        [3.0, 1.0, 0.0],
        [3.0, 3.0, 0.0],
        [2.0, 3.0, 0.0],
        [2.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 3.0, 0.0],
        [0.0, 3.0, 0.0],
    ];
    let idx: Vec<u32> = (0..12).collect();
    let mut m = Mesh::from_polygons(&p, &[idx]).unwrap();
    let t = add_totals(&mut m);
    let f = m.faces().next().unwrap();
    let tris = checked(&mut m, |m| m.triangulate(f)).unwrap();
    assert_eq!(tris.len(), 10);
    let mut total = 0.0;
    for &g in &tris {
        let a = signed_area(&m, g);
        assert!(a > 0.0, "triangle {g} is inverted or flat: {a}");
        total += a;
    }
    assert!(
        (total - 11.0).abs() < 1e-9,
        "areas add up to the polygon's: {total}"
    );
    assert!((face_total(&m, &t) - 1.0).abs() < 1e-12);
    // Shares are by area.
    for &g in &tris {
        let share = *m.attr(&t.face, g).unwrap().unwrap();
        assert!((share - signed_area(&m, g) / 11.0).abs() < 1e-12);
    }
}

#[test]
fn non_convex_quad_is_cut_at_its_reflex_corner() {
    // A dart: corner 3 is reflex, so only the diagonal 1-3 is inside.
    let p = [
        [0.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [0.0, 2.0, 0.0],
        [0.5, 1.0, 0.0],
    ];
    let mut m = Mesh::from_polygons(&p, &[[0u32, 1, 2, 3]]).unwrap();
    let f = m.faces().next().unwrap();
    let tris = checked(&mut m, |m| m.triangulate(f)).unwrap();
    for g in tris {
        assert!(signed_area(&m, g) > 0.0);
    }
    let v: Vec<_> = m.vertices().collect();
    assert!(m.find_halfedge(v[1], v[3]).unwrap().is_some());
}

#[test]
fn fan_without_positions_avoids_existing_edges() {
    // Quad (0,1,2,3) whose diagonal 0-2 exists outside it.
    let mut m = Mesh::from_faces(5, &[vec![0u32, 1, 2, 3], vec![0, 4, 2]])
        .unwrap_or_else(|e| panic!("{e}"));
    let quad = m.faces().next().unwrap();
    let tris = checked(&mut m, |m| m.triangulate(quad)).unwrap();
    assert_eq!(tris.len(), 2);
    let v: Vec<_> = m.vertices().collect();
    assert!(m.find_halfedge(v[1], v[3]).unwrap().is_some());
}

#[test]
fn triangulate_all_on_named_meshes() {
    for mut m in [shapes::cube(), l_shape(), quad_grid(4), one_ring()] {
        let t = add_totals(&mut m);
        let (v, f0, chi) = (m.vertex_count(), m.face_count(), m.euler_characteristic());
        let corners: usize = m.faces().map(|f| m.face(f).unwrap().degree() - 2).sum();
        assert!(m.triangulate_all().is_empty());
        m.validate().unwrap();
        assert_eq!(m.face_count(), corners);
        assert_eq!(m.vertex_count(), v);
        assert_eq!(m.euler_characteristic(), chi);
        assert!(m.faces().all(|f| m.face(f).unwrap().degree() == 3));
        assert!((face_total(&m, &t) - f0 as f64).abs() < 1e-9);
    }
    // Holes are refused.
    let mut m = l_shape();
    let h = m.holes().next().unwrap();
    assert!(checked(&mut m, |m| m.triangulate(h)).is_err());
}
