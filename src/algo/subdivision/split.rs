//! The level of the face-splitting schemes (Loop, Catmull-Clark, midpoint):
//! one generic level and one generic positions function over the scheme's
//! cut rule and stencils.
//!
//! A scheme says how faces are cut ([`FaceSplit::cut`]) and, if it moves
//! vertices, gives its [`SmoothRules`]: the smooth masks (the general path
//! every crease, corner and boundary rule goes through, and the smooth
//! column plans) and the fast stencils for the common case, a smooth
//! interior vertex or edge:
//!
//! - a scatter pass that gathers, in element order, the sum a smooth
//!   vertex rule reads and the vertex's valence (and the face points, for a
//!   scheme that has them);
//! - the vertex weights `(a, b)`: a smooth interior vertex of valence `n`
//!   goes to `a v + b s`, `s` its scatter sum;
//! - the smooth edge point of an interior edge.
//!
//! Everything is generic, not `dyn`: each scheme gets its own copy of the
//! passes with its stencils inlined.

use crate::algo::progress::Progress;
use crate::error::Result;
use crate::layout::{with_headroom, Eid, Hid, Vid};
use crate::mesh::Mesh;

use super::columns::{crease_children, RefinePlans};
use super::creases::{emit_edge, emit_vertex, Features, Mask, PointSink, RuleCounts, Sink, Spoke};
use super::refine::{check_valence_two, refine, valence_two_error, CutRule, Refinement};
use super::{
    check_finite_position, finish_columns, Growth, LevelReport, Pass, Scheme, Subdivider,
    SubdivisionOptions, ON_HOLE,
};

/// A scheme whose levels split every edge at an edge point and cut every
/// face by a [`CutRule`] (the topology of [`refine`]).
pub(crate) trait FaceSplit {
    /// The scheme.
    const SCHEME: Scheme;
    /// Its smooth rules ([`Linear`] for a scheme that moves nothing).
    type Rules: SmoothRules;

    /// How faces are cut.
    fn cut(&self) -> CutRule;

    /// The smooth rules, `None` when no vertex moves: positions and every
    /// vertex column then follow the linear plan.
    fn rules(&self) -> Option<&Self::Rules>;
}

/// The smooth rules of a face-splitting scheme: the masks, and the fast
/// stencils of smooth interior vertices and edges.
pub(crate) trait SmoothRules: Mask {
    /// Whether the scheme has face points (a point per face cut into
    /// quads, which the vertex rules read).
    const FACE_POINTS: bool;

    /// Before the vertex rules: for each parent vertex slot, the sum its
    /// smooth rule reads into `sums` and its valence into `valence`
    /// ([`ON_HOLE`] on a hole), and the face points into `face_points`, by
    /// face rank (empty without [`FACE_POINTS`](Self::FACE_POINTS)).
    fn scatter(
        &self,
        mesh: &Mesh,
        p: &[[f64; 3]],
        sums: &mut [[f64; 3]],
        valence: &mut [u32],
        face_points: &mut [[f64; 3]],
        pass: &mut Pass<'_, '_>,
    ) -> Result<()>;

    /// `(a, b)`: a smooth interior vertex `v` of valence `n` goes to
    /// `a v + b s`, with `s` its sum from [`scatter`](Self::scatter).
    fn vertex_weights(&self, n: usize) -> (f64, f64);

    /// The smooth edge point of the interior edge of half-edge `h`.
    fn edge_point(&self, mesh: &Mesh, h: Hid, points: &PointSink<'_>) -> [f64; 3];
}

/// No smooth rules: the rules of a scheme that moves nothing (midpoint).
/// It has no value, so none of its rules can run.
pub(crate) enum Linear {}

impl Mask for Linear {
    fn smooth_vertex<S: Sink>(&self, _: &Mesh, _: Vid, _: &[Spoke], _: f64, _: &mut S) {
        match *self {}
    }

    fn smooth_edge<S: Sink>(&self, _: &Mesh, _: Hid, _: f64, _: &mut S) {
        match *self {}
    }
}

impl SmoothRules for Linear {
    const FACE_POINTS: bool = false;

    fn scatter(
        &self,
        _: &Mesh,
        _: &[[f64; 3]],
        _: &mut [[f64; 3]],
        _: &mut [u32],
        _: &mut [[f64; 3]],
        _: &mut Pass<'_, '_>,
    ) -> Result<()> {
        match *self {}
    }

    fn vertex_weights(&self, _: usize) -> (f64, f64) {
        match *self {}
    }

    fn edge_point(&self, _: &Mesh, _: Hid, _: &PointSink<'_>) -> [f64; 3] {
        match *self {}
    }
}

impl<S: FaceSplit> Subdivider for S {
    const SCHEME: Scheme = S::SCHEME;

    fn growth(&self) -> Growth {
        match self.cut() {
            CutRule::Triangles => Growth::Four,
            CutRule::Quads => Growth::Corners,
        }
    }

    fn level(
        &self,
        mesh: &Mesh,
        options: &SubdivisionOptions,
        level: u32,
        progress: &mut Progress<'_>,
    ) -> Result<(Mesh, LevelReport)> {
        split_level(self, mesh, options, level, progress)
    }
}

/// One level of a face-splitting scheme: the topology of [`refine`], the
/// positions by the scheme's rules (when it has any and the positions are
/// dense), every other column by its plan.
fn split_level<S: FaceSplit>(
    scheme: &S,
    mesh: &Mesh,
    options: &SubdivisionOptions,
    level: u32,
    progress: &mut Progress<'_>,
) -> Result<(Mesh, LevelReport)> {
    let algorithm = S::SCHEME.algorithm();
    let rule = scheme.cut();
    let rules = scheme.rules();
    let features = match rules {
        Some(_) => Features::read(
            mesh,
            algorithm,
            options.boundary,
            options.corner_column.as_deref(),
            options.crease_column.as_deref(),
        )?,
        None => Features::read(mesh, algorithm, options.boundary, None, None)?,
    };
    let dense = mesh
        .attrs()
        .positions()
        .filter(|c| rules.is_some() && c.present_bits().is_none())
        .map(|c| c.raw());
    if dense.is_none() {
        // The position pass checks as it goes; without it, check first.
        check_valence_two(mesh, rule, algorithm)?;
    }
    let mut pass = Pass {
        progress,
        algorithm,
        level,
    };
    let (r, topology) = refine(mesh, rule, &mut pass)?;
    let mut report = LevelReport {
        sharp_edges: features.sharp_edges,
        ..LevelReport::default()
    };
    let positions = match (rules, dense) {
        (Some(rules), Some(p)) => {
            let positions = Positions {
                rules,
                cut: rule,
                mesh,
                r: &r,
                features: &features,
                p,
            };
            let (points, counts) = positions.run(&mut pass)?;
            report.crease_vertices = counts.crease;
            report.corner_vertices = counts.corner;
            report.blended_vertices = counts.blended;
            Some(points)
        }
        _ => None,
    };
    let plans = RefinePlans {
        mesh,
        r: &r,
        smooth: rules.map(|rules| (rules, &features)),
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

/// The positions of a new level from the parent's dense positions `p`.
struct Positions<'a, R> {
    rules: &'a R,
    cut: CutRule,
    mesh: &'a Mesh,
    r: &'a Refinement,
    features: &'a Features,
    p: &'a [[f64; 3]],
}

impl<R: SmoothRules> Positions<'_, R> {
    /// Every new position, in the new vertex slots' order: old vertices by
    /// the vertex rules, then edge points, then face points.
    fn run(&self, pass: &mut Pass<'_, '_>) -> Result<(Vec<[f64; 3]>, RuleCounts)> {
        let (nv, ne) = (self.r.nv as usize, self.r.edges as usize);
        let slots = self.r.vertex_slots();
        // The old vertices' slots first hold the scatter sums.
        let mut out: Vec<[f64; 3]> = with_headroom(slots);
        let mut valence = vec![0u32; nv];
        let counts = if R::FACE_POINTS {
            // The vertex rules read the face points, which go last: every
            // slot now, the edge points written in place.
            out.resize(slots, [0.0; 3]);
            let (old, rest) = out.split_at_mut(nv);
            let (edge_points, face_points) = rest.split_at_mut(ne);
            self.rules
                .scatter(self.mesh, self.p, old, &mut valence, face_points, pass)?;
            let mut sink = PointSink {
                p: self.p,
                face_points,
                face_rank: &self.r.face_rank,
                acc: [0.0; 3],
            };
            let counts = self.old_vertices(old, &valence, &mut sink, pass)?;
            let mut k = 0;
            self.edge_points(&mut sink, pass, |x| {
                edge_points[k] = x;
                k += 1;
            })?;
            counts
        } else {
            // No face points: the edge points are pushed after the old
            // vertices.
            out.resize(nv, [0.0; 3]);
            self.rules
                .scatter(self.mesh, self.p, &mut out, &mut valence, &mut [], pass)?;
            let mut sink = PointSink::new(self.p);
            let counts = self.old_vertices(&mut out, &valence, &mut sink, pass)?;
            self.edge_points(&mut sink, pass, |x| out.push(x))?;
            counts
        };
        debug_assert_eq!(out.len(), slots);
        Ok((out, counts))
    }

    /// The old vertices, in place over their sums: smooth interior ones by
    /// the fast stencil, the others (boundary, crease, corner) by the
    /// general rules.
    fn old_vertices(
        &self,
        out: &mut [[f64; 3]],
        valence: &[u32],
        sink: &mut PointSink<'_>,
        pass: &mut Pass<'_, '_>,
    ) -> Result<RuleCounts> {
        let (mesh, p, features) = (self.mesh, self.p, self.features);
        let algorithm = pass.algorithm;
        let weights: Vec<(f64, f64)> = (0..64).map(|n| self.rules.vertex_weights(n)).collect();
        // Two faces cut 1-to-4 around a vertex of valence 2 would join the
        // same two edge points twice.
        let triangles = self.cut == CutRule::Triangles;
        let mut counts = RuleCounts::default();
        let mut ring = Vec::new();
        let mut stage = pass.stage("vertices", out.len())?;
        for (vi, out) in out.iter_mut().enumerate() {
            stage.tick(vi)?;
            if !mesh.vertex_live(vi) {
                continue;
            }
            let v = Vid::new(vi as u32);
            let pv = p[vi];
            check_finite_position(mesh, v, pv)?;
            let n = valence[vi];
            if n != ON_HOLE && n > 0 && !features.is_special(v) {
                // Interior and smooth: `out` holds the scatter sum.
                if n == 2 && triangles {
                    if let Some(e) = valence_two_error(mesh, v, self.cut, algorithm) {
                        return Err(e);
                    }
                }
                let n = n as usize;
                let (a, b) = weights
                    .get(n)
                    .copied()
                    .unwrap_or_else(|| self.rules.vertex_weights(n));
                let sum = *out;
                *out = [
                    a * pv[0] + b * sum[0],
                    a * pv[1] + b * sum[1],
                    a * pv[2] + b * sum[2],
                ];
            } else {
                let boundary = features.gather(mesh, v, &mut ring);
                if triangles && !boundary && ring.len() == 2 {
                    if let Some(e) = valence_two_error(mesh, v, self.cut, algorithm) {
                        return Err(e);
                    }
                }
                let rule = features.rule(v, &ring, boundary);
                counts.count(&rule);
                emit_vertex(self.rules, mesh, v, &ring, rule, sink);
                *out = sink.take();
            }
        }
        stage.finish()?;
        Ok(counts)
    }

    /// The edge points, to `put` in edge order: smooth interior edges by the
    /// fast stencil, boundary and sharp ones by the crease rules.
    fn edge_points(
        &self,
        sink: &mut PointSink<'_>,
        pass: &mut Pass<'_, '_>,
        mut put: impl FnMut([f64; 3]),
    ) -> Result<()> {
        let (mesh, r) = (self.mesh, self.r);
        let ne = mesh.edge_slots();
        let mut stage = pass.stage("edge points", ne)?;
        for ei in 0..ne {
            stage.tick(ei)?;
            if !mesh.edge_live(ei) {
                continue;
            }
            let e = Eid::new(ei as u32);
            let [h, t] = e.halfedges();
            let boundary = r.corner_of(h).is_none() || r.corner_of(t).is_none();
            let s = if boundary {
                f64::INFINITY
            } else {
                self.features.sharpness(e)
            };
            put(if s == 0.0 {
                self.rules.edge_point(mesh, h, sink)
            } else {
                emit_edge(self.rules, mesh, e, s, sink);
                sink.take()
            });
        }
        stage.finish()
    }
}
