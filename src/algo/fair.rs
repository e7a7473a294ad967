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
//! let report = fair(&mut mesh, &FairOptions::default().region(region), Progress::none())?;
//! assert_eq!(report.moved, 1);
//! assert!(mesh.position(centre)?[2].abs() < 1e-12);
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::collections::HashSet;

mod system;

use system::Accumulator;
pub(crate) use system::{solve_local, LocalSolution};

use super::constraints::{Classifier, Constraints, Keep, LineSources, Polylines, FREE, LINE};
use super::laplacian::{laplacian_at, mass_matrix_at, positions, LaplaceWeights, LaplacianOptions};
use super::progress::Progress;
use super::sparse::{solve_spd, LowerCsc};
use crate::attr::{EdgeAttr, VertexAttr};
use crate::error::{Error, Result};
use crate::keys::VertexKey;
use crate::layout::{IdVec, Vid};
use crate::mesh::Mesh;
use crate::vec3::{norm, sub, V3};

const ALGORITHM: &str = "fair";

/// The vertices [`fair`] may move.
///
/// Its one word is `all`: the other two carry what no word can name (a
/// column handle, a list of vertices), so the command line names a mask
/// column (`meshloom fair --region NAME`) and Python passes an array.
///
/// ```
/// use meshloom::algo::fair::FairRegion;
/// assert_eq!("all".parse::<FairRegion>()?, FairRegion::All);
/// assert!("mask".parse::<FairRegion>().is_err());
/// # Ok::<(), meshloom::choice::UnknownChoice>(())
/// ```
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

impl FairRegion {
    /// The words [`FairRegion`] reads: `all` (see its docs).
    pub const WORDS: &'static [&'static str] = &["all"];
}

impl std::str::FromStr for FairRegion {
    type Err = crate::choice::UnknownChoice;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        if crate::choice::spells(s, "all") {
            Ok(FairRegion::All)
        } else {
            Err(crate::choice::UnknownChoice {
                option: "FairRegion",
                given: s.to_owned(),
                choices: Self::WORDS,
            })
        }
    }
}

/// Options of [`fair`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
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

crate::algo::constraints::constrained!(FairOptions);

crate::choice::setters!(FairOptions {
    region: FairRegion,
    order: u32,
    weights: LaplaceWeights,
    boundary: Keep,
    seams: Keep,
    feature_angle: Option<f64>,
    features: Option<EdgeAttr<bool>>,
    pinned: Option<VertexAttr<bool>>,
});

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
#[non_exhaustive]
pub struct FairReport {
    /// Vertices that moved: solved for, or spread along a sliding line.
    pub moved: usize,
    /// Vertices kept in place that entered the system as boundary
    /// conditions (the fixed rings, pinned vertices, line corners).
    pub fixed: usize,
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
/// not in the mesh; [`Error::AttributeHandle`] for a removed mask, pinned
/// or feature column;
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
    let Movers { solve, slid } = {
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
        let mut free = vec![false; mesh.vertex_slots()];
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
        fixed: solution.constraints,
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

/// The vertices fairing moves.
struct Movers {
    /// Solved for, in slot order.
    solve: Vec<Vid>,
    /// Spread along a sliding line, with their new positions.
    slid: Vec<(Vid, V3)>,
}

/// The whole mesh's movers: the free vertices to solve for (in slot
/// order) and the sliding ones with their spread positions. Unless the
/// boundary is free, the `k − 1` rings around it are held.
fn whole_movers(mesh: &Mesh, p: &[V3], held: &Classifier<'_>, boundary: Keep, k: u32) -> Movers {
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
    Movers { solve, slid }
}

/// Per vertex slot: whether it lies within `k − 1` rings of the boundary
/// (a breadth-first search from the boundary, `k − 1` steps deep).
fn boundary_rings(mesh: &Mesh, k: u32) -> Vec<bool> {
    let mut front: Vec<Vid> = mesh.vids().filter(|&v| mesh.on_boundary(v)).collect();
    let mut near = vec![false; mesh.vertex_slots()];
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
    Ok(Movers { solve, slid })
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

#[cfg(test)]
mod tests {
    use super::*;

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
                if !super::super::sparse::AVAILABLE {
                    continue;
                }
                let report = fair(&mut whole, &options, Progress::none()).unwrap();
                assert_eq!(report.moved, free.len());
                assert_eq!(report.fixed, local.constraints);
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
