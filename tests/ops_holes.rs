//! remove_face and fill_hole.

mod common;
use common::*;
use meshloom::{shapes, Error, Mesh, Refusal};

#[test]
fn remove_interior_face_makes_a_hole() {
    let mut m = shapes::icosahedron();
    let f = m.faces().next().unwrap();
    let holes = checked(&mut m, |m| m.remove_face(f)).unwrap();
    assert_eq!(holes, vec![f]);
    assert!(m.face(f).unwrap().is_hole());
    assert_eq!(counts(&m), (12, 30, 19, 1));
    assert_eq!(m.euler_characteristic(), 1);
    // Filling it gives the face back.
    assert_eq!(checked(&mut m, |m| m.fill_hole(f)).unwrap(), f);
    assert!(m.is_closed());
    assert_eq!(m.euler_characteristic(), 2);
}

#[test]
fn remove_boundary_face_merges_holes_and_drops_dangling_edges() {
    let mut m = l_shape();
    let corner = m.faces().next().unwrap();
    let holes = checked(&mut m, |m| m.remove_face(corner)).unwrap();
    assert_eq!(holes.len(), 1);
    assert!(!m.contains_face(corner) || m.face(corner).unwrap().is_hole());
    // The corner quad had two boundary edges and one vertex only it used.
    assert_eq!(counts(&m), (7, 8, 2, 1));
}

#[test]
fn removing_the_middle_of_a_strip_splits_the_hole() {
    let mut m = Mesh::from_faces(8, &[[0u32, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6]]).unwrap();
    let mid = m.faces().nth(1).unwrap();
    let holes = checked(&mut m, |m| m.remove_face(mid)).unwrap();
    assert_eq!(holes.len(), 2);
    assert_eq!(counts(&m), (8, 8, 2, 2));
    for h in holes {
        assert_eq!(m.face(h).unwrap().degree(), 4);
    }
}

#[test]
fn removing_a_lone_triangle_removes_everything() {
    let mut m = bowtie();
    let f = m.faces().next().unwrap();
    let holes = checked(&mut m, |m| m.remove_face(f)).unwrap();
    assert!(holes.is_empty());
    assert_eq!(counts(&m), (3, 3, 1, 1));
    let g = m.faces().next().unwrap();
    assert!(checked(&mut m, |m| m.remove_face(g)).unwrap().is_empty());
    assert_eq!(counts(&m), (0, 0, 0, 0));
    assert!(m.is_empty());
}

#[test]
fn fill_refuses_faces_and_bowtie_holes() {
    let mut m = bowtie();
    let f = m.faces().next().unwrap();
    assert!(matches!(
        checked(&mut m, |m| m.fill_hole(f)),
        Err(Error::Refused {
            reason: Refusal::NotHole,
            ..
        })
    ));
    let hole = m.holes().next().unwrap();
    assert!(matches!(
        checked(&mut m, |m| m.fill_hole(hole)),
        Err(Error::Refused {
            reason: Refusal::NonManifold,
            ..
        })
    ));
    assert!(matches!(
        checked(&mut m, |m| m.remove_face(hole)),
        Err(Error::Refused {
            reason: Refusal::Hole,
            ..
        })
    ));
}

#[test]
fn fill_and_triangulate_a_real_hole() {
    let mut m = read_off(&mesh_path("boundary/cgal_mesh_with_border.off"));
    let hole = m.holes().next().unwrap();
    let n = m.face(hole).unwrap().degree();
    let f = checked(&mut m, |m| m.fill_hole(hole)).unwrap();
    let tris = checked(&mut m, |m| m.triangulate(f)).unwrap();
    assert_eq!(tris.len(), n - 2);
    assert!(m.is_closed());
    assert_eq!(m.euler_characteristic(), 2);
}
