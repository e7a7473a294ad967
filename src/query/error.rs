//! What a spatial query refuses, and where.

use crate::keys::FaceKey;

/// Why a [`FaceTree`](super::FaceTree) refused a build, a refit or a query.
///
/// Batch calls name the offending input by its index in the batch; single
/// calls say index 0.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum QueryError {
    /// Occurs when the mesh has no position column.
    #[error("the mesh has no positions")]
    NoPositions,
    /// Occurs when the tree is used with a mesh that changed since it was
    /// built or refitted (`built` and `now` are [`Mesh::revision`]s), or
    /// with another mesh (`same_mesh` false).
    ///
    /// [`Mesh::revision`]: crate::Mesh::revision
    #[error("the tree was built for revision {built} of {which}, the mesh is at revision {now}: refit or rebuild it", which = if *same_mesh { "this mesh" } else { "another mesh" })]
    StaleTree {
        /// The revision the tree was built or last refitted for.
        built: u64,
        /// The mesh's revision now.
        now: u64,
        /// Whether it is the same mesh value (not another mesh or a clone).
        same_mesh: bool,
    },
    /// Occurs when [`refit`](super::FaceTree::refit) finds the faces
    /// changed (a face removed, or its corners changed): only positions may
    /// move under a refit; rebuild instead.
    #[error("face {face} changed since the tree was built: rebuild the tree")]
    TopologyChanged {
        /// The first face found changed (the face itself if it is gone).
        face: FaceKey,
    },
    /// Occurs when the number of faces changed since the build.
    #[error("the mesh has {now} faces, the tree was built over {built}: rebuild the tree")]
    FaceCountChanged {
        /// Faces when the tree was built.
        built: usize,
        /// Faces now.
        now: usize,
    },
    /// Occurs when [`update`](super::FaceTree::update) is given a change
    /// set that does not cover exactly the edits since the tree's revision:
    /// it must start at the tree's revision (`from == tree`) and end at the
    /// mesh's (`to == now`); see
    /// [`Changes::from_revision`](crate::journal::Changes::from_revision).
    #[error("the change set covers revisions {from}..{to}, the tree is at {tree} and the mesh at {now}: rebuild the tree")]
    ChangesMismatch {
        /// The tree's revision.
        tree: u64,
        /// The change set's first revision.
        from: u64,
        /// The change set's last revision.
        to: u64,
        /// The mesh's revision now.
        now: u64,
    },
    /// Occurs when a ray's origin or direction has a NaN or infinite
    /// coordinate.
    #[error("ray {index}: origin {origin:?} or direction {direction:?} is not finite")]
    NonFiniteRay {
        /// The ray's index in the batch.
        index: usize,
        /// Its origin.
        origin: [f64; 3],
        /// Its direction.
        direction: [f64; 3],
    },
    /// Occurs when a ray's direction is the zero vector.
    #[error("ray {index}: the direction is zero")]
    ZeroDirection {
        /// The ray's index in the batch.
        index: usize,
    },
    /// Occurs when a query point has a NaN or infinite coordinate.
    #[error("point {index}: {point:?} is not finite")]
    NonFinitePoint {
        /// The point's index in the batch.
        index: usize,
        /// The point.
        point: [f64; 3],
    },
    /// Occurs when a radius, a maximum distance or a maximum `t` is NaN or
    /// negative.
    #[error("{what} {value} is NaN or negative")]
    InvalidBound {
        /// Which bound: "radius", "max_distance", "max_t".
        what: &'static str,
        /// The value given.
        value: f64,
    },
}

/// `p` as a query point, or the error naming it.
pub(super) fn check_point(index: usize, p: [f64; 3]) -> Result<(), QueryError> {
    if p.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(QueryError::NonFinitePoint { index, point: p })
    }
}

/// `value` as a bound (0 to +∞ inclusive), or the error naming it.
pub(super) fn check_bound(what: &'static str, value: f64) -> Result<(), QueryError> {
    if value >= 0.0 {
        Ok(())
    } else {
        Err(QueryError::InvalidBound { what, value })
    }
}
