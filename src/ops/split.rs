//! Operators that add elements inside an edge or a face: `split_edge`,
//! `split_face` / `insert_edge`, `poke_face`.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling, Unrecorded};
use crate::keys::{EdgeKey, FaceKey, HalfedgeKey, VertexKey};
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::{Mesh, Writer};

/// Faces up to this degree are handled without heap allocation.
const SMALL: usize = 8;

struct SplitEdgePlan {
    h: Hid,
    t: Hid,
    /// The half-edge before `h` in its face.
    ph: Hid,
}

/// One corner of a poked face: its old side, the spoke to the centre and
/// the triangle on that side.
#[derive(Copy, Clone)]
struct Spoke {
    ring: Hid,
    spoke: Eid,
    face: Fid,
}

impl Spoke {
    const NONE: Spoke = Spoke {
        ring: Hid::NONE,
        spoke: Eid::NONE,
        face: Fid::NONE,
    };
}

struct SplitFacePlan {
    pa: Hid,
    ha: Hid,
    pb: Hid,
    hb: Hid,
}

impl Mesh {
    fn plan_split_edge(&self, e: EdgeKey, t: f64) -> Result<SplitEdgePlan> {
        let e = self.check_edge(e)?;
        if !(0.0..=1.0).contains(&t) {
            return Err(refuse(
                "split_edge",
                self.ekey(e),
                Refusal::Parameter("t must lie in 0..=1"),
            ));
        }
        let [h, t] = e.halfedges();
        Ok(SplitEdgePlan {
            h,
            t,
            ph: self.prev_fast(h),
        })
    }

    /// Whether [`split_edge`](Mesh::split_edge) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`split_edge`](Mesh::split_edge).
    pub fn check_split_edge(&self, e: EdgeKey, t: f64) -> Result<()> {
        self.plan_split_edge(e, t).map(|_| ())
    }

    /// Put a new vertex `m` on edge `e`, at parameter `t` from `a` (the
    /// origin of `e`'s first half-edge, [`EdgeKey::halfedge_key`]`(0)`) to
    /// `b`. Both faces (or holes) beside the edge gain a side.
    ///
    /// ```text
    ///        c                    c
    ///      /   \                /   \
    ///     a --h-> b    =>      a -> m -h-> b
    ///      \   /                \   /
    ///        d                    d
    /// ```
    ///
    /// Returns `m`. The old edge's half-edge `h` now runs `m → b`; the new
    /// edge joins `a` and `m`. Attributes: `m = interpolate(a: 1−t, b: t)`;
    /// the edge splits with share `1−t` to `m–b` and `t` to `a–m`; the new
    /// corners at `m` interpolate the corners at `a` and `b` of the same
    /// face. χ is unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey);
    /// [`Refusal::Parameter`] when `t` is not in `0..=1` (NaN included).
    ///
    /// # Complexity
    /// O(degree of `a`) (to find the half-edge before `h`).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let e = mesh.edges().next().unwrap();
    /// let m = mesh.split_edge(e, 0.5)?;
    /// assert_eq!(mesh.vertex(m)?.degree(), 2);
    /// assert_eq!((mesh.vertex_count(), mesh.edge_count(), mesh.euler_characteristic()), (5, 7, 2));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn split_edge(&mut self, e: EdgeKey, t: f64) -> Result<VertexKey> {
        journaled!(self.split_edge_with(e, t))
    }

    /// The remesher's door: [`split_edge`](Mesh::split_edge) of a live
    /// edge slot at `t` in `0..=1`, without the per-call debug validation
    /// (the caller validates once at the end). A recording mesh takes the
    /// full operator, so every step is sealed as usual.
    pub(crate) fn split_edge_unvalidated(&mut self, e: Eid, t: f64) -> Vid {
        if self.rec.is_some() {
            let v = self
                .split_edge(self.ekey(e), t)
                .expect("a live edge slot and t in 0..=1 split");
            return self.check_vertex(v).expect("the new vertex is live");
        }
        let [h, tw] = e.halfedges();
        let plan = SplitEdgePlan {
            h,
            t: tw,
            ph: self.prev_fast(h),
        };
        self.writer::<Unrecorded>().commit_split_edge(plan, t)
    }

    fn plan_split_face(&self, f: FaceKey, a: VertexKey, b: VertexKey) -> Result<SplitFacePlan> {
        let f = self.check_face(f)?;
        let va = self.check_vertex(a)?;
        let vb = self.check_vertex(b)?;
        let fk = self.fkey(f);
        if self.is_hole(f) {
            return Err(refuse("split_face", fk, Refusal::Hole));
        }
        if va == vb {
            return Err(refuse("split_face", fk, Refusal::Adjacent));
        }
        let (mut ha, mut hb, mut pa, mut pb) = (None, None, None, None);
        let start = self.face_halfedge(f);
        let mut prev = self.prev(start);
        for h in self.face_halfedges(f) {
            let o = self.origin(h);
            if o == va {
                ha = Some(h);
                pa = Some(prev);
            } else if o == vb {
                hb = Some(h);
                pb = Some(prev);
            }
            prev = h;
        }
        let (Some(ha), Some(hb), Some(pa), Some(pb)) = (ha, hb, pa, pb) else {
            return Err(refuse("split_face", fk, Refusal::NotInFace));
        };
        if self.next(ha) == hb || self.next(hb) == ha {
            return Err(refuse("split_face", fk, Refusal::Adjacent));
        }
        if self.find_halfedge_raw(va, vb).is_some() {
            return Err(refuse("split_face", fk, Refusal::EdgeExists));
        }
        Ok(SplitFacePlan { pa, ha, pb, hb })
    }

    /// Whether [`split_face`](Mesh::split_face) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`split_face`](Mesh::split_face).
    pub fn check_split_face(&self, f: FaceKey, a: VertexKey, b: VertexKey) -> Result<()> {
        self.plan_split_face(f, a, b).map(|_| ())
    }

    /// Cut face `f` in two with a new edge between its corners `a` and `b`.
    ///
    /// ```text
    ///   a ----- x          a ----- x
    ///   |       |          | \  g  |
    ///   |   f   |    =>    |  \    |
    ///   |       |          | f \   |
    ///   y ----- b          y ----- b
    /// ```
    ///
    /// Returns the new half-edge `a → b`; it lies in the new face `g` (the
    /// part of `f` from `b` round to `a`), its twin in `f`. Attributes: the
    /// face splits by area (equal shares without positions); the new
    /// corners copy the corners of `a` and `b` in `f`. χ is unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Hole`] on a
    /// hole; [`Refusal::NotInFace`] unless both are corners of `f`;
    /// [`Refusal::Adjacent`] when `a == b` or they are neighbours in `f`;
    /// [`Refusal::EdgeExists`] when an edge `a–b` exists elsewhere.
    ///
    /// # Complexity
    /// O(degree of `f` + degree of `a`).
    ///
    /// # Examples
    /// ```
    /// use meshloom::Mesh;
    /// let mut quad = Mesh::from_faces(4, &[[0u32, 1, 2, 3]])?;
    /// let f = quad.faces().next().unwrap();
    /// let v: Vec<_> = quad.face(f)?.vertices().collect();
    /// let h = quad.split_face(f, v[0], v[2])?;
    /// assert_eq!(quad.face_count(), 2);
    /// assert_eq!(quad.halfedge(h)?.face().degree(), 3);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn split_face(&mut self, f: FaceKey, a: VertexKey, b: VertexKey) -> Result<HalfedgeKey> {
        journaled!(self.split_face_with(f, a, b))
    }

    fn common_face(&self, a: VertexKey, b: VertexKey) -> Result<FaceKey> {
        let va = self.check_vertex(a)?;
        let vb = self.check_vertex(b)?;
        for o in self.outgoing(va) {
            let f = self.face_of(o);
            if !self.is_hole(f) && self.face_halfedges(f).any(|h| self.origin(h) == vb) {
                return Ok(self.fkey(f));
            }
        }
        Err(refuse("insert_edge", a, Refusal::NotInFace))
    }

    /// Whether [`insert_edge`](Mesh::insert_edge) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`insert_edge`](Mesh::insert_edge).
    pub fn check_insert_edge(&self, a: VertexKey, b: VertexKey) -> Result<()> {
        let f = self.common_face(a, b)?;
        self.check_split_face(f, a, b)
    }

    /// [`split_face`](Mesh::split_face) on the first face (not a hole) that
    /// has both `a` and `b` as corners. Returns the new half-edge `a → b`.
    ///
    /// # Errors
    /// [`Refusal::NotInFace`] when no face has both; otherwise as
    /// `split_face`.
    ///
    /// # Complexity
    /// O(Σ degree of the faces around `a`).
    pub fn insert_edge(&mut self, a: VertexKey, b: VertexKey) -> Result<HalfedgeKey> {
        let f = self.common_face(a, b)?;
        self.split_face(f, a, b)
    }

    fn plan_poke_face(&self, f: FaceKey) -> Result<Fid> {
        let f = self.check_face(f)?;
        if self.is_hole(f) {
            return Err(refuse("poke_face", self.fkey(f), Refusal::Hole));
        }
        Ok(f)
    }

    /// Whether [`poke_face`](Mesh::poke_face) would succeed; changes nothing.
    ///
    /// # Errors
    /// As [`poke_face`](Mesh::poke_face).
    pub fn check_poke_face(&self, f: FaceKey) -> Result<()> {
        self.plan_poke_face(f).map(|_| ())
    }

    /// Put a new vertex `c` inside face `f` and fan it to every corner: a
    /// face of degree `n` becomes `n` triangles.
    ///
    /// ```text
    ///   v3 ------ v2        v3 ------ v2
    ///   |          |        |  \    /  |
    ///   |    f     |   =>   |    c     |
    ///   |          |        |  /    \  |
    ///   v0 ------ v1        v0 ------ v1
    /// ```
    ///
    /// Returns `c`; `f` becomes the triangle on `f`'s first half-edge. `c`
    /// names its half-edge to the last corner, so that collapsing that
    /// half-edge ([`collapse_edge`](Mesh::collapse_edge) of `c`'s
    /// half-edge) dissolves the two triangles beside it and gives a poked
    /// triangle back exactly: `f` and its half-edges keep their keys.
    /// Attributes: `c = interpolate(corners, equal weights)` (positions: the
    /// centroid); the face splits over the triangles by area; corners at `c`
    /// interpolate the old corners, the others copy theirs. χ is unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Hole`].
    ///
    /// # Complexity
    /// O(degree of `f`).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let c = mesh.poke_face(f)?;
    /// assert_eq!(mesh.vertex(c)?.degree(), 4);
    /// assert_eq!(mesh.face_count(), 9);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn poke_face(&mut self, f: FaceKey) -> Result<VertexKey> {
        journaled!(self.poke_face_with(f))
    }
}

impl Mesh {
    /// [`split_edge`](Mesh::split_edge)'s body, in journaling mode `J`.
    fn split_edge_with<J: Journaling>(&mut self, e: EdgeKey, t: f64) -> Result<VertexKey> {
        let mut w = self.writer::<J>();
        let plan = w.plan_split_edge(e, t)?;
        let m = w.commit_split_edge(plan, t);
        w.end_op();
        Ok(w.vkey(m))
    }

    /// [`split_face`](Mesh::split_face)'s body, in journaling mode `J`.
    fn split_face_with<J: Journaling>(
        &mut self,
        f: FaceKey,
        a: VertexKey,
        b: VertexKey,
    ) -> Result<HalfedgeKey> {
        let mut w = self.writer::<J>();
        let SplitFacePlan { pa, ha, pb, hb } = w.plan_split_face(f, a, b)?;
        let f = w.face_of(ha);
        let (n0, g) = w.split_face_raw(pa, ha, pb, hb);
        w.split_face_values(f, &[f, g]);
        w.end_op();
        Ok(w.hkey(n0))
    }

    /// [`poke_face`](Mesh::poke_face)'s body, in journaling mode `J`.
    fn poke_face_with<J: Journaling>(&mut self, f: FaceKey) -> Result<VertexKey> {
        let mut w = self.writer::<J>();
        let f = w.plan_poke_face(f)?;
        // Small faces stay on the stack. Per corner i: the old side
        // `ring[i]`, the new spoke edge and the triangle `faces[i]`.
        let n = w.face_degree(f);
        let mut stack = [Spoke::NONE; SMALL];
        let mut heap = Vec::new();
        let buf: &mut [Spoke] = if n <= SMALL {
            &mut stack[..n]
        } else {
            heap.resize(n, Spoke::NONE);
            &mut heap
        };
        for (slot, h) in buf.iter_mut().zip(w.face_halfedges(f)) {
            slot.ring = h;
        }
        let c = w.alloc_vertex();
        // Spoke i joins c and corner v_i = origin(ring[i]):
        // out_i = c -> v_i (side 0), in_i = v_i -> c (side 1).
        for s in buf.iter_mut() {
            s.spoke = w.alloc_edge();
        }
        buf[0].face = f;
        for s in buf[1..].iter_mut() {
            s.face = w.alloc_face(false);
        }
        // Only the ring and `f` existed before this call: the spokes, `c`
        // and the other faces were allocated above (a reused slot was
        // recorded as it was taken), so their writes record nothing.
        w.log_face(f);
        for i in 0..n {
            let j = (i + 1) % n;
            let Spoke { ring: h, face, .. } = buf[i];
            let out_i = buf[i].spoke.halfedge(0);
            let in_j = buf[j].spoke.halfedge(1);
            let ring = w.he_mut(h);
            ring.next = in_j;
            ring.face = face;
            *w.fresh_he_mut(in_j) = HalfedgeRecord {
                origin: w.origin(buf[j].ring),
                next: out_i,
                face,
            };
            *w.fresh_he_mut(out_i) = HalfedgeRecord {
                origin: c,
                next: h,
                face,
            };
            w.fresh_face_link(face, h);
        }
        // c names its spoke to the last corner: collapsing that half-edge
        // dissolves the last two triangles and leaves `f` (on the first),
        // so `collapse_edge` of it gives back a poked triangle exactly.
        *w.fresh_v_halfedge_mut(c) = buf[n - 1].spoke.halfedge(0);
        // Attributes.
        let share = 1.0 / n as f64;
        if !w.attrs.vertex.cols.is_empty() {
            let mut corners = [(0usize, 0.0f64); SMALL];
            let mut corners_heap = Vec::new();
            let corners: &mut [(usize, f64)] = if n <= SMALL {
                &mut corners[..n]
            } else {
                corners_heap.resize(n, (0, 0.0));
                &mut corners_heap
            };
            for (slot, s) in corners.iter_mut().zip(buf.iter()) {
                *slot = (w.origin(s.ring).index(), share);
            }
            w.attrs.vertex.interpolate(c.index(), corners);
        }
        if !w.attrs.edge.cols.is_empty() {
            for s in buf.iter() {
                w.attrs.edge.interpolate(s.spoke.index(), &[]);
            }
        }
        if !w.attrs.halfedge.cols.is_empty() {
            let old_corners: Vec<(usize, f64)> =
                buf.iter().map(|s| (s.ring.index(), share)).collect();
            for s in buf.iter() {
                let [out, into] = s.spoke.halfedges();
                w.attrs.halfedge.interpolate(out.index(), &old_corners);
                w.attrs.halfedge.copy(s.ring.index(), into.index());
            }
        }
        if !w.attrs.face.cols.is_empty() {
            let faces: Vec<Fid> = buf.iter().map(|s| s.face).collect();
            w.split_face_values(f, &faces);
        }
        w.end_op();
        Ok(w.vkey(c))
    }
}

impl<J: Journaling> Writer<'_, J> {
    /// The commit and rules of a planned edge split; cannot fail.
    fn commit_split_edge(&mut self, plan: SplitEdgePlan, t: f64) -> Vid {
        let SplitEdgePlan { h, t: tw, ph } = plan;
        let a = self.origin(h);
        let b = self.origin(tw);
        let nh = self.next(h);
        let nt = self.next(tw);
        let f_tw = self.face_of(tw);
        let m = self.alloc_vertex();
        let ne = self.alloc_edge();
        // n0: a -> m (in h's face), n1: m -> a (in tw's face).
        let [n0, n1] = ne.halfedges();
        *self.he_mut(n0) = HalfedgeRecord {
            origin: a,
            next: h,
            face: self.face_of(h),
        };
        *self.he_mut(n1) = HalfedgeRecord {
            origin: m,
            next: nt,
            face: f_tw,
        };
        self.he_mut(h).origin = m;
        self.set_next(ph, n0);
        self.set_next(tw, n1);
        // Rule 11: on a boundary edge m leaves into the hole (h and n1
        // lie in the faces of h and tw); n0 lies in h's face, like h.
        *self.v_halfedge_mut(m) = if self.holes > 0 && self.is_hole(f_tw) {
            n1
        } else {
            h
        };
        if self.v_halfedge[a] == h {
            *self.v_halfedge_mut(a) = n0;
        }
        // Attributes.
        self.attrs
            .vertex
            .interpolate(m.index(), &[(a.index(), 1.0 - t), (b.index(), t)]);
        let old = h.edge().index();
        self.attrs
            .edge
            .split(old, &[(ne.index(), t), (old, 1.0 - t)]);
        let hc = &mut self.attrs.halfedge;
        hc.copy(h.index(), n0.index());
        hc.interpolate(h.index(), &[(n0.index(), 1.0 - t), (nh.index(), t)]);
        hc.interpolate(n1.index(), &[(nt.index(), 1.0 - t), (tw.index(), t)]);
        m
    }
}
