//! The merge/split rule trait and the linear-value trait interpolation needs.
//! The stock rules live in [`rules`](super::rules).

pub use super::rules::Interpolate;
use crate::error::RuleError;

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
///
/// # Rules that can fail
///
/// A rule that may have no sensible answer (it calls out to a script, or
/// the values contradict each other) sets [`FALLIBLE`](Rule::FALLIBLE) and
/// implements the `try_` functions it can fail in
/// ([`try_merge`](Rule::try_merge), [`try_interpolate`](Rule::try_interpolate),
/// [`try_split`](Rule::try_split); each defaults to its plain twin). When
/// one returns an error, the edit that ran it fails with
/// [`Error::Rule`](crate::Error::Rule) (carrying the [`RuleError`], which
/// then names the column) and leaves the mesh as it was: an operator refuses, an
/// algorithm or a [transaction](crate::Mesh::transaction) rolls back whole.
/// For that, every edit of a mesh with such a column runs as a
/// transaction (its cost is the size of the edit); the rule is not called
/// again on that column until the edit has failed. Columns whose rules
/// cannot fail pay nothing.
///
/// ```
/// use meshloom::attr::{Rule, RuleError};
/// use meshloom::{Error, VertexKey};
///
/// /// Labels that refuse to merge two different labels.
/// struct Strict;
/// impl Rule<u32> for Strict {
///     const FALLIBLE: bool = true;
///     fn merge(inputs: &[(Option<&u32>, f64)]) -> Option<u32> {
///         Self::try_merge(inputs).ok().flatten()
///     }
///     fn try_merge(inputs: &[(Option<&u32>, f64)]) -> Result<Option<u32>, RuleError> {
///         let mut labels = inputs.iter().filter_map(|(v, _)| *v);
///         let first = labels.next().copied();
///         match labels.find(|&&l| Some(l) != first) {
///             Some(other) => Err(RuleError::new(format!("labels {first:?} and {other} meet"))),
///             None => Ok(first),
///         }
///     }
///     fn split(source: Option<&u32>, _share: f64) -> Option<u32> {
///         source.copied()
///     }
/// }
///
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let label = mesh.add_attr_with_rule::<VertexKey, u32, Strict>("label")?;
/// let vs: Vec<_> = mesh.vertices().collect();
/// for (i, &v) in vs.iter().enumerate() {
///     mesh.set_attr(&label, v, i as u32)?;
/// }
/// let h = mesh.halfedges().next().unwrap();
/// let before = mesh.clone();
/// match mesh.collapse_edge(h) {
///     Err(Error::Rule(error)) => {
///         assert_eq!(error.column(), Some((meshloom::ElementKind::Vertex, "label")));
///         assert!(error.message().contains("meet"));
///     }
///     other => panic!("{other:?}"),
/// }
/// assert_eq!(mesh.vertex_count(), before.vertex_count());
/// assert!(vs.iter().all(|&v| mesh.contains_vertex(v)));
/// # Ok::<(), meshloom::Error>(())
/// ```
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

    /// Whether the rule can fail: the columns then call the `try_`
    /// functions instead of the plain ones (see "Rules that can fail"
    /// above). The stock rules cannot.
    const FALLIBLE: bool = false;

    /// The rule's name, as [`Mesh::attr_info`](crate::Mesh::attr_info)
    /// reports it: the stock rules say `"Interpolate"`, `"Conserved"`,
    /// `"Contagion"`, `"Incompatible"`, `"KeepFirst"`, `"Discard"` and
    /// `"Dynamic"`; by default, the type's name without its module path
    /// and generic arguments.
    fn name() -> &'static str {
        let full = std::any::type_name::<Self>();
        let head = full.split('<').next().unwrap_or(full);
        head.rsplit("::").next().unwrap_or(head)
    }

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

    /// [`merge`](Rule::merge) of a [fallible](Rule::FALLIBLE) rule, which
    /// may refuse. Defaults to `merge`.
    ///
    /// # Errors
    /// Whatever the rule refuses; the edit then fails with
    /// [`Error::Rule`](crate::Error::Rule).
    fn try_merge(inputs: &[(Option<&T>, f64)]) -> Result<Option<T>, RuleError> {
        Ok(Self::merge(inputs))
    }

    /// [`interpolate`](Rule::interpolate) of a [fallible](Rule::FALLIBLE)
    /// rule. Defaults to `interpolate` (so a fallible rule whose
    /// interpolation merges overrides both `try_merge` and this).
    ///
    /// # Errors
    /// As [`try_merge`](Rule::try_merge).
    fn try_interpolate(inputs: &[(Option<&T>, f64)]) -> Result<Option<T>, RuleError> {
        Ok(Self::interpolate(inputs))
    }

    /// [`split`](Rule::split) of a [fallible](Rule::FALLIBLE) rule.
    /// Defaults to `split`.
    ///
    /// # Errors
    /// As [`try_merge`](Rule::try_merge).
    fn try_split(source: Option<&T>, share: f64) -> Result<Option<T>, RuleError> {
        Ok(Self::split(source, share))
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
