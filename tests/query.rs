//! The face tree against brute force over several meshes (closed, open,
//! n-gons, holes, slivers), winding numbers, staleness and refits.

mod common;

use common::query::{bbox, fans, meshes, Rng};
use meshloom::query::{triangle_closest, triangle_hit, FaceTree, QueryError, Ray, WindingMode};
use meshloom::shapes;
use meshloom::{FaceKey, Mesh};

#[test]
fn first_hits_equal_brute_force() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (name, mesh) in meshes() {
        let tree = FaceTree::build(&mesh).unwrap();
        let tris = fans(&mesh);
        let (lo, hi) = bbox(&mesh);
        let pad = [0, 1, 2].map(|k| (hi[k] - lo[k]).max(1.0));
        let (olo, ohi) = (
            [0, 1, 2].map(|k| lo[k] - pad[k]),
            [0, 1, 2].map(|k| hi[k] + pad[k]),
        );
        let mut rays = Vec::new();
        for i in 0..600 {
            let o = rng.in_box(olo, ohi);
            let target = rng.in_box(lo, hi);
            let mut d = [0, 1, 2].map(|k| target[k] - o[k]);
            if i % 5 == 0 {
                d[i % 3] = 0.0; // axis-parallel planes of travel
            }
            rays.push(Ray::new(o, d));
        }
        // Rays through vertices and along edges.
        for (_, t) in tris.iter().step_by(7) {
            rays.push(Ray::new(
                [t[0][0], t[0][1], t[0][2] + 2.0],
                [0.0, 0.0, -1.0],
            ));
            let mid = [0, 1, 2].map(|k| 0.5 * (t[0][k] + t[1][k]));
            rays.push(Ray::new(
                [mid[0] + 0.3, mid[1] - 0.2, mid[2] + 1.5],
                [-0.3, 0.2, -1.5],
            ));
        }
        let hits = check_rays(name, &mesh, &tree, &rays);
        assert!(hits > 100, "{name}: only {hits} hits");
    }
}

/// Casts `rays` through `tree` and by brute force over `mesh`'s fan
/// triangles; the first hits agree (the face, or the distance on a tie)
/// and the hit lists and shadow tests with them. Returns the hits.
fn check_rays(name: &str, mesh: &Mesh, tree: &FaceTree, rays: &[Ray]) -> usize {
    let tris = fans(mesh);
    let mut hits = 0;
    let batch = tree.ray_cast_batch(mesh, rays).unwrap();
    for (ray, got) in rays.iter().zip(batch) {
        let mut best: Option<(f64, FaceKey)> = None;
        for (f, t) in &tris {
            if let Some((tt, _, _)) = triangle_hit(ray, t) {
                if best.is_none_or(|b| tt < b.0) {
                    best = Some((tt, *f));
                }
            }
        }
        match (best, got) {
            (None, None) => {}
            (Some((t, f)), Some(h)) => {
                hits += 1;
                assert!(
                    h.face == f || (h.t - t).abs() <= 1e-12 * t.abs().max(1e-300),
                    "{name}: {ray:?}: tree {h:?}, brute force {t} on {f:?}"
                );
                assert!(
                    (h.t - t).abs() <= 1e-12 * t.abs(),
                    "{name}: t {} vs {t}",
                    h.t
                );
                let w = h.coords.weights;
                assert!((w[0] + w[1] + w[2] - 1.0).abs() < 1e-9);
                // The hit list starts with the first hit.
                let all = tree.ray_hits(mesh, *ray).unwrap();
                assert!((all[0].t - t).abs() <= 1e-12 * t.abs(), "{name}");
                assert!(tree.any_hit(mesh, *ray, f64::INFINITY).unwrap());
            }
            (b, g) => panic!("{name}: {ray:?}: brute force {b:?}, tree {g:?}"),
        }
    }
    hits
}

/// The box tests run in `f32` where that is safe: far from the origin
/// (where `f32` cannot hold the origin), at the ends of `f32`'s range and
/// with direction components too small for an `f32` reciprocal, the tree
/// still answers as brute force.
#[test]
fn first_hits_equal_brute_force_far_away_and_at_extreme_scales() {
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    for (scale, offset) in [
        (1.0, 1e6),
        (1e-3, 3.3e4),
        (1e-30, 0.0),
        (1e30, 0.0),
        (1e36, 1e37),
    ] {
        for (name, base) in meshes().into_iter().take(3) {
            let mut mesh = base;
            for p in mesh.position_slots_mut().unwrap() {
                *p = p.map(|c| c * scale + offset);
            }
            let tree = FaceTree::build(&mesh).unwrap();
            let (lo, hi) = bbox(&mesh);
            let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
            let pad = [size; 3];
            let (olo, ohi) = (
                [0, 1, 2].map(|k| lo[k] - pad[k]),
                [0, 1, 2].map(|k| hi[k] + pad[k]),
            );
            let mut rays = Vec::new();
            for i in 0..300 {
                let o = rng.in_box(olo, ohi);
                let target = rng.in_box(lo, hi);
                let mut d = [0, 1, 2].map(|k| target[k] - o[k]);
                if i % 4 == 0 {
                    d[i % 3] *= 1e-300; // no f32 reciprocal
                }
                rays.push(Ray::new(o, d));
            }
            let hits = check_rays(name, &mesh, &tree, &rays);
            assert!(hits > 30, "{name} at {scale}, {offset}: only {hits} hits");
        }
    }
}

#[test]
fn closest_points_equal_brute_force() {
    let mut rng = Rng(0x1234_5678_9ABC_DEF1);
    for (name, mesh) in meshes() {
        let tree = FaceTree::build(&mesh).unwrap();
        let tris = fans(&mesh);
        let (lo, hi) = bbox(&mesh);
        let pad = [0, 1, 2].map(|k| 0.5 * (hi[k] - lo[k]).max(1.0));
        let points: Vec<[f64; 3]> = (0..500)
            .map(|_| {
                rng.in_box(
                    [0, 1, 2].map(|k| lo[k] - pad[k]),
                    [0, 1, 2].map(|k| hi[k] + pad[k]),
                )
            })
            .collect();
        let got = tree.closest_points(&mesh, &points, None).unwrap();
        for (q, c) in points.iter().zip(got) {
            let c = c.unwrap();
            let mut best = f64::INFINITY;
            for (_, t) in &tris {
                let (x, _) = triangle_closest(*q, t);
                let d = [0, 1, 2].map(|k| x[k] - q[k]);
                best = best.min((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt());
            }
            assert!(
                (c.distance - best).abs() <= 1e-12 * best.max(1e-300),
                "{name}: {q:?}: {} vs {best}",
                c.distance
            );
            // A limit below the distance finds nothing; at it, the same.
            assert!(tree
                .closest_point(&mesh, *q, Some(best * 0.999))
                .unwrap()
                .is_none());
            let at = tree.closest_point(&mesh, *q, Some(best)).unwrap().unwrap();
            assert_eq!(at.distance, c.distance);
            // Radius queries hold the closest face, nearest vertex agrees.
            let within = tree.faces_within(&mesh, *q, best * (1.0 + 1e-9)).unwrap();
            assert!(within.contains(&c.face), "{name}");
            let n = tree.nearest_vertex(&mesh, *q).unwrap().unwrap();
            let brute = tris
                .iter()
                .flat_map(|(_, t)| t.iter())
                .map(|p| {
                    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
                })
                .fold(f64::INFINITY, f64::min);
            assert!((n.distance - brute).abs() <= 1e-12 * brute, "{name}");
            let vs = tree
                .vertices_within(&mesh, *q, brute * (1.0 + 1e-9))
                .unwrap();
            assert!(vs.contains(&n.vertex), "{name}");
        }
    }
}

#[test]
fn winding_numbers_tell_inside_from_outside() {
    let mut rng = Rng(77);
    for mesh in [shapes::icosphere(3), shapes::uv_sphere(24, 12)] {
        let tree = FaceTree::build(&mesh).unwrap();
        for _ in 0..300 {
            let p = rng.in_box([-1.6; 3], [1.6; 3]);
            let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            if (0.9..1.1).contains(&r) {
                continue;
            }
            let want = if r < 1.0 { 1.0 } else { 0.0 };
            let exact = tree.winding_number(&mesh, p, WindingMode::Exact).unwrap();
            assert!((exact - want).abs() < 1e-9, "{p:?}: exact {exact}");
            let fast = tree
                .winding_number(&mesh, p, WindingMode::default())
                .unwrap();
            assert!((fast - want).abs() < 5e-2, "{p:?}: fast {fast}");
            let closer = tree
                .winding_number(&mesh, p, WindingMode::Approximate { accuracy: 8.0 })
                .unwrap();
            assert!((closer - exact).abs() <= (fast - exact).abs() + 1e-3);
            assert_eq!(tree.contains(&mesh, p).unwrap(), r < 1.0);
        }
    }
}

#[test]
fn an_open_half_sphere_winds_one_half_on_its_cut() {
    let mut mesh = shapes::uv_sphere(32, 16);
    let below: Vec<FaceKey> = mesh
        .faces()
        .filter(|&f| {
            mesh.face(f)
                .unwrap()
                .vertices()
                .any(|v| mesh.position(v).unwrap()[2] < -1e-9)
        })
        .collect();
    for f in below {
        mesh.remove_face(f).unwrap();
    }
    assert!(!mesh.is_closed());
    let tree = FaceTree::build(&mesh).unwrap();
    for p in [[0.0, 0.0, 0.0], [0.3, -0.2, 0.0], [-0.5, 0.1, 0.0]] {
        let w = tree.winding_number(&mesh, p, WindingMode::Exact).unwrap();
        assert!((w.abs() - 0.5).abs() < 1e-9, "{p:?}: {w}");
        let fast = tree
            .winding_number(&mesh, p, WindingMode::default())
            .unwrap();
        assert!((fast - w).abs() < 2e-2, "{p:?}: {fast} vs {w}");
    }
}

#[test]
fn a_tree_refuses_a_mesh_that_changed_and_another_mesh() {
    let mut mesh = shapes::icosphere(2);
    let tree = FaceTree::build(&mesh).unwrap();
    let ray = Ray::new([0.0, 0.0, -3.0], [0.0, 0.0, 1.0]);
    assert!(tree.ray_cast(&mesh, ray).is_ok());
    // A clone is another mesh value.
    let copy = mesh.clone();
    let other = tree.ray_cast(&copy, ray);
    assert!(
        matches!(
            other,
            Err(QueryError::StaleTree {
                same_mesh: false,
                ..
            })
        ),
        "{other:?}"
    );
    // A topological edit far from the ray.
    let e = mesh.edges().next().unwrap();
    mesh.flip_edge(e).unwrap();
    let stale = tree.ray_cast(&mesh, ray);
    assert!(
        matches!(
            stale,
            Err(QueryError::StaleTree {
                same_mesh: true,
                ..
            })
        ),
        "{stale:?}"
    );
    assert!(tree.closest_point(&mesh, [0.0; 3], None).is_err());
    assert!(tree
        .winding_number(&mesh, [0.0; 3], WindingMode::Exact)
        .is_err());
    assert!(!tree.is_current(&mesh));
    // A refit refuses changed faces; a rebuild serves.
    let mut refitted = tree.clone();
    assert!(matches!(
        refitted.refit(&mesh),
        Err(QueryError::TopologyChanged { .. })
    ));
    assert!(FaceTree::build(&mesh).unwrap().ray_cast(&mesh, ray).is_ok());
}

#[test]
fn undo_and_a_bulk_position_view_make_the_tree_stale() {
    let mut mesh = shapes::cube();
    mesh.history_mut().enable(Default::default());
    let v = mesh.vertices().next().unwrap();
    mesh.set_position(v, [-0.6, -0.6, -0.6]).unwrap();
    let tree = FaceTree::build(&mesh).unwrap();
    assert!(mesh.undo());
    assert!(!tree.is_current(&mesh));
    let tree = FaceTree::build(&mesh).unwrap();
    mesh.position_slots_mut().unwrap()[0][0] += 0.1;
    assert!(!tree.is_current(&mesh));
}

#[test]
fn a_refit_answers_as_a_fresh_build() {
    let mut rng = Rng(4242);
    for (name, mut mesh) in meshes() {
        let mut tree = FaceTree::build(&mesh).unwrap();
        for p in mesh.position_slots_mut().unwrap() {
            for c in p.iter_mut() {
                *c += 0.2 * (rng.next() - 0.5);
            }
        }
        tree.refit(&mesh).unwrap();
        let fresh = FaceTree::build(&mesh).unwrap();
        let (lo, hi) = bbox(&mesh);
        for _ in 0..200 {
            let o = rng.in_box(
                [0, 1, 2].map(|k| lo[k] - 1.0),
                [0, 1, 2].map(|k| hi[k] + 1.0),
            );
            let t = rng.in_box(lo, hi);
            let ray = Ray::new(o, [0, 1, 2].map(|k| t[k] - o[k]));
            let a = tree.ray_cast(&mesh, ray).unwrap().map(|h| h.t);
            let b = fresh.ray_cast(&mesh, ray).unwrap().map(|h| h.t);
            assert_eq!(a, b, "{name}");
            let a = tree
                .closest_point(&mesh, o, None)
                .unwrap()
                .unwrap()
                .distance;
            let b = fresh
                .closest_point(&mesh, o, None)
                .unwrap()
                .unwrap()
                .distance;
            assert_eq!(a, b, "{name}");
        }
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let mesh = shapes::cube();
    let tree = FaceTree::build(&mesh).unwrap();
    let nan = Ray::new([f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0]);
    assert!(matches!(
        tree.ray_cast(&mesh, nan),
        Err(QueryError::NonFiniteRay { index: 0, .. })
    ));
    let rays = [
        Ray::new([0.0; 3], [1.0, 0.0, 0.0]),
        Ray::new([0.0; 3], [0.0; 3]),
    ];
    assert_eq!(
        tree.ray_cast_batch(&mesh, &rays),
        Err(QueryError::ZeroDirection { index: 1 })
    );
    let inf = Ray::new([0.0; 3], [f64::INFINITY, 0.0, 0.0]);
    assert!(matches!(
        tree.ray_hits(&mesh, inf),
        Err(QueryError::NonFiniteRay { .. })
    ));
    let pts = [[0.0; 3], [0.0, f64::NAN, 0.0]];
    assert!(matches!(
        tree.closest_points(&mesh, &pts, None),
        Err(QueryError::NonFinitePoint { index: 1, .. })
    ));
    assert!(matches!(
        tree.winding_numbers(&mesh, &pts, WindingMode::Exact),
        Err(QueryError::NonFinitePoint { index: 1, .. })
    ));
    assert!(matches!(
        tree.faces_within(&mesh, [0.0; 3], -1.0),
        Err(QueryError::InvalidBound { what: "radius", .. })
    ));
    assert!(matches!(
        tree.closest_point(&mesh, [0.0; 3], Some(f64::NAN)),
        Err(QueryError::InvalidBound { .. })
    ));
    assert!(matches!(
        tree.any_hit(&mesh, rays[0], -1.0),
        Err(QueryError::InvalidBound { what: "max_t", .. })
    ));
    assert_eq!(
        FaceTree::build(&Mesh::default()).err(),
        Some(QueryError::NoPositions)
    );
    let msg = tree.ray_cast_batch(&mesh, &rays).unwrap_err().to_string();
    assert!(msg.contains("ray 1"), "{msg}");
}
