//! The finished picture and its PNG encoding.

use std::path::Path;

use super::RenderError;

/// An RGB picture, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) rgb: Vec<u8>,
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
    ///
    /// ```
    /// use meshloom_cli::render::{render, RenderOptions};
    /// let image = render(&meshloom::shapes::icosahedron(), &RenderOptions::default())?;
    /// let path = std::env::temp_dir().join(format!("meshloom-doc-{}.png", std::process::id()));
    /// image.write_png(&path)?;
    /// assert!(std::fs::read(&path)?.starts_with(b"\x89PNG"));
    /// # std::fs::remove_file(&path)?;
    /// let err = image.write_png("/no/such/dir/mesh.png").unwrap_err();
    /// assert!(err.to_string().contains("/no/such/dir/mesh.png"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
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
