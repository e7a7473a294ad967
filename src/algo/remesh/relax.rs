//! Relaxation in the tangent plane (or along a line) and projection back
//! onto the input surface.

use super::engine::{positions, Engine};
use super::setup::E_LINE;
use crate::algo::constraints::{FIXED, FREE, LINE};
use crate::layout::Vid;
use crate::mesh::Mesh;
use crate::vec3::{cross, dist2, dot, sub, V3};

impl Engine {
    /// One Jacobi step of tangential relaxation.
    pub(super) fn relax(&mut self, mesh: &mut Mesh) {
        let nv = mesh.slot_counts()[0];
        self.fit(mesh);
        self.update.clear();
        self.update.resize(nv, [0.0; 3]);
        {
            let pos = positions(mesh);
            for i in 0..nv {
                let kind = self.kind[i];
                if kind == FIXED || !mesh.vertex_live(i) {
                    continue;
                }
                let v = Vid::new(i as u32);
                self.update[i] = if kind == LINE {
                    self.line_step(mesh, pos, v)
                } else {
                    self.surface_step(mesh, pos, v)
                };
            }
        }
        let Some(pos) = mesh.position_slots_mut() else {
            return;
        };
        for (i, u) in self.update.iter().enumerate() {
            if u[0] != 0.0 || u[1] != 0.0 || u[2] != 0.0 {
                let p = &mut pos[i];
                p[0] += u[0];
                p[1] += u[1];
                p[2] += u[2];
            }
        }
    }

    /// A free vertex's move: towards the area-weighted centroid of its
    /// triangles (weights divided by the squared target length when
    /// adaptive), in its tangent plane.
    #[inline]
    pub(super) fn surface_step(&self, mesh: &Mesh, pos: &[V3], v: Vid) -> V3 {
        let p = pos[v.index()];
        let mut n = [0.0; 3];
        let mut c = [0.0; 3];
        let mut ww = 0.0;
        let start = mesh.vertex_halfedge(v);
        let mut o = start;
        loop {
            let r = mesh.halfedge_record(o);
            let tw = mesh.halfedge_record(o.twin());
            if !mesh.is_hole(r.face) {
                let w1 = tw.origin;
                let w2 = mesh.origin(mesh.next(r.next));
                let (p1, p2) = (pos[w1.index()], pos[w2.index()]);
                let x = cross(sub(p1, p), sub(p2, p));
                let mut area = dot(x, x).sqrt();
                if area == 0.0 {
                    area = 1e-300;
                }
                if self.uniform.is_none() {
                    let s = (self.sizing[v.index()]
                        + self.sizing[w1.index()]
                        + self.sizing[w2.index()])
                        / 3.0;
                    if s > 0.0 {
                        area /= s * s;
                    }
                }
                for k in 0..3 {
                    n[k] += x[k];
                    c[k] += area * (p[k] + p1[k] + p2[k]);
                }
                ww += area;
            }
            o = tw.next;
            if o == start {
                break;
            }
        }
        if ww <= 0.0 {
            return [0.0; 3];
        }
        let s = 1.0 / (3.0 * ww);
        let mut u = [c[0] * s - p[0], c[1] * s - p[1], c[2] * s - p[2]];
        let nn = dot(n, n);
        if nn > 0.0 {
            let k = dot(u, n) / nn;
            for i in 0..3 {
                u[i] -= k * n[i];
            }
        }
        if u.iter().all(|x| x.is_finite()) {
            u
        } else {
            [0.0; 3]
        }
    }

    /// A line vertex's move: towards the weighted mean of its two line
    /// edges' midpoints, along the line.
    pub(super) fn line_step(&self, mesh: &Mesh, pos: &[V3], v: Vid) -> V3 {
        let p = pos[v.index()];
        let mut ends = [Vid::NONE; 2];
        let mut n = 0;
        for o in mesh.outgoing(v) {
            if self.eflags[o.edge().index()] & E_LINE != 0 {
                if n == 2 {
                    return [0.0; 3];
                }
                ends[n] = mesh.dest(o);
                n += 1;
            }
        }
        if n != 2 {
            return [0.0; 3];
        }
        let mut u = [0.0; 3];
        let mut ww = 0.0;
        let mut t = [0.0; 3];
        for (k, w) in ends.into_iter().enumerate() {
            let q = pos[w.index()];
            let l = dist2(p, q).sqrt();
            let s = 0.5 * (self.sizing[v.index()] + self.sizing[w.index()]);
            let weight = if s > 0.0 { l / s } else { l };
            for i in 0..3 {
                u[i] += weight * 0.5 * (p[i] + q[i]);
            }
            ww += weight;
            if l > 0.0 {
                let sign = if k == 0 { 1.0 } else { -1.0 };
                for i in 0..3 {
                    t[i] += sign * (q[i] - p[i]) / l;
                }
            }
        }
        let tt = dot(t, t);
        if ww <= 0.0 || tt <= 0.0 {
            return [0.0; 3];
        }
        let d = [u[0] / ww - p[0], u[1] / ww - p[1], u[2] / ww - p[2]];
        let k = dot(d, t) / tt;
        let out = [k * t[0], k * t[1], k * t[2]];
        if out.iter().all(|x| x.is_finite()) {
            out
        } else {
            [0.0; 3]
        }
    }

    /// Move every free vertex to its closest point on the input triangles
    /// and every line vertex to its closest point on the input's lines.
    pub(super) fn project(&mut self, mesh: &mut Mesh) {
        self.fit(mesh);
        let nv = mesh.slot_counts()[0];
        let adaptive = self.uniform.is_none();
        let reference = &self.reference;
        let stack = &mut self.stack;
        let (live, attrs) = mesh.vertex_arena_and_attrs_mut();
        let Some(pos) = attrs.positions_mut().map(|c| c.raw_mut()) else {
            return;
        };
        for (i, p) in pos.iter_mut().enumerate().take(nv) {
            if self.kind[i] == FIXED || !live.is_live(i) {
                continue;
            }
            match self.kind[i] {
                FREE => {
                    if let Some(near) = reference.tree.closest_near(*p, Some(self.hint[i]), stack) {
                        *p = near.point;
                        self.hint[i] = near.tri;
                        if adaptive {
                            self.sizing[i] = reference.interpolate_sizing(near.tri, near.weights);
                        }
                    }
                }
                LINE => {
                    if let Some(near) = reference.lines.closest(*p, Some(self.line_hint[i]), stack)
                    {
                        *p = near.point;
                        self.line_hint[i] = near.seg;
                    }
                }
                _ => {}
            }
        }
    }
}
