//! `meshloom dissolve IN OUT --limited DEG [--delimit ...]`: limited
//! dissolve of a whole file, delimited by material ids (always: they are
//! never merged away), UV seams and sharp edges on request.

mod common;

use common::{scratch, Scratch};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_meshloom");

fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

fn json(o: &Output) -> serde_json::Value {
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

/// A flat 2 × 1 strip of squares, two triangles each; the right square's
/// corners have their own texture coordinates (a UV seam at x = 1), and
/// with `materials` the squares have materials a and b.
fn strip(dir: &Scratch, name: &str, materials: bool) -> String {
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n");
    obj += "vt 0 0\nvt 0.5 0\nvt 0 0.5\nvt 0.5 0.5\nvt 0.6 0\nvt 1 0\nvt 0.6 0.5\nvt 1 0.5\n";
    if materials {
        obj += "usemtl a\n";
    }
    obj += "f 1/1 2/2 5/4\nf 1/1 5/4 4/3\n";
    if materials {
        obj += "usemtl b\n";
    }
    obj += "f 2/5 3/6 6/8\nf 2/5 6/8 5/7\n";
    let p = dir.join(name);
    std::fs::write(&p, obj).unwrap();
    p.to_str().unwrap().to_owned()
}

#[test]
fn a_flat_strip_becomes_one_face_or_stops_at_delimiters() {
    let dir = scratch("dissolve-strip");
    let out = dir.join("out.obj");
    let out = out.to_str().unwrap();
    let plain = strip(&dir, "plain.obj", false);
    let r = json(&run(&["dissolve", &plain, out, "--limited", "5", "--json"]));
    assert_eq!(
        (r["faces_before"].as_u64(), r["faces"].as_u64()),
        (Some(4), Some(1))
    );
    assert_eq!(r["vertices"].as_u64(), Some(4));
    // The seam keeps the middle edge: two squares.
    let r = json(&run(&[
        "dissolve",
        &plain,
        out,
        "--limited",
        "5",
        "--delimit",
        "seams",
        "--json",
    ]));
    assert_eq!(r["faces"].as_u64(), Some(2));
    // Material ids are never merged away, named or not.
    let mats = strip(&dir, "mats.obj", true);
    for extra in [&[][..], &["--delimit", "material"][..]] {
        let mut args = vec!["dissolve", &mats, out, "--limited", "5", "--json"];
        args.extend_from_slice(extra);
        assert_eq!(json(&run(&args))["faces"].as_u64(), Some(2));
    }
    // The written file holds the result.
    let o = run(&["dissolve", &plain, out, "--limited", "5"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("4 faces → 1"));
    let text = std::fs::read_to_string(out).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 1);
}

#[test]
fn a_missing_column_or_a_bad_angle_fails() {
    let dir = scratch("dissolve-bad");
    let out = dir.join("bad.obj");
    let out = out.to_str().unwrap();
    let plain = strip(&dir, "bad-in.obj", false);
    let o = run(&[
        "dissolve",
        &plain,
        out,
        "--limited",
        "5",
        "--delimit",
        "sharp",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("sharp"));
    let o = run(&["dissolve", &plain, out, "--limited", "-1"]);
    assert_eq!(o.status.code(), Some(2));
    let o = run(&[
        "dissolve",
        &plain,
        out,
        "--limited",
        "5",
        "--delimit",
        "colour",
    ]);
    assert_eq!(o.status.code(), Some(2));
}
