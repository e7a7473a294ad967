//! glTF writing: one mesh, one buffer, one primitive per material, from
//! the engine buffers, split further where face columns differ.

use std::collections::HashMap;

use serde_json::{json, Value as Json};

use super::super::error::{Error, Location};
use super::{base64, GltfEncoding, GltfWriteOptions, FACE_PREFIX, MATERIAL, VERTEX_ID};
use crate::attr::{Value, ValueType};
use crate::buffers::{ColumnChoice, Reader, TriangleBufferOptions};
use crate::keys::{ElementKind, FaceKey};
use crate::mesh::Mesh;

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_SHORT: u32 = 5123;
const UNSIGNED_INT: u32 = 5125;

fn unwritable(what: String) -> Error {
    Error::Unwritable {
        at: Location::whole(),
        what,
    }
}

/// The glTF attribute name of a column of `comps` values.
fn semantic(name: &str, comps: usize) -> String {
    let numbered = |base: &str| -> Option<u32> {
        let rest = name.strip_prefix(base)?;
        if rest.is_empty() {
            Some(0)
        } else {
            rest.parse().ok().filter(|&n| n > 0)
        }
    };
    match (numbered("texcoord"), numbered("color")) {
        _ if name == "normal" && comps == 3 => "NORMAL".into(),
        (Some(n), _) if comps == 2 => format!("TEXCOORD_{n}"),
        (_, Some(n)) if comps == 3 || comps == 4 => format!("COLOR_{n}"),
        _ => format!("_{name}"),
    }
}

/// Whether a column's values may be numbers.
fn numeric(ty: Option<ValueType>) -> bool {
    !matches!(ty, None | Some(ValueType::Bool | ValueType::Text))
}

/// The most vertices whose `_VERTEX_ID`s are written: every vertex number
/// up to it is exact in a 32-bit float (glTF forbids unsigned int custom
/// attributes). Larger meshes are written without, and read back welded
/// by position.
const MAX_VERTEX_IDS: usize = 1 << 24;

/// Each buffer vertex's mesh vertex, numbered in the mesh's vertex order
/// (`None` past [`MAX_VERTEX_IDS`] vertices).
fn vertex_ids(mesh: &Mesh, sources: &[crate::keys::VertexKey]) -> Option<Vec<f32>> {
    if mesh.vertex_count() > MAX_VERTEX_IDS {
        return None;
    }
    let slots = mesh.vertices().map(|v| v.index() + 1).max().unwrap_or(0);
    let mut dense = vec![0u32; slots];
    for (i, v) in mesh.vertices().enumerate() {
        dense[v.index()] = i as u32;
    }
    let ids = sources
        .iter()
        .map(|v| dense.get(v.index()).copied().unwrap_or(0) as f32)
        .collect();
    Some(ids)
}

pub(super) fn write(mesh: &Mesh, options: &GltfWriteOptions) -> Result<Vec<u8>, Error> {
    if !mesh.has_positions() {
        return Err(unwritable("the mesh has no vertex positions".into()));
    }
    if mesh.face_count() == 0 {
        return Err(unwritable("the mesh has no faces".into()));
    }
    super::super::check_f32_positions(
        mesh,
        "glTF",
        options.allow_lossy_f32,
        Some("GltfWriteOptions::allow_lossy_f32"),
    )?;
    let b = triangle_buffers(mesh)?;
    let faces = face_columns(mesh)?;
    let width: usize = faces.iter().map(|c| c.reader.components()).sum();
    let triangle_values = triangle_face_values(&faces, &b.triangle_faces, width);
    let split = split_by_face_values(
        b.vertex_count(),
        &b.indices.to_u32(),
        &triangle_values,
        width,
    )?;
    let (material_names, triangle_material) = materials(mesh, &b.triangle_faces);
    let mut out = Binary::new(split.source.len());
    let mut attributes = vertex_attributes(mesh, &b, &split, &mut out);
    face_attributes(&faces, &split, width, &mut attributes, &mut out);
    let primitives = primitives(&attributes, &triangle_material, &split.corners, &mut out);
    let (text, bin) = document(out, primitives, &material_names, options.encoding)?;
    match options.encoding {
        GltfEncoding::Json => Ok(text),
        GltfEncoding::Binary => glb(&text, &bin),
    }
}

/// The mesh as triangle buffers split at corner values, with every
/// numeric corner column and every other numeric vertex column.
fn triangle_buffers(mesh: &Mesh) -> Result<crate::buffers::TriangleBuffers, Error> {
    let mut columns: Vec<ColumnChoice> = mesh
        .attr_info(ElementKind::Halfedge)
        .into_iter()
        .filter(|a| numeric(a.value_type))
        .map(|a| ColumnChoice::corner(&a.name))
        .collect();
    for a in mesh.attr_info(ElementKind::Vertex) {
        if a.name != crate::attr::POSITION
            && numeric(a.value_type)
            && !columns.iter().any(|c| c.name == a.name)
        {
            columns.push(ColumnChoice::vertex(&a.name));
        }
    }
    let options = TriangleBufferOptions {
        normals: None,
        columns,
        ..TriangleBufferOptions::default()
    };
    let b = mesh
        .to_triangle_buffers(&options)
        .map_err(|e| unwritable(e.to_string()))?;
    if b.positions.iter().flatten().any(|c| !c.is_finite()) {
        return Err(unwritable(
            "a position is too large for a 32-bit float".into(),
        ));
    }
    Ok(b)
}

/// `POSITION` (with its bounds), `_VERTEX_ID` and the columns' attributes
/// of the written vertices.
fn vertex_attributes(
    mesh: &Mesh,
    b: &crate::buffers::TriangleBuffers,
    split: &FaceSplit,
    out: &mut Binary,
) -> serde_json::Map<String, Json> {
    let mut attributes = serde_json::Map::new();
    let positions: Vec<[f32; 3]> = split
        .source
        .iter()
        .map(|&o| b.positions[o as usize])
        .collect();
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let flat: Vec<f32> = positions.into_iter().flatten().collect();
    let at = out.floats(&flat, 3, json!({"min": lo, "max": hi}));
    attributes.insert("POSITION".into(), json!(at));
    if let Some(ids) = vertex_ids(mesh, &b.vertex_sources) {
        let ids: Vec<f32> = split.source.iter().map(|&o| ids[o as usize]).collect();
        let at = out.floats(&ids, 1, json!({}));
        attributes.insert(format!("_{VERTEX_ID}"), json!(at));
    }
    for c in &b.columns {
        let name = semantic(&c.name, c.components);
        if attributes.contains_key(&name) {
            continue;
        }
        let k = c.components;
        let data: Vec<f32> = split
            .source
            .iter()
            .flat_map(|&o| &c.data[o as usize * k..(o as usize + 1) * k])
            .copied()
            .collect();
        let at = out.floats(&data, k, json!({}));
        attributes.insert(name, json!(at));
    }
    attributes
}

/// The face columns as `_FACE_NAME` attributes of the written vertices.
fn face_attributes(
    faces: &[FaceColumn<'_>],
    split: &FaceSplit,
    width: usize,
    attributes: &mut serde_json::Map<String, Json>,
    out: &mut Binary,
) {
    let mut first = 0;
    for c in faces {
        let k = c.reader.components();
        let name = format!("_{FACE_PREFIX}{}", c.name);
        if !attributes.contains_key(&name) {
            let data: Vec<f32> = split
                .values
                .chunks_exact(width)
                .flat_map(|v| &v[first..first + k])
                .copied()
                .collect();
            let at = out.floats(&data, k, json!({}));
            attributes.insert(name, json!(at));
        }
        first += k;
    }
}

/// One primitive per material, in order of first use; the triangles with
/// none in one more, without a material. They share the attributes.
fn primitives(
    attributes: &serde_json::Map<String, Json>,
    triangle_material: &[Option<u32>],
    corners: &[u32],
    out: &mut Binary,
) -> Vec<Json> {
    let mut groups: Vec<(Option<u32>, Vec<u32>)> = Vec::new();
    for (t, m) in triangle_material.iter().enumerate() {
        let at = match groups.iter().position(|(g, _)| g == m) {
            Some(at) => at,
            None => {
                groups.push((*m, Vec::new()));
                groups.len() - 1
            }
        };
        groups[at].1.extend_from_slice(&corners[3 * t..3 * t + 3]);
    }
    groups
        .iter()
        .map(|(m, corners)| {
            let mut prim =
                json!({"attributes": attributes, "indices": out.indices(corners), "mode": 4});
            if let Some(m) = m {
                prim["material"] = json!(m);
            }
            prim
        })
        .collect()
}

/// The JSON document and the binary buffer (inside the JSON as a `data:`
/// URI for [`GltfEncoding::Json`]).
fn document(
    out: Binary,
    primitives: Vec<Json>,
    material_names: &[String],
    encoding: GltfEncoding,
) -> Result<(Vec<u8>, Vec<u8>), Error> {
    let Binary {
        mut bin,
        views,
        accessors,
        ..
    } = out;
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let mut buffer = json!({"byteLength": bin.len()});
    if encoding == GltfEncoding::Json {
        buffer["uri"] = json!(format!(
            "data:application/octet-stream;base64,{}",
            base64::encode(&bin)
        ));
    }
    let mut doc = json!({
        "asset": {"version": "2.0", "generator": concat!("meshloom ", env!("CARGO_PKG_VERSION"))},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": primitives}],
        "buffers": [buffer],
        "bufferViews": views,
        "accessors": accessors,
    });
    if !material_names.is_empty() {
        doc["materials"] = material_names.iter().map(|n| json!({"name": n})).collect();
    }
    let text = serde_json::to_vec(&doc).map_err(|e| unwritable(e.to_string()))?;
    Ok((text, bin))
}

/// The GLB container: header, JSON chunk (padded with spaces), BIN chunk.
fn glb(text: &[u8], bin: &[u8]) -> Result<Vec<u8>, Error> {
    let json_len = text.len().next_multiple_of(4);
    let total = 12 + 8 + json_len + 8 + bin.len();
    let total32 =
        u32::try_from(total).map_err(|_| unwritable("more than 4 GiB for a GLB".into()))?;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total32.to_le_bytes());
    out.extend_from_slice(&(json_len as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(text);
    out.resize(20 + json_len, b' ');
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    Ok(out)
}

/// The one binary buffer being filled, with its views and accessors.
struct Binary {
    bin: Vec<u8>,
    views: Vec<Json>,
    accessors: Vec<Json>,
    /// Vertices written.
    vertex_count: usize,
}

impl Binary {
    fn new(vertex_count: usize) -> Binary {
        Binary {
            bin: Vec::new(),
            views: Vec::new(),
            accessors: Vec::new(),
            vertex_count,
        }
    }

    /// A view of `bytes` (4-aligned) for `target`; its index.
    fn view(&mut self, bytes: impl Iterator<Item = u8>, target: u32) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend(bytes);
        self.views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": self.bin.len() - offset, "target": target}));
        self.views.len() - 1
    }

    /// A vertex attribute of `comps` floats per vertex, with `extra`
    /// accessor fields; the accessor's index.
    fn floats(&mut self, values: &[f32], comps: usize, extra: Json) -> usize {
        let view = self.view(values.iter().flat_map(|v| v.to_le_bytes()), ARRAY_BUFFER);
        let kind = ["", "SCALAR", "VEC2", "VEC3", "VEC4"][comps];
        let mut acc = json!({"bufferView": view, "componentType": FLOAT, "count": self.vertex_count, "type": kind});
        if let (Json::Object(a), Json::Object(e)) = (&mut acc, extra) {
            a.extend(e);
        }
        self.accessors.push(acc);
        self.accessors.len() - 1
    }

    /// Triangle corners, `u16` when every vertex index fits (65,535 stays
    /// free, the primitive-restart value), else `u32`; the accessor's
    /// index.
    fn indices(&mut self, corners: &[u32]) -> usize {
        let (view, component) = if self.vertex_count < 65_536 {
            let bytes = corners.iter().flat_map(|&x| (x as u16).to_le_bytes());
            (self.view(bytes, ELEMENT_ARRAY_BUFFER), UNSIGNED_SHORT)
        } else {
            let bytes = corners.iter().flat_map(|&x| x.to_le_bytes());
            (self.view(bytes, ELEMENT_ARRAY_BUFFER), UNSIGNED_INT)
        };
        self.accessors.push(json!({"bufferView": view, "componentType": component, "count": corners.len(), "type": "SCALAR"}));
        self.accessors.len() - 1
    }
}

/// A numeric face column, written per triangle as the attribute
/// `_FACE_NAME` (see the module's documentation).
struct FaceColumn<'m> {
    name: String,
    reader: Reader<'m, FaceKey>,
}

/// Every numeric face column of one to four values. (A text `material`
/// becomes the primitives; other text and boolean columns are not
/// written.)
fn face_columns(mesh: &Mesh) -> Result<Vec<FaceColumn<'_>>, Error> {
    let mut out = Vec::new();
    for a in mesh.attr_info(ElementKind::Face) {
        if !numeric(a.value_type) {
            continue;
        }
        let reader =
            Reader::new(mesh, &a.name, mesh.faces()).map_err(|e| unwritable(e.to_string()))?;
        if (1..=4).contains(&reader.components()) {
            out.push(FaceColumn {
                name: a.name,
                reader,
            });
        }
    }
    Ok(out)
}

/// Each triangle's face values, `width` apiece (absent values as zeros).
fn triangle_face_values(
    faces: &[FaceColumn<'_>],
    triangle_faces: &[FaceKey],
    width: usize,
) -> Vec<f32> {
    let mut out = Vec::with_capacity(triangle_faces.len() * width);
    let mut tmp = [0.0f64; 4];
    for &f in triangle_faces {
        for c in faces {
            let k = c.reader.components();
            c.reader.read(f, &mut tmp[..k]);
            out.extend(tmp[..k].iter().map(|&x| x as f32));
        }
    }
    out
}

/// The distinct values of the text face column `material` in order of
/// first use, and each triangle's (`None`: no value, or no such column).
fn materials(mesh: &Mesh, triangle_faces: &[FaceKey]) -> (Vec<String>, Vec<Option<u32>>) {
    let text = mesh
        .attr_info(ElementKind::Face)
        .into_iter()
        .any(|a| a.name == MATERIAL && a.value_type == Some(ValueType::Text));
    if !text {
        return (Vec::new(), vec![None; triangle_faces.len()]);
    }
    let mut names: Vec<String> = Vec::new();
    let mut index: HashMap<String, u32> = HashMap::new();
    let per_triangle = triangle_faces
        .iter()
        .map(|&f| match mesh.attr_value(MATERIAL, f).ok().flatten() {
            Some(Value::Text(s)) => Some(*index.entry(s.clone()).or_insert_with(|| {
                names.push(s);
                names.len() as u32 - 1
            })),
            _ => None,
        })
        .collect();
    (names, per_triangle)
}

/// The buffer vertices split where the face values of the triangles around
/// one differ, so that each triangle's corners carry its face's values.
struct FaceSplit {
    /// The buffer vertex each written vertex copies.
    source: Vec<u32>,
    /// The triangles' corners, as written vertices.
    corners: Vec<u32>,
    /// The face values of each written vertex, `width` apiece.
    values: Vec<f32>,
}

/// Split the `vertex_count` buffer vertices that `corners` (three per
/// triangle) use by the face values of their triangles (`width` per
/// triangle in `triangle_values`), compared bit for bit.
fn split_by_face_values(
    vertex_count: usize,
    corners: &[u32],
    triangle_values: &[f32],
    width: usize,
) -> Result<FaceSplit, Error> {
    if width == 0 {
        return Ok(FaceSplit {
            source: (0..vertex_count as u32).collect(),
            corners: corners.to_vec(),
            values: Vec::new(),
        });
    }
    const NONE: u32 = u32::MAX;
    // The written copies of one buffer vertex are chained: head[o] is the
    // last made, chain[w] the one made before w.
    let mut head = vec![NONE; vertex_count];
    let mut chain: Vec<u32> = Vec::with_capacity(vertex_count);
    let mut split = FaceSplit {
        source: Vec::with_capacity(vertex_count),
        corners: Vec::with_capacity(corners.len()),
        values: Vec::with_capacity(vertex_count * width),
    };
    let same = |a: &[f32], b: &[f32]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
    for (c, &o) in corners.iter().enumerate() {
        let t = c / 3;
        let want = &triangle_values[t * width..(t + 1) * width];
        let mut w = head[o as usize];
        while w != NONE && !same(&split.values[w as usize * width..][..width], want) {
            w = chain[w as usize];
        }
        if w == NONE {
            w = u32::try_from(split.source.len())
                .ok()
                .filter(|&w| w != NONE)
                .ok_or_else(|| unwritable("more than 2^32 - 1 glTF vertices".into()))?;
            split.source.push(o);
            split.values.extend_from_slice(want);
            chain.push(head[o as usize]);
            head[o as usize] = w;
        }
        split.corners.push(w);
    }
    Ok(split)
}

#[cfg(test)]
mod tests {
    use super::semantic;

    #[test]
    fn column_names_map_to_gltf_attributes() {
        assert_eq!(semantic("normal", 3), "NORMAL");
        assert_eq!(semantic("texcoord", 2), "TEXCOORD_0");
        assert_eq!(semantic("texcoord1", 2), "TEXCOORD_1");
        assert_eq!(semantic("color", 4), "COLOR_0");
        assert_eq!(semantic("color2", 3), "COLOR_2");
        assert_eq!(semantic("temperature", 1), "_temperature");
        assert_eq!(semantic("texcoord", 3), "_texcoord");
    }
}
