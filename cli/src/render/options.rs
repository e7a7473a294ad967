//! What to draw and how: view, shading, colours, size.

use std::fmt;
use std::str::FromStr;

use super::camera::Camera;
use super::RenderError;

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
    /// use meshloom_cli::render::View;
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

/// What gives the faces their colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Coloring {
    /// The front and back colours of [`Colors`].
    #[default]
    Plain,
    /// The mean curvature at each vertex (`meshloom::algo::curvature`),
    /// blended across the faces, by a diverging colour map: blue where the
    /// surface is concave (`H < 0`), white where it is flat, red where it
    /// is convex. The range is symmetric, `±` the 98th percentile of `|H|`
    /// over the vertices, so a few extreme vertices (sharp corners,
    /// boundary spikes) do not wash the rest out to white; beyond it the
    /// colour saturates. Both sides of a face take the same colour.
    Curvature,
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
    /// What gives the faces their colour (default: the plain colours).
    pub coloring: Coloring,
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
    /// use meshloom_cli::render::RenderOptions;
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
            coloring: Coloring::Plain,
        }
    }
}
