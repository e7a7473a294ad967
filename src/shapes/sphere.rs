//! Spheres: the subdivided icosahedron and the latitude-longitude sphere.

use std::f64::consts::PI;

use super::{icosahedron_buffers, mesh_of, Buffers, MAX_SEGMENTS, MAX_SUBDIVISIONS};
use crate::vec3::{add, normalize_or_zero};
use crate::{Mesh, Polygons};

/// A unit sphere made by splitting each triangle of the
/// [`icosahedron`](super::icosahedron) into four, `subdivisions` times, and pushing the new
/// vertices onto the sphere. Midpoints are shared between neighbouring
/// triangles, so the result is closed: 10·4ⁿ + 2 vertices, 30·4ⁿ edges,
/// 20·4ⁿ triangles.
///
/// # Arguments
/// `subdivisions` is clamped to `0..=`[`MAX_SUBDIVISIONS`](super::MAX_SUBDIVISIONS);
/// 0 gives the icosahedron.
///
/// # Complexity
/// Linear in the output (midpoints are cached per edge in a list beside its
/// lower vertex, at most six entries long).
///
/// ```
/// use meshloom::shapes::icosphere;
/// let m = icosphere(2);
/// assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (162, 480, 320));
/// assert_eq!(m.euler_characteristic(), 2);
/// assert!(m.is_closed());
/// assert_eq!(icosphere(0).vertex_count(), 12);
/// ```
pub fn icosphere(subdivisions: u32) -> Mesh {
    mesh_of(&icosphere_polygons(subdivisions))
}

/// [`icosphere`] as buffers.
///
/// ```
/// let p = meshloom::shapes::icosphere_polygons(1);
/// assert_eq!((p.positions.len(), p.face_count()), (42, 80));
/// ```
pub fn icosphere_polygons(subdivisions: u32) -> Polygons {
    let n = subdivisions.min(MAX_SUBDIVISIONS);
    let (mut positions, mut faces) = icosahedron_buffers();
    for _ in 0..n {
        let nv = positions.len();
        // Each new midpoint, keyed by its edge: `cache[lo]` lists (hi, mid).
        let mut cache: Vec<Vec<(u32, u32)>> = vec![Vec::new(); nv];
        positions.reserve(faces.len() * 3 / 2);
        let mut midpoint = |a: u32, b: u32, positions: &mut Vec<[f64; 3]>| -> u32 {
            let (lo, hi) = (a.min(b), a.max(b));
            if let Some(&(_, m)) = cache[lo as usize].iter().find(|&&(h, _)| h == hi) {
                return m;
            }
            let (p, q) = (positions[a as usize], positions[b as usize]);
            // Never zero: an edge's ends are not antipodal.
            positions.push(normalize_or_zero(add(p, q)));
            let m = (positions.len() - 1) as u32;
            cache[lo as usize].push((hi, m));
            m
        };
        let mut finer = Vec::with_capacity(faces.len() * 4);
        for &[a, b, c] in &faces {
            let ab = midpoint(a, b, &mut positions);
            let bc = midpoint(b, c, &mut positions);
            let ca = midpoint(c, a, &mut positions);
            finer.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = finer;
    }
    super::polygons_of(&positions, &faces)
}

/// A unit sphere of latitude rings and longitude segments: quads between
/// rings and a fan of triangles at each pole, closed. `s(r − 1) + 2`
/// vertices, `s(2r − 1)` edges, `s·r` faces (`2s` of them triangles).
///
/// # Arguments
/// - `segments`: vertices per latitude ring, clamped to `3..=`[`MAX_SEGMENTS`](super::MAX_SEGMENTS).
/// - `rings`: bands from pole to pole, clamped to `2..=MAX_SEGMENTS` (2
///   gives a double pyramid: two fans and no quads).
///
/// ```
/// use meshloom::shapes::uv_sphere;
/// let m = uv_sphere(8, 4);
/// assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (26, 56, 32));
/// assert_eq!(m.euler_characteristic(), 2);
/// assert!(m.is_closed());
/// // Too few segments are clamped to the smallest sphere that exists.
/// assert_eq!(uv_sphere(0, 0).vertex_count(), uv_sphere(3, 2).vertex_count());
/// ```
pub fn uv_sphere(segments: usize, rings: usize) -> Mesh {
    mesh_of(&uv_sphere_polygons(segments, rings))
}

/// [`uv_sphere`] as buffers. Vertex 0 is the north pole (`+z`), the last the
/// south pole.
///
/// ```
/// let p = meshloom::shapes::uv_sphere_polygons(6, 3);
/// assert_eq!((p.positions.len(), p.face_count()), (14, 18));
/// assert_eq!(p.positions[0], [0.0, 0.0, 1.0]);
/// ```
pub fn uv_sphere_polygons(segments: usize, rings: usize) -> Polygons {
    let s = segments.clamp(3, MAX_SEGMENTS);
    let r = rings.clamp(2, MAX_SEGMENTS);
    let nv = s * (r - 1) + 2;
    let mut b = Buffers::with_capacity(nv, s * r, 4 * s * r);
    let north = b.vertex([0.0, 0.0, 1.0]);
    for k in 1..r {
        let theta = PI * k as f64 / r as f64;
        let (z, rho) = (theta.cos(), theta.sin());
        for j in 0..s {
            let phi = 2.0 * PI * j as f64 / s as f64;
            b.vertex([rho * phi.cos(), rho * phi.sin(), z]);
        }
    }
    let south = b.vertex([0.0, 0.0, -1.0]);
    // Vertex `j` (taken modulo s) of ring `k` (1-based).
    let at = |k: usize, j: usize| (1 + (k - 1) * s + j % s) as u32;
    for j in 0..s {
        b.face(&[north, at(1, j), at(1, j + 1)]);
    }
    for k in 1..r - 1 {
        for j in 0..s {
            b.face(&[at(k, j), at(k + 1, j), at(k + 1, j + 1), at(k, j + 1)]);
        }
    }
    for j in 0..s {
        b.face(&[south, at(r - 1, j + 1), at(r - 1, j)]);
    }
    b.finish()
}
