//! compact() and the low-level reflecting setters.

mod common;
use common::*;
use meshloom::{shapes, Error};

#[test]
fn compact_after_many_edits_keeps_structure_and_values() {
    let mut m = shapes::icosahedron();
    let t = add_totals(&mut m);
    for _ in 0..4 {
        let h = m
            .halfedges()
            .find(|&h| m.check_collapse_edge(h).is_ok())
            .unwrap();
        m.collapse_edge(h).unwrap();
    }
    let f = m.faces().nth(2).unwrap();
    m.poke_face(f).unwrap();
    let v = m.vertices().last().unwrap();
    let pv = m.position(v).unwrap();
    let (c, ft, vt, chi) = (
        counts(&m),
        face_total(&m, &t),
        vertex_total(&m, &t),
        m.euler_characteristic(),
    );
    let old_h = m.halfedges().nth(5).unwrap();
    let (oo, od) = (
        m.halfedge(old_h).unwrap().origin().key(),
        m.halfedge(old_h).unwrap().dest().key(),
    );
    let maps = m.compact();
    m.validate().unwrap();
    assert_eq!(counts(&m), c);
    assert_eq!(m.slot_counts(), [c.0, 2 * c.1, c.1, c.2 + c.3]);
    assert_eq!(
        (
            face_total(&m, &t),
            vertex_total(&m, &t),
            m.euler_characteristic()
        ),
        (ft, vt, chi)
    );
    let nv = maps.vertex(v).unwrap();
    assert_eq!(m.position(nv).unwrap(), pv);
    let nh = maps.halfedge(old_h).unwrap();
    assert_eq!(
        m.halfedge(nh).unwrap().origin().key(),
        maps.vertex(oo).unwrap()
    );
    assert_eq!(
        m.halfedge(nh).unwrap().dest().key(),
        maps.vertex(od).unwrap()
    );
    assert!(maps.face(f).is_some());
}

#[test]
fn raw_edit_reports_broken_rules_and_stale_keys() {
    let mut m = shapes::tetrahedron();
    let hs: Vec<_> = m.halfedges().collect();
    let v = m.vertices().next().unwrap();
    {
        let mut edit = m.raw_edit();
        assert!(edit.next(hs[0]).unwrap().is_some());
        // Point a half-edge at itself: next is no longer a permutation.
        edit.link(hs[0], hs[0]).unwrap();
        assert!(matches!(edit.validate(), Err(Error::Invalid(_))));
    }
    let mut m = shapes::tetrahedron();
    let e = m.edges().next().unwrap();
    m.raw_edit().remove_edge(e).unwrap();
    assert!(matches!(
        m.raw_edit().remove_edge(e),
        Err(Error::StaleKey(_))
    ));
    assert!(m.raw_edit().finish().is_err());
    let _ = v;
}

#[test]
fn raw_edit_builds_a_triangle_by_hand() {
    let mut m = meshloom::Mesh::new();
    let mut edit = m.raw_edit();
    let v = [edit.new_vertex(), edit.new_vertex(), edit.new_vertex()];
    let e = [edit.new_edge(), edit.new_edge(), edit.new_edge()];
    let f = edit.new_face(false);
    let hole = edit.new_face(true);
    for i in 0..3 {
        let (inner, outer) = (e[i].halfedge_key(0), e[i].halfedge_key(1));
        edit.set_origin(inner, v[i]).unwrap();
        edit.set_origin(outer, v[(i + 1) % 3]).unwrap();
        edit.set_face(inner, f).unwrap();
        edit.set_face(outer, hole).unwrap();
        edit.link(inner, e[(i + 1) % 3].halfedge_key(0)).unwrap();
        edit.link(e[(i + 1) % 3].halfedge_key(1), outer).unwrap();
        // Reflection: the vertex now names its half-edge.
        edit.set_origin(inner, v[i]).unwrap();
    }
    edit.finish().unwrap();
    assert_eq!(counts(&m), (3, 3, 1, 1));
}

#[test]
fn operators_terminate_on_a_mesh_left_broken_by_raw_edits() {
    // Rings that never return to their start must not hang an operator:
    // every walk is bounded. (What a broken mesh yields is unspecified, and
    // debug builds may panic when an operator's result fails `validate`;
    // only termination is tested.)
    let (done, finished) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut m = shapes::icosahedron();
        let hs: Vec<_> = m.halfedges().collect();
        {
            let mut edit = m.raw_edit();
            // Two half-edges of one ring now skip into another ring.
            edit.link(hs[1], hs[7]).unwrap();
            edit.link(hs[9], hs[20]).unwrap();
        }
        for &h in &hs {
            let mut copy = m.clone();
            let e = m.halfedge(h).unwrap().edge().key();
            let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(move || {
                let _ = copy.check_flip_edge(e);
                let _ = copy.check_collapse_edge(h);
                let _ = copy.flip_edge(e);
                let _ = copy.collapse_edge(h);
            }));
        }
        done.send(()).unwrap();
    });
    let waited = finished.recv_timeout(std::time::Duration::from_secs(60));
    assert!(
        waited.is_ok(),
        "an operator did not return on a broken mesh"
    );
}

/// Rule 11 through the raw setters: `set_origin` reflects into the vertex,
/// which may leave a boundary vertex naming an interior half-edge. `validate`
/// reports that as rule 11; `finish` re-establishes the rule, then
/// validates.
#[test]
fn raw_edit_finish_points_boundary_vertices_into_holes() {
    // Two triangles: every vertex is on the boundary.
    let mut m = meshloom::Mesh::from_faces(4, &[[0u32, 1, 2], [0, 2, 3]]).unwrap();
    let v: Vec<_> = m.vertices().collect();
    let inner = m.find_halfedge(v[0], v[2]).unwrap().unwrap();
    assert!(!m.halfedge(inner).unwrap().is_boundary());
    let mut edit = m.raw_edit();
    edit.set_origin(inner, v[0]).unwrap(); // v0 now names 0 -> 2, no hole
    match edit.validate() {
        Err(Error::Invalid(e)) => assert_eq!(
            (e.rule, e.rule_name()),
            (11, "boundary vertices point into a hole")
        ),
        other => panic!("{other:?}"),
    }
    edit.finish().unwrap();
    m.validate().unwrap();
    let v0 = m.vertex(v[0]).unwrap();
    assert!(v0.is_boundary() && v0.halfedge().is_boundary());
}
