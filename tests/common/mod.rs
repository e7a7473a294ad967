//! Shared helpers for the operator tests: named meshes, snapshots, reading
//! the shared meshes, conserved totals.
#![allow(dead_code)]

pub mod hausdorff;
pub mod ops;
pub mod query;

use meshloom::attr::{Conserved, FaceAttr, VertexAttr};
use meshloom::{FaceKey, HalfedgeKey, Mesh, VertexKey};

/// A vertex one-ring: centre 0 and six triangles around it (closed fan,
/// open outer boundary).
pub fn one_ring() -> Mesh {
    let mut p = vec![[0.0, 0.0, 0.0]];
    for i in 0..6 {
        let a = std::f64::consts::TAU * f64::from(i) / 6.0;
        p.push([a.cos(), a.sin(), 0.0]);
    }
    let faces: Vec<[u32; 3]> = (0..6).map(|i| [0, 1 + i, 1 + (i + 1) % 6]).collect();
    Mesh::from_polygons(&p, &faces).unwrap()
}

/// A boundary fan: centre 0 on the boundary, four triangles.
pub fn boundary_fan() -> Mesh {
    let mut p = vec![[0.0, 0.0, 0.0]];
    for i in 0..5 {
        let a = std::f64::consts::PI * f64::from(i) / 4.0;
        p.push([a.cos(), a.sin(), 0.0]);
    }
    let faces: Vec<[u32; 3]> = (0..4).map(|i| [0, 1 + i, 2 + i]).collect();
    Mesh::from_polygons(&p, &faces).unwrap()
}

/// An L-shape of three unit quads.
pub fn l_shape() -> Mesh {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
        [0.0, 2.0, 0.0],
        [1.0, 2.0, 0.0],
    ];
    Mesh::from_polygons(&p, &[[0u32, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6]]).unwrap()
}

/// An open cone: apex 0 above a ring of six, no base.
pub fn open_cone() -> Mesh {
    let mut p = vec![[0.0, 0.0, 1.0]];
    for i in 0..6 {
        let a = std::f64::consts::TAU * f64::from(i) / 6.0;
        p.push([a.cos(), a.sin(), 0.0]);
    }
    let faces: Vec<[u32; 3]> = (0..6).map(|i| [0, 1 + (i + 1) % 6, 1 + i]).collect();
    Mesh::from_polygons(&p, &faces).unwrap()
}

/// A bowtie vertex: two triangles meeting only at vertex 0.
pub fn bowtie() -> Mesh {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, -0.5, 0.0],
        [1.0, 0.5, 0.0],
        [-1.0, 0.5, 0.0],
        [-1.0, -0.5, 0.0],
    ];
    Mesh::from_polygons(&p, &[[0u32, 1, 2], [0, 3, 4]]).unwrap()
}

/// An `n × n` grid of unit quads.
pub fn quad_grid(n: u32) -> Mesh {
    let mut p = Vec::new();
    for y in 0..=n {
        for x in 0..=n {
            p.push([f64::from(x), f64::from(y), 0.0]);
        }
    }
    let mut faces = Vec::new();
    for y in 0..n {
        for x in 0..n {
            let v = y * (n + 1) + x;
            faces.push([v, v + 1, v + n + 2, v + n + 1]);
        }
    }
    Mesh::from_polygons(&p, &faces).unwrap()
}

/// Everything observable about the structure: keys, links, hole flags,
/// positions, slot counts.
#[derive(Debug, PartialEq)]
pub struct Snapshot {
    counts: [usize; 4],
    slots: [usize; 4],
    halfedges: Vec<(HalfedgeKey, VertexKey, HalfedgeKey, FaceKey)>,
    vertices: Vec<(VertexKey, HalfedgeKey, Option<[u64; 3]>)>,
    faces: Vec<(FaceKey, HalfedgeKey, bool)>,
}

pub fn snapshot(m: &Mesh) -> Snapshot {
    Snapshot {
        counts: [
            m.vertex_count(),
            m.edge_count(),
            m.face_count(),
            m.hole_count(),
        ],
        slots: m.slot_counts(),
        halfedges: m
            .halfedges()
            .map(|h| {
                let v = m.halfedge(h).unwrap();
                (h, v.origin().key(), v.next().key(), v.face().key())
            })
            .collect(),
        vertices: m
            .vertices()
            .map(|v| {
                let view = m.vertex(v).unwrap();
                (
                    v,
                    view.halfedge().key(),
                    view.position().map(|p| p.map(f64::to_bits)),
                )
            })
            .collect(),
        faces: m
            .faces_and_holes()
            .map(|f| {
                let view = m.face(f).unwrap();
                (f, view.halfedge().key(), view.is_hole())
            })
            .collect(),
    }
}

/// Read a test mesh with the crate's reader, dropping vertices no face
/// uses (a few of the shared meshes have them).
pub fn read_off(path: &str) -> Mesh {
    let mut options = meshloom::io::ReadOptions::strict();
    options.repair.drop_unreferenced_vertices = true;
    meshloom::io::read_with(path, &options)
        .map(|(mesh, _)| mesh)
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

pub fn mesh_path(rel: &str) -> String {
    format!("{}/../shared/data/meshes/{rel}", env!("CARGO_MANIFEST_DIR"))
}

/// Conserved columns on faces and vertices, filled with 1.0 per element.
pub struct Totals {
    pub face: FaceAttr<f64, Conserved>,
    pub vertex: VertexAttr<f64, Conserved>,
}

pub fn add_totals(m: &mut Mesh) -> Totals {
    let face = m
        .add_attr_with_rule::<FaceKey, f64, Conserved>("mass")
        .unwrap();
    let vertex = m
        .add_attr_with_rule::<VertexKey, f64, Conserved>("charge")
        .unwrap();
    let faces: Vec<_> = m.faces().collect();
    for f in faces {
        m.set_attr(&face, f, 1.0).unwrap();
    }
    let vs: Vec<_> = m.vertices().collect();
    for v in vs {
        m.set_attr(&vertex, v, 1.0).unwrap();
    }
    Totals { face, vertex }
}

pub fn face_total(m: &Mesh, t: &Totals) -> f64 {
    m.faces()
        .filter_map(|f| m.attr(&t.face, f).unwrap().copied())
        .sum()
}

pub fn vertex_total(m: &Mesh, t: &Totals) -> f64 {
    m.vertices()
        .filter_map(|v| m.attr(&t.vertex, v).unwrap().copied())
        .sum()
}

pub fn counts(m: &Mesh) -> (usize, usize, usize, usize) {
    (
        m.vertex_count(),
        m.edge_count(),
        m.face_count(),
        m.hole_count(),
    )
}

/// Run `op`; on error the mesh must equal its snapshot; on success it must
/// validate. Returns the op's result.
pub fn checked<T>(
    m: &mut Mesh,
    op: impl FnOnce(&mut Mesh) -> meshloom::Result<T>,
) -> meshloom::Result<T> {
    let before = snapshot(m);
    let r = op(m);
    match &r {
        Ok(_) => m.validate().unwrap(),
        Err(_) => assert_eq!(snapshot(m), before, "a refused operator changed the mesh"),
    }
    r
}
