//! `meshloom fair IN OUT [--region COLUMN] [--order 1|2|3]
//! [--weights cotan|uniform] [--boundary free|slide|lock] ...`: move a
//! region's vertices to the smoothest surface with `meshloom::algo::fair`,
//! then write.

use meshloom::algo::fair::{fair, FairOptions, FairRegion};
use meshloom::algo::{Flow, ProgressInfo};
use meshloom::Mesh;
use serde_json::json;

use crate::cli::FairArgs;
use crate::commands::constraints::{self, Temps};
use crate::commands::normals;
use crate::output;
use crate::progress::Progress;
use crate::{input, Failure};

/// The library's options from the flags (its defaults where a flag is
/// absent), with the columns they name read into temporary columns.
fn options(mesh: &mut Mesh, args: &FairArgs) -> Result<(FairOptions, Temps), Failure> {
    let mut o = FairOptions::default();
    if let Some(order) = args.order {
        o = o.order(order);
    }
    if let Some(weights) = args.weights {
        o = o.weights(weights);
    }
    let (c, mut temps) = constraints::resolve(mesh, &args.keep, o.constraints(), None)?;
    o = o.with_constraints(c);
    if let Some(name) = &args.region {
        match temps.region(mesh, name, "--region") {
            Ok(h) => o = o.region(FairRegion::Mask(h)),
            Err(e) => {
                temps.remove(mesh);
                return Err(e);
            }
        }
    }
    Ok((o, temps))
}

/// Read, fair, optionally add normals, write, report.
pub fn run(args: &FairArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let (opts, temps) = options(&mut mesh, args)?;
    let report = {
        let bar = Progress::bar("fairing", 1);
        let mut cb = |p: &ProgressInfo<'_>| {
            bar.set_length(p.total);
            bar.set(p.done as usize);
            Flow::Continue
        };
        fair(&mut mesh, &opts, meshloom::algo::Progress::new(&mut cb))
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
            "order": opts.order,
            "weights": opts.weights.word(),
            "moved": report.moved,
            "fixed": report.fixed,
            "max_displacement": report.max_displacement,
            "dropped_columns": dropped,
            "normals": normals,
        }));
    }
    let mut text = format!(
        "order {} fairing ({} weights): {} vertices moved (at most {:.6}), {} fixed\n",
        opts.order, opts.weights, report.moved, report.max_displacement, report.fixed
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
