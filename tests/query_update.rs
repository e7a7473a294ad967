//! `FaceTree::update` from the journal's change set against a fresh build,
//! after random edits on several meshes, and the refusal of change sets
//! that do not cover exactly the edits since the tree's revision.

use meshloom::query::{FaceTree, QueryError, Ray, WindingMode};
use meshloom::shapes::{self, GridFaces};
use meshloom::Mesh;

mod common;

use common::query::{bbox, Rng};

/// One random edit (it may be refused; a refused edit changes nothing).
fn edit(mesh: &mut Mesh, rng: &mut Rng) {
    let faces: Vec<_> = mesh.faces().collect();
    let edges: Vec<_> = mesh.edges().collect();
    let verts: Vec<_> = mesh.vertices().collect();
    if faces.is_empty() {
        return;
    }
    let f = faces[rng.below(faces.len())];
    let e = edges[rng.below(edges.len())];
    let h = mesh.edge(e).unwrap().halfedge(rng.below(2) as u32).key();
    match rng.below(10) {
        0 => drop(mesh.split_edge(e, 0.3 + 0.4 * rng.next())),
        1 => drop(mesh.collapse_edge(h)),
        2 => drop(mesh.flip_edge(e)),
        3 => drop(mesh.remove_face(f)),
        4 => {
            let holes: Vec<_> = mesh.holes().collect();
            if let Some(&hole) = holes.first() {
                drop(mesh.fill_hole(hole));
            }
        }
        5 | 6 => {
            for _ in 0..1 + rng.below(5) {
                let v = verts[rng.below(verts.len())];
                let mut p = mesh.position(v).unwrap();
                for c in p.iter_mut() {
                    *c += 0.3 * (rng.next() - 0.5);
                }
                mesh.set_position(v, p).unwrap();
            }
        }
        7 => drop(mesh.extrude_face(f, 0.2)),
        8 => drop(mesh.poke_face(f)),
        _ => {
            if rng.next() < 0.7 {
                mesh.undo();
            } else {
                mesh.redo();
            }
        }
    }
}

/// First hits, closest distances and winding numbers of `tree` equal a
/// fresh build's.
fn same_answers(name: &str, mesh: &Mesh, tree: &FaceTree, rng: &mut Rng) {
    let fresh = FaceTree::build(mesh).unwrap();
    assert_eq!(tree.triangle_count(), fresh.triangle_count(), "{name}");
    assert_eq!(tree.face_count(), fresh.face_count(), "{name}");
    if mesh.face_count() == 0 {
        return;
    }
    let (lo, hi) = bbox(mesh);
    for _ in 0..60 {
        let o = rng.in_box(lo.map(|c| c - 1.0), hi.map(|c| c + 1.0));
        let t = rng.in_box(lo, hi);
        let ray = Ray::new(o, [0, 1, 2].map(|k| t[k] - o[k]));
        let a = tree.ray_cast(mesh, ray).unwrap();
        let b = fresh.ray_cast(mesh, ray).unwrap();
        assert_eq!(a.map(|h| h.t), b.map(|h| h.t), "{name}");
        if let (Some(a), Some(b)) = (a, b) {
            // The same face unless two faces tie at this t.
            assert!(a.face == b.face || a.point == b.point, "{name}");
        }
        let a = tree.closest_point(mesh, o, None).unwrap().unwrap();
        let b = fresh.closest_point(mesh, o, None).unwrap().unwrap();
        assert_eq!(a.distance, b.distance, "{name}");
        let a = tree.winding_number(mesh, o, WindingMode::Exact).unwrap();
        let b = fresh.winding_number(mesh, o, WindingMode::Exact).unwrap();
        assert!((a - b).abs() < 1e-9, "{name}: {a} vs {b}");
    }
}

fn meshes() -> Vec<(&'static str, Mesh)> {
    let dir = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../shared/data/meshes/polygons/"
    );
    let mut out = vec![
        ("closed icosphere", shapes::icosphere(3)),
        ("open grid", shapes::grid(20, 15, GridFaces::Triangles)),
        ("quad grid", shapes::grid(12, 10, GridFaces::Quads)),
    ];
    if let Ok(m) = meshloom::io::read(format!("{dir}cgal_cube_poly.off")) {
        out.push(("n-gon cube", m));
    }
    out
}

#[test]
fn updates_answer_as_a_fresh_build_after_random_edits() {
    let mut rng = Rng(0x5EED_1234_ABCD_0001);
    for (name, mut mesh) in meshes() {
        mesh.history_mut().enable(Default::default());
        mesh.history_mut().track_changes(true);
        let mut tree = FaceTree::build(&mesh).unwrap();
        let mut partial = 0;
        for round in 0..40 {
            for _ in 0..1 + rng.below(3) {
                edit(&mut mesh, &mut rng);
            }
            let changes = mesh.history_mut().take_changes();
            let report = tree.update(&mesh, &changes).unwrap();
            partial += usize::from(!report.full_rebuild);
            assert!(tree.is_current(&mesh), "{name} round {round}");
            same_answers(name, &mesh, &tree, &mut rng);
        }
        // Small meshes cross the rebuild bound (a quarter of the triangles).
        if mesh.face_count() >= 200 {
            assert!(partial > 10, "{name}: only {partial} partial updates");
        }
    }
}

#[test]
fn a_skipped_or_stale_change_set_is_refused() {
    let mut mesh = shapes::icosphere(2);
    mesh.history_mut().track_changes(true);
    let mut tree = FaceTree::build(&mesh).unwrap();
    let f = mesh.faces().next().unwrap();
    mesh.poke_face(f).unwrap();
    let first = mesh.history_mut().take_changes();
    let g = mesh.faces().nth(5).unwrap();
    mesh.poke_face(g).unwrap();
    let second = mesh.history_mut().take_changes();
    // The first set was skipped.
    let err = tree.update(&mesh, &second).unwrap_err();
    assert!(matches!(err, QueryError::ChangesMismatch { .. }), "{err}");
    // The first set does not reach the mesh's revision.
    let err = tree.update(&mesh, &first).unwrap_err();
    assert!(matches!(err, QueryError::ChangesMismatch { .. }), "{err}");
    // Edits after a take.
    let mut tree = FaceTree::build(&mesh).unwrap();
    let v = mesh.vertices().next().unwrap();
    mesh.set_position(v, [0.0, 0.0, 2.0]).unwrap();
    let third = mesh.history_mut().take_changes();
    mesh.set_position(v, [0.0, 0.0, 3.0]).unwrap();
    let err = tree.update(&mesh, &third).unwrap_err();
    assert!(matches!(err, QueryError::ChangesMismatch { .. }), "{err}");
    // Another mesh.
    let copy = mesh.clone();
    let fourth = mesh.history_mut().take_changes();
    assert!(matches!(
        tree.update(&copy, &fourth),
        Err(QueryError::StaleTree {
            same_mesh: false,
            ..
        })
    ));
    // Refusals left the tree as it was; a covering set is accepted.
    let mut tree = FaceTree::build(&mesh).unwrap();
    mesh.set_position(v, [0.0, 0.0, 1.5]).unwrap();
    let fifth = mesh.history_mut().take_changes();
    assert_eq!(fifth.from_revision, tree.revision());
    tree.update(&mesh, &fifth).unwrap();
    assert!(tree.is_current(&mesh));
}
