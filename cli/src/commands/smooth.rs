//! `meshloom smooth IN OUT --method uniform|cotan|taubin|implicit`: move
//! the vertices with `meshloom::algo::smooth`, then write.

use meshloom::algo::smooth::{smooth, SmoothOptions};
use meshloom::algo::{Flow, Keep, ProgressInfo};
use serde_json::json;

use crate::cli::SmoothArgs;
use crate::commands::{constraints, normals};
use crate::output;
use crate::progress::Progress;
use crate::{input, Failure};

/// Read, smooth, optionally add normals, write, report.
pub fn run(args: &SmoothArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let method = args.method;
    let defaults = SmoothOptions::with_method(method);
    let iterations = args.iterations.unwrap_or(defaults.iterations);
    let mut options = defaults
        .iterations(iterations)
        .step(args.step)
        .rescale(args.rescale);
    if args.mask_column.is_some() {
        constraints::deprecated("--mask-column NAME", "--pinned with the complement");
    }
    let (c, temps) = constraints::resolve(
        &mut mesh,
        &args.keep,
        options.constraints(),
        args.mask_column.as_deref(),
    )?;
    options = options.with_constraints(c);
    if args.free_boundary {
        constraints::deprecated("--free-boundary", "--boundary free");
        options.boundary = Keep::Free;
    }
    let report = {
        let bar = Progress::bar("smoothing", options.iterations as usize);
        let mut callback = |info: &ProgressInfo<'_>| {
            bar.set(info.done as usize);
            Flow::Continue
        };
        smooth(
            &mut mesh,
            &options,
            meshloom::algo::Progress::new(&mut callback),
        )
    };
    temps.remove(&mut mesh);
    let report = report.map_err(Failure::input)?;
    let dropped = normals::drop_stale(&mut mesh);
    let normals = if args.normals {
        Some(normals::add_for_path(&mut mesh, &args.output)?)
    } else {
        None
    };
    input::write(&mesh, &args.output, false, false)?;
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "method": method.word(),
            "iterations": report.iterations,
            "step": args.step,
            "moved": report.moved,
            "fixed": report.fixed,
            "max_displacement": report.max_displacement,
            "stale_columns": report.stale,
            "dropped_columns": dropped,
            "normals": normals,
        }));
    }
    let mut text = format!(
        "{method:?} smoothing, {} iterations: {} vertices moved (at most {:.6}), {} fixed\n",
        report.iterations, report.moved, report.max_displacement, report.fixed
    );
    if !dropped.is_empty() {
        text.push_str(&format!(
            "dropped stale columns: {} (use --normals to recompute)\n",
            dropped.join(", ")
        ));
    }
    if let Some(n) = normals {
        text.push_str(&format!("normals: {n}\n"));
    }
    text.push_str(&format!("wrote {}\n", args.output.display()));
    output::print(&text)
}
