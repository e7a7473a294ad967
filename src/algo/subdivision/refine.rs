//! The topology of the face-splitting schemes: every edge splits at a new
//! edge point, and every face is cut either 1-to-4 (a triangle: its three
//! corner triangles and a centre triangle, as Loop) or into one quad per
//! corner around a new face point (any polygon, as Catmull-Clark).
//!
//! ```text
//!   triangle (1-to-4)               polygon (quads)
//!
//!         v1                            v1 ---- m0 ---- v0
//!        /  \                           |       |       |
//!      m0 -- m1                         m1 ---- c ----- m3
//!      / \  / \                         |       |       |
//!    v0 -- m2 -- v2                     v2 ---- m2 ---- v3
//! ```
//!
//! # The new layout
//!
//! With `nv` the parent's vertex slots, `E` its edges, `C` its face corners
//! (half-edges not in holes), `T` the faces cut 1-to-4, `Q` those cut into
//! quads and `H` the holes:
//!
//! | arena | slots |
//! |---|---|
//! | vertices | `[0, nv)` the parent's (vacant ones stay vacant), `[nv, nv + E)` edge points by edge rank, `[nv + E, nv + E + Q)` face points by rank |
//! | edges | `[0, C)` one new edge inside a face per corner, by corner id; `[C, C + 2E)` the two children of each parent edge (the one at the end the parent's side-0 half-edge leaves first) |
//! | faces | `[0, C)` one child face per corner (the triangle or quad at that corner), by corner id; `[C, C + T)` centre triangles; `[C + T, C + T + H)` the holes |
//!
//! Corner ids number the corners face by face in slot order, each face from
//! its own half-edge along `next`. The face pass writes the records of the
//! new inside edges in that order, the edge pass the four records of each
//! parent edge's children in edge order: every record is written once, in
//! slot order, into arenas reserved at their final size.

use crate::error::Result;
use crate::layout::{with_headroom, Eid, FaceLink, Fid, HalfedgeRecord, Hid, IdVec, Vid};
use crate::mesh::{Mesh, Topology};
use crate::slots::Slots;

use super::{unsuitable, Pass};

/// How a face is cut.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Cut {
    /// A triangle into four triangles.
    Triangle,
    /// A polygon into one quad per corner around a face point.
    Quads,
}

/// Which faces are cut how.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum CutRule {
    /// Every face is a triangle cut 1-to-4 (other faces are refused).
    Triangles,
    /// Every face is cut into quads.
    Quads,
}

impl CutRule {
    /// How a face of `degree` sides is cut, `None` if it cannot be.
    #[inline]
    pub(crate) fn cut(self, degree: usize) -> Option<Cut> {
        match self {
            CutRule::Triangles => (degree == 3).then_some(Cut::Triangle),
            CutRule::Quads => Some(Cut::Quads),
        }
    }
}

/// Dense ranks of the live slots of an arena: the identity while no slot
/// was ever freed, a table otherwise.
pub(crate) struct Ranks(Option<Vec<u32>>);

impl Ranks {
    pub(crate) fn of(slots: &Slots) -> Ranks {
        if slots.intact() {
            return Ranks(None);
        }
        let mut next = 0u32;
        let table = (0..slots.slot_count())
            .map(|i| {
                let r = next;
                next += u32::from(slots.is_live(i));
                r
            })
            .collect();
        Ranks(Some(table))
    }

    /// The rank of live slot `i`.
    #[inline(always)]
    pub(crate) fn get(&self, i: usize) -> u32 {
        match &self.0 {
            None => i as u32,
            Some(t) => t[i],
        }
    }
}

/// The maps from the parent to the new layout (see the module doc).
pub(crate) struct Refinement {
    /// The parent's vertex slots.
    pub(crate) nv: u32,
    /// The parent's live edges.
    pub(crate) edges: u32,
    /// The parent's face corners.
    pub(crate) corners: u32,
    /// Faces cut 1-to-4.
    pub(crate) tris: u32,
    /// Faces cut into quads.
    pub(crate) quads: u32,
    /// Holes.
    pub(crate) holes: u32,
    pub(crate) rule: CutRule,
    pub(crate) edge_rank: Ranks,
    /// Per parent half-edge slot: its corner id + 1; 0 in holes and vacant
    /// slots.
    pub(crate) corner: Vec<u32>,
    /// Per parent face slot: its rank among the faces cut the same way, or
    /// among the holes.
    pub(crate) face_rank: Vec<u32>,
}

/// Children per parent edge.
const CHILDREN: u32 = 2;

impl Refinement {
    /// The edge point of parent edge `e`.
    #[inline(always)]
    pub(crate) fn edge_point(&self, e: Eid) -> Vid {
        Vid::new(self.nv + self.edge_rank.get(e.index()))
    }

    /// Child `j` of parent edge `e`: child 0 touches the end that side 0
    /// leaves, child 1 the other.
    #[inline(always)]
    pub(crate) fn child(&self, e: Eid, j: u32) -> Eid {
        Eid::new(self.corners + CHILDREN * self.edge_rank.get(e.index()) + j)
    }

    /// The child of parent half-edge `p` that leaves `origin(p)`, on `p`'s
    /// side.
    #[inline(always)]
    pub(crate) fn first_child(&self, p: Hid) -> Hid {
        self.child(p.edge(), p.side()).halfedge(p.side())
    }

    /// The child of `p` that enters `dest(p)`, on `p`'s side.
    #[inline(always)]
    pub(crate) fn second_child(&self, p: Hid) -> Hid {
        self.child(p.edge(), 1 - p.side()).halfedge(p.side())
    }

    /// The corner id of parent half-edge `h`, if it is in a face.
    #[inline(always)]
    pub(crate) fn corner_of(&self, h: Hid) -> Option<u32> {
        self.corner[h.index()].checked_sub(1)
    }

    /// The new hole of parent hole `f`.
    #[inline(always)]
    pub(crate) fn hole(&self, f: Fid) -> Fid {
        Fid::new(self.corners + self.tris + self.face_rank[f.index()])
    }

    /// The new vertex slots.
    pub(crate) fn vertex_slots(&self) -> usize {
        (self.nv + self.edges + self.quads) as usize
    }
}

/// The half-edges of the face through `h`, in order (bounded by the
/// number of half-edge slots).
#[inline]
pub(crate) fn face_ring(mesh: &Mesh, start: Hid, ring: &mut Vec<Hid>) {
    ring.clear();
    let mut h = start;
    for _ in 0..mesh.halfedge_slots() {
        ring.push(h);
        h = mesh.next(h);
        if h == start {
            break;
        }
    }
}

/// The three half-edges of the face through `h0`, if it is a triangle.
#[inline(always)]
fn triangle_at(mesh: &Mesh, h0: Hid) -> Option<[Hid; 3]> {
    let h1 = mesh.next(h0);
    let h2 = mesh.next(h1);
    (mesh.next(h2) == h0).then_some([h0, h1, h2])
}

/// What the face pass writes: the records of the new inside edges and the
/// links of the corner faces, in corner order, and the links to append
/// after them (centre triangles, holes; face points after the vertices).
struct FaceRecords {
    records: IdVec<Hid, HalfedgeRecord>,
    face_links: IdVec<Fid, FaceLink>,
    centers: Vec<FaceLink>,
    hole_links: Vec<FaceLink>,
    face_point_links: Vec<Hid>,
}

impl FaceRecords {
    /// Cut triangle `hs` (corner ids from `c0`) 1-to-4: its corner ids, the
    /// records of its three inside edges and the links of its four
    /// triangles, as [`cut_ring`](Self::cut_ring) writes them for any ring
    /// of three.
    #[inline(always)]
    fn cut_triangle(&mut self, r: &mut Refinement, hs: [Hid; 3], c0: u32) {
        let center = Fid::new(r.corners + r.tris);
        for (i, &h) in hs.iter().enumerate() {
            r.corner[h.index()] = c0 + i as u32 + 1;
        }
        for i in 0..3 {
            let (hi, hp) = (hs[i], hs[(i + 2) % 3]);
            let (mi, mp) = (r.edge_point(hi.edge()), r.edge_point(hp.edge()));
            self.records.push(HalfedgeRecord {
                origin: mi,
                next: r.second_child(hp),
                face: Fid::new(c0 + i as u32),
            });
            self.records.push(HalfedgeRecord {
                origin: mp,
                next: Eid::new(c0 + ((i + 1) % 3) as u32).halfedge(1),
                face: center,
            });
        }
        for h in hs {
            self.face_links.push(FaceLink::new(r.first_child(h), false));
        }
        self.centers
            .push(FaceLink::new(Eid::new(c0).halfedge(1), false));
    }

    /// Cut the face of half-edges `ring` (parent face slot `fi`, corner ids
    /// from `c0`) by `cut`: the records of its inside edges and the links
    /// of its children.
    fn cut_ring(&mut self, r: &mut Refinement, ring: &[Hid], cut: Cut, fi: usize, c0: u32) {
        let n = ring.len();
        for (i, &h) in ring.iter().enumerate() {
            r.corner[h.index()] = c0 + i as u32 + 1;
        }
        // Corner ids of position i, i - 1 and i + 1 around the face, without
        // a division (this loop runs once per corner of the mesh).
        let cid = |i: usize| c0 + i as u32;
        let prev = |i: usize| if i == 0 { n - 1 } else { i - 1 };
        let next = |i: usize| if i + 1 == n { 0 } else { i + 1 };
        match cut {
            Cut::Triangle => {
                r.face_rank[fi] = r.tris;
                let center = Fid::new(r.corners + r.tris);
                r.tris += 1;
                for i in 0..n {
                    let (hi, hp) = (ring[i], ring[prev(i)]);
                    let (mi, mp) = (r.edge_point(hi.edge()), r.edge_point(hp.edge()));
                    // m_i -> m_{i-1}, in the corner triangle at origin(h_i).
                    self.records.push(HalfedgeRecord {
                        origin: mi,
                        next: r.second_child(hp),
                        face: Fid::new(cid(i)),
                    });
                    // m_{i-1} -> m_i, in the centre triangle.
                    self.records.push(HalfedgeRecord {
                        origin: mp,
                        next: Eid::new(cid(next(i))).halfedge(1),
                        face: center,
                    });
                }
                self.centers
                    .push(FaceLink::new(Eid::new(c0).halfedge(1), false));
            }
            Cut::Quads => {
                r.face_rank[fi] = r.quads;
                let c = Vid::new(r.nv + r.edges + r.quads);
                r.quads += 1;
                for (i, &hi) in ring.iter().enumerate() {
                    let mi = r.edge_point(hi.edge());
                    // m_i -> c, in the quad at origin(h_i).
                    self.records.push(HalfedgeRecord {
                        origin: mi,
                        next: Eid::new(cid(prev(i))).halfedge(1),
                        face: Fid::new(cid(i)),
                    });
                    // c -> m_i, in the quad at dest(h_i).
                    self.records.push(HalfedgeRecord {
                        origin: c,
                        next: r.second_child(hi),
                        face: Fid::new(cid(next(i))),
                    });
                }
                self.face_point_links.push(Eid::new(c0).halfedge(1));
            }
        }
        for &h in ring {
            self.face_links.push(FaceLink::new(r.first_child(h), false));
        }
    }
}

/// A fresh arena of `n` live slots whose generations are above every
/// generation `old` ever issued.
pub(crate) fn fresh_slots(old: &Slots, n: usize, algorithm: &'static str) -> Result<Slots> {
    old.compacted(n).ok_or_else(|| {
        unsuitable(
            algorithm,
            None,
            "an arena has used up its generations (2^32 reuses of a slot)",
        )
    })
}

/// Build the connectivity of one level: every edge split, every face cut by
/// `rule`.
///
/// # Errors
/// [`Error::Unsuitable`](crate::Error::Unsuitable) for a face `rule` cannot
/// cut; [`Error::Cancelled`](crate::Error::Cancelled).
pub(crate) fn refine(
    mesh: &Mesh,
    rule: CutRule,
    pass: &mut Pass<'_, '_>,
) -> Result<(Refinement, Topology)> {
    let algorithm = pass.algorithm;
    let mut r = Refinement::new(mesh, rule, algorithm)?;
    let FaceRecords {
        records: mut he,
        face_links: mut f_halfedge,
        centers,
        hole_links,
        face_point_links,
    } = face_pass(mesh, &mut r, pass)?;
    f_halfedge.extend_from(&centers);
    f_halfedge.extend_from(&hole_links);
    let mut vertex_links = old_vertex_links(mesh, &r);
    edge_pass(mesh, &r, &mut he, &mut vertex_links, pass)?;
    vertex_links.extend_from(&face_point_links);
    let new_edges = (r.corners + 2 * r.edges) as usize;
    let topology = Topology {
        vertex_arena: mesh.vertex_arena().extended((r.edges + r.quads) as usize),
        edge_arena: fresh_slots(mesh.edge_arena(), new_edges, algorithm)?,
        face_arena: fresh_slots(mesh.face_arena(), f_halfedge.len(), algorithm)?,
        vertex_links,
        records: he,
        face_links: f_halfedge,
        hole_count: r.holes as usize,
    };
    Ok((r, topology))
}

impl Refinement {
    /// The maps of `mesh`'s level before the face pass fills them: counts,
    /// edge ranks, and room for the corner ids and face ranks.
    ///
    /// # Errors
    /// [`Error::Unsuitable`](crate::Error::Unsuitable) for a result past
    /// 2^31 half-edges.
    fn new(mesh: &Mesh, rule: CutRule, algorithm: &'static str) -> Result<Refinement> {
        let nv = mesh.vertex_slots();
        let edges = mesh.edge_count();
        let mut boundary = 0usize;
        for f in mesh.fids() {
            if mesh.is_hole(f) {
                boundary += mesh.face_halfedges(f).count();
            }
        }
        let corners = Eid::halfedge_slots(edges) - boundary;
        let too_big = u32::try_from(nv + edges + mesh.face_count()).is_err()
            || u32::try_from(Eid::halfedge_slots(corners + 2 * edges)).is_err()
            || Eid::halfedge_slots(corners + 2 * edges) >= (1usize << 31);
        if too_big {
            return Err(unsuitable(
                algorithm,
                None,
                "the result would have more than 2^31 half-edges",
            ));
        }
        Ok(Refinement {
            nv: nv as u32,
            edges: edges as u32,
            corners: corners as u32,
            tris: 0,
            quads: 0,
            holes: 0,
            rule,
            edge_rank: Ranks::of(mesh.edge_arena()),
            corner: vec![0u32; Eid::halfedge_slots(mesh.edge_slots())],
            face_rank: vec![0u32; mesh.face_slots()],
        })
    }
}

/// The faces, in slot order: the records of the new inside edges and the
/// links of the child faces, in corner order; fills `r`'s corner ids and
/// face ranks.
fn face_pass(mesh: &Mesh, r: &mut Refinement, pass: &mut Pass<'_, '_>) -> Result<FaceRecords> {
    let nf_slots = mesh.face_slots();
    let new_edges = (r.corners + 2 * r.edges) as usize;
    let max_faces = r.corners as usize + mesh.face_count() + mesh.hole_count();
    let mut out = FaceRecords {
        records: IdVec::from_vec(with_headroom(Eid::halfedge_slots(new_edges))),
        face_links: IdVec::from_vec(with_headroom(max_faces)),
        centers: Vec::new(),
        hole_links: Vec::with_capacity(mesh.hole_count()),
        face_point_links: Vec::new(),
    };
    let mut ring: Vec<Hid> = Vec::with_capacity(16);
    let mut next_corner = 0u32;
    let mut stage = pass.stage("faces", nf_slots)?;
    for fi in 0..nf_slots {
        stage.tick(fi)?;
        if !mesh.face_live(fi) {
            continue;
        }
        let f = Fid::new(fi as u32);
        let link = mesh.face_link(f);
        if link.is_hole() {
            r.face_rank[fi] = r.holes;
            r.holes += 1;
            out.hole_links
                .push(FaceLink::new(r.first_child(link.halfedge()), true));
            continue;
        }
        if r.rule == CutRule::Triangles {
            if let Some(hs) = triangle_at(mesh, link.halfedge()) {
                // The common case, with the ring in registers.
                out.cut_triangle(r, hs, next_corner);
                r.face_rank[fi] = r.tris;
                r.tris += 1;
                next_corner += 3;
                continue;
            }
        }
        face_ring(mesh, link.halfedge(), &mut ring);
        let n = ring.len();
        let Some(cut) = r.rule.cut(n) else {
            return Err(unsuitable(
                pass.algorithm,
                Some(mesh.fkey(f).into()),
                format!("the scheme takes triangles; this face has {n} sides"),
            ));
        };
        out.cut_ring(r, &ring, cut, fi, next_corner);
        next_corner += n as u32;
    }
    stage.finish()?;
    debug_assert_eq!(next_corner, r.corners);
    Ok(out)
}

/// The outgoing half-edges of the parent's vertices, which keep their
/// slots (vacant ones stay vacant), with room for the new vertices.
fn old_vertex_links(mesh: &Mesh, r: &Refinement) -> IdVec<Vid, Hid> {
    let nv = r.nv as usize;
    let mut vertex_links: IdVec<Vid, Hid> = IdVec::from_vec(with_headroom(r.vertex_slots()));
    for vi in 0..nv {
        let v = Vid::new(vi as u32);
        vertex_links.push(if mesh.vertex_live(vi) {
            r.first_child(mesh.vertex_halfedge(v))
        } else {
            Hid::NONE
        });
    }
    vertex_links
}

/// The edges, in slot order: the records of the two children of each, and
/// the outgoing half-edge of its edge point.
fn edge_pass(
    mesh: &Mesh,
    r: &Refinement,
    he: &mut IdVec<Hid, HalfedgeRecord>,
    vertex_links: &mut IdVec<Vid, Hid>,
    pass: &mut Pass<'_, '_>,
) -> Result<()> {
    let ne_slots = mesh.edge_slots();
    let mut stage = pass.stage("edges", ne_slots)?;
    for ei in 0..ne_slots {
        stage.tick(ei)?;
        if !mesh.edge_live(ei) {
            continue;
        }
        let e = Eid::new(ei as u32);
        let m = r.edge_point(e);
        let [h, t] = e.halfedges();
        let (ha, hb) = child_records(mesh, r, h, m);
        let (ta, tb) = child_records(mesh, r, t, m);
        // Child 0 is (a, m): h's first child and t's second; child 1 is
        // (m, b): h's second child and t's first.
        he.push(ha);
        he.push(tb);
        he.push(hb);
        he.push(ta);
        // An edge point on the boundary names its half-edge in the hole.
        let out = if r.corner_of(t).is_none() {
            r.second_child(t)
        } else {
            r.second_child(h)
        };
        vertex_links.push(out);
    }
    stage.finish()
}

/// The records of the two children of parent half-edge `p`, whose edge
/// point is `m`: the first leaves `origin(p)`, the second enters `dest(p)`.
#[inline(always)]
fn child_records(mesh: &Mesh, r: &Refinement, p: Hid, m: Vid) -> (HalfedgeRecord, HalfedgeRecord) {
    let rec = mesh.halfedge_record(p);
    let next_first = r.first_child(rec.next);
    match r.corner_of(p) {
        Some(c) => {
            // In a face: the first child lies in the child face at origin(p)
            // and goes on along the new edge inside the face; the second
            // lies in the child face at dest(p), the corner of next(p).
            let next_corner = r.corner[rec.next.index()] - 1;
            (
                HalfedgeRecord {
                    origin: rec.origin,
                    next: Eid::new(c).halfedge(0),
                    face: Fid::new(c),
                },
                HalfedgeRecord {
                    origin: m,
                    next: next_first,
                    face: Fid::new(next_corner),
                },
            )
        }
        None => {
            let hole = r.hole(rec.face);
            (
                HalfedgeRecord {
                    origin: rec.origin,
                    next: r.second_child(p),
                    face: hole,
                },
                HalfedgeRecord {
                    origin: m,
                    next: next_first,
                    face: hole,
                },
            )
        }
    }
}

/// Refuse an interior vertex of valence 2 whose two faces are both cut
/// 1-to-4: its two faces share both its edges, and each would join the same
/// two edge points, making a double edge.
pub(crate) fn check_valence_two(mesh: &Mesh, rule: CutRule, algorithm: &'static str) -> Result<()> {
    if rule == CutRule::Quads {
        return Ok(());
    }
    for v in mesh.vids() {
        if let Some(e) = valence_two_error(mesh, v, rule, algorithm) {
            return Err(e);
        }
    }
    Ok(())
}

/// The error for `v` if it is an interior vertex of valence 2 between two
/// faces cut 1-to-4.
#[inline]
pub(crate) fn valence_two_error(
    mesh: &Mesh,
    v: Vid,
    rule: CutRule,
    algorithm: &'static str,
) -> Option<crate::Error> {
    let h0 = mesh.vertex_halfedge(v);
    if mesh.in_hole(h0) {
        return None;
    }
    let h1 = mesh.next(h0.twin());
    if h1 == h0 || mesh.next(h1.twin()) != h0 {
        return None;
    }
    let both_cut = [h0, h1]
        .iter()
        .all(|&h| rule.cut(mesh.face_halfedges(mesh.face_of(h)).count()) == Some(Cut::Triangle));
    both_cut.then(|| {
        unsuitable(
            algorithm,
            Some(mesh.vkey(v).into()),
            "an interior vertex of valence 2: its two faces share both its edges, \
             and splitting them would join two edge points twice",
        )
    })
}
