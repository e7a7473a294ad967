//! remove_edge, merge_faces, remove_vertex.

mod common;
use common::*;
use meshloom::{shapes, Error, Mesh, Refusal};

fn refusal<T: std::fmt::Debug>(r: meshloom::Result<T>) -> Refusal {
    match r {
        Err(Error::Refused { reason, .. }) => reason,
        other => panic!("expected a refusal, got {other:?}"),
    }
}

#[test]
fn remove_interior_edge_merges_faces() {
    let mut m = l_shape();
    let t = add_totals(&mut m);
    let e = m
        .edges()
        .find(|&e| !m.edge(e).unwrap().is_boundary())
        .unwrap();
    let f = checked(&mut m, |m| m.remove_edge(e)).unwrap();
    assert_eq!(m.face(f).unwrap().degree(), 6);
    assert_eq!(counts(&m), (8, 9, 2, 1));
    assert_eq!(face_total(&m, &t), 3.0);
    assert!(!m.contains_edge(e));
}

#[test]
fn remove_boundary_edge_grows_the_hole() {
    let mut m = boundary_fan();
    // A rim edge of the middle triangle: its other sides are interior.
    let e = m
        .edges()
        .find(|&e| m.edge(e).unwrap().is_boundary() && m.check_remove_edge(e).is_ok())
        .unwrap();
    let hole = m.holes().next().unwrap();
    let deg = m.face(hole).unwrap().degree();
    let chi = m.euler_characteristic();
    assert_eq!(checked(&mut m, |m| m.remove_edge(e)).unwrap(), hole);
    assert_eq!(m.face(hole).unwrap().degree(), deg + 1);
    assert_eq!(m.face_count(), 3);
    assert_eq!(m.euler_characteristic(), chi);
}

#[test]
fn bridges_and_pinches_are_refused() {
    // A strip of three quads: the middle quad's boundary edges are bridges.
    let mut m = Mesh::from_faces(8, &[[0u32, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6]]).unwrap();
    let v: Vec<_> = m.vertices().collect();
    let top = m.find_halfedge(v[1], v[2]).unwrap().unwrap();
    let e = m.halfedge(top).unwrap().edge().key();
    assert_eq!(
        refusal(checked(&mut m, |m| m.remove_edge(e))),
        Refusal::Bridge
    );
    // The end quads' outer edge: the quad has three boundary edges.
    let end = m.find_halfedge(v[0], v[1]).unwrap().unwrap();
    let e = m.halfedge(end).unwrap().edge().key();
    assert_eq!(
        refusal(checked(&mut m, |m| m.remove_edge(e))),
        Refusal::Bridge
    );
    // Faces that share two edges around a corner vertex: removing one of
    // the edges would leave a face meeting that vertex twice.
    let mut m = shapes::cube();
    let f = m.faces().next().unwrap();
    let g = m.face(f).unwrap().neighbors().next().unwrap();
    m.merge_faces(f, g).unwrap();
    let shared = m
        .face(f)
        .unwrap()
        .halfedges()
        .map(|h| m.halfedge(h).unwrap())
        .find(|h| {
            let other = h.twin().face();
            other
                .halfedges()
                .filter(|&x| m.halfedge(x).unwrap().twin().face().key() == f)
                .count()
                == 2
        })
        .unwrap()
        .edge()
        .key();
    assert_eq!(
        refusal(checked(&mut m, |m| m.remove_edge(shared))),
        Refusal::NonManifold
    );
}

#[test]
fn merge_faces_of_cube() {
    let mut m = shapes::cube();
    let t = add_totals(&mut m);
    let f: Vec<_> = m.faces().collect();
    // The opposite face is not adjacent.
    let far = m
        .faces()
        .find(|&x| x != f[0] && !m.face(f[0]).unwrap().neighbors().any(|n| n == x))
        .unwrap();
    assert_eq!(
        refusal(checked(&mut m, |m| m.merge_faces(f[0], far))),
        Refusal::NotAdjacent
    );
    assert_eq!(
        refusal(checked(&mut m, |m| m.merge_faces(f[0], f[0]))),
        Refusal::Adjacent
    );
    let g = m.face(f[0]).unwrap().neighbors().next().unwrap();
    assert_eq!(checked(&mut m, |m| m.merge_faces(f[0], g)).unwrap(), f[0]);
    assert_eq!(m.face(f[0]).unwrap().degree(), 6);
    assert!(!m.contains_face(g));
    assert_eq!(face_total(&m, &t), 6.0);
    // The hexagon and a side face now share two edges (a U around a
    // corner): merging them is refused.
    let side = m
        .faces()
        .find(|&x| {
            m.face(x)
                .unwrap()
                .halfedges()
                .filter(|&h| m.halfedge(h).unwrap().twin().face().key() == f[0])
                .count()
                == 2
        })
        .unwrap();
    assert_eq!(
        refusal(checked(&mut m, |m| m.merge_faces(f[0], side))),
        Refusal::NonManifold
    );
}

#[test]
fn remove_vertex_of_one_ring_and_refusals() {
    let mut m = one_ring();
    let t = add_totals(&mut m);
    let c = m.vertices().next().unwrap();
    let f = checked(&mut m, |m| m.remove_vertex(c)).unwrap();
    assert_eq!(m.face(f).unwrap().degree(), 6);
    assert_eq!(counts(&m), (6, 6, 1, 1));
    assert_eq!(face_total(&m, &t), 6.0);
    // Boundary vertices are refused.
    let mut m = boundary_fan();
    let c = m.vertices().next().unwrap();
    assert_eq!(
        refusal(checked(&mut m, |m| m.remove_vertex(c))),
        Refusal::Boundary
    );
    // On a tetrahedron the merged face would be a triangle over the
    // opposite face's corners: two faces with the same corners is fine
    // structurally, but the ring meets each neighbour once: allowed.
    let mut m = shapes::tetrahedron();
    let v = m.vertices().next().unwrap();
    checked(&mut m, |m| m.remove_vertex(v)).unwrap();
    assert_eq!(counts(&m), (3, 3, 2, 0));
    // On that pillow, removing a vertex would leave a two-sided face.
    let v = m.vertices().next().unwrap();
    assert_eq!(
        refusal(checked(&mut m, |m| m.remove_vertex(v))),
        Refusal::Degenerate
    );
}

#[test]
fn remove_degree_two_vertex_after_split_edge() {
    let mut m = l_shape();
    let e = m
        .edges()
        .find(|&e| !m.edge(e).unwrap().is_boundary())
        .unwrap();
    let v = m.split_edge(e, 0.5).unwrap();
    // Interior degree-2 vertex: its two quads merge into a hexagon.
    let f = checked(&mut m, |m| m.remove_vertex(v)).unwrap();
    assert_eq!(m.face(f).unwrap().degree(), 6);
    assert_eq!(counts(&m), (8, 9, 2, 1));
}
