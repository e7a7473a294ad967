//! `meshloom validate FILE [--json]`: a strict read, then every structural
//! rule.

use meshloom::io::{self, Position, ReadOptions};
use serde_json::json;

use crate::cli::ValidateArgs;
use crate::output;
use crate::progress::Progress;
use crate::Failure;

/// Print a verdict; exit 1 if the file is not a valid mesh as it stands.
pub fn run(args: &ValidateArgs) -> Result<(), Failure> {
    let path = &args.file;
    let name = path.display().to_string();
    let progress = Progress::spinner(format!("checking {name}"));
    let verdict = io::read(path).map_err(|e| {
        let (line, byte) = match e.location().position {
            Position::Line(l) => (Some(l), None),
            Position::Byte(b) => (None, Some(b)),
            Position::Whole => (None, None),
        };
        (e.to_string(), line, byte)
    });
    let verdict = verdict.and_then(|mesh| {
        mesh.validate()
            .map(|()| mesh)
            .map_err(|e| (format!("{name}: {e}"), None, None))
    });
    // For an invalid file, say whether `meshloom repair` would fix it.
    let repairable = verdict.is_err() && io::read_with(path, &ReadOptions::repair_all()).is_ok();
    drop(progress);
    match verdict {
        Ok(mesh) => {
            if args.json {
                output::json(&json!({
                    "file": name,
                    "valid": true,
                    "vertices": mesh.vertex_count(),
                    "edges": mesh.edge_count(),
                    "faces": mesh.face_count(),
                    "holes": mesh.hole_count(),
                }))
            } else {
                output::print(&format!(
                    "{name}: valid ({} vertices, {} edges, {} faces, {} holes)\n",
                    mesh.vertex_count(),
                    mesh.edge_count(),
                    mesh.face_count(),
                    mesh.hole_count()
                ))
            }
        }
        Err((message, line, byte)) => {
            if args.json {
                output::json(&json!({
                    "file": name,
                    "valid": false,
                    "error": message,
                    "line": line,
                    "byte_offset": byte,
                    "repairable": repairable,
                }))?;
                return Err(Failure::reported());
            }
            let hint = if repairable {
                format!("\nhint: `meshloom repair {name} OUT` reads it with repairs")
            } else {
                String::new()
            };
            Err(Failure::input(format!("invalid: {message}{hint}")))
        }
    }
}
