//! Discrete curvatures at the vertices: mean, Gaussian and principal.
//!
//! - **Mean curvature** `H`: half the length of the cotangent Laplacian of
//!   the positions over the vertex's mixed Voronoi area
//!   ([`laplacian`](super::laplacian)), `H = |Σ_j w_ij (x_j − x_i)| / (2 A_i)`
//!   with `w_ij = ½ (cot α + cot β)` (Meyer, Desbrun, Schröder, Barr 2003).
//!   It is *signed*: positive where the surface bends away from its
//!   (angle-weighted) vertex normal, as on a sphere with outward normals,
//!   negative in a saddle-free dent.
//! - **Gaussian curvature** `K`: the angle defect over the same area,
//!   `K = (2π − Σ θ) / A_i`. Summed with the areas it satisfies the
//!   discrete Gauss-Bonnet theorem exactly (up to rounding) on closed
//!   triangle meshes: `Σ K_i A_i = 2π χ`. Polygons use the angle between
//!   their two edges at each corner.
//! - **Principal curvatures** `κ_min ≤ κ_max` from `H` and `K`:
//!   `H ∓ √max(0, H² − K)` (no curvature tensor is fitted, so no principal
//!   directions; pmp-library's default `curvature` does the same).
//!
//! **Boundary vertices.** The one-ring of a boundary vertex is cut open, so
//! its Laplacian measures the boundary curve's bending as much as the
//! surface's. [`BoundaryCurvature::FromInterior`] (the default, as
//! pmp-library) gives each boundary vertex the average of its interior
//! neighbours' values (zero when it has none);
//! [`BoundaryCurvature::OneSided`] keeps the one-sided values, with the
//! defect `π − Σ θ` for `K` (the discrete geodesic curvature of the
//! boundary), so that `Σ K_i A_i = 2π χ` holds on meshes with boundary too.
//!
//! **Degenerate input.** Faces without area add no weight and no area (see
//! [`laplacian`](super::laplacian)); a vertex with zero area gets zero
//! curvatures. Every value is finite.
//!
//! **Results** as plain `Vec`s by vertex slot ([`curvature`]) or vertex
//! columns ([`add_curvature`]; `f64`, [`Interpolate`] rule, so they follow
//! later edits approximately: recompute after large edits).
//!
//! **Cost.** One pass over the faces (two `atan2` and one square root per
//! triangle), one over the vertices.
//!
//! ```
//! use meshloom::algo::curvature::{curvature, CurvatureOptions};
//! let sphere = meshloom::shapes::icosphere(4); // unit radius
//! let c = curvature(&sphere, &CurvatureOptions::default())?;
//! for v in sphere.vertices() {
//!     assert!((c.mean[v.index()] - 1.0).abs() < 0.02);
//!     assert!((c.gaussian[v.index()] - 1.0).abs() < 0.05);
//! }
//! // Gauss-Bonnet: the area-weighted Gaussian curvature is 2πχ = 4π.
//! let total: f64 = sphere.vertices().map(|v| c.gaussian[v.index()] * c.area[v.index()]).sum();
//! assert!((total - 4.0 * std::f64::consts::PI).abs() < 1e-9);
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::f64::consts::PI;

use super::laplacian::{as_triangle, live_faces, polygon, positions, triangle};
use crate::attr::{Interpolate, VertexAttr};
use crate::error::{Error, Result};
use crate::keys::VertexKey;
use crate::layout::Vid;
use crate::mesh::Mesh;
use crate::vec3::{add, add_scaled, angle, cross, dot, norm, sub, V3};

/// The name of the vertex column of mean curvature.
pub const MEAN_CURVATURE: &str = "mean_curvature";
/// The name of the vertex column of Gaussian curvature.
pub const GAUSSIAN_CURVATURE: &str = "gaussian_curvature";
/// The name of the vertex column of the smaller principal curvature.
pub const MIN_CURVATURE: &str = "min_curvature";
/// The name of the vertex column of the larger principal curvature.
pub const MAX_CURVATURE: &str = "max_curvature";

/// What boundary vertices get.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum BoundaryCurvature {
    /// The average of the interior neighbours' values (default).
    #[default]
    FromInterior,
    /// The one-sided values; `K` from the defect `π − Σ θ`.
    OneSided,
}

crate::choice::choices!(BoundaryCurvature {
    FromInterior = "from-interior",
    OneSided = "one-sided",
});

/// Options of [`curvature`] and [`add_curvature`].
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct CurvatureOptions {
    /// What boundary vertices get (default: their interior neighbours'
    /// average).
    pub boundary: BoundaryCurvature,
}

crate::choice::setters!(CurvatureOptions {
    boundary: BoundaryCurvature,
});

/// Curvatures by vertex slot (vacant slots hold zeros).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Curvatures {
    /// Signed mean curvature `H`.
    pub mean: Vec<f64>,
    /// Gaussian curvature `K`.
    pub gaussian: Vec<f64>,
    /// The smaller principal curvature `H − √max(0, H² − K)`.
    pub min: Vec<f64>,
    /// The larger principal curvature `H + √max(0, H² − K)`.
    pub max: Vec<f64>,
    /// The mixed Voronoi area each value is normalised by.
    pub area: Vec<f64>,
}

/// Mean, Gaussian and principal curvatures of every vertex (see the module
/// docs).
///
/// # Errors
/// [`Error::NoPositions`].
///
/// # Complexity
/// O(corners).
pub fn curvature(mesh: &Mesh, options: &CurvatureOptions) -> Result<Curvatures> {
    let p = positions(mesh)?;
    let Sums {
        lx,
        area,
        angles,
        normal,
    } = face_sums(mesh, p);
    let nv = area.len();
    let mut out = Curvatures {
        mean: vec![0.0; nv],
        gaussian: vec![0.0; nv],
        min: vec![0.0; nv],
        max: vec![0.0; nv],
        area,
    };
    let mut boundary: Vec<Vid> = Vec::new();
    for v in mesh.vids() {
        let i = v.index();
        let on_boundary = mesh.on_boundary(v);
        if on_boundary {
            boundary.push(v);
        }
        let a = out.area[i];
        if a.is_nan() || a <= 0.0 {
            continue;
        }
        let len = norm(lx[i]);
        let sign = if dot(lx[i], normal[i]) > 0.0 {
            -1.0
        } else {
            1.0
        };
        let h = sign * len / (2.0 * a);
        let full = if on_boundary { PI } else { 2.0 * PI };
        let k = (full - angles[i]) / a;
        set(&mut out, i, h, k);
    }
    if options.boundary == BoundaryCurvature::FromInterior {
        from_interior(mesh, &mut out, &boundary);
    }
    Ok(out)
}

/// What the faces give each vertex slot: the cotangent Laplacian `L x`, the
/// mixed area, the sum of corner angles and the angle-weighted normal.
struct Sums {
    lx: Vec<V3>,
    area: Vec<f64>,
    angles: Vec<f64>,
    normal: Vec<V3>,
}

/// One pass over the live faces: triangles by their closed forms, other
/// polygons by [`polygon`]'s cotangent pairs and Newell normal. Inlined
/// into [`curvature`]: as a call of its own it costs more instructions.
#[inline(always)]
fn face_sums(mesh: &Mesh, p: &[V3]) -> Sums {
    let nv = mesh.vertex_slots();
    // Per vertex slot: L x, area, angle sum, angle-weighted normal.
    let mut lx = vec![[0.0; 3]; nv];
    let mut area = vec![0.0; nv];
    let mut angles = vec![0.0; nv];
    let mut normal = vec![[0.0; 3]; nv];
    let (mut ps, mut vs) = (Vec::<V3>::new(), Vec::<Vid>::new());
    let (mut pairs, mut parea) = (Vec::new(), Vec::new());
    for (_, h0) in live_faces(mesh) {
        if let Some(hs) = as_triangle(mesh, h0) {
            let [a, b, c] = hs.map(|h| mesh.origin(h).index());
            let q = [p[a], p[b], p[c]];
            let (t, d, twice) = triangle(q);
            let [w0, w1, w2] = t.half_cot;
            // Edge ab has the weight of the corner opposite, c; and so on.
            let (ab, bc, ca) = (sub(q[1], q[0]), sub(q[2], q[1]), sub(q[0], q[2]));
            add_scaled(&mut lx[a], ab, w2);
            add_scaled(&mut lx[a], ca, -w1);
            add_scaled(&mut lx[b], bc, w0);
            add_scaled(&mut lx[b], ab, -w2);
            add_scaled(&mut lx[c], ca, w1);
            add_scaled(&mut lx[c], bc, -w0);
            for (k, &v) in [a, b, c].iter().enumerate() {
                area[v] += t.area[k];
            }
            // The angles sum to π: two atan2 give the third.
            let ta = twice.atan2(d[0]);
            let tb = twice.atan2(d[1]);
            let tc = (PI - ta - tb).max(0.0);
            angles[a] += ta;
            angles[b] += tb;
            angles[c] += tc;
            if twice > 0.0 && twice.is_finite() {
                let n = cross(ab, bc);
                let u = [n[0] / twice, n[1] / twice, n[2] / twice];
                add_scaled(&mut normal[a], u, ta);
                add_scaled(&mut normal[b], u, tb);
                add_scaled(&mut normal[c], u, tc);
            }
            continue;
        }
        vs.clear();
        vs.extend(mesh.face_halfedges_from(h0).map(|h| mesh.origin(h)));
        ps.clear();
        ps.extend(vs.iter().map(|v| p[v.index()]));
        polygon(&ps, &mut pairs, &mut parea);
        for &(k, m, w) in &pairs {
            let e = sub(ps[m], ps[k]);
            add_scaled(&mut lx[vs[k].index()], e, w);
            add_scaled(&mut lx[vs[m].index()], e, -w);
        }
        let mut newell = [0.0; 3];
        let n = ps.len();
        for k in 0..n {
            newell = add(newell, cross(ps[k], ps[(k + 1) % n]));
        }
        let len = norm(newell);
        for k in 0..n {
            let v = vs[k].index();
            area[v] += parea[k];
            let (u, w) = (sub(ps[(k + 1) % n], ps[k]), sub(ps[(k + n - 1) % n], ps[k]));
            let theta = angle(u, w);
            angles[v] += theta;
            if len > 0.0 && len.is_finite() {
                add_scaled(&mut normal[v], newell, theta / len);
            }
        }
    }
    Sums {
        lx,
        area,
        angles,
        normal,
    }
}

/// Gives each boundary vertex the average of its interior neighbours' values
/// (zeros when it has none).
fn from_interior(mesh: &Mesh, out: &mut Curvatures, boundary: &[Vid]) {
    for &v in boundary {
        let (mut h, mut k, mut lo, mut hi, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for w in mesh.outgoing(v).map(|h| mesh.dest(h)) {
            if !mesh.on_boundary(w) {
                let j = w.index();
                h += out.mean[j];
                k += out.gaussian[j];
                lo += out.min[j];
                hi += out.max[j];
                n += 1.0;
            }
        }
        let i = v.index();
        if n > 0.0 {
            out.mean[i] = h / n;
            out.gaussian[i] = k / n;
            out.min[i] = lo / n;
            out.max[i] = hi / n;
        } else {
            out.mean[i] = 0.0;
            out.gaussian[i] = 0.0;
            out.min[i] = 0.0;
            out.max[i] = 0.0;
        }
    }
}

#[inline]
fn set(out: &mut Curvatures, i: usize, h: f64, k: f64) {
    let s = (h * h - k).max(0.0).sqrt();
    out.mean[i] = h;
    out.gaussian[i] = k;
    out.min[i] = h - s;
    out.max[i] = h + s;
}

/// The vertex columns [`add_curvature`] writes.
#[derive(Clone, Debug)]
pub struct CurvatureColumns {
    /// [`MEAN_CURVATURE`].
    pub mean: VertexAttr<f64>,
    /// [`GAUSSIAN_CURVATURE`].
    pub gaussian: VertexAttr<f64>,
    /// [`MIN_CURVATURE`].
    pub min: VertexAttr<f64>,
    /// [`MAX_CURVATURE`].
    pub max: VertexAttr<f64>,
}

/// [`curvature`] as the `f64` vertex columns [`MEAN_CURVATURE`],
/// [`GAUSSIAN_CURVATURE`], [`MIN_CURVATURE`] and [`MAX_CURVATURE`], added
/// or overwritten.
///
/// # Errors
/// [`Error::NoPositions`]; [`Error::AttributeType`] if a vertex column of
/// one of those names holds another type. Nothing is written then.
///
/// ```
/// use meshloom::algo::curvature::{add_curvature, CurvatureOptions};
/// let mut mesh = meshloom::shapes::icosphere(3);
/// let cols = add_curvature(&mut mesh, &CurvatureOptions::default())?;
/// let v = mesh.vertices().next().unwrap();
/// let h = *mesh.attr(&cols.mean, v)?.unwrap();
/// assert!((h - 1.0).abs() < 0.05);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn add_curvature(mesh: &mut Mesh, options: &CurvatureOptions) -> Result<CurvatureColumns> {
    mesh.as_one_step("Add curvature", |mesh| add_curvature_run(mesh, options))
}

/// [`add_curvature`] itself, outside the journal's step.
fn add_curvature_run(mesh: &mut Mesh, options: &CurvatureOptions) -> Result<CurvatureColumns> {
    let c = curvature(mesh, options)?;
    // Check every name before adding any column.
    for name in [
        MEAN_CURVATURE,
        GAUSSIAN_CURVATURE,
        MIN_CURVATURE,
        MAX_CURVATURE,
    ] {
        match mesh.attr_handle::<VertexKey, f64, Interpolate>(name) {
            Ok(_) | Err(Error::AttributeMissing { .. }) => {}
            Err(e) => return Err(e),
        }
    }
    let keys: Vec<VertexKey> = mesh.vertices().collect();
    let mut write = |name: &str, values: &[f64]| -> Result<VertexAttr<f64>> {
        let col = f64_column(mesh, name)?;
        let mut view = mesh.attr_view_mut(&col)?;
        for &v in &keys {
            view.set(v, Some(values[v.index()]))?;
        }
        Ok(col)
    };
    Ok(CurvatureColumns {
        mean: write(MEAN_CURVATURE, &c.mean)?,
        gaussian: write(GAUSSIAN_CURVATURE, &c.gaussian)?,
        min: write(MIN_CURVATURE, &c.min)?,
        max: write(MAX_CURVATURE, &c.max)?,
    })
}

/// The `f64` vertex column `name`, found or added.
fn f64_column(mesh: &mut Mesh, name: &str) -> Result<VertexAttr<f64>> {
    match mesh.attr_handle::<VertexKey, f64, Interpolate>(name) {
        Ok(h) => Ok(h),
        Err(Error::AttributeMissing { .. }) => mesh.add_attr::<VertexKey, f64>(name),
        Err(e) => Err(e),
    }
}
