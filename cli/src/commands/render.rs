//! `meshloom render IN OUT.png [--view ..] [--flat] [--wireframe] [--boundary]
//! [--color plain|curvature]`.

use meshloom_cli::render::{self, Coloring, RenderOptions, Shading};

use crate::cli::{ColorBy, RenderArgs};
use crate::progress::Progress;
use crate::{input, output, Failure};

/// Draw the mesh and save the picture.
pub fn run(args: &RenderArgs) -> Result<(), Failure> {
    let options = RenderOptions {
        width: args.size.0,
        height: args.size.1,
        view: args.view,
        shading: if args.flat {
            Shading::Flat
        } else {
            Shading::Smooth
        },
        wireframe: args.wireframe,
        boundary: args.boundary,
        supersample: args.supersample,
        coloring: match args.color {
            ColorBy::Plain => Coloring::Plain,
            ColorBy::Curvature => Coloring::Curvature,
        },
        ..RenderOptions::default()
    };
    // Options that cannot work are a usage error, found before any reading.
    options.check().map_err(|e| Failure {
        code: Failure::USAGE,
        message: e.to_string(),
    })?;
    let (mesh, _) = input::read(&args.input, args.read, false)?;
    let image = {
        let progress = Progress::bar("rendering faces", mesh.face_count());
        render::render_with_progress(&mesh, &options, &mut |done, _| progress.set(done))
    }
    .map_err(|e| Failure::input(format!("{}: {e}", args.input.display())))?;
    {
        let _progress = Progress::spinner(format!("writing {}", args.output.display()));
        image.write_png(&args.output).map_err(Failure::input)?;
    }
    output::print(&format!(
        "wrote {} ({}x{}, view {})\n",
        args.output.display(),
        image.width(),
        image.height(),
        args.view
    ))
}
