//! glTF 2.0: reading the shared samples, round trips through OBJ and glTF,
//! and located errors (never panics) for the invalid files.
#![cfg(feature = "gltf")]

use meshloom::attr::Value;
use meshloom::io::{self, Error, ReadOptions};
use meshloom::{HalfedgeKey, Mesh};

const DATA: &str = "../shared/data/meshes";

fn path(rel: &str) -> String {
    format!("{DATA}/{rel}")
}

/// Interior edges across which a corner column differs at either end.
fn seams(mesh: &Mesh, name: &str) -> usize {
    let value = |h: HalfedgeKey| mesh.attr_value(name, h).unwrap();
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

fn triangles(mesh: &Mesh) -> usize {
    mesh.faces()
        .map(|f| mesh.face(f).unwrap().degree() - 2)
        .sum()
}

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("meshloom-gltf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn box_textured_reads_as_8_welded_vertices_with_uv_seams() {
    for file in ["gltf/BoxTextured/BoxTextured.gltf", "gltf/BoxTextured.glb"] {
        let mesh = io::read(path(file)).unwrap();
        mesh.validate().unwrap();
        assert_eq!((mesh.vertex_count(), mesh.face_count()), (8, 12), "{file}");
        assert!(mesh.is_closed());
        // 24 file vertices, split where UVs and normals differ: the UVs
        // become corner values that differ across the seams.
        let s = seams(&mesh, "texcoord");
        assert!(s > 0, "{file}");
        // Every corner has a UV and a unit normal from the file.
        for h in mesh.halfedges() {
            if mesh.halfedge(h).unwrap().is_boundary() {
                continue;
            }
            assert!(
                matches!(mesh.attr_value("texcoord", h).unwrap(), Some(Value::List(l)) if l.len() == 2)
            );
            let Some(Value::List(n)) = mesh.attr_value("normal", h).unwrap() else {
                panic!("no normal");
            };
            let n: Vec<f64> = n.iter().map(|x| x.as_f64().unwrap()).collect();
            assert!((n.iter().map(|c| c * c).sum::<f64>() - 1.0).abs() < 1e-6);
        }
        // The node's matrix turns y up into z: faces still point outwards
        // (the face normals agree with the file's normals).
        for f in mesh.faces() {
            let fnormal = mesh.face_normal(f).unwrap();
            let h = mesh.face(f).unwrap().halfedges().next().unwrap();
            let Some(Value::List(n)) = mesh.attr_value("normal", h).unwrap() else {
                panic!()
            };
            let dot: f64 = (0..3).map(|i| fnormal[i] * n[i].as_f64().unwrap()).sum();
            assert!(dot > 0.99, "{file}: {dot}");
        }
        // Write and read back: same counts and seams, both encodings.
        for out in ["box.gltf", "box.glb"] {
            let p = tmp(out);
            io::write(&mesh, &p).unwrap();
            let back = io::read(&p).unwrap();
            assert_eq!((back.vertex_count(), back.face_count()), (8, 12), "{out}");
            assert_eq!(seams(&back, "texcoord"), s, "{out}");
        }
    }
}

#[test]
fn the_gltf_and_glb_boxes_agree() {
    let a = io::read(path("gltf/BoxTextured/BoxTextured.gltf")).unwrap();
    let b = io::read(path("gltf/BoxTextured.glb")).unwrap();
    assert_eq!(a.to_polygons().0, b.to_polygons().0);
    assert_eq!(seams(&a, "texcoord"), seams(&b, "texcoord"));
    let c = io::read(path("gltf/BoxTexcoords/boxTexcoords.gltf")).unwrap();
    assert_eq!((c.vertex_count(), c.face_count()), (8, 12));
}

#[test]
fn spider_round_trips_obj_gltf_obj() {
    // Repair keeps the spider's coincident vertices apart (welding is opt-in
    // and refused where it would make the mesh non-manifold), while glTF's
    // split vertices are welded by position on reading: the first trip
    // welds them, and from then on the trips are exact.
    let (raw, _) = io::read_with(path("textured/spider.obj"), &ReadOptions::repair_all()).unwrap();
    let first = tmp("spider-first.glb");
    io::write(&raw, &first).unwrap();
    let spider = io::read(&first).unwrap();
    let distinct: std::collections::HashSet<_> = raw
        .vertices()
        .map(|v| raw.position(v).unwrap().map(f64::to_bits))
        .collect();
    assert_eq!(spider.vertex_count(), distinct.len());
    assert!(spider.vertex_count() < raw.vertex_count());
    let (v, t, s) = (
        spider.vertex_count(),
        triangles(&spider),
        seams(&spider, "texcoord"),
    );
    assert!(s > 0);
    for ext in ["gltf", "glb"] {
        let g = tmp(&format!("spider.{ext}"));
        io::write(&spider, &g).unwrap();
        let via = io::read(&g).unwrap();
        via.validate().unwrap();
        assert_eq!((via.vertex_count(), via.face_count()), (v, t), "{ext}");
        assert_eq!(seams(&via, "texcoord"), s, "{ext}");
        let o = tmp(&format!("spider-{ext}.obj"));
        io::write(&via, &o).unwrap();
        let back = io::read(&o).unwrap();
        assert_eq!((back.vertex_count(), triangles(&back)), (v, t), "{ext}");
        assert_eq!(seams(&back, "texcoord"), s, "{ext}");
    }
}

#[test]
fn the_engine_reads_as_components_and_one_mesh_can_be_picked() {
    let file = path("gltf/2CylinderEngine.glb");
    let (mesh, _) = io::read_with(&file, &ReadOptions::repair_all()).unwrap();
    mesh.validate().unwrap();
    assert!(mesh.component_stats().len() > 1);
    let one = io::gltf::GltfOptions { mesh: Some(0) };
    let (part, _) = io::gltf::read_gltf_with(&file, &ReadOptions::repair_all(), &one).unwrap();
    assert!(part.face_count() > 0 && part.face_count() < mesh.face_count());
    let none = io::gltf::GltfOptions { mesh: Some(10_000) };
    let err = io::gltf::read_gltf_with(&file, &ReadOptions::strict(), &none).unwrap_err();
    assert!(err.to_string().contains("no mesh 10000"), "{err}");
}

#[test]
fn invalid_files_give_located_errors() {
    let err = io::read(path("gltf/invalid/IndexOutOfRange/IndexOutOfRange.gltf")).unwrap_err();
    let Error::IndexOutOfRange {
        at,
        what,
        index,
        count,
    } = &err
    else {
        panic!("{err}")
    };
    assert_eq!(*what, "vertex");
    assert!(*index >= *count as i64);
    assert!(matches!(at.position, io::Position::Byte(_)), "{err}");
    assert!(
        at.path.as_ref().unwrap().ends_with("IndexOutOfRange.bin"),
        "{err}"
    );
    let err = io::read(path(
        "gltf/invalid/IndexOutOfRange/AllIndicesOutOfRange.gltf",
    ))
    .unwrap_err();
    assert!(matches!(err, Error::IndexOutOfRange { .. }), "{err}");

    let err = io::read(path("gltf/invalid/BoxWithInfinites.glb")).unwrap_err();
    let Error::NonFinite { at, position, .. } = &err else {
        panic!("{err}")
    };
    assert!(position.iter().any(|c| c.is_infinite()));
    assert!(err.byte_offset().is_some(), "{err}");
    assert!(at.path.as_ref().unwrap().ends_with("BoxWithInfinites.glb"));

    let err = io::read(path("gltf/invalid/badNumber.gltf")).unwrap_err();
    assert!(matches!(err, Error::Syntax { .. }), "{err}");
    assert!(err.line().is_some(), "{err}");
}

#[test]
fn damaged_bytes_give_errors_not_panics() {
    let good = std::fs::read(path("gltf/BoxTextured.glb")).unwrap();
    let opts = ReadOptions::strict();
    let pick = io::gltf::GltfOptions::default();
    // Every truncation, and every single-byte change in the first 200
    // bytes and in the binary chunk's first 100.
    for len in (0..good.len()).step_by(7) {
        let _ = io::gltf::read_gltf_bytes(&good[..len], &opts, &pick);
    }
    let json_len = u32::from_le_bytes(good[12..16].try_into().unwrap()) as usize;
    let bin = 20 + json_len + 8;
    for at in (0..200).chain(bin..bin + 100) {
        for x in [0u8, 0xff, b'9'] {
            let mut bad = good.clone();
            bad[at] = x;
            let _ = io::gltf::read_gltf_bytes(&bad, &opts, &pick);
        }
    }
    // A JSON glTF with a buffer in another file cannot be read from memory.
    let json = std::fs::read(path("gltf/BoxTextured/BoxTextured.gltf")).unwrap();
    let err = io::gltf::read_gltf_bytes(&json, &opts, &pick).unwrap_err();
    assert!(matches!(err, Error::UnsupportedFormat { .. }), "{err}");
    // A byte limit bounds what is read.
    let small = ReadOptions {
        max_bytes: 100,
        ..ReadOptions::strict()
    };
    assert!(matches!(
        io::read_with(path("gltf/BoxTextured.glb"), &small),
        Err(Error::TooLarge { .. })
    ));
}

#[test]
fn points_and_lines_are_refused_and_strips_read() {
    use serde_json::json;
    // A unit square as 4 positions; the same data drawn four ways.
    let floats: [f32; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let uri = format!("data:application/octet-stream;base64,{}", b64(&bytes));
    let doc = |mode: u32| {
        json!({
            "asset": {"version": "2.0"},
            "buffers": [{"byteLength": 48, "uri": uri}],
            "bufferViews": [{"buffer": 0, "byteLength": 48}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 0]}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": mode}]}],
        })
        .to_string()
    };
    let read = |mode| {
        io::gltf::read_gltf_bytes(
            doc(mode).as_bytes(),
            &ReadOptions::strict(),
            &Default::default(),
        )
    };
    // Strip 0 1 3 2 and fan 0 1 2 3 need index orders: with none, the
    // strip of 0 1 2 3 is two triangles of the square.
    let strip = read(5).unwrap().0;
    assert_eq!((strip.vertex_count(), strip.face_count()), (4, 2));
    let fan = read(6).unwrap().0;
    assert_eq!((fan.vertex_count(), fan.face_count()), (4, 2));
    for mode in [0, 1, 2, 3] {
        let err = read(mode).unwrap_err();
        assert!(matches!(err, Error::UnsupportedFormat { .. }), "{err}");
        assert!(err.to_string().contains("mesh 0 primitive 0"), "{err}");
    }
}

/// Base64 for the test's data URI.
fn b64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in data.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            s.push(if k <= c.len() {
                A[(n >> (18 - 6 * k) & 63) as usize] as char
            } else {
                '='
            });
        }
    }
    s
}
