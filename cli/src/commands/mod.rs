//! One module per command family: each prints what the library computes.

pub mod check;
pub mod constraints;
pub mod convert;
pub mod decimate;
pub mod dissolve;
pub mod fair;
pub mod normals;
pub mod quads;
pub mod remesh;
pub mod render;
pub mod sample;
pub mod smooth;
pub mod stats;
pub mod subdivide;
pub mod validate;
