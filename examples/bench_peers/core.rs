//! Core: building from buffers, one-ring circulation, heap bytes per vertex.
//!
//! pmp-library (C++) on a machine like ours: build 49 ms (grid) / 33 ms
//! (icosphere 7); one-ring sums 2.5 ms / 3.1 ms. Targets: build <= 0.8x,
//! one-ring <= 1.0x, memory <= 132 bytes per vertex (CGAL Surface_mesh with
//! f64 and no stale-key detection).

use meshloom::{Mesh, Polygons};

use crate::harness::{Peer, Report};

/// The 250k-vertex grid: 500 x 500 vertices, each quad split in two.
fn grid() -> Polygons {
    let n = 500u32;
    let mut p = Polygons {
        positions: Vec::new(),
        offsets: vec![0],
        indices: Vec::new(),
    };
    for j in 0..n {
        for i in 0..n {
            p.positions.push([f64::from(i), f64::from(j), 0.0]);
        }
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i;
            let (b, c, d) = (a + 1, a + n + 1, a + n);
            p.indices.extend_from_slice(&[a, b, c, a, c, d]);
            let k = p.indices.len() as u32;
            p.offsets.push(k - 3);
            p.offsets.push(k);
        }
    }
    p
}

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
    workload(r, "grid 250k vertices", &grid(), 49.0, 2.5);
}
