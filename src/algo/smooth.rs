//! Smoothing: explicit Laplacian (uniform or cotangent weights), Taubin's
//! λ|μ filter, and implicit (backward Euler) cotangent smoothing.
//!
//! | [`SmoothMethod`] | one iteration | step |
//! |---|---|---|
//! | `Uniform` | `x_i += λ (mean of the neighbours − x_i)` | `λ` in (0, 1], default 0.5 |
//! | `Cotan` | `x_i += λ (Σ w_ij x_j / Σ w_ij − x_i)`, cotangent weights clamped at zero, recomputed every iteration | as above |
//! | `Taubin` | a uniform step with `λ`, then one with `μ < −λ` (Taubin 1995: no shrinkage) | `λ`; `μ` from [`SmoothOptions::taubin_mu`] or the pass band `1/λ + 1/μ = 0.1` |
//! | `Implicit` | solve `(M − t L) x' = M x` (Desbrun, Meyer, Schröder, Barr 1999) | the time step `t` (squared length units), default 0.001 as pmp-library |
//!
//! `L` is the cotangent Laplacian with negative weights clamped to zero and
//! `M` the mixed-Voronoi mass matrix ([`laplacian`](super::laplacian)), both
//! recomputed each implicit step; the system is solved by a sparse Cholesky
//! factorisation (faer). The explicit updates are Jacobi steps (every vertex
//! from the previous positions).
//!
//! **Which vertices move.** Boundary vertices stay where they are unless
//! [`SmoothOptions::fix_boundary`] is `false`; with a
//! [`SmoothOptions::mask`] (a `bool` vertex column) only vertices whose value
//! is `true` move. Every other vertex keeps its position bit for bit (the
//! smoothed positions are written back only for the moving ones), and a
//! fixed vertex still pulls on its moving neighbours. Vertices whose faces
//! all lack area have no cotangent weight and stay too.
//! [`SmoothOptions::rescale`] (implicit only) then restores the surface area
//! and area-weighted centroid of the input by a similarity transform of the
//! whole mesh, as pmp-library does; it moves every vertex, so it is refused
//! together with a mask.
//!
//! **Attributes.** Only the position column changes: no element is split or
//! merged, so no rule runs and every other column keeps its values. Columns
//! derived from the geometry go stale: normals ([`normals`](super::normals)),
//! curvatures ([`curvature`](super::curvature)). The report lists the
//! columns of those names found on the mesh ([`SmoothReport::stale`]);
//! recompute them with the `add_*` functions.
//!
//! **All or nothing.** Everything is computed on a copy of the positions;
//! the mesh changes only at the end, when every new coordinate is known to be
//! finite. A cancelled run ([`Progress`]) or a failed one (an unsuitable
//! option, a factorisation that fails) leaves the mesh as it was.
//!
//! **Cost.** Explicit: O(corners) per iteration. Implicit: the Cholesky
//! factorisation of a matrix with one row per moving vertex (nearly linear
//! in practice on surface meshes, with the fill-reducing ordering).
//!
//! ```
//! use meshloom::algo::smooth::{smooth, SmoothMethod, SmoothOptions};
//! use meshloom::algo::Progress;
//! let mut sphere = meshloom::shapes::icosphere(3);
//! let opts = SmoothOptions { method: SmoothMethod::Taubin, iterations: 5, ..Default::default() };
//! let report = smooth(&mut sphere, &opts, Progress::none())?;
//! assert_eq!(report.moved, sphere.vertex_count());
//! sphere.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

use super::laplacian::{
    add_scaled, as_triangle, cross, laplacian_at, live_faces, mass_matrix_at, norm, positions, sub,
    Laplacian, LaplacianOptions, V3,
};
use super::progress::Progress;
use super::sparse::{solve_spd, LowerCsc};
use crate::attr::VertexAttr;
use crate::error::{Error, Result};
use crate::keys::ElementKind;
use crate::mesh::Mesh;

const ALGORITHM: &str = "smooth";

/// How [`smooth`] moves vertices (see the module docs).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum SmoothMethod {
    /// Explicit steps toward the neighbours' mean (default).
    #[default]
    Uniform,
    /// Explicit steps toward the cotangent-weighted mean.
    Cotan,
    /// Taubin's λ|μ: a shrinking and an inflating uniform step per
    /// iteration, which keeps the volume.
    Taubin,
    /// Backward Euler steps of the cotangent mean-curvature flow.
    Implicit,
}

/// Options of [`smooth`].
#[derive(Clone, Debug, PartialEq)]
pub struct SmoothOptions {
    /// The method (default [`SmoothMethod::Uniform`]).
    pub method: SmoothMethod,
    /// Iterations (Taubin: λ|μ pairs; implicit: time steps). Default 10.
    pub iterations: u32,
    /// Explicit and Taubin: `λ` in (0, 1] (default 0.5). Implicit: the time
    /// step, `> 0`; `None` gives 0.001 (pmp-library's default).
    pub step: Option<f64>,
    /// Taubin's `μ` (must be below `−λ`); `None` takes the pass band
    /// `k = 0.1`: `μ = 1 / (k − 1/λ)` (−0.526 for λ = 0.5).
    pub taubin_mu: Option<f64>,
    /// Keep boundary vertices where they are (default `true`).
    pub fix_boundary: bool,
    /// Move only the vertices where this `bool` vertex column is `true`.
    pub mask: Option<VertexAttr<bool>>,
    /// Implicit only: restore the input's surface area and centroid
    /// afterwards (default `false`; refused with a mask).
    pub rescale: bool,
}

impl Default for SmoothOptions {
    fn default() -> Self {
        SmoothOptions {
            method: SmoothMethod::Uniform,
            iterations: 10,
            step: None,
            taubin_mu: None,
            fix_boundary: true,
            mask: None,
            rescale: false,
        }
    }
}

impl SmoothOptions {
    /// The defaults with another method.
    pub fn with_method(method: SmoothMethod) -> SmoothOptions {
        SmoothOptions {
            method,
            iterations: if method == SmoothMethod::Implicit {
                1
            } else {
                10
            },
            ..SmoothOptions::default()
        }
    }
}

/// What [`smooth`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SmoothReport {
    /// Vertices that were free to move.
    pub moved: usize,
    /// Vertices kept in place (boundary, outside the mask, no area).
    pub fixed: usize,
    /// Iterations run.
    pub iterations: u32,
    /// The largest distance a vertex moved.
    pub max_displacement: f64,
    /// Columns derived from positions that are now stale (`"vertex
    /// normal"`, `"halfedge normal"`, `"face normal"`, `"vertex
    /// mean_curvature"`, ...).
    pub stale: Vec<String>,
}

fn unsuitable(reason: impl Into<String>) -> Error {
    Error::Unsuitable {
        algorithm: ALGORITHM,
        key: None,
        reason: reason.into(),
    }
}

/// Smooth the positions of `mesh` (see the module docs).
///
/// # Errors
/// [`Error::Unsuitable`] for implicit smoothing without the `sparse`
/// feature (faer); [`Error::NoPositions`]; [`Error::AttributeHandle`] if the mask column was
/// removed; [`Error::Unsuitable`] for a step outside its range, a Taubin `μ`
/// not below `−λ`, a mask that selects no vertex that may move, `rescale`
/// with a mask or with an explicit method, a failed factorisation, or a
/// result that is not finite; [`Error::Cancelled`]. The mesh is unchanged
/// after any error.
///
/// # Complexity
/// Explicit: O(iterations · corners). Implicit: one sparse Cholesky
/// factorisation per iteration.
pub fn smooth(
    mesh: &mut Mesh,
    options: &SmoothOptions,
    progress: Progress<'_>,
) -> Result<SmoothReport> {
    mesh.as_one_step("Smooth", |mesh| smooth_run(mesh, options, progress))
}

/// [`smooth`] itself, outside the journal's step.
fn smooth_run(
    mesh: &mut Mesh,
    options: &SmoothOptions,
    mut progress: Progress<'_>,
) -> Result<SmoothReport> {
    let explicit = options.method != SmoothMethod::Implicit;
    if !explicit && !super::sparse::AVAILABLE {
        return Err(unsuitable(super::sparse::UNAVAILABLE));
    }
    let p0 = positions(mesh)?;
    let step = options.step.unwrap_or(if explicit { 0.5 } else { 0.001 });
    if explicit && !(step > 0.0 && step <= 1.0) {
        return Err(unsuitable(format!("step {step} is not in (0, 1]")));
    }
    if !(explicit || step > 0.0 && step.is_finite()) {
        return Err(unsuitable(format!(
            "time step {step} is not positive and finite"
        )));
    }
    let mu = match options.taubin_mu {
        Some(mu) => mu,
        None => 1.0 / (0.1 - 1.0 / step),
    };
    if options.method == SmoothMethod::Taubin && !(mu < -step && mu.is_finite()) {
        return Err(unsuitable(format!(
            "Taubin mu {mu} is not below -lambda = {}",
            -step
        )));
    }
    if options.rescale && (explicit || options.mask.is_some()) {
        return Err(unsuitable(
            "rescale applies to implicit smoothing without a mask (it moves every vertex)",
        ));
    }
    let free = free_vertices(mesh, options)?;
    let moved = free.iter().filter(|&&f| f).count();
    if options.mask.is_some() && moved == 0 {
        return Err(unsuitable("the mask selects no vertex that may move"));
    }

    let mut x: Vec<V3> = p0.to_vec();
    let n = options.iterations;
    match options.method {
        SmoothMethod::Uniform | SmoothMethod::Taubin => {
            let rings = FreeRings::of(mesh, &free);
            let mut next = x.clone();
            for it in 0..n {
                progress.report(ALGORITHM, "iterations", u64::from(it), u64::from(n))?;
                rings.uniform_step(&x, &mut next, step);
                std::mem::swap(&mut x, &mut next);
                if options.method == SmoothMethod::Taubin {
                    rings.uniform_step(&x, &mut next, mu);
                    std::mem::swap(&mut x, &mut next);
                }
            }
        }
        SmoothMethod::Cotan => {
            let mut next = x.clone();
            for it in 0..n {
                progress.report(ALGORITHM, "iterations", u64::from(it), u64::from(n))?;
                let l = laplacian_at(mesh, &x, &LaplacianOptions::default());
                explicit_step(&l, &free, &x, &mut next, step);
                std::mem::swap(&mut x, &mut next);
            }
        }
        SmoothMethod::Implicit => {
            let (area0, centre0) = area_and_centroid(mesh, &x);
            for it in 0..n {
                progress.report(ALGORITHM, "implicit steps", u64::from(it), u64::from(n))?;
                implicit_step(mesh, &free, &mut x, step)?;
            }
            if options.rescale {
                let (area1, centre1) = area_and_centroid(mesh, &x);
                if area1 > 0.0 && area0 > 0.0 {
                    let s = (area0 / area1).sqrt();
                    for v in mesh.vids() {
                        let q = &mut x[v.index()];
                        for k in 0..3 {
                            q[k] = centre0[k] + s * (q[k] - centre1[k]);
                        }
                    }
                }
            }
        }
    }
    progress.report(ALGORITHM, "iterations", u64::from(n), u64::from(n))?;

    // Commit: only free vertices (all of them after a rescale), and only if
    // every coordinate is finite.
    let write_all = options.rescale;
    let mut max_d: f64 = 0.0;
    for v in mesh.vids() {
        let i = v.index();
        if write_all || free[i] {
            if !x[i].iter().all(|c| c.is_finite()) {
                return Err(Error::Unsuitable {
                    algorithm: ALGORITHM,
                    key: Some(mesh.vkey(v).into()),
                    reason: "the smoothed position is not finite".into(),
                });
            }
            max_d = max_d.max(norm(sub(x[i], p0[i])));
        }
    }
    let stale = stale_columns(mesh);
    let out = mesh.position_slots_mut().ok_or(Error::NoPositions)?;
    for (i, (o, q)) in out.iter_mut().zip(&x).enumerate() {
        if write_all || free[i] {
            *o = *q;
        }
    }
    debug_assert!(mesh.validate().is_ok());
    Ok(SmoothReport {
        moved,
        fixed: mesh.vertex_count() - moved,
        iterations: n,
        max_displacement: max_d,
        stale,
    })
}

/// Whether each vertex slot may move.
pub(crate) fn free_vertices(mesh: &Mesh, options: &SmoothOptions) -> Result<Vec<bool>> {
    let mut free = vec![false; mesh.v_halfedge.len()];
    for v in mesh.vids() {
        free[v.index()] = !(options.fix_boundary && mesh.on_boundary(v));
    }
    if let Some(mask) = &options.mask {
        let view = mesh.attr_view(mask)?;
        for v in mesh.vertices() {
            if view.get(v) != Some(&true) {
                free[v.index()] = false;
            }
        }
    }
    Ok(free)
}

/// The one-rings of the vertices that move, flattened once per call (CSR):
/// the uniform steps then read three flat arrays and the positions, with
/// no half-edge navigation and no row for a fixed vertex.
struct FreeRings {
    /// The moving vertex slots with at least one neighbour, in slot order.
    rows: Vec<u32>,
    /// Row `k`'s neighbours are `cols[offsets[k]..offsets[k + 1]]`.
    offsets: Vec<u32>,
    /// Neighbour vertex slots (one per outgoing half-edge).
    cols: Vec<u32>,
    /// `1 / degree` per row.
    inv_degree: Vec<f64>,
}

impl FreeRings {
    /// The rings of the vertices `free` marks, by one turn around each.
    fn of(mesh: &Mesh, free: &[bool]) -> FreeRings {
        let moving = free.iter().filter(|&&f| f).count();
        let mut rings = FreeRings {
            rows: Vec::with_capacity(moving),
            offsets: Vec::with_capacity(moving + 1),
            cols: Vec::with_capacity(mesh.he.len().min(8 * moving)),
            inv_degree: Vec::with_capacity(moving),
        };
        rings.offsets.push(0);
        for v in mesh.vids() {
            if !free[v.index()] {
                continue;
            }
            let start = rings.cols.len();
            rings
                .cols
                .extend(mesh.outgoing(v).map(|h| mesh.he[h.twin()].origin.raw()));
            let degree = rings.cols.len() - start;
            if degree == 0 {
                continue;
            }
            rings.rows.push(v.raw());
            rings.offsets.push(rings.cols.len() as u32);
            rings.inv_degree.push(1.0 / degree as f64);
        }
        rings
    }

    /// One Jacobi step toward the neighbours' mean: `next_i = (1 − s) x_i +
    /// s · mean_j x_j` for every row (with `s = 1`, exactly the mean); the
    /// other slots of `next` are left as they are.
    fn uniform_step(&self, x: &[V3], next: &mut [V3], s: f64) {
        let keep = 1.0 - s;
        let spans = self.offsets.windows(2);
        for ((&i, span), &inv) in self.rows.iter().zip(spans).zip(&self.inv_degree) {
            let mut acc = [0.0f64; 3];
            for &c in &self.cols[span[0] as usize..span[1] as usize] {
                let q = x[c as usize];
                acc[0] += q[0];
                acc[1] += q[1];
                acc[2] += q[2];
            }
            let q = x[i as usize];
            let t = s * inv;
            next[i as usize] = [
                keep * q[0] + t * acc[0],
                keep * q[1] + t * acc[1],
                keep * q[2] + t * acc[2],
            ];
        }
    }
}

/// One Jacobi step with normalised weights: `next_i = x_i + s (Σ w x_j /
/// Σ w − x_i)` for free vertices with positive weight.
fn explicit_step(l: &Laplacian, free: &[bool], x: &[V3], next: &mut [V3], s: f64) {
    for i in 0..l.len() {
        if !free[i] {
            continue;
        }
        let (cols, ws) = l.row_raw(i);
        let mut acc = [0.0; 3];
        let mut total = 0.0;
        for (&c, &w) in cols.iter().zip(ws) {
            add_scaled(&mut acc, x[c as usize], w);
            total += w;
        }
        if total > 0.0 {
            let q = x[i];
            let t = s / total;
            next[i] = [
                q[0] + t * acc[0] - s * q[0],
                q[1] + t * acc[1] - s * q[1],
                q[2] + t * acc[2] - s * q[2],
            ];
        } else {
            next[i] = x[i];
        }
    }
}

/// One backward Euler step: `(M − t L) x' = M x` over the free vertices,
/// the others as boundary conditions.
fn implicit_step(mesh: &Mesh, free: &[bool], x: &mut [V3], t: f64) -> Result<()> {
    let l = laplacian_at(mesh, x, &LaplacianOptions::default());
    let m = mass_matrix_at(mesh, x);
    // Unknowns: free vertices with area, numbered in slot order.
    let nv = free.len();
    let mut local = vec![u32::MAX; nv];
    let mut slots: Vec<u32> = Vec::new();
    for i in 0..nv {
        if free[i] && m[i] > 0.0 {
            local[i] = slots.len() as u32;
            slots.push(i as u32);
        }
    }
    let mut a = LowerCsc::with_capacity(slots.len(), slots.len() + l.off_diagonal_count() / 2);
    let mut b: Vec<V3> = Vec::with_capacity(slots.len());
    for &s in &slots {
        let i = s as usize;
        let (cols, ws) = l.row_raw(i);
        a.push(local[i] as usize, m[i] - t * l.diagonal(i));
        let mut rhs = [m[i] * x[i][0], m[i] * x[i][1], m[i] * x[i][2]];
        for (&c, &w) in cols.iter().zip(ws) {
            let j = local[c as usize];
            if j == u32::MAX {
                add_scaled(&mut rhs, x[c as usize], t * w);
            } else if j > local[i] && w != 0.0 {
                a.push(j as usize, -t * w);
            }
        }
        a.end_column();
        b.push(rhs);
    }
    solve_spd(&a, &mut b).map_err(|e| unsuitable(e.to_string()))?;
    for (&s, q) in slots.iter().zip(&b) {
        x[s as usize] = *q;
    }
    Ok(())
}

/// Surface area and area-weighted centroid at positions `x`.
pub(crate) fn area_and_centroid(mesh: &Mesh, x: &[V3]) -> (f64, V3) {
    let mut area = 0.0;
    let mut c = [0.0; 3];
    let mut ring: Vec<V3> = Vec::new();
    for (_, h0) in live_faces(mesh) {
        ring.clear();
        if let Some(hs) = as_triangle(mesh, h0) {
            ring.extend(hs.map(|h| x[mesh.he[h].origin.index()]));
        } else {
            ring.extend(
                mesh.face_loop_from(h0)
                    .map(|h| x[mesh.he[h].origin.index()]),
            );
        }
        // Fan from the first corner.
        for k in 1..ring.len() - 1 {
            let a = 0.5 * norm(cross(sub(ring[k], ring[0]), sub(ring[k + 1], ring[0])));
            area += a;
            for d in 0..3 {
                c[d] += a * (ring[0][d] + ring[k][d] + ring[k + 1][d]) / 3.0;
            }
        }
    }
    if area > 0.0 {
        c = c.map(|v| v / area);
    }
    (area, c)
}

/// Columns of the names the geometry algorithms write.
fn stale_columns(mesh: &Mesh) -> Vec<String> {
    let derived = [
        super::normals::NORMAL,
        super::curvature::MEAN_CURVATURE,
        super::curvature::GAUSSIAN_CURVATURE,
        super::curvature::MIN_CURVATURE,
        super::curvature::MAX_CURVATURE,
    ];
    let mut out = Vec::new();
    for (kind, label) in [
        (ElementKind::Vertex, "vertex"),
        (ElementKind::Halfedge, "halfedge"),
        (ElementKind::Face, "face"),
    ] {
        for info in mesh.attr_info(kind) {
            if derived.contains(&info.name.as_str()) {
                out.push(format!("{label} {}", info.name));
            }
        }
    }
    out
}
