//! meshloom's side of the pypeers spatial-query workloads
//! (`../shared/peers/pypeers/README.md`): `ray_cast_random_{100k,2m}`,
//! `closest_point_100k`, `winding_number_100k`, each with `.build`, on the
//! files of its `gen_inputs.py`, printed in its tab-separated format.
//!
//! ```text
//! cargo run --release --example query_peers -- target/peers/inputs [ROUNDS]
//! ```
//!
//! Build without the `parallel` feature: one thread, as the peers run.
//! Reading files is outside the clock; the clock is the wall clock (the
//! peers report process CPU time, equal to wall for one busy thread on an
//! idle core). `BENCH_ONLY` (comma list) filters the workloads.

use meshloom::query::{FaceTree, Ray, WindingMode};
use meshloom::Mesh;
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
    println!("# meshloom query_peers: rounds {rounds}, clock wall, one thread");
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
    let torus = || meshloom::io::read(dir.join("torus_100k.off")).expect("mesh");
    let points = || read_points(&dir.join("points_100k.obj"));
    if wanted("closest_point_100k") {
        closest(&torus(), &points(), rounds);
    }
    if wanted("winding_number_100k") {
        winding(&torus(), &points(), rounds);
    }
}

/// Median, min and max of `rounds` runs of `f`, and its last result.
fn time<R>(rounds: usize, mut f: impl FnMut() -> R) -> ([f64; 3], R) {
    let mut times = Vec::new();
    let mut out = None;
    for _ in 0..rounds.max(1) {
        let t = Instant::now();
        let r = f();
        times.push(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    times.sort_by(f64::total_cmp);
    (
        [times[times.len() / 2], times[0], times[times.len() - 1]],
        out.expect("one round"),
    )
}

fn line(name: &str, t: [f64; 3], note: &str) {
    println!("{name}\t{:.6}\t{:.6}\t{:.6}\t{note}", t[0], t[1], t[2]);
}

fn build_line(name: &str, mesh: &Mesh, rounds: usize) -> FaceTree {
    let (t, tree) = time(rounds, || FaceTree::build(mesh).expect("tree"));
    let per_face = tree.heap_bytes() as f64 / mesh.face_count() as f64;
    line(
        &format!("{name}.build"),
        t,
        &format!(
            "{} F; threads 1; FaceTree::build, {per_face:.0} bytes a face",
            mesh.face_count()
        ),
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
        &format!(
            "{hits} hits; threads 1; {rate:.3e} rays/s; {} rays, ray_cast_batch (f64)",
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
        &format!("{} points; threads 1; {rate:.3e} queries/s; closest_points (exact), mean dist {mean:.6}", points.len()),
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
        &format!("{} points; threads 1; {rate:.3e} queries/s; {inside} inside (w > 0.5); dipoles, accuracy 2", points.len()),
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
