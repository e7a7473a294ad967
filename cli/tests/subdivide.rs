//! `meshloom subdivide` on the library's one driver: the scheme and option
//! words are the library's, the option checks are the library's (a crease
//! column only for loop and catmull-clark), the report names the scheme.

use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_meshloom");
const BUNDLED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/elephant.off");

fn out_path(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!(
        "meshloom-cli-subdivide-{}-{name}",
        std::process::id()
    ))
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

fn json(o: &Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

#[test]
fn midpoint_faces_and_the_report_scheme() {
    let out = out_path("mid.obj");
    let out_s = out.to_str().unwrap();
    let o = run(&[
        "subdivide",
        BUNDLED,
        out_s,
        "--scheme",
        "midpoint",
        "--json",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let auto = json(&o);
    let faces = auto["report"]["input"]["faces"].as_u64().unwrap();
    assert_eq!(auto["report"]["scheme"], "midpoint");
    assert_eq!(auto["report"]["levels"][0]["output"]["faces"], 4 * faces);
    let o = run(&[
        "subdivide",
        BUNDLED,
        out_s,
        "--scheme",
        "midpoint",
        "--midpoint-faces",
        "quads",
        "--json",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        json(&o)["report"]["levels"][0]["output"]["faces"],
        3 * faces
    );
    let o = run(&[
        "subdivide",
        BUNDLED,
        out_s,
        "--scheme",
        "catmull-clark",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let j = json(&o);
    assert_eq!(j["scheme"], "catmull-clark");
    assert_eq!(j["report"]["scheme"], "catmull-clark");
    std::fs::remove_file(&out).unwrap();
}

#[test]
fn options_are_checked_by_the_library() {
    let out = out_path("bad.obj");
    let out_s = out.to_str().unwrap();
    for (scheme, extra, says) in [
        ("sqrt3", ["--crease-column", "sharpness"], "creases"),
        ("midpoint", ["--crease-column", "sharpness"], "creases"),
        ("loop", ["--crease-column", "sharpness"], "sharpness"),
        ("catmull-clark", ["--corner-column", "pinned"], "pinned"),
    ] {
        let mut args = vec!["subdivide", BUNDLED, out_s, "--scheme", scheme];
        args.extend(extra);
        let o = run(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!out.exists(), "nothing written on failure");
    }
    // A word the option does not take is a usage error that lists them.
    let o = run(&[
        "subdivide",
        BUNDLED,
        out_s,
        "--scheme",
        "midpoint",
        "--midpoint-faces",
        "hexagons",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("auto, quads, triangles"));
}
