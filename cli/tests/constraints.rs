//! The constraint flags mean one thing in every command (issue 25): on an
//! open, noisy grid written to a file, `decimate`, `remesh`, `smooth` and
//! `fair` with `--boundary lock` leave every boundary vertex bit for bit, with
//! `--boundary slide` keep every boundary vertex on the input's boundary
//! polyline (within 1e-9 of the bounding box's diagonal), `smooth
//! --boundary free` moves some off it, and `--pinned COLUMN` vertices stay
//! bit for bit. The old flags still work, with a warning, as lock.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_meshloom");

type V3 = [f64; 3];

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("the meshloom binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn code(o: &Output) -> i32 {
    o.status.code().expect("an exit code")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "meshloom-cli-constraints-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn path_str(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// A 20 × 20 triangle grid (cells of 1): its positions, interior ones
/// jittered by a fixed LCG (±0.25 in x and y, ±0.3 in z), and triangles.
fn noisy_grid() -> (Vec<V3>, Vec<[usize; 3]>) {
    let n = 20;
    let mut state: u64 = 25;
    let mut noise = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64, j as f64);
            let (a, b, c) = (noise(), noise(), noise());
            if i == 0 || j == 0 || i == n || j == n {
                p.push([x, y, 0.0]);
            } else {
                p.push([x + 0.25 * a, y + 0.25 * b, 0.3 * c]);
            }
        }
    }
    let mut t = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            t.push([a, a + 1, a + n + 2]);
            t.push([a, a + n + 2, a + n + 1]);
        }
    }
    (p, t)
}

fn write_obj(path: &Path, p: &[V3], t: &[[usize; 3]]) {
    let mut s = String::new();
    for q in p {
        s.push_str(&format!("v {:?} {:?} {:?}\n", q[0], q[1], q[2]));
    }
    for f in t {
        s.push_str(&format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1));
    }
    std::fs::write(path, s).unwrap();
}

/// The grid as ASCII PLY with a `uchar pinned` vertex property.
fn write_ply(path: &Path, p: &[V3], t: &[[usize; 3]], pinned: &[bool]) {
    let mut s = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty double x\nproperty double y\n\
         property double z\nproperty uchar pinned\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        p.len(),
        t.len()
    );
    for (q, &pin) in p.iter().zip(pinned) {
        s.push_str(&format!(
            "{:?} {:?} {:?} {}\n",
            q[0],
            q[1],
            q[2],
            u8::from(pin)
        ));
    }
    for f in t {
        s.push_str(&format!("3 {} {} {}\n", f[0], f[1], f[2]));
    }
    std::fs::write(path, s).unwrap();
}

/// Positions and faces of an OBJ file (`v` and `f` lines).
fn read_obj(path: &Path) -> (Vec<V3>, Vec<Vec<usize>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut p = Vec::new();
    let mut f = Vec::new();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let c: Vec<f64> = it.take(3).map(|x| x.parse().unwrap()).collect();
                p.push([c[0], c[1], c[2]]);
            }
            Some("f") => f.push(
                it.map(|x| x.split('/').next().unwrap().parse::<usize>().unwrap() - 1)
                    .collect(),
            ),
            _ => {}
        }
    }
    (p, f)
}

/// The boundary edges (used by one face) as vertex index pairs.
fn boundary_edges(faces: &[Vec<usize>]) -> Vec<(usize, usize)> {
    let mut uses: HashMap<(usize, usize), usize> = HashMap::new();
    for f in faces {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    uses.into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(e, _)| e)
        .collect()
}

fn bits(p: V3) -> [u64; 3] {
    p.map(f64::to_bits)
}

/// The positions' bits of the boundary vertices.
fn boundary_bits(p: &[V3], faces: &[Vec<usize>]) -> HashSet<[u64; 3]> {
    boundary_edges(faces)
        .into_iter()
        .flat_map(|(a, b)| [bits(p[a]), bits(p[b])])
        .collect()
}

fn distance_to(segments: &[(V3, V3)], p: V3) -> f64 {
    let sub = |a: V3, b: V3| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: V3, b: V3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    segments
        .iter()
        .map(|&(a, b)| {
            let d = sub(b, a);
            let t = (dot(sub(p, a), d) / dot(d, d)).clamp(0.0, 1.0);
            let e = sub(p, [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]]);
            dot(e, e).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

fn diagonal(p: &[V3]) -> f64 {
    (0..3)
        .map(|k| {
            let lo = p.iter().map(|q| q[k]).fold(f64::INFINITY, f64::min);
            let hi = p.iter().map(|q| q[k]).fold(f64::NEG_INFINITY, f64::max);
            (hi - lo).powi(2)
        })
        .sum::<f64>()
        .sqrt()
}

/// Each command, with what it needs to run on the grid.
fn commands() -> [Vec<&'static str>; 4] {
    [
        vec!["decimate", "--ratio", "0.3"],
        vec!["remesh", "--iterations", "5"],
        vec!["smooth", "--method", "taubin"],
        vec!["fair", "--order", "2"],
    ]
}

/// Run `command` (its first word) on `input`, writing `output`, with
/// `extra` flags; exit 0 expected.
fn apply(command: &[&str], input: &Path, output: &Path, extra: &[&str]) -> Output {
    let mut args = vec![command[0], path_str(input), path_str(output)];
    args.extend(&command[1..]);
    args.extend(extra);
    let o = run(&args);
    assert_eq!(code(&o), 0, "{args:?}: {}", stderr(&o));
    o
}

#[test]
fn boundary_lock_slide_and_free_mean_one_thing() {
    let dir = scratch("boundary");
    let (p, t) = noisy_grid();
    let input = dir.join("grid.obj");
    write_obj(&input, &p, &t);
    let (p0, f0) = read_obj(&input);
    let before = boundary_bits(&p0, &f0);
    assert_eq!(before.len(), 80);
    let line: Vec<(V3, V3)> = boundary_edges(&f0)
        .into_iter()
        .map(|(a, b)| (p0[a], p0[b]))
        .collect();
    let tolerance = 1e-9 * diagonal(&p0);
    let out = dir.join("out.obj");
    for command in commands() {
        // Lock: every boundary vertex bit for bit, the boundary edges too.
        apply(&command, &input, &out, &["--boundary", "lock"]);
        let (p1, f1) = read_obj(&out);
        assert_eq!(boundary_bits(&p1, &f1), before, "{command:?} lock");
        assert_eq!(boundary_edges(&f1).len(), 80, "{command:?} lock");
        // Slide: on the input's boundary, and not all where they were.
        apply(&command, &input, &out, &["--boundary", "slide"]);
        let (p1, f1) = read_obj(&out);
        let after = boundary_bits(&p1, &f1);
        for q in &after {
            let d = distance_to(&line, q.map(f64::from_bits));
            assert!(d <= tolerance, "{command:?} slide: {q:?} is {d} off");
        }
        // Fairing spreads the boundary evenly, as the grid's already is.
        if command[0] != "fair" {
            assert_ne!(after, before, "{command:?} slide");
        }
    }
    // Free: smoothing moves boundary vertices off the boundary.
    apply(&commands()[2], &input, &out, &["--boundary", "free"]);
    let (p1, f1) = read_obj(&out);
    let off = boundary_bits(&p1, &f1)
        .into_iter()
        .filter(|q| distance_to(&line, q.map(f64::from_bits)) > tolerance)
        .count();
    assert!(
        off > 0,
        "smooth --boundary free moved nothing off the boundary"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn pinned_vertices_stay_bit_for_bit() {
    let dir = scratch("pinned");
    let (p, t) = noisy_grid();
    let pinned: Vec<bool> = (0..p.len()).map(|i| i % 7 == 3).collect();
    let input = dir.join("grid.ply");
    write_ply(&input, &p, &t, &pinned);
    let kept: Vec<[u64; 3]> = p
        .iter()
        .zip(&pinned)
        .filter(|&(_, &pin)| pin)
        .map(|(q, _)| bits(*q))
        .collect();
    let out = dir.join("out.obj");
    for command in commands() {
        for boundary in ["lock", "slide"] {
            apply(
                &command,
                &input,
                &out,
                &["--pinned", "pinned", "--boundary", boundary],
            );
            let (p1, _) = read_obj(&out);
            let after: HashSet<[u64; 3]> = p1.iter().map(|&q| bits(q)).collect();
            for q in &kept {
                assert!(after.contains(q), "{command:?} {boundary}: {q:?} moved");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn old_flags_warn_and_mean_lock() {
    let dir = scratch("old");
    let (p, t) = noisy_grid();
    let input = dir.join("grid.obj");
    write_obj(&input, &p, &t);
    let (p0, f0) = read_obj(&input);
    let before = boundary_bits(&p0, &f0);
    let out = dir.join("out.obj");
    for command in [&commands()[0], &commands()[1]] {
        let o = apply(command, &input, &out, &["--keep-boundary"]);
        assert!(
            stderr(&o).contains("--keep-boundary is deprecated; use --boundary lock"),
            "{}",
            stderr(&o)
        );
        let (p1, f1) = read_obj(&out);
        assert_eq!(boundary_bits(&p1, &f1), before, "{command:?}");
    }
    let o = apply(&commands()[2], &input, &out, &["--free-boundary"]);
    assert!(stderr(&o).contains("--boundary free"), "{}", stderr(&o));
    // The old flag and the new one together: a usage error.
    let o = run(&[
        "decimate",
        path_str(&input),
        path_str(&out),
        "--ratio",
        "0.3",
        "--keep-boundary",
        "--boundary",
        "slide",
    ]);
    assert_eq!(code(&o), 2, "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_words_and_missing_columns_are_refused() {
    let dir = scratch("bad");
    let (p, t) = noisy_grid();
    let input = dir.join("grid.obj");
    write_obj(&input, &p, &t);
    let out = dir.join("out.obj");
    // A word that is not free, slide or lock: a usage error naming them.
    let o = run(&[
        "smooth",
        path_str(&input),
        path_str(&out),
        "--boundary",
        "locked",
    ]);
    assert_eq!(code(&o), 2, "{}", stderr(&o));
    assert!(stderr(&o).contains("free, slide, lock"), "{}", stderr(&o));
    // The option enums' words are the library's, listed on a bad one.
    for (command, flag, words) in [
        ("smooth", "--method", "uniform, cotan, taubin, implicit"),
        ("fair", "--weights", "cotan, uniform"),
    ] {
        let o = run(&[command, path_str(&input), path_str(&out), flag, "bogus"]);
        assert_eq!(code(&o), 2, "{}", stderr(&o));
        assert!(stderr(&o).contains(words), "{command}: {}", stderr(&o));
    }
    for method in ["uniform", "cotan", "taubin", "implicit"] {
        apply(&["smooth", "--method", method], &input, &out, &[]);
    }
    // Columns the file does not have: bad input, nothing written.
    let _ = std::fs::remove_file(&out);
    for flag in ["--pinned", "--features"] {
        let o = run(&["smooth", path_str(&input), path_str(&out), flag, "nothing"]);
        assert_eq!(code(&o), 1, "{flag}: {}", stderr(&o));
        assert!(stderr(&o).contains(flag), "{}", stderr(&o));
        assert!(!out.exists());
    }
    let o = run(&[
        "fair",
        path_str(&input),
        path_str(&out),
        "--region",
        "nothing",
    ]);
    assert_eq!(code(&o), 1, "{}", stderr(&o));
    assert!(stderr(&o).contains("--region"), "{}", stderr(&o));
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fair_moves_its_region_only_and_reports() {
    let dir = scratch("fair");
    let (p, t) = noisy_grid();
    // The region: every seventh vertex (each surrounded by fixed ones).
    let region: Vec<bool> = (0..p.len()).map(|i| i % 7 == 3).collect();
    let input = dir.join("grid.ply");
    write_ply(&input, &p, &t, &region);
    let out = dir.join("out.obj");
    for order in ["1", "2", "3"] {
        for weights in ["cotan", "uniform"] {
            let o = apply(
                &["fair", "--order", order, "--weights", weights],
                &input,
                &out,
                &["--region", "pinned", "--json"],
            );
            let (p1, _) = read_obj(&out);
            assert_eq!(p1.len(), p.len());
            let mut moved = 0;
            for (i, (a, b)) in p.iter().zip(&p1).enumerate() {
                if region[i] {
                    moved += usize::from(bits(*a) != bits(*b));
                } else {
                    assert_eq!(bits(*a), bits(*b), "order {order}: vertex {i} moved");
                }
            }
            let inner = (0..p.len())
                .filter(|&i| region[i] && p[i][2] != 0.0)
                .count();
            // The rings next to the locked boundary stay too (order − 1).
            assert!(moved > 0 && moved <= inner, "order {order} {weights}");
            let json: serde_json::Value =
                serde_json::from_slice(&o.stdout).expect("one JSON object");
            assert_eq!(json["moved"], moved);
            assert!(json["fixed"].as_u64().unwrap() > 0);
            assert_eq!(json["weights"], weights);
            assert_eq!(json["order"], order.parse::<u32>().unwrap());
        }
    }
    // Order 4 is out of range: a usage error.
    let o = run(&["fair", path_str(&input), path_str(&out), "--order", "4"]);
    assert_eq!(code(&o), 2, "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}
