//! `meshloom quads IN OUT [--face-angle DEG] [--shape-angle DEG]
//! [--delimit material,seams,sharp] [--json]`: join pairs of triangles
//! into quads with [`Mesh::join_triangles`], then write.

use meshloom::attr::EdgeAttr;
use meshloom::io::names::{MATERIAL, TEXCOORD};
use meshloom::model::{Delimit, JoinTrianglesOptions};
use meshloom::{ElementKind, Mesh};
use serde_json::json;

use crate::cli::QuadsArgs;
use crate::output;
use crate::{input, Failure};

/// The corner column whose seams `--delimit seams` keeps, before the
/// readers' texture coordinates.
const UV: &str = "uv";
/// The boolean edge column `--delimit sharp` keeps.
const SHARP: &str = "sharp";

/// Read, join, write, report.
pub fn run(args: &QuadsArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let (delimit, used) = delimit(&mesh, &args.delimit)?;
    let options = JoinTrianglesOptions {
        face_angle: args.face_angle.to_radians(),
        shape_angle: args.shape_angle.to_radians(),
        delimit,
        faces: None,
    };
    let before = mesh.face_count();
    let joined = mesh.join_triangles(&options).map_err(Failure::input)?;
    input::write(&mesh, &args.output, false, false)?;
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "faces_before": before,
            "faces": mesh.face_count(),
            "quads": joined.quads.len(),
            "triangles_left": joined.triangles_left,
            "delimit": used,
        }));
    }
    let mut text = format!(
        "joined {} pairs of triangles into quads ({} triangles left): {} faces, was {}\n",
        joined.quads.len(),
        joined.triangles_left,
        mesh.face_count(),
        before
    );
    if !used.is_empty() {
        text.push_str(&format!("kept edges by columns: {}\n", used.join(", ")));
    }
    text.push_str(&format!("wrote {}\n", args.output.display()));
    output::print(&text)
}

/// The delimiters the `--delimit` words name, with the columns found
/// (`material` → the "material" face column, `seams` → the "uv" corner
/// column, else "texcoord", `sharp` → the boolean "sharp" edge column); a
/// word whose column the mesh lacks keeps nothing.
///
/// # Errors
/// A "sharp" column that is not boolean.
pub fn delimit(mesh: &Mesh, words: &[String]) -> Result<(Delimit, Vec<String>), Failure> {
    let has = |kind, name: &str| mesh.attr_info(kind).iter().any(|c| c.name == name);
    let mut d = Delimit::default();
    let mut used = Vec::new();
    for w in words {
        match w.as_str() {
            "material" if has(ElementKind::Face, MATERIAL) => {
                d.material = Some(MATERIAL.into());
                used.push(format!("face {MATERIAL}"));
            }
            "seams" => {
                let found = [UV, TEXCOORD]
                    .into_iter()
                    .find(|n| has(ElementKind::Halfedge, n));
                if let Some(n) = found {
                    d.seams = Some(n.into());
                    used.push(format!("corner {n}"));
                }
            }
            "sharp" if has(ElementKind::Edge, SHARP) => {
                let h: EdgeAttr<bool> = mesh.attr_handle(SHARP).map_err(|e| {
                    Failure::input(format!("--delimit sharp: {e} (a boolean edge column)"))
                })?;
                d.sharp = Some(h);
                used.push(format!("edge {SHARP}"));
            }
            _ => {}
        }
    }
    Ok((d, used))
}
