//! Named shapes for tests, docs and benchmarks. Every shape is closed unless
//! its doc says otherwise, and its faces run counter-clockwise seen from
//! outside.

use crate::Mesh;

fn build<F: AsRef<[u32]>>(positions: &[[f64; 3]], faces: &[F]) -> Mesh {
    Mesh::from_polygons(positions, faces).expect("built-in shapes are valid")
}

/// A regular tetrahedron: 4 vertices, 6 edges, 4 triangles.
///
/// ```
/// let t = meshloom::shapes::tetrahedron();
/// assert_eq!((t.vertex_count(), t.edge_count(), t.face_count()), (4, 6, 4));
/// ```
pub fn tetrahedron() -> Mesh {
    let p = [
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ];
    build(&p, &[[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
}

/// The unit cube `[0, 1]³` in quads: 8 vertices, 12 edges, 6 faces.
///
/// ```
/// let c = meshloom::shapes::cube();
/// assert_eq!((c.vertex_count(), c.edge_count(), c.face_count()), (8, 12, 6));
/// ```
pub fn cube() -> Mesh {
    let mut p = Vec::with_capacity(8);
    for i in 0..8u32 {
        p.push([
            f64::from(i & 1),
            f64::from((i >> 1) & 1),
            f64::from((i >> 2) & 1),
        ]);
    }
    build(
        &p,
        &[
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ],
    )
}

/// A regular icosahedron on the unit sphere: 12 vertices, 30 edges, 20
/// triangles.
///
/// ```
/// let m = meshloom::shapes::icosahedron();
/// assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (12, 30, 20));
/// ```
pub fn icosahedron() -> Mesh {
    let (p, f) = icosahedron_buffers();
    build(&p, &f)
}

pub(crate) fn icosahedron_buffers() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let s = (1.0 + t * t).sqrt();
    let raw = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let p = raw.iter().map(|q| [q[0] / s, q[1] / s, q[2] / s]).collect();
    let f = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    (p, f)
}
