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
//!   place; every operator checks first and changes nothing when it refuses.
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
//!
//! # A map of the crate
//!
//! Every public module, by layer. Start at [`Mesh`] and [`view`]; the
//! editing layer changes a mesh, the attribute layer says what its values do
//! meanwhile, and the algorithms, the journal and the file formats are built
//! on those.
//!
//! **Core: the mesh, its keys and how to walk it.**
//!
//! | module | what it holds |
//! |---|---|
//! | [`Mesh`] | the arenas of vertices, half-edges, edges and faces: counts, positions, slots (the type is re-exported at the root) |
//! | [`keys`] | [`VertexKey`], [`HalfedgeKey`], [`EdgeKey`], [`FaceKey`]: a slot and a generation, so a stale key is an error, never another element |
//! | [`view`] | borrowed views ([`Mesh::vertex`], [`Mesh::halfedge`], ...): a key checked once, then navigation that cannot fail |
//! | [`iter`] | the named element iterators ([`iter::Vertices`], [`iter::Faces`], ...), in slot order with exact lengths |
//! | [`link`] | [`link::RawEdit`]: reflecting low-level link setters, for writing your own operators |
//! | [`map`] | [`map::SecondaryMap`]: scratch values per element beside a mesh, stale-key safe |
//! | [`traverse`] | breadth- and depth-first orders, connected components, shortest paths, edge loops, edge rings and face loops |
//! | [`validate`] | every structural rule, numbered, as [`Mesh::validate`] checks them |
//! | [`stats`] | whole-mesh figures: counts, boundary loops, components, Euler characteristic, genus |
//!
//! **Editing: changing a mesh without breaking it.**
//!
//! | module | what it holds |
//! |---|---|
//! | [`ops`] | the operators (split, collapse, flip, remove, fill, triangulate, extrude, cut, compact), each with a side-effect-free `check_*` twin, all or nothing |
//! | [`model`] | modelling tools over regions (loop cut, ...), each one composite edit, all or nothing and one undo step |
//! | [`build`] | meshes from polygons or flat buffers of any point type, in linear time with typed errors, and polygons back |
//! | [`repair`] | repair policies for dirty polygon soups (weld, drop degenerate faces, reorient, split non-manifold elements), with a report |
//! | [`shapes`] | named shapes for docs, tests and benchmarks: tetrahedron, cube, icosphere, grid, torus, ... |
//!
//! **Attributes and geometry: values that follow the edits.**
//!
//! | module | what it holds |
//! |---|---|
//! | [`attr`] | typed columns on vertices, half-edges (corners), edges and faces; the [`attr::Rule`] trait and the stock rules that merge, split and interpolate them inside every operator |
//! | [`geometry`] | the [`geometry::Point`] trait (your own point types as positions) and measures: lengths, normals, areas, centroids |
//!
//! **Spatial queries.**
//!
//! | module | what it holds |
//! |---|---|
//! | [`query`] | [`query::FaceTree`]: a bounding volume hierarchy over the faces for ray casts, closest points, radius queries, nearest vertices and generalized winding numbers (inside tests), refused once the mesh changes without a refit |
//!
//! **Algorithms** ([`algo`]: one algorithm per module, each all or nothing,
//! with a [`Progress`](algo::Progress) callback where it may take long).
//!
//! | module | what it does |
//! |---|---|
//! | [`algo::normals`] | face, vertex and corner normals (split at creases and hard edges) |
//! | [`algo::laplacian`] | the cotangent or uniform Laplacian and the mass matrix |
//! | [`algo::curvature`] | mean, Gaussian and principal curvatures |
//! | [`algo::smooth`] | explicit, Taubin and implicit smoothing |
//! | [`algo::fair`] | the smoothest (k-harmonic) surface over a region |
//! | [`algo::fill_hole`](mod@algo::fill_hole) | Liepa's hole filling: triangulate, refine, fair |
//! | [`algo::decimate`](mod@algo::decimate) | quadric error decimation and level-of-detail chains |
//! | [`algo::remesh`](mod@algo::remesh) | isotropic remeshing to a uniform or adaptive edge length |
//! | [`algo::subdivision`] | what the subdivision schemes share: options, creases, the report |
//! | [`algo::loop_subdivision`], [`algo::catmull_clark`](mod@algo::catmull_clark), [`algo::sqrt3`], [`algo::midpoint`] | the four subdivision schemes |
//! | [`algo::progress`] | the progress-and-cancel callback |
//!
//! **Journal, files, engines.**
//!
//! | module | what it holds |
//! |---|---|
//! | [`journal`] | transactions, undo and redo, change tracking: what an editor needs from its mesh kernel |
//! | [`io`] | the file formats: OBJ, OFF, PLY, STL (and `.gz`), glTF with the `gltf` feature; strict or repairing reads with located errors |
//! | [`buffers`] | engine buffers: a mesh as flat `f32` triangle arrays split at UV seams and creases, and back |
//!
//! **Plumbing.**
//!
//! | module | what it holds |
//! |---|---|
//! | [`choice`] | option enums spelled as words (`Display`, `FromStr`, `WORDS`), shared by the command line and Python |
//! | [`error`] | [`Error`], [`BuildError`], [`Refusal`], [`AnyError`] and the validation error: each names what was wrong and where |
//! | `arbitrary` | `quickcheck::Arbitrary` valid random meshes for your own property tests (feature `quickcheck`) |
//!
//! # Cargo features
//!
//! | feature | default | what it adds |
//! |---|---|---|
//! | `gzip` | yes | reading and writing gzip-compressed files (`.gz`), pure Rust |
//! | `sparse` | no | implicit smoothing and fairing through faer's sparse Cholesky factorisation (without it they refuse with [`Error::Unsuitable`]; hole filling fairs by conjugate gradients) |
//! | `serde` | no | `Serialize`/`Deserialize` for meshes, validated on the way in |
//! | `quickcheck` | no | `Arbitrary` valid random meshes (the `arbitrary` module) |
//! | `mint`, `glam`, `nalgebra` | no | their points and vectors as positions and attribute values ([`geometry`] lists the versions) |
//! | `parallel` | no | normals and engine buffers of large meshes on rayon's threads |
//! | `gltf` | no | reading and writing glTF 2.0 (`.gltf`, `.glb`) |
//! | `validate-edits` | no | debug builds validate the whole mesh after every edit (inside a transaction, once when the outermost ends): for meshloom's own tests and fuzzing, not for applications |
#![deny(missing_docs)]
#![forbid(unsafe_code)]

// Layers, lowest first. A module may use (by `crate::` paths, outside
// `#[cfg(test)]` code) only the modules named before it here, so imports
// run one way and never form a cycle; tests/layers.rs checks it.
//
// - core: vec3 predicates choice keys layout map slots error store record
// - mesh: mesh
// - access: circulate iter view traverse validate link stats attr geometry serde_impl
// - editing: journal ops model
// - building: build shapes repair arbitrary
// - spatial: query
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
pub mod model;
pub mod ops;
mod predicates;
pub mod query;
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
mod vec3;
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
