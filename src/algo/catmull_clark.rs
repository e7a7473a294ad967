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
//! **Built wholesale**, not through the operators (`split_edge` on every
//! edge, then `poke_face` and edge removals, or `split_face` fans): one
//! pass over the faces and one over the edges write every record once into
//! arenas allocated at their final size. See
//! [`subdivision`](crate::algo::subdivision) for keys and cancellation;
//! `BENCHMARKS.md` has the figures against the peers.
//!
//! **Cost.** O(V + E + F) per level: passes over the faces (face points,
//! inside edges), the vertices and the edges, plus one per arena that has
//! attribute columns.
//!
//! ```
//! use meshloom::algo::{catmull_clark, Progress, SubdivisionOptions};
//! let mut cube = meshloom::shapes::cube();
//! catmull_clark(&mut cube, &SubdivisionOptions::levels(3), Progress::none())?;
//! assert_eq!(cube.face_count(), 6 * 4 * 4 * 4);
//! // The cube shrinks toward its limit surface, inside the unit cube.
//! for v in cube.vertices() {
//!     let p = cube.position(v)?;
//!     assert!(p.iter().all(|&c| (0.0..=1.0).contains(&c)));
//! }
//! # Ok::<(), meshloom::Error>(())
//! ```

use crate::algo::progress::Progress;
use crate::algo::subdivision::creases::{
    emit_edge, emit_vertex, Features, Mask, PointSink, RuleCounts, Sink, Spoke,
};
use crate::algo::subdivision::refine::{face_ring, refine, CutRule, Refinement};
use crate::algo::subdivision::{
    check_columns, crease_children, finish_columns, run_levels, Growth, LevelReport, Levels,
    RefinePlans, Stage, SubdivisionOptions, SubdivisionReport, ON_HOLE,
};
use crate::error::{Error, Result};
use crate::layout::{Eid, Fid, Hid, Vid};
use crate::mesh::Mesh;

const ALGORITHM: &str = "catmull_clark";

/// Apply `options.levels` levels of Catmull-Clark subdivision.
///
/// # Errors
/// [`Error::Unsuitable`] for a NaN sharpness;
/// [`Error::AttributeMissing`] / [`Error::AttributeType`] for a column
/// named in the options; [`Error::NonFinitePosition`] for a vertex at NaN
/// or infinity; [`Error::Cancelled`]. On any error the mesh is exactly as
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
/// assert_eq!(r.output().faces, 12);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn catmull_clark(
    mesh: &mut Mesh,
    options: &SubdivisionOptions,
    progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    mesh.as_one_step("Catmull-Clark", |mesh| {
        catmull_clark_run(mesh, options, progress)
    })
}

/// [`catmull_clark`] itself, outside the journal's step.
fn catmull_clark_run(
    mesh: &mut Mesh,
    options: &SubdivisionOptions,
    mut progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    check_columns(
        mesh,
        ALGORITHM,
        options.corner_column.as_deref(),
        options.crease_column.as_deref(),
        &options.vertex_data,
    )?;
    run_levels(
        mesh,
        ALGORITHM,
        Levels {
            count: options.levels,
            growth: Growth::Corners,
            max_faces: options.max_faces,
        },
        &mut progress,
        |parent, level, progress| cc_level(parent, options, level, progress),
    )
}

/// The smooth rules of Catmull-Clark subdivision.
pub(crate) struct CatmullClarkMask;

impl Mask for CatmullClarkMask {
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
        let (rh, rt) = (mesh.he[h], mesh.he[t]);
        sink.vertex(rh.origin, 0.25 * w);
        sink.vertex(rt.origin, 0.25 * w);
        sink.face(rh.face, 0.25 * w);
        sink.face(rt.face, 0.25 * w);
    }
}

fn cc_level(
    mesh: &Mesh,
    options: &SubdivisionOptions,
    level: u32,
    progress: &mut Progress<'_>,
) -> Result<(Mesh, LevelReport)> {
    let features = Features::read(
        mesh,
        ALGORITHM,
        options.boundary,
        options.corner_column.as_deref(),
        options.crease_column.as_deref(),
    )?;
    let (r, topology) = refine(mesh, CutRule::Quads, ALGORITHM, level, progress)?;
    let mut report = LevelReport {
        sharp_edges: features.sharp_edges,
        ..LevelReport::default()
    };
    let dense = mesh
        .attrs
        .positions()
        .filter(|c| c.present_bits().is_none())
        .map(|c| c.raw());
    let positions = match dense {
        Some(p) => {
            let (positions, counts) = cc_positions(mesh, &r, &features, p, level, progress)?;
            report.crease_vertices = counts.crease;
            report.corner_vertices = counts.corner;
            report.blended_vertices = counts.blended;
            Some(positions)
        }
        None => None,
    };
    let plans = RefinePlans {
        mesh,
        r: &r,
        smooth: Some((&CatmullClarkMask, &features)),
    };
    let crease = options.crease_column.as_deref().map(|name| {
        let children = crease_children(mesh, name, |e, push| {
            push(r.child(e, 0).raw());
            push(r.child(e, 1).raw());
        });
        (name, children)
    });
    let attrs = finish_columns(mesh, &plans, positions, &options.vertex_data, crease);
    Ok((topology.into_mesh(attrs), report))
}

/// The face point of the face whose half-edges are `ring`; for each corner
/// `v`, adds the face point and the next corner (the far end of `v`'s
/// outgoing edge in this face) to `sums[v]` and counts the face in
/// `valence[v]` (saturating, so [`ON_HOLE`] stays).
///
/// Around an interior vertex every outgoing edge lies in exactly one face,
/// so after the pass `sums[v]` is `Σ uᵢ + Σ Fᵢ` and `valence[v]` is `n`:
/// the smooth vertex rule then reads its slot in order instead of turning
/// around `v`. Measured on icosphere(7) (three runs each, the positions
/// stage): the turn took 48-60 ms, with a miss for nearly every spoke, where
/// the scatter reads the half-edges in face order and writes a vertex-sized
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

/// The positions of the new level: face points, then old vertices by the
/// vertex rules, then edge points.
fn cc_positions(
    mesh: &Mesh,
    r: &Refinement,
    features: &Features,
    p: &[[f64; 3]],
    level: u32,
    progress: &mut Progress<'_>,
) -> Result<(Vec<[f64; 3]>, RuleCounts)> {
    let nv = r.nv as usize;
    let mut out = crate::layout::filled_with_headroom([0.0f64; 3], r.vertex_slots());
    let (old, rest) = out.split_at_mut(nv);
    let (edge_points, face_points) = rest.split_at_mut(r.edges as usize);

    // Face points, in face-slot order (their rank order); the same pass
    // gathers the smooth vertex rule's sums (see `scatter_face`).
    let mut valence = vec![0u32; nv];
    let nf = mesh.f_slots.slot_count();
    let mut stage = Stage::new(progress, ALGORITHM, level, "face points", nf)?;
    let mut ring = Vec::new();
    let mut k = 0usize;
    for fi in 0..nf {
        stage.tick(fi)?;
        if !mesh.f_slots.is_live(fi) {
            continue;
        }
        let link = mesh.f_halfedge[Fid::new(fi as u32)];
        face_ring(mesh, link.halfedge(), &mut ring);
        if link.is_hole() {
            for &h in &ring {
                valence[mesh.origin(h).index()] = ON_HOLE;
            }
            continue;
        }
        face_points[k] = scatter_face(mesh, p, &ring, old, &mut valence);
        k += 1;
    }
    stage.finish()?;
    let face_points: &[[f64; 3]] = face_points;
    let face_rank = &r.face_rank;
    let face_point = |f: Fid| face_points[face_rank[f.index()] as usize];

    let mut counts = RuleCounts::default();
    let mut sink = PointSink {
        p,
        face_points,
        face_rank,
        acc: [0.0; 3],
    };
    let mut spokes = Vec::new();
    let mut stage = Stage::new(progress, ALGORITHM, level, "vertices", nv)?;
    for (vi, out) in old.iter_mut().enumerate() {
        stage.tick(vi)?;
        if !mesh.v_slots.is_live(vi) {
            continue;
        }
        let v = Vid::new(vi as u32);
        let pv = p[vi];
        if !pv.iter().all(|c| c.is_finite()) {
            return Err(Error::NonFinitePosition {
                key: mesh.vkey(v).into(),
                position: pv,
            });
        }
        let n = valence[vi];
        if n != ON_HOLE && n > 0 && !features.is_special(v) {
            // Interior and smooth: `out` holds the sum of the neighbours
            // and of the face points around v.
            let nf = f64::from(n);
            let (a, b) = ((nf - 2.0) / nf, 1.0 / (nf * nf));
            let sum = *out;
            *out = [
                a * pv[0] + b * sum[0],
                a * pv[1] + b * sum[1],
                a * pv[2] + b * sum[2],
            ];
        } else {
            let boundary = features.gather(mesh, v, &mut spokes);
            let rule = features.rule(v, &spokes, boundary);
            counts.count(&rule);
            emit_vertex(&CatmullClarkMask, mesh, v, &spokes, rule, &mut sink);
            *out = sink.take();
        }
    }
    stage.finish()?;

    let ne = mesh.e_slots.slot_count();
    let mut stage = Stage::new(progress, ALGORITHM, level, "edge points", ne)?;
    let mut k = 0usize;
    for ei in 0..ne {
        stage.tick(ei)?;
        if !mesh.e_slots.is_live(ei) {
            continue;
        }
        let e = Eid::new(ei as u32);
        let [h, t] = e.halfedges();
        let boundary = r.corner_of(h).is_none() || r.corner_of(t).is_none();
        let s = if boundary {
            f64::INFINITY
        } else {
            features.sharpness(e)
        };
        edge_points[k] = if s == 0.0 {
            let (rh, rt) = (mesh.he[h], mesh.he[t]);
            let (a, b) = (p[rh.origin.index()], p[rt.origin.index()]);
            let (fa, fb) = (face_point(rh.face), face_point(rt.face));
            [
                0.25 * (a[0] + b[0] + fa[0] + fb[0]),
                0.25 * (a[1] + b[1] + fa[1] + fb[1]),
                0.25 * (a[2] + b[2] + fa[2] + fb[2]),
            ]
        } else {
            emit_edge(&CatmullClarkMask, mesh, e, s, &mut sink);
            sink.take()
        };
        k += 1;
    }
    stage.finish()?;
    Ok((out, counts))
}
