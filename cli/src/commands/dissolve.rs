//! `meshloom dissolve IN OUT --limited ANGLE [--delimit material,seams,sharp]`:
//! limited dissolve (`meshloom::Mesh::dissolve_limited`) of the whole
//! mesh, then write.

use meshloom::attr::Contagion;
use meshloom::model::{Delimit, DissolveLimitedOptions};
use meshloom::EdgeKey;
use serde_json::json;

use crate::cli::DissolveArgs;
use crate::output;
use crate::{input, Failure};

/// Read, dissolve, write, report.
pub fn run(args: &DissolveArgs) -> Result<(), Failure> {
    let (mut mesh, _) = input::read(&args.input, args.read, false)?;
    let wants = |w: &str| args.delimit.iter().any(|d| d == w);
    let sharp = if wants("sharp") {
        Some(
            mesh.attr_handle::<EdgeKey, bool, Contagion>(&args.sharp_column)
                .map_err(Failure::input)?,
        )
    } else {
        None
    };
    let options = DissolveLimitedOptions {
        angle: args.limited.to_radians(),
        delimit: Delimit {
            material: wants("material").then(|| args.material_column.clone()),
            seams: wants("seams").then(|| args.seams_column.clone()),
            sharp,
        },
        boundaries: args.boundaries,
        ..Default::default()
    };
    let (faces, vertices) = (mesh.face_count(), mesh.vertex_count());
    let d = mesh.dissolve_limited(&options).map_err(Failure::input)?;
    input::write(&mesh, &args.output, false, false)?;
    if args.json {
        return output::json(&json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "angle_degrees": args.limited,
            "delimit": args.delimit,
            "faces_before": faces,
            "vertices_before": vertices,
            "faces": mesh.face_count(),
            "vertices": mesh.vertex_count(),
            "merged_faces": d.faces.len(),
            "removed_faces": d.removed_faces,
            "removed_edges": d.removed_edges,
            "removed_vertices": d.removed_vertices,
        }));
    }
    output::print(&format!(
        "limited dissolve at {}°: {faces} faces → {}, {vertices} vertices → {}\nwrote {}\n",
        args.limited,
        mesh.face_count(),
        mesh.vertex_count(),
        args.output.display()
    ))
}
