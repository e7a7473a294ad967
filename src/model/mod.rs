//! Modelling tools: edits over a region of the mesh (a ring of edges, a
//! set of faces) made of the [`ops`](crate::ops) operators, each one
//! composite edit that is all or nothing and one undo step.
//!
//! Every tool plans first (checking its selection and options against the
//! mesh as it is, changing nothing), then runs its operators inside a
//! [transaction](crate::Mesh::transaction), so a refusal or a failed
//! attribute rule leaves the mesh, attributes included, as it was. The
//! attributes follow each operator's rules: a loop cut's new vertices and
//! corners interpolate along the edges they split, its face pieces split
//! the quads' values by area, and its new edges get `interpolate` of
//! nothing, as Blender's BMesh does.
//!
//! | tool | what it does |
//! |---|---|
//! | [`Mesh::bridge_loops`](crate::Mesh::bridge_loops) | join two loops or chains of boundary edges by a band of quads (holes consumed or joined) |
//! | [`Mesh::grid_fill`](crate::Mesh::grid_fill) | fill a hole of an even number of edges with a grid of quads |
//! | [`Mesh::duplicate_faces`](crate::Mesh::duplicate_faces), [`Mesh::separate`](crate::Mesh::separate) | copies of faces beside their sources, or moved into a mesh of their own |
//! | [`Mesh::extrude_faces`](crate::Mesh::extrude_faces) | push faces out as regions (or each on its own) with walls along their boundary |
//! | [`Mesh::inset_faces`](crate::Mesh::inset_faces) | a smaller copy of regions (or of each face) inside them, joined by a rim of quads |
//! | [`Mesh::loop_cut`](crate::Mesh::loop_cut) | cut an edge ring's quads with new edge loops |
//! | [`Mesh::dissolve_vertices`](crate::Mesh::dissolve_vertices), [`Mesh::dissolve_edges`](crate::Mesh::dissolve_edges), [`Mesh::dissolve_faces`](crate::Mesh::dissolve_faces) | remove elements, merging the faces around them; a region of faces into one face |
//! | [`Mesh::dissolve_limited`](crate::Mesh::dissolve_limited) | merge nearly coplanar faces and straighten chains below an angle, stopping at delimiters |
//! | [`Mesh::split_edges`](crate::Mesh::split_edges) | rip: disconnect the faces along chosen edges (seams from [`Delimit::edges`]) |
//! | [`Mesh::join_triangles`](crate::Mesh::join_triangles) | pair adjacent triangles into quads by angle and shape, best pairs first, stopping at delimiters |
//! | [`Mesh::transform_vertices`](crate::Mesh::transform_vertices), [`Mesh::transform_faces`](crate::Mesh::transform_faces) | scale, rotate and move a selection about a pivot (each region about its own, for faces) |

mod bridge;
mod delimit;
mod dissolve;
mod dissolve_limited;
mod duplicate;
mod extrude;
mod grid_fill;
mod inset;
mod interp;
mod join_triangles;
mod loop_cut;
mod split_edges;
#[cfg(test)]
mod testing;
mod transform;

pub use bridge::{Bridge, BridgeOptions, MAX_BRIDGE_CUTS};
pub use delimit::Delimit;
pub(crate) use delimit::Delimiters;
pub use dissolve::{DissolveEdgesOptions, Dissolved};
pub use dissolve_limited::DissolveLimitedOptions;
pub use duplicate::Duplicate;
pub use extrude::{ExtrudeOptions, Extrusion};
pub use grid_fill::{GridFill, GridFillOptions};
pub use inset::{Inset, InsetOptions};
pub use join_triangles::{JoinTrianglesOptions, Joined};
pub use loop_cut::{LoopCut, LoopCutOptions, MAX_CUTS};
pub use split_edges::SplitEdges;
pub use transform::{Pivot, Transform};
