//! The linear systems of fairing: row products of the `k`-Laplacian
//! (`(−1)^k L (M⁻¹ L)^(k−1)`, over the whole mesh's Laplacian or over the
//! rows of a region and its rings) and the region-local system, solved by
//! a sparse Cholesky factorisation or conjugate gradients.

use std::collections::hash_map::Entry;
use std::collections::HashMap;

use super::super::laplacian::{polygon, triangle, LaplaceWeights, Laplacian};
use super::super::sparse::{solve_spd, LowerCsc, AVAILABLE};
use crate::layout::Vid;
use crate::mesh::Mesh;
use crate::vec3::V3;

/// A symmetric sparse matrix read row by row: the whole mesh's
/// Laplacian, or the region-local rows of [`solve_local`].
pub(super) trait SymmetricRows {
    fn diagonal(&self, m: usize) -> f64;
    fn for_each_off_diagonal(&self, m: usize, f: impl FnMut(u32, f64));
}

impl SymmetricRows for Laplacian {
    #[inline]
    fn diagonal(&self, m: usize) -> f64 {
        Laplacian::diagonal(self, m)
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
pub(super) struct Accumulator {
    value: Vec<f64>,
    seen: Vec<bool>,
    list: Vec<(u32, f64)>,
    scratch: Vec<(u32, f64)>,
}

impl Accumulator {
    pub(super) fn new(n: usize) -> Accumulator {
        Accumulator {
            value: vec![0.0; n],
            seen: vec![false; n],
            list: Vec::new(),
            scratch: Vec::new(),
        }
    }

    /// The unit vector `x e_i`.
    pub(super) fn reset_to(&mut self, i: usize, x: f64) {
        self.list.clear();
        self.list.push((i as u32, x));
    }

    /// Multiply entry-wise by `d`.
    pub(super) fn scale(&mut self, d: &[f64]) {
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
    pub(super) fn apply(&mut self, a: &impl SymmetricRows) {
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

    pub(super) fn entries(&self) -> &[(u32, f64)] {
        &self.list
    }
}

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
                mesh.face_halfedges_from(h)
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
        ring.extend(mesh.face_halfedges_from(h).map(|g| mesh.origin(g)));
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
}
