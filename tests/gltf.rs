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

fn triangles(mesh: &Mesh) -> usize {
    mesh.faces()
        .map(|f| mesh.face(f).unwrap().degree() - 2)
        .sum()
}

fn tmp(name: &str) -> TempFile {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("meshloom-gltf-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    TempFile(dir.join(name))
}

/// A scratch file in a folder of its own (tests run in parallel), removed
/// with the folder when the test ends.
struct TempFile(std::path::PathBuf);

impl std::ops::Deref for TempFile {
    type Target = std::path::PathBuf;
    fn deref(&self) -> &std::path::PathBuf {
        &self.0
    }
}

impl AsRef<std::path::Path> for TempFile {
    fn as_ref(&self) -> &std::path::Path {
        &self.0
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if let Some(dir) = self.0.parent() {
            let _ = std::fs::remove_dir_all(dir);
        }
    }
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
    // and refused where it would make the mesh non-manifold). meshloom's
    // glTF carries each vertex's identity (`_VERTEX_ID`), so every trip,
    // the first included, keeps them apart: the trips are exact.
    let (raw, _) = io::read_with(path("textured/spider.obj"), &ReadOptions::repair_all()).unwrap();
    let first = tmp("spider-first.glb");
    io::write(&raw, &first).unwrap();
    let spider = io::read(&first).unwrap();
    let distinct: std::collections::HashSet<_> = raw
        .vertices()
        .map(|v| raw.position(v).unwrap().map(f64::to_bits))
        .collect();
    assert!(distinct.len() < raw.vertex_count());
    assert_eq!(spider.vertex_count(), raw.vertex_count());
    assert_eq!(triangles(&spider), triangles(&raw));
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
    let one = io::gltf::GltfOptions::default().mesh(Some(0));
    let (part, _) = io::gltf::read_gltf_with(&file, &ReadOptions::repair_all(), &one).unwrap();
    assert!(part.face_count() > 0 && part.face_count() < mesh.face_count());
    let none = io::gltf::GltfOptions::default().mesh(Some(10_000));
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
    let small = ReadOptions::strict().max_bytes(100);
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

/// Triangles per value of the text face column `material` (`None`: no
/// value).
fn material_triangles(mesh: &Mesh) -> std::collections::BTreeMap<Option<String>, usize> {
    let mut out = std::collections::BTreeMap::new();
    for f in mesh.faces() {
        let m = match mesh.attr_value("material", f).unwrap_or(None) {
            Some(Value::Text(s)) => Some(s),
            None => None,
            Some(other) => panic!("material {other:?} is not text"),
        };
        *out.entry(m).or_insert(0) += mesh.face(f).unwrap().degree() - 2;
    }
    out
}

/// A face's corner positions as exact bits, sorted: the same face in a
/// mesh whatever the order of its faces and corners.
fn face_id(mesh: &Mesh, f: meshloom::FaceKey) -> Vec<[u64; 3]> {
    let mut id: Vec<[u64; 3]> = mesh
        .face(f)
        .unwrap()
        .vertices()
        .map(|v| mesh.position(v).unwrap().map(f64::to_bits))
        .collect();
    id.sort_unstable();
    id
}

#[test]
fn material_and_numeric_face_columns_round_trip() {
    use meshloom::shapes::{grid, GridFaces};
    let mut mesh = grid(6, 4, GridFaces::Triangles);
    let material = mesh.add_face_attr::<String>("material").unwrap();
    let heat = mesh.add_face_attr::<f64>("temperature").unwrap();
    let pair = mesh.add_face_attr::<[f64; 2]>("pair").unwrap();
    let faces: Vec<_> = mesh.faces().collect();
    for (i, &f) in faces.iter().enumerate() {
        // Three materials in stripes, and some faces with none.
        if i % 7 != 3 {
            let name = ["steel", "glass", "rubber"][i % 3];
            mesh.set_attr(&material, f, name.to_owned()).unwrap();
        }
        // Exact in f32, different on neighbouring faces.
        mesh.set_attr(&heat, f, 0.5 * i as f64 - 3.0).unwrap();
        mesh.set_attr(&pair, f, [i as f64, -(i as f64) / 4.0])
            .unwrap();
    }
    let want_materials = material_triangles(&mesh);
    assert_eq!(want_materials.len(), 4);
    let mut want = std::collections::HashMap::new();
    for &f in &faces {
        let m = mesh.attr(&material, f).unwrap().cloned();
        let t = *mesh.attr(&heat, f).unwrap().unwrap();
        let p = *mesh.attr(&pair, f).unwrap().unwrap();
        want.insert(face_id(&mesh, f), (m, t, p));
    }
    for out in ["faces.gltf", "faces.glb"] {
        let p = tmp(out);
        io::write(&mesh, &p).unwrap();
        let back = io::read(&p).unwrap();
        back.validate().unwrap();
        // Vertices split for the file are welded again.
        assert_eq!(
            (back.vertex_count(), back.face_count(), back.hole_count()),
            (mesh.vertex_count(), mesh.face_count(), 1),
            "{out}"
        );
        assert_eq!(material_triangles(&back), want_materials, "{out}");
        let heat_back =
            back.attr_handle::<meshloom::FaceKey, f64, meshloom::attr::Interpolate>("temperature");
        let pair_back =
            back.attr_handle::<meshloom::FaceKey, [f64; 2], meshloom::attr::Interpolate>("pair");
        let (heat_back, pair_back) = (heat_back.unwrap(), pair_back.unwrap());
        for f in back.faces() {
            let m = match back.attr_value("material", f).unwrap() {
                Some(Value::Text(s)) => Some(s),
                _ => None,
            };
            let t = *back.attr(&heat_back, f).unwrap().unwrap();
            let p = *back.attr(&pair_back, f).unwrap().unwrap();
            assert_eq!(want[&face_id(&back, f)], (m, t, p), "{out}");
        }
        // One primitive per material, a fourth for the faces without.
        let text = std::fs::read(&p).unwrap();
        let text = String::from_utf8_lossy(&text);
        assert_eq!(text.matches("\"mode\":4").count(), 4, "{out}");
        assert!(text.contains("_FACE_temperature"), "{out}");
    }
}

#[test]
fn a_face_attribute_that_varies_over_a_triangle_is_not_a_face_column() {
    // A custom attribute named like a face column but differing at the
    // corners of a triangle comes back as an ordinary column.
    let mut mesh = meshloom::shapes::tetrahedron();
    let col = mesh.add_vertex_attr::<f64>("FACE_odd").unwrap();
    let vs: Vec<_> = mesh.vertices().collect();
    for (i, &v) in vs.iter().enumerate() {
        mesh.set_attr(&col, v, i as f64).unwrap();
    }
    let p = tmp("odd.glb");
    io::write(&mesh, &p).unwrap();
    let back = io::read(&p).unwrap();
    assert!(back
        .attr_info(meshloom::ElementKind::Face)
        .iter()
        .all(|a| a.name != "odd"));
    assert!(back
        .attr_info(meshloom::ElementKind::Vertex)
        .iter()
        .any(|a| a.name == "FACE_odd"));
}

#[test]
fn the_spiders_materials_survive_obj_gltf_obj() {
    let (raw, _) = io::read_with(path("textured/spider.obj"), &ReadOptions::repair_all()).unwrap();
    let raw_materials = material_triangles(&raw);
    assert_eq!(raw_materials.len(), 4, "{raw_materials:?}");
    // The first trip welds the spider's coincident vertices (see
    // spider_round_trips_obj_gltf_obj), which drops 56 of its triangles
    // that then have no area or repeat others; every material stays.
    let first = tmp("spider-materials.glb");
    io::write(&raw, &first).unwrap();
    let spider = io::read(&first).unwrap();
    let want = material_triangles(&spider);
    assert!(want.keys().eq(raw_materials.keys()), "{want:?}");
    for ext in ["gltf", "glb"] {
        let g = tmp(&format!("spider-materials.{ext}"));
        io::write(&spider, &g).unwrap();
        let via = io::read(&g).unwrap();
        assert_eq!(material_triangles(&via), want, "{ext}");
        let o = tmp(&format!("spider-materials-{ext}.obj"));
        io::write(&via, &o).unwrap();
        let back = io::read(&o).unwrap();
        assert_eq!(material_triangles(&back), want, "{ext}");
        assert_eq!(
            seams(&back, "texcoord"),
            seams(&spider, "texcoord"),
            "{ext}"
        );
    }
}

#[test]
fn the_samples_keep_counts_seams_and_materials_through_a_write() {
    for file in [
        "gltf/BoxTextured.glb",
        "gltf/BoxTextured/BoxTextured.gltf",
        "gltf/BoxTexcoords/boxTexcoords.gltf",
        "gltf/2CylinderEngine.glb",
    ] {
        let (read, _) = io::read_with(path(file), &ReadOptions::repair_all()).unwrap();
        // The first write rounds node-transformed positions to f32 (which
        // may weld vertices); from then on the trips are exact.
        let first = tmp("sample-first.glb");
        io::write(&read, &first).unwrap();
        let (mesh, _) = io::read_with(&first, &ReadOptions::repair_all()).unwrap();
        let materials = material_triangles(&mesh);
        assert_eq!(
            materials.keys().collect::<Vec<_>>(),
            material_triangles(&read).keys().collect::<Vec<_>>(),
            "{file}"
        );
        let counts = (mesh.vertex_count(), mesh.face_count(), mesh.edge_count());
        for out in ["sample.glb", "sample.gltf"] {
            let p = tmp(out);
            io::write(&mesh, &p).unwrap();
            let (back, _) = io::read_with(&p, &ReadOptions::repair_all()).unwrap();
            back.validate().unwrap();
            let got = (back.vertex_count(), back.face_count(), back.edge_count());
            assert_eq!(got, counts, "{file} -> {out}");
            assert_eq!(material_triangles(&back), materials, "{file} -> {out}");
            assert_eq!(
                seams(&back, "texcoord"),
                seams(&mesh, "texcoord"),
                "{file} -> {out}"
            );
        }
    }
}
