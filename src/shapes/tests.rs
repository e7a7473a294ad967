//! Shape checks: validity, counts against the formulas, orientation.

use super::*;

/// Six times the signed volume enclosed (fan-triangulated faces).
fn signed_volume6(p: &Polygons) -> f64 {
    let mut v = 0.0;
    for f in p.faces() {
        let a = p.positions[f[0] as usize];
        for k in 1..f.len() - 1 {
            let b = p.positions[f[k] as usize];
            let c = p.positions[f[k + 1] as usize];
            v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]);
        }
    }
    v
}

/// The z component of each face's (fan) area vector.
fn normal_z(p: &Polygons, f: &[u32]) -> f64 {
    let mut z = 0.0;
    for k in 0..f.len() {
        let a = p.positions[f[k] as usize];
        let b = p.positions[f[(k + 1) % f.len()] as usize];
        z += a[0] * b[1] - a[1] * b[0];
    }
    z
}

fn vef(m: &Mesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

fn closed_and_outward(p: &Polygons) -> Mesh {
    let m = Mesh::from_buffers(p).unwrap();
    m.validate().unwrap();
    assert!(m.is_closed());
    assert!(signed_volume6(p) > 0.0, "faces must point outwards");
    assert_eq!(m.to_polygons().0, *p, "slot order follows input order");
    m
}

fn flat_and_up(p: &Polygons) -> Mesh {
    let m = Mesh::from_buffers(p).unwrap();
    m.validate().unwrap();
    assert_eq!((m.hole_count(), m.euler_characteristic()), (1, 1));
    assert!(
        p.faces().all(|f| normal_z(p, f) > 0.0),
        "faces must face +z"
    );
    m
}

#[test]
fn platonic_solids_are_closed_and_outward() {
    for (p, counts) in [
        (tetrahedron_polygons(), (4, 6, 4)),
        (cube_polygons(), (8, 12, 6)),
        (octahedron_polygons(), (6, 12, 8)),
        (icosahedron_polygons(), (12, 30, 20)),
    ] {
        assert_eq!(vef(&closed_and_outward(&p)), counts);
    }
}

#[test]
fn icosphere_counts_and_radius() {
    for n in 0..=3u32 {
        let p = icosphere_polygons(n);
        let m = closed_and_outward(&p);
        let k = 4usize.pow(n);
        assert_eq!(vef(&m), (10 * k + 2, 30 * k, 20 * k));
        for q in &p.positions {
            let r = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            assert!((r - 1.0).abs() < 1e-12);
        }
        // Subdivided vertices have degree 6; the 12 originals keep 5.
        let five = m
            .vertices()
            .filter(|&v| m.vertex(v).unwrap().degree() == 5)
            .count();
        assert_eq!(five, 12);
    }
}

#[test]
fn uv_sphere_counts() {
    for s in 3..7 {
        for r in 2..6 {
            let p = uv_sphere_polygons(s, r);
            let m = closed_and_outward(&p);
            assert_eq!(vef(&m), (s * (r - 1) + 2, s * (2 * r - 1), s * r));
            assert_eq!(p.faces().filter(|f| f.len() == 3).count(), 2 * s);
        }
    }
}

#[test]
fn torus_counts_and_genus() {
    for big in 3..6 {
        for small in 3..6 {
            let p = torus_polygons(big, small, 2.0, 0.5);
            let m = closed_and_outward(&p);
            assert_eq!(vef(&m), (big * small, 2 * big * small, big * small));
            assert_eq!(m.euler_characteristic(), 0);
        }
    }
    for bad in [f64::NAN, f64::INFINITY, f64::MAX] {
        assert!(torus(4, 4, bad, bad).is_err());
    }
}

#[test]
fn grid_counts() {
    for c in 1..5 {
        for r in 1..5 {
            let e = c * (r + 1) + r * (c + 1);
            let q = flat_and_up(&grid_polygons(c, r, GridFaces::Quads));
            assert_eq!(vef(&q), ((c + 1) * (r + 1), e, c * r));
            let t = flat_and_up(&grid_polygons(c, r, GridFaces::Triangles));
            assert_eq!(vef(&t), ((c + 1) * (r + 1), e + c * r, 2 * c * r));
            let hole = t.holes().next().unwrap();
            assert_eq!(t.face(hole).unwrap().degree(), 2 * (c + r));
        }
    }
}

#[test]
fn disk_counts() {
    for s in 3..9 {
        let d = flat_and_up(&disk_polygons(s));
        assert_eq!(vef(&d), (s + 1, 2 * s, s));
    }
}

#[test]
fn small_and_huge_parameters_are_clamped() {
    assert_eq!(vef(&grid(0, 0, GridFaces::Quads)), (4, 4, 1));
    assert_eq!(vef(&disk(0)), (4, 6, 3));
    assert_eq!(vef(&uv_sphere(1, 1)), (5, 9, 6));
    assert_eq!(vef(&torus(0, 1, 1.0, 0.5).unwrap()), (9, 18, 9));
    assert_eq!(disk(usize::MAX).face_count(), MAX_SEGMENTS);
    assert_eq!(
        grid_polygons(usize::MAX, 1, GridFaces::Quads).face_count(),
        MAX_SEGMENTS
    );
    assert_eq!(uv_sphere(usize::MAX, 2).face_count(), 2 * MAX_SEGMENTS);
}
