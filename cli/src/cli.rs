//! The command line: every command, its arguments and its help text.

use std::path::PathBuf;

use crate::input::MeshFormat;
use clap::{Args, Parser, Subcommand};
use meshloom::algo::laplacian::LaplaceWeights;
use meshloom::algo::smooth::SmoothMethod;
use meshloom::algo::subdivision::MidpointFaces;
use meshloom::algo::Keep;
use meshloom::algo::Scheme;
use meshloom_cli::render::View;

const EXAMPLES: &str = "\
Examples:
  meshloom stats data/elephant.off
  meshloom validate data/elephant.off
  meshloom render data/elephant.off elephant.png --wireframe
  meshloom smooth data/elephant.off smooth.off --method taubin
  meshloom decimate data/elephant.off small.off --ratio 0.1
  meshloom remesh data/elephant.off even.off

Exit codes: 0 success, 1 bad input, 2 usage.";

/// Look at, check, convert, repair, simplify and render polygon mesh files
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
    ///
    /// "holes" counts hole faces; "boundary loops" counts loops as
    /// independent checkers walk them (at a vertex where several loops
    /// meet, turning into the first boundary edge not yet walked, in face
    /// order). They differ only where boundary loops meet at a pinched
    /// vertex: there one hole face passes through every loop.
    #[command(after_help = "\
Example:
  meshloom stats data/elephant.off
  meshloom stats data/elephant.off --json
  meshloom stats meshes/ more.ply        (a table: file, V, F, status)
  cat cube.off | meshloom stats - --format off")]
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
    Components(ComponentsArgs),
    /// Check that a file is a valid half-edge mesh as it stands.
    ///
    /// Reads strictly (no repairs) and checks every structural rule. Exit
    /// code 1 and a message naming the file and line if it is not valid,
    /// with a hint when `meshloom repair` would fix it.
    #[command(after_help = "\
Example:
  meshloom validate data/elephant.off && echo clean
  meshloom validate meshes/ --json        (one object per file and line)")]
    Validate(ValidateArgs),
    /// Check a mesh's geometry: the pairs of faces that intersect.
    ///
    /// Faces sharing a vertex or an edge count only when they meet beyond
    /// it; faces with nothing in common count when they touch. Decided with
    /// exact predicates. Prints the count and the first 20 pairs (face
    /// indices in the file's order); exit code 1 if there are any.
    #[command(after_help = "\
Example:
  meshloom check data/elephant.off --self-intersections
  meshloom check scan.ply --self-intersections --json")]
    Check(CheckArgs),
    /// Convert between formats, chosen by the file extensions.
    #[command(after_help = "\
Example:
  meshloom convert data/elephant.off elephant.ply
  meshloom convert scan.stl scan.obj.gz --repair
  meshloom convert model.glb model.obj
  meshloom convert meshes/ --out-dir as-ply/ --format ply
  meshloom convert scan.stl - --format obj | less
  meshloom convert data/elephant.off elephant.obj --normals")]
    Convert(ConvertArgs),
    /// Repair a dirty file and report what was done.
    ///
    /// Reads with every repair on (weld, drop degenerate and duplicate
    /// faces, orient, split non-manifold edges and vertices, drop unused
    /// vertices) and writes the result.
    #[command(after_help = "\
Example:
  meshloom repair scan.ply fixed.ply
  meshloom repair scan.ply fixed.off --json
  meshloom repair scans/ --out-dir fixed/")]
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
    /// polygon, cut into triangles with --triangulate. With --refine, each
    /// hole gets Liepa's patch instead: the triangulation of least dihedral
    /// angle and area, refined to the rim's edge length; --fair also fairs
    /// it (bi-Laplacian by default, --fair-order), so it continues the
    /// surface around the hole. Attributes (UVs, colours, materials) are
    /// taken from the rim. Holes whose loop passes a vertex twice are left
    /// open and counted.
    #[command(after_help = "\
Example:
  meshloom fill-holes scan.ply closed.ply --triangulate
  meshloom fill-holes scan.ply closed.ply --fair
  meshloom fill-holes part.off part-filled.off --max-sides 12 --json")]
    FillHoles(FillHolesArgs),
    /// Smooth the vertex positions and write the result.
    ///
    /// uniform and cotan: explicit Laplacian steps (--step is the fraction
    /// of the way to the neighbours' mean, default 0.5; 10 iterations);
    /// taubin: a shrinking and an inflating uniform step per iteration,
    /// which keeps the volume; implicit: backward Euler steps of the
    /// cotangent flow (--step is the time step, default 0.001; 1
    /// iteration), solved by a sparse Cholesky factorisation. Boundary
    /// vertices stay put (--boundary lock) unless --boundary slide (they
    /// move along the input's boundary) or free; vertices where the
    /// --pinned vertex column is true (or non-zero) never move. Every
    /// other column keeps its values; normal columns read from the input
    /// are stale and dropped (--normals computes new ones).
    #[command(after_help = "\
Example:
  meshloom smooth scan.ply smooth.ply --method taubin --iterations 20
  meshloom smooth part.obj part-smooth.obj --method implicit --step 0.01 --normals --json")]
    Smooth(SmoothArgs),
    /// Fair a region: move its vertices to minimise the Laplacian energy.
    ///
    /// Solves Δᵏx = 0 for the free vertices (--order 1: membrane, 2: thin
    /// plate, the default, 3: minimum variation), with cotangent weights
    /// (--weights uniform: the graph Laplacian). The region is every
    /// vertex, or those where the --region vertex column is true (or
    /// non-zero). The boundary and the order - 1 rings inside it stay put
    /// (--boundary lock) unless --boundary slide (boundary vertices are
    /// spread along the input's boundary) or free; --pinned vertices never
    /// move; --features and --feature-angle edges are lines whose
    /// vertices slide along them. Normal columns read from the input are
    /// stale and dropped (--normals computes new ones).
    #[command(after_help = "\
Example:
  meshloom fair patch.obj smooth-patch.obj --region selected
  meshloom fair scan.ply faired.ply --order 3 --pinned keep --json")]
    Fair(FairArgs),
    /// Simplify a triangle mesh by quadric error edge collapse.
    ///
    /// Stops at a share of the vertices, a vertex or face count, or before
    /// the error (a distance in mesh units) would pass --max-error; give
    /// one target, or --max-error alone. Boundaries and UV seams are kept
    /// as lines (their vertices slide only along them); --boundary lock
    /// and --seams lock keep their vertices where they are, free lets them
    /// go. UVs, colours and other attributes follow each collapse. Faces
    /// must be triangles (`meshloom triangulate` first).
    #[command(after_help = "\
Example:
  meshloom decimate bunny.off bunny-10.off --ratio 0.1
  meshloom decimate scan.ply small.ply --faces 5000 --max-error 0.01 --boundary lock --json")]
    Decimate(DecimateArgs),
    /// Write several levels of detail from one decimation.
    ///
    /// Level i (from 1) goes to OUT_PREFIX_i with OUT_PREFIX's extension
    /// (`lod.obj` gives `lod_1.obj`, ...; no extension: `.obj`). Each level
    /// is the one before it, decimated further.
    #[command(after_help = "\
Example:
  meshloom lod bunny.off out/bunny.obj --ratios 0.5,0.25,0.1
  meshloom lod part.glb part.glb --ratios 0.3,0.1 --seams lock --json")]
    Lod(LodArgs),
    /// Merge nearly coplanar faces into polygons (limited dissolve).
    ///
    /// Faces whose normals differ by less than the --limited angle
    /// (degrees) merge, smallest angle first, then vertices left between
    /// two edges that bend by less go (Blender's Limited Dissolve). Edges
    /// on the boundary always stay; --delimit keeps material borders (the
    /// face column --material-column), UV seams (the corner column
    /// --seams-column) and sharp edges (the boolean edge column
    /// --sharp-column). Integer face columns (material ids) are never
    /// merged away.
    #[command(after_help = "\
Example:
  meshloom dissolve scan.obj flat.obj --limited 5
  meshloom dissolve model.obj out.obj --limited 10 --delimit material,seams --json")]
    Dissolve(DissolveArgs),
    /// Draw a shaded picture of a mesh as PNG.
    ///
    /// Orthographic, flat or smooth shading, optional wireframe and
    /// boundary highlight; the back of faces (seen through holes) is
    /// orange.
    #[command(after_help = "\
Example:
  meshloom render data/elephant.off elephant.png
  meshloom render part.obj part.png --view top --flat --wireframe --boundary --size 1024x768
  meshloom render bunny.obj bunny.png --color curvature")]
    Render(RenderArgs),
    /// Subdivide: Loop, Catmull-Clark, sqrt(3) or midpoint, any levels.
    ///
    /// Loop and sqrt3 take triangles, catmull-clark and midpoint any
    /// polygons. Boundaries follow the crease rule (add --corners to keep
    /// the corners of single faces; sqrt3 trisects the boundary every
    /// second level); an f64 edge column named by --crease-column gives
    /// semi-sharp creases (loop and catmull-clark only). Attributes follow:
    /// UVs stay linear per face, so seams stay seams; face values go to
    /// every child face.
    #[command(after_help = "\
Example:
  meshloom subdivide cube.obj smooth.obj --scheme catmull-clark --levels 3
  meshloom subdivide bunny.off bunny4.ply --scheme loop --levels 2 --json")]
    Subdivide(SubdivideArgs),
    /// Remesh a triangle mesh isotropically (Botsch-Kobbelt).
    ///
    /// Splits long edges, collapses short ones, flips towards valence 6
    /// and relaxes the vertices in their tangent planes, projecting them
    /// back onto the input surface, --iterations times (default 10). The
    /// target edge length is --edge-length, or by default the input's mean
    /// edge length; --adaptive TOL makes it follow the curvature instead
    /// (the largest length within TOL of the surface). Boundaries slide
    /// along themselves, corners stay (--boundary lock keeps them as they
    /// are); --feature-angle DEG keeps edges sharper than DEG degrees as
    /// lines too. UVs and other vertex and
    /// corner attributes are resampled from the input, per seam side.
    /// Faces must be triangles (`meshloom triangulate` first).
    #[command(after_help = "\
Example:
  meshloom remesh bunny.off even.off --edge-length 0.002
  meshloom remesh part.obj part-remeshed.obj --adaptive 0.001 --feature-angle 40 --json")]
    Remesh(RemeshArgs),
    /// Write N points uniformly distributed inside a closed mesh as CSV.
    ///
    /// Rejection sampling in the bounding box with the face tree's inside
    /// test (winding number above 1/2). The same seed gives the same
    /// points. Fails (exit 1) when the mesh encloses almost no volume.
    #[command(after_help = "\
Example:
  meshloom sample data/bunny.off inside.csv --inside 10000 --seed 7")]
    Sample(SampleArgs),
    /// Join pairs of adjacent triangles into quads (Blender's Tris to Quads).
    ///
    /// Two triangles join when their normals differ by at most
    /// --face-angle, every corner of the quad is within --shape-angle of a
    /// right angle and the quad is convex; the best pairs go first, each
    /// triangle joins once. --delimit keeps the edges between faces of
    /// different materials (the "material" face column), UV seams (the
    /// "uv" corner column, else the readers' "texcoord") and sharp edges
    /// (the boolean "sharp" edge column); a column the file lacks keeps
    /// nothing. A quad keeps its first triangle's face values and every
    /// corner's UVs.
    #[command(after_help = "\
Example:
  meshloom quads scan.obj quads.obj
  meshloom quads model.obj quads.obj --face-angle 30 --delimit material,seams --json")]
    Quads(QuadsArgs),
}

/// How to read an input file.
#[derive(Args, Debug, Clone, Copy, Default)]
pub struct ReadArgs {
    /// Repair the input while reading (as `meshloom repair` does) instead of
    /// refusing what a half-edge mesh cannot hold.
    #[arg(long)]
    pub repair: bool,
    /// Also weld vertices at bit-identical positions where every edge and
    /// vertex stays manifold (implies --repair; off by default because
    /// coincident vertices may keep parts apart on purpose).
    #[arg(long)]
    pub weld: bool,
}

/// `meshloom components`.
#[derive(Args, Debug)]
pub struct ComponentsArgs {
    /// The mesh file.
    #[arg(value_parser = mesh_path)]
    pub file: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom check`.
#[derive(Args, Debug)]
pub struct CheckArgs {
    /// The mesh file.
    #[arg(value_parser = mesh_path)]
    pub file: PathBuf,
    /// Find the pairs of faces that intersect.
    #[arg(long)]
    pub self_intersections: bool,
    /// Print one JSON object instead of text (with every pair).
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom stats`.
#[derive(Args, Debug)]
pub struct StatsArgs {
    /// Mesh files or folders (searched recursively for the extensions the
    /// readers know); `-` reads standard input (format from --format).
    #[arg(required = true, value_parser = input_path)]
    pub files: Vec<PathBuf>,
    /// Print JSON instead of text: one object per file, one per line.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
    /// The format of standard input (`-`): obj, off, ply, stl, gltf or glb.
    #[arg(long, value_parser = format_name)]
    pub format: Option<MeshFormat>,
}

/// `meshloom validate`.
#[derive(Args, Debug)]
pub struct ValidateArgs {
    /// Mesh files or folders (searched recursively); `-` reads standard
    /// input (format from --format).
    #[arg(required = true, value_parser = input_path)]
    pub files: Vec<PathBuf>,
    /// Print JSON instead of text: one object per file, one per line.
    #[arg(long)]
    pub json: bool,
    /// The format of standard input (`-`): obj, off, ply, stl, gltf or glb.
    #[arg(long, value_parser = format_name)]
    pub format: Option<MeshFormat>,
}

/// Where the results of `convert` and `repair` go.
#[derive(Args, Debug, Clone)]
pub struct OutArgs {
    /// Write every result into this folder, at the input's path relative to
    /// the folder argument it was found in (a file named on its own: its
    /// file name). All paths are then inputs.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
    /// The format written into --out-dir (obj, off, ply, stl, each with an
    /// optional .gz, gltf or glb; default: the input's own), or of a `-`
    /// input or output.
    #[arg(long, value_parser = format_name)]
    pub format: Option<MeshFormat>,
}

/// `meshloom convert`.
#[derive(Args, Debug)]
pub struct ConvertArgs {
    /// `IN OUT` (format from the extensions; `-` for standard input or
    /// output, with --format), or with --out-dir: files and folders to
    /// convert.
    #[arg(required = true, value_name = "PATHS", value_parser = input_path)]
    pub paths: Vec<PathBuf>,
    #[command(flatten)]
    pub out: OutArgs,
    /// Compute angle-weighted vertex normals and write them where the format
    /// carries them (OBJ vn, OFF NOFF, PLY nx ny nz, glTF NORMAL).
    #[arg(long)]
    pub normals: bool,
    #[command(flatten)]
    pub read: ReadArgs,
    /// Print JSON instead of text, one object per file and line (what was
    /// written, and the attributes the output format cannot hold).
    #[arg(long)]
    pub json: bool,
}

/// `meshloom smooth`.
#[derive(Args, Debug)]
pub struct SmoothArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// How to smooth: uniform, cotan, taubin or implicit.
    #[arg(long, default_value = "uniform",
          value_parser = words::<SmoothMethod>(SmoothMethod::WORDS))]
    pub method: SmoothMethod,
    /// Iterations (implicit: time steps); default 10, implicit 1.
    #[arg(long)]
    pub iterations: Option<u32>,
    /// Explicit and Taubin: the step lambda in (0, 1] (default 0.5);
    /// implicit: the time step (default 0.001).
    #[arg(long)]
    pub step: Option<f64>,
    #[command(flatten)]
    pub keep: ConstraintArgs,
    /// Deprecated: `--pinned` with the complement (only the vertices where
    /// this vertex column is true or non-zero move).
    #[arg(long, value_name = "NAME", hide = true, conflicts_with = "pinned")]
    pub mask_column: Option<String>,
    /// Deprecated: `--boundary free`.
    #[arg(long, hide = true, conflicts_with = "boundary")]
    pub free_boundary: bool,
    /// Implicit only: restore the input's surface area and centroid.
    #[arg(long)]
    pub rescale: bool,
    /// Compute angle-weighted vertex normals and write them where the format
    /// carries them (OBJ vn, OFF NOFF, PLY nx ny nz, glTF NORMAL).
    #[arg(long)]
    pub normals: bool,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom fair`.
#[derive(Args, Debug)]
pub struct FairArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// A vertex column whose true (or non-zero) vertices move (default:
    /// every vertex but the fixed rings).
    #[arg(long, value_name = "COLUMN")]
    pub region: Option<String>,
    /// The power of the Laplacian: 1 membrane, 2 thin plate, 3 minimum
    /// variation (default 2).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=3))]
    pub order: Option<u32>,
    /// The Laplacian's weights: cotan or uniform (default cotan).
    #[arg(long, value_parser = words::<LaplaceWeights>(LaplaceWeights::WORDS))]
    pub weights: Option<LaplaceWeights>,
    #[command(flatten)]
    pub keep: ConstraintArgs,
    /// Compute angle-weighted vertex normals and write them where the format
    /// carries them (OBJ vn, OFF NOFF, PLY nx ny nz, glTF NORMAL).
    #[arg(long)]
    pub normals: bool,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom repair`.
#[derive(Args, Debug)]
pub struct RepairArgs {
    /// `IN OUT` (format from the extensions; `-` for standard input or
    /// output, with --format), or with --out-dir: files and folders to
    /// repair.
    #[arg(required = true, value_name = "PATHS", value_parser = input_path)]
    pub paths: Vec<PathBuf>,
    #[command(flatten)]
    pub out: OutArgs,
    /// Print the report as JSON, one object per file and line (on failure
    /// too: `{"ok": false, "error": ...}`).
    #[arg(long)]
    pub json: bool,
    /// Also weld vertices at bit-identical positions where every edge and
    /// vertex stays manifold.
    #[arg(long)]
    pub weld: bool,
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
    /// Fill with Liepa's patch: the optimal triangulation, refined to the
    /// rim's edge length (new vertices inside the hole).
    #[arg(long)]
    pub refine: bool,
    /// As --refine, then fair the patch's new vertices (implies --refine).
    #[arg(long)]
    pub fair: bool,
    /// The power of the Laplacian in --fair: 1 membrane, 2 thin plate
    /// (default), 3 minimum variation.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=3), requires = "fair")]
    pub fair_order: Option<u32>,
    /// With --refine or --fair: holes with more rim edges than this are
    /// triangulated but not refined (the patch grows as the rim's square).
    #[arg(long, value_name = "N", default_value_t = meshloom::algo::FillHoleOptions::default().max_refined_rim)]
    pub max_refined_rim: usize,
    /// Print the summary as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom decimate`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("target").required(true).multiple(true).args(["ratio", "vertices", "faces", "max_error"])))]
pub struct DecimateArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// Stop at this share of the vertices (0 to 1).
    #[arg(long, value_parser = ratio, conflicts_with_all = ["vertices", "faces"])]
    pub ratio: Option<f64>,
    /// Stop at this many vertices.
    #[arg(long, conflicts_with = "faces")]
    pub vertices: Option<usize>,
    /// Stop at this many faces (or one fewer).
    #[arg(long)]
    pub faces: Option<usize>,
    /// Stop before a collapse whose error (mesh units) would pass this.
    #[arg(long, value_parser = non_negative)]
    pub max_error: Option<f64>,
    #[command(flatten)]
    pub keep: ConstraintArgs,
    /// Deprecated: `--boundary lock`.
    #[arg(long, hide = true, conflicts_with = "boundary")]
    pub keep_boundary: bool,
    /// Deprecated: `--seams lock`.
    #[arg(long, hide = true, conflicts_with = "seams")]
    pub keep_seams: bool,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom dissolve`.
#[derive(Args, Debug)]
pub struct DissolveArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// The angle limit in degrees (at most 90 acts).
    #[arg(long, value_parser = non_negative)]
    pub limited: f64,
    /// What keeps edges besides the boundary: a comma list of material,
    /// seams, sharp.
    #[arg(long, value_delimiter = ',', value_parser = ["material", "seams", "sharp"])]
    pub delimit: Vec<String>,
    /// The face column `--delimit material` compares.
    #[arg(long, default_value = "material")]
    pub material_column: String,
    /// The corner column whose seams `--delimit seams` keeps (the files'
    /// UVs are `texcoord`).
    #[arg(long, default_value = "texcoord")]
    pub seams_column: String,
    /// The boolean edge column `--delimit sharp` reads.
    #[arg(long, default_value = "sharp")]
    pub sharp_column: String,
    /// Dissolve every vertex left between two edges, whatever the angle.
    #[arg(long)]
    pub boundaries: bool,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom remesh`.
#[derive(Args, Debug)]
pub struct RemeshArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// The target edge length (default: the input's mean edge length).
    #[arg(long, value_parser = positive, conflicts_with = "adaptive")]
    pub edge_length: Option<f64>,
    /// Adaptive lengths that follow the curvature, within this
    /// approximation error (mesh units).
    #[arg(long, value_parser = positive)]
    pub adaptive: Option<f64>,
    /// The shortest adaptive length (default: a quarter of the mean edge length).
    #[arg(long, value_parser = positive, requires = "adaptive")]
    pub min_length: Option<f64>,
    /// The longest adaptive length (default: four times the mean edge length).
    #[arg(long, value_parser = positive, requires = "adaptive")]
    pub max_length: Option<f64>,
    /// Rounds of split, collapse, flip and relaxation.
    #[arg(long, default_value_t = 10)]
    pub iterations: usize,
    #[command(flatten)]
    pub keep: ConstraintArgs,
    /// Deprecated: `--boundary lock`.
    #[arg(long, hide = true, conflicts_with = "boundary")]
    pub keep_boundary: bool,
    /// Refuse, before any work, a target length estimated to make more
    /// faces than this.
    #[arg(long, value_name = "N", default_value_t = meshloom::algo::DEFAULT_MAX_FACES)]
    pub max_faces: usize,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom lod`.
#[derive(Args, Debug)]
pub struct LodArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// Where the levels go: `_1`, `_2`, ... before the extension.
    pub output_prefix: PathBuf,
    /// The levels' shares of the input's vertices, largest first.
    #[arg(long, value_delimiter = ',', required = true, value_parser = ratio)]
    pub ratios: Vec<f64>,
    #[command(flatten)]
    pub keep: ConstraintArgs,
    /// Deprecated: `--boundary lock`.
    #[arg(long, hide = true, conflicts_with = "boundary")]
    pub keep_boundary: bool,
    /// Deprecated: `--seams lock`.
    #[arg(long, hide = true, conflicts_with = "seams")]
    pub keep_seams: bool,
    /// Print the levels' reports as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// What an algorithm keeps: the library's constraints, in the words of
/// `meshloom::algo::Keep` (free, slide, lock).
#[derive(Args, Debug)]
pub struct ConstraintArgs {
    /// Boundary vertices: free (no constraint), slide (they stay on the
    /// input's boundary; corners stay) or lock (they and the boundary
    /// edges stay). Default: slide for decimate, lod and remesh; lock for
    /// smooth and fair.
    #[arg(long, value_name = "free|slide|lock", value_parser = keep)]
    pub boundary: Option<Keep>,
    /// UV seams (edges across which a corner column's values differ):
    /// free, slide or lock. Default: slide for decimate, lod and remesh;
    /// free for smooth and fair.
    #[arg(long, value_name = "free|slide|lock", value_parser = keep)]
    pub seams: Option<Keep>,
    /// Edges whose faces meet at more than this many degrees are feature
    /// edges (decimate holds their vertices; remesh and smooth slide along
    /// them); it is also the turn that makes a line's vertex a corner
    /// (default 45).
    #[arg(long, value_name = "DEG", value_parser = degrees)]
    pub feature_angle: Option<f64>,
    /// An edge column whose true (or non-zero) edges are feature edges.
    #[arg(long, value_name = "COLUMN")]
    pub features: Option<String>,
    /// A vertex column whose true (or non-zero) vertices are pinned: they
    /// never move.
    #[arg(long, value_name = "COLUMN")]
    pub pinned: Option<String>,
}

/// A word of `Keep` (free, slide, lock), read by the library's own parser.
fn keep(s: &str) -> Result<Keep, String> {
    s.parse()
        .map_err(|e: meshloom::choice::UnknownChoice| e.to_string())
}

/// A number from 0 to 1.
fn ratio(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(r) if (0.0..=1.0).contains(&r) => Ok(r),
        _ => Err("expected a number from 0 to 1".into()),
    }
}

/// A finite number > 0.
fn positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(r) if r.is_finite() && r > 0.0 => Ok(r),
        _ => Err("expected a finite number > 0".into()),
    }
}

/// An angle in degrees, 0 to 180.
fn degrees(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(r) if (0.0..=180.0).contains(&r) => Ok(r),
        _ => Err("expected an angle in degrees from 0 to 180".into()),
    }
}

/// A finite number ≥ 0.
fn non_negative(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(r) if r.is_finite() && r >= 0.0 => Ok(r),
        _ => Err("expected a finite number ≥ 0".into()),
    }
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
    /// What colours the faces: plain, or curvature (mean curvature: blue
    /// concave, white flat, red convex; range ± the 98th percentile of |H|).
    #[arg(long, value_enum, default_value = "plain")]
    pub color: ColorBy,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom quads`.
#[derive(Args, Debug)]
pub struct QuadsArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// The largest angle between the two triangles' normals, in degrees
    /// (180: no limit).
    #[arg(long, default_value_t = 40.0, value_parser = non_negative)]
    pub face_angle: f64,
    /// The largest distance of a quad's corner from 90°, in degrees (180:
    /// no limit; the quad is always convex).
    #[arg(long, default_value_t = 40.0, value_parser = non_negative)]
    pub shape_angle: f64,
    /// The edges to keep, comma-separated: material, seams, sharp.
    #[arg(long, value_delimiter = ',', value_parser = ["material", "seams", "sharp"])]
    pub delimit: Vec<String>,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// `meshloom sample`.
#[derive(Args, Debug)]
pub struct SampleArgs {
    /// The mesh file (closed).
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The CSV file to write: a header `x,y,z`, then one point a line.
    pub output: PathBuf,
    /// How many points inside the mesh.
    #[arg(long, value_name = "N")]
    pub inside: usize,
    /// The random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// What colours the faces in `meshloom render`.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorBy {
    /// The plain front and back colours.
    Plain,
    /// Mean curvature, by a diverging colour map.
    Curvature,
}

/// `meshloom subdivide`.
#[derive(Args, Debug)]
pub struct SubdivideArgs {
    /// The mesh file to read.
    #[arg(value_parser = mesh_path)]
    pub input: PathBuf,
    /// The mesh file to write (format from its extension).
    #[arg(value_parser = mesh_path)]
    pub output: PathBuf,
    /// The scheme: loop (triangles), catmull-clark (any polygons; quads
    /// after one level), sqrt3 (triangles), midpoint (nothing moves).
    #[arg(long, value_name = "SCHEME", value_parser = words::<Scheme>(Scheme::WORDS))]
    pub scheme: Scheme,
    /// Levels, 0 to 8 (each multiplies the faces by 3 or 4).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(0..=8))]
    pub levels: u32,
    /// An f64 edge column of crease sharpness (loop, catmull-clark).
    #[arg(long, value_name = "NAME")]
    pub crease_column: Option<String>,
    /// A bool vertex column: vertices where it is true stay where they are.
    #[arg(long, value_name = "NAME")]
    pub corner_column: Option<String>,
    /// Keep boundary corners (vertices of a single face) in place.
    #[arg(long)]
    pub corners: bool,
    /// How midpoint cuts the faces: auto (triangles 1-to-4 when every face
    /// is a triangle, else quads), quads or triangles.
    #[arg(long, value_name = "HOW", default_value_t = MidpointFaces::Auto,
          value_parser = words::<MidpointFaces>(MidpointFaces::WORDS))]
    pub midpoint_faces: MidpointFaces,
    /// Refuse, before any work, a result estimated past this many faces.
    #[arg(long, value_name = "N", default_value_t = meshloom::algo::DEFAULT_MAX_FACES)]
    pub max_faces: usize,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub read: ReadArgs,
}

/// The value parser of an option enum that takes the library's words
/// (its `FromStr`): `--help` lists them, another word is a usage error.
fn words<T>(words: &'static [&'static str]) -> impl clap::builder::TypedValueParser<Value = T>
where
    T: std::str::FromStr<Err = meshloom::choice::UnknownChoice> + Clone + Send + Sync + 'static,
{
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(words.iter().copied()).try_map(|s| s.parse::<T>())
}

/// What the readers know, for messages.
pub const KNOWN: &str = "expected .obj, .off, .ply or .stl (each optionally + .gz), .gltf or .glb";

/// A path whose extension names a mesh format (for commands that take one
/// file): a folder or an unknown extension is a usage error that says so.
fn mesh_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    if path.is_dir() {
        return Err(format!("{s} is a folder; this command takes one mesh file"));
    }
    if MeshFormat::of_path(&path).is_some() {
        Ok(path)
    } else {
        Err(unknown_extension(&path))
    }
}

/// An input of the commands that take several: `-`, a folder, or a path
/// whose extension names a mesh format (an output path of `convert IN OUT`
/// passes here too).
fn input_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    if s == "-" || path.is_dir() || MeshFormat::of_path(&path).is_some() {
        Ok(path)
    } else {
        Err(unknown_extension(&path))
    }
}

/// The message for a file name no reader knows.
pub fn unknown_extension(path: &std::path::Path) -> String {
    match path.extension() {
        Some(e) => format!(
            "{}: unknown extension .{}; {KNOWN}",
            path.display(),
            e.to_string_lossy()
        ),
        None => format!("{}: no extension; {KNOWN}", path.display()),
    }
}

/// A format named on the command line: `ply`, `.off`, `obj.gz`, `glb`.
fn format_name(s: &str) -> Result<MeshFormat, String> {
    let name = s.trim_start_matches('.');
    MeshFormat::of_path(std::path::Path::new(&format!("x.{name}")))
        .ok_or_else(|| format!("unknown format {s:?}; {KNOWN}"))
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
