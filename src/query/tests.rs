//! Unit tests of the tree's inner parts; the brute-force comparisons are in
//! tests/query.rs.

use super::*;
use crate::shapes;

#[test]
fn every_triangle_sits_in_one_leaf_inside_every_box_on_its_path() {
    let mesh = shapes::icosphere(3);
    let tree = FaceTree::build(&mesh).unwrap();
    let mut seen = vec![0u32; tree.tris.len()];
    // Walk from the root, carrying the parent's box.
    let mut stack = vec![(0usize, tree.nodes[0].lo(), tree.nodes[0].hi())];
    while let Some((i, plo, phi)) = stack.pop() {
        let n = tree.nodes[i];
        for k in 0..3 {
            assert!(
                n.lo()[k] >= plo[k] && n.hi()[k] <= phi[k],
                "node {i} outside its parent"
            );
        }
        if n.is_leaf() {
            for t in n.first..n.first + n.count {
                seen[t as usize] += 1;
                for p in tree.tris[t as usize] {
                    for ((x, lo), hi) in p.iter().zip(n.lo()).zip(n.hi()) {
                        assert!(*x >= lo && *x <= hi);
                    }
                }
            }
        } else {
            // A build lays the children side by side, after their parent.
            let (a, b) = n.children(i);
            assert!(a > i && b == a + 1);
            stack.push((a, n.lo(), n.hi()));
            stack.push((b, n.lo(), n.hi()));
        }
    }
    assert!(seen.iter().all(|&c| c == 1));
    assert_eq!(tree.triangle_count(), mesh.face_count());
}

#[test]
fn a_refit_of_an_unmoved_mesh_keeps_the_boxes_and_dipoles() {
    let mesh = shapes::torus(20, 10, 1.0, 0.3).unwrap();
    let built = FaceTree::build(&mesh).unwrap();
    let mut refitted = built.clone();
    refitted.refit(&mesh).unwrap();
    for (a, b) in built.nodes.iter().zip(&refitted.nodes) {
        assert_eq!(
            (a.lo, a.hi, a.first, a.count),
            (b.lo, b.hi, b.first, b.count)
        );
    }
    for (a, b) in built.far_field().iter().zip(refitted.far_field()) {
        assert_eq!((a.area, a.centre, a.radius), (b.area, b.centre, b.radius));
    }
}

#[test]
fn the_root_dipole_of_a_closed_mesh_has_no_area_and_holds_every_triangle() {
    let mesh = shapes::icosphere(2);
    let tree = FaceTree::build(&mesh).unwrap();
    let d = tree.far_field()[0];
    assert!(crate::vec3::norm(d.area) < 1e-12);
    for t in &tree.tris {
        for p in t {
            assert!(crate::vec3::dist2(*p, d.centre).sqrt() <= d.radius * (1.0 + 1e-12));
        }
    }
}

#[test]
fn an_empty_mesh_gives_an_empty_tree_that_answers_nothing() {
    let mesh = Mesh::new();
    let tree = FaceTree::build(&mesh).unwrap();
    let ray = Ray::new([0.0; 3], [1.0, 0.0, 0.0]);
    assert!(!tree.root_met(&ray));
    assert_eq!(tree.ray_cast(&mesh, ray).unwrap(), None);
    assert_eq!(tree.closest_point(&mesh, [0.0; 3], None).unwrap(), None);
    assert_eq!(
        tree.winding_number(&mesh, [0.0; 3], WindingMode::default())
            .unwrap(),
        0.0
    );
}

/// Every node reached from the root holds its triangles and children in
/// its box, and its far-field data is its triangles' (area and weight
/// summed afresh); every triangle reached is live and reached once; the
/// faces reached are the mesh's, each with its whole fan. Returns the
/// number of leaves reached.
fn check_structure(tree: &FaceTree, mesh: &Mesh) -> usize {
    use std::collections::BTreeMap;
    fn walk(
        tree: &FaceTree,
        i: usize,
        seen: &mut Vec<u32>,
        leaves: &mut usize,
    ) -> (crate::vec3::V3, f64) {
        let n = tree.nodes[i];
        let inside = |p: crate::vec3::V3| (0..3).all(|k| p[k] >= n.lo()[k] && p[k] <= n.hi()[k]);
        let (area, weight) = if n.is_leaf() {
            *leaves += 1;
            for t in n.first..n.first + n.count {
                seen[t as usize] += 1;
                assert!(tree.tris[t as usize].iter().all(|p| inside(*p)), "node {i}");
            }
            let range = n.first as usize..(n.first + n.count) as usize;
            let d = winding::leaf_dipole(&tree.tris[range]);
            (d.area, d.weight)
        } else {
            let (a, b) = n.children(i);
            assert!(a > i && b > i && a != b, "node {i}: children {a}, {b}");
            for c in [a, b] {
                assert!(
                    inside(tree.nodes[c].lo()) && inside(tree.nodes[c].hi()),
                    "node {i}"
                );
            }
            let (x, wx) = walk(tree, a, seen, leaves);
            let (y, wy) = walk(tree, b, seen, leaves);
            (crate::vec3::add(x, y), wx + wy)
        };
        let d = tree.far_field()[i];
        let scale = 1e-9 * weight.max(1e-300);
        assert!(
            (0..3).all(|k| (d.area[k] - area[k]).abs() <= scale),
            "node {i}: area"
        );
        assert!((d.weight - weight).abs() <= scale, "node {i}: weight");
        (area, weight)
    }
    let mut seen = vec![0u32; tree.tris.len()];
    let mut leaves = 0;
    if !tree.nodes.is_empty() {
        walk(tree, 0, &mut seen, &mut leaves);
    }
    assert!(seen.iter().all(|&c| c <= 1));
    let live: usize = seen.iter().map(|&c| c as usize).sum();
    assert_eq!(live, tree.triangle_count());
    let mut fans: BTreeMap<FaceKey, usize> = BTreeMap::new();
    for (t, _) in seen.iter().enumerate().filter(|s| *s.1 == 1) {
        *fans.entry(tree.meta[t].face).or_default() += 1;
    }
    let want: BTreeMap<FaceKey, usize> = mesh
        .faces()
        .map(|f| (f, mesh.face(f).unwrap().vertices().count() - 2))
        .collect();
    assert_eq!(fans, want);
    assert_eq!(tree.face_count(), mesh.face_count());
    check_wide(tree);
    leaves
}

/// The ray casts' wide copy reaches the binary tree's triangles, each
/// once, and every lane's box holds what the lane leads to.
fn check_wide(tree: &FaceTree) {
    use super::wide::WideNode;
    fn holds(n: &WideNode, l: usize, p: crate::vec3::V3) -> bool {
        (0..3).all(|k| p[k] >= f64::from(n.bounds[0][k][l]) && p[k] <= f64::from(n.bounds[1][k][l]))
    }
    let mut binary = Vec::new();
    tree.for_each_leaf(|_, r| binary.extend(r));
    let mut wide = Vec::new();
    let mut stack = Vec::new();
    if !tree.wide.is_empty() {
        stack.push(0usize);
    }
    while let Some(i) = stack.pop() {
        let n = &tree.wide[i];
        for l in 0..super::wide::LANES {
            let (c, count) = (n.child[l] as usize, n.count[l]);
            if count > 0 {
                wide.extend(c..c + count as usize);
                let tris = &tree.tris[c..c + count as usize];
                assert!(tris.iter().flatten().all(|p| holds(n, l, *p)), "wide {i}");
            } else if n.bounds[0][0][l] <= n.bounds[1][0][l] {
                assert!(c > i, "wide {i}: child {c}");
                let m = &tree.wide[c];
                for ml in
                    (0..super::wide::LANES).filter(|&ml| m.bounds[0][0][ml] <= m.bounds[1][0][ml])
                {
                    let lo = std::array::from_fn(|k| f64::from(m.bounds[0][k][ml]));
                    let hi = std::array::from_fn(|k| f64::from(m.bounds[1][k][ml]));
                    assert!(holds(n, l, lo) && holds(n, l, hi), "wide {i}");
                }
                stack.push(c);
            }
        }
    }
    binary.sort_unstable();
    wide.sort_unstable();
    assert_eq!(wide, binary);
}

#[test]
fn updates_in_place_keep_every_node_whole_through_splits_and_emptied_leaves() {
    let mut mesh = shapes::grid(40, 30, shapes::GridFaces::Triangles);
    mesh.history_mut().track_changes(true);
    let mut tree = FaceTree::build(&mesh).unwrap();
    check_structure(&tree, &mesh);
    let (mut splits, mut partial) = (0, 0);
    let mut faces: Vec<FaceKey> = mesh.faces().collect();
    for round in 0..30 {
        // Poke a run of neighbouring faces (their leaves overfill), remove
        // another run (leaves empty), move a few vertices.
        let at = (round * 37) % faces.len().max(1);
        let around = |k: usize, r: f64| {
            let v = mesh.face(faces[k % faces.len()]).unwrap().vertices().next();
            tree.faces_within(&mesh, mesh.position(v.unwrap()).unwrap(), r)
                .unwrap()
        };
        let (poke, remove) = (around(at, 1.8), around(at + 300, 1.5));
        for f in poke {
            let _ = mesh.poke_face(f);
        }
        for f in remove {
            let _ = mesh.remove_face(f);
        }
        for v in mesh.vertices().skip(round * 11).take(3).collect::<Vec<_>>() {
            let mut p = mesh.position(v).unwrap();
            p[2] += 0.05;
            mesh.set_position(v, p).unwrap();
        }
        let changes = mesh.history_mut().take_changes();
        let report = tree.update(&mesh, &changes).unwrap();
        splits += report.split_leaves;
        partial += usize::from(!report.full_rebuild);
        check_structure(&tree, &mesh);
        let fresh = FaceTree::build(&mesh).unwrap();
        assert_eq!(
            tree.self_intersections(&mesh).unwrap(),
            fresh.self_intersections(&mesh).unwrap()
        );
        faces = mesh.faces().collect();
    }
    assert!(
        partial >= 10 && splits > 0,
        "{partial} partial updates, {splits} splits"
    );
    // Remove every face: the tree empties, then fills again.
    for f in mesh.faces().collect::<Vec<_>>() {
        mesh.remove_face(f).unwrap();
    }
    let changes = mesh.history_mut().take_changes();
    tree.update(&mesh, &changes).unwrap();
    check_structure(&tree, &mesh);
    assert_eq!(tree.triangle_count(), 0);
}

#[test]
fn an_update_that_empties_a_leaf_under_the_root_keeps_the_rest() {
    // A grid and one triangle far away: the root's split puts the far
    // triangle in a leaf of its own, right under the root.
    let grid = shapes::grid(10, 10, shapes::GridFaces::Triangles);
    let mut p: Vec<[f64; 3]> = grid.vertices().map(|v| grid.position(v).unwrap()).collect();
    let mut tris: Vec<[u32; 3]> = grid
        .faces()
        .map(|f| {
            let vs: Vec<u32> = grid
                .face(f)
                .unwrap()
                .vertices()
                .map(|v| v.index() as u32)
                .collect();
            [vs[0], vs[1], vs[2]]
        })
        .collect();
    let n = p.len() as u32;
    p.extend([[1e4, 0.0, 0.0], [1e4 + 1.0, 0.0, 0.0], [1e4, 1.0, 0.0]]);
    tris.push([n, n + 1, n + 2]);
    for far_first in [true, false] {
        let mut mesh = Mesh::from_polygons(&p, &tris).unwrap();
        mesh.history_mut().track_changes(true);
        let mut tree = FaceTree::build(&mesh).unwrap();
        let root = tree.nodes[0];
        let (a, b) = root.children(0);
        let far = if tree.nodes[a].is_leaf() && tree.nodes[a].count == 1 {
            a
        } else {
            b
        };
        assert!(tree.nodes[far].is_leaf() && tree.nodes[far].count == 1);
        let f = tree.meta[tree.nodes[far].first as usize].face;
        if far_first {
            mesh.remove_face(f).unwrap();
        } else {
            // Also a face of the big side, so both kinds of change meet.
            let other = mesh.faces().find(|&g| g != f).unwrap();
            mesh.remove_face(other).unwrap();
            mesh.remove_face(f).unwrap();
        }
        let changes = mesh.history_mut().take_changes();
        let report = tree.update(&mesh, &changes).unwrap();
        assert!(!report.full_rebuild);
        check_structure(&tree, &mesh);
        assert!(
            tree.far_field()[0].radius < 20.0,
            "the root's box still holds the far triangle"
        );
        // A refit reads only the nodes the update left reachable.
        tree.refit(&mesh).unwrap();
        check_structure(&tree, &mesh);
    }
}

#[test]
fn the_far_field_is_made_on_first_use_and_kept_by_refits() {
    let mut mesh = shapes::icosphere(2);
    let mut tree = FaceTree::build(&mesh).unwrap();
    let bare = tree.heap_bytes();
    assert!(tree.dipoles.get().is_none());
    tree.refit(&mesh).unwrap();
    assert!(tree.dipoles.get().is_none(), "a refit does not make it");
    tree.contains(&mesh, [0.0; 3]).unwrap();
    assert!(tree.heap_bytes() > bare);
    for p in mesh.position_slots_mut().unwrap() {
        p[2] *= 2.0;
    }
    let before = tree.dipoles.get().unwrap()[0].radius;
    tree.refit(&mesh).unwrap();
    let (kept, made) = (tree.dipoles.get().unwrap(), tree.far_field_afresh());
    assert!(kept[0].radius > before, "the refit moved it");
    for (a, b) in kept.iter().zip(&made) {
        assert_eq!((a.area, a.centre, a.radius), (b.area, b.centre, b.radius));
    }
}

#[test]
fn bracket_gives_the_neighbouring_f32_values() {
    use super::ray::bracket;
    let mut seed = 12345u64;
    for _ in 0..2000 {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let x = (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
        for v in [x, x * 1e-30, x * 1e30, x * 1e6 + 0.5] {
            let (lo, hi) = bracket(v);
            assert!(f64::from(lo) <= v && v <= f64::from(hi), "{v}");
            if f64::from(lo) == v {
                assert_eq!(lo, hi);
            } else {
                assert!(
                    lo < hi
                        && f64::from(hi) - f64::from(lo)
                            <= f64::from(hi).abs().max(f64::from(lo).abs()) * 2.4e-7,
                    "{v}"
                );
            }
        }
    }
    assert_eq!(bracket(0.5), (0.5, 0.5));
    assert_eq!(bracket(1e300).1, f32::INFINITY);
    assert_eq!(bracket(-1e300).0, f32::NEG_INFINITY);
    let (lo, hi) = bracket(1e-50);
    assert!(lo == 0.0 && hi > 0.0);
}
