//! split_edge, split_face / insert_edge, poke_face on small named meshes.

mod common;
use common::*;
use meshloom::{Error, Mesh, Refusal};

#[test]
fn split_interior_edge_of_one_ring() {
    let mut m = one_ring();
    let t = add_totals(&mut m);
    let c = m.vertices().next().unwrap();
    let h = m.vertex(c).unwrap().outgoing().next().unwrap();
    let e = m.halfedge(h).unwrap().edge().key();
    let [a, b] = m.edge(e).unwrap().vertices();
    let (pa, pb) = (m.position(a).unwrap(), m.position(b).unwrap());
    let chi = m.euler_characteristic();
    let v = checked(&mut m, |m| m.split_edge(e, 0.25)).unwrap();
    assert_eq!(counts(&m), (8, 13, 6, 1));
    assert_eq!(m.euler_characteristic(), chi);
    assert_eq!(m.vertex(v).unwrap().degree(), 2);
    let p = m.position(v).unwrap();
    for k in 0..3 {
        assert!((p[k] - (0.75 * pa[k] + 0.25 * pb[k])).abs() < 1e-12);
    }
    // Both faces gained a side.
    let degrees: Vec<usize> = m
        .vertex(v)
        .unwrap()
        .faces()
        .map(|f| m.face(f).unwrap().degree())
        .collect();
    assert_eq!(degrees, vec![4, 4]);
    assert!(m.find_halfedge(a, v).unwrap().is_some() && m.find_halfedge(v, b).unwrap().is_some());
    assert!(m.find_halfedge(a, b).unwrap().is_none());
    assert_eq!(face_total(&m, &t), 6.0);
    assert_eq!(vertex_total(&m, &t), 7.0);
}

#[test]
fn split_boundary_edge_grows_the_hole() {
    let mut m = boundary_fan();
    let e = m
        .edges()
        .find(|&e| m.edge(e).unwrap().is_boundary())
        .unwrap();
    let hole = m.holes().next().unwrap();
    let before = m.face(hole).unwrap().degree();
    checked(&mut m, |m| m.split_edge(e, 0.5)).unwrap();
    assert_eq!(m.face(hole).unwrap().degree(), before + 1);
    assert_eq!(m.hole_count(), 1);
}

#[test]
fn split_edge_refuses_bad_t_and_stale_keys() {
    let mut m = l_shape();
    let e = m.edges().next().unwrap();
    for t in [-0.1, 1.5, f64::NAN] {
        let r = checked(&mut m, |m| m.split_edge(e, t));
        assert!(matches!(
            r,
            Err(Error::Refused {
                reason: Refusal::Parameter(_),
                ..
            })
        ));
        assert!(m.check_split_edge(e, t).is_err());
    }
    let [a, _] = m.edge(e).unwrap().vertices();
    let v = m.split_edge(e, 0.5).unwrap();
    // The split edge keeps its key (it now starts at the new vertex).
    assert_eq!(m.edge(e).unwrap().vertices()[0], v);
    // Collapsing the new vertex back into `a` restores the counts.
    let h = m.find_halfedge(v, a).unwrap().unwrap();
    checked(&mut m, |m| m.collapse_edge(h)).unwrap();
    assert_eq!(counts(&m), counts(&l_shape()));
    assert!(!m.contains_vertex(v));
    // The collapse removed the new edge; `e` joins `a` and `b` again.
    assert!(m.edge(e).unwrap().vertices().contains(&a));
    let gone = m.split_edge(e, 0.5).unwrap();
    let h = m.find_halfedge(gone, a).unwrap().unwrap();
    m.collapse_edge(h).unwrap();
    let first = m.edges().next().unwrap();
    assert!(m.split_edge(first, 0.5).is_ok());
    let stale = m.vertex(gone).err().unwrap();
    assert!(matches!(stale, Error::StaleKey(_)));
}

#[test]
fn split_face_of_l_shape_quad() {
    let mut m = l_shape();
    let t = add_totals(&mut m);
    let f = m.faces().next().unwrap();
    let c: Vec<_> = m.face(f).unwrap().vertices().collect();
    assert!(m.check_split_face(f, c[0], c[1]).is_err());
    let r = checked(&mut m, |m| m.split_face(f, c[0], c[1]));
    assert!(matches!(
        r,
        Err(Error::Refused {
            reason: Refusal::Adjacent,
            ..
        })
    ));
    let r = checked(&mut m, |m| m.split_face(f, c[0], c[0]));
    assert!(matches!(
        r,
        Err(Error::Refused {
            reason: Refusal::Adjacent,
            ..
        })
    ));
    let far = m.vertices().find(|v| !c.contains(v)).unwrap();
    let r = checked(&mut m, |m| m.split_face(f, c[0], far));
    assert!(matches!(
        r,
        Err(Error::Refused {
            reason: Refusal::NotInFace,
            ..
        })
    ));
    let hole = m.holes().next().unwrap();
    let r = checked(&mut m, |m| m.split_face(hole, c[0], c[2]));
    assert!(matches!(
        r,
        Err(Error::Refused {
            reason: Refusal::Hole,
            ..
        })
    ));

    let h = checked(&mut m, |m| m.split_face(f, c[0], c[2])).unwrap();
    let hv = m.halfedge(h).unwrap();
    assert_eq!((hv.origin().key(), hv.dest().key()), (c[0], c[2]));
    assert_eq!(hv.face().degree(), 3);
    assert_eq!(hv.twin().face().degree(), 3);
    assert_eq!(counts(&m), (8, 11, 4, 1));
    assert!((face_total(&m, &t) - 3.0).abs() < 1e-12);
    // The same diagonal again exists already.
    let g = hv.twin().face().key();
    let r = checked(&mut m, |m| m.split_face(g, c[0], c[2]));
    assert!(r.is_err());
}

#[test]
fn split_face_refuses_an_existing_edge_elsewhere() {
    // Build explicitly: quad (0,2,3,4) and triangle (0,1,2) share edge 0-2.
    let mut m = Mesh::from_faces(6, &[vec![0u32, 1, 2], vec![0, 2, 3, 4], vec![0, 4, 5]]).unwrap();
    let v: Vec<_> = m.vertices().collect();
    let quad = m
        .faces()
        .find(|&f| m.face(f).unwrap().degree() == 4)
        .unwrap();
    // 0-3 is new: fine. 4-2 is new: fine. But insert_edge(0, 4)? adjacent.
    assert!(m.check_split_face(quad, v[0], v[3]).is_ok());
    let r = checked(&mut m, |m| m.insert_edge(v[0], v[4]));
    assert!(r.is_err());
    let h = checked(&mut m, |m| m.insert_edge(v[2], v[4])).unwrap();
    assert_eq!(m.halfedge(h).unwrap().dest().key(), v[4]);
    let r = checked(&mut m, |m| m.insert_edge(v[1], v[5]));
    assert!(matches!(
        r,
        Err(Error::Refused {
            reason: Refusal::NotInFace,
            ..
        })
    ));
}

#[test]
fn poke_faces_everywhere() {
    for mut m in [one_ring(), boundary_fan(), l_shape(), open_cone(), bowtie()] {
        let t = add_totals(&mut m);
        let (v0, e0, f0, h0) = counts(&m);
        let chi = m.euler_characteristic();
        let faces: Vec<_> = m.faces().collect();
        let mut added_faces = 0;
        for f in faces {
            let n = m.face(f).unwrap().degree();
            let centroid = {
                let ps: Vec<_> = m
                    .face(f)
                    .unwrap()
                    .vertices()
                    .map(|v| m.position(v).unwrap())
                    .collect();
                let mut c = [0.0; 3];
                for p in &ps {
                    for k in 0..3 {
                        c[k] += p[k] / n as f64;
                    }
                }
                c
            };
            let c = checked(&mut m, |m| m.poke_face(f)).unwrap();
            assert_eq!(m.vertex(c).unwrap().degree(), n);
            let p = m.position(c).unwrap();
            for k in 0..3 {
                assert!((p[k] - centroid[k]).abs() < 1e-12);
            }
            assert!(m
                .vertex(c)
                .unwrap()
                .faces()
                .all(|g| m.face(g).unwrap().degree() == 3));
            added_faces += n - 1;
        }
        assert_eq!(m.euler_characteristic(), chi);
        assert_eq!(m.face_count(), f0 + added_faces);
        assert_eq!(m.hole_count(), h0);
        assert_eq!(m.vertex_count(), v0 + f0);
        assert!(m.edge_count() > e0);
        assert!((face_total(&m, &t) - f0 as f64).abs() < 1e-9);
        assert_eq!(vertex_total(&m, &t), v0 as f64);
    }
    let mut m = l_shape();
    let hole = m.holes().next().unwrap();
    assert!(checked(&mut m, |m| m.poke_face(hole)).is_err());
}

#[test]
fn collapsing_the_poked_vertex_gives_the_triangle_back() {
    // Every triangle of an icosahedron and of a fan with a boundary: the
    // face, its half-edges and its corners keep their keys, so an edit
    // made of pokes and collapses back leaves the mesh as it was.
    for mut m in [meshloom::shapes::icosahedron(), one_ring()] {
        let faces: Vec<_> = m.faces().collect();
        for f in faces {
            let sides: Vec<_> = m.face(f).unwrap().halfedges().collect();
            let corners: Vec<_> = m.face(f).unwrap().vertices().collect();
            let positions: Vec<_> = corners.iter().map(|&v| m.position(v).unwrap()).collect();
            let (v0, e0, f0, h0) = counts(&m);
            let c = checked(&mut m, |m| m.poke_face(f)).unwrap();
            let h = m.vertex(c).unwrap().halfedge().key();
            checked(&mut m, |m| m.collapse_edge(h)).unwrap();
            assert!(m.vertex(c).is_err());
            let back: Vec<_> = m.face(f).unwrap().halfedges().collect();
            assert_eq!(back, sides, "face {f:?} came back with other half-edges");
            let again: Vec<_> = m.face(f).unwrap().vertices().collect();
            assert_eq!(again, corners);
            for (v, p) in corners.iter().zip(&positions) {
                assert_eq!(m.position(*v).unwrap(), *p);
            }
            assert_eq!(counts(&m), (v0, e0, f0, h0));
        }
    }
}
