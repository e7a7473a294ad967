//! Every target over its committed seed corpus (and the crashes kept
//! there), as plain tests: CI replays them without AFL. Each corpus must
//! hold seeds, so a missing corpus fails rather than passes empty.

use std::path::Path;

fn replay(target: &str, body: fn(&[u8])) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus")
        .join(target);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{} holds no seeds", dir.display());
    for f in files {
        let data = std::fs::read(&f).unwrap();
        let run = std::panic::catch_unwind(|| body(&data));
        assert!(run.is_ok(), "{target} panics on {}", f.display());
    }
}

#[test]
fn obj() {
    replay("obj", meshloom_fuzz::obj);
}

#[test]
fn off() {
    replay("off", meshloom_fuzz::off);
}

#[test]
fn ply() {
    replay("ply", meshloom_fuzz::ply);
}

#[test]
fn stl() {
    replay("stl", meshloom_fuzz::stl);
}

#[test]
fn gzip() {
    replay("gzip", meshloom_fuzz::gzip);
}

#[test]
fn buffers() {
    replay("buffers", meshloom_fuzz::buffers);
}

#[test]
fn repair() {
    replay("repair", meshloom_fuzz::repair_target);
}

#[test]
fn serde() {
    replay("serde", meshloom_fuzz::serde);
}

#[test]
fn ops() {
    replay("ops", meshloom_fuzz::ops);
}

#[test]
fn gltf() {
    replay("gltf", meshloom_fuzz::gltf);
}

/// The synthetic seeds in code match the committed ones (rerun
/// `seeds.sh` after changing them).
#[test]
fn synthetic_seeds_are_committed() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus");
    for (target, name, bytes) in meshloom_fuzz::synthetic_seeds() {
        let path = root.join(target).join(&name);
        let committed = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(
            committed,
            bytes,
            "{} differs: rerun fuzz/seeds.sh",
            path.display()
        );
    }
}
