//! `meshloom convert IN OUT [--repair]` and `meshloom repair IN OUT [--json]`.

use serde_json::json;

use crate::cli::{ConvertArgs, ReadArgs, RepairArgs};
use crate::output::{self, to_json};
use crate::{input, Failure};

/// Read one format, write another.
pub fn convert(args: &ConvertArgs) -> Result<(), Failure> {
    let (mesh, repairs) = input::read(&args.input, args.read)?;
    input::write(&mesh, &args.output)?;
    let mut text = format!(
        "wrote {} ({} vertices, {} faces)\n",
        args.output.display(),
        mesh.vertex_count(),
        mesh.face_count()
    );
    if let Some(report) = repairs {
        text.push_str(&format!("{report}\n"));
    }
    output::print(&text)
}

/// Read with every repair on, write, report what was done.
pub fn repair(args: &RepairArgs) -> Result<(), Failure> {
    let (mesh, report) = input::read(&args.input, ReadArgs { repair: true })?;
    let report = report.unwrap_or_default();
    input::write(&mesh, &args.output)?;
    let stats = mesh.stats();
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "clean": report.is_clean(),
            "repairs": to_json(&report)?,
            "result": to_json(&stats)?,
        }));
    }
    output::print(&format!(
        "{report}\nwrote {} ({} vertices, {} edges, {} faces, {} holes, {} components)\n",
        args.output.display(),
        stats.vertices,
        stats.edges,
        stats.faces,
        stats.holes,
        stats.components
    ))
}
