//! `meshloom convert IN OUT [--repair]` (or `INPUTS... --out-dir DIR`),
//! `meshloom repair IN OUT [--json]` (or `INPUTS... --out-dir DIR`),
//! `meshloom triangulate IN OUT [--json]` and `meshloom fill-holes IN OUT`:
//! read, change, write.

use meshloom::io;
use serde_json::json;

use crate::batch::{self, Record, Source, Target};
use crate::cli::{ConvertArgs, FillHolesArgs, ReadArgs, RepairArgs, TriangulateArgs};
use crate::commands::normals;
use crate::input::MeshFormat;
use crate::output::{self, to_json};
use crate::progress::Progress;
use crate::{input, Failure};

/// Read one format, write another; say which attributes the output format
/// cannot hold. `IN OUT`, or many inputs with `--out-dir`.
pub fn convert(args: &ConvertArgs) -> Result<(), Failure> {
    let (batch, targets) = batch::plan(&args.paths, &args.out)?;
    let records = batch.run(|i, source| convert_one(source, &targets[i], args, batch.several));
    let to_stderr = targets.first() == Some(&Target::Stdout);
    batch.report("convert", &records, args.json, to_stderr)
}

fn convert_one(source: &Source, target: &Target, args: &ConvertArgs, quiet: bool) -> Record {
    let name = source.name();
    let (mut mesh, repairs) = match source.read(args.read, args.out.format, quiet) {
        Ok(read) => read,
        Err(f) => return Record::failed(name, f.message),
    };
    let plain = match target.format(args.out.format) {
        Some(MeshFormat::Plain(format, _)) => Some(format),
        _ => None,
    };
    let normals = if args.normals {
        match normals::add_for(&mut mesh, plain) {
            Ok(n) => Some(n),
            Err(f) => return Record::failed(name, f.message),
        }
    } else {
        None
    };
    let mut record = Record::ok(name, &mesh);
    record.fields.insert("input".into(), json!(record.file));
    record.fields.insert("output".into(), json!(target.name()));
    if let Err(f) = target.write(&mesh, args.out.format, quiet) {
        record.error = Some(f.message);
        return record;
    }
    let dropped = match plain {
        Some(format) => io::dropped_columns(&mesh, format),
        None => Vec::new(),
    };
    record.status = match dropped.len() {
        0 => format!("wrote {}", target.name()),
        n => format!("wrote {} ({n} attributes dropped)", target.name()),
    };
    record.fields.insert("dropped".into(), json!(dropped));
    let mut text = format!(
        "wrote {} ({} vertices, {} faces)\n",
        target.name(),
        mesh.vertex_count(),
        mesh.face_count()
    );
    for d in &dropped {
        text.push_str(&format!(
            "dropped: {d} (the output format cannot hold it)\n"
        ));
    }
    if let Some(n) = normals {
        text.push_str(&format!("normals: {n}\n"));
        record.fields.insert("normals".into(), json!(n));
    }
    if let Some(report) = repairs {
        if let Ok(r) = to_json(&report) {
            record.fields.insert("repairs".into(), r);
        }
        text.push_str(&format!("{report}\n"));
    }
    record.text = text;
    record
}

/// Read with every repair on, write, report what was done. `IN OUT`, or
/// many inputs with `--out-dir`. With `--json`, a failure prints
/// `{"ok": false, "error": ...}` too (and exits 1).
pub fn repair(args: &RepairArgs) -> Result<(), Failure> {
    let (batch, targets) = batch::plan(&args.paths, &args.out)?;
    let records = batch.run(|i, source| repair_one(source, &targets[i], args, batch.several));
    let to_stderr = targets.first() == Some(&Target::Stdout);
    batch.report("repair", &records, args.json, to_stderr)
}

fn repair_one(source: &Source, target: &Target, args: &RepairArgs, quiet: bool) -> Record {
    let name = source.name();
    let how = ReadArgs {
        repair: true,
        weld: args.weld,
    };
    let mut failed = Record::failed(name.clone(), String::new());
    failed.fields.insert("input".into(), json!(name));
    failed.fields.insert("output".into(), json!(target.name()));
    let (mesh, report) = match source.read(how, args.out.format, quiet) {
        Ok(read) => read,
        Err(f) => {
            failed.error = Some(f.message);
            return failed;
        }
    };
    let report = report.unwrap_or_default();
    if let Err(f) = target.write(&mesh, args.out.format, quiet) {
        failed.error = Some(f.message);
        return failed;
    }
    let stats = mesh.stats();
    let mut record = Record::ok(name, &mesh);
    record.fields = failed.fields;
    record
        .fields
        .insert("clean".into(), json!(report.is_clean()));
    if let (Ok(r), Ok(s)) = (to_json(&report), to_json(&stats)) {
        record.fields.insert("repairs".into(), r);
        record.fields.insert("result".into(), s);
    }
    record.status = if report.is_clean() {
        format!("wrote {} (no repairs needed)", target.name())
    } else {
        format!("wrote {} (repaired)", target.name())
    };
    record.text = format!(
        "{report}\nwrote {} ({} vertices, {} edges, {} faces, {} holes, {} boundary loops, {} components)\n",
        target.name(),
        stats.vertices,
        stats.edges,
        stats.faces,
        stats.holes,
        stats.boundary_loops,
        stats.components
    );
    record
}

/// Read, triangulate every face of more than three sides, write.
pub fn triangulate(args: &TriangulateArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let faces_before = mesh.face_count();
    let left = {
        let _progress = Progress::spinner("triangulating");
        mesh.triangulate_all()
    };
    input::write(&mesh, &args.output, false, false)?;
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
    if args.refine || args.fair {
        return fill_holes_liepa(args);
    }
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
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
    input::write(&mesh, &args.output, false, false)?;
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

/// `fill-holes --refine` / `--fair`: `algo::fill_hole::fill_holes`.
fn fill_holes_liepa(args: &FillHolesArgs) -> Result<(), Failure> {
    use meshloom::algo::fill_hole::{fill_holes, FillHoleOptions};
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let holes_before = mesh.hole_count();
    let max = args
        .max_sides
        .map(|m| usize::try_from(m).unwrap_or(usize::MAX));
    let too_big = mesh
        .holes()
        .filter(|&h| max.is_some_and(|m| mesh.face(h).map_or(0, |f| f.degree()) > m))
        .count();
    let options = FillHoleOptions::default()
        .max_rim(max)
        .refine(true)
        .fair(args.fair)
        .fair_order(args.fair_order.unwrap_or(2))
        .max_refined_rim(args.max_refined_rim);
    let report = {
        let _progress = Progress::spinner("filling holes");
        fill_holes(&mut mesh, &options, meshloom::algo::Progress::none()).map_err(Failure::input)?
    };
    let refused = report.skipped.len() - too_big;
    input::write(&mesh, &args.output, false, false)?;
    let method = if args.fair { "fair" } else { "refine" };
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "method": method,
            "holes_before": holes_before,
            "filled": report.holes_filled,
            "larger_than_max_sides": too_big,
            "refused": refused,
            "left_untriangulated": 0,
            "faces_added": report.faces_added,
            "vertices_added": report.vertices_added,
            "ear_clipped": report.ear_clipped,
            "unrefined": report.unrefined,
            "holes": mesh.hole_count(),
        }));
    }
    let mut text = format!(
        "filled {} of {holes_before} holes ({method}): {} faces and {} vertices added; {} left\n",
        report.holes_filled,
        report.faces_added,
        report.vertices_added,
        mesh.hole_count()
    );
    if too_big > 0 {
        text.push_str(&format!(
            "{too_big} holes have more than {} sides\n",
            args.max_sides.unwrap_or(0)
        ));
    }
    if refused > 0 {
        text.push_str(&format!(
            "{refused} holes pass a vertex twice (bowtie) and were left open\n"
        ));
    }
    if report.ear_clipped > 0 {
        text.push_str(&format!(
            "{} holes were cut by ear clipping (too long for the optimal triangulation)\n",
            report.ear_clipped
        ));
    }
    if report.unrefined > 0 {
        text.push_str(&format!(
            "{} holes were filled without refinement (rims over {} edges)\n",
            report.unrefined,
            FillHoleOptions::default().max_refined_rim
        ));
    }
    text.push_str(&format!("wrote {}\n", args.output.display()));
    output::print(&text)
}
