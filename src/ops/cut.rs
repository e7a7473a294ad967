//! `cut_path`: open a seam along a path of edges into new boundary.

use std::collections::HashMap;

use super::refuse;
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::{EdgeKey, FaceKey, VertexKey};
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::{Mesh, Writer};

struct CutPlan {
    /// Path half-edges `h_i = v_i -> v_i+1`.
    hs: Vec<Hid>,
    closed: bool,
    /// For an open path: the hole half-edge leaving `v_0` (resp. `v_k`)
    /// when that end lies on a boundary.
    hole_out: [Option<Hid>; 2],
    /// Per path vertex index that splits: the outgoing half-edges right of
    /// the path, which move to its copy.
    wedges: Vec<(usize, Vec<Hid>)>,
}

impl Mesh {
    /// The half-edges leaving `origin(from)` clockwise after `from` up to
    /// `stop`, both excluded.
    fn ring_between(&self, from: Hid, stop: Hid) -> Vec<Hid> {
        let mut wedge = Vec::new();
        let mut o = self.next(from.twin());
        for _ in 0..self.he.len() {
            if o == stop {
                break;
            }
            wedge.push(o);
            o = self.next(o.twin());
        }
        wedge
    }

    fn plan_cut(&self, path: &[VertexKey]) -> Result<CutPlan> {
        const OP: &str = "cut_path";
        let mut vs = Vec::with_capacity(path.len());
        for &v in path {
            vs.push(self.check_vertex(v)?);
        }
        let Some(&first) = path.first() else {
            // No vertex to name: generation 0 is never live, so this key
            // names no element.
            return Err(refuse(OP, VertexKey::new(0, 0), Refusal::Empty));
        };
        let closed = vs.len() > 1 && vs[0] == vs[vs.len() - 1];
        let k = vs.len().saturating_sub(1);
        // (O(1) for a vertex no hole touches, by rule 11.)
        let holes_at = |v: Vid| -> Vec<Hid> {
            if self.on_boundary(v) {
                self.outgoing(v).filter(|&o| self.in_hole(o)).collect()
            } else {
                Vec::new()
            }
        };
        let mut hole_out = [None, None];
        if !closed && k >= 1 {
            for (end, &v) in [vs[0], vs[k]].iter().enumerate() {
                match holes_at(v)[..] {
                    [] => {}
                    [o] => hole_out[end] = Some(o),
                    _ => return Err(refuse(OP, path[end * k], Refusal::NonManifold)),
                }
            }
        }
        let min_edges = if closed {
            3
        } else if hole_out == [None, None] {
            2
        } else {
            1
        };
        if k < min_edges {
            return Err(refuse(
                OP,
                first,
                Refusal::Parameter(
                    "the path needs two edges (one from a boundary, three if closed)",
                ),
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
            if self.in_hole(h) || self.in_hole(h.twin()) {
                return Err(refuse(OP, self.ekey(h.edge()), Refusal::Boundary));
            }
            hs.push(h);
        }
        let inner = if closed { 0..k } else { 1..k };
        for i in inner.clone() {
            if self.on_boundary(vs[i]) {
                return Err(refuse(OP, path[i], Refusal::Boundary));
            }
        }
        let mut wedges = Vec::with_capacity(k + 1);
        for i in inner {
            let stop = hs[(i + k - 1) % k].twin();
            wedges.push((i, self.ring_between(hs[i], stop)));
        }
        if let Some(ho) = hole_out[0] {
            wedges.push((0, self.ring_between(hs[0], ho)));
        }
        if let Some(ho) = hole_out[1] {
            // From the hole's half-edge (included) round to twin(h_k-1).
            let mut wedge = vec![ho];
            wedge.extend(self.ring_between(ho, hs[k - 1].twin()));
            wedges.push((k, wedge));
        }
        Ok(CutPlan {
            hs,
            closed,
            hole_out,
            wedges,
        })
    }

    /// Whether [`cut_path`](Mesh::cut_path) would succeed; changes nothing.
    ///
    /// # Errors
    /// As [`cut_path`](Mesh::cut_path).
    pub fn check_cut_path(&self, path: &[VertexKey]) -> Result<()> {
        self.plan_cut(path).map(|_| ())
    }

    /// Cut the surface open along a path of edges `v_0, v_1, …, v_k`
    /// (consecutive vertices joined by edges not on a boundary). Every path
    /// edge becomes two, one on each side, and every path vertex inside the
    /// surface splits in two (the copy takes the faces on the right of the
    /// path); an end on a boundary splits too, and the cut joins that hole.
    ///
    /// - An open path between interior vertices makes a slit: a new hole.
    /// - An open path from a boundary opens that hole further; from
    ///   boundary to boundary it joins two holes, or, when both ends are on
    ///   the same hole, cuts the mesh apart (or through a handle): Plexus'
    ///   `split_at_path`, then [`split_components`](Mesh::split_components).
    /// - A closed path (`v_k == v_0`) makes two holes, one on each side.
    ///
    /// ```text
    ///   . --- . --- .         . --- . --- .
    ///   |  L  |  L  |         |  L  |  L  |
    ///   v0 -- v1 -- v2   =>   v0 -- v1 -- v2      (hole between v1 and v1')
    ///   |  R  |  R  |          \    v1'   /
    ///   . --- . --- .         . --- . --- .
    /// ```
    ///
    /// Returns the holes along the cut: the one on the left side first, and
    /// a second one when the cut made two loops. Attributes: a copy `v_i'` =
    /// `interpolate(v_i: 1)`; each path edge splits into its two copies with
    /// equal shares; a right-side corner keeps its value. χ changes by
    /// (vertices split) − k: −1 for a slit, 0 from one boundary or for a
    /// closed path, +1 from boundary to boundary.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey);
    /// [`Refusal::Parameter`] for too short a path (two edges between
    /// interior vertices, one from a boundary, three when closed);
    /// [`Refusal::NonManifold`] when the path meets a vertex twice or an end
    /// is a vertex where several holes meet; [`Refusal::NotAdjacent`] when
    /// consecutive vertices are not joined; [`Refusal::Boundary`] when a path
    /// edge lies on a boundary or an inner path vertex touches a hole.
    ///
    /// # Complexity
    /// O(Σ degree of the path vertices + degree of the holes joined).
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
        journaled!(self.cut_path_with(path)).map(|made| made.holes)
    }

    /// [`cut_path`](Mesh::cut_path), returning everything it made.
    pub(crate) fn cut_path_made(&mut self, path: &[VertexKey]) -> Result<CutMade> {
        journaled!(self.cut_path_with(path))
    }

    /// What the cut reads before it changes anything: the twins of the path
    /// half-edges and their neighbours, the holes at its ends, its vertices.
    fn read_cut(&self, plan: CutPlan) -> Cut {
        let hs = &plan.hs;
        let k = hs.len();
        let ts: Vec<Hid> = hs.iter().map(|&h| h.twin()).collect();
        let index_of_t = ts.iter().enumerate().map(|(i, &t)| (t, i)).collect();
        let prevs = ts.iter().map(|&t| self.prev(t)).collect();
        let nexts = ts.iter().map(|&t| self.next(t)).collect();
        let rights = ts.iter().map(|&t| self.face_of(t)).collect();
        // The hole half-edges entering the boundary ends, and their holes.
        let hole_in = plan.hole_out.map(|o| o.map(|o| self.prev(o)));
        let old_holes = plan.hole_out.map(|o| o.map(|o| self.face_of(o)));
        let vs: Vec<Vid> = (0..=k)
            .map(|i| {
                if i < k {
                    self.origin(hs[i])
                } else {
                    self.dest(hs[k - 1])
                }
            })
            .collect();
        Cut {
            copy: vs.clone(),
            vs,
            ts,
            index_of_t,
            prevs,
            nexts,
            rights,
            hole_in,
            old_holes,
            new_edges: Vec::new(),
            plan,
        }
    }

    /// Attributes: copies interpolate their vertex, each path edge splits
    /// into its two copies, right-side corners keep their values, new holes
    /// interpolate nothing.
    fn cut_attributes(&mut self, cut: &Cut, made: &[Fid], spare: &[Fid]) {
        for (i, _) in &cut.plan.wedges {
            self.attrs
                .vertex
                .interpolate(cut.copy[*i].index(), &[(cut.vs[*i].index(), 1.0)]);
        }
        for i in 0..cut.ts.len() {
            let e = cut.plan.hs[i].edge().index();
            self.attrs
                .edge
                .split(e, &[(e, 0.5), (cut.new_edges[i].index(), 0.5)]);
            self.attrs
                .halfedge
                .copy(cut.ts[i].index(), cut.g(i).index());
            self.attrs.halfedge.interpolate(cut.gt(i).index(), &[]);
        }
        for &h in made {
            if !spare.contains(&h) {
                self.attrs.face.interpolate(h.index(), &[]);
            }
        }
    }
}

/// What a cut made: the holes along it (left side first), the vertex
/// copies (right side) and the edge copies (right side, in path order).
pub(crate) struct CutMade {
    pub(crate) holes: Vec<FaceKey>,
    pub(crate) vertices: Vec<VertexKey>,
    pub(crate) edges: Vec<EdgeKey>,
}

/// A planned cut with what it read before editing and the elements it adds.
struct Cut {
    plan: CutPlan,
    /// The twins `t_i` of the path half-edges, and where each is in `ts`.
    ts: Vec<Hid>,
    index_of_t: HashMap<Hid, usize>,
    /// The half-edges before and after each `t_i`, and its face.
    prevs: Vec<Hid>,
    nexts: Vec<Hid>,
    rights: Vec<Fid>,
    /// The hole half-edges entering the boundary ends, and their holes.
    hole_in: [Option<Hid>; 2],
    old_holes: [Option<Fid>; 2],
    /// The path vertices `v_i`, and their right-side copies (the vertex
    /// itself where it does not split).
    vs: Vec<Vid>,
    copy: Vec<Vid>,
    /// One new edge per path edge.
    new_edges: Vec<Eid>,
}

impl Cut {
    /// `g_i = v'_i+1 -> v'_i`, on the right side.
    fn g(&self, i: usize) -> Hid {
        self.new_edges[i].halfedge(0)
    }

    /// `g_i`'s twin, on the new boundary.
    fn gt(&self, i: usize) -> Hid {
        self.new_edges[i].halfedge(1)
    }

    /// `x`, or `g_i` where `x` is `t_i` (which `g_i` replaces).
    fn map(&self, x: Hid) -> Hid {
        self.index_of_t.get(&x).map_or(x, |&j| self.g(j))
    }
}

impl Mesh {
    /// [`cut_path`](Mesh::cut_path)'s body, in journaling mode `J`.
    fn cut_path_with<J: Journaling>(&mut self, path: &[VertexKey]) -> Result<CutMade> {
        let mut w = self.writer::<J>();
        let plan = w.plan_cut(path)?;
        let mut cut = w.read_cut(plan);
        // Vertices: v_i and their right-side copies.
        for (i, _) in &cut.plan.wedges {
            cut.copy[*i] = w.alloc_vertex();
        }
        if cut.plan.closed {
            let k = cut.plan.hs.len();
            cut.copy[k] = cut.copy[0];
        }
        cut.new_edges = (0..cut.plan.hs.len()).map(|_| w.alloc_edge()).collect();
        w.link_cut_right(&cut);
        w.link_cut_boundary(&cut);
        w.move_cut_wedges(&cut);
        let (made, spare) = w.label_cut_holes(&cut);
        w.cut_attributes(&cut, &made, &spare);
        w.end_op();
        Ok(CutMade {
            holes: made.into_iter().map(|h| w.fkey(h)).collect(),
            vertices: cut
                .plan
                .wedges
                .iter()
                .map(|(i, _)| w.vkey(cut.copy[*i]))
                .collect(),
            edges: cut.new_edges.iter().map(|&e| w.ekey(e)).collect(),
        })
    }
}

impl<J: Journaling> Writer<'_, J> {
    /// `g_i = v'_i+1 -> v'_i` takes `t_i`'s place in its right face.
    fn link_cut_right(&mut self, cut: &Cut) {
        let k = cut.ts.len();
        for i in 0..k {
            *self.he_mut(cut.g(i)) = HalfedgeRecord {
                origin: cut.copy[i + 1],
                next: cut.map(cut.nexts[i]),
                face: cut.rights[i],
            };
        }
        for i in 0..k {
            let p = cut.map(cut.prevs[i]);
            self.set_next(p, cut.g(i));
            if self.face_halfedge(cut.rights[i]) == cut.ts[i] {
                self.set_face_link(cut.rights[i], cut.g(i));
            }
        }
    }

    /// The new boundary: `t_i` run backwards along the left side, `gt_i`
    /// (the twin of `g_i`) forwards along the right side; at a boundary end
    /// they join the hole that was there.
    fn link_cut_boundary(&mut self, cut: &Cut) {
        let (ts, closed, hole_out) = (&cut.ts, cut.plan.closed, cut.plan.hole_out);
        let k = ts.len();
        for i in 0..k {
            let next_t = if i > 0 {
                ts[i - 1]
            } else if closed {
                ts[k - 1]
            } else {
                hole_out[0].unwrap_or(cut.gt(0))
            };
            self.he_mut(ts[i]).next = next_t;
            let next_gt = if i + 1 < k {
                cut.gt(i + 1)
            } else if closed {
                cut.gt(0)
            } else {
                hole_out[1].unwrap_or(ts[k - 1])
            };
            // The face is set when the new loops are labelled.
            *self.he_mut(cut.gt(i)) = HalfedgeRecord {
                origin: cut.copy[i],
                next: next_gt,
                face: Fid::NONE,
            };
        }
        if let Some(hi) = cut.hole_in[0] {
            self.set_next(hi, cut.gt(0));
        }
        if let Some(hi) = cut.hole_in[1] {
            self.set_next(hi, ts[k - 1]);
        }
    }

    /// The half-edges right of the path leave the copies; every path
    /// vertex and copy names a half-edge it still has.
    fn move_cut_wedges(&mut self, cut: &Cut) {
        let k = cut.ts.len();
        for (i, wedge) in &cut.plan.wedges {
            for &o in wedge {
                self.he_mut(o).origin = cut.copy[*i];
            }
            let out = if *i < k { cut.gt(*i) } else { wedge[0] };
            *self.v_halfedge_mut(cut.copy[*i]) = out;
        }
        for i in 0..k {
            *self.v_halfedge_mut(cut.vs[i]) = cut.plan.hs[i];
        }
        if !cut.plan.closed {
            *self.v_halfedge_mut(cut.vs[k]) = cut.ts[k - 1];
        }
    }

    /// Hole faces: the loop through `t_0`, then the one through `gt_0` if it
    /// is another loop. Old holes are reused, one left over is freed.
    /// Returns the holes made and the old ones.
    fn label_cut_holes(&mut self, cut: &Cut) -> (Vec<Fid>, Vec<Fid>) {
        let mut spare: Vec<Fid> = cut.old_holes.iter().flatten().copied().collect();
        spare.dedup();
        let mut made = Vec::new();
        let first = spare
            .first()
            .copied()
            .unwrap_or_else(|| self.alloc_face(true));
        self.he_mut(cut.ts[0]).face = Fid::NONE;
        self.relabel_loop(cut.ts[0], first);
        made.push(first);
        if self.face_of(cut.gt(0)) != first {
            let second = if spare.len() > 1 {
                spare[1]
            } else {
                self.alloc_face(true)
            };
            self.relabel_loop(cut.gt(0), second);
            made.push(second);
        } else if spare.len() > 1 {
            self.free_face(spare[1]);
        }
        (made, spare)
    }
}
