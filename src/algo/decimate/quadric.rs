//! Quadrics (Garland & Heckbert 1997): `E(x) = xᵀAx + 2bᵀx + c`, stored in
//! `f32` (40 bytes a vertex; the weight is the trace of `A`, so it needs no
//! slot of its own) and computed in `f64`. Positions are scaled into the unit
//! box before they become quadrics, so `f32` keeps about seven digits of the
//! mesh's extent.

use crate::vec3::{dot, V3};

/// `a00 a11 a22 a01 a02 a12 b0 b1 b2 c`.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub(super) struct Quadric(pub(super) [f32; 10]);

/// A quadric in `f64`, for sums and solves.
#[derive(Copy, Clone, Debug, Default)]
pub(super) struct Q64(pub(super) [f64; 10]);

impl Quadric {
    #[inline(always)]
    pub(super) fn wide(self) -> Q64 {
        Q64(self.0.map(f64::from))
    }

    #[inline(always)]
    pub(super) fn add_assign(&mut self, o: &Quadric) {
        for (x, y) in self.0.iter_mut().zip(o.0) {
            *x += y;
        }
    }
}

impl Q64 {
    /// The plane `n·x + d = 0` (`n` a unit normal) with weight `w`.
    #[inline(always)]
    pub(super) fn plane(n: V3, d: f64, w: f64) -> Q64 {
        let [a, b, c] = n;
        Q64([
            w * a * a,
            w * b * b,
            w * c * c,
            w * a * b,
            w * a * c,
            w * b * c,
            w * a * d,
            w * b * d,
            w * c * d,
            w * d * d,
        ])
    }

    #[inline(always)]
    pub(super) fn sum(self, o: Q64) -> Q64 {
        let mut r = self.0;
        for (x, y) in r.iter_mut().zip(o.0) {
            *x += y;
        }
        Q64(r)
    }

    #[inline(always)]
    pub(super) fn narrow(self) -> Quadric {
        Quadric(self.0.map(|x| x as f32))
    }

    /// The total weight (the trace of `A`).
    #[inline(always)]
    pub(super) fn weight(&self) -> f64 {
        self.0[0] + self.0[1] + self.0[2]
    }

    /// `A x`.
    #[inline(always)]
    fn a_mul(&self, x: V3) -> V3 {
        let q = &self.0;
        [
            q[0] * x[0] + q[3] * x[1] + q[4] * x[2],
            q[3] * x[0] + q[1] * x[1] + q[5] * x[2],
            q[4] * x[0] + q[5] * x[1] + q[2] * x[2],
        ]
    }

    /// `E(x)` as computed (the position part of an attribute quadric, which
    /// alone may be of either sign).
    #[inline(always)]
    pub(super) fn eval_signed(&self, x: V3) -> f64 {
        let q = &self.0;
        let b = [q[6], q[7], q[8]];
        dot(x, self.a_mul(x)) + 2.0 * dot(b, x) + q[9]
    }

    /// `E(x)`, never negative (rounding can make it slightly so).
    #[inline(always)]
    pub(super) fn eval(&self, x: V3) -> f64 {
        let q = &self.0;
        let b = [q[6], q[7], q[8]];
        (dot(x, self.a_mul(x)) + 2.0 * dot(b, x) + q[9]).max(0.0)
    }

    /// The minimiser of `E`, if `A` is well conditioned: `A x = −b` by
    /// cofactors, refused when the determinant is tiny against the
    /// weight cubed (a flat or straight neighbourhood: every point of a
    /// plane or line is optimal).
    #[inline(always)]
    pub(super) fn minimiser(&self) -> Option<V3> {
        let q = &self.0;
        let (a00, a11, a22, a01, a02, a12) = (q[0], q[1], q[2], q[3], q[4], q[5]);
        let c00 = a11 * a22 - a12 * a12;
        let c01 = a02 * a12 - a01 * a22;
        let c02 = a01 * a12 - a02 * a11;
        let det = a00 * c00 + a01 * c01 + a02 * c02;
        let w = self.weight();
        if det.is_nan() || det.abs() <= 1e-9 * w * w * w {
            return None;
        }
        let c11 = a00 * a22 - a02 * a02;
        let c12 = a01 * a02 - a00 * a12;
        let c22 = a00 * a11 - a01 * a01;
        let rb = [-q[6], -q[7], -q[8]];
        let inv = 1.0 / det;
        let x = [
            (c00 * rb[0] + c01 * rb[1] + c02 * rb[2]) * inv,
            (c01 * rb[0] + c11 * rb[1] + c12 * rb[2]) * inv,
            (c02 * rb[0] + c12 * rb[1] + c22 * rb[2]) * inv,
        ];
        x.iter().all(|c| c.is_finite()).then_some(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vec3::sub;

    #[test]
    fn three_planes_meet_at_their_corner() {
        let q = Q64::plane([1.0, 0.0, 0.0], -1.0, 1.0)
            .sum(Q64::plane([0.0, 1.0, 0.0], -2.0, 2.0))
            .sum(Q64::plane([0.0, 0.0, 1.0], -3.0, 0.5));
        let x = q.minimiser().unwrap();
        assert!(sub(x, [1.0, 2.0, 3.0]).iter().all(|c| c.abs() < 1e-12));
        assert!(q.eval(x) < 1e-12);
        assert!((q.eval([0.0, 2.0, 3.0]) - 1.0).abs() < 1e-12);
        assert!((q.weight() - 3.5).abs() < 1e-12);
    }

    #[test]
    fn a_plane_alone_is_singular() {
        let q = Q64::plane([0.0, 0.0, 1.0], 0.0, 1.0);
        assert!(q.minimiser().is_none());
        let narrowed = q.narrow().wide();
        assert_eq!(narrowed.0, q.0);
    }
}
