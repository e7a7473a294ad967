//! The shapes with walls and ends: the box, the cylinder and the cone.

use std::f64::consts::PI;

use super::{check_count, check_size, unsuitable, Draft, ShapeOptions, BOTTOM, SIDE, TOP};
use crate::{Mesh, Result};

/// The corners of each box face, as vertex numbers `4x + 2y + z` (each
/// bit: the `+` side on that axis), counter-clockwise from outside: the
/// walls `−x`, `+y`, `+x`, `−y`, then the bottom and the top; with the
/// lower left corner of each face's square in the UV cross and its
/// material.
const BOX_FACES: [([u32; 4], [f64; 2], u32); 6] = [
    ([0, 1, 3, 2], [0.375, 0.0], SIDE),
    ([2, 3, 7, 6], [0.375, 0.25], SIDE),
    ([6, 7, 5, 4], [0.375, 0.5], SIDE),
    ([4, 5, 1, 0], [0.375, 0.75], SIDE),
    ([2, 6, 4, 0], [0.125, 0.5], BOTTOM),
    ([7, 3, 1, 5], [0.625, 0.5], TOP),
];

/// A box of sizes `[x, y, z]` centred on the origin, in six quads, with the
/// UV cross of Blender's cube: the walls one above the other, the bottom
/// and the top on either side of the third wall, one island (7 seam
/// edges). Materials: [`SIDE`] on the four walls, [`BOTTOM`] and [`TOP`]
/// on the ends.
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a size that is not
/// finite and positive.
///
/// ```
/// use meshloom::attr::{FaceAttr, HalfedgeAttr};
/// use meshloom::shapes::{box_mesh, ShapeOptions, TOP};
/// let opts = ShapeOptions { materials: true, ..ShapeOptions::default() };
/// let b = box_mesh([2.0, 1.0, 0.5], &opts)?;
/// assert_eq!((b.vertex_count(), b.edge_count(), b.face_count()), (8, 12, 6));
/// assert!(b.is_closed());
/// let material: FaceAttr<u32> = b.attr_handle("material")?;
/// let uv: HalfedgeAttr<[f64; 2]> = b.attr_handle("uv")?;
/// let top = b.faces().find(|&f| b.attr(&material, f).unwrap() == Some(&TOP)).unwrap();
/// let h = b.face(top)?.halfedge().key();
/// assert_eq!(b.attr(&uv, h)?, Some(&[0.625, 0.5]));
/// assert!(box_mesh([1.0, f64::NAN, 1.0], &opts).is_err());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn box_mesh(size: [f64; 3], options: &ShapeOptions) -> Result<Mesh> {
    const SHAPE: &str = "box";
    for (name, s) in ["x size", "y size", "z size"].into_iter().zip(size) {
        check_size(SHAPE, name, s, false)?;
    }
    let mut d = Draft::with_capacity(8, 6, 24);
    for i in 0..8u32 {
        let coordinate = |axis: usize, bit: u32| {
            let half = 0.5 * size[axis];
            if i >> bit & 1 == 1 {
                half
            } else {
                -half
            }
        };
        d.vertex([coordinate(0, 2), coordinate(1, 1), coordinate(2, 0)]);
    }
    const W: f64 = 0.25;
    for (corners, [u, v], material) in BOX_FACES {
        let square = [[u, v], [u + W, v], [u + W, v + W], [u, v + W]];
        let face: Vec<(u32, [f64; 2])> = corners.into_iter().zip(square).collect();
        d.face(&face, material);
    }
    d.finish(SHAPE, options)
}

/// A cylinder around the `z` axis from `z = −height/2` to `height/2`, with
/// `segments` quads around its wall and (with [`ShapeOptions::caps`]) an
/// n-gon at each end. The first vertex of each ring is on `+y`, the rest
/// follow counter-clockwise seen from `+z`. UVs as Blender's: the wall a
/// strip over the upper half (the whole square without caps) with its seam
/// at the first vertex, each cap a disk (the top centred at
/// `(0.25, 0.25)`, the bottom at `(0.75, 0.25)`, mirrored so that it is not
/// flipped). Materials: [`SIDE`], [`BOTTOM`], [`TOP`].
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a radius or height
/// that is not finite and positive, `segments` outside
/// `3..=`[`MAX_SEGMENTS`](crate::shapes::MAX_SEGMENTS).
///
/// ```
/// use meshloom::shapes::{cylinder, ShapeOptions};
/// let c = cylinder(1.0, 2.0, 16, &ShapeOptions::default())?;
/// assert_eq!((c.vertex_count(), c.edge_count(), c.face_count()), (32, 48, 18));
/// assert_eq!(c.euler_characteristic(), 2);
/// assert!(cylinder(1.0, 2.0, 2, &ShapeOptions::default()).is_err());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn cylinder(radius: f64, height: f64, segments: usize, options: &ShapeOptions) -> Result<Mesh> {
    const SHAPE: &str = "cylinder";
    check_size(SHAPE, "radius", radius, false)?;
    frustum(SHAPE, [radius, radius], height, segments, options)
}

/// A cone (a frustum) around the `z` axis from `z = −height/2` (radius
/// `radius_bottom`) to `height/2` (radius `radius_top`), laid out as
/// [`cylinder`]. An end of radius 0 is a single apex vertex: the wall is a
/// fan of triangles there, that end has no cap, and the wall's UVs are its
/// projection along the axis into the disk of the end it faces (as
/// Blender's), with no seam.
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a radius that is
/// negative or not finite, both radii 0, a height that is not finite and
/// positive, `segments` outside `3..=`[`MAX_SEGMENTS`](crate::shapes::MAX_SEGMENTS).
///
/// ```
/// use meshloom::shapes::{cone, ShapeOptions};
/// let c = cone(1.0, 0.0, 2.0, 12, &ShapeOptions::default())?;
/// assert_eq!((c.vertex_count(), c.edge_count(), c.face_count()), (13, 24, 13));
/// assert!(c.is_closed());
/// let frustum = cone(1.0, 0.5, 1.0, 12, &ShapeOptions::default())?;
/// assert_eq!(frustum.face_count(), 14);
/// assert!(cone(0.0, 0.0, 1.0, 12, &ShapeOptions::default()).is_err());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn cone(
    radius_bottom: f64,
    radius_top: f64,
    height: f64,
    segments: usize,
    options: &ShapeOptions,
) -> Result<Mesh> {
    const SHAPE: &str = "cone";
    check_size(SHAPE, "radius_bottom", radius_bottom, true)?;
    check_size(SHAPE, "radius_top", radius_top, true)?;
    if radius_bottom == 0.0 && radius_top == 0.0 {
        return Err(unsuitable(SHAPE, "one radius must be positive".into()));
    }
    frustum(
        SHAPE,
        [radius_bottom, radius_top],
        height,
        segments,
        options,
    )
}

/// Where a cylinder's or a cone's corners go in UV space.
struct WallUvs {
    caps: bool,
    /// UV units per unit of length, for the faces that look up and down.
    scale: [f64; 2],
}

impl WallUvs {
    fn new(radii: [f64; 2], caps: bool) -> WallUvs {
        let disk = if caps { 0.24 } else { 0.5 };
        // An apex end borrows the other end's radius (Blender's real cone).
        let other = |r: f64, o: f64| if r > 0.0 { disk / r } else { disk / o };
        WallUvs {
            caps,
            scale: [other(radii[0], radii[1]), other(radii[1], radii[0])],
        }
    }

    /// A corner of the wall strip: `j` of `segments` around, on the top or
    /// the bottom ring.
    fn wall(&self, j: usize, segments: usize, top: bool) -> [f64; 2] {
        let low = if self.caps { 0.5 } else { 0.0 };
        [j as f64 / segments as f64, if top { 1.0 } else { low }]
    }

    /// A corner of a face that looks up (`+z`), seen from above.
    fn up(&self, p: [f64; 3]) -> [f64; 2] {
        let c = if self.caps { [0.25, 0.25] } else { [0.5, 0.5] };
        [c[0] + p[0] * self.scale[1], c[1] + p[1] * self.scale[1]]
    }

    /// A corner of a face that looks down, seen from below (mirrored in u).
    fn down(&self, p: [f64; 3]) -> [f64; 2] {
        let c = if self.caps { [0.75, 0.25] } else { [0.5, 0.5] };
        [c[0] - p[0] * self.scale[0], c[1] + p[1] * self.scale[0]]
    }
}

/// A cylinder or cone: rings (or apexes) at both ends, the wall, the caps.
fn frustum(
    shape: &'static str,
    radii: [f64; 2],
    height: f64,
    segments: usize,
    options: &ShapeOptions,
) -> Result<Mesh> {
    check_size(shape, "height", height, false)?;
    check_count(shape, "segments", segments, 3)?;
    let s = segments;
    let z = [-0.5 * height, 0.5 * height];
    let mut d = Draft::with_capacity(2 * s, s + 2, 6 * s);
    // Each end: the index of its first vertex, and whether it is a ring.
    let mut ends = [(0u32, false); 2];
    for (end, &r) in radii.iter().enumerate() {
        let first = d.polygons.positions.len() as u32;
        if r > 0.0 {
            for j in 0..s {
                let t = 2.0 * PI * j as f64 / s as f64;
                d.vertex([-r * t.sin(), r * t.cos(), z[end]]);
            }
        } else {
            d.vertex([0.0, 0.0, z[end]]);
        }
        ends[end] = (first, r > 0.0);
    }
    let at = |end: usize, j: usize| {
        let (first, ring) = ends[end];
        if ring {
            first + (j % s) as u32
        } else {
            first
        }
    };
    let uvs = WallUvs::new(radii, options.caps);
    let pos = |d: &Draft, v: u32| d.polygons.positions[v as usize];
    for j in 0..s {
        let k = j + 1;
        let face: Vec<(u32, [f64; 2])> = match (ends[0].1, ends[1].1) {
            (true, true) => vec![
                (at(0, j), uvs.wall(j, s, false)),
                (at(0, k), uvs.wall(k, s, false)),
                (at(1, k), uvs.wall(k, s, true)),
                (at(1, j), uvs.wall(j, s, true)),
            ],
            (true, false) => [at(0, j), at(0, k), at(1, 0)]
                .map(|v| (v, uvs.up(pos(&d, v))))
                .to_vec(),
            _ => [at(0, 0), at(1, k), at(1, j)]
                .map(|v| (v, uvs.down(pos(&d, v))))
                .to_vec(),
        };
        d.face(&face, SIDE);
    }
    if options.caps && ends[0].1 {
        let face: Vec<_> = (0..s)
            .rev()
            .map(|j| at(0, j))
            .map(|v| (v, uvs.down(pos(&d, v))))
            .collect();
        d.face(&face, BOTTOM);
    }
    if options.caps && ends[1].1 {
        let face: Vec<_> = (0..s)
            .map(|j| at(1, j))
            .map(|v| (v, uvs.up(pos(&d, v))))
            .collect();
        d.face(&face, TOP);
    }
    d.finish(shape, options)
}
