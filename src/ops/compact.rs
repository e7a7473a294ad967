//! `compact`: dense storage after many edits.

use crate::keys::{EdgeKey, FaceKey, HalfedgeKey, VertexKey};
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid, IdVec, Vid};
use crate::mesh::Mesh;
use crate::slots::Slots;

/// Old → new key maps returned by [`Mesh::compact`]. Keys keep their
/// generation and get a new index; a key that was stale before compacting
/// maps to `None`.
#[derive(Clone, Debug, Default)]
pub struct KeyMaps {
    /// Per old vertex slot: (new index or `u32::MAX`, generation).
    vertices: Vec<(u32, u32)>,
    /// Per old edge slot.
    edges: Vec<(u32, u32)>,
    /// Per old face slot.
    faces: Vec<(u32, u32)>,
}

/// A vacant slot's entry in a map.
const GONE: u32 = u32::MAX;

fn lookup(map: &[(u32, u32)], index: usize, generation: u32) -> Option<u32> {
    let &(new, g) = map.get(index)?;
    (new != GONE && g == generation).then_some(new)
}

impl KeyMaps {
    /// The new key of a vertex.
    pub fn vertex(&self, v: VertexKey) -> Option<VertexKey> {
        lookup(&self.vertices, v.index(), v.generation()).map(|i| VertexKey::new(i, v.generation()))
    }

    /// The new key of an edge.
    pub fn edge(&self, e: EdgeKey) -> Option<EdgeKey> {
        lookup(&self.edges, e.index(), e.generation()).map(|i| EdgeKey::new(i, e.generation()))
    }

    /// The new key of a half-edge (it stays on the same side of its edge).
    pub fn halfedge(&self, h: HalfedgeKey) -> Option<HalfedgeKey> {
        let old = h.id();
        lookup(&self.edges, old.edge().index(), h.generation())
            .map(|e| Eid::new(e).halfedge(old.side()).key(h.generation()))
    }

    /// The new key of a face or hole.
    pub fn face(&self, f: FaceKey) -> Option<FaceKey> {
        lookup(&self.faces, f.index(), f.generation()).map(|i| FaceKey::new(i, f.generation()))
    }
}

/// Live slots in order, and the old → new index map.
fn order(slots: &Slots) -> (Vec<u32>, Vec<(u32, u32)>) {
    let live: Vec<u32> = slots.live_indices().collect();
    let mut map: Vec<(u32, u32)> = (0..slots.slot_count())
        .map(|i| (GONE, slots.generation(i).unwrap_or(0)))
        .collect();
    for (new, &old) in live.iter().enumerate() {
        map[old as usize].0 = new as u32;
    }
    (live, map)
}

impl Mesh {
    /// Move every element to a dense prefix of its arena, in slot order, and
    /// drop the vacant slots (and their free lists), so storage and
    /// iteration cost only what is live.
    ///
    /// Returns old → new key maps. Every key held from before must be
    /// translated through them: the same index may now name another element.
    /// Attribute values move with their elements. The mesh is otherwise
    /// unchanged (χ, counts, connectivity).
    ///
    /// # Complexity
    /// O(slots + attribute columns · slots).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let b = mesh.collapse_edge(h)?;
    /// let maps = mesh.compact();
    /// assert_eq!(mesh.slot_counts()[0], 11);
    /// let b = maps.vertex(b).unwrap();
    /// assert_eq!(mesh.vertex(b)?.degree(), 6);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn compact(&mut self) -> KeyMaps {
        let (v_live, v_map) = order(&self.v_slots);
        let (e_live, e_map) = order(&self.e_slots);
        let (f_live, f_map) = order(&self.f_slots);
        let vnew = |v: Vid| Vid::new(v_map[v.index()].0);
        let fnew = |f: Fid| Fid::new(f_map[f.index()].0);
        let hnew = |h: Hid| Eid::new(e_map[h.edge().index()].0).halfedge(h.side());
        let mut he = IdVec::from_vec(Vec::with_capacity(Eid::halfedge_slots(e_live.len())));
        let mut h_order = Vec::with_capacity(Eid::halfedge_slots(e_live.len()));
        for &e in &e_live {
            for h in Eid::new(e).halfedges() {
                let r = self.he[h];
                he.push(HalfedgeRecord {
                    origin: vnew(r.origin),
                    next: hnew(r.next),
                    face: fnew(r.face),
                });
                h_order.push(h.raw());
            }
        }
        let v_halfedge: IdVec<Vid, Hid> = IdVec::from_vec(
            v_live
                .iter()
                .map(|&v| hnew(self.v_halfedge[Vid::new(v)]))
                .collect(),
        );
        let f_halfedge = IdVec::from_vec(
            f_live
                .iter()
                .map(|&f| {
                    let link = self.f_halfedge[Fid::new(f)];
                    link.with_halfedge(hnew(link.halfedge()))
                })
                .collect(),
        );
        let gens = |live: &[u32], s: &Slots| -> Vec<u32> {
            live.iter().map(|&i| s.generation_of(i)).collect()
        };
        self.v_slots = Slots::from_generations(gens(&v_live, &self.v_slots));
        self.e_slots = Slots::from_generations(gens(&e_live, &self.e_slots));
        self.f_slots = Slots::from_generations(gens(&f_live, &self.f_slots));
        self.he = he;
        self.v_halfedge = v_halfedge;
        self.f_halfedge = f_halfedge;
        self.attrs.vertex.permute(&v_live);
        self.attrs.edge.permute(&e_live);
        self.attrs.face.permute(&f_live);
        self.attrs.halfedge.permute(&h_order);
        self.debug_validate();
        KeyMaps {
            vertices: v_map,
            edges: e_map,
            faces: f_map,
        }
    }
}
