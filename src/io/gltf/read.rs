//! glTF reading: container, buffers, accessors (all checked here), scene
//! walk, welding, and the soup every reader ends in.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::{Mode, Semantic};

use super::super::attrs::{Data, SoupColumn};
use super::super::error::{Error, Location, Position};
use super::super::soup::Soup;
use super::super::{ReadOptions, RepairReport};
use super::{at_byte, base64, GltfOptions, FACE_PREFIX, MATERIAL};
use crate::buffers::{weld, Weld};
use crate::mesh::Mesh;

const JSON_CHUNK: u32 = 0x4E4F_534A;
const BIN_CHUNK: u32 = 0x004E_4942;

type M4 = [[f64; 4]; 4];
const IDENTITY: M4 = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// One buffer's bytes and where they sit in which file.
struct Buffer {
    data: Vec<u8>,
    /// The file the bytes are in (`None`: the file being read).
    path: Option<PathBuf>,
    /// Offset of `data[0]` in that file (`None`: not file bytes, a `data:`
    /// URI).
    base: Option<u64>,
}

/// An accessor's values as `f64`, and where element `i` sits.
struct Values {
    data: Vec<f64>,
    comps: usize,
    first: Option<u64>,
    stride: u64,
    path: Option<PathBuf>,
}

impl Values {
    fn count(&self) -> usize {
        self.data.len() / self.comps.max(1)
    }

    fn get(&self, i: usize) -> &[f64] {
        &self.data[i * self.comps..(i + 1) * self.comps]
    }

    fn location(&self, i: usize) -> Location {
        Location {
            path: self.path.clone(),
            position: match self.first {
                Some(b) => Position::Byte(b + i as u64 * self.stride),
                None => Position::Whole,
            },
        }
    }
}

fn unsupported(what: String) -> Error {
    Error::UnsupportedFormat {
        at: Location::whole(),
        what,
    }
}

fn header(at: Location, message: String) -> Error {
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
        let mut buffer = match b.source() {
            gltf::buffer::Source::Bin => {
                let (data, base) = bin.ok_or_else(|| {
                    header(
                        Location::whole(),
                        format!("buffer {i} is the GLB BIN chunk, and there is none"),
                    )
                })?;
                Buffer {
                    data: data.to_vec(),
                    path: None,
                    base: Some(base),
                }
            }
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
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
                let data = base64::decode(text).map_err(|k| Error::Syntax {
                    at: Location::whole(),
                    expected: format!("base64 in the data URI of buffer {i}"),
                    found: format!("byte {k} of its data"),
                })?;
                Buffer {
                    data,
                    path: None,
                    base: None,
                }
            }
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
                let data = super::super::source::read_all(file, budget, 0)
                    .map_err(|e| e.with_path(&path))?;
                Buffer {
                    data,
                    path: Some(path),
                    base: Some(0),
                }
            }
        };
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

/// Read an accessor with checked offsets; `what` names it in errors.
fn read_accessor(acc: &gltf::Accessor, bufs: &[Buffer], what: &str) -> Result<Values, Error> {
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
    let buffer = bufs.get(view.buffer().index()).ok_or_else(|| {
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
    let at = |offset: usize| Location {
        path: buffer.path.clone(),
        position: match buffer.base {
            Some(b) => Position::Byte(b + offset as u64),
            None => Position::Whole,
        },
    };
    let (Some(start), Some(end), Some(view_end)) = (start, end, view_end) else {
        return Err(Error::TooLarge {
            at: at(view.offset()),
            what: format!("{what}: accessor {i} spans more bytes than can be addressed"),
        });
    };
    if stride < elem || end > view_end || view_end > buffer.data.len() {
        return Err(Error::Truncated {
            at: at(start),
            expected: format!(
                "{what}: accessor {i}: {count} elements of {elem} bytes every {stride} bytes within buffer view {} ({} bytes from byte {})",
                view.index(),
                view.length(),
                view.offset()
            ),
        });
    }
    let normalized = acc.normalized();
    let d = &buffer.data;
    let mut data = Vec::with_capacity(count * comps);
    for k in 0..count {
        let base = start + k * stride;
        for c in 0..comps {
            let o = base + c * size;
            let x = match acc.data_type() {
                DataType::I8 => {
                    let v = f64::from(d[o] as i8);
                    if normalized {
                        (v / 127.0).max(-1.0)
                    } else {
                        v
                    }
                }
                DataType::U8 => {
                    let v = f64::from(d[o]);
                    if normalized {
                        v / 255.0
                    } else {
                        v
                    }
                }
                DataType::I16 => {
                    let v = f64::from(i16::from_le_bytes([d[o], d[o + 1]]));
                    if normalized {
                        (v / 32767.0).max(-1.0)
                    } else {
                        v
                    }
                }
                DataType::U16 => {
                    let v = f64::from(u16::from_le_bytes([d[o], d[o + 1]]));
                    if normalized {
                        v / 65535.0
                    } else {
                        v
                    }
                }
                DataType::U32 => {
                    f64::from(u32::from_le_bytes([d[o], d[o + 1], d[o + 2], d[o + 3]]))
                }
                DataType::F32 => {
                    f64::from(f32::from_le_bytes([d[o], d[o + 1], d[o + 2], d[o + 3]]))
                }
            };
            data.push(x);
        }
    }
    Ok(Values {
        data,
        comps,
        first: buffer.base.map(|b| b + start as u64),
        stride: stride as u64,
        path: buffer.path.clone(),
    })
}

/// A node's matrix, column-major, in f64.
fn matrix(node: &gltf::Node) -> M4 {
    node.transform().matrix().map(|c| c.map(f64::from))
}

fn mul(a: &M4, b: &M4) -> M4 {
    let mut m = [[0.0; 4]; 4];
    for (c, col) in m.iter_mut().enumerate() {
        for (r, x) in col.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[k][r] * b[c][k]).sum();
        }
    }
    m
}

fn apply(m: &M4, p: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|r| m[0][r] * p[0] + m[1][r] * p[1] + m[2][r] * p[2] + m[3][r])
}

/// The cofactor matrix of the upper 3×3 (rows), and its determinant:
/// normals go by it (the inverse transpose up to a positive scale when
/// the determinant is positive).
fn normal_matrix(m: &M4) -> ([[f64; 3]; 3], f64) {
    let a = |r: usize, c: usize| m[c][r];
    let cof = |r: usize, c: usize| {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
        a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1)
    };
    let n: [[f64; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|c| cof(r, c)));
    let det = a(0, 0) * n[0][0] + a(0, 1) * n[0][1] + a(0, 2) * n[0][2];
    (n, det)
}

/// One attribute gathered over the whole file.
struct Gathered {
    /// Whether it may be a vertex column (`COLOR_n`, custom).
    vertex_kind: bool,
    comps: usize,
    /// Where it was first met, for errors.
    first_seen: String,
    corner: Vec<f64>,
    corner_present: Vec<bool>,
    vertex: Vec<f64>,
    vertex_present: Vec<bool>,
    /// Copies of a welded vertex disagree: not a vertex column.
    disagree: bool,
}

/// The column name of an attribute, and whether it may be a vertex column.
fn column_of(semantic: &Semantic) -> Option<(String, bool)> {
    let numbered = |base: &str, n: u32| {
        if n == 0 {
            base.to_owned()
        } else {
            format!("{base}{n}")
        }
    };
    match semantic {
        Semantic::Normals => Some(("normal".into(), false)),
        Semantic::TexCoords(n) => Some((numbered("texcoord", *n), false)),
        Semantic::Colors(n) => Some((numbered("color", *n), true)),
        Semantic::Extras(name) => Some((name.clone(), true)),
        _ => None,
    }
}

pub(super) fn read(
    bytes: &[u8],
    path: Option<&Path>,
    options: &ReadOptions,
    pick: &GltfOptions,
) -> Result<(Mesh, RepairReport), Error> {
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
    // Validation, except the bounds of accessors: they only help culling,
    // and a file whose bounds are missing is read (its values are checked
    // here anyway, non-finite positions included).
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
    let budget = options.max_bytes.saturating_sub(bytes.len() as u64);
    let bufs = load_buffers(&doc, bin, path.and_then(Path::parent), budget)?;

    // Mesh instances, in scene order, with their world matrices.
    let mut instances: Vec<(M4, gltf::Mesh)> = Vec::new();
    match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => {
            let mut stack: Vec<(gltf::Node, M4)> =
                scene.nodes().map(|n| (n, IDENTITY)).collect::<Vec<_>>();
            stack.reverse();
            let limit = doc.nodes().len().saturating_mul(4) + 16;
            let mut visits = 0usize;
            while let Some((node, parent)) = stack.pop() {
                visits += 1;
                if visits > limit {
                    return Err(header(
                        Location::whole(),
                        format!(
                            "node {} is reached again and again: the node hierarchy is not a tree",
                            node.index()
                        ),
                    ));
                }
                let m = mul(&parent, &matrix(&node));
                if let Some(mesh) = node.mesh() {
                    instances.push((m, mesh));
                }
                let children: Vec<_> = node.children().collect();
                stack.extend(children.into_iter().rev().map(|c| (c, m)));
            }
        }
        None => instances.extend(doc.meshes().map(|m| (IDENTITY, m))),
    }
    if let Some(i) = pick.mesh {
        let Some(mesh) = doc.meshes().nth(i) else {
            return Err(unsupported(format!(
                "there is no mesh {i} to pick (the file has {})",
                doc.meshes().len()
            )));
        };
        instances.retain(|(_, m)| m.index() == i);
        if instances.is_empty() {
            instances.push((IDENTITY, mesh));
        }
    }

    let mut soup = Soup::new(false);
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut face_at: Vec<u64> = Vec::new();
    let mut vertex_at: Vec<u64> = Vec::new();
    let mut all_in_file = true;
    let mut materials: Vec<Option<String>> = Vec::new();
    let mut gathered: BTreeMap<String, Gathered> = BTreeMap::new();
    let corner_limit = options.max_bytes / 4;
    let in_glb = bufs.iter().all(|b| b.path.is_none() && b.base.is_some());
    for (m, mesh) in &instances {
        let (nmat, det) = normal_matrix(m);
        // The instance's vertices (referenced ones only) and triangles.
        let mut local: Vec<[f64; 3]> = Vec::new();
        let mut local_at: Vec<Option<u64>> = Vec::new();
        let mut tris: Vec<([u32; 3], Option<u64>, Option<String>)> = Vec::new();
        let mut attrs: BTreeMap<String, (bool, usize, Vec<f64>, Vec<bool>)> = BTreeMap::new();
        for prim in mesh.primitives() {
            let what = format!("mesh {} primitive {}", mesh.index(), prim.index());
            let mode = prim.mode();
            if !matches!(
                mode,
                Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
            ) {
                return Err(unsupported(format!(
                    "{what} has mode {mode:?}: only triangles, strips and fans hold faces"
                )));
            }
            let pos_acc = prim
                .get(&Semantic::Positions)
                .ok_or_else(|| header(Location::whole(), format!("{what} has no POSITION")))?;
            let pos = read_accessor(&pos_acc, &bufs, &format!("{what} POSITION"))?;
            if pos.comps != 3 {
                return Err(header(
                    Location::whole(),
                    format!("{what}: POSITION is not VEC3"),
                ));
            }
            let n = pos.count();
            // Triangle corners as accessor elements.
            let (idx, idx_at): (Vec<u32>, Option<Values>) = match prim.indices() {
                Some(acc) => {
                    let v = read_accessor(&acc, &bufs, &format!("{what} indices"))?;
                    let list: Vec<u32> = v.data.iter().map(|&x| x as u32).collect();
                    if let Some(k) = list.iter().position(|&x| x as usize >= n) {
                        return Err(Error::IndexOutOfRange {
                            at: v.location(k),
                            what: "vertex",
                            index: i64::from(list[k]),
                            count: n,
                        });
                    }
                    (list, Some(v))
                }
                None => ((0..n as u32).collect(), None),
            };
            let corners_at = |k: usize| {
                idx_at
                    .as_ref()
                    .and_then(|v| v.first.map(|f| f + k as u64 * v.stride))
            };
            let mut prim_tris: Vec<([u32; 3], Option<u64>)> = Vec::new();
            match mode {
                Mode::Triangles => {
                    for (t, c) in idx.chunks_exact(3).enumerate() {
                        prim_tris.push(([c[0], c[1], c[2]], corners_at(3 * t)));
                    }
                }
                Mode::TriangleStrip => {
                    for i in 0..idx.len().saturating_sub(2) {
                        let c = if i % 2 == 0 {
                            [idx[i], idx[i + 1], idx[i + 2]]
                        } else {
                            [idx[i + 1], idx[i], idx[i + 2]]
                        };
                        prim_tris.push((c, corners_at(i)));
                    }
                }
                _ => {
                    for i in 1..idx.len().saturating_sub(1) {
                        prim_tris.push(([idx[0], idx[i], idx[i + 1]], corners_at(i)));
                    }
                }
            }
            if tris.len() + prim_tris.len() > corner_limit as usize / 3 {
                return Err(Error::TooLarge {
                    at: Location::whole(),
                    what: "more triangles than the byte limit allows".into(),
                });
            }
            // Keep only the elements the triangles use, in first-use order.
            let mut remap = vec![u32::MAX; n];
            let mut used: Vec<usize> = Vec::new();
            for (c, _) in &mut prim_tris {
                for x in c.iter_mut() {
                    let r = &mut remap[*x as usize];
                    if *r == u32::MAX {
                        *r = (local.len() + used.len()) as u32;
                        used.push(*x as usize);
                    }
                    *x = *r;
                }
            }
            for &e in &used {
                let q = pos.get(e);
                let p = [q[0], q[1], q[2]];
                if !p.iter().all(|c| c.is_finite()) {
                    return Err(Error::NonFinite {
                        at: pos.location(e),
                        vertex: e,
                        position: p,
                    });
                }
                local.push(apply(m, p));
                local_at.push(
                    pos.first
                        .filter(|_| pos.path.is_none())
                        .map(|f| f + e as u64 * pos.stride),
                );
            }
            let material = prim.material().name().map(str::to_owned);
            for (c, at) in prim_tris {
                tris.push((c, at, material.clone()));
            }
            // Attributes of the used elements; absent for earlier primitives.
            let before = local.len() - used.len();
            let mut seen: Vec<String> = Vec::new();
            for (semantic, acc) in prim.attributes() {
                let Some((name, vertex_kind)) = column_of(&semantic) else {
                    continue;
                };
                let vals = read_accessor(&acc, &bufs, &format!("{what} {}", semantic.to_string()))?;
                if vals.count() != n {
                    return Err(header(
                        Location::whole(),
                        format!(
                            "{what}: {} has {} elements, POSITION {n}",
                            semantic.to_string(),
                            vals.count()
                        ),
                    ));
                }
                let entry = attrs.entry(name.clone()).or_insert_with(|| {
                    (
                        vertex_kind,
                        vals.comps,
                        vec![0.0; before * vals.comps],
                        vec![false; before],
                    )
                });
                if entry.1 != vals.comps {
                    return Err(unsupported(format!(
                        "{what}: {} has {} values per vertex where another primitive has {}; read one mesh with GltfOptions::mesh",
                        semantic.to_string(),
                        vals.comps,
                        entry.1
                    )));
                }
                for &e in &used {
                    let mut v = vals.get(e).to_vec();
                    if name == "normal" {
                        let s = det.signum();
                        let t: [f64; 3] = std::array::from_fn(|r| {
                            s * (nmat[r][0] * v[0] + nmat[r][1] * v[1] + nmat[r][2] * v[2])
                        });
                        let l = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
                        v = if l > 0.0 {
                            t.map(|c| c / l).to_vec()
                        } else {
                            t.to_vec()
                        };
                    }
                    entry.2.extend(v);
                    entry.3.push(true);
                }
                seen.push(name);
            }
            for (name, entry) in attrs.iter_mut() {
                if !seen.contains(name) {
                    entry
                        .2
                        .extend(std::iter::repeat_n(0.0, used.len() * entry.1));
                    entry.3.extend(std::iter::repeat_n(false, used.len()));
                }
            }
        }
        // Weld the instance and add it to the soup.
        let (rep, welded) =
            weld(&local, Weld::Exact).map_err(|e| header(Location::whole(), e.to_string()))?;
        let base = positions.len() as u32;
        let mut first_copy = vec![usize::MAX; welded.len()];
        for (i, &r) in rep.iter().enumerate() {
            if first_copy[r as usize] == usize::MAX {
                first_copy[r as usize] = i;
            }
        }
        positions.extend_from_slice(&welded);
        for &i in &first_copy {
            match local_at[i] {
                Some(b) => vertex_at.push(b),
                None => {
                    all_in_file = false;
                    vertex_at.push(0);
                }
            }
        }
        let corners_before = soup.polygons.indices.len();
        let vertices_before = base as usize;
        for (name, (vertex_kind, comps, values, present)) in &attrs {
            let g = gathered.entry(name.clone()).or_insert_with(|| Gathered {
                vertex_kind: *vertex_kind,
                comps: *comps,
                first_seen: format!("mesh {}", mesh.index()),
                corner: vec![0.0; corners_before * comps],
                corner_present: vec![false; corners_before],
                vertex: vec![0.0; vertices_before * comps],
                vertex_present: vec![false; vertices_before],
                disagree: false,
            });
            if g.comps != *comps {
                return Err(unsupported(format!(
                    "attribute {name:?} has {comps} values per vertex in mesh {} and {} in {}; read one mesh with GltfOptions::mesh",
                    mesh.index(),
                    g.comps,
                    g.first_seen
                )));
            }
            // Vertex values: the first copy's; do the other copies agree?
            for &i in &first_copy {
                g.vertex
                    .extend_from_slice(&values[i * comps..(i + 1) * comps]);
                g.vertex_present.push(present[i]);
            }
            for (i, &r) in rep.iter().enumerate() {
                let j = first_copy[r as usize];
                if present[i] != present[j]
                    || values[i * comps..(i + 1) * comps] != values[j * comps..(j + 1) * comps]
                {
                    g.disagree = true;
                }
            }
        }
        for (c, at, material) in tris {
            let mut w = c.map(|x| rep[x as usize]);
            let mut c = c;
            if det < 0.0 {
                w.swap(1, 2);
                c.swap(1, 2);
            }
            if w[0] == w[1] || w[1] == w[2] || w[2] == w[0] {
                continue;
            }
            soup.polygons.indices.extend(w.map(|x| x + base));
            soup.polygons
                .offsets
                .push(soup.polygons.indices.len() as u32);
            match at {
                Some(b) if in_glb => face_at.push(b),
                _ => {
                    all_in_file = false;
                    face_at.push(0);
                }
            }
            materials.push(material);
            for (name, (_, comps, values, present)) in &attrs {
                let g = gathered.get_mut(name).expect("gathered above");
                for &x in &c {
                    let x = x as usize;
                    g.corner
                        .extend_from_slice(&values[x * comps..(x + 1) * comps]);
                    g.corner_present.push(present[x]);
                }
            }
        }
        // Attributes this instance lacks stay absent here.
        let corners_now = soup.polygons.indices.len();
        for (name, g) in gathered.iter_mut() {
            if !attrs.contains_key(name) {
                g.corner.resize(corners_now * g.comps, 0.0);
                g.corner_present.resize(corners_now, false);
                g.vertex.resize(positions.len() * g.comps, 0.0);
                g.vertex_present.resize(positions.len(), false);
            }
        }
    }
    soup.polygons.positions = positions;
    if all_in_file {
        soup.record = true;
        soup.binary = true;
        soup.face_at = face_at;
        soup.vertex_at = vertex_at;
    }
    for (name, g) in gathered {
        if let Some(column) = face_column(&name, &g) {
            soup.attrs.face.push(column);
            continue;
        }
        let vertex = g.vertex_kind && !g.disagree;
        let (values, present) = if vertex {
            (g.vertex, g.vertex_present)
        } else {
            (g.corner, g.corner_present)
        };
        let column = SoupColumn {
            name,
            data: data_of(values, g.comps),
            present: (!present.iter().all(|&p| p)).then_some(present),
        };
        if vertex {
            soup.attrs.vertex.push(column);
        } else {
            soup.attrs.corner.push(column);
        }
    }
    if materials.iter().any(Option::is_some) && !soup.attrs.face.iter().any(|c| c.name == MATERIAL)
    {
        let present: Vec<bool> = materials.iter().map(Option::is_some).collect();
        let names: Vec<String> = materials
            .into_iter()
            .map(Option::unwrap_or_default)
            .collect();
        soup.attrs.face.push(SoupColumn {
            name: MATERIAL.into(),
            data: Data::Text(names),
            present: (!present.iter().all(|&p| p)).then_some(present),
        });
    }
    soup.finish(options)
}

/// Values of `comps` numbers apiece as soup data.
fn data_of(values: Vec<f64>, comps: usize) -> Data {
    match comps {
        1 => Data::Scalar(values),
        2 => Data::Vec2(values.chunks_exact(2).map(|c| [c[0], c[1]]).collect()),
        3 => Data::Vec3(values.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()),
        _ => Data::Vec4(
            values
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2], c[3]])
                .collect(),
        ),
    }
}

/// A custom attribute `_FACE_NAME` (as meshloom writes a face column) as
/// the face column `NAME`, when its values are the same at the three
/// corners of every triangle; `None` otherwise (it is then read as any
/// other custom attribute, under the name `FACE_NAME`).
fn face_column(name: &str, g: &Gathered) -> Option<SoupColumn> {
    let face = name.strip_prefix(FACE_PREFIX).filter(|f| !f.is_empty())?;
    if !g.vertex_kind {
        return None;
    }
    let k = g.comps;
    let corner = |c: usize| (g.corner_present[c], &g.corner[c * k..(c + 1) * k]);
    let same = |a: (bool, &[f64]), b: (bool, &[f64])| {
        a.0 == b.0 && a.1.iter().zip(b.1).all(|(x, y)| x.to_bits() == y.to_bits())
    };
    let triangles = g.corner_present.len() / 3;
    let constant = (0..triangles)
        .all(|t| same(corner(3 * t), corner(3 * t + 1)) && same(corner(3 * t), corner(3 * t + 2)));
    if !constant {
        return None;
    }
    let mut values = Vec::with_capacity(triangles * k);
    let mut present = Vec::with_capacity(triangles);
    for t in 0..triangles {
        let (has, v) = corner(3 * t);
        values.extend_from_slice(v);
        present.push(has);
    }
    Some(SoupColumn {
        name: face.to_owned(),
        data: data_of(values, k),
        present: (!present.iter().all(|&p| p)).then_some(present),
    })
}
