//! What a dependent's debug build pays per edit: run it unoptimised, as a
//! user's own code runs (`cargo run --example debug_edits`, no features).
//!
//! 500 `poke_face` edits on triangle grids of 800 and 12,800 faces, and
//! engine buffers of a 968-quad mesh. Without the `validate-edits`
//! feature the edits' cost follows the number of edits, not the mesh's
//! size; with it (`--features validate-edits`, as meshloom's own tests run)
//! every edit validates the whole mesh.

use std::time::Instant;

use meshloom::buffers::TriangleBufferOptions;
use meshloom::shapes::{grid, GridFaces};

fn pokes(cols: usize, rows: usize) -> (usize, f64) {
    let mut mesh = grid(cols, rows, GridFaces::Triangles);
    let faces: Vec<_> = mesh.faces().take(500).collect();
    let start = Instant::now();
    for f in faces {
        mesh.poke_face(f).expect("a grid triangle pokes");
    }
    (mesh.face_count() - 1000, start.elapsed().as_secs_f64())
}

fn main() {
    let validating = cfg!(feature = "validate-edits");
    println!(
        "debug assertions: {}, validate-edits: {validating}",
        cfg!(debug_assertions)
    );
    for (cols, rows) in [(20, 20), (80, 80)] {
        let (faces, secs) = pokes(cols, rows);
        println!("500 pokes on {faces} faces: {:.1} ms", secs * 1e3);
    }
    let quads = grid(44, 22, GridFaces::Quads);
    let start = Instant::now();
    let buffers = quads
        .to_triangle_buffers(&TriangleBufferOptions::default())
        .expect("a grid has positions");
    println!(
        "triangle buffers of {} quads ({} triangles): {:.1} ms",
        quads.face_count(),
        buffers.triangle_faces.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
}
