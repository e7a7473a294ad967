//! Layout and index-width details.

use super::*;

#[test]
fn index_width_follows_the_vertex_count() {
    let small = crate::shapes::icosphere(2);
    let b = small
        .to_triangle_buffers(&TriangleBufferOptions::default())
        .unwrap();
    assert_eq!(b.indices.width(), 2);
    let wide = TriangleBufferOptions {
        index_width: IndexWidth::U32,
        ..TriangleBufferOptions::default()
    };
    let b32 = small.to_triangle_buffers(&wide).unwrap();
    assert_eq!(b32.indices.width(), 4);
    assert_eq!(b32.indices.to_u32(), b.indices.to_u32());
    // 40,962 vertices and smooth normals: still u16; 163,842: u32.
    let smooth = TriangleBufferOptions {
        normals: Some(CornerNormalOptions::smooth()),
        ..TriangleBufferOptions::default()
    };
    let big = crate::shapes::icosphere(7);
    let b = big.to_triangle_buffers(&smooth).unwrap();
    assert_eq!(b.vertex_count(), big.vertex_count());
    assert_eq!(b.indices.width(), 4);
}

#[test]
fn interleaved_puts_columns_after_normals() {
    let b = TriangleBuffers::<f32> {
        positions: vec![[1.0, 2.0, 3.0]],
        normals: vec![[0.0, 0.0, 1.0]],
        columns: vec![BufferColumn {
            name: "uv".into(),
            source: ColumnSource::Corner,
            components: 2,
            data: vec![0.25, 0.75],
        }],
        indices: Indices::U16(vec![]),
        triangle_faces: vec![],
        vertex_sources: vec![],
    };
    let (data, layout) = b.interleaved();
    assert_eq!(data, [1.0, 2.0, 3.0, 0.0, 0.0, 1.0, 0.25, 0.75]);
    assert_eq!(layout.stride, 8);
    assert_eq!(layout.attributes[2].offset, 6);
}
