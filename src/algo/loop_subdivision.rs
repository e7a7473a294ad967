//! Loop subdivision (Charles Loop, 1987): every triangle becomes four, the
//! surface converges to a C² limit (C¹ at extraordinary vertices).
//!
//! **Counts** per level: V' = V + E, E' = 2E + 3F, F' = 4F; holes keep
//! their number and double their sides. Triangles only
//! ([`Error::Unsuitable`] names the first other face; triangulate first or
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
//! **Built wholesale**, not through [`Mesh::split_edge`] and
//! [`Mesh::split_face`]: the operators would relink one element at a time,
//! with a check and the rules of every column each, where here one pass
//! over the faces and one over the edges write every record once into
//! arenas allocated at their final size. See
//! [`subdivision`](crate::algo::subdivision) for what that means for keys
//! and cancellation; `BENCHMARKS.md` has the figures against the peers.
//!
//! **Cost.** O(V + E + F) per level, three passes over the parent (faces,
//! vertices, edges) plus one per arena that has attribute columns.
//!
//! ```
//! use meshloom::algo::{loop_subdivide, Progress, SubdivisionOptions};
//! let mut mesh = meshloom::shapes::icosahedron();
//! let v = mesh.vertices().next().unwrap();
//! let report = loop_subdivide(&mut mesh, &SubdivisionOptions::levels(2), Progress::none())?;
//! assert_eq!(report.levels[0].counts.faces, 80);
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (162, 320));
//! // Vertex keys from before still name their (moved) vertex.
//! assert!(mesh.position(v)?.iter().all(|c| c.is_finite()));
//! mesh.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::f64::consts::PI;

use crate::algo::progress::Progress;
use crate::algo::subdivision::creases::{
    emit_edge, emit_vertex, Features, Mask, PointSink, RuleCounts, Sink, Spoke,
};
use crate::algo::subdivision::refine::{
    check_valence_two, refine, valence_two_error, CutRule, Refinement,
};
use crate::algo::subdivision::{
    check_columns, crease_children, finish_columns, run_levels, scatter_edge_ends, Growth,
    LevelReport, Levels, RefinePlans, Stage, SubdivisionOptions, SubdivisionReport, ON_HOLE,
};
use crate::error::{Error, Result};
use crate::layout::{with_headroom, Eid, Hid, Vid};
use crate::mesh::Mesh;

const ALGORITHM: &str = "loop_subdivide";

/// Apply `options.levels` levels of Loop subdivision to a triangle mesh.
///
/// # Errors
/// [`Error::Unsuitable`] for a face that is not a triangle or an interior
/// vertex of valence 2 (its two faces share both its edges), and for a NaN
/// sharpness; [`Error::AttributeMissing`] / [`Error::AttributeType`] for a
/// column named in the options; [`Error::NonFinitePosition`] for a vertex
/// at NaN or infinity; [`Error::Cancelled`]. On any error the mesh is
/// exactly as it was.
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
    mesh.as_one_step("Loop subdivision", |mesh| {
        loop_subdivide_run(mesh, options, progress)
    })
}

/// [`loop_subdivide`] itself, outside the journal's step.
fn loop_subdivide_run(
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
            growth: Growth::Four,
            max_faces: options.max_faces,
        },
        &mut progress,
        |parent, level, progress| loop_level(parent, options, level, progress),
    )
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

/// The smooth rules of Loop subdivision.
pub(crate) struct LoopMask;

impl Mask for LoopMask {
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
        let (rh, rt) = (mesh.he[h], mesh.he[t]);
        let c = mesh.origin(rh.next.twin());
        let d = mesh.origin(rt.next.twin());
        sink.vertex(rh.origin, 0.375 * w);
        sink.vertex(rt.origin, 0.375 * w);
        sink.vertex(c, 0.125 * w);
        sink.vertex(d, 0.125 * w);
    }
}

fn loop_level(
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
    let (r, topology) = refine(mesh, CutRule::Triangles, ALGORITHM, level, progress)?;
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
            let (positions, counts) = loop_positions(mesh, &r, &features, p, level, progress)?;
            report.crease_vertices = counts.crease;
            report.corner_vertices = counts.corner;
            report.blended_vertices = counts.blended;
            Some(positions)
        }
        None => {
            check_valence_two(mesh, CutRule::Triangles, ALGORITHM)?;
            None
        }
    };
    let plans = RefinePlans {
        mesh,
        r: &r,
        smooth: Some((&LoopMask, &features)),
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

/// The positions of the new level: old vertices by the vertex rules, then
/// edge points.
fn loop_positions(
    mesh: &Mesh,
    r: &Refinement,
    features: &Features,
    p: &[[f64; 3]],
    level: u32,
    progress: &mut Progress<'_>,
) -> Result<(Vec<[f64; 3]>, RuleCounts)> {
    let nv = r.nv as usize;
    // The old vertices' slots first hold the neighbour sums (see
    // `scatter_edges`); the edge points are pushed after them.
    let mut out: Vec<[f64; 3]> = with_headroom(r.vertex_slots());
    out.resize(nv, [0.0; 3]);
    let mut valence = vec![0u32; nv];
    scatter_edge_ends(mesh, p, &mut out, &mut valence);
    let betas: Vec<f64> = (0..64).map(loop_beta).collect();
    let mut counts = RuleCounts::default();
    let mut sink = PointSink::new(p);
    let mut ring = Vec::new();

    let mut stage = Stage::new(progress, ALGORITHM, level, "vertices", nv)?;
    for (vi, out) in out.iter_mut().enumerate() {
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
            // Interior and smooth: `out` holds the sum of the neighbours.
            if n == 2 {
                if let Some(e) = valence_two_error(mesh, v, CutRule::Triangles, ALGORITHM) {
                    return Err(e);
                }
            }
            let n = n as usize;
            let b = betas.get(n).copied().unwrap_or_else(|| loop_beta(n));
            let a = 1.0 - n as f64 * b;
            let sum = *out;
            *out = [
                a * pv[0] + b * sum[0],
                a * pv[1] + b * sum[1],
                a * pv[2] + b * sum[2],
            ];
        } else {
            let boundary = features.gather(mesh, v, &mut ring);
            if !boundary && ring.len() == 2 {
                if let Some(e) = valence_two_error(mesh, v, CutRule::Triangles, ALGORITHM) {
                    return Err(e);
                }
            }
            let rule = features.rule(v, &ring, boundary);
            counts.count(&rule);
            emit_vertex(&LoopMask, mesh, v, &ring, rule, &mut sink);
            *out = sink.take();
        }
    }
    stage.finish()?;

    let ne = mesh.e_slots.slot_count();
    let mut stage = Stage::new(progress, ALGORITHM, level, "edge points", ne)?;
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
        out.push(if s == 0.0 {
            let (rh, rt) = (mesh.he[h], mesh.he[t]);
            let (a, b) = (p[rh.origin.index()], p[rt.origin.index()]);
            let c = p[mesh.origin(rh.next.twin()).index()];
            let d = p[mesh.origin(rt.next.twin()).index()];
            [
                0.375 * (a[0] + b[0]) + 0.125 * (c[0] + d[0]),
                0.375 * (a[1] + b[1]) + 0.125 * (c[1] + d[1]),
                0.375 * (a[2] + b[2]) + 0.125 * (c[2] + d[2]),
            ]
        } else {
            emit_edge(&LoopMask, mesh, e, s, &mut sink);
            sink.take()
        });
    }
    stage.finish()?;
    debug_assert_eq!(out.len(), r.vertex_slots());
    Ok((out, counts))
}
