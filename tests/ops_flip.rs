//! flip_edge: triangles on both sides, refusals, attributes.

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
fn flip_spoke_of_one_ring() {
    let mut m = one_ring();
    let t = add_totals(&mut m);
    let c = m.vertices().next().unwrap();
    let h = m.vertex(c).unwrap().outgoing().next().unwrap();
    let e = m.halfedge(h).unwrap().edge().key();
    let hv = m.halfedge(h).unwrap();
    let (x, y) = (hv.next().dest().key(), hv.twin().next().dest().key());
    assert_eq!(checked(&mut m, |m| m.flip_edge(e)).unwrap(), e);
    let [p, q] = m.edge(e).unwrap().vertices();
    assert!((p, q) == (x, y) || (p, q) == (y, x));
    assert_eq!(m.vertex(c).unwrap().degree(), 5);
    assert_eq!(counts(&m), (7, 12, 6, 1));
    assert_eq!(face_total(&m, &t), 6.0);
    // Flipping back restores the spoke.
    checked(&mut m, |m| m.flip_edge(e)).unwrap();
    assert_eq!(m.vertex(c).unwrap().degree(), 6);
}

#[test]
fn boundary_and_quads_are_refused() {
    let mut m = boundary_fan();
    let rim = m
        .edges()
        .find(|&e| m.edge(e).unwrap().is_boundary())
        .unwrap();
    assert_eq!(
        refusal(checked(&mut m, |m| m.flip_edge(rim))),
        Refusal::Boundary
    );
    let mut q = l_shape();
    let inner = q
        .edges()
        .find(|&e| !q.edge(e).unwrap().is_boundary())
        .unwrap();
    assert_eq!(
        refusal(checked(&mut q, |m| m.flip_edge(inner))),
        Refusal::NotTriangles
    );
}

#[test]
fn existing_edge_is_refused() {
    // On a tetrahedron every flip would duplicate an edge.
    let mut m = shapes::tetrahedron();
    for e in m.edges().collect::<Vec<_>>() {
        assert_eq!(
            refusal(checked(&mut m, |m| m.flip_edge(e))),
            Refusal::EdgeExists
        );
        assert!(m.check_flip_edge(e).is_err());
    }
}

#[test]
fn flip_every_edge_of_icosahedron_twice() {
    let mut m = shapes::icosahedron();
    for e in m.edges().collect::<Vec<_>>() {
        m.flip_edge(e).unwrap();
        m.flip_edge(e).unwrap();
    }
    m.validate().unwrap();
    assert_eq!(m.euler_characteristic(), 2);
    assert!(m.vertices().all(|v| m.vertex(v).unwrap().degree() == 5));
}

/// The opposite corners `c`, `d` of an edge between two triangles.
fn opposite_corners(m: &meshloom::Mesh, e: meshloom::EdgeKey) -> Option<[meshloom::VertexKey; 2]> {
    let ev = m.edge(e).unwrap();
    let (h, t) = (ev.halfedge(0), ev.halfedge(1));
    if h.face().is_hole() || t.face().is_hole() {
        return None;
    }
    Some([h.next().dest().key(), t.next().dest().key()])
}

#[test]
fn existing_edge_refusal_agrees_with_an_edge_set() {
    // Random flips pile edges into fans and make short cycles, where the
    // new diagonal often exists already; compare every decision with a
    // set of vertex pairs built independently of the ring walk.
    use std::collections::HashSet;
    for mut m in [shapes::icosphere(1), shapes::octahedron(), one_ring()] {
        let (mut seed, mut refused) = (0x9e37_79b9_u64, 0);
        for _ in 0..400 {
            let pairs: HashSet<_> = m
                .edges()
                .map(|e| {
                    let [p, q] = m.edge(e).unwrap().vertices();
                    (p.min(q), p.max(q))
                })
                .collect();
            let edges: Vec<_> = m.edges().collect();
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let e = edges[(seed >> 33) as usize % edges.len()];
            let triangles = m
                .edge(e)
                .unwrap()
                .faces()
                .iter()
                .all(|f| f.is_some_and(|f| m.face(f).unwrap().degree() == 3));
            let expect_exists = match opposite_corners(&m, e) {
                Some([c, d]) if triangles => c == d || pairs.contains(&(c.min(d), c.max(d))),
                _ => false,
            };
            match checked(&mut m, |m| m.flip_edge(e)) {
                Ok(_) => assert!(triangles && !expect_exists),
                Err(Error::Refused {
                    reason: Refusal::EdgeExists,
                    ..
                }) => assert!(expect_exists),
                Err(other) => assert!(!triangles, "{other:?}"),
            }
            refused += usize::from(expect_exists);
        }
        m.validate().unwrap();
        assert!(refused > 0, "the walk met no existing diagonal");
    }
}
