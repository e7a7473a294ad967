//! The topology of a √3 level: where every new element goes ([`Layout`])
//! and the passes that write their records ([`build`]).

use crate::error::Result;
use crate::layout::{with_headroom, Eid, FaceLink, Fid, HalfedgeRecord, Hid, IdVec, Vid};
use crate::mesh::Mesh;

use super::ALGORITHM;
use crate::algo::subdivision::refine::{fresh_slots, Ranks};
use crate::algo::subdivision::{unsuitable, Pass};
use crate::mesh::Topology;

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
pub(super) struct Layout {
    pub(super) nv: u32,
    pub(super) corners: u32,
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
    pub(super) boundary: u32,
}

impl Layout {
    /// Whether old edge `e` is kept (boundary or seam) rather than flipped.
    #[inline(always)]
    pub(super) fn kept(&self, e: Eid) -> bool {
        self.kept[e.index()]
    }

    #[inline(always)]
    pub(super) fn corner_of(&self, h: Hid) -> Option<u32> {
        self.corner[h.index()].checked_sub(1)
    }

    #[inline(always)]
    pub(super) fn spoke(&self, h: Hid) -> Eid {
        Eid::new(self.corner[h.index()] - 1)
    }

    /// The flipped (interior) or kept (boundary) edge of old edge `e`.
    #[inline(always)]
    pub(super) fn edge(&self, e: Eid) -> Eid {
        Eid::new(self.corners + self.edge_rank.get(e.index()))
    }

    #[inline(always)]
    pub(super) fn triangle(&self, h: Hid) -> Fid {
        Fid::new(self.corner[h.index()] - 1)
    }

    #[inline(always)]
    pub(super) fn face_point(&self, f: Fid) -> Vid {
        Vid::new(self.nv + self.face_rank[f.index()])
    }

    #[inline(always)]
    pub(super) fn hole(&self, f: Fid) -> Fid {
        Fid::new(self.corners + 2 * self.boundary + self.face_rank[f.index()])
    }

    /// The rank of `e` among the trisected edges, if it is one.
    #[inline(always)]
    pub(super) fn trisected(&self, e: Eid) -> Option<u32> {
        self.trisected.get(e.index()).and_then(|r| r.checked_sub(1))
    }

    /// The trisected edges in slot order: each one's rank and inner
    /// half-edge.
    pub(super) fn trisected_edges<'m>(
        &'m self,
        mesh: &'m Mesh,
    ) -> impl Iterator<Item = (u32, Hid)> + 'm {
        let slots = if self.boundary > 0 {
            mesh.edge_slots()
        } else {
            0
        };
        (0..slots).filter_map(move |ei| {
            let e = Eid::new(ei as u32);
            let r = self.trisected(e)?;
            Some((r, boundary_inner(mesh, e)?))
        })
    }

    /// Extra edge `k` of trisected edge rank `r`: 0 the middle third, 1
    /// the last third, 2 and 3 the spokes from the first and the second
    /// boundary point.
    #[inline(always)]
    pub(super) fn extra_edge(&self, r: u32, k: u32) -> Eid {
        Eid::new(self.corners + self.edges + 4 * r + k)
    }

    /// Extra triangle `k` of trisected edge rank `r`: 0 on the middle
    /// third, 1 on the last third.
    #[inline(always)]
    pub(super) fn extra_face(&self, r: u32, k: u32) -> Fid {
        Fid::new(self.corners + 2 * r + k)
    }

    /// Boundary point `k` (0 a third along the inner half-edge, 1 two
    /// thirds) of trisected edge rank `r`.
    #[inline(always)]
    pub(super) fn boundary_point(&self, r: u32, k: u32) -> Vid {
        Vid::new(self.nv + self.faces + 2 * r + k)
    }

    /// The new hole half-edge leaving `origin(t)` along old hole half-edge
    /// `t`: the last third's hole side if `t`'s edge is trisected.
    #[inline(always)]
    pub(super) fn hole_start(&self, t: Hid) -> Hid {
        match self.trisected(t.edge()) {
            Some(r) => self.extra_edge(r, 1).halfedge(1),
            None => self.edge(t.edge()).halfedge(t.side()),
        }
    }

    pub(super) fn of(mesh: &Mesh, trisect: bool) -> Layout {
        let mut corner = vec![0u32; mesh.halfedge_slots()];
        let mut next = 0u32;
        for e in mesh.eids() {
            for h in e.halfedges() {
                if !mesh.in_hole(h) {
                    next += 1;
                    corner[h.index()] = next;
                }
            }
        }
        let mut face_rank = vec![0u32; mesh.face_slots()];
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
            trisected = vec![0u32; mesh.edge_slots()];
            for e in mesh.eids() {
                if boundary_inner(mesh, e).is_some() {
                    boundary += 1;
                    trisected[e.index()] = boundary;
                }
            }
        }
        Layout {
            nv: mesh.vertex_slots() as u32,
            corners: next,
            faces,
            edges: mesh.edge_count() as u32,
            edge_rank: Ranks::of(mesh.edge_arena()),
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
pub(super) fn boundary_inner(mesh: &Mesh, e: Eid) -> Option<Hid> {
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
    let columns = &mesh.attrs().halfedge.cols;
    let mut kept = vec![false; mesh.edge_slots()];
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

/// The connectivity of the new level (see [`Layout`]).
pub(super) fn build(mesh: &Mesh, l: &Layout, pass: &mut Pass<'_, '_>) -> Result<Topology> {
    let c = l.corners as usize;
    let faces = mesh.face_count();
    let b = l.boundary as usize;
    let new_edges = c + mesh.edge_count() + 4 * b;
    let too_big = u32::try_from(l.nv as usize + faces + 2 * b).is_err()
        || Eid::halfedge_slots(new_edges) >= (1usize << 31);
    if too_big {
        return Err(unsuitable(
            ALGORITHM,
            None,
            "the result would have more than 2^31 half-edges",
        ));
    }
    let mut out = Records {
        records: IdVec::from_vec(with_headroom(Eid::halfedge_slots(new_edges))),
        face_links: IdVec::from_vec(with_headroom(c + 2 * b + mesh.hole_count())),
    };
    out.spokes(mesh, l, pass)?;
    out.old_edges(mesh, l);
    out.trisected_edges(mesh, l);
    debug_assert_eq!(out.records.len(), Eid::halfedge_slots(new_edges));
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            let h = mesh.face_halfedge(f);
            out.face_links.push(FaceLink::new(l.hole_start(h), true));
        }
    }
    Ok(Topology {
        vertex_arena: mesh.vertex_arena().extended(faces + 2 * b),
        edge_arena: fresh_slots(mesh.edge_arena(), new_edges, ALGORITHM)?,
        face_arena: fresh_slots(mesh.face_arena(), out.face_links.len(), ALGORITHM)?,
        vertex_links: vertex_links(mesh, l),
        records: out.records,
        face_links: out.face_links,
        hole_count: mesh.hole_count(),
    })
}

/// The half-edge records and face links of a level, written in slot order.
struct Records {
    records: IdVec<Hid, HalfedgeRecord>,
    face_links: IdVec<Fid, FaceLink>,
}

impl Records {
    /// The spokes, in corner order, and the triangle at each corner.
    fn spokes(&mut self, mesh: &Mesh, l: &Layout, pass: &mut Pass<'_, '_>) -> Result<()> {
        let ne_slots = mesh.edge_slots();
        let mut stage = pass.stage("spokes", ne_slots)?;
        for ei in 0..ne_slots {
            stage.tick(ei)?;
            if !mesh.edge_live(ei) {
                continue;
            }
            for h in Eid::new(ei as u32).halfedges() {
                if l.corner_of(h).is_none() {
                    continue;
                }
                let rec = mesh.halfedge_record(h);
                let cf = l.face_point(rec.face);
                // prev(h) in a triangle.
                let p = mesh.next(rec.next);
                // Side 0: origin(h) -> c, in the triangle beside p's edge at
                // dest(p): across the flipped edge, in p's own kept piece,
                // or on the last third of p's trisected edge.
                self.records.push(if l.kept(p.edge()) {
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
                    l.spoke(mesh.next(t)).halfedge(0)
                };
                self.records.push(HalfedgeRecord {
                    origin: cf,
                    next,
                    face: l.triangle(h),
                });
                self.face_links
                    .push(FaceLink::new(l.spoke(h).halfedge(1), false));
            }
        }
        stage.finish()
    }

    /// Per old edge: flipped (side s from the face point of side s's face
    /// to the other, in the triangle at the origin of side 1 − s), or kept
    /// (trisected: its first third).
    fn old_edges(&mut self, mesh: &Mesh, l: &Layout) {
        for ei in 0..mesh.edge_slots() {
            if !mesh.edge_live(ei) {
                continue;
            }
            let e = Eid::new(ei as u32);
            let hs = e.halfedges();
            let kept = l.kept(e);
            let third = if kept { l.trisected(e) } else { None };
            for s in 0..2 {
                let (own, other) = (hs[s], hs[1 - s]);
                let rec = mesh.halfedge_record(own);
                self.records.push(if !kept {
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
    }

    /// Per trisected edge (inner half-edge h from a to b, face point m,
    /// boundary points a' and b'): the middle third a'b', the last third
    /// b'b, the spokes a'm and b'm, and the two new triangles.
    fn trisected_edges(&mut self, mesh: &Mesh, l: &Layout) {
        for (r, h) in l.trisected_edges(mesh) {
            let t = h.twin();
            let rec = mesh.halfedge_record(h);
            let m = l.face_point(rec.face);
            let hole = l.hole(mesh.face_of(t));
            let (a1, b1) = (l.boundary_point(r, 0), l.boundary_point(r, 1));
            let [mid, last, spoke_a, spoke_b] = [0, 1, 2, 3].map(|k| l.extra_edge(r, k));
            let (tri_mid, tri_last) = (l.extra_face(r, 0), l.extra_face(r, 1));
            let record = |origin, next, face| HalfedgeRecord { origin, next, face };
            self.records.extend_from(&[
                record(a1, spoke_b.halfedge(0), tri_mid),
                record(b1, l.edge(h.edge()).halfedge(t.side()), hole),
                record(b1, l.spoke(rec.next).halfedge(0), tri_last),
                record(mesh.origin(t), mid.halfedge(1), hole),
                record(a1, l.spoke(h).halfedge(1), l.triangle(h)),
                record(m, mid.halfedge(0), tri_mid),
                record(b1, spoke_a.halfedge(1), tri_mid),
                record(m, last.halfedge(0), tri_last),
            ]);
            self.face_links.push(FaceLink::new(mid.halfedge(0), false));
            self.face_links.push(FaceLink::new(last.halfedge(0), false));
        }
    }
}

/// The outgoing half-edge of every new vertex: old ones (along the hole
/// for a boundary vertex), face points, boundary points (along the hole:
/// a' -> a, b' -> a').
fn vertex_links(mesh: &Mesh, l: &Layout) -> IdVec<Vid, Hid> {
    let nv = l.nv as usize;
    let slots = nv + mesh.face_count() + 2 * l.boundary as usize;
    let mut vertex_links: IdVec<Vid, Hid> = IdVec::from_vec(with_headroom(slots));
    for vi in 0..nv {
        let v = Vid::new(vi as u32);
        vertex_links.push(if !mesh.vertex_live(vi) {
            Hid::NONE
        } else {
            let h = mesh.vertex_halfedge(v);
            if mesh.in_hole(h) {
                l.hole_start(h)
            } else {
                l.spoke(h).halfedge(0)
            }
        });
    }
    for f in mesh.fids() {
        if !mesh.is_hole(f) {
            vertex_links.push(l.spoke(mesh.face_halfedge(f)).halfedge(1));
        }
    }
    for (r, h) in l.trisected_edges(mesh) {
        vertex_links.push(l.edge(h.edge()).halfedge(h.twin().side()));
        vertex_links.push(l.extra_edge(r, 0).halfedge(1));
    }
    vertex_links
}
