//! Traversals: breadth- and depth-first order, connected components,
//! shortest paths, and the edge loops, edge rings and face loops an editor
//! selects from one edge ([`Mesh::edge_loop`](crate::Mesh::edge_loop),
//! [`Mesh::edge_ring`](crate::Mesh::edge_ring),
//! [`Mesh::face_loop`](crate::Mesh::face_loop)):
//!
//! - an **edge loop** goes straight on through vertices of degree 4
//!   (leaving by the edge opposite the one it came in on) and stops at a
//!   pole (any other degree) or at the boundary; through a boundary edge it
//!   follows the boundary through vertices of degree 3 and stops at corners;
//! - an **edge ring** crosses quads, from an edge to the opposite side of
//!   the quad beside it, and stops at a face that is not a quad or at a
//!   hole; a **face loop** is the quads it crosses.
//!
//! Like petgraph's walkers, [`Bfs`] and [`Dfs`] hold only their own state (a
//! queue or stack and a visited set) and take the mesh at every step, so
//! the caller keeps full use of it between steps. Both walk either vertices
//! (through edges, holes' sides included) or faces (through the edges they
//! share; holes are never visited, so a face's walk stops at the boundary):
//! the key type of the start picks which.
//!
//! ```
//! use meshloom::shapes::{grid, GridFaces};
//! use meshloom::traverse::{self, Bfs};
//!
//! let mesh = grid(4, 4, GridFaces::Quads);
//! let start = mesh.vertices().next().unwrap();
//! // Step by step, holding only the walker's state:
//! let mut bfs = Bfs::new(&mesh, start)?;
//! let mut seen = 0;
//! while let Some(_v) = bfs.next(&mesh) {
//!     seen += 1;
//! }
//! assert_eq!(seen, mesh.vertex_count());
//! // Or as an iterator borrowing the mesh:
//! assert_eq!(mesh.dfs_faces(mesh.faces().next().unwrap())?.count(), 16);
//! assert_eq!(traverse::components(&mesh).count(), 1);
//! # Ok::<(), meshloom::Error>(())
//! ```
//!
//! A key to a removed element is refused with
//! [`Error::StaleKey`](crate::Error::StaleKey) when a walk or a search
//! starts; elements removed during a walk are skipped.

mod components;
mod loops;
mod path;
mod walk;

pub use components::{components, Components};
pub use loops::Chain;
pub use path::{shortest_path, Path};
pub use walk::{Bfs, Dfs, Node};
