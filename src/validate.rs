//! Every structural rule of a mesh, stated and checked in one place.
//!
//! [`Mesh::validate`] walks the raw records with bounded loops (a corrupted
//! ring cannot hang it) and reports the first broken rule with the keys
//! involved. Debug builds run it after every mutation; tests run it after
//! every step of random operation streams.
//!
//! # The rules
//!
//! 1. **Storage.** Link arrays and attribute columns have one entry per
//!    slot of their arena; live counts match the generations; the hole count
//!    matches the flagged faces.
//! 2. **Links in range.** Every live half-edge's `origin`, `next` and `face`
//!    name live elements.
//! 3. **No loops.** The two half-edges of an edge leave different vertices.
//! 4. **Next is a permutation.** Every live half-edge is the `next` of
//!    exactly one half-edge.
//! 5. **Faces are cycles.** `next(h)` has the face of `h`, and leaves the
//!    vertex `h` enters.
//! 6. **Face links.** Every live face names a half-edge of its own, and the
//!    `next` cycle from it holds every half-edge of that face.
//! 7. **Face size.** A face (not a hole) has at least three sides and no
//!    corner vertex twice.
//! 8. **Vertex links.** Every live vertex names a half-edge leaving it, and
//!    turning around it (`twin(h).next`) visits every half-edge that leaves
//!    it, once: one ring per vertex, also where several holes meet.
//! 9. **No dangling edges.** Every edge has a face (not a hole) on at least
//!    one side.
//! 10. **No multi-edges.** No two edges join the same two vertices.
//! 11. **Boundary vertices point into a hole.** A vertex with an outgoing
//!     half-edge in a hole names such a half-edge (any of them where several
//!     holes meet), so "is this vertex on the boundary" is one look-up
//!     ([`VertexView::is_boundary`](crate::VertexView::is_boundary)), as in
//!     pmp-library. The operators, the builder and deserialization keep it;
//!     [`RawEdit::finish`](crate::link::RawEdit::finish) re-establishes it.

pub use crate::error::ValidationError;
use crate::keys::AnyKey;
use crate::layout::{Eid, IdVec, Vid};
use crate::mesh::Mesh;

fn broken(rule: u8, key: Option<AnyKey>, detail: impl Into<String>) -> ValidationError {
    ValidationError {
        rule,
        key,
        detail: detail.into(),
    }
}

impl Mesh {
    /// The whole-mesh check after every operator, for the crate's own
    /// tests and fuzzing (the `validate-edits` feature in a debug build;
    /// the README's test command turns it on): O(mesh) per edit, so a dependent's debug build,
    /// which runs its own code unoptimised, does not pay it (a generator
    /// of 1,000 edits would be quadratic). Operators keep their O(1)
    /// `debug_assert!`s on what they touch. Inside a transaction the check
    /// waits for the outermost one to end: a composite edit (an algorithm,
    /// a tool) is checked once, not after each of its thousands of steps.
    #[inline]
    pub(crate) fn debug_validate(&self) {
        #[cfg(any(test, all(debug_assertions, feature = "validate-edits")))]
        {
            if self.rec.as_deref().is_some_and(|r| r.tx_depth > 0) {
                return;
            }
            if let Err(e) = self.validate() {
                panic!("operator broke the mesh: {e}");
            }
        }
    }

    /// Check every structural rule (listed in [`validate`](crate::validate)).
    ///
    /// # Errors
    /// The first broken rule, with its number, the element and what was
    /// found.
    ///
    /// # Complexity
    /// O(half-edges + Σ vertex degree · log degree).
    ///
    /// ```
    /// let mesh = meshloom::shapes::icosahedron();
    /// assert_eq!(mesh.validate(), Ok(()));
    /// ```
    pub fn validate(&self) -> Result<(), ValidationError> {
        self.check_storage()?;
        self.check_halfedges()?;
        self.check_faces()?;
        self.check_vertices()?;
        Ok(())
    }

    fn check_storage(&self) -> Result<(), ValidationError> {
        let [nv, nh, ne, nf] = self.slot_counts();
        if self.v_halfedge.len() != nv
            || nh != Eid::halfedge_slots(ne)
            || self.f_halfedge.len() != nf
        {
            return Err(broken(
                1,
                None,
                "link arrays and generations disagree in length",
            ));
        }
        let columns = [
            (&self.attrs.vertex, nv, "vertex"),
            (&self.attrs.halfedge, nh, "half-edge"),
            (&self.attrs.edge, ne, "edge"),
            (&self.attrs.face, nf, "face"),
        ];
        for (cols, n, kind) in columns {
            for (name, c) in &cols.cols {
                if c.len() != n {
                    return Err(broken(
                        1,
                        None,
                        format!(
                            "{kind} column {name:?} does not have one value per slot ({n} slots)"
                        ),
                    ));
                }
            }
        }
        for (slots, kind) in [
            (&self.v_slots, "vertices"),
            (&self.e_slots, "edges"),
            (&self.f_slots, "faces"),
        ] {
            let live = (0..slots.slot_count())
                .filter(|&i| slots.is_live(i))
                .count();
            if live != slots.live() {
                return Err(broken(
                    1,
                    None,
                    format!(
                        "{live} {kind} have live generations but the count says {}",
                        slots.live()
                    ),
                ));
            }
        }
        let flagged = self.holes().count();
        if flagged != self.holes {
            return Err(broken(
                1,
                None,
                format!(
                    "{flagged} faces are flagged as holes but the count says {}",
                    self.holes
                ),
            ));
        }
        Ok(())
    }

    fn check_halfedges(&self) -> Result<(), ValidationError> {
        let nh = self.he.len();
        let mut is_next_of = IdVec::filled(0u8, nh);
        for e in self.eids() {
            for h in e.halfedges() {
                let key = Some(AnyKey::Halfedge(self.hkey(h)));
                let r = self.he[h];
                if !self.v_slots.is_live(r.origin.index()) {
                    return Err(broken(
                        2,
                        key,
                        format!("origin {} is not a live vertex", r.origin.raw()),
                    ));
                }
                if !self.he.contains(r.next) || !self.e_slots.is_live(r.next.edge().index()) {
                    return Err(broken(
                        2,
                        key,
                        format!("next {} is not a live half-edge", r.next.raw()),
                    ));
                }
                if !self.f_slots.is_live(r.face.index()) {
                    return Err(broken(
                        2,
                        key,
                        format!("face {} is not a live face", r.face.raw()),
                    ));
                }
                let c = &mut is_next_of[r.next];
                *c = c.saturating_add(1);
            }
            let [h, t] = e.halfedges();
            let (a, b) = (self.origin(h), self.origin(t));
            if a == b {
                return Err(broken(
                    3,
                    Some(AnyKey::Edge(self.ekey(e))),
                    format!("both half-edges leave vertex {}", a.raw()),
                ));
            }
            if self.in_hole(h) && self.in_hole(t) {
                return Err(broken(
                    9,
                    Some(AnyKey::Edge(self.ekey(e))),
                    "holes on both sides",
                ));
            }
        }
        for h in self.hids() {
            let key = Some(AnyKey::Halfedge(self.hkey(h)));
            if is_next_of[h] != 1 {
                return Err(broken(
                    4,
                    key,
                    format!("is the next of {} half-edges", is_next_of[h]),
                ));
            }
            let n = self.next(h);
            if self.face_of(n) != self.face_of(h) {
                return Err(broken(5, key, "next half-edge lies in another face"));
            }
            if self.origin(n) != self.dest(h) {
                return Err(broken(
                    5,
                    key,
                    "next half-edge does not leave this one's end",
                ));
            }
        }
        Ok(())
    }

    fn check_faces(&self) -> Result<(), ValidationError> {
        let mut per_face = IdVec::filled(0u32, self.f_halfedge.len());
        for h in self.hids() {
            per_face[self.face_of(h)] += 1;
        }
        let mut corners: Vec<Vid> = Vec::new();
        for f in self.fids() {
            let key = Some(AnyKey::Face(self.fkey(f)));
            let h = self.face_halfedge(f);
            if !self.he.contains(h)
                || !self.e_slots.is_live(h.edge().index())
                || self.face_of(h) != f
            {
                return Err(broken(
                    6,
                    key,
                    format!("names half-edge {}, which is not its own", h.raw()),
                ));
            }
            let len = self.face_halfedges(f).count();
            if len != per_face[f] as usize {
                return Err(broken(
                    6,
                    key,
                    format!("its cycle has {len} half-edges but {} name it", per_face[f]),
                ));
            }
            if !self.is_hole(f) {
                if len < 3 {
                    return Err(broken(7, key, format!("has {len} sides")));
                }
                corners.clear();
                corners.extend(self.face_halfedges(f).map(|h| self.origin(h)));
                corners.sort_unstable();
                if let Some(w) = corners.windows(2).find(|w| w[0] == w[1]) {
                    return Err(broken(
                        7,
                        key,
                        format!("corner {} appears twice", self.vkey(w[0])),
                    ));
                }
            }
        }
        Ok(())
    }

    fn check_vertices(&self) -> Result<(), ValidationError> {
        let mut out_degree = IdVec::filled(0u32, self.v_halfedge.len());
        for h in self.hids() {
            out_degree[self.origin(h)] += 1;
        }
        let mut ends: Vec<Vid> = Vec::new();
        for v in self.vids() {
            let key = Some(AnyKey::Vertex(self.vkey(v)));
            let h = self.v_halfedge[v];
            if h.is_none()
                || !self.he.contains(h)
                || !self.e_slots.is_live(h.edge().index())
                || self.origin(h) != v
            {
                return Err(broken(8, key, "does not name a half-edge leaving it"));
            }
            ends.clear();
            let mut touches_hole = false;
            for o in self.outgoing(v) {
                if self.origin(o) != v {
                    return Err(broken(
                        8,
                        key,
                        "its ring reaches a half-edge leaving elsewhere",
                    ));
                }
                touches_hole |= self.in_hole(o);
                ends.push(self.dest(o));
            }
            if ends.len() != out_degree[v] as usize {
                return Err(broken(
                    8,
                    key,
                    format!(
                        "its ring visits {} of the {} half-edges leaving it",
                        ends.len(),
                        out_degree[v]
                    ),
                ));
            }
            ends.sort_unstable();
            if let Some(w) = ends.windows(2).find(|w| w[0] == w[1]) {
                return Err(broken(
                    10,
                    key,
                    format!("two edges join it to {}", self.vkey(w[0])),
                ));
            }
            if touches_hole && !self.in_hole(h) {
                return Err(broken(
                    11,
                    key,
                    format!(
                        "a hole touches it but it names {}, which lies in no hole",
                        self.hkey(h)
                    ),
                ));
            }
        }
        Ok(())
    }
}
