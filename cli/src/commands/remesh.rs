//! `meshloom remesh IN OUT [--edge-length L | --adaptive TOL]
//! [--iterations N] [--feature-angle DEG]`: isotropic remeshing.

use meshloom::algo::remesh::{remesh, BoundaryMode, RemeshOptions, RemeshReport, Sizing};
use meshloom::algo::{Flow, ProgressInfo};
use serde_json::json;

use crate::cli::RemeshArgs;
use crate::output::{self, to_json};
use crate::progress::Progress;
use crate::{input, Failure};

/// The library's options from the flags.
fn options(args: &RemeshArgs) -> RemeshOptions {
    let sizing = match (args.edge_length, args.adaptive) {
        (Some(l), _) => Sizing::Uniform(l),
        (None, Some(tolerance)) => Sizing::Adaptive {
            tolerance,
            min_length: args.min_length,
            max_length: args.max_length,
        },
        (None, None) => Sizing::MeanEdgeLength,
    };
    RemeshOptions {
        sizing,
        iterations: args.iterations,
        feature_angle: args.feature_angle.map(f64::to_radians),
        boundary: if args.keep_boundary {
            BoundaryMode::Fixed
        } else {
            BoundaryMode::Slide
        },
        max_faces: args.max_faces,
        ..RemeshOptions::default()
    }
}

fn summary(r: &RemeshReport) -> String {
    let l = &r.edge_lengths;
    format!(
        "{} vertices, {} faces -> {} vertices, {} faces ({} iterations: {} splits, {} collapses, {} flips)\n\
         target length {:.6}; edge lengths {:.6} to {:.6}, mean {:.6}; {:.1}% within [4/5, 4/3] of the target\n\
         {} feature edges, {} vertices fixed{}\n",
        r.vertices_before,
        r.faces_before,
        r.vertices,
        r.faces,
        r.iterations,
        r.splits,
        r.collapses,
        r.flips,
        r.target_length,
        l.min,
        l.max,
        l.mean,
        100.0 * l.within,
        r.feature_edges,
        r.fixed_vertices,
        if r.resampled.is_empty() {
            String::new()
        } else {
            format!("; resampled {}", r.resampled.join(", "))
        }
    )
}

/// Read, remesh, write.
pub fn run(args: &RemeshArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let opts = options(args);
    let report = {
        let bar = Progress::bar("remeshing", args.iterations);
        let mut cb = |p: &ProgressInfo<'_>| {
            bar.set_length(p.total);
            bar.set(p.done as usize);
            Flow::Continue
        };
        remesh(&mut mesh, &opts, meshloom::algo::Progress::new(&mut cb)).map_err(Failure::input)?
    };
    input::write(&mesh, &args.output, false, false)?;
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "report": to_json(&report)?,
        }));
    }
    output::print(&format!(
        "{}wrote {}\n",
        summary(&report),
        args.output.display()
    ))
}
