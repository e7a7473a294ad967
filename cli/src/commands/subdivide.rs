//! `meshloom subdivide IN OUT --scheme loop|catmull-clark|sqrt3|midpoint
//! [--levels N] [--crease-column NAME] [--corners] [--json]`.

use serde_json::json;

use meshloom::algo::{
    self, Boundary, Flow, MidpointOptions, ProgressInfo, SubdivisionOptions, SubdivisionReport,
};

use crate::cli::{Scheme, SubdivideArgs};
use crate::output::{self, to_json};
use crate::progress::Progress;
use crate::{input, Failure};

/// Read, subdivide, write, report the counts of every level.
pub fn run(args: &SubdivideArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let options = SubdivisionOptions {
        levels: args.levels,
        boundary: if args.corners {
            Boundary::CreaseAndCorners
        } else {
            Boundary::Crease
        },
        crease_column: args.crease_column.clone(),
        max_faces: args.max_faces,
        ..SubdivisionOptions::default()
    };
    let report = {
        let bar = Progress::spinner(format!("subdividing ({})", args.scheme.name()));
        let mut show = |info: &ProgressInfo<'_>| {
            bar.message(format!(
                "{}: {} {}/{}",
                args.scheme.name(),
                info.stage,
                info.done,
                info.total
            ));
            Flow::Continue
        };
        let progress = algo::Progress::new(&mut show);
        let done: meshloom::Result<SubdivisionReport> = match args.scheme {
            Scheme::Loop => algo::loop_subdivide(&mut mesh, &options, progress),
            Scheme::CatmullClark => algo::catmull_clark(&mut mesh, &options, progress),
            Scheme::Sqrt3 => algo::sqrt3_subdivide(&mut mesh, &options, progress),
            Scheme::Midpoint => {
                if args.crease_column.is_some() {
                    return Err(Failure::input(
                        "--crease-column needs --scheme loop or catmull-clark",
                    ));
                }
                let options = MidpointOptions {
                    max_faces: args.max_faces,
                    ..MidpointOptions::levels(args.levels)
                };
                algo::midpoint_subdivide(&mut mesh, &options, progress)
            }
        };
        done.map_err(Failure::input)?
    };
    input::write(&mesh, &args.output, false, false)?;
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "scheme": args.scheme.name(),
            "report": to_json(&report)?,
        }));
    }
    let mut text = String::new();
    let c = report.input;
    text.push_str(&format!(
        "input: {} vertices, {} edges, {} faces, {} holes\n",
        c.vertices, c.edges, c.faces, c.holes
    ));
    for (i, level) in report.levels.iter().enumerate() {
        let c = level.counts;
        text.push_str(&format!(
            "level {}: {} vertices, {} edges, {} faces, {} holes\n",
            i + 1,
            c.vertices,
            c.edges,
            c.faces,
            c.holes
        ));
    }
    text.push_str(&format!("wrote {}\n", args.output.display()));
    output::print(&text)
}
