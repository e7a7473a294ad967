//! The one-sided shapes: the grid, the two spheres and the torus, built as
//! their untextured twins in [`shapes`](super::super) (same vertices, same
//! faces in the same order), scaled, with UVs by face.

use super::{check_count, check_size, unsuitable, Draft, ShapeOptions, SIDE};
use crate::shapes::{
    grid_polygons, icosphere_polygons, torus_polygons, uv_sphere_polygons, GridFaces,
    MAX_SUBDIVISIONS,
};
use crate::{Mesh, Polygons, Result};

/// A draft of `polygons` (scaled by `scale` about the origin, after
/// `shift`) with one UV per corner, every face on the one side [`SIDE`].
fn one_sided(
    mut polygons: Polygons,
    shift: [f64; 3],
    scale: [f64; 3],
    uvs: Vec<[f64; 2]>,
) -> Draft {
    for p in &mut polygons.positions {
        for a in 0..3 {
            p[a] = (p[a] + shift[a]) * scale[a];
        }
    }
    debug_assert_eq!(uvs.len(), polygons.indices.len());
    let materials = vec![SIDE; polygons.face_count()];
    Draft {
        polygons,
        uvs,
        materials,
    }
}

/// A flat grid of `cols × rows` quads in the `z = 0` plane, of sizes
/// `[x, y]` centred on the origin, faces counter-clockwise from `+z`, with
/// the unit square as its UVs (`u` along `x`), one island, no seam.
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a size that is not
/// finite and positive, `cols` or `rows` outside
/// `1..=`[`MAX_SEGMENTS`](crate::shapes::MAX_SEGMENTS).
///
/// ```
/// use meshloom::shapes::{textured_grid, ShapeOptions};
/// let g = textured_grid([2.0, 1.0], 4, 2, &ShapeOptions::default())?;
/// assert_eq!((g.vertex_count(), g.edge_count(), g.face_count()), (15, 22, 8));
/// assert_eq!(g.hole_count(), 1);
/// assert!(textured_grid([2.0, 1.0], 0, 2, &ShapeOptions::default()).is_err());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn textured_grid(
    size: [f64; 2],
    cols: usize,
    rows: usize,
    options: &ShapeOptions,
) -> Result<Mesh> {
    const SHAPE: &str = "grid";
    check_size(SHAPE, "x size", size[0], false)?;
    check_size(SHAPE, "y size", size[1], false)?;
    check_count(SHAPE, "cols", cols, 1)?;
    check_count(SHAPE, "rows", rows, 1)?;
    let p = grid_polygons(cols, rows, GridFaces::Quads);
    let (c, r) = (cols as f64, rows as f64);
    // Vertex (i, j) sits at (i, j, 0) before scaling: its UV is (i/c, j/r).
    let uvs = p
        .indices
        .iter()
        .map(|&v| {
            let q = p.positions[v as usize];
            [q[0] / c, q[1] / r]
        })
        .collect();
    let scale = [size[0] / c, size[1] / r, 1.0];
    one_sided(p, [-0.5 * c, -0.5 * r, 0.0], scale, uvs).finish(SHAPE, options)
}

/// The `u` of the two sides of column `j` of `n` around a seam: Blender's
/// wrap, `u = ((j + offset) mod n) / n`, the right side one step on (so 1
/// at the seam).
fn column(j: usize, n: usize, offset: usize) -> [f64; 2] {
    let k = (j + offset) % n;
    [k as f64 / n as f64, (k + 1) as f64 / n as f64]
}

/// A sphere of `radius` of latitude rings and longitude segments, as
/// [`uv_sphere`](crate::shapes::uv_sphere) (quads between rings, a fan of
/// triangles at each pole), with Blender's UVs: `u` the longitude, the seam
/// on the `−x` meridian, `v` the latitude from 0 (south pole) to 1 (north
/// pole); each pole triangle's pole corner sits above (below) the middle of
/// its segment, so the pole edges are seams too.
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a radius that is not
/// finite and positive, `segments` outside `3..=`[`MAX_SEGMENTS`](crate::shapes::MAX_SEGMENTS),
/// `rings` outside `2..=MAX_SEGMENTS`.
///
/// ```
/// use meshloom::shapes::{textured_uv_sphere, ShapeOptions};
/// let s = textured_uv_sphere(2.0, 8, 4, &ShapeOptions::default())?;
/// assert_eq!((s.vertex_count(), s.edge_count(), s.face_count()), (26, 56, 32));
/// assert!(s.is_closed());
/// assert!(textured_uv_sphere(-1.0, 8, 4, &ShapeOptions::default()).is_err());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn textured_uv_sphere(
    radius: f64,
    segments: usize,
    rings: usize,
    options: &ShapeOptions,
) -> Result<Mesh> {
    const SHAPE: &str = "uv_sphere";
    check_size(SHAPE, "radius", radius, false)?;
    check_count(SHAPE, "segments", segments, 3)?;
    check_count(SHAPE, "rings", rings, 2)?;
    let (s, r) = (segments, rings);
    let p = uv_sphere_polygons(s, r);
    let v = |k: usize| 1.0 - k as f64 / r as f64;
    let mut uvs = Vec::with_capacity(p.indices.len());
    // The faces in uv_sphere_polygons' order: the north fan, the bands, the
    // south fan.
    for j in 0..s {
        let [u0, u1] = column(j, s, s / 2);
        uvs.extend_from_slice(&[[0.5 * (u0 + u1), 1.0], [u0, v(1)], [u1, v(1)]]);
    }
    for k in 1..r - 1 {
        for j in 0..s {
            let [u0, u1] = column(j, s, s / 2);
            uvs.extend_from_slice(&[[u0, v(k)], [u0, v(k + 1)], [u1, v(k + 1)], [u1, v(k)]]);
        }
    }
    for j in 0..s {
        let [u0, u1] = column(j, s, s / 2);
        uvs.extend_from_slice(&[[0.5 * (u0 + u1), 0.0], [u1, v(r - 1)], [u0, v(r - 1)]]);
    }
    one_sided(p, [0.0; 3], [radius; 3], uvs).finish(SHAPE, options)
}

/// Where the icosahedron's face corners go in its UV net, in
/// `icosahedron_buffers`' face order: `(u, row)` with `u` in elevenths and
/// rows `√3/11` apart. The band of ten triangles lies between rows 1 and
/// 2, the fans around vertex 0 above it and around vertex 3 below.
const ICOSAHEDRON_NET: [[(u8, u8); 3]; 20] = [
    [(2, 3), (1, 2), (3, 2)],
    [(4, 3), (3, 2), (5, 2)],
    [(6, 3), (5, 2), (7, 2)],
    [(8, 3), (7, 2), (9, 2)],
    [(10, 3), (9, 2), (11, 2)],
    [(5, 2), (3, 2), (4, 1)],
    [(3, 2), (1, 2), (2, 1)],
    [(11, 2), (9, 2), (10, 1)],
    [(9, 2), (7, 2), (8, 1)],
    [(7, 2), (5, 2), (6, 1)],
    [(3, 0), (4, 1), (2, 1)],
    [(1, 0), (2, 1), (0, 1)],
    [(9, 0), (10, 1), (8, 1)],
    [(7, 0), (8, 1), (6, 1)],
    [(5, 0), (6, 1), (4, 1)],
    [(2, 1), (4, 1), (3, 2)],
    [(0, 1), (2, 1), (1, 2)],
    [(8, 1), (10, 1), (9, 2)],
    [(6, 1), (8, 1), (7, 2)],
    [(4, 1), (6, 1), (5, 2)],
];

/// An icosphere of `radius`, as [`icosphere`](crate::shapes::icosphere),
/// with the UV net of Blender's: the icosahedron's 20 triangles unfolded
/// into equilateral triangles of side 2/11 (a band of ten, a fan of five
/// above and below; `v ≤ 3√3/11`), one island whose seams are the edges at
/// two opposite vertices and one band edge; each subdivision splits the
/// UVs at their midpoints as it splits the triangles.
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a radius that is not
/// finite and positive, `subdivisions` above [`MAX_SUBDIVISIONS`].
///
/// ```
/// use meshloom::shapes::{textured_icosphere, ShapeOptions};
/// let s = textured_icosphere(1.0, 2, &ShapeOptions::default())?;
/// assert_eq!((s.vertex_count(), s.edge_count(), s.face_count()), (162, 480, 320));
/// assert!(textured_icosphere(1.0, 99, &ShapeOptions::default()).is_err());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn textured_icosphere(radius: f64, subdivisions: u32, options: &ShapeOptions) -> Result<Mesh> {
    const SHAPE: &str = "icosphere";
    check_size(SHAPE, "radius", radius, false)?;
    if subdivisions > MAX_SUBDIVISIONS {
        return Err(unsuitable(
            SHAPE,
            format!("subdivisions must be in 0..={MAX_SUBDIVISIONS} (got {subdivisions})"),
        ));
    }
    let row = 3f64.sqrt() / 11.0;
    let mut tris: Vec<[[f64; 2]; 3]> = ICOSAHEDRON_NET
        .iter()
        .map(|t| t.map(|(u, k)| [f64::from(u) / 11.0, f64::from(k) * row]))
        .collect();
    let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
    for _ in 0..subdivisions {
        // The children in icosphere_polygons' order.
        tris = tris
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    let uvs = tris.into_iter().flatten().collect();
    let p = icosphere_polygons(subdivisions);
    one_sided(p, [0.0; 3], [radius; 3], uvs).finish(SHAPE, options)
}

/// A torus around the `z` axis, as [`torus`](crate::shapes::torus) (quad
/// `(i, j)`: `i` of `major_segments` around the axis, `j` of
/// `minor_segments` around the tube), with the UVs of Blender's add-mesh
/// torus: `u` around the axis, `v` around the tube, the unit square once,
/// the seams on the `−x` side and along the inside of the ring.
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a radius that is not
/// finite and positive, a segment count outside
/// `3..=`[`MAX_SEGMENTS`](crate::shapes::MAX_SEGMENTS).
///
/// ```
/// use meshloom::shapes::{textured_torus, ShapeOptions};
/// let t = textured_torus(1.0, 0.25, 12, 6, &ShapeOptions::default())?;
/// assert_eq!((t.vertex_count(), t.edge_count(), t.face_count()), (72, 144, 72));
/// assert_eq!(t.euler_characteristic(), 0);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn textured_torus(
    major_radius: f64,
    minor_radius: f64,
    major_segments: usize,
    minor_segments: usize,
    options: &ShapeOptions,
) -> Result<Mesh> {
    const SHAPE: &str = "torus";
    check_size(SHAPE, "major_radius", major_radius, false)?;
    check_size(SHAPE, "minor_radius", minor_radius, false)?;
    check_count(SHAPE, "major_segments", major_segments, 3)?;
    check_count(SHAPE, "minor_segments", minor_segments, 3)?;
    let (big, small) = (major_segments, minor_segments);
    let p = torus_polygons(big, small, major_radius, minor_radius);
    let mut uvs = Vec::with_capacity(p.indices.len());
    for i in 0..big {
        let [u0, u1] = column(i, big, big.div_ceil(2));
        for j in 0..small {
            let [v0, v1] = column(j, small, small.div_ceil(2));
            uvs.extend_from_slice(&[[u0, v0], [u1, v0], [u1, v1], [u0, v1]]);
        }
    }
    one_sided(p, [0.0; 3], [1.0; 3], uvs).finish(SHAPE, options)
}
