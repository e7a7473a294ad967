//! Stages 5 to 8 of the builder: number the edges in face order and link
//! the faces' half-edges, link the unpaired sides into holes (chaining the
//! fans at a bowtie), label the hole faces, check every vertex ring; then
//! the mesh from the links.

use super::input::{Flat, UsedVertices};
use super::pair::Mates;
use crate::error::{BuildError, Result};
use crate::geometry::Point;
use crate::keys::{FaceKey, VertexKey};
use crate::layout::{
    headroom, to_vec_with_headroom, with_headroom, Eid, FaceLink, Fid, HalfedgeRecord, Hid, IdVec,
    Vid,
};
use crate::mesh::Mesh;
use crate::slots::Slots;
use crate::store::rules::Interpolate;
use crate::store::{Column, POSITION};

/// Stage 5's result: the hole half-edges with their origins, the number of
/// edges, and each input face's half-edge.
pub(super) struct Twins {
    /// Each unpaired side's twin (it lies in a hole) and its origin.
    pub(super) boundary: Vec<(Hid, Vid)>,
    pub(super) edges: usize,
    /// The half-edge of each input face's first corner (room is left for
    /// the holes of stage 7).
    pub(super) f_halfedge: Vec<FaceLink>,
}

/// The links being built.
pub(super) struct Links {
    pub(super) he: IdVec<Hid, HalfedgeRecord>,
    pub(super) v_halfedge: IdVec<Vid, Hid>,
    /// Half-edges leaving each vertex, to check its ring.
    pub(super) out_degree: IdVec<Vid, u32>,
}

/// Numbering state of stage 5: `mate` as stage 4 left it, except that an
/// entry with the high bit set is the half-edge of a side whose twin was
/// numbered first.
pub(super) struct Numbering {
    pub(super) mate: Vec<u32>,
    pub(super) edges: u32,
    pub(super) boundary: Vec<(Hid, Vid)>,
}

impl Numbering {
    const NUMBERED: u32 = 1 << 31;

    /// The half-edge of the side from corner `c` to vertex `dest`: a new
    /// edge (its half-edge 0) unless its twin side came first. A new edge's
    /// two records are appended to `he` here, in numbering order, so the
    /// arena is written once as it grows (no fill pass before).
    #[inline(always)]
    pub(super) fn halfedge(
        &mut self,
        c: usize,
        dest: u32,
        he: &mut IdVec<Hid, HalfedgeRecord>,
    ) -> Hid {
        let m = self.mate[c];
        if m & Self::NUMBERED != 0 {
            return Hid::new(m & !Self::NUMBERED);
        }
        let [inner, outer] = Eid::new(self.edges).halfedges();
        self.edges += 1;
        debug_assert_eq!(he.len(), inner.index());
        he.push(HalfedgeRecord::VACANT);
        he.push(HalfedgeRecord::VACANT);
        if m == 0 {
            self.boundary.push((outer, Vid::new(dest)));
        } else {
            self.mate[m as usize - 1] = outer.raw() | Self::NUMBERED;
        }
        inner
    }
}

impl Links {
    /// Link the half-edge of a face's side starting at `origin`.
    #[inline(always)]
    pub(super) fn link(&mut self, h: Hid, origin: u32, next: Hid, face: Fid) {
        let origin = Vid::new(origin);
        self.he[h] = HalfedgeRecord { origin, next, face };
        self.v_halfedge[origin] = h;
    }
}

/// Stage 5: number the edges in face order, as the faces first use them
/// (half-edge 0 runs along that first side, as when faces are added one
/// by one), and link the half-edges of the faces; every vertex names a
/// half-edge. Consecutive faces get consecutive edges, so the arena
/// follows the input's face order.
pub(super) fn link_faces(faces: Flat<'_>, nv: usize, mates: Mates) -> (Links, Twins) {
    let corners = faces.indices.len();
    let edges = corners - mates.pairs;
    let unpaired = corners - 2 * mates.pairs;
    let nf = faces.face_count();
    let mut links = Links {
        he: IdVec::from_vec(Vec::with_capacity(Eid::halfedge_slots(
            edges + headroom(edges),
        ))),
        v_halfedge: IdVec::filled_with_headroom(Hid::NONE, nv),
        out_degree: IdVec::from_vec(mates.out_degree),
    };
    let mut numbering = Numbering {
        mate: mates.mate,
        edges: 0,
        boundary: Vec::with_capacity(unpaired),
    };
    let mut f_halfedge = with_headroom(nf + unpaired);
    let idx = faces.indices;
    let mut ring: Vec<Hid> = Vec::new();
    for f in 0..nf {
        let (s, e) = (faces.offsets[f] as usize, faces.offsets[f + 1] as usize);
        let face = Fid::new(f as u32);
        if let [a, b, c] = idx[s..e] {
            let h0 = numbering.halfedge(s, b, &mut links.he);
            let h1 = numbering.halfedge(s + 1, c, &mut links.he);
            let h2 = numbering.halfedge(s + 2, a, &mut links.he);
            links.link(h0, a, h1, face);
            links.link(h1, b, h2, face);
            links.link(h2, c, h0, face);
            f_halfedge.push(FaceLink::new(h0, false));
            continue;
        }
        ring.clear();
        for c in s..e {
            let n = if c + 1 < e { c + 1 } else { s };
            ring.push(numbering.halfedge(c, idx[n], &mut links.he));
        }
        for (k, c) in (s..e).enumerate() {
            let next = ring.get(k + 1).copied().unwrap_or(ring[0]);
            links.link(ring[k], idx[c], next, face);
        }
        f_halfedge.push(FaceLink::new(ring[0], false));
    }
    debug_assert_eq!(numbering.edges as usize, edges);
    debug_assert_eq!(links.he.len(), Eid::halfedge_slots(edges));
    (
        links,
        Twins {
            boundary: numbering.boundary,
            edges,
            f_halfedge,
        },
    )
}

/// Stage 6: the hole half-edges' origins, and each one's `next`: the hole
/// half-edge leaving the vertex it enters (where several leave one vertex,
/// a bowtie, the fans there are chained).
pub(super) fn link_boundary(
    links: &mut Links,
    boundary: &[(Hid, Vid)],
    vertices: &UsedVertices<'_>,
) -> Result<()> {
    let he = &mut links.he;
    // Vertices that several hole half-edges leave (one bit each); the
    // hole half-edge leaving any other boundary vertex is its
    // `v_halfedge`.
    let mut several = vec![0u64; links.v_halfedge.len().div_ceil(64)];
    for &(g, o) in boundary {
        he[g].origin = o;
        // Rule 11: a boundary vertex names a half-edge in a hole (hole
        // half-edges have no face yet: stage 7 gives them theirs).
        let before = links.v_halfedge[o];
        if he[before].face.is_none() {
            several[o.index() / 64] |= 1 << (o.index() % 64);
        }
        links.v_halfedge[o] = g;
        links.out_degree[o] += 1;
    }
    let mut bowtie = false;
    for &(g, _) in boundary {
        let a = he[g.twin()].origin; // g enters a
        if several[a.index() / 64] >> (a.index() % 64) & 1 == 1 {
            bowtie = true;
        } else {
            let k = links.v_halfedge[a];
            if he[k].face.is_none() {
                he[g].next = k;
            }
        }
    }
    if bowtie {
        link_bowties(he, boundary, vertices)?;
    }
    if let Some(&(g, _)) = boundary.iter().find(|&&(g, _)| he[g].next.is_none()) {
        let a = he[g.twin()].origin;
        return Err(BuildError::NonManifoldVertex {
            vertex: vertices.input_of(a),
            face: he[g.twin()].face.index(),
        }
        .into());
    }
    Ok(())
}

/// At each vertex with several hole half-edges leaving it, find the fan each
/// starts, and chain the fans: the hole half-edge ending fan `i` continues
/// with the one starting fan `i + 1`.
pub(super) fn link_bowties(
    he: &mut IdVec<Hid, HalfedgeRecord>,
    boundary: &[(Hid, Vid)],
    vertices: &UsedVertices<'_>,
) -> Result<()> {
    // Hole half-edges leaving each bowtie vertex, grouped by vertex.
    let mut leaving: Vec<(Vid, Hid)> = boundary.iter().map(|&(k, o)| (o, k)).collect();
    leaving.sort_unstable();
    let mut kept = Vec::with_capacity(leaving.len());
    for (i, &(a, k)) in leaving.iter().enumerate() {
        let shared =
            (i > 0 && leaving[i - 1].0 == a) || leaving.get(i + 1).is_some_and(|n| n.0 == a);
        if shared {
            kept.push((a, k));
        }
    }
    let leaving = kept;
    let budget = he.len();
    let mut i = 0;
    while i < leaving.len() {
        let a = leaving[i].0;
        let mut j = i;
        while j < leaving.len() && leaving[j].0 == a {
            j += 1;
        }
        // The hole half-edge that ends the fan started by each k.
        let mut ends = Vec::with_capacity(j - i);
        for &(_, k) in &leaving[i..j] {
            let mut o = he[k.twin()].next; // first interior outgoing
            let mut end = Hid::NONE;
            for _ in 0..budget {
                let x = o.twin(); // enters a
                if he[x].face.is_none() {
                    end = x;
                    break;
                }
                o = he[x].next;
            }
            if end.is_none() {
                return Err(BuildError::NonManifoldVertex {
                    vertex: vertices.input_of(a),
                    face: he[k.twin()].face.index(),
                }
                .into());
            }
            ends.push(end);
        }
        let m = j - i;
        for (fan, &end) in ends.iter().enumerate() {
            he[end].next = leaving[i + (fan + 1) % m].1;
        }
        i = j;
    }
    Ok(())
}

/// Stage 7: a hole face for every boundary loop (numbered after the input
/// faces), and every face's link. Returns the links and the hole count.
pub(super) fn make_hole_faces(
    he: &mut IdVec<Hid, HalfedgeRecord>,
    faces: Flat<'_>,
    twins: Twins,
) -> (IdVec<Fid, FaceLink>, usize) {
    let nf = faces.face_count();
    let boundary = &twins.boundary;
    let mut f_halfedge = twins.f_halfedge;
    for &(g, _) in boundary {
        if !he[g].face.is_none() {
            continue;
        }
        let f = Fid::new(f_halfedge.len() as u32);
        f_halfedge.push(FaceLink::new(g, true));
        let mut h = g;
        for _ in 0..=boundary.len() {
            he[h].face = f;
            h = he[h].next;
            if h == g || h.is_none() {
                break;
            }
        }
    }
    let holes = f_halfedge.len() - nf;
    (IdVec::from_vec(f_halfedge), holes)
}

/// Stage 8: every vertex's ring must reach all its half-edges (faces that
/// meet at a vertex in separate closed fans cannot share one ring).
pub(super) fn check_vertex_rings(links: &Links, vertices: &UsedVertices<'_>) -> Result<()> {
    let Links {
        he,
        v_halfedge,
        out_degree,
    } = links;
    for v in v_halfedge.ids() {
        let start = v_halfedge[v];
        let (mut h, mut ring) = (start, 0u32);
        loop {
            ring += 1;
            h = he[h.twin()].next;
            if h == start || ring > out_degree[v] {
                break;
            }
        }
        if ring != out_degree[v] {
            return Err(BuildError::NonManifoldVertex {
                vertex: vertices.input_of(v),
                face: he[start].face.min(he[start.twin()].face).index(),
            }
            .into());
        }
    }
    Ok(())
}

/// The mesh from the links, with the positions of the used vertices.
pub(super) fn assemble<P: Point>(
    links: Links,
    edges: usize,
    f_halfedge: IdVec<Fid, FaceLink>,
    holes: usize,
    positions: Option<&[P]>,
    vertices: &UsedVertices<'_>,
) -> Mesh {
    let faces = f_halfedge.len();
    let mut mesh = Mesh {
        v_halfedge: links.v_halfedge.into(),
        v_slots: Slots::full(vertices.count),
        he: links.he.into(),
        e_slots: Slots::full(edges),
        f_halfedge: f_halfedge.into(),
        f_slots: Slots::full(faces),
        holes,
        attrs: Default::default(),
        rec: None,
        stamp: crate::mesh::Stamp::fresh(),
    };
    if let Some(p) = positions {
        let values: Vec<[f64; 3]> = match &vertices.input_of_slot {
            None => to_vec_with_headroom(&P::slice_xyz(&p[..vertices.count])),
            Some(map) => {
                let mut v = with_headroom(map.len());
                v.extend(map.iter().map(|&i| p[i as usize].xyz()));
                v
            }
        };
        mesh.attrs.position = Some(mesh.attrs.vertex.push(
            POSITION,
            Box::new(Column::<[f64; 3], Interpolate>::dense(values)),
        ));
    }
    mesh
}

/// The key of each input vertex (`None` for unused ones) and face: one entry
/// per input vertex, as the caller asked.
pub(super) fn input_keys(
    mesh: &Mesh,
    n_in: usize,
    nf: usize,
    vertices: &UsedVertices<'_>,
) -> (Vec<Option<VertexKey>>, Vec<FaceKey>) {
    let mut keys = vec![None; n_in];
    for slot in 0..vertices.count as u32 {
        keys[vertices.input(slot)] = Some(mesh.vkey(Vid::new(slot)));
    }
    let faces = (0..nf as u32).map(|f| mesh.fkey(Fid::new(f))).collect();
    (keys, faces)
}
