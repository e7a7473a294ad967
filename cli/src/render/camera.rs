//! Vector helpers and the orthographic camera (vertex normals come from
//! `meshloom::algo`).

use super::{RenderError, View};
use meshloom::Mesh;

pub(super) type V3 = [f64; 3];

pub(super) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(super) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(super) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub(super) fn scale(a: V3, k: f64) -> V3 {
    [a[0] * k, a[1] * k, a[2] * k]
}
pub(super) fn normalize(a: V3) -> Option<V3> {
    let len = dot(a, a).sqrt();
    (len > 0.0 && len.is_finite()).then(|| scale(a, 1.0 / len))
}

/// Newell's normal of a polygon: twice its area along the normal, also for
/// non-planar and non-convex polygons.
pub(super) fn newell_normal(corners: impl Iterator<Item = V3> + Clone) -> V3 {
    let next = corners.clone().cycle().skip(1);
    corners.zip(next).fold([0.0; 3], |n, (p, q)| {
        [
            n[0] + (p[1] - q[1]) * (p[2] + q[2]),
            n[1] + (p[2] - q[2]) * (p[0] + q[0]),
            n[2] + (p[0] - q[0]) * (p[1] + q[1]),
        ]
    })
}

/// An orthographic camera: screen axes `right`, `up`, and the direction
/// toward the eye.
pub(super) struct Camera {
    pub(super) right: V3,
    pub(super) up: V3,
    pub(super) toward_eye: V3,
}

impl Camera {
    pub(super) fn new(view: View) -> Result<Camera, RenderError> {
        let (direction, up) = view.camera();
        let bad = || RenderError::View { direction, up };
        let toward_eye = normalize(direction).ok_or_else(bad)?;
        let right = normalize(cross(up, toward_eye)).ok_or_else(bad)?;
        let up = cross(toward_eye, right);
        Ok(Camera {
            right,
            up,
            toward_eye,
        })
    }

    /// A lamp above, left of and behind the eye.
    pub(super) fn light(&self) -> V3 {
        let d = add(
            self.toward_eye,
            add(scale(self.up, 0.5), scale(self.right, -0.3)),
        );
        normalize(d).unwrap_or(self.toward_eye)
    }

    /// Screen position (x right, y down, in pixels) and depth (larger is
    /// farther) of every vertex slot, scaled so the mesh fills the canvas
    /// with a margin.
    pub(super) fn fit(&self, mesh: &Mesh, positions: &[V3], width: u32, height: u32) -> Vec<V3> {
        let project = |p: V3| {
            [
                dot(p, self.right),
                dot(p, self.up),
                -dot(p, self.toward_eye),
            ]
        };
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for v in mesh.vertices() {
            let q = project(positions[v.index()]);
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        let (w, h) = (f64::from(width), f64::from(height));
        let margin = 0.06 * w.min(h);
        let span = [hi[0] - lo[0], hi[1] - lo[1]];
        let fits = [(w - 2.0 * margin) / span[0], (h - 2.0 * margin) / span[1]];
        let k = fits
            .into_iter()
            .filter(|f| f.is_finite())
            .fold(f64::INFINITY, f64::min);
        let k = if k.is_finite() { k } else { 1.0 };
        let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
        positions
            .iter()
            .map(|&p| {
                let q = project(p);
                [
                    w / 2.0 + (q[0] - centre[0]) * k,
                    h / 2.0 - (q[1] - centre[1]) * k,
                    q[2] * k,
                ]
            })
            .collect()
    }
}
