//! The merge/split rule trait and the linear-value trait interpolation needs.
//! The stock rules live in [`rules`](super::rules).

pub use super::rules::Interpolate;

/// What happens to an attribute value when elements merge or split.
///
/// Every topological operation runs the rules of every column itself; user
/// code never calls them by hand. Contributors always arrive in a
/// deterministic order fixed by the operation (its docs, and the table in
/// [`ops`](crate::ops), say which): in a merge **the surviving element
/// comes first** (the vertex a collapse keeps, the face a face merge keeps,
/// the side of a disappearing triangle that stays), then the elements that
/// disappear. An absent value is passed as `None` so a rule can tell "no
/// value" from any value.
///
/// Implement this on a zero-sized type to write a new rule, then name it in
/// [`Attribute::Rule`](crate::attr::Attribute) or pass it when adding a
/// column.
pub trait Rule<T>: 'static {
    /// Whether [`merge`](Rule::merge) and [`interpolate`](Rule::interpolate)
    /// are the weighted mean of the present values: an affine combination,
    /// so an algorithm may pass any non-negative weights that sum to 1 (a
    /// subdivision stencil over a vertex's neighbours) and get that
    /// combination back. [`Interpolate`] says so; the other stock rules
    /// (sums, flags, labels) do not. Subdivision smooths the columns whose
    /// rule is linear like positions (OpenSubdiv's "vertex" data, unless
    /// asked for linear "varying" data) and gives the others their rule's
    /// `interpolate` over the linear contributors, as the operators do.
    const LINEAR: bool = false;

    /// Several elements become one (collapse: two vertices, and two edges
    /// where a triangle disappears; remove edge or merge faces: two faces;
    /// remove vertex: a ring of faces). `inputs` are `(value, weight)`
    /// pairs, the surviving element's first; the weights are non-negative
    /// and sum to 1 (collapse passes the position parameter, merges of faces
    /// pass equal weights).
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

    /// A value for an element that has none, inferred on demand from its
    /// neighbours' values (`(value, weight)`, in ring order; the weights are
    /// equal and sum to 1). The default infers nothing; [`Interpolate`]
    /// takes the mean of the present neighbours. Called by
    /// [`Mesh::infer_attr`](crate::Mesh::infer_attr), never by operations.
    fn infer(neighbours: &[(Option<&T>, f64)]) -> Option<T> {
        let _ = neighbours;
        None
    }
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
