//! Core: building from buffers, one-ring circulation, heap bytes per vertex.

use crate::harness::Report;

/// Run the core rows.
pub fn run(_r: &mut Report) {}
