//! PLY (Polygon File Format), ascii and binary in both byte orders.
//!
//! The reader is written here rather than taken from `ply-rs-bw`: its
//! current version needs a newer Rust than this crate's minimum (1.80), its
//! reader builds a map of named properties for every element (slow on the
//! 871k-face dragon), and what this module needs is bounded reads that
//! never reserve by a header's count and errors that name the header line,
//! or the body line (ascii) or byte offset (binary), where the data is
//! wrong. The header is
//! parsed into elements and typed properties; the body is read element by
//! element, every element the header declares (unknown ones are read and
//! skipped, so what follows them is found).
//!
//! Read: `vertex` with `x y z` (any numeric type), `face` with a list named
//! `vertex_indices` or `vertex_index`. Writing puts positions as `double`
//! so they read back exactly.
//!
//! ```
//! use meshloom::io::{read_ply, write_ply, PlyEncoding};
//! let mut bytes = Vec::new();
//! write_ply(&meshloom::shapes::cube(), &mut bytes, PlyEncoding::BinaryBigEndian)?;
//! let cube = read_ply(&bytes[..])?;
//! assert_eq!((cube.vertex_count(), cube.face_count()), (8, 6));
//! # Ok::<(), meshloom::io::Error>(())
//! ```

use std::io::Read;

use super::error::Error;
use super::{slurp, ReadOptions};
use crate::mesh::Mesh;

mod body;
mod header;
mod write;

pub(crate) use body::parse;
pub use write::write_ply;

/// The half-edge columns [`write_ply`] leaves out.
pub(crate) fn corner_dropped(mesh: &Mesh, maps: &crate::build::IndexMaps) -> Vec<String> {
    write::corner_columns(mesh, maps).dropped
}

const FORMAT: super::Format = super::Format::Ply;
use crate::repair::RepairReport;

/// How a PLY body is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlyEncoding {
    /// Text.
    Ascii,
    /// Binary, least significant byte first.
    BinaryLittleEndian,
    /// Binary, most significant byte first.
    BinaryBigEndian,
}

crate::choice::choices!(PlyEncoding {
    Ascii = "ascii",
    BinaryLittleEndian = "binary-little-endian",
    BinaryBigEndian = "binary-big-endian",
});

/// Read a PLY mesh, strictly.
///
/// # Errors
/// [`Error`] with the line (header, ascii body) or byte offset (binary
/// body): a malformed header, missing `x y z` or face list, a malformed or
/// truncated body, an index out of range, polygons that need repair.
pub fn read_ply(reader: impl Read) -> Result<Mesh, Error> {
    read_ply_with(reader, &ReadOptions::strict()).map(|(m, _)| m)
}

/// Read a PLY mesh with repair policies.
///
/// # Errors
/// As [`read_ply`], less what the policies repair.
pub fn read_ply_with(
    reader: impl Read,
    options: &ReadOptions,
) -> Result<(Mesh, RepairReport), Error> {
    let bytes = slurp(reader, options)?;
    super::read_soup(FORMAT, &bytes, options)
}
