//! meshloom's side of the BMesh modelling-tool workloads
//! (`../shared/peers/bmesh/README.md`), on the files of its
//! `gen_inputs.py`, printed in its tab-separated format (the counts after
//! the tool, then the wall time and notes), so that
//! `../shared/peers/ratios.py` pairs the lines:
//!
//! ```text
//! cargo run --release --example model_peers -- target/peers/inputs [ROUNDS]
//! ```
//!
//! Each round runs the tool on a fresh copy of the input (the copy and the
//! selection are outside the clock, as the peer's are); the clock is
//! process CPU time. `BENCH_ONLY` (comma list) filters the workloads.

use meshloom::model::{
    DissolveLimitedOptions, ExtrudeOptions, InsetOptions, JoinTrianglesOptions, LoopCutOptions,
};
use meshloom::{FaceKey, Mesh};
use std::path::Path;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = Path::new(
        args.get(1)
            .map(String::as_str)
            .unwrap_or("target/peers/inputs"),
    );
    let rounds: usize = args.get(2).and_then(|r| r.parse().ok()).unwrap_or(3);
    let only = std::env::var("BENCH_ONLY").ok();
    let wanted = |name: &str| {
        only.as_deref()
            .is_none_or(|o| o.split(',').any(|w| w == name))
    };
    println!("# meshloom model_peers: rounds {rounds}, clock process CPU, one thread");
    let grid_tools = [
        "loop_cut_10",
        "extrude_region_half",
        "extrude_individual_all",
        "inset_individual_all",
        "inset_region_half",
    ];
    if grid_tools.iter().any(|w| wanted(w)) {
        let grid = meshloom::io::read(dir.join("quadgrid_1000x250.obj")).expect("quad grid");
        if wanted("loop_cut_10") {
            loop_cut_10(&grid, rounds);
        }
        if wanted("extrude_region_half") {
            extrude_region_half(&grid, rounds);
        }
        if wanted("extrude_individual_all") {
            extrude_individual_all(&grid, rounds);
        }
        if wanted("inset_individual_all") {
            inset(
                "inset_individual_all",
                &grid,
                grid.faces().collect(),
                true,
                rounds,
            );
        }
        if wanted("inset_region_half") {
            inset("inset_region_half", &grid, half_by_x(&grid), false, rounds);
        }
    }
    if wanted("dissolve_limited") {
        dissolve_limited(dir, rounds);
    }
    if wanted("join_triangles") {
        let tris = meshloom::io::read(dir.join("trigrid_500.obj")).expect("triangle grid");
        join_triangles(&tris, rounds);
    }
}

/// `join_triangles`: every face, Blender's 40° face and shape angles.
fn join_triangles(mesh: &Mesh, rounds: usize) {
    let options = JoinTrianglesOptions::default();
    let mut quads = 0;
    let (t, m) = time_fresh(rounds, mesh, |m| {
        quads = m.join_triangles(&options).expect("join").quads.len();
    });
    line("join_triangles", t, &counts(&m), &format!("{quads} quads"));
}

/// `dissolve_limited`: the whole triangulated grid at 5°, no delimiters,
/// no "all boundaries".
fn dissolve_limited(dir: &Path, rounds: usize) {
    let mesh = meshloom::io::read(dir.join("trigrid_500.obj")).expect("triangle grid");
    let options = DissolveLimitedOptions::default();
    let (t, m) = time_fresh(rounds, &mesh, |m| {
        m.dissolve_limited(&options).expect("dissolve");
    });
    line("dissolve_limited", t, &counts(&m), "");
}

/// `extrude_region_half`: the faces whose centroid's x is below the
/// median, extruded together by the mean edge length along +z.
fn extrude_region_half(mesh: &Mesh, rounds: usize) {
    let half = half_by_x(mesh);
    let options = ExtrudeOptions {
        distance: mean_edge_length(mesh),
        direction: Some([0.0, 0.0, 1.0]),
        individual: false,
    };
    let (t, m) = time_fresh(rounds, mesh, |m| {
        m.extrude_faces(&half, &options).expect("extrude");
    });
    line(
        "extrude_region_half",
        t,
        &counts(&m),
        &format!("{} faces", half.len()),
    );
}

/// `extrude_individual_all`: every face on its own, not moved.
fn extrude_individual_all(mesh: &Mesh, rounds: usize) {
    let all: Vec<FaceKey> = mesh.faces().collect();
    let options = ExtrudeOptions {
        individual: true,
        ..Default::default()
    };
    let (t, m) = time_fresh(rounds, mesh, |m| {
        m.extrude_faces(&all, &options).expect("extrude");
    });
    line("extrude_individual_all", t, &counts(&m), "");
}

/// `inset_individual_all` and `inset_region_half`: by 0.2 mean edge
/// lengths, even offset.
fn inset(name: &str, mesh: &Mesh, faces: Vec<FaceKey>, individual: bool, rounds: usize) {
    let options = InsetOptions {
        thickness: 0.2 * mean_edge_length(mesh),
        individual,
        ..Default::default()
    };
    let (t, m) = time_fresh(rounds, mesh, |m| {
        m.inset_faces(&faces, &options).expect("inset");
    });
    line(name, t, &counts(&m), &format!("{} faces", faces.len()));
}

/// The faces whose centroid (mean of its corners) has x below the median.
fn half_by_x(mesh: &Mesh) -> Vec<FaceKey> {
    let x = |f: FaceKey| {
        let vs: Vec<f64> = mesh
            .face(f)
            .expect("face")
            .vertices()
            .map(|v| mesh.position(v).expect("p")[0])
            .collect();
        vs.iter().sum::<f64>() / vs.len() as f64
    };
    let mut xs: Vec<f64> = mesh.faces().map(x).collect();
    xs.sort_by(f64::total_cmp);
    let median = xs[xs.len() / 2];
    mesh.faces().filter(|&f| x(f) < median).collect()
}

/// The mean length of the mesh's edges.
fn mean_edge_length(mesh: &Mesh) -> f64 {
    let total: f64 = mesh
        .edges()
        .map(|e| {
            let [a, b] = mesh.edge(e).expect("edge").vertices();
            let (p, q) = (mesh.position(a).expect("p"), mesh.position(b).expect("p"));
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
        })
        .sum();
    total / mesh.edge_count() as f64
}

/// `loop_cut_10`: ten cuts across the ring through face 0's first corner
/// edge (in corner order) that has a face on both sides.
fn loop_cut_10(mesh: &Mesh, rounds: usize) {
    let f0 = mesh.faces().next().expect("a face");
    let e = mesh
        .face(f0)
        .expect("face 0")
        .halfedges()
        .map(|h| mesh.halfedge(h).expect("live").edge())
        .find(|e| !e.is_boundary())
        .map(|e| e.key())
        .expect("an inner edge in face 0");
    let ring = mesh.edge_ring(e).expect("ring").keys.len();
    let options = LoopCutOptions {
        cuts: 10,
        ..Default::default()
    };
    let (t, m) = time_fresh(rounds, mesh, |m| {
        m.loop_cut(e, &options).expect("loop cut");
    });
    line("loop_cut_10", t, &counts(&m), &format!("ring {ring} edges"));
}

/// `N V M F` of `mesh`.
fn counts(mesh: &Mesh) -> String {
    format!("{} V {} F", mesh.vertex_count(), mesh.face_count())
}

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}

unsafe extern "C" {
    fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
}

/// Process CPU seconds.
fn cpu() -> f64 {
    let mut ts = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one Timespec through a valid pointer.
    unsafe { clock_gettime(2, &mut ts) };
    ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64
}

/// CPU seconds (median, min, max) and the median wall seconds of `rounds`
/// runs of `f`, each on a fresh copy of `mesh` made outside the clock;
/// the last copy, as `f` left it.
fn time_fresh(rounds: usize, mesh: &Mesh, mut f: impl FnMut(&mut Mesh)) -> ([f64; 4], Mesh) {
    let (mut cpus, mut walls) = (Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..rounds.max(1) {
        let mut m = mesh.clone();
        let (t, c) = (Instant::now(), cpu());
        f(&mut m);
        cpus.push(cpu() - c);
        walls.push(t.elapsed().as_secs_f64());
        last = Some(m);
    }
    cpus.sort_by(f64::total_cmp);
    walls.sort_by(f64::total_cmp);
    let n = cpus.len();
    (
        [cpus[n / 2], cpus[0], cpus[n - 1], walls[n / 2]],
        last.expect("one round"),
    )
}

/// One line of the peers' format.
fn line(name: &str, t: [f64; 4], counts: &str, note: &str) {
    println!(
        "{name}\t{:.6}\t{:.6}\t{:.6}\t{counts}; wall {:.3}; threads 1; {note}",
        t[0], t[1], t[2], t[3]
    );
}
