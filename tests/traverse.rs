//! Traversals: walk orders, components, shortest paths, refused input.

use std::collections::{HashMap, HashSet};

use meshloom::shapes::{self, GridFaces};
use meshloom::traverse::{components, shortest_path, Bfs, Dfs};
use meshloom::{Error, FaceKey, Mesh, Polygons, Refusal, VertexKey};

/// Several shapes side by side in one buffer, like a model of many parts.
fn union(parts: &[Polygons]) -> Polygons {
    let mut out = Polygons {
        offsets: vec![0],
        ..Polygons::default()
    };
    for p in parts {
        let base = out.positions.len() as u32;
        out.positions.extend_from_slice(&p.positions);
        for f in p.faces() {
            out.indices.extend(f.iter().map(|&i| i + base));
            out.offsets.push(out.indices.len() as u32);
        }
    }
    out
}

/// (i, j) of a grid vertex, from its position.
fn cell(mesh: &Mesh, v: VertexKey) -> (i64, i64) {
    let p = mesh.position(v).unwrap();
    (p[0] as i64, p[1] as i64)
}

#[test]
fn components_of_a_multi_piece_mesh() {
    let parts = [
        shapes::icosphere_polygons(1),
        shapes::cube_polygons(),
        shapes::grid_polygons(3, 2, GridFaces::Triangles),
        shapes::torus_polygons(5, 3, 1.0, 0.2),
        shapes::disk_polygons(7),
        shapes::tetrahedron_polygons(),
    ];
    let mesh = Mesh::from_buffers(&union(&parts)).unwrap();
    let c = components(&mesh);
    assert_eq!(c.count(), parts.len());
    let sizes: Vec<usize> = parts.iter().map(|p| p.positions.len()).collect();
    assert_eq!(c.vertex_counts(), &sizes[..]);
    assert_eq!(mesh.components(), c);
    for (i, &n) in sizes.iter().enumerate() {
        assert_eq!(c.vertices(i).count(), n);
        assert!(c.vertices(i).all(|v| c.of_vertex(v) == Some(i)));
    }
    // Every face and hole lies in the component of each of its corners.
    for f in mesh.faces_and_holes() {
        let id = c.of_face(f).unwrap();
        assert!(mesh
            .face(f)
            .unwrap()
            .vertices()
            .all(|v| c.of_vertex(v) == Some(id)));
    }
    // Walks stay inside one component.
    for v in mesh.vertices().step_by(7) {
        let reached: Vec<_> = mesh.bfs_vertices(v).unwrap().collect();
        assert_eq!(reached.len(), sizes[c.of_vertex(v).unwrap()]);
    }
    // A key from another mesh is not in this snapshot.
    let far = shapes::icosphere(3).vertices().last().unwrap();
    assert_eq!(c.of_vertex(far), None);
    assert_eq!(components(&Mesh::new()).count(), 0);
}

#[test]
fn a_bowtie_is_one_component() {
    let mesh = Mesh::from_faces(5, &[[0u32, 1, 2], [0, 3, 4]]).unwrap();
    assert_eq!(components(&mesh).count(), 1);
    // Faces meet only at a vertex: a face walk does not cross it.
    let f = mesh.faces().next().unwrap();
    assert_eq!(mesh.bfs_faces(f).unwrap().count(), 1);
}

#[test]
fn unit_cost_paths_on_a_quad_grid_are_manhattan() {
    let mesh = shapes::grid(6, 4, GridFaces::Quads);
    let vs: Vec<_> = mesh.vertices().collect();
    for &a in vs.iter().step_by(5) {
        for &b in &vs {
            let path = shortest_path(&mesh, a, b, |_| 1.0).unwrap().unwrap();
            let ((ai, aj), (bi, bj)) = (cell(&mesh, a), cell(&mesh, b));
            let manhattan = (ai - bi).abs() + (aj - bj).abs();
            assert_eq!(path.cost, manhattan as f64);
            check_path(&mesh, &path, a, b);
        }
    }
}

#[test]
fn unit_cost_paths_on_a_triangle_grid_use_diagonals() {
    // Diagonals run from (i, j) to (i + 1, j + 1).
    let mesh = shapes::grid(5, 5, GridFaces::Triangles);
    let vs: Vec<_> = mesh.vertices().collect();
    for &a in vs.iter().step_by(4) {
        for &b in &vs {
            let path = mesh.shortest_path(a, b, |_| 1.0).unwrap().unwrap();
            let ((ai, aj), (bi, bj)) = (cell(&mesh, a), cell(&mesh, b));
            let (di, dj) = (bi - ai, bj - aj);
            let expected = if di.signum() * dj.signum() >= 0 {
                di.abs().max(dj.abs())
            } else {
                di.abs() + dj.abs()
            };
            assert_eq!(
                path.cost,
                expected as f64,
                "{:?} -> {:?}",
                (ai, aj),
                (bi, bj)
            );
            check_path(&mesh, &path, a, b);
        }
    }
}

fn check_path(mesh: &Mesh, path: &meshloom::traverse::Path, a: VertexKey, b: VertexKey) {
    assert_eq!(path.vertices.first(), Some(&a));
    assert_eq!(path.vertices.last(), Some(&b));
    assert_eq!(path.halfedges.len() + 1, path.vertices.len());
    for (k, &h) in path.halfedges.iter().enumerate() {
        let h = mesh.halfedge(h).unwrap();
        assert_eq!(h.origin().key(), path.vertices[k]);
        assert_eq!(h.dest().key(), path.vertices[k + 1]);
    }
}

#[test]
fn directed_costs_and_walls() {
    let mesh = shapes::grid(4, 1, GridFaces::Quads);
    let v: Vec<_> = mesh.vertices().collect();
    // Walking in +x is free, against it costs 10.
    let dx = |h| {
        let h = mesh.halfedge(h).unwrap();
        let (a, b) = (h.origin().position().unwrap(), h.dest().position().unwrap());
        if b[0] > a[0] {
            0.0
        } else if b[0] < a[0] {
            10.0
        } else {
            1.0
        }
    };
    assert_eq!(
        mesh.shortest_path(v[0], v[4], dx).unwrap().unwrap().cost,
        0.0
    );
    assert_eq!(
        mesh.shortest_path(v[4], v[0], dx).unwrap().unwrap().cost,
        40.0
    );
    // Infinite costs on every half-edge leaving the start: unreachable.
    let start = v[0];
    let walled = |h| {
        if mesh.halfedge(h).unwrap().origin().key() == start {
            f64::INFINITY
        } else {
            1.0
        }
    };
    assert_eq!(mesh.shortest_path(start, v[9], walled).unwrap(), None);
    // Start = end.
    let p = mesh.shortest_path(v[3], v[3], |_| 1.0).unwrap().unwrap();
    assert_eq!(
        (p.vertices, p.halfedges.len(), p.cost),
        (vec![v[3]], 0, 0.0)
    );
}

#[test]
fn cost_calls_are_lazy_and_at_most_once_per_halfedge() {
    let mesh = shapes::icosphere(2);
    let v: Vec<_> = mesh.vertices().collect();
    let mut calls = HashMap::new();
    let p = mesh
        .shortest_path(v[0], v[100], |h| {
            *calls.entry(h).or_insert(0) += 1;
            1.0
        })
        .unwrap()
        .unwrap();
    assert!(calls.values().all(|&n| n == 1));
    assert!(calls.len() <= mesh.halfedge_count());
    assert!(p.cost >= 1.0);
}

#[test]
fn paths_between_components_do_not_exist() {
    let two = union(&[shapes::cube_polygons(), shapes::tetrahedron_polygons()]);
    let mesh = Mesh::from_buffers(&two).unwrap();
    let v: Vec<_> = mesh.vertices().collect();
    assert_eq!(mesh.shortest_path(v[0], v[9], |_| 1.0).unwrap(), None);
}

#[test]
fn bad_costs_and_stale_keys_are_errors() {
    let mesh = shapes::cube();
    let v: Vec<_> = mesh.vertices().collect();
    for bad in [-1.0, f64::NAN, -f64::INFINITY] {
        let e = mesh.shortest_path(v[0], v[7], |_| bad).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Refused {
                    op: "shortest_path",
                    reason: Refusal::Parameter(_),
                    ..
                }
            ),
            "{e:?}"
        );
    }
    let far = shapes::icosphere(1).vertices().last().unwrap();
    assert!(matches!(
        mesh.shortest_path(v[0], far, |_| 1.0),
        Err(Error::StaleKey(_))
    ));
    assert!(matches!(Bfs::new(&mesh, far), Err(Error::StaleKey(_))));
    assert!(matches!(mesh.dfs_vertices(far), Err(Error::StaleKey(_))));
    let far_face: FaceKey = shapes::icosphere(1).faces().last().unwrap();
    assert!(matches!(mesh.bfs_faces(far_face), Err(Error::StaleKey(_))));
    let disk = shapes::disk(5);
    let hole = disk.holes().next().unwrap();
    assert!(matches!(
        Dfs::new(&disk, hole),
        Err(Error::Refused {
            reason: Refusal::Hole,
            ..
        })
    ));
}

#[test]
fn bfs_visits_vertices_in_order_of_distance() {
    let mesh = shapes::grid(7, 5, GridFaces::Quads);
    for start in mesh.vertices().step_by(6) {
        let mut bfs = Bfs::new(&mesh, start).unwrap();
        let s = cell(&mesh, start);
        let mut last = 0;
        let mut seen = HashSet::new();
        while let Some((v, depth)) = bfs.next_with_depth(&mesh) {
            let c = cell(&mesh, v);
            assert_eq!(depth as i64, (c.0 - s.0).abs() + (c.1 - s.1).abs());
            assert!(depth >= last, "BFS depth went down");
            last = depth;
            assert!(seen.insert(v));
        }
        assert_eq!(seen.len(), mesh.vertex_count());
    }
}

#[test]
fn bfs_over_faces_stops_at_holes_and_orders_by_distance() {
    let mesh = shapes::grid(5, 4, GridFaces::Quads);
    let centre = |f: FaceKey| {
        let vs: Vec<_> = mesh.face(f).unwrap().vertices().collect();
        let (i, j) = vs.iter().map(|&v| cell(&mesh, v)).min().unwrap();
        (i, j)
    };
    let start = mesh.faces().nth(7).unwrap();
    let s = centre(start);
    let mut bfs = Bfs::new(&mesh, start).unwrap();
    let mut n = 0;
    while let Some((f, depth)) = bfs.next_with_depth(&mesh) {
        let c = centre(f);
        assert_eq!(depth as i64, (c.0 - s.0).abs() + (c.1 - s.1).abs());
        assert!(!mesh.face(f).unwrap().is_hole());
        n += 1;
    }
    assert_eq!(n, 20);
}

#[test]
fn dfs_visits_everything_once_each_step_next_to_the_walk() {
    let meshes = [
        shapes::icosphere(2),
        shapes::uv_sphere(7, 5),
        shapes::torus(6, 4, 1.0, 0.3).unwrap(),
        shapes::grid(4, 4, GridFaces::Triangles),
    ];
    for mesh in &meshes {
        let start = mesh.vertices().nth(3).unwrap();
        let order: Vec<_> = Dfs::new(mesh, start).unwrap().iter(mesh).collect();
        assert_eq!(order.len(), mesh.vertex_count());
        assert_eq!(order[0], start);
        let mut seen = HashSet::new();
        for &v in &order {
            if !seen.is_empty() {
                // Preorder: each vertex hangs off one visited before it.
                assert!(mesh
                    .vertex(v)
                    .unwrap()
                    .neighbors()
                    .any(|w| seen.contains(&w)));
            }
            assert!(seen.insert(v));
        }
        // Depth first: the second vertex is the first neighbour of the start.
        let first = mesh.vertex(start).unwrap().neighbors().next().unwrap();
        assert_eq!(order[1], first);
        let f = mesh.faces().next().unwrap();
        let faces: HashSet<_> = mesh.dfs_faces(f).unwrap().collect();
        assert_eq!(faces.len(), mesh.face_count());
        assert_eq!(mesh.bfs_faces(f).unwrap().count(), mesh.face_count());
    }
}

#[test]
fn keys_by_slot_match_the_iterators() {
    let mut m = shapes::grid(3, 3, GridFaces::Triangles);
    // Free some slots: a removed vertex takes its edges with it.
    let inner = m
        .vertices()
        .find(|&v| !m.vertex(v).unwrap().is_boundary())
        .unwrap();
    m.remove_vertex(inner).unwrap();
    let [nv, _, ne, nf] = m.slot_counts();
    // A few indices past the end answer None too.
    let vs: Vec<_> = (0..nv + 3).filter_map(|i| m.vertex_at(i)).collect();
    let es: Vec<_> = (0..ne + 3).filter_map(|i| m.edge_at(i)).collect();
    let fs: Vec<_> = (0..nf + 3).filter_map(|i| m.face_at(i)).collect();
    assert_eq!(vs, m.vertices().collect::<Vec<_>>());
    assert_eq!(es, m.edges().collect::<Vec<_>>());
    assert_eq!(fs, m.faces().collect::<Vec<_>>());
    assert!(vs.len() < nv && es.len() < ne, "removal left vacant slots");
    assert!(m.holes().all(|h| m.face_at(h.index()).is_none()));
    assert_eq!(m.edge_at(usize::MAX), None);
    assert_eq!(m.vertex_at(1 << 40), None);
}
