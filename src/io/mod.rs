//! Reading and writing mesh files: one format per file, dispatch by
//! extension, gzip by a trailing `.gz` (and gzip data is recognised by its
//! magic bytes on reading), repair of dirty input by policy.
//!
//! | format | read | write | module |
//! |---|---|---|---|
//! | OBJ | n-gons, negative indices, `v/vt/vn` | yes | [`obj`] |
//! | OFF | n-gons, comments, `[ST][C][N][4][n]OFF` headers, colours | yes | [`off`] |
//! | PLY | ascii, binary little and big endian | ascii, binary LE and BE | [`ply`] |
//! | STL | ascii (also a bare `solid` first line) and binary; vertices welded by exact position | ascii, binary | [`stl`] |
//! | glTF 2.0 (feature `gltf`) | `.gltf` and `.glb`: triangles, strips, fans; welded by position; normals, UVs, colours, custom attributes | `.gltf` (buffer inside) and `.glb` | `gltf` |
//!
//! # Strict and repairing reads
//!
//! [`read`] is strict: input a half-edge mesh cannot hold as it is (a
//! repeated corner, an edge shared by three faces, faces that disagree in
//! orientation, a vertex no face uses) is an [`Error`] that names the file,
//! the line or byte offset of the face, and the problem. [`read_with`] takes
//! [`ReadOptions`] whose [`RepairOptions`] policies repair such input first
//! and returns a [`RepairReport`] of what was done
//! ([`repair`](crate::repair) explains each policy).
//!
//! # Bounded memory
//!
//! A file is read whole into memory (at most [`ReadOptions::max_bytes`],
//! after decompression) and parsed from there. No reader reserves space by a
//! count written in a header: capacities are capped by what the remaining
//! bytes could hold, so a header that claims billions of vertices costs
//! nothing and ends in an error naming the line where the data ran out.
//!
//! ```
//! use meshloom::io::{self, ReadOptions};
//! let dir = std::env::temp_dir().join(format!("meshloom-doc-io-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let path = dir.join("cube.off");
//! io::write(&meshloom::shapes::cube(), &path)?;
//! let cube = io::read(&path)?;
//! assert_eq!((cube.vertex_count(), cube.face_count()), (8, 6));
//! let (again, report) = io::read_with(&path, &ReadOptions::repair_all())?;
//! assert!(report.is_clean());
//! assert_eq!(again.face_count(), 6);
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod attrs;
mod error;
#[cfg(feature = "gltf")]
pub mod gltf;
pub mod names;
pub mod obj;
pub mod off;
pub mod ply;
mod soup;
mod source;
pub mod stl;
mod text;

use std::path::Path;

pub use crate::repair::{RepairOptions, RepairReport};
pub use error::{Error, Location, Position};
pub use obj::{read_obj, read_obj_with, write_obj};
pub use off::{read_off, read_off_with, write_off};
pub use ply::{read_ply, read_ply_with, write_ply, PlyEncoding};
pub use source::Format;
pub use stl::{read_stl, read_stl_with, write_stl, StlEncoding};

use crate::mesh::Mesh;

/// How to read: which repairs to run, and how many bytes to accept.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReadOptions {
    /// The repair policies (all off by default: strict).
    pub repair: RepairOptions,
    /// The largest input accepted, in bytes after decompression (default
    /// 4 GiB).
    pub max_bytes: u64,
}

crate::choice::setters!(ReadOptions {
    repair: RepairOptions,
    max_bytes: u64,
});

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions::strict()
    }
}

impl ReadOptions {
    /// No repair: input a half-edge mesh cannot hold is an error.
    pub fn strict() -> ReadOptions {
        ReadOptions {
            repair: RepairOptions::none(),
            max_bytes: 4 << 30,
        }
    }

    /// Every repair policy on.
    pub fn repair_all() -> ReadOptions {
        ReadOptions {
            repair: RepairOptions::all(),
            ..ReadOptions::strict()
        }
    }
}

/// Read a mesh file, strictly; the format comes from the extension (`.obj`,
/// `.off`, `.ply`, `.stl`, each optionally followed by `.gz`).
///
/// # Errors
/// [`Error`] naming the file and the line or byte offset: unreadable or
/// malformed input, an unknown extension, an empty file, or polygons that
/// need repair (see [`read_with`]).
pub fn read(path: impl AsRef<Path>) -> Result<Mesh, Error> {
    read_with(path, &ReadOptions::strict()).map(|(mesh, _)| mesh)
}

/// Read a mesh file with repair policies; returns the mesh and what the
/// repairs did.
///
/// # Errors
/// As [`read`], less what the chosen policies repair.
pub fn read_with(
    path: impl AsRef<Path>,
    options: &ReadOptions,
) -> Result<(Mesh, RepairReport), Error> {
    let path = path.as_ref();
    #[cfg(feature = "gltf")]
    if gltf::encoding_of(path).is_some() {
        return gltf::read_gltf_with(path, options, &gltf::GltfOptions::default());
    }
    let (format, gz) = format_of(path)?;
    let bytes = source::load(path, gz, options.max_bytes)?;
    parse_bytes(format, &bytes, options).map_err(|e| e.with_path(path))
}

/// Read a mesh of a known format from bytes in memory (not gzipped).
///
/// # Errors
/// As [`read_with`]; locations name no file.
pub fn read_bytes(
    format: Format,
    bytes: &[u8],
    options: &ReadOptions,
) -> Result<(Mesh, RepairReport), Error> {
    parse_bytes(format, bytes, options)
}

fn parse_bytes(
    format: Format,
    bytes: &[u8],
    options: &ReadOptions,
) -> Result<(Mesh, RepairReport), Error> {
    if bytes.len() as u64 > options.max_bytes {
        return Err(Error::TooLarge {
            at: Location::whole(),
            what: format!("the input is larger than {} bytes", options.max_bytes),
        });
    }
    read_soup(format, bytes, options)
}

fn parse_soup(format: Format, bytes: &[u8], record: bool) -> Result<soup::Soup, Error> {
    match format {
        Format::Obj => obj::parse(bytes, record),
        Format::Off => off::parse(bytes, record),
        Format::Ply => ply::parse(bytes, record),
        Format::Stl => stl::parse(bytes, record),
    }
}

/// Parse, repair and build; a face the builder refuses is placed by a
/// second parse that records where each face was read.
fn read_soup(
    format: Format,
    bytes: &[u8],
    options: &ReadOptions,
) -> Result<(Mesh, RepairReport), Error> {
    // Text formats may come with a byte-order mark (UTF-8, or UTF-16 as
    // some Windows tools write them).
    let decoded = match format {
        Format::Obj | Format::Off => source::decode_text(bytes),
        _ => std::borrow::Cow::Borrowed(bytes),
    };
    let bytes = &decoded[..];
    let again = || parse_soup(format, bytes, true);
    match parse_soup(format, bytes, false)?.finish(options) {
        Err(Error::Build { face, source, .. }) => {
            let at = again()
                .map(|s| s.location_of_face(face))
                .unwrap_or_default();
            Err(Error::Build { at, face, source })
        }
        Err(Error::NonFinite {
            vertex, position, ..
        }) => {
            let at = again()
                .map(|s| s.location_of_vertex(vertex))
                .unwrap_or_default();
            Err(Error::NonFinite {
                at,
                vertex,
                position,
            })
        }
        Err(Error::Unreferenced { count, first, .. }) => {
            let at = again()
                .map(|s| s.location_of_vertex(first))
                .unwrap_or_default();
            Err(Error::Unreferenced { at, count, first })
        }
        other => other,
    }
}

/// How to write the formats that have several encodings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct WriteOptions {
    /// PLY body encoding (default binary little endian).
    pub ply: PlyEncoding,
    /// STL encoding (default binary).
    pub stl: StlEncoding,
    /// glTF: write positions even where narrowing them to 32-bit floats
    /// turns a nonzero coordinate into zero or a subnormal (default off:
    /// an error; see `gltf::GltfWriteOptions::allow_lossy_f32`).
    pub allow_lossy_f32: bool,
}

crate::choice::setters!(WriteOptions {
    ply: PlyEncoding,
    stl: StlEncoding,
    allow_lossy_f32: bool,
});

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions {
            ply: PlyEncoding::BinaryLittleEndian,
            stl: StlEncoding::Binary,
            allow_lossy_f32: false,
        }
    }
}

impl WriteOptions {
    /// Text encodings for every format.
    pub fn ascii() -> WriteOptions {
        WriteOptions {
            ply: PlyEncoding::Ascii,
            stl: StlEncoding::Ascii,
            ..WriteOptions::default()
        }
    }
}

/// Write a mesh file; the format comes from the extension, `.gz` compresses.
/// PLY is written as binary little endian, STL as binary
/// ([`write_with`] chooses).
///
/// # Errors
/// [`Error::UnsupportedFormat`] for an unknown extension, [`Error::Io`],
/// [`Error::Unwritable`] for a mesh without positions.
pub fn write(mesh: &Mesh, path: impl AsRef<Path>) -> Result<(), Error> {
    write_with(mesh, path, &WriteOptions::default())
}

/// [`write()`] with the encodings of PLY and STL chosen.
///
/// ```
/// use meshloom::io::{self, WriteOptions};
/// let path = std::env::temp_dir().join(format!("meshloom-doc-{}.stl", std::process::id()));
/// io::write_with(&meshloom::shapes::cube(), &path, &WriteOptions::ascii())?;
/// assert!(std::fs::read(&path)?.starts_with(b"solid"));
/// assert_eq!(io::read(&path)?.face_count(), 12);
/// # std::fs::remove_file(&path)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`write()`].
pub fn write_with(
    mesh: &Mesh,
    path: impl AsRef<Path>,
    options: &WriteOptions,
) -> Result<(), Error> {
    let path = path.as_ref();
    #[cfg(feature = "gltf")]
    if let Some(encoding) = gltf::encoding_of(path) {
        let mut bytes = Vec::new();
        let gltf_options = gltf::GltfWriteOptions {
            encoding,
            allow_lossy_f32: options.allow_lossy_f32,
        };
        gltf::write_gltf_with(mesh, &mut bytes, &gltf_options).map_err(|e| e.with_path(path))?;
        return std::fs::write(path, &bytes).map_err(|e| Error::io(e).with_path(path));
    }
    let (format, gz) = format_of(path)?;
    let mut bytes = Vec::new();
    let written = match format {
        Format::Obj => write_obj(mesh, &mut bytes),
        Format::Off => write_off(mesh, &mut bytes),
        Format::Ply => write_ply(mesh, &mut bytes, options.ply),
        Format::Stl => write_stl(mesh, &mut bytes, options.stl),
    };
    written.map_err(|e| e.with_path(path))?;
    source::store(path, gz, &bytes)
}

/// What writing `mesh` as `format` leaves out, one line per attribute
/// column (empty when the format holds everything): the CLI's `convert`
/// prints it. Positions and faces are always written.
///
/// ```
/// use meshloom::io::{dropped_columns, Format};
/// let mut mesh = meshloom::shapes::cube();
/// let w = mesh.add_vertex_attr::<f64>("weight")?;
/// mesh.fill_attr(&w, 1.0)?;
/// assert!(dropped_columns(&mesh, Format::Ply).is_empty());
/// assert_eq!(dropped_columns(&mesh, Format::Stl).len(), 1);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn dropped_columns(mesh: &Mesh, format: Format) -> Vec<String> {
    use crate::ElementKind::{Edge, Face, Halfedge, Vertex};
    let mut dropped = Vec::new();
    let all = |kind| mesh.attr_info(kind).into_iter().map(move |i| (kind, i));
    let columns = all(Vertex)
        .chain(all(Halfedge))
        .chain(all(Edge))
        .chain(all(Face))
        .filter(|(k, i)| !(*k == Vertex && i.name == crate::attr::POSITION));
    for (kind, info) in columns {
        let kept = match format {
            Format::Stl => false,
            Format::Obj => match kind {
                Halfedge => ["texcoord", "normal"].contains(&info.name.as_str()),
                Face => ["object", "group", "material"].contains(&info.name.as_str()),
                _ => false,
            },
            Format::Off => match kind {
                Vertex => ["w", "normal", "color", "texcoord"].contains(&info.name.as_str()),
                Face => ["color", "color_index"].contains(&info.name.as_str()),
                _ => false,
            },
            Format::Ply => match kind {
                Vertex | Face => info
                    .value_type
                    .is_some_and(|t| t != crate::attr::ValueType::Text),
                Halfedge => true, // decided below, by seams
                Edge => false,
            },
        };
        if !kept {
            dropped.push(format!("{kind} attribute {:?}", info.name));
        }
    }
    if format == Format::Ply {
        let (_, maps) = mesh.to_polygons();
        dropped.extend(ply::corner_dropped(mesh, &maps));
    }
    dropped
}

fn format_of(path: &Path) -> Result<(Format, bool), Error> {
    Format::from_path(path).ok_or_else(|| Error::UnsupportedFormat {
        at: Location {
            path: Some(path.to_path_buf()),
            position: Position::Whole,
        },
        what: "the extension is not .obj, .off, .ply or .stl (optionally + .gz)".into(),
    })
}

/// Read all of `reader` under the byte limit, gunzipping gzip data.
fn slurp(reader: impl std::io::Read, options: &ReadOptions) -> Result<Vec<u8>, Error> {
    let bytes = source::read_all(reader, options.max_bytes, 0)?;
    source::gunzip_if_gzip(bytes, options.max_bytes)
}

/// Write `bytes` to `writer`, mapping the error.
fn emit(mut writer: impl std::io::Write, bytes: &[u8]) -> Result<(), Error> {
    writer
        .write_all(bytes)
        .and_then(|()| writer.flush())
        .map_err(Error::io)
}

/// The mesh's positions and faces as dense buffers with their keys, or an
/// error if it has no positions.
/// Refuse positions that the 32-bit floats of `format` cannot hold: a
/// coordinate out of their range (always: it would become infinite), or a
/// nonzero one that would become zero or subnormal, unless `allow_lossy`
/// (`option`, if the format has one, names the setting that allows it).
/// The message names the vertex by its index in vertex order.
pub(crate) fn check_f32_positions(
    mesh: &Mesh,
    format: &str,
    allow_lossy: bool,
    option: Option<&str>,
) -> Result<(), Error> {
    let unwritable = |what| Error::Unwritable {
        at: Location::whole(),
        what,
    };
    for (i, v) in mesh.vertices().enumerate() {
        let Ok(p) = mesh.position(v) else {
            continue;
        };
        for &x in &p {
            let y = x as f32;
            if !y.is_finite() {
                return Err(unwritable(format!(
                    "vertex {i}: the position {p:?} is out of the range of 32-bit floats (at most {:e}), which {format} positions are",
                    f32::MAX
                )));
            }
            if !allow_lossy && x != 0.0 && (y == 0.0 || y.is_subnormal()) {
                let hint = option.map_or(String::new(), |o| format!(", or allow it with {o}"));
                return Err(unwritable(format!(
                    "vertex {i}: narrowing the position {p:?} to the 32-bit floats of {format} turns {x:e} into {y:e}; scale the mesh{hint}"
                )));
            }
        }
    }
    Ok(())
}

fn polygons_of(mesh: &Mesh) -> Result<(crate::build::Polygons, crate::build::IndexMaps), Error> {
    let (p, maps) = mesh.to_polygons();
    if p.positions.len() != mesh.vertex_count() {
        return Err(Error::Unwritable {
            at: Location::whole(),
            what: "the mesh has no vertex positions".into(),
        });
    }
    Ok((p, maps))
}
