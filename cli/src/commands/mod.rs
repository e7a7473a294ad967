//! One module per command family: each prints what the library computes.

pub mod convert;
pub mod render;
pub mod stats;
pub mod validate;
