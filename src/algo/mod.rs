//! Geometry algorithms over a [`Mesh`](crate::Mesh): one algorithm per
//! file, as pmp-library's `algorithms/`.
//!
//! | module | what | results |
//! |---|---|---|
//! | [`progress`] | the progress-and-cancel callback every long algorithm takes | [`Progress`], [`Error::Cancelled`](crate::Error::Cancelled) |
//! | [`normals`] | face normals; vertex normals weighted by angle, area or uniformly; corner (half-edge) normals split at creases and hard edges | plain `Vec`s indexed by slot, or attribute columns named [`normals::NORMAL`] |
//!
//! Each algorithm reads the mesh through its public API (views, keys,
//! [`Mesh::position_slots`](crate::Mesh::position_slots)) and states its
//! cost. Analysis (`&Mesh`) never changes the mesh; the `add_*` functions
//! that write a column compute everything first and write only when
//! nothing can fail any more.
//!
//! With the `parallel` feature, the passes over large meshes run on rayon's
//! thread pool; the results are bit-identical to the serial ones only up to
//! the order of floating-point sums (see each function).

pub mod normals;
pub mod progress;

pub use normals::{
    add_corner_normals, add_face_normals, add_vertex_normals, corner_normals, face_normals,
    vertex_normals, CornerNormalOptions, NormalWeight, VertexNormalOptions, NORMAL,
};
pub use progress::{Flow, Progress, ProgressInfo};
