//! The journal against a model that keeps full snapshots: random streams of
//! every operator, attribute writes (typed, dynamic, bulk views, column
//! add/remove), raw edits and compaction under undo history; undo all,
//! redo all, random interleavings of undo/redo/new edits; transactions that
//! fail or panic at a random step; change sets against snapshot diffs.
//!
//! "Equal" (see the `journal` module docs): the same live keys of every
//! kind, the same links between them (origin, next, face of every
//! half-edge; each vertex's and face's half-edge; hole flags), the same
//! attribute columns (kind, name, type, order) with the same values on
//! every live element. Vacant slots, free-list order and slot counts may
//! differ.

mod common;
use common::ops::{self, nth, TopoOp};
use common::*;
use meshloom::algo::{self, decimate, smooth, subdivision, Progress};
use meshloom::attr::{Incompatible, Interpolate, Value};
use meshloom::journal::{ColumnChangeKind, HistoryLimits};
use meshloom::{shapes, AnyKey, EdgeKey, ElementKind, FaceKey, Mesh, VertexKey};
use quickcheck::{Arbitrary, Gen, QuickCheck, TestResult};
use std::collections::{BTreeMap, BTreeSet, HashSet};

/// One edit: an operator of the shared stream (`common::ops`, the same
/// generator as `ops_model.rs`), or an attribute write, a bulk write, a
/// column change, a raw edit or an algorithm run.
#[derive(Clone, Debug)]
enum Op {
    Topo(TopoOp),
    SetPosition(usize, i8),
    SetWeight(usize, i8),
    ClearWeight(usize),
    SetLabel(usize, u8),
    BulkMove(i8),
    ViewWrite(i8),
    AddColumn,
    RemoveColumn,
    RawRepoint(usize),
    Smooth,
    Decimate(u8),
    Subdivide(u8),
    Remesh,
    FillHoles,
    Fair,
    Normals(u8),
}

impl Arbitrary for Op {
    fn arbitrary(g: &mut Gen) -> Op {
        let i = usize::arbitrary(g);
        let t = u8::arbitrary(g) % 11;
        let d = i8::arbitrary(g);
        match u8::arbitrary(g) % 37 {
            0..=21 => Op::Topo(TopoOp::arbitrary(g)),
            22..=23 => Op::SetPosition(i, d),
            24..=25 => Op::SetWeight(i, d),
            26 => Op::ClearWeight(i),
            27 => Op::SetLabel(i, t),
            28 => Op::BulkMove(d),
            29 => Op::ViewWrite(d),
            30 => Op::AddColumn,
            31 => Op::RemoveColumn,
            32 => Op::Smooth,
            33 => Op::Decimate(t),
            34 => match u8::arbitrary(g) % 6 {
                0 => Op::Remesh,
                1 => Op::FillHoles,
                2 => Op::Fair,
                3 => Op::Normals(t),
                _ => Op::Subdivide(t),
            },
            _ => Op::RawRepoint(i),
        }
    }
}

fn shape(i: u8) -> Mesh {
    let mut m = match i % 6 {
        0 => one_ring(),
        1 => l_shape(),
        2 => quad_grid(3),
        3 => shapes::cube(),
        4 => shapes::icosahedron(),
        _ => open_cone(),
    };
    let w = m.add_vertex_attr::<f64>("weight").unwrap();
    let vs: Vec<_> = m.vertices().collect();
    for (n, v) in vs.into_iter().enumerate() {
        if n % 3 != 0 {
            m.set_attr(&w, v, n as f64).unwrap();
        }
    }
    m.add_face_attr::<u32>("label").unwrap();
    add_every_rule(&mut m);
    m
}

/// A custom rule as a Python rule object would be: not linear, reads every
/// contributor and its weight, and splits by building a new value.
struct Joined;

/// The value of the custom rule's columns (portable as text, so the
/// snapshot compares it like any other column).
#[derive(Clone, Debug, Default, PartialEq)]
struct Tag(String);

impl meshloom::attr::Rule<Tag> for Joined {
    fn merge(inputs: &[(Option<&Tag>, f64)]) -> Option<Tag> {
        let parts: Vec<String> = inputs
            .iter()
            .map(|(v, w)| format!("{}*{w}", v.map_or("-", |t| t.0.as_str())))
            .collect();
        Some(Tag(digest(&format!("({})", parts.join("+")))))
    }

    fn split(source: Option<&Tag>, share: f64) -> Option<Tag> {
        source.map(|t| Tag(digest(&format!("{}/{share}", t.0))))
    }
}

/// A value made from every contributor, of bounded length: a streamed
/// test runs subdivisions one after another, and a value that held its
/// inputs' text whole grew by the faces' degree at each level (it ran
/// the test out of memory).
fn digest(text: &str) -> String {
    if text.len() <= 48 {
        return text.to_string();
    }
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
    }
    format!("#{h:016x}")
}

impl meshloom::attr::Attribute for Tag {
    type Rule = Joined;

    fn to_value(&self) -> Option<Value> {
        Some(Value::Text(self.0.clone()))
    }

    fn from_value(value: &Value) -> Option<Self> {
        match value {
            Value::Text(s) => Some(Tag(s.clone())),
            _ => None,
        }
    }
}

/// Columns of every element kind under every stock rule and a custom one,
/// with a distinct value on every element (some left absent), so a value
/// restored to the wrong slot, or not restored, shows in the snapshot.
fn add_every_rule(m: &mut Mesh) {
    use meshloom::attr::{Conserved, Contagion, Discard, KeepFirst};
    use meshloom::HalfedgeKey;
    let hs: Vec<HalfedgeKey> = m.halfedges().collect();
    let es: Vec<EdgeKey> = m.edges().collect();
    let fs: Vec<FaceKey> = m.faces().collect();
    let vs: Vec<VertexKey> = m.vertices().collect();
    let uv = m.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let corner = m
        .add_attr_with_rule::<HalfedgeKey, u32, KeepFirst>("corner")
        .unwrap();
    let htag = m.add_halfedge_attr::<Tag>("corner_tag").unwrap();
    for (n, &h) in hs.iter().enumerate() {
        m.set_attr(&uv, h, [n as f64, 0.5 * n as f64]).unwrap();
        if n % 4 != 1 {
            m.set_attr(&corner, h, n as u32).unwrap();
        }
        m.set_attr(&htag, h, Tag(format!("h{n}"))).unwrap();
    }
    let seam = m
        .add_attr_with_rule::<EdgeKey, bool, Contagion>("seam")
        .unwrap();
    let length = m
        .add_attr_with_rule::<EdgeKey, f64, Conserved>("length")
        .unwrap();
    let etag = m.add_edge_attr::<Tag>("edge_tag").unwrap();
    for (n, &e) in es.iter().enumerate() {
        m.set_attr(&seam, e, n % 3 == 0).unwrap();
        m.set_attr(&length, e, 1.0 + n as f64).unwrap();
        m.set_attr(&etag, e, Tag(format!("e{n}"))).unwrap();
    }
    let material = m
        .add_attr_with_rule::<FaceKey, u32, KeepFirst>("material")
        .unwrap();
    let area = m
        .add_attr_with_rule::<FaceKey, f64, Conserved>("area")
        .unwrap();
    let scratch = m
        .add_attr_with_rule::<FaceKey, f32, Discard>("scratch")
        .unwrap();
    let ftag = m.add_face_attr::<Tag>("face_tag").unwrap();
    for (n, &f) in fs.iter().enumerate() {
        m.set_attr(&material, f, n as u32).unwrap();
        m.set_attr(&area, f, 0.25 * n as f64).unwrap();
        m.set_attr(&scratch, f, n as f32).unwrap();
        m.set_attr(&ftag, f, Tag(format!("f{n}"))).unwrap();
    }
    let mass = m
        .add_attr_with_rule::<VertexKey, f64, Conserved>("mass")
        .unwrap();
    let selected = m
        .add_attr_with_rule::<VertexKey, bool, Contagion>("selected")
        .unwrap();
    let vtag = m.add_vertex_attr::<Tag>("vertex_tag").unwrap();
    for (n, &v) in vs.iter().enumerate() {
        m.set_attr(&mass, v, n as f64).unwrap();
        m.set_attr(&selected, v, n % 2 == 0).unwrap();
        m.set_attr(&vtag, v, Tag(format!("v{n}"))).unwrap();
    }
}

/// Apply one op; errors are fine (a refused op must change nothing, which
/// the model checks through the undo length).
fn apply(m: &mut Mesh, op: &Op) {
    match *op {
        Op::Topo(ref t) => {
            let _ = ops::apply(m, t);
        }
        Op::Smooth => {
            // An algorithm run: one undo unit.
            let _ = smooth::smooth(m, &smooth::SmoothOptions::default(), Progress::none());
        }
        Op::Decimate(t) => {
            // Decimation in place (no progress callback): one undo unit.
            let target = m.vertex_count() * usize::from(t) / 10;
            let _ = decimate::decimate(
                m,
                &decimate::DecimateOptions::to(decimate::Target::Vertices(target)),
                Progress::none(),
            );
        }
        Op::Subdivide(t) => {
            // Small meshes only: a level multiplies the faces by 3 or 4.
            if m.face_count() <= 64 {
                let options = subdivision::SubdivisionOptions::default();
                let _ = match t % 4 {
                    0 => algo::loop_subdivide(m, &options, Progress::none()),
                    1 => algo::catmull_clark(m, &options, Progress::none()),
                    2 => algo::sqrt3_subdivide(m, &options, Progress::none()),
                    _ => algo::midpoint_subdivide(
                        m,
                        &algo::MidpointOptions::default(),
                        Progress::none(),
                    ),
                };
            }
        }
        Op::Remesh => {
            if m.face_count() <= 64 {
                let options = algo::RemeshOptions::default().iterations(2);
                let _ = algo::remesh(m, &options, Progress::none());
            }
        }
        Op::FillHoles => {
            let _ = algo::fill_holes(m, &algo::FillHoleOptions::default(), Progress::none());
        }
        Op::Fair => {
            let _ = algo::fair::fair(m, &algo::fair::FairOptions::default(), Progress::none());
        }
        Op::Normals(t) => {
            let _ = match t % 3 {
                0 => algo::add_face_normals(m).map(drop),
                1 => algo::add_vertex_normals(m, &algo::VertexNormalOptions::default()).map(drop),
                _ => algo::add_corner_normals(m, &algo::CornerNormalOptions::default()).map(drop),
            };
        }
        Op::SetPosition(i, d) => {
            if let Some(v) = nth(m.vertices(), m.vertex_count(), i) {
                let p = m.position(v).unwrap();
                let _ = m.set_position(v, [p[0] + f64::from(d), p[1], p[2]]);
            }
        }
        Op::SetWeight(i, d) => {
            if let (Some(v), Ok(w)) = (
                nth(m.vertices(), m.vertex_count(), i),
                m.attr_handle::<VertexKey, f64, Interpolate>("weight"),
            ) {
                let _ = m.set_attr(&w, v, f64::from(d));
            }
        }
        Op::ClearWeight(i) => {
            if let (Some(v), Ok(w)) = (
                nth(m.vertices(), m.vertex_count(), i),
                m.attr_handle::<VertexKey, f64, Interpolate>("weight"),
            ) {
                let _ = m.clear_attr(&w, v);
            }
        }
        Op::SetLabel(i, t) => {
            if let Some(f) = nth(m.faces(), m.face_count(), i) {
                let _ = m.set_attr_value("label", f, Some(&Value::U32(u32::from(t))));
            }
        }
        Op::BulkMove(d) => {
            let live: Vec<usize> = m.vertices().map(|v| v.index()).collect();
            if let Some(p) = m.position_slots_mut() {
                for (n, i) in live.into_iter().enumerate() {
                    if n % 2 == 0 {
                        p[i][1] += f64::from(d);
                    }
                }
            }
        }
        Op::ViewWrite(d) => {
            if let Ok(w) = m.attr_handle::<VertexKey, f64, Interpolate>("weight") {
                let mut view = m.attr_view_mut(&w).unwrap();
                for (n, (_, x)) in view.iter_mut().enumerate() {
                    if n % 2 == 1 {
                        *x += f64::from(d);
                    }
                }
            }
        }
        Op::AddColumn => {
            // Two edits as one named unit.
            let _ = m.step("Add crease", |m| {
                let c = m.add_edge_attr::<i32>("crease")?;
                let first = m.edges().next();
                if let Some(e) = first {
                    m.set_attr(&c, e, 7)?;
                }
                Ok(())
            });
        }
        Op::RemoveColumn => {
            if let Ok(c) = m.attr_handle::<EdgeKey, i32, Incompatible>("crease") {
                m.remove_attr(&c).unwrap();
            } else if let Ok(w) = m.attr_handle::<VertexKey, f64, Interpolate>("weight") {
                m.remove_attr(&w).unwrap();
            }
        }
        Op::RawRepoint(i) => {
            // A user operator: point a vertex at another outgoing half-edge.
            if let Some(v) = nth(m.vertices(), m.vertex_count(), i) {
                let outs: Vec<_> = m.vertex(v).unwrap().outgoing().collect();
                let h = outs[i % outs.len()];
                let mut edit = m.raw_edit();
                edit.set_vertex_halfedge(v, h).unwrap();
                edit.finish().unwrap();
            }
        }
    }
}

/// The canonical form "equal" compares (see the file docs).
#[derive(Clone, Debug, PartialEq)]
struct Canon {
    halfedges: Vec<(u64, u64, u64, u64)>,
    vertices: Vec<(VertexKey, u64)>,
    edges: Vec<EdgeKey>,
    faces: Vec<(FaceKey, u64, bool)>,
    attrs: Vec<ColumnCanon>,
}

/// A column: kind, name, declared type, value per live element.
type ColumnCanon = (ElementKind, String, String, BTreeMap<String, Option<Value>>);

fn hk(k: meshloom::HalfedgeKey) -> u64 {
    (k.index() as u64) << 32 | u64::from(k.generation())
}

fn canon(m: &Mesh) -> Canon {
    m.validate().unwrap();
    let mut attrs = Vec::new();
    for kind in [
        ElementKind::Vertex,
        ElementKind::Halfedge,
        ElementKind::Edge,
        ElementKind::Face,
    ] {
        for info in m.attr_info(kind) {
            let keys: Vec<AnyKey> = match kind {
                ElementKind::Vertex => m.vertices().map(AnyKey::Vertex).collect(),
                ElementKind::Halfedge => m.halfedges().map(AnyKey::Halfedge).collect(),
                ElementKind::Edge => m.edges().map(AnyKey::Edge).collect(),
                ElementKind::Face => m.faces_and_holes().map(AnyKey::Face).collect(),
            };
            let values = keys
                .into_iter()
                .map(|k| (format!("{k:?}"), m.attr_value_at(&info.name, k).unwrap()))
                .collect();
            attrs.push((
                kind,
                info.name.clone(),
                format!("{:?}", info.value_type),
                values,
            ));
        }
    }
    Canon {
        halfedges: m
            .halfedges()
            .map(|h| {
                let v = m.halfedge(h).unwrap();
                let o = v.origin().key();
                let f = v.face().key();
                (
                    hk(h),
                    (o.index() as u64) << 32 | u64::from(o.generation()),
                    hk(v.next().key()),
                    (f.index() as u64) << 32 | u64::from(f.generation()),
                )
            })
            .collect(),
        vertices: m
            .vertices()
            .map(|v| (v, hk(m.vertex(v).unwrap().halfedge().key())))
            .collect(),
        edges: m.edges().collect(),
        faces: m
            .faces_and_holes()
            .map(|f| {
                let view = m.face(f).unwrap();
                (f, hk(view.halfedge().key()), view.is_hole())
            })
            .collect(),
        attrs,
    }
}

/// Every key live in `c`.
fn keys_of(c: &Canon) -> HashSet<AnyKey> {
    let mut s = HashSet::new();
    s.extend(c.vertices.iter().map(|v| AnyKey::Vertex(v.0)));
    s.extend(c.edges.iter().map(|&e| AnyKey::Edge(e)));
    s.extend(c.faces.iter().map(|f| AnyKey::Face(f.0)));
    s
}

#[derive(Clone, Debug)]
enum Act {
    Edit(Op),
    Undo,
    Redo,
}

impl Arbitrary for Act {
    fn arbitrary(g: &mut Gen) -> Act {
        match u8::arbitrary(g) % 8 {
            0 | 1 => Act::Undo,
            2 => Act::Redo,
            _ => Act::Edit(Op::arbitrary(g)),
        }
    }
}

#[derive(Clone, Debug)]
struct Case {
    shape: u8,
    acts: Vec<Act>,
}

impl Arbitrary for Case {
    fn arbitrary(g: &mut Gen) -> Case {
        Case {
            shape: u8::arbitrary(g),
            acts: (0..(usize::arbitrary(g) % 30 + 1))
                .map(|_| Act::arbitrary(g))
                .collect(),
        }
    }

    fn shrink(&self) -> Box<dyn Iterator<Item = Case>> {
        let shape = self.shape;
        Box::new(self.acts.shrink().map(move |acts| Case { shape, acts }))
    }
}

/// One edit under the journal: either it recorded exactly one unit and the
/// redo branch is gone, or it changed nothing.
fn edit(m: &mut Mesh, op: &Op, before: &Canon) -> Option<Canon> {
    let n = m.history().undo_len();
    apply(m, op);
    m.history_mut().commit_writes();
    let after = canon(m);
    match m.history().undo_len() {
        k if k == n => {
            assert_eq!(
                &after, before,
                "{op:?} changed the mesh but recorded nothing"
            );
            None
        }
        k => {
            assert_eq!(k, n + 1, "{op:?} recorded {} units", k - n);
            assert_eq!(m.history().redo_len(), 0, "{op:?} kept the redo branch");
            Some(after)
        }
    }
}

#[test]
fn undo_all_and_redo_all_restore_the_snapshots() {
    fn prop(shape: u8, ops: Vec<Op>) -> TestResult {
        let mut m = shape_with_history(shape);
        let mut states = vec![canon(&m)];
        for op in &ops {
            let before = states.last().unwrap().clone();
            if let Some(c) = edit(&mut m, op, &before) {
                states.push(c);
            }
        }
        let final_keys = keys_of(states.last().unwrap());
        // Undo all: every intermediate state, back to the start.
        for s in states.iter().rev().skip(1) {
            assert!(m.undo());
            assert_eq!(&canon(&m), s);
        }
        assert!(!m.undo());
        // Keys only the undone edits created are stale.
        for k in final_keys.difference(&keys_of(&states[0])) {
            assert!(!live(&m, *k), "{k:?} still valid after undo all");
        }
        // Redo all: every state again, with the same keys.
        for s in states.iter().skip(1) {
            assert!(m.redo());
            assert_eq!(&canon(&m), s);
        }
        assert!(!m.redo());
        TestResult::passed()
    }
    QuickCheck::new()
        .tests(150)
        .quickcheck(prop as fn(u8, Vec<Op>) -> TestResult);
}

fn shape_with_history(shape_i: u8) -> Mesh {
    let mut m = shape(shape_i);
    m.history_mut().enable(HistoryLimits::default());
    m
}

fn live(m: &Mesh, k: AnyKey) -> bool {
    match k {
        AnyKey::Vertex(v) => m.vertex(v).is_ok(),
        AnyKey::Edge(e) => m.edge(e).is_ok(),
        AnyKey::Face(f) => m.face(f).is_ok(),
        AnyKey::Halfedge(h) => m.halfedge(h).is_ok(),
    }
}

#[test]
fn interleaved_undo_redo_and_edits_agree_with_the_snapshot_model() {
    fn prop(case: Case) -> TestResult {
        let mut m = shape_with_history(case.shape);
        let mut undo = vec![canon(&m)];
        let mut redo: Vec<Canon> = Vec::new();
        // Keys that went stale with a dropped redo branch: never valid again.
        let mut forbidden: HashSet<AnyKey> = HashSet::new();
        for act in &case.acts {
            match act {
                Act::Edit(op) => {
                    let before = undo.last().unwrap().clone();
                    if let Some(c) = edit(&mut m, op, &before) {
                        let now = keys_of(&c);
                        for s in redo.drain(..) {
                            forbidden.extend(keys_of(&s).difference(&now));
                        }
                        for s in &undo {
                            forbidden.extend(keys_of(s).difference(&now));
                        }
                        // Keys of the kept history may come back by undo.
                        for s in &undo {
                            for k in keys_of(s) {
                                forbidden.remove(&k);
                            }
                        }
                        undo.push(c);
                    }
                }
                Act::Undo => {
                    if undo.len() > 1 {
                        assert!(m.undo());
                        redo.push(undo.pop().unwrap());
                    } else {
                        assert!(!m.undo());
                    }
                }
                Act::Redo => {
                    if let Some(c) = redo.pop() {
                        assert!(m.redo());
                        undo.push(c);
                    } else {
                        assert!(!m.redo());
                    }
                }
            }
            let c = canon(&m);
            assert_eq!(&c, undo.last().unwrap(), "after {act:?}");
            assert_eq!(
                (m.history().undo_len(), m.history().redo_len()),
                (undo.len() - 1, redo.len())
            );
            for k in keys_of(&c) {
                assert!(
                    !forbidden.contains(&k),
                    "{k:?} came back after its edit was dropped"
                );
            }
        }
        TestResult::passed()
    }
    QuickCheck::new()
        .tests(200)
        .quickcheck(prop as fn(Case) -> TestResult);
}

#[test]
fn failing_or_panicking_transactions_leave_the_snapshot() {
    fn prop(shape_i: u8, ops: Vec<Op>, fail_at: usize, panic: bool, history: bool) -> TestResult {
        let mut m = shape(shape_i);
        if history {
            m.history_mut().enable(HistoryLimits::default());
            apply(&mut m, &Op::Topo(TopoOp::Poke(0)));
            // A redo branch, which a failed transaction must keep.
            apply(&mut m, &Op::Topo(TopoOp::Poke(1)));
            m.undo();
        }
        let before = canon(&m);
        let undo_len = m.history().undo_len();
        let redo_len = m.history().redo_len();
        let stop = fail_at % (ops.len() + 1);
        let run = |m: &mut Mesh| {
            m.transaction(|m| {
                for (n, op) in ops.iter().enumerate() {
                    if n == stop {
                        break;
                    }
                    apply(m, op);
                    // A nested transaction that commits.
                    if n % 3 == 0 {
                        m.transaction(|m| {
                            apply(m, &Op::Topo(TopoOp::SplitEdge(n, 5)));
                            Ok(())
                        })?;
                    }
                }
                if panic {
                    panic!("the tool crashed");
                }
                Err::<(), _>(meshloom::Error::Cancelled { algorithm: "tool" })
            })
        };
        if panic {
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run(&mut m)));
            assert!(r.is_err());
        } else {
            assert!(run(&mut m).is_err());
        }
        assert!(!m.history().in_transaction());
        assert_eq!(canon(&m), before);
        assert_eq!(m.history().undo_len(), undo_len);
        assert_eq!(
            m.history().redo_len(),
            redo_len,
            "a failed transaction changed the redo branch"
        );
        if redo_len > 0 {
            // The kept branch still redoes, and undoes back.
            assert!(m.redo());
            assert!(m.undo());
            assert_eq!(canon(&m), before);
        }
        assert_eq!(m.history().enabled(), history);
        // The mesh goes on working: a committed transaction is one unit.
        let r = m.transaction(|m| {
            apply(m, &Op::Topo(TopoOp::Poke(1)));
            apply(m, &Op::Topo(TopoOp::SplitEdge(2, 3)));
            Ok(7)
        });
        assert_eq!(r.unwrap(), 7);
        if history && canon(&m) != before {
            assert_eq!(m.history().undo_len(), undo_len + 1);
            assert!(m.undo());
            assert_eq!(canon(&m), before);
        }
        TestResult::passed()
    }
    std::panic::set_hook(Box::new(|_| {}));
    QuickCheck::new()
        .tests(150)
        .quickcheck(prop as fn(u8, Vec<Op>, usize, bool, bool) -> TestResult);
    let _ = std::panic::take_hook();
}

/// The vertex loop of every live face, by key.
fn loops(m: &Mesh) -> BTreeMap<FaceKey, Vec<VertexKey>> {
    m.faces_and_holes()
        .map(|f| (f, m.face(f).unwrap().vertices().collect()))
        .collect()
}

fn positions(m: &Mesh) -> BTreeMap<VertexKey, Option<Value>> {
    m.vertices()
        .map(|v| (v, m.attr_value_at("position", AnyKey::Vertex(v)).unwrap()))
        .collect()
}

#[test]
fn change_sets_agree_with_snapshot_diffs() {
    fn check<K: Ord + Copy + std::fmt::Debug>(
        what: &str,
        before: &BTreeSet<K>,
        after: &BTreeSet<K>,
        ch: &meshloom::journal::ElementChanges<K>,
    ) {
        let created: BTreeSet<K> = after.difference(before).copied().collect();
        let removed: BTreeSet<K> = before.difference(after).copied().collect();
        assert_eq!(
            ch.created.iter().copied().collect::<BTreeSet<_>>(),
            created,
            "{what} created"
        );
        assert_eq!(
            ch.removed.iter().copied().collect::<BTreeSet<_>>(),
            removed,
            "{what} removed"
        );
        for k in &ch.modified {
            assert!(
                before.contains(k) && after.contains(k),
                "{what} modified {k:?} is not live at both"
            );
        }
    }
    fn prop(case: Case) -> TestResult {
        let mut m = shape_with_history(case.shape);
        m.history_mut().track_changes(true);
        for act in &case.acts {
            let (c0, l0, p0) = (canon(&m), loops(&m), positions(&m));
            match act {
                Act::Edit(op) => apply(&mut m, op),
                Act::Undo => {
                    m.undo();
                }
                Act::Redo => {
                    m.redo();
                }
            }
            let ch = m.history_mut().take_changes();
            let (c1, l1, p1) = (canon(&m), loops(&m), positions(&m));
            if ch.rebuilt {
                continue;
            }
            let vs = |c: &Canon| c.vertices.iter().map(|v| v.0).collect::<BTreeSet<_>>();
            let es = |c: &Canon| c.edges.iter().copied().collect::<BTreeSet<_>>();
            let fs = |c: &Canon| c.faces.iter().map(|f| f.0).collect::<BTreeSet<_>>();
            check("vertex", &vs(&c0), &vs(&c1), &ch.vertices);
            check("edge", &es(&c0), &es(&c1), &ch.edges);
            check("face", &fs(&c0), &fs(&c1), &ch.faces);
            // Every face whose loop changed and every vertex that moved is
            // reported modified.
            let mf: BTreeSet<_> = ch.faces.modified.iter().copied().collect();
            for (f, l) in &l1 {
                if let Some(l_before) = l0.get(f) {
                    if l_before != l {
                        assert!(mf.contains(f), "face {f:?} changed its loop, not reported");
                    }
                }
            }
            let mv: BTreeSet<_> = ch.vertices.modified.iter().copied().collect();
            for (v, p) in &p1 {
                if p0.get(v).is_some_and(|q| q != p) {
                    assert!(mv.contains(v), "vertex {v:?} moved, not reported");
                }
            }
            // Columns: created, removed, or with a changed value: reported.
            let cols = |c: &Canon| {
                c.attrs
                    .iter()
                    .map(|a| ((a.0 as u8, a.1.clone()), a.3.clone()))
                    .collect::<BTreeMap<_, _>>()
            };
            let (a0, a1) = (cols(&c0), cols(&c1));
            for (k, v) in &a1 {
                let want = match a0.get(k) {
                    None => Some(ColumnChangeKind::Created),
                    Some(w) if w != v => {
                        // Values of elements live at both that differ.
                        let differs = v.iter().any(|(e, x)| w.get(e).is_some_and(|y| y != x));
                        differs.then_some(ColumnChangeKind::Modified)
                    }
                    _ => None,
                };
                if let Some(want) = want {
                    assert!(
                        ch.columns
                            .iter()
                            .any(|c| c.kind as u8 == k.0 && c.name == k.1 && c.change == want),
                        "column {k:?} {want:?} not reported: {:?}",
                        ch.columns
                    );
                }
            }
            for k in a0.keys() {
                if !a1.contains_key(k) {
                    assert!(ch.columns.iter().any(|c| c.kind as u8 == k.0
                        && c.name == k.1
                        && c.change == ColumnChangeKind::Removed));
                }
            }
            if c0 == c1 {
                assert!(ch.vertices.created.is_empty() && ch.faces.removed.is_empty());
            }
        }
        TestResult::passed()
    }
    QuickCheck::new()
        .tests(150)
        .quickcheck(prop as fn(Case) -> TestResult);
}

#[test]
fn named_steps_limits_and_clearing() {
    let mut m = shape_with_history(3);
    let f = m.faces().next().unwrap();
    m.history_mut().begin_step("Bevel");
    m.poke_face(f).unwrap();
    let e = m.edges().next().unwrap();
    m.split_edge(e, 0.5).unwrap();
    m.history_mut().end_step();
    assert_eq!(
        (m.history().undo_len(), m.history().undo_name()),
        (1, Some("Bevel"))
    );
    let v = m.vertex_count();
    assert!(m.undo());
    assert_eq!(m.vertex_count(), v - 2);
    assert_eq!(m.history().redo_name(), Some("Bevel"));
    assert!(m.redo());
    assert_eq!(m.vertex_count(), v);
    // Depth limit: only the last three units stay.
    m.history_mut().enable(HistoryLimits {
        max_steps: Some(3),
        max_bytes: None,
    });
    for i in 0..6 {
        let e = m.edges().nth(i).unwrap();
        m.split_edge(e, 0.5).unwrap();
    }
    assert_eq!(m.history().undo_len(), 3);
    while m.undo() {}
    assert_eq!(m.vertex_count(), v + 3);
    // Memory limit.
    m.history_mut().enable(HistoryLimits {
        max_steps: None,
        max_bytes: Some(200),
    });
    for i in 0..20 {
        let e = m.edges().nth(i).unwrap();
        m.split_edge(e, 0.5).unwrap();
    }
    assert!(m.history().bytes() < 200 + 4096, "{}", m.history().bytes());
    assert!(m.history().undo_len() < 20 && m.history().undo_len() >= 1);
    m.history_mut().clear();
    assert_eq!((m.history().undo_len(), m.history().redo_len()), (0, 0));
    assert!(!m.undo());
    m.history_mut().disable();
    assert!(!m.history().enabled());
    let e = m.edges().next().unwrap();
    m.split_edge(e, 0.5).unwrap();
    assert!(!m.undo());
}

#[test]
fn serde_and_clone_of_a_journaled_mesh_carry_no_history() {
    let mut m = shape_with_history(4);
    let f = m.faces().next().unwrap();
    m.poke_face(f).unwrap();
    assert!(m.undo());
    let mut c = m.clone();
    assert!(!c.history().enabled() && !c.redo());
    assert_eq!(canon(&c), canon(&m));
    // The slot the undo held for a redo is free in the copy: a new edit
    // reuses it, at a generation that keeps the undone key stale.
    let f2 = c.faces().next().unwrap();
    c.poke_face(f2).unwrap();
    c.validate().unwrap();
    #[cfg(feature = "serde")]
    {
        let json = serde_json::to_string(&m).unwrap();
        let back: Mesh = serde_json::from_str(&json).unwrap();
        assert!(!back.history().enabled());
        assert_eq!(canon(&back), canon(&m));
    }
    assert!(m.redo());
}

/// The fresh floor an undo raised travels with the serde form: a key of an
/// element an undo took back stays stale in the deserialised copy, even
/// when the copy reuses the same slot.
#[cfg(feature = "serde")]
#[test]
fn serde_keeps_the_fresh_floor_so_undone_keys_stay_stale() {
    let mut m = shapes::icosahedron();
    m.history_mut().enable(HistoryLimits::default());
    let v = m.vertices().next().unwrap();
    m.remove_vertex(v).unwrap();
    let f = m.faces().next().unwrap();
    // The poke takes the slot the removal freed (the free list's top).
    let c = m.poke_face(f).unwrap();
    assert_eq!(c.index(), v.index());
    assert!(m.undo() && m.undo());
    assert!(m.vertex(v).is_ok() && m.vertex(c).is_err());
    let json = serde_json::to_string(&m).unwrap();
    let mut back: Mesh = serde_json::from_str(&json).unwrap();
    // The same edits again in the copy: the slot is reused once more, and
    // the key the undone poke issued must not name the new vertex.
    back.remove_vertex(v).unwrap();
    let f = back.faces().next().unwrap();
    let c2 = back.poke_face(f).unwrap();
    assert_eq!(c2.index(), v.index());
    assert_ne!(c2, c);
    assert!(back.vertex(c).is_err(), "an undone key names a new vertex");
    // Without an undo the floor stays the base and the form is unchanged.
    let plain = shapes::icosahedron();
    assert!(!serde_json::to_string(&plain).unwrap().contains("fresh"));
}

/// An algorithm run is one undo unit named after it (decimation in place
/// used to be one step per collapse); a composite operator is one unit.
#[test]
fn an_algorithm_run_is_one_named_unit() {
    use meshloom::shapes::{grid, GridFaces};
    let mut m = grid(12, 12, GridFaces::Triangles);
    m.history_mut().enable(HistoryLimits::default());
    let start = canon(&m);
    let n0 = m.vertex_count();
    let options = decimate::DecimateOptions::to(decimate::Target::Vertices(n0 / 3));
    decimate::decimate(&mut m, &options, Progress::none()).unwrap();
    assert!(
        m.vertex_count() < n0 / 2,
        "{} of {n0} left",
        m.vertex_count()
    );
    assert_eq!(
        (m.history().undo_len(), m.history().undo_name()),
        (1, Some("Decimate"))
    );
    let decimated = canon(&m);
    smooth::smooth(&mut m, &smooth::SmoothOptions::default(), Progress::none()).unwrap();
    assert_eq!(
        (m.history().undo_len(), m.history().undo_name()),
        (2, Some("Smooth"))
    );
    assert!(m.undo());
    assert_eq!(canon(&m), decimated);
    assert!(m.undo());
    assert_eq!(canon(&m), start);
    assert!(m.redo() && m.redo());
    // Inside a group of the caller's, the group's name wins.
    m.step("Tidy", |m| {
        smooth::smooth(m, &smooth::SmoothOptions::default(), Progress::none())
    })
    .unwrap();
    assert_eq!(
        (m.history().undo_len(), m.history().undo_name()),
        (3, Some("Tidy"))
    );

    let mut q = quad_grid(4);
    q.history_mut().enable(HistoryLimits::default());
    let before = canon(&q);
    assert!(q.triangulate_all().is_empty());
    assert_eq!(q.history().undo_len(), 1);
    assert!(q.undo());
    assert_eq!(canon(&q), before);
}

/// Slots born and removed inside one open step (and reused there) record
/// no events: undo, redo, a rollback and a later edit must still restore
/// the exact links and keys, and keep every key of theirs stale.
#[test]
fn slots_born_and_removed_in_one_step_undo_and_redo_exactly() {
    let mut m = shapes::icosahedron();
    m.history_mut().enable(HistoryLimits::default());
    m.history_mut().track_changes(true);
    let before = canon(&m);
    let faces: Vec<FaceKey> = m.faces().take(6).collect();
    let mut gone = Vec::new();
    let mut kept = Vec::new();
    m.history_mut().begin_step("Churn");
    for (i, &f) in faces.iter().enumerate() {
        let c = m.poke_face(f).unwrap();
        if i % 3 != 2 {
            // Collapse the centre back: its vertex, three edges and two
            // faces were born in this step and die in it; the next poke
            // reuses their slots.
            let h = m.vertex(c).unwrap().halfedge().key();
            m.collapse_edge(h).unwrap();
            gone.push(c);
        } else {
            kept.push(c);
        }
    }
    m.history_mut().end_step();
    let after = canon(&m);
    let changes = m.history_mut().take_changes();
    assert_eq!(changes.vertices.created, kept);
    assert_eq!(m.vertex_count(), 12 + kept.len());
    for round in 0..2 {
        assert!(m.undo(), "round {round}");
        assert_eq!(canon(&m), before);
        assert!(gone.iter().chain(&kept).all(|&v| m.vertex(v).is_err()));
        let undone = m.history_mut().take_changes();
        assert_eq!(undone.vertices.removed, kept);
        assert!(undone.vertices.created.is_empty());
        assert!(m.redo(), "round {round}");
        assert_eq!(canon(&m), after);
        assert!(kept.iter().all(|&v| m.vertex(v).is_ok()));
        assert!(gone.iter().all(|&v| m.vertex(v).is_err()));
        assert_eq!(m.history_mut().take_changes().vertices.created, kept);
    }
    // A rolled-back transaction of the same kind changes nothing.
    let r: Result<(), meshloom::Error> = m.transaction(|m| {
        let f = m.faces().next().unwrap();
        let c = m.poke_face(f)?;
        let h = m.vertex(c)?.halfedge().key();
        m.collapse_edge(h)?;
        m.poke_face(f)?;
        Err(meshloom::Error::Cancelled { algorithm: "test" })
    });
    assert!(r.is_err());
    assert_eq!(canon(&m), after);
    // Undo, then a new edit: the held slots go back to the free list, and
    // no key handed out before comes back.
    assert!(m.undo());
    let mut fresh = Vec::new();
    m.history_mut().begin_step("Again");
    for f in m.faces().take(4).collect::<Vec<_>>() {
        fresh.push(m.poke_face(f).unwrap());
    }
    m.history_mut().end_step();
    assert!(fresh.iter().all(|v| !gone.contains(v) && !kept.contains(v)));
    m.validate().unwrap();
    assert!(m.undo());
    assert_eq!(canon(&m), before);
}

/// The defect the snapshot test missed while it held no corner column: a
/// collapse merges and copies corner values, and undo (or a failed
/// transaction) must put every corner's own value back.
#[test]
fn collapse_then_undo_or_rollback_restores_every_corner_value() {
    let setup = || {
        let mut m = shapes::cube();
        let uv = m.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
        let hs: Vec<_> = m.halfedges().collect();
        for (n, &h) in hs.iter().enumerate() {
            m.set_attr(&uv, h, [n as f64, 0.0]).unwrap();
        }
        (m, uv, hs)
    };
    let values = |m: &Mesh, uv: &meshloom::attr::HalfedgeAttr<[f64; 2]>, hs: &[_]| {
        hs.iter()
            .map(|&h| m.attr(uv, h).unwrap().copied())
            .collect::<Vec<_>>()
    };
    // Undo.
    let (mut m, uv, hs) = setup();
    let before = values(&m, &uv, &hs);
    m.history_mut().enable(HistoryLimits::default());
    m.collapse_edge(hs[0]).unwrap();
    assert!(m.undo());
    assert_eq!(values(&m, &uv, &hs), before);
    // A failing transaction, with and without history.
    for history in [false, true] {
        let (mut m, uv, hs) = setup();
        if history {
            m.history_mut().enable(HistoryLimits::default());
        }
        let r = m.transaction(|m| {
            m.collapse_edge(hs[0])?;
            Err::<(), _>(meshloom::Error::Cancelled { algorithm: "tool" })
        });
        assert!(r.is_err());
        assert_eq!(values(&m, &uv, &hs), before, "history: {history}");
    }
}
