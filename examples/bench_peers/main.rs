//! `bench_peers`: meshloom's figures beside the C++ peers' on the same
//! workloads, as medians of several runs.
//!
//! Run with `cargo run --release --example bench_peers [-- --runs N] [--only TEXT]`
//! (`--only` times just the rows whose name contains TEXT).
//! Peer figures were measured by the issue authors on a machine like the
//! benchmark machine; they are printed beside ours, with the target ratio.
//! Each section lives in its own file; this file holds the harness.

mod harness;
mod sections;

fn main() {
    let runs = std::env::args()
        .skip_while(|a| a != "--runs")
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(7);
    let only = std::env::args().skip_while(|a| a != "--only").nth(1);
    let mut report = harness::Report::new(runs, only);
    sections::run_all(&mut report);
    report.finish();
}
