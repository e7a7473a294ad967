//! Malformed glTF files that made the reader panic (the defects issue,
//! item 2; inputs in `../shared/data/repros`): each is now a typed error
//! saying what and where, through the path and the bytes readers. The test
//! profile keeps debug assertions, so overflows are caught here too.
#![cfg(feature = "gltf")]

use meshloom::io::gltf::{read_gltf_bytes, GltfOptions};
use meshloom::io::{self, Error, ReadOptions};

const REPROS: &str = "../shared/data/repros";

/// The error of reading `name`, the same through the path and the bytes.
fn error_of(name: &str) -> Error {
    let path = format!("{REPROS}/{name}");
    let bytes = std::fs::read(&path).unwrap();
    for options in [ReadOptions::strict(), ReadOptions::repair_all()] {
        let from_bytes = read_gltf_bytes(&bytes, &options, &GltfOptions::default());
        assert!(from_bytes.is_err(), "{name} read from bytes");
    }
    let err = io::read(&path).unwrap_err();
    assert!(
        err.to_string().contains(name),
        "{name}: the error names the file: {err}"
    );
    err
}

#[test]
fn a_position_naming_a_missing_accessor_is_an_error_not_a_dependency_panic() {
    for (name, index, count) in [
        ("gltf_dep_meshrs151_panic.gltf", 4, 0),
        ("gltf_position_accessor_oob.gltf", 7, 1),
    ] {
        let err = error_of(name);
        assert!(matches!(err, Error::Header { .. }), "{err}");
        let text = err.to_string();
        assert!(
            text.contains("meshes[0].primitives[0].attributes.POSITION")
                && text.contains(&format!("accessor {index}, and there are {count}")),
            "{text}"
        );
    }
}

#[test]
fn normals_that_are_not_vec3_are_an_error() {
    // NORMAL as VEC2 (688) and as VEC4 (755, 761; 755 also sits one byte
    // off): each was a slice past its values.
    for name in [
        "gltf_read688_normal_panic.glb",
        "gltf_read755_slice_panic.glb",
        "gltf_read761_slice_panic.glb",
    ] {
        let err = error_of(name);
        assert!(matches!(err, Error::Header { .. }), "{name}: {err}");
        assert!(
            err.to_string().contains("mesh 0 primitive 0 NORMAL"),
            "{name}: {err}"
        );
    }
}

#[test]
fn a_buffer_view_offset_of_u64_max_is_an_error_not_an_overflow() {
    let err = error_of("gltf_read285_overflow_debugonly.glb");
    let Error::TooLarge { at, what } = &err else {
        panic!("{err}")
    };
    assert!(what.contains("accessor 1"), "{err}");
    assert_eq!(at.position, io::Position::Byte(u64::MAX), "{err}");
}

#[test]
fn indices_must_be_unsigned_integer_scalars() {
    use serde_json::json;
    // A unit triangle; its indices as floats.
    let floats: [f32; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 2.0];
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let doc = json!({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": 48, "uri": format!("data:application/octet-stream;base64,{}", b64(&bytes))}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "SCALAR"}
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    })
    .to_string();
    let err = read_gltf_bytes(
        doc.as_bytes(),
        &ReadOptions::strict(),
        &GltfOptions::default(),
    )
    .unwrap_err();
    assert!(
        err.to_string().contains("not unsigned integer scalars"),
        "{err}"
    );
}

#[test]
fn many_instances_of_a_mesh_are_bounded_by_the_byte_limit() {
    use serde_json::json;
    // A mesh of ten primitives (one triangle, welded into one), drawn by
    // 200 nodes: every instance reads its accessors again, and the byte
    // limit bounds the total.
    let floats: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let nodes: Vec<_> = (0..200)
        .map(|i| json!({"mesh": 0, "translation": [i, 0, 0]}))
        .collect();
    let doc = json!({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": 36, "uri": format!("data:application/octet-stream;base64,{}", b64(&bytes))}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": vec![json!({"attributes": {"POSITION": 0}}); 10]}],
        "nodes": nodes,
        "scenes": [{"nodes": (0..200).collect::<Vec<_>>()}],
    })
    .to_string();
    let pick = GltfOptions::default();
    let (all, _) = read_gltf_bytes(doc.as_bytes(), &ReadOptions::repair_all(), &pick).unwrap();
    assert!(all.face_count() >= 200);
    // The file and its buffer fit the limit; 200 instances of the
    // triangle do not (a quarter of the limit is the budget of values
    // read and corners made).
    let small = ReadOptions::repair_all().max_bytes(doc.len() as u64 + 1000);
    let err = match read_gltf_bytes(doc.as_bytes(), &small, &pick) {
        Ok((m, _)) => panic!("read {} faces", m.face_count()),
        Err(e) => e,
    };
    assert!(matches!(err, Error::TooLarge { .. }), "{err}");
    assert!(err.to_string().contains("each instance"), "{err}");
}

/// Base64 for a data URI.
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
