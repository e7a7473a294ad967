//! √3 subdivision (Kobbelt 2000): a point in the middle of every
//! triangle, joined to its corners, then every old edge flipped; the
//! triangles triple per level (a factor of 9 every two levels, where Loop
//! gives 16), and the surface converges to a C² limit (C¹ at extraordinary
//! vertices).
//!
//! **Counts** per level: V' = V + F, F' = 3F, E' = E + 3F (3E on a closed
//! mesh); holes keep their number and their sides. Triangles only:
//! [`Error::Unsuitable`] names the first face that is not a triangle, or an
//! interior vertex of valence 2.
//!
//! **Boundary.** Boundary edges (and seams, below) are not flipped: the
//! piece of the triangle beside one stays, and boundary vertices stay
//! where they are.
//! The boundary is therefore not refined: Kobbelt's rule (trisect the
//! boundary every second level, with its own curve stencils) is not
//! implemented, so after many levels long thin triangles line the
//! boundary. Closed meshes are not affected.
//!
//! **Rules.** Face point: the centroid. Old vertex
//! `(1 − αₙ) v + αₙ/n Σ uᵢ` with `αₙ = (4 − 2 cos(2π/n)) / 9`.
//! [`SubdivisionOptions::corner_column`] keeps marked vertices where they
//! are; a crease column is refused (every old edge is flipped away, so no
//! child edge runs along it).
//!
//! **Attributes.** Vertex columns as in
//! [`subdivision`](crate::algo::subdivision) (the face point is the
//! centroid for both smooth and linear data). Every new triangle covers
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
//! chart's values. Edge columns: every new edge gets `interpolate` of
//! nothing (no edge runs along a parent edge), a kept edge keeps its
//! value.
//!
//! **Built wholesale**, not by `poke_face` and `flip_edge` on every
//! element: one pass over the edges writes the six half-edges of each, in
//! slot order, into arenas allocated at their final size; see
//! [`subdivision`](crate::algo::subdivision) for keys and cancellation.
//!
//! ```
//! use meshloom::algo::{sqrt3_subdivide, Progress, SubdivisionOptions};
//! let mut mesh = meshloom::shapes::icosahedron();
//! sqrt3_subdivide(&mut mesh, &SubdivisionOptions::levels(2), Progress::none())?;
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (12 + 20 + 60, 180));
//! mesh.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::f64::consts::PI;

use crate::algo::progress::Progress;
use crate::algo::subdivision::creases::Features;
use crate::algo::subdivision::refine::{fresh_slots, valence_two_error, CutRule, Ranks, Topology};
use crate::algo::subdivision::{
    check_columns, finish_columns, run_levels, unsuitable, ColumnPlans, LevelReport, Stage,
    SubdivisionOptions, SubdivisionReport,
};
use crate::error::{Error, Result};
use crate::layout::{Eid, FaceLink, Fid, HalfedgeRecord, Hid, IdVec, Vid};
use crate::mesh::Mesh;
use crate::store::plan::ColumnPlan;

const ALGORITHM: &str = "sqrt3_subdivide";

/// Apply `options.levels` levels of √3 subdivision to a triangle mesh
/// (boundary edges and vertices are kept, see the module doc).
///
/// # Errors
/// [`Error::Unsuitable`] for a face that is not a triangle, an interior
/// vertex of valence 2, or a crease column in the options;
/// [`Error::AttributeMissing`] / [`Error::AttributeType`] for a column
/// named in the options; [`Error::NonFinitePosition`]; [`Error::Cancelled`].
/// On any error the mesh is exactly as it was.
///
/// ```
/// use meshloom::algo::{sqrt3_subdivide, Progress, SubdivisionOptions};
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let r = sqrt3_subdivide(&mut mesh, &SubdivisionOptions::default(), Progress::none())?;
/// assert_eq!(r.output().vertices, 4 + 4); // V + F
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
    mesh.as_one_step("Sqrt(3) subdivision", |mesh| {
        sqrt3_subdivide_run(mesh, options, progress)
    })
}

/// [`sqrt3_subdivide`] itself, outside the journal's step.
fn sqrt3_subdivide_run(
    mesh: &mut Mesh,
    options: &SubdivisionOptions,
    mut progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    check_columns(
        mesh,
        ALGORITHM,
        options.corner_column.as_deref(),
        None,
        &options.vertex_data,
    )?;
    if options.crease_column.is_some() {
        return Err(unsuitable(
            ALGORITHM,
            None,
            "√3 flips every old edge away, so it cannot keep creases (use Loop)",
        ));
    }
    run_levels(
        mesh,
        ALGORITHM,
        options.levels,
        &mut progress,
        |parent, level, progress| sqrt3_level(parent, options, level, progress),
    )
}

/// Kobbelt's α for valence `n`.
#[inline]
fn alpha(n: usize) -> f64 {
    (4.0 - 2.0 * (2.0 * PI / n as f64).cos()) / 9.0
}

/// The new layout, with `C` the corners (half-edges in faces, numbered in
/// slot order): vertices `[0, nv)` old, `[nv, nv + F)` face points by face
/// rank; edges `[0, C)` spokes (corner `h`'s joins `origin(h)` to the face
/// point of `face(h)`, side 0 leaving `origin(h)`), `[C, C + E)` one per
/// old edge by rank: the flipped edge of an interior edge (side `s` from
/// the face point of side `s`'s face), the boundary edge itself, kept;
/// faces `[0, C)` the triangle at each corner (at `origin(h)`, beside
/// `h`'s old edge), `[C, C + H)` the holes.
struct Layout {
    nv: u32,
    corners: u32,
    edge_rank: Ranks,
    /// Per old half-edge slot: its corner id + 1, 0 in holes.
    corner: Vec<u32>,
    /// Per old face slot: the rank among faces, or among holes.
    face_rank: Vec<u32>,
    /// Per old edge slot: whether the edge is kept instead of flipped (a
    /// boundary edge, or a seam of a corner column).
    kept: Vec<bool>,
}

impl Layout {
    /// Whether old edge `e` is kept (boundary or seam) rather than flipped.
    #[inline(always)]
    fn kept(&self, e: Eid) -> bool {
        self.kept[e.index()]
    }

    #[inline(always)]
    fn corner_of(&self, h: Hid) -> Option<u32> {
        self.corner[h.index()].checked_sub(1)
    }

    #[inline(always)]
    fn spoke(&self, h: Hid) -> Eid {
        Eid::new(self.corner[h.index()] - 1)
    }

    /// The flipped (interior) or kept (boundary) edge of old edge `e`.
    #[inline(always)]
    fn edge(&self, e: Eid) -> Eid {
        Eid::new(self.corners + self.edge_rank.get(e.index()))
    }

    #[inline(always)]
    fn triangle(&self, h: Hid) -> Fid {
        Fid::new(self.corner[h.index()] - 1)
    }

    #[inline(always)]
    fn face_point(&self, f: Fid) -> Vid {
        Vid::new(self.nv + self.face_rank[f.index()])
    }

    #[inline(always)]
    fn hole(&self, f: Fid) -> Fid {
        Fid::new(self.corners + self.face_rank[f.index()])
    }

    fn of(mesh: &Mesh) -> Layout {
        let mut corner = vec![0u32; mesh.he.len()];
        let mut next = 0u32;
        for e in mesh.eids() {
            for h in e.halfedges() {
                if !mesh.in_hole(h) {
                    next += 1;
                    corner[h.index()] = next;
                }
            }
        }
        let mut face_rank = vec![0u32; mesh.f_slots.slot_count()];
        let (mut faces, mut holes) = (0u32, 0u32);
        for f in mesh.fids() {
            let count = if mesh.is_hole(f) {
                &mut holes
            } else {
                &mut faces
            };
            face_rank[f.index()] = *count;
            *count += 1;
        }
        Layout {
            nv: mesh.v_slots.slot_count() as u32,
            corners: next,
            edge_rank: Ranks::of(&mesh.e_slots),
            corner,
            face_rank,
            kept: kept_edges(mesh),
        }
    }
}

/// Per edge slot: whether √3 keeps the edge instead of flipping it. A
/// boundary edge has no face across to flip into; a seam of any corner
/// (half-edge) column, where the corners on the two sides differ at either
/// end (by [`Attribute::same_value`](crate::attr::Attribute::same_value),
/// as [`decimate`](crate::algo::decimate) finds seams), would otherwise
/// run through the middle of the new triangles, where no corner can hold
/// both charts' values.
fn kept_edges(mesh: &Mesh) -> Vec<bool> {
    let columns = &mesh.attrs.halfedge.cols;
    let mut kept = vec![false; mesh.e_slots.slot_count()];
    for e in mesh.eids() {
        let [h, t] = e.halfedges();
        kept[e.index()] = mesh.in_hole(h)
            || mesh.in_hole(t)
            || columns.iter().any(|(_, c)| {
                !c.same(h.index(), mesh.next(t).index()) || !c.same(mesh.next(h).index(), t.index())
            });
    }
    kept
}

/// Refuse what √3 cannot take.
fn check(mesh: &Mesh) -> Result<()> {
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        let n = mesh.face_loop(f).count();
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
    let l = Layout::of(mesh);
    let topology = build(mesh, &l, level, progress)?;
    let mut report = LevelReport::default();
    let dense = mesh
        .attrs
        .positions()
        .filter(|c| c.present_bits().is_none())
        .map(|c| c.raw());
    // Boundary vertices stay where they are, as do pinned ones.
    let pinned = |v: Vid| features.is_special(v) || mesh.in_hole(mesh.v_halfedge[v]);
    let positions = match dense {
        Some(p) => {
            let (positions, corners) = positions(mesh, &l, p, &pinned, level, progress)?;
            report.corner_vertices = corners;
            Some(positions)
        }
        None => None,
    };
    let plans = Plans {
        mesh,
        l: &l,
        pinned: &pinned,
    };
    let attrs = finish_columns(mesh, &plans, positions, &options.vertex_data, None);
    Ok((topology.into_mesh(attrs), report))
}

/// The connectivity of the new level (see [`Layout`]).
fn build(mesh: &Mesh, l: &Layout, level: u32, progress: &mut Progress<'_>) -> Result<Topology> {
    let e = mesh.edge_count();
    let c = l.corners as usize;
    let faces = mesh.face_count();
    let new_edges = c + e;
    let too_big = u32::try_from(l.nv as usize + faces).is_err()
        || Eid::halfedge_slots(new_edges) >= (1usize << 31);
    if too_big {
        return Err(unsuitable(
            ALGORITHM,
            None,
            "the result would have more than 2^31 half-edges",
        ));
    }
    let mut he: IdVec<Hid, HalfedgeRecord> =
        IdVec::from_vec(Vec::with_capacity(Eid::halfedge_slots(new_edges)));
    let mut f_halfedge: IdVec<Fid, FaceLink> =
        IdVec::from_vec(Vec::with_capacity(c + mesh.hole_count()));
    let ne_slots = mesh.e_slots.slot_count();
    let mut stage = Stage::new(progress, ALGORITHM, level, "spokes", ne_slots)?;
    // Spokes, in corner order.
    for ei in 0..ne_slots {
        stage.tick(ei)?;
        if !mesh.e_slots.is_live(ei) {
            continue;
        }
        for h in Eid::new(ei as u32).halfedges() {
            if l.corner_of(h).is_none() {
                continue;
            }
            let rec = mesh.he[h];
            let cf = l.face_point(rec.face);
            let p = mesh.he[rec.next].next; // prev(h) in a triangle
                                            // Side 0: origin(h) -> c, in the triangle beside p's edge at
                                            // dest(p): across the flipped edge, or in p's own kept piece.
            he.push(if l.kept(p.edge()) {
                HalfedgeRecord {
                    origin: rec.origin,
                    next: l.spoke(p).halfedge(1),
                    face: l.triangle(p),
                }
            } else {
                HalfedgeRecord {
                    origin: rec.origin,
                    next: l.edge(p.edge()).halfedge(p.side()),
                    face: l.triangle(p.twin()),
                }
            });
            // Side 1: c -> origin(h), in the triangle at origin(h).
            let t = h.twin();
            let next = if l.kept(h.edge()) {
                l.edge(h.edge()).halfedge(h.side())
            } else {
                l.spoke(mesh.he[t].next).halfedge(0)
            };
            he.push(HalfedgeRecord {
                origin: cf,
                next,
                face: l.triangle(h),
            });
            f_halfedge.push(FaceLink::new(l.spoke(h).halfedge(1), false));
        }
    }
    stage.finish()?;
    // Per old edge: flipped (side s from the face point of side s's face
    // to the other, in the triangle at the origin of side 1 − s), or kept.
    let mut holes: Vec<FaceLink> = Vec::with_capacity(mesh.hole_count());
    for ei in 0..ne_slots {
        if !mesh.e_slots.is_live(ei) {
            continue;
        }
        let e = Eid::new(ei as u32);
        let hs = e.halfedges();
        let kept = l.kept(e);
        for s in 0..2 {
            let (own, other) = (hs[s], hs[1 - s]);
            let rec = mesh.he[own];
            he.push(if !kept {
                HalfedgeRecord {
                    origin: l.face_point(rec.face),
                    next: l.spoke(other).halfedge(1),
                    face: l.triangle(other),
                }
            } else if mesh.in_hole(own) {
                HalfedgeRecord {
                    origin: rec.origin,
                    next: l.edge(rec.next.edge()).halfedge(rec.next.side()),
                    face: l.hole(rec.face),
                }
            } else {
                HalfedgeRecord {
                    origin: rec.origin,
                    next: l.spoke(rec.next).halfedge(0),
                    face: l.triangle(own),
                }
            });
        }
    }
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            let h = mesh.face_halfedge(f);
            holes.push(FaceLink::new(l.edge(h.edge()).halfedge(h.side()), true));
        }
    }
    f_halfedge.extend_from(&holes);
    let nv = l.nv as usize;
    let mut v_halfedge: IdVec<Vid, Hid> = IdVec::from_vec(Vec::with_capacity(nv + faces));
    for vi in 0..nv {
        let v = Vid::new(vi as u32);
        v_halfedge.push(if !mesh.v_slots.is_live(vi) {
            Hid::NONE
        } else {
            let h = mesh.v_halfedge[v];
            if mesh.in_hole(h) {
                l.edge(h.edge()).halfedge(h.side())
            } else {
                l.spoke(h).halfedge(0)
            }
        });
    }
    for f in mesh.fids() {
        if !mesh.is_hole(f) {
            v_halfedge.push(l.spoke(mesh.face_halfedge(f)).halfedge(1));
        }
    }
    Ok(Topology {
        v_slots: mesh.v_slots.extended(faces),
        e_slots: fresh_slots(&mesh.e_slots, new_edges, ALGORITHM)?,
        f_slots: fresh_slots(&mesh.f_slots, f_halfedge.len(), ALGORITHM)?,
        v_halfedge,
        he,
        f_halfedge,
        holes: mesh.hole_count(),
    })
}

/// Positions: old vertices by Kobbelt's rule (pinned ones stay), then the
/// face points.
fn positions(
    mesh: &Mesh,
    l: &Layout,
    p: &[[f64; 3]],
    pinned: &dyn Fn(Vid) -> bool,
    level: u32,
    progress: &mut Progress<'_>,
) -> Result<(Vec<[f64; 3]>, usize)> {
    let nv = l.nv as usize;
    let mut out = Vec::with_capacity(nv + mesh.face_count());
    let alphas: Vec<f64> = (0..64).map(alpha).collect();
    let budget = mesh.he.len();
    let mut corners = 0;
    let mut stage = Stage::new(progress, ALGORITHM, level, "vertices", nv)?;
    for vi in 0..nv {
        stage.tick(vi)?;
        if !mesh.v_slots.is_live(vi) {
            out.push([0.0; 3]);
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
        if pinned(v) {
            corners += 1;
            out.push(pv);
            continue;
        }
        let h0 = mesh.v_halfedge[v];
        let (mut sum, mut n, mut h) = ([0.0f64; 3], 0usize, h0);
        loop {
            let twin = mesh.he[h.twin()];
            let q = p[twin.origin.index()];
            sum[0] += q[0];
            sum[1] += q[1];
            sum[2] += q[2];
            n += 1;
            h = twin.next;
            if h == h0 || n >= budget {
                break;
            }
        }
        let a = alphas.get(n).copied().unwrap_or_else(|| alpha(n));
        let (keep, share) = (1.0 - a, a / n as f64);
        out.push([
            keep * pv[0] + share * sum[0],
            keep * pv[1] + share * sum[1],
            keep * pv[2] + share * sum[2],
        ]);
    }
    stage.finish()?;
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        let h = mesh.face_halfedge(f);
        let (a, b) = (mesh.next(h), mesh.he[mesh.next(h)].next);
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
    Ok((out, corners))
}

/// The attribute plans of a √3 level.
struct Plans<'a> {
    mesh: &'a Mesh,
    l: &'a Layout,
    pinned: &'a dyn Fn(Vid) -> bool,
}

impl Plans<'_> {
    /// Face points: the mean of the corners' vertices.
    fn face_points(&self, plan: &mut ColumnPlan) {
        let m = self.mesh;
        for f in m.fids() {
            if m.is_hole(f) {
                continue;
            }
            let h = m.face_halfedge(f);
            let third = 1.0 / 3.0;
            plan.interpolate([
                (m.origin(h).raw(), third),
                (m.origin(m.next(h)).raw(), third),
                (m.origin(m.next(m.next(h))).raw(), third),
            ]);
        }
    }

    /// The mean of the three corners of `h`'s face.
    ///
    /// Always summed from the face's own half-edge, whichever corner `h`
    /// is: the corners around one face point then get bit-identical values
    /// (a sum in another order may differ in the last bit, which would
    /// count as a seam at every face point).
    fn face_corners(&self, h: Hid, plan: &mut ColumnPlan) {
        let m = self.mesh;
        let third = 1.0 / 3.0;
        let first = m.face_halfedge(m.face_of(h));
        let (a, b) = (m.next(first), m.next(m.next(first)));
        plan.interpolate([(first.raw(), third), (a.raw(), third), (b.raw(), third)]);
    }
}

impl ColumnPlans for Plans<'_> {
    fn vertex_linear(&self) -> ColumnPlan {
        let nv = self.l.nv;
        let mut plan = ColumnPlan::with_capacity(nv as usize + self.mesh.face_count(), 0);
        for v in 0..nv {
            plan.copy(v);
        }
        self.face_points(&mut plan);
        plan
    }

    fn vertex_smooth(&self) -> ColumnPlan {
        let m = self.mesh;
        let nv = self.l.nv;
        let mut plan = ColumnPlan::with_capacity(nv as usize + m.face_count(), 8 * nv as usize);
        for vi in 0..nv {
            let v = Vid::new(vi);
            if !m.v_slots.is_live(vi as usize) || (self.pinned)(v) {
                plan.copy(vi);
                continue;
            }
            let n = m.outgoing(v).count();
            let a = alpha(n);
            let start = plan.begin_interpolate();
            plan.push_input(vi, 1.0 - a);
            for h in m.outgoing(v) {
                plan.push_input(m.origin(h.twin()).raw(), a / n as f64);
            }
            plan.end_interpolate(start);
        }
        self.face_points(&mut plan);
        plan
    }

    fn halfedge(&self) -> ColumnPlan {
        let m = self.mesh;
        let (c, e) = (self.l.corners as usize, m.edge_count());
        let mut plan = ColumnPlan::with_capacity(Eid::halfedge_slots(c + e), 8 * c);
        for edge in m.eids() {
            for h in edge.halfedges() {
                if m.in_hole(h) {
                    continue;
                }
                // Side 0 leaves origin(h), in a triangle over face(h) and
                // the face across prev(h): the mean of the two corners
                // (only h's own where prev(h) is on the boundary).
                let p = m.next(m.next(h));
                if self.l.kept(p.edge()) {
                    plan.copy(h.raw());
                } else {
                    plan.interpolate([(h.raw(), 0.5), (p.twin().raw(), 0.5)]);
                }
                // Side 1 leaves the face point of face(h).
                self.face_corners(h, &mut plan);
            }
        }
        for edge in m.eids() {
            let kept = self.l.kept(edge);
            for h in edge.halfedges() {
                if kept {
                    plan.copy(h.raw());
                } else {
                    self.face_corners(h, &mut plan);
                }
            }
        }
        plan
    }

    fn edge(&self) -> ColumnPlan {
        let m = self.mesh;
        let c = self.l.corners as usize;
        let mut plan = ColumnPlan::with_capacity(c + m.edge_count(), 0);
        for _ in 0..c {
            plan.interpolate([]);
        }
        for edge in m.eids() {
            if self.l.kept(edge) {
                plan.copy(edge.raw());
            } else {
                plan.interpolate([]);
            }
        }
        plan
    }

    fn face(&self) -> ColumnPlan {
        let m = self.mesh;
        let c = self.l.corners as usize;
        let mut plan = ColumnPlan::with_capacity(c + m.hole_count(), 2 * c);
        let third = 1.0 / 3.0;
        for edge in m.eids() {
            for h in edge.halfedges() {
                if m.in_hole(h) {
                    continue;
                }
                let (own, other) = (m.face_of(h).raw(), m.face_of(h.twin()));
                if self.l.kept(edge) {
                    // The kept piece beside a boundary or seam edge.
                    plan.split(own, third);
                } else {
                    // Half of each piece beside the flipped edge, this
                    // side's first.
                    plan.flip_piece(own, third, other.raw(), third);
                }
            }
        }
        for f in m.fids() {
            if m.is_hole(f) {
                plan.copy(f.raw());
            }
        }
        plan
    }
}
