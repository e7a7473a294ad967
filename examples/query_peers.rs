//! meshloom's side of the pypeers spatial-query workloads
//! (`../shared/peers/pypeers/README.md`): `ray_cast_random_{100k,2m}`,
//! `ray_cast_camera_{100k,2m}` (coherent rays from `bench/camera_rays.py`),
//! `closest_point_100k`, `winding_number_100k`, each with `.build`, on the
//! files of its `gen_inputs.py`, printed in its tab-separated format; and
//! meshloom's own `tree_update_1k_2m` (no peer: an update against a
//! rebuild) and `self_intersections_100k` (no peer in the kit).
//!
//! ```text
//! cargo run --release --example query_peers -- target/peers/inputs [ROUNDS]
//! ```
//!
//! Build without the `parallel` feature: one thread, as the peers run.
//! Reading files is outside the clock; the clock is process CPU time, as
//! the peers' (the wall time goes in the note). `BENCH_ONLY` (comma list)
//! filters the workloads.

use meshloom::query::{FaceTree, Ray, WindingMode};
use meshloom::{EdgeKey, Mesh};
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
    println!("# meshloom query_peers: rounds {rounds}, clock process CPU, one thread");
    let mut rays = None;
    for (name, file) in [
        ("ray_cast_random_100k", "torus_100k.off"),
        ("ray_cast_random_2m", "torus_2m.off"),
    ] {
        if !wanted(name) {
            continue;
        }
        let rays = rays.get_or_insert_with(|| read_rays(&dir.join("rays_1m.obj")));
        let mesh = meshloom::io::read(dir.join(file)).expect("mesh");
        ray_cast(name, &mesh, rays, rounds);
    }
    let camera = dir.join("rays_camera_1m.obj");
    let mut camera_rays = None;
    for (name, file) in [
        ("ray_cast_camera_100k", "torus_100k.off"),
        ("ray_cast_camera_2m", "torus_2m.off"),
    ] {
        if !wanted(name) {
            continue;
        }
        if !camera.exists() {
            println!(
                "# {name}: no {} (python3 bench/camera_rays.py writes it)",
                camera.display()
            );
            continue;
        }
        let rays = camera_rays.get_or_insert_with(|| read_rays(&camera));
        let mesh = meshloom::io::read(dir.join(file)).expect("mesh");
        ray_cast(name, &mesh, rays, rounds);
    }
    let torus = || meshloom::io::read(dir.join("torus_100k.off")).expect("mesh");
    let points = || read_points(&dir.join("points_100k.obj"));
    if wanted("closest_point_100k") {
        closest(&torus(), &points(), rounds);
    }
    if wanted("winding_number_100k") {
        winding(&torus(), &points(), rounds);
    }
    if wanted("self_intersections_100k") {
        self_intersections(&torus(), rounds);
    }
    if wanted("tree_update_1k_2m") {
        let mesh = meshloom::io::read(dir.join("torus_2m.off")).expect("mesh");
        update_1k(mesh, rounds);
    }
}

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}
unsafe extern "C" {
    fn clock_gettime(clk: i32, ts: *mut Timespec) -> i32;
}

/// The process's CPU seconds (Linux `CLOCK_PROCESS_CPUTIME_ID`).
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
/// runs of `f`, and its last result.
fn time<R>(rounds: usize, mut f: impl FnMut() -> R) -> ([f64; 4], R) {
    let (mut cpus, mut walls) = (Vec::new(), Vec::new());
    let mut out = None;
    for _ in 0..rounds.max(1) {
        let (t, c) = (Instant::now(), cpu());
        let r = f();
        cpus.push(cpu() - c);
        walls.push(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    cpus.sort_by(f64::total_cmp);
    walls.sort_by(f64::total_cmp);
    let n = cpus.len();
    (
        [cpus[n / 2], cpus[0], cpus[n - 1], walls[n / 2]],
        out.expect("one round"),
    )
}

/// One line of the peers' format: name, median, min, max, then the counts
/// before the first `;`, the wall median, the notes.
fn line(name: &str, t: [f64; 4], counts: &str, note: &str) {
    println!(
        "{name}\t{:.6}\t{:.6}\t{:.6}\t{counts}; wall {:.3}; threads 1; {note}",
        t[0], t[1], t[2], t[3]
    );
}

fn build_line(name: &str, mesh: &Mesh, rounds: usize) -> FaceTree {
    let (t, tree) = time(rounds, || FaceTree::build(mesh).expect("tree"));
    let per_face = tree.heap_bytes() as f64 / mesh.face_count() as f64;
    line(
        &format!("{name}.build"),
        t,
        &format!("{} F", mesh.face_count()),
        &format!("FaceTree::build, {per_face:.0} bytes a face"),
    );
    tree
}

fn ray_cast(name: &str, mesh: &Mesh, rays: &[Ray], rounds: usize) {
    let tree = build_line(name, mesh, rounds);
    let (t, hits) = time(rounds, || {
        let hits = tree.ray_cast_batch(mesh, rays).expect("rays");
        hits.iter().filter(|h| h.is_some()).count()
    });
    let rate = rays.len() as f64 / t[0];
    line(
        name,
        t,
        &format!("{hits} hits"),
        &format!(
            "{rate:.3e} rays/s; {} rays, ray_cast_batch (f64)",
            rays.len()
        ),
    );
}

fn closest(mesh: &Mesh, points: &[[f64; 3]], rounds: usize) {
    let name = "closest_point_100k";
    let tree = build_line(name, mesh, rounds);
    let (t, mean) = time(rounds, || {
        let c = tree.closest_points(mesh, points, None).expect("points");
        c.iter().map(|c| c.expect("a face").distance).sum::<f64>() / c.len() as f64
    });
    let rate = points.len() as f64 / t[0];
    line(
        name,
        t,
        &format!("{} points", points.len()),
        &format!("{rate:.3e} queries/s; closest_points (exact); mean distance {mean:.6}"),
    );
}

fn winding(mesh: &Mesh, points: &[[f64; 3]], rounds: usize) {
    let name = "winding_number_100k";
    let tree = build_line(name, mesh, rounds);
    let (t, inside) = time(rounds, || {
        let w = tree
            .winding_numbers(mesh, points, WindingMode::default())
            .expect("points");
        w.iter().filter(|&&w| w > 0.5).count()
    });
    let rate = points.len() as f64 / t[0];
    line(
        name,
        t,
        &format!("{} points", points.len()),
        &format!(
            "{rate:.3e} queries/s; {inside} inside (w > 0.5); three far-field terms, accuracy 2"
        ),
    );
}

fn self_intersections(mesh: &Mesh, rounds: usize) {
    let name = "self_intersections_100k";
    let tree = build_line(name, mesh, rounds);
    let (t, pairs) = time(rounds, || {
        tree.self_intersections(mesh).expect("pairs").len()
    });
    line(
        name,
        t,
        &format!("{pairs} pairs"),
        "FaceTree::self_intersections (exact predicates)",
    );
}

/// The `v` lines of an OBJ file.
fn read_points(path: &Path) -> Vec<[f64; 3]> {
    read_tagged(path, "v")
}

/// Rays: the k-th `v` is the origin, the k-th `vn` the direction.
fn read_rays(path: &Path) -> Vec<Ray> {
    let o = read_tagged(path, "v");
    let d = read_tagged(path, "vn");
    o.into_iter().zip(d).map(|(o, d)| Ray::new(o, d)).collect()
}

fn read_tagged(path: &Path, tag: &str) -> Vec<[f64; 3]> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            (w.next() == Some(tag)).then(|| {
                let mut p = [0.0; 3];
                for c in &mut p {
                    *c = w.next().expect("3 coordinates").parse().expect("a number");
                }
                p
            })
        })
        .collect()
}

/// `FaceTree::update` after 500 edge flips (1,000 faces changed), spread
/// over the 2M-triangle torus, against the build on the line before it.
/// The flips are outside the clock; each round flips other edges.
fn update_1k(mut mesh: Mesh, rounds: usize) {
    let name = "tree_update_1k_2m";
    mesh.history_mut().track_changes(true);
    let mut tree = build_line(name, &mesh, rounds);
    let edges: Vec<EdgeKey> = mesh.edges().collect();
    let mut next = 0usize;
    let (mut cpus, mut walls, mut changed) = (Vec::new(), Vec::new(), 0);
    for _ in 0..rounds.max(1) {
        let mut faces = 0;
        while faces < 1000 {
            // A stride coprime with the count: spread, each edge once.
            next = (next + 1_000_003) % edges.len();
            if mesh.flip_edge(edges[next]).is_ok() {
                faces += 2;
            }
        }
        let changes = mesh.history_mut().take_changes();
        let (t, c) = (Instant::now(), cpu());
        let report = tree.update(&mesh, &changes).expect("update");
        cpus.push(cpu() - c);
        walls.push(t.elapsed().as_secs_f64());
        assert!(!report.full_rebuild);
        changed = report.inserted_triangles;
    }
    cpus.sort_by(f64::total_cmp);
    walls.sort_by(f64::total_cmp);
    let n = cpus.len();
    line(
        name,
        [cpus[n / 2], cpus[0], cpus[n - 1], walls[n / 2]],
        &format!("{changed} triangles reinserted"),
        "FaceTree::update after 500 flips (1,000 faces)",
    );
}
