//! `meshloom stats FILE [--json] [--repair]` and `meshloom components FILE
//! [--json] [--repair]`.

use serde_json::json;

use crate::cli::StatsArgs;
use crate::output::{self, to_json};
use crate::{input, Failure};

/// Print the mesh's figures as aligned text or one JSON object.
pub fn run(args: &StatsArgs) -> Result<(), Failure> {
    let (mesh, repairs) = input::read(&args.file, args.read)?;
    let stats = mesh.stats();
    if args.json {
        let mut value = to_json(&stats)?;
        value["file"] = json!(args.file.display().to_string());
        value["closed"] = json!(stats.is_closed());
        if let Some(report) = &repairs {
            value["repairs"] = to_json(report)?;
        }
        return output::json(&value);
    }
    let mut text = format!("{:<22}{}\n{stats}", "file", args.file.display());
    if let Some(report) = &repairs {
        for line in report.to_string().lines() {
            text.push_str(&format!("{:<22}{line}\n", "repairs"));
        }
    }
    output::print(&text)
}

/// Print one row of figures per connected component.
pub fn components(args: &StatsArgs) -> Result<(), Failure> {
    let (mesh, _) = input::read(&args.file, args.read)?;
    let parts = mesh.component_stats();
    if args.json {
        return output::json(&json!({
            "file": args.file.display().to_string(),
            "components": to_json(&parts)?,
        }));
    }
    let mut text = format!(
        "{:>9} {:>9} {:>9} {:>9} {:>6} {:>6} {:>6}\n",
        "component", "vertices", "edges", "faces", "holes", "euler", "genus"
    );
    for (i, c) in parts.iter().enumerate() {
        let genus = c.genus.map_or("-".to_string(), |g| g.to_string());
        text.push_str(&format!(
            "{i:>9} {:>9} {:>9} {:>9} {:>6} {:>6} {genus:>6}\n",
            c.vertices, c.edges, c.faces, c.holes, c.euler_characteristic
        ));
    }
    output::print(&text)
}
