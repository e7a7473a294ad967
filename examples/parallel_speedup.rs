//! Times each path the `parallel` feature makes parallel, for a speed-up
//! table: run the same binary with `RAYON_NUM_THREADS=1` and `=2` and
//! compare (`bench/parallel.sh` does both and prints the table).
//!
//!     cargo build --release --features parallel --example parallel_speedup
//!     RAYON_NUM_THREADS=1 target/release/examples/parallel_speedup grid.obj 5
//!     RAYON_NUM_THREADS=2 target/release/examples/parallel_speedup grid.obj 5
//!
//! The input is a mesh file (any format `meshloom::io::read` reads), or
//! `grid:N` for an N × N vertex grid of triangles made in memory. Each path
//! runs `reps` times (default 5); one line per path: its name, the median
//! and the fastest wall-clock time in milliseconds, and a count that shows
//! the work was done. `read` is serial (no parallel reader): it is there as
//! the control row, whose ratio shows how noisy the machine is.

use std::time::Instant;

use meshloom::algo::{
    corner_normals, face_normals, vertex_normals, CornerNormalOptions, VertexNormalOptions,
};
use meshloom::buffers::TriangleBufferOptions;
use meshloom::shapes::{grid, GridFaces};
use meshloom::Mesh;

/// Median and fastest of `reps` runs of `work`, in milliseconds, and the
/// last run's count.
fn time(reps: usize, mut work: impl FnMut() -> usize) -> (f64, f64, usize) {
    let mut times = Vec::with_capacity(reps);
    let mut count = 0;
    for _ in 0..reps.max(1) {
        let t = Instant::now();
        count = std::hint::black_box(work());
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], times[0], count)
}

fn report(name: &str, (median, min, count): (f64, f64, usize)) {
    println!("{name:<22} {median:>10.2} {min:>10.2} {count:>10}");
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let input = args.get(1).map_or("grid:1414", String::as_str);
    let reps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);
    let threads = std::env::var("RAYON_NUM_THREADS").unwrap_or_else(|_| "default".into());
    eprintln!("input {input}, {reps} runs per path, RAYON_NUM_THREADS={threads}");
    println!(
        "{:<22} {:>10} {:>10} {:>10}",
        "path", "median_ms", "min_ms", "count"
    );

    let mesh: Mesh = match input.strip_prefix("grid:") {
        Some(n) => {
            let n: usize = n.parse()?;
            let t = Instant::now();
            let m = grid(n - 1, n - 1, GridFaces::Triangles);
            eprintln!("grid made in {:.0} ms", t.elapsed().as_secs_f64() * 1e3);
            m
        }
        None => {
            report(
                "read (serial)",
                time(reps, || {
                    meshloom::io::read(input).map_or(0, |m: Mesh| m.face_count())
                }),
            );
            meshloom::io::read(input)?
        }
    };
    eprintln!(
        "{} vertices, {} faces",
        mesh.vertex_count(),
        mesh.face_count()
    );

    report(
        "face_normals",
        time(reps, || face_normals(&mesh).map_or(0, |n| n.len())),
    );
    report(
        "vertex_normals",
        time(reps, || {
            vertex_normals(&mesh, &VertexNormalOptions::default()).map_or(0, |n| n.len())
        }),
    );
    report(
        "corner_normals",
        time(reps, || {
            corner_normals(&mesh, &CornerNormalOptions::default()).map_or(0, |n| n.len())
        }),
    );
    report(
        "corner_normals_flat",
        time(reps, || {
            corner_normals(&mesh, &CornerNormalOptions::flat()).map_or(0, |n| n.len())
        }),
    );
    report(
        "to_triangle_buffers",
        time(reps, || {
            mesh.to_triangle_buffers(&TriangleBufferOptions::default())
                .map_or(0, |b| b.vertex_count())
        }),
    );
    Ok(())
}
