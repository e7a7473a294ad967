//! Loop subdivision (Charles Loop, 1987): every triangle becomes four, the
//! surface converges to a C² limit (C¹ at extraordinary vertices).
//!
//! **Counts** per level: V' = V + E, E' = 2E + 3F, F' = 4F; holes keep
//! their number and double their sides. Triangles only
//! ([`Error::Unsuitable`](crate::Error::Unsuitable) names the first other face; triangulate first or
//! use [Catmull-Clark](crate::algo::catmull_clark())).
//!
//! **Rules.** Edge point `⅜ (a + b) + ⅛ (c + d)` (`c`, `d` the opposite
//! corners); old vertex `(1 − nβ) v + β Σ uᵢ` with Loop's
//! `β = (⅝ − (⅜ + ¼ cos 2π/n)²) / n`. Boundary edges and edges of sharpness
//! ≥ 1 take the midpoint, boundary and crease vertices `¾ v + ⅛ (a + b)`,
//! corners stay; semi-sharp creases, corners and the boundary option are
//! described in [`subdivision`](crate::algo::subdivision) and
//! [`SubdivisionOptions`].
//!
//! **Attributes** follow the table in
//! [`subdivision`](crate::algo::subdivision): UVs stay linear in each
//! parent triangle (seams stay seams), face values split in four (¼ each),
//! edge flags reach both halves of their edge.
//!
//! **Built wholesale** by the face-splitting level the driver shares with
//! Catmull-Clark and midpoint, not through [`Mesh::split_edge`] and
//! [`Mesh::split_face`]: one pass over the faces and one over the edges
//! write every record once into arenas allocated at their final size. See
//! [`subdivision`](crate::algo::subdivision) for the driver, keys and
//! cancellation. This file holds Loop's rules: its masks and fast
//! stencils. `BENCHMARKS.md` has the figures against the peers.
//!
//! **Cost.** O(V + E + F) per level: the topology's passes over the
//! faces and the edges, the positions' over the edges (the scatter), the
//! vertices and the edges, plus one per arena that has attribute columns.
//!
//! ```
//! use meshloom::algo::{loop_subdivide, Progress, SubdivisionOptions};
//! let mut mesh = meshloom::shapes::icosahedron();
//! let v = mesh.vertices().next().unwrap();
//! let report = loop_subdivide(&mut mesh, &SubdivisionOptions::default().levels(2), Progress::none())?;
//! assert_eq!(report.levels[0].output.faces, 80);
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (162, 320));
//! // Vertex keys from before still name their (moved) vertex.
//! assert!(mesh.position(v)?.iter().all(|c| c.is_finite()));
//! mesh.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::f64::consts::PI;

use crate::algo::progress::Progress;
use crate::algo::subdivision::creases::{Mask, PointSink, Sink, Spoke};
use crate::algo::subdivision::refine::CutRule;
use crate::algo::subdivision::split::{FaceSplit, SmoothRules};
use crate::algo::subdivision::{
    scatter_edge_ends, subdivide, Pass, Scheme, SubdivisionOptions, SubdivisionReport,
};
use crate::error::Result;
use crate::layout::{Hid, Vid};
use crate::mesh::Mesh;

/// Apply `options.levels` levels of Loop subdivision to a triangle mesh:
/// [`subdivide`] with [`Scheme::Loop`].
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a face that is not
/// a triangle or an interior vertex of valence 2 (its two faces share both
/// its edges), and for a NaN sharpness; the other errors of [`subdivide`].
/// On any error the mesh is exactly as it was.
///
/// # Complexity
/// O(output size) time; the result of each level is allocated once.
///
/// ```
/// use meshloom::algo::{loop_subdivide, Progress, SubdivisionOptions};
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let r = loop_subdivide(&mut mesh, &SubdivisionOptions::default(), Progress::none())?;
/// assert_eq!((r.input.vertices, r.input.edges), (4, 6));
/// assert_eq!(mesh.vertex_count(), 4 + 6); // V + E
/// assert_eq!(mesh.face_count(), 16); // 4F
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn loop_subdivide(
    mesh: &mut Mesh,
    options: &SubdivisionOptions,
    progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    subdivide(mesh, Scheme::Loop, options, progress)
}

/// Loop's β for valence `n`.
#[inline]
pub(crate) fn loop_beta(n: usize) -> f64 {
    if n == 0 {
        return 0.0;
    }
    let c = 0.375 + 0.25 * (2.0 * PI / n as f64).cos();
    (0.625 - c * c) / n as f64
}

/// Loop subdivision, on the face-splitting level.
pub(crate) struct Loop;

impl FaceSplit for Loop {
    const SCHEME: Scheme = Scheme::Loop;
    type Rules = Loop;

    #[inline]
    fn cut(&self) -> CutRule {
        CutRule::Triangles
    }

    #[inline]
    fn rules(&self) -> Option<&Loop> {
        Some(self)
    }
}

/// The smooth masks: old vertex `(1 − nβ) v + β Σ uᵢ`, edge point
/// `⅜ (a + b) + ⅛ (c + d)`.
impl Mask for Loop {
    #[inline]
    fn smooth_vertex<S: Sink>(&self, _mesh: &Mesh, v: Vid, ring: &[Spoke], w: f64, sink: &mut S) {
        let n = ring.len();
        let b = loop_beta(n);
        sink.vertex(v, w * (1.0 - n as f64 * b));
        for sp in ring {
            sink.vertex(sp.u, w * b);
        }
    }

    #[inline]
    fn smooth_edge<S: Sink>(&self, mesh: &Mesh, h: Hid, w: f64, sink: &mut S) {
        let t = h.twin();
        let (rh, rt) = (mesh.halfedge_record(h), mesh.halfedge_record(t));
        let c = mesh.origin(rh.next.twin());
        let d = mesh.origin(rt.next.twin());
        sink.vertex(rh.origin, 0.375 * w);
        sink.vertex(rt.origin, 0.375 * w);
        sink.vertex(c, 0.125 * w);
        sink.vertex(d, 0.125 * w);
    }
}

/// The fast stencils: the vertex sums `Σ uᵢ` from the edge-order scatter
/// pass, no face points.
impl SmoothRules for Loop {
    const FACE_POINTS: bool = false;

    #[inline]
    fn scatter(
        &self,
        mesh: &Mesh,
        p: &[[f64; 3]],
        sums: &mut [[f64; 3]],
        valence: &mut [u32],
        _face_points: &mut [[f64; 3]],
        _pass: &mut Pass<'_, '_>,
    ) -> Result<()> {
        scatter_edge_ends(mesh, p, sums, valence);
        Ok(())
    }

    #[inline]
    fn vertex_weights(&self, n: usize) -> (f64, f64) {
        let b = loop_beta(n);
        (1.0 - n as f64 * b, b)
    }

    #[inline(always)]
    fn edge_point(&self, mesh: &Mesh, h: Hid, points: &PointSink<'_>) -> [f64; 3] {
        let p = points.p;
        let (rh, rt) = (mesh.halfedge_record(h), mesh.halfedge_record(h.twin()));
        let (a, b) = (p[rh.origin.index()], p[rt.origin.index()]);
        let c = p[mesh.origin(rh.next.twin()).index()];
        let d = p[mesh.origin(rt.next.twin()).index()];
        [
            0.375 * (a[0] + b[0]) + 0.125 * (c[0] + d[0]),
            0.375 * (a[1] + b[1]) + 0.125 * (c[1] + d[1]),
            0.375 * (a[2] + b[2]) + 0.125 * (c[2] + d[2]),
        ]
    }
}
