//! Curvature: spheres converge to 1/r and 1/r², planes give zero,
//! Gauss-Bonnet holds to rounding, degenerate input stays finite.

use meshloom::algo::curvature::{
    add_curvature, curvature, BoundaryCurvature, CurvatureOptions, GAUSSIAN_CURVATURE,
};
use meshloom::shapes::{self, GridFaces};
use meshloom::Mesh;
use std::f64::consts::PI;

fn scaled(mut mesh: Mesh, r: f64) -> Mesh {
    for p in mesh.position_slots_mut().unwrap() {
        *p = p.map(|c| c * r);
    }
    mesh
}

/// Largest |H − 1/r| and |K − 1/r²| over the vertices, relative.
fn sphere_errors(level: u32, r: f64) -> (f64, f64) {
    let mesh = scaled(shapes::icosphere(level), r);
    let c = curvature(&mesh, &CurvatureOptions::default()).unwrap();
    let mut eh: f64 = 0.0;
    let mut ek: f64 = 0.0;
    for v in mesh.vertices() {
        let i = v.index();
        eh = eh.max((c.mean[i] * r - 1.0).abs());
        ek = ek.max((c.gaussian[i] * r * r - 1.0).abs());
        assert!(c.min[i] <= c.max[i]);
    }
    (eh, ek)
}

#[test]
fn sphere_curvatures_converge_under_refinement() {
    // Stated tolerances (relative, max over vertices), levels 2 to 5: both
    // errors fall by about 4x per level (second order). Measured: H 1.4e-4,
    // 3.5e-5, 8.7e-6, 2.2e-6; K 2.0e-2, 5.5e-3, 1.4e-3, 3.6e-4.
    let tol_h = [3e-4, 8e-5, 2e-5, 5e-6];
    let tol_k = [3e-2, 8e-3, 2e-3, 5e-4];
    let mut last = (f64::INFINITY, f64::INFINITY);
    for (k, level) in (2..=5).enumerate() {
        for r in [1.0, 0.01, 250.0] {
            let (eh, ek) = sphere_errors(level, r);
            assert!(eh < tol_h[k], "level {level} r {r}: H error {eh}");
            assert!(ek < tol_k[k], "level {level} r {r}: K error {ek}");
            if r == 1.0 {
                assert!(eh < last.0 && ek < last.1, "level {level}: errors grow");
                last = (eh, ek);
            }
        }
    }
}

#[test]
fn planes_have_zero_curvature() {
    for faces in [GridFaces::Triangles, GridFaces::Quads] {
        let mut mesh = shapes::grid(7, 5, faces);
        // Tilt the plane and jitter interior vertices within it.
        let keys: Vec<_> = mesh.vertices().collect();
        for (i, &v) in keys.iter().enumerate() {
            let mut p = mesh.position(v).unwrap();
            if !mesh.vertex(v).unwrap().is_boundary() {
                p[0] += 0.03 * ((i * 7 % 5) as f64 - 2.0);
                p[1] += 0.03 * ((i * 3 % 5) as f64 - 2.0);
            }
            let z = 0.3 * p[0] - 0.2 * p[1];
            mesh.set_position(v, [p[0], p[1], z]).unwrap();
        }
        for boundary in [BoundaryCurvature::FromInterior, BoundaryCurvature::OneSided] {
            let c = curvature(&mesh, &CurvatureOptions::default().boundary(boundary)).unwrap();
            for &v in &keys {
                let i = v.index();
                if boundary == BoundaryCurvature::OneSided && mesh.vertex(v).unwrap().is_boundary()
                {
                    continue;
                }
                assert!(c.mean[i].abs() < 1e-9, "{faces:?} H {}", c.mean[i]);
                assert!(c.gaussian[i].abs() < 1e-9, "{faces:?} K {}", c.gaussian[i]);
            }
        }
    }
}

fn total_gaussian(mesh: &Mesh, boundary: BoundaryCurvature) -> f64 {
    let c = curvature(mesh, &CurvatureOptions::default().boundary(boundary)).unwrap();
    mesh.vertices()
        .map(|v| c.gaussian[v.index()] * c.area[v.index()])
        .sum()
}

#[test]
fn gauss_bonnet_on_closed_meshes() {
    let elephant = meshloom::io::read("../shared/data/meshes/closed/cgal_elephant.off").unwrap();
    let bunny = meshloom::io::read("../shared/data/meshes/closed/cgal_bunny00.off").unwrap();
    let cases: Vec<(&str, Mesh)> = vec![
        ("icosphere", shapes::icosphere(3)),
        ("tetrahedron", shapes::tetrahedron()),
        ("cube (quads)", shapes::cube()),
        (
            "torus (planar quads)",
            shapes::torus(12, 8, 2.0, 0.6).unwrap(),
        ),
        ("elephant (genus 3)", elephant),
        ("bunny", bunny),
    ];
    for (name, mesh) in cases {
        assert!(mesh.is_closed());
        let chi = mesh.euler_characteristic() as f64;
        let total = total_gaussian(&mesh, BoundaryCurvature::FromInterior);
        // Exact up to rounding: a sum of V angle defects.
        let tol = 1e-10 * mesh.vertex_count() as f64;
        assert!(
            (total - 2.0 * PI * chi).abs() < tol,
            "{name}: {total} vs {}",
            2.0 * PI * chi
        );
    }
}

#[test]
fn gauss_bonnet_with_boundary_one_sided() {
    for mesh in [
        shapes::grid(6, 4, GridFaces::Triangles),
        shapes::disk(12),
        meshloom::io::read("../shared/data/meshes/boundary/cgal_holes.off").unwrap(),
    ] {
        let chi = mesh.euler_characteristic() as f64;
        let total = total_gaussian(&mesh, BoundaryCurvature::OneSided);
        assert!((total - 2.0 * PI * chi).abs() < 1e-9, "{total} vs {chi}");
    }
}

#[test]
fn boundary_vertices_take_the_interior_average() {
    let mesh = shapes::grid(4, 4, GridFaces::Triangles);
    let mut bent = mesh.clone();
    let keys: Vec<_> = bent.vertices().collect();
    for &v in &keys {
        let p = bent.position(v).unwrap();
        bent.set_position(v, [p[0], p[1], 0.1 * (p[0] * p[0] + p[1] * p[1])])
            .unwrap();
    }
    let c = curvature(&bent, &CurvatureOptions::default()).unwrap();
    for &v in &keys {
        let view = bent.vertex(v).unwrap();
        if !view.is_boundary() {
            continue;
        }
        let inner: Vec<usize> = view
            .neighbors()
            .filter(|w| !bent.vertex(*w).unwrap().is_boundary())
            .map(|w| w.index())
            .collect();
        let want = if inner.is_empty() {
            0.0
        } else {
            inner.iter().map(|&j| c.mean[j]).sum::<f64>() / inner.len() as f64
        };
        assert!((c.mean[v.index()] - want).abs() < 1e-15);
    }
}

#[test]
fn degenerate_faces_stay_finite() {
    // Collinear and coincident corners; a NaN-free result with zero-area
    // vertices getting zero.
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    let mesh = Mesh::from_polygons(&p, &[[0u32, 1, 3], [1, 2, 3], [0, 2, 1], [3, 2, 4]]);
    let mesh = match mesh {
        Ok(m) => m,
        Err(_) => Mesh::from_polygons(&p, &[[0u32, 1, 3], [1, 2, 4], [0, 4, 1]]).unwrap(),
    };
    let c = curvature(&mesh, &CurvatureOptions::default()).unwrap();
    for v in [&c.mean, &c.gaussian, &c.min, &c.max, &c.area] {
        assert!(v.iter().all(|x| x.is_finite()));
    }
    // Empty mesh: empty results.
    let c = curvature(&Mesh::new(), &CurvatureOptions::default()).unwrap();
    assert!(c.mean.is_empty());
}

#[test]
fn columns_hold_the_values_and_refuse_a_wrong_type() {
    let mut mesh = shapes::icosphere(2);
    let cols = add_curvature(&mut mesh, &CurvatureOptions::default()).unwrap();
    let c = curvature(&mesh, &CurvatureOptions::default()).unwrap();
    for v in mesh.vertices() {
        assert_eq!(
            mesh.attr(&cols.gaussian, v).unwrap(),
            Some(&c.gaussian[v.index()])
        );
        assert_eq!(mesh.attr(&cols.max, v).unwrap(), Some(&c.max[v.index()]));
    }
    mesh.validate().unwrap();
    // A column of that name with another type: refused, nothing written.
    let mut other = shapes::icosphere(1);
    other.add_vertex_attr::<u32>(GAUSSIAN_CURVATURE).unwrap();
    let before = other.attr_info(meshloom::ElementKind::Vertex).len();
    assert!(add_curvature(&mut other, &CurvatureOptions::default()).is_err());
    assert_eq!(other.attr_info(meshloom::ElementKind::Vertex).len(), before);
}
