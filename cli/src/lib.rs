//! The library half of the `meshloom` command-line tool: the software
//! renderer behind `meshloom render`, usable on its own.
//!
//! The mesh library itself is the [`meshloom`] crate; this crate adds what a
//! library user does not need by default (argument parsing, progress bars,
//! PNG output).
#![deny(missing_docs)]
#![forbid(unsafe_code)]

pub mod render;
