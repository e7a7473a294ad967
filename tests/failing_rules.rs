//! Rules that can fail (`Rule::FALLIBLE`): a failure refuses the operator,
//! algorithm or transaction that ran it with `Error::Rule`, carrying the
//! rule's own error, and leaves the mesh as it was.

use std::collections::BTreeMap;

use meshloom::algo::{self, Progress, SubdivisionOptions};
use meshloom::attr::{Interpolate, Rule, RuleError, VertexAttr};
use meshloom::journal::HistoryLimits;
use meshloom::shapes::{self, GridFaces};
use meshloom::{EdgeKey, ElementKind, Error, FaceKey, Mesh, VertexKey};

/// What the picky rule refuses, kept whole in the `RuleError`.
#[derive(Debug, PartialEq)]
struct Negative(i64);

impl std::fmt::Display for Negative {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} is negative", self.0)
    }
}

impl std::error::Error for Negative {}

/// Sums like `Conserved`, but refuses negative values; can fail only when
/// `FAILS` is set (the same arithmetic either way, to compare).
struct Picky<const FAILS: bool>;

impl<const FAILS: bool> Picky<FAILS> {
    fn check(inputs: &[(Option<&i64>, f64)]) -> Result<(), RuleError> {
        match inputs.iter().filter_map(|(v, _)| *v).find(|&&v| v < 0) {
            Some(&v) => Err(RuleError::from_source(Negative(v))),
            None => Ok(()),
        }
    }

    fn sum(inputs: &[(Option<&i64>, f64)]) -> Option<i64> {
        inputs
            .iter()
            .filter_map(|(v, _)| *v)
            .copied()
            .reduce(|a, b| a + b)
    }
}

impl<const FAILS: bool> Rule<i64> for Picky<FAILS> {
    const FALLIBLE: bool = FAILS;

    fn merge(inputs: &[(Option<&i64>, f64)]) -> Option<i64> {
        Self::sum(inputs)
    }

    fn split(source: Option<&i64>, _share: f64) -> Option<i64> {
        source.copied()
    }

    fn try_merge(inputs: &[(Option<&i64>, f64)]) -> Result<Option<i64>, RuleError> {
        Self::check(inputs)?;
        Ok(Self::sum(inputs))
    }

    fn try_interpolate(inputs: &[(Option<&i64>, f64)]) -> Result<Option<i64>, RuleError> {
        Self::try_merge(inputs)
    }

    fn try_split(source: Option<&i64>, share: f64) -> Result<Option<i64>, RuleError> {
        Self::check(&[(source, share)])?;
        Ok(source.copied())
    }
}

type Strict = Picky<true>;

/// Everything an edit could change: each live element's key, the vertex
/// loops of the faces (holes too), positions, and every value of the
/// `picky` columns of each arena.
#[derive(Debug, PartialEq)]
struct Snapshot {
    vertices: Vec<(VertexKey, [f64; 3])>,
    faces: BTreeMap<FaceKey, Vec<VertexKey>>,
    edges: Vec<EdgeKey>,
    values: Vec<(String, Option<i64>)>,
}

fn snapshot(m: &Mesh) -> Snapshot {
    let mut values = Vec::new();
    if let Ok(h) = m.attr_handle::<VertexKey, i64, Strict>("picky") {
        for v in m.vertices() {
            values.push((format!("{v:?}"), m.attr(&h, v).unwrap().copied()));
        }
    }
    if let Ok(h) = m.attr_handle::<EdgeKey, i64, Strict>("picky") {
        for e in m.edges() {
            values.push((format!("{e:?}"), m.attr(&h, e).unwrap().copied()));
        }
    }
    if let Ok(h) = m.attr_handle::<FaceKey, i64, Strict>("picky") {
        for f in m.faces() {
            values.push((format!("{f:?}"), m.attr(&h, f).unwrap().copied()));
        }
    }
    Snapshot {
        vertices: m.vertices().map(|v| (v, m.position(v).unwrap())).collect(),
        faces: m
            .faces_and_holes()
            .map(|f| (f, m.face(f).unwrap().vertices().collect()))
            .collect(),
        edges: m.edges().collect(),
        values,
    }
}

/// A noisy 4 × 4 triangle grid with a `picky` vertex column: vertex `i`
/// holds `i`, the vertex `bad` holds −7.
fn grid_with_picky_vertices(bad: usize) -> (Mesh, VertexAttr<i64, Strict>, Vec<VertexKey>) {
    let mut m = shapes::grid(4, 4, GridFaces::Triangles);
    let h = m
        .add_attr_with_rule::<VertexKey, i64, Strict>("picky")
        .unwrap();
    let vs: Vec<_> = m.vertices().collect();
    for (i, &v) in vs.iter().enumerate() {
        let x = if i == bad { -7 } else { i as i64 };
        m.set_attr(&h, v, x).unwrap();
        let p = m.position(v).unwrap();
        let z = ((i * 37) % 11) as f64 * 0.01;
        m.set_position(v, [p[0], p[1], z]).unwrap();
    }
    (m, h, vs)
}

fn ends(m: &Mesh, h: meshloom::HalfedgeKey) -> [VertexKey; 2] {
    let h = m.halfedge(h).unwrap();
    [h.origin().key(), h.dest().key()]
}

/// The rule error inside `e`, checked to name the column and carry the
/// rule's own error.
fn rule_error(e: Error, kind: ElementKind, want: i64) -> RuleError {
    match e {
        Error::Rule(error) => {
            assert_eq!(error.column(), Some((kind, "picky")));
            let cause = error.cause().expect("the rule's error is kept");
            assert_eq!(cause.downcast_ref::<Negative>(), Some(&Negative(want)));
            assert_eq!(error.message(), format!("{want} is negative"));
            error
        }
        other => panic!("expected Error::Rule, got {other:?}"),
    }
}

#[test]
fn a_failing_merge_refuses_the_collapse_and_changes_nothing() {
    let bad = 5;
    let (mut m, picky, vs) = grid_with_picky_vertices(bad);
    let before = snapshot(&m);
    let h = m
        .vertex(vs[bad])
        .unwrap()
        .outgoing()
        .find(|&h| m.check_collapse_edge(h).is_ok())
        .unwrap();
    let e = m.collapse_edge(h).unwrap_err();
    let error = rule_error(e.clone(), ElementKind::Vertex, -7);
    assert!(e.to_string().contains("\"picky\""), "{e}");
    assert!(std::error::Error::source(&e).is_some());
    assert_eq!(error, error.clone());
    assert_eq!(snapshot(&m), before);
    m.validate().unwrap();

    // The rule runs again: a collapse between positive values succeeds and
    // sums them; the end it keeps keeps its key.
    let h = m
        .halfedges()
        .find(|&h| {
            let [a, b] = ends(&m, h);
            a != vs[bad] && b != vs[bad] && m.check_collapse_edge(h).is_ok()
        })
        .unwrap();
    let [a, b] = ends(&m, h);
    let sum = m.attr(&picky, a).unwrap().unwrap() + m.attr(&picky, b).unwrap().unwrap();
    assert_eq!(m.collapse_edge(h).unwrap(), b);
    assert_eq!(m.attr(&picky, b).unwrap(), Some(&sum));
    m.validate().unwrap();
}

#[test]
fn a_failing_split_refuses_split_edge_and_changes_nothing() {
    let mut m = shapes::grid(3, 3, GridFaces::Quads);
    let h = m
        .add_attr_with_rule::<EdgeKey, i64, Strict>("picky")
        .unwrap();
    let es: Vec<_> = m.edges().collect();
    for (i, &e) in es.iter().enumerate() {
        m.set_attr(&h, e, if i == 4 { -1 } else { i as i64 })
            .unwrap();
    }
    let before = snapshot(&m);
    rule_error(m.split_edge(es[4], 0.5).unwrap_err(), ElementKind::Edge, -1);
    assert_eq!(snapshot(&m), before);
    // Another edge splits: both halves keep its value.
    m.split_edge(es[3], 0.5).unwrap();
    assert_eq!(m.attr(&h, es[3]).unwrap(), Some(&3));
    m.validate().unwrap();
}

#[test]
fn triangulate_all_cuts_no_face_when_a_rule_fails() {
    let mut m = shapes::grid(3, 2, GridFaces::Quads);
    let h = m
        .add_attr_with_rule::<FaceKey, i64, Strict>("picky")
        .unwrap();
    let fs: Vec<_> = m.faces().collect();
    for (i, &f) in fs.iter().enumerate() {
        m.set_attr(&h, f, if i == 4 { -2 } else { i as i64 })
            .unwrap();
    }
    let before = snapshot(&m);
    assert_eq!(m.triangulate_all(), fs);
    assert_eq!(snapshot(&m), before);
    m.set_attr(&h, fs[4], 4).unwrap();
    assert!(m.triangulate_all().is_empty());
    assert_eq!(m.face_count(), 12);
    assert_eq!(m.attr(&h, fs[4]).unwrap(), Some(&4));
}

#[test]
fn a_failure_inside_a_transaction_fails_it_even_when_ignored() {
    let bad = 6;
    let (mut m, _, vs) = grid_with_picky_vertices(bad);
    m.history_mut().enable(HistoryLimits::default());
    let before = snapshot(&m);
    let undo_len = m.history().undo_len();
    let f = m
        .faces()
        .find(|&f| m.face(f).unwrap().vertices().all(|v| v != vs[bad]))
        .unwrap();
    let mut refused_by_the_rule = 0;
    let r = m.transaction(|m| {
        m.poke_face(f)?;
        for h in m.vertex(vs[bad])?.outgoing().collect::<Vec<_>>() {
            // Refused (by the rule, or by the link condition): ignored.
            if let Err(Error::Rule(_)) = m.collapse_edge(h) {
                refused_by_the_rule += 1;
            }
        }
        Ok(())
    });
    assert!(refused_by_the_rule > 0);
    rule_error(r.unwrap_err(), ElementKind::Vertex, -7);
    assert_eq!(snapshot(&m), before);
    assert_eq!(m.history().undo_len(), undo_len);
    assert!(!m.history().in_transaction());
    // The history goes on: an edit that succeeds is one undo unit.
    m.poke_face(f).unwrap();
    assert_eq!(m.history().undo_len(), undo_len + 1);
    assert!(m.undo());
    assert_eq!(snapshot(&m), before);
}

#[test]
fn a_failure_inside_an_algorithm_rolls_it_back_whole() {
    let bad = 12;
    let (m0, _, _) = grid_with_picky_vertices(bad);
    let before = snapshot(&m0);

    let mut m = m0.clone();
    let options = algo::DecimateOptions::default().target(algo::decimate::Target::Vertices(4));
    rule_error(
        algo::decimate(&mut m, &options, Progress::none()).unwrap_err(),
        ElementKind::Vertex,
        -7,
    );
    assert_eq!(snapshot(&m), before);

    let mut m = m0.clone();
    let options = algo::remesh::RemeshOptions::default().sizing(algo::remesh::Sizing::Uniform(1.5));
    rule_error(
        algo::remesh(&mut m, &options, Progress::none()).unwrap_err(),
        ElementKind::Vertex,
        -7,
    );
    assert_eq!(snapshot(&m), before);

    // Subdivision rebuilds every column: the face pieces are split by the
    // rule, which refuses the face holding −3.
    let mut m = shapes::grid(3, 3, GridFaces::Triangles);
    let h = m
        .add_attr_with_rule::<FaceKey, i64, Strict>("picky")
        .unwrap();
    let fs: Vec<_> = m.faces().collect();
    for (i, &f) in fs.iter().enumerate() {
        m.set_attr(&h, f, if i == 7 { -3 } else { i as i64 })
            .unwrap();
    }
    let before = snapshot(&m);
    rule_error(
        algo::loop_subdivide(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap_err(),
        ElementKind::Face,
        -3,
    );
    assert_eq!(snapshot(&m), before);
    m.validate().unwrap();
}

/// The same edits on a mesh whose column can fail but does not, and on
/// one whose identical column cannot: the guarded path (a transaction per
/// edit) changes nothing else.
#[test]
fn a_fallible_rule_that_succeeds_edits_as_an_infallible_one() {
    fn run<const FAILS: bool>() -> (Vec<[f64; 3]>, Vec<Option<i64>>, usize) {
        let mut m = shapes::grid(5, 5, GridFaces::Triangles);
        let h = m
            .add_attr_with_rule::<VertexKey, i64, Picky<FAILS>>("picky")
            .unwrap();
        let vs: Vec<_> = m.vertices().collect();
        for (i, &v) in vs.iter().enumerate() {
            m.set_attr(&h, v, i as i64).unwrap();
        }
        let f = m.faces().next().unwrap();
        m.poke_face(f).unwrap();
        let e = m.edges().nth(7).unwrap();
        m.split_edge(e, 0.25).unwrap();
        assert!(m.triangulate_all().is_empty());
        let options = algo::DecimateOptions::default().target(algo::decimate::Target::Vertices(20));
        algo::decimate(&mut m, &options, Progress::none()).unwrap();
        algo::loop_subdivide(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
        let vs: Vec<_> = m.vertices().collect();
        (
            vs.iter().map(|&v| m.position(v).unwrap()).collect(),
            vs.iter()
                .map(|&v| m.attr(&h, v).unwrap().copied())
                .collect(),
            m.face_count(),
        )
    }
    assert_eq!(run::<true>(), run::<false>());
}

#[test]
fn columns_name_their_rules() {
    let mut m = shapes::grid(2, 2, GridFaces::Quads);
    m.add_attr_with_rule::<FaceKey, i64, Strict>("picky")
        .unwrap();
    m.add_attr_with_rule::<FaceKey, f64, meshloom::attr::Conserved>("area")
        .unwrap();
    m.add_dynamic_attr::<FaceKey>("label", meshloom::attr::ValueType::I32)
        .unwrap();
    let info = m.attr_info(ElementKind::Face);
    let rules: Vec<_> = info.iter().map(|i| (i.name.as_str(), i.rule)).collect();
    // A custom rule without a name of its own says its type's name.
    assert_eq!(
        rules,
        [
            ("picky", "Picky"),
            ("area", "Conserved"),
            ("label", "Dynamic")
        ]
    );
    assert_eq!(info[0].type_name, "i64");
    assert_eq!(
        m.attr_info(ElementKind::Vertex)[0].rule,
        <Interpolate as Rule<[f64; 3]>>::name()
    );
}
