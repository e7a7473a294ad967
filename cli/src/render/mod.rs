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
//! - [`Coloring::Curvature`] colours the surface by its mean curvature
//!   (blue concave, white flat, red convex) instead of the plain colours.
//!
//! ```
//! use meshloom_cli::render::{render, RenderOptions, View};
//! let mesh = meshloom::shapes::cube();
//! let options = RenderOptions { width: 64, height: 48, view: View::Iso, ..RenderOptions::default() };
//! let image = render(&mesh, &options)?;
//! assert_eq!((image.width(), image.height()), (64, 48));
//! assert_ne!(image.pixel(32, 24), Some(options.colors.background)); // the cube is in the middle
//! assert_eq!(image.pixel(0, 0), Some(options.colors.background));
//! # Ok::<(), meshloom_cli::render::RenderError>(())
//! ```

mod camera;
mod image;
mod options;
mod raster;
#[cfg(test)]
mod tests;

use std::path::PathBuf;

pub use image::Image;
pub use options::{
    Coloring, Colors, RenderOptions, Shading, View, MAX_SAMPLES, MAX_SIDE, VIEW_NAMES,
};

use camera::{add, dot, newell_normal, normalize, scale, Camera};
use meshloom::algo::{vertex_normals, NormalWeight, VertexNormalOptions};
use meshloom::Mesh;
use raster::Canvas;

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
/// number of faces filled so far, and once at the end with
/// `done == total`.
///
/// # Errors
/// As [`render`].
///
/// ```
/// use meshloom_cli::render::{render_with_progress, RenderOptions};
/// let mesh = meshloom::shapes::cube();
/// let mut last = (0, 0);
/// render_with_progress(&mesh, &RenderOptions::default(), &mut |done, total| last = (done, total))?;
/// assert_eq!(last, (6, 6));
/// # Ok::<(), meshloom_cli::render::RenderError>(())
/// ```
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
        // Area-weighted, as the renderer always shaded (the Newell normals
        // of the faces summed).
        Shading::Smooth => Some(
            vertex_normals(
                mesh,
                &VertexNormalOptions::default().weight(NormalWeight::Area),
            )
            .map_err(|_| RenderError::NoPositions)?,
        ),
    };
    let vertex_colors = match o.coloring {
        Coloring::Plain => None,
        Coloring::Curvature => Some(curvature_colors(mesh)?),
    };
    let light = camera.light();
    let total = mesh.face_count();
    let mut done = 0;
    let mut corners: Vec<u32> = Vec::new();
    for f in mesh.faces() {
        let Ok(face) = mesh.face(f) else { continue };
        corners.clear();
        corners.extend(face.vertices().map(|v| v.index() as u32));
        let n = newell_normal(corners.iter().map(|&v| positions[v as usize]));
        let facing = dot(n, camera.toward_eye);
        let (base, side) = if facing >= 0.0 {
            (o.colors.front, 1.0)
        } else {
            (o.colors.back, -1.0)
        };
        let flat = normalize(n).unwrap_or(camera.toward_eye);
        let base = base.map(f64::from);
        let shade = |normal: [f64; 3], color: [f64; 3]| {
            let lambert = (side * dot(normal, light)).max(0.0);
            let k = AMBIENT + (1.0 - AMBIENT) * lambert;
            color.map(|c| (c * k).round().clamp(0.0, 255.0) as u8)
        };
        canvas.fill_polygon(&corners, &screen, |vertex_weights| {
            let blend = |values: &[[f64; 3]]| {
                let mut m = [0.0; 3];
                for &(v, w) in vertex_weights {
                    m = add(m, scale(values[v as usize], w));
                }
                m
            };
            let color = vertex_colors.as_deref().map_or(base, blend);
            match &normals {
                None => shade(flat, color),
                Some(vn) => shade(normalize(blend(vn)).unwrap_or(flat), color),
            }
        });
        done += 1;
        if done % 16384 == 0 {
            progress(done, total);
        }
    }
    progress(total, total);
    let bias = canvas.depth_bias();
    let edges = || mesh.edges().filter_map(|e| mesh.edge(e).ok());
    let ends = |e: meshloom::EdgeView<'_>| e.vertices().map(|v| screen[v.index()]);
    if o.wireframe {
        for e in edges() {
            if o.boundary && e.is_boundary() {
                continue;
            }
            let [a, b] = ends(e);
            canvas.line(a, b, s, bias, o.colors.wire);
        }
    }
    if o.boundary {
        for e in edges().filter(|e| e.is_boundary()) {
            let [a, b] = ends(e);
            canvas.line(a, b, 3 * s, 4.0 * bias, o.colors.boundary);
        }
    }
    Ok(canvas.downsample(s))
}

/// The colour of every vertex slot by its mean curvature (see
/// [`Coloring::Curvature`]), as sRGB values in `[0, 255]`.
fn curvature_colors(mesh: &Mesh) -> Result<Vec<[f64; 3]>, RenderError> {
    use meshloom::algo::curvature::{curvature, CurvatureOptions};
    let h = curvature(mesh, &CurvatureOptions::default())
        .map_err(|_| RenderError::NoPositions)?
        .mean;
    let range = symmetric_range(mesh.vertices().map(|v| h[v.index()]));
    Ok(h.iter().map(|&x| diverging(x / range)).collect())
}

/// Percentile of `|H|` that sets the colour range.
const CURVATURE_PERCENTILE: f64 = 0.98;

/// The half-width of the colour range: the 98th percentile of the finite
/// `|values|`, or 1 when that is zero (a flat mesh: everything white).
fn symmetric_range(values: impl Iterator<Item = f64>) -> f64 {
    let mut magnitudes: Vec<f64> = values.filter(|x| x.is_finite()).map(f64::abs).collect();
    if magnitudes.is_empty() {
        return 1.0;
    }
    let k = ((magnitudes.len() - 1) as f64 * CURVATURE_PERCENTILE).round() as usize;
    let (_, &mut r, _) = magnitudes.select_nth_unstable_by(k, f64::total_cmp);
    if r > 0.0 {
        r
    } else {
        1.0
    }
}

/// A diverging colour map over `t` in `[−1, 1]` (clamped; NaN is white):
/// blue, white, red, as sRGB values.
fn diverging(t: f64) -> [f64; 3] {
    const BLUE: [f64; 3] = [59.0, 76.0, 192.0];
    const WHITE: [f64; 3] = [242.0, 242.0, 242.0];
    const RED: [f64; 3] = [180.0, 4.0, 38.0];
    let t = if t.is_nan() { 0.0 } else { t.clamp(-1.0, 1.0) };
    let (end, s) = if t < 0.0 { (BLUE, -t) } else { (RED, t) };
    [0, 1, 2].map(|k| WHITE[k] + s * (end[k] - WHITE[k]))
}

/// Share of light that reaches faces turned away from the lamp.
const AMBIENT: f64 = 0.35;
