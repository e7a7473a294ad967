//! The remesher's state over the working copy, and its topological
//! passes: split long edges, collapse short ones, flip towards valence 6,
//! remove caps.

use super::reference::Reference;
use super::setup::{same_apex, ResampleColumn, Setup, E_LINE, E_LOCKED};
use super::EdgeLengthStats;
use crate::algo::constraints::{FIXED, FREE, LINE};
use crate::error::Result;
use crate::journal::Unrecorded;
use crate::layout::{Eid, Hid, Vid};
use crate::mesh::Mesh;
use crate::vec3::{cross, dist2, dot, sub, V3};

/// The remesher's state over the working copy.
pub(super) struct Engine {
    pub(super) reference: Reference,
    /// Scratch space for the tree walks.
    pub(super) stack: Vec<u32>,
    pub(super) uniform: Option<f64>,
    /// Per vertex slot.
    pub(super) kind: Vec<u8>,
    pub(super) sizing: Vec<f64>,
    pub(super) hint: Vec<u32>,
    pub(super) line_hint: Vec<u32>,
    /// Per edge slot.
    pub(super) eflags: Vec<u8>,
    /// Scratch, per vertex slot.
    pub(super) update: Vec<V3>,
    pub(super) valence: Vec<u32>,
    pub(super) resample: Vec<ResampleColumn>,
}

impl Engine {
    pub(super) fn new(input: &Mesh, work: &Mesh, setup: Setup) -> Result<Engine> {
        let pos = input.position_slots().unwrap_or(&[]);
        let mut segs = Vec::new();
        for e in input.eids() {
            if setup.edges[e.index()] & E_LINE != 0 {
                let [h, t] = e.halfedges();
                segs.push([pos[input.origin(h).index()], pos[input.origin(t).index()]]);
            }
        }
        let reference = Reference::new(input, &segs, setup.sizing.clone())?;
        let nv = work.slot_counts()[0];
        let mut hint = vec![0u32; nv];
        for v in input.vids() {
            let h = input.vertex_halfedge(v);
            // A vertex on a boundary names a half-edge in a hole: its twin's
            // next leaves v in a face.
            let h = if input.in_hole(h) {
                input.next(h.twin())
            } else {
                h
            };
            let t = reference.tri_of_face[input.face_of(h).index()];
            hint[v.index()] = if t == u32::MAX { 0 } else { t };
        }
        let uniform = setup.uniform.then_some(setup.target_length);
        Ok(Engine {
            reference,
            stack: Vec::new(),
            uniform,
            kind: setup.kinds,
            sizing: setup.sizing,
            hint,
            line_hint: vec![0; nv],
            eflags: setup.edges,
            update: Vec::new(),
            valence: Vec::new(),
            resample: setup.resample,
        })
    }

    /// Grow the per-slot arrays to the mesh's slot counts.
    pub(super) fn fit(&mut self, mesh: &Mesh) {
        let [nv, _, ne, _] = mesh.slot_counts();
        if self.kind.len() < nv {
            self.kind.resize(nv, FREE);
            self.sizing.resize(nv, self.uniform.unwrap_or(0.0));
            self.hint.resize(nv, 0);
            self.line_hint.resize(nv, 0);
        }
        if self.eflags.len() < ne {
            self.eflags.resize(ne, 0);
        }
    }

    #[inline(always)]
    pub(super) fn target(&self, a: Vid, b: Vid) -> f64 {
        match self.uniform {
            Some(l) => l,
            None => self.sizing[a.index()].min(self.sizing[b.index()]),
        }
    }

    /// Split every edge longer than 4/3 of its target, until none is (at
    /// most 10 passes). Returns the splits made.
    pub(super) fn split_long_edges(&mut self, mesh: &mut Mesh) -> usize {
        let mut splits = 0;
        for _ in 0..10 {
            let mut any = false;
            // The edges there are now: one level of splits a pass (edges
            // made by this pass wait for the next, as in pmp-library;
            // splitting the new ones at once can run away).
            for i in 0..mesh.edge_slots() {
                let e = Eid::new(i as u32);
                if !mesh.edge_live(e.index()) || self.eflags[e.index()] & E_LOCKED != 0 {
                    continue;
                }
                let [h, t] = e.halfedges();
                let (a, b) = (mesh.origin(h), mesh.origin(t));
                let pos = positions(mesh);
                let l = self.target(a, b) * (4.0 / 3.0);
                let d = dist2(pos[a.index()], pos[b.index()]);
                // (Not `d <= l²`: a NaN must not split forever.)
                if d.is_nan() || d <= l * l || !d.is_finite() || same_apex(mesh, h) {
                    continue;
                }
                self.split(mesh, e, a, b);
                splits += 1;
                any = true;
            }
            if !any {
                break;
            }
        }
        splits
    }

    /// Split edge `e` (a–b) at its midpoint and the triangles beside it.
    /// The two triangles must not share their apex (see [`same_apex`]).
    pub(super) fn split(&mut self, mesh: &mut Mesh, e: Eid, a: Vid, b: Vid) {
        let [h, t] = e.halfedges();
        let (fh, ft) = (mesh.face_of(h), mesh.face_of(t));
        let (hole_h, hole_t) = (mesh.is_hole(fh), mesh.is_hole(ft));
        let m = mesh.split_edge_unvalidated(e, 0.5);
        // h: m -> b now; n0 = a -> m before it; n1 = m -> a after t.
        let n1 = mesh.next(t);
        let ne = n1.edge();
        let mut spokes = [Eid::NONE; 2];
        if !hole_h {
            let nh = mesh.next(h);
            let c = mesh.next(nh);
            let n0 = mesh.next(c);
            let (x, g) = mesh.split_face_raw::<Unrecorded>(n0, h, nh, c);
            mesh.split_face_values(fh, &[fh, g]);
            spokes[0] = x.edge();
        }
        if !hole_t {
            let nt = mesh.next(n1);
            let d = mesh.next(nt);
            let (x, g) = mesh.split_face_raw::<Unrecorded>(t, n1, nt, d);
            mesh.split_face_values(ft, &[ft, g]);
            spokes[1] = x.edge();
        }
        self.fit(mesh);
        let line = self.eflags[e.index()] & E_LINE;
        self.eflags[ne.index()] = line;
        for s in spokes {
            if !s.is_none() {
                self.eflags[s.index()] = 0;
            }
        }
        let (ia, ib, im) = (a.index(), b.index(), m.index());
        self.kind[im] = if line != 0 { LINE } else { FREE };
        self.sizing[im] = 0.5 * (self.sizing[ia] + self.sizing[ib]);
        self.hint[im] = self.hint[ia];
        self.line_hint[im] = self.line_hint[ia];
    }

    /// Collapse every edge shorter than 4/5 of its target where allowed
    /// (at most 10 passes). Returns the collapses made.
    pub(super) fn collapse_short_edges(&mut self, mesh: &mut Mesh) -> usize {
        let mut collapses = 0;
        for _ in 0..10 {
            let mut any = false;
            for i in 0..mesh.edge_slots() {
                let e = Eid::new(i as u32);
                if !mesh.edge_live(i) || self.eflags[i] & E_LOCKED != 0 {
                    continue;
                }
                let [h0, h1] = e.halfedges();
                let (v0, v1) = (mesh.origin(h0), mesh.origin(h1));
                let pos = positions(mesh);
                let l = self.target(v0, v1) * 0.8;
                if dist2(pos[v0.index()], pos[v1.index()]) >= l * l {
                    continue;
                }
                let c01 = self.may_remove(mesh, h0);
                let c10 = self.may_remove(mesh, h1);
                // The vertex of lower valence goes first; the other way if
                // that would make an edge too long or is refused.
                let order = if c01 && c10 && valence(mesh, v0) >= valence(mesh, v1) {
                    [h1, h0]
                } else {
                    [h0, h1]
                };
                // Two free vertices meet at the midpoint (Botsch and
                // Kobbelt): its new edges are shorter than at either end,
                // so fewer collapses are refused for making an edge too long.
                if c01 && c10 && self.kind[v0.index()] == FREE && self.kind[v1.index()] == FREE {
                    let (p0, p1) = (pos[v0.index()], pos[v1.index()]);
                    let mid = [0, 1, 2].map(|k| 0.5 * (p0[k] + p1[k]));
                    if self.ring_fits(mesh, order[0], mid)
                        && self.ring_fits(mesh, order[0].twin(), mid)
                        && mesh
                            .collapse_unvalidated::<Unrecorded>(order[0], 0.5, None)
                            .is_ok()
                    {
                        collapses += 1;
                        any = true;
                        continue;
                    }
                }
                for h in order {
                    let allowed = if h == h0 { c01 } else { c10 };
                    if allowed
                        && self.short_enough_after(mesh, h)
                        && mesh
                            .collapse_unvalidated::<Unrecorded>(h, 1.0, None)
                            .is_ok()
                    {
                        collapses += 1;
                        any = true;
                        break;
                    }
                }
            }
            if !any {
                break;
            }
        }
        collapses
    }

    /// Whether `origin(h)` may merge into `dest(h)` as far as kinds and
    /// lines go (the operator checks the topology).
    pub(super) fn may_remove(&self, mesh: &Mesh, h: Hid) -> bool {
        let a = mesh.origin(h);
        match self.kind[a.index()] {
            FIXED => false,
            LINE => {
                if self.eflags[h.edge().index()] & E_LINE == 0 {
                    return false;
                }
                // The sides at `a` of the triangles that disappear must not
                // be lines (a line would fold onto itself).
                let t = h.twin();
                let before = mesh.prev_fast(h);
                let after = mesh.next(t);
                let side_line =
                    |x: Hid| !mesh.in_hole(x) && self.eflags[x.edge().index()] & E_LINE != 0;
                (!side_line(before) || mesh.in_hole(h)) && (!side_line(after) || mesh.in_hole(t))
            }
            _ => {
                // A free vertex: off any line, unless the mesh has a
                // boundary it is not told of (never with Slide).
                !mesh.on_boundary(a)
            }
        }
    }

    /// Whether merging `origin(h)` into `dest(h)` keeps every new edge within
    /// 4/3 of its target.
    pub(super) fn short_enough_after(&self, mesh: &Mesh, h: Hid) -> bool {
        let pb = positions(mesh)[mesh.dest(h).index()];
        self.ring_fits(mesh, h, pb)
    }

    /// Whether every neighbour of `origin(h)` but `dest(h)` is within 4/3
    /// of its target (with `dest(h)`) of `pb`: the edges `origin(h)`'s
    /// ring would have after a collapse of `h` to `pb`.
    pub(super) fn ring_fits(&self, mesh: &Mesh, h: Hid, pb: V3) -> bool {
        let (a, b) = (mesh.origin(h), mesh.dest(h));
        let pos = positions(mesh);
        let mut o = mesh.vertex_halfedge(a);
        let start = o;
        loop {
            let w = mesh.dest(o);
            if w != b {
                let l = self.target(b, w) * (4.0 / 3.0);
                if dist2(pb, pos[w.index()]) > l * l {
                    return false;
                }
            }
            o = mesh.next(o.twin());
            if o == start {
                return true;
            }
        }
    }

    /// Flip edges towards valence 6 (4 on a boundary), at most 10 passes.
    pub(super) fn flip_edges(&mut self, mesh: &mut Mesh) -> usize {
        let nv = mesh.slot_counts()[0];
        self.valence.clear();
        self.valence.resize(nv, 0);
        for e in mesh.eids() {
            let [h, t] = e.halfedges();
            self.valence[mesh.origin(h).index()] += 1;
            self.valence[mesh.origin(t).index()] += 1;
        }
        let mut flips = 0;
        for _ in 0..10 {
            let mut any = false;
            for i in 0..mesh.edge_slots() {
                let Some((e, vs)) = self.flip_candidate(mesh, i) else {
                    continue;
                };
                let [a, b, c, d] = vs;
                let target = |v: Vid| if mesh.on_boundary(v) { 4i32 } else { 6 };
                let val = vs.map(|v| self.valence[v.index()] as i32);
                let dev = |delta: [i32; 4]| -> i32 {
                    (0..4)
                        .map(|k| {
                            let x = val[k] + delta[k] - target(vs[k]);
                            x * x
                        })
                        .sum()
                };
                if dev([-1, -1, 1, 1]) >= dev([0; 4]) {
                    continue;
                }
                if !flip_keeps_orientation(positions(mesh), [a, b, c, d]) {
                    continue;
                }
                if mesh.flip_unvalidated(e).is_ok() {
                    self.valence[a.index()] -= 1;
                    self.valence[b.index()] -= 1;
                    self.valence[c.index()] += 1;
                    self.valence[d.index()] += 1;
                    flips += 1;
                    any = true;
                }
            }
            if !any {
                break;
            }
        }
        flips
    }

    /// Edge slot `i` as a flip candidate of [`Self::flip_edges`] and
    /// [`Self::remove_caps`]: a live edge that is no feature or boundary
    /// (no flag), between two triangles, none of whose four vertices is
    /// fixed; with its vertices `[a, b, c, d]` (the edge `a–b`, `c` and `d`
    /// opposite it in the faces of `a → b` and `b → a`).
    pub(super) fn flip_candidate(&self, mesh: &Mesh, i: usize) -> Option<(Eid, [Vid; 4])> {
        if !mesh.edge_live(i) || self.eflags[i] != 0 {
            return None;
        }
        let e = Eid::new(i as u32);
        let [h, t] = e.halfedges();
        if mesh.in_hole(h) || mesh.in_hole(t) {
            return None;
        }
        let (hn, tn) = (mesh.next(h), mesh.next(t));
        if mesh.next(mesh.next(hn)) != h || mesh.next(mesh.next(tn)) != t {
            return None;
        }
        let vs = [mesh.origin(h), mesh.origin(t), mesh.dest(hn), mesh.dest(tn)];
        if vs.iter().any(|v| self.kind[v.index()] == FIXED) {
            return None;
        }
        Some((e, vs))
    }

    /// Flip the edges opposite an angle over 170° where that lowers the
    /// largest angle of the two triangles (pmp-library's `remove_caps`),
    /// one pass. Returns the flips made.
    pub(super) fn remove_caps(&mut self, mesh: &mut Mesh) -> usize {
        self.fit(mesh);
        let mut flips = 0;
        for i in 0..mesh.edge_slots() {
            let Some((e, [a, b, c, d])) = self.flip_candidate(mesh, i) else {
                continue;
            };
            let pos = positions(mesh);
            let p = |v: Vid| pos[v.index()];
            let before =
                largest_angle_cos(p(a), p(b), p(c)).min(largest_angle_cos(p(b), p(a), p(d)));
            if before >= CAP_COS {
                continue;
            }
            let after =
                largest_angle_cos(p(c), p(d), p(b)).min(largest_angle_cos(p(d), p(c), p(a)));
            if after <= before || !flip_keeps_orientation(pos, [a, b, c, d]) {
                continue;
            }
            if mesh.flip_unvalidated(e).is_ok() {
                flips += 1;
            }
        }
        flips
    }

    /// Lengths of the result's edges against their targets.
    pub(super) fn edge_lengths(&self, mesh: &Mesh) -> EdgeLengthStats {
        let pos = positions(mesh);
        let mut s = EdgeLengthStats {
            min: f64::INFINITY,
            max: 0.0,
            mean: 0.0,
            within: 0.0,
        };
        let mut n = 0usize;
        let mut ok = 0usize;
        for e in mesh.eids() {
            let [h, t] = e.halfedges();
            let (a, b) = (mesh.origin(h), mesh.origin(t));
            let l = dist2(pos[a.index()], pos[b.index()]).sqrt();
            let target = match self.uniform {
                Some(l) => l,
                None => 0.5 * (self.sizing[a.index()] + self.sizing[b.index()]),
            };
            s.min = s.min.min(l);
            s.max = s.max.max(l);
            s.mean += l;
            n += 1;
            if l >= 0.8 * target * (1.0 - 1e-9) && l <= target * (4.0 / 3.0) * (1.0 + 1e-9) {
                ok += 1;
            }
        }
        if n == 0 {
            return EdgeLengthStats::default();
        }
        s.mean /= n as f64;
        s.within = ok as f64 / n as f64;
        s
    }
}

/// The position column by vertex slot.
#[inline(always)]
pub(super) fn positions(mesh: &Mesh) -> &[V3] {
    mesh.position_slots().unwrap_or(&[])
}

/// The number of edges at `v`.
pub(super) fn valence(mesh: &Mesh, v: Vid) -> usize {
    mesh.outgoing(v).count()
}

/// The cosine of 170°: an angle over it makes a cap.
pub(super) const CAP_COS: f64 = -0.984_807_753_012_208;

/// The cosine of the largest angle of triangle (a, b, c) (the smallest of
/// its three cosines); 1 for a degenerate one.
pub(super) fn largest_angle_cos(a: V3, b: V3, c: V3) -> f64 {
    let corner = |p: V3, q: V3, r: V3| {
        let (u, v) = (sub(q, p), sub(r, p));
        let l = (dot(u, u) * dot(v, v)).sqrt();
        if l > 0.0 {
            dot(u, v) / l
        } else {
            1.0
        }
    };
    corner(a, b, c).min(corner(b, c, a)).min(corner(c, a, b))
}

/// Whether flipping the edge a–b of triangles (a, b, c) and (b, a, d) to
/// c–d gives two triangles that face the way the two old ones did.
pub(super) fn flip_keeps_orientation(pos: &[V3], [a, b, c, d]: [Vid; 4]) -> bool {
    let p = |v: Vid| pos[v.index()];
    let (pa, pb, pc, pd) = (p(a), p(b), p(c), p(d));
    let n_old = {
        let x = cross(sub(pb, pa), sub(pc, pa));
        let y = cross(sub(pa, pb), sub(pd, pb));
        [x[0] + y[0], x[1] + y[1], x[2] + y[2]]
    };
    // New faces: (c, d, b) and (d, c, a).
    let n1 = cross(sub(pd, pc), sub(pb, pc));
    let n2 = cross(sub(pc, pd), sub(pa, pd));
    dot(n1, n_old) > 0.0 && dot(n2, n_old) > 0.0
}
