//! Geometry algorithms over a [`Mesh`](crate::Mesh): one algorithm per
//! file, as pmp-library's `algorithms/`.
//!
//! | module | what | results |
//! |---|---|---|
//! | [`constraints`] | what an algorithm keeps, in one vocabulary: boundary and seams free, slide or lock; feature edges; pinned vertices | [`Constraints`], [`Keep`] |
//! | [`decimate`](mod@decimate) | quadric error edge collapse to a count, ratio or error, with guards and kept lines (boundaries, UV seams, materials, features) | [`DecimateReport`] |
//! | [`progress`] | the progress-and-cancel callback every long algorithm takes | [`Progress`], [`Error::Cancelled`](crate::Error::Cancelled) |
//! | [`laplacian`] | the cotangent (or uniform) Laplacian and the mixed-Voronoi mass matrix, the building blocks below | [`laplacian::Laplacian`] (sparse, by vertex slot), `Vec` of areas |
//! | [`curvature`] | mean, Gaussian and principal curvatures (cotangent Laplacian, angle defect) | `Vec`s by slot, or vertex columns |
//! | [`smooth`] | explicit (uniform, cotangent), Taubin and implicit smoothing, the boundary locked, sliding or free and pinned vertices kept | the mesh's positions, [`smooth::SmoothReport`] |
//! | [`fill_hole`](mod@fill_hole) | Liepa's hole filling: the least-weight triangulation of each hole, refined to the rim's edge length and faired (k-harmonic) over the patch | the mesh, [`FillHoleReport`] |
//! | [`fair`] | the smoothest (k-harmonic, k = 1..3) surface over a region with its surroundings fixed | the mesh's positions, [`fair::FairReport`] |
//! | [`subdivision`] | [`subdivide`] by any [`Scheme`] on one driver; what the schemes share: options (levels, boundary, creases, per-column vertex/varying data), the report | the mesh, rebuilt wholesale; [`SubdivisionReport`] |
//! | [`loop_subdivision`] | Loop subdivision of triangle meshes, semi-sharp creases | the mesh, rebuilt wholesale |
//! | [`catmull_clark`](mod@catmull_clark) | Catmull-Clark subdivision of any polygons, semi-sharp creases | the mesh, rebuilt wholesale |
//! | [`sqrt3`] | Kobbelt's sqrt(3) subdivision | the mesh, rebuilt wholesale |
//! | [`midpoint`] | linear subdivision: triangles 1-to-4, other polygons to quads | the mesh, rebuilt wholesale |
//! | [`remesh`](mod@remesh) | isotropic remeshing (Botsch-Kobbelt): split, collapse, flip, tangential relaxation, projection onto the input through a BVH; uniform or curvature-adaptive length; boundaries and features kept; UVs resampled per seam side | the mesh, handed over wholesale; [`RemeshReport`] |
//! | [`normals`] | face normals; vertex normals weighted by angle, area or uniformly; corner (half-edge) normals split at creases and hard edges | plain `Vec`s indexed by slot, or attribute columns named [`normals::NORMAL`] |
//!
//! The hot loops (the Laplacian, curvature, smoothing, fairing and vertex
//! normals) read the arenas through the crate's typed slot ids (`Vid`,
//! `Hid`, `Fid` of `layout.rs`: no key checks, no generations); keys are
//! checked once at the public door (a mask column, a region's vertices).
//! Every algorithm states its cost. Analysis (`&Mesh`) never changes the mesh; the `add_*` functions
//! that write a column compute everything first and write only when
//! nothing can fail any more.
//!
//! With the `parallel` feature, the passes over large meshes run on rayon's
//! thread pool; the results are bit-identical to the serial ones only up to
//! the order of floating-point sums (see each function).

pub mod catmull_clark;
pub mod constraints;
pub mod curvature;
pub mod decimate;
pub mod fair;
pub mod fill_hole;
pub mod laplacian;
pub mod loop_subdivision;
pub mod midpoint;

pub mod normals;
pub mod progress;
pub mod remesh;
pub mod smooth;
mod sparse;
pub mod sqrt3;
pub mod subdivision;

pub use catmull_clark::catmull_clark;

/// The default `max_faces` of the algorithms whose output size follows
/// from their options (the subdivisions, remeshing): ten million faces
/// (about 2 GB of mesh at ~110 bytes per vertex, plus the input and the
/// columns). A request estimated past it is refused before any work with
/// [`Error::TooLarge`](crate::Error::TooLarge).
pub const DEFAULT_MAX_FACES: usize = 10_000_000;

/// Refuse a mesh with a face that is not a triangle, naming the first:
/// `doing` ("decimation", "remeshing") says what needs the triangles.
pub(crate) fn check_triangles(
    mesh: &crate::Mesh,
    algorithm: &'static str,
    doing: &str,
) -> crate::Result<()> {
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        let h = mesh.face_halfedge(f);
        if mesh.next(mesh.next(mesh.next(h))) != h {
            return Err(crate::Error::Unsuitable {
                algorithm,
                key: Some(mesh.fkey(f).into()),
                reason: format!(
                    "face {} has {} sides; {doing} needs triangles (triangulate first)",
                    mesh.fkey(f),
                    mesh.face_degree(f)
                ),
            });
        }
    }
    Ok(())
}

/// A rebuilt mesh's positions are all finite (a level's sums of
/// coordinates near the largest `f64` overflow), else the first vertex
/// that is not.
pub(crate) fn check_finite(mesh: &crate::Mesh, algorithm: &'static str) -> crate::Result<()> {
    let Some(pos) = mesh.position_slots() else {
        return Ok(());
    };
    match mesh
        .vertices()
        .find(|v| !pos[v.index()].iter().all(|c| c.is_finite()))
    {
        Some(v) => Err(crate::Error::NonFiniteResult {
            algorithm,
            key: v.into(),
            position: pos[v.index()],
        }),
        None => Ok(()),
    }
}

pub use constraints::{Constraints, Keep};
pub use decimate::{decimate, DecimateOptions, DecimateReport};
pub use fill_hole::{fill_hole, fill_holes, FillHoleOptions, FillHoleReport};
pub use loop_subdivision::loop_subdivide;
pub use midpoint::{midpoint_subdivide, MidpointFaces, MidpointOptions};
pub use normals::{
    add_corner_normals, add_face_normals, add_vertex_normals, corner_normals, face_normals,
    vertex_normals, CornerNormalOptions, NormalWeight, VertexNormalOptions, NORMAL,
};
pub use progress::{Flow, Progress, ProgressInfo};
pub use remesh::{remesh, RemeshOptions, RemeshReport};
pub use sqrt3::sqrt3_subdivide;
pub use subdivision::{
    subdivide, Boundary, Counts, LevelReport, Scheme, SubdivisionOptions, SubdivisionReport,
    VertexData, VertexInterpolation,
};
