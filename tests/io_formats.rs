//! Every format: write then read gives back the same mesh and attributes;
//! the features of each format; errors that say where.

use meshloom::attr::{Value, ValueType};
use meshloom::io::{
    self, read_obj, read_off, read_ply, read_stl, write_obj, write_off, write_ply, write_stl,
    Error, Format, PlyEncoding, ReadOptions, StlEncoding,
};
use meshloom::{ElementKind, FaceKey, HalfedgeKey, Mesh, VertexKey};

/// A pentagon, two triangles and a quad around it: n-gons and a boundary.
fn mixed() -> Mesh {
    let p = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 1.5, 0.0],
        [1.0, 2.5, 0.25],
        [-1.0, 1.5, 0.0],
        [1.0, -1.5, 0.0],
        [4.0, -0.5, 0.5],
        [0.1, 0.2, 0.3],
    ];
    Mesh::from_polygons(
        &p,
        &[
            vec![0u32, 1, 2, 3, 4],
            vec![0, 5, 1],
            vec![1, 5, 6, 2],
            vec![4, 7, 0],
        ],
    )
    .unwrap()
}

/// Positions, faces and face order of a mesh, for comparison.
fn shape(m: &Mesh) -> meshloom::Polygons {
    m.to_polygons().0
}

fn temp(name: &str) -> TempFile {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("meshloom-io-tests-{}-{n}", std::process::id()));
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
fn obj_round_trip_keeps_ngons_and_exact_positions() {
    let m = mixed();
    let mut bytes = Vec::new();
    write_obj(&m, &mut bytes).unwrap();
    let back = read_obj(&bytes[..]).unwrap();
    back.validate().unwrap();
    assert_eq!(shape(&back), shape(&m));
}

#[test]
fn off_round_trip() {
    let m = mixed();
    let mut bytes = Vec::new();
    write_off(&m, &mut bytes).unwrap();
    assert!(bytes.starts_with(b"OFF\n8 4 0\n"));
    assert_eq!(shape(&read_off(&bytes[..]).unwrap()), shape(&m));
}

#[test]
fn ply_round_trip_in_every_encoding() {
    let m = mixed();
    for enc in [
        PlyEncoding::Ascii,
        PlyEncoding::BinaryLittleEndian,
        PlyEncoding::BinaryBigEndian,
    ] {
        let mut bytes = Vec::new();
        write_ply(&m, &mut bytes, enc).unwrap();
        assert_eq!(shape(&read_ply(&bytes[..]).unwrap()), shape(&m), "{enc:?}");
    }
}

#[test]
fn stl_round_trip_ascii_and_binary() {
    // Coordinates exact in f32, so STL's single precision loses nothing.
    let cube = meshloom::shapes::cube();
    for enc in [StlEncoding::Ascii, StlEncoding::Binary] {
        let mut bytes = Vec::new();
        write_stl(&cube, &mut bytes, enc).unwrap();
        let back = read_stl(&bytes[..]).unwrap();
        back.validate().unwrap();
        assert_eq!((back.vertex_count(), back.face_count()), (8, 12), "{enc:?}");
        assert!(back.is_closed());
        // Writing the triangles again gives the same bytes.
        let mut again = Vec::new();
        write_stl(&back, &mut again, enc).unwrap();
        assert_eq!(
            read_stl(&again[..]).unwrap().to_polygons().0,
            back.to_polygons().0
        );
    }
}

#[test]
fn files_by_extension_with_gzip() {
    let m = mixed();
    for name in [
        "m.obj", "m.off", "m.ply", "m.obj.gz", "m.off.gz", "m.ply.gz", "m.PLY",
    ] {
        let path = temp(name);
        io::write(&m, &path).unwrap();
        let back = io::read(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(shape(&back), shape(&m), "{name}");
        if name.ends_with(".gz") {
            let raw = std::fs::read(&path).unwrap();
            assert_eq!(&raw[..2], &[0x1f, 0x8b], "{name} is gzip");
        }
    }
    let path = temp("m.stl.gz");
    io::write(&meshloom::shapes::cube(), &path).unwrap();
    assert_eq!(io::read(&path).unwrap().face_count(), 12);
    assert!(matches!(
        io::write(&m, temp("m.xyz")),
        Err(Error::UnsupportedFormat { .. })
    ));
    assert_eq!(Format::from_path("a.b.off.gz"), Some((Format::Off, true)));
}

#[test]
fn obj_negative_indices_and_corner_attributes() {
    let obj = "\
# a textured square with normals, in two groups
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
g left
usemtl red
f 1/1/1 2/2/1 3/3/1
g right
f -4/-4/-1 -2/-2/-1 -1/-1/-1
";
    let m = read_obj(obj.as_bytes()).unwrap();
    assert_eq!((m.vertex_count(), m.face_count()), (4, 2));
    let names: Vec<String> = m
        .attr_info(ElementKind::Halfedge)
        .into_iter()
        .map(|a| a.name)
        .collect();
    assert_eq!(names, ["texcoord", "normal"]);
    // Every corner's texture coordinate equals its vertex's position xy.
    for f in m.faces() {
        for h in m.face(f).unwrap().halfedges() {
            let v = m.halfedge(h).unwrap().origin().key();
            let p = m.position(v).unwrap();
            let uv = m.attr_value("texcoord", h).unwrap().unwrap();
            assert_eq!(uv, Value::List(vec![Value::F64(p[0]), Value::F64(p[1])]));
            let n = m.attr_value("normal", h).unwrap().unwrap();
            assert_eq!(
                n,
                Value::List(vec![Value::F64(0.0), Value::F64(0.0), Value::F64(1.0)])
            );
        }
    }
    let faces: Vec<FaceKey> = m.faces().collect();
    let group = |f| m.attr_value("group", f).unwrap();
    assert_eq!(group(faces[0]), Some(Value::Text("left".into())));
    assert_eq!(group(faces[1]), Some(Value::Text("right".into())));
    assert_eq!(
        m.attr_value("material", faces[1]).unwrap(),
        Some(Value::Text("red".into()))
    );
    // Written back: the same corners, groups and materials.
    let mut bytes = Vec::new();
    write_obj(&m, &mut bytes).unwrap();
    let back = read_obj(&bytes[..]).unwrap();
    assert_eq!(shape(&back), shape(&m));
    for (f, g) in m.faces().zip(back.faces()) {
        for name in ["group", "material"] {
            assert_eq!(
                m.attr_value(name, f).unwrap(),
                back.attr_value(name, g).unwrap()
            );
        }
        let a: Vec<HalfedgeKey> = m.face(f).unwrap().halfedges().collect();
        let b: Vec<HalfedgeKey> = back.face(g).unwrap().halfedges().collect();
        for (x, y) in a.iter().zip(&b) {
            for name in ["texcoord", "normal"] {
                assert_eq!(
                    m.attr_value(name, *x).unwrap(),
                    back.attr_value(name, *y).unwrap()
                );
            }
        }
    }
    let text = String::from_utf8(bytes).unwrap();
    assert_eq!(text.matches("\nvt ").count(), 4, "{text}");
    assert_eq!(text.matches("vn ").count(), 1, "{text}");
}

#[test]
fn obj_index_errors_name_the_line() {
    let zero = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n".as_bytes()).unwrap_err();
    assert!(
        matches!(
            zero,
            Error::IndexOutOfRange {
                index: 0,
                count: 3,
                ..
            }
        ),
        "{zero}"
    );
    assert_eq!(zero.line(), Some(4));
    let vt = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/2 2/1 3/1\n".as_bytes()).unwrap_err();
    assert_eq!(vt.line(), Some(5));
    assert!(vt.to_string().contains("index 2 is out of range"), "{vt}");
    let bad = read_obj("v 0 0 zero\n".as_bytes()).unwrap_err();
    assert_eq!(
        bad.to_string(),
        "<input>:1: expected a vertex coordinate, found \"zero\""
    );
}

#[test]
fn off_comments_headers_and_colours() {
    let off = "\
# made by hand
COFF
# counts on their own line
4 2 5
0 0 0 255 0 0 255
1 0 0 0 255 0 255
1 1 0 0 0 255 255
0 1 0 255 255 255 128 # half transparent
3 0 1 2 1.0 0.5 0.0
3 0 2 3 0 0 255
";
    let m = read_off(off.as_bytes()).unwrap();
    assert_eq!((m.vertex_count(), m.face_count()), (4, 2));
    let faces: Vec<FaceKey> = m.faces().collect();
    let colour = |v: Option<Value>| match v {
        Some(Value::List(items)) => items
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect::<Vec<_>>(),
        other => panic!("{other:?}"),
    };
    assert_eq!(
        colour(m.attr_value("color", faces[0]).unwrap()),
        [1.0, 0.5, 0.0, 1.0]
    );
    assert_eq!(
        colour(m.attr_value("color", faces[1]).unwrap()),
        [0.0, 0.0, 1.0, 1.0]
    );
    let vs: Vec<VertexKey> = m.vertices().collect();
    assert_eq!(
        colour(m.attr_value("color", vs[3]).unwrap()),
        [1.0, 1.0, 1.0, 128.0 / 255.0]
    );
    let mut bytes = Vec::new();
    write_off(&m, &mut bytes).unwrap();
    assert!(bytes.starts_with(b"COFF\n"));
    let back = read_off(&bytes[..]).unwrap();
    for (f, g) in m.faces().zip(back.faces()) {
        assert_eq!(
            m.attr_value("color", f).unwrap(),
            back.attr_value("color", g).unwrap()
        );
    }
    for (v, w) in m.vertices().zip(back.vertices()) {
        assert_eq!(
            m.attr_value("color", v).unwrap(),
            back.attr_value("color", w).unwrap()
        );
    }
}

#[test]
fn off_errors() {
    let short =
        read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n# ........................\n".as_bytes()).unwrap_err();
    assert!(matches!(short, Error::Truncated { .. }), "{short}");
    assert_eq!(short.line(), Some(6));
    assert!(short.to_string().contains("vertex 3 of 3"), "{short}");
    let huge = read_off("OFF\n99999999999 1 0\n0 0 0\n".as_bytes()).unwrap_err();
    assert!(matches!(huge, Error::Header { .. }), "{huge}");
    assert_eq!(huge.line(), Some(2));
    let range = read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n".as_bytes()).unwrap_err();
    assert!(matches!(range, Error::IndexOutOfRange { index: 3, .. }));
    assert_eq!(range.line(), Some(6));
    let binary = read_off("OFF BINARY\n".as_bytes()).unwrap_err();
    assert!(matches!(binary, Error::UnsupportedFormat { .. }));
}

#[test]
fn ply_properties_are_kept_and_written_back() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../shared/data/meshes/closed/openmesh_cube-minimal-custom_props-binary.ply"
    );
    let m = io::read(path).unwrap();
    let vertex: Vec<(String, Option<ValueType>)> = m
        .attr_info(ElementKind::Vertex)
        .into_iter()
        .map(|a| (a.name, a.value_type))
        .collect();
    assert_eq!(
        vertex,
        [
            ("position".to_string(), vertex[0].1),
            ("nx".into(), Some(ValueType::F32)),
            ("ny".into(), Some(ValueType::F32)),
            ("nz".into(), Some(ValueType::F32)),
            ("quality".into(), Some(ValueType::F32)),
            ("index".into(), Some(ValueType::U32)),
            ("test_values".into(), Some(ValueType::List)),
        ]
    );
    let face: Vec<String> = m
        .attr_info(ElementKind::Face)
        .into_iter()
        .map(|a| a.name)
        .collect();
    assert_eq!(face, ["texcoords", "faceIndex"]);
    for enc in [
        PlyEncoding::Ascii,
        PlyEncoding::BinaryLittleEndian,
        PlyEncoding::BinaryBigEndian,
    ] {
        let mut bytes = Vec::new();
        write_ply(&m, &mut bytes, enc).unwrap();
        let back = read_ply(&bytes[..]).unwrap();
        assert_eq!(shape(&back), shape(&m));
        for kind_names in [["quality", "index", "test_values"]] {
            for name in kind_names {
                for (v, w) in m.vertices().zip(back.vertices()) {
                    assert_eq!(
                        m.attr_value(name, v).unwrap(),
                        back.attr_value(name, w).unwrap(),
                        "{name} {enc:?}"
                    );
                }
            }
        }
        for (f, g) in m.faces().zip(back.faces()) {
            for name in ["texcoords", "faceIndex"] {
                assert_eq!(
                    m.attr_value(name, f).unwrap(),
                    back.attr_value(name, g).unwrap()
                );
            }
        }
    }
}

#[test]
fn ply_errors_name_line_or_byte() {
    let header = read_ply("ply\nformat ascii 1.0\nelement vertex 3\nproperty flot x\n".as_bytes())
        .unwrap_err();
    assert_eq!(header.line(), Some(4), "{header}");
    // A binary body cut short: the byte offset where the data ends.
    let mut bytes = Vec::new();
    write_ply(&mixed(), &mut bytes, PlyEncoding::BinaryLittleEndian).unwrap();
    bytes.truncate(bytes.len() - 3);
    let cut = read_ply(&bytes[..]).unwrap_err();
    assert!(matches!(cut, Error::Truncated { .. }), "{cut}");
    let at = cut.byte_offset().unwrap();
    assert!(
        at as usize <= bytes.len() && at as usize > bytes.len() - 8,
        "{cut}"
    );
    // A header claiming billions of faces fails at once, allocating nothing.
    let huge = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
                property float y\nproperty float z\nelement face 4000000000\n\
                property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let err = read_ply(huge.as_bytes()).unwrap_err();
    assert!(matches!(err, Error::Truncated { .. }), "{err}");
    assert!(err.to_string().contains("4000000000"), "{err}");
}

#[test]
fn stl_with_a_bare_solid_line_and_binary_that_starts_with_solid() {
    let ascii = "solid\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n\
                 vertex 0 1 0\n  endloop\n endfacet\n facet normal 0 0 1\n  outer loop\n\
                 vertex 1 0 0\n   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid\n";
    let m = read_stl(ascii.as_bytes()).unwrap();
    assert_eq!(
        (m.vertex_count(), m.face_count(), m.edge_count()),
        (4, 2, 5)
    );
    let mut bin = Vec::new();
    write_stl(&m, &mut bin, StlEncoding::Binary).unwrap();
    bin[..5].copy_from_slice(b"solid");
    let back = read_stl(&bin[..]).unwrap();
    assert_eq!(back.face_count(), 2);
    bin.truncate(bin.len() - 10);
    let cut = read_stl(&bin[..]).unwrap_err();
    assert_eq!(cut.byte_offset(), Some(84 + 50), "{cut}");
}

#[test]
fn strict_reads_reject_what_repair_fixes() {
    // A triangle listed twice, once flipped.
    let off = "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n3 0 2 1\n";
    let err = read_off(off.as_bytes()).unwrap_err();
    assert!(matches!(err, Error::Build { face: 2, .. }), "{err}");
    assert_eq!(err.line(), Some(9));
    let (m, report) = io::read_off_with(off.as_bytes(), &ReadOptions::repair_all()).unwrap();
    assert_eq!(report.duplicate_faces, 1);
    assert_eq!(m.face_count(), 2);
}

#[test]
fn gzip_data_is_recognised_without_the_extension() {
    use std::io::Write;
    let mut bytes = Vec::new();
    write_obj(&mixed(), &mut bytes).unwrap();
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(&bytes).unwrap();
    let gz = gz.finish().unwrap();
    assert_eq!(shape(&read_obj(&gz[..]).unwrap()), shape(&mixed()));
    let path = temp("packed.obj");
    std::fs::write(&path, &gz).unwrap();
    assert_eq!(shape(&io::read(&path).unwrap()), shape(&mixed()));
    // Corrupt gzip data is an i/o error naming the file.
    let path = temp("broken.obj.gz");
    std::fs::write(&path, &gz[..gz.len() / 2]).unwrap();
    let err = io::read(&path).unwrap_err();
    assert!(matches!(err, Error::Io { .. }), "{err}");
    assert!(err.to_string().contains("broken.obj.gz"), "{err}");
}

#[test]
fn non_finite_positions_are_refused_by_vertex() {
    let err = read_obj("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n".as_bytes()).unwrap_err();
    assert!(matches!(err, Error::NonFinite { vertex: 1, .. }), "{err}");
    assert_eq!(err.line(), Some(2));
    let err = read_off("OFF\n3 1 0\n0 0 0\n1e999 0 0\n0 1 0\n3 0 1 2\n".as_bytes()).unwrap_err();
    assert!(matches!(err, Error::NonFinite { vertex: 1, .. }), "{err}");
    assert_eq!(err.line(), Some(4));
}

#[test]
fn unknown_extensions_and_missing_files() {
    let err = io::read("mesh.xyz").unwrap_err();
    assert!(matches!(err, Error::UnsupportedFormat { .. }), "{err}");
    let err = io::read(temp("does-not-exist.off")).unwrap_err();
    assert!(matches!(err, Error::Io { .. }), "{err}");
    assert!(err.to_string().contains("does-not-exist.off"), "{err}");
}

/// Materials named through the typed helper reach OBJ and glTF files and
/// come back on the same faces (found by their normals on the cube: the
/// readers renumber, and glTF comes back triangulated).
#[test]
fn face_materials_round_trip_through_obj_and_gltf() {
    use std::collections::BTreeMap;
    let mut m = meshloom::shapes::cube();
    let faces: Vec<_> = m.faces().collect();
    for (i, &f) in faces.iter().enumerate() {
        m.set_face_material(f, if i % 2 == 0 { "brick" } else { "glass" })
            .unwrap();
    }
    let by_normal = |m: &meshloom::Mesh| {
        let mut out = BTreeMap::new();
        for f in m.faces() {
            let p: Vec<[f64; 3]> = m
                .face(f)
                .unwrap()
                .vertices()
                .map(|v| m.position(v).unwrap())
                .collect();
            let (u, v) = (
                [0, 1, 2].map(|k| p[1][k] - p[0][k]),
                [0, 1, 2].map(|k| p[2][k] - p[0][k]),
            );
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let key = n.map(|x| x.signum() as i32 * i32::from(x.abs() > 1e-9));
            let name = m.face_material(f);
            // Every triangle of one cube face carries that face's material.
            assert_eq!(*out.entry(key).or_insert(name.clone()), name);
        }
        out
    };
    let expected = by_normal(&m);
    assert_eq!(expected.len(), 6);
    for ext in ["obj", "glb"] {
        let path =
            std::env::temp_dir().join(format!("meshloom-materials-{}.{ext}", std::process::id()));
        meshloom::io::write(&m, &path).unwrap();
        let back = meshloom::io::read(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(by_normal(&back), expected, "{ext}");
    }
}
