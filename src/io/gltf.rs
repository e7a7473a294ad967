//! glTF 2.0 (`.gltf`, `.glb`), with the `gltf` feature.
//!
//! **Reading** goes through the `gltf` crate's JSON model and validation
//! (so a field of the wrong type is an error naming its JSON line, an
//! invalid reference one naming its JSON path); the container (GLB chunks),
//! the buffers (`data:` URIs, files beside a `.gltf`, the GLB `BIN` chunk)
//! and every accessor are read here with checked arithmetic, so a bad
//! offset, count or index is an [`Error`] naming the file and the byte,
//! never a panic, and nothing is allocated beyond what the buffers hold
//! (their total is capped by [`ReadOptions::max_bytes`]).
//!
//! - **Scene.** The default scene (else the first; else every mesh once),
//!   walked from its root nodes with each node's transform applied:
//!   positions by the node's matrix, normals by its inverse transpose.
//! - **Welding.** glTF has no connectivity: a vertex is split into one
//!   glTF vertex per corner value. The primitives of one mesh instance are
//!   welded into one surface: by the custom attribute `_VERTEX_ID` where
//!   every primitive has it (meshloom writes it: its own files come back
//!   with the same vertices, components and holes), else by exact
//!   position, where the result stays manifold: coincident vertices whose
//!   joining would make an edge or a vertex non-manifold (parts that only
//!   touch at a point, distinct vertices of one surface that share a
//!   position) stay apart. The [`RepairReport`] counts the vertices
//!   welded and those left apart, and the triangles dropped for two
//!   corners at one position (no area). Different mesh instances stay
//!   separate components.
//! - **Attributes.** `NORMAL` becomes the half-edge column `normal`,
//!   `TEXCOORD_n` the half-edge column `texcoord` (`texcoord1`, ... for
//!   n ≥ 1), so a UV seam, where the file splits a vertex, becomes corner
//!   values that differ across an edge. `COLOR_n` (`color`, `color1`, ...)
//!   and custom attributes `_NAME` (column `NAME`) become vertex columns
//!   where every copy of a welded vertex agrees, half-edge columns
//!   otherwise. Primitives without an attribute leave it absent. The
//!   material's name becomes the face column `material`. A custom
//!   attribute `_FACE_NAME` (how meshloom writes a face column) becomes
//!   the face column `NAME` when it has one value over each triangle (else
//!   it is read as any custom attribute, as the column `FACE_NAME`).
//!   `TANGENT`,
//!   `JOINTS_n`, `WEIGHTS_n`, morph targets, skins, cameras and textures are
//!   not read.
//! - **Modes.** Triangles, triangle strips and fans; points and lines are
//!   an [`Error::UnsupportedFormat`] naming the mesh and primitive (they
//!   hold no faces). Sparse accessors are refused the same way.
//! - **Several meshes** become components of one mesh. To read one mesh
//!   alone, [`read_gltf_with`] takes [`GltfOptions::mesh`] (the index in
//!   the file's `meshes`).
//!
//! **Writing** makes one mesh, one buffer, and one primitive per material:
//! positions (with their bounds), the half-edge or vertex column `normal`
//! as `NORMAL`, `texcoord`/`texcoordN` as `TEXCOORD_n`, `color`/`colorN`
//! as `COLOR_n`, every other numeric vertex or half-edge column of one to
//! four values as `_NAME`, split into glTF vertices where corner values
//! differ ([`Mesh::to_triangle_buffers`]); polygons are triangulated for
//! the file. Face columns are kept:
//!
//! - the text face column `material` makes the primitives: one per
//!   distinct value, in order of first use, each with a material of that
//!   name (faces without a value go to one more primitive with no
//!   material); reading it back gives the same column and the same number
//!   of faces per material. The primitives share the vertex attributes.
//! - every other numeric face column of one to four values is written as
//!   the custom vertex attribute `_FACE_NAME`, the glTF vertices split
//!   where the faces around a vertex differ, so every triangle's three
//!   corners carry its face's value (absent values are written as zeros).
//!   meshloom reads it back as the face column `NAME`; other tools see an
//!   ordinary per-vertex attribute. Do not name other columns `FACE_...`.
//! - other text and boolean face columns (OBJ's `object` and `group`) are
//!   not written.
//!
//! Every glTF vertex also carries its mesh vertex's number (in the mesh's
//! vertex order) as the custom attribute `_VERTEX_ID` (a float scalar,
//! as glTF forbids unsigned int custom attributes; left out past 2²⁴
//! vertices, where floats stop being exact): reading it back welds by it,
//! so a round trip keeps the vertices, components, holes and seams (and
//! triangulates polygons). Other tools see an ordinary custom attribute.
//! Do not name other columns `VERTEX_ID`.
//!
//! Values are stored as 32-bit floats. A position they cannot hold is an
//! [`Error::Unwritable`]: out of their range always, and a nonzero
//! coordinate that would become zero or subnormal unless
//! [`GltfWriteOptions::allow_lossy_f32`] is set. A `.gltf` holds its
//! buffer as a base64 `data:` URI, so the file stands alone; `.glb` is
//! binary.
//!
//! ```
//! use meshloom::io;
//! let dir = std::env::temp_dir().join(format!("meshloom-doc-gltf-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let path = dir.join("cube.glb");
//! io::write(&meshloom::shapes::cube(), &path)?;
//! let cube = io::read(&path)?;
//! assert_eq!((cube.vertex_count(), cube.face_count()), (8, 12));
//! assert!(cube.is_closed());
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::io::Write;
use std::path::Path;

use super::error::{Error, Location, Position};
use super::{ReadOptions, RepairReport};
use crate::mesh::Mesh;

mod base64;
mod gather;
mod read;
mod scene;
mod weld;
mod write;

/// The face column whose text values name the primitives' materials.
const MATERIAL: &str = "material";
/// Written before a face column's name in its custom attribute
/// (`_FACE_NAME`), so that the reader knows it for a face column.
const FACE_PREFIX: &str = "FACE_";
/// The custom attribute (`_VERTEX_ID`, without its underscore as the
/// `gltf` crate names it) that carries each glTF vertex's mesh vertex.
const VERTEX_ID: &str = "VERTEX_ID";

/// How to read a glTF file beyond [`ReadOptions`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct GltfOptions {
    /// Read only the mesh of this index in the file's `meshes` (every
    /// instance of it in the scene); `None`: every mesh.
    pub mesh: Option<usize>,
}

crate::choice::setters!(GltfOptions {
    mesh: Option<usize>,
});

/// The two glTF encodings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GltfEncoding {
    /// JSON (`.gltf`) with the buffer inside as a base64 `data:` URI.
    Json,
    /// Binary glTF (`.glb`).
    #[default]
    Binary,
}

crate::choice::choices!(GltfEncoding {
    Json = "json",
    Binary = "binary",
});

/// How to write glTF.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct GltfWriteOptions {
    /// JSON or binary.
    pub encoding: GltfEncoding,
    /// glTF positions are 32-bit floats. A position out of their range is
    /// always refused (glTF positions must be finite); a nonzero
    /// coordinate that would become zero or subnormal (below about
    /// 1.2e-38 in magnitude) is refused too, unless this is set (default
    /// off: the writer never loses a position silently).
    pub allow_lossy_f32: bool,
}

crate::choice::setters!(GltfWriteOptions {
    encoding: GltfEncoding,
    allow_lossy_f32: bool,
});

/// Whether the path names a glTF file (`.gltf` or `.glb`,
/// case-insensitive), and which encoding.
pub fn encoding_of(path: impl AsRef<Path>) -> Option<GltfEncoding> {
    let ext = path.as_ref().extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "gltf" => Some(GltfEncoding::Json),
        "glb" => Some(GltfEncoding::Binary),
        _ => None,
    }
}

/// Read a `.gltf` or `.glb` file (buffers in other files are looked up
/// beside it), strictly.
///
/// # Errors
/// [`Error`] naming the file and, where it can, the byte (binary data) or
/// line (JSON): malformed JSON or GLB, an invalid reference, an index out
/// of range, a non-finite position, points or lines, triangles that cannot
/// form a half-edge mesh.
pub fn read_gltf(path: impl AsRef<Path>) -> Result<Mesh, Error> {
    read_gltf_with(path, &ReadOptions::strict(), &GltfOptions::default()).map(|(m, _)| m)
}

/// [`read_gltf`] with repair policies and glTF options.
///
/// # Errors
/// As [`read_gltf`], less what the policies repair.
///
/// ```
/// use meshloom::io::gltf::{read_gltf_with, GltfOptions};
/// use meshloom::io::ReadOptions;
/// # let path = "../shared/data/meshes/gltf/2CylinderEngine.glb";
/// # if std::path::Path::new(path).exists() {
/// let one = GltfOptions::default().mesh(Some(0));
/// let (mesh, _) = read_gltf_with(path, &ReadOptions::repair_all(), &one)?;
/// assert!(mesh.face_count() > 0);
/// # }
/// # Ok::<(), meshloom::io::Error>(())
/// ```
pub fn read_gltf_with(
    path: impl AsRef<Path>,
    options: &ReadOptions,
    gltf: &GltfOptions,
) -> Result<(Mesh, RepairReport), Error> {
    let path = path.as_ref();
    let bytes = super::source::read_all(
        std::fs::File::open(path).map_err(|e| Error::io(e).with_path(path))?,
        options.max_bytes,
        0,
    )
    .map_err(|e| e.with_path(path))?;
    read::read(&bytes, Some(path), options, gltf).map_err(|e| match e.location().path {
        Some(_) => e,
        None => e.with_path(path),
    })
}

/// Read glTF from bytes in memory (JSON or GLB, told by the first bytes).
/// Buffers must be inside (a `data:` URI or the GLB `BIN` chunk): there is
/// no folder to look in.
///
/// # Errors
/// As [`read_gltf`]; a buffer in another file is an
/// [`Error::UnsupportedFormat`].
pub fn read_gltf_bytes(
    bytes: &[u8],
    options: &ReadOptions,
    gltf: &GltfOptions,
) -> Result<(Mesh, RepairReport), Error> {
    read::read(bytes, None, options, gltf)
}

/// Write a mesh as glTF.
///
/// # Errors
/// [`Error::Unwritable`] without positions, past 2³² − 1 glTF vertices,
/// or for a position that 32-bit floats cannot hold (out of their range,
/// or a nonzero coordinate that would become zero or subnormal: see
/// [`GltfWriteOptions::allow_lossy_f32`]); [`Error::Io`].
///
/// ```
/// use meshloom::io::gltf::{read_gltf_bytes, write_gltf, GltfEncoding, GltfOptions};
/// let mut bytes = Vec::new();
/// write_gltf(&meshloom::shapes::icosahedron(), &mut bytes, GltfEncoding::Json)?;
/// assert!(bytes.starts_with(b"{"));
/// let (back, _) = read_gltf_bytes(&bytes, &Default::default(), &GltfOptions::default())?;
/// assert_eq!((back.vertex_count(), back.face_count()), (12, 20));
/// # Ok::<(), meshloom::io::Error>(())
/// ```
pub fn write_gltf(mesh: &Mesh, writer: impl Write, encoding: GltfEncoding) -> Result<(), Error> {
    let options = GltfWriteOptions {
        encoding,
        ..GltfWriteOptions::default()
    };
    write_gltf_with(mesh, writer, &options)
}

/// [`write_gltf`] with options: the encoding, and whether positions may
/// lose precision to glTF's 32-bit floats.
///
/// # Errors
/// As [`write_gltf`].
///
/// ```
/// use meshloom::io::gltf::{write_gltf_with, GltfEncoding, GltfWriteOptions};
/// let mut tiny = meshloom::shapes::tetrahedron();
/// let vs: Vec<_> = tiny.vertices().collect();
/// for v in vs {
///     let p = tiny.position(v)?;
///     tiny.set_position(v, p.map(|c| c * 1e-300))?;
/// }
/// let strict = GltfWriteOptions::default();
/// assert!(write_gltf_with(&tiny, Vec::new(), &strict).is_err());
/// let lossy = strict.allow_lossy_f32(true);
/// assert!(write_gltf_with(&tiny, Vec::new(), &lossy).is_ok());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_gltf_with(
    mesh: &Mesh,
    writer: impl Write,
    options: &GltfWriteOptions,
) -> Result<(), Error> {
    let bytes = write::write(mesh, options)?;
    super::emit(writer, &bytes)
}

/// A located error in the input (no path yet).
fn at_byte(offset: u64) -> Location {
    Location {
        path: None,
        position: Position::Byte(offset),
    }
}
