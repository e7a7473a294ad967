//! Primitives ready for texturing: a corner UV column laid out as Blender's
//! primitives lay theirs out (`calc_uvs` in BMesh's `bmo_primitive.cc`,
//! the torus as its add-mesh operator), and optionally a face material id
//! per natural side, so a generator starts from a textured shape.
//!
//! The UVs sit in the half-edge (corner) column [`UV`] as `[f64; 2]`, every
//! value in `[0, 1]²`, every face counter-clockwise in UV space as it is on
//! the surface (no mirrored island). Corners around a vertex share their
//! value inside an island; along a seam the corners on the two sides of
//! the edge differ, so the tools that follow keep the seam (a seam is where
//! the values on the two sides of an edge differ).
//!
//! | shape | V | E | F | χ | UV islands | seam edges |
//! |---|---|---|---|---|---|---|
//! | [`box_mesh`] | 8 | 12 | 6 | 2 | 1 (a cross) | 7 |
//! | [`cylinder`]`(s)` with caps | 2s | 3s | s + 2 | 2 | 3 (side, 2 caps) | 2s + 1 |
//! | [`cylinder`]`(s)` open | 2s | 3s | s | 0 | 1 | 1 |
//! | [`cone`]`(s)` to a point, with cap | s + 1 | 2s | s + 1 | 2 | 2 (side, cap) | s |
//! | [`textured_grid`]`(c, r)` | (c + 1)(r + 1) | c(r + 1) + r(c + 1) | c·r | 1 | 1 | 0 |
//! | [`textured_uv_sphere`]`(s, r)` | s(r − 1) + 2 | s(2r − 1) | s·r | 2 | 1 (s for r = 2) | r − 2 + 2s |
//! | [`textured_icosphere`]`(n)` | 10·4ⁿ + 2 | 30·4ⁿ | 20·4ⁿ | 2 | 1 | 11·2ⁿ |
//! | [`textured_torus`]`(M, m)` | M·m | 2M·m | M·m | 0 | 1 | M + m |
//!
//! The layouts, after Blender:
//! - **box**: the cross of `BM_mesh_calc_uvs_cube`: the four walls in a
//!   column of squares of side ¼ at `u ∈ [0.375, 0.625]`, the bottom and
//!   the top beside the third wall, one island.
//! - **cylinder, cone** (`BM_mesh_calc_uvs_cone`): the wall a strip across
//!   the width (the upper half with caps, the whole square without), the
//!   seam at the first segment (`+y`); each cap a disk of radius 0.24
//!   centred at `(0.25, 0.25)` (top) and `(0.75, 0.25)` (bottom). A cone's
//!   wall that narrows to a point is projected along the axis like a cap,
//!   into the disk of the end it faces: no seam on it. Unlike Blender the
//!   faces that look down (the bottom cap) are mirrored in `u`, so that no
//!   island is flipped.
//! - **grid** (`BM_mesh_calc_uvs_grid`): the unit square, `u` along `x`.
//! - **UV sphere** (`BM_mesh_calc_uvs_sphere`): `u` the longitude, `v` the
//!   latitude (1 at the north pole), the seam on the `−x` meridian; each
//!   pole triangle has its own pole corner, in the middle of its segment.
//! - **icosphere**: the 20 triangles unfolded as Blender's fixed table
//!   unfolds them (a band of ten with a fan of five above and below, each
//!   of side 2/11, `v ∈ [0, 3√3/11]`); every subdivision splits the
//!   triangles' UVs at their midpoints, as their positions.
//! - **torus** (`add_mesh_torus.py`): `u` around the axis, `v` around the
//!   tube, the seams on the `−x` side and inside the ring.
//!
//! The material ids (the `u32` face column [`MATERIAL`], with
//! [`ShapeOptions::materials`]) name each shape's natural sides:
//! [`SIDE`] for the walls of a box, a cylinder or a cone and for every face
//! of the shapes with one side (grid, spheres, torus); [`BOTTOM`] and
//! [`TOP`] for the box's and the caps' ends.
//!
//! Invalid parameters (a count out of range, a size that is not finite and
//! positive) return [`Error::Unsuitable`] naming
//! the shape and the parameter; nothing panics.

mod prism;
mod round;
#[cfg(test)]
mod tests;

pub use prism::{box_mesh, cone, cylinder};
pub use round::{textured_grid, textured_icosphere, textured_torus, textured_uv_sphere};

use crate::error::{Error, Result};
use crate::keys::HalfedgeKey;
use crate::{Mesh, Polygons};

/// The name of the corner column of UVs (`[f64; 2]`).
pub const UV: &str = "uv";

/// The name of the face column of material ids (`u32`).
pub const MATERIAL: &str = "material";

/// The material id of the walls (and of every face of a one-sided shape).
pub const SIDE: u32 = 0;

/// The material id of the bottom (`−z`) end: a box's bottom, a bottom cap.
pub const BOTTOM: u32 = 1;

/// The material id of the top (`+z`) end: a box's top, a top cap.
pub const TOP: u32 = 2;

/// What a textured primitive carries besides its positions.
///
/// ```
/// use meshloom::shapes::ShapeOptions;
/// let o = ShapeOptions::default();
/// assert!(o.uv && !o.materials && o.caps);
/// let open = ShapeOptions { caps: false, ..ShapeOptions::default() };
/// let tube = meshloom::shapes::cylinder(1.0, 2.0, 8, &open)?;
/// assert_eq!(tube.hole_count(), 2);
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ShapeOptions {
    /// Add the corner column [`UV`] (default: yes).
    pub uv: bool,
    /// Add the face column [`MATERIAL`] of side ids (default: no).
    pub materials: bool,
    /// Close a cylinder's or a cone's ends with one polygon each (default:
    /// yes); the other shapes ignore it.
    pub caps: bool,
}

impl Default for ShapeOptions {
    fn default() -> ShapeOptions {
        ShapeOptions {
            uv: true,
            materials: false,
            caps: true,
        }
    }
}

/// A shape under construction: polygons, a UV per corner, a material per
/// face, in input order.
struct Draft {
    polygons: Polygons,
    uvs: Vec<[f64; 2]>,
    materials: Vec<u32>,
}

impl Draft {
    fn with_capacity(vertices: usize, faces: usize, corners: usize) -> Draft {
        let mut offsets = Vec::with_capacity(faces + 1);
        offsets.push(0);
        Draft {
            polygons: Polygons {
                positions: Vec::with_capacity(vertices),
                offsets,
                indices: Vec::with_capacity(corners),
            },
            uvs: Vec::with_capacity(corners),
            materials: Vec::with_capacity(faces),
        }
    }

    fn vertex(&mut self, p: [f64; 3]) -> u32 {
        self.polygons.positions.push(p);
        (self.polygons.positions.len() - 1) as u32
    }

    /// A face: its corners with their UVs, counter-clockwise from outside.
    fn face(&mut self, corners: &[(u32, [f64; 2])], material: u32) {
        for &(v, uv) in corners {
            self.polygons.indices.push(v);
            self.uvs.push(uv);
        }
        let end = self.polygons.indices.len() as u32;
        self.polygons.offsets.push(end);
        self.materials.push(material);
    }

    /// The mesh with the columns `options` ask for.
    fn finish(self, shape: &'static str, options: &ShapeOptions) -> Result<Mesh> {
        debug_assert_eq!(self.uvs.len(), self.polygons.indices.len());
        debug_assert_eq!(self.materials.len(), self.polygons.face_count());
        if let Some(p) = self
            .polygons
            .positions
            .iter()
            .find(|p| !p.iter().all(|x| x.is_finite()))
        {
            return Err(unsuitable(
                shape,
                format!("the sizes are too large: a position overflows to {p:?}"),
            ));
        }
        let built = Mesh::build_buffers(&self.polygons)?;
        let mut mesh = built.mesh;
        if options.uv {
            // `halfedges` starts at each face's first input corner.
            let corners: Vec<HalfedgeKey> = built
                .faces
                .iter()
                .flat_map(|&f| mesh.face(f).map(|f| f.halfedges()).into_iter().flatten())
                .collect();
            let column = mesh.add_halfedge_attr::<[f64; 2]>(UV)?;
            let mut view = mesh.attr_view_mut(&column)?;
            for (&h, &uv) in corners.iter().zip(&self.uvs) {
                view.set(h, Some(uv))?;
            }
            view.drop_full_presence();
        }
        if options.materials {
            let column = mesh.add_face_attr::<u32>(MATERIAL)?;
            let mut view = mesh.attr_view_mut(&column)?;
            for (&f, &m) in built.faces.iter().zip(&self.materials) {
                view.set(f, Some(m))?;
            }
        }
        Ok(mesh)
    }
}

/// The error of a parameter out of its range.
fn unsuitable(shape: &'static str, reason: String) -> Error {
    Error::Unsuitable {
        algorithm: shape,
        key: None,
        reason,
    }
}

/// `Ok` if `value` is finite and positive (or zero, with `zero_ok`).
fn check_size(shape: &'static str, name: &str, value: f64, zero_ok: bool) -> Result<()> {
    let fine = value.is_finite() && (value > 0.0 || (zero_ok && value == 0.0));
    if fine {
        Ok(())
    } else {
        let want = if zero_ok {
            "finite and not negative"
        } else {
            "finite and positive"
        };
        Err(unsuitable(
            shape,
            format!("{name} must be {want} (got {value})"),
        ))
    }
}

/// `Ok` if `count` lies in `min..=`[`MAX_SEGMENTS`](super::MAX_SEGMENTS).
fn check_count(shape: &'static str, name: &str, count: usize, min: usize) -> Result<()> {
    let max = super::MAX_SEGMENTS;
    if (min..=max).contains(&count) {
        Ok(())
    } else {
        Err(unsuitable(
            shape,
            format!("{name} must be in {min}..={max} (got {count})"),
        ))
    }
}
