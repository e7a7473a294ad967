//! The attribute part of the error (Hoppe 1999): per face, the linear
//! function `s(x) = g·x + d` that takes each named column's corner values
//! at the corners; per vertex, the sums over its faces of `area·g`,
//! `area·d`, `area` and the quadric `area·(g·x + d)²`, so that
//! `Σ area·(s − s_f(x))²` over the faces merged into a vertex is
//! `A s² − 2 s (G·x + D) + X(x)`. A collapse is scored at its new position
//! with the value the column's rule will give there (interpolation at the
//! projection), divided by the area: the area-weighted mean squared
//! deviation, times the column's weight squared.
//!
//! Corner columns use the corners of the face left of the collapsing
//! half-edge (right, if left is a hole). A vertex on a seam has one
//! attribute quadric for both sides; its collapses are limited to the
//! seam, where each side interpolates its own values, so this only
//! overestimates its cost.

use super::quadric::{Quadric, Q64};
use super::{AttributeWeight, ALGORITHM};
use crate::attr::Value;
use crate::error::{Error, Result};
use crate::keys::ElementKind;
use crate::layout::{Hid, Vid};
use crate::mesh::Mesh;
use crate::vec3::{cross, dot, sub, V3};

/// One column in the error.
struct Column {
    corner: bool,
    /// Its index in its arena's column list (no column is added or removed
    /// while the decimator runs).
    index: usize,
    dims: usize,
    weight: f32,
    /// Current values, scaled by the weight, `dims` per slot.
    values: Vec<f32>,
    /// Per vertex slot, per dim: `G` (3) and `D`.
    grads: Vec<f32>,
}

/// The attribute error of every named column.
pub(super) struct AttrError {
    cols: Vec<Column>,
    /// Per vertex slot: the summed area.
    area: Vec<f32>,
    /// Per vertex slot: the position part `X(x)`, all columns summed.
    xq: Vec<Quadric>,
}

fn unsuitable(reason: String) -> Error {
    Error::Unsuitable {
        algorithm: ALGORITHM,
        key: None,
        reason,
    }
}

/// A value as floats, if it is a float or a list of floats.
fn floats(v: &Value, out: &mut Vec<f64>) -> bool {
    match v {
        Value::F32(x) => out.push(f64::from(*x)),
        Value::F64(x) => out.push(*x),
        Value::List(items) => {
            for item in items {
                match item {
                    Value::F32(x) => out.push(f64::from(*x)),
                    Value::F64(x) => out.push(*x),
                    _ => return false,
                }
            }
        }
        _ => return false,
    }
    true
}

impl Column {
    /// Read slot `i` into `values` (scaled); absent values read as zeros.
    fn refresh(&mut self, mesh: &Mesh, i: usize, scratch: &mut Vec<f64>) {
        let weight = self.weight;
        let arena = if self.corner {
            &mesh.attrs().halfedge
        } else {
            &mesh.attrs().vertex
        };
        scratch.clear();
        let ok = arena.cols[self.index]
            .1
            .value_at(i)
            .is_some_and(|v| floats(&v, scratch))
            && scratch.len() == self.dims;
        let dst = &mut self.values[i * self.dims..(i + 1) * self.dims];
        for (k, d) in dst.iter_mut().enumerate() {
            *d = if ok {
                (scratch[k] as f32) * weight
            } else {
                0.0
            };
        }
    }
}

impl AttrError {
    /// Columns by name (vertex first, then corner), checked: floats of one
    /// dimension throughout.
    pub(super) fn new(
        mesh: &Mesh,
        weights: &[AttributeWeight],
        unit: &dyn Fn(V3) -> V3,
    ) -> Result<Option<AttrError>> {
        if weights.is_empty() {
            return Ok(None);
        }
        let [nv, nh, _, _] = mesh.slot_counts();
        let mut cols = Vec::new();
        let mut scratch = Vec::new();
        for aw in weights {
            if !(aw.weight.is_finite() && aw.weight >= 0.0) {
                return Err(unsuitable(format!(
                    "the weight {} of attribute {:?} is not a finite number ≥ 0",
                    aw.weight, aw.name
                )));
            }
            let (corner, index) = match mesh.attrs().vertex.find(&aw.name) {
                Some(i) => (false, i),
                None => match mesh.attrs().halfedge.find(&aw.name) {
                    Some(i) => (true, i),
                    None => {
                        return Err(Error::AttributeMissing {
                            kind: ElementKind::Vertex,
                            name: aw.name.clone(),
                        })
                    }
                },
            };
            let arena = if corner {
                &mesh.attrs().halfedge
            } else {
                &mesh.attrs().vertex
            };
            let col = &arena.cols[index].1;
            // The dimension, from the first value present.
            let slots = if corner { nh } else { nv };
            let mut dims = None;
            for i in 0..slots {
                if let Some(v) = col.value_at(i) {
                    scratch.clear();
                    if !floats(&v, &mut scratch) {
                        return Err(unsuitable(format!(
                            "attribute {:?} holds {}, not floats: it cannot take part in the error",
                            aw.name,
                            col.type_name()
                        )));
                    }
                    dims = Some(scratch.len());
                    break;
                }
            }
            let dims = dims.unwrap_or(0);
            if dims == 0 {
                continue;
            }
            let mut c = Column {
                corner,
                index,
                dims,
                weight: aw.weight as f32,
                values: vec![0.0; slots * dims],
                grads: vec![0.0; nv * dims * 4],
            };
            let live: Vec<usize> = if corner {
                mesh.hids().map(Hid::index).collect()
            } else {
                mesh.vids().map(Vid::index).collect()
            };
            for i in live {
                c.refresh(mesh, i, &mut scratch);
            }
            cols.push(c);
        }
        let mut at = AttrError {
            cols,
            area: vec![0.0; nv],
            xq: vec![Quadric::default(); nv],
        };
        at.fill(mesh, unit);
        Ok(Some(at))
    }

    /// Accumulate every face's attribute planes into its vertices.
    fn fill(&mut self, mesh: &Mesh, unit: &dyn Fn(V3) -> V3) {
        let Some(pos) = mesh.position_slots() else {
            return;
        };
        for f in mesh.fids() {
            if mesh.is_hole(f) {
                continue;
            }
            let h0 = mesh.face_halfedge(f);
            let h1 = mesh.next(h0);
            let h2 = mesh.next(h1);
            let hs = [h0, h1, h2];
            let vs = hs.map(|h| mesh.origin(h));
            let p = vs.map(|v| unit(pos[v.index()]));
            let e1 = sub(p[1], p[0]);
            let e2 = sub(p[2], p[0]);
            let (g11, g12, g22) = (dot(e1, e1), dot(e1, e2), dot(e2, e2));
            let det = g11 * g22 - g12 * g12;
            let n = cross(e1, e2);
            let area = 0.5 * dot(n, n).sqrt();
            if det.is_nan() || det <= 1e-30 || area.is_nan() || area <= 0.0 {
                continue;
            }
            let mut xq = Q64::default();
            for c in &mut self.cols {
                for k in 0..c.dims {
                    let s: [f64; 3] = std::array::from_fn(|j| {
                        let slot = if c.corner {
                            hs[j].index()
                        } else {
                            vs[j].index()
                        };
                        f64::from(c.values[slot * c.dims + k])
                    });
                    let (d1, d2) = (s[1] - s[0], s[2] - s[0]);
                    let alpha = (d1 * g22 - d2 * g12) / det;
                    let beta = (d2 * g11 - d1 * g12) / det;
                    let g: V3 = std::array::from_fn(|i| alpha * e1[i] + beta * e2[i]);
                    let d = s[0] - dot(g, p[0]);
                    // area (g·x + d)²: the plane quadric of (g, d) with the
                    // normal unnormalised.
                    let gg = [
                        g[0] * g[0],
                        g[1] * g[1],
                        g[2] * g[2],
                        g[0] * g[1],
                        g[0] * g[2],
                        g[1] * g[2],
                        g[0] * d,
                        g[1] * d,
                        g[2] * d,
                        d * d,
                    ];
                    xq = xq.sum(Q64(gg.map(|x| x * area)));
                    for v in vs {
                        let o = (v.index() * c.dims + k) * 4;
                        for (dst, gi) in c.grads[o..o + 3].iter_mut().zip(g) {
                            *dst += (area * gi) as f32;
                        }
                        c.grads[o + 3] += (area * d) as f32;
                    }
                }
            }
            let xq = xq.narrow();
            for v in vs {
                self.area[v.index()] += area as f32;
                self.xq[v.index()].add_assign(&xq);
            }
        }
    }

    /// The attribute cost of collapsing `h` (origin into dest) to `x` (unit
    /// box) at weight `t`.
    pub(super) fn cost(&self, mesh: &Mesh, h: Hid, x: V3, t: f64) -> f64 {
        let a = mesh.origin(h).index();
        let b = mesh.origin(h.twin()).index();
        let area = f64::from(self.area[a]) + f64::from(self.area[b]);
        if area.is_nan() || area <= 0.0 {
            return 0.0;
        }
        let mut e = self.xq[a].wide().sum(self.xq[b].wide()).eval_signed(x);
        // The corners beside the edge: the left face's, else the right's.
        let (ca, cb) = if mesh.in_hole(h) {
            (mesh.next(h.twin()), h.twin())
        } else {
            (h, mesh.next(h))
        };
        for c in &self.cols {
            let (sa, sb) = if c.corner {
                (ca.index(), cb.index())
            } else {
                (a, b)
            };
            for k in 0..c.dims {
                let s = (1.0 - t) * f64::from(c.values[sa * c.dims + k])
                    + t * f64::from(c.values[sb * c.dims + k]);
                let mut lin = 0.0;
                for v in [a, b] {
                    let o = (v * c.dims + k) * 4;
                    let g = &c.grads[o..o + 4];
                    lin += f64::from(g[0]) * x[0]
                        + f64::from(g[1]) * x[1]
                        + f64::from(g[2]) * x[2]
                        + f64::from(g[3]);
                }
                e += area * s * s - 2.0 * s * lin;
            }
        }
        e.max(0.0) / area
    }

    /// After `a` merged into `b`: sum the quadrics, read `b`'s new values.
    pub(super) fn after_collapse(&mut self, mesh: &Mesh, a: Vid, b: Vid) {
        let (a, b) = (a.index(), b.index());
        self.area[b] += self.area[a];
        let xa = self.xq[a];
        self.xq[b].add_assign(&xa);
        let mut scratch = Vec::new();
        for c in &mut self.cols {
            let n = c.dims * 4;
            for k in 0..n {
                let x = c.grads[a * n + k];
                c.grads[b * n + k] += x;
            }
            if c.corner {
                for h in mesh.outgoing(Vid::new(b as u32)) {
                    c.refresh(mesh, h.index(), &mut scratch);
                }
            } else {
                c.refresh(mesh, b, &mut scratch);
            }
        }
    }
}
