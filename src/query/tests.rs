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
        if n.count > 0 {
            for t in n.first..n.first + n.count {
                seen[t as usize] += 1;
                for p in tree.tris[t as usize] {
                    for ((x, lo), hi) in p.iter().zip(n.lo()).zip(n.hi()) {
                        assert!(*x >= lo && *x <= hi);
                    }
                }
            }
        } else {
            assert!(n.first as usize > i + 1);
            stack.push((i + 1, n.lo(), n.hi()));
            stack.push((n.first as usize, n.lo(), n.hi()));
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
    for (a, b) in built.dipoles.iter().zip(&refitted.dipoles) {
        assert_eq!((a.area, a.centre, a.radius), (b.area, b.centre, b.radius));
    }
}

#[test]
fn the_root_dipole_of_a_closed_mesh_has_no_area_and_holds_every_triangle() {
    let mesh = shapes::icosphere(2);
    let tree = FaceTree::build(&mesh).unwrap();
    let d = tree.dipoles[0];
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
