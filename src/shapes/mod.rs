//! Named shapes for tests, docs and benchmarks.
//!
//! Every shape comes twice: as a [`Mesh`] (`icosphere(2)`) and as compact
//! [`Polygons`] buffers (`icosphere_polygons(2)`), for callers that time or
//! test the build itself. Faces run counter-clockwise seen from outside
//! (from `+z` for the flat shapes). Closed shapes have Euler characteristic
//! 2 (the torus 0); the flat ones have one boundary loop and characteristic 1.
//!
//! | shape | V | E | F | χ |
//! |---|---|---|---|---|
//! | [`tetrahedron`] | 4 | 6 | 4 | 2 |
//! | [`cube`] (quads) | 8 | 12 | 6 | 2 |
//! | [`octahedron`] | 6 | 12 | 8 | 2 |
//! | [`icosahedron`] | 12 | 30 | 20 | 2 |
//! | [`icosphere`]`(n)` | 10·4ⁿ + 2 | 30·4ⁿ | 20·4ⁿ | 2 |
//! | [`uv_sphere`]`(s, r)` | s(r − 1) + 2 | s(2r − 1) | s·r | 2 |
//! | [`torus`]`(M, m, ..)` | M·m | 2M·m | M·m | 0 |
//! | [`grid`]`(c, r, Quads)` | (c + 1)(r + 1) | c(r + 1) + r(c + 1) | c·r | 1 |
//! | [`grid`]`(c, r, Triangles)` | (c + 1)(r + 1) | c(r + 1) + r(c + 1) + c·r | 2c·r | 1 |
//! | [`disk`]`(s)` | s + 1 | 2s | s | 1 |
//!
//! # Parameters
//!
//! Parameters are clamped into ranges that always give a valid mesh, so no
//! shape panics or fails on a count: subdivisions to
//! `0..=`[`MAX_SUBDIVISIONS`], segment, ring, row and column counts to their
//! documented minimum and at most [`MAX_SEGMENTS`]. Only [`torus`], whose
//! radii are caller-chosen floats, can fail (on a non-finite position).
//!
//! # Textured primitives
//!
//! [`box_mesh`], [`cylinder`], [`cone`], [`textured_grid`],
//! [`textured_uv_sphere`], [`textured_icosphere`] and [`textured_torus`]
//! come with a corner UV column laid out as Blender's primitives lay theirs
//! out, and a face material id per side when asked ([`ShapeOptions`]); see
//! [`textured`]. They check their parameters instead of clamping them.
//!
//! ```
//! use meshloom::attr::HalfedgeAttr;
//! use meshloom::shapes::{cylinder, ShapeOptions};
//! let opts = ShapeOptions { materials: true, ..ShapeOptions::default() };
//! let can = cylinder(0.5, 1.0, 24, &opts)?;
//! let uv: HalfedgeAttr<[f64; 2]> = can.attr_handle("uv")?;
//! let inside = |p: &[f64; 2]| p.iter().all(|x| (0.0..=1.0).contains(x));
//! assert!(can.halfedges().filter_map(|h| can.attr(&uv, h).unwrap()).all(inside));
//! # Ok::<(), meshloom::Error>(())
//! ```

mod grid;
mod sphere;
pub mod textured;

pub use grid::{disk, disk_polygons, grid, grid_polygons, torus, torus_polygons, GridFaces};
pub use sphere::{icosphere, icosphere_polygons, uv_sphere, uv_sphere_polygons};
pub use textured::{
    box_mesh, cone, cylinder, textured_grid, textured_icosphere, textured_torus,
    textured_uv_sphere, ShapeOptions, BOTTOM, MATERIAL, SIDE, TOP, UV,
};

use crate::{Mesh, Polygons};

/// The largest subdivision level [`icosphere`] accepts (larger ones are
/// clamped): 10·4⁹ + 2 = 2,621,442 vertices.
pub const MAX_SUBDIVISIONS: u32 = 9;

/// The largest segment, ring, row or column count any shape accepts (larger
/// ones are clamped).
pub const MAX_SEGMENTS: usize = 2048;

/// Polygons under construction: vertices and faces appended in order.
struct Buffers(Polygons);

impl Buffers {
    fn with_capacity(vertices: usize, faces: usize, corners: usize) -> Buffers {
        let mut offsets = Vec::with_capacity(faces + 1);
        offsets.push(0);
        Buffers(Polygons {
            positions: Vec::with_capacity(vertices),
            offsets,
            indices: Vec::with_capacity(corners),
        })
    }

    fn vertex(&mut self, p: [f64; 3]) -> u32 {
        self.0.positions.push(p);
        (self.0.positions.len() - 1) as u32
    }

    fn face(&mut self, corners: &[u32]) {
        self.0.indices.extend_from_slice(corners);
        self.0.offsets.push(self.0.indices.len() as u32);
    }

    fn finish(self) -> Polygons {
        self.0
    }
}

/// Buffers from positions and fixed-degree faces.
fn polygons_of<const N: usize>(positions: &[[f64; 3]], faces: &[[u32; N]]) -> Polygons {
    let mut b = Buffers::with_capacity(positions.len(), faces.len(), N * faces.len());
    for &p in positions {
        b.vertex(p);
    }
    for f in faces {
        b.face(f);
    }
    b.finish()
}

/// Build a shape whose buffers are valid by construction.
fn mesh_of(polygons: &Polygons) -> Mesh {
    // The shapes' parameters are clamped to ranges that give valid meshes
    // with finite positions, so this cannot fail on any caller input.
    Mesh::from_buffers(polygons).expect("built-in shapes are valid")
}

/// A regular tetrahedron: 4 vertices, 6 edges, 4 triangles.
///
/// ```
/// let t = meshloom::shapes::tetrahedron();
/// assert_eq!((t.vertex_count(), t.edge_count(), t.face_count()), (4, 6, 4));
/// assert_eq!(t.euler_characteristic(), 2);
/// ```
pub fn tetrahedron() -> Mesh {
    mesh_of(&tetrahedron_polygons())
}

/// [`tetrahedron`] as buffers.
pub fn tetrahedron_polygons() -> Polygons {
    let p = [
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ];
    polygons_of(&p, &[[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
}

/// The unit cube `[0, 1]³` in quads: 8 vertices, 12 edges, 6 faces.
///
/// ```
/// let c = meshloom::shapes::cube();
/// assert_eq!((c.vertex_count(), c.edge_count(), c.face_count()), (8, 12, 6));
/// assert_eq!(c.euler_characteristic(), 2);
/// ```
pub fn cube() -> Mesh {
    mesh_of(&cube_polygons())
}

/// [`cube`] as buffers.
pub fn cube_polygons() -> Polygons {
    let p: Vec<[f64; 3]> = (0..8u32)
        .map(|i| {
            [
                f64::from(i & 1),
                f64::from((i >> 1) & 1),
                f64::from((i >> 2) & 1),
            ]
        })
        .collect();
    polygons_of(
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

/// A regular octahedron with its corners on the axes (`±x`, `±y`, `±z`):
/// 6 vertices, 12 edges, 8 triangles.
///
/// ```
/// let o = meshloom::shapes::octahedron();
/// assert_eq!((o.vertex_count(), o.edge_count(), o.face_count()), (6, 12, 8));
/// assert_eq!(o.euler_characteristic(), 2);
/// assert!(o.vertices().all(|v| o.vertex(v).unwrap().degree() == 4));
/// ```
pub fn octahedron() -> Mesh {
    mesh_of(&octahedron_polygons())
}

/// [`octahedron`] as buffers.
pub fn octahedron_polygons() -> Polygons {
    let p = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    polygons_of(
        &p,
        &[
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    )
}

/// A regular icosahedron on the unit sphere: 12 vertices, 30 edges, 20
/// triangles.
///
/// ```
/// let m = meshloom::shapes::icosahedron();
/// assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (12, 30, 20));
/// assert_eq!(m.euler_characteristic(), 2);
/// ```
pub fn icosahedron() -> Mesh {
    mesh_of(&icosahedron_polygons())
}

/// [`icosahedron`] as buffers.
pub fn icosahedron_polygons() -> Polygons {
    let (p, f) = icosahedron_buffers();
    polygons_of(&p, &f)
}

fn icosahedron_buffers() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
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

#[cfg(test)]
mod tests;
