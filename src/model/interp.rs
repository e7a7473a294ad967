//! The tools' interpolation toolkit: values at a point of a face, from the
//! face as it was before the edit (Blender's `BM_loop_interp_from_face`).
//!
//! A [`FaceSnapshot`] keeps a face's corner and vertex slots and its
//! corners projected into its plane (Newell normal). [`FaceSnapshot::weights`]
//! gives mean-value coordinates (Floater; Hormann and Floater's stable
//! form `tan(α/2) = 2A / (r r' + d)`) of a point projected into that plane:
//! exact at a corner, linear along an edge, and reproducing any linear
//! field inside a convex face. Where the weights would be negative (a
//! point outside the face, or in a concave corner's shadow) they are
//! clipped at zero and renormalized, so the stock rules always see a
//! convex combination.

use crate::layout::{Fid, Hid, Vid};
use crate::mesh::Mesh;
use crate::vec3::{self, V3};

/// A face as it was: its corners (half-edge slots, in order), their
/// vertices, and their positions in the face's plane.
pub(crate) struct FaceSnapshot {
    pub(crate) corners: Vec<Hid>,
    pub(crate) vertices: Vec<Vid>,
    points: Vec<[f64; 2]>,
    origin: V3,
    axes: [V3; 2],
}

impl FaceSnapshot {
    /// Face `f` as it is now; `None` without positions or for a face with
    /// no area (no plane).
    pub(crate) fn new(mesh: &Mesh, f: Fid) -> Option<FaceSnapshot> {
        let pos = mesh.position_slots()?;
        let corners: Vec<Hid> = mesh.face_halfedges(f).collect();
        let vertices: Vec<Vid> = corners.iter().map(|&h| mesh.origin(h)).collect();
        let ps: Vec<V3> = vertices.iter().map(|v| pos[v.index()]).collect();
        let n = vec3::normalize(vec3::newell(&ps))?;
        let helper = if n[0].abs() < 0.6 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let u = vec3::normalize(vec3::cross(n, helper))?;
        let axes = [u, vec3::cross(n, u)];
        let origin = ps[0];
        let points = ps.iter().map(|&p| project(p, origin, &axes)).collect();
        Some(FaceSnapshot {
            corners,
            vertices,
            points,
            origin,
            axes,
        })
    }

    /// The weights of the face's corners (by their place in
    /// [`corners`](Self::corners)) at `p` projected into the face's plane:
    /// non-negative, summing to 1.
    pub(crate) fn weights(&self, p: V3) -> Vec<(usize, f64)> {
        let q = project(p, self.origin, &self.axes);
        let n = self.points.len();
        // Per corner: its offset from `q`, its distance, and (later) the
        // half-angle tangent of its wedge towards the next corner.
        let mut c: Vec<([f64; 2], f64, f64)> = self
            .points
            .iter()
            .map(|pt| {
                let d = [pt[0] - q[0], pt[1] - q[1]];
                (d, (d[0] * d[0] + d[1] * d[1]).sqrt(), 0.0)
            })
            .collect();
        let scale = c.iter().fold(0.0f64, |m, x| m.max(x.1));
        if let Some(i) = (0..n).find(|&i| c[i].1 <= 1e-12 * scale) {
            return vec![(i, 1.0)];
        }
        for i in 0..n {
            let j = (i + 1) % n;
            let ((si, ri, _), (sj, rj, _)) = (c[i], c[j]);
            let area2 = si[0] * sj[1] - si[1] * sj[0];
            let denom = ri * rj + si[0] * sj[0] + si[1] * sj[1];
            if denom <= 1e-12 * ri * rj {
                // On edge i–j: linear along it.
                let t = ri / (ri + rj);
                return vec![(i, 1.0 - t), (j, t)];
            }
            c[i].2 = area2 / denom;
        }
        let mut out = Vec::with_capacity(n);
        let mut total = 0.0;
        for i in 0..n {
            let w = ((c[(i + n - 1) % n].2 + c[i].2) / c[i].1).max(0.0);
            if w > 0.0 {
                out.push((i, w));
                total += w;
            }
        }
        if !(total > 0.0 && total.is_finite()) {
            // Nothing usable (a point far outside): the nearest corner.
            let i = (0..n)
                .min_by(|&a, &b| c[a].1.total_cmp(&c[b].1))
                .unwrap_or(0);
            return vec![(i, 1.0)];
        }
        out.iter_mut().for_each(|x| x.1 /= total);
        out
    }
}

/// `p` in the plane through `origin` spanned by `axes`.
fn project(p: V3, origin: V3, axes: &[V3; 2]) -> [f64; 2] {
    let d = vec3::sub(p, origin);
    [vec3::dot(d, axes[0]), vec3::dot(d, axes[1])]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_reproduce_a_linear_field_and_are_exact_at_corners_and_edges() {
        // A convex pentagon in a tilted plane.
        let ring = [[0.0, 0.0], [2.0, 0.0], [2.5, 1.5], [1.0, 2.5], [-0.5, 1.0]];
        let lift = |x: f64, y: f64| [x, y, 0.3 * x - 0.2 * y + 1.0];
        let ps: Vec<V3> = ring.iter().map(|p| lift(p[0], p[1])).collect();
        let mesh = Mesh::from_polygons(&ps, &[vec![0u32, 1, 2, 3, 4]]).unwrap();
        let f = mesh.check_face(mesh.faces().next().unwrap()).unwrap();
        let snap = FaceSnapshot::new(&mesh, f).unwrap();
        let field = |p: V3| 3.0 * p[0] - p[1] + 0.5 * p[2];
        let value_at = |p: V3| {
            let w = snap.weights(p);
            assert!((w.iter().map(|x| x.1).sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(w.iter().all(|x| x.1 >= 0.0));
            w.iter()
                .map(|&(i, x)| x * field(mesh.position_slots().unwrap()[snap.vertices[i].index()]))
                .sum::<f64>()
        };
        for (x, y) in [
            (1.0, 1.0),
            (0.2, 0.1),
            (2.2, 1.0),
            (1.0, 0.0),
            (1.75, 2.0),
            (0.0, 0.0),
        ] {
            let p = lift(x, y);
            assert!((value_at(p) - field(p)).abs() < 1e-12, "({x}, {y})");
        }
        // Off the plane: projected first.
        let normal = vec3::normalize([-0.3, 0.2, 1.0]).unwrap();
        let p = vec3::axpy(lift(1.0, 1.0), 0.7, normal);
        assert!((value_at(p) - field(lift(1.0, 1.0))).abs() < 1e-12);
        // Outside: a convex combination still (clipped).
        let w = snap.weights(lift(5.0, 5.0));
        assert!(
            w.iter().all(|x| x.1 >= 0.0)
                && (w.iter().map(|x| x.1).sum::<f64>() - 1.0).abs() < 1e-12
        );
    }
}
