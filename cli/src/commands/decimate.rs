//! `meshloom decimate IN OUT (--ratio R | --vertices N | --faces N |
//! --max-error E)` and `meshloom lod IN OUT_PREFIX --ratios ...`: quadric
//! decimation, once or through several levels.

use std::path::{Path, PathBuf};

use meshloom::algo::decimate::{
    decimate as run_decimate, lod_chain, DecimateOptions, DecimateReport, Keep, LodOptions, Target,
};
use meshloom::algo::{Flow, ProgressInfo};
use meshloom::Mesh;
use serde_json::json;

use crate::cli::{ConstraintArgs, DecimateArgs, LodArgs};
use crate::commands::constraints::{self, Temps};
use crate::output::{self, to_json};
use crate::progress::Progress;
use crate::{input, Failure};

/// The library's options from the flags shared by both commands (the old
/// `--keep-boundary` and `--keep-seams` mean lock, with a warning).
fn options(
    mesh: &mut Mesh,
    keep: &ConstraintArgs,
    keep_boundary: bool,
    keep_seams: bool,
) -> Result<(DecimateOptions, Temps), Failure> {
    let mut o = DecimateOptions::default();
    let (c, temps) = constraints::resolve(mesh, keep, o.constraints(), None)?;
    o = o.with_constraints(c);
    if keep_boundary {
        constraints::deprecated("--keep-boundary", "--boundary lock");
        o.boundary = Keep::Lock;
    }
    if keep_seams {
        constraints::deprecated("--keep-seams", "--seams lock");
        o.seams = Keep::Lock;
    }
    Ok((o, temps))
}

fn summary(r: &DecimateReport) -> String {
    let why = match r.stopped_by {
        meshloom::algo::decimate::StopReason::Target => "the target was reached",
        meshloom::algo::decimate::StopReason::MaxError => {
            "the next collapse would pass --max-error"
        }
        meshloom::algo::decimate::StopReason::NoCollapses => {
            "no edge could be collapsed any more (kept lines or refused)"
        }
    };
    format!(
        "{} vertices, {} faces -> {} vertices, {} faces ({} collapses; {why}); largest error {:.4e}\n\
         refused: {} by topology, {} by normal deviation, {} by quality, {} by valence; {} vertices fixed\n",
        r.input.vertices,
        r.input.faces,
        r.output.vertices,
        r.output.faces,
        r.collapses,
        r.error,
        r.refused.topology,
        r.refused.normal,
        r.refused.quality,
        r.refused.valence,
        r.fixed
    )
}

/// Read, decimate, write.
pub fn decimate(args: &DecimateArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let (mut opts, temps) = options(&mut mesh, &args.keep, args.keep_boundary, args.keep_seams)?;
    opts.target = match (args.ratio, args.vertices, args.faces) {
        (Some(r), _, _) => Target::Ratio(r),
        (_, Some(n), _) => Target::Vertices(n),
        (_, _, Some(n)) => Target::Faces(n),
        _ => Target::None,
    };
    opts.max_error = args.max_error;
    let report = {
        let bar = Progress::bar("decimating", 1);
        let mut cb = |p: &ProgressInfo<'_>| {
            bar.set_length(p.total);
            bar.set(p.done as usize);
            Flow::Continue
        };
        run_decimate(&mut mesh, &opts, meshloom::algo::Progress::new(&mut cb))
            .map_err(Failure::input)?
    };
    temps.remove(&mut mesh);
    input::write(&mesh, &args.output, false, false)?;
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "report": to_json(&report)?,
        }));
    }
    output::print(&format!(
        "{}wrote {}\n",
        summary(&report),
        args.output.display()
    ))
}

/// `prefix` with `_{level}` before its mesh extension (or `.obj` added
/// when it has none).
pub fn level_path(prefix: &Path, level: usize) -> PathBuf {
    let name = prefix.to_string_lossy();
    for ext in [
        ".obj.gz", ".off.gz", ".ply.gz", ".stl.gz", ".obj", ".off", ".ply", ".stl", ".gltf", ".glb",
    ] {
        if let Some(stem) = name.strip_suffix(ext) {
            return PathBuf::from(format!("{stem}_{level}{ext}"));
        }
    }
    PathBuf::from(format!("{name}_{level}.obj"))
}

/// Read, decimate through every ratio, write each level.
pub fn lod(args: &LodArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let (decimate, temps) = options(&mut mesh, &args.keep, args.keep_boundary, args.keep_seams)?;
    let opts = LodOptions::default()
        .targets(args.ratios.iter().map(|&r| Target::Ratio(r)).collect())
        .decimate(decimate)
        .meshes(true)
        .record(false);
    let chain = {
        let bar = Progress::bar("decimating", 1);
        let mut cb = |p: &ProgressInfo<'_>| {
            bar.set_length(p.total);
            bar.set(p.done as usize);
            Flow::Continue
        };
        lod_chain(&mesh, &opts, meshloom::algo::Progress::new(&mut cb)).map_err(Failure::input)?
    };
    let mut levels = Vec::new();
    let mut text = String::new();
    for (i, (mut level, ratio)) in chain.levels.into_iter().zip(&args.ratios).enumerate() {
        let path = level_path(&args.output_prefix, i + 1);
        if let Some(m) = &mut level.mesh {
            temps.clone().remove(m);
            input::write(m, &path, false, false)?;
        }
        text.push_str(&format!(
            "level {} (ratio {ratio}): {} vertices, {} faces, largest error {:.4e}; wrote {}\n",
            i + 1,
            level.report.output.vertices,
            level.report.output.faces,
            level.report.error,
            path.display()
        ));
        levels.push(json!({
            "ratio": ratio,
            "output": path.display().to_string(),
            "report": to_json(&level.report)?,
        }));
    }
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "levels": levels,
        }));
    }
    output::print(&text)
}
