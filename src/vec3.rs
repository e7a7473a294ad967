//! Small vector maths on `[f64; 3]`: the one place where the algorithms,
//! the operators, the shapes and the readers get sums, dot and cross
//! products, lengths, unit vectors and Newell normals.
//!
//! Plain functions on arrays rather than a vector type, because positions
//! are stored as `[f64; 3]` and every caller already holds one. Each
//! function is written in one fixed order of operations, so a result is the
//! same bit for bit wherever it is computed (tests compare exact outputs):
//! `cross(a, b)` is `(a₁b₂ − a₂b₁, a₂b₀ − a₀b₂, a₀b₁ − a₁b₀)`, `dot` sums
//! `x`, `y`, `z` in that order, and `norm` is the square root of `dot(a, a)`.
//!
//! Two ways to make a vector unit length, because callers rely on either:
//! [`normalize`] and [`normalize_or_zero`] divide each component by the
//! length; [`normalize_or_zero_recip`] multiplies by its reciprocal (one
//! division instead of three, and within an ulp or so of the former), which
//! the normals' inner loops use. None of them divides by a zero, infinite or
//! NaN length: [`normalize`] says `None`, the others give the zero vector.
//!
//! This module imports nothing from the crate, so any layer may use it.

/// A point or a vector.
pub(crate) type V3 = [f64; 3];

/// `a + b`.
#[inline(always)]
pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a − b`.
#[inline(always)]
pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The componentwise minimum (a NaN component gives way to the other).
#[inline(always)]
pub(crate) fn min(a: V3, b: V3) -> V3 {
    [a[0].min(b[0]), a[1].min(b[1]), a[2].min(b[2])]
}

/// The componentwise maximum (a NaN component gives way to the other).
#[inline(always)]
pub(crate) fn max(a: V3, b: V3) -> V3 {
    [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])]
}

/// `a · s`, component by component.
#[inline(always)]
pub(crate) fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `a + s · d`.
#[inline(always)]
pub(crate) fn axpy(a: V3, s: f64, d: V3) -> V3 {
    [a[0] + s * d[0], a[1] + s * d[1], a[2] + s * d[2]]
}

/// `acc += v · w`, in place.
#[inline(always)]
pub(crate) fn add_scaled(acc: &mut V3, v: V3, w: f64) {
    acc[0] += v[0] * w;
    acc[1] += v[1] * w;
    acc[2] += v[2] * w;
}

/// The dot product `a₀b₀ + a₁b₁ + a₂b₂`, summed in that order.
#[inline(always)]
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The cross product `a × b` (right-handed: `x × y = z`).
#[inline(always)]
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The squared length, `dot(a, a)`.
#[inline(always)]
pub(crate) fn norm2(a: V3) -> f64 {
    dot(a, a)
}

/// The length, the square root of `dot(a, a)` (no guard against overflow:
/// a component beyond about 1e154 gives infinity).
#[inline(always)]
pub(crate) fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// The squared distance between two points, `norm2(a − b)`.
#[inline(always)]
pub(crate) fn dist2(a: V3, b: V3) -> f64 {
    let d = sub(a, b);
    dot(d, d)
}

/// `a / |a|` (each component divided by the length), or `None` when the
/// length is zero, infinite or NaN.
#[inline(always)]
pub(crate) fn normalize(a: V3) -> Option<V3> {
    let l = norm(a);
    if l > 0.0 && l.is_finite() {
        Some([a[0] / l, a[1] / l, a[2] / l])
    } else {
        None
    }
}

/// `a / |a|` as [`normalize`] computes it, or the zero vector when the
/// length is zero, infinite or NaN.
#[inline(always)]
pub(crate) fn normalize_or_zero(a: V3) -> V3 {
    normalize(a).unwrap_or([0.0; 3])
}

/// `a · (1 / |a|)`: one division and three multiplications, within an ulp
/// or so of [`normalize_or_zero`] (not bit-identical to it); the zero vector
/// when the length is zero, infinite or NaN.
#[inline(always)]
pub(crate) fn normalize_or_zero_recip(a: V3) -> V3 {
    let l = norm(a);
    if l > 0.0 && l.is_finite() {
        let inv = 1.0 / l;
        [a[0] * inv, a[1] * inv, a[2] * inv]
    } else {
        [0.0; 3]
    }
}

/// The angle between `a` and `b`, in `[0, π]`, as `atan2(|a × b|, a · b)`
/// (accurate for near-parallel vectors, where `acos` is not); 0 when either
/// is zero.
#[inline(always)]
pub(crate) fn angle(a: V3, b: V3) -> f64 {
    norm(cross(a, b)).atan2(dot(a, b))
}

/// Adds the edge `a → b` of a closed polygon to `n`, its Newell normal:
/// summed over every edge, `n` is twice the polygon's vector area (exact for
/// a planar polygon, and a good average normal for a bent one).
#[inline(always)]
pub(crate) fn newell_edge(n: &mut V3, a: V3, b: V3) {
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
}

/// The Newell normal of the closed polygon `points` (the last joined back to
/// the first): twice its vector area, the zero vector for fewer than three
/// points.
pub(crate) fn newell(points: &[V3]) -> V3 {
    let mut n = [0.0; 3];
    for i in 0..points.len() {
        newell_edge(&mut n, points[i], points[(i + 1) % points.len()]);
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;

    const X: V3 = [1.0, 0.0, 0.0];
    const Y: V3 = [0.0, 1.0, 0.0];
    const Z: V3 = [0.0, 0.0, 1.0];

    #[test]
    fn cross_of_unit_axes_is_right_handed() {
        assert_eq!(cross(X, Y), Z);
        assert_eq!(cross(Y, Z), X);
        assert_eq!(cross(Z, X), Y);
        assert_eq!(cross(Y, X), [0.0, 0.0, -1.0]);
        assert_eq!(cross(X, X), [0.0; 3]);
    }

    #[test]
    fn cross_is_orthogonal_and_keeps_its_component_order() {
        let (a, b) = ([1.5, -2.0, 0.25], [0.5, 3.0, -4.0]);
        let c = cross(a, b);
        assert_eq!(
            c,
            [
                -2.0 * -4.0 - 0.25 * 3.0,
                0.25 * 0.5 - 1.5 * -4.0,
                1.5 * 3.0 - -2.0 * 0.5
            ]
        );
        assert_eq!(dot(c, a), 0.0);
        assert_eq!(dot(c, b), 0.0);
    }

    #[test]
    fn sums_products_and_lengths() {
        let (a, b) = ([1.0, 2.0, 3.0], [4.0, -5.0, 6.0]);
        assert_eq!(add(a, b), [5.0, -3.0, 9.0]);
        assert_eq!(sub(a, b), [-3.0, 7.0, -3.0]);
        assert_eq!(scale(a, 2.0), [2.0, 4.0, 6.0]);
        assert_eq!(axpy(a, 2.0, b), [9.0, -8.0, 15.0]);
        let mut acc = a;
        add_scaled(&mut acc, b, 0.5);
        assert_eq!(acc, [3.0, -0.5, 6.0]);
        assert_eq!(dot(a, b), 12.0);
        assert_eq!(norm2([2.0, 3.0, 6.0]), 49.0);
        assert_eq!(norm([2.0, 3.0, 6.0]), 7.0);
        assert_eq!(dist2(a, b), 9.0 + 49.0 + 9.0);
    }

    #[test]
    fn normalize_gives_unit_vectors_and_refuses_zero_and_non_finite() {
        assert_eq!(normalize([0.0, 3.0, 4.0]), Some([0.0, 0.6, 0.8]));
        assert_eq!(normalize_or_zero([0.0, 0.0, -2.0]), [0.0, 0.0, -1.0]);
        let r = normalize_or_zero_recip([1.0, 1.0, 1.0]);
        assert!((norm(r) - 1.0).abs() < 1e-15);
        for bad in [[0.0; 3], [f64::NAN, 0.0, 0.0], [f64::INFINITY, 1.0, 0.0]] {
            assert_eq!(normalize(bad), None);
            assert_eq!(normalize_or_zero(bad), [0.0; 3]);
            assert_eq!(normalize_or_zero_recip(bad), [0.0; 3]);
        }
        // A length that overflows when squared is refused too.
        assert_eq!(normalize([1e200, 0.0, 0.0]), None);
    }

    #[test]
    fn angles() {
        assert_eq!(angle(X, X), 0.0);
        assert_eq!(angle(X, Y), std::f64::consts::FRAC_PI_2);
        assert_eq!(angle(X, [-2.0, 0.0, 0.0]), std::f64::consts::PI);
        assert_eq!(angle([0.0; 3], Y), 0.0);
    }

    #[test]
    fn newell_is_twice_the_vector_area() {
        // The unit square in the xy-plane, counter-clockwise seen from +z.
        let square = [[0.0, 0.0, 0.0], X, [1.0, 1.0, 0.0], Y];
        assert_eq!(newell(&square), [0.0, 0.0, 2.0]);
        let mut reversed = square;
        reversed.reverse();
        assert_eq!(newell(&reversed), [0.0, 0.0, -2.0]);
        assert_eq!(newell(&[X, Y]), [0.0; 3]);
        assert_eq!(newell(&[]), [0.0; 3]);
    }
}
