//! Self-intersections and mesh–mesh intersecting pairs: constructed cases
//! with known answers, touching cases, clean meshes, and the tree's walk
//! against an all-pairs loop over the same exact triangle test.

mod common;

use common::query::{meshes, Rng};
use meshloom::query::{intersect_beyond_shared, triangles_meet, FaceTree, QueryError};
use meshloom::shapes::{self, GridFaces};
use meshloom::{FaceKey, Mesh, VertexKey};

type Tri = (FaceKey, [VertexKey; 3], [[f64; 3]; 3]);

/// Every face's fan triangles with their corners' vertices.
fn fan_tris(mesh: &Mesh) -> Vec<Tri> {
    let mut out = Vec::new();
    for f in mesh.faces() {
        let vs: Vec<VertexKey> = mesh.face(f).unwrap().vertices().collect();
        for i in 1..vs.len() - 1 {
            let v = [vs[0], vs[i], vs[i + 1]];
            out.push((f, v, v.map(|v| mesh.position(v).unwrap())));
        }
    }
    out
}

fn ordered(a: FaceKey, b: FaceKey) -> (FaceKey, FaceKey) {
    if a.index() < b.index() {
        (a, b)
    } else {
        (b, a)
    }
}

/// All pairs of fan triangles of distinct faces, no tree.
fn brute_self(mesh: &Mesh) -> Vec<(FaceKey, FaceKey)> {
    let t = fan_tris(mesh);
    let mut out = Vec::new();
    for i in 0..t.len() {
        for j in i + 1..t.len() {
            if t[i].0 != t[j].0 && intersect_beyond_shared(&t[i].2, &t[i].1, &t[j].2, &t[j].1) {
                out.push(ordered(t[i].0, t[j].0));
            }
        }
    }
    out.sort_by_key(|p| (p.0.index(), p.1.index()));
    out.dedup();
    out
}

fn brute_pairs(a: &Mesh, b: &Mesh) -> Vec<(FaceKey, FaceKey)> {
    let (ta, tb) = (fan_tris(a), fan_tris(b));
    let mut out = Vec::new();
    for s in &ta {
        for t in &tb {
            if triangles_meet(&s.2, &t.2) {
                out.push((s.0, t.0));
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

fn self_pairs(mesh: &Mesh) -> Vec<(FaceKey, FaceKey)> {
    FaceTree::build(mesh)
        .unwrap()
        .self_intersections(mesh)
        .unwrap()
}

fn face_indices(pairs: &[(FaceKey, FaceKey)]) -> Vec<(usize, usize)> {
    pairs.iter().map(|p| (p.0.index(), p.1.index())).collect()
}

/// A unit tetrahedron's corners moved by `d`, scaled by `s`.
fn tetra(d: [f64; 3], s: f64) -> Vec<[f64; 3]> {
    [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ]
    .iter()
    .map(|p| [0, 1, 2].map(|k| p[k] * s + d[k]))
    .collect()
}

const TET: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

/// Two tetrahedra in one mesh: the first unit one, the second `tetra(d, s)`.
fn two_tetrahedra(d: [f64; 3], s: f64) -> Mesh {
    let mut p = tetra([0.0; 3], 1.0);
    p.extend(tetra(d, s));
    let mut faces: Vec<[u32; 3]> = TET.to_vec();
    faces.extend(TET.iter().map(|f| f.map(|i| i + 4)));
    Mesh::from_polygons(&p, &faces).unwrap()
}

#[test]
fn two_crossing_tetrahedra() {
    let mesh = two_tetrahedra([0.2, 0.2, 0.2], 1.0);
    let got = self_pairs(&mesh);
    assert_eq!(got, brute_self(&mesh));
    assert!(got.len() >= 3, "{got:?}");
    // Only faces of different tetrahedra (faces 0–3 and 4–7).
    for (a, b) in face_indices(&got) {
        assert!(a < 4 && b >= 4, "{a} {b}");
    }
    // Apart, they do not intersect.
    assert!(self_pairs(&two_tetrahedra([2.0, 0.0, 0.0], 1.0)).is_empty());
    // One inside the other without touching: no face crosses a face.
    assert!(self_pairs(&two_tetrahedra([0.1, 0.1, 0.1], 0.2)).is_empty());
}

#[test]
fn a_cube_pushed_through_another() {
    let a = shapes::cube();
    let mut b = shapes::cube();
    for p in b.position_slots_mut().unwrap() {
        *p = [p[0] * 0.5 + 0.75, p[1] * 0.5 + 0.25, p[2] * 0.5 + 0.25];
    }
    let (ta, tb) = (FaceTree::build(&a).unwrap(), FaceTree::build(&b).unwrap());
    let got = ta.intersecting_pairs(&a, &tb, &b).unwrap();
    assert_eq!(got, brute_pairs(&a, &b));
    // The small cube pokes through the big one's +x face only: that face
    // against the small cube's four side faces around the x axis.
    assert_eq!(got.len(), 4, "{got:?}");
    let big_faces: std::collections::BTreeSet<FaceKey> = got.iter().map(|p| p.0).collect();
    assert_eq!(big_faces.len(), 1);
    // Far apart: none; the other way round: the same pairs, swapped.
    let back = tb.intersecting_pairs(&b, &ta, &a).unwrap();
    let mut swapped: Vec<_> = back.iter().map(|p| (p.1, p.0)).collect();
    swapped.sort();
    assert_eq!(swapped, got);
}

#[test]
fn coplanar_overlaps_count_and_coplanar_neighbours_do_not() {
    let tri = |p: Vec<[f64; 3]>, f: Vec<[u32; 3]>| Mesh::from_polygons(&p, &f).unwrap();
    // Two separate triangles in z = 0, overlapping.
    let m = tri(
        vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.5, 0.5, 0.0],
            [3.0, 0.5, 0.0],
            [0.5, 3.0, 0.0],
        ],
        vec![[0, 1, 2], [3, 4, 5]],
    );
    assert_eq!(face_indices(&self_pairs(&m)), vec![(0, 1)]);
    // Sharing an edge, on opposite sides: a flat neighbour, no pair.
    let flat = tri(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [2, 1, 3]],
    );
    assert!(self_pairs(&flat).is_empty());
    // Sharing an edge, the second folded flat onto the first (same side).
    let folded = tri(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.2, 0.2, 0.0],
        ],
        vec![[0, 1, 2], [2, 1, 3]],
    );
    assert_eq!(face_indices(&self_pairs(&folded)), vec![(0, 1)]);
    // The same fold one ulp out of the plane: they meet on the edge only.
    let z = f64::from_bits(1e-300f64.to_bits());
    let nearly = tri(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.2, 0.2, z],
        ],
        vec![[0, 1, 2], [2, 1, 3]],
    );
    assert!(self_pairs(&nearly).is_empty());
}

#[test]
fn touching_counts_only_without_a_shared_vertex() {
    let mesh = |p: Vec<[f64; 3]>, f: Vec<[u32; 3]>| Mesh::from_polygons(&p, &f).unwrap();
    // Sharing a vertex, in different planes: a touch at the shared vertex.
    let m = mesh(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 1.0],
            [0.0, -1.0, 1.0],
        ],
        vec![[0, 1, 2], [0, 3, 4]],
    );
    assert!(self_pairs(&m).is_empty());
    // Sharing a vertex in one plane: a bow tie (no pair) and an overlap.
    let bow = mesh(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 3, 4]],
    );
    assert!(self_pairs(&bow).is_empty());
    let over = mesh(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 3, 4]],
    );
    assert_eq!(face_indices(&self_pairs(&over)), vec![(0, 1)]);
    // Sharing a vertex, the second passing through the first.
    let through = mesh(
        vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [1.0, 1.0, -1.0],
            [0.5, 0.5, 1.0],
        ],
        vec![[0, 1, 2], [0, 3, 4]],
    );
    assert_eq!(face_indices(&self_pairs(&through)), vec![(0, 1)]);
    // Sharing an edge at a sharp dihedral angle: none.
    let sharp = mesh(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.1, 0.1, 1e-9],
        ],
        vec![[0, 1, 2], [2, 1, 3]],
    );
    assert!(self_pairs(&sharp).is_empty());
    // A vertex of another face resting on a face (no shared vertex): a
    // touch, which counts.
    let rest = mesh(
        vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.5, 0.5, 1.0],
            [1.5, 0.5, 1.0],
        ],
        vec![[0, 1, 2], [3, 4, 5]],
    );
    assert_eq!(face_indices(&self_pairs(&rest)), vec![(0, 1)]);
    // ... and one ulp above it, not.
    let above = mesh(
        vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.5, 0.5, f64::from_bits(1)],
            [0.5, 0.5, 1.0],
            [1.5, 0.5, 1.0],
        ],
        vec![[0, 1, 2], [3, 4, 5]],
    );
    assert!(self_pairs(&above).is_empty());
}

#[test]
fn a_grid_folded_flat_onto_itself() {
    let mut mesh = shapes::grid(6, 4, GridFaces::Triangles);
    assert!(self_pairs(&mesh).is_empty());
    // Fold the columns beyond x = 3 back over the others, flat.
    let vs: Vec<VertexKey> = mesh.vertices().collect();
    for v in vs {
        let p = mesh.position(v).unwrap();
        if p[0] > 3.0 {
            mesh.set_position(v, [6.0 - p[0], p[1], 0.0]).unwrap();
        }
    }
    let got = self_pairs(&mesh);
    assert_eq!(got, brute_self(&mesh));
    assert!(got.len() >= 24, "{}", got.len());
    // Lifted a little at the far edge instead: a wedge, no pair.
    let mut wedge = shapes::grid(6, 4, GridFaces::Quads);
    let vs: Vec<VertexKey> = wedge.vertices().collect();
    for v in vs {
        let p = wedge.position(v).unwrap();
        if p[0] > 3.0 {
            wedge
                .set_position(v, [6.0 - p[0], p[1], (p[0] - 3.0) * 0.01])
                .unwrap();
        }
    }
    assert!(self_pairs(&wedge).is_empty());
}

#[test]
fn clean_meshes_have_none() {
    for (name, mesh) in meshes() {
        // Its columns are moved onto their neighbours: distinct vertices
        // at one position touch, which counts.
        if name == "slivers" {
            assert!(!self_pairs(&mesh).is_empty());
            continue;
        }
        assert!(self_pairs(&mesh).is_empty(), "{name}");
    }
    let dir = std::path::Path::new("../shared/data/meshes/closed");
    for name in [
        "cgal_cube.off",
        "cgal_icosahedron.off",
        "cgal_sphere966.off",
    ] {
        let path = dir.join(name);
        if !path.exists() {
            continue;
        }
        let mesh = meshloom::io::read(&path).unwrap();
        assert!(self_pairs(&mesh).is_empty(), "{name}");
    }
}

#[test]
fn the_tree_walk_equals_all_pairs_on_perturbed_meshes() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut found = 0;
    let mut bases = vec![
        shapes::grid(5, 4, GridFaces::Triangles),
        shapes::grid(4, 4, GridFaces::Quads),
        shapes::icosphere(1),
        shapes::uv_sphere(8, 5),
    ];
    bases.push(two_tetrahedra([0.3, 0.1, 0.2], 0.8));
    for base in &bases {
        for round in 0..12 {
            let mut mesh = base.clone();
            let amount = [0.05, 0.3, 1.0][round % 3];
            for p in mesh.position_slots_mut().unwrap() {
                for x in p.iter_mut() {
                    *x += (rng.next() - 0.5) * amount;
                }
            }
            let got = self_pairs(&mesh);
            assert_eq!(got, brute_self(&mesh), "round {round}");
            found += got.len();
            let mut other = base.clone();
            for p in other.position_slots_mut().unwrap() {
                p[0] += (rng.next() - 0.5) * amount;
            }
            let (ta, tb) = (
                FaceTree::build(&mesh).unwrap(),
                FaceTree::build(&other).unwrap(),
            );
            assert_eq!(
                ta.intersecting_pairs(&mesh, &tb, &other).unwrap(),
                brute_pairs(&mesh, &other)
            );
        }
    }
    assert!(found > 50, "{found}");
}

#[test]
fn a_stale_tree_is_refused() {
    let mut mesh = two_tetrahedra([0.2, 0.2, 0.2], 1.0);
    let tree = FaceTree::build(&mesh).unwrap();
    let v = mesh.vertices().next().unwrap();
    mesh.set_position(v, [-0.1, 0.0, 0.0]).unwrap();
    assert!(matches!(
        tree.self_intersections(&mesh),
        Err(QueryError::StaleTree { .. })
    ));
    let other = shapes::cube();
    let to = FaceTree::build(&other).unwrap();
    assert!(matches!(
        to.intersecting_pairs(&other, &tree, &mesh),
        Err(QueryError::StaleTree { .. })
    ));
    assert!(matches!(
        to.intersecting_pairs(&mesh, &to, &other),
        Err(QueryError::StaleTree { .. })
    ));
}
