//! Real meshes from ../shared/data/meshes: counts against manifest.tsv
//! (computed by independent readers), repair of dirty files, typed errors
//! for invalid ones.

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use meshloom::io::{self, Error, ReadOptions};
use meshloom::Mesh;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/meshes");

/// manifest.tsv as one map of column name to value per file.
fn manifest() -> BTreeMap<String, HashMap<String, String>> {
    let text = std::fs::read_to_string(Path::new(DATA).join("manifest.tsv")).unwrap();
    let mut lines = text.lines();
    let names: Vec<&str> = lines.next().unwrap().split('\t').collect();
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let row: HashMap<String, String> = names
                .iter()
                .zip(l.split('\t'))
                .map(|(n, v)| (n.to_string(), v.to_string()))
                .collect();
            (row["path"].clone(), row)
        })
        .collect()
}

fn num(row: &HashMap<String, String>, col: &str) -> i64 {
    row[col]
        .parse()
        .unwrap_or_else(|_| panic!("{col} = {:?}", row[col]))
}

fn histogram(m: &Mesh) -> String {
    let mut h = BTreeMap::new();
    for f in m.faces() {
        *h.entry(m.face(f).unwrap().degree()).or_insert(0) += 1;
    }
    h.iter()
        .map(|(k, v)| format!("{k}:{v}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Whether the manifest says a strict read can hold the file as it is:
/// no defects but bowtie vertices (several open fans), which the half-edge
/// structure holds (the hole passes through the vertex once per fan).
fn clean(row: &HashMap<String, String>) -> bool {
    [
        "nonmanifold_edges",
        "orientation_conflict_edges",
        "duplicate_faces",
        "degenerate_faces",
        "unreferenced_vertices",
    ]
    .iter()
    .all(|c| num(row, c) == 0)
}

fn files_in(dir: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(Path::new(DATA).join(dir))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

fn rel(p: &Path) -> String {
    p.strip_prefix(DATA)
        .unwrap()
        .to_string_lossy()
        .replace('\\', "/")
}

/// Clean files load strictly with every figure of the manifest; the others
/// load with repair into a valid mesh whose report agrees with the manifest
/// where the two count the same thing.
fn check_dir(dir: &str, skip: &[&str]) {
    let manifest = manifest();
    let mut checked = 0;
    for path in files_in(dir) {
        let name = rel(&path);
        if skip.iter().any(|s| name.ends_with(s)) {
            continue;
        }
        let row = &manifest[&name];
        if clean(row) {
            let m = io::read(&path).unwrap_or_else(|e| panic!("{e}"));
            m.validate().unwrap();
            assert_eq!(m.vertex_count() as i64, num(row, "V"), "{name} V");
            assert_eq!(m.face_count() as i64, num(row, "F"), "{name} F");
            assert_eq!(m.edge_count() as i64, num(row, "E"), "{name} E");
            assert_eq!(histogram(&m), row["face_sizes"], "{name} face sizes");
            if num(row, "nonmanifold_vertices") == 0 {
                assert_eq!(
                    m.hole_count() as i64,
                    num(row, "boundary_loops"),
                    "{name} loops"
                );
            }
            assert_eq!(
                m.euler_characteristic(),
                num(row, "euler_char"),
                "{name} euler"
            );
        } else {
            let Err(err) = io::read(&path) else {
                panic!("{name} read strictly")
            };
            assert!(
                err.line().is_some() || err.byte_offset().is_some(),
                "{name}: {err}"
            );
            let (m, report) =
                io::read_with(&path, &ReadOptions::repair_all()).unwrap_or_else(|e| panic!("{e}"));
            m.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(!report.is_clean(), "{name}");
            assert_eq!(
                report.degenerate_faces as i64,
                num(row, "degenerate_faces"),
                "{name}"
            );
            if num(row, "degenerate_faces") == 0 {
                assert_eq!(
                    report.duplicate_faces as i64,
                    num(row, "duplicate_faces"),
                    "{name}"
                );
            }
            assert_eq!(
                m.face_count() as i64,
                num(row, "F") - (report.degenerate_faces + report.duplicate_faces) as i64,
                "{name}"
            );
        }
        checked += 1;
    }
    assert!(checked > 0);
}

#[test]
fn closed_meshes() {
    check_dir("closed", &[]);
}

#[test]
fn boundary_meshes() {
    check_dir("boundary", &[]);
}

#[test]
fn polygon_meshes_keep_their_polygons() {
    check_dir("polygons", &[]);
}

#[test]
fn stl_meshes() {
    check_dir("stl", &[]);
}

#[test]
fn large_res2() {
    check_dir("large", &["dragon_vrip.ply.gz"]);
}

#[test]
fn every_dirty_file_loads_with_repair_and_validates() {
    let manifest = manifest();
    for path in files_in("dirty") {
        let name = rel(&path);
        let row = &manifest[&name];
        let (m, report) =
            io::read_with(&path, &ReadOptions::repair_all()).unwrap_or_else(|e| panic!("{e}"));
        m.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(m.face_count() > 0, "{name}");
        assert!(m.face_count() as i64 <= num(row, "F"), "{name}: {report}");
        if num(row, "orientation_conflict_edges") > 0 && num(row, "nonmanifold_edges") == 0 {
            assert!(report.flipped_faces > 0, "{name}");
            assert_eq!(m.face_count() as i64, num(row, "F"), "{name}");
        }
    }
}

#[test]
fn flipped_faces_are_turned_back() {
    for name in [
        "dirty/cgal_tet-shuffled.off",
        "dirty/cgal_cube4-shuffled.off",
    ] {
        let path = Path::new(DATA).join(name);
        assert!(matches!(io::read(&path), Err(Error::Build { .. })));
        let (m, report) = io::read_with(&path, &ReadOptions::repair_all()).unwrap();
        assert!(report.flipped_faces > 0);
        assert!(m.is_closed(), "{name}");
        assert_eq!(m.euler_characteristic(), 2);
    }
}

#[test]
fn repeated_corners_collapse_instead_of_dropping_the_face() {
    let path = Path::new(DATA).join("dirty/openmesh_cube-minimal-degenerated.obj");
    let (m, report) = io::read_with(&path, &ReadOptions::repair_all()).unwrap();
    // "f 2 6 8 8 2" is the triangle 2 6 8 with two corners repeated; the two
    // all-repeated triangles go.
    assert_eq!(report.collapsed_corners, 2);
    assert_eq!((m.vertex_count(), m.face_count()), (8, 12));
    assert!(m.is_closed());
}

#[test]
fn every_invalid_file_gives_a_located_error() {
    for path in files_in("invalid") {
        let name = rel(&path);
        for options in [ReadOptions::strict(), ReadOptions::repair_all()] {
            let Err(err) = io::read_with(&path, &options) else {
                panic!("{name} read")
            };
            assert_eq!(
                err.location().path.as_deref(),
                Some(path.as_path()),
                "{name}"
            );
            let text = err.to_string();
            assert!(
                text.contains(path.file_name().unwrap().to_str().unwrap()),
                "{text}"
            );
            match err {
                Error::Empty { .. } => {
                    assert!(std::fs::metadata(&path).unwrap().len() < 64, "{text}")
                }
                _ => assert!(
                    err.line().is_some() || err.byte_offset().is_some(),
                    "{name}: {text}"
                ),
            }
        }
    }
}

#[test]
fn a_header_claiming_billions_allocates_nothing_for_them() {
    let path = Path::new(DATA).join("invalid/assimp_OutOfMemory.off");
    let err = io::read(&path).unwrap_err();
    assert!(matches!(err, Error::Header { .. }), "{err}");
    assert_eq!(err.line(), Some(2));
    assert!(err.to_string().contains("353535235358"), "{err}");
}

#[test]
fn invalid_files_say_what_was_wrong() {
    let cases = [
        (
            "assimp_malformed.obj",
            "vertex index 12 is out of range",
            23,
        ),
        (
            "assimp_malformed2.obj",
            "expected vertex indices after f",
            23,
        ),
        ("assimp_invalid.off", "face's corner count", 6),
        (
            "openscad_toomanyvertices.stl",
            "expected \"endloop\", found \"vertex\"",
            91,
        ),
        (
            "openscad_unparseable.stl",
            "expected a number, found \"\\x10\"",
            4,
        ),
    ];
    for (file, what, line) in cases {
        let err = io::read(Path::new(DATA).join("invalid").join(file)).unwrap_err();
        assert!(err.to_string().contains(what), "{file}: {err}");
        assert_eq!(err.line(), Some(line), "{file}: {err}");
    }
}

#[test]
fn full_dragon_through_gzip() {
    check_dir("large", &["dragon_vrip_res2.ply"]);
}

#[test]
fn an_unused_vertex_is_named_with_its_line() {
    let path = Path::new(DATA).join("dirty/cgal_cube-ouvert.off");
    let err = io::read(&path).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Unreferenced {
                count: 1,
                first: 8,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(err.line(), Some(11), "{err}");
}
