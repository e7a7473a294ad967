//! The `meshloom` binary, run as a user would: figures checked against the
//! shared data's independent manifest, exit codes, messages, help texts,
//! round trips and pictures.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_meshloom");
const BUNDLED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/elephant.off");
const SHARED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/meshes");

fn shared(rel: &str) -> String {
    format!("{SHARED}/{rel}")
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("the meshloom binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit code, with the output shown when an assertion fails.
fn code(o: &Output) -> i32 {
    o.status.code().unwrap_or_else(|| {
        panic!(
            "killed by a signal\nstdout: {}\nstderr: {}",
            stdout(o),
            stderr(o)
        )
    })
}

fn json(o: &Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}): {}\nstderr: {}", stdout(o), stderr(o)))
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("meshloom-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn path_str(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// The manifest row of `rel` as column name -> value.
fn manifest(rel: &str) -> std::collections::HashMap<String, String> {
    let text = std::fs::read_to_string(shared("manifest.tsv")).expect("manifest.tsv");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split('\t').collect();
    let row = lines
        .map(|l| l.split('\t').collect::<Vec<_>>())
        .find(|r| r[0] == rel)
        .unwrap_or_else(|| panic!("{rel} not in manifest"));
    header
        .iter()
        .zip(row)
        .map(|(h, v)| (h.to_string(), v.to_string()))
        .collect()
}

#[test]
fn stats_on_bundled_mesh_prints_its_figures() {
    let o = run(&["stats", BUNDLED]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let text = stdout(&o);
    for line in [
        "vertices              2775",
        "edges                 8337",
        "faces                 5558",
        "holes                 0",
        "components            1",
        "Euler characteristic  -4",
        "genus                 3",
        "face degrees          3: 5558",
    ] {
        assert!(text.contains(line), "missing {line:?} in\n{text}");
    }
    // Not a terminal: no progress output.
    assert_eq!(stderr(&o), "");
}

#[test]
fn stats_json_matches_the_independent_manifest() {
    let files = [
        "closed/cgal_elephant.off",
        "closed/pyvista_ant.ply",
        "boundary/cgal_holes.off",
        "boundary/cgal_quads_to_stitch.off",
        "polygons/cgal_double-torus-3-holes.off",
        "polygons/cgal_3torus.off",
        "polygons/geomview_dodec.off",
        "stl/occt_sh1.stl",
    ];
    for rel in files {
        let m = manifest(rel);
        let o = run(&["stats", "--json", &shared(rel)]);
        assert_eq!(code(&o), 0, "{rel}: {}", stderr(&o));
        let j = json(&o);
        let n = |key: &str| {
            j[key]
                .as_i64()
                .unwrap_or_else(|| panic!("{rel}: {key} in {j}"))
        };
        let want = |col: &str| -> i64 { m[col].parse().unwrap_or_else(|_| panic!("{rel}: {col}")) };
        assert_eq!(n("vertices"), want("V"), "{rel} V");
        assert_eq!(n("edges"), want("E"), "{rel} E");
        assert_eq!(n("faces"), want("F"), "{rel} F");
        assert_eq!(n("boundary_edges"), want("boundary_edges"), "{rel}");
        assert_eq!(n("boundary_loops"), want("boundary_loops"), "{rel}");
        assert_eq!(n("holes"), want("boundary_loops"), "{rel}");
        assert_eq!(n("components"), want("components"), "{rel}");
        assert_eq!(n("euler_characteristic"), want("euler_char"), "{rel}");
        assert_eq!(j["closed"], m["closed"] == "True", "{rel}");
        if !m["genus"].is_empty() {
            assert_eq!(n("genus"), want("genus"), "{rel} genus");
        }
        if m["closed"] != "True" {
            assert!(j["genus"].is_null(), "{rel}: genus of an open mesh");
        }
        let histogram: Vec<String> = j["face_degrees"]
            .as_object()
            .expect("histogram")
            .iter()
            .map(|(d, c)| format!("{d}:{c}"))
            .collect();
        let mut expected: Vec<&str> = m["face_sizes"].split(' ').collect();
        expected.sort_by_key(|s| s.split(':').next().and_then(|d| d.parse::<u32>().ok()));
        assert_eq!(histogram, expected, "{rel} face sizes");
        assert!(j["file"].as_str().is_some_and(|f| f.ends_with(rel)));
    }
}

#[test]
fn stats_repair_reports_what_was_repaired() {
    let rel = "dirty/meshio_bun_zipper_res4.ply";
    let strict = run(&["stats", &shared(rel)]);
    assert_eq!(code(&strict), 1);
    let o = run(&["stats", "--repair", "--json", &shared(rel)]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let j = json(&o);
    assert!(
        j["repairs"]["nonmanifold_edges"]
            .as_u64()
            .is_some_and(|n| n > 0),
        "{j}"
    );
    assert!(j["faces"].as_u64().is_some_and(|n| n > 0));
}

#[test]
fn validate_accepts_clean_files() {
    for file in [
        BUNDLED.to_string(),
        shared("polygons/cgal_P.off"),
        shared("boundary/cgal_holes.off"),
    ] {
        let o = run(&["validate", &file]);
        assert_eq!(code(&o), 0, "{file}: {}", stderr(&o));
        assert!(stdout(&o).contains("valid"), "{}", stdout(&o));
        assert!(stdout(&o).contains(&file));
    }
    let o = run(&["validate", "--json", BUNDLED]);
    assert_eq!(code(&o), 0);
    let j = json(&o);
    assert_eq!(j["valid"], true);
    assert_eq!(j["faces"], 5558);
}

/// The line number in `FILE:LINE:` of a message about `rel`.
fn line_named(message: &str, rel: &str) -> usize {
    let after = message
        .split_once(&format!("{rel}:"))
        .unwrap_or_else(|| panic!("{rel} not named in {message}"))
        .1;
    after
        .split(':')
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no line number after {rel} in {message}"))
}

/// Line `n` (from 1) of a shared file, as tokens.
fn tokens_of_line(rel: &str, n: usize) -> Vec<String> {
    let text = std::fs::read_to_string(shared(rel)).expect("text file");
    let line = text.lines().nth(n - 1).expect("line exists");
    line.split_whitespace().map(str::to_owned).collect()
}

#[test]
fn validate_rejects_bad_files_naming_file_and_line() {
    // A face with no corners: the line holds just "0".
    let rel = "invalid/assimp_invalid.off";
    let o = run(&["validate", &shared(rel)]);
    assert_eq!(code(&o), 1, "{rel}: {}", stdout(&o));
    let n = line_named(&stderr(&o), rel);
    assert_eq!(tokens_of_line(rel, n), ["0"], "{}", stderr(&o));

    // An edge shared by three faces: the line named is a face using both
    // ends of the edge the message names.
    let rel = "dirty/meshio_bun_zipper_res4.ply";
    let o = run(&["validate", &shared(rel)]);
    assert_eq!(code(&o), 1, "{rel}: {}", stdout(&o));
    let err = stderr(&o);
    assert!(err.contains("more than two faces"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let n = line_named(&err, rel);
    let (a, b) = err
        .split_once("edge ")
        .and_then(|(_, r)| r.split_once(' '))
        .and_then(|(ab, _)| ab.split_once('-'))
        .expect("the message names the edge a-b");
    let face = tokens_of_line(rel, n);
    assert!(
        face[1..].contains(&a.to_string()) && face[1..].contains(&b.to_string()),
        "line {n}: {face:?} vs {err}"
    );

    let o = run(&["validate", "--json", &shared(rel)]);
    assert_eq!(code(&o), 1);
    let j = json(&o);
    assert_eq!(j["valid"], false);
    assert_eq!(j["line"], n);
    assert_eq!(j["repairable"], true);
    assert!(j["error"]
        .as_str()
        .is_some_and(|e| e.contains("more than two faces")));
}

#[test]
fn no_input_file_makes_it_panic() {
    let dir = std::fs::read_dir(shared("invalid")).expect("invalid/");
    let mut seen = 0;
    for entry in dir {
        let path = entry.expect("entry").path();
        let file = path_str(&path);
        for command in ["stats", "validate"] {
            let o = run(&[command, file]);
            let c = code(&o);
            assert!(
                c == 0 || c == 1,
                "{command} {file}: exit {c}\n{}",
                stderr(&o)
            );
            assert!(!stderr(&o).contains("panicked"), "{file}: {}", stderr(&o));
            if c == 1 {
                assert!(stderr(&o).contains("meshloom: error:"), "{}", stderr(&o));
            }
        }
        seen += 1;
    }
    assert!(seen >= 10);
    let o = run(&["stats", "/no/such/dir/mesh.off"]);
    assert_eq!(code(&o), 1);
    assert!(
        stderr(&o).contains("/no/such/dir/mesh.off"),
        "{}",
        stderr(&o)
    );
    // Outputs that cannot be written are failures naming the file.
    for (command, out) in [
        ("convert", "/no/such/dir/out.ply"),
        ("render", "/no/such/dir/out.png"),
    ] {
        let o = run(&[command, BUNDLED, out]);
        assert_eq!(code(&o), 1, "{command}");
        assert!(stderr(&o).contains(out), "{}", stderr(&o));
    }
}

#[test]
fn convert_round_trips_through_every_format() {
    let dir = scratch("convert");
    let mut previous = BUNDLED.to_string();
    for ext in ["ply", "obj", "stl", "off.gz", "off"] {
        let out = dir.join(format!("elephant.{ext}"));
        let o = run(&["convert", &previous, path_str(&out)]);
        assert_eq!(code(&o), 0, "{ext}: {}", stderr(&o));
        assert!(stdout(&o).contains("wrote"));
        let s = json(&run(&["stats", "--json", path_str(&out)]));
        assert_eq!(
            (&s["vertices"], &s["edges"], &s["faces"], &s["genus"]),
            (&2775.into(), &8337.into(), &5558.into(), &3.into()),
            "{ext}"
        );
        previous = path_str(&out).to_string();
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn convert_reads_and_writes_gltf() {
    let dir = scratch("convert-gltf");
    let obj = dir.join("box.obj");
    let o = run(&["convert", &shared("gltf/BoxTextured.glb"), path_str(&obj)]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(
        stdout(&o).contains("8 vertices, 12 faces"),
        "{}",
        stdout(&o)
    );
    // The UVs and normals went to the OBJ as vt and vn lines.
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(text.lines().any(|l| l.starts_with("vt ")));
    assert!(text.lines().any(|l| l.starts_with("vn ")));
    for ext in ["gltf", "glb"] {
        let out = dir.join(format!("box.{ext}"));
        let o = run(&["convert", path_str(&obj), path_str(&out)]);
        assert_eq!(code(&o), 0, "{ext}: {}", stderr(&o));
        let s = json(&run(&["stats", "--json", path_str(&out)]));
        assert_eq!(
            (&s["vertices"], &s["faces"]),
            (&8.into(), &12.into()),
            "{ext}"
        );
    }
    let bad = run(&[
        "convert",
        &shared("gltf/invalid/BoxWithInfinites.glb"),
        path_str(&obj),
    ]);
    assert_ne!(code(&bad), 0);
    assert!(stderr(&bad).contains("non-finite"), "{}", stderr(&bad));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn repair_writes_a_valid_mesh_and_reports() {
    let dir = scratch("repair");
    let out = dir.join("bunny.off");
    let input = shared("dirty/meshio_bun_zipper_res4.ply");
    let o = run(&["repair", &input, path_str(&out), "--json"]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let j = json(&o);
    assert_eq!(j["clean"], false);
    assert!(
        j["repairs"]["duplicate_faces"]
            .as_u64()
            .is_some_and(|n| n > 0),
        "{j}"
    );
    let v = run(&["validate", path_str(&out)]);
    assert_eq!(code(&v), 0, "{}", stderr(&v));
    // Text report on a clean file says so.
    let o = run(&["repair", BUNDLED, path_str(&dir.join("e.obj"))]);
    assert_eq!(code(&o), 0);
    assert!(stdout(&o).contains("no repairs needed"), "{}", stdout(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn usage_errors_exit_2() {
    let cases: [&[&str]; 8] = [
        &[],
        &["frobnicate"],
        &["stats"],
        &["stats", "mesh.xyz"],
        &["convert", BUNDLED],
        &["render", BUNDLED, "out.jpg"],
        &["render", BUNDLED, "out.png", "--size", "0x10"],
        &[
            "render",
            BUNDLED,
            "out.png",
            "--size",
            "8192x8192",
            "--supersample",
            "2",
        ],
    ];
    for args in cases {
        let o = run(args);
        assert_eq!(code(&o), 2, "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("Usage") || stderr(&o).contains("error"),
            "{args:?}"
        );
        assert_eq!(stdout(&o), "");
    }
    let o = run(&["render", BUNDLED, "x.png", "--view", "sideways"]);
    assert_eq!(code(&o), 2);
    assert!(stderr(&o).contains("iso"), "{}", stderr(&o));
}

#[test]
fn every_command_has_help_with_an_example() {
    let o = run(&["--help"]);
    assert_eq!(code(&o), 0);
    assert!(stdout(&o).contains("Examples:"));
    for command in [
        "stats",
        "components",
        "validate",
        "convert",
        "repair",
        "triangulate",
        "fill-holes",
        "render",
    ] {
        assert!(
            stdout(&o).contains(command),
            "top-level help lists {command}"
        );
        let o = run(&[command, "--help"]);
        assert_eq!(code(&o), 0, "{command}");
        let text = stdout(&o);
        assert!(text.contains("Example:"), "{command}: {text}");
        assert!(
            text.contains(&format!("meshloom {command} ")),
            "{command}: {text}"
        );
    }
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let dir = scratch("render");
    let out = dir.join("elephant.png");
    let o = run(&[
        "render",
        BUNDLED,
        path_str(&out),
        "--size",
        "120x90",
        "--wireframe",
        "--flat",
        "--view",
        "front",
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
    let bytes = std::fs::read(&out).expect("png written");
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    // IHDR: width and height, big endian, right after the chunk header.
    let width = u32::from_be_bytes([bytes[16], bytes[17], bytes[18], bytes[19]]);
    let height = u32::from_be_bytes([bytes[20], bytes[21], bytes[22], bytes[23]]);
    assert_eq!((width, height), (120, 90));

    let open = dir.join("holes.png");
    let o = run(&[
        "render",
        &shared("boundary/cgal_holes.off"),
        path_str(&open),
        "--boundary",
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));

    // A file that does not read is bad input, and no picture is written.
    let bad = dir.join("bad.png");
    let o = run(&[
        "render",
        &shared("invalid/assimp_invalid.off"),
        path_str(&bad),
    ]);
    assert_eq!(code(&o), 1);
    assert!(!bad.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn triangulate_cuts_polygons_into_triangles() {
    let dir = scratch("triangulate");
    // Mixed 4- to 7-gons with boundary; χ and the boundary stay.
    let rel = "polygons/cgal_double-torus-3-holes.off";
    let out = dir.join("tri.off");
    let o = run(&["triangulate", &shared(rel), path_str(&out), "--json"]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let j = json(&o);
    assert_eq!(j["faces_before"], 201);
    assert_eq!(j["left_as_they_were"], 0);
    assert_eq!(j["faces"], j["triangles"]);
    let m = manifest(rel);
    let s = json(&run(&["stats", "--json", path_str(&out)]));
    let corners: i64 = m["face_sizes"]
        .split(' ')
        .filter_map(|p| p.split_once(':'))
        .map(|(d, c)| (d.parse::<i64>().unwrap() - 2) * c.parse::<i64>().unwrap())
        .sum();
    assert_eq!(s["faces"].as_i64(), Some(corners), "n-gon -> n-2 triangles");
    assert_eq!(
        s["euler_characteristic"].as_i64(),
        m["euler_char"].parse().ok()
    );
    assert_eq!(
        s["boundary_loops"].as_i64(),
        m["boundary_loops"].parse().ok()
    );
    assert_eq!(s["vertices"].as_i64(), m["V"].parse().ok());
    let mut degrees = s["face_degrees"].as_object().unwrap().keys();
    assert_eq!(degrees.next().map(String::as_str), Some("3"));
    assert_eq!(degrees.next(), None);
    let o = run(&["triangulate", BUNDLED, path_str(&dir.join("e.ply"))]);
    assert_eq!(code(&o), 0);
    assert!(
        stdout(&o).contains("5558 faces became 5558"),
        "{}",
        stdout(&o)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn readme_quickstart_output_is_what_the_tool_prints() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let readme = std::fs::read_to_string(format!("{root}/README.md")).expect("README.md");
    let shown = readme
        .split_once("The first prints:\n\n```text\n")
        .and_then(|(_, rest)| rest.split_once("```"))
        .map(|(block, _)| block)
        .expect("the README shows the quickstart's output");
    let o = Command::new(BIN)
        .args(["stats", "data/elephant.off"])
        .current_dir(root)
        .output()
        .expect("runs");
    assert_eq!(code(&o), 0);
    assert_eq!(stdout(&o), shown);
    // The quickstart's commands are the two the README promises.
    assert!(readme.contains(
        "```sh\ncargo run --release -p meshloom-cli -- stats data/elephant.off\ncargo test --workspace --all-features\n```"
    ));
}

#[test]
fn components_lists_each_piece() {
    // 15 closed pieces (the manifest's count), together χ = 30.
    let rel = "closed/pyvista_ant.ply";
    let m = manifest(rel);
    let o = run(&["components", "--json", &shared(rel)]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let j = json(&o);
    let parts = j["components"].as_array().expect("a list");
    assert_eq!(parts.len().to_string(), m["components"]);
    let total = |key: &str| parts.iter().map(|c| c[key].as_i64().unwrap()).sum::<i64>();
    assert_eq!(total("vertices").to_string(), m["V"]);
    assert_eq!(total("edges").to_string(), m["E"]);
    assert_eq!(total("faces").to_string(), m["F"]);
    assert_eq!(total("euler_characteristic").to_string(), m["euler_char"]);
    assert!(parts.iter().all(|c| c["holes"] == 0 && c["genus"].is_u64()));

    let o = run(&["components", BUNDLED]);
    assert_eq!(code(&o), 0);
    let text = stdout(&o);
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows.len(), 2, "{text}");
    assert!(rows[0].contains("genus"));
    let cells: Vec<&str> = rows[1].split_whitespace().collect();
    assert_eq!(cells, ["0", "2775", "8337", "5558", "0", "-4", "3"]);
}

#[test]
fn fill_holes_closes_the_mesh() {
    let dir = scratch("fill");
    let rel = "boundary/cgal_holes.off";
    let m = manifest(rel);
    let loops: i64 = m["boundary_loops"].parse().unwrap();
    let chi: i64 = m["euler_char"].parse().unwrap();
    let out = dir.join("closed.off");
    let o = run(&[
        "fill-holes",
        &shared(rel),
        path_str(&out),
        "--triangulate",
        "--json",
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let j = json(&o);
    assert_eq!(j["holes_before"].as_i64(), Some(loops));
    assert_eq!(j["filled"].as_i64(), Some(loops));
    assert_eq!(j["holes"], 0);
    let s = json(&run(&["stats", "--json", path_str(&out)]));
    assert_eq!(s["closed"], true);
    // Each filled hole adds one face (χ + 1); triangulating keeps χ.
    assert_eq!(s["euler_characteristic"].as_i64(), Some(chi + loops));
    assert_eq!(s["genus"], 0);
    assert_eq!(s["face_degrees"].as_object().map(|h| h.len()), Some(1));
    // Only small holes: the bigger ones stay.
    let o = run(&[
        "fill-holes",
        &shared(rel),
        path_str(&out),
        "--max-sides",
        "3",
    ]);
    assert_eq!(code(&o), 0);
    assert!(
        stdout(&o).contains("have more than 3 sides"),
        "{}",
        stdout(&o)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
