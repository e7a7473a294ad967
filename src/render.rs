//! A small software renderer: shaded orthographic pictures of a mesh as PNG.
//!
//! No GPU and no window: [`render`] projects the mesh orthographically along a
//! [`View`], fills every face into a z-buffer with Lambert shading (flat, or
//! smooth from area-weighted vertex normals), optionally draws the edges and
//! highlights the boundary, and hands back an [`Image`] that
//! [`Image::write_png`] saves.
//!
//! - Faces of any degree are filled with the even-odd rule over a fan of
//!   triangles, so non-convex planar polygons come out right.
//! - Both sides are lit; the back side of a face (seen through a hole of an
//!   open mesh) has its own colour.
//! - Each pixel averages `supersample²` samples, which smooths edges.
//!
//! ```
//! use meshloom::render::{render, RenderOptions, View};
//! let mesh = meshloom::shapes::cube();
//! let options = RenderOptions { width: 64, height: 48, view: View::Iso, ..RenderOptions::default() };
//! let image = render(&mesh, &options)?;
//! assert_eq!((image.width(), image.height()), (64, 48));
//! assert_ne!(image.pixel(32, 24), Some(options.colors.background)); // the cube is in the middle
//! assert_eq!(image.pixel(0, 0), Some(options.colors.background));
//! # Ok::<(), meshloom::render::RenderError>(())
//! ```

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use crate::mesh::Mesh;

/// Why a picture could not be made or saved.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// Occurs when the mesh has no faces.
    #[error("the mesh has no faces to render")]
    Empty,
    /// Occurs when the mesh is topology-only (built without positions).
    #[error("the mesh has no vertex positions to render")]
    NoPositions,
    /// Occurs when the image size or supersampling is out of range.
    #[error("image size {width}x{height} with supersampling {supersample} is out of range (sides 1 to {MAX_SIDE} pixels, supersampling 1 to 4, at most {MAX_SAMPLES} samples)")]
    Size {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
        /// Requested supersampling.
        supersample: u32,
    },
    /// Occurs when a view direction is zero or not finite, or parallel to
    /// the up direction.
    #[error("view direction {direction:?} with up {up:?} does not define a camera (zero, non-finite or parallel)")]
    View {
        /// The direction toward the eye.
        direction: [f64; 3],
        /// The up direction.
        up: [f64; 3],
    },
    /// Occurs when the PNG file cannot be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Occurs when the PNG encoder fails.
    #[error("PNG encoding failed: {0}")]
    Png(String),
}

/// The largest image side accepted, in pixels.
pub const MAX_SIDE: u32 = 8192;

/// The most samples (pixels times supersampling squared) accepted: the
/// buffers take 7 bytes a sample, so at most 448 MiB.
pub const MAX_SAMPLES: u64 = 1 << 26;

/// Where the camera looks from. Named views look at the mesh from outside
/// along an axis; y is up, except for the top and bottom views.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum View {
    /// A three-quarter view from front, right and above.
    #[default]
    Iso,
    /// From +z.
    Front,
    /// From −z.
    Back,
    /// From −x.
    Left,
    /// From +x.
    Right,
    /// From +y, with −z up.
    Top,
    /// From −y, with +z up.
    Bottom,
    /// From this direction (pointing from the mesh toward the eye), y up
    /// (z up if the direction is along y).
    Direction([f64; 3]),
}

impl View {
    /// The direction from the mesh toward the eye, and the up direction.
    pub fn camera(self) -> ([f64; 3], [f64; 3]) {
        let y = [0.0, 1.0, 0.0];
        match self {
            View::Iso => ([0.75, 0.55, 1.0], y),
            View::Front => ([0.0, 0.0, 1.0], y),
            View::Back => ([0.0, 0.0, -1.0], y),
            View::Left => ([-1.0, 0.0, 0.0], y),
            View::Right => ([1.0, 0.0, 0.0], y),
            View::Top => ([0.0, 1.0, 0.0], [0.0, 0.0, -1.0]),
            View::Bottom => ([0.0, -1.0, 0.0], [0.0, 0.0, 1.0]),
            View::Direction(d) => {
                let along_y = d[0] == 0.0 && d[2] == 0.0;
                (
                    d,
                    if along_y {
                        [0.0, 0.0, -d[1].signum()]
                    } else {
                        y
                    },
                )
            }
        }
    }
}

/// The names [`View::from_str`] accepts besides `x,y,z`.
pub const VIEW_NAMES: [&str; 7] = ["iso", "front", "back", "left", "right", "top", "bottom"];

impl FromStr for View {
    type Err = String;

    /// A name from [`VIEW_NAMES`] or a direction `x,y,z` toward the eye.
    ///
    /// ```
    /// use meshloom::render::View;
    /// assert_eq!("top".parse::<View>(), Ok(View::Top));
    /// assert_eq!("1,0,0.5".parse::<View>(), Ok(View::Direction([1.0, 0.0, 0.5])));
    /// assert!("sideways".parse::<View>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<View, String> {
        let named = match s.trim().to_ascii_lowercase().as_str() {
            "iso" => Some(View::Iso),
            "front" => Some(View::Front),
            "back" => Some(View::Back),
            "left" => Some(View::Left),
            "right" => Some(View::Right),
            "top" => Some(View::Top),
            "bottom" => Some(View::Bottom),
            _ => None,
        };
        if let Some(v) = named {
            return Ok(v);
        }
        let parts: Vec<_> = s.split(',').map(|p| p.trim().parse::<f64>()).collect();
        match parts[..] {
            [Ok(x), Ok(y), Ok(z)]
                if [x, y, z].iter().all(|c| c.is_finite()) && (x, y, z) != (0.0, 0.0, 0.0) =>
            {
                Ok(View::Direction([x, y, z]))
            }
            _ => Err(format!(
                "unknown view {s:?}: expected one of {} or a non-zero direction x,y,z",
                VIEW_NAMES.join(", ")
            )),
        }
    }
}

impl fmt::Display for View {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            View::Direction([x, y, z]) => write!(f, "{x},{y},{z}"),
            named => write!(f, "{}", format!("{named:?}").to_ascii_lowercase()),
        }
    }
}

/// How faces are shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Shading {
    /// One normal per face: facets show.
    Flat,
    /// Normals interpolated from area-weighted vertex normals.
    #[default]
    Smooth,
}

/// Colours of a picture, as sRGB bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Colors {
    /// Where no face is.
    pub background: [u8; 3],
    /// The front side of faces (where their normal points to the eye).
    pub front: [u8; 3],
    /// The back side of faces.
    pub back: [u8; 3],
    /// Edges, when drawn.
    pub wire: [u8; 3],
    /// Boundary edges, when highlighted.
    pub boundary: [u8; 3],
}

impl Default for Colors {
    fn default() -> Colors {
        Colors {
            background: [255, 255, 255],
            front: [176, 196, 222],
            back: [222, 168, 112],
            wire: [30, 32, 40],
            boundary: [220, 20, 60],
        }
    }
}

/// What to draw and how.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Where the camera looks from.
    pub view: View,
    /// Flat or smooth shading.
    pub shading: Shading,
    /// Draw every edge over the faces.
    pub wireframe: bool,
    /// Draw boundary edges (those beside a hole) thick in the boundary
    /// colour.
    pub boundary: bool,
    /// Samples per pixel along each axis (1 to 4).
    pub supersample: u32,
    /// The colours.
    pub colors: Colors,
}

impl RenderOptions {
    /// Check the size, supersampling and view, without a mesh.
    ///
    /// # Errors
    /// [`RenderError::Size`] for a side outside 1 to [`MAX_SIDE`],
    /// supersampling outside 1 to 4, or more than [`MAX_SAMPLES`] samples;
    /// [`RenderError::View`] for a view that defines no camera.
    ///
    /// ```
    /// use meshloom::render::RenderOptions;
    /// assert!(RenderOptions::default().check().is_ok());
    /// assert!(RenderOptions { width: 0, ..RenderOptions::default() }.check().is_err());
    /// ```
    pub fn check(&self) -> Result<(), RenderError> {
        let samples =
            u64::from(self.width) * u64::from(self.height) * u64::from(self.supersample).pow(2);
        if !(1..=MAX_SIDE).contains(&self.width)
            || !(1..=MAX_SIDE).contains(&self.height)
            || !(1..=4).contains(&self.supersample)
            || samples > MAX_SAMPLES
        {
            return Err(RenderError::Size {
                width: self.width,
                height: self.height,
                supersample: self.supersample,
            });
        }
        Camera::new(self.view).map(|_| ())
    }
}

impl Default for RenderOptions {
    fn default() -> RenderOptions {
        RenderOptions {
            width: 800,
            height: 600,
            view: View::Iso,
            shading: Shading::Smooth,
            wireframe: false,
            boundary: false,
            supersample: 2,
            colors: Colors::default(),
        }
    }
}

/// An RGB picture, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Image {
    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The colour at column `x`, row `y` (row 0 at the top); `None` outside.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = 3 * (y as usize * self.width as usize + x as usize);
        Some([self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]])
    }

    /// Every pixel's red, green and blue bytes, row after row.
    pub fn as_rgb(&self) -> &[u8] {
        &self.rgb
    }

    /// Encode as an 8-bit RGB PNG into `out`.
    ///
    /// # Errors
    /// [`RenderError::Png`] when the encoder or the writer fails.
    pub fn encode_png<W: std::io::Write>(&self, out: W) -> Result<(), RenderError> {
        let mut encoder = png::Encoder::new(out, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let png_error = |e: png::EncodingError| RenderError::Png(e.to_string());
        let mut writer = encoder.write_header().map_err(png_error)?;
        writer.write_image_data(&self.rgb).map_err(png_error)?;
        writer.finish().map_err(png_error)
    }

    /// Save as a PNG file.
    ///
    /// # Errors
    /// [`RenderError::Io`] naming the file when it cannot be created or
    /// written; [`RenderError::Png`] when encoding fails.
    pub fn write_png(&self, path: impl AsRef<Path>) -> Result<(), RenderError> {
        let path = path.as_ref();
        let io_error = |source| RenderError::Io {
            path: path.to_path_buf(),
            source,
        };
        let file = std::fs::File::create(path).map_err(io_error)?;
        let mut out = std::io::BufWriter::new(file);
        self.encode_png(&mut out)?;
        std::io::Write::flush(&mut out).map_err(io_error)
    }
}

/// Render a shaded picture of `mesh`.
///
/// # Errors
/// [`RenderError::Empty`] for a mesh without faces,
/// [`RenderError::NoPositions`] for a topology-only mesh,
/// [`RenderError::Size`] and [`RenderError::View`] for unusable options.
///
/// # Complexity
/// O(corners + covered pixels · face degree + width · height).
pub fn render(mesh: &Mesh, options: &RenderOptions) -> Result<Image, RenderError> {
    render_with_progress(mesh, options, &mut |_, _| {})
}

/// [`render`], calling `progress(done, total)` now and then with the
/// number of faces filled so far.
///
/// # Errors
/// As [`render`].
pub fn render_with_progress(
    mesh: &Mesh,
    options: &RenderOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Image, RenderError> {
    let o = options;
    o.check()?;
    if mesh.face_count() == 0 {
        return Err(RenderError::Empty);
    }
    let positions = mesh.position_slots().ok_or(RenderError::NoPositions)?;
    let camera = Camera::new(o.view)?;
    let s = o.supersample;
    let mut canvas = Canvas::new(o.width * s, o.height * s, o.colors.background);
    let screen = camera.fit(mesh, positions, canvas.width, canvas.height);
    let normals = match o.shading {
        Shading::Flat => None,
        Shading::Smooth => Some(vertex_normals(mesh, positions)),
    };
    let light = camera.light();
    let total = mesh.face_count();
    let mut done = 0;
    let mut corners: Vec<u32> = Vec::new();
    for f in mesh.f_slots.live_indices() {
        if mesh.is_hole_raw(f) {
            continue;
        }
        corners.clear();
        corners.extend(mesh.face_loop_raw(f).map(|h| mesh.origin_of(h)));
        let n = newell_normal(corners.iter().map(|&v| positions[v as usize]));
        let facing = dot(n, camera.toward_eye);
        let (base, side) = if facing >= 0.0 {
            (o.colors.front, 1.0)
        } else {
            (o.colors.back, -1.0)
        };
        let flat = normalize(n).unwrap_or(camera.toward_eye);
        let shade = |normal: [f64; 3]| {
            let lambert = (side * dot(normal, light)).max(0.0);
            let k = AMBIENT + (1.0 - AMBIENT) * lambert;
            base.map(|c| (f64::from(c) * k).round().clamp(0.0, 255.0) as u8)
        };
        canvas.fill_polygon(&corners, &screen, |vertex_weights| match &normals {
            None => shade(flat),
            Some(vn) => {
                let mut m = [0.0; 3];
                for &(v, w) in vertex_weights {
                    m = add(m, scale(vn[v as usize], w));
                }
                shade(normalize(m).unwrap_or(flat))
            }
        });
        done += 1;
        if done % 16384 == 0 {
            progress(done, total);
        }
    }
    progress(total, total);
    let bias = canvas.depth_bias();
    if o.wireframe {
        for e in mesh.e_slots.live_indices() {
            let on_boundary = mesh.in_hole_raw(2 * e) || mesh.in_hole_raw(2 * e + 1);
            if o.boundary && on_boundary {
                continue;
            }
            let (a, b) = (mesh.origin_of(2 * e), mesh.origin_of(2 * e + 1));
            canvas.line(
                screen[a as usize],
                screen[b as usize],
                s,
                bias,
                o.colors.wire,
            );
        }
    }
    if o.boundary {
        for e in mesh.e_slots.live_indices() {
            if mesh.in_hole_raw(2 * e) || mesh.in_hole_raw(2 * e + 1) {
                let (a, b) = (mesh.origin_of(2 * e), mesh.origin_of(2 * e + 1));
                let (pa, pb) = (screen[a as usize], screen[b as usize]);
                canvas.line(pa, pb, 3 * s, 4.0 * bias, o.colors.boundary);
            }
        }
    }
    Ok(canvas.downsample(s))
}

/// Share of light that reaches faces turned away from the lamp.
const AMBIENT: f64 = 0.35;

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: V3, k: f64) -> V3 {
    [a[0] * k, a[1] * k, a[2] * k]
}
fn normalize(a: V3) -> Option<V3> {
    let len = dot(a, a).sqrt();
    (len > 0.0 && len.is_finite()).then(|| scale(a, 1.0 / len))
}

/// Newell's normal of a polygon: twice its area along the normal, also for
/// non-planar and non-convex polygons.
fn newell_normal(corners: impl Iterator<Item = V3> + Clone) -> V3 {
    let next = corners.clone().cycle().skip(1);
    corners.zip(next).fold([0.0; 3], |n, (p, q)| {
        [
            n[0] + (p[1] - q[1]) * (p[2] + q[2]),
            n[1] + (p[2] - q[2]) * (p[0] + q[0]),
            n[2] + (p[0] - q[0]) * (p[1] + q[1]),
        ]
    })
}

/// Area-weighted vertex normals, indexed by vertex slot.
fn vertex_normals(mesh: &Mesh, positions: &[V3]) -> Vec<V3> {
    let mut normals = vec![[0.0; 3]; positions.len()];
    for f in mesh.f_slots.live_indices() {
        if mesh.is_hole_raw(f) {
            continue;
        }
        let corners = mesh
            .face_loop_raw(f)
            .map(|h| positions[mesh.origin_of(h) as usize]);
        let n = newell_normal(corners);
        for h in mesh.face_loop_raw(f) {
            let v = mesh.origin_of(h) as usize;
            normals[v] = add(normals[v], n);
        }
    }
    for n in &mut normals {
        *n = normalize(*n).unwrap_or([0.0; 3]);
    }
    normals
}

/// An orthographic camera: screen axes `right`, `up`, and the direction
/// toward the eye.
struct Camera {
    right: V3,
    up: V3,
    toward_eye: V3,
}

impl Camera {
    fn new(view: View) -> Result<Camera, RenderError> {
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
    fn light(&self) -> V3 {
        let d = add(
            self.toward_eye,
            add(scale(self.up, 0.5), scale(self.right, -0.3)),
        );
        normalize(d).unwrap_or(self.toward_eye)
    }

    /// Screen position (x right, y down, in pixels) and depth (larger is
    /// farther) of every vertex slot, scaled so the mesh fills the canvas
    /// with a margin.
    fn fit(&self, mesh: &Mesh, positions: &[V3], width: u32, height: u32) -> Vec<V3> {
        let project = |p: V3| {
            [
                dot(p, self.right),
                dot(p, self.up),
                -dot(p, self.toward_eye),
            ]
        };
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for v in mesh.v_slots.live_indices() {
            let q = project(positions[v as usize]);
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

/// Sample offset inside a pixel, off the pixel centre by odd amounts so that
/// a sample almost never lies exactly on an edge.
const SAMPLE: [f64; 2] = [0.5 + 1.2345e-4, 0.5 + 3.1416e-4];

/// The supersampled colour and depth buffers.
struct Canvas {
    width: u32,
    height: u32,
    color: Vec<[u8; 3]>,
    depth: Vec<f32>,
    depth_range: [f64; 2],
}

impl Canvas {
    fn new(width: u32, height: u32, background: [u8; 3]) -> Canvas {
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
    fn depth_bias(&self) -> f64 {
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
    fn fill_polygon(
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
    fn line(&mut self, a: V3, b: V3, thickness: u32, bias: f64, color: [u8; 3]) {
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
    fn downsample(self, s: u32) -> Image {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    fn small(view: View) -> RenderOptions {
        RenderOptions {
            width: 80,
            height: 60,
            view,
            ..RenderOptions::default()
        }
    }

    #[test]
    fn cube_covers_the_middle_not_the_corners() {
        for view in [
            View::Iso,
            View::Front,
            View::Top,
            View::Direction([-1.0, -2.0, 0.5]),
        ] {
            let o = small(view);
            let img = render(&shapes::cube(), &o).unwrap();
            let bg = o.colors.background;
            assert_ne!(img.pixel(40, 30), Some(bg), "{view}");
            for (x, y) in [(0, 0), (79, 0), (0, 59), (79, 59)] {
                assert_eq!(img.pixel(x, y), Some(bg), "{view} corner {x},{y}");
            }
        }
    }

    #[test]
    fn front_view_of_cube_is_one_flat_square() {
        // Seen along z the cube is a square filling the height minus margins;
        // every pixel inside has the same colour under flat shading.
        let o = RenderOptions {
            shading: Shading::Flat,
            supersample: 1,
            ..small(View::Front)
        };
        let img = render(&shapes::cube(), &o).unwrap();
        let centre = img.pixel(40, 30).unwrap();
        for (x, y) in [(25, 15), (54, 15), (25, 44), (54, 44)] {
            assert_eq!(img.pixel(x, y), Some(centre), "{x},{y}");
        }
        assert_eq!(img.pixel(10, 30), Some(o.colors.background));
    }

    #[test]
    fn open_mesh_shows_boundary_colour() {
        // A cube without its top: the rim is boundary.
        let p: Vec<[f64; 3]> = (0..8u32)
            .map(|i| {
                [
                    f64::from(i & 1),
                    f64::from((i >> 1) & 1),
                    f64::from((i >> 2) & 1),
                ]
            })
            .collect();
        let faces = [
            [0u32, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let mesh = Mesh::from_polygons(&p, &faces).unwrap();
        let with = RenderOptions {
            boundary: true,
            ..small(View::Iso)
        };
        let red = with.colors.boundary;
        let img = render(&mesh, &with).unwrap();
        let count = |img: &Image| img.as_rgb().chunks(3).filter(|c| *c == red).count();
        assert!(count(&img) > 20, "boundary pixels: {}", count(&img));
        let without = render(&mesh, &small(View::Iso)).unwrap();
        assert_eq!(count(&without), 0);
        // The inside is seen through the opening: back colour appears.
        let brownish = img
            .as_rgb()
            .chunks(3)
            .filter(|c| u16::from(c[0]) > u16::from(c[2]) + 40)
            .count();
        assert!(brownish > 20);
    }

    #[test]
    fn wireframe_draws_lines_in_the_wire_colour() {
        let o = RenderOptions {
            wireframe: true,
            ..small(View::Iso)
        };
        let wire = o.colors.wire;
        let near_wire = |img: &Image| {
            img.as_rgb()
                .chunks(3)
                .filter(|c| c.iter().zip(wire).all(|(&a, b)| a.abs_diff(b) < 16))
                .count()
        };
        let img = render(&shapes::icosahedron(), &o).unwrap();
        assert!(near_wire(&img) > 50, "wire pixels: {}", near_wire(&img));
        let plain = render(&shapes::icosahedron(), &small(View::Iso)).unwrap();
        assert_eq!(near_wire(&plain), 0);
    }

    #[test]
    fn non_convex_polygon_leaves_its_notch_empty() {
        // An L-shape in the z = 0 plane: the notch at the top right stays
        // background.
        let p = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
        ];
        let mesh = Mesh::from_polygons(&p, &[[2u32, 3, 4, 5, 0, 1]]).unwrap();
        let o = RenderOptions {
            width: 100,
            height: 100,
            supersample: 1,
            ..small(View::Front)
        };
        let img = render(&mesh, &o).unwrap();
        let bg = o.colors.background;
        assert_ne!(img.pixel(25, 75), Some(bg)); // lower left square
        assert_ne!(img.pixel(75, 75), Some(bg)); // lower right square
        assert_ne!(img.pixel(25, 25), Some(bg)); // upper left square
        assert_eq!(img.pixel(75, 25), Some(bg)); // the notch
    }

    #[test]
    fn empty_and_topology_only_meshes_are_errors() {
        let o = RenderOptions::default();
        assert!(matches!(render(&Mesh::new(), &o), Err(RenderError::Empty)));
        let topo = Mesh::from_faces(3, &[[0u32, 1, 2]]).unwrap();
        let err = render(&topo, &o).unwrap_err();
        assert!(matches!(err, RenderError::NoPositions));
        assert!(err.to_string().contains("positions"));
    }

    #[test]
    fn bad_options_are_errors() {
        let cube = shapes::cube();
        let zero = RenderOptions {
            width: 0,
            ..RenderOptions::default()
        };
        assert!(matches!(
            render(&cube, &zero),
            Err(RenderError::Size { .. })
        ));
        let degenerate = RenderOptions {
            view: View::Direction([0.0, 0.0, 0.0]),
            ..RenderOptions::default()
        };
        assert!(matches!(
            render(&cube, &degenerate),
            Err(RenderError::View { .. })
        ));
    }

    #[test]
    fn flat_mesh_seen_edge_on_does_not_panic() {
        let square = Mesh::from_polygons(
            &[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            &[[0u32, 1, 2, 3]],
        )
        .unwrap();
        let img = render(&square, &small(View::Right)).unwrap();
        assert_eq!(img.width(), 80);
    }

    #[test]
    fn png_round_trip_has_the_right_size() {
        let img = render(&shapes::tetrahedron(), &small(View::Iso)).unwrap();
        let mut bytes = Vec::new();
        img.encode_png(&mut bytes).unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let reader = decoder.read_info().unwrap();
        let info = reader.info();
        assert_eq!((info.width, info.height), (80, 60));
    }

    #[test]
    fn view_names_round_trip() {
        for name in VIEW_NAMES {
            let v: View = name.parse().unwrap();
            assert_eq!(v.to_string(), name);
        }
    }
}
