//! meshloom counterpart of src/{pmp,openmesh,cgal}_bench.cpp in the peers kit.
//!
//! Same input OBJ, same soup reader semantics, same timing scheme as the C++
//! programs: non-mutating workloads report the best of `reps` runs by thread
//! CPU time; mutating workloads run once on a fresh clone (clone untimed).
//! Every result is one line in the C++ format:
//!
//!   "<lib> <workload> <cpu s> s cpu <wall s> s wall  <note>"
//!
//! (meshloom lines add " [proc cpu <s> s]": CPU time of all threads.)
//!
//! Usage: ml_bench mesh.obj [reps]
//!
//! Copied from the peers kit (`../shared/peers/meshloom/ml_bench.rs`); it is
//! meshloom's own now. Build and compare:
//!
//!   cargo build --release --example ml_bench
//!   ../shared/peers/compare.sh . 3 --meshloom-bin target/release/examples/ml_bench
//!
//! BENCH_ONLY="name,name,..." (comma-separated workload names) runs only the
//! listed workloads; unset or empty runs all. `load` and `build` always run
//! and print (every workload needs the mesh).
//!
//! Adding a workload: write `fn <name>(input: &Input) -> (Elapsed, String)`
//! with the same name as in the C++ programs, make its note start with the
//! same counts ("-> V V, F F" etc., see README.md), and add it to WORKLOADS.

use meshloom::{Mesh, Polygons};
use std::time::Instant;

// ---------------------------------------------------------------------------
// timing helpers (thread CPU, process CPU, wall), heap accounting
// ---------------------------------------------------------------------------

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}
#[repr(C)]
#[derive(Default)]
struct MallInfo2 {
    arena: usize,
    ordblks: usize,
    smblks: usize,
    hblks: usize,
    hblkhd: usize,
    usmblks: usize,
    fsmblks: usize,
    uordblks: usize,
    fordblks: usize,
    keepcost: usize,
}
extern "C" {
    fn clock_gettime(clk: i32, ts: *mut Timespec) -> i32;
    fn mallinfo2() -> MallInfo2;
}
const CLOCK_PROCESS_CPUTIME_ID: i32 = 2;
const CLOCK_THREAD_CPUTIME_ID: i32 = 3;

fn cpu(clk: i32) -> f64 {
    let mut ts = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    unsafe { clock_gettime(clk, &mut ts) };
    ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64
}
fn heap_in_use() -> usize {
    let mi = unsafe { mallinfo2() };
    mi.uordblks + mi.hblkhd
}
fn status_kb(key: &str) -> usize {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    s.lines()
        .find(|l| l.starts_with(key))
        .and_then(|l| {
            l[key.len()..]
                .trim()
                .trim_end_matches("kB")
                .trim()
                .parse()
                .ok()
        })
        .unwrap_or(0)
}

#[derive(Clone, Copy)]
pub struct Stamp {
    wall: Instant,
    cpu: f64,
    pcpu: f64,
}
#[derive(Clone, Copy)]
pub struct Elapsed {
    wall: f64,
    cpu: f64,
    pcpu: f64,
}
fn stamp() -> Stamp {
    Stamp {
        wall: Instant::now(),
        cpu: cpu(CLOCK_THREAD_CPUTIME_ID),
        pcpu: cpu(CLOCK_PROCESS_CPUTIME_ID),
    }
}
fn since(s: Stamp) -> Elapsed {
    Elapsed {
        wall: s.wall.elapsed().as_secs_f64(),
        cpu: cpu(CLOCK_THREAD_CPUTIME_ID) - s.cpu,
        pcpu: cpu(CLOCK_PROCESS_CPUTIME_ID) - s.pcpu,
    }
}
const LIB: &str = "ml";
fn report(op: &str, e: Elapsed, note: &str) {
    println!(
        "{:<6} {:<18} {:>9.4} s cpu {:>9.4} s wall  {} [proc cpu {:.4} s]",
        LIB, op, e.cpu, e.wall, note, e.pcpu
    );
}
/// Runs `f` `reps` times, returns the fastest run by thread CPU time.
fn best_of<R>(reps: usize, mut f: impl FnMut() -> R) -> (Elapsed, R) {
    let mut best: Option<(Elapsed, R)> = None;
    for _ in 0..reps.max(1) {
        let s = stamp();
        let r = std::hint::black_box(f());
        let e = since(s);
        if best.as_ref().map_or(true, |(b, _)| e.cpu < b.cpu) {
            best = Some((e, r));
        }
    }
    best.unwrap()
}

/// The same soup reader as bench_common.h (v/f lines, fan triangulation).
fn read_obj(path: &str) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let text = std::fs::read_to_string(path).expect("read");
    let mut xyz = Vec::new();
    let mut tri = Vec::new();
    let mut poly: Vec<i64> = Vec::new();
    for line in text.lines() {
        let mut it = line.split_ascii_whitespace();
        match it.next() {
            Some("v") => {
                let mut p = [0.0; 3];
                for c in p.iter_mut() {
                    *c = it.next().and_then(|s| s.parse().ok()).unwrap_or(0.0);
                }
                xyz.push(p);
            }
            Some("f") => {
                poly.clear();
                for tok in it {
                    let idx: i64 = tok.split('/').next().unwrap().parse().unwrap();
                    let nv = xyz.len() as i64;
                    poly.push(if idx > 0 { idx - 1 } else { nv + idx });
                }
                for i in 1..poly.len().saturating_sub(1) {
                    tri.push([poly[0] as u32, poly[i] as u32, poly[i + 1] as u32]);
                }
            }
            _ => {}
        }
    }
    (xyz, tri)
}

// ---------------------------------------------------------------------------
// shared input helpers (same rules as bench_common.h)
// ---------------------------------------------------------------------------

/// What every workload gets: the OBJ path, reps, the soup and the built mesh.
pub struct Input {
    pub path: String,
    pub reps: usize,
    pub xyz: Vec<[f64; 3]>,
    pub tri: Vec<[u32; 3]>,
    pub mesh: Mesh,
}

/// Mean length of the input's undirected edges, from the soup in f64
/// (bench::mean_edge_length): the target of uniform_remeshing.
#[allow(dead_code)]
fn mean_edge_length(input: &Input) -> f64 {
    let mut e: Vec<(u32, u32)> = input
        .tri
        .iter()
        .flat_map(|t| (0..3).map(move |i| (t[i].min(t[(i + 1) % 3]), t[i].max(t[(i + 1) % 3]))))
        .collect();
    e.sort_unstable();
    e.dedup();
    let sum: f64 = e
        .iter()
        .map(|&(a, b)| {
            let (p, q) = (input.xyz[a as usize], input.xyz[b as usize]);
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
        })
        .sum();
    sum / e.len().max(1) as f64
}

/// The holes of fill_holes (bench::holes): 8 holes; hole k (1..=8) removes the
/// 64 input faces [s_k, s_k + 64), s_k = 64 * floor(k * F / (64 * 9)); fill
/// from the border halfedge that ran from corner 0 to corner 1 of face s_k.
/// Returns (s_k, corner 0, corner 1) per hole.
#[allow(dead_code)]
fn holes(input: &Input) -> Vec<(usize, u32, u32)> {
    let nf = input.tri.len();
    (1..=8usize)
        .map(|k| {
            let s = 64 * ((k * nf) / (64 * 9));
            (s, input.tri[s][0], input.tri[s][1])
        })
        .collect()
}

// ---------------------------------------------------------------------------
// workloads: one function each, named as in the C++ programs
// ---------------------------------------------------------------------------

type Workload = fn(&Input) -> (Elapsed, String);

/// Order as in the C++ programs. Workloads meshloom does not have yet are
/// listed in the comment; add a function and a line when it has them.
const WORKLOADS: &[(&str, Workload)] = &[
    ("read_lib", read_lib),
    ("circulate", circulate),
    ("smooth_10", smooth_10),
    ("split_collapse_checked", split_collapse_checked),
    ("flip_back", flip_back),
    // not in meshloom yet (C++ names and count notes, see README.md):
    // ("normals_lib", ...)           "angle-weighted"
    // ("loop_subdiv", ...)           "-> V V, F F"
    // ("decimate_10pct", ...)        "-> V V, F F"
    // ("catmull_clark", ...)         "-> V V, F F"
    // ("sqrt3", ...)                 "-> V V, F F"
    // ("vertex_normals", ...)        "V V; ..."
    // ("curvature", ...)             "V V; mean, average H x"
    // ("implicit_smoothing", ...)    "V V; 1 step, cotan, dt 0.001, rescale"
    // ("uniform_remeshing", ...)     "-> V V, F F; target length L, 10 iterations"   (mean_edge_length)
    // ("fill_holes", ...)            "8 holes filled -> V V, F F; holed input V V, F F"   (holes)
];

/// meshloom's own OBJ reader (parses files >= 4 MiB on two threads; the
/// table uses the process CPU of this line).
fn read_lib(input: &Input) -> (Elapsed, String) {
    let t0 = stamp();
    let m2 = meshloom::io::read(&input.path).expect("read");
    let e = since(t0);
    (e, format!("{} V, {} F", m2.vertex_count(), m2.face_count()))
}

/// For every vertex, sum the indices of its one-ring; best of reps.
fn circulate(input: &Input) -> (Elapsed, String) {
    let m = &input.mesh;
    let (e, sum) = best_of(input.reps, || {
        let mut s = 0usize;
        for v in m.vertices() {
            if let Ok(view) = m.vertex(v) {
                for w in view.neighbors() {
                    s += w.index();
                }
            }
        }
        s
    });
    (e, format!("checksum {sum}"))
}

/// 10 Jacobi iterations of uniform barycentre smoothing through the attribute
/// API, boundary vertices fixed (as the C++ smooth_10).
fn smooth_10(input: &Input) -> (Elapsed, String) {
    let mut mesh = input.mesh.clone();
    let t0 = stamp();
    let pos = mesh.position_attr().expect("positions");
    let vertices: Vec<_> = mesh.vertices().collect();
    let mut next = vec![[0.0f64; 3]; vertices.len()];
    for _ in 0..10 {
        let view = mesh.attr_view(&pos).unwrap();
        for (out, &v) in next.iter_mut().zip(&vertices) {
            let vv = mesh.vertex(v).unwrap();
            if vv.is_boundary() {
                *out = *view.get(v).unwrap();
                continue;
            }
            let mut sum = [0.0; 3];
            let mut n = 0.0;
            for u in vv.neighbors() {
                if let Some(p) = view.get(u) {
                    sum[0] += p[0];
                    sum[1] += p[1];
                    sum[2] += p[2];
                    n += 1.0;
                }
            }
            *out = sum.map(|c| c / n);
        }
        let mut view = mesh.attr_view_mut(&pos).unwrap();
        for (p, &v) in next.iter().zip(&vertices) {
            if let Some(slot) = view.get_mut(v) {
                *slot = *p;
            }
        }
    }
    let e = since(t0);
    let p = mesh.position_slots().unwrap();
    let chk: f64 = p.iter().map(|q| q[2]).sum();
    (e, format!("10 iterations, sum z {chk:.6}"))
}

/// Poke every face (1-to-3 split), then collapse every new centre vertex
/// (meshloom's collapse_edge always checks the link condition). No garbage
/// collection: meshloom leaves vacant slots (the peers' time includes GC).
fn split_collapse_checked(input: &Input) -> (Elapsed, String) {
    let mut m = input.mesh.clone();
    let mut refused = 0usize;
    let t0 = stamp();
    let [first_new, _, _, faces] = m.slot_counts();
    for i in 0..faces {
        if let Some(f) = m.face_at(i) {
            m.poke_face(f).expect("poke");
        }
    }
    let t_split = since(t0);
    for i in first_new..m.slot_counts()[0] {
        if let Some(c) = m.vertex_at(i) {
            let h = m.vertex(c).expect("live").halfedge().key();
            if m.collapse_edge(h).is_err() {
                refused += 1;
            }
        }
    }
    let t_all = since(t0);
    let note = format!(
        "back to {} V, {} F, {} refused; wall split {:.4} + collapse {:.4} + gc 0 s",
        m.vertex_count(),
        m.face_count(),
        refused,
        t_split.wall,
        t_all.wall - t_split.wall
    );
    (t_all, note)
}

/// Every edge index in order: if flippable, flip and flip straight back
/// (flip_edge checks on every call).
fn flip_back(input: &Input) -> (Elapsed, String) {
    let mut m = input.mesh.clone();
    let (mut flipped, mut refused_back) = (0usize, 0usize);
    let t0 = stamp();
    for i in 0..m.slot_counts()[2] {
        if let Some(e) = m.edge_at(i) {
            if m.flip_edge(e).is_ok() {
                if m.flip_edge(e).is_err() {
                    refused_back += 1;
                }
                flipped += 1;
            }
        }
    }
    let e = since(t0);
    (
        e,
        format!("{flipped} edges flipped and back, {refused_back} back-flips refused"),
    )
}

// ---------------------------------------------------------------------------

/// The BENCH_ONLY filter (same rule as bench::wanted in bench_common.h):
/// None = run everything.
fn only_list() -> Option<Vec<String>> {
    let v = std::env::var("BENCH_ONLY").unwrap_or_default();
    let names: Vec<String> = v
        .split(',')
        .map(|n| {
            n.chars()
                .filter(|&c| c != ' ' && c != '\t')
                .collect::<String>()
        })
        .filter(|n| !n.is_empty())
        .collect();
    if names.is_empty() {
        None
    } else {
        Some(names)
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .expect("usage: ml_bench mesh.obj [reps]")
        .clone();
    let reps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);

    // --- load (own soup parser; not compared) ---
    let t0 = stamp();
    let (xyz, tri) = read_obj(&path);
    report(
        "load",
        since(t0),
        &format!("{} V, {} F", xyz.len(), tri.len()),
    );

    // input buffers (untimed conversion: the C++ build also starts from arrays)
    let poly = Polygons {
        positions: xyz.clone(),
        offsets: (0..=tri.len() as u32).map(|i| 3 * i).collect(),
        indices: tri.iter().flatten().copied().collect(),
    };

    // --- build ---
    let heap0 = heap_in_use();
    let t0 = stamp();
    let mesh = Mesh::from_buffers(&poly).expect("valid");
    let t_build = since(t0);
    let heap1 = heap_in_use();
    drop(poly);
    let nv = mesh.vertex_count().max(1);
    report(
        "build",
        t_build,
        &format!(
            "E={} heap {} B/vertex",
            mesh.edge_count(),
            (heap1 - heap0) / nv
        ),
    );

    let input = Input {
        path,
        reps,
        xyz,
        tri,
        mesh,
    };
    let only = only_list();
    for (name, f) in WORKLOADS {
        if let Some(only) = &only {
            if !only.iter().any(|n| n == name) {
                continue;
            }
        }
        let (e, note) = f(&input);
        report(name, e, &note);
    }
    println!(
        "{:<6} {:<18} {:>9} kB",
        LIB,
        "peak_rss",
        status_kb("VmHWM:")
    );
}
