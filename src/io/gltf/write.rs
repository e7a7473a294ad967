//! glTF writing: one mesh, one primitive, one buffer, from the engine
//! buffers.

use serde_json::{json, Value as Json};

use super::super::error::{Error, Location};
use super::{base64, GltfEncoding};
use crate::attr::ValueType;
use crate::buffers::{ColumnChoice, TriangleBufferOptions};
use crate::keys::ElementKind;
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

pub(super) fn write(mesh: &Mesh, encoding: GltfEncoding) -> Result<Vec<u8>, Error> {
    if !mesh.has_positions() {
        return Err(unwritable("the mesh has no vertex positions".into()));
    }
    if mesh.face_count() == 0 {
        return Err(unwritable("the mesh has no faces".into()));
    }
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

    let mut bin: Vec<u8> = Vec::new();
    let mut views: Vec<Json> = Vec::new();
    let mut accessors: Vec<Json> = Vec::new();
    let mut attributes = serde_json::Map::new();
    let n = b.vertex_count();
    let mut add_floats = |values: &[f32], comps: usize, extra: Json| -> usize {
        while bin.len() % 4 != 0 {
            bin.push(0);
        }
        let offset = bin.len();
        for v in values {
            bin.extend_from_slice(&v.to_le_bytes());
        }
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": bin.len() - offset, "target": ARRAY_BUFFER}));
        let kind = ["", "SCALAR", "VEC2", "VEC3", "VEC4"][comps];
        let mut acc = json!({"bufferView": views.len() - 1, "componentType": FLOAT, "count": n, "type": kind});
        if let (Json::Object(a), Json::Object(e)) = (&mut acc, extra) {
            a.extend(e);
        }
        accessors.push(acc);
        accessors.len() - 1
    };
    let flat: Vec<f32> = b.positions.iter().flatten().copied().collect();
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &b.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let at = add_floats(&flat, 3, json!({"min": lo, "max": hi}));
    attributes.insert("POSITION".into(), json!(at));
    for c in &b.columns {
        let name = semantic(&c.name, c.components);
        if attributes.contains_key(&name) {
            continue;
        }
        let at = add_floats(&c.data, c.components, json!({}));
        attributes.insert(name, json!(at));
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let offset = bin.len();
    let component = match &b.indices {
        crate::buffers::Indices::U16(i) => {
            i.iter()
                .for_each(|x| bin.extend_from_slice(&x.to_le_bytes()));
            UNSIGNED_SHORT
        }
        crate::buffers::Indices::U32(i) => {
            i.iter()
                .for_each(|x| bin.extend_from_slice(&x.to_le_bytes()));
            UNSIGNED_INT
        }
    };
    views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": bin.len() - offset, "target": ELEMENT_ARRAY_BUFFER}));
    accessors.push(json!({"bufferView": views.len() - 1, "componentType": component, "count": b.indices.len(), "type": "SCALAR"}));
    let indices = accessors.len() - 1;
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
    let doc = json!({
        "asset": {"version": "2.0", "generator": concat!("meshloom ", env!("CARGO_PKG_VERSION"))},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": attributes, "indices": indices, "mode": 4}]}],
        "buffers": [buffer],
        "bufferViews": views,
        "accessors": accessors,
    });
    let text = serde_json::to_vec(&doc).map_err(|e| unwritable(e.to_string()))?;
    if encoding == GltfEncoding::Json {
        return Ok(text);
    }
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
    out.extend_from_slice(&text);
    out.resize(20 + json_len, b' ');
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    Ok(out)
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
