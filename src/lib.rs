//! # meshloom
//!
//! Polygon meshes as a half-edge graph whose attributes follow every edit.
//!
//! - **Edges own the connectivity.** Half-edges live in an arena and link to
//!   their origin, twin, next and face. A vertex or face exists only while a
//!   half-edge refers to it: no isolated vertices, no dangling faces.
//! - **Holes are faces.** Outside every boundary loop sits a face flagged as
//!   a hole, so every half-edge has a twin and a face. Face listings skip
//!   holes unless asked ([`Mesh::holes`], [`Mesh::faces_and_holes`]).
//! - **Keys are safe.** [`VertexKey`], [`HalfedgeKey`], [`EdgeKey`] and
//!   [`FaceKey`] are generational: a key to a removed element is reported as
//!   [`Error::StaleKey`], never a panic or a wrong element. Keys are checked
//!   once, when a view is made ([`Mesh::halfedge`]); navigation from a view
//!   cannot fail.
//! - **Attributes merge and split by rule.** Columns of typed values sit
//!   beside each arena ([`attr`]); positions are the vertex column
//!   [`attr::POSITION`].
//! - **Checked structure.** [`Mesh::validate`] states every rule in one
//!   place.
//!
//! ```
//! use meshloom::Mesh;
//! let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [2.0, 0.5, 0.0]];
//! let mesh = Mesh::from_polygons(&positions, &[vec![0u32, 1, 2, 3], vec![1, 4, 2]])?;
//! assert_eq!(mesh.face_count(), 2);
//! assert_eq!(mesh.hole_count(), 1);
//! let f = mesh.faces().next().unwrap();
//! let corners: Vec<_> = mesh.face(f)?.vertices().collect();
//! assert_eq!(corners.len(), 4);
//! mesh.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```
#![deny(missing_docs)]
#![forbid(unsafe_code)]

// Layers, lowest first. A module may use (by `crate::` paths, outside
// `#[cfg(test)]` code) only the modules named before it here, so imports
// run one way and never form a cycle; tests/layers.rs checks it.
//
// - core: choice keys layout map slots store error record
// - mesh: mesh
// - access: circulate iter traverse validate view link stats attr geometry serde_impl
// - editing: journal ops
// - building: build shapes repair arbitrary
// - algorithms: algo
// - exchange: buffers io
// - umbrella: any_error

pub mod algo;
mod any_error;
#[cfg(feature = "quickcheck")]
pub mod arbitrary;
pub mod attr;
pub mod buffers;
pub mod build;
pub mod choice;
mod circulate;
pub mod error;
pub mod geometry;
pub mod io;
pub mod iter;
pub mod journal;
pub mod keys;
mod layout;
pub mod link;
pub mod map;
mod mesh;
pub mod ops;
mod record;
pub mod repair;
#[cfg(feature = "serde")]
mod serde_impl;
pub mod shapes;
mod slots;
pub mod stats;
mod store;
pub mod traverse;
pub mod validate;
pub mod view;

pub use any_error::AnyError;
pub use build::{Built, IndexMaps, Polygons, PolygonsRef, VertexIndex};
pub use error::{BuildError, Error, Refusal, Result};
pub use keys::{AnyKey, EdgeKey, ElementKey, ElementKind, FaceKey, HalfedgeKey, VertexKey};
pub use mesh::Mesh;
pub use stats::{ComponentStats, Stats};
pub use validate::ValidationError;
pub use view::{EdgeView, FaceView, HalfedgeView, VertexView};

/// The README's examples, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
