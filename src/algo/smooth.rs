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
//! **Which vertices move** (the shared vocabulary of
//! [`constraints`](super::constraints)). With [`SmoothOptions::boundary`]
//! [`Keep::Lock`] (the default) boundary vertices stay where they are; with
//! [`Keep::Slide`] they move but stay on the input's boundary: after every
//! step each is put back on the closest point of its own piece of the
//! input's boundary polyline (between two corners, or around its loop), and
//! the corners (turns of more than the feature angle, 45° without one)
//! stay; with [`Keep::Free`] they move as any other vertex. Seams
//! ([`SmoothOptions::seams`], default free) and feature edges slide or
//! lock the same way. Pinned vertices ([`SmoothOptions::pinned`]) never
//! move. Every vertex held keeps its position bit for bit (the smoothed
//! positions are written back only for the moving ones), and still pulls
//! on its moving neighbours. Vertices whose faces all lack area have no
//! cotangent weight and stay too. [`SmoothOptions::rescale`] (implicit
//! only) then restores the surface area and area-weighted centroid of the
//! input by a similarity transform of the whole mesh, as pmp-library does:
//! it moves every vertex, the boundary too, so it is refused with pinned
//! vertices.
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
//! let opts = SmoothOptions::default().method(SmoothMethod::Taubin).iterations(5);
//! let report = smooth(&mut sphere, &opts, Progress::none())?;
//! assert_eq!(report.moved, sphere.vertex_count());
//! sphere.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

use super::constraints::{Classifier, Constraints, Keep, LineSources, Polylines, FIXED, LINE};
use super::laplacian::{
    as_triangle, laplacian_at, live_faces, mass_matrix_at, positions, Laplacian, LaplacianOptions,
};
use super::progress::Progress;
use super::sparse::{solve_spd, LowerCsc};
use crate::attr::{EdgeAttr, VertexAttr};
use crate::circulate::VertexNeighbors;
use crate::error::{Error, Result};
use crate::keys::ElementKind;
use crate::layout::Vid;
use crate::mesh::Mesh;
use crate::vec3::{add_scaled, cross, dot, norm, sub, V3};

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

crate::choice::choices!(SmoothMethod {
    Uniform = "uniform",
    Cotan = "cotan",
    Taubin = "taubin",
    Implicit = "implicit",
});

/// Options of [`smooth`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
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
    /// Boundary vertices (default [`Keep::Lock`]: they stay; `Slide`: they
    /// stay on the input's boundary; `Free`: they move as any other). See
    /// [`Constraints`].
    pub boundary: Keep,
    /// Seam vertices: where a corner column's values differ across an edge
    /// (default [`Keep::Free`]: no constraint).
    pub seams: Keep,
    /// Edges whose faces meet at more than this dihedral angle (radians)
    /// are feature edges, whose vertices slide along them; also the turn
    /// that makes a line's vertex a corner (45° without it). Default: none.
    pub feature_angle: Option<f64>,
    /// An edge column: edges whose value is `true` are feature edges.
    pub features: Option<EdgeAttr<bool>>,
    /// A vertex column: vertices whose value is `true` are pinned (never
    /// move). To move only a region, pin its complement.
    pub pinned: Option<VertexAttr<bool>>,
    /// Implicit only: restore the input's surface area and centroid
    /// afterwards, moving every vertex (default `false`; refused with
    /// pinned vertices).
    pub rescale: bool,
}

crate::algo::constraints::constrained!(SmoothOptions);

crate::choice::setters!(SmoothOptions {
    method: SmoothMethod,
    iterations: u32,
    step: Option<f64>,
    taubin_mu: Option<f64>,
    boundary: Keep,
    seams: Keep,
    feature_angle: Option<f64>,
    features: Option<EdgeAttr<bool>>,
    pinned: Option<VertexAttr<bool>>,
    rescale: bool,
});

impl Default for SmoothOptions {
    fn default() -> Self {
        SmoothOptions {
            method: SmoothMethod::Uniform,
            iterations: 10,
            step: None,
            taubin_mu: None,
            boundary: Keep::Lock,
            seams: Keep::Free,
            feature_angle: None,
            features: None,
            pinned: None,
            rescale: false,
        }
    }
}

impl SmoothOptions {
    /// The defaults with another method, and that method's default
    /// `iterations` (1 for implicit, else 10); the setter
    /// [`method`](Self::method) changes the method alone.
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
#[non_exhaustive]
pub struct SmoothReport {
    /// Vertices that were free to move.
    pub moved: usize,
    /// Vertices kept in place (pinned, on a locked line, line corners,
    /// no area).
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
/// feature (faer); [`Error::NoPositions`]; [`Error::AttributeHandle`] if
/// the pinned or feature column was removed; [`Error::Unsuitable`] for a
/// step outside its range, a Taubin `μ` not below `−λ`, a feature angle
/// that is not finite, pinned vertices that leave no vertex that may move,
/// `rescale` with pinned vertices or with an explicit method, a failed
/// factorisation, or a result that is not finite; [`Error::Cancelled`].
/// The mesh is unchanged after any error.
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
    let (step, mu) = steps(options)?;
    let mut held = Held::of(mesh, p0, options)?;
    let n = options.iterations;
    // `moves`: the slots to write back; `None` for the uniform steps, whose
    // buffer holds every other slot's position bit for bit, so it is
    // copied whole.
    let (x, moved, max_d, moves) = match options.method {
        SmoothMethod::Uniform | SmoothMethod::Taubin => {
            let rings = FreeRings::of(mesh, &held.kinds);
            check_selects(options, rings.moving)?;
            let steps: &[f64] = if options.method == SmoothMethod::Taubin {
                &[step, mu]
            } else {
                &[step]
            };
            let x = rings.run(p0, steps, n, &mut held, &mut progress)?;
            let moving = rings.degree.iter().map(|&d| d > 0);
            let max_d = checked_displacement(mesh, p0, &x, moving)?;
            (x, rings.moving, max_d, None)
        }
        SmoothMethod::Cotan => {
            let free = held.free();
            let moved = check_selects(options, free.iter().filter(|&&f| f).count())?;
            let x = cotan_run(mesh, p0, &free, n, step, &mut held, &mut progress)?;
            let max_d = checked_displacement(mesh, p0, &x, free.iter().copied())?;
            (x, moved, max_d, Some(free))
        }
        SmoothMethod::Implicit => {
            let free = held.free();
            let moved = check_selects(options, free.iter().filter(|&&f| f).count())?;
            let x = implicit_run(mesh, p0, &free, n, step, &mut held, &mut progress)?;
            let (x, moves) = if options.rescale {
                // A rescale moves every vertex.
                let live = (0..x.len()).map(|i| mesh.vertex_live(i)).collect();
                (rescaled(mesh, p0, x), live)
            } else {
                (x, free)
            };
            let max_d = checked_displacement(mesh, p0, &x, moves.iter().copied())?;
            (x, moved, max_d, Some(moves))
        }
    };
    progress.report(ALGORITHM, "iterations", u64::from(n), u64::from(n))?;
    let stale = stale_columns(mesh);
    let out = mesh.position_slots_mut().ok_or(Error::NoPositions)?;
    match moves {
        None => out.copy_from_slice(&x),
        Some(moves) => {
            for ((o, q), m) in out.iter_mut().zip(&x).zip(moves) {
                if m {
                    *o = *q;
                }
            }
        }
    }
    mesh.debug_validate();
    Ok(SmoothReport {
        moved,
        fixed: mesh.vertex_count() - moved,
        iterations: n,
        max_displacement: max_d,
        stale,
    })
}

/// The step (`λ` or the time step) and Taubin's `μ`, checked; and
/// `rescale` refused where it does not apply.
fn steps(options: &SmoothOptions) -> Result<(f64, f64)> {
    let explicit = options.method != SmoothMethod::Implicit;
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
    if options.rescale && (explicit || options.pinned.is_some()) {
        return Err(unsuitable(
            "rescale applies to implicit smoothing without pinned vertices (it moves every vertex)",
        ));
    }
    Ok((step, mu))
}

/// What holds the vertices: each one's kind (the shared classifier), and
/// the input's lines for those that slide.
struct Held {
    kinds: Vec<u8>,
    lines: Option<Polylines>,
}

impl Held {
    fn of(mesh: &Mesh, p0: &[V3], options: &SmoothOptions) -> Result<Held> {
        let constraints = options.constraints();
        constraints.check(ALGORITHM)?;
        let sources = LineSources::all_corner_columns(mesh, Keep::Slide, false);
        let c = Classifier::new(mesh, p0, &constraints, sources)?.classify();
        let kinds = c.kinds;
        let lines = kinds.contains(&LINE).then(|| {
            Polylines::new(
                mesh,
                p0,
                mesh.vids().filter(|v| kinds[v.index()] == LINE),
                |v| kinds[v.index()] == LINE,
                |e| c.lines.get(e),
            )
        });
        Ok(Held { kinds, lines })
    }

    /// Whether each vertex slot may move.
    fn free(&self) -> Vec<bool> {
        self.kinds.iter().map(|&k| k != FIXED).collect()
    }

    /// Put the sliding vertices of `x` back on their lines.
    fn slide(&mut self, x: &mut [V3]) {
        if let Some(lines) = &mut self.lines {
            lines.project_all(x);
        }
    }
}

/// `n` explicit cotangent steps from `p0` (weights from the current
/// positions each step).
fn cotan_run(
    mesh: &Mesh,
    p0: &[V3],
    free: &[bool],
    n: u32,
    step: f64,
    held: &mut Held,
    progress: &mut Progress<'_>,
) -> Result<Vec<V3>> {
    let mut x: Vec<V3> = p0.to_vec();
    let mut next = x.clone();
    for it in 0..n {
        progress.report(ALGORITHM, "iterations", u64::from(it), u64::from(n))?;
        let l = laplacian_at(mesh, &x, &LaplacianOptions::default());
        explicit_step(&l, free, &x, &mut next, step);
        held.slide(&mut next);
        std::mem::swap(&mut x, &mut next);
    }
    Ok(x)
}

/// `n` backward Euler steps of time `t` from `p0`.
fn implicit_run(
    mesh: &Mesh,
    p0: &[V3],
    free: &[bool],
    n: u32,
    t: f64,
    held: &mut Held,
    progress: &mut Progress<'_>,
) -> Result<Vec<V3>> {
    let mut x: Vec<V3> = p0.to_vec();
    for it in 0..n {
        progress.report(ALGORITHM, "implicit steps", u64::from(it), u64::from(n))?;
        implicit_step(mesh, free, &mut x, t)?;
        held.slide(&mut x);
    }
    Ok(x)
}

/// `x` moved by the similarity that gives it the surface area and the
/// area-weighted centroid of `p0` (pmp-library's rescale).
fn rescaled(mesh: &Mesh, p0: &[V3], mut x: Vec<V3>) -> Vec<V3> {
    let (area0, centre0) = area_and_centroid(mesh, p0);
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
    x
}

/// With pinned vertices, refuse a run that would move nothing; else pass
/// the count.
fn check_selects(options: &SmoothOptions, moving: usize) -> Result<usize> {
    if options.pinned.is_some() && moving == 0 {
        return Err(unsuitable(
            "no vertex may move: every one is pinned or held by a line",
        ));
    }
    Ok(moving)
}

/// The largest displacement of a moving vertex, or an error naming the
/// first moving vertex whose new position is not finite (the commit's
/// check: nothing is written before it passes).
fn checked_displacement(
    mesh: &Mesh,
    p0: &[V3],
    x: &[V3],
    moves: impl Iterator<Item = bool>,
) -> Result<f64> {
    let mut max_d2: f64 = 0.0;
    for (i, ((q, p), m)) in x.iter().zip(p0).zip(moves).enumerate() {
        if !m {
            continue;
        }
        if !q.iter().all(|c| c.is_finite()) {
            return Err(Error::Unsuitable {
                algorithm: ALGORITHM,
                key: Some(mesh.vkey(Vid::new(i as u32)).into()),
                reason: "the smoothed position is not finite".into(),
            });
        }
        let d = sub(*q, *p);
        max_d2 = max_d2.max(dot(d, d));
    }
    Ok(max_d2.sqrt())
}

/// A degree of [`MANY`] or more is kept in [`FreeRings::many`].
const MANY: u8 = u8::MAX;

/// The one-rings of the vertices that move, flattened once per call: the
/// uniform steps then read the degrees, the neighbour list and the
/// positions in slot order, with no half-edge navigation.
///
/// One byte per vertex slot says whether it moves and how many neighbours
/// it has, and the first step reads the mesh's positions, so nothing is
/// copied before it. Measured on the 2M-vertex grid (`smooth_10`, three
/// paired runs): 386-504 ms with a row list, row offsets and a stored
/// `1/degree` (16 more bytes per moving vertex) and two position copies
/// made up front; 289-324 ms this way. The difference is a separate pass
/// for the boundary test, the two copies, and the 32 MB of the dropped
/// arrays, touched for the first time inside the call (about 2.5 µs per
/// 4 KiB page on that machine).
struct FreeRings {
    /// Per vertex slot: 0 if it stays, else its degree ([`MANY`]: the
    /// degree is the next entry of `many`).
    degree: Vec<u8>,
    /// The degrees of [`MANY`] or more, in slot order.
    many: Vec<u32>,
    /// The moving vertices' neighbour slots, ring after ring in slot order.
    cols: Vec<u32>,
    /// How many vertices move.
    moving: usize,
}

impl FreeRings {
    /// The rings of the vertices that move: those whose kind is not
    /// fixed.
    fn of(mesh: &Mesh, kinds: &[u8]) -> FreeRings {
        let mut rings = FreeRings {
            degree: vec![0; mesh.vertex_slots()],
            many: Vec::new(),
            cols: Vec::with_capacity(mesh.halfedge_slots()),
            moving: 0,
        };
        for v in mesh.vids() {
            let i = v.index();
            if kinds[i] == FIXED {
                continue;
            }
            let start = rings.cols.len();
            rings
                .cols
                .extend(VertexNeighbors::new(mesh, v).map(Vid::raw));
            let degree = rings.cols.len() - start;
            rings.moving += usize::from(degree > 0);
            rings.degree[i] = match u8::try_from(degree) {
                Ok(d) if d < MANY => d,
                _ => {
                    rings.many.push(degree as u32);
                    MANY
                }
            };
        }
        rings
    }

    /// `iterations` rounds of uniform steps, one per entry of `steps` (its
    /// `s`), from `p0`: the positions after the last step, by slot. Two
    /// buffers take turns; the first step reads `p0` itself.
    fn run(
        &self,
        p0: &[V3],
        steps: &[f64],
        iterations: u32,
        held: &mut Held,
        progress: &mut Progress<'_>,
    ) -> Result<Vec<V3>> {
        let mut x: Vec<V3> = Vec::new();
        let mut next: Vec<V3> = Vec::new();
        for it in 0..iterations {
            progress.report(
                ALGORITHM,
                "iterations",
                u64::from(it),
                u64::from(iterations),
            )?;
            for &s in steps {
                // Zeroed memory comes from the system untouched: the step
                // writes every slot, so nothing is copied in first.
                if next.is_empty() {
                    next = vec![[0.0; 3]; p0.len()];
                }
                self.uniform_step(if x.is_empty() { p0 } else { &x }, &mut next, s);
                held.slide(&mut next);
                std::mem::swap(&mut x, &mut next);
            }
        }
        Ok(if x.is_empty() { p0.to_vec() } else { x })
    }

    /// One Jacobi step toward the neighbours' mean: `next_i = (1 − s) x_i +
    /// s · mean_j x_j` for every moving slot (with `s = 1`, exactly the
    /// mean); every other slot of `next` gets its `x`.
    fn uniform_step(&self, x: &[V3], next: &mut [V3], s: f64) {
        let keep = 1.0 - s;
        let share: [f64; MANY as usize] = std::array::from_fn(|d| s * (1.0 / d as f64));
        let mut cols = self.cols.as_slice();
        let mut many = self.many.iter();
        for ((&d, q), o) in self.degree.iter().zip(x).zip(next.iter_mut()) {
            if d == 0 {
                *o = *q;
                continue;
            }
            let (degree, t) = if d < MANY {
                (usize::from(d), share[usize::from(d)])
            } else {
                let n = many.next().copied().unwrap_or(0);
                (n as usize, s * (1.0 / f64::from(n)))
            };
            let (ring, rest) = cols.split_at(degree.min(cols.len()));
            cols = rest;
            let mut acc = [0.0f64; 3];
            for &c in ring {
                let p = x[c as usize];
                acc[0] += p[0];
                acc[1] += p[1];
                acc[2] += p[2];
            }
            *o = [
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
            ring.extend(hs.map(|h| x[mesh.origin(h).index()]));
        } else {
            ring.extend(
                mesh.face_halfedges_from(h0)
                    .map(|h| x[mesh.origin(h).index()]),
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
