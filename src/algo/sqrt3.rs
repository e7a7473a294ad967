//! √3 subdivision (Kobbelt 2000): a point in the middle of every
//! triangle, joined to its corners, then every old edge flipped; the
//! triangles triple per level (a factor of 9 every two levels, where Loop
//! gives 16), and the surface converges to a C² limit (C¹ at extraordinary
//! vertices).
//!
//! **Counts** per level: V' = V + F, F' = 3F, E' = E + 3F (3E on a closed
//! mesh); at a level that trisects the boundary (below) add 2B vertices,
//! 2B faces and 4B edges for the B boundary edges. Holes keep their
//! number. Triangles only: [`Error::Unsuitable`](crate::Error::Unsuitable) names the first face that
//! is not a triangle, or an interior vertex of valence 2.
//!
//! **Boundary** (Kobbelt's rule). Boundary edges are never flipped. Odd
//! levels of a call (1, 3, 5, ...) keep them: the triangle beside one is
//! the piece of its parent between the edge and the face point, and
//! boundary vertices stay where they are. Even levels (2, 4, ...) trisect
//! every boundary edge: two boundary points on it, joined to the face
//! point, so the piece becomes three triangles. Two levels thus refine
//! the boundary by 3 where the inside is refined by √3² = 3, and the
//! boundary converges to a cubic B-spline curve: at an even level it
//! moves by the ternary cubic B-spline's masks (its subdivision mask is
//! `(1, 4, 10, 16, 19, 16, 10, 4, 1) / 27`). With `p, a, b, q` four
//! consecutive vertices of a boundary loop before the level:
//!
//! | new point | mask |
//! |---|---|
//! | old boundary vertex `a` | `(4p + 19a + 4b) / 27` |
//! | a third of the way from `a` to `b` | `(p + 16a + 10b) / 27` |
//! | two thirds of the way from `a` to `b` | `(10a + 16b + q) / 27` |
//! | a third of the way from `a` to `b`, `a` a corner | `(2a + b) / 3` (`a` stays) |
//!
//! A boundary vertex that stays is a corner and ends the curve: the
//! corner of a single face with [`Boundary::CreaseAndCorners`](crate::algo::Boundary)
//! (at the even level of valence 3: the odd level before cut its face in
//! three, two at it), a vertex of the
//! [`corner_column`](SubdivisionOptions::corner_column), or a vertex on
//! more than two boundary edges. Levels are counted within one call: two
//! calls of one level each never trisect; ask for `levels: 2`. Seams
//! (below) are kept but not trisected.
//!
//! **Rules.** Face point: the centroid. Old interior vertex
//! `(1 − αₙ) v + αₙ/n Σ uᵢ` with `αₙ = (4 − 2 cos(2π/n)) / 9`.
//! [`SubdivisionOptions::corner_column`] keeps marked vertices where they
//! are; a crease column is refused (every old edge is flipped away, so no
//! child edge runs along it).
//!
//! **Attributes.** Vertex columns as in
//! [`subdivision`](crate::algo::subdivision) (the face point is the
//! centroid for both smooth and linear data; a boundary point takes the
//! curve stencil above, or the thirds of its edge for linear data). Every
//! new triangle covers
//! half of one parent piece on each side of a flipped edge: its face
//! columns get the two pieces merged and halved, as
//! [`Mesh::flip_edge`](crate::Mesh::flip_edge) does (a conserved value
//! keeps its total, a label comes from the triangle's own side). A corner
//! at a face point takes the mean of its face's corners; a corner at an
//! old vertex lies in two parent faces and takes the mean of the two
//! corners there, which are the same value unless the edge between them
//! is a seam. **Seams stay seams:** an edge where any corner (half-edge)
//! column differs across it (a UV seam, a split corner normal) is kept,
//! not flipped, as a boundary edge is; the triangles beside it stay in
//! their own parent face, and the corners on each side keep their own
//! chart's values. On a trisected boundary edge the corners at a boundary
//! point take the parent face's two corners at the edge's ends, a third
//! and two thirds of the way (the hole's side likewise), and the three
//! triangles of the piece get a ninth of the parent's face values each.
//! Edge columns: every new edge gets `interpolate` of nothing (no edge
//! runs along a parent edge but the boundary), a kept edge keeps its
//! value, the three thirds of a trisected edge get `split(value, ⅓)`
//! (flags are copied, conserved values divided).
//!
//! **Built wholesale**, not by `poke_face` and `flip_edge` on every
//! element: one pass over the edges writes the six half-edges of each, in
//! slot order, into arenas allocated at their final size; see
//! [`subdivision`](crate::algo::subdivision) for keys and cancellation.
//!
//! ```
//! use meshloom::algo::{sqrt3_subdivide, Progress, SubdivisionOptions};
//! let mut mesh = meshloom::shapes::icosahedron();
//! sqrt3_subdivide(&mut mesh, &SubdivisionOptions::default().levels(2), Progress::none())?;
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (12 + 20 + 60, 180));
//! mesh.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::f64::consts::PI;

use crate::algo::progress::Progress;
use crate::algo::subdivision::creases::{Features, PointSink, Rule, Sink};
use crate::algo::subdivision::refine::{valence_two_error, CutRule};
use crate::algo::subdivision::{
    check_finite_position, finish_columns, scatter_edge_ends, subdivide, unsuitable, Growth,
    LevelReport, Pass, Scheme, Subdivider, SubdivisionOptions, SubdivisionReport, ON_HOLE,
};
use crate::error::Result;
use crate::layout::{with_headroom, Fid, Hid, Vid};
use crate::mesh::Mesh;

mod plans;
mod topology;

use plans::Plans;
use topology::{build, Layout};

const ALGORITHM: &str = "sqrt3_subdivide";

/// Apply `options.levels` levels of √3 subdivision to a triangle mesh
/// (the boundary is kept at odd levels and trisected at even ones, see the
/// module doc): [`subdivide`] with [`Scheme::Sqrt3`].
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a face that is not a triangle, an interior
/// vertex of valence 2, or a crease column in the options; the other
/// errors of [`subdivide`]. On any error the mesh is exactly as it was.
///
/// ```
/// use meshloom::algo::{sqrt3_subdivide, Progress, SubdivisionOptions};
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let r = sqrt3_subdivide(&mut mesh, &SubdivisionOptions::default(), Progress::none())?;
/// assert_eq!(r.output.vertices, 4 + 4); // V + F
/// assert_eq!(mesh.face_count(), 12); // 3F
/// // Quads are refused, and the mesh is left alone.
/// let mut cube = meshloom::shapes::cube();
/// assert!(sqrt3_subdivide(&mut cube, &SubdivisionOptions::default(), Progress::none()).is_err());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn sqrt3_subdivide(
    mesh: &mut Mesh,
    options: &SubdivisionOptions,
    progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    subdivide(mesh, Scheme::Sqrt3, options, progress)
}

/// √3 subdivision on the driver, with its own level.
pub(crate) struct Sqrt3;

impl Subdivider for Sqrt3 {
    const SCHEME: Scheme = Scheme::Sqrt3;

    fn growth(&self) -> Growth {
        Growth::Three
    }

    fn level(
        &self,
        mesh: &Mesh,
        options: &SubdivisionOptions,
        level: u32,
        progress: &mut Progress<'_>,
    ) -> Result<(Mesh, LevelReport)> {
        sqrt3_level(mesh, options, level, progress)
    }
}

/// Kobbelt's α for valence `n`.
#[inline]
fn alpha(n: usize) -> f64 {
    (4.0 - 2.0 * (2.0 * PI / n as f64).cos()) / 9.0
}

/// Refuse what √3 cannot take.
fn check(mesh: &Mesh) -> Result<()> {
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        let n = mesh.face_halfedges(f).count();
        if n != 3 {
            return Err(unsuitable(
                ALGORITHM,
                Some(mesh.fkey(f).into()),
                format!("the scheme takes triangles; this face has {n} sides"),
            ));
        }
    }
    for v in mesh.vids() {
        if let Some(e) = valence_two_error(mesh, v, CutRule::Triangles, ALGORITHM) {
            return Err(e);
        }
    }
    Ok(())
}

fn sqrt3_level(
    mesh: &Mesh,
    options: &SubdivisionOptions,
    level: u32,
    progress: &mut Progress<'_>,
) -> Result<(Mesh, LevelReport)> {
    check(mesh)?;
    let features = Features::read(
        mesh,
        ALGORITHM,
        options.boundary,
        options.corner_column.as_deref(),
        None,
    )?;
    // Levels 2, 4, ... (index 1, 3, ...) trisect the boundary.
    let trisect = level % 2 == 1;
    let l = Layout::of(mesh, trisect);
    let mut pass = Pass {
        progress,
        algorithm: ALGORITHM,
        level,
    };
    let topology = build(mesh, &l, &mut pass)?;
    let mut report = LevelReport {
        boundary_trisected: trisect,
        ..LevelReport::default()
    };
    let dense = mesh
        .attrs()
        .positions()
        .filter(|c| c.present_bits().is_none())
        .map(|c| c.raw());
    let rules = VertexRules::of(mesh, &features, trisect);
    let positions = match dense {
        Some(p) => {
            let (positions, counts) = positions(mesh, &l, &rules, p, &mut pass)?;
            report.corner_vertices = counts.corner;
            report.crease_vertices = counts.crease;
            Some(positions)
        }
        None => None,
    };
    let plans = Plans {
        mesh,
        l: &l,
        rules: &rules,
    };
    let attrs = finish_columns(mesh, &plans, positions, &options.vertex_data, None);
    Ok((topology.into_mesh(attrs), report))
}

/// What each old vertex does at one level.
#[derive(Copy, Clone, Debug, PartialEq)]
enum VertexMove {
    /// Kobbelt's interior rule.
    Smooth,
    /// Stays where it is: pinned by the corner column or
    /// [`Boundary::CreaseAndCorners`](crate::algo::subdivision::Boundary),
    /// a non-manifold boundary vertex, or any boundary vertex at an odd
    /// level.
    Stay,
    /// The boundary curve rule `(4 a + 19 v + 4 b) / 27`, `a` and `b` the
    /// boundary neighbours (even levels).
    Curve(Vid, Vid),
}

/// The moves of the old vertices at one level.
struct VertexRules<'a> {
    mesh: &'a Mesh,
    features: &'a Features,
    trisect: bool,
}

impl<'a> VertexRules<'a> {
    fn of(mesh: &'a Mesh, features: &'a Features, trisect: bool) -> VertexRules<'a> {
        VertexRules {
            mesh,
            features,
            trisect,
        }
    }

    /// The move of live vertex `v`.
    #[inline(always)]
    fn of_vertex(&self, v: Vid) -> VertexMove {
        let m = self.mesh;
        if !m.in_hole(m.vertex_halfedge(v)) {
            if self.features.is_special(v) {
                VertexMove::Stay
            } else {
                VertexMove::Smooth
            }
        } else if !self.trisect {
            VertexMove::Stay
        } else {
            self.boundary_move(v)
        }
    }

    /// The move of boundary vertex `v` at an even level.
    #[inline(never)]
    fn boundary_move(&self, v: Vid) -> VertexMove {
        let mut ring = Vec::new();
        let on_boundary = self.features.gather(self.mesh, v, &mut ring);
        // The corner of a single face (valence 2) had that face cut in
        // three by the level before, two of them at it: valence 3 now (a
        // boundary vertex of valence n comes out of an odd level with
        // n + 1 or more).
        if self.features.boundary_corners() && on_boundary && ring.len() == 3 {
            return VertexMove::Stay;
        }
        match self.features.rule(v, &ring, on_boundary).parent {
            Rule::Crease(a, b) => VertexMove::Curve(a, b),
            _ => VertexMove::Stay,
        }
    }

    /// The boundary neighbour of curve vertex `v` other than `u`, `None`
    /// when `v` stays (a corner: the curve ends there).
    #[inline]
    fn beyond(&self, v: Vid, u: Vid) -> Option<Vid> {
        match self.of_vertex(v) {
            VertexMove::Curve(a, b) => Some(if a == u { b } else { a }),
            _ => None,
        }
    }

    /// The stencil of boundary point `k` (0: a third along `h`, 1: two
    /// thirds) on trisected edge `h` (the inner half-edge): the ternary
    /// cubic B-spline rule `(p₋ + 16 a + 10 b) / 27` for the point next to
    /// `a`, with `p₋` `a`'s other boundary neighbour; next to a corner,
    /// the point a third of the way (the curve ends at the corner).
    fn boundary_point<S: Sink>(&self, h: Hid, k: u32, sink: &mut S) {
        let m = self.mesh;
        let (a, b) = (m.origin(h), m.origin(h.twin()));
        let (near, far) = if k == 0 { (a, b) } else { (b, a) };
        match self.beyond(near, far) {
            Some(before) => {
                sink.vertex(before, 1.0 / 27.0);
                sink.vertex(near, 16.0 / 27.0);
                sink.vertex(far, 10.0 / 27.0);
            }
            None => {
                sink.vertex(near, 2.0 / 3.0);
                sink.vertex(far, 1.0 / 3.0);
            }
        }
    }
}

/// How many old vertices moved by which rule.
#[derive(Default)]
struct MoveCounts {
    corner: usize,
    crease: usize,
}

/// Positions: old vertices by Kobbelt's rule (pinned ones stay; boundary
/// ones stay at odd levels, follow the curve rule at even ones), then the
/// face points, then the boundary points.
fn positions(
    mesh: &Mesh,
    l: &Layout,
    rules: &VertexRules<'_>,
    p: &[[f64; 3]],
    pass: &mut Pass<'_, '_>,
) -> Result<(Vec<[f64; 3]>, MoveCounts)> {
    let nv = l.nv as usize;
    let mut out = with_headroom(nv + mesh.face_count() + 2 * l.boundary as usize);
    // The old vertices' slots first hold the neighbour sums.
    out.resize(nv, [0.0; 3]);
    let mut valence = vec![0u32; nv];
    scatter_edge_ends(mesh, p, &mut out, &mut valence);
    let alphas: Vec<f64> = (0..64).map(alpha).collect();
    let mut counts = MoveCounts::default();
    let mut stage = pass.stage("vertices", nv)?;
    for (vi, out) in out.iter_mut().enumerate() {
        stage.tick(vi)?;
        if !mesh.vertex_live(vi) {
            continue;
        }
        let v = Vid::new(vi as u32);
        let pv = p[vi];
        check_finite_position(mesh, v, pv)?;
        match rules.of_vertex(v) {
            VertexMove::Smooth => {}
            VertexMove::Stay => {
                counts.corner += 1;
                *out = pv;
                continue;
            }
            VertexMove::Curve(a, b) => {
                counts.crease += 1;
                let mut sink = PointSink::new(p);
                curve_vertex(v, a, b, &mut sink);
                *out = sink.take();
                continue;
            }
        }
        // Interior (rule 11: no hole at v): `out` holds the sum of the
        // neighbours.
        debug_assert!(valence[vi] != ON_HOLE);
        let n = valence[vi] as usize;
        let sum = *out;
        let a = alphas.get(n).copied().unwrap_or_else(|| alpha(n));
        let (keep, share) = (1.0 - a, a / n as f64);
        *out = [
            keep * pv[0] + share * sum[0],
            keep * pv[1] + share * sum[1],
            keep * pv[2] + share * sum[2],
        ];
    }
    stage.finish()?;
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        let h = mesh.face_halfedge(f);
        let (a, b) = (mesh.next(h), mesh.next(mesh.next(h)));
        let (pa, pb, pc) = (
            p[mesh.origin(h).index()],
            p[mesh.origin(a).index()],
            p[mesh.origin(b).index()],
        );
        let third = 1.0 / 3.0;
        out.push([
            (pa[0] + pb[0] + pc[0]) * third,
            (pa[1] + pb[1] + pc[1]) * third,
            (pa[2] + pb[2] + pc[2]) * third,
        ]);
    }
    debug_assert_eq!(l.face_point(Fid::new(0)).index(), nv);
    let mut sink = PointSink::new(p);
    for (_, h) in l.trisected_edges(mesh) {
        for k in 0..2 {
            rules.boundary_point(h, k, &mut sink);
            out.push(sink.take());
        }
    }
    Ok((out, counts))
}

/// The boundary curve rule at `v` between boundary neighbours `a` and `b`
/// (the ternary cubic B-spline's vertex rule).
#[inline]
fn curve_vertex<S: Sink>(v: Vid, a: Vid, b: Vid, sink: &mut S) {
    sink.vertex(a, 4.0 / 27.0);
    sink.vertex(v, 19.0 / 27.0);
    sink.vertex(b, 4.0 / 27.0);
}
