//! The sliding lines of the input as polylines, for the algorithms that
//! move vertices without changing the mesh (smoothing, fairing): each
//! *chain* is a run of line vertices along line edges, between two
//! vertices that stay (its ends), or a closed loop of line vertices. A
//! line vertex slides only on its own chain, so it never passes a corner
//! nor jumps to another line.

use crate::layout::{Eid, Hid, Vid};
use crate::mesh::Mesh;
use crate::vec3::{dot, sub, V3};

/// One chain: `len` points from `start`; open chains begin and end at a
/// vertex that stays.
#[derive(Copy, Clone, Debug)]
struct Chain {
    start: u32,
    len: u32,
    closed: bool,
}

/// The chains through the vertices that slide, with the input's positions.
pub(crate) struct Polylines {
    /// Chain points (input positions), chain after chain.
    points: Vec<V3>,
    /// The vertex of each point.
    verts: Vec<Vid>,
    /// Per point: its chain.
    chain_of: Vec<u32>,
    chains: Vec<Chain>,
    /// Per vertex slot: 1 + its point index for a sliding vertex, else 0.
    at: Vec<u32>,
    /// Per point: the segment (from the chain's start) last projected on.
    hint: Vec<u32>,
}

impl Polylines {
    /// The chains through the vertices of `starts` for which `slides`
    /// holds (each must have exactly two edges where `is_line` holds),
    /// walking along line edges until a vertex that does not slide.
    pub(crate) fn new(
        mesh: &Mesh,
        pos: &[V3],
        starts: impl Iterator<Item = Vid>,
        slides: impl Fn(Vid) -> bool,
        is_line: impl Fn(Eid) -> bool,
    ) -> Polylines {
        let mut out = Polylines {
            points: Vec::new(),
            verts: Vec::new(),
            chain_of: Vec::new(),
            chains: Vec::new(),
            at: vec![0; mesh.slot_counts()[0]],
            hint: Vec::new(),
        };
        for v in starts {
            if out.at[v.index()] != 0 || !slides(v) {
                continue;
            }
            out.walk(mesh, pos, v, &slides, &is_line);
        }
        out.hint = (0..out.points.len() as u32)
            .map(|i| i - out.chains[out.chain_of[i as usize] as usize].start)
            .collect();
        out
    }

    /// The chain through `v` (a vertex that slides, not yet walked).
    fn walk(
        &mut self,
        mesh: &Mesh,
        pos: &[V3],
        v: Vid,
        slides: &impl Fn(Vid) -> bool,
        is_line: &impl Fn(Eid) -> bool,
    ) {
        let Some([back, _]) = line_edges(mesh, v, is_line) else {
            return;
        };
        // Back to where the chain begins: a vertex that stays, or v again.
        let mut h = back;
        let mut budget = mesh.slot_counts()[0];
        let closed = loop {
            let w = mesh.dest(h);
            if w == v {
                break true;
            }
            if !slides(w) || budget == 0 {
                break false;
            }
            budget -= 1;
            match next_line(mesh, w, h, is_line) {
                Some(x) => h = x,
                None => break false,
            }
        };
        // Forward from there: h leaves the first point.
        let first = if closed { v } else { mesh.dest(h) };
        let mut h = if closed { back } else { h.twin() };
        let chain = self.chains.len() as u32;
        let start = self.points.len() as u32;
        let push = |this: &mut Self, w: Vid| {
            this.points.push(pos[w.index()]);
            this.verts.push(w);
            this.chain_of.push(chain);
        };
        push(self, first);
        if slides(first) {
            self.at[first.index()] = self.points.len() as u32;
        }
        let mut budget = mesh.slot_counts()[0];
        loop {
            let w = mesh.dest(h);
            if (closed && w == first) || budget == 0 {
                break;
            }
            budget -= 1;
            push(self, w);
            if !slides(w) {
                break;
            }
            self.at[w.index()] = self.points.len() as u32;
            match next_line(mesh, w, h, is_line) {
                Some(x) => h = x,
                None => break,
            }
        }
        let len = self.points.len() as u32 - start;
        self.chains.push(Chain { start, len, closed });
    }

    /// The segments of chain `c`.
    fn segments(c: &Chain) -> usize {
        if c.closed {
            c.len as usize
        } else {
            c.len as usize - 1
        }
    }

    /// The ends of segment `s` of chain `c`.
    #[inline]
    fn segment(&self, c: &Chain, s: usize) -> (V3, V3) {
        let i = c.start as usize + s;
        let j = if s + 1 == c.len as usize {
            c.start as usize
        } else {
            i + 1
        };
        (self.points[i], self.points[j])
    }

    /// Every sliding vertex's position in `x` (by vertex slot) put on the
    /// closest point of its own chain: a walk along the chain from the
    /// segment last found, while the distance falls.
    pub(crate) fn project_all(&mut self, x: &mut [V3]) {
        for i in 0..self.points.len() {
            let v = self.verts[i].index();
            if self.at[v] as usize == i + 1 {
                x[v] = self.project_point(i, x[v]);
            }
        }
    }

    /// The closest point to `p` on the chain of the sliding vertex at
    /// point `i`.
    fn project_point(&mut self, i: usize, p: V3) -> V3 {
        let c = self.chains[self.chain_of[i] as usize];
        let n = Self::segments(&c);
        if n == 0 {
            return p;
        }
        let step = |s: usize, forward: bool| -> Option<usize> {
            match (forward, c.closed) {
                (true, _) if s + 1 < n => Some(s + 1),
                (true, true) => Some(0),
                (false, _) if s > 0 => Some(s - 1),
                (false, true) => Some(n - 1),
                _ => None,
            }
        };
        let mut s = (self.hint[i] as usize).min(n - 1);
        let (mut best, mut q) = closest(self.segment(&c, s), p);
        for forward in [true, false] {
            let mut moved = 0;
            while let Some(t) = step(s, forward) {
                let (d, x) = closest(self.segment(&c, t), p);
                if d >= best || moved == n {
                    break;
                }
                (best, q, s) = (d, x, t);
                moved += 1;
            }
        }
        self.hint[i] = s as u32;
        q
    }

    /// Every sliding vertex spread evenly by arc length along its chain:
    /// between the chain's ends on an open chain, around it on a closed
    /// one (at the shift that moves them least). Each new position lies
    /// on the chain's polyline.
    pub(crate) fn spread(&self) -> Vec<(Vid, V3)> {
        let mut out = Vec::new();
        let mut arc: Vec<f64> = Vec::new();
        for c in &self.chains {
            let (s, n) = (c.start as usize, c.len as usize);
            let segs = Self::segments(c);
            arc.clear();
            arc.push(0.0);
            for k in 0..segs {
                let (a, b) = self.segment(c, k);
                let d = sub(b, a);
                arc.push(arc[k] + dot(d, d).sqrt());
            }
            let total = arc[segs];
            if !(total > 0.0 && total.is_finite()) {
                continue;
            }
            if c.closed {
                let gap = total / n as f64;
                let shift = (0..n).map(|j| arc[j] - j as f64 * gap).sum::<f64>() / n as f64;
                for j in 0..n {
                    let t = (shift + j as f64 * gap).rem_euclid(total);
                    out.push((self.verts[s + j], self.at_arc(c, &arc, t)));
                }
            } else {
                let gap = total / (n - 1) as f64;
                for j in 1..n - 1 {
                    out.push((self.verts[s + j], self.at_arc(c, &arc, j as f64 * gap)));
                }
            }
        }
        out
    }

    /// The point at arc length `t` along chain `c` (`arc`: the arc length
    /// at each segment's start, and the total last).
    fn at_arc(&self, c: &Chain, arc: &[f64], t: f64) -> V3 {
        let segs = arc.len() - 1;
        let k = arc.partition_point(|&x| x <= t).clamp(1, segs) - 1;
        let (a, b) = self.segment(c, k);
        let l = arc[k + 1] - arc[k];
        let u = if l > 0.0 {
            ((t - arc[k]) / l).clamp(0.0, 1.0)
        } else {
            0.0
        };
        [
            a[0] + u * (b[0] - a[0]),
            a[1] + u * (b[1] - a[1]),
            a[2] + u * (b[2] - a[2]),
        ]
    }
}

/// The squared distance from `p` to segment `(a, b)` and the closest point.
#[inline]
fn closest((a, b): (V3, V3), p: V3) -> (f64, V3) {
    let d = sub(b, a);
    let l = dot(d, d);
    let u = if l > 0.0 {
        (dot(sub(p, a), d) / l).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = [a[0] + u * d[0], a[1] + u * d[1], a[2] + u * d[2]];
    let e = sub(p, q);
    (dot(e, e), q)
}

/// The two outgoing half-edges of `v` along line edges, if it has exactly
/// two.
fn line_edges(mesh: &Mesh, v: Vid, is_line: &impl Fn(Eid) -> bool) -> Option<[Hid; 2]> {
    let mut out = [Hid::NONE; 2];
    let mut n = 0;
    for o in mesh.outgoing(v) {
        if is_line(o.edge()) {
            if n == 2 {
                return None;
            }
            out[n] = o;
            n += 1;
        }
    }
    (n == 2).then_some(out)
}

/// The line half-edge leaving `w` that does not go back along `h` (which
/// arrives at `w`).
fn next_line(mesh: &Mesh, w: Vid, h: Hid, is_line: &impl Fn(Eid) -> bool) -> Option<Hid> {
    let [x, y] = line_edges(mesh, w, is_line)?;
    Some(if x.edge() == h.edge() { y } else { x })
}
