//! Model tests: random streams of every operator on random small shapes and
//! on real meshes. After every step the mesh validates, χ changes as the
//! operator's doc says, conserved totals are kept, and `check_x` agreed with
//! `x`; after every refusal the mesh equals its snapshot.

mod common;
use common::ops::{pick, Target, TopoOp};
use common::*;
use meshloom::{shapes, Mesh};
use quickcheck::{Arbitrary, Gen, QuickCheck, TestResult};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;

/// The shared operator stream (`common::ops`).
type Op = TopoOp;

#[derive(Clone, Debug)]
struct Case {
    shape: u8,
    ops: Vec<Op>,
}

impl Arbitrary for Case {
    fn arbitrary(g: &mut Gen) -> Case {
        Case {
            shape: u8::arbitrary(g),
            ops: (0..(usize::arbitrary(g) % 40 + 1))
                .map(|_| Op::arbitrary(g))
                .collect(),
        }
    }

    fn shrink(&self) -> Box<dyn Iterator<Item = Case>> {
        let shape = self.shape;
        Box::new(self.ops.shrink().map(move |ops| Case { shape, ops }))
    }
}

fn small_shape(i: u8) -> Mesh {
    match i % 11 {
        0 => one_ring(),
        1 => boundary_fan(),
        2 => l_shape(),
        3 => open_cone(),
        4 => bowtie(),
        5 => quad_grid(3),
        6 => shapes::tetrahedron(),
        7 => shapes::cube(),
        8 => shapes::icosahedron(),
        9 => Mesh::from_faces(6, &[vec![0u32, 1, 2, 3, 4, 5]]).unwrap(),
        _ => Mesh::from_polygons(
            &[
                [0.0, 0.0, 0.0],
                [3.0, 0.0, 0.0],
                [3.0, 3.0, 0.0],
                [2.0, 1.0, 0.0],
                [1.0, 2.0, 0.0],
                [0.0, 3.0, 0.0],
            ],
            &[[0u32, 1, 2, 3, 4, 5]],
        )
        .unwrap(),
    }
}

fn real_meshes() -> &'static Vec<Mesh> {
    static MESHES: OnceLock<Vec<Mesh>> = OnceLock::new();
    MESHES.get_or_init(|| {
        [
            "boundary/cgal_open_cube.off",
            "boundary/cgal_triangular_hole.off",
            "boundary/cgal_quads_to_stitch.off",
            "boundary/cgal_mesh_with_border.off",
            "closed/cgal_sphere966.off",
            "dirty/cgal_cube-ouvert.off",
        ]
        .iter()
        .map(|p| read_off(&mesh_path(p)))
        .collect()
    })
}

/// Run one op with every check (nothing to do when the op finds no element
/// to pick).
fn step(m: &mut Mesh, totals: &Totals, op: &Op) {
    let Some(target) = pick(m, op) else {
        return;
    };
    let chi = m.euler_characteristic();
    let (ft, vt) = (face_total(m, totals), vertex_total(m, totals));
    let fcount = m.face_count();
    let before = snapshot(m);
    // (check result, op result, χ change, face total kept, vertex total kept)
    let (check, ok, dchi, keep_f, keep_v): (bool, bool, i64, bool, bool) = match (op, target) {
        (Op::SplitEdge(..), Target::Edge(e, t)) => (
            m.check_split_edge(e, t).is_ok(),
            m.split_edge(e, t).is_ok(),
            0,
            true,
            true,
        ),
        (Op::SplitFace(..), Target::FaceCorners(f, a, b)) => (
            m.check_split_face(f, a, b).is_ok(),
            m.split_face(f, a, b).is_ok(),
            0,
            true,
            true,
        ),
        (Op::Poke(_), Target::Face(f)) => (
            m.check_poke_face(f).is_ok(),
            m.poke_face(f).is_ok(),
            0,
            true,
            true,
        ),
        (Op::Collapse(_) | Op::CollapseAt(..), Target::Halfedge(h, t)) => {
            let hv = m.halfedge(h).unwrap();
            let closes = [hv.face(), hv.twin().face()]
                .iter()
                .any(|f| f.is_hole() && f.degree() == 3);
            let check = m.check_collapse_edge_at(h, t).is_ok();
            (
                check,
                m.collapse_edge_at(h, t).is_ok(),
                i64::from(closes),
                true,
                true,
            )
        }
        (Op::Flip(_), Target::Edge(e, _)) => (
            m.check_flip_edge(e).is_ok(),
            m.flip_edge(e).is_ok(),
            0,
            true,
            true,
        ),
        (Op::RemoveEdge(_), Target::Edge(e, _)) => {
            let boundary = m.edge(e).unwrap().is_boundary();
            (
                m.check_remove_edge(e).is_ok(),
                m.remove_edge(e).is_ok(),
                0,
                !boundary,
                true,
            )
        }
        (Op::MergeFaces(..), Target::Faces(f, g)) => (
            m.check_merge_faces(f, g).is_ok(),
            m.merge_faces(f, g).is_ok(),
            0,
            true,
            true,
        ),
        (Op::RemoveVertex(_), Target::Vertex(v)) => (
            m.check_remove_vertex(v).is_ok(),
            m.remove_vertex(v).is_ok(),
            0,
            true,
            false,
        ),
        (Op::RemoveFace(i), Target::Face(f)) => {
            let check = m.check_remove_face(f).is_ok();
            let ok = m.remove_face(f).is_ok();
            if ok {
                assert_eq!(m.face_count(), fcount - 1);
                m.validate().unwrap();
            }
            if ok && i % 3 == 0 {
                // Also: a bridge removed on request, on the first boundary edge.
                let boundary = m.edges().find(|&e| m.edge(e).unwrap().is_boundary());
                if let Some(e) = boundary {
                    let f_before = m.face_count();
                    assert!(m.check_remove_edge_allowing_bridge(e).is_ok());
                    m.remove_edge_allowing_bridge(e).unwrap();
                    m.validate().unwrap();
                    assert_eq!(m.face_count(), f_before - 1);
                }
            }
            tally(op, ok);
            return assert_eq!(check, ok);
        }
        (Op::FillHole(i), Target::Face(h)) => {
            if i % 2 == 0 {
                (
                    m.check_fill_hole(h).is_ok(),
                    m.fill_hole(h).is_ok(),
                    1,
                    true,
                    true,
                )
            } else {
                let check = m.check_fill_hole_triangulated(h).is_ok();
                let r = m.fill_hole_triangulated(h);
                if let Ok(tris) = &r {
                    assert!(tris.iter().all(|&t| m.face(t).unwrap().degree() == 3));
                }
                (check, r.is_ok(), 1, true, true)
            }
        }
        (Op::Triangulate(_), Target::Face(f)) => (
            m.check_triangulate(f).is_ok(),
            m.triangulate(f).is_ok(),
            0,
            true,
            true,
        ),
        (Op::TriangulateAll, _) => {
            let left = m.triangulate_all();
            for f in &left {
                assert!(m.face(*f).unwrap().degree() > 3);
            }
            (true, true, 0, true, true)
        }
        (Op::Compact, _) => {
            // Every key from before is stale or maps to the same element
            // (same position, same ends); none names another element.
            let vs: Vec<_> = m.vertices().map(|v| (v, m.position(v).ok())).collect();
            let hs: Vec<_> = m
                .halfedges()
                .map(|h| (h, m.halfedge(h).unwrap().origin().key()))
                .collect();
            let fs: Vec<_> = m
                .faces_and_holes()
                .map(|f| (f, m.face(f).unwrap().degree()))
                .collect();
            let maps = m.compact();
            for &(v, p) in &vs {
                let n = maps.vertex(v).expect("a live vertex maps");
                assert!(!m.contains_vertex(v) || n == v, "{v:?} names {n:?}");
                assert_eq!(m.position(n).ok(), p);
            }
            for &(h, o) in &hs {
                let n = maps.halfedge(h).expect("a live half-edge maps");
                assert!(!m.contains_halfedge(h) || n == h, "{h:?} names {n:?}");
                let origin = m.halfedge(n).unwrap().origin().key();
                assert_eq!(Some(origin), maps.vertex(o));
            }
            for &(f, d) in &fs {
                let n = maps.face(f).expect("a live face maps");
                assert!(!m.contains_face(f) || n == f, "{f:?} names {n:?}");
                assert_eq!(m.face(n).unwrap().degree(), d);
            }
            (true, true, 0, true, true)
        }
        (Op::Extrude(_), Target::Face(f)) => (
            m.check_extrude_face(f, 0.5).is_ok(),
            m.extrude_face(f, 0.5).is_ok(),
            0,
            true,
            true,
        ),
        (Op::SplitVertex(..), Target::Outgoing(hc, hd)) => (
            m.check_split_vertex(hc, hd).is_ok(),
            m.split_vertex(hc, hd).is_ok(),
            0,
            true,
            true,
        ),
        (Op::CutOpen(..), Target::Path(path)) => {
            // χ: −1 for a slit, +1 for each end on a boundary.
            let ends = [path[0], *path.last().unwrap()]
                .iter()
                .filter(|&&v| m.vertex(v).unwrap().is_boundary())
                .count() as i64;
            (
                m.check_cut_path(&path).is_ok(),
                m.cut_path(&path).is_ok(),
                ends - 1,
                true,
                true,
            )
        }
        (Op::CutLoop(_), Target::Path(ring)) => (
            m.check_cut_path(&ring).is_ok(),
            m.cut_path(&ring).is_ok(),
            0,
            true,
            true,
        ),
        (op, t) => unreachable!("{op:?} picked {t:?}"),
    };
    assert_eq!(check, ok, "check_* disagrees with the operator on {op:?}");
    tally(op, ok);
    if ok {
        if let Err(e) = m.validate() {
            panic!("{op:?} broke the mesh: {e}");
        }
        check_boundary_test(m, op);
        assert_eq!(m.euler_characteristic(), chi + dchi, "χ after {op:?}");
        if keep_f {
            assert!(
                (face_total(m, totals) - ft).abs() < 1e-6 * ft.max(1.0),
                "face total after {op:?}"
            );
        }
        if keep_v {
            assert!(
                (vertex_total(m, totals) - vt).abs() < 1e-6 * vt.max(1.0),
                "vertex total after {op:?}"
            );
        }
    } else {
        assert_eq!(snapshot(m), before, "refused {op:?} changed the mesh");
    }
}

/// Rule 11 seen from outside: the O(1) `is_boundary` of every vertex agrees
/// with a walk around it, and a boundary vertex's half-edge lies in a hole.
fn check_boundary_test(m: &Mesh, op: &Op) {
    for v in m.vertices() {
        let view = m.vertex(v).unwrap();
        let walked = view
            .outgoing()
            .any(|h| m.halfedge(h).unwrap().is_boundary());
        assert_eq!(
            view.is_boundary(),
            walked,
            "is_boundary of {v:?} after {op:?}"
        );
        assert_eq!(view.halfedge().is_boundary(), walked, "{v:?} after {op:?}");
    }
}

static TALLY: [[AtomicUsize; 2]; 18] =
    [const { [const { AtomicUsize::new(0) }, const { AtomicUsize::new(0) }] }; 18];

fn op_index(op: &Op) -> usize {
    match op {
        Op::SplitEdge(..) => 0,
        Op::SplitFace(..) => 1,
        Op::Poke(..) => 2,
        Op::Collapse(..) => 3,
        Op::CollapseAt(..) => 4,
        Op::Flip(..) => 5,
        Op::RemoveEdge(..) => 6,
        Op::MergeFaces(..) => 7,
        Op::RemoveVertex(..) => 8,
        Op::RemoveFace(..) => 9,
        Op::FillHole(..) => 10,
        Op::Triangulate(..) => 11,
        Op::TriangulateAll => 12,
        Op::Compact => 13,
        Op::Extrude(..) => 14,
        Op::SplitVertex(..) => 15,
        Op::CutOpen(..) => 16,
        Op::CutLoop(..) => 17,
    }
}

fn tally(op: &Op, ok: bool) {
    TALLY[op_index(op)][usize::from(ok)].fetch_add(1, Ordering::Relaxed);
}

/// Every operator must succeed somewhere in the run, or the streams test
/// nothing.
fn assert_coverage() {
    let names = [
        "split_edge",
        "split_face",
        "poke",
        "collapse",
        "collapse_at",
        "flip",
        "remove_edge",
        "merge_faces",
        "remove_vertex",
        "remove_face",
        "fill_hole",
        "triangulate",
        "triangulate_all",
        "compact",
        "extrude",
        "split_vertex",
        "cut_open",
        "cut_loop",
    ];
    for (i, name) in names.iter().enumerate() {
        let (no, yes) = (
            TALLY[i][0].load(Ordering::Relaxed),
            TALLY[i][1].load(Ordering::Relaxed),
        );
        eprintln!("{name:>16}: {yes} done, {no} refused");
        assert!(yes > 0, "{name} never succeeded");
    }
}

fn run(mut m: Mesh, ops: &[Op]) {
    m.validate().unwrap();
    let totals = add_totals(&mut m);
    for op in ops {
        step(&mut m, &totals, op);
    }
}

#[test]
fn random_streams_on_small_shapes() {
    fn prop(case: Case) -> TestResult {
        run(small_shape(case.shape), &case.ops);
        TestResult::passed()
    }
    QuickCheck::new()
        .tests(800)
        .quickcheck(prop as fn(Case) -> TestResult);
}

/// Many more short streams, each step checked through `validate` (rule 11
/// among the others) and `check_boundary_test`: the boundary rule is kept
/// by every operator, also on meshes with holes, bowties and several
/// pieces. `MESHLOOM_MODEL_CASES` raises the count for a longer run.
#[test]
fn boundary_rule_on_random_streams() {
    fn prop(case: Case) -> TestResult {
        let m = match case.shape % 3 {
            0 => small_shape(case.shape / 3),
            1 => {
                let meshes = real_meshes();
                meshes[case.shape as usize % meshes.len()].clone()
            }
            _ => {
                // A shape with holes punched in first.
                let mut m = small_shape(case.shape / 3);
                let faces: Vec<_> = m.faces().step_by(3).collect();
                for f in faces {
                    let _ = m.remove_face(f);
                }
                if m.is_empty() {
                    return TestResult::discard();
                }
                m
            }
        };
        run(m, &case.ops);
        TestResult::passed()
    }
    let cases = std::env::var("MESHLOOM_MODEL_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(600);
    QuickCheck::new()
        .tests(cases)
        .max_tests(4 * cases)
        .quickcheck(prop as fn(Case) -> TestResult);
}

#[test]
fn random_streams_on_real_meshes() {
    fn prop(case: Case) -> TestResult {
        let meshes = real_meshes();
        let m = meshes[case.shape as usize % meshes.len()].clone();
        run(m, &case.ops);
        TestResult::passed()
    }
    QuickCheck::new()
        .tests(80)
        .quickcheck(prop as fn(Case) -> TestResult);
    let mut g = Gen::new(1000);
    let ops: Vec<Op> = (0..600).map(|_| Op::arbitrary(&mut g)).collect();
    run(quad_grid(6), &ops);
    // Long streams reach states the short ones do not.
    for (seed, m) in real_meshes().iter().enumerate() {
        let mut g = Gen::new(10_000 + seed);
        let ops: Vec<Op> = (0..400).map(|_| Op::arbitrary(&mut g)).collect();
        run(m.clone(), &ops);
    }
    assert_coverage();
}
