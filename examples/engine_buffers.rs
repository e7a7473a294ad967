//! Fill wgpu-style vertex and index buffers from a mesh, with no per-vertex
//! code: one interleaved vertex buffer (position, normal, UV) and one index
//! buffer, as bytes, plus the vertex layout a render pipeline declares.
//! No GPU is needed: the example checks the bytes it made and exits
//! non-zero if anything is off (CI runs it).
//!
//!     cargo run --example engine_buffers

use bytemuck::{Pod, Zeroable};
use meshloom::buffers::{ColumnChoice, Indices, TriangleBufferOptions, VertexLayout};

/// The vertex a shader reads: `#[repr(C)]`, so its bytes are the
/// interleaved buffer's.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    uv: [f32; 2],
}

/// What `wgpu::VertexAttribute` holds (wgpu is not a dependency here).
#[derive(Debug)]
struct VertexAttribute {
    format: &'static str,
    offset: u64,
    shader_location: u32,
}

/// The unit square's corners: every cube face's UVs.
const SQUARE: [[f32; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mesh = uv_cube()?;
    let options = TriangleBufferOptions::default().columns(vec![ColumnChoice::corner("texcoord")]);
    let buffers = mesh.to_triangle_buffers(&options)?;
    let (interleaved, layout) = buffers.interleaved();

    // The bytes wgpu's queue.write_buffer / create_buffer_init take.
    let vertex_bytes: &[u8] = bytemuck::cast_slice(&interleaved);
    let (index_bytes, index_format): (&[u8], &str) = match &buffers.indices {
        Indices::U16(i) => (bytemuck::cast_slice(i), "Uint16"),
        Indices::U32(i) => (bytemuck::cast_slice(i), "Uint32"),
    };
    let scalar = std::mem::size_of::<f32>() as u64;
    let attributes = vertex_attributes(&layout, scalar);
    let stride = layout.stride as u64 * scalar;
    println!(
        "{} vertices x {stride} bytes = {} vertex bytes; {} indices ({index_format}) = {} index bytes",
        buffers.vertex_count(),
        vertex_bytes.len(),
        buffers.indices.len(),
        index_bytes.len()
    );
    for a in &attributes {
        println!(
            "  @location({}) {} at byte {}",
            a.shader_location, a.format, a.offset
        );
    }

    // Check what a GPU would read.
    let vertices: &[Vertex] = bytemuck::cast_slice(vertex_bytes);
    let checks = [
        (
            "24 vertices: every cube corner split by normal and UV",
            buffers.vertex_count() == 24,
        ),
        (
            "36 indices, u16",
            index_bytes.len() == 72 && index_format == "Uint16",
        ),
        (
            "stride 32 bytes",
            stride == std::mem::size_of::<Vertex>() as u64,
        ),
        (
            "layout: position, normal, uv",
            attributes.iter().map(|a| a.offset).eq([0, 12, 24]),
        ),
        (
            "index buffer size is a multiple of 4 (wgpu copy alignment)",
            index_bytes.len() % 4 == 0,
        ),
        (
            "vertex bytes hold the positions",
            vertices
                .iter()
                .zip(&buffers.positions)
                .all(|(v, p)| v.position == *p),
        ),
        (
            "every normal is a unit axis",
            vertices
                .iter()
                .all(|v| v.normal.iter().map(|c| c.abs()).sum::<f32>() == 1.0),
        ),
        (
            "every UV is a corner of the unit square",
            vertices.iter().all(|v| SQUARE.contains(&v.uv)),
        ),
        (
            "every index names a vertex",
            buffers
                .indices
                .iter()
                .all(|i| (i as usize) < vertices.len()),
        ),
    ];
    report(&checks)
}

/// A cube whose every face is its own UV island: corner values differ
/// across every edge (and the flat normals differ too).
fn uv_cube() -> meshloom::Result<meshloom::Mesh> {
    let mut mesh = meshloom::shapes::cube();
    let uv = mesh.add_halfedge_attr::<[f32; 2]>("texcoord")?;
    for f in mesh.faces().collect::<Vec<_>>() {
        let corners: Vec<_> = mesh.face(f)?.halfedges().collect();
        for (h, value) in corners.into_iter().zip(SQUARE) {
            mesh.set_attr(&uv, h, value)?;
        }
    }
    Ok(mesh)
}

/// The vertex attributes a render pipeline declares for `layout`, with
/// offsets in bytes (`scalar` bytes per value).
fn vertex_attributes(layout: &VertexLayout, scalar: u64) -> Vec<VertexAttribute> {
    layout
        .attributes
        .iter()
        .enumerate()
        .map(|(location, a)| VertexAttribute {
            format: ["", "Float32", "Float32x2", "Float32x3", "Float32x4"][a.components],
            offset: a.offset as u64 * scalar,
            shader_location: location as u32,
        })
        .collect()
}

/// Print each check; an error when any failed.
fn report(checks: &[(&str, bool)]) -> Result<(), Box<dyn std::error::Error>> {
    let mut failed = 0;
    for &(what, ok) in checks {
        println!("{} {what}", if ok { "ok  " } else { "FAIL" });
        failed += usize::from(!ok);
    }
    if failed > 0 {
        return Err(format!("{failed} checks failed").into());
    }
    Ok(())
}
