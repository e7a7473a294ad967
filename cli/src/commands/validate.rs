//! `meshloom validate FILE... [--json]`: a strict read, then every
//! structural rule.

use meshloom::io::{self, Position, ReadOptions};
use serde_json::json;

use crate::batch::{Batch, Record, Source};
use crate::cli::{ReadArgs, ValidateArgs};
use crate::progress::Progress;
use crate::Failure;

/// Print a verdict per file; exit 1 if any file is not a valid mesh as it
/// stands.
pub fn run(args: &ValidateArgs) -> Result<(), Failure> {
    let batch = Batch::expand(&args.files, args.format)?;
    let records = batch.run(|_, source| one(source, args, batch.several));
    batch.report("validate", &records, args.json, false)
}

/// The verdict on one input.
fn one(source: &Source, args: &ValidateArgs, quiet: bool) -> Record {
    let name = source.name();
    let progress = (!quiet).then(|| Progress::spinner(format!("checking {name}")));
    let (verdict, repairable) = match source {
        Source::File { path, .. } => {
            let verdict = io::read(path).map_err(|e| located(&e));
            let verdict = verdict.and_then(|mesh| {
                mesh.validate()
                    .map(|()| mesh)
                    .map_err(|e| (format!("{name}: {e}"), None, None))
            });
            // For an invalid file, say whether `meshloom repair` would fix it.
            let repairable =
                verdict.is_err() && io::read_with(path, &ReadOptions::repair_all()).is_ok();
            (verdict, repairable)
        }
        // Standard input can be read once: no second, repairing read.
        Source::Stdin => {
            let verdict = source
                .read(ReadArgs::default(), args.format, quiet)
                .map_err(|f| (f.message, None, None))
                .and_then(|(mesh, _)| {
                    mesh.validate()
                        .map(|()| mesh)
                        .map_err(|e| (format!("standard input: {e}"), None, None))
                });
            (verdict, false)
        }
    };
    drop(progress);
    match verdict {
        Ok(mesh) => {
            let mut record = Record::ok(name.clone(), &mesh);
            record.status = "valid".into();
            for (k, v) in [
                ("valid", json!(true)),
                ("edges", json!(mesh.edge_count())),
                ("holes", json!(mesh.hole_count())),
            ] {
                record.fields.insert(k.into(), v);
            }
            record.text = format!(
                "{name}: valid ({} vertices, {} edges, {} faces, {} holes)\n",
                mesh.vertex_count(),
                mesh.edge_count(),
                mesh.face_count(),
                mesh.hole_count()
            );
            record
        }
        Err((message, line, byte)) => {
            let hint = if repairable {
                format!("\nhint: `meshloom repair {name} OUT` reads it with repairs")
            } else {
                String::new()
            };
            let mut record = Record::failed(name, format!("invalid: {message}{hint}"));
            for (k, v) in [
                ("valid", json!(false)),
                ("line", json!(line)),
                ("byte_offset", json!(byte)),
                ("repairable", json!(repairable)),
            ] {
                record.fields.insert(k.into(), v);
            }
            record
        }
    }
}

/// The message and the line or byte offset of a reading error.
fn located(e: &io::Error) -> (String, Option<u64>, Option<u64>) {
    let (line, byte) = match e.location().position {
        Position::Line(l) => (Some(l), None),
        Position::Byte(b) => (None, Some(b)),
        Position::Whole => (None, None),
    };
    (e.to_string(), line, byte)
}
