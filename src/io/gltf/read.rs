//! glTF reading, stage by stage: the container and its JSON (indices the
//! `gltf` crate would follow unchecked are checked first), the buffers,
//! the accessors (every offset, stride and count checked), then the scene
//! ([`super::scene`]), the weld ([`super::weld`]) and the soup
//! ([`super::gather`]) every reader ends in.

use std::path::{Path, PathBuf};

use gltf::accessor::{DataType, Dimensions};

use super::super::error::{Error, Location, Position};
use super::super::{ReadOptions, RepairReport};
use super::gather::Gather;
use super::{at_byte, base64, scene, weld, GltfOptions};
use crate::mesh::Mesh;

const JSON_CHUNK: u32 = 0x4E4F_534A;
const BIN_CHUNK: u32 = 0x004E_4942;

/// One buffer's bytes and where they sit in which file.
pub(super) struct Buffer {
    data: Vec<u8>,
    /// The file the bytes are in (`None`: the file being read).
    path: Option<PathBuf>,
    /// Offset of `data[0]` in that file (`None`: not file bytes, a `data:`
    /// URI).
    pub(super) base: Option<u64>,
}

impl Buffer {
    /// Whether the bytes are the GLB's own `BIN` chunk.
    pub(super) fn in_glb(&self) -> bool {
        self.path.is_none() && self.base.is_some()
    }

    /// Where byte `offset` of the buffer is (saturating: an offset from
    /// the file may be anything).
    fn at(&self, offset: usize) -> Location {
        Location {
            path: self.path.clone(),
            position: match self.base {
                Some(b) => Position::Byte(b.saturating_add(offset as u64)),
                None => Position::Whole,
            },
        }
    }
}

/// An accessor's values as `f64`, and where element `i` sits.
pub(super) struct Values {
    pub(super) data: Vec<f64>,
    pub(super) comps: usize,
    /// Byte offset of element 0 in its file (`None`: a `data:` URI).
    pub(super) first: Option<u64>,
    pub(super) stride: u64,
    /// The file (`None`: the file being read).
    pub(super) path: Option<PathBuf>,
    /// Whether the values are integers as stored (an integer component
    /// type, not normalized).
    pub(super) integer: bool,
}

impl Values {
    pub(super) fn count(&self) -> usize {
        self.data.len() / self.comps.max(1)
    }

    /// Element `i` (below [`count`](Self::count)).
    pub(super) fn get(&self, i: usize) -> &[f64] {
        self.data
            .get(i * self.comps..(i + 1) * self.comps)
            .unwrap_or(&[])
    }

    /// Byte offset of element `i` in its file.
    pub(super) fn offset(&self, i: usize) -> Option<u64> {
        self.first
            .map(|f| f.saturating_add((i as u64).saturating_mul(self.stride)))
    }

    pub(super) fn location(&self, i: usize) -> Location {
        Location {
            path: self.path.clone(),
            position: self.offset(i).map_or(Position::Whole, Position::Byte),
        }
    }
}

pub(super) fn unsupported(what: String) -> Error {
    Error::UnsupportedFormat {
        at: Location::whole(),
        what,
    }
}

pub(super) fn header(at: Location, message: String) -> Error {
    Error::Header { at, message }
}

/// The GLB `BIN` chunk and its offset in the file.
type BinChunk<'a> = Option<(&'a [u8], u64)>;

/// Split a GLB into its JSON chunk and its BIN chunk.
fn glb(bytes: &[u8]) -> Result<(&[u8], BinChunk<'_>), Error> {
    let u32_at = |at: usize| -> Result<u32, Error> {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .ok_or_else(|| Error::Truncated {
                at: at_byte(at as u64),
                expected: "a GLB header or chunk header".into(),
            })
    };
    let version = u32_at(4)?;
    if version != 2 {
        return Err(unsupported(format!(
            "GLB version {version} (only 2 is glTF 2.0)"
        )));
    }
    let length = u32_at(8)? as usize;
    if length > bytes.len() || length < 12 {
        return Err(header(
            at_byte(8),
            format!(
                "the GLB length {length} does not fit the {} bytes read",
                bytes.len()
            ),
        ));
    }
    let mut at = 12usize;
    let (mut json, mut bin) = (None, None);
    while at + 8 <= length {
        let (len, kind) = (u32_at(at)? as usize, u32_at(at + 4)?);
        let start = at + 8;
        let end = start
            .checked_add(len)
            .filter(|&e| e <= length)
            .ok_or_else(|| Error::Truncated {
                at: at_byte(at as u64),
                expected: format!("a chunk of {len} bytes"),
            })?;
        match kind {
            JSON_CHUNK if json.is_none() => json = Some(&bytes[start..end]),
            BIN_CHUNK if bin.is_none() && json.is_some() => {
                bin = Some((&bytes[start..end], start as u64))
            }
            _ => {}
        }
        at = end;
    }
    let json = json.ok_or_else(|| header(at_byte(12), "the GLB has no JSON chunk first".into()))?;
    Ok((json, bin))
}

/// Decode a `%XX` escaped relative URI.
fn percent_decode(s: &str) -> Vec<u8> {
    let b = s.as_bytes();
    let hex = |c: u8| (c as char).to_digit(16).map(|d| d as u8);
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push(h * 16 + l);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    out
}

/// Every buffer's bytes, the total capped by `budget`.
fn load_buffers(
    doc: &gltf::Document,
    bin: BinChunk<'_>,
    dir: Option<&Path>,
    mut budget: u64,
) -> Result<Vec<Buffer>, Error> {
    let mut out = Vec::new();
    for b in doc.buffers() {
        let i = b.index();
        let mut buffer = buffer_source(b.source(), i, bin, dir, budget)?;
        if buffer.data.len() < b.length() {
            return Err(Error::Truncated {
                at: Location {
                    path: buffer.path.clone(),
                    position: Position::Byte(buffer.data.len() as u64),
                },
                expected: format!("buffer {i} of {} bytes", b.length()),
            });
        }
        buffer.data.truncate(b.length());
        budget = budget.saturating_sub(buffer.data.len() as u64);
        out.push(buffer);
    }
    Ok(out)
}

/// The bytes of buffer `i`, from the GLB, a `data:` URI or a file beside
/// the one read.
fn buffer_source(
    source: gltf::buffer::Source<'_>,
    i: usize,
    bin: BinChunk<'_>,
    dir: Option<&Path>,
    budget: u64,
) -> Result<Buffer, Error> {
    match source {
        gltf::buffer::Source::Bin => {
            let (data, base) = bin.ok_or_else(|| {
                header(
                    Location::whole(),
                    format!("buffer {i} is the GLB BIN chunk, and there is none"),
                )
            })?;
            Ok(Buffer {
                data: data.to_vec(),
                path: None,
                base: Some(base),
            })
        }
        gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => Ok(Buffer {
            data: data_uri(uri, i, budget)?,
            path: None,
            base: None,
        }),
        gltf::buffer::Source::Uri(uri) => {
            if uri.contains(':') || uri.starts_with('/') || uri.starts_with('\\') {
                return Err(unsupported(format!(
                    "buffer {i} is at {uri:?}: only files beside the glTF file and data URIs are read"
                )));
            }
            let dir = dir.ok_or_else(|| {
                unsupported(format!(
                    "buffer {i} is in the file {uri:?}, and bytes in memory have no folder"
                ))
            })?;
            let name = String::from_utf8_lossy(&percent_decode(uri)).into_owned();
            let path = dir.join(name);
            let file = std::fs::File::open(&path).map_err(|e| Error::io(e).with_path(&path))?;
            let data =
                super::super::source::read_all(file, budget, 0).map_err(|e| e.with_path(&path))?;
            Ok(Buffer {
                data,
                path: Some(path),
                base: Some(0),
            })
        }
    }
}

/// The bytes of a base64 `data:` URI, within `budget`.
fn data_uri(uri: &str, i: usize, budget: u64) -> Result<Vec<u8>, Error> {
    let comma = uri.find(',').unwrap_or(uri.len());
    if !uri[..comma].ends_with(";base64") {
        return Err(unsupported(format!(
            "buffer {i}: a data URI that is not base64"
        )));
    }
    let text = &uri.as_bytes()[(comma + 1).min(uri.len())..];
    if text.len() as u64 / 4 * 3 > budget {
        return Err(Error::TooLarge {
            at: Location::whole(),
            what: format!("buffer {i} is larger than the byte limit left"),
        });
    }
    base64::decode(text).map_err(|k| Error::Syntax {
        at: Location::whole(),
        expected: format!("base64 in the data URI of buffer {i}"),
        found: format!("byte {k} of its data"),
    })
}

/// Where an accessor's elements lie in its buffer, every bound checked.
struct Layout {
    comps: usize,
    /// Bytes per component.
    size: usize,
    start: usize,
    stride: usize,
    count: usize,
}

/// The accessor's layout in `buffer`: its elements, `count` of them every
/// `stride` bytes from `start`, all within its buffer view and the buffer
/// (checked arithmetic: offsets from the file may be anything).
fn layout(acc: &gltf::Accessor, bufs: &[Buffer], what: &str) -> Result<(Layout, usize), Error> {
    let i = acc.index();
    if acc.sparse().is_some() {
        return Err(unsupported(format!("{what}: accessor {i} is sparse")));
    }
    let comps = match acc.dimensions() {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 => 4,
        other => {
            return Err(unsupported(format!(
                "{what}: accessor {i} holds {other:?} values"
            )))
        }
    };
    let size = match acc.data_type() {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    };
    let view = acc
        .view()
        .ok_or_else(|| unsupported(format!("{what}: accessor {i} has no buffer view")))?;
    let b = view.buffer().index();
    let buffer = bufs.get(b).ok_or_else(|| {
        header(
            Location::whole(),
            format!("{what}: accessor {i} names a missing buffer"),
        )
    })?;
    let elem = comps * size;
    let stride = view.stride().unwrap_or(elem);
    let count = acc.count();
    let start = view.offset().checked_add(acc.offset());
    let span = count.checked_sub(1).map_or(Some(0), |n| {
        n.checked_mul(stride).and_then(|s| s.checked_add(elem))
    });
    let end = start.zip(span).and_then(|(s, n)| s.checked_add(n));
    let view_end = view.offset().checked_add(view.length());
    let (Some(start), Some(end), Some(view_end)) = (start, end, view_end) else {
        return Err(Error::TooLarge {
            at: buffer.at(view.offset()),
            what: format!("{what}: accessor {i} spans more bytes than can be addressed"),
        });
    };
    if stride < elem || end > view_end || view_end > buffer.data.len() {
        return Err(Error::Truncated {
            at: buffer.at(start),
            expected: format!(
                "{what}: accessor {i}: {count} elements of {elem} bytes every {stride} bytes within buffer view {} ({} bytes from byte {})",
                view.index(),
                view.length(),
                view.offset()
            ),
        });
    }
    let layout = Layout {
        comps,
        size,
        start,
        stride,
        count,
    };
    Ok((layout, b))
}

/// Read an accessor with checked offsets; `what` names it in errors.
pub(super) fn read_accessor(
    acc: &gltf::Accessor,
    bufs: &[Buffer],
    what: &str,
) -> Result<Values, Error> {
    let (l, b) = layout(acc, bufs, what)?;
    let buffer = &bufs[b];
    let (ty, normalized) = (acc.data_type(), acc.normalized());
    let mut data = Vec::with_capacity(l.count * l.comps);
    for k in 0..l.count {
        let base = l.start + k * l.stride;
        for c in 0..l.comps {
            let o = base + c * l.size;
            data.push(component(&buffer.data[o..o + l.size], ty, normalized));
        }
    }
    Ok(Values {
        data,
        comps: l.comps,
        first: buffer.base.map(|b| b.saturating_add(l.start as u64)),
        stride: l.stride as u64,
        path: buffer.path.clone(),
        integer: !normalized && !matches!(ty, DataType::F32),
    })
}

/// One component of type `ty` from its little-endian bytes (`d` holds
/// exactly its size), scaled to [-1, 1] or [0, 1] when `normalized`.
fn component(d: &[u8], ty: DataType, normalized: bool) -> f64 {
    let (v, scale) = match ty {
        DataType::I8 => (f64::from(d[0] as i8), 127.0),
        DataType::U8 => (f64::from(d[0]), 255.0),
        DataType::I16 => (f64::from(i16::from_le_bytes([d[0], d[1]])), 32767.0),
        DataType::U16 => (f64::from(u16::from_le_bytes([d[0], d[1]])), 65535.0),
        DataType::U32 => return f64::from(u32::from_le_bytes([d[0], d[1], d[2], d[3]])),
        DataType::F32 => return f64::from(f32::from_le_bytes([d[0], d[1], d[2], d[3]])),
    };
    if normalized {
        (v / scale).max(-1.0)
    } else {
        v
    }
}

/// The container and its JSON as a validated document (bounds of
/// accessors excepted: they only help culling, and the values are checked
/// here anyway), and the GLB `BIN` chunk.
fn document(bytes: &[u8]) -> Result<(gltf::Document, BinChunk<'_>), Error> {
    let (json, bin) = if bytes.starts_with(b"glTF") {
        glb(bytes)?
    } else {
        (bytes, None)
    };
    let root: gltf::json::Root =
        gltf::json::deserialize::from_slice(json).map_err(|e| Error::Syntax {
            at: Location::line(e.line() as u64),
            expected: if bin.is_some() {
                "glTF JSON (in the GLB JSON chunk)"
            } else {
                "glTF JSON"
            }
            .into(),
            found: e.to_string(),
        })?;
    check_positions(&root)?;
    let doc = match gltf::Document::from_json(root.clone()) {
        Ok(doc) => doc,
        Err(gltf::Error::Validation(mut list)) => {
            list.retain(|(p, _)| !(p.as_str().ends_with(".min") || p.as_str().ends_with(".max")));
            if !list.is_empty() {
                let shown: Vec<String> = list
                    .iter()
                    .take(3)
                    .map(|(p, err)| format!("{}: {err}", p.as_str()))
                    .collect();
                return Err(header(
                    Location::whole(),
                    format!(
                        "invalid glTF ({} problems): {}",
                        list.len(),
                        shown.join("; ")
                    ),
                ));
            }
            gltf::Document::from_json_without_validation(root)
        }
        Err(other) => return Err(header(Location::whole(), format!("invalid glTF: {other}"))),
    };
    Ok((doc, bin))
}

/// Every primitive's `POSITION` names an accessor that exists. The `gltf`
/// crate's validation looks the accessor up unchecked (gltf-json 1.4
/// panics on a missing one), so this runs before it.
fn check_positions(root: &gltf::json::Root) -> Result<(), Error> {
    use gltf::json::validation::Checked;
    let position = Checked::Valid(gltf::json::mesh::Semantic::Positions);
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let Some(acc) = prim.attributes.get(&position) else {
                continue;
            };
            if acc.value() >= root.accessors.len() {
                return Err(header(
                    Location::whole(),
                    format!(
                        "invalid glTF: meshes[{m}].primitives[{p}].attributes.POSITION names accessor {}, and there are {}",
                        acc.value(),
                        root.accessors.len()
                    ),
                ));
            }
        }
    }
    Ok(())
}

pub(super) fn read(
    bytes: &[u8],
    path: Option<&Path>,
    options: &ReadOptions,
    pick: &GltfOptions,
) -> Result<(Mesh, RepairReport), Error> {
    let (doc, bin) = document(bytes)?;
    let budget = options.max_bytes.saturating_sub(bytes.len() as u64);
    let bufs = load_buffers(&doc, bin, path.and_then(Path::parent), budget)?;
    let instances = scene::instances(&doc, pick)?;
    let mut gather = Gather::new(bufs.iter().all(Buffer::in_glb));
    // The elements read (every instance reads its mesh's accessors again)
    // and the corners made are bounded by the byte limit, so a scene of
    // many instances of a large mesh is an error, not a long wait.
    let mut budget = usize::try_from(options.max_bytes / 4).unwrap_or(usize::MAX);
    for (m, mesh) in &instances {
        let instance = scene::read_instance(mesh, m, &bufs, budget)?;
        budget = budget.saturating_sub(instance.work);
        let welded = weld::weld(&instance)?;
        gather.add(&instance, &welded, mesh.index())?;
    }
    gather.finish(options)
}
