//! Snapping and picking against brute force: edges within a radius, the
//! nearest edge, and vertex and edge picks in cones, through surfaces and
//! not.

mod common;

use common::query::{bbox, fans, meshes, Rng};
use meshloom::query::{
    point_in_cone, segment_in_cone, triangle_hit, Cone, FaceTree, Occlusion, QueryError, Ray,
};
use meshloom::{EdgeKey, Mesh, VertexKey};

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    dot(sub(a, b), sub(a, b)).sqrt()
}

/// The edges with a face on a side, with their end positions.
fn face_edges(mesh: &Mesh) -> Vec<(EdgeKey, [f64; 3], [f64; 3])> {
    mesh.edges()
        .filter_map(|e| {
            let view = mesh.edge(e).unwrap();
            if view.faces().iter().all(Option::is_none) {
                return None;
            }
            let [u, v] = view.vertices();
            Some((e, mesh.position(u).unwrap(), mesh.position(v).unwrap()))
        })
        .collect()
}

/// The vertices with a face around them.
fn face_vertices(mesh: &Mesh) -> Vec<(VertexKey, [f64; 3])> {
    let mut vs: Vec<VertexKey> = mesh
        .faces()
        .flat_map(|f| mesh.face(f).unwrap().vertices().collect::<Vec<_>>())
        .collect();
    vs.sort_unstable();
    vs.dedup();
    vs.into_iter()
        .map(|v| (v, mesh.position(v).unwrap()))
        .collect()
}

fn segment_distance(q: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(b, a);
    let len2 = dot(d, d);
    let s = if len2 > 0.0 {
        (dot(sub(q, a), d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    dist(q, [a[0] + s * d[0], a[1] + s * d[1], a[2] + s * d[2]])
}

#[test]
fn edges_within_and_the_nearest_edge_equal_brute_force() {
    let mut rng = Rng(0x5eed_0001);
    for (name, mesh) in meshes() {
        let tree = FaceTree::build(&mesh).unwrap();
        let edges = face_edges(&mesh);
        let (lo, hi) = bbox(&mesh);
        let diag = dist(lo, hi);
        let pad = [0.2 * diag; 3];
        for i in 0..60 {
            let q = rng.in_box(
                sub(lo, pad),
                [hi[0] + pad[0], hi[1] + pad[1], hi[2] + pad[2]],
            );
            let r = 0.3 * diag * rng.next();
            let mut want: Vec<EdgeKey> = edges
                .iter()
                .filter(|(_, a, b)| segment_distance(q, *a, *b) <= r)
                .map(|e| e.0)
                .collect();
            want.sort_unstable();
            assert_eq!(
                tree.edges_within(&mesh, q, r).unwrap(),
                want,
                "{name}, point {i}"
            );
            let best = edges
                .iter()
                .map(|(e, a, b)| (segment_distance(q, *a, *b), *e))
                .min_by(|x, y| x.0.total_cmp(&y.0))
                .unwrap();
            let got = tree.nearest_edge(&mesh, q).unwrap().unwrap();
            assert!(
                (got.distance - best.0).abs() <= 1e-12 * best.0.max(1e-300),
                "{name}, point {i}: {} vs {}",
                got.distance,
                best.0
            );
            assert!((dist(q, got.point) - got.distance).abs() <= 1e-12 * diag);
        }
    }
}

/// A random cone from outside the mesh's box towards a point in it:
/// perspective, or orthographic every third time.
fn random_cone(rng: &mut Rng, lo: [f64; 3], hi: [f64; 3], i: usize) -> Cone {
    let diag = dist(lo, hi);
    let centre = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    let dir = [0, 1, 2].map(|_| rng.next() - 0.5);
    let n = dot(dir, dir).sqrt();
    let origin = [0, 1, 2].map(|k| centre[k] + 1.5 * diag * dir[k] / n);
    let target = rng.in_box(lo, hi);
    // Not unit length, so `t` is checked in the direction's units.
    let ray = Ray::new(origin, [0, 1, 2].map(|k| 0.5 * (target[k] - origin[k])));
    if i % 3 == 2 {
        Cone::orthographic(ray, 0.1 * diag * rng.next())
    } else {
        Cone::perspective(ray, 0.01 + 0.1 * rng.next())
    }
}

/// Whether a fan triangle meets the line of sight to `x` (depth `t`)
/// before `x` (brute force).
fn hidden(tris: &[[[f64; 3]; 3]], cone: &Cone, x: [f64; 3]) -> bool {
    let d = cone.ray.direction;
    let n = dot(d, d).sqrt();
    let u = d.map(|c| c / n);
    let eye = if cone.spread == 0.0 {
        let depth = dot(sub(x, cone.ray.origin), u);
        [0, 1, 2].map(|k| x[k] - depth * u[k])
    } else {
        assert_eq!(cone.radius, 0.0);
        cone.ray.origin
    };
    let sight = Ray::new(eye, sub(x, eye));
    tris.iter()
        .any(|p| triangle_hit(&sight, p).is_some_and(|(t, _, _)| t < 1.0 - 1e-6))
}

/// The brute-force pick: of the candidates `(offset, t, key, point)`, the
/// first by offset then depth within the cone, not hidden if asked.
fn brute_pick<K: Copy>(
    mut found: Vec<(f64, f64, K, [f64; 3])>,
    tris: &[[[f64; 3]; 3]],
    cone: &Cone,
    occlusion: Occlusion,
) -> Option<(f64, f64, K)> {
    found.retain(|c| c.0 <= 1.0);
    found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    found
        .into_iter()
        .find(|c| occlusion == Occlusion::XRay || !hidden(tris, cone, c.3))
        .map(|c| (c.0, c.1, c.2))
}

/// The tree's pick and the brute force's agree: the same element, or
/// (a tie) the same offset and depth.
fn same_pick<K: PartialEq + std::fmt::Debug>(
    got: Option<(f64, f64, K)>,
    want: Option<(f64, f64, K)>,
    tol: f64,
    what: &str,
) {
    match (got, want) {
        (None, None) => {}
        (Some(g), Some(w)) => assert!(
            g.2 == w.2
                || ((g.0 - w.0).abs() <= tol && (g.1 - w.1).abs() <= tol * g.1.abs().max(1.0)),
            "{what}: got {g:?}, want {w:?}"
        ),
        (g, w) => panic!("{what}: got {g:?}, want {w:?}"),
    }
}

#[test]
fn vertex_and_edge_picks_equal_brute_force_through_surfaces_and_not() {
    let mut rng = Rng(0x5eed_0002);
    let mut hidden_picks = 0;
    for (name, mesh) in meshes() {
        let tree = FaceTree::build(&mesh).unwrap();
        let tris: Vec<[[f64; 3]; 3]> = fans(&mesh).into_iter().map(|f| f.1).collect();
        let vertices = face_vertices(&mesh);
        let edges = face_edges(&mesh);
        let (lo, hi) = bbox(&mesh);
        let mut picked = 0;
        for i in 0..40 {
            let cone = random_cone(&mut rng, lo, hi, i);
            let xray = tree.pick_vertex(&mesh, cone, Occlusion::XRay).unwrap();
            let visible = tree.pick_vertex(&mesh, cone, Occlusion::Visible).unwrap();
            hidden_picks += usize::from(xray.map(|p| p.key) != visible.map(|p| p.key));
            for occlusion in [Occlusion::XRay, Occlusion::Visible] {
                let what = format!("{name}, cone {i}, {occlusion:?}");
                let found = vertices
                    .iter()
                    .filter_map(|&(v, p)| point_in_cone(&cone, p).map(|(o, t)| (o, t, v, p)))
                    .collect();
                let want = brute_pick(found, &tris, &cone, occlusion);
                let got = tree.pick_vertex(&mesh, cone, occlusion).unwrap();
                if let Some(g) = got {
                    assert_eq!(mesh.position(g.key).unwrap(), g.point);
                    picked += 1;
                }
                same_pick(got.map(|g| (g.offset, g.t, g.key)), want, 1e-12, &what);
                let found = edges
                    .iter()
                    .filter_map(|&(e, a, b)| {
                        segment_in_cone(&cone, a, b).map(|(x, o, t)| (o, t, e, x))
                    })
                    .collect();
                let want = brute_pick(found, &tris, &cone, occlusion);
                let got = tree.pick_edge(&mesh, cone, occlusion).unwrap();
                same_pick(got.map(|g| (g.offset, g.t, g.key)), want, 1e-9, &what);
            }
        }
        assert!(
            picked >= 5,
            "{name}: only {picked} vertex picks: the cones miss"
        );
    }
    // The closed meshes hide some nearest vertices: occlusion was tried.
    assert!(
        hidden_picks > 20,
        "only {hidden_picks} picks differ through surfaces"
    );
}

#[test]
fn the_point_of_least_offset_on_a_segment_beats_every_sample() {
    let mut rng = Rng(0x5eed_0003);
    for i in 0..200 {
        let cone = random_cone(&mut rng, [-1.0; 3], [1.0; 3], i);
        let (a, b) = (
            rng.in_box([-1.0; 3], [1.0; 3]),
            rng.in_box([-1.0; 3], [1.0; 3]),
        );
        let sampled = (0..=2000)
            .filter_map(|k| {
                let s = k as f64 / 2000.0;
                point_in_cone(&cone, [0, 1, 2].map(|j| a[j] + s * (b[j] - a[j]))).map(|x| x.0)
            })
            .fold(f64::INFINITY, f64::min);
        match segment_in_cone(&cone, a, b) {
            Some((x, o, t)) => {
                assert!(o <= sampled + 1e-9, "segment {i}: {o} > sampled {sampled}");
                let (ox, tx) = point_in_cone(&cone, x).unwrap();
                assert!((ox - o).abs() <= 1e-12 && (tx - t).abs() <= 1e-12 * t.max(1.0));
            }
            None => assert!(
                sampled.is_infinite(),
                "segment {i}: missed, sampled {sampled}"
            ),
        }
    }
}

#[test]
fn a_pick_refuses_a_bad_cone_and_a_stale_tree() {
    let mut mesh = meshloom::shapes::cube();
    let tree = FaceTree::build(&mesh).unwrap();
    let ray = Ray::new([0.5, 0.5, 3.0], [0.0, 0.0, -1.0]);
    for cone in [
        Cone::perspective(ray, f64::NAN),
        Cone::orthographic(ray, -1.0),
        Cone::orthographic(ray, f64::INFINITY),
        Cone::orthographic(ray, 0.0),
    ] {
        assert!(matches!(
            tree.pick_vertex(&mesh, cone, Occlusion::Visible),
            Err(QueryError::InvalidBound { .. })
        ));
    }
    let bad = Cone::perspective(Ray::new([0.0; 3], [0.0; 3]), 0.1);
    assert!(matches!(
        tree.pick_edge(&mesh, bad, Occlusion::XRay),
        Err(QueryError::ZeroDirection { .. })
    ));
    assert!(matches!(
        tree.nearest_edge(&mesh, [f64::NAN, 0.0, 0.0]),
        Err(QueryError::NonFinitePoint { .. })
    ));
    let v = mesh.vertices().next().unwrap();
    mesh.set_position(v, [0.1, 0.1, 0.1]).unwrap();
    let cone = Cone::perspective(ray, 0.1);
    assert!(matches!(
        tree.pick_vertex(&mesh, cone, Occlusion::Visible),
        Err(QueryError::StaleTree { .. })
    ));
    assert!(matches!(
        tree.edges_within(&mesh, [0.0; 3], 1.0),
        Err(QueryError::StaleTree { .. })
    ));
}
