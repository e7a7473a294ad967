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

/// Ids on every arena, each element its own: `Incompatible` keeps an id only
/// while nothing merges into it.
struct Ids {
    v: meshloom::attr::VertexAttr<i64, meshloom::attr::Incompatible>,
    h: meshloom::attr::HalfedgeAttr<i64, meshloom::attr::Incompatible>,
    e: meshloom::attr::EdgeAttr<i64, meshloom::attr::Incompatible>,
    f: meshloom::attr::FaceAttr<i64, meshloom::attr::Incompatible>,
}

fn number_everything(m: &mut meshloom::Mesh) -> Ids {
    use meshloom::attr::Incompatible;
    use meshloom::{EdgeKey, FaceKey, HalfedgeKey, VertexKey};
    let ids = Ids {
        v: m.add_attr_with_rule::<VertexKey, i64, Incompatible>("vid")
            .unwrap(),
        h: m.add_attr_with_rule::<HalfedgeKey, i64, Incompatible>("hid")
            .unwrap(),
        e: m.add_attr_with_rule::<EdgeKey, i64, Incompatible>("eid")
            .unwrap(),
        f: m.add_attr_with_rule::<FaceKey, i64, Incompatible>("fid")
            .unwrap(),
    };
    let (vs, hs): (Vec<_>, Vec<_>) = (m.vertices().collect(), m.halfedges().collect());
    let (es, fs): (Vec<_>, Vec<_>) = (m.edges().collect(), m.faces_and_holes().collect());
    for (i, k) in vs.into_iter().enumerate() {
        m.set_attr(&ids.v, k, 1000 + i as i64).unwrap();
    }
    for (i, k) in hs.into_iter().enumerate() {
        m.set_attr(&ids.h, k, 2000 + i as i64).unwrap();
    }
    for (i, k) in es.into_iter().enumerate() {
        m.set_attr(&ids.e, k, 3000 + i as i64).unwrap();
    }
    for (i, k) in fs.into_iter().enumerate() {
        m.set_attr(&ids.f, k, 4000 + i as i64).unwrap();
    }
    ids
}

/// Issue 10, defect 4: `compact()` moved elements into the slots of
/// removed ones but kept generations, so a key to a removed vertex read the
/// survivor now sitting in its slot. Every key taken before compacting (of
/// removed, moved and unmoved elements alike) is now stale, maps through
/// the returned maps to the same element (by its id), or to nothing for a
/// removed one; none reads another element's value.
#[test]
fn keys_from_before_compact_are_stale_or_remapped() {
    let mut m = shapes::icosahedron();
    let ids = number_everything(&mut m);
    let (vs, hs): (Vec<_>, Vec<_>) = (m.vertices().collect(), m.halfedges().collect());
    let (es, fs): (Vec<_>, Vec<_>) = (m.edges().collect(), m.faces_and_holes().collect());
    // The minimal input: one collapse frees vertex slot 0 (its origin) and
    // slots of two faces and three edges; compaction moves the last vertex
    // into slot 0.
    let h = m
        .halfedges()
        .find(|&h| m.halfedge(h).unwrap().origin().key().index() == 0)
        .unwrap();
    let removed = m.halfedge(h).unwrap().origin().key();
    m.collapse_edge(h).unwrap();
    // Record what every key named before compacting (None: removed).
    let was = |m: &meshloom::Mesh| {
        (
            vs.iter()
                .map(|&k| m.attr(&ids.v, k).ok().flatten().copied())
                .collect::<Vec<_>>(),
            hs.iter()
                .map(|&k| m.attr(&ids.h, k).ok().flatten().copied())
                .collect::<Vec<_>>(),
            es.iter()
                .map(|&k| m.attr(&ids.e, k).ok().flatten().copied())
                .collect::<Vec<_>>(),
            fs.iter()
                .map(|&k| m.attr(&ids.f, k).ok().flatten().copied())
                .collect::<Vec<_>>(),
        )
    };
    let before = was(&m);
    assert_eq!(before.0[0], None, "the removed vertex's key is stale");
    let live = (
        vs.iter().map(|&k| m.contains_vertex(k)).collect::<Vec<_>>(),
        es.iter().map(|&k| m.contains_edge(k)).collect::<Vec<_>>(),
        fs.iter().map(|&k| m.contains_face(k)).collect::<Vec<_>>(),
    );
    assert!(live.0.iter().any(|&l| !l) && live.1.iter().any(|&l| !l) && live.2.iter().any(|&l| !l));
    let maps = m.compact();
    m.validate().unwrap();
    // Slot 0 holds another vertex now; the removed vertex's key must not
    // read it (it read `Ok(Some(1011))` before the fix).
    assert!(m.vertex_at(0).is_some());
    assert!(matches!(m.attr(&ids.v, removed), Err(Error::StaleKey(_))));
    assert_eq!(maps.vertex(removed), None);
    // Every old key: stale; through the maps, the same element or nothing.
    for (i, &k) in vs.iter().enumerate() {
        assert!(
            matches!(m.attr(&ids.v, k), Err(Error::StaleKey(_))),
            "{k:?}"
        );
        assert_eq!(maps.vertex(k).is_some(), live.0[i], "{k:?}");
        let now = maps
            .vertex(k)
            .and_then(|n| m.attr(&ids.v, n).unwrap().copied());
        assert_eq!(now, before.0[i], "{k:?}");
    }
    for (i, &k) in hs.iter().enumerate() {
        assert!(
            matches!(m.attr(&ids.h, k), Err(Error::StaleKey(_))),
            "{k:?}"
        );
        assert_eq!(maps.halfedge(k).is_some(), live.1[i / 2], "{k:?}");
        let now = maps
            .halfedge(k)
            .and_then(|n| m.attr(&ids.h, n).unwrap().copied());
        assert_eq!(now, before.1[i], "{k:?}");
    }
    for (i, &k) in es.iter().enumerate() {
        assert!(
            matches!(m.attr(&ids.e, k), Err(Error::StaleKey(_))),
            "{k:?}"
        );
        assert_eq!(maps.edge(k).is_some(), live.1[i], "{k:?}");
        let now = maps
            .edge(k)
            .and_then(|n| m.attr(&ids.e, n).unwrap().copied());
        assert_eq!(now, before.2[i], "{k:?}");
    }
    for (i, &k) in fs.iter().enumerate() {
        assert!(
            matches!(m.attr(&ids.f, k), Err(Error::StaleKey(_))),
            "{k:?}"
        );
        assert_eq!(maps.face(k).is_some(), live.2[i], "{k:?}");
        let now = maps
            .face(k)
            .and_then(|n| m.attr(&ids.f, n).unwrap().copied());
        assert_eq!(now, before.3[i], "{k:?}");
    }
    // The fast paths survive: every arena is dense at its new base again,
    // and a view reads by the new keys, not by the old ones.
    let view = m.attr_view(&ids.v).unwrap();
    for (i, &k) in vs.iter().enumerate() {
        assert_eq!(view.get(k), None, "{k:?}");
        if let Some(n) = maps.vertex(k) {
            assert_eq!(view.get(n).copied(), before.0[i]);
        }
    }
    // A second compaction after more edits: keys of both eras stay stale.
    let kept: Vec<_> = m.vertices().collect();
    let f = m.faces().next().unwrap();
    m.poke_face(f).unwrap();
    let h = m
        .halfedges()
        .find(|&h| m.check_collapse_edge(h).is_ok())
        .unwrap();
    m.collapse_edge(h).unwrap();
    m.compact();
    for &k in vs.iter().chain(&kept) {
        assert!(!m.contains_vertex(k), "{k:?}");
    }
}

/// An arena with no vacant slot has nothing to move: its keys stay valid
/// and map to themselves.
#[test]
fn compacting_a_dense_mesh_keeps_its_keys() {
    let mut m = shapes::cube();
    let (vs, hs): (Vec<_>, Vec<_>) = (m.vertices().collect(), m.halfedges().collect());
    let maps = m.compact();
    for &v in &vs {
        assert!(m.contains_vertex(v));
        assert_eq!(maps.vertex(v), Some(v));
    }
    for &h in &hs {
        assert_eq!(maps.halfedge(h), Some(h));
    }
}

/// Issue 10, defect 5: a saved mesh with a generation of `u32::MAX` was
/// accepted; removing that element wrapped the generation to 0 and reissued
/// the slot at generation 1, so an old key resolved again. Now a live
/// generation past `u32::MAX - 2` is refused on loading, and a slot whose
/// next generation would pass it is retired, never reissued.
#[test]
fn generations_never_wrap_through_serde() {
    let mesh = shapes::icosahedron();
    let json = serde_json::to_value(&mesh).unwrap();
    // u32::MAX is not a generation meshloom issues.
    let mut bad = json.clone();
    bad["vertex_generations"][0] = serde_json::json!(u32::MAX);
    let err = serde_json::from_value::<meshloom::Mesh>(bad)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("vertex slot 0 has the live generation 4294967295"),
        "{err}"
    );
    // Nor a base that is even, or a generation below the base.
    let mut bad = json.clone();
    bad["edge_base"] = serde_json::json!(2);
    assert!(serde_json::from_value::<meshloom::Mesh>(bad).is_err());
    let mut bad = json.clone();
    bad["face_base"] = serde_json::json!(3);
    let err = serde_json::from_value::<meshloom::Mesh>(bad)
        .unwrap_err()
        .to_string();
    assert!(err.contains("below the base generation 3"), "{err}");
    // The largest live generation: removing the element retires the slot.
    let top = u32::MAX - 2;
    let mut big = json.clone();
    big["vertex_generations"][0] = serde_json::json!(top);
    let mut m: meshloom::Mesh = serde_json::from_value(big).unwrap();
    let old = m.vertices().next().unwrap();
    assert_eq!((old.index(), old.generation()), (0, top));
    let h = m.vertex(old).unwrap().halfedge().key();
    m.collapse_edge(h).unwrap();
    assert!(!m.contains_vertex(old));
    // New vertices never take slot 0, and no key of it resolves again.
    for _ in 0..4 {
        let e = m.edges().next().unwrap();
        let v = m.split_edge(e, 0.5).unwrap();
        assert_ne!(v.index(), 0);
    }
    assert!(m.vertex_at(0).is_none());
    for g in [top, u32::MAX, 0, 1] {
        let mut k = serde_json::to_value(old).unwrap();
        k["generation"] = serde_json::json!(g);
        let k: meshloom::VertexKey = serde_json::from_value(k).unwrap();
        assert!(!m.contains_vertex(k), "{k:?}");
    }
    // It survives another round trip retired.
    let mut back: meshloom::Mesh =
        serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
    let e = back.edges().next().unwrap();
    assert_ne!(back.split_edge(e, 0.5).unwrap().index(), 0);
    // Compaction cannot give this arena a base above u32::MAX - 2: the
    // vertex arena is left as it is (its keys stay valid), never reissued.
    let v = back.vertices().last().unwrap();
    let maps = back.compact();
    back.validate().unwrap();
    assert_eq!(maps.vertex(v), Some(v));
    assert!(back.contains_vertex(v));
}
