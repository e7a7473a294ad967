//! The order every merging operator passes its contributors in (issue 10,
//! defect 7): the surviving element first, as the `Rule` and `KeepFirst`
//! docs say. A recording rule turns the order into the merged value: the
//! merge of contributors with ids x, y, z is the number x·100² + y·100 + z.

use meshloom::attr::{Attr, Element, KeepFirst, Rule};
use meshloom::{shapes, EdgeKey, FaceKey, Mesh, VertexKey};

/// Records the order of the contributors of a merge (ids below 100; an
/// absent one counts as 0). A split piece keeps the source.
struct Order;

impl Rule<i64> for Order {
    fn merge(inputs: &[(Option<&i64>, f64)]) -> Option<i64> {
        Some(
            inputs
                .iter()
                .fold(0, |acc, (v, _)| acc * 100 + v.copied().unwrap_or(0)),
        )
    }

    fn split(source: Option<&i64>, _share: f64) -> Option<i64> {
        source.copied()
    }
}

/// The merged value of contributors in this order.
fn order(ids: &[i64]) -> i64 {
    ids.iter().fold(0, |acc, id| acc * 100 + id)
}

/// A column of ids 1, 2, 3, ... in slot order.
fn ids<K: Element>(m: &mut Mesh, name: &str, keys: Vec<K>) -> Attr<K, i64, Order> {
    let col = m.add_attr_with_rule::<K, i64, Order>(name).unwrap();
    for (i, k) in keys.into_iter().enumerate() {
        m.set_attr(&col, k, i as i64 + 1).unwrap();
    }
    col
}

fn id<K: Element>(m: &Mesh, col: &Attr<K, i64, Order>, k: K) -> i64 {
    *m.attr(col, k).unwrap().unwrap()
}

/// collapse_edge: `merge(b, a)`, the surviving `b` first. With `KeepFirst`
/// `b` keeps its own value (it kept `a`'s before the fix).
#[test]
fn collapse_passes_the_surviving_vertex_first() {
    for t in [None, Some(0.3)] {
        let mut m = shapes::icosahedron();
        let vs: Vec<VertexKey> = m.vertices().collect();
        let col = ids(&mut m, "id", vs);
        let keep = m
            .add_attr_with_rule::<VertexKey, i64, KeepFirst>("keep")
            .unwrap();
        let h = m.halfedges().next().unwrap();
        let (a, b) = (
            m.halfedge(h).unwrap().origin().key(),
            m.halfedge(h).unwrap().dest().key(),
        );
        let (ia, ib) = (id(&m, &col, a), id(&m, &col, b));
        m.set_attr(&keep, a, -1).unwrap();
        m.set_attr(&keep, b, 7).unwrap();
        let kept = match t {
            None => m.collapse_edge(h).unwrap(),
            Some(t) => m.collapse_edge_at(h, t).unwrap(),
        };
        assert_eq!(kept, b);
        assert_eq!(id(&m, &col, b), order(&[ib, ia]), "{t:?}");
        assert_eq!(m.attr(&keep, b).unwrap(), Some(&7), "{t:?}");
    }
}

/// collapse_edge where triangles disappear: each keeps its side at `b`,
/// which merges with its side at `a` (kept first), and the triangle's face
/// merges into the face that receives the kept side (that face first).
#[test]
fn collapse_passes_the_kept_side_and_face_first() {
    let mut m = shapes::icosahedron();
    let es: Vec<EdgeKey> = m.edges().collect();
    let fs: Vec<FaceKey> = m.faces().collect();
    let ecol = ids(&mut m, "eid", es);
    let fcol = ids(&mut m, "fid", fs);
    let h = m.halfedges().next().unwrap();
    let hv = m.halfedge(h).unwrap();
    let b = hv.dest().key();
    // Left triangle (a, b, c) on h, right triangle (b, a, d) on its twin:
    // each side at b, side at a, apex; the face across the side at a
    // receives the side at b.
    let t = hv.twin();
    let sides = [
        (hv, hv.next(), hv.next().next(), hv.next().dest()),
        (t, t.next().next(), t.next(), t.next().next().origin()),
    ];
    let mut expect = Vec::new();
    for (side, at_b, at_a, apex) in sides {
        let receiver = at_a.twin().face().key();
        expect.push((
            apex.key(),
            order(&[
                id(&m, &ecol, at_b.edge().key()),
                id(&m, &ecol, at_a.edge().key()),
            ]),
            receiver,
            order(&[id(&m, &fcol, receiver), id(&m, &fcol, side.face().key())]),
        ));
    }
    m.collapse_edge(h).unwrap();
    for (apex, edge_value, receiver, face_value) in expect {
        let kept = m.find_halfedge(b, apex).unwrap().unwrap();
        let e = m.halfedge(kept).unwrap().edge().key();
        assert_eq!(id(&m, &ecol, e), edge_value);
        assert_eq!(id(&m, &fcol, receiver), face_value);
    }
}

/// flip_edge: the faces merge as (face of the first half-edge, face of its
/// twin), then split.
#[test]
fn flip_passes_the_first_half_edges_face_first() {
    let mut m = shapes::icosahedron();
    let fs: Vec<FaceKey> = m.faces().collect();
    let col = ids(&mut m, "fid", fs);
    let e = m.edges().next().unwrap();
    let [f0, f1] = m.edge(e).unwrap().faces().map(Option::unwrap);
    let expected = order(&[id(&m, &col, f0), id(&m, &col, f1)]);
    m.flip_edge(e).unwrap();
    assert_eq!((id(&m, &col, f0), id(&m, &col, f1)), (expected, expected));
}

/// remove_edge keeps the face of the edge's first half-edge and passes it
/// first; merge_faces(f, g) passes f first.
#[test]
fn face_merges_pass_the_kept_face_first() {
    let mut m = shapes::cube();
    let fs: Vec<FaceKey> = m.faces().collect();
    let col = ids(&mut m, "fid", fs);
    let e = m.edges().next().unwrap();
    let [fl, fr] = m.edge(e).unwrap().faces().map(Option::unwrap);
    let expected = order(&[id(&m, &col, fl), id(&m, &col, fr)]);
    assert_eq!(m.remove_edge(e).unwrap(), fl);
    assert_eq!(id(&m, &col, fl), expected);

    let mut m = shapes::cube();
    let fs: Vec<FaceKey> = m.faces().collect();
    let col = ids(&mut m, "fid", fs);
    let f = m.faces().nth(2).unwrap();
    let g = m.face(f).unwrap().neighbors().next().unwrap();
    let expected = order(&[id(&m, &col, f), id(&m, &col, g)]);
    assert_eq!(m.merge_faces(f, g).unwrap(), f);
    assert_eq!(id(&m, &col, f), expected);
    // And the other way round: g first.
    let mut m = shapes::cube();
    let fs: Vec<FaceKey> = m.faces().collect();
    let col = ids(&mut m, "fid", fs);
    let expected = order(&[id(&m, &col, g), id(&m, &col, f)]);
    assert_eq!(m.merge_faces(g, f).unwrap(), g);
    assert_eq!(id(&m, &col, g), expected);
}

/// remove_vertex: the faces around the vertex in ring order, from the face
/// of its first outgoing half-edge (the kept one).
#[test]
fn remove_vertex_passes_the_ring_from_the_kept_face() {
    let mut m = shapes::cube();
    let f = m.faces().next().unwrap();
    let c = m.poke_face(f).unwrap();
    let fs: Vec<FaceKey> = m.faces().collect();
    let col = ids(&mut m, "fid", fs);
    let ring: Vec<FaceKey> = m.vertex(c).unwrap().faces().collect();
    assert_eq!(ring.len(), 4);
    let expected = order(&ring.iter().map(|&g| id(&m, &col, g)).collect::<Vec<_>>());
    let kept = m.remove_vertex(c).unwrap();
    assert_eq!(kept, ring[0]);
    assert_eq!(id(&m, &col, kept), expected);
}
