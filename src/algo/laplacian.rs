//! The discrete Laplace-Beltrami operator and the mass matrix: the building
//! blocks of curvature, smoothing and fairing.
//!
//! - [`laplacian`] builds the sparse symmetric matrix `L` by vertex slot,
//!   with `(L x)_i = Σ_j w_ij (x_j − x_i)` (negative semi-definite, the sign
//!   of pmp-library and libigl). Weights are [`LaplaceWeights::Cotan`]
//!   (`w_ij = ½ (cot α_ij + cot β_ij)`, the angles opposite edge `ij` in its
//!   two faces) or [`LaplaceWeights::Uniform`] (`w_ij = 1` per edge).
//! - [`mass_matrix`] gives the lumped (diagonal) mass matrix: each vertex's
//!   *mixed Voronoi area* (Meyer, Desbrun, Schröder, Barr 2003): the Voronoi
//!   area of its corner in a non-obtuse triangle, half the triangle's area
//!   at an obtuse corner and a quarter at the other two corners of an obtuse
//!   triangle. The areas add up to the surface area exactly.
//!
//! **Polygons** are refined by a virtual vertex at their centroid into a fan
//! of triangles, whose cotangent matrix is reduced back onto the polygon's
//! corners (`Pᵀ L_fan P`, with `P` the centroid's weights `1/n`), as in
//! Bunge, Herholz, Kazhdan and Botsch, "Polygon Laplacian made simple"
//! (2020), who place the virtual vertex where the squared fan areas are
//! smallest; the centroid is the same point for planar regular polygons and
//! costs no solve. A polygon couples all its corners, not only the ends of
//! its edges. The virtual vertex's area is shared equally by the corners.
//!
//! **Degenerate faces.** A triangle whose doubled area is at most
//! `1e-14 · (sum of its squared edge lengths)`, or not finite, adds no
//! weight and no area; other cotangents are clamped to `±1e6` (an angle of
//! about 1e-6 rad). So every weight and area is finite; a vertex whose
//! faces are all degenerate has an empty row and zero area, and the
//! algorithms built on these matrices keep it where it is.
//!
//! **Clamping.** With [`LaplacianOptions::clamp_negative`] (the default), a
//! negative cotangent weight (two obtuse angles opposite one edge) becomes
//! zero, as pmp-library's smoothing and fairing do: the matrix is then an
//! M-matrix and explicit smoothing with it is a convex combination.
//!
//! ```
//! use meshloom::algo::laplacian::{laplacian, mass_matrix, LaplacianOptions};
//! let mesh = meshloom::shapes::icosphere(2);
//! let l = laplacian(&mesh, &LaplacianOptions::default())?;
//! let m = mass_matrix(&mesh)?;
//! // Rows sum to zero; the areas sum to the surface area.
//! let v = mesh.vertices().next().unwrap().index();
//! let row: f64 = l.row(v).map(|(_, w)| w).sum::<f64>() + l.diagonal(v);
//! assert!(row.abs() < 1e-12);
//! assert!(m.iter().sum::<f64>() > 12.0 && m.iter().sum::<f64>() < 4.0 * std::f64::consts::PI);
//! # Ok::<(), meshloom::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::layout::{Fid, Hid, IdVec, Vid};
use crate::mesh::Mesh;
use crate::vec3::{add_scaled, cross, dot, norm, sub, V3};

/// A triangle is degenerate when its doubled area is at most this times the
/// sum of its squared edge lengths.
const DEGENERATE: f64 = 1e-14;
/// Cotangents are clamped to this magnitude.
const MAX_COT: f64 = 1e6;

/// The cotangent quantities of one triangle `(p0, p1, p2)`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Triangle {
    /// Half the cotangent of the angle at each corner (0 if degenerate).
    pub(crate) half_cot: [f64; 3],
    /// The mixed Voronoi area of each corner (0 if degenerate).
    pub(crate) area: [f64; 3],
}

/// Cotangents and mixed areas of a triangle, with the dot products of the
/// two edges at each corner and the doubled area (for angles).
#[inline(always)]
pub(crate) fn triangle(p: [V3; 3]) -> (Triangle, [f64; 3], f64) {
    let e = [sub(p[1], p[0]), sub(p[2], p[1]), sub(p[0], p[2])];
    let l2 = [dot(e[0], e[0]), dot(e[1], e[1]), dot(e[2], e[2])];
    // Corner i lies between edge i (leaving it) and edge i + 2 (entering).
    let d = [-dot(e[0], e[2]), -dot(e[1], e[0]), -dot(e[2], e[1])];
    let twice = norm(cross(e[0], e[1]));
    let mut t = Triangle::default();
    if !(twice > DEGENERATE * (l2[0] + l2[1] + l2[2]) && twice.is_finite()) {
        return (t, d, twice);
    }
    let inv = 1.0 / twice;
    let cot = d.map(|d| (d * inv).clamp(-MAX_COT, MAX_COT));
    t.half_cot = cot.map(|c| 0.5 * c);
    let area = 0.5 * twice;
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        t.area[i] = if d[i] < 0.0 {
            0.5 * area
        } else if d[j] < 0.0 || d[k] < 0.0 {
            0.25 * area
        } else {
            // |p_i p_j|² cot(k) + |p_i p_k|² cot(j), over 8.
            0.125 * (l2[i] * cot[k] + l2[k] * cot[j])
        };
    }
    (t, d, twice)
}

/// The pairwise weights and corner areas of a polygon (more than three
/// corners), refined at its centroid (see the module docs). `pairs` gets
/// `(k, m, w)` for `k < m`, `area` one entry per corner.
pub(crate) fn polygon(p: &[V3], pairs: &mut Vec<(usize, usize, f64)>, area: &mut Vec<f64>) {
    let n = p.len();
    let inv_n = 1.0 / n as f64;
    let mut c = [0.0; 3];
    for q in p {
        add_scaled(&mut c, *q, inv_n);
    }
    pairs.clear();
    area.clear();
    area.resize(n, 0.0);
    // Fan triangle k = (p_k, p_k+1, c): edge weight, and the weights of the
    // spokes to the centre.
    let mut spoke = vec![0.0; n];
    let mut edge = vec![0.0; n];
    let mut centre_area = 0.0;
    for k in 0..n {
        let k1 = (k + 1) % n;
        let (t, _, _) = triangle([p[k], p[k1], c]);
        edge[k] += t.half_cot[2];
        spoke[k1] += t.half_cot[0];
        spoke[k] += t.half_cot[1];
        area[k] += t.area[0];
        area[k1] += t.area[1];
        centre_area += t.area[2];
    }
    // Eliminating the centre x_c = Σ x_m / n: the spoke energy
    // Σ u_k (x_k − x_c)² is Σ_{k<m} ((u_k + u_m)/n − U/n²) (x_k − x_m)².
    let total: f64 = spoke.iter().sum();
    for k in 0..n {
        for m in k + 1..n {
            let mut w = (spoke[k] + spoke[m]) * inv_n - total * inv_n * inv_n;
            if m == k + 1 {
                w += edge[k];
            }
            if k == 0 && m == n - 1 {
                w += edge[m];
            }
            pairs.push((k, m, w));
        }
    }
    for a in area.iter_mut() {
        *a += centre_area * inv_n;
    }
}

/// The live faces (not holes) and one half-edge of each.
#[inline]
pub(crate) fn live_faces(mesh: &Mesh) -> impl Iterator<Item = (Fid, Hid)> + '_ {
    let n = mesh.face_slots();
    (0..n).filter_map(move |i| {
        let f = Fid::new(i as u32);
        let link = mesh.face_link(f);
        (!link.is_hole() && mesh.face_live(i)).then(|| (f, link.halfedge()))
    })
}

/// The triangle through `h0`, if its face is one: its half-edges.
#[inline(always)]
pub(crate) fn as_triangle(mesh: &Mesh, h0: Hid) -> Option<[Hid; 3]> {
    let h1 = mesh.next(h0);
    let h2 = mesh.next(h1);
    (mesh.next(h2) == h0).then_some([h0, h1, h2])
}

/// The positions, or [`Error::NoPositions`].
pub(crate) fn positions(mesh: &Mesh) -> Result<&[V3]> {
    mesh.position_slots().ok_or(Error::NoPositions)
}

/// The weights of [`laplacian`].
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum LaplaceWeights {
    /// `½ (cot α + cot β)`: the discrete Laplace-Beltrami operator
    /// (default).
    #[default]
    Cotan,
    /// `1` per edge: the graph Laplacian (depends on the connectivity only).
    Uniform,
}

crate::choice::choices!(LaplaceWeights {
    Cotan = "cotan",
    Uniform = "uniform",
});

/// Options of [`laplacian`].
#[derive(Copy, Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct LaplacianOptions {
    /// Cotangent (default) or uniform weights.
    pub weights: LaplaceWeights,
    /// Negative off-diagonal weights become zero (default `true`).
    pub clamp_negative: bool,
}

crate::choice::setters!(LaplacianOptions {
    weights: LaplaceWeights,
    clamp_negative: bool,
});

impl Default for LaplacianOptions {
    fn default() -> Self {
        LaplacianOptions {
            weights: LaplaceWeights::Cotan,
            clamp_negative: true,
        }
    }
}

/// A sparse symmetric Laplacian by vertex slot: for each row the
/// off-diagonal entries, sorted by column, and the diagonal `−Σ_j w_ij`.
/// Vacant slots have empty rows.
#[derive(Clone, Debug, PartialEq)]
pub struct Laplacian {
    offsets: Vec<usize>,
    cols: Vec<u32>,
    weights: Vec<f64>,
    diagonal: Vec<f64>,
}

impl Laplacian {
    /// The number of rows (vertex slots).
    pub fn len(&self) -> usize {
        self.diagonal.len()
    }

    /// Whether there are no rows.
    pub fn is_empty(&self) -> bool {
        self.diagonal.is_empty()
    }

    /// Row `i`'s off-diagonal entries `(column, w_ij)`, by column; empty
    /// past the end.
    pub fn row(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let r = self.range(i);
        self.cols[r.clone()]
            .iter()
            .zip(&self.weights[r])
            .map(|(&c, &w)| (c as usize, w))
    }

    /// The diagonal entry of row `i` (`−Σ_j w_ij`; 0 past the end).
    pub fn diagonal(&self, i: usize) -> f64 {
        self.diagonal.get(i).copied().unwrap_or(0.0)
    }

    /// The number of off-diagonal entries.
    pub fn off_diagonal_count(&self) -> usize {
        self.cols.len()
    }

    #[inline]
    fn range(&self, i: usize) -> std::ops::Range<usize> {
        if i + 1 < self.offsets.len() {
            self.offsets[i]..self.offsets[i + 1]
        } else {
            0..0
        }
    }

    /// Row `i` as raw slices (columns, weights).
    #[inline]
    pub(crate) fn row_raw(&self, i: usize) -> (&[u32], &[f64]) {
        let r = self.range(i);
        (&self.cols[r.clone()], &self.weights[r])
    }

    /// `L x` for `x` indexed by vertex slot: `Σ_j w_ij (x_j − x_i)`.
    ///
    /// # Panics
    /// If `x` is shorter than [`len`](Self::len).
    pub fn apply(&self, x: &[V3]) -> Vec<V3> {
        (0..self.len())
            .map(|i| {
                let (cols, ws) = self.row_raw(i);
                let mut s = [0.0; 3];
                for (&c, &w) in cols.iter().zip(ws) {
                    add_scaled(&mut s, sub(x[c as usize], x[i]), w);
                }
                s
            })
            .collect()
    }
}

/// The Laplacian of `mesh` (see the module docs).
///
/// # Errors
/// [`Error::NoPositions`] for cotangent weights on a topology-only mesh.
///
/// # Complexity
/// O(corners + Σ row length · log): one face pass, one vertex pass.
///
/// ```
/// use meshloom::algo::laplacian::{laplacian, LaplaceWeights, LaplacianOptions};
/// let grid = meshloom::shapes::grid(3, 3, meshloom::shapes::GridFaces::Triangles);
/// let opts = LaplacianOptions::default().weights(LaplaceWeights::Uniform);
/// let l = laplacian(&grid, &opts)?;
/// // A uniform row holds one entry per neighbour.
/// let v = grid.vertices().next().unwrap();
/// assert_eq!(l.row(v.index()).count(), grid.vertex(v)?.neighbors().count());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn laplacian(mesh: &Mesh, options: &LaplacianOptions) -> Result<Laplacian> {
    match options.weights {
        LaplaceWeights::Uniform => Ok(laplacian_at(mesh, &[], options)),
        LaplaceWeights::Cotan => Ok(laplacian_at(mesh, positions(mesh)?, options)),
    }
}

/// [`laplacian`] with positions `p` by vertex slot (unused for uniform
/// weights).
pub(crate) fn laplacian_at(mesh: &Mesh, p: &[V3], options: &LaplacianOptions) -> Laplacian {
    // Per half-edge: its share of its edge's weight. Polygons add pairs of
    // corners that share no edge.
    let nh = mesh.halfedge_slots();
    let mut hw: IdVec<Hid, f64> = IdVec::filled(0.0, nh);
    let mut extra: Vec<(u32, u32, f64)> = Vec::new();
    match options.weights {
        LaplaceWeights::Uniform => {
            for h in mesh.hids() {
                hw[h] = 0.5;
            }
        }
        LaplaceWeights::Cotan => {
            let mut ring: Vec<Hid> = Vec::new();
            let mut ps: Vec<V3> = Vec::new();
            let (mut pairs, mut area) = (Vec::new(), Vec::new());
            for (_, h0) in live_faces(mesh) {
                if let Some(hs) = as_triangle(mesh, h0) {
                    let v = hs.map(|h| mesh.origin(h));
                    let (t, _, _) = triangle(v.map(|v| p[v.index()]));
                    // Half-edge k runs from corner k to k + 1; the corner
                    // opposite is k + 2.
                    hw[hs[0]] = t.half_cot[2];
                    hw[hs[1]] = t.half_cot[0];
                    hw[hs[2]] = t.half_cot[1];
                    continue;
                }
                ring.clear();
                ring.extend(mesh.face_halfedges_from(h0));
                ps.clear();
                ps.extend(ring.iter().map(|&h| p[mesh.origin(h).index()]));
                polygon(&ps, &mut pairs, &mut area);
                let n = ring.len();
                for &(k, m, w) in &pairs {
                    if m == k + 1 {
                        hw[ring[k]] += w;
                    } else if k == 0 && m == n - 1 {
                        hw[ring[m]] += w;
                    } else {
                        let (a, b) = (mesh.origin(ring[k]), mesh.origin(ring[m]));
                        extra.push((a.raw(), b.raw(), w));
                    }
                }
            }
        }
    }
    assemble(mesh, &hw, &extra, options.clamp_negative)
}

/// Rows from half-edge weights (`w_ij = hw[h] + hw[twin h]`) and extra
/// symmetric pairs.
fn assemble(
    mesh: &Mesh,
    hw: &IdVec<Hid, f64>,
    extra: &[(u32, u32, f64)],
    clamp: bool,
) -> Laplacian {
    let nv = mesh.vertex_slots();
    let mut offsets = Vec::with_capacity(nv + 1);
    let mut cols: Vec<u32> = Vec::with_capacity(mesh.halfedge_slots() + 2 * extra.len());
    let mut weights: Vec<f64> = Vec::with_capacity(cols.capacity());
    let mut diagonal = Vec::with_capacity(nv);
    // Extra pairs by row (both directions).
    let mut extra_rows: Vec<Vec<(u32, f64)>> = Vec::new();
    if !extra.is_empty() {
        extra_rows.resize(nv, Vec::new());
        for &(a, b, w) in extra {
            extra_rows[a as usize].push((b, w));
            extra_rows[b as usize].push((a, w));
        }
    }
    let mut row: Vec<(u32, f64)> = Vec::with_capacity(16);
    offsets.push(0);
    for i in 0..nv {
        let v = Vid::new(i as u32);
        row.clear();
        if mesh.vertex_live(i) {
            for h in mesh.outgoing(v) {
                let t = h.twin();
                row.push((mesh.origin(t).raw(), hw[h] + hw[t]));
            }
            if let Some(e) = extra_rows.get(i) {
                row.extend_from_slice(e);
            }
        }
        // Sort by column (rows are short: insertion sort), merge repeats.
        for k in 1..row.len() {
            let mut j = k;
            while j > 0 && row[j - 1].0 > row[j].0 {
                row.swap(j - 1, j);
                j -= 1;
            }
        }
        let start = cols.len();
        let mut sum = 0.0;
        for &(c, w) in &row {
            if cols.len() > start && *cols.last().unwrap_or(&u32::MAX) == c {
                *weights.last_mut().expect("pushed") += w;
            } else {
                cols.push(c);
                weights.push(w);
            }
        }
        for w in &mut weights[start..] {
            if clamp && *w < 0.0 {
                *w = 0.0;
            }
            sum += *w;
        }
        diagonal.push(-sum);
        offsets.push(cols.len());
    }
    Laplacian {
        offsets,
        cols,
        weights,
        diagonal,
    }
}

/// The mixed Voronoi area of every vertex, by vertex slot (vacant slots
/// hold 0): the lumped mass matrix. The areas add up to the surface area.
///
/// # Errors
/// [`Error::NoPositions`].
///
/// # Complexity
/// O(corners).
///
/// ```
/// use meshloom::algo::laplacian::mass_matrix;
/// let grid = meshloom::shapes::grid(4, 4, meshloom::shapes::GridFaces::Quads);
/// let m = mass_matrix(&grid)?;
/// let total: f64 = m.iter().sum();
/// let area: f64 = grid.faces().map(|f| grid.face_area(f).unwrap()).sum();
/// assert!((total - area).abs() < 1e-12);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn mass_matrix(mesh: &Mesh) -> Result<Vec<f64>> {
    Ok(mass_matrix_at(mesh, positions(mesh)?))
}

/// [`mass_matrix`] with positions `p` by vertex slot.
pub(crate) fn mass_matrix_at(mesh: &Mesh, p: &[V3]) -> Vec<f64> {
    let mut m = vec![0.0; mesh.vertex_slots()];
    let mut ps: Vec<V3> = Vec::new();
    let mut vs: Vec<Vid> = Vec::new();
    let (mut pairs, mut area) = (Vec::new(), Vec::new());
    for (_, h0) in live_faces(mesh) {
        if let Some(hs) = as_triangle(mesh, h0) {
            let v = hs.map(|h| mesh.origin(h));
            let (t, _, _) = triangle(v.map(|v| p[v.index()]));
            for k in 0..3 {
                m[v[k].index()] += t.area[k];
            }
            continue;
        }
        vs.clear();
        vs.extend(mesh.face_halfedges_from(h0).map(|h| mesh.origin(h)));
        ps.clear();
        ps.extend(vs.iter().map(|v| p[v.index()]));
        polygon(&ps, &mut pairs, &mut area);
        for (v, a) in vs.iter().zip(&area) {
            m[v.index()] += a;
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{self, GridFaces};

    #[test]
    fn triangle_cotangents_and_areas() {
        // Right isosceles triangle: angles 90, 45, 45.
        let (t, _, twice) = triangle([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert!((twice - 1.0).abs() < 1e-15);
        assert!(t.half_cot[0].abs() < 1e-15);
        assert!((t.half_cot[1] - 0.5).abs() < 1e-15 && (t.half_cot[2] - 0.5).abs() < 1e-15);
        // Not obtuse: Voronoi areas, summing to the area.
        assert!((t.area.iter().sum::<f64>() - 0.5).abs() < 1e-15);
        assert!((t.area[0] - 0.25).abs() < 1e-15);
        // Obtuse at corner 0: half there, a quarter at the others.
        let (t, _, _) = triangle([[0.0, 0.1, 0.0], [-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]);
        assert!((t.area[0] - 0.05).abs() < 1e-15 && (t.area[1] - 0.025).abs() < 1e-15);
        assert!(t.half_cot[0] < 0.0);
    }

    #[test]
    fn degenerate_triangles_add_nothing() {
        for p in [
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
            [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 1e-300, 0.0]],
        ] {
            let (t, _, _) = triangle(p);
            assert_eq!(t.half_cot, [0.0; 3]);
            assert_eq!(t.area, [0.0; 3]);
        }
    }

    #[test]
    fn square_polygon_equals_its_own_refinement() {
        // A unit square: the centre fan's four right isosceles triangles.
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let (mut pairs, mut area) = (Vec::new(), Vec::new());
        polygon(&p, &mut pairs, &mut area);
        assert!(area.iter().all(|a| (a - 0.25).abs() < 1e-15));
        // Rows sum: weights are symmetric and finite; the form is exact on
        // linear functions (a planar polygon reproduces x with zero L x).
        let mut lx = [[0.0; 3]; 4];
        for &(k, m, w) in &pairs {
            add_scaled(&mut lx[k], sub(p[m], p[k]), w);
            add_scaled(&mut lx[m], sub(p[k], p[m]), w);
        }
        // Corners of a square are not interior points: L x is the same
        // vector length at each corner, pointing inwards.
        let l0 = norm(lx[0]);
        assert!(lx.iter().all(|v| (norm(*v) - l0).abs() < 1e-12));
    }

    #[test]
    fn rows_are_symmetric_and_sum_to_zero() {
        let mesh = shapes::grid(5, 4, GridFaces::Quads);
        for weights in [LaplaceWeights::Cotan, LaplaceWeights::Uniform] {
            let l = laplacian(
                &mesh,
                &LaplacianOptions {
                    weights,
                    clamp_negative: true,
                },
            )
            .unwrap();
            for i in 0..l.len() {
                let s: f64 = l.row(i).map(|(_, w)| w).sum();
                assert!((s + l.diagonal(i)).abs() < 1e-12);
                for (j, w) in l.row(i) {
                    let back = l.row(j).find(|&(k, _)| k == i).map(|(_, w)| w);
                    assert_eq!(back, Some(w));
                }
            }
        }
    }

    #[test]
    fn linear_precision_inside_a_flat_grid() {
        // Cotan Laplacian of a planar mesh is zero at interior vertices.
        let mut mesh = shapes::grid(6, 6, GridFaces::Triangles);
        // Perturb interior vertices in the plane.
        let keys: Vec<_> = mesh.vertices().collect();
        for (i, v) in keys.iter().enumerate() {
            if !mesh.vertex(*v).unwrap().is_boundary() {
                let mut p = mesh.position(*v).unwrap();
                p[0] += 0.05 * ((i * 7 % 5) as f64 - 2.0) / 2.0;
                p[1] += 0.05 * ((i * 3 % 5) as f64 - 2.0) / 2.0;
                mesh.set_position(*v, p).unwrap();
            }
        }
        let l = laplacian(
            &mesh,
            &LaplacianOptions {
                clamp_negative: false,
                ..Default::default()
            },
        )
        .unwrap();
        let lx = l.apply(mesh.position_slots().unwrap());
        for v in &keys {
            if !mesh.vertex(*v).unwrap().is_boundary() {
                assert!(norm(lx[v.index()]) < 1e-12, "{:?}", lx[v.index()]);
            }
        }
    }
}
