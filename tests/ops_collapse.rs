//! collapse_edge: interior, boundary, link condition, n-gons, attributes.

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
fn collapse_spoke_of_one_ring() {
    let mut m = one_ring();
    let t = add_totals(&mut m);
    let c = m.vertices().next().unwrap();
    // Spoke from the centre out: the centre is merged into a rim vertex.
    let h = m.vertex(c).unwrap().outgoing().next().unwrap();
    let b = m.halfedge(h).unwrap().dest().key();
    let pb = m.position(b).unwrap();
    let got = checked(&mut m, |m| m.collapse_edge(h)).unwrap();
    assert_eq!(got, b);
    assert!(!m.contains_vertex(c));
    assert_eq!(counts(&m), (6, 9, 4, 1));
    assert_eq!(m.position(b).unwrap(), pb);
    assert_eq!(face_total(&m, &t), 6.0);
    assert_eq!(vertex_total(&m, &t), 7.0);
    assert_eq!(m.euler_characteristic(), 1);
}

#[test]
fn collapse_at_midpoint_moves_the_survivor() {
    let mut m = shapes::icosahedron();
    let h = m.halfedges().next().unwrap();
    let (a, b) = (
        m.halfedge(h).unwrap().origin().key(),
        m.halfedge(h).unwrap().dest().key(),
    );
    let (pa, pb) = (m.position(a).unwrap(), m.position(b).unwrap());
    assert!(m.check_collapse_edge_at(h, 2.0).is_err());
    let v = checked(&mut m, |m| m.collapse_edge_at(h, 0.5)).unwrap();
    let p = m.position(v).unwrap();
    for k in 0..3 {
        assert!((p[k] - 0.5 * (pa[k] + pb[k])).abs() < 1e-12);
    }
    assert_eq!(m.euler_characteristic(), 2);
}

#[test]
fn interior_edge_between_boundary_vertices_is_refused() {
    let mut m = l_shape();
    m.triangulate_all();
    let interior_between_boundaries = m
        .edges()
        .find(|&e| {
            let ev = m.edge(e).unwrap();
            !ev.is_boundary()
                && ev
                    .vertices()
                    .iter()
                    .all(|&v| m.vertex(v).unwrap().is_boundary())
        })
        .unwrap();
    let h = m
        .edge(interior_between_boundaries)
        .unwrap()
        .halfedge(0)
        .key();
    assert_eq!(
        refusal(checked(&mut m, |m| m.collapse_edge(h))),
        Refusal::NonManifold
    );
}

#[test]
fn boundary_edge_of_fan() {
    let mut m = boundary_fan();
    let rim = m
        .halfedges()
        .find(|&h| {
            let hv = m.halfedge(h).unwrap();
            !hv.face().is_hole() && hv.twin().face().is_hole()
        })
        .unwrap();
    let chi = m.euler_characteristic();
    checked(&mut m, |m| m.collapse_edge(rim)).unwrap();
    assert_eq!(counts(&m), (5, 7, 3, 1));
    assert_eq!(m.euler_characteristic(), chi);
}

#[test]
fn tetrahedron_to_pillow_then_refused() {
    let mut m = shapes::tetrahedron();
    let h = m.halfedges().next().unwrap();
    checked(&mut m, |m| m.collapse_edge(h)).unwrap();
    assert_eq!(counts(&m), (3, 3, 2, 0));
    for h in m.halfedges().collect::<Vec<_>>() {
        assert_eq!(
            refusal(checked(&mut m, |m| m.collapse_edge(h))),
            Refusal::LinkCondition
        );
    }
}

#[test]
fn link_condition_on_poked_tetrahedron() {
    // Poke one face of a tetrahedron: its old edges now join vertices that
    // share a third neighbour with no face between them.
    let mut m = shapes::tetrahedron();
    let f = m.faces().next().unwrap();
    let corners: Vec<_> = m.face(f).unwrap().vertices().collect();
    let c = m.poke_face(f).unwrap();
    let h = m.find_halfedge(corners[0], corners[1]).unwrap().unwrap();
    assert_eq!(
        refusal(checked(&mut m, |m| m.collapse_edge(h))),
        Refusal::LinkCondition
    );
    // The spokes are fine: collapsing the centre back restores a tetrahedron.
    let spoke = m.find_halfedge(c, corners[0]).unwrap().unwrap();
    checked(&mut m, |m| m.collapse_edge(spoke)).unwrap();
    assert_eq!(counts(&m), (4, 6, 4, 0));
    // On the open cone, apex-to-rim collapses are fine.
    let mut m = open_cone();
    let apex = m.vertices().next().unwrap();
    let h = m.vertex(apex).unwrap().outgoing().next().unwrap();
    checked(&mut m, |m| m.collapse_edge(h)).unwrap();
    assert_eq!(counts(&m), (6, 9, 4, 1));
}

#[test]
fn ngon_sides_lose_a_side() {
    let mut m = l_shape();
    let t = add_totals(&mut m);
    // The edge shared by the corner quad and the bottom-right quad.
    let v: Vec<_> = m.vertices().collect();
    let h = m.find_halfedge(v[4], v[1]).unwrap().unwrap();
    let r = checked(&mut m, |m| m.collapse_edge(h));
    // 4 is interior? no: the L has 4 on the boundary at the inner corner,
    // and 1 on the bottom boundary: interior edge between boundary
    // vertices -> refused.
    assert_eq!(refusal(r), Refusal::NonManifold);
    // A bottom boundary edge 0 -> 1: quad (0,1,4,3) becomes a triangle.
    let h = m.find_halfedge(v[0], v[1]).unwrap().unwrap();
    checked(&mut m, |m| m.collapse_edge(h)).unwrap();
    let f = m
        .vertex(v[1])
        .unwrap()
        .faces()
        .find(|&f| m.face(f).unwrap().degree() == 3)
        .unwrap();
    assert!(m.face(f).unwrap().vertices().any(|x| x == v[3]));
    assert_eq!(face_total(&m, &t), 3.0);
    assert_eq!(m.face_count(), 3);
}

#[test]
fn triangular_hole_closes() {
    // A triangle fan around a triangular hole: collapse a hole edge.
    let mut m = read_off(&mesh_path("boundary/cgal_triangular_hole.off"));
    let holes_before = m.hole_count();
    let chi = m.euler_characteristic();
    let h = m
        .halfedges()
        .find(|&h| {
            let hv = m.halfedge(h).unwrap();
            hv.twin().face().is_hole()
                && hv.twin().face().degree() == 3
                && m.check_collapse_edge(h).is_ok()
        })
        .expect("a collapsible edge on the triangular hole");
    checked(&mut m, |m| m.collapse_edge(h)).unwrap();
    assert_eq!(m.hole_count(), holes_before - 1);
    assert_eq!(m.euler_characteristic(), chi + 1);
}

#[test]
fn bowtie_triangle_edges() {
    let mut m = bowtie();
    // Every edge of a lone triangle would leave a dangling edge or pinch.
    for h in m.halfedges().collect::<Vec<_>>() {
        assert!(checked(&mut m, |m| m.collapse_edge(h)).is_err());
    }
}

#[test]
fn stale_key_is_reported() {
    let mut m = shapes::icosahedron();
    let h = m.halfedges().next().unwrap();
    m.collapse_edge(h).unwrap();
    assert!(matches!(m.collapse_edge(h), Err(Error::StaleKey(_))));
}

#[test]
fn link_condition_agrees_with_neighbour_sets() {
    // On closed triangle meshes a collapse of a -> b is allowed exactly
    // when the two apexes differ and every common neighbour of a and b is
    // one of them. Neighbour sets come from the edge list, not from the
    // ring walks under test; random flips and pokes in between make
    // low-valence vertices and short cycles.
    use std::collections::{HashMap, HashSet};
    let mut poked = shapes::icosahedron();
    for f in poked.faces().collect::<Vec<_>>().into_iter().step_by(3) {
        poked.poke_face(f).unwrap();
    }
    for mut m in [shapes::icosphere(1), shapes::icosphere(2), poked] {
        let (mut seed, mut refused, mut done) = (0x2545_f491_u64, 0, 0);
        for step in 0..300 {
            if m.vertex_count() <= 8 {
                break;
            }
            let mut around: HashMap<_, HashSet<_>> = HashMap::new();
            for e in m.edges() {
                let [p, q] = m.edge(e).unwrap().vertices();
                around.entry(p).or_default().insert(q);
                around.entry(q).or_default().insert(p);
            }
            let hs: Vec<_> = m.halfedges().collect();
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let h = hs[(seed >> 33) as usize % hs.len()];
            if step % 4 == 3 {
                let _ = m.flip_edge(m.halfedge(h).unwrap().edge().key());
                continue;
            }
            let hv = m.halfedge(h).unwrap();
            let (a, b) = (hv.origin().key(), hv.dest().key());
            let (c, d) = (hv.next().dest().key(), hv.twin().next().dest().key());
            let allowed = c != d
                && around[&a]
                    .intersection(&around[&b])
                    .all(|&w| w == c || w == d);
            match checked(&mut m, |m| m.collapse_edge(h)) {
                Ok(kept) => {
                    assert!(
                        allowed,
                        "collapse of {a:?} into {b:?} broke the link condition"
                    );
                    assert_eq!(kept, b);
                    done += 1;
                }
                Err(e) => {
                    assert!(!allowed, "collapse of {a:?} into {b:?} refused: {e}");
                    refused += 1;
                }
            }
        }
        eprintln!("{done} collapses, {refused} refusals");
        assert!(
            done > 0 && refused > 0,
            "{done} collapses, {refused} refusals"
        );
    }
}
