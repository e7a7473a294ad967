//! `meshloom check FILE --self-intersections [--json]`: geometric checks
//! beyond the structural rules `validate` applies.

use meshloom::query::FaceTree;
use serde_json::json;

use crate::cli::CheckArgs;
use crate::{input, output, Failure};

/// How many pairs the text report lists.
const SHOWN: usize = 20;

/// Report the pairs of faces that intersect (face indices in the file's
/// order); exit 1 when there are any.
pub fn run(args: &CheckArgs) -> Result<(), Failure> {
    if !args.self_intersections {
        return Err(Failure::usage("name a check to run: --self-intersections"));
    }
    let (mesh, _) = input::read(&args.file, args.read, args.json)?;
    let tree = FaceTree::build(&mesh)
        .map_err(|e| Failure::input(format!("{}: {e}", args.file.display())))?;
    let pairs = tree
        .self_intersections(&mesh)
        .map_err(|e| Failure::input(e.to_string()))?;
    let indices: Vec<[usize; 2]> = pairs.iter().map(|p| [p.0.index(), p.1.index()]).collect();
    if args.json {
        output::json(&json!({
            "file": args.file.display().to_string(),
            "self_intersections": indices.len(),
            "pairs": indices,
        }))?;
    } else {
        let mut text = format!(
            "{}: {} self-intersecting face pair{}\n",
            args.file.display(),
            indices.len(),
            if indices.len() == 1 { "" } else { "s" }
        );
        for [a, b] in indices.iter().take(SHOWN) {
            text.push_str(&format!("  faces {a} {b}\n"));
        }
        if indices.len() > SHOWN {
            text.push_str(&format!("  ... and {} more\n", indices.len() - SHOWN));
        }
        output::print(&text)?;
    }
    if indices.is_empty() {
        Ok(())
    } else {
        Err(Failure {
            code: Failure::INPUT,
            message: String::new(),
        })
    }
}
