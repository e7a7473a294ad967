//! Getting the bytes of a file: formats by extension, gzip, size limits.
//!
//! Readers parse from one in-memory buffer: the file is read whole (or
//! decompressed whole), never more than
//! [`ReadOptions::max_bytes`](crate::io::ReadOptions::max_bytes) bytes, so
//! memory is bounded by the input's real size and the caller's limit, not
//! by counts a header claims.

use std::io::Read;
use std::path::Path;

use super::error::{Error, Location};

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Format {
    /// Wavefront OBJ.
    Obj,
    /// Object File Format (geomview, CGAL).
    Off,
    /// Polygon File Format (Stanford), ascii or binary.
    Ply,
    /// Stereolithography, ascii or binary.
    Stl,
}

crate::choice::choices!(Format {
    Obj = "obj",
    Off = "off",
    Ply = "ply",
    Stl = "stl",
});

impl Format {
    /// The format named by a file's extension (case-insensitive), and
    /// whether a trailing `.gz` asks for gzip.
    ///
    /// ```
    /// use meshloom::io::Format;
    /// assert_eq!(Format::from_path("a/dragon.ply.gz"), Some((Format::Ply, true)));
    /// assert_eq!(Format::from_path("cube.OBJ"), Some((Format::Obj, false)));
    /// assert_eq!(Format::from_path("notes.txt"), None);
    /// ```
    pub fn from_path(path: impl AsRef<Path>) -> Option<(Format, bool)> {
        let path = path.as_ref();
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        let (ext, gz) = if ext == "gz" {
            let stem = Path::new(path.file_stem()?);
            (stem.extension()?.to_str()?.to_ascii_lowercase(), true)
        } else {
            (ext, false)
        };
        let format = match ext.as_str() {
            "obj" => Format::Obj,
            "off" => Format::Off,
            "ply" => Format::Ply,
            "stl" => Format::Stl,
            _ => return None,
        };
        Some((format, gz))
    }

    /// The usual extension, without a dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Obj => "obj",
            Format::Off => "off",
            Format::Ply => "ply",
            Format::Stl => "stl",
        }
    }
}

/// Read all of `reader`, at most `limit` bytes.
pub(crate) fn read_all(reader: impl Read, limit: u64, size_hint: usize) -> Result<Vec<u8>, Error> {
    let mut buf = Vec::with_capacity(size_hint.min(limit as usize));
    reader
        .take(limit.saturating_add(1))
        .read_to_end(&mut buf)
        .map_err(Error::io)?;
    if buf.len() as u64 > limit {
        return Err(Error::TooLarge {
            at: Location::whole(),
            what: format!("the input is larger than the limit of {limit} bytes"),
        });
    }
    Ok(buf)
}

/// The bytes of a file, gunzipped when `gz` (or when they start with the
/// gzip magic bytes anyway).
pub(crate) fn load(path: &Path, gz: bool, limit: u64) -> Result<Vec<u8>, Error> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(e).with_path(path))?;
    let size = file.metadata().map(|m| m.len() as usize).unwrap_or(0);
    let bytes = if gz {
        gzip::decoder(std::io::BufReader::new(file))
            .and_then(|decoder| read_all(decoder, limit, size.saturating_mul(4)))
    } else {
        read_all(file, limit, size).and_then(|b| gunzip_if_gzip(b, limit))
    };
    bytes.map_err(|e| e.with_path(path))
}

/// `bytes` decompressed if they are gzip data, else as they are.
pub(crate) fn gunzip_if_gzip(bytes: Vec<u8>, limit: u64) -> Result<Vec<u8>, Error> {
    if bytes.starts_with(&[0x1f, 0x8b, 8]) {
        let size = bytes.len().saturating_mul(4);
        read_all(gzip::decoder(&bytes[..])?, limit, size)
    } else {
        Ok(bytes)
    }
}

/// Write `bytes` to `path`, gzipped when `gz`.
pub(crate) fn store(path: &Path, gz: bool, bytes: &[u8]) -> Result<(), Error> {
    use std::io::Write;
    let run = || -> std::io::Result<()> {
        let file = std::fs::File::create(path)?;
        if gz {
            gzip::write(std::io::BufWriter::new(file), bytes)
        } else {
            let mut w = std::io::BufWriter::new(file);
            w.write_all(bytes)?;
            w.flush()
        }
    };
    run().map_err(|e| Error::io(e).with_path(path))
}

/// gzip through flate2 (pure Rust), or a clear error when the `gzip`
/// feature is off.
#[cfg(feature = "gzip")]
mod gzip {
    use std::io::{Read, Write};

    use super::Error;

    pub(super) fn decoder(inner: impl Read) -> Result<impl Read, Error> {
        Ok(flate2::read::MultiGzDecoder::new(inner))
    }

    pub(super) fn write(inner: impl Write, bytes: &[u8]) -> std::io::Result<()> {
        let mut enc = flate2::write::GzEncoder::new(inner, flate2::Compression::default());
        enc.write_all(bytes)?;
        enc.finish()?.flush()
    }
}

#[cfg(not(feature = "gzip"))]
mod gzip {
    use std::io::{Read, Write};

    use super::Error;

    const OFF: &str = "gzip data needs meshloom's `gzip` feature (on by default)";

    pub(super) fn decoder(_inner: impl Read) -> Result<std::io::Empty, Error> {
        Err(Error::io(std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            OFF,
        )))
    }

    pub(super) fn write(_inner: impl Write, _bytes: &[u8]) -> std::io::Result<()> {
        Err(std::io::Error::new(std::io::ErrorKind::Unsupported, OFF))
    }
}

/// Text with a byte-order mark as UTF-8 without one: a UTF-8 mark is
/// dropped, UTF-16 (either byte order, by its mark) is transcoded (unpaired
/// surrogates and an odd last byte become U+FFFD). Text without a mark is
/// returned as it is. Line numbers are unchanged.
///
/// Memory: at most 1.5 times the input (a UTF-16 code unit becomes at most
/// three UTF-8 bytes).
pub(crate) fn decode_text(bytes: &[u8]) -> std::borrow::Cow<'_, [u8]> {
    use std::borrow::Cow;
    if let Some(rest) = bytes.strip_prefix(b"\xEF\xBB\xBF") {
        return Cow::Borrowed(rest);
    }
    let big = match bytes {
        [0xFF, 0xFE, ..] => false,
        [0xFE, 0xFF, ..] => true,
        _ => return Cow::Borrowed(bytes),
    };
    let units = bytes[2..].chunks(2).map(|c| match c {
        [a, b] if big => u16::from_be_bytes([*a, *b]),
        [a, b] => u16::from_le_bytes([*a, *b]),
        _ => 0xFFFD,
    });
    let mut out = String::with_capacity(bytes.len() / 2);
    out.extend(char::decode_utf16(units).map(|c| c.unwrap_or('\u{FFFD}')));
    Cow::Owned(out.into_bytes())
}
