//! Fairing: the smoothest surface over a region with its surroundings
//! fixed, by minimising the `k`-Laplacian energy (`k` = 1 membrane, 2 thin
//! plate, 3 minimum variation), as pmp-library's `fair`.
//!
//! The free vertices' positions solve `A x = 0` with
//! `A = (−1)^k (L M⁻¹)^(k−1) L`: `L` the Laplacian
//! ([`laplacian`](super::laplacian), cotangent weights clamped at zero by
//! default, or uniform), `M` the mixed-Voronoi mass matrix (the identity
//! for uniform weights). `A` is symmetric; the fixed vertices' positions
//! move to the right-hand side and the system over the free vertices is
//! positive definite as long as every part of the region reaches a fixed
//! vertex, and is solved by one sparse Cholesky factorisation (faer) for the
//! three coordinates. `L` and `M` are taken from the input positions.
//!
//! **Which vertices move.** The vertices of [`FairOptions::region`] (all
//! vertices by default), except boundary vertices and, for `k > 1`, the
//! `k − 1` rings around the boundary (whose one-sided Laplacian would pull
//! the boundary in), as pmp-library locks them. Every other vertex keeps
//! its position bit for bit; the `k` rings of fixed vertices around the
//! region are the boundary conditions: position (`k = 1`), position and
//! tangent plane (`k = 2`), and curvature too (`k = 3`).
//!
//! **Attributes.** Only the position column changes; no element is split
//! or merged, so no rule runs and every other column keeps its values
//! (normals and curvature columns go stale, as after
//! [`smooth`](super::smooth::smooth)).
//!
//! **All or nothing.** The solution is computed on the side; the mesh
//! changes only when every new coordinate is finite. A cancelled
//! ([`Progress`]) or failed run (a region with no vertex that may move, a
//! region not anchored to any fixed vertex, an order outside 1..=3) leaves
//! the mesh as it was.
//!
//! **Cost.** Building `A`: O(free vertices · ring size^k) (the `k`-ring of
//! each free vertex); one sparse Cholesky factorisation of a matrix with one
//! row per free vertex.
//!
//! ```
//! use meshloom::algo::fair::{fair, FairOptions, FairRegion};
//! use meshloom::algo::Progress;
//! use meshloom::shapes::{grid, GridFaces};
//! // A flat grid with a spike in the middle: fairing the middle flattens it.
//! let mut mesh = grid(9, 9, GridFaces::Triangles);
//! let centre = mesh.vertices().nth(4 * 10 + 4).unwrap();
//! let p = mesh.position(centre)?;
//! mesh.set_position(centre, [p[0], p[1], 1.0])?;
//! let region = FairRegion::Vertices(vec![centre]);
//! let report = fair(&mut mesh, &FairOptions { region, ..Default::default() }, Progress::none())?;
//! assert_eq!(report.moved, 1);
//! assert!(mesh.position(centre)?[2].abs() < 1e-12);
//! # Ok::<(), meshloom::Error>(())
//! ```

use super::laplacian::{
    laplacian_at, mass_matrix_at, norm, positions, sub, LaplaceWeights, LaplacianOptions, V3,
};
use super::progress::Progress;
use super::sparse::{solve_spd, LowerCsc};
use crate::attr::VertexAttr;
use crate::error::{Error, Result};
use crate::keys::VertexKey;
use crate::layout::{IdVec, Vid};
use crate::mesh::Mesh;

const ALGORITHM: &str = "fair";

/// The vertices [`fair`] may move.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum FairRegion {
    /// Every vertex (default): only the boundary rings are fixed.
    #[default]
    All,
    /// The vertices where this `bool` vertex column is `true`.
    Mask(VertexAttr<bool>),
    /// These vertices (repeats are ignored).
    Vertices(Vec<VertexKey>),
}

/// Options of [`fair`].
#[derive(Clone, Debug, PartialEq)]
pub struct FairOptions {
    /// The vertices to move (default: all but the boundary rings).
    pub region: FairRegion,
    /// The power `k` of the Laplacian, 1 to 3 (default 2, the thin-plate
    /// energy of pmp-library's `fair`).
    pub order: u32,
    /// Cotangent (default) or uniform weights.
    pub weights: LaplaceWeights,
}

impl Default for FairOptions {
    fn default() -> Self {
        FairOptions {
            region: FairRegion::All,
            order: 2,
            weights: LaplaceWeights::Cotan,
        }
    }
}

/// What [`fair`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FairReport {
    /// Vertices that were solved for.
    pub moved: usize,
    /// Fixed vertices that entered the system as boundary conditions.
    pub constraints: usize,
    /// The largest distance a vertex moved.
    pub max_displacement: f64,
}

fn unsuitable(key: Option<VertexKey>, reason: impl Into<String>) -> Error {
    Error::Unsuitable {
        algorithm: ALGORITHM,
        key: key.map(Into::into),
        reason: reason.into(),
    }
}

/// Fair the region of `mesh` (see the module docs).
///
/// # Errors
/// [`Error::Unsuitable`] without the `sparse` feature (faer);
/// [`Error::NoPositions`]; [`Error::StaleKey`] for a region vertex that is
/// not in the mesh; [`Error::AttributeHandle`] for a removed mask column;
/// [`Error::Unsuitable`] for an order outside 1..=3, a region with no vertex
/// that may move, a connected part of the region with no edge to a fixed
/// vertex (such as a whole closed mesh: nothing would hold it), a system
/// that is not positive definite, or a non-finite result; [`Error::Cancelled`]. The mesh is unchanged after any
/// error.
///
/// # Complexity
/// O(free vertices · ring size^k) to build the system, then one sparse
/// Cholesky factorisation.
///
/// ```
/// use meshloom::algo::fair::{fair, FairOptions};
/// use meshloom::algo::Progress;
/// // A closed mesh has nothing fixed: refused, and left as it was.
/// let mut sphere = meshloom::shapes::icosphere(2);
/// let before = sphere.clone();
/// assert!(fair(&mut sphere, &FairOptions::default(), Progress::none()).is_err());
/// assert_eq!(sphere.position_slots(), before.position_slots());
/// ```
pub fn fair(mesh: &mut Mesh, options: &FairOptions, progress: Progress<'_>) -> Result<FairReport> {
    mesh.as_one_step("Fair", |mesh| fair_run(mesh, options, progress))
}

/// [`fair`] itself, outside the journal's step.
fn fair_run(
    mesh: &mut Mesh,
    options: &FairOptions,
    mut progress: Progress<'_>,
) -> Result<FairReport> {
    let k = options.order;
    if !(1..=3).contains(&k) {
        return Err(unsuitable(None, format!("order {k} is not 1, 2 or 3")));
    }
    if !super::sparse::AVAILABLE {
        return Err(unsuitable(None, super::sparse::UNAVAILABLE));
    }
    let p = positions(mesh)?;
    let free = free_vertices(mesh, &options.region, k)?;
    let moved = free.iter().filter(|&&f| f).count();
    if moved == 0 {
        return Err(unsuitable(None, "the region holds no vertex that may move"));
    }
    if let Some(v) = unanchored(mesh, &free) {
        return Err(unsuitable(
            Some(mesh.vkey(v)),
            "a connected part of the region touches no fixed vertex (nothing holds it in place)",
        ));
    }
    progress.report(ALGORITHM, "matrices", 0, 3)?;
    let l = laplacian_at(
        mesh,
        p,
        &LaplacianOptions {
            weights: options.weights,
            clamp_negative: true,
        },
    );
    let inv_mass: Vec<f64> = match options.weights {
        LaplaceWeights::Uniform => vec![1.0; l.len()],
        LaplaceWeights::Cotan => mass_matrix_at(mesh, p)
            .into_iter()
            .map(|a| if a > 0.0 { 1.0 / a } else { 0.0 })
            .collect(),
    };
    // Unknowns: the free vertices, numbered in slot order.
    let nv = l.len();
    let mut local: IdVec<Vid, u32> = IdVec::filled(u32::MAX, nv);
    let mut slots: Vec<Vid> = Vec::with_capacity(moved);
    for (i, &f) in free.iter().enumerate() {
        if f {
            let v = Vid::new(i as u32);
            local[v] = slots.len() as u32;
            slots.push(v);
        }
    }
    let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
    let mut acc = Accumulator::new(nv);
    let mut a = LowerCsc::with_capacity(slots.len(), slots.len() * (1 + 6 * k as usize));
    let mut b: Vec<V3> = Vec::with_capacity(slots.len());
    let mut column: Vec<(u32, f64)> = Vec::new();
    let mut constrained = vec![false; nv];
    let every = (slots.len() / 64).max(1);
    for (n, &v) in slots.iter().enumerate() {
        if n % every == 0 {
            progress.report(ALGORITHM, "system", n as u64, slots.len() as u64)?;
        }
        // Row v of A: e_v, then L, then (M⁻¹ then L) k − 1 times.
        acc.reset_to(v.index(), 1.0);
        acc.apply_laplacian(&l);
        for _ in 1..k {
            acc.scale(&inv_mass);
            acc.apply_laplacian(&l);
        }
        let me = local[v];
        let mut rhs = [0.0; 3];
        column.clear();
        for &(j, val) in acc.entries() {
            let w = sign * val;
            let lj = local[Vid::new(j)];
            if lj == u32::MAX {
                // A fixed vertex: to the right-hand side.
                let q = p[j as usize];
                rhs = [rhs[0] - w * q[0], rhs[1] - w * q[1], rhs[2] - w * q[2]];
                constrained[j as usize] |= w != 0.0;
            } else if lj >= me {
                column.push((lj, w));
            }
        }
        column.sort_unstable_by_key(|&(j, _)| j);
        for &(j, w) in &column {
            a.push(j as usize, w);
        }
        a.end_column();
        b.push(rhs);
    }
    progress.report(ALGORITHM, "solve", 1, 3)?;
    solve_spd(&a, &mut b).map_err(|e| {
        unsuitable(
            None,
            format!("{e} (does every part of the region reach a fixed vertex?)"),
        )
    })?;
    progress.report(ALGORITHM, "solve", 3, 3)?;
    let mut max_d: f64 = 0.0;
    for (&v, q) in slots.iter().zip(&b) {
        if !q.iter().all(|c| c.is_finite()) {
            return Err(unsuitable(
                Some(mesh.vkey(v)),
                "the faired position is not finite",
            ));
        }
        max_d = max_d.max(norm(sub(*q, p[v.index()])));
    }
    let out = mesh.position_slots_mut().ok_or(Error::NoPositions)?;
    for (&v, q) in slots.iter().zip(&b) {
        out[v.index()] = *q;
    }
    debug_assert!(mesh.validate().is_ok());
    Ok(FairReport {
        moved,
        constraints: constrained.iter().filter(|&&c| c).count(),
        max_displacement: max_d,
    })
}

/// Whether each vertex slot is solved for: in the region, and not within
/// `k − 1` rings of the boundary.
fn free_vertices(mesh: &Mesh, region: &FairRegion, k: u32) -> Result<Vec<bool>> {
    let nv = mesh.v_halfedge.len();
    let mut free = vec![false; nv];
    match region {
        FairRegion::All => {
            for v in mesh.vids() {
                free[v.index()] = true;
            }
        }
        FairRegion::Mask(mask) => {
            let view = mesh.attr_view(mask)?;
            for v in mesh.vertices() {
                free[v.index()] = view.get(v) == Some(&true);
            }
        }
        FairRegion::Vertices(keys) => {
            for &key in keys {
                free[mesh.check_vertex(key)?.index()] = true;
            }
        }
    }
    // Lock the boundary and its k − 1 rings: a breadth-first search from
    // the boundary, k − 1 steps deep.
    let mut front: Vec<Vid> = mesh.vids().filter(|&v| mesh.on_boundary(v)).collect();
    let mut locked = vec![false; nv];
    for &v in &front {
        locked[v.index()] = true;
    }
    let mut next: Vec<Vid> = Vec::new();
    for _ in 1..k {
        next.clear();
        for &v in &front {
            for h in mesh.outgoing(v) {
                let w = mesh.dest(h);
                if !locked[w.index()] {
                    locked[w.index()] = true;
                    next.push(w);
                }
            }
        }
        std::mem::swap(&mut front, &mut next);
    }
    for (f, l) in free.iter_mut().zip(&locked) {
        *f &= !*l;
    }
    Ok(free)
}

/// A vertex of a connected part of the free vertices (joined by edges)
/// that has no edge to a fixed vertex, if there is one: its system would be
/// singular (rounding can hide that from the factorisation).
fn unanchored(mesh: &Mesh, free: &[bool]) -> Option<Vid> {
    let mut seen = vec![false; free.len()];
    let mut stack: Vec<Vid> = Vec::new();
    for start in mesh.vids() {
        if !free[start.index()] || seen[start.index()] {
            continue;
        }
        seen[start.index()] = true;
        stack.push(start);
        let mut anchored = false;
        while let Some(v) = stack.pop() {
            for h in mesh.outgoing(v) {
                let w = mesh.dest(h);
                if !free[w.index()] {
                    anchored = true;
                } else if !seen[w.index()] {
                    seen[w.index()] = true;
                    stack.push(w);
                }
            }
        }
        if !anchored {
            return Some(start);
        }
    }
    None
}

/// A sparse vector by vertex slot: dense values, the touched slots listed.
struct Accumulator {
    value: Vec<f64>,
    seen: Vec<bool>,
    list: Vec<(u32, f64)>,
    scratch: Vec<(u32, f64)>,
}

impl Accumulator {
    fn new(n: usize) -> Accumulator {
        Accumulator {
            value: vec![0.0; n],
            seen: vec![false; n],
            list: Vec::new(),
            scratch: Vec::new(),
        }
    }

    /// The unit vector `x e_i`.
    fn reset_to(&mut self, i: usize, x: f64) {
        self.list.clear();
        self.list.push((i as u32, x));
    }

    /// Multiply entry-wise by `d`.
    fn scale(&mut self, d: &[f64]) {
        for (i, x) in &mut self.list {
            *x *= d[*i as usize];
        }
    }

    #[inline]
    fn add(&mut self, i: u32, x: f64) {
        let s = i as usize;
        if !self.seen[s] {
            self.seen[s] = true;
            self.scratch.push((i, 0.0));
        }
        self.value[s] += x;
    }

    /// Replace the vector by `L` times it (`L` is symmetric: column `m`
    /// is row `m`).
    fn apply_laplacian(&mut self, l: &super::laplacian::Laplacian) {
        let input = std::mem::take(&mut self.list);
        self.scratch.clear();
        for &(m, x) in &input {
            let mi = m as usize;
            self.add(m, l.diagonal(mi) * x);
            let (cols, ws) = l.row_raw(mi);
            for (&c, &w) in cols.iter().zip(ws) {
                self.add(c, w * x);
            }
        }
        let mut out = std::mem::take(&mut self.scratch);
        for (i, x) in &mut out {
            let s = *i as usize;
            *x = self.value[s];
            self.value[s] = 0.0;
            self.seen[s] = false;
        }
        self.scratch = input;
        self.list = out;
    }

    fn entries(&self) -> &[(u32, f64)] {
        &self.list
    }
}
