//! meshloom's own glTF reads back as it was written (the defects issue,
//! item 3): every shared mesh the library reads goes to glTF and back with
//! the same vertices, edges, holes, components and seams (polygons come
//! back triangulated); welding by position, for other files, never makes
//! a non-manifold vertex; positions that 32-bit floats cannot hold are
//! refused unless the caller allows the loss.
//!
//! Files above [`MAX_BYTES`] are skipped to keep the run short (the test
//! profile is opt-level 1): `large/` and `closed/cgal_bunny00.off`.
#![cfg(feature = "gltf")]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use meshloom::io::gltf::{
    read_gltf_bytes, write_gltf, write_gltf_with, GltfEncoding, GltfOptions, GltfWriteOptions,
};
use meshloom::io::{self, Error, ReadOptions};
use meshloom::{ElementKind, HalfedgeKey, Mesh};

const DATA: &str = "../shared/data/meshes";
const REPROS: &str = "../shared/data/repros";
/// The largest shared file the round trip reads.
const MAX_BYTES: u64 = 2_000_000;

/// Every shared mesh file of a format the library reads (not glTF).
fn shared_files() -> Vec<PathBuf> {
    let mut out = Vec::new();
    for dir in std::fs::read_dir(DATA).expect("../shared/data/meshes") {
        let dir = dir.unwrap().path();
        if !dir.is_dir() {
            continue;
        }
        for f in std::fs::read_dir(&dir).unwrap() {
            let f = f.unwrap().path();
            if io::Format::from_path(&f).is_some() {
                out.push(f);
            }
        }
    }
    out.sort();
    out
}

/// Interior edges across which the corner column `name` differs.
fn seams(mesh: &Mesh, name: &str) -> usize {
    let value = |h: HalfedgeKey| mesh.attr_value(name, h).unwrap_or(None);
    mesh.edges()
        .filter(|&e| {
            let view = mesh.edge(e).unwrap();
            if view.is_boundary() {
                return false;
            }
            let (h, t) = (view.halfedge(0), view.halfedge(1));
            value(h.key()) != value(t.next().key()) || value(h.next().key()) != value(t.key())
        })
        .count()
}

/// What a round trip keeps: (V, V − E + F, holes, boundary loops,
/// components, triangles) (the Euler characteristic, as triangulating
/// adds as many edges as faces), the positions as 32-bit floats (sorted),
/// the seams of each corner column.
type Figures = ([i64; 6], Vec<[u32; 3]>, BTreeMap<String, usize>);

fn figures(mesh: &Mesh) -> Figures {
    let s = mesh.stats();
    let triangles: usize = mesh
        .faces()
        .map(|f| mesh.face(f).unwrap().degree() - 2)
        .sum();
    let counts = [
        s.vertices as i64,
        s.euler_characteristic,
        s.holes as i64,
        s.boundary_loops as i64,
        s.components as i64,
        triangles as i64,
    ];
    let mut positions: Vec<[u32; 3]> = mesh
        .vertices()
        .map(|v| mesh.position(v).unwrap().map(|c| (c as f32).to_bits()))
        .collect();
    positions.sort_unstable();
    let seams = mesh
        .attr_info(ElementKind::Halfedge)
        .into_iter()
        .map(|a| (a.name.clone(), seams(mesh, &a.name)))
        .collect();
    (counts, positions, seams)
}

/// The mesh written as glTF (`encoding`) and read back strictly.
fn round_trip(mesh: &Mesh, encoding: GltfEncoding) -> Result<Mesh, Error> {
    let mut bytes = Vec::new();
    write_gltf(mesh, &mut bytes, encoding)?;
    let (back, report) = read_gltf_bytes(&bytes, &ReadOptions::strict(), &GltfOptions::default())?;
    assert!(report.is_clean(), "{report}");
    back.validate().unwrap();
    Ok(back)
}

#[test]
fn every_shared_mesh_round_trips_through_gltf() {
    let mut checked = 0;
    let mut failures = Vec::new();
    for f in shared_files() {
        if std::fs::metadata(&f).unwrap().len() > MAX_BYTES {
            continue;
        }
        // What the library reads: strictly, else with its repairs.
        let mesh = match io::read(&f) {
            Ok(m) => m,
            Err(_) => match io::read_with(&f, &ReadOptions::repair_all()) {
                Ok((m, _)) => m,
                Err(_) => continue,
            },
        };
        if mesh.face_count() == 0 || !mesh.has_positions() {
            continue;
        }
        let want = figures(&mesh);
        eprintln!(
            "{}: V, V-E+F, holes, loops, components, triangles = {:?}",
            f.display(),
            want.0
        );
        for encoding in [GltfEncoding::Binary, GltfEncoding::Json] {
            match round_trip(&mesh, encoding) {
                Ok(back) if figures(&back) == want => {}
                Ok(back) => failures.push(format!(
                    "{} ({encoding:?}): {:?} became {:?}",
                    f.display(),
                    want.0,
                    figures(&back).0
                )),
                Err(e) => failures.push(format!("{} ({encoding:?}): {e}", f.display())),
            }
        }
        checked += 1;
    }
    assert!(checked >= 55, "only {checked} shared files were read");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_cow_converted_to_glb_reads_back_strictly() {
    let cow = io::read(format!("{DATA}/closed/cgal_cow.off")).unwrap();
    let dir = std::env::temp_dir().join(format!("meshloom-gltf-rt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let glb = dir.join("cow.glb");
    io::write(&cow, &glb).unwrap();
    let back = io::read(&glb).unwrap();
    assert_eq!(figures(&back), figures(&cow));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn separate_faces_and_components_stay_apart() {
    for file in ["textured/cube_uv.ply", "boundary/cgal_quads_to_stitch.off"] {
        let mesh = io::read(format!("{DATA}/{file}")).unwrap();
        let back = round_trip(&mesh, GltfEncoding::Binary).unwrap();
        assert_eq!(back.stats().components, mesh.stats().components, "{file}");
        assert_eq!(figures(&back), figures(&mesh), "{file}");
    }
}

#[test]
fn a_repaired_nonmanifold_edge_round_trips() {
    // Three triangles on one edge: repair splits it, and the copies of its
    // two vertices share their positions.
    let path = format!("{REPROS}/nme3_repair_to_glb.obj");
    let (mesh, report) = io::read_with(&path, &ReadOptions::repair_all()).unwrap();
    assert!(report.nonmanifold_edges > 0, "{report}");
    for encoding in [GltfEncoding::Binary, GltfEncoding::Json] {
        let back = round_trip(&mesh, encoding).unwrap();
        assert_eq!(figures(&back), figures(&mesh), "{encoding:?}");
    }
}

/// The mesh as `.gltf` JSON without `_VERTEX_ID`: a file from another
/// tool, welded by position.
fn without_vertex_ids(mesh: &Mesh) -> Vec<u8> {
    let mut bytes = Vec::new();
    write_gltf(mesh, &mut bytes, GltfEncoding::Json).unwrap();
    let mut doc: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
    for prim in doc["meshes"][0]["primitives"].as_array_mut().unwrap() {
        let attributes = prim["attributes"].as_object_mut().unwrap();
        assert!(attributes.remove("_VERTEX_ID").is_some());
    }
    serde_json::to_vec(&doc).unwrap()
}

#[test]
fn welding_by_position_never_makes_a_nonmanifold_vertex() {
    // The cow has distinct vertices at one position; the repaired
    // three-triangle edge has copies at its ends. Welded by position, the
    // coincident vertices whose joining would be non-manifold stay apart,
    // and the report says how many.
    let cow = io::read(format!("{DATA}/closed/cgal_cow.off")).unwrap();
    let (nme, _) = io::read_with(
        format!("{REPROS}/nme3_repair_to_glb.obj"),
        &ReadOptions::repair_all(),
    )
    .unwrap();
    for (name, mesh) in [("cow", cow), ("nme3", nme)] {
        let bytes = without_vertex_ids(&mesh);
        let (back, report) =
            read_gltf_bytes(&bytes, &ReadOptions::strict(), &GltfOptions::default())
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        back.validate().unwrap();
        assert!(report.weld_refused > 0, "{name}: {report}");
        assert_eq!(figures(&back).0, figures(&mesh).0, "{name}");
    }
}

#[test]
fn two_triangles_touching_at_a_point_stay_two_components() {
    use meshloom::Polygons;
    let p = Polygons {
        positions: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ],
        offsets: vec![0, 3, 6],
        indices: vec![0, 1, 2, 3, 4, 5],
    };
    let mesh = Mesh::from_buffers(&p).unwrap();
    let bytes = without_vertex_ids(&mesh);
    let (back, report) =
        read_gltf_bytes(&bytes, &ReadOptions::strict(), &GltfOptions::default()).unwrap();
    assert_eq!(back.stats().components, 2);
    assert_eq!(back.vertex_count(), 6);
    assert_eq!((report.welded_vertices, report.weld_refused), (0, 1));
}

/// The repro `name`, read and written as glTF (`allow_lossy_f32` as
/// given).
fn write_repro(name: &str, allow_lossy_f32: bool) -> Result<Vec<u8>, Error> {
    let mesh = io::read(Path::new(REPROS).join(name)).unwrap();
    let mut bytes = Vec::new();
    let options = GltfWriteOptions::default()
        .encoding(GltfEncoding::Binary)
        .allow_lossy_f32(allow_lossy_f32);
    write_gltf_with(&mesh, &mut bytes, &options).map(|()| bytes)
}

#[test]
fn positions_that_underflow_f32_are_refused_unless_allowed() {
    let err = write_repro("tiny1e-300.obj", false).unwrap_err();
    assert!(matches!(err, Error::Unwritable { .. }), "{err}");
    let text = err.to_string();
    assert!(
        text.contains("1e-300") && text.contains("allow_lossy_f32"),
        "{text}"
    );
    // Through io::write too (the CLI's convert).
    let dir = std::env::temp_dir().join(format!("meshloom-gltf-f32-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = io::read(Path::new(REPROS).join("tiny1e-300.obj")).unwrap();
    assert!(io::write(&mesh, dir.join("tiny.glb")).is_err());
    let lossy = io::WriteOptions::default().allow_lossy_f32(true);
    io::write_with(&mesh, dir.join("tiny.glb"), &lossy).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    // Allowed: every position is 0, and the vertices stay apart.
    let bytes = write_repro("tiny1e-300.obj", true).unwrap();
    let (back, _) =
        read_gltf_bytes(&bytes, &ReadOptions::strict(), &GltfOptions::default()).unwrap();
    assert_eq!((back.vertex_count(), back.face_count()), (4, 4));
    assert!(back
        .vertices()
        .all(|v| back.position(v).unwrap() == [0.0; 3]));
}

#[test]
fn positions_out_of_f32_range_are_refused_even_when_loss_is_allowed() {
    for allow in [false, true] {
        let err = write_repro("big1e300.obj", allow).unwrap_err();
        assert!(matches!(err, Error::Unwritable { .. }), "{err}");
        assert!(err.to_string().contains("out of the range"), "{err}");
    }
}
