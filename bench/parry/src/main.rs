//! `parry-bench INPUTS [ROUNDS]`: parry3d-f64's `TriMesh` (its BVH build,
//! first-hit ray casts and closest points) on the pypeers kit's files,
//! printed in the kit's tab-separated line format under the workload names
//! of meshloom's `examples/query_peers.rs`, so `../shared/peers/ratios.py`
//! pairs them: `ray_cast_random_{100k,2m}`, `ray_cast_camera_{100k,2m}`
//! (the rays of `bench/camera_rays.py`) and `closest_point_100k`, each
//! with `.build`, and `.memory` lines (bytes a face held by the `TriMesh`,
//! counted by this program's allocator).
//!
//! One thread, process CPU time, the rounds in one process from a fresh
//! `TriMesh`; reading files is outside the clock. parry3d-f64 is the
//! `f64` build, as meshloom's tree answers in `f64`. Rays are cast with
//! `solid = false` and no length limit: the first hit on the surface, from
//! either side, as meshloom's `ray_cast`.

use parry3d_f64::math::Vector;
use parry3d_f64::query::{PointQuery, Ray, RayCast};
use parry3d_f64::shape::TriMesh;
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::time::Instant;

/// The system allocator, counting the bytes in use.
struct Counting;

static IN_USE: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is passed to the system allocator unchanged.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        IN_USE.fetch_add(l.size(), Relaxed);
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        IN_USE.fetch_sub(l.size(), Relaxed);
        unsafe { System.dealloc(p, l) }
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}
extern "C" {
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

/// CPU seconds (median, min, max), the median wall seconds, and the last
/// result of `rounds` runs of `f`.
fn time<R>(rounds: usize, mut f: impl FnMut() -> R) -> ([f64; 4], R) {
    let (mut cpus, mut walls, mut out) = (Vec::new(), Vec::new(), None);
    for _ in 0..rounds.max(1) {
        let (t, c) = (Instant::now(), cpu());
        out = Some(f());
        cpus.push(cpu() - c);
        walls.push(t.elapsed().as_secs_f64());
    }
    cpus.sort_by(f64::total_cmp);
    walls.sort_by(f64::total_cmp);
    let n = cpus.len();
    (
        [cpus[n / 2], cpus[0], cpus[n - 1], walls[n / 2]],
        out.unwrap(),
    )
}

fn line(name: &str, t: [f64; 4], counts: &str, note: &str) {
    println!(
        "{name}\t{:.6}\t{:.6}\t{:.6}\t{counts}; wall {:.3}; threads 1; {note}",
        t[0], t[1], t[2], t[3]
    );
}

/// An OFF file's vertices and triangles.
fn read_off(path: &Path) -> (Vec<Vector>, Vec<[u32; 3]>) {
    let text = std::fs::read_to_string(path).expect("read the OFF file");
    let mut lines = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .skip(1);
    let counts: Vec<usize> = lines
        .next()
        .expect("counts")
        .split_whitespace()
        .map(|x| x.parse().expect("a count"))
        .collect();
    let v: Vec<Vector> = (0..counts[0])
        .map(|_| {
            let p: Vec<f64> = lines
                .next()
                .expect("a vertex")
                .split_whitespace()
                .map(|x| x.parse().expect("a number"))
                .collect();
            Vector::new(p[0], p[1], p[2])
        })
        .collect();
    let f = (0..counts[1])
        .map(|_| {
            let c: Vec<u32> = lines
                .next()
                .expect("a face")
                .split_whitespace()
                .map(|x| x.parse().expect("an index"))
                .collect();
            assert_eq!(c[0], 3, "triangles only");
            [c[1], c[2], c[3]]
        })
        .collect();
    (v, f)
}

/// The `tag` lines (`v` or `vn`) of an OBJ file.
fn read_tagged(path: &Path, tag: &str) -> Vec<Vector> {
    let text = std::fs::read_to_string(path).expect("read the OBJ file");
    text.lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace();
            (it.next() == Some(tag)).then(|| {
                let p: Vec<f64> = it.map(|x| x.parse().expect("a number")).collect();
                Vector::new(p[0], p[1], p[2])
            })
        })
        .collect()
}

/// Build the TriMesh `rounds` times; print the `.build` and `.memory`
/// lines; return the last.
fn build(name: &str, mesh: &(Vec<Vector>, Vec<[u32; 3]>), rounds: usize) -> TriMesh {
    let faces = mesh.1.len();
    let (t, (tri, bytes)) = time(rounds, || {
        let (v, f) = (mesh.0.clone(), mesh.1.clone());
        let before = IN_USE.load(Relaxed);
        let tri = TriMesh::new(v, f).expect("a valid TriMesh");
        // The vertex and index arrays were counted before: add them back.
        let held = IN_USE.load(Relaxed) - before + 24 * mesh.0.len() + 12 * faces;
        (tri, held)
    });
    line(
        &format!("{name}.build"),
        t,
        &format!("{faces} F"),
        &format!(
            "TriMesh::new (its BVH), {:.0} bytes a face with its vertices and indices",
            bytes as f64 / faces as f64
        ),
    );
    tri
}

fn ray_cast(name: &str, mesh: &(Vec<Vector>, Vec<[u32; 3]>), rays: &[Ray], rounds: usize) {
    let tri = build(name, mesh, rounds);
    let (t, hits) = time(rounds, || {
        rays.iter()
            .filter(|r| tri.cast_local_ray(r, f64::MAX, false).is_some())
            .count()
    });
    line(
        name,
        t,
        &format!("{hits} hits"),
        &format!(
            "{:.3e} rays/s; {} rays, cast_local_ray (solid false)",
            rays.len() as f64 / t[0],
            rays.len()
        ),
    );
}

fn closest(mesh: &(Vec<Vector>, Vec<[u32; 3]>), points: &[Vector], rounds: usize) {
    let name = "closest_point_100k";
    let tri = build(name, mesh, rounds);
    let (t, mean) = time(rounds, || {
        let sum: f64 = points
            .iter()
            .map(|p| (tri.project_local_point(*p, false).point - *p).length())
            .sum();
        sum / points.len() as f64
    });
    line(
        name,
        t,
        &format!("{} points", points.len()),
        &format!(
            "{:.3e} queries/s; project_local_point (solid false); mean distance {mean:.6}",
            points.len() as f64 / t[0]
        ),
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = Path::new(args.get(1).map_or("target/peers/inputs", String::as_str));
    let rounds: usize = args.get(2).and_then(|r| r.parse().ok()).unwrap_or(3);
    let only = std::env::var("BENCH_ONLY").ok();
    let wanted = |name: &str| {
        only.as_deref()
            .is_none_or(|o| o.split(',').any(|w| w == name))
    };
    println!("# parry3d-f64 0.31 bench: rounds {rounds}, clock process CPU, one thread");
    for (kind, file) in [("random", "rays_1m.obj"), ("camera", "rays_camera_1m.obj")] {
        let mut rays = None;
        for tag in ["100k", "2m"] {
            let name = format!("ray_cast_{kind}_{tag}");
            if !wanted(&name) {
                continue;
            }
            let path = dir.join(file);
            if !path.exists() {
                println!("# {name}: no {}", path.display());
                continue;
            }
            let rays = rays.get_or_insert_with(|| {
                let o = read_tagged(&path, "v");
                let d = read_tagged(&path, "vn");
                o.into_iter()
                    .zip(d)
                    .map(|(o, d)| Ray::new(o, d))
                    .collect::<Vec<_>>()
            });
            let mesh = read_off(&dir.join(format!("torus_{tag}.off")));
            ray_cast(&name, &mesh, rays, rounds);
        }
    }
    if wanted("closest_point_100k") {
        let mesh = read_off(&dir.join("torus_100k.off"));
        let points = read_tagged(&dir.join("points_100k.obj"), "v");
        closest(&mesh, &points, rounds);
    }
}
