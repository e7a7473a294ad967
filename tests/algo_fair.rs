//! Fairing: a bump flattens, planes stay planes, the fixed rings stay bit
//! for bit, the solution satisfies the k-Laplace equation (checked here from
//! the public neighbour lists), failures and cancels change nothing.
//! (Fairing needs the `sparse` feature, on by default.)
#![cfg(feature = "sparse")]

use meshloom::algo::fair::{fair, FairOptions, FairRegion};
use meshloom::algo::laplacian::LaplaceWeights;
use meshloom::algo::{Flow, Progress, ProgressInfo};
use meshloom::shapes::{self, GridFaces};
use meshloom::{Error, Mesh, VertexKey};

const WEIGHTS: [LaplaceWeights; 2] = [LaplaceWeights::Cotan, LaplaceWeights::Uniform];

fn snapshot(mesh: &Mesh) -> Vec<[u64; 3]> {
    mesh.position_slots()
        .unwrap()
        .iter()
        .map(|p| p.map(f64::to_bits))
        .collect()
}

/// A 20 × 20 grid with a smooth bump of height 2 and radius 5 at (10, 10).
fn bump() -> Mesh {
    let mut mesh = shapes::grid(20, 20, GridFaces::Triangles);
    for p in mesh.position_slots_mut().unwrap() {
        let r = ((p[0] - 10.0).powi(2) + (p[1] - 10.0).powi(2)).sqrt();
        if r < 5.0 {
            p[2] = 2.0 * (0.5 + 0.5 * (std::f64::consts::PI * r / 5.0).cos());
        }
    }
    mesh
}

fn within(mesh: &Mesh, radius: f64) -> Vec<VertexKey> {
    mesh.vertices()
        .filter(|&v| {
            let p = mesh.position(v).unwrap();
            (p[0] - 10.0).powi(2) + (p[1] - 10.0).powi(2) < radius * radius
        })
        .collect()
}

fn max_height(mesh: &Mesh) -> f64 {
    mesh.position_slots()
        .unwrap()
        .iter()
        .map(|p| p[2].abs())
        .fold(0.0, f64::max)
}

#[test]
fn fairing_the_top_of_a_bump_lowers_it_and_keeps_the_rest() {
    let mesh = bump();
    assert!((max_height(&mesh) - 2.0).abs() < 1e-12);
    for weights in WEIGHTS {
        for order in 1..=3 {
            let mut m = mesh.clone();
            let region = within(&m, 3.0);
            let before = snapshot(&m);
            let opts = FairOptions::default()
                .region(FairRegion::Vertices(region.clone()))
                .order(order)
                .weights(weights);
            let report = fair(&mut m, &opts, Progress::none()).unwrap();
            m.validate().unwrap();
            assert_eq!(report.moved, region.len());
            assert!(report.fixed > 0);
            let after = snapshot(&m);
            // Everything outside the region is bit-identical.
            for v in m.vertices() {
                if !region.contains(&v) {
                    assert_eq!(before[v.index()], after[v.index()]);
                }
            }
            // Stated: the top loses at least a tenth of its height (the
            // membrane, k = 1, spans the ring at r = 3 (height ~0.69);
            // k = 2 and 3 also follow its slope, so they stay higher).
            let h = max_height(&m);
            assert!(h < 1.8, "{weights:?} k={order}: {h}");
            assert!(h > 0.5, "{weights:?} k={order}: {h}");
        }
    }
}

#[test]
fn a_bump_on_flat_surroundings_becomes_the_plane() {
    // The region covers the bump and its fixed rings are flat: the fair
    // surface is the plane (the z right-hand side is exactly zero).
    for weights in WEIGHTS {
        for order in 1..=3 {
            let mut m = bump();
            let region = within(&m, 6.5);
            let opts = FairOptions::default()
                .region(FairRegion::Vertices(region))
                .order(order)
                .weights(weights);
            fair(&mut m, &opts, Progress::none()).unwrap();
            m.validate().unwrap();
            assert!(max_height(&m) < 1e-12, "{weights:?} k={order}");
        }
    }
}

#[test]
fn a_planar_region_stays_planar() {
    // A tilted plane whose inner vertices are jittered within the plane.
    let (a, b, c) = (0.3, -0.2, 1.0);
    let mut mesh = shapes::grid(12, 12, GridFaces::Triangles);
    let mut seed = 11u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    };
    let keys: Vec<_> = mesh.vertices().collect();
    for &v in &keys {
        let mut p = mesh.position(v).unwrap();
        if !mesh.vertex(v).unwrap().is_boundary() {
            p[0] += 0.3 * rnd();
            p[1] += 0.3 * rnd();
        }
        p[2] = a * p[0] + b * p[1] + c;
        mesh.set_position(v, p).unwrap();
    }
    let off_plane = |m: &Mesh| {
        m.position_slots()
            .unwrap()
            .iter()
            .map(|p| (a * p[0] + b * p[1] + c - p[2]).abs())
            .fold(0.0, f64::max)
    };
    assert!(off_plane(&mesh) < 1e-12);
    for weights in WEIGHTS {
        for order in 1..=3 {
            let mut m = mesh.clone();
            let opts = FairOptions::default()
                .region(FairRegion::All)
                .order(order)
                .weights(weights);
            let report = fair(&mut m, &opts, Progress::none()).unwrap();
            m.validate().unwrap();
            assert!(report.max_displacement > 1e-3, "{weights:?} k={order}");
            assert!(off_plane(&m) < 1e-9, "{weights:?} k={order}");
        }
    }
}

#[test]
fn the_boundary_and_its_rings_stay_bit_identical() {
    // Region = all; on a grid, the boundary and its k − 1 rings are locked.
    let mesh = bump();
    // Ring number of each vertex: its distance (in edges) to the boundary.
    let ring = |m: &Mesh, v: VertexKey| {
        let p = m.position(v).unwrap();
        let (i, j) = (p[0].round() as i64, p[1].round() as i64);
        i.min(j).min(20 - i).min(20 - j)
    };
    // A noisy z near the boundary so that moving would show.
    let mut noisy = mesh.clone();
    let keys: Vec<_> = noisy.vertices().collect();
    for (n, &v) in keys.iter().enumerate() {
        let mut p = noisy.position(v).unwrap();
        p[2] += 0.1 * ((n * 7919 % 13) as f64 / 13.0 - 0.5);
        noisy.set_position(v, p).unwrap();
    }
    for order in 1..=3u32 {
        let mut m = noisy.clone();
        let before = snapshot(&m);
        let opts = FairOptions::default().order(order);
        fair(&mut m, &opts, Progress::none()).unwrap();
        m.validate().unwrap();
        let after = snapshot(&m);
        for &v in &keys {
            let r = ring(&m, v);
            let same = before[v.index()] == after[v.index()];
            if r < i64::from(order) {
                assert!(same, "k={order}: ring {r} moved");
            } else {
                assert!(!same, "k={order}: ring {r} did not move");
            }
        }
    }
}

/// `L x` at `v` with uniform weights, from the public neighbour lists.
fn uniform_laplace(m: &Mesh, x: &dyn Fn(VertexKey) -> [f64; 3], v: VertexKey) -> [f64; 3] {
    let mut s = [0.0; 3];
    let p = x(v);
    for w in m.vertex(v).unwrap().neighbors() {
        let q = x(w);
        for k in 0..3 {
            s[k] += q[k] - p[k];
        }
    }
    s
}

#[test]
fn uniform_fairing_solves_the_k_laplace_equation() {
    for order in 1..=2u32 {
        let mut m = bump();
        let region = within(&m, 4.0);
        let opts = FairOptions::default()
            .region(FairRegion::Vertices(region.clone()))
            .order(order)
            .weights(LaplaceWeights::Uniform);
        fair(&mut m, &opts, Progress::none()).unwrap();
        let pos = |v: VertexKey| m.position(v).unwrap();
        for &v in &region {
            let r = if order == 1 {
                uniform_laplace(&m, &pos, v)
            } else {
                let lap = |w: VertexKey| uniform_laplace(&m, &pos, w);
                uniform_laplace(&m, &lap, v)
            };
            assert!(r.iter().all(|c| c.abs() < 1e-9), "k={order}: {r:?}");
        }
    }
}

/// A unit icosphere (level 4) and its cap z > 0.6, the cap pushed
/// radially by up to ±2.5 % when `noisy`.
fn sphere_cap(noisy: bool) -> (Mesh, Vec<VertexKey>) {
    let mut m = shapes::icosphere(4);
    let cap: Vec<_> = m
        .vertices()
        .filter(|&v| m.position(v).unwrap()[2] > 0.6)
        .collect();
    if noisy {
        for (n, &v) in cap.iter().enumerate() {
            let p = m.position(v).unwrap();
            let s = 1.0 + 0.05 * ((n * 7919 % 17) as f64 / 17.0 - 0.5);
            m.set_position(v, p.map(|c| c * s)).unwrap();
        }
    }
    (m, cap)
}

/// The largest distance of the cap's vertices to the unit sphere.
fn off_sphere(m: &Mesh, cap: &[VertexKey]) -> f64 {
    cap.iter()
        .map(|&v| {
            let p = m.position(v).unwrap();
            ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn fairing_a_noisy_cap_of_a_sphere_evens_it() {
    let (mut m, cap) = sphere_cap(true);
    let before = off_sphere(&m, &cap);
    assert!(before > 0.024);
    let keys: Vec<_> = m.vertices().collect();
    let mask = m.add_vertex_attr::<bool>("cap").unwrap();
    for &v in &cap {
        m.set_attr(&mask, v, true).unwrap();
    }
    let colour = m.add_vertex_attr::<f32>("colour").unwrap();
    for (n, &v) in keys.iter().enumerate() {
        m.set_attr(&colour, v, n as f32).unwrap();
    }
    // k = 3 (its fixed rings carry position, tangent plane and curvature)
    // brings the cap back to the sphere: stated within 1.5 % (measured
    // 0.98 %; 0.35 % from a clean cap, the rest from cotangent weights
    // taken on the noisy cap). k = 2 sags (a sphere's Laplacian is not
    // zero): stated within 6 % (measured 5.4 %). k = 1 is the flat disc
    // spanning the cap's rim: 0.43 below the pole.
    for (order, bound) in [(3, 0.015), (2, 0.06)] {
        let mut faired = m.clone();
        let opts = FairOptions::default()
            .region(FairRegion::Mask(mask.clone()))
            .order(order);
        let report = fair(&mut faired, &opts, Progress::none()).unwrap();
        faired.validate().unwrap();
        assert_eq!(report.moved, cap.len());
        let after = off_sphere(&faired, &cap);
        assert!(after < bound, "k={order}: {before} -> {after}");
        // Other columns keep their values.
        for (n, &v) in keys.iter().enumerate() {
            assert_eq!(faired.attr(&colour, v).unwrap(), Some(&(n as f32)));
            assert_eq!(faired.attr(&mask, v).unwrap(), m.attr(&mask, v).unwrap());
        }
    }
}

#[test]
fn uniform_fairing_forgets_the_region_old_positions() {
    // Uniform weights do not depend on positions, so the noisy and the
    // clean cap fair to the same surface (up to rounding).
    let (clean, cap) = sphere_cap(false);
    let (noisy, _) = sphere_cap(true);
    for order in 1..=3 {
        let opts = FairOptions::default()
            .region(FairRegion::Vertices(cap.clone()))
            .order(order)
            .weights(LaplaceWeights::Uniform);
        let (mut a, mut b) = (clean.clone(), noisy.clone());
        fair(&mut a, &opts, Progress::none()).unwrap();
        fair(&mut b, &opts, Progress::none()).unwrap();
        for &v in &cap {
            let (p, q) = (a.position(v).unwrap(), b.position(v).unwrap());
            assert!((0..3).all(|k| (p[k] - q[k]).abs() < 1e-12), "k={order}");
        }
    }
}

#[test]
fn refusals_and_cancels_leave_the_mesh_unchanged() {
    let mut m = bump();
    let before = snapshot(&m);
    let region = within(&m, 3.0);
    // Count the reports, then cancel at each in turn (the last one comes
    // after the solve, just before the write).
    let mut reports = 0;
    let mut count = |_: &ProgressInfo<'_>| {
        reports += 1;
        Flow::Continue
    };
    let opts = FairOptions::default().region(FairRegion::Vertices(region.clone()));
    fair(&mut m.clone(), &opts, Progress::new(&mut count)).unwrap();
    assert!(reports >= 4);
    for stop in 1..=reports {
        let mut calls = 0;
        let mut cb = |_: &ProgressInfo<'_>| {
            calls += 1;
            if calls >= stop {
                Flow::Cancel
            } else {
                Flow::Continue
            }
        };
        let opts = FairOptions::default().region(FairRegion::Vertices(region.clone()));
        let r = fair(&mut m, &opts, Progress::new(&mut cb));
        assert!(matches!(r, Err(Error::Cancelled { .. })), "{stop}: {r:?}");
        assert_eq!(snapshot(&m), before);
    }
    let empty = m.add_vertex_attr::<bool>("empty").unwrap();
    let boundary: Vec<_> = m
        .vertices()
        .filter(|&v| m.vertex(v).unwrap().is_boundary())
        .collect();
    for opts in [
        FairOptions::default().order(0),
        FairOptions::default().order(4),
        FairOptions::default().region(FairRegion::Mask(empty)),
        FairOptions::default().region(FairRegion::Vertices(boundary)),
        FairOptions::default().region(FairRegion::Vertices(Vec::new())),
    ] {
        let r = fair(&mut m, &opts, Progress::none());
        assert!(
            matches!(r, Err(Error::Unsuitable { .. })),
            "{opts:?}: {r:?}"
        );
        assert_eq!(snapshot(&m), before);
    }
    // A stale key.
    let mut other = shapes::grid(30, 30, GridFaces::Quads);
    let far = other.vertices().last().unwrap();
    let r = fair(
        &mut m,
        &FairOptions::default().region(FairRegion::Vertices(vec![far])),
        Progress::none(),
    );
    assert!(matches!(r, Err(Error::StaleKey(_))), "{r:?}");
    // A closed mesh with everything free has nothing to hold it.
    let mut sphere = shapes::icosphere(2);
    let s0 = snapshot(&sphere);
    for order in 1..=3 {
        let opts = FairOptions::default().order(order);
        let r = fair(&mut sphere, &opts, Progress::none());
        assert!(
            matches!(r, Err(Error::Unsuitable { .. })),
            "k={order}: {r:?}"
        );
        assert_eq!(snapshot(&sphere), s0);
    }
    // No positions.
    other = Mesh::from_faces(3, &[[0u32, 1, 2]]).unwrap();
    assert!(matches!(
        fair(&mut other, &FairOptions::default(), Progress::none()),
        Err(Error::NoPositions)
    ));
}

#[test]
fn degenerate_triangles_give_no_nan() {
    // A fan around vertex 0 with a collapsed triangle and a needle, inside
    // an outer ring so that vertex 0 and its ring can be solved for.
    let mut mesh = shapes::grid(6, 6, GridFaces::Triangles);
    let keys: Vec<_> = mesh.vertices().collect();
    // Collapse two neighbouring interior vertices onto each other and make
    // a third collinear with its neighbours.
    let p = mesh.position(keys[2 * 7 + 2]).unwrap();
    mesh.set_position(keys[2 * 7 + 3], p).unwrap();
    let q = mesh.position(keys[3 * 7 + 3]).unwrap();
    mesh.set_position(keys[3 * 7 + 4], [q[0] + 0.5, q[1], 0.0])
        .unwrap();
    for weights in WEIGHTS {
        for order in 1..=3 {
            let mut m = mesh.clone();
            let opts = FairOptions::default().order(order).weights(weights);
            match fair(&mut m, &opts, Progress::none()) {
                Ok(_) | Err(Error::Unsuitable { .. }) => {}
                Err(e) => panic!("{weights:?} k={order}: {e}"),
            }
            assert!(m
                .position_slots()
                .unwrap()
                .iter()
                .flatten()
                .all(|c| c.is_finite()));
            m.validate().unwrap();
        }
    }
}
