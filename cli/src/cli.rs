//! The command line: every command, its arguments and its help text.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use meshloom::io::Format;
use meshloom_cli::render::View;

const EXAMPLES: &str = "\
Examples:
  meshloom stats data/elephant.off
  meshloom validate data/elephant.off
  meshloom render data/elephant.off elephant.png --wireframe

Exit codes: 0 success, 1 bad input, 2 usage.";

/// Look at, check, convert, repair and render polygon mesh files
/// (OBJ, OFF, PLY, STL; a trailing .gz is read and written as gzip).
#[derive(Parser, Debug)]
#[command(name = "meshloom", version, after_help = EXAMPLES)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The commands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Print counts, boundary, components, Euler characteristic and genus.
    ///
    /// Vertices, edges, faces, holes, boundary edges and loops, connected
    /// components, Euler characteristic V - E + F, genus where the mesh is
    /// closed (summed over components), the face-degree histogram and the
    /// bounding box.
    #[command(after_help = "\
Example:
  meshloom stats data/elephant.off
  meshloom stats data/elephant.off --json")]
    Stats(StatsArgs),
    /// Print the figures of each connected component.
    ///
    /// One row per component, numbered in the order of their first vertex:
    /// vertices, edges, faces, holes, Euler characteristic, and the genus
    /// of closed components.
    #[command(after_help = "\
Example:
  meshloom components data/elephant.off
  meshloom components scan.ply --json")]
    Components(StatsArgs),
    /// Check that a file is a valid half-edge mesh as it stands.
    ///
    /// Reads strictly (no repairs) and checks every structural rule. Exit
    /// code 1 and a message naming the file and line if it is not valid,
    /// with a hint when `meshloom repair` would fix it.
    #[command(after_help = "\
Example:
  meshloom validate data/elephant.off && echo clean")]
    Validate(ValidateArgs),
    /// Convert between formats, chosen by the file extensions.
    #[command(after_help = "\
Example:
  meshloom convert data/elephant.off elephant.ply
  meshloom convert scan.stl scan.obj.gz --repair
  meshloom convert model.glb model.obj")]
    Convert(ConvertArgs),
    /// Repair a dirty file and report what was done.
    ///
    /// Reads with every repair on (weld, drop degenerate and duplicate
    /// faces, orient, split non-manifold edges and vertices, drop unused
    /// vertices) and writes the result.
    #[command(after_help = "\
Example:
  meshloom repair scan.ply fixed.ply
  meshloom repair scan.ply fixed.off --json")]
    Repair(RepairArgs),
    /// Cut every face of more than three sides into triangles.
    ///
    /// Ear clipping, so non-convex faces stay inside their outline;
    /// attributes split with the faces.
    #[command(after_help = "\
Example:
  meshloom triangulate quads.obj triangles.obj
  meshloom triangulate part.off part.stl --json")]
    Triangulate(TriangulateArgs),
    /// Close holes with new faces.
    ///
    /// Each hole (boundary loop) of at most --max-sides sides becomes one
    /// polygon, cut into triangles with --triangulate. Holes whose loop
    /// passes a vertex twice are left open and counted.
    #[command(after_help = "\
Example:
  meshloom fill-holes scan.ply closed.ply --triangulate
  meshloom fill-holes part.off part-filled.off --max-sides 12 --json")]
    FillHoles(FillHolesArgs),
    /// Draw a shaded picture of a mesh as PNG.
    ///
    /// Orthographic, flat or smooth shading, optional wireframe and
    /// boundary highlight; the back of faces (seen through holes) is
    /// orange.
    #[command(after_help = "\
Example:
  meshloom render data/elephant.off elephant.png
  meshloom render part.obj part.png --view top --flat --wireframe --boundary --size 1024x768")]
    Render(RenderArgs),
}

/// How to read an input file.
#[derive(Args, Debug, Clone, Copy)]
pub struct ReadArgs {
    /// Repair the input while reading (as `meshloom repair` does) instead of
    /// refusing what a half-edge mesh cannot hold.
    #[arg(long)]
    pub repair: bool,
}

/// `meshloom stats`.
#[derive(Args, Debug)]
pub struct StatsArgs {
    /// The mesh file.
    #[arg(value_parser = mesh_path)]
    pub file: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom validate`.
#[derive(Args, Debug)]
pub struct ValidateArgs {
    /// The mesh file.
    #[arg(value_parser = mesh_path)]
    pub file: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

/// `meshloom convert`.
#[derive(Args, Debug)]
pub struct ConvertArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom repair`.
#[derive(Args, Debug)]
pub struct RepairArgs {
    /// The mesh file to read and repair.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

/// `meshloom triangulate`.
#[derive(Args, Debug)]
pub struct TriangulateArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// Print the summary as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom fill-holes`.
#[derive(Args, Debug)]
pub struct FillHolesArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// Fill only holes of at most this many sides.
    #[arg(long, value_parser = clap::value_parser!(u64).range(3..))]
    pub max_sides: Option<u64>,
    /// Cut each new face into triangles.
    #[arg(long)]
    pub triangulate: bool,
    /// Print the summary as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// The mesh file.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The picture to write (.png).
    #[arg(value_parser = png_path)]
    pub output: PathBuf,
    /// Where to look from: iso, front, back, left, right, top, bottom, or a
    /// direction x,y,z toward the eye (y is up).
    #[arg(long, default_value = "iso", value_parser = view)]
    pub view: View,
    /// Flat shading (facets show) instead of smooth.
    #[arg(long)]
    pub flat: bool,
    /// Draw every edge.
    #[arg(long)]
    pub wireframe: bool,
    /// Highlight boundary edges (beside a hole) in red.
    #[arg(long)]
    pub boundary: bool,
    /// Picture size in pixels, WIDTHxHEIGHT (or one number for a square).
    #[arg(long, default_value = "800x600", value_parser = size)]
    pub size: (u32, u32),
    /// Samples per pixel along each axis, 1 to 4 (smoother edges, slower).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=4))]
    pub supersample: u32,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// A path whose extension names a mesh format.
fn mesh_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    if Format::from_path(&path).is_some() || meshloom::io::gltf::encoding_of(&path).is_some() {
        Ok(path)
    } else {
        Err(
            "expected a file ending in .obj, .off, .ply or .stl (optionally + .gz), .gltf or .glb"
                .into(),
        )
    }
}

/// A path ending in `.png`.
fn png_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    let is_png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if is_png {
        Ok(path)
    } else {
        Err("expected a file ending in .png".into())
    }
}

fn view(s: &str) -> Result<View, String> {
    s.parse()
}

/// `WIDTHxHEIGHT` or `SIDE`, each 1 to the renderer's largest side.
fn size(s: &str) -> Result<(u32, u32), String> {
    let max = meshloom_cli::render::MAX_SIDE;
    let side = |t: &str| {
        t.trim()
            .parse::<u32>()
            .ok()
            .filter(|n| (1..=max).contains(n))
            .ok_or_else(|| format!("expected WIDTHxHEIGHT with sides 1 to {max}, got {s:?}"))
    };
    match s.split_once(['x', 'X']) {
        Some((w, h)) => Ok((side(w)?, side(h)?)),
        None => side(s).map(|n| (n, n)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn command_line_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn sizes_parse() {
        assert_eq!(size("640x480"), Ok((640, 480)));
        assert_eq!(size("256"), Ok((256, 256)));
        assert!(size("0x10").is_err());
        assert!(size("wide").is_err());
    }
}
