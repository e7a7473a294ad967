//! `meshloom stats FILE [--json] [--repair]`.

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
