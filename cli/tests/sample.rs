//! `meshloom sample --inside`: the points lie inside the mesh, fill it
//! evenly, repeat with the seed, and an open sheet is refused.

use std::path::PathBuf;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_meshloom");

const OCTAHEDRON: &str = "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n\
3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("meshloom-sample-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("the binary runs")
}

fn points(csv: &std::path::Path) -> Vec<[f64; 3]> {
    let text = std::fs::read_to_string(csv).expect("the CSV was written");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|c| c.parse().expect("a number")).collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

#[test]
fn points_fill_the_octahedron_and_repeat_with_the_seed() {
    let dir = scratch("octa");
    let mesh = dir.join("octa.off");
    std::fs::write(&mesh, OCTAHEDRON).unwrap();
    let csv = |name: &str| dir.join(name);
    let mesh = mesh.to_str().unwrap();
    for (name, seed) in [("a.csv", "3"), ("b.csv", "3"), ("c.csv", "4")] {
        let out = run(&[
            "sample",
            mesh,
            csv(name).to_str().unwrap(),
            "--inside",
            "3000",
            "--seed",
            seed,
        ]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let a = points(&csv("a.csv"));
    assert_eq!(a.len(), 3000);
    assert!(a
        .iter()
        .all(|p| p.iter().map(|c| c.abs()).sum::<f64>() < 1.0));
    // Uniform: the octahedron holds 1/8 of its volume within |x|+|y|+|z| < 1/2.
    let core = a
        .iter()
        .filter(|p| p.iter().map(|c| c.abs()).sum::<f64>() < 0.5)
        .count();
    assert!(
        (250..500).contains(&core),
        "{core} of 3000 in the inner eighth"
    );
    assert_eq!(a, points(&csv("b.csv")));
    assert_ne!(a, points(&csv("c.csv")));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_open_sheet_encloses_no_volume() {
    let dir = scratch("sheet");
    let mesh = dir.join("sheet.off");
    std::fs::write(
        &mesh,
        "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 0.5\n3 0 1 2\n3 0 2 3\n",
    )
    .unwrap();
    let out = run(&[
        "sample",
        mesh.to_str().unwrap(),
        dir.join("x.csv").to_str().unwrap(),
        "--inside",
        "10",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no volume"));
    let _ = std::fs::remove_dir_all(&dir);
}
