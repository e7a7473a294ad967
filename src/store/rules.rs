//! The stock rules: what each does when elements merge, when a new element
//! is made from others (interpolate), and when one element splits.
//!
//! | rule | merge | interpolate | split piece | for |
//! |---|---|---|---|---|
//! | [`Interpolate`] | weighted mean of present values | same | source value | positions, UVs, colours, normals |
//! | [`Conserved`] | sum of present values | absent | source × share | mass, area, counts |
//! | [`Contagion`] | greatest present value (`true` beats `false`) | same | source value | flags: hole, selection, crease tags |
//! | [`Incompatible`] | the value if all contributors have it and agree, else absent | same | source value | material ids, group labels |
//! | [`KeepFirst`] | first contributor's value (absent if it has none) | same | source value | ids that the surviving element keeps |
//! | [`Discard`] | absent | absent | absent | caches that must be recomputed |
//!
//! "First" is the first contributor in the order the operation passes them,
//! which each operator documents: every merge passes the surviving element
//! first (a collapse the vertex it keeps, a face merge the face it keeps),
//! so every result is deterministic and [`KeepFirst`] keeps the survivor's
//! value.

use super::rule::{Linear, Rule};

/// Interpolate: the weighted mean of the present values (weights
/// renormalised over them; an unweighted mean if their weights are all
/// zero); a split piece keeps the source value; an absent value is inferred
/// as the mean of the present neighbours. Positions, UVs, colours, normals.
///
/// ```
/// use meshloom::attr::{Interpolate, Rule};
/// let m = <Interpolate as Rule<f64>>::merge(&[(Some(&0.0), 0.25), (Some(&4.0), 0.75)]);
/// assert_eq!(m, Some(3.0));
/// // An absent contributor is skipped and the weights renormalised.
/// assert_eq!(<Interpolate as Rule<f64>>::merge(&[(None, 0.5), (Some(&4.0), 0.5)]), Some(4.0));
/// assert_eq!(<Interpolate as Rule<f64>>::split(Some(&4.0), 0.3), Some(4.0));
/// ```
#[derive(Copy, Clone, Debug, Default)]
pub struct Interpolate;

impl<T: Linear> Rule<T> for Interpolate {
    const LINEAR: bool = true;

    fn name() -> &'static str {
        "Interpolate"
    }

    // Inlined into the column's merge and interpolate: left to the
    // compiler's heuristics it was not, after an unrelated change moved it
    // to another codegen unit (+8% instructions in `ErasedColumn::merge`).
    #[inline]
    fn merge(inputs: &[(Option<&T>, f64)]) -> Option<T> {
        let mut total = 0.0;
        let mut present = 0usize;
        for (v, w) in inputs {
            if v.is_some() {
                total += *w;
                present += 1;
            }
        }
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

    fn infer(neighbours: &[(Option<&T>, f64)]) -> Option<T> {
        Self::merge(neighbours)
    }
}

/// Conserved: the total over the mesh stays the same. Merge sums the present
/// values (weights ignored); a split piece gets `source × share` (the
/// shares sum to 1); an element made from others that remain
/// (interpolate) gets nothing, so no quantity is created. Mass, area-like
/// quantities, counts.
///
/// ```
/// use meshloom::attr::{Conserved, Rule};
/// assert_eq!(<Conserved as Rule<f64>>::merge(&[(Some(&1.5), 0.5), (None, 0.0), (Some(&2.0), 0.5)]), Some(3.5));
/// assert_eq!(<Conserved as Rule<f64>>::split(Some(&3.0), 0.25), Some(0.75));
/// assert_eq!(<Conserved as Rule<f64>>::interpolate(&[(Some(&1.0), 0.5), (Some(&1.0), 0.5)]), None);
/// ```
#[derive(Copy, Clone, Debug, Default)]
pub struct Conserved;

impl<T: Linear> Rule<T> for Conserved {
    fn name() -> &'static str {
        "Conserved"
    }

    fn merge(inputs: &[(Option<&T>, f64)]) -> Option<T> {
        let mut out: Option<T> = None;
        for v in inputs.iter().filter_map(|(v, _)| *v) {
            out.get_or_insert_with(T::zero).add_scaled(v, 1.0);
        }
        out
    }

    fn interpolate(_inputs: &[(Option<&T>, f64)]) -> Option<T> {
        None
    }

    fn split(source: Option<&T>, share: f64) -> Option<T> {
        source.map(|v| v.scaled(share))
    }
}

/// Contagion: if any contributor has a value, the result has one: the
/// greatest present value (the first of equal ones), so `true` beats
/// `false` and a flag spreads; every split piece keeps the source's value.
/// A flag never disappears while its elements live: the hole flag,
/// selections, tags.
///
/// ```
/// use meshloom::attr::{Contagion, Rule};
/// assert_eq!(<Contagion as Rule<bool>>::merge(&[(Some(&false), 0.5), (Some(&true), 0.5)]), Some(true));
/// assert_eq!(<Contagion as Rule<bool>>::merge(&[(None, 0.5), (Some(&false), 0.5)]), Some(false));
/// assert_eq!(<Contagion as Rule<bool>>::merge(&[(None, 0.5), (None, 0.5)]), None);
/// assert_eq!(<Contagion as Rule<u8>>::split(Some(&7), 0.5), Some(7));
/// ```
#[derive(Copy, Clone, Debug, Default)]
pub struct Contagion;

impl<T: Clone + PartialOrd> Rule<T> for Contagion {
    fn name() -> &'static str {
        "Contagion"
    }

    fn merge(inputs: &[(Option<&T>, f64)]) -> Option<T> {
        let mut best: Option<&T> = None;
        for v in inputs.iter().filter_map(|(v, _)| *v) {
            best = match best {
                Some(b) if v > b => Some(v),
                Some(b) => Some(b),
                None => Some(v),
            };
        }
        best.cloned()
    }

    fn split(source: Option<&T>, _share: f64) -> Option<T> {
        source.cloned()
    }
}

/// Incompatible: kept only when every contributor has a value and all the
/// values are equal; otherwise the result is absent (an absent contributor
/// disagrees with any value). Split pieces keep the source value. Values
/// never mix: material ids, group labels, part names.
///
/// ```
/// use meshloom::attr::{Incompatible, Rule};
/// type R = Incompatible;
/// assert_eq!(<R as Rule<u32>>::merge(&[(Some(&3), 0.5), (Some(&3), 0.5)]), Some(3));
/// assert_eq!(<R as Rule<u32>>::merge(&[(Some(&3), 0.5), (Some(&4), 0.5)]), None);
/// assert_eq!(<R as Rule<u32>>::merge(&[(Some(&3), 0.5), (None, 0.5)]), None);
/// ```
#[derive(Copy, Clone, Debug, Default)]
pub struct Incompatible;

impl<T: Clone + PartialEq> Rule<T> for Incompatible {
    fn name() -> &'static str {
        "Incompatible"
    }

    fn merge(inputs: &[(Option<&T>, f64)]) -> Option<T> {
        let first = inputs.first()?.0?;
        if inputs.iter().all(|(v, _)| *v == Some(first)) {
            Some(first.clone())
        } else {
            None
        }
    }

    fn split(source: Option<&T>, _share: f64) -> Option<T> {
        source.cloned()
    }
}

/// Keep-first: the result is the first contributor's value, absent if it
/// has none (each operator documents its first contributor: the surviving
/// element). Split pieces keep the source value.
///
/// ```
/// use meshloom::attr::{KeepFirst, Rule};
/// assert_eq!(<KeepFirst as Rule<i64>>::merge(&[(Some(&1), 0.1), (Some(&2), 0.9)]), Some(1));
/// assert_eq!(<KeepFirst as Rule<i64>>::merge(&[(None, 0.1), (Some(&2), 0.9)]), None);
/// ```
#[derive(Copy, Clone, Debug, Default)]
pub struct KeepFirst;

impl<T: Clone> Rule<T> for KeepFirst {
    fn name() -> &'static str {
        "KeepFirst"
    }

    fn merge(inputs: &[(Option<&T>, f64)]) -> Option<T> {
        inputs.first().and_then(|(v, _)| *v).cloned()
    }

    fn split(source: Option<&T>, _share: f64) -> Option<T> {
        source.cloned()
    }
}

/// Discard (the "drop" rule): every merged, interpolated or split element loses its value;
/// untouched elements keep theirs. For derived data (cached normals,
/// curvature) that must be recomputed after an edit.
///
/// ```
/// use meshloom::attr::{Discard, Rule};
/// assert_eq!(<Discard as Rule<f64>>::merge(&[(Some(&1.0), 1.0)]), None);
/// assert_eq!(<Discard as Rule<f64>>::split(Some(&1.0), 1.0), None);
/// ```
#[derive(Copy, Clone, Debug, Default)]
pub struct Discard;

impl<T> Rule<T> for Discard {
    fn name() -> &'static str {
        "Discard"
    }

    fn merge(_inputs: &[(Option<&T>, f64)]) -> Option<T> {
        None
    }

    fn split(_source: Option<&T>, _share: f64) -> Option<T> {
        None
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
        assert_eq!(
            <Interpolate as Rule<f64>>::infer(&[(None, 0.5), (Some(&2.0), 0.5)]),
            Some(2.0)
        );
    }

    #[test]
    fn conserved_merge_of_absent_is_absent() {
        assert_eq!(<Conserved as Rule<f64>>::merge(&[(None, 1.0)]), None);
        assert_eq!(<Conserved as Rule<f64>>::split(None, 0.5), None);
        assert_eq!(<Conserved as Rule<f64>>::infer(&[(Some(&1.0), 1.0)]), None);
    }

    #[test]
    fn incompatible_empty_is_absent() {
        assert_eq!(<Incompatible as Rule<u8>>::merge(&[]), None);
        assert_eq!(<KeepFirst as Rule<u8>>::merge(&[]), None);
        assert_eq!(<Contagion as Rule<u8>>::merge(&[]), None);
    }
}
