//! `meshloom convert IN OUT [--repair]`, `meshloom repair IN OUT [--json]`
//! `meshloom triangulate IN OUT [--json]` and `meshloom fill-holes IN OUT`:
//! read, change, write.

use serde_json::json;

use crate::cli::{ConvertArgs, FillHolesArgs, ReadArgs, RepairArgs, TriangulateArgs};
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

/// Read, fill the holes asked for (and triangulate the new faces), write.
pub fn fill_holes(args: &FillHolesArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read)?;
    let holes_before = mesh.hole_count();
    let max = args.max_sides.unwrap_or(u64::MAX);
    let (mut filled, mut too_big, mut refused, mut untriangulated) = (0, 0, 0, 0);
    {
        let _progress = Progress::spinner("filling holes");
        let holes: Vec<_> = mesh.holes().collect();
        for hole in holes {
            let sides = mesh.face(hole).map_or(0, |h| h.degree()) as u64;
            if sides > max {
                too_big += 1;
                continue;
            }
            match mesh.fill_hole(hole) {
                Ok(face) => {
                    filled += 1;
                    if args.triangulate && mesh.triangulate(face).is_err() {
                        untriangulated += 1;
                    }
                }
                Err(_) => refused += 1,
            }
        }
    }
    input::write(&mesh, &args.output)?;
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "holes_before": holes_before,
            "filled": filled,
            "larger_than_max_sides": too_big,
            "refused": refused,
            "left_untriangulated": untriangulated,
            "holes": mesh.hole_count(),
        }));
    }
    let mut text = format!(
        "filled {filled} of {holes_before} holes; {} left\n",
        mesh.hole_count()
    );
    if too_big > 0 {
        text.push_str(&format!("{too_big} holes have more than {max} sides\n"));
    }
    if refused > 0 {
        text.push_str(&format!(
            "{refused} holes pass a vertex twice (bowtie) and were left open\n"
        ));
    }
    if untriangulated > 0 {
        text.push_str(&format!(
            "{untriangulated} new faces could not be triangulated (every cut needs an existing edge)\n"
        ));
    }
    text.push_str(&format!("wrote {}\n", args.output.display()));
    output::print(&text)
}
