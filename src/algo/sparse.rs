//! Sparse symmetric positive definite solves for the algorithms (implicit
//! smoothing, fairing): faer's sparse Cholesky factorisation (`L Lᵀ`, an
//! approximate-minimum-degree ordering, supernodal or simplicial as faer
//! chooses by the matrix), one factorisation for the three coordinate
//! columns. Crate-internal: the public API speaks in meshes, not in faer's
//! types, so faer's version is not part of meshloom's.
//!
//! faer comes with the `sparse` feature (on by default). It is a feature
//! because it is large: 48 crates more than the rest of the library
//! (faer, gemm and its kernels, pulp, ...). Without it, [`solve_spd`]
//! refuses and the algorithms that need it say so
//! ([`Error::Unsuitable`](crate::Error::Unsuitable)).

#[cfg(feature = "sparse")]
use faer::linalg::solvers::Solve;
#[cfg(feature = "sparse")]
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
#[cfg(feature = "sparse")]
use faer::{Mat, Side};

use crate::vec3::V3;

/// The lower triangle of a symmetric matrix in compressed columns, built
/// one column at a time with rows in increasing order (diagonal first).
#[derive(Debug, Default)]
pub(crate) struct LowerCsc {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    val: Vec<f64>,
}

impl LowerCsc {
    /// An empty matrix, with room for `n` columns and `nnz` entries.
    pub(crate) fn with_capacity(n: usize, nnz: usize) -> LowerCsc {
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        LowerCsc {
            col_ptr,
            row_idx: Vec::with_capacity(nnz),
            val: Vec::with_capacity(nnz),
        }
    }

    /// Entry `(row, current column)`; rows must increase within a column
    /// and be at least the column.
    #[inline]
    pub(crate) fn push(&mut self, row: usize, value: f64) {
        self.row_idx.push(row);
        self.val.push(value);
    }

    /// Close the current column.
    #[inline]
    pub(crate) fn end_column(&mut self) {
        self.col_ptr.push(self.row_idx.len());
    }

    /// The number of closed columns.
    #[cfg_attr(not(feature = "sparse"), allow(dead_code))]
    pub(crate) fn columns(&self) -> usize {
        self.col_ptr.len() - 1
    }
}

/// Whether sparse solves are compiled in (the `sparse` feature).
pub(crate) const AVAILABLE: bool = cfg!(feature = "sparse");

/// Why solves are not available, for [`Error::Unsuitable`](crate::Error::Unsuitable).
pub(crate) const UNAVAILABLE: &str =
    "needs meshloom's `sparse` feature (faer's sparse Cholesky), which this build leaves out";

/// Why a solve failed.
#[derive(Debug)]
pub(crate) enum SolveError {
    /// The `sparse` feature is off.
    #[cfg_attr(feature = "sparse", allow(dead_code))]
    Unavailable,
    /// The factorisation met a non-positive pivot.
    #[cfg_attr(not(feature = "sparse"), allow(dead_code))]
    NotPositiveDefinite,
    /// faer refused (out of memory, index overflow).
    #[cfg_attr(not(feature = "sparse"), allow(dead_code))]
    Other(String),
}

impl std::fmt::Display for SolveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolveError::NotPositiveDefinite => {
                write!(f, "the system matrix is not positive definite")
            }
            SolveError::Other(s) => write!(f, "sparse Cholesky factorisation failed: {s}"),
            SolveError::Unavailable => f.write_str(UNAVAILABLE),
        }
    }
}

/// Without the `sparse` feature: always [`SolveError::Unavailable`].
#[cfg(not(feature = "sparse"))]
pub(crate) fn solve_spd(_a: &LowerCsc, _rhs: &mut [V3]) -> Result<(), SolveError> {
    Err(SolveError::Unavailable)
}

/// Solve `A X = B` in place for the three columns of `rhs` (one row per
/// column of `a`). `a` must be square with `rhs.len()` columns.
#[cfg(feature = "sparse")]
pub(crate) fn solve_spd(a: &LowerCsc, rhs: &mut [V3]) -> Result<(), SolveError> {
    let n = a.columns();
    debug_assert_eq!(n, rhs.len());
    if n == 0 {
        return Ok(());
    }
    let symbolic = SymbolicSparseColMatRef::new_checked(n, n, &a.col_ptr, None, &a.row_idx);
    let mat = SparseColMatRef::new(symbolic, &a.val);
    let llt = mat.sp_cholesky(Side::Lower).map_err(|e| match e {
        faer::sparse::linalg::LltError::Numeric(_) => SolveError::NotPositiveDefinite,
        other => SolveError::Other(format!("{other:?}")),
    })?;
    let mut b = Mat::<f64>::from_fn(n, 3, |i, j| rhs[i][j]);
    llt.solve_in_place(b.as_mut());
    for (i, r) in rhs.iter_mut().enumerate() {
        *r = [b[(i, 0)], b[(i, 1)], b[(i, 2)]];
    }
    Ok(())
}

#[cfg(all(test, feature = "sparse"))]
mod tests {
    use super::*;

    #[test]
    fn solves_a_small_spd_system() {
        // [4 1 0; 1 3 1; 0 1 2] x = b
        let mut a = LowerCsc::with_capacity(3, 5);
        a.push(0, 4.0);
        a.push(1, 1.0);
        a.end_column();
        a.push(1, 3.0);
        a.push(2, 1.0);
        a.end_column();
        a.push(2, 2.0);
        a.end_column();
        let x = [[1.0, 2.0, 3.0], [-1.0, 0.5, 0.0], [2.0, 0.0, 1.0]];
        let mut b = [[0.0; 3]; 3];
        for k in 0..3 {
            b[0][k] = 4.0 * x[0][k] + x[1][k];
            b[1][k] = x[0][k] + 3.0 * x[1][k] + x[2][k];
            b[2][k] = x[1][k] + 2.0 * x[2][k];
        }
        solve_spd(&a, &mut b).unwrap();
        for i in 0..3 {
            for k in 0..3 {
                assert!((b[i][k] - x[i][k]).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn refuses_an_indefinite_matrix() {
        let mut a = LowerCsc::with_capacity(2, 3);
        a.push(0, 1.0);
        a.push(1, 2.0);
        a.end_column();
        a.push(1, 1.0);
        a.end_column();
        let mut b = [[1.0; 3]; 2];
        assert!(matches!(
            solve_spd(&a, &mut b),
            Err(SolveError::NotPositiveDefinite)
        ));
    }
}
