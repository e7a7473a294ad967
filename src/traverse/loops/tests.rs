use crate::shapes::{self, GridFaces};
use crate::{EdgeKey, Error, Mesh};

/// The edges of a chain meet end to end (a closed one also last to first)
/// and none repeats.
fn check_edges_chain(mesh: &Mesh, keys: &[EdgeKey], closed: bool) {
    let mut seen = keys.to_vec();
    seen.sort();
    seen.dedup();
    assert_eq!(seen.len(), keys.len(), "an edge repeats");
    let ends = |e: EdgeKey| mesh.edge(e).unwrap().vertices();
    let pairs = keys.windows(2).map(|w| (w[0], w[1]));
    let last = (closed && keys.len() > 1).then(|| (keys[keys.len() - 1], keys[0]));
    for (a, b) in pairs.chain(last) {
        let ([a0, a1], [b0, b1]) = (ends(a), ends(b));
        assert!(
            [a0, a1].iter().any(|v| *v == b0 || *v == b1),
            "{a:?} and {b:?} do not meet"
        );
    }
}

/// The direction of edge `e` as a unit vector.
fn direction(mesh: &Mesh, e: EdgeKey) -> [f64; 3] {
    let [a, b] = mesh.edge(e).unwrap().vertices();
    let (p, q) = (
        mesh.vertex(a).unwrap().position().unwrap(),
        mesh.vertex(b).unwrap().position().unwrap(),
    );
    let d: [f64; 3] = std::array::from_fn(|k| q[k] - p[k]);
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    d.map(|c| c / n)
}

fn parallel(a: [f64; 3], b: [f64; 3]) -> bool {
    (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).abs() > 1.0 - 1e-12
}

#[test]
fn on_a_quad_grid_loops_run_straight_from_side_to_side_and_rings_cross_it() {
    let (cols, rows) = (6, 4);
    let mesh = shapes::grid(cols, rows, GridFaces::Quads);
    for e in mesh.edges() {
        let run = mesh.edge_loop(e).unwrap();
        assert!(!run.closed);
        check_edges_chain(&mesh, &run.keys, false);
        let d = direction(&mesh, e);
        assert!(run.keys.iter().all(|&f| parallel(direction(&mesh, f), d)));
        // Side to side: as many edges as quads along that direction.
        let along_x = d[0].abs() > 0.5;
        assert_eq!(run.keys.len(), if along_x { cols } else { rows }, "{e:?}");
        let ring = mesh.edge_ring(e).unwrap();
        assert!(!ring.closed && ring.keys.contains(&e));
        assert!(ring.keys.iter().all(|&f| parallel(direction(&mesh, f), d)));
        assert_eq!(ring.keys.len(), if along_x { rows + 1 } else { cols + 1 });
        let faces = mesh.face_loop(e).unwrap();
        assert_eq!(faces.keys.len(), ring.keys.len() - 1);
        for (w, f) in ring.keys.windows(2).zip(&faces.keys) {
            let edges: Vec<EdgeKey> = mesh.face(*f).unwrap().edges().collect();
            assert!(edges.contains(&w[0]) && edges.contains(&w[1]));
        }
    }
}

#[test]
fn on_a_torus_every_loop_ring_and_face_loop_closes_and_they_partition_the_edges() {
    let (major, minor) = (9, 5);
    let mesh = shapes::torus(major, minor, 1.0, 0.3).unwrap();
    let mut loops_of = std::collections::HashMap::new();
    for e in mesh.edges() {
        let run = mesh.edge_loop(e).unwrap();
        assert!(run.closed && (run.keys.len() == major || run.keys.len() == minor));
        assert_eq!(run.keys[0], e);
        check_edges_chain(&mesh, &run.keys, true);
        let mut set = run.keys.clone();
        set.sort();
        // Every edge of a loop has that same loop.
        if let Some(other) = loops_of.insert(e, set.clone()) {
            assert_eq!(other, set);
        }
        for &f in &run.keys {
            loops_of.entry(f).or_insert_with(|| set.clone());
        }
        let ring = mesh.edge_ring(e).unwrap();
        let faces = mesh.face_loop(e).unwrap();
        assert!(ring.closed && faces.closed);
        assert_eq!(ring.keys.len() + run.keys.len(), major + minor);
        assert_eq!(faces.keys.len(), ring.keys.len());
    }
    let distinct: std::collections::HashSet<_> = loops_of.values().collect();
    assert_eq!(distinct.len(), major + minor);
}

#[test]
fn loops_stop_at_poles_and_rings_at_faces_that_are_not_quads() {
    // A cube's corners have degree 3: each loop is one edge; rings go
    // round the cube.
    let cube = shapes::cube();
    for e in cube.edges() {
        assert_eq!(cube.edge_loop(e).unwrap().keys, vec![e]);
        let ring = cube.edge_ring(e).unwrap();
        assert!(ring.closed && ring.keys.len() == 4);
        assert_eq!(cube.face_loop(e).unwrap().keys.len(), 4);
    }
    // A UV sphere: loops along a meridian stop at the poles' triangle fans;
    // rings stop at the triangles.
    let sphere = shapes::uv_sphere(8, 6);
    for e in sphere.edges() {
        let run = sphere.edge_loop(e).unwrap();
        check_edges_chain(&sphere, &run.keys, run.closed);
        assert!(run.closed == (run.keys.len() == 8), "{run:?}");
        let ring = sphere.edge_ring(e).unwrap();
        check_quads_between(&sphere, &ring.keys, ring.closed);
    }
    // Triangles: a ring is its edge alone, with no face loop.
    let tris = shapes::grid(3, 3, GridFaces::Triangles);
    for e in tris.edges() {
        assert_eq!(tris.edge_ring(e).unwrap().keys, vec![e]);
        assert!(tris.face_loop(e).unwrap().keys.is_empty());
    }
}

/// Consecutive ring edges are opposite sides of a quad.
fn check_quads_between(mesh: &Mesh, keys: &[EdgeKey], closed: bool) {
    let pairs = keys.windows(2).map(|w| (w[0], w[1]));
    let last = (closed && keys.len() > 1).then(|| (keys[keys.len() - 1], keys[0]));
    for (a, b) in pairs.chain(last) {
        let quad = mesh.faces().find(|&f| {
            let view = mesh.face(f).unwrap();
            let edges: Vec<EdgeKey> = view.edges().collect();
            edges.len() == 4
                && edges
                    .iter()
                    .position(|&x| x == a)
                    .is_some_and(|i| edges[(i + 2) % 4] == b)
        });
        assert!(quad.is_some(), "{a:?} and {b:?} are not opposite in a quad");
    }
}

#[test]
fn a_boundary_edge_loop_follows_the_boundary_from_corner_to_corner_and_round_a_hole() {
    let (cols, rows) = (5, 3);
    let mut mesh = shapes::grid(cols, rows, GridFaces::Quads);
    let boundary: Vec<EdgeKey> = mesh
        .edges()
        .filter(|&e| mesh.edge(e).unwrap().is_boundary())
        .collect();
    for &e in &boundary {
        let run = mesh.edge_loop(e).unwrap();
        assert!(run
            .keys
            .iter()
            .all(|&f| mesh.edge(f).unwrap().is_boundary()));
        let along_x = direction(&mesh, e)[0].abs() > 0.5;
        assert_eq!(run.keys.len(), if along_x { cols } else { rows });
    }
    // A hole in the middle of a larger grid: its rim's vertices have degree
    // 4, so the rim is walked as the boundary only through degree 3.
    let mut big = shapes::grid(5, 5, GridFaces::Quads);
    let centre = big
        .faces()
        .find(|&f| {
            big.face(f)
                .unwrap()
                .vertices()
                .all(|v| !big.vertex(v).unwrap().is_boundary())
        })
        .unwrap();
    let rim: Vec<EdgeKey> = big.face(centre).unwrap().edges().collect();
    big.remove_face(centre).unwrap();
    big.validate().unwrap();
    for &e in &rim {
        let run = big.edge_loop(e).unwrap();
        assert_eq!(
            run.keys,
            vec![e],
            "the rim's corners have degree 4: a pole of the boundary"
        );
    }
    // Stale keys are refused.
    let e = boundary[0];
    let f = mesh
        .edge(e)
        .unwrap()
        .faces()
        .into_iter()
        .flatten()
        .next()
        .unwrap();
    mesh.remove_face(f).unwrap();
    let gone = mesh.edges().all(|x| x != e);
    if gone {
        assert!(matches!(mesh.edge_loop(e), Err(Error::StaleKey { .. })));
        assert!(matches!(mesh.edge_ring(e), Err(Error::StaleKey { .. })));
        assert!(matches!(mesh.face_loop(e), Err(Error::StaleKey { .. })));
    }
}
