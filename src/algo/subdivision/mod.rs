//! Subdivision: one driver, four schemes.
//!
//! [`subdivide`] refines a mesh by any [`Scheme`]: Loop, Catmull-Clark, √3
//! or midpoint. The per-scheme functions ([`loop_subdivide`](crate::algo::loop_subdivide),
//! [`catmull_clark`](crate::algo::catmull_clark()),
//! [`sqrt3_subdivide`](crate::algo::sqrt3_subdivide),
//! [`midpoint_subdivide`](crate::algo::midpoint_subdivide)) are the same
//! call with the scheme fixed.
//!
//! ```
//! use meshloom::algo::{subdivide, Progress, Scheme, SubdivisionOptions};
//! let scheme: Scheme = "catmull-clark".parse()?;
//! let mut cube = meshloom::shapes::cube();
//! let report = subdivide(&mut cube, scheme, &SubdivisionOptions::default().levels(2), Progress::none())?;
//! assert_eq!(report.scheme, Scheme::CatmullClark);
//! assert_eq!(cube.face_count(), 6 * 4 * 4);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # The driver and the schemes
//!
//! The driver checks the options once for every scheme (the named columns
//! exist with a fitting type; a crease column only for the schemes that
//! keep creases), refuses a result estimated past
//! [`max_faces`](SubdivisionOptions::max_faces) before any work, runs the
//! levels, each built from the previous one, and hands the last over in
//! one journal step. A scheme is a type behind one trait, and the driver
//! and the level passes are generic over it: each scheme's loops are
//! compiled for it alone, with its stencils inlined.
//!
//! | scheme | a level's topology | new positions |
//! |---|---|---|
//! | Loop | every edge split, every triangle cut 1-to-4 | the generic passes with Loop's masks |
//! | Catmull-Clark | every edge split, every face cut into one quad per corner | the generic passes with Catmull-Clark's masks |
//! | midpoint | as Loop (triangles) or as Catmull-Clark (quads) | none move: new vertices by the linear plan |
//! | √3 | a point in every face joined to its corners, every old interior edge flipped; the boundary kept or trisected | its own passes |
//!
//! Loop, Catmull-Clark and midpoint share one level function: the
//! topology of `refine`, the crease and corner rules, the position passes
//! (a scatter pass that gathers each vertex's sums in element order, the
//! old vertices' rules with a fast path for smooth interior vertices, the
//! edge points) and the attribute plans. **√3 does not fit that level**:
//! no edge is split, every interior edge is flipped away, and the boundary
//! alternates between kept and trisected, so its layout of new elements,
//! its topology pass, its point rules and its attribute plans are its own
//! ([`sqrt3`](crate::algo::sqrt3)). It shares the driver, the options and
//! their checks, the report, the corner rules (the corner column,
//! [`Boundary::CreaseAndCorners`]), the scatter pass for its vertex sums,
//! the progress stages and the assembly of the new columns.
//!
//! # How a level is built
//!
//! A level is built wholesale into a new [`Mesh`] from the previous one,
//! never through the operators: one pass over the faces and one over the
//! edges write every new half-edge record once, in slot order, into arenas
//! allocated once at their final size. The operators would do the same
//! relinking one element at a time, each with its own checks and rule
//! calls. The smooth vertex rules read
//! sums made by a scatter pass in face or edge order instead of turning
//! around each vertex: the turn misses the cache for nearly every spoke
//! on a mesh whose vertex order is not its edge order. `BENCHMARKS.md`
//! times the schemes beside pmp-library, OpenMesh and CGAL.
//!
//! Nothing of the input changes until every level is built: a cancelled
//! or failed run drops its scratch meshes and leaves the input exactly as
//! it was. The result goes in through `Mesh::replace_with`.
//!
//! # Keys
//!
//! Vertex keys from before stay valid and name the same (moved) vertex:
//! vertex slots keep their numbers and new vertices come after them. Edge,
//! half-edge and face keys from before are stale afterwards: every such
//! element was split, and their arenas start at a base generation above
//! every generation they ever issued (as [`Mesh::compact`] does).
//!
//! # Attributes
//!
//! Every column of the input is in the result, under the same name and id,
//! so handles keep working:
//!
//! | arena | what the children get |
//! |---|---|
//! | vertices, positions | the scheme's stencil |
//! | vertices, columns with a linear rule ([`Rule::LINEAR`](crate::attr::Rule::LINEAR): [`Interpolate`](crate::attr::Interpolate), floats in dynamic columns) | the stencil ("vertex" data, the default) or linear interpolation ("varying" data), chosen per column by [`VertexData`] |
//! | vertices, other columns | old vertices keep their value; new ones get the rule's `interpolate` over the linear contributors (edge ends, face corners), as `split_edge` and `poke_face` do |
//! | half-edges (corners: UVs) | face-varying, linear: each child corner interpolates the corners of its parent face only, so seams stay seams and charts never mix (OpenSubdiv's "linear all" face-varying interpolation) |
//! | edges | the two children along a parent edge get `split(value, ½)` (flags are copied, conserved values halved); new edges inside a face get `interpolate` of nothing; the crease column's children get sharpness − 1 |
//! | faces | every child gets `split(value, share)`, shares by area in the parent's plane (¼ for a triangle cut in four); holes keep their values |
//!
//! √3 differs where its topology does: see [`sqrt3`](crate::algo::sqrt3).

mod columns;
pub(crate) mod creases;
mod driver;
pub(crate) mod refine;
pub(crate) mod split;

pub(crate) use columns::{finish_columns, ColumnPlans};
pub use driver::{subdivide, Scheme};
pub(crate) use driver::{Growth, Subdivider};

use crate::algo::progress::Progress;
use crate::attr::ValueType;
use crate::error::{Error, Result};
use crate::keys::{AnyKey, ElementKind};
use crate::layout::{Eid, Vid};
use crate::mesh::Mesh;

/// How the boundary is treated (boundary edges are always infinitely
/// sharp creases: the boundary curve follows the curve rule of the scheme).
/// Words: `crease`, `crease-and-corners`.
///
/// ```
/// use meshloom::algo::Boundary;
/// assert_eq!("crease-and-corners".parse::<Boundary>()?, Boundary::CreaseAndCorners);
/// assert_eq!(Boundary::default().to_string(), "crease");
/// # Ok::<(), meshloom::choice::UnknownChoice>(())
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Boundary {
    /// Every boundary vertex follows the crease (curve) rule, corners
    /// included: a flat square's corners are rounded off (OpenSubdiv's
    /// `VTX_BOUNDARY_EDGE_ONLY`). The default.
    #[default]
    Crease,
    /// As `Crease`, and boundary vertices of valence 2 (the corner of a
    /// single face) stay where they are: a flat square keeps its corners
    /// (OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER`).
    CreaseAndCorners,
}

crate::choice::choices!(Boundary {
    Crease = "crease",
    CreaseAndCorners = "crease-and-corners",
});

/// How a vertex column with a linear rule is refined. Words: `smooth`,
/// `linear`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum VertexInterpolation {
    /// With the scheme's stencil, like positions (OpenSubdiv's "vertex"
    /// data): colours, weights and other values that should be as smooth as
    /// the surface. The default.
    #[default]
    Smooth,
    /// Linearly: old vertices keep their value, a new vertex on an edge gets
    /// the mean of its ends, a face point the mean of the face's corners
    /// (OpenSubdiv's "varying" data).
    Linear,
}

crate::choice::choices!(VertexInterpolation {
    Smooth = "smooth",
    Linear = "linear",
});

/// How [`Scheme::Midpoint`] cuts the faces (the other schemes cut by their
/// rule). Words: `auto`, `quads`, `triangles`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum MidpointFaces {
    /// Triangles 1-to-4 when every face is a triangle, quads otherwise.
    #[default]
    Auto,
    /// Every face into one quad per corner, around its centroid.
    Quads,
    /// Every triangle into four (other faces are refused).
    Triangles,
}

crate::choice::choices!(MidpointFaces {
    Auto = "auto",
    Quads = "quads",
    Triangles = "triangles",
});

/// The choice between [`VertexInterpolation::Smooth`] and
/// [`Linear`](VertexInterpolation::Linear) for the vertex columns with a
/// linear rule (positions always take the scheme's stencil).
///
/// ```
/// use meshloom::algo::subdivision::{VertexData, VertexInterpolation};
/// // Smooth every column but "temperature", which is interpolated linearly.
/// let data = VertexData::default().with("temperature", VertexInterpolation::Linear);
/// assert_eq!(data.of("temperature"), VertexInterpolation::Linear);
/// assert_eq!(data.of("colour"), VertexInterpolation::Smooth);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VertexData {
    /// For the columns not named in `columns`.
    pub default: VertexInterpolation,
    /// Per column, by name.
    pub columns: Vec<(String, VertexInterpolation)>,
}

impl VertexData {
    /// The same, with `name` interpolated as `how`.
    pub fn with(mut self, name: &str, how: VertexInterpolation) -> VertexData {
        self.columns.retain(|(n, _)| n != name);
        self.columns.push((name.to_owned(), how));
        self
    }

    /// How column `name` is interpolated.
    pub fn of(&self, name: &str) -> VertexInterpolation {
        self.columns
            .iter()
            .find(|(n, _)| n == name)
            .map_or(self.default, |(_, how)| *how)
    }
}

/// Options of [`subdivide`] (and of the per-scheme functions). Every scheme
/// reads `levels`, `max_faces` and checks the columns named; the schemes
/// that move vertices (all but midpoint) read `boundary`,
/// `corner_column` and `vertex_data`; only Loop and Catmull-Clark take a
/// `crease_column` (the others refuse one, see [`Scheme::takes_creases`]);
/// only midpoint reads `midpoint_faces`.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SubdivisionOptions {
    /// Levels to apply (default 1; 0 leaves the mesh as it is).
    pub levels: u32,
    /// Boundary corners (default: every boundary vertex follows the curve
    /// rule).
    pub boundary: Boundary,
    /// A boolean vertex column: vertices where it is `true` stay where they
    /// are (the corner rule), anywhere on the mesh. Default: none.
    pub corner_column: Option<String>,
    /// A numeric (`f64` or `f32`) edge column of crease sharpness (Loop and
    /// Catmull-Clark only), as in
    /// OpenSubdiv and Pixar's semi-sharp creases: an edge of sharpness
    /// `s ≥ 1` follows the sharp (curve) rule, its two children get `s − 1`;
    /// `0 < s < 1` blends the sharp and smooth rules; `f64::INFINITY` never
    /// softens. Absent values, zero and negative values are smooth; NaN is
    /// refused. Default: none (no creases but the boundary).
    pub crease_column: Option<String>,
    /// Smooth or linear, per vertex column with a linear rule.
    pub vertex_data: VertexData,
    /// How midpoint subdivision cuts the faces (default: by the mesh).
    pub midpoint_faces: MidpointFaces,
    /// The most faces the result may have: a request estimated past it is
    /// refused before any work with [`Error::TooLarge`] (default
    /// [`DEFAULT_MAX_FACES`](crate::algo::DEFAULT_MAX_FACES)). Each level multiplies the faces by 3 or 4.
    pub max_faces: usize,
}

crate::choice::setters!(SubdivisionOptions {
    levels: u32,
    boundary: Boundary,
    corner_column: Option<String>,
    crease_column: Option<String>,
    vertex_data: VertexData,
    midpoint_faces: MidpointFaces,
    max_faces: usize,
});

impl Default for SubdivisionOptions {
    fn default() -> Self {
        SubdivisionOptions {
            levels: 1,
            boundary: Boundary::Crease,
            corner_column: None,
            crease_column: None,
            vertex_data: VertexData::default(),
            midpoint_faces: MidpointFaces::Auto,
            max_faces: super::DEFAULT_MAX_FACES,
        }
    }
}

/// Element counts of a mesh.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Counts {
    /// Vertices.
    pub vertices: usize,
    /// Edges.
    pub edges: usize,
    /// Faces (holes excluded).
    pub faces: usize,
    /// Holes (boundary loops).
    pub holes: usize,
}

impl Counts {
    /// The counts of `mesh`.
    pub fn of(mesh: &Mesh) -> Counts {
        Counts {
            vertices: mesh.vertex_count(),
            edges: mesh.edge_count(),
            faces: mesh.face_count(),
            holes: mesh.hole_count(),
        }
    }
}

/// What one level did.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct LevelReport {
    /// Counts after the level.
    pub output: Counts,
    /// Interior edges of the parent with a positive sharpness.
    pub sharp_edges: usize,
    /// Parent vertices moved by the crease (curve) rule: boundary vertices
    /// and vertices on two sharp edges.
    pub crease_vertices: usize,
    /// Parent vertices that stayed put (the corner rule).
    pub corner_vertices: usize,
    /// Parent vertices whose rule changes at this level (a sharpness
    /// decaying below 1), moved by a blend of the two rules.
    pub blended_vertices: usize,
    /// √3 only: whether this level trisected the boundary edges.
    pub boundary_trisected: bool,
}

/// What a subdivision did: counts before and after every level, and the
/// rules it used. Time-independent: the same input gives the same report.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct SubdivisionReport {
    /// The scheme.
    pub scheme: Scheme,
    /// Counts of the input.
    pub input: Counts,
    /// Counts after the last level (the input's when no level ran).
    pub output: Counts,
    /// One entry per level, in order.
    pub levels: Vec<LevelReport>,
}

/// A vertex on a hole, in the position passes' valence counts (which
/// saturate, so it stays).
pub(crate) const ON_HOLE: u32 = u32::MAX;

/// In edge order, adds each end of an edge between two faces to the other
/// end's `sums` and counts it in the other's `valence`; the ends of an
/// edge on a hole get [`ON_HOLE`].
///
/// Around an interior vertex every edge lies between two faces, so after
/// the pass `sums[v]` is `Σ uᵢ` and `valence[v]` is `n`, and a smooth
/// vertex rule reads `v`'s slot instead of turning around it. The turn
/// misses the cache for nearly every spoke on a mesh whose vertex order is
/// not its edge order (icosphere(7)); this pass reads the half-edges in
/// order. Loop on icosphere(7), one level, paired runs (lower quartile):
/// 139 ms turning, 115 ms with this pass.
pub(crate) fn scatter_edge_ends(
    mesh: &Mesh,
    p: &[[f64; 3]],
    sums: &mut [[f64; 3]],
    valence: &mut [u32],
) {
    for ei in 0..mesh.edge_slots() {
        if !mesh.edge_live(ei) {
            continue;
        }
        let [h, t] = Eid::new(ei as u32).halfedges();
        let (rh, rt) = (mesh.halfedge_record(h), mesh.halfedge_record(t));
        let (a, b) = (rh.origin.index(), rt.origin.index());
        if mesh.is_hole(rh.face) || mesh.is_hole(rt.face) {
            valence[a] = ON_HOLE;
            valence[b] = ON_HOLE;
            continue;
        }
        let (pa, pb) = (p[a], p[b]);
        for k in 0..3 {
            sums[a][k] += pb[k];
            sums[b][k] += pa[k];
        }
        valence[a] = valence[a].saturating_add(1);
        valence[b] = valence[b].saturating_add(1);
    }
}

/// Reports progress every `STRIDE` units of a pass.
pub(crate) struct Stage<'p, 'a> {
    progress: &'p mut Progress<'a>,
    algorithm: &'static str,
    name: String,
    total: u64,
}

impl<'p, 'a> Stage<'p, 'a> {
    /// Report every this many units (a power of two).
    pub(crate) const STRIDE: usize = 1 << 15;

    pub(crate) fn new(
        progress: &'p mut Progress<'a>,
        algorithm: &'static str,
        level: u32,
        what: &str,
        total: usize,
    ) -> Result<Stage<'p, 'a>> {
        let name = format!("level {}: {what}", level + 1);
        progress.report(algorithm, &name, 0, total as u64)?;
        Ok(Stage {
            progress,
            algorithm,
            name,
            total: total as u64,
        })
    }

    /// Report `done` units if `done` is a multiple of [`STRIDE`](Self::STRIDE).
    #[inline]
    pub(crate) fn tick(&mut self, done: usize) -> Result<()> {
        if done & (Self::STRIDE - 1) == 0 && self.progress.is_active() {
            self.progress
                .report(self.algorithm, &self.name, done as u64, self.total)?;
        }
        Ok(())
    }

    /// The stage is over.
    pub(crate) fn finish(self) -> Result<()> {
        self.progress
            .report(self.algorithm, &self.name, self.total, self.total)
    }
}

/// The progress of one level's passes.
pub(crate) struct Pass<'p, 'a> {
    pub(crate) progress: &'p mut Progress<'a>,
    pub(crate) algorithm: &'static str,
    pub(crate) level: u32,
}

impl<'a> Pass<'_, 'a> {
    /// A stage of `total` units named `what`.
    pub(crate) fn stage(&mut self, what: &str, total: usize) -> Result<Stage<'_, 'a>> {
        Stage::new(self.progress, self.algorithm, self.level, what, total)
    }
}

/// Refuse a parent position at NaN or infinity, before a level reads it.
#[inline(always)]
pub(crate) fn check_finite_position(mesh: &Mesh, v: Vid, p: [f64; 3]) -> Result<()> {
    if p.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinitePosition {
            key: mesh.vkey(v).into(),
            position: p,
        })
    }
}

/// An `Unsuitable` error.
pub(crate) fn unsuitable(
    algorithm: &'static str,
    key: Option<AnyKey>,
    reason: impl Into<String>,
) -> Error {
    Error::Unsuitable {
        algorithm,
        key,
        reason: reason.into(),
    }
}

/// Check the options that name columns: they exist with a fitting type.
pub(crate) fn check_columns(
    mesh: &Mesh,
    algorithm: &'static str,
    corner_column: Option<&str>,
    crease_column: Option<&str>,
    vertex_data: &VertexData,
) -> Result<()> {
    if let Some(name) = corner_column {
        corner_column_index(mesh, name)?;
    }
    if let Some(name) = crease_column {
        crease_column_index(mesh, name)?;
    }
    for (name, _) in &vertex_data.columns {
        if name == crate::attr::POSITION {
            return Err(unsuitable(
                algorithm,
                None,
                "positions always follow the scheme's stencil; VertexData cannot name them",
            ));
        }
        if mesh.attrs().vertex.find(name).is_none() {
            return Err(Error::AttributeMissing {
                kind: ElementKind::Vertex,
                name: name.clone(),
            });
        }
    }
    Ok(())
}

/// The index of corner column `name`: a boolean vertex column.
pub(crate) fn corner_column_index(mesh: &Mesh, name: &str) -> Result<usize> {
    column_of_type(mesh, ElementKind::Vertex, name, &[ValueType::Bool], "bool")
}

/// The index of crease column `name`: an `f64` or `f32` edge column.
pub(crate) fn crease_column_index(mesh: &Mesh, name: &str) -> Result<usize> {
    column_of_type(
        mesh,
        ElementKind::Edge,
        name,
        &[ValueType::F64, ValueType::F32],
        "f64",
    )
}

/// The index of column `name` of arena `kind`, whose values convert to one
/// of `types`.
fn column_of_type(
    mesh: &Mesh,
    kind: ElementKind,
    name: &str,
    types: &[ValueType],
    expected: &'static str,
) -> Result<usize> {
    let cols = mesh.attrs().columns(kind);
    let i = cols.find(name).ok_or_else(|| Error::AttributeMissing {
        kind,
        name: name.to_owned(),
    })?;
    let col = &cols.cols[i].1;
    let ty = cols.meta[i].value_type.or_else(|| col.portable_type());
    if ty.is_some_and(|t| types.contains(&t)) {
        Ok(i)
    } else {
        Err(Error::AttributeType {
            kind,
            name: name.to_owned(),
            expected,
            found: col.type_name(),
        })
    }
}
