//! The sections of `bench_peers`, one file per capability.

#[path = "core.rs"]
mod core;

use crate::harness::Report;

/// Run every section in order.
pub fn run_all(r: &mut Report) {
    core::run(r);
}
