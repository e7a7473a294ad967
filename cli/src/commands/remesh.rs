//! `meshloom remesh IN OUT [--edge-length L | --adaptive TOL]
//! [--iterations N] [--boundary free|slide|lock] [--feature-angle DEG]`:
//! isotropic remeshing.

use meshloom::algo::remesh::{remesh, Keep, RemeshOptions, RemeshReport, Sizing};
use meshloom::algo::{Flow, ProgressInfo};
use meshloom::Mesh;
use serde_json::json;

use crate::cli::RemeshArgs;
use crate::commands::constraints::{self, Temps};
use crate::output::{self, to_json};
use crate::progress::Progress;
use crate::{input, Failure};

/// The library's options from the flags (the old `--keep-boundary` means
/// lock, with a warning).
fn options(mesh: &mut Mesh, args: &RemeshArgs) -> Result<(RemeshOptions, Temps), Failure> {
    let sizing = match (args.edge_length, args.adaptive) {
        (Some(l), _) => Sizing::Uniform(l),
        (None, Some(tolerance)) => Sizing::Adaptive {
            tolerance,
            min_length: args.min_length,
            max_length: args.max_length,
        },
        (None, None) => Sizing::MeanEdgeLength,
    };
    let mut o = RemeshOptions::default()
        .sizing(sizing)
        .iterations(args.iterations)
        .max_faces(args.max_faces);
    let (c, temps) = constraints::resolve(mesh, &args.keep, o.constraints(), None)?;
    o = o.with_constraints(c);
    if args.keep_boundary {
        constraints::deprecated("--keep-boundary", "--boundary lock");
        o.boundary = Keep::Lock;
    }
    Ok((o, temps))
}

fn summary(r: &RemeshReport) -> String {
    let l = &r.edge_lengths;
    format!(
        "{} vertices, {} faces -> {} vertices, {} faces ({} iterations: {} splits, {} collapses, {} flips)\n\
         target length {:.6}; edge lengths {:.6} to {:.6}, mean {:.6}; {:.1}% within [4/5, 4/3] of the target\n\
         {} feature edges, {} vertices fixed{}\n",
        r.input.vertices,
        r.input.faces,
        r.output.vertices,
        r.output.faces,
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
        r.fixed,
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
    let (opts, temps) = options(&mut mesh, args)?;
    let report = {
        let bar = Progress::bar("remeshing", args.iterations);
        let mut cb = |p: &ProgressInfo<'_>| {
            bar.set_length(p.total);
            bar.set(p.done as usize);
            Flow::Continue
        };
        remesh(&mut mesh, &opts, meshloom::algo::Progress::new(&mut cb)).map_err(Failure::input)?
    };
    temps.remove(&mut mesh);
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
