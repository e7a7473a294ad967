//! √3 subdivision (Kobbelt 2000): a point in the middle of every
//! triangle, joined to its corners, then every old edge flipped; the
//! triangles triple per level (a factor of 9 every two levels, where Loop
//! gives 16), and the surface converges to a C² limit (C¹ at extraordinary
//! vertices).
//!
//! **Counts** per level: V' = V + F, F' = 3F, E' = E + 3F (3E on a closed
//! mesh); at a level that trisects the boundary (below) add 2B vertices,
//! 2B faces and 4B edges for the B boundary edges. Holes keep their
//! number. Triangles only: [`Error::Unsuitable`] names the first face that
//! is not a triangle, or an interior vertex of valence 2.
//!
//! **Boundary** (Kobbelt's rule). Boundary edges are never flipped. The
//! first level of a call (and every odd one: 1, 3, 5, ...) keeps them as
//! they are: the triangle beside one is the piece of its parent between
//! the edge and the face point, and boundary vertices stay where they are.
//! The second level (and every even one) trisects every boundary edge:
//! two boundary points on it, joined to the face point, so the piece
//! becomes three triangles, and the boundary moves by the ternary cubic
//! B-spline rules (mask `(1, 4, 10, 16, 19, 16, 10, 4, 1) / 27`): an old
//! boundary vertex `v` between boundary neighbours `a` and `b` goes to
//! `(4a + 19v + 4b) / 27`, the point a third of the way from `a` to `b`
//! to `(p + 16a + 10b) / 27` (`p` the boundary vertex before `a`), the
//! point two thirds of the way symmetrically. Two levels thus refine the
//! boundary by 3 where the inside is refined by √3² = 3, and the boundary
//! converges to a cubic B-spline curve. A boundary vertex that stays (a
//! corner: [`Boundary::CreaseAndCorners`](crate::algo::Boundary) at
//! valence 2, the corner column, a vertex on more than two boundary
//! edges) ends the curve: the new points beside it lie at the thirds of
//! the straight edge. Levels are counted within one call: two calls of
//! one level each never trisect; ask for `levels: 2`. Seams (below) are
//! kept but not trisected.
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
//! sqrt3_subdivide(&mut mesh, &SubdivisionOptions::levels(2), Progress::none())?;
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (12 + 20 + 60, 180));
//! mesh.validate()?;
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::f64::consts::PI;

use crate::algo::progress::Progress;
use crate::algo::subdivision::creases::{Features, PlanSink, PointSink, Rule, Sink};
use crate::algo::subdivision::refine::{fresh_slots, valence_two_error, CutRule, Ranks, Topology};
use crate::algo::subdivision::{
    finish_columns, scatter_edge_ends, subdivide, unsuitable, ColumnPlans, Growth, LevelReport,
    Scheme, Stage, Subdivider, SubdivisionOptions, SubdivisionReport,
};
use crate::error::{Error, Result};
use crate::layout::{with_headroom, Eid, FaceLink, Fid, HalfedgeRecord, Hid, IdVec, Vid};
use crate::mesh::Mesh;
use crate::store::plan::ColumnPlan;

const ALGORITHM: &str = "sqrt3_subdivide";

/// Apply `options.levels` levels of √3 subdivision to a triangle mesh
/// (the boundary is kept at odd levels and trisected at even ones, see the
/// module doc): [`subdivide`] with [`Scheme::Sqrt3`].
///
/// # Errors
/// [`Error::Unsuitable`] for a face that is not a triangle, an interior
/// vertex of valence 2, or a crease column in the options; the other
/// errors of [`subdivide`]. On any error the mesh is exactly as it was.
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

/// The new layout, with `C` the corners (half-edges in faces, numbered in
/// slot order), `B` the boundary edges trisected at this level (none at an
/// odd level) and `r(e)` a trisected edge's rank among them: vertices
/// `[0, nv)` old, `[nv, nv + F)` face points by face rank, then two
/// boundary points per trisected edge (`nv + F + 2r(e)` a third along its
/// inner half-edge, `+ 1` two thirds along); edges `[0, C)` spokes
/// (corner `h`'s joins `origin(h)` to the face point of `face(h)`, side 0
/// leaving `origin(h)`), `[C, C + E)` one per old edge by rank: the
/// flipped edge of an interior edge (side `s` from the face point of side
/// `s`'s face), the boundary edge itself, kept (trisected: its first third,
/// from the inner half-edge's origin), then four per trisected edge at
/// `C + E + 4r(e)`: the middle third, the last third (side 0 along the
/// inner half-edge) and the spokes from the two boundary points to the
/// face point (side 0 leaving the boundary point); faces `[0, C)` the
/// triangle at each corner (at `origin(h)`, beside `h`'s old edge), then
/// two per trisected edge at `C + 2r(e)` (the middle third's triangle,
/// the last third's), then the holes.
struct Layout {
    nv: u32,
    corners: u32,
    /// Live faces (not holes) of the parent.
    faces: u32,
    /// Live edges of the parent.
    edges: u32,
    edge_rank: Ranks,
    /// Per old half-edge slot: its corner id + 1, 0 in holes.
    corner: Vec<u32>,
    /// Per old face slot: the rank among faces, or among holes.
    face_rank: Vec<u32>,
    /// Per old edge slot: whether the edge is kept instead of flipped (a
    /// boundary edge, or a seam of a corner column).
    kept: Vec<bool>,
    /// Per old edge slot: its rank among the trisected boundary edges + 1,
    /// 0 when not trisected (every slot at an odd level).
    trisected: Vec<u32>,
    /// Boundary edges trisected at this level.
    boundary: u32,
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
        Fid::new(self.corners + 2 * self.boundary + self.face_rank[f.index()])
    }

    /// The rank of `e` among the trisected edges, if it is one.
    #[inline(always)]
    fn trisected(&self, e: Eid) -> Option<u32> {
        self.trisected.get(e.index()).and_then(|r| r.checked_sub(1))
    }

    /// Extra edge `k` of trisected edge rank `r`: 0 the middle third, 1
    /// the last third, 2 and 3 the spokes from the first and the second
    /// boundary point.
    #[inline(always)]
    fn extra_edge(&self, r: u32, k: u32) -> Eid {
        Eid::new(self.corners + self.edges + 4 * r + k)
    }

    /// Extra triangle `k` of trisected edge rank `r`: 0 on the middle
    /// third, 1 on the last third.
    #[inline(always)]
    fn extra_face(&self, r: u32, k: u32) -> Fid {
        Fid::new(self.corners + 2 * r + k)
    }

    /// Boundary point `k` (0 a third along the inner half-edge, 1 two
    /// thirds) of trisected edge rank `r`.
    #[inline(always)]
    fn boundary_point(&self, r: u32, k: u32) -> Vid {
        Vid::new(self.nv + self.faces + 2 * r + k)
    }

    /// The new hole half-edge leaving `origin(t)` along old hole half-edge
    /// `t`: the last third's hole side if `t`'s edge is trisected.
    #[inline(always)]
    fn hole_start(&self, t: Hid) -> Hid {
        match self.trisected(t.edge()) {
            Some(r) => self.extra_edge(r, 1).halfedge(1),
            None => self.edge(t.edge()).halfedge(t.side()),
        }
    }

    fn of(mesh: &Mesh, trisect: bool) -> Layout {
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
        let mut trisected = Vec::new();
        let mut boundary = 0u32;
        if trisect {
            trisected = vec![0u32; mesh.e_slots.slot_count()];
            for e in mesh.eids() {
                if boundary_inner(mesh, e).is_some() {
                    boundary += 1;
                    trisected[e.index()] = boundary;
                }
            }
        }
        Layout {
            nv: mesh.v_slots.slot_count() as u32,
            corners: next,
            faces,
            edges: mesh.edge_count() as u32,
            edge_rank: Ranks::of(&mesh.e_slots),
            corner,
            face_rank,
            kept: kept_edges(mesh),
            trisected,
            boundary,
        }
    }
}

/// The inner half-edge of boundary edge `e` (the one in a face; its twin
/// is in a hole), `None` for an interior edge.
#[inline]
fn boundary_inner(mesh: &Mesh, e: Eid) -> Option<Hid> {
    let [h, t] = e.halfedges();
    match (mesh.in_hole(h), mesh.in_hole(t)) {
        (false, true) => Some(h),
        (true, false) => Some(t),
        _ => None,
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
    // Levels 2, 4, ... (index 1, 3, ...) trisect the boundary.
    let trisect = level % 2 == 1;
    let l = Layout::of(mesh, trisect);
    let topology = build(mesh, &l, level, progress)?;
    let mut report = LevelReport {
        boundary_trisected: trisect,
        ..LevelReport::default()
    };
    let dense = mesh
        .attrs
        .positions()
        .filter(|c| c.present_bits().is_none())
        .map(|c| c.raw());
    let rules = VertexRules::of(mesh, &features, trisect);
    let positions = match dense {
        Some(p) => {
            let (positions, counts) = positions(mesh, &l, &rules, p, level, progress)?;
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
        if !m.in_hole(m.v_halfedge[v]) {
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

/// The connectivity of the new level (see [`Layout`]).
fn build(mesh: &Mesh, l: &Layout, level: u32, progress: &mut Progress<'_>) -> Result<Topology> {
    let e = mesh.edge_count();
    let c = l.corners as usize;
    let faces = mesh.face_count();
    let b = l.boundary as usize;
    let new_edges = c + e + 4 * b;
    let too_big = u32::try_from(l.nv as usize + faces + 2 * b).is_err()
        || Eid::halfedge_slots(new_edges) >= (1usize << 31);
    if too_big {
        return Err(unsuitable(
            ALGORITHM,
            None,
            "the result would have more than 2^31 half-edges",
        ));
    }
    let mut he: IdVec<Hid, HalfedgeRecord> =
        IdVec::from_vec(with_headroom(Eid::halfedge_slots(new_edges)));
    let mut f_halfedge: IdVec<Fid, FaceLink> =
        IdVec::from_vec(with_headroom(c + 2 * b + mesh.hole_count()));
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
                                            // dest(p): across the flipped edge, in p's own kept piece,
                                            // or on the last third of p's trisected edge.
            he.push(if l.kept(p.edge()) {
                match l.trisected(p.edge()) {
                    Some(r) => HalfedgeRecord {
                        origin: rec.origin,
                        next: l.extra_edge(r, 3).halfedge(1),
                        face: l.extra_face(r, 1),
                    },
                    None => HalfedgeRecord {
                        origin: rec.origin,
                        next: l.spoke(p).halfedge(1),
                        face: l.triangle(p),
                    },
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
    // to the other, in the triangle at the origin of side 1 − s), or kept
    // (trisected: its first third).
    let mut holes: Vec<FaceLink> = Vec::with_capacity(mesh.hole_count());
    for ei in 0..ne_slots {
        if !mesh.e_slots.is_live(ei) {
            continue;
        }
        let e = Eid::new(ei as u32);
        let hs = e.halfedges();
        let kept = l.kept(e);
        let third = if kept { l.trisected(e) } else { None };
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
                    // Trisected: from the first boundary point to the
                    // inner half-edge's origin.
                    origin: third.map_or(rec.origin, |r| l.boundary_point(r, 0)),
                    next: l.hole_start(rec.next),
                    face: l.hole(rec.face),
                }
            } else {
                HalfedgeRecord {
                    origin: rec.origin,
                    next: match third {
                        Some(r) => l.extra_edge(r, 2).halfedge(0),
                        None => l.spoke(rec.next).halfedge(0),
                    },
                    face: l.triangle(own),
                }
            });
        }
    }
    // Per trisected edge (inner half-edge h from a to b, face point m,
    // boundary points a' and b'): the middle third a'b', the last third
    // b'b, the spokes a'm and b'm.
    let trisected_slots = if l.boundary > 0 { ne_slots } else { 0 };
    for ei in 0..trisected_slots {
        let e = Eid::new(ei as u32);
        let Some(r) = l.trisected(e) else { continue };
        let Some(h) = boundary_inner(mesh, e) else {
            continue;
        };
        let t = h.twin();
        let rec = mesh.he[h];
        let m = l.face_point(rec.face);
        let hole = l.hole(mesh.he[t].face);
        let (a1, b1) = (l.boundary_point(r, 0), l.boundary_point(r, 1));
        let [mid, last, spoke_a, spoke_b] = [0, 1, 2, 3].map(|k| l.extra_edge(r, k));
        let (tri_mid, tri_last) = (l.extra_face(r, 0), l.extra_face(r, 1));
        he.push(HalfedgeRecord {
            origin: a1,
            next: spoke_b.halfedge(0),
            face: tri_mid,
        });
        he.push(HalfedgeRecord {
            origin: b1,
            next: l.edge(e).halfedge(t.side()),
            face: hole,
        });
        he.push(HalfedgeRecord {
            origin: b1,
            next: l.spoke(rec.next).halfedge(0),
            face: tri_last,
        });
        he.push(HalfedgeRecord {
            origin: mesh.he[t].origin,
            next: mid.halfedge(1),
            face: hole,
        });
        he.push(HalfedgeRecord {
            origin: a1,
            next: l.spoke(h).halfedge(1),
            face: l.triangle(h),
        });
        he.push(HalfedgeRecord {
            origin: m,
            next: mid.halfedge(0),
            face: tri_mid,
        });
        he.push(HalfedgeRecord {
            origin: b1,
            next: spoke_a.halfedge(1),
            face: tri_mid,
        });
        he.push(HalfedgeRecord {
            origin: m,
            next: last.halfedge(0),
            face: tri_last,
        });
        f_halfedge.push(FaceLink::new(mid.halfedge(0), false));
        f_halfedge.push(FaceLink::new(last.halfedge(0), false));
    }
    debug_assert_eq!(he.len(), Eid::halfedge_slots(new_edges));
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            let h = mesh.face_halfedge(f);
            holes.push(FaceLink::new(l.hole_start(h), true));
        }
    }
    f_halfedge.extend_from(&holes);
    let nv = l.nv as usize;
    let mut v_halfedge: IdVec<Vid, Hid> = IdVec::from_vec(with_headroom(nv + faces + 2 * b));
    for vi in 0..nv {
        let v = Vid::new(vi as u32);
        v_halfedge.push(if !mesh.v_slots.is_live(vi) {
            Hid::NONE
        } else {
            let h = mesh.v_halfedge[v];
            if mesh.in_hole(h) {
                l.hole_start(h)
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
    // Boundary points leave along the hole: a' -> a, b' -> a'.
    for ei in 0..trisected_slots {
        let e = Eid::new(ei as u32);
        let Some(r) = l.trisected(e) else { continue };
        let Some(h) = boundary_inner(mesh, e) else {
            continue;
        };
        v_halfedge.push(l.edge(e).halfedge(h.twin().side()));
        v_halfedge.push(l.extra_edge(r, 0).halfedge(1));
    }
    Ok(Topology {
        v_slots: mesh.v_slots.extended(faces + 2 * b),
        e_slots: fresh_slots(&mesh.e_slots, new_edges, ALGORITHM)?,
        f_slots: fresh_slots(&mesh.f_slots, f_halfedge.len(), ALGORITHM)?,
        v_halfedge,
        he,
        f_halfedge,
        holes: mesh.hole_count(),
    })
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
    level: u32,
    progress: &mut Progress<'_>,
) -> Result<(Vec<[f64; 3]>, MoveCounts)> {
    let nv = l.nv as usize;
    let mut out = with_headroom(nv + mesh.face_count() + 2 * l.boundary as usize);
    // The old vertices' slots first hold the neighbour sums.
    out.resize(nv, [0.0; 3]);
    let mut valence = vec![0u32; nv];
    scatter_edge_ends(mesh, p, &mut out, &mut valence);
    let alphas: Vec<f64> = (0..64).map(alpha).collect();
    let mut counts = MoveCounts::default();
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
        debug_assert!(valence[vi] != super::subdivision::ON_HOLE);
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
    if l.boundary > 0 {
        let mut sink = PointSink::new(p);
        for e in mesh.eids() {
            if l.trisected(e).is_none() {
                continue;
            }
            let Some(h) = boundary_inner(mesh, e) else {
                continue;
            };
            for k in 0..2 {
                rules.boundary_point(h, k, &mut sink);
                out.push(sink.take());
            }
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

/// The attribute plans of a √3 level.
struct Plans<'a> {
    mesh: &'a Mesh,
    l: &'a Layout,
    rules: &'a VertexRules<'a>,
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

    /// The inner half-edges of the trisected edges, in rank order.
    fn trisected(&self) -> impl Iterator<Item = Hid> + '_ {
        let m = self.mesh;
        m.eids()
            .filter(|&e| self.l.trisected(e).is_some())
            .filter_map(move |e| boundary_inner(m, e))
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

/// The corner value `k` thirds along `from` towards `to` (`k` 1 or 2).
fn thirds(from: Hid, to: Hid, k: u32) -> [(u32, f64); 2] {
    let t = f64::from(k) / 3.0;
    [(from.raw(), 1.0 - t), (to.raw(), t)]
}

impl ColumnPlans for Plans<'_> {
    fn vertex_linear(&self) -> ColumnPlan {
        let m = self.mesh;
        let nv = self.l.nv;
        let b = 2 * self.l.boundary as usize;
        let mut plan = ColumnPlan::with_capacity(nv as usize + m.face_count() + b, 2 * b);
        for v in 0..nv {
            plan.copy(v);
        }
        self.face_points(&mut plan);
        for h in self.trisected() {
            let (a, b) = (m.origin(h).raw(), m.origin(h.twin()).raw());
            plan.interpolate([(a, 2.0 / 3.0), (b, 1.0 / 3.0)]);
            plan.interpolate([(a, 1.0 / 3.0), (b, 2.0 / 3.0)]);
        }
        plan
    }

    fn vertex_smooth(&self) -> ColumnPlan {
        let m = self.mesh;
        let nv = self.l.nv;
        let b = 2 * self.l.boundary as usize;
        let mut plan =
            ColumnPlan::with_capacity(nv as usize + m.face_count() + b, 8 * nv as usize + 3 * b);
        for vi in 0..nv {
            let v = Vid::new(vi);
            if !m.v_slots.is_live(vi as usize) {
                plan.copy(vi);
                continue;
            }
            match self.rules.of_vertex(v) {
                VertexMove::Stay => plan.copy(vi),
                VertexMove::Curve(a, b) => {
                    let start = plan.begin_interpolate();
                    curve_vertex(
                        v,
                        a,
                        b,
                        &mut PlanSink {
                            mesh: m,
                            plan: &mut plan,
                        },
                    );
                    plan.end_interpolate(start);
                }
                VertexMove::Smooth => {
                    let n = m.outgoing(v).count();
                    let a = alpha(n);
                    let start = plan.begin_interpolate();
                    plan.push_input(vi, 1.0 - a);
                    for h in m.outgoing(v) {
                        plan.push_input(m.origin(h.twin()).raw(), a / n as f64);
                    }
                    plan.end_interpolate(start);
                }
            }
        }
        self.face_points(&mut plan);
        for h in self.trisected() {
            for k in 0..2 {
                let start = plan.begin_interpolate();
                self.rules.boundary_point(
                    h,
                    k,
                    &mut PlanSink {
                        mesh: m,
                        plan: &mut plan,
                    },
                );
                plan.end_interpolate(start);
            }
        }
        plan
    }

    fn halfedge(&self) -> ColumnPlan {
        let m = self.mesh;
        let (c, e) = (self.l.corners as usize, m.edge_count());
        let b = self.l.boundary as usize;
        let mut plan =
            ColumnPlan::with_capacity(Eid::halfedge_slots(c + e + 4 * b), 8 * c + 16 * b);
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
            let trisected = self.l.trisected(edge).is_some();
            for h in edge.halfedges() {
                if trisected && m.in_hole(h) {
                    // From the first boundary point, a third along the
                    // inner half-edge, on the hole's side.
                    plan.interpolate(thirds(m.next(h), h, 1));
                } else if kept {
                    plan.copy(h.raw());
                } else {
                    self.face_corners(h, &mut plan);
                }
            }
        }
        // Per trisected edge: the middle third (inner side from a', hole
        // side from b'), the last third (inner from b', hole from b), the
        // spokes from a' and b' (their face-point sides).
        for h in self.trisected() {
            let (t, hn) = (h.twin(), m.next(h));
            let tn = m.next(t);
            plan.interpolate(thirds(h, hn, 1));
            plan.interpolate(thirds(tn, t, 2));
            plan.interpolate(thirds(h, hn, 2));
            plan.copy(t.raw());
            plan.interpolate(thirds(h, hn, 1));
            self.face_corners(h, &mut plan);
            plan.interpolate(thirds(h, hn, 2));
            self.face_corners(h, &mut plan);
        }
        plan
    }

    fn edge(&self) -> ColumnPlan {
        let m = self.mesh;
        let c = self.l.corners as usize;
        let b = self.l.boundary as usize;
        let mut plan = ColumnPlan::with_capacity(c + m.edge_count() + 4 * b, 3 * b);
        for _ in 0..c {
            plan.interpolate([]);
        }
        let third = 1.0 / 3.0;
        for edge in m.eids() {
            if self.l.trisected(edge).is_some() {
                plan.split(edge.raw(), third);
            } else if self.l.kept(edge) {
                plan.copy(edge.raw());
            } else {
                plan.interpolate([]);
            }
        }
        for h in self.trisected() {
            let e = h.edge().raw();
            plan.split(e, third);
            plan.split(e, third);
            plan.interpolate([]);
            plan.interpolate([]);
        }
        plan
    }

    fn face(&self) -> ColumnPlan {
        let m = self.mesh;
        let c = self.l.corners as usize;
        let b = self.l.boundary as usize;
        let mut plan = ColumnPlan::with_capacity(c + 2 * b + m.hole_count(), 2 * c + 2 * b);
        let third = 1.0 / 3.0;
        let ninth = 1.0 / 9.0;
        for edge in m.eids() {
            for h in edge.halfedges() {
                if m.in_hole(h) {
                    continue;
                }
                let (own, other) = (m.face_of(h).raw(), m.face_of(h.twin()));
                if self.l.trisected(edge).is_some() {
                    // The first of three triangles on the kept piece.
                    plan.split(own, ninth);
                } else if self.l.kept(edge) {
                    // The kept piece beside a boundary or seam edge.
                    plan.split(own, third);
                } else {
                    // Half of each piece beside the flipped edge, this
                    // side's first.
                    plan.flip_piece(own, third, other.raw(), third);
                }
            }
        }
        for h in self.trisected() {
            let own = m.face_of(h).raw();
            plan.split(own, ninth);
            plan.split(own, ninth);
        }
        for f in m.fids() {
            if m.is_hole(f) {
                plan.copy(f.raw());
            }
        }
        plan
    }
}
