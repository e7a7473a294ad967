//! `meshloom subdivide IN OUT --scheme loop|catmull-clark|sqrt3|midpoint
//! [--levels N] [--crease-column NAME] [--corner-column NAME] [--corners]
//! [--midpoint-faces auto|quads|triangles] [--json]`: the library's one
//! driver, [`algo::subdivide`], which also checks the options (a crease
//! column only for loop and catmull-clark).

use serde_json::json;

use meshloom::algo::{self, Boundary, Flow, ProgressInfo, SubdivisionOptions};

use crate::cli::SubdivideArgs;
use crate::output::{self, to_json};
use crate::progress::Progress;
use crate::{input, Failure};

/// Read, subdivide, write, report the counts of every level.
pub fn run(args: &SubdivideArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let options = SubdivisionOptions::default()
        .levels(args.levels)
        .boundary(if args.corners {
            Boundary::CreaseAndCorners
        } else {
            Boundary::Crease
        })
        .corner_column(args.corner_column.clone())
        .crease_column(args.crease_column.clone())
        .midpoint_faces(args.midpoint_faces)
        .max_faces(args.max_faces);
    let scheme = args.scheme;
    let report = {
        let bar = Progress::spinner(format!("subdividing ({scheme})"));
        let mut show = |info: &ProgressInfo<'_>| {
            bar.message(format!(
                "{scheme}: {} {}/{}",
                info.stage, info.done, info.total
            ));
            Flow::Continue
        };
        let progress = algo::Progress::new(&mut show);
        algo::subdivide(&mut mesh, scheme, &options, progress).map_err(Failure::input)?
    };
    input::write(&mesh, &args.output, false, false)?;
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "scheme": scheme.word(),
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
        let c = level.output;
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
