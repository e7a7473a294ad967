//! `meshloom smooth IN OUT --method uniform|cotan|taubin|implicit`: move
//! the vertices with `meshloom::algo::smooth`, then write.

use meshloom::algo::smooth::{smooth, SmoothMethod, SmoothOptions};
use meshloom::algo::{Flow, ProgressInfo};
use meshloom::attr::Value;
use meshloom::{Mesh, VertexKey};
use serde_json::json;

use crate::cli::{Method, SmoothArgs};
use crate::commands::normals;
use crate::output;
use crate::progress::Progress;
use crate::{input, Failure};

/// The temporary `bool` column that carries `--mask-column` (whatever its
/// stored type) into the library; removed before writing.
const MASK: &str = "meshloom-cli smooth mask";

/// Read, smooth, optionally add normals, write, report.
pub fn run(args: &SmoothArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let method = match args.method {
        Method::Uniform => SmoothMethod::Uniform,
        Method::Cotan => SmoothMethod::Cotan,
        Method::Taubin => SmoothMethod::Taubin,
        Method::Implicit => SmoothMethod::Implicit,
    };
    let defaults = SmoothOptions::with_method(method);
    let mut options = SmoothOptions {
        iterations: args.iterations.unwrap_or(defaults.iterations),
        step: args.step,
        fix_boundary: !args.free_boundary,
        rescale: args.rescale,
        ..defaults
    };
    if let Some(name) = &args.mask_column {
        options.mask = Some(mask_from(&mut mesh, name)?);
    }
    let report = {
        let bar = Progress::bar("smoothing", options.iterations as usize);
        let mut callback = |info: &ProgressInfo<'_>| {
            bar.set(info.done as usize);
            Flow::Continue
        };
        smooth(
            &mut mesh,
            &options,
            meshloom::algo::Progress::new(&mut callback),
        )
    };
    if let Some(mask) = &options.mask {
        // Ours, just added: removing it cannot fail.
        let _ = mesh.remove_attr(mask);
    }
    let report = report.map_err(Failure::input)?;
    let dropped = normals::drop_stale(&mut mesh);
    let normals = if args.normals {
        Some(normals::add_for_path(&mut mesh, &args.output)?)
    } else {
        None
    };
    input::write(&mesh, &args.output, false, false)?;
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "method": format!("{method:?}").to_lowercase(),
            "iterations": report.iterations,
            "step": args.step,
            "moved": report.moved,
            "fixed": report.fixed,
            "max_displacement": report.max_displacement,
            "stale_columns": report.stale,
            "dropped_columns": dropped,
            "normals": normals,
        }));
    }
    let mut text = format!(
        "{method:?} smoothing, {} iterations: {} vertices moved (at most {:.6}), {} fixed\n",
        report.iterations, report.moved, report.max_displacement, report.fixed
    );
    if !dropped.is_empty() {
        text.push_str(&format!(
            "dropped stale columns: {} (use --normals to recompute)\n",
            dropped.join(", ")
        ));
    }
    if let Some(n) = normals {
        text.push_str(&format!("normals: {n}\n"));
    }
    text.push_str(&format!("wrote {}\n", args.output.display()));
    output::print(&text)
}

/// A `bool` column holding whether the vertex column `name` is true (a
/// `bool`, or a non-zero number) at each vertex.
fn mask_from(mesh: &mut Mesh, name: &str) -> Result<meshloom::attr::VertexAttr<bool>, Failure> {
    let keys: Vec<VertexKey> = mesh.vertices().collect();
    let mut on = Vec::with_capacity(keys.len());
    for &v in &keys {
        let value = mesh
            .attr_value(name, v)
            .map_err(|e| Failure::input(format!("--mask-column: {e}")))?;
        on.push(match value {
            None => false,
            Some(Value::Bool(b)) => b,
            Some(Value::Text(t)) => {
                return Err(Failure::input(format!(
                    "--mask-column: {name:?} holds text ({t:?}), not flags or numbers"
                )))
            }
            Some(Value::List(_)) => {
                return Err(Failure::input(format!(
                    "--mask-column: {name:?} holds lists, not flags or numbers"
                )))
            }
            Some(number) => number_of(&number) != 0.0,
        });
    }
    let mask = mesh.add_vertex_attr::<bool>(MASK).map_err(Failure::input)?;
    for (&v, &b) in keys.iter().zip(&on) {
        mesh.set_attr(&mask, v, b).map_err(Failure::input)?;
    }
    Ok(mask)
}

fn number_of(v: &Value) -> f64 {
    match *v {
        Value::I8(x) => f64::from(x),
        Value::U8(x) => f64::from(x),
        Value::I16(x) => f64::from(x),
        Value::U16(x) => f64::from(x),
        Value::I32(x) => f64::from(x),
        Value::U32(x) => f64::from(x),
        Value::I64(x) => x as f64,
        Value::U64(x) => x as f64,
        Value::F32(x) => f64::from(x),
        Value::F64(x) => x,
        _ => 0.0,
    }
}
