//! The supersampled z-buffer: polygon fill, lines, downsampling.

use super::camera::V3;
use super::Image;

/// Sample offset inside a pixel, off the pixel centre by odd amounts so that
/// a sample almost never lies exactly on an edge.
const SAMPLE: [f64; 2] = [0.5 + 1.2345e-4, 0.5 + 3.1416e-4];

/// The supersampled colour and depth buffers.
pub(super) struct Canvas {
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) color: Vec<[u8; 3]>,
    pub(super) depth: Vec<f32>,
    pub(super) depth_range: [f64; 2],
}

impl Canvas {
    pub(super) fn new(width: u32, height: u32, background: [u8; 3]) -> Canvas {
        let n = width as usize * height as usize;
        Canvas {
            width,
            height,
            color: vec![background; n],
            depth: vec![f32::INFINITY; n],
            depth_range: [f64::INFINITY, f64::NEG_INFINITY],
        }
    }

    /// How far behind the surface a line may be and still show: a little
    /// more than a pixel of depth, the depths being in pixel units.
    pub(super) fn depth_bias(&self) -> f64 {
        let span = self.depth_range[1] - self.depth_range[0];
        if span.is_finite() {
            (0.004 * span).max(1.5)
        } else {
            1.5
        }
    }

    /// Fill a polygon by the even-odd rule over the fan from its first
    /// corner. `color_at` gets the corners' barycentric weights at the
    /// sample.
    pub(super) fn fill_polygon(
        &mut self,
        corners: &[u32],
        screen: &[V3],
        mut color_at: impl FnMut(&[(u32, f64); 3]) -> [u8; 3],
    ) {
        if corners.len() < 3 {
            return;
        }
        let pts: Vec<V3> = corners.iter().map(|&v| screen[v as usize]).collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &pts {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let x0 = (lo[0] - SAMPLE[0]).ceil().max(0.0) as i64;
        let y0 = (lo[1] - SAMPLE[1]).ceil().max(0.0) as i64;
        let x1 = ((hi[0] - SAMPLE[0]).floor() as i64).min(i64::from(self.width) - 1);
        let y1 = ((hi[1] - SAMPLE[1]).floor() as i64).min(i64::from(self.height) - 1);
        // Fan triangles with a non-zero screen area.
        let fan: Vec<(usize, f64)> = (1..pts.len() - 1)
            .filter_map(|i| {
                let area = edge(pts[0], pts[i], pts[i + 1]);
                (area != 0.0 && area.is_finite()).then_some((i, area))
            })
            .collect();
        if fan.is_empty() {
            return;
        }
        for y in y0..=y1 {
            for x in x0..=x1 {
                let p = [x as f64 + SAMPLE[0], y as f64 + SAMPLE[1], 0.0];
                let mut hit = None;
                for &(i, area) in &fan {
                    let (a, b, c) = (pts[0], pts[i], pts[i + 1]);
                    let w0 = edge(b, c, p) / area;
                    let w1 = edge(c, a, p) / area;
                    let w2 = edge(a, b, p) / area;
                    if w0 > 0.0 && w1 > 0.0 && w2 > 0.0 {
                        hit = match hit {
                            None => Some((i, [w0, w1, w2])),
                            Some(_) => None,
                        };
                    }
                }
                let Some((i, w)) = hit else { continue };
                let z = w[0] * pts[0][2] + w[1] * pts[i][2] + w[2] * pts[i + 1][2];
                let at = y as usize * self.width as usize + x as usize;
                let z = z as f32;
                if z < self.depth[at] {
                    self.depth[at] = z;
                    self.depth_range = [
                        self.depth_range[0].min(f64::from(z)),
                        self.depth_range[1].max(f64::from(z)),
                    ];
                    let weights = [
                        (corners[0], w[0]),
                        (corners[i], w[1]),
                        (corners[i + 1], w[2]),
                    ];
                    self.color[at] = color_at(&weights);
                }
            }
        }
    }

    /// Draw a line `thickness` samples wide where it is at most `bias`
    /// behind the surface.
    pub(super) fn line(&mut self, a: V3, b: V3, thickness: u32, bias: f64, color: [u8; 3]) {
        let steps = (b[0] - a[0]).abs().max((b[1] - a[1]).abs()).ceil().max(1.0);
        if !steps.is_finite() || steps > 1e7 {
            return;
        }
        let half = (thickness as i64 - 1) / 2;
        for k in 0..=steps as i64 {
            let t = k as f64 / steps;
            let x = (a[0] + t * (b[0] - a[0])).floor() as i64;
            let y = (a[1] + t * (b[1] - a[1])).floor() as i64;
            let z = a[2] + t * (b[2] - a[2]);
            for dy in -half..=(thickness as i64 - 1 - half) {
                for dx in -half..=(thickness as i64 - 1 - half) {
                    let (px, py) = (x + dx, y + dy);
                    if px < 0
                        || py < 0
                        || px >= i64::from(self.width)
                        || py >= i64::from(self.height)
                    {
                        continue;
                    }
                    let at = py as usize * self.width as usize + px as usize;
                    if z <= f64::from(self.depth[at]) + bias {
                        self.color[at] = color;
                    }
                }
            }
        }
    }

    /// Average `s × s` blocks into one pixel.
    pub(super) fn downsample(self, s: u32) -> Image {
        let (w, h) = (self.width / s, self.height / s);
        let mut rgb = Vec::with_capacity(3 * w as usize * h as usize);
        let n = u32::pow(s, 2);
        for y in 0..h {
            for x in 0..w {
                let mut sum = [0u32; 3];
                for sy in 0..s {
                    for sx in 0..s {
                        let at =
                            (y * s + sy) as usize * self.width as usize + (x * s + sx) as usize;
                        for (acc, c) in sum.iter_mut().zip(self.color[at]) {
                            *acc += u32::from(c);
                        }
                    }
                }
                rgb.extend(sum.map(|c| ((c + n / 2) / n) as u8));
            }
        }
        Image {
            width: w,
            height: h,
            rgb,
        }
    }
}

/// Twice the signed area of triangle `a b p` in the screen plane.
fn edge(a: V3, b: V3, p: V3) -> f64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}
