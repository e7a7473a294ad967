//! Engine buffers: vertex splits where corner values differ, exact round
//! trips, UV seams kept through buffers and back, typed errors.

use meshloom::algo::CornerNormalOptions;
use meshloom::attr::Value;
use meshloom::buffers::{
    BufferColumn, BufferError, ColumnChoice, ColumnSource, FromBuffersOptions, Indices,
    TriangleBufferOptions, TriangleBuffers, Weld,
};
use meshloom::{HalfedgeKey, Mesh};

const SPIDER: &str = "../shared/data/meshes/textured/spider.obj";

/// The spider has faces that disagree in orientation: read it with every
/// repair on.
/// The spider as repair reads it: it keeps coincident vertices apart (welding
/// is opt-in and refused where it would make the mesh non-manifold) and
/// keeps triangles whose corners share a position.
fn raw_spider() -> Mesh {
    let opts = meshloom::io::ReadOptions::repair_all();
    meshloom::io::read_with(SPIDER, &opts).unwrap().0
}

/// The spider after one trip through buffers: vertices welded by position,
/// so every vertex has a position of its own and the next trips are exact.
fn spider() -> Mesh {
    let raw = raw_spider();
    let b = raw.to_triangle_buffers(&uv_options(false)).unwrap();
    Mesh::from_triangle_buffers(&b, &FromBuffersOptions::default()).unwrap()
}

/// Distinct vertex positions (bit patterns, `-0.0` as `0.0`).
fn distinct_positions(mesh: &Mesh) -> usize {
    let key = |p: [f64; 3]| p.map(|c| if c == 0.0 { 0 } else { c.to_bits() });
    let set: std::collections::HashSet<_> = mesh
        .vertices()
        .map(|v| key(mesh.position(v).unwrap()))
        .collect();
    set.len()
}

#[test]
fn coincident_vertices_weld_on_the_way_back() {
    let raw = raw_spider();
    let b = raw
        .to_triangle_buffers_f64(&TriangleBufferOptions::default())
        .unwrap();
    let back = Mesh::build_triangle_buffers(&b, &FromBuffersOptions::default()).unwrap();
    assert!(distinct_positions(&raw) < raw.vertex_count());
    assert_eq!(back.mesh.vertex_count(), distinct_positions(&raw));
    let same = |a: [f64; 3], b: [f64; 3]| a == b;
    let indices = b.indices.to_u32();
    let degenerate = indices
        .chunks(3)
        .filter(|t| {
            let p = |i: u32| b.positions[i as usize];
            same(p(t[0]), p(t[1])) || same(p(t[1]), p(t[2])) || same(p(t[0]), p(t[2]))
        })
        .count();
    assert_eq!(back.collapsed, degenerate);
    assert_eq!(back.mesh.face_count(), b.triangle_count() - degenerate);
    back.mesh.validate().unwrap();
}

/// Interior edges across which a corner column differs at either end.
fn seams(mesh: &Mesh, name: &str) -> usize {
    let value = |h: HalfedgeKey| mesh.attr_value(name, h).unwrap();
    mesh.edges()
        .filter(|&e| {
            let view = mesh.edge(e).unwrap();
            if view.is_boundary() {
                return false;
            }
            let (h, t) = (view.halfedge(0), view.halfedge(1));
            value(h.key()) != value(t.next().key()) || value(h.next().key()) != value(t.key())
        })
        .count()
}

/// Distinct (vertex, corner value) pairs over the faces' corners.
fn distinct_corners(mesh: &Mesh, name: &str) -> usize {
    let mut seen = std::collections::HashSet::new();
    for f in mesh.faces() {
        for h in mesh.face(f).unwrap().halfedges() {
            let v = mesh.halfedge(h).unwrap().origin().key();
            let bits: Vec<u64> = match mesh.attr_value(name, h).unwrap() {
                Some(Value::List(l)) => l.iter().map(|x| x.as_f64().unwrap().to_bits()).collect(),
                _ => vec![],
            };
            seen.insert((v, bits));
        }
    }
    seen.len()
}

fn uv_options(normals: bool) -> TriangleBufferOptions {
    TriangleBufferOptions::default()
        .normals(normals.then(CornerNormalOptions::default))
        .columns(vec![ColumnChoice::corner("texcoord")])
}

#[test]
fn a_cube_with_flat_normals_has_24_vertices() {
    let cube = meshloom::shapes::cube();
    let b = cube
        .to_triangle_buffers(&TriangleBufferOptions::default())
        .unwrap();
    assert_eq!((b.vertex_count(), b.triangle_count()), (24, 12));
    assert!(matches!(b.indices, Indices::U16(_)));
    // Every buffer vertex's normal is the normal of the face it came from.
    for (t, f) in b.triangle_faces.iter().enumerate() {
        let n = cube.face_normal(*f).unwrap().map(|c| c as f32);
        for c in 0..3 {
            let v = b.indices.get(3 * t + c).unwrap() as usize;
            assert_eq!(b.normals[v], n);
        }
    }
    // Smooth normals: one vertex per corner of the cube.
    let smooth = TriangleBufferOptions::default().normals(Some(CornerNormalOptions::smooth()));
    assert_eq!(cube.to_triangle_buffers(&smooth).unwrap().vertex_count(), 8);
    // No normals, no columns: nothing splits.
    let bare = TriangleBufferOptions::default().normals(None);
    let b = cube.to_triangle_buffers(&bare).unwrap();
    assert_eq!(b.vertex_count(), 8);
    assert!(b.normals.is_empty());
}

#[test]
fn a_hard_edge_splits_the_buffer_vertices_along_it() {
    // Two quads folded by 10° along the edge from vertex 1 to vertex 2:
    // gentler than the 30° crease, so smooth unless the edge is hard.
    let t = 10f64.to_radians();
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0 + t.cos(), 0.0, t.sin()],
        [1.0 + t.cos(), 1.0, t.sin()],
    ];
    let mut mesh = Mesh::from_polygons(&p, &[[0u32, 1, 2, 3], [1, 4, 5, 2]]).unwrap();
    let hard = mesh.add_edge_attr::<bool>("hard").unwrap();
    let opts = TriangleBufferOptions::default().normals(Some(
        CornerNormalOptions::default().features(Some(hard.clone())),
    ));
    let b = mesh.to_triangle_buffers(&opts).unwrap();
    assert_eq!((b.vertex_count(), b.triangle_count()), (6, 4));
    let v: Vec<_> = mesh.vertices().collect();
    let h = mesh.find_halfedge(v[1], v[2]).unwrap().unwrap();
    mesh.set_attr(&hard, h.edge_key(), true).unwrap();
    let b = mesh.to_triangle_buffers(&opts).unwrap();
    assert_eq!((b.vertex_count(), b.triangle_count()), (8, 4));
}

#[test]
fn positions_round_trip_exactly() {
    for mesh in [meshloom::shapes::icosphere(3), spider()] {
        let b = mesh
            .to_triangle_buffers_f64(&TriangleBufferOptions::default())
            .unwrap();
        for (i, v) in b.vertex_sources.iter().enumerate() {
            assert_eq!(b.positions[i], mesh.position(*v).unwrap());
        }
        let back = Mesh::build_triangle_buffers(&b, &FromBuffersOptions::default()).unwrap();
        assert_eq!(back.collapsed, 0);
        assert_eq!(back.mesh.vertex_count(), mesh.vertex_count());
        for (i, v) in back.vertices.iter().enumerate() {
            let p = back.mesh.position(v.unwrap()).unwrap();
            assert_eq!(p, mesh.position(b.vertex_sources[i]).unwrap());
        }
        back.mesh.validate().unwrap();
    }
}

#[test]
fn uv_seams_survive_buffers_and_back() {
    let spider = spider();
    let before = seams(&spider, "texcoord");
    assert!(before > 0);
    let b = spider.to_triangle_buffers(&uv_options(false)).unwrap();
    // A vertex is split once per distinct UV at its corners, no more.
    assert_eq!(b.vertex_count(), distinct_corners(&spider, "texcoord"));
    let triangles: usize = spider
        .faces()
        .map(|f| spider.face(f).unwrap().degree() - 2)
        .sum();
    assert_eq!(b.triangle_count(), triangles);
    let back = Mesh::from_triangle_buffers(&b, &FromBuffersOptions::default()).unwrap();
    assert_eq!(back.vertex_count(), spider.vertex_count());
    assert_eq!(back.face_count(), triangles);
    assert_eq!(seams(&back, "texcoord"), before);
    // And once more: the buffers of the rebuilt mesh are the same size.
    let again = back.to_triangle_buffers(&uv_options(false)).unwrap();
    assert_eq!(again.vertex_count(), b.vertex_count());
    // With normals too, seams stay seams.
    let b = spider.to_triangle_buffers(&uv_options(true)).unwrap();
    let back = Mesh::from_triangle_buffers(&b, &FromBuffersOptions::default()).unwrap();
    assert_eq!(seams(&back, "texcoord"), before);
}

#[test]
fn vertex_columns_stay_vertex_columns_when_copies_agree() {
    let mut cube = meshloom::shapes::cube();
    let colour = cube.add_vertex_attr::<[f32; 3]>("colour").unwrap();
    for v in cube.vertices().collect::<Vec<_>>() {
        let p = cube.position(v).unwrap();
        cube.set_attr(&colour, v, p.map(|c| c as f32)).unwrap();
    }
    let opts = TriangleBufferOptions::default().columns(vec![ColumnChoice::vertex("colour")]);
    let b = cube.to_triangle_buffers(&opts).unwrap();
    assert_eq!(b.vertex_count(), 24); // split by normals, not by colour
    let col = b.column("colour").unwrap();
    assert_eq!(col.components, 3);
    let back = Mesh::from_triangle_buffers(&b, &FromBuffersOptions::default()).unwrap();
    let h =
        back.attr_handle::<meshloom::VertexKey, [f64; 3], meshloom::attr::Interpolate>("colour");
    let h = h.expect("a vertex column");
    for v in back.vertices() {
        let p = back.position(v).unwrap();
        assert_eq!(back.attr(&h, v).unwrap(), Some(&p));
    }
    // Normals come back as corner values.
    let n = back
        .attr_handle::<HalfedgeKey, [f64; 3], meshloom::attr::Interpolate>("normal")
        .unwrap();
    let f = back.faces().next().unwrap();
    let h0 = back.face(f).unwrap().halfedges().next().unwrap();
    let fnormal = back.face_normal(f).unwrap();
    let got = back.attr(&n, h0).unwrap().unwrap();
    assert!((0..3).all(|i| (got[i] - fnormal[i]).abs() < 1e-6));
}

#[test]
fn a_tolerance_welds_near_positions() {
    // Two triangles of a square whose shared corners differ by 1e-9.
    let e = 1e-9;
    let b = TriangleBuffers::<f64> {
        positions: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 0.0, e],
            [1.0 + e, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        normals: vec![],
        columns: vec![],
        indices: Indices::U32(vec![0, 1, 2, 3, 4, 5]),
        triangle_faces: vec![],
        vertex_sources: vec![],
    };
    let exact = Mesh::from_triangle_buffers(&b, &FromBuffersOptions::default()).unwrap();
    assert_eq!((exact.vertex_count(), exact.face_count()), (6, 2));
    let opts = FromBuffersOptions::default().weld(Weld::Tolerance(1e-6));
    let near = Mesh::from_triangle_buffers(&b, &opts).unwrap();
    assert_eq!((near.vertex_count(), near.edge_count()), (4, 5));
    // A weld that swallows triangles drops them and says so.
    let wide = Mesh::build_triangle_buffers(
        &b,
        &FromBuffersOptions::default().weld(Weld::Tolerance(1.0)),
    )
    .unwrap();
    assert_eq!(wide.collapsed, 2);
    assert_eq!(wide.triangles, [None, None]);
    assert!(wide.mesh.is_empty());
    assert!(matches!(
        Mesh::from_triangle_buffers(
            &b,
            &FromBuffersOptions::default().weld(Weld::Tolerance(-1.0))
        ),
        Err(BufferError::Tolerance(_))
    ));
}

#[test]
fn bad_buffers_give_typed_errors() {
    let good = meshloom::shapes::tetrahedron()
        .to_triangle_buffers(&TriangleBufferOptions::default())
        .unwrap();
    let opts = FromBuffersOptions::default();
    let mut b = good.clone();
    b.indices = Indices::U32(vec![0, 1]);
    assert_eq!(
        Mesh::from_triangle_buffers(&b, &opts).unwrap_err(),
        BufferError::NotTriangles { len: 2 }
    );
    let mut b = good.clone();
    b.indices = Indices::U32(vec![0, 1, 99]);
    let err = Mesh::from_triangle_buffers(&b, &opts).unwrap_err();
    assert!(matches!(
        err,
        BufferError::IndexOutOfRange {
            at: 2,
            index: 99,
            ..
        }
    ));
    assert!(err.to_string().contains("position 2"));
    let mut b = good.clone();
    b.normals.pop();
    assert!(matches!(
        Mesh::from_triangle_buffers(&b, &opts),
        Err(BufferError::Length { .. })
    ));
    let mut b = good.clone();
    b.positions[1][0] = f32::INFINITY;
    assert!(matches!(
        Mesh::from_triangle_buffers(&b, &opts),
        Err(BufferError::NonFinite { vertex: 1, .. })
    ));
    let mut b = good.clone();
    b.columns.push(BufferColumn {
        name: "wide".into(),
        source: ColumnSource::Vertex,
        components: 5,
        data: vec![0.0; 5 * good.vertex_count()],
    });
    assert!(matches!(
        Mesh::from_triangle_buffers(&b, &opts),
        Err(BufferError::Components { components: 5, .. })
    ));
    // An edge used by three triangles: the builder's error, placed.
    let fin = TriangleBuffers::<f32> {
        positions: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        normals: vec![],
        columns: vec![],
        indices: Indices::U16(vec![0, 1, 2, 1, 0, 3, 0, 1, 4]),
        triangle_faces: vec![],
        vertex_sources: vec![],
    };
    let err = Mesh::from_triangle_buffers(&fin, &opts).unwrap_err();
    assert!(
        matches!(err, BufferError::Build { triangle: 2, .. }),
        "{err}"
    );
    // Export: a missing column and a text column are errors.
    let mut mesh = meshloom::shapes::cube();
    assert!(matches!(
        mesh.to_triangle_buffers(&uv_options(false)),
        Err(BufferError::Mesh(meshloom::Error::AttributeMissing { .. }))
    ));
    mesh.add_halfedge_attr::<String>("texcoord").unwrap();
    let h = mesh.halfedges().next().unwrap();
    let name = mesh.attr_handle::<HalfedgeKey, String, meshloom::attr::Incompatible>("texcoord");
    mesh.set_attr(&name.unwrap(), h, "x".into()).unwrap();
    assert!(matches!(
        mesh.to_triangle_buffers(&uv_options(false)),
        Err(BufferError::Mesh(meshloom::Error::AttributeType { .. }))
    ));
}

#[test]
fn polygons_are_cut_without_changing_the_mesh() {
    // The L-shaped hexagon: a fan from corner 0 would leave the polygon.
    let p = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 2.0, 0.0],
        [0.0, 2.0, 0.0],
    ];
    let mesh = Mesh::from_polygons(&p, &[[0u32, 1, 2, 3, 4, 5]]).unwrap();
    let b = mesh
        .to_triangle_buffers_f64(&TriangleBufferOptions::default())
        .unwrap();
    assert_eq!((b.vertex_count(), b.triangle_count()), (6, 4));
    assert_eq!(mesh.face_count(), 1);
    // The triangles cover the polygon's area (3) exactly once.
    let idx = b.indices.to_u32();
    let area: f64 = idx
        .chunks(3)
        .map(|t| {
            let [a, b2, c] = [0, 1, 2].map(|k| b.positions[t[k] as usize]);
            0.5 * ((b2[0] - a[0]) * (c[1] - a[1]) - (b2[1] - a[1]) * (c[0] - a[0]))
        })
        .sum();
    assert_eq!(area, 3.0);
    assert!(b.normals.iter().all(|&n| n == [0.0, 0.0, 1.0]));
}
