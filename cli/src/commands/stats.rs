//! `meshloom stats FILE... [--json] [--repair]` and `meshloom components
//! FILE [--json] [--repair]`.

use serde_json::{json, Value};

use crate::batch::{Batch, Record, Source};
use crate::cli::{ComponentsArgs, StatsArgs};
use crate::output::{self, to_json};
use crate::{input, Failure};

/// Print each mesh's figures: aligned text for one file, a table for
/// several, or one JSON object per file.
pub fn run(args: &StatsArgs) -> Result<(), Failure> {
    let batch = Batch::expand(&args.files, args.format)?;
    let records = batch.run(|_, source| one(source, args, batch.several));
    batch.report("stats", &records, args.json, false)
}

/// The figures of one input.
fn one(source: &Source, args: &StatsArgs, quiet: bool) -> Record {
    let name = source.name();
    let (mesh, repairs) = match source.read(args.read, args.format, quiet) {
        Ok(read) => read,
        Err(f) => return Record::failed(name, f.message),
    };
    let stats = mesh.stats();
    let mut record = Record::ok(name.clone(), &mesh);
    let parts = match stats.components {
        1 => "1 component".to_string(),
        n => format!("{n} components"),
    };
    record.status = match stats.holes {
        0 => format!("closed, {parts}"),
        1 => format!("1 hole, {parts}"),
        n => format!("{n} holes, {parts}"),
    };
    if let Ok(Value::Object(fields)) = to_json(&stats) {
        record.fields = fields;
    }
    record
        .fields
        .insert("closed".into(), json!(stats.is_closed()));
    if let Some(report) = &repairs {
        if let Ok(r) = to_json(report) {
            record.fields.insert("repairs".into(), r);
        }
    }
    let mut text = format!("{:<22}{name}\n{stats}", "file");
    if stats.boundary_loops != stats.holes {
        text.push_str(&format!(
            "{:<22}boundary loops meet at pinched vertices: {} hole faces pass through {} loops \
             (loops counted as independent checkers walk them)\n",
            "note", stats.holes, stats.boundary_loops
        ));
    }
    if let Some(report) = &repairs {
        for line in report.to_string().lines() {
            text.push_str(&format!("{:<22}{line}\n", "repairs"));
        }
    }
    record.text = text;
    record
}

/// Print one row of figures per connected component.
pub fn components(args: &ComponentsArgs) -> Result<(), Failure> {
    let (mesh, _) = input::read(&args.file, args.read, false)?;
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
