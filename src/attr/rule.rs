//! The merge/split rule trait and the linear-value trait interpolation needs.

/// What happens to an attribute value when elements merge or split.
///
/// Every topological operation runs the rules of every column itself; user
/// code never calls them by hand. Contributors always arrive in a
/// deterministic order fixed by the operation (its docs say which), and an
/// absent value is passed as `None` so a rule can tell "no value" from any
/// value.
///
/// Implement this on a zero-sized type to write a new rule, then name it in
/// [`Attribute::Rule`](crate::attr::Attribute) or pass it when adding a
/// column.
pub trait Rule<T>: 'static {
    /// Several elements become one (collapse: two vertices; remove edge or
    /// merge faces: two faces; remove vertex: a ring of faces). `inputs` are
    /// `(value, weight)` pairs; the weights are non-negative and sum to 1
    /// (collapse passes the position parameter, merges of faces pass equal
    /// weights).
    fn merge(inputs: &[(Option<&T>, f64)]) -> Option<T>;

    /// A new element is made from existing ones that remain (the vertex of
    /// `split_edge` from both ends at parameter `t`, the centre of
    /// `poke_face` from the corners). Defaults to [`merge`](Rule::merge);
    /// conserved quantities override it so the new element takes nothing.
    fn interpolate(inputs: &[(Option<&T>, f64)]) -> Option<T> {
        Self::merge(inputs)
    }

    /// One piece of an element that splits in several (the two halves of a
    /// split edge, the faces of a split face). `share` is the piece's portion
    /// of the source, in `[0, 1]`; the shares of all pieces sum to 1.
    fn split(source: Option<&T>, share: f64) -> Option<T>;
}

/// Values that can be scaled and added: what interpolation and conserved
/// sums need. Implemented for `f32`, `f64` and fixed-size arrays of them.
pub trait Linear: Clone {
    /// The additive identity.
    fn zero() -> Self;
    /// `self += other * w`.
    fn add_scaled(&mut self, other: &Self, w: f64);
    /// `self * w`.
    fn scaled(&self, w: f64) -> Self {
        let mut out = Self::zero();
        out.add_scaled(self, w);
        out
    }
}

impl Linear for f64 {
    #[inline]
    fn zero() -> Self {
        0.0
    }
    #[inline]
    fn add_scaled(&mut self, other: &Self, w: f64) {
        *self += other * w;
    }
}

impl Linear for f32 {
    #[inline]
    fn zero() -> Self {
        0.0
    }
    #[inline]
    fn add_scaled(&mut self, other: &Self, w: f64) {
        *self += (f64::from(*other) * w) as f32;
    }
}

impl<T: Linear + Copy, const N: usize> Linear for [T; N] {
    #[inline]
    fn zero() -> Self {
        [T::zero(); N]
    }
    #[inline]
    fn add_scaled(&mut self, other: &Self, w: f64) {
        for (a, b) in self.iter_mut().zip(other) {
            a.add_scaled(b, w);
        }
    }
}

/// Interpolate: the weighted mean of the present values (weights
/// renormalised over them; an unweighted mean if their weights are all
/// zero); a split piece keeps the source value. Positions, UVs, colours,
/// normals.
#[derive(Copy, Clone, Debug, Default)]
pub struct Interpolate;

impl<T: Linear> Rule<T> for Interpolate {
    fn merge(inputs: &[(Option<&T>, f64)]) -> Option<T> {
        let total: f64 = inputs
            .iter()
            .filter(|(v, _)| v.is_some())
            .map(|(_, w)| *w)
            .sum();
        let present = inputs.iter().filter(|(v, _)| v.is_some()).count();
        if present == 0 {
            return None;
        }
        let mut out = T::zero();
        for (v, w) in inputs {
            if let Some(v) = v {
                let w = if total > 0.0 {
                    *w / total
                } else {
                    1.0 / present as f64
                };
                out.add_scaled(v, w);
            }
        }
        Some(out)
    }

    fn split(source: Option<&T>, _share: f64) -> Option<T> {
        source.cloned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolate_renormalises_over_present_values() {
        let a = [0.0, 0.0, 0.0];
        let b = [2.0, 4.0, 6.0];
        let m = <Interpolate as Rule<[f64; 3]>>::merge(&[(Some(&a), 0.25), (Some(&b), 0.75)]);
        assert_eq!(m, Some([1.5, 3.0, 4.5]));
        let m = <Interpolate as Rule<[f64; 3]>>::merge(&[(None, 0.5), (Some(&b), 0.5)]);
        assert_eq!(m, Some(b));
        let m = <Interpolate as Rule<[f64; 3]>>::merge(&[(Some(&a), 0.0), (Some(&b), 0.0)]);
        assert_eq!(m, Some([1.0, 2.0, 3.0]));
        assert_eq!(<Interpolate as Rule<f64>>::merge(&[(None, 1.0)]), None);
    }
}
