//! Core: building from buffers, one-ring circulation, heap bytes per vertex.
//!
//! pmp-library (C++) on a machine like ours: build 49 ms (grid) / 33 ms
//! (icosphere 7); one-ring sums 2.5 ms / 3.1 ms. Targets: build <= 0.8x,
//! one-ring <= 1.0x, memory <= 132 bytes per vertex (CGAL Surface_mesh with
//! f64 and no stale-key detection).

use meshloom::shapes::{self, GridFaces};
use meshloom::{Mesh, Polygons};

use crate::harness::{Peer, Report};

fn one_ring_sum(m: &Mesh) -> usize {
    let mut s = 0usize;
    for v in m.vertices() {
        if let Ok(view) = m.vertex(v) {
            for w in view.neighbors() {
                s += w.index();
            }
        }
    }
    s
}

fn workload(r: &mut Report, name: &str, poly: &Polygons, build_ms: f64, ring_ms: f64) {
    r.time(
        &format!("build from buffers, {name}"),
        Some(Peer {
            name: "pmp-library",
            seconds: build_ms / 1e3,
            ratio: 0.8,
        }),
        || (),
        |()| Mesh::from_buffers(poly).expect("valid"),
    );
    let mesh = Mesh::from_buffers(poly).expect("valid");
    r.time(
        &format!("one-ring neighbour sums, {name}"),
        Some(Peer {
            name: "pmp-library",
            seconds: ring_ms / 1e3,
            ratio: 1.0,
        }),
        || (),
        |()| one_ring_sum(&mesh),
    );
    r.figure(
        &format!("heap bytes per vertex, {name}"),
        mesh.heap_bytes() as f64 / mesh.vertex_count() as f64,
        "B ",
        Some((132.0, "CGAL Surface_mesh, f64")),
    );
}

/// Run the core rows.
pub fn run(r: &mut Report) {
    // 499 x 499 cells: 500 x 500 = 250,000 vertices, each quad split in two.
    let grid = shapes::grid_polygons(499, 499, GridFaces::Triangles);
    workload(r, "grid 250k vertices", &grid, 49.0, 2.5);
    // 10 * 4^7 + 2 = 163,842 vertices.
    workload(
        r,
        "icosphere(7) 164k vertices",
        &shapes::icosphere_polygons(7),
        33.0,
        3.1,
    );
}
