//! `cut_path`: open a seam along a path of edges into new boundary.

use std::collections::HashMap;

use super::refuse;
use crate::error::{Refusal, Result};
use crate::keys::{FaceKey, VertexKey};
use crate::mesh::{HalfedgeRecord, Mesh};

struct CutPlan {
    /// Path half-edges `h_i = v_i -> v_i+1`.
    hs: Vec<u32>,
    closed: bool,
    /// Per path vertex index that splits: the outgoing half-edges right of
    /// the path (clockwise from `h_i`, exclusive, to `twin(h_i-1)`).
    wedges: Vec<(usize, Vec<u32>)>,
}

impl Mesh {
    fn plan_cut(&self, path: &[VertexKey]) -> Result<CutPlan> {
        const OP: &str = "cut_path";
        let mut vs = Vec::with_capacity(path.len());
        for &v in path {
            vs.push(self.check_vertex(v)?);
        }
        let Some(&first) = path.first() else {
            return Err(refuse(
                OP,
                crate::keys::AnyKey::Vertex(VertexKey::new(0, 0)),
                Refusal::Empty,
            ));
        };
        let closed = vs.len() > 1 && vs[0] == vs[vs.len() - 1];
        let k = vs.len().saturating_sub(1);
        if (closed && k < 3) || (!closed && k < 2) {
            return Err(refuse(
                OP,
                first,
                Refusal::Parameter("the path needs two edges (three if closed)"),
            ));
        }
        let mut distinct = vs[..if closed { k } else { k + 1 }].to_vec();
        distinct.sort_unstable();
        if distinct.windows(2).any(|w| w[0] == w[1]) {
            return Err(refuse(OP, first, Refusal::NonManifold));
        }
        let mut hs = Vec::with_capacity(k);
        for i in 0..k {
            let Some(h) = self.find_halfedge_raw(vs[i], vs[i + 1]) else {
                return Err(refuse(OP, path[i], Refusal::NotAdjacent));
            };
            if self.in_hole_raw(h) || self.in_hole_raw(h ^ 1) {
                return Err(refuse(OP, self.ekey(h >> 1), Refusal::Boundary));
            }
            hs.push(h);
        }
        for (i, &v) in vs.iter().enumerate().take(k + 1) {
            if self.outgoing_raw(v).any(|o| self.in_hole_raw(o)) {
                return Err(refuse(OP, path[i], Refusal::Boundary));
            }
        }
        let split: Vec<usize> = if closed {
            (0..k).collect()
        } else {
            (1..k).collect()
        };
        let mut wedges = Vec::with_capacity(split.len());
        for i in split {
            let h = hs[i];
            let stop = hs[(i + k - 1) % k] ^ 1;
            let mut wedge = Vec::new();
            let mut o = self.next_of(h ^ 1);
            for _ in 0..self.he.len() {
                if o == stop {
                    break;
                }
                wedge.push(o);
                o = self.next_of(o ^ 1);
            }
            wedges.push((i, wedge));
        }
        Ok(CutPlan { hs, closed, wedges })
    }

    /// Whether [`cut_path`](Mesh::cut_path) would succeed; changes nothing.
    ///
    /// # Errors
    /// As [`cut_path`](Mesh::cut_path).
    pub fn check_cut_path(&self, path: &[VertexKey]) -> Result<()> {
        self.plan_cut(path).map(|_| ())
    }

    /// Cut the surface open along a path of edges `v_0, v_1, …, v_k`
    /// (consecutive vertices joined by edges). Every path edge becomes two,
    /// one on each side, and every vertex inside the path splits in two
    /// (the copy takes the faces on the right of the path). An open path
    /// makes a slit: one new hole whose ends are `v_0` and `v_k`. A closed
    /// path (`v_k == v_0`) makes two holes, one on each side, and may split
    /// the mesh in two (see [`split_components`](Mesh::split_components)):
    /// Plexus' `split_at_path`.
    ///
    /// ```text
    ///   . --- . --- .         . --- . --- .
    ///   |  L  |  L  |         |  L  |  L  |
    ///   v0 -- v1 -- v2   =>   v0 -- v1 -- v2      (hole between v1 and v1')
    ///   |  R  |  R  |          \    v1'   /
    ///   . --- . --- .         . --- . --- .
    /// ```
    ///
    /// Returns the new holes (one for an open path, two for a closed one,
    /// the left side's first). Attributes: a copy `v_i'` =
    /// `interpolate(v_i: 1)`; each path edge splits into its two copies with
    /// equal shares; a right-side corner keeps its value. χ drops by 1 for an
    /// open path (V + k − 1, E + k) and is unchanged for a closed one.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey);
    /// [`Refusal::Parameter`] for fewer than two edges (three when closed);
    /// [`Refusal::NonManifold`] when the path meets a vertex twice;
    /// [`Refusal::NotAdjacent`] when consecutive vertices are not joined;
    /// [`Refusal::Boundary`] when a path edge or vertex touches a hole (this
    /// version cuts inside the surface only).
    ///
    /// # Complexity
    /// O(Σ degree of the path vertices).
    ///
    /// # Examples
    /// ```
    /// let mut m = meshloom::shapes::icosahedron();
    /// let v: Vec<_> = m.vertices().collect();
    /// // A closed loop round vertex 0: its neighbours in order.
    /// let mut ring: Vec<_> = m.vertex(v[0])?.neighbors().collect();
    /// ring.push(ring[0]);
    /// let holes = m.cut_path(&ring)?;
    /// assert_eq!(holes.len(), 2);
    /// let parts = m.split_components(true);
    /// assert_eq!(parts.len(), 2);
    /// assert_eq!(parts[0].face_count() + parts[1].face_count(), 20);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn cut_path(&mut self, path: &[VertexKey]) -> Result<Vec<FaceKey>> {
        let CutPlan { hs, closed, wedges } = self.plan_cut(path)?;
        let k = hs.len();
        let ts: Vec<u32> = hs.iter().map(|&h| h ^ 1).collect();
        let index_of_t: HashMap<u32, usize> = ts.iter().enumerate().map(|(i, &t)| (t, i)).collect();
        let prevs: Vec<u32> = ts.iter().map(|&t| self.prev_of(t)).collect();
        let nexts: Vec<u32> = ts.iter().map(|&t| self.next_of(t)).collect();
        let rights: Vec<u32> = ts.iter().map(|&t| self.face_of(t)).collect();
        // Vertices: v_i and their right-side copies.
        let vs: Vec<u32> = (0..=k)
            .map(|i| {
                if i < k {
                    self.origin_of(hs[i])
                } else {
                    self.dest_of(hs[k - 1])
                }
            })
            .collect();
        let mut copy: Vec<u32> = vs.clone();
        for (i, _) in &wedges {
            copy[*i] = self.alloc_vertex();
        }
        if closed {
            copy[k] = copy[0];
        }
        let new_edges: Vec<u32> = (0..k).map(|_| self.alloc_edge()).collect();
        let g = |i: usize| 2 * new_edges[i];
        let map = |x: u32| index_of_t.get(&x).map_or(x, |&j| g(j));
        let hole_left = self.alloc_face(true);
        let hole_right = if closed {
            self.alloc_face(true)
        } else {
            hole_left
        };
        // g_i = v'_i+1 -> v'_i takes t_i's place in its right face.
        for i in 0..k {
            self.he[g(i) as usize] = HalfedgeRecord {
                origin: copy[i + 1],
                next: map(nexts[i]),
                face: rights[i],
            };
        }
        for i in 0..k {
            let p = map(prevs[i]);
            self.set_next(p, g(i));
            if self.face_halfedge_raw(rights[i]) == ts[i] {
                self.set_face_link(rights[i], g(i));
            }
        }
        // The holes: t_i run backwards along the left side, gt_i forwards
        // along the right side.
        for i in 0..k {
            let gt = g(i) + 1;
            let next_t = if i > 0 {
                ts[i - 1]
            } else if closed {
                ts[k - 1]
            } else {
                g(0) + 1
            };
            self.he[ts[i] as usize].next = next_t;
            self.he[ts[i] as usize].face = hole_left;
            let next_gt = if i + 1 < k {
                g(i + 1) + 1
            } else if closed {
                g(0) + 1
            } else {
                ts[k - 1]
            };
            self.he[gt as usize] = HalfedgeRecord {
                origin: copy[i],
                next: next_gt,
                face: hole_right,
            };
        }
        self.set_face_link(hole_left, ts[0]);
        if closed {
            self.set_face_link(hole_right, g(0) + 1);
        }
        for (i, wedge) in &wedges {
            for &o in wedge {
                self.he[o as usize].origin = copy[*i];
            }
            self.v_halfedge[copy[*i] as usize] = g(*i) + 1;
        }
        for i in 0..k {
            self.v_halfedge[vs[i] as usize] = hs[i];
        }
        if !closed {
            self.v_halfedge[vs[k] as usize] = ts[k - 1];
        }
        // Attributes.
        for (i, _) in &wedges {
            self.attrs
                .vertex
                .interpolate(copy[*i] as usize, &[(vs[*i] as usize, 1.0)]);
        }
        for i in 0..k {
            let e = (hs[i] >> 1) as usize;
            self.attrs
                .edge
                .split(e, &[(e, 0.5), (new_edges[i] as usize, 0.5)]);
            self.attrs.halfedge.copy(ts[i] as usize, g(i) as usize);
            self.attrs.halfedge.interpolate(g(i) as usize + 1, &[]);
        }
        self.attrs.face.interpolate(hole_left as usize, &[]);
        self.attrs.face.interpolate(hole_right as usize, &[]);
        self.debug_validate();
        let mut out = vec![self.fkey(hole_left)];
        if closed {
            out.push(self.fkey(hole_right));
        }
        Ok(out)
    }
}
