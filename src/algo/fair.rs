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
//! three coordinates. `L` and `M` are taken from the input positions (with
//! any sliding line already spread along itself).
//!
//! **Which vertices move** (the shared vocabulary of
//! [`constraints`](super::constraints)). The vertices of
//! [`FairOptions::region`] (all vertices by default), except the held
//! ones. With [`FairOptions::boundary`] [`Keep::Lock`] (the default) the
//! boundary vertices and, for `k > 1`, the `k − 1` rings around the
//! boundary (whose one-sided Laplacian would pull the boundary in) stay,
//! as pmp-library locks them. With [`Keep::Slide`] the same rings stay,
//! and the boundary vertices of the region move along the input's
//! boundary: each piece of it between two corners (turns of more than the
//! feature angle, 45° without one, or a vertex outside the region), or a
//! whole loop, gets its vertices spread evenly by arc length on the
//! input's polyline (the membrane energy of the line itself); the surface
//! is then faired against them. With [`Keep::Free`] boundary vertices are
//! solved for like any other (then something else must hold the region:
//! pinned vertices, or vertices outside it). Seams
//! ([`FairOptions::seams`], default free) and feature edges slide or lock
//! the same way; pinned vertices ([`FairOptions::pinned`]) never move.
//! Every other vertex keeps its position bit for bit; the `k` rings of
//! fixed vertices around the region are the boundary conditions: position
//! (`k = 1`), position and tangent plane (`k = 2`), and curvature too
//! (`k = 3`).
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
//! row per free vertex. For [`FairRegion::All`] the whole mesh's Laplacian
//! and masses are built once; for a [`FairRegion::Vertices`] or
//! [`FairRegion::Mask`] region the system is *region-local*: only the
//! region's vertices and their `k` rings are visited (Laplacian rows of the
//! region and its `k − 1` rings, the fixed vertices within `k` rings as
//! constraints), so fairing a small patch of a large mesh costs what the
//! patch costs (a mask is still read once over all vertices).
//! [`fill_hole`](mod@super::fill_hole) fairs each patch through the same system.
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

use std::collections::hash_map::Entry;
use std::collections::{HashMap, HashSet};

use super::constraints::{Classifier, Constraints, Keep, LineSources, Polylines, FREE, LINE};
use super::laplacian::{
    laplacian_at, mass_matrix_at, polygon, positions, triangle, LaplaceWeights, LaplacianOptions,
};
use super::progress::Progress;
use super::sparse::{solve_spd, LowerCsc, AVAILABLE};
use crate::attr::{EdgeAttr, VertexAttr};
use crate::error::{Error, Result};
use crate::keys::VertexKey;
use crate::layout::{IdVec, Vid};
use crate::mesh::Mesh;
use crate::vec3::{norm, sub, V3};

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
    /// Boundary vertices (default [`Keep::Lock`]: they and the `k − 1`
    /// rings around them stay; `Slide`: they are spread along the input's
    /// boundary, the rings stay; `Free`: they are solved for). See
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
    /// move).
    pub pinned: Option<VertexAttr<bool>>,
}

impl FairOptions {
    /// The constraints these options name.
    pub fn constraints(&self) -> Constraints {
        Constraints {
            boundary: self.boundary,
            seams: self.seams,
            feature_angle: self.feature_angle,
            features: self.features.clone(),
            pinned: self.pinned.clone(),
        }
    }
}

impl Default for FairOptions {
    fn default() -> Self {
        FairOptions {
            region: FairRegion::All,
            order: 2,
            weights: LaplaceWeights::Cotan,
            boundary: Keep::Lock,
            seams: Keep::Free,
            feature_angle: None,
            features: None,
            pinned: None,
        }
    }
}

/// What [`fair`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FairReport {
    /// Vertices that moved: solved for, or spread along a sliding line.
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
    let constraints = options.constraints();
    constraints.check(ALGORITHM)?;
    let p = positions(mesh)?;
    let (solve, slid) = {
        let sources = LineSources::all_corner_columns(mesh, Keep::Slide, false);
        let held = Classifier::new(mesh, p, &constraints, sources)?;
        match &options.region {
            FairRegion::All => whole_movers(mesh, p, &held, options.boundary, k),
            region => region_movers(mesh, p, &held, region, options.boundary, k)?,
        }
    };
    if solve.is_empty() && slid.is_empty() {
        return Err(unsuitable(None, "the region holds no vertex that may move"));
    }
    let loose = if options.region == FairRegion::All {
        let mut free = vec![false; mesh.v_halfedge.len()];
        for v in &solve {
            free[v.index()] = true;
        }
        unanchored(mesh, &free)
    } else {
        unanchored_part(mesh, &solve)
    };
    if let Some(v) = loose {
        return Err(unsuitable(
            Some(mesh.vkey(v)),
            "a connected part of the region touches no fixed vertex (nothing holds it in place)",
        ));
    }
    // The positions the system reads: the input's, the slid lines moved.
    let moved_p;
    let q: &[V3] = if slid.is_empty() {
        p
    } else {
        let mut x = p.to_vec();
        for &(v, y) in &slid {
            x[v.index()] = y;
        }
        moved_p = x;
        &moved_p
    };
    let solution = if solve.is_empty() {
        LocalSolution {
            positions: Vec::new(),
            constraints: 0,
        }
    } else if options.region == FairRegion::All {
        solve_whole(mesh, q, &solve, options, &mut progress)?
    } else {
        progress.report(ALGORITHM, "matrices", 0, 3)?;
        progress.report(ALGORITHM, "system", 1, 3)?;
        progress.report(ALGORITHM, "solve", 2, 3)?;
        solve_local(mesh, q, &solve, k, options.weights).map_err(not_held)?
    };
    progress.report(ALGORITHM, "solve", 3, 3)?;
    let moves: Vec<(Vid, V3)> = solve
        .iter()
        .copied()
        .zip(solution.positions)
        .chain(slid)
        .collect();
    let max_displacement = write_back(mesh, &moves)?;
    Ok(FairReport {
        moved: moves.len(),
        constraints: solution.constraints,
        max_displacement,
    })
}

/// The error of a system that could not be solved.
fn not_held(e: String) -> Error {
    unsuitable(
        None,
        format!("{e} (does every part of the region reach a fixed vertex?)"),
    )
}

/// Write the new positions `moves` once every one is finite; the largest
/// displacement.
fn write_back(mesh: &mut Mesh, moves: &[(Vid, V3)]) -> Result<f64> {
    let p = positions(mesh)?;
    let mut max_d: f64 = 0.0;
    for &(v, q) in moves {
        if !q.iter().all(|c| c.is_finite()) {
            return Err(unsuitable(
                Some(mesh.vkey(v)),
                "the faired position is not finite",
            ));
        }
        max_d = max_d.max(norm(sub(q, p[v.index()])));
    }
    let out = mesh.position_slots_mut().ok_or(Error::NoPositions)?;
    for &(v, q) in moves {
        out[v.index()] = q;
    }
    mesh.debug_validate();
    Ok(max_d)
}

/// The whole mesh's movers: the free vertices to solve for (in slot
/// order) and the sliding ones with their spread positions. Unless the
/// boundary is free, the `k − 1` rings around it are held.
fn whole_movers(
    mesh: &Mesh,
    p: &[V3],
    held: &Classifier<'_>,
    boundary: Keep,
    k: u32,
) -> (Vec<Vid>, Vec<(Vid, V3)>) {
    let c = held.classify();
    let mut free: Vec<bool> = c.kinds.iter().map(|&kind| kind == FREE).collect();
    if boundary != Keep::Free {
        for (f, near) in free.iter_mut().zip(boundary_rings(mesh, k)) {
            *f &= !near;
        }
    }
    let solve = mesh.vids().filter(|v| free[v.index()]).collect();
    let slid = if c.kinds.contains(&LINE) {
        let kinds = &c.kinds;
        let lines = &c.lines;
        Polylines::new(
            mesh,
            p,
            mesh.vids().filter(|v| kinds[v.index()] == LINE),
            |v| kinds[v.index()] == LINE,
            |e| lines.get(e),
        )
        .spread()
    } else {
        Vec::new()
    };
    (solve, slid)
}

/// Per vertex slot: whether it lies within `k − 1` rings of the boundary
/// (a breadth-first search from the boundary, `k − 1` steps deep).
fn boundary_rings(mesh: &Mesh, k: u32) -> Vec<bool> {
    let mut front: Vec<Vid> = mesh.vids().filter(|&v| mesh.on_boundary(v)).collect();
    let mut near = vec![false; mesh.v_halfedge.len()];
    for &v in &front {
        near[v.index()] = true;
    }
    let mut next: Vec<Vid> = Vec::new();
    for _ in 1..k {
        next.clear();
        for &v in &front {
            for h in mesh.outgoing(v) {
                let w = mesh.dest(h);
                if !near[w.index()] {
                    near[w.index()] = true;
                    next.push(w);
                }
            }
        }
        std::mem::swap(&mut front, &mut next);
    }
    near
}

/// The vertices to solve for, and the held vertices with their positions.
type Movers = (Vec<Vid>, Vec<(Vid, V3)>);

/// A region's movers, as [`whole_movers`], visiting only the region and
/// its neighbourhood (a mask is read once over all vertices).
fn region_movers(
    mesh: &Mesh,
    p: &[V3],
    held: &Classifier<'_>,
    region: &FairRegion,
    boundary: Keep,
    k: u32,
) -> Result<Movers> {
    let region: Vec<Vid> = match region {
        FairRegion::All => mesh.vids().collect(),
        FairRegion::Mask(mask) => {
            let view = mesh.attr_view(mask)?;
            mesh.vertices()
                .filter(|&v| view.get(v) == Some(&true))
                .map(|v| v.id())
                .collect()
        }
        FairRegion::Vertices(keys) => {
            let mut out = Vec::with_capacity(keys.len());
            for &key in keys {
                out.push(mesh.check_vertex(key)?);
            }
            out.sort_unstable();
            out.dedup();
            out
        }
    };
    let kinds: Vec<u8> = region.iter().map(|&v| held.vertex(v)).collect();
    let rings = boundary != Keep::Free;
    let solve = region
        .iter()
        .zip(&kinds)
        .filter(|&(&v, &kind)| kind == FREE && !(rings && near_boundary(mesh, v, k - 1)))
        .map(|(&v, _)| v)
        .collect();
    let slid = if kinds.contains(&LINE) {
        let in_region = |v: Vid| region.binary_search(&v).is_ok();
        let starts = region.iter().zip(&kinds).filter(|&(_, &kind)| kind == LINE);
        Polylines::new(
            mesh,
            p,
            starts.map(|(&v, _)| v),
            |v| in_region(v) && held.vertex(v) == LINE,
            |e| held.edge(e).line,
        )
        .spread()
    } else {
        Vec::new()
    };
    Ok((solve, slid))
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

/// As [`unanchored`] for the free vertices `free` (sorted), visiting only
/// them and their neighbours.
fn unanchored_part(mesh: &Mesh, free: &[Vid]) -> Option<Vid> {
    let is_free = |v: Vid| free.binary_search(&v).is_ok();
    let mut seen: HashSet<Vid> = HashSet::with_capacity(free.len());
    let mut stack: Vec<Vid> = Vec::new();
    for &start in free {
        if !seen.insert(start) {
            continue;
        }
        stack.push(start);
        let mut anchored = false;
        while let Some(v) = stack.pop() {
            for h in mesh.outgoing(v) {
                let w = mesh.dest(h);
                if !is_free(w) {
                    anchored = true;
                } else if seen.insert(w) {
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

/// The whole mesh's system (its Laplacian and masses built once) for the
/// free vertices `free` (in slot order) at positions `p`.
fn solve_whole(
    mesh: &Mesh,
    p: &[V3],
    free: &[Vid],
    options: &FairOptions,
    progress: &mut Progress<'_>,
) -> Result<LocalSolution> {
    let k = options.order;
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
    for (n, &v) in free.iter().enumerate() {
        local[v] = n as u32;
    }
    let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
    let mut acc = Accumulator::new(nv);
    let mut a = LowerCsc::with_capacity(free.len(), free.len() * (1 + 6 * k as usize));
    let mut b: Vec<V3> = Vec::with_capacity(free.len());
    let mut column: Vec<(u32, f64)> = Vec::new();
    let mut constrained = vec![false; nv];
    let every = (free.len() / 64).max(1);
    for (n, &v) in free.iter().enumerate() {
        if n % every == 0 {
            progress.report(ALGORITHM, "system", n as u64, free.len() as u64)?;
        }
        // Row v of A: e_v, then L, then (M⁻¹ then L) k − 1 times.
        acc.reset_to(v.index(), 1.0);
        acc.apply(&l);
        for _ in 1..k {
            acc.scale(&inv_mass);
            acc.apply(&l);
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
    solve_spd(&a, &mut b).map_err(|e| not_held(e.to_string()))?;
    Ok(LocalSolution {
        positions: b,
        constraints: constrained.iter().filter(|&&c| c).count(),
    })
}

/// A symmetric sparse matrix read row by row: the whole mesh's
/// Laplacian, or the region-local rows of [`solve_local`].
trait SymmetricRows {
    fn diagonal(&self, m: usize) -> f64;
    fn for_each_off_diagonal(&self, m: usize, f: impl FnMut(u32, f64));
}

impl SymmetricRows for super::laplacian::Laplacian {
    #[inline]
    fn diagonal(&self, m: usize) -> f64 {
        super::laplacian::Laplacian::diagonal(self, m)
    }
    #[inline]
    fn for_each_off_diagonal(&self, m: usize, mut f: impl FnMut(u32, f64)) {
        let (cols, ws) = self.row_raw(m);
        for (&c, &w) in cols.iter().zip(ws) {
            f(c, w);
        }
    }
}

/// The region-local rows: off-diagonal entries per row and the diagonal.
struct LocalRows<'a> {
    rows: &'a [Vec<(u32, f64)>],
    diagonal: &'a [f64],
}

impl SymmetricRows for LocalRows<'_> {
    #[inline]
    fn diagonal(&self, m: usize) -> f64 {
        self.diagonal[m]
    }
    #[inline]
    fn for_each_off_diagonal(&self, m: usize, mut f: impl FnMut(u32, f64)) {
        for &(c, w) in &self.rows[m] {
            f(c, w);
        }
    }
}

/// A sparse vector by slot (vertex slot, or the region-local numbering):
/// dense values, the touched slots listed.
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

    /// Replace the vector by `A` times it (`A` symmetric: column `m` is
    /// row `m`; only rows of the vector's support are read).
    fn apply(&mut self, a: &impl SymmetricRows) {
        let input = std::mem::take(&mut self.list);
        self.scratch.clear();
        for &(m, x) in &input {
            let mi = m as usize;
            self.add(m, a.diagonal(mi) * x);
            a.for_each_off_diagonal(mi, |c, w| self.add(c, w * x));
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

// ---------------------------------------------------------------------------
// The region-local system
// ---------------------------------------------------------------------------

/// The solution of [`solve_local`].
pub(crate) struct LocalSolution {
    /// The new positions of the free vertices, in their order.
    pub(crate) positions: Vec<V3>,
    /// Fixed vertices that entered the right-hand side with a non-zero
    /// weight.
    pub(crate) constraints: usize,
}

/// Solve `A x = 0` (see the module docs) for the vertices `free` (no
/// repeats), every other vertex fixed, over a system built from the free
/// vertices and their `k` rings only: the unknowns are the free vertices,
/// the Laplacian rows are those of the free vertices and their `k − 1`
/// rings, the fixed vertices within `k` rings are the constraints. Nothing
/// is read or allocated per vertex of the whole mesh, so the cost follows
/// the region, not the mesh (what [`fair`] does for a region, and what
/// [`fill_hole`](super::fill_hole) does for each patch). With the `sparse`
/// feature the system is solved by faer's sparse Cholesky factorisation;
/// without it by conjugate gradients (the same positions to solver
/// precision).
pub(crate) fn solve_local(
    mesh: &Mesh,
    p: &[V3],
    free: &[Vid],
    k: u32,
    weights: LaplaceWeights,
) -> std::result::Result<LocalSolution, String> {
    // Local numbering: the free vertices first, then their k rings.
    let mut local: HashMap<Vid, u32> = HashMap::with_capacity(free.len() * 4);
    let mut order: Vec<Vid> = Vec::with_capacity(free.len() * 4);
    for &v in free {
        local.insert(v, order.len() as u32);
        order.push(v);
    }
    let mut ring_end = vec![order.len()];
    let mut begin = 0;
    let mut near = Vec::new();
    for _ in 0..k {
        let end = order.len();
        for i in begin..end {
            stencil(mesh, order[i], weights, &mut near);
            for &w in &near {
                if let Entry::Vacant(slot) = local.entry(w) {
                    slot.insert(order.len() as u32);
                    order.push(w);
                }
            }
        }
        begin = end;
        ring_end.push(order.len());
    }
    // Laplacian rows and inverse masses of the vertices within k − 1 rings.
    let with_rows = ring_end[k as usize - 1];
    let mut rows: Vec<Vec<(u32, f64)>> = Vec::with_capacity(with_rows);
    let mut diagonal: Vec<f64> = Vec::with_capacity(with_rows);
    let mut inv_mass: Vec<f64> = Vec::with_capacity(with_rows);
    let mut scratch = Vec::new();
    for &v in &order[..with_rows] {
        let mass = laplacian_row(mesh, p, v, weights, &mut scratch);
        let row: Vec<(u32, f64)> = scratch.iter().map(|&(u, w)| (local[&u], w)).collect();
        diagonal.push(-row.iter().map(|&(_, w)| w).sum::<f64>());
        rows.push(row);
        inv_mass.push(if mass > 0.0 { 1.0 / mass } else { 0.0 });
    }
    // Row v of A = (−1)^k L (M⁻¹ L)^(k−1), restricted to the free columns;
    // the fixed columns go to the right-hand side.
    let nf = free.len();
    let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
    let local_rows = LocalRows {
        rows: &rows,
        diagonal: &diagonal,
    };
    let mut acc = Accumulator::new(order.len());
    let mut columns: Vec<Vec<(u32, f64)>> = Vec::with_capacity(nf);
    let mut rhs: Vec<V3> = Vec::with_capacity(nf);
    let mut constrained = vec![false; order.len() - nf];
    for me in 0..nf {
        acc.reset_to(me, 1.0);
        acc.apply(&local_rows);
        for _ in 1..k {
            acc.scale(&inv_mass);
            acc.apply(&local_rows);
        }
        let mut b = [0.0; 3];
        let mut column = Vec::new();
        for &(j, val) in acc.entries() {
            let w = sign * val;
            let j = j as usize;
            if j < nf {
                if j >= me {
                    column.push((j as u32, w));
                }
            } else {
                let q = p[order[j].index()];
                b = [b[0] - w * q[0], b[1] - w * q[1], b[2] - w * q[2]];
                constrained[j - nf] |= w != 0.0;
            }
        }
        column.sort_unstable_by_key(|&(j, _)| j);
        columns.push(column);
        rhs.push(b);
    }
    solve_columns(&columns, &mut rhs)?;
    Ok(LocalSolution {
        positions: rhs,
        constraints: constrained.iter().filter(|&&c| c).count(),
    })
}

/// The vertices [`laplacian_row`] can name for `v`: its neighbours across
/// edges, and with cotangent weights every corner of the faces around it
/// (a polygon's Laplacian joins `v` to corners it shares no edge with, as
/// the far corner of a quad). The rings of [`solve_local`] grow by this
/// stencil, so every vertex a row names has a local number.
fn stencil(mesh: &Mesh, v: Vid, weights: LaplaceWeights, out: &mut Vec<Vid>) {
    out.clear();
    for h in mesh.outgoing(v) {
        out.push(mesh.dest(h));
        if weights == LaplaceWeights::Uniform || mesh.is_hole(mesh.face_of(h)) {
            continue;
        }
        // Corners of a triangle are neighbours already.
        let far = mesh.next(mesh.next(h));
        if mesh.next(far) != h {
            out.extend(
                mesh.face_loop_from(h)
                    .map(|g| mesh.origin(g))
                    .filter(|&u| u != v),
            );
        }
    }
}

/// The Laplacian row of `v` (neighbours with their weights, cotangent
/// ones clamped at zero) and its mass (mixed-Voronoi for cotangent
/// weights, 1 for uniform), from the faces around it, as
/// [`laplacian_at`] and [`mass_matrix_at`] compute them for the whole
/// mesh.
fn laplacian_row(
    mesh: &Mesh,
    p: &[V3],
    v: Vid,
    weights: LaplaceWeights,
    row: &mut Vec<(Vid, f64)>,
) -> f64 {
    row.clear();
    if weights == LaplaceWeights::Uniform {
        row.extend(mesh.outgoing(v).map(|h| (mesh.dest(h), 1.0)));
        row.sort_unstable_by_key(|&(u, _)| u);
        row.dedup_by_key(|&mut (u, _)| u);
        return 1.0;
    }
    let mut mass = 0.0;
    let (mut ps, mut ring, mut pairs, mut area) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for h in mesh.outgoing(v) {
        let f = mesh.face_of(h);
        if mesh.is_hole(f) {
            continue;
        }
        let h1 = mesh.next(h);
        let h2 = mesh.next(h1);
        if mesh.next(h2) == h {
            let (b, c) = (mesh.origin(h1), mesh.origin(h2));
            let (t, _, _) = triangle([p[v.index()], p[b.index()], p[c.index()]]);
            // Edge v-b is opposite corner c; edge c-v opposite corner b.
            row.push((b, t.half_cot[2]));
            row.push((c, t.half_cot[1]));
            mass += t.area[0];
            continue;
        }
        ring.clear();
        ring.extend(mesh.face_loop_from(h).map(|g| mesh.origin(g)));
        ps.clear();
        ps.extend(ring.iter().map(|u| p[u.index()]));
        polygon(&ps, &mut pairs, &mut area);
        for &(k, m, w) in &pairs {
            if k == 0 {
                row.push((ring[m], w));
            }
        }
        mass += area[0];
    }
    row.sort_unstable_by_key(|&(u, _)| u);
    row.dedup_by(|later, first| {
        if later.0 == first.0 {
            first.1 += later.1;
            true
        } else {
            false
        }
    });
    for (_, w) in row.iter_mut() {
        *w = w.max(0.0);
    }
    mass
}

/// Whether a boundary vertex lies within `rings` edges of `v`.
pub(crate) fn near_boundary(mesh: &Mesh, v: Vid, rings: u32) -> bool {
    let mut front = vec![v];
    let mut seen: HashSet<Vid> = HashSet::from([v]);
    for step in 0..=rings {
        let mut next = Vec::new();
        for &u in &front {
            if mesh.on_boundary(u) {
                return true;
            }
            if step < rings {
                for g in mesh.outgoing(u) {
                    let w = mesh.dest(g);
                    if seen.insert(w) {
                        next.push(w);
                    }
                }
            }
        }
        front = next;
    }
    false
}

/// Solve the symmetric positive definite system given by its lower
/// columns (rows sorted, diagonal first), for the three columns of `rhs`:
/// faer's sparse Cholesky with the `sparse` feature, conjugate gradients
/// without.
fn solve_columns(columns: &[Vec<(u32, f64)>], rhs: &mut [V3]) -> std::result::Result<(), String> {
    if AVAILABLE {
        let nnz = columns.iter().map(Vec::len).sum();
        let mut a = LowerCsc::with_capacity(columns.len(), nnz);
        for column in columns {
            for &(j, w) in column {
                a.push(j as usize, w);
            }
            a.end_column();
        }
        solve_spd(&a, rhs).map_err(|e| e.to_string())
    } else {
        conjugate_gradients(columns, rhs)
    }
}

/// Jacobi-preconditioned conjugate gradients, one coordinate at a time, to
/// a relative residual of 1e-12.
fn conjugate_gradients(
    columns: &[Vec<(u32, f64)>],
    rhs: &mut [V3],
) -> std::result::Result<(), String> {
    let n = columns.len();
    let multiply = |x: &[f64], y: &mut [f64]| {
        y.iter_mut().for_each(|v| *v = 0.0);
        for (j, column) in columns.iter().enumerate() {
            for &(i, w) in column {
                let i = i as usize;
                y[i] += w * x[j];
                if i != j {
                    y[j] += w * x[i];
                }
            }
        }
    };
    let diag: Vec<f64> = columns
        .iter()
        .enumerate()
        .map(|(j, c)| {
            c.iter()
                .find(|&&(i, _)| i as usize == j)
                .map_or(0.0, |&(_, w)| w)
        })
        .collect();
    if diag.iter().any(|&d| d <= 0.0 || !d.is_finite()) {
        return Err("the system matrix is not positive definite".into());
    }
    for c in 0..3 {
        let b: Vec<f64> = rhs.iter().map(|r| r[c]).collect();
        let b_norm = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut x = vec![0.0; n];
        let mut r = b.clone();
        let mut z: Vec<f64> = r.iter().zip(&diag).map(|(r, d)| r / d).collect();
        let mut d = z.clone();
        let mut rz: f64 = r.iter().zip(&z).map(|(a, b)| a * b).sum();
        let mut q = vec![0.0; n];
        if b_norm > 0.0 {
            for _ in 0..10 * n + 100 {
                multiply(&d, &mut q);
                let dq: f64 = d.iter().zip(&q).map(|(a, b)| a * b).sum();
                if dq <= 0.0 || !dq.is_finite() {
                    return Err("the system matrix is not positive definite".into());
                }
                let alpha = rz / dq;
                for (xi, di) in x.iter_mut().zip(&d) {
                    *xi += alpha * di;
                }
                for (ri, qi) in r.iter_mut().zip(&q) {
                    *ri -= alpha * qi;
                }
                if r.iter().map(|v| v * v).sum::<f64>().sqrt() <= 1e-12 * b_norm {
                    break;
                }
                for ((zi, ri), di) in z.iter_mut().zip(&r).zip(&diag) {
                    *zi = ri / di;
                }
                let rz_next: f64 = r.iter().zip(&z).map(|(a, b)| a * b).sum();
                let beta = rz_next / rz;
                rz = rz_next;
                for (di, zi) in d.iter_mut().zip(&z) {
                    *di = zi + beta * *di;
                }
            }
        }
        for (out, v) in rhs.iter_mut().zip(x) {
            out[c] = v;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    type Columns = Vec<Vec<(u32, f64)>>;

    fn small_system() -> (Columns, Vec<V3>, Vec<V3>) {
        // [4 1 0; 1 3 1; 0 1 2] x = b
        let columns = vec![
            vec![(0, 4.0), (1, 1.0)],
            vec![(1, 3.0), (2, 1.0)],
            vec![(2, 2.0)],
        ];
        let x: Vec<V3> = vec![[1.0, 2.0, 3.0], [-1.0, 0.5, 0.0], [2.0, 0.0, 1.0]];
        let b = vec![
            std::array::from_fn(|k| 4.0 * x[0][k] + x[1][k]),
            std::array::from_fn(|k| x[0][k] + 3.0 * x[1][k] + x[2][k]),
            std::array::from_fn(|k| x[1][k] + 2.0 * x[2][k]),
        ];
        (columns, b, x)
    }

    #[test]
    fn conjugate_gradients_solve_a_small_system() {
        let (columns, mut b, x) = small_system();
        conjugate_gradients(&columns, &mut b).unwrap();
        for (got, want) in b.iter().zip(&x) {
            for (g, w) in got.iter().zip(want) {
                assert!((g - w).abs() < 1e-10);
            }
        }
    }

    #[test]
    fn conjugate_gradients_refuse_a_non_positive_diagonal() {
        let columns = vec![vec![(0, -1.0)]];
        let mut b = vec![[1.0; 3]];
        assert!(conjugate_gradients(&columns, &mut b).is_err());
    }

    #[test]
    fn local_rows_match_the_global_laplacian() {
        let mesh = crate::shapes::icosphere(2);
        let p = mesh.position_slots().unwrap();
        let global = crate::algo::laplacian::laplacian(
            &mesh,
            &crate::algo::laplacian::LaplacianOptions::default(),
        )
        .unwrap();
        let masses = crate::algo::laplacian::mass_matrix(&mesh).unwrap();
        let mut row = Vec::new();
        for v in mesh.vids().take(20) {
            let mass = laplacian_row(&mesh, p, v, LaplaceWeights::Cotan, &mut row);
            assert!((mass - masses[v.index()]).abs() < 1e-12);
            let expect: Vec<(usize, f64)> = global.row(v.index()).collect();
            assert_eq!(row.len(), expect.len());
            for (&(u, w), &(c, x)) in row.iter().zip(&expect) {
                assert_eq!(u.index(), c);
                assert!((w - x).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn the_local_system_matches_the_whole_mesh_system() {
        // Fairing all of a bumpy grid (whole-mesh Laplacian) and solving
        // the same free vertices by the local system give the same
        // positions.
        let mut mesh = crate::shapes::grid(8, 8, crate::shapes::GridFaces::Triangles);
        let keys: Vec<_> = mesh.vertices().collect();
        for (i, &v) in keys.iter().enumerate() {
            let q = mesh.position(v).unwrap();
            mesh.set_position(v, [q[0], q[1], ((i * 7) % 5) as f64 * 0.1])
                .unwrap();
        }
        for k in 1..=3 {
            for weights in [LaplaceWeights::Cotan, LaplaceWeights::Uniform] {
                let free: Vec<Vid> = mesh
                    .vids()
                    .filter(|&v| !near_boundary(&mesh, v, k - 1))
                    .collect();
                let p = mesh.position_slots().unwrap();
                let local = solve_local(&mesh, p, &free, k, weights).unwrap();
                let mut whole = mesh.clone();
                let options = FairOptions {
                    order: k,
                    weights,
                    ..FairOptions::default()
                };
                if !AVAILABLE {
                    continue;
                }
                let report = fair(&mut whole, &options, Progress::none()).unwrap();
                assert_eq!(report.moved, free.len());
                assert_eq!(report.constraints, local.constraints);
                let q = whole.position_slots().unwrap();
                for (&v, x) in free.iter().zip(&local.positions) {
                    for c in 0..3 {
                        assert!((q[v.index()][c] - x[c]).abs() < 1e-9, "k {k} {weights:?}");
                    }
                }
            }
        }
    }
}
