//! `meshloom`: look at, check, convert, repair and render mesh files.
//!
//! A thin shell over the library: this file parses arguments and maps
//! failures to exit codes; one module per command prints what the library
//! computes.
//!
//! Exit codes: 0 success, 1 bad input (a file that cannot be read, parsed,
//! built or written), 2 usage (clap's code for bad arguments).
#![forbid(unsafe_code)]

mod batch;
mod cli;
mod commands;
mod input;
mod output;
mod progress;

use std::process::ExitCode;

use clap::Parser;

use cli::{Cli, Command};
use commands::{
    check, convert, decimate, dissolve, fair, quads, remesh, render, sample, smooth, stats,
    subdivide, validate,
};

/// Why a command failed, and the exit code that says so.
#[derive(Debug)]
pub struct Failure {
    /// The exit code.
    pub code: u8,
    /// What to tell the user.
    pub message: String,
}

impl Failure {
    /// Exit code for bad input.
    pub const INPUT: u8 = 1;
    /// Exit code for a usage error (as clap's).
    pub const USAGE: u8 = 2;

    /// A bad-input failure.
    pub fn input(message: impl std::fmt::Display) -> Failure {
        Failure {
            code: Failure::INPUT,
            message: message.to_string(),
        }
    }

    /// A usage failure (exit 2).
    pub fn usage(message: impl std::fmt::Display) -> Failure {
        Failure {
            code: Failure::USAGE,
            message: message.to_string(),
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let done = match cli.command {
        Command::Stats(a) => stats::run(&a),
        Command::Components(a) => stats::components(&a),
        Command::Validate(a) => validate::run(&a),
        Command::Check(a) => check::run(&a),
        Command::Convert(a) => convert::convert(&a),
        Command::Repair(a) => convert::repair(&a),
        Command::Triangulate(a) => convert::triangulate(&a),
        Command::FillHoles(a) => convert::fill_holes(&a),
        Command::Smooth(a) => smooth::run(&a),
        Command::Fair(a) => fair::run(&a),
        Command::Decimate(a) => decimate::decimate(&a),
        Command::Lod(a) => decimate::lod(&a),
        Command::Dissolve(a) => dissolve::run(&a),
        Command::Render(a) => render::run(&a),
        Command::Subdivide(a) => subdivide::run(&a),
        Command::Remesh(a) => remesh::run(&a),
        Command::Sample(a) => sample::run(&a),
        Command::Quads(a) => quads::run(&a),
    };
    match done {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            if !f.message.is_empty() {
                eprintln!("meshloom: error: {}", f.message);
            }
            ExitCode::from(f.code)
        }
    }
}
