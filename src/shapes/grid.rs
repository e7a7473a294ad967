//! Shapes laid out on a grid of parameters: the flat grid, the disk and the
//! torus (a grid wrapped both ways).

use std::f64::consts::PI;

use super::{mesh_of, Buffers, MAX_SEGMENTS};
use crate::{Mesh, Polygons, Result};

/// How [`grid`] fills its cells.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum GridFaces {
    /// One quad per cell.
    Quads,
    /// Two triangles per cell, split along the diagonal from the cell's
    /// lower-left corner to its upper-right one.
    Triangles,
}

crate::choice::choices!(GridFaces {
    Quads = "quads",
    Triangles = "triangles",
});

/// A flat grid of `cols × rows` cells in the `z = 0` plane, with vertex
/// `(i, j)` at `(i, j, 0)` for `i` in `0..=cols`, `j` in `0..=rows`: open,
/// one boundary loop, faces counter-clockwise seen from `+z`.
///
/// # Arguments
/// `cols` and `rows` are clamped to `1..=`[`MAX_SEGMENTS`](super::MAX_SEGMENTS).
///
/// ```
/// use meshloom::shapes::{grid, GridFaces};
/// let q = grid(3, 2, GridFaces::Quads);
/// assert_eq!((q.vertex_count(), q.edge_count(), q.face_count()), (12, 17, 6));
/// assert_eq!((q.euler_characteristic(), q.hole_count()), (1, 1));
/// let t = grid(3, 2, GridFaces::Triangles);
/// assert_eq!((t.vertex_count(), t.edge_count(), t.face_count()), (12, 23, 12));
/// assert_eq!(t.euler_characteristic(), 1);
/// ```
pub fn grid(cols: usize, rows: usize, faces: GridFaces) -> Mesh {
    mesh_of(&grid_polygons(cols, rows, faces))
}

/// [`grid`] as buffers: vertex `(i, j)` has index `j · (cols + 1) + i`,
/// cells are listed row by row.
///
/// ```
/// use meshloom::shapes::{grid_polygons, GridFaces};
/// let p = grid_polygons(2, 2, GridFaces::Quads);
/// assert_eq!(p.face(0), Some(&[0, 1, 4, 3][..]));
/// assert_eq!(p.positions[4], [1.0, 1.0, 0.0]);
/// ```
pub fn grid_polygons(cols: usize, rows: usize, faces: GridFaces) -> Polygons {
    let c = cols.clamp(1, MAX_SEGMENTS);
    let r = rows.clamp(1, MAX_SEGMENTS);
    let (nf, nc) = match faces {
        GridFaces::Quads => (c * r, 4 * c * r),
        GridFaces::Triangles => (2 * c * r, 6 * c * r),
    };
    let mut b = Buffers::with_capacity((c + 1) * (r + 1), nf, nc);
    for j in 0..=r {
        for i in 0..=c {
            b.vertex([i as f64, j as f64, 0.0]);
        }
    }
    let at = |i: usize, j: usize| (j * (c + 1) + i) as u32;
    for j in 0..r {
        for i in 0..c {
            let (v00, v10, v11, v01) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            match faces {
                GridFaces::Quads => b.face(&[v00, v10, v11, v01]),
                GridFaces::Triangles => {
                    b.face(&[v00, v10, v11]);
                    b.face(&[v00, v11, v01]);
                }
            }
        }
    }
    b.finish()
}

/// A unit disk in the `z = 0` plane as a fan of triangles around its centre:
/// `segments + 1` vertices, `2 · segments` edges, `segments` triangles, one
/// boundary loop.
///
/// # Arguments
/// `segments` is clamped to `3..=`[`MAX_SEGMENTS`](super::MAX_SEGMENTS).
///
/// ```
/// let d = meshloom::shapes::disk(6);
/// assert_eq!((d.vertex_count(), d.edge_count(), d.face_count()), (7, 12, 6));
/// assert_eq!((d.euler_characteristic(), d.hole_count()), (1, 1));
/// assert_eq!(meshloom::shapes::disk(1).face_count(), 3);
/// ```
pub fn disk(segments: usize) -> Mesh {
    mesh_of(&disk_polygons(segments))
}

/// [`disk`] as buffers; vertex 0 is the centre.
///
/// ```
/// let p = meshloom::shapes::disk_polygons(4);
/// assert_eq!(p.face(0), Some(&[0, 1, 2][..]));
/// ```
pub fn disk_polygons(segments: usize) -> Polygons {
    let s = segments.clamp(3, MAX_SEGMENTS);
    let mut b = Buffers::with_capacity(s + 1, s, 3 * s);
    let centre = b.vertex([0.0, 0.0, 0.0]);
    for k in 0..s {
        let phi = 2.0 * PI * k as f64 / s as f64;
        b.vertex([phi.cos(), phi.sin(), 0.0]);
    }
    for k in 0..s {
        b.face(&[centre, 1 + k as u32, 1 + ((k + 1) % s) as u32]);
    }
    b.finish()
}

/// A torus around the `z` axis in quads: genus 1, closed, `M·m` vertices,
/// `2M·m` edges, `M·m` faces.
///
/// # Arguments
/// - `major_segments` (`M`): quads around the `z` axis, clamped to
///   `3..=`[`MAX_SEGMENTS`](super::MAX_SEGMENTS).
/// - `minor_segments` (`m`): quads around the tube, clamped likewise.
/// - `major_radius`: from the axis to the tube's centre line.
/// - `minor_radius`: the tube's radius. Any finite radii give a valid
///   mesh (a self-intersecting one if `minor_radius > major_radius`).
///
/// # Errors
/// [`Error::Build`](crate::Error::Build) with
/// [`BuildError::NonFinitePosition`](crate::BuildError::NonFinitePosition)
/// if a radius is NaN or so large that a coordinate overflows.
///
/// ```
/// let t = meshloom::shapes::torus(8, 6, 2.0, 0.5)?;
/// assert_eq!((t.vertex_count(), t.edge_count(), t.face_count()), (48, 96, 48));
/// assert_eq!(t.euler_characteristic(), 0);
/// assert!(t.is_closed());
/// assert!(meshloom::shapes::torus(8, 6, f64::NAN, 0.5).is_err());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn torus(
    major_segments: usize,
    minor_segments: usize,
    major_radius: f64,
    minor_radius: f64,
) -> Result<Mesh> {
    Mesh::from_buffers(&torus_polygons(
        major_segments,
        minor_segments,
        major_radius,
        minor_radius,
    ))
}

/// [`torus`] as buffers: vertex `(i, j)` (`i` around the axis, `j` around
/// the tube) has index `i · m + j`. Positions are not checked here (a NaN
/// radius gives NaN positions, which [`Mesh::from_buffers`] refuses).
///
/// ```
/// let p = meshloom::shapes::torus_polygons(4, 3, 1.0, 0.25);
/// assert_eq!((p.positions.len(), p.face_count()), (12, 12));
/// assert_eq!(p.positions[0], [1.25, 0.0, 0.0]);
/// ```
pub fn torus_polygons(
    major_segments: usize,
    minor_segments: usize,
    major_radius: f64,
    minor_radius: f64,
) -> Polygons {
    let big = major_segments.clamp(3, MAX_SEGMENTS);
    let small = minor_segments.clamp(3, MAX_SEGMENTS);
    let mut b = Buffers::with_capacity(big * small, big * small, 4 * big * small);
    for i in 0..big {
        let u = 2.0 * PI * i as f64 / big as f64;
        for j in 0..small {
            let v = 2.0 * PI * j as f64 / small as f64;
            let rho = major_radius + minor_radius * v.cos();
            b.vertex([rho * u.cos(), rho * u.sin(), minor_radius * v.sin()]);
        }
    }
    let at = |i: usize, j: usize| ((i % big) * small + j % small) as u32;
    for i in 0..big {
        for j in 0..small {
            b.face(&[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    b.finish()
}
