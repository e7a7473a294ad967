//! `compact`: dense storage after many edits.

use crate::keys::{EdgeKey, FaceKey, HalfedgeKey, VertexKey};
use crate::layout::{with_headroom, Eid, Fid, HalfedgeRecord, Hid, IdVec, Vid};
use crate::mesh::Mesh;
use crate::slots::Slots;

/// Old → new key maps returned by [`Mesh::compact`]. A key that named a
/// live element before compacting maps to that element's new key (another
/// index and, where the arena was compacted, another generation); a key
/// that was stale before maps to `None`. The old keys themselves are all
/// stale afterwards (except in an arena that had nothing to compact).
#[derive(Clone, Debug, Default)]
pub struct KeyMaps {
    vertices: ArenaMap,
    /// Edges, and half-edges through their edge.
    edges: ArenaMap,
    faces: ArenaMap,
}

/// One arena's map.
#[derive(Clone, Debug, Default)]
struct ArenaMap {
    /// Per old slot: (new index or `GONE`, the generation it had).
    slots: Vec<(u32, u32)>,
    /// The generation of every element afterwards; `None` when the arena
    /// was left as it was (keys keep their generation).
    generation: Option<u32>,
}

/// A vacant slot's entry in a map.
const GONE: u32 = u32::MAX;

impl ArenaMap {
    /// `(new index, new generation)` of the element `(index, generation)`
    /// named before compacting.
    fn get(&self, index: usize, generation: u32) -> Option<(u32, u32)> {
        let &(new, g) = self.slots.get(index)?;
        (new != GONE && g == generation).then(|| (new, self.generation.unwrap_or(g)))
    }
}

impl KeyMaps {
    /// The new key of a vertex.
    pub fn vertex(&self, v: VertexKey) -> Option<VertexKey> {
        let (i, g) = self.vertices.get(v.index(), v.generation())?;
        Some(Vid::new(i).key(g))
    }

    /// The new key of an edge.
    pub fn edge(&self, e: EdgeKey) -> Option<EdgeKey> {
        let (i, g) = self.edges.get(e.index(), e.generation())?;
        Some(Eid::new(i).key(g))
    }

    /// The new key of a half-edge (it stays on the same side of its edge).
    pub fn halfedge(&self, h: HalfedgeKey) -> Option<HalfedgeKey> {
        let old = h.id();
        let (e, g) = self.edges.get(old.edge().index(), h.generation())?;
        Some(Eid::new(e).halfedge(old.side()).key(g))
    }

    /// The new key of a face or hole.
    pub fn face(&self, f: FaceKey) -> Option<FaceKey> {
        let (i, g) = self.faces.get(f.index(), f.generation())?;
        Some(Fid::new(i).key(g))
    }
}

/// What compaction does to one arena.
struct ArenaPlan {
    /// Old slot of each new slot: the live slots in order, or every slot
    /// when the arena stays as it was.
    order: Vec<u32>,
    /// New index of each old slot (`GONE` for vacant ones dropped).
    new_index: Vec<u32>,
    /// The arena's slots afterwards; `None`: it stays as it was.
    slots: Option<Slots>,
    map: ArenaMap,
}

impl ArenaPlan {
    fn of(slots: &Slots) -> ArenaPlan {
        let n = slots.slot_count();
        let generation_at = |i: usize| slots.generation(i).unwrap_or(0);
        let moved = if slots.live() == n {
            // Nothing vacant: no element moves, every key stays valid.
            None
        } else {
            // Elements move: a new base above every generation issued, so no
            // old key names another element. When the generations are
            // exhausted the arena stays as it was (still correct, only not
            // dense).
            slots.compacted(slots.live())
        };
        match moved {
            None => ArenaPlan {
                order: (0..n as u32).collect(),
                new_index: (0..n as u32).collect(),
                slots: None,
                map: ArenaMap {
                    slots: (0..n)
                        .map(|i| {
                            let live = slots.is_live(i);
                            (if live { i as u32 } else { GONE }, generation_at(i))
                        })
                        .collect(),
                    generation: None,
                },
            },
            Some(new) => {
                let order: Vec<u32> = slots.live_indices().collect();
                let mut new_index = vec![GONE; n];
                for (new, &old) in order.iter().enumerate() {
                    new_index[old as usize] = new as u32;
                }
                let map = ArenaMap {
                    slots: (0..n).map(|i| (new_index[i], generation_at(i))).collect(),
                    generation: Some(new.base()),
                };
                ArenaPlan {
                    order,
                    new_index,
                    slots: Some(new),
                    map,
                }
            }
        }
    }

    /// The new index of old slot `raw` (`NONE` links stay `NONE`).
    #[inline]
    fn remap(&self, raw: u32) -> u32 {
        self.new_index.get(raw as usize).copied().unwrap_or(raw)
    }
}

impl Mesh {
    /// Move every element to a dense prefix of its arena, in slot order, and
    /// drop the vacant slots (and their free lists), so storage and
    /// iteration cost only what is live.
    ///
    /// Returns old → new key maps. Every key held from before is stale
    /// afterwards (elements that moved get a generation above any the arena
    /// ever issued): translate it through the maps, which give the new key
    /// of every element that was live. No old key ever names another
    /// element. An arena with no vacant slot is left as it is, and its keys
    /// stay valid. Attribute values move with their elements. The mesh is
    /// otherwise unchanged (χ, counts, connectivity).
    ///
    /// An arena whose generations are exhausted (a generation within two of
    /// 2^32, which only deserialized input can carry) cannot take a new
    /// base; it is left as it is, not dense, rather than reissue a
    /// generation.
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
    /// assert!(mesh.vertex(b).is_err(), "keys from before are stale");
    /// let b = maps.vertex(b).unwrap();
    /// assert_eq!(mesh.vertex(b)?.degree(), 6);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn compact(&mut self) -> KeyMaps {
        // A rebuild: the journal keeps the prior mesh as one step.
        let mut maps = None;
        self.wholesale(|m| maps = Some(m.compact_in_place()));
        maps.expect("compaction ran")
    }

    fn compact_in_place(&mut self) -> KeyMaps {
        let v = ArenaPlan::of(&self.v_slots);
        let e = ArenaPlan::of(&self.e_slots);
        let f = ArenaPlan::of(&self.f_slots);
        let vnew = |x: Vid| Vid::new(v.remap(x.raw()));
        let fnew = |x: Fid| Fid::new(f.remap(x.raw()));
        let hnew = |h: Hid| {
            if h.is_none() {
                h
            } else {
                Eid::new(e.remap(h.edge().raw())).halfedge(h.side())
            }
        };
        let nh = Eid::halfedge_slots(e.order.len());
        // The new arrays keep the arena's headroom (`layout::headroom`): the
        // first edit after compacting would otherwise regrow every one.
        let mut he = IdVec::from_vec(with_headroom(nh));
        let mut h_order = Vec::with_capacity(nh);
        for &old in &e.order {
            for h in Eid::new(old).halfedges() {
                let r = self.he[h];
                he.push(HalfedgeRecord {
                    origin: vnew(r.origin),
                    next: hnew(r.next),
                    face: fnew(r.face),
                });
                h_order.push(h.raw());
            }
        }
        let mut v_halfedge = with_headroom(v.order.len());
        v_halfedge.extend(
            v.order
                .iter()
                .map(|&old| hnew(self.v_halfedge[Vid::new(old)])),
        );
        let mut f_halfedge = with_headroom(f.order.len());
        f_halfedge.extend(f.order.iter().map(|&old| {
            let link = self.f_halfedge[Fid::new(old)];
            let h = link.halfedge();
            if self.he.contains(h) {
                link.with_halfedge(hnew(h))
            } else {
                link
            }
        }));
        self.he = he.into();
        self.v_halfedge = IdVec::<Vid, Hid>::from_vec(v_halfedge).into();
        self.f_halfedge = IdVec::from_vec(f_halfedge).into();
        if let Some(s) = v.slots {
            self.v_slots = s;
            self.attrs.vertex.permute(&v.order);
        }
        if let Some(s) = e.slots {
            self.e_slots = s;
            self.attrs.edge.permute(&e.order);
            self.attrs.halfedge.permute(&h_order);
        }
        if let Some(s) = f.slots {
            self.f_slots = s;
            self.attrs.face.permute(&f.order);
        }
        // Inside `wholesale`, which holds the recorder aside: nothing to record,
        // nothing to seal.
        self.debug_validate();
        KeyMaps {
            vertices: v.map,
            edges: e.map,
            faces: f.map,
        }
    }
}
