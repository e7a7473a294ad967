//! Catmull-Clark subdivision (Catmull and Clark, 1978): every face of `n`
//! sides becomes `n` quads around a face point; after one level the mesh is
//! all quads and the surface converges to a bicubic B-spline (C²) away from
//! extraordinary vertices.
//!
//! **Counts** per level: V' = V + E + F, E' = 2E + Σ degrees, F' = Σ
//! degrees (the corners); holes keep their number and double their sides.
//! Any polygons.
//!
//! **Rules.** Face point: the centroid. Edge point `(a + b + F₁ + F₂) / 4`
//! (the face points on either side). Old vertex
//! `((n − 2) v + Σ uᵢ / n + Σ Fᵢ / n) / n`. Boundary edges and edges of
//! sharpness ≥ 1 take the midpoint; boundary and crease vertices
//! `¾ v + ⅛ (a + b)` (the cubic B-spline of the crease curve); corners stay.
//! Semi-sharp creases, corners and the boundary option: see
//! [`subdivision`](crate::algo::subdivision) and [`SubdivisionOptions`].
//!
//! **Attributes** follow the table in
//! [`subdivision`](crate::algo::subdivision): UVs stay linear in each
//! parent face (seams stay seams), face values go to every child quad with
//! shares by area, edge flags reach both halves of their edge.
//!
//! **Built wholesale** by the face-splitting level the driver shares with
//! Loop and midpoint, not through the operators (`split_edge` on every
//! edge, then `poke_face` and edge removals, or `split_face` fans): one
//! pass over the faces and one over the edges write every record once into
//! arenas allocated at their final size. See
//! [`subdivision`](crate::algo::subdivision) for the driver, keys and
//! cancellation. This file holds Catmull-Clark's rules: its masks and fast
//! stencils. `BENCHMARKS.md` has the figures against the peers.
//!
//! **Cost.** O(V + E + F) per level: passes over the faces (face points,
//! inside edges), the vertices and the edges, plus one per arena that has
//! attribute columns.
//!
//! ```
//! use meshloom::algo::{catmull_clark, Progress, SubdivisionOptions};
//! let mut cube = meshloom::shapes::cube();
//! catmull_clark(&mut cube, &SubdivisionOptions::default().levels(3), Progress::none())?;
//! assert_eq!(cube.face_count(), 6 * 4 * 4 * 4);
//! // The cube shrinks toward its limit surface, inside the unit cube.
//! for v in cube.vertices() {
//!     let p = cube.position(v)?;
//!     assert!(p.iter().all(|&c| (0.0..=1.0).contains(&c)));
//! }
//! # Ok::<(), meshloom::Error>(())
//! ```

use crate::algo::progress::Progress;
use crate::algo::subdivision::creases::{Mask, PointSink, Sink, Spoke};
use crate::algo::subdivision::refine::{face_ring, CutRule};
use crate::algo::subdivision::split::{FaceSplit, SmoothRules};
use crate::algo::subdivision::{
    subdivide, Pass, Scheme, SubdivisionOptions, SubdivisionReport, ON_HOLE,
};
use crate::error::Result;
use crate::layout::{Fid, Hid, Vid};
use crate::mesh::Mesh;

/// Apply `options.levels` levels of Catmull-Clark subdivision:
/// [`subdivide`] with [`Scheme::CatmullClark`].
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a NaN sharpness;
/// the other errors of [`subdivide`]. On any error the mesh is exactly as
/// it was.
///
/// # Complexity
/// O(output size) time; the result of each level is allocated once.
///
/// ```
/// use meshloom::algo::{catmull_clark, Progress, SubdivisionOptions};
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let r = catmull_clark(&mut mesh, &SubdivisionOptions::default(), Progress::none())?;
/// assert_eq!(mesh.vertex_count(), 4 + 6 + 4); // V + E + F
/// assert_eq!(mesh.face_count(), 12); // the sum of the face degrees
/// assert_eq!(r.output.faces, 12);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn catmull_clark(
    mesh: &mut Mesh,
    options: &SubdivisionOptions,
    progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    subdivide(mesh, Scheme::CatmullClark, options, progress)
}

/// Catmull-Clark subdivision, on the face-splitting level.
pub(crate) struct CatmullClark;

impl FaceSplit for CatmullClark {
    const SCHEME: Scheme = Scheme::CatmullClark;
    type Rules = CatmullClark;

    #[inline]
    fn cut(&self) -> CutRule {
        CutRule::Quads
    }

    #[inline]
    fn rules(&self) -> Option<&CatmullClark> {
        Some(self)
    }
}

/// The smooth masks: old vertex `((n − 2) v + Σ uᵢ / n + Σ Fᵢ / n) / n`,
/// edge point `(a + b + F₁ + F₂) / 4`.
impl Mask for CatmullClark {
    #[inline]
    fn smooth_vertex<S: Sink>(&self, mesh: &Mesh, v: Vid, ring: &[Spoke], w: f64, sink: &mut S) {
        let n = ring.len() as f64;
        sink.vertex(v, w * (n - 2.0) / n);
        let k = w / (n * n);
        for sp in ring {
            sink.vertex(sp.u, k);
            sink.face(mesh.face_of(sp.h), k);
        }
    }

    #[inline]
    fn smooth_edge<S: Sink>(&self, mesh: &Mesh, h: Hid, w: f64, sink: &mut S) {
        let t = h.twin();
        let (rh, rt) = (mesh.halfedge_record(h), mesh.halfedge_record(t));
        sink.vertex(rh.origin, 0.25 * w);
        sink.vertex(rt.origin, 0.25 * w);
        sink.face(rh.face, 0.25 * w);
        sink.face(rt.face, 0.25 * w);
    }
}

/// The fast stencils: the face points and the vertex sums `Σ uᵢ + Σ Fᵢ`
/// from one pass in face order (see [`scatter_face`]).
impl SmoothRules for CatmullClark {
    const FACE_POINTS: bool = true;

    fn scatter(
        &self,
        mesh: &Mesh,
        p: &[[f64; 3]],
        sums: &mut [[f64; 3]],
        valence: &mut [u32],
        face_points: &mut [[f64; 3]],
        pass: &mut Pass<'_, '_>,
    ) -> Result<()> {
        // Face points, in face-slot order (their rank order).
        let nf = mesh.face_slots();
        let mut stage = pass.stage("face points", nf)?;
        let mut ring = Vec::new();
        let mut k = 0usize;
        for fi in 0..nf {
            stage.tick(fi)?;
            if !mesh.face_live(fi) {
                continue;
            }
            let link = mesh.face_link(Fid::new(fi as u32));
            face_ring(mesh, link.halfedge(), &mut ring);
            if link.is_hole() {
                for &h in &ring {
                    valence[mesh.origin(h).index()] = ON_HOLE;
                }
                continue;
            }
            face_points[k] = scatter_face(mesh, p, &ring, sums, valence);
            k += 1;
        }
        stage.finish()
    }

    #[inline]
    fn vertex_weights(&self, n: usize) -> (f64, f64) {
        let nf = n as f64;
        ((nf - 2.0) / nf, 1.0 / (nf * nf))
    }

    #[inline(always)]
    fn edge_point(&self, mesh: &Mesh, h: Hid, points: &PointSink<'_>) -> [f64; 3] {
        let p = points.p;
        let (rh, rt) = (mesh.halfedge_record(h), mesh.halfedge_record(h.twin()));
        let (a, b) = (p[rh.origin.index()], p[rt.origin.index()]);
        let (fa, fb) = (points.face_point(rh.face), points.face_point(rt.face));
        [
            0.25 * (a[0] + b[0] + fa[0] + fb[0]),
            0.25 * (a[1] + b[1] + fa[1] + fb[1]),
            0.25 * (a[2] + b[2] + fa[2] + fb[2]),
        ]
    }
}

/// The face point of the face whose half-edges are `ring`; for each corner
/// `v`, adds the face point and the next corner (the far end of `v`'s
/// outgoing edge in this face) to `sums[v]` and counts the face in
/// `valence[v]` (saturating, so [`ON_HOLE`] stays).
///
/// Around an interior vertex every outgoing edge lies in exactly one face,
/// so after the pass `sums[v]` is `Σ uᵢ + Σ Fᵢ` and `valence[v]` is `n`:
/// the smooth vertex rule then reads its slot in order instead of turning
/// around `v` (a cache miss for nearly every spoke on a large mesh); the
/// scatter reads the half-edges in face order and writes a vertex-sized
/// array.
fn scatter_face(
    mesh: &Mesh,
    p: &[[f64; 3]],
    ring: &[Hid],
    sums: &mut [[f64; 3]],
    valence: &mut [u32],
) -> [f64; 3] {
    let mut c = [0.0f64; 3];
    for &h in ring {
        let q = p[mesh.origin(h).index()];
        c[0] += q[0];
        c[1] += q[1];
        c[2] += q[2];
    }
    let w = 1.0 / ring.len() as f64;
    let fp = [c[0] * w, c[1] * w, c[2] * w];
    for (i, &h) in ring.iter().enumerate() {
        let v = mesh.origin(h).index();
        let u = p[mesh.origin(ring[(i + 1) % ring.len()]).index()];
        let sum = &mut sums[v];
        sum[0] += fp[0] + u[0];
        sum[1] += fp[1] + u[1];
        sum[2] += fp[2] + u[2];
        valence[v] = valence[v].saturating_add(1);
    }
    fp
}
