//! The sections of `bench_peers`, one file per capability.

#[path = "attributes.rs"]
mod attributes;
#[path = "core.rs"]
mod core;
#[path = "io.rs"]
mod io;
#[path = "ops.rs"]
mod ops;

use crate::harness::Report;

/// Run every section in order.
pub fn run_all(r: &mut Report) {
    core::run(r);
    attributes::run(r);
    ops::run(r);
    io::run(r);
}
