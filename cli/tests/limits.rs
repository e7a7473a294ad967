//! The `meshloom` binary on requests past their limits and on values the
//! output format cannot hold: a clear refusal with exit 1 (input), no
//! output file, no memory exhausted.

use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_meshloom");
const BUNDLED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/elephant.off");
const REPROS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/repros");

fn out_path(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("meshloom-cli-limits-{}-{name}", std::process::id()))
}

/// Eight levels of the 5,558-triangle elephant would be 364M faces: the
/// run is refused at once with the estimate (it was killed for memory).
#[test]
fn subdivide_past_max_faces_is_refused_with_the_estimate() {
    let out = out_path("sub.obj");
    for scheme in ["loop", "catmull-clark", "sqrt3", "midpoint"] {
        let o = Command::new(BIN)
            .args([
                "subdivide",
                BUNDLED,
                out.to_str().unwrap(),
                "--scheme",
                scheme,
                "--levels",
                "8",
            ])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{scheme}: {err}");
        assert!(
            err.contains("max_faces") && err.contains("faces"),
            "{scheme}: {err}"
        );
        assert!(!out.exists());
    }
    // A raised limit lets one level through.
    let o = Command::new(BIN)
        .args([
            "subdivide",
            BUNDLED,
            out.to_str().unwrap(),
            "--scheme",
            "loop",
            "--max-faces",
            "30000",
        ])
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    std::fs::remove_file(&out).unwrap();
}

/// STL holds f32: 1e300 and 1e-300 are refused by `convert`, naming the
/// vertex, instead of writing inf or 0.
#[test]
fn convert_to_stl_refuses_coordinates_f32_cannot_hold() {
    for name in ["big1e300.obj", "tiny1e-300.obj"] {
        let out = out_path("x.stl");
        let o = Command::new(BIN)
            .args([
                "convert",
                &format!("{REPROS}/{name}"),
                out.to_str().unwrap(),
            ])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_ne!(o.status.code(), Some(0), "{name}");
        assert!(
            err.contains("vertex") && err.contains("32-bit"),
            "{name}: {err}"
        );
        assert!(!out.exists(), "{name}: a file was written");
    }
}

/// Holes with more rim edges than --max-refined-rim are triangulated but
/// not refined, and the report counts them.
#[test]
fn fill_holes_leaves_rims_over_the_bound_unrefined() {
    let input = out_path("cone.obj");
    let mut obj = String::new();
    for k in 0..12 {
        let a = std::f64::consts::TAU * f64::from(k) / 12.0;
        obj += &format!("v {} {} 0\n", a.cos(), a.sin());
    }
    obj += "v 0 0 -1\n";
    for k in 0..12 {
        obj += &format!("f {} {} 13\n", (k + 1) % 12 + 1, k + 1);
    }
    std::fs::write(&input, obj).unwrap();
    let out = out_path("filled.obj");
    let run = |bound: &str| {
        let o = Command::new(BIN)
            .args([
                "fill-holes",
                input.to_str().unwrap(),
                out.to_str().unwrap(),
                "--refine",
                "--max-refined-rim",
                bound,
                "--json",
            ])
            .output()
            .unwrap();
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    assert!(run("11").contains("\"unrefined\":1"), "{}", run("11"));
    assert!(run("12").contains("\"unrefined\":0"), "{}", run("12"));
    std::fs::remove_file(&input).unwrap();
    std::fs::remove_file(&out).unwrap();
}
