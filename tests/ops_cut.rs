//! cut_path: slits and closed seams; split_components after a seam.

mod common;
use common::*;
use meshloom::{shapes, Error, Refusal};

fn refusal<T: std::fmt::Debug>(r: meshloom::Result<T>) -> Refusal {
    match r {
        Err(Error::Refused { reason, .. }) => reason,
        other => panic!("expected a refusal, got {other:?}"),
    }
}

#[test]
fn slit_inside_a_grid() {
    let mut m = quad_grid(4);
    let t = add_totals(&mut m);
    let v: Vec<_> = m.vertices().collect();
    // Row 2, columns 1..=3: interior vertices 11, 12, 13.
    let path = [v[11], v[12], v[13]];
    let chi = m.euler_characteristic();
    let holes = checked(&mut m, |m| m.cut_path(&path)).unwrap();
    assert_eq!(holes.len(), 1);
    assert_eq!(m.face(holes[0]).unwrap().degree(), 4);
    assert_eq!(counts(&m), (26, 42, 16, 2));
    assert_eq!(m.euler_characteristic(), chi - 1);
    assert_eq!(face_total(&m, &t), 16.0);
    // The middle vertex split: both copies are on the new hole.
    assert!(m.vertex(v[12]).unwrap().is_boundary());
    assert_eq!(m.split_components(false).len(), 1);
}

#[test]
fn closed_seam_cuts_an_icosahedron_in_two() {
    let mut m = shapes::icosahedron();
    let v: Vec<_> = m.vertices().collect();
    let mut ring: Vec<_> = m.vertex(v[0]).unwrap().neighbors().collect();
    ring.push(ring[0]);
    let holes = checked(&mut m, |m| m.cut_path(&ring)).unwrap();
    assert_eq!(holes.len(), 2);
    assert_eq!(counts(&m), (17, 35, 20, 2));
    assert_eq!(m.euler_characteristic(), 2);
    let parts = m.split_components(true);
    assert_eq!(parts.len(), 2);
    let mut sizes: Vec<_> = parts
        .iter()
        .map(|p| (p.vertex_count(), p.face_count()))
        .collect();
    sizes.sort();
    assert_eq!(sizes, vec![(6, 5), (11, 15)]);
}

#[test]
fn refusals_leave_the_mesh_alone() {
    let mut m = quad_grid(3);
    let v: Vec<_> = m.vertices().collect();
    // Too short.
    assert!(matches!(
        refusal(checked(&mut m, |m| m.cut_path(&[v[5], v[6]]))),
        Refusal::Parameter(_)
    ));
    // Not joined.
    assert_eq!(
        refusal(checked(&mut m, |m| m.cut_path(&[v[5], v[10], v[6]]))),
        Refusal::NotAdjacent
    );
    // A boundary edge on the path.
    assert_eq!(
        refusal(checked(&mut m, |m| m.cut_path(&[v[0], v[1], v[5]]))),
        Refusal::Boundary
    );
    // An inner path vertex on the boundary.
    assert_eq!(
        refusal(checked(&mut m, |m| m.cut_path(&[v[6], v[2], v[1], v[5]]))),
        Refusal::Boundary
    );
    // A boundary end is fine.
    assert!(m.check_cut_path(&[v[4], v[5], v[6]]).is_ok());
    // Meets a vertex twice.
    assert_eq!(
        refusal(checked(&mut m, |m| m.cut_path(&[v[5], v[6], v[5]]))),
        Refusal::Parameter("the path needs two edges (one from a boundary, three if closed)")
    );
    assert_eq!(
        refusal(checked(&mut m, |m| m.cut_path(&[v[5], v[6], v[10], v[6]]))),
        Refusal::NonManifold
    );
}

#[test]
fn boundary_to_boundary_cuts_a_grid_in_two() {
    let mut m = quad_grid(3);
    let t = add_totals(&mut m);
    let v: Vec<_> = m.vertices().collect();
    // Column 1, from the bottom boundary to the top one: 1, 5, 9, 13.
    let path = [v[1], v[5], v[9], v[13]];
    let chi = m.euler_characteristic();
    let holes = checked(&mut m, |m| m.cut_path(&path)).unwrap();
    assert_eq!(holes.len(), 2);
    assert_eq!(m.euler_characteristic(), chi + 1);
    assert_eq!(counts(&m), (20, 27, 9, 2));
    assert_eq!(face_total(&m, &t), 9.0);
    let parts = m.split_components(true);
    let mut sizes: Vec<_> = parts.iter().map(|p| p.face_count()).collect();
    sizes.sort();
    assert_eq!(sizes, vec![3, 6]);
}

#[test]
fn from_the_boundary_inwards_and_between_two_holes() {
    let mut m = quad_grid(4);
    let v: Vec<_> = m.vertices().collect();
    let chi = m.euler_characteristic();
    // From the bottom boundary up into the middle: 2, 7, 12.
    let holes = checked(&mut m, |m| m.cut_path(&[v[2], v[7], v[12]])).unwrap();
    assert_eq!(holes.len(), 1);
    assert_eq!(m.hole_count(), 1);
    assert_eq!(m.euler_characteristic(), chi);
    assert_eq!(m.face(holes[0]).unwrap().degree(), 16 + 4);
    // Two holes joined by a cut between them.
    let mut m = quad_grid(4);
    let v: Vec<_> = m.vertices().collect();
    let inner = m.faces().nth(5).unwrap(); // the quad at (1, 1)
    m.remove_face(inner).unwrap();
    assert_eq!(m.hole_count(), 2);
    // From corner 12 of the inner hole round to the bottom boundary.
    let holes = checked(&mut m, |m| m.cut_path(&[v[12], v[13], v[8], v[3]])).unwrap();
    assert_eq!(holes.len(), 1);
    assert_eq!(m.hole_count(), 1);
    assert_eq!(m.split_components(false).len(), 1);
}
