//! Files real peers read, and inputs that once panicked the PLY reader
//! (issue 10): each with its minimal input.

use meshloom::io::{self, Error, Format, ReadOptions};

fn both(format: Format, bytes: &[u8]) -> [Result<(meshloom::Mesh, io::RepairReport), Error>; 2] {
    [
        io::read_bytes(format, bytes, &ReadOptions::strict()),
        io::read_bytes(format, bytes, &ReadOptions::repair_all()),
    ]
}

fn header_line(e: &Error) -> Option<u64> {
    match e {
        Error::Header { .. } | Error::Syntax { .. } => e.line(),
        _ => None,
    }
}

#[test]
fn ply_second_vertex_element_without_xyz_is_a_located_error() {
    let ply = b"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement vertex 1\nend_header\n\n";
    for r in both(Format::Ply, ply) {
        let e = r.unwrap_err();
        assert_eq!(header_line(&e), Some(7), "{e}");
        assert!(e.to_string().contains("second vertex element"), "{e}");
    }
    // Through a file too.
    let path = std::env::temp_dir().join(format!("meshloom-dup-{}.ply", std::process::id()));
    std::fs::write(&path, ply).unwrap();
    let e = io::read(&path).unwrap_err();
    assert_eq!(e.line(), Some(7));
    assert!(e.to_string().contains(&*path.to_string_lossy()));
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn ply_header_audit_duplicates_lists_and_missing_parts() {
    let tri = "3 0 1 2\n";
    let verts = "0 0 0\n1 0 0\n0 1 0\n";
    let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    let cases: [(String, u64); 4] = [
        // A second face element.
        (
            format!("{head}element face 1\nproperty list uchar int vertex_indices\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n{verts}{tri}{tri}"),
            9,
        ),
        // A face element without a vertex list.
        (
            format!("{head}element face 1\nproperty uchar flags\nend_header\n{verts}1\n"),
            7,
        ),
        // A list with a float count type.
        (
            format!("{head}element face 1\nproperty list float int vertex_indices\nend_header\n{verts}{tri}"),
            8,
        ),
        // No vertex element at all: named on the header.
        (
            "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n3 0 1 2\n".to_owned(),
            2,
        ),
    ];
    for (text, line) in cases {
        for r in both(Format::Ply, text.as_bytes()) {
            let e = r.unwrap_err();
            assert_eq!(e.line(), Some(line), "{e}\n{text}");
        }
    }
    // A negative list length and a list longer than the file.
    for body in ["-1 0 1 2\n", "200 0 1 2\n"] {
        let text = format!("{head}element face 1\nproperty list char int vertex_indices\nend_header\n{verts}{body}");
        for r in both(Format::Ply, text.as_bytes()) {
            assert!(r.is_err());
        }
    }
}

#[test]
fn ply_nonstandard_header_line_strict_refuses_repair_warns() {
    let ply = b"ply\nformat ascii 1.0\nCreated by Blender 2.79 - www.blender.org, source file: ''\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let [strict, repaired] = both(Format::Ply, ply);
    let e = strict.unwrap_err();
    assert!(matches!(e, Error::NonStandard { .. }), "{e}");
    assert_eq!(e.line(), Some(3));
    let (mesh, report) = repaired.unwrap();
    assert_eq!(mesh.face_count(), 1);
    assert_eq!(report.warnings.len(), 1, "{report}");
    assert!(
        report.warnings[0].contains(":3:") && report.warnings[0].contains("Created by Blender")
    );
    assert!(report.to_string().starts_with("warning: "));
}

const TRIANGLE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

#[test]
fn obj_with_utf8_or_utf16_byte_order_mark_reads() {
    let mut utf8 = b"\xEF\xBB\xBF".to_vec();
    utf8.extend_from_slice(TRIANGLE_OBJ.as_bytes());
    let mut le = vec![0xFF, 0xFE];
    let mut be = vec![0xFE, 0xFF];
    for u in TRIANGLE_OBJ.encode_utf16() {
        le.extend_from_slice(&u.to_le_bytes());
        be.extend_from_slice(&u.to_be_bytes());
    }
    for bytes in [utf8, le, be] {
        for r in both(Format::Obj, &bytes) {
            let (m, _) = r.unwrap();
            assert_eq!((m.vertex_count(), m.face_count()), (3, 1));
        }
    }
}

#[test]
fn obj_texture_index_out_of_range_is_named_as_such() {
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/5 3/1\n";
    for r in both(Format::Obj, obj.as_bytes()) {
        let e = r.unwrap_err();
        assert!(
            matches!(
                e,
                Error::IndexOutOfRange {
                    what: "texture coordinate",
                    index: 5,
                    count: 1,
                    ..
                }
            ),
            "{e}"
        );
        assert_eq!(
            e.to_string(),
            "<input>:5: texture coordinate index 5 is out of range (there are 1 texture coordinates)"
        );
    }
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n";
    let e = io::read_bytes(Format::Obj, obj.as_bytes(), &ReadOptions::strict()).unwrap_err();
    assert!(
        matches!(e, Error::IndexOutOfRange { what: "normal", .. }),
        "{e}"
    );
}

#[test]
fn a_polygon_touching_itself_survives_repair() {
    // A concave heptagon whose corners 4 and 6 share a position (a slit):
    // valid as it is; repair keeps it, welding too (the weld would repeat
    // a corner, so it is refused).
    let obj = "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 2 0\nv 2 1 0\nv 2 2 0\nv 0 4 0\nf 1 2 3 4 5 6 7\n";
    for r in both(Format::Obj, obj.as_bytes()) {
        let (m, report) = r.unwrap();
        assert_eq!((m.vertex_count(), m.face_count()), (7, 1), "{report}");
    }
    let weld =
        ReadOptions::strict().repair(meshloom::repair::RepairOptions::all().weld_vertices(true));
    let (m, report) = io::read_bytes(Format::Obj, obj.as_bytes(), &weld).unwrap();
    assert_eq!(m.face_count(), 1);
    assert_eq!((report.welded_vertices, report.weld_refused), (0, 1));
}

#[test]
fn repair_that_drops_every_face_says_so() {
    // Two faces, both degenerate (a repeated corner): strict names the
    // face, repair says it dropped both and why.
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\nf 1 1 1\n";
    let [strict, repaired] = both(Format::Obj, obj.as_bytes());
    assert!(matches!(strict.unwrap_err(), Error::Build { .. }));
    let e = repaired.unwrap_err();
    assert!(matches!(e, Error::NothingLeft { faces: 2, .. }), "{e}");
    let text = e.to_string();
    assert!(
        text.contains("repairs dropped all 2 faces")
            && text.contains("degenerate faces dropped: 2"),
        "{text}"
    );
}
