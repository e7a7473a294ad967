//! Repair of faces that visit a vertex twice: a polygon with a hole joined
//! to its outline by a bridge (as LightWave writes it, and assimp reads
//! it) and a figure eight become simple faces over the same area; none is
//! dropped, and the corners keep their UVs.

use meshloom::attr::Value;
use meshloom::io::{self, Format, ReadOptions};
use meshloom::Mesh;

type V3 = [f64; 3];

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The polygon's signed area along unit normal `n` (the shoelace formula
/// in its plane: half the Newell normal's component along `n`).
fn shoelace(points: &[V3], n: V3) -> f64 {
    let mut s = [0.0; 3];
    for i in 0..points.len() {
        let c = cross(points[i], points[(i + 1) % points.len()]);
        s = [s[0] + c[0], s[1] + c[1], s[2] + c[2]];
    }
    dot(s, n) / 2.0
}

/// Each face's area along `n` (negative for a face turned over), summed.
fn signed_area(mesh: &Mesh, n: V3) -> (f64, usize) {
    let mut sum = 0.0;
    let mut turned = 0;
    for f in mesh.faces() {
        let q: Vec<V3> = mesh
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| mesh.position(v).unwrap())
            .collect();
        let a = shoelace(&q, n);
        turned += usize::from(a <= 0.0);
        sum += a;
    }
    (sum, turned)
}

/// The vertices and the one face of an OBJ file (1-based `f` indices,
/// `v//vn` corners).
fn obj_polygon(text: &str) -> Vec<V3> {
    let v: Vec<V3> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let x: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            [x[0], x[1], x[2]]
        })
        .collect();
    let f = text.lines().find_map(|l| l.strip_prefix("f ")).unwrap();
    f.split_whitespace()
        .map(|c| v[c.split('/').next().unwrap().parse::<usize>().unwrap() - 1])
        .collect()
}

/// assimp's concave polygon: 66 corners, an outline and a hole joined by
/// a bridge edge walked both ways. Repair triangulated it as a polygon
/// with a hole (it dropped it whole, and the file was refused): the
/// triangles cover the polygon's area exactly, none turned over.
#[test]
fn a_polygon_with_a_bridged_hole_is_triangulated_not_dropped() {
    let path = "../shared/data/repros/assimp_concave_polygon.obj";
    let text = std::fs::read_to_string(path).unwrap();
    let polygon = obj_polygon(&text);
    assert_eq!(polygon.len(), 66);
    let (mesh, report) = io::read_with(path, &ReadOptions::repair_all()).unwrap();
    mesh.validate().unwrap();
    assert_eq!((report.split_faces, report.degenerate_faces), (1, 0));
    // Its plane's normal (the Newell normal of the polygon).
    let mut n = [0.0; 3];
    for i in 0..polygon.len() {
        let c = cross(polygon[i], polygon[(i + 1) % polygon.len()]);
        n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
    }
    let len = dot(n, n).sqrt();
    let n = n.map(|x| x / len);
    let whole = shoelace(&polygon, n);
    assert!(whole > 0.0);
    let (sum, turned) = signed_area(&mesh, n);
    assert_eq!(turned, 0, "a triangle is turned over");
    assert!((sum - whole).abs() < 1e-9 * whole, "{sum} vs {whole}");
    // 64 vertices, a polygon with one hole: V + 2 (holes) − 2 = 64 triangles.
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (64, 64));
    assert_eq!(mesh.hole_count(), 2);
}

/// The numbers of a texture coordinate value.
fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::List(xs) => xs.iter().filter_map(Value::as_f64).collect(),
        x => x.as_f64().into_iter().collect(),
    }
}

/// A square with a square hole, bridged (as above), each corner with its
/// own UV: every corner of the triangles keeps the UV of the polygon's
/// corner it came from (here, the vertex's x and y), and the area is the
/// square's less the hole's.
#[test]
fn a_bridged_polygon_keeps_its_corner_uvs() {
    let obj = "\
v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 1 1 0\nv 1 3 0\nv 3 3 0\nv 3 1 0\n\
vt 0 0\nvt 4 0\nvt 4 4\nvt 0 4\nvt 1 1\nvt 1 3\nvt 3 3\nvt 3 1\n\
f 1/1 2/2 3/3 4/4 1/1 5/5 6/6 7/7 8/8 5/5\n";
    let (mesh, report) =
        io::read_bytes(Format::Obj, obj.as_bytes(), &ReadOptions::repair_all()).unwrap();
    mesh.validate().unwrap();
    assert_eq!(report.split_faces, 1);
    let (sum, turned) = signed_area(&mesh, [0.0, 0.0, 1.0]);
    assert_eq!(turned, 0);
    assert!((sum - 12.0).abs() < 1e-12, "{sum}");
    assert_eq!((mesh.face_count(), mesh.hole_count()), (8, 2));
    for f in mesh.faces() {
        for h in mesh.face(f).unwrap().halfedges() {
            let p = mesh
                .position(mesh.halfedge(h).unwrap().origin().key())
                .unwrap();
            let uv = mesh.attr_value("texcoord", h).unwrap().unwrap();
            assert_eq!(numbers(&uv), [p[0], p[1]]);
        }
    }
}

/// A figure eight (two triangles' worth of outline through one vertex,
/// no bridge) becomes two faces, one per loop, at the same vertex.
#[test]
fn a_figure_eight_becomes_two_faces() {
    let obj = "v 0 0 0\nv 2 -1 0\nv 2 1 0\nv -2 1 0\nv -2 -1 0\nf 1 2 3 1 4 5\n";
    let (mesh, report) =
        io::read_bytes(Format::Obj, obj.as_bytes(), &ReadOptions::repair_all()).unwrap();
    mesh.validate().unwrap();
    assert_eq!((report.split_faces, report.degenerate_faces), (1, 0));
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (5, 2));
    let (sum, turned) = signed_area(&mesh, [0.0, 0.0, 1.0]);
    assert_eq!(turned, 0);
    assert!((sum - 4.0).abs() < 1e-12, "{sum}");
}
