//! `meshloom convert IN OUT [--repair]`, `meshloom repair IN OUT [--json]`
//! and `meshloom triangulate IN OUT [--json]`: read, change, write.

use serde_json::json;

use crate::cli::{ConvertArgs, ReadArgs, RepairArgs, TriangulateArgs};
use crate::output::{self, to_json};
use crate::progress::Progress;
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

/// Read, triangulate every face of more than three sides, write.
pub fn triangulate(args: &TriangulateArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read)?;
    let faces_before = mesh.face_count();
    let left = {
        let _progress = Progress::spinner("triangulating");
        mesh.triangulate_all()
    };
    input::write(&mesh, &args.output)?;
    let triangles = mesh
        .faces()
        .filter(|&f| mesh.face(f).is_ok_and(|v| v.degree() == 3))
        .count();
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "faces_before": faces_before,
            "faces": mesh.face_count(),
            "triangles": triangles,
            "left_as_they_were": left.len(),
        }));
    }
    let mut text = format!(
        "{faces_before} faces became {} ({triangles} triangles)\nwrote {}\n",
        mesh.face_count(),
        args.output.display()
    );
    if !left.is_empty() {
        text.push_str(&format!(
            "{} faces left as they were: every way to cut them needs an edge that exists already\n",
            left.len()
        ));
    }
    output::print(&text)
}
