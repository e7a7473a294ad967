//! `meshopt-bench mesh.obj`: meshoptimizer's `simplify` to a tenth of the
//! vertices (the `decimate_10pct` row), printed in the peers kit's line
//! format: `meshopt decimate_10pct <cpu> s cpu <wall> s wall  -> V V, F F`.
//!
//! The same OBJ soup as `examples/ml_bench.rs` (`v` and `f` lines, polygons
//! fanned). meshoptimizer targets an index count: a tenth of the vertices
//! is about a tenth of the triangles on these meshes, so the target is a
//! tenth of the indices, with no error limit (`target_error` 1.0, relative).

use std::time::Instant;

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}
extern "C" {
    fn clock_gettime(clk: i32, ts: *mut Timespec) -> i32;
}
const CLOCK_THREAD_CPUTIME_ID: i32 = 3;

fn thread_cpu() -> f64 {
    let mut ts = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid clock id and a pointer to a live Timespec.
    unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64
}

fn main() {
    let path = std::env::args().nth(1).expect("usage: meshopt-bench mesh.obj");
    let text = std::fs::read_to_string(&path).expect("read the OBJ file");
    let mut xyz: Vec<[f32; 3]> = Vec::new();
    let mut idx: Vec<u32> = Vec::new();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let p: Vec<f32> = it.take(3).map(|x| x.parse().expect("a number")).collect();
                xyz.push([p[0], p[1], p[2]]);
            }
            Some("f") => {
                let c: Vec<u32> = it
                    .map(|t| t.split('/').next().unwrap().parse::<u32>().expect("an index") - 1)
                    .collect();
                for k in 1..c.len() - 1 {
                    idx.extend_from_slice(&[c[0], c[k], c[k + 1]]);
                }
            }
            _ => {}
        }
    }
    let bytes = meshopt::typed_to_bytes(&xyz);
    let adapter = meshopt::VertexDataAdapter::new(bytes, 12, 0).expect("positions");
    let target = idx.len() / 10 / 3 * 3;
    let (c0, w0) = (thread_cpu(), Instant::now());
    let mut err = 0.0f32;
    let out = meshopt::simplify(
        &idx,
        &adapter,
        target,
        1.0,
        meshopt::SimplifyOptions::None,
        Some(&mut err),
    );
    let (cpu, wall) = (thread_cpu() - c0, w0.elapsed().as_secs_f64());
    let mut used = vec![false; xyz.len()];
    for &i in &out {
        used[i as usize] = true;
    }
    let nv = used.iter().filter(|&&u| u).count();
    println!(
        "meshopt decimate_10pct {cpu:.4} s cpu {wall:.4} s wall  -> {nv} V, {} F; relative error {err:.3e}",
        out.len() / 3
    );
}
