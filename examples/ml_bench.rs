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
unsafe extern "C" {
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
        if best.as_ref().is_none_or(|(b, _)| e.cpu < b.cpu) {
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
    // meshloom only: smooth_10 as the peers write it, through views.
    ("smooth_10_views", smooth_10_views),
    // meshloom only: smooth_10 through keys instead of views.
    ("smooth_10_keys", smooth_10_keys),
    ("split_collapse_checked", split_collapse_checked),
    // meshloom only: the same followed by compact() (the peers' time
    // includes their garbage collection).
    ("split_collapse_compact", split_collapse_compact),
    ("flip_back", flip_back),
    ("vertex_normals", vertex_normals),
    ("loop_subdiv", loop_subdiv),
    ("catmull_clark", catmull_clark),
    ("sqrt3", sqrt3),
    ("curvature", curvature),
    ("implicit_smoothing", implicit_smoothing),
    ("decimate_10pct", decimate_10pct),
    ("fill_holes", fill_holes),
    ("uniform_remeshing", uniform_remeshing),
    // meshloom only (no peer row): engine buffers.
    ("triangle_buffers", triangle_buffers),
    // meshloom only: the journal (issue 15).
    ("journal", journal),
    ("transaction_vs_clone", transaction_vs_clone),
    // The peers' normals rows: the library's call, and a user's own loops.
    ("normals_lib", normals_lib),
    ("normals_classic", normals_classic),
    ("flip_all", flip_all),
];

/// Remove the faces of the kit's 8 holes (untimed), then fill them with
/// `algo::fill_hole::fill_holes_at` (one call, one undo step, each hole from
/// its border half-edge: optimal triangulation, refinement to the rim's
/// edge length when a triangle fails Liepa's density test, bi-Laplacian
/// fairing of the new vertices), as CGAL's `triangulate_refine_and_fair_hole`
/// per hole (Liepa: triangulate, refine by the same density test, fair) and
/// pmp's `fill_hole`. Neither peer has undo; CGAL's refinement adds no
/// vertex on the grid's strips (their triangles fit), and neither does ours.
fn fill_holes(input: &Input) -> (Elapsed, String) {
    use meshloom::algo::fill_hole::{fill_holes_at, FillHoleOptions};
    let mut m = input.mesh.clone();
    let hs = holes(input);
    for &(s, _, _) in &hs {
        for i in s..s + 64 {
            let f = m.face_at(i).expect("hole face");
            m.remove_face(f).expect("remove_face");
        }
    }
    let border: Vec<_> = hs
        .iter()
        .map(|&(s, a, b)| {
            let (va, vb) = (m.vertex_at(a as usize), m.vertex_at(b as usize));
            let h = m
                .find_halfedge(va.expect("corner 0"), vb.expect("corner 1"))
                .expect("live")
                .unwrap_or_else(|| panic!("fill_holes: no border halfedge at face {s}"));
            assert!(m.halfedge(h).expect("live").face().is_hole());
            h
        })
        .collect();
    let before = format!("{} V, {} F", m.vertex_count(), m.face_count());
    let options = FillHoleOptions::default();
    let t0 = stamp();
    let filled = fill_holes_at(&mut m, &border, &options).map_or(0, |r| r.holes_filled);
    let e = since(t0);
    (
        e,
        format!(
            "{filled} holes filled -> {} V, {} F; holed input {before}",
            m.vertex_count(),
            m.face_count()
        ),
    )
}

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

/// 10 Jacobi iterations of uniform barycentre smoothing, boundary vertices
/// fixed (as the C++ smooth_10), by the library's own smoother:
/// `algo::smooth` with the uniform method and `λ = 1` (each moving vertex
/// goes to the mean of its neighbours). It flattens the one-rings of the
/// moving vertices once per call and then runs the ten steps over flat
/// arrays; the peers walk their half-edges in every step
/// (`smooth_10_views` is the same loop through meshloom's views).
fn smooth_10(input: &Input) -> (Elapsed, String) {
    use meshloom::algo::smooth::{smooth, SmoothMethod, SmoothOptions};
    let mut mesh = input.mesh.clone();
    let opts = SmoothOptions::with_method(SmoothMethod::Uniform)
        .iterations(10)
        .step(Some(1.0));
    let t0 = stamp();
    smooth(&mut mesh, &opts, meshloom::algo::Progress::none()).expect("smooth");
    let e = since(t0);
    let p = mesh.position_slots().unwrap();
    let chk: f64 = p.iter().map(|q| q[2]).sum();
    (e, format!("10 iterations, sum z {chk:.6}"))
}

/// meshloom only: smooth_10 as the peers write it, a loop through the
/// attribute API, boundary vertices fixed (as the C++ smooth_10): vertex views, their
/// neighbours as views (`neighbor_views`) and `AttrView::at`, the read the
/// attribute docs name as the fastest in a loop that navigates.
///
/// Same work as the peers: they add their scratch property (`np`) before
/// the timer starts and iterate the vertices inside it; here the scratch
/// buffer is allocated before the timer and the vertex keys are collected
/// inside it.
fn smooth_10_views(input: &Input) -> (Elapsed, String) {
    let mut mesh = input.mesh.clone();
    let pos = mesh.position_attr().expect("positions");
    let mut next = vec![[0.0f64; 3]; mesh.vertex_count()];
    let t0 = stamp();
    let vertices: Vec<_> = mesh.vertices().collect();
    for _ in 0..10 {
        let view = mesh.attr_view(&pos).unwrap();
        for (out, &v) in next.iter_mut().zip(&vertices) {
            let vv = mesh.vertex(v).unwrap();
            if vv.is_boundary() {
                *out = *view.at(vv).unwrap();
                continue;
            }
            let mut sum = [0.0; 3];
            let mut n = 0.0;
            for u in vv.neighbor_views() {
                if let Some(p) = view.at(u) {
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

/// meshloom only: smooth_10 through keys (`neighbors` and `AttrView::get`,
/// a generation check on every read) instead of views.
fn smooth_10_keys(input: &Input) -> (Elapsed, String) {
    let mut mesh = input.mesh.clone();
    let pos = mesh.position_attr().expect("positions");
    let mut next = vec![[0.0f64; 3]; mesh.vertex_count()];
    let t0 = stamp();
    let vertices: Vec<_> = mesh.vertices().collect();
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

/// What one poke-then-collapse run did (see [`poke_collapse`]).
struct PokeCollapse {
    /// Thread CPU and wall time of the whole run.
    all: Elapsed,
    /// Wall time of the poke pass alone.
    split_wall: f64,
    /// Faces poked.
    poked: usize,
    /// Centre vertices whose collapse succeeded.
    collapsed: usize,
    /// Centre vertices whose collapse was refused.
    refused: usize,
}

/// Poke every face (1-to-3 split), then collapse every new centre vertex
/// (meshloom's collapse_edge always checks the link condition): the loops
/// that `split_collapse_checked`, `split_collapse_compact` and `journal`
/// share. No garbage collection.
fn poke_collapse(m: &mut Mesh) -> PokeCollapse {
    let t0 = stamp();
    let [first_new, _, _, faces] = m.slot_counts();
    let mut poked = 0usize;
    for i in 0..faces {
        if let Some(f) = m.face_at(i) {
            m.poke_face(f).expect("poke");
            poked += 1;
        }
    }
    let split_wall = since(t0).wall;
    let (mut collapsed, mut refused) = (0usize, 0usize);
    for i in first_new..m.slot_counts()[0] {
        if let Some(c) = m.vertex_at(i) {
            let h = m.vertex(c).expect("live").halfedge().key();
            if m.collapse_edge(h).is_ok() {
                collapsed += 1;
            } else {
                refused += 1;
            }
        }
    }
    PokeCollapse {
        all: since(t0),
        split_wall,
        poked,
        collapsed,
        refused,
    }
}

/// Poke every face, then collapse every new centre vertex (see
/// [`poke_collapse`]). No garbage collection: meshloom leaves vacant slots
/// (the peers' time includes GC).
fn split_collapse_checked(input: &Input) -> (Elapsed, String) {
    let mut m = input.mesh.clone();
    let run = poke_collapse(&mut m);
    let note = format!(
        "back to {} V, {} F, {} refused; wall split {:.4} + collapse {:.4} + gc 0 s",
        m.vertex_count(),
        m.face_count(),
        run.refused,
        run.split_wall,
        run.all.wall - run.split_wall
    );
    (run.all, note)
}

/// meshloom only: split_collapse_checked followed by `compact()`, the
/// counterpart of the peers' garbage collection, which their
/// split_collapse_checked time includes (README caveat 2).
fn split_collapse_compact(input: &Input) -> (Elapsed, String) {
    let mut m = input.mesh.clone();
    let t0 = stamp();
    let run = poke_collapse(&mut m);
    let t_coll = since(t0);
    let maps = m.compact();
    std::hint::black_box(&maps);
    let t_all = since(t0);
    let note = format!(
        "back to {} V, {} F, {} refused; wall split {:.4} + collapse {:.4} + compact {:.4} s",
        m.vertex_count(),
        m.face_count(),
        run.refused,
        run.split_wall,
        t_coll.wall - run.split_wall,
        t_all.wall - t_coll.wall
    );
    (t_all, note)
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// split_collapse_checked with the undo journal off and on, alternating,
/// `reps` rounds each (medians of thread CPU time, with min..max; "on"
/// includes closing the run's step, which encodes its delta); the
/// journal's bytes per operator; undoing the whole run as one unit.
fn journal(input: &Input) -> (Elapsed, String) {
    let rounds = input.reps.max(3);
    let (mut off, mut on, mut undo) = (Vec::new(), Vec::new(), Vec::new());
    let (mut bytes, mut ops) = (0usize, 0usize);
    let t_all = stamp();
    for _ in 0..rounds {
        let mut m = input.mesh.clone();
        off.push(poke_collapse(&mut m).all.cpu);
        drop(m);
        let mut m = input.mesh.clone();
        m.history_mut().enable(Default::default());
        // Timed with the step's end: sealing (encoding the delta) is part
        // of what the journal costs.
        let t0 = stamp();
        m.history_mut().begin_step("run");
        let run = poke_collapse(&mut m);
        m.history_mut().end_step();
        on.push(since(t0).cpu);
        bytes = m.history().bytes();
        ops = run.poked + run.collapsed;
        let t0 = stamp();
        assert!(m.undo());
        undo.push(since(t0).cpu);
        assert_eq!(m.vertex_count(), input.mesh.vertex_count());
    }
    let spread = |v: &[f64]| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(0.0, f64::max);
        format!("{lo:.3}..{hi:.3}")
    };
    let (s_off, s_on, s_undo) = (spread(&off), spread(&on), spread(&undo));
    let (m_off, m_on, m_undo) = (median(&mut off), median(&mut on), median(&mut undo));
    let note = format!(
        "{rounds} rounds, median cpu s: off {m_off:.3} [{s_off}], on {m_on:.3} [{s_on}] = {:.2}x; \
         {ops} ops, journal {bytes} B = {:.1} B/op; undo all {m_undo:.3} [{s_undo}] = {:.2}x of do",
        m_on / m_off,
        bytes as f64 / ops.max(1) as f64,
        m_undo / m_on
    );
    (since(t_all), note)
}

/// A small failed edit on the whole mesh: a transaction that pokes one
/// face and fails (rollback = undo to the mark) against the copy-and-
/// restore it replaces. Medians of 21 rounds each.
fn transaction_vs_clone(input: &Input) -> (Elapsed, String) {
    let mut m = input.mesh.clone();
    let f = m.faces().next().expect("a face");
    let t_all = stamp();
    let (mut tx, mut cl) = (Vec::new(), Vec::new());
    for _ in 0..21 {
        let t0 = stamp();
        let r: meshloom::Result<()> = m.transaction(|m| {
            m.poke_face(f)?;
            Err(meshloom::Error::Cancelled { algorithm: "bench" })
        });
        assert!(r.is_err());
        tx.push(since(t0).cpu);
        let t0 = stamp();
        let copy = m.clone();
        m.poke_face(f).expect("poke");
        m = copy;
        cl.push(since(t0).cpu);
    }
    let (t, c) = (median(&mut tx), median(&mut cl));
    let note = format!(
        "median cpu: transaction {:.1} us, clone+restore {:.1} us ({:.0}x)",
        t * 1e6,
        c * 1e6,
        c / t
    );
    (since(t_all), note)
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

/// Every edge slot in order, flipped once where the checked flip allows
/// it (the peers check `is_flip_ok` first; meshloom's flip checks itself).
/// The builder numbers edges as the faces first use them, as the peers'
/// `add_face` does, so the slots come in the peers' order and the flips
/// (and their count) are the same.
fn flip_all(input: &Input) -> (Elapsed, String) {
    let mut m = input.mesh.clone();
    let mut flipped = 0usize;
    let t0 = stamp();
    for i in 0..m.slot_counts()[2] {
        if let Some(e) = m.edge_at(i) {
            if m.flip_edge(e).is_ok() {
                flipped += 1;
            }
        }
    }
    (since(t0), format!("{flipped} flips"))
}

/// The library's angle-weighted vertex normals, as the peers' library call
/// (the same computation as `vertex_normals`; the peers list both rows).
fn normals_lib(input: &Input) -> (Elapsed, String) {
    let m = &input.mesh;
    let opts = meshloom::algo::VertexNormalOptions::default();
    let (e, n) = best_of_parallel(input.reps, || {
        meshloom::algo::vertex_normals(m, &opts).expect("positions")
    });
    std::hint::black_box(&n);
    // Our own call, as each peer's: vertex normals only, angle-weighted in
    // f64 (pmp: angle-weighted in float; OpenMesh 9's update_normals: face
    // and vertex normals, unweighted average of unit face normals in
    // float; CGAL: its own weighting in double).
    (
        e,
        "vertex_normals: angle-weighted, f64, no face normals kept".into(),
    )
}

/// A user's own loops through the public API, as the peers' classic row:
/// a unit normal per face from its first three corners, then per vertex the
/// normalised sum of its faces' normals.
fn normals_classic(input: &Input) -> (Elapsed, String) {
    let m = &input.mesh;
    let pos = m.position_attr().expect("positions");
    let view = m.attr_view(&pos).expect("live column");
    let mut face_n = vec![[0.0f64; 3]; m.slot_counts()[3]];
    let mut vertex_n = vec![[0.0f64; 3]; m.slot_counts()[0]];
    let unit = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if l > 0.0 {
            v.map(|c| c / l)
        } else {
            v
        }
    };
    let (e, _) = best_of(input.reps, || {
        for f in m.faces() {
            let mut corners = m.face(f).expect("live").vertices();
            let mut next = || {
                *view
                    .get(corners.next().expect("a corner"))
                    .expect("position")
            };
            let (p0, p1, p2) = (next(), next(), next());
            let a = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
            let b = [p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]];
            face_n[f.index()] = unit([
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]);
        }
        for v in m.vertices() {
            let mut n = [0.0; 3];
            for f in m.vertex(v).expect("live").faces() {
                let q = face_n[f.index()];
                n = [n[0] + q[0], n[1] + q[1], n[2] + q[2]];
            }
            vertex_n[v.index()] = unit(n);
        }
    });
    std::hint::black_box(&vertex_n);
    (e, "unweighted face average".into())
}

/// Best of reps: by thread CPU (as the peers), or by wall time when the
/// work runs on rayon's threads (`--features parallel`), where the calling
/// thread's CPU time is only its own share.
fn best_of_parallel<R>(reps: usize, f: impl FnMut() -> R) -> (Elapsed, R) {
    if !cfg!(feature = "parallel") {
        return best_of(reps, f);
    }
    let mut f = f;
    let mut best: Option<(Elapsed, R)> = None;
    for _ in 0..reps.max(1) {
        let s = stamp();
        let r = std::hint::black_box(f());
        let e = since(s);
        if best.as_ref().is_none_or(|(b, _)| e.wall < b.wall) {
            best = Some((e, r));
        }
    }
    best.unwrap()
}

fn threads() -> &'static str {
    if cfg!(feature = "parallel") {
        "rayon, best by wall"
    } else {
        "1 thread"
    }
}

/// Angle-weighted vertex normals (meshloom::algo::vertex_normals, as pmp's
/// vertex_normals); best of reps.
fn vertex_normals(input: &Input) -> (Elapsed, String) {
    let m = &input.mesh;
    let opts = meshloom::algo::VertexNormalOptions::default();
    let (e, n) = best_of_parallel(input.reps, || {
        meshloom::algo::vertex_normals(m, &opts).expect("positions")
    });
    let sum_z: f64 = n.iter().map(|v| v[2]).sum();
    let note = format!(
        "{} V; angle-weighted, {}, sum z {sum_z:.6}",
        m.vertex_count(),
        threads()
    );
    (e, note)
}

/// One level of a subdivision scheme, once on a fresh clone (clone untimed).
fn subdivide(
    input: &Input,
    run: fn(
        &mut Mesh,
        &meshloom::algo::SubdivisionOptions,
        meshloom::algo::Progress<'_>,
    ) -> meshloom::Result<meshloom::algo::SubdivisionReport>,
) -> (Elapsed, String) {
    let mut m = input.mesh.clone();
    let opts = meshloom::algo::SubdivisionOptions::default();
    let t0 = stamp();
    run(&mut m, &opts, meshloom::algo::Progress::none()).expect("subdivide");
    let e = since(t0);
    (
        e,
        format!("-> {} V, {} F", m.vertex_count(), m.face_count()),
    )
}

/// Loop subdivision, one level (as pmp's loop_subdivision, CGAL's
/// Loop_subdivision).
fn loop_subdiv(input: &Input) -> (Elapsed, String) {
    subdivide(input, meshloom::algo::loop_subdivide)
}

/// Catmull-Clark subdivision, one level, of the triangle mesh.
fn catmull_clark(input: &Input) -> (Elapsed, String) {
    subdivide(input, meshloom::algo::catmull_clark)
}

/// √3 subdivision, one level (as OpenMesh's Sqrt3T, CGAL's
/// Sqrt3_subdivision).
fn sqrt3(input: &Input) -> (Elapsed, String) {
    subdivide(input, meshloom::algo::sqrt3_subdivide)
}

/// Mean curvature (meshloom::algo::curvature, as pmp's
/// `curvature(mesh, Curvature::Mean)`: cotangent Laplacian over the mixed
/// Voronoi area, boundary vertices from their interior neighbours); best of
/// reps. meshloom's function also gives Gaussian and principal curvatures
/// in the same pass (pmp's Mean does not compute them).
fn curvature(input: &Input) -> (Elapsed, String) {
    let m = &input.mesh;
    let opts = meshloom::algo::curvature::CurvatureOptions::default();
    let (e, c) = best_of(input.reps, || {
        meshloom::algo::curvature::curvature(m, &opts).expect("positions")
    });
    let sum: f64 = m.vertices().map(|v| c.mean[v.index()]).sum();
    let note = format!(
        "{} V; mean, average H {:.4}",
        m.vertex_count(),
        sum / m.vertex_count() as f64
    );
    (e, note)
}

/// One implicit smoothing step (meshloom::algo::smooth, Implicit: cotan
/// Laplacian clamped at zero, mixed-Voronoi mass, (M - 0.001 L) X' = M X by
/// faer's sparse Cholesky, boundary fixed, then rescaled to the input's
/// area and centroid), as pmp's `implicit_smoothing(m, 0.001, 1, false,
/// true)`; once on a copy.
fn implicit_smoothing(input: &Input) -> (Elapsed, String) {
    use meshloom::algo::smooth::{smooth, SmoothMethod, SmoothOptions};
    let mut m = input.mesh.clone();
    let opts = SmoothOptions::with_method(SmoothMethod::Implicit)
        .iterations(1)
        .step(Some(0.001))
        .rescale(true);
    let t0 = stamp();
    let r = smooth(&mut m, &opts, meshloom::algo::Progress::none()).expect("smooth");
    let e = since(t0);
    let note = format!(
        "{} V; 1 step, cotan, dt 0.001, rescale; moved {}, max displacement {:.3e}",
        m.vertex_count(),
        r.moved,
        r.max_displacement
    );
    (e, note)
}

/// meshloom only: engine buffers with the default options (f32 positions,
/// angle-weighted corner normals split at 30 degrees, u32/u16 indices);
/// best of reps.
fn triangle_buffers(input: &Input) -> (Elapsed, String) {
    let m = &input.mesh;
    let opts = meshloom::buffers::TriangleBufferOptions::default();
    let (e, b) = best_of_parallel(input.reps, || {
        m.to_triangle_buffers(&opts).expect("positions")
    });
    let bytes = 24 * b.vertex_count() + b.indices.len() * b.indices.width();
    let note = format!(
        "{} V -> {} buffer vertices, {} triangles, {bytes} bytes; {}",
        m.vertex_count(),
        b.vertex_count(),
        b.triangle_count(),
        threads()
    );
    (e, note)
}

// ---------------------------------------------------------------------------

/// Quadric decimation to 10 % of the vertices (as pmp's `decimate` to
/// n/10, OpenMesh's `decimate_to`, CGAL's `Count_ratio_stop_predicate(0.1)`),
/// on a clone; defaults (optimal placement, flips refused, boundary kept
/// as a line). In place (no progress callback, so nothing to undo). The
/// note adds the decimator's peak heap beyond the mesh, per input vertex.
fn decimate_10pct(input: &Input) -> (Elapsed, String) {
    use meshloom::algo::decimate::{decimate, DecimateOptions, Target};
    let mut m = input.mesh.clone();
    let nv = m.vertex_count().max(1);
    let before = counting::reset_peak();
    let t0 = stamp();
    let r = decimate(
        &mut m,
        &DecimateOptions::to(Target::Ratio(0.1)),
        meshloom::algo::Progress::none(),
    )
    .expect("decimate");
    let e = since(t0);
    let peak = counting::peak();
    // What the mesh itself keeps afterwards (free lists of the vacated
    // slots), the decimator's buffers being gone.
    let kept = counting::in_use().saturating_sub(before);
    (
        e,
        format!(
            "-> {} V, {} F; error {:.3e}, {} passes, {} collapses, refused {:?}; heap peak {:.1} B/vertex beyond the input mesh, of which the mesh keeps {:.1} (free lists)",
            m.vertex_count(),
            m.face_count(),
            r.error,
            r.passes,
            r.collapses,
            r.refused,
            (peak - before) as f64 / nv as f64,
            kept as f64 / nv as f64
        ),
    )
}

/// Isotropic remeshing to the input's mean edge length (bench's
/// `mean_edge_length` of the soup), 10 iterations, projection on, as pmp's
/// `uniform_remeshing(m, len, 10, true)` and CGAL's `isotropic_remeshing`;
/// once on a clone, without a progress callback.
fn uniform_remeshing(input: &Input) -> (Elapsed, String) {
    use meshloom::algo::remesh::{remesh, RemeshOptions, Sizing};
    let mut m = input.mesh.clone();
    let len = mean_edge_length(input);
    let opts = RemeshOptions::default()
        .sizing(Sizing::Uniform(len))
        .iterations(10)
        .project(true);
    let t0 = stamp();
    let r = remesh(&mut m, &opts, meshloom::algo::Progress::none()).expect("remesh");
    let e = since(t0);
    (
        e,
        format!(
            "-> {} V, {} F; target length {len:.6}, 10 iterations; {} splits, {} collapses, {} flips, {:.1}% of edges within [4/5, 4/3] L",
            m.vertex_count(),
            m.face_count(),
            r.splits,
            r.collapses,
            r.flips,
            100.0 * r.edge_lengths.within
        ),
    )
}

/// A counting allocator: bytes in use and the peak since the last reset.
mod counting {
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

    struct Counting;
    static IN_USE: AtomicUsize = AtomicUsize::new(0);
    static PEAK: AtomicUsize = AtomicUsize::new(0);

    unsafe impl GlobalAlloc for Counting {
        unsafe fn alloc(&self, l: Layout) -> *mut u8 {
            let p = unsafe { System.alloc(l) };
            if !p.is_null() {
                let now = IN_USE.fetch_add(l.size(), Relaxed) + l.size();
                PEAK.fetch_max(now, Relaxed);
            }
            p
        }
        unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
            unsafe { System.dealloc(p, l) };
            IN_USE.fetch_sub(l.size(), Relaxed);
        }
        unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
            let q = unsafe { System.realloc(p, l, new) };
            if !q.is_null() {
                if new >= l.size() {
                    let now = IN_USE.fetch_add(new - l.size(), Relaxed) + new - l.size();
                    PEAK.fetch_max(now, Relaxed);
                } else {
                    IN_USE.fetch_sub(l.size() - new, Relaxed);
                }
            }
            q
        }
    }

    #[global_allocator]
    static GLOBAL: Counting = Counting;

    /// Start a new peak at the bytes in use now; returns them.
    pub fn reset_peak() -> usize {
        let now = IN_USE.load(Relaxed);
        PEAK.store(now, Relaxed);
        now
    }

    /// Bytes in use now.
    pub fn in_use() -> usize {
        IN_USE.load(Relaxed)
    }

    /// The peak since the last reset.
    pub fn peak() -> usize {
        PEAK.load(Relaxed)
    }
}

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
