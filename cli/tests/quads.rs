//! `meshloom quads`: triangles joined into quads, stopped by `--delimit`.

mod common;

use common::{scratch, Scratch};
use std::path::Path;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_meshloom");

fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

/// Two unit cells in a row, each split on its diagonal; the last triangle
/// has its own material and its own UV island.
const STRIP: &str = "\
v 0 0 0
v 1 0 0
v 2 0 0
v 0 1 0
v 1 1 0
v 2 1 0
vt 0 0
vt 1 0
vt 2 0
vt 0 1
vt 1 1
vt 2 1
vt 5 5
vt 6 6
vt 7 7
usemtl a
f 1/1 2/2 5/5
f 1/1 5/5 4/4
f 2/2 3/3 6/6
usemtl b
f 2/7 6/8 5/9
";

fn quads(dir: &Scratch, input: &Path, extra: &[&str]) -> serde_json::Value {
    let out = dir.join("out.obj");
    let mut args = vec![
        "quads",
        input.to_str().unwrap(),
        out.to_str().unwrap(),
        "--json",
    ];
    args.extend_from_slice(extra);
    let o = run(&args);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

#[test]
fn triangles_join_unless_a_delimiter_keeps_their_edge() {
    let dir = scratch("quads-strip");
    let input = dir.join("strip.obj");
    std::fs::write(&input, STRIP).unwrap();
    let all = quads(&dir, &input, &[]);
    assert_eq!(
        (all["quads"].as_u64(), all["faces"].as_u64()),
        (Some(2), Some(2))
    );
    for word in ["material", "seams"] {
        let kept = quads(&dir, &input, &["--delimit", word]);
        assert_eq!(kept["quads"], 1, "{word}");
        assert_eq!(kept["triangles_left"], 2, "{word}");
    }
    let both = quads(&dir, &input, &["--delimit", "material,seams,sharp"]);
    assert_eq!(both["quads"], 1);
    assert_eq!(both["delimit"].as_array().unwrap().len(), 2);
    // A tight shape angle still joins the unit squares; written quads
    // read back as quads.
    let tight = quads(&dir, &input, &["--shape-angle", "1", "--face-angle", "0.5"]);
    assert_eq!(tight["quads"], 2);
    let written = std::fs::read_to_string(dir.join("out.obj")).unwrap();
    let faces: Vec<&str> = written.lines().filter(|l| l.starts_with("f ")).collect();
    assert_eq!(faces.len(), 2);
    assert!(faces.iter().all(|f| f.split_whitespace().count() == 5));
}

#[test]
fn bad_words_are_usage_errors() {
    let dir = scratch("quads-bad");
    let input = dir.join("strip2.obj");
    std::fs::write(&input, STRIP).unwrap();
    let out = dir.join("out2.obj");
    let (i, o) = (input.to_str().unwrap(), out.to_str().unwrap());
    assert_eq!(
        run(&["quads", i, o, "--delimit", "colour"]).status.code(),
        Some(2)
    );
    assert_eq!(
        run(&["quads", i, o, "--face-angle", "-3"]).status.code(),
        Some(2)
    );
}
