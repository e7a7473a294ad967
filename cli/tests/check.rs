//! `meshloom check --self-intersections`: a clean mesh exits 0, two
//! crossing tetrahedra exit 1 and name the crossing faces.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_meshloom");

/// Two tetrahedra, the second moved by 0.2 on every axis (faces 0–3 and
/// 4–7); `shift` 2.0 moves it clear of the first.
fn tetrahedra(shift: f64) -> String {
    let mut s = String::from("OFF\n8 8 0\n");
    for d in [0.0, shift] {
        for p in [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ] {
            s.push_str(&format!("{} {} {}\n", p[0] + d, p[1] + d, p[2] + d));
        }
    }
    for o in [0, 4] {
        for f in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
            s.push_str(&format!("3 {} {} {}\n", f[0] + o, f[1] + o, f[2] + o));
        }
    }
    s
}

/// A scratch directory that removes itself when the test ends.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Scratch {
        let dir =
            std::env::temp_dir().join(format!("meshloom-check-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir");
        Scratch(dir)
    }
    fn file(&self, name: &str, text: &str) -> String {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("the binary runs")
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

#[test]
fn a_clean_mesh_exits_0() {
    let dir = Scratch::new("clean");
    let apart = dir.file("apart.off", &tetrahedra(2.0));
    let out = run(&["check", &apart, "--self-intersections"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    assert!(
        text(&out).contains(": 0 self-intersecting face pairs"),
        "{}",
        text(&out)
    );
    let cube = Path::new("../../shared/data/meshes/closed/cgal_cube.off");
    if cube.exists() {
        let out = run(&["check", cube.to_str().unwrap(), "--self-intersections"]);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    }
}

#[test]
fn crossing_tetrahedra_exit_1_and_name_the_pairs() {
    let dir = Scratch::new("crossing");
    let path = dir.file("crossing.off", &tetrahedra(0.2));
    let out = run(&["check", &path, "--self-intersections"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    let shown: Vec<(usize, usize)> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| {
            let mut w = l.trim().strip_prefix("faces ")?.split(' ');
            Some((w.next()?.parse().ok()?, w.next()?.parse().ok()?))
        })
        .collect();
    assert!(shown.len() >= 3, "{}", text(&out));
    assert!(
        shown.iter().all(|&(a, b)| a < 4 && (4..8).contains(&b)),
        "{shown:?}"
    );
    let json = run(&["check", &path, "--self-intersections", "--json"]);
    assert_eq!(json.status.code(), Some(1), "{}", text(&json));
    let v: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(v["self_intersections"], serde_json::json!(shown.len()));
    assert_eq!(v["pairs"][0], serde_json::json!([shown[0].0, shown[0].1]));
    // No check named: a usage error.
    assert_eq!(run(&["check", &path]).status.code(), Some(2));
}
