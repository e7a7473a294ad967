//! Operators: the Surface_mesh paper's split-and-collapse test and flipping
//! every flippable edge, against pmp-library; triangulating a UV sphere of
//! 90k quads, against Plexus.
//!
//! Meshes: `shapes::grid(499, 499, Triangles)` (250,000 vertices),
//! `shapes::icosphere(7)` (163,842 vertices), `shapes::uv_sphere(300, 302)`
//! (300 × 300 quads and two triangle fans).

use crate::harness::{Peer, Report};
use meshloom::shapes::{self, GridFaces};
use meshloom::Mesh;

/// Poke every face, then collapse every new centre into a corner. Slots
/// are walked by index (as pmp's loop does), so no key list is collected:
/// on a freshly built mesh the centres fill the vertex slots after the
/// original ones.
fn split_collapse(mut m: Mesh) -> Mesh {
    let [first_new, _, _, faces] = m.slot_counts();
    for i in 0..faces {
        if let Some(f) = m.face_at(i) {
            m.poke_face(f).expect("poke");
        }
    }
    for i in first_new..m.slot_counts()[0] {
        if let Some(c) = m.vertex_at(i) {
            let h = m.vertex(c).expect("live").halfedge().key();
            m.collapse_edge(h).expect("collapse back");
        }
    }
    m
}

/// Flip every edge that can be flipped, and flip it back at once: two
/// flips per flippable edge, twice pmp's work. (Flipping each edge once in
/// key order piles the flipped edges into fans: on the grid, degrees pass
/// 20,000 and the run measures the fans, not the flips.)
fn flip_all(mut m: Mesh) -> (Mesh, usize) {
    let mut flipped = 0;
    for i in 0..m.slot_counts()[2] {
        if let Some(e) = m.edge_at(i) {
            if m.flip_edge(e).is_ok() {
                m.flip_edge(e).expect("flips back");
                flipped += 1;
            }
        }
    }
    (m, flipped)
}

/// Run the operator rows.
pub fn run(r: &mut Report) {
    let grid = shapes::grid(499, 499, GridFaces::Triangles);
    let ico = shapes::icosphere(7);
    assert_eq!(grid.vertex_count(), 250_000);
    assert_eq!(ico.vertex_count(), 163_842);
    for (name, mesh, split_peer, flip_peer) in [
        ("grid 250k", &grid, 0.145, 0.014),
        ("icosphere 7", &ico, 0.096, 0.009),
    ] {
        let out = split_collapse(mesh.clone());
        assert_eq!(
            (out.vertex_count(), out.face_count()),
            (mesh.vertex_count(), mesh.face_count())
        );
        r.time(
            &format!("ops: split 1-to-3 + collapse back, {name}"),
            Some(Peer {
                name: "pmp-library",
                seconds: split_peer,
                ratio: 1.0,
            }),
            || mesh.clone(),
            split_collapse,
        );
        r.time(
            &format!("ops: flip every flippable edge and back, {name}"),
            Some(Peer {
                name: "pmp-library x2",
                seconds: 2.0 * flip_peer,
                ratio: 1.0,
            }),
            || mesh.clone(),
            flip_all,
        );
    }
    let uv = shapes::uv_sphere(300, 302);
    assert_eq!(
        uv.faces()
            .filter(|&f| uv.face(f).map_or(0, |v| v.degree()) == 4)
            .count(),
        90_000
    );
    r.time(
        "ops: triangulate a 90k-quad UV sphere",
        Some(Peer {
            name: "Plexus (target 30 ms)",
            seconds: 3.0,
            ratio: 0.01,
        }),
        || uv.clone(),
        |mut m| {
            let left = m.triangulate_all();
            assert!(left.is_empty());
            m
        },
    );
}
