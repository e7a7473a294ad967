//! The bodies of meshloom's fuzz targets, free of any fuzzing library: AFL++
//! drives them through `src/bin/*.rs` (`cargo afl build`), and
//! `tests/replay.rs` runs them over the committed seed corpus under plain
//! `cargo test`, so CI replays every seed (and every crash kept as a seed)
//! without AFL.
//!
//! Each target panics only when meshloom breaks a promise: a panic inside
//! the library on any input, a mesh that reads or builds but does not
//! validate, a repair that harms valid input or is not idempotent, a serde
//! round trip that changes the mesh, an operator that leaves an invalid
//! mesh or changes the mesh when it refuses.
#![forbid(unsafe_code)]
#![deny(missing_docs)]

use meshloom::attr::{Conserved, Value, ValueType};
use meshloom::io::{self, Format, ReadOptions};
use meshloom::repair::{repair, RepairOptions};
use meshloom::{shapes, BuildError, EdgeKey, FaceKey, HalfedgeKey, Mesh, Polygons, VertexKey};

/// Repair options with welding too.
fn weld_all() -> RepairOptions {
    RepairOptions::all().weld_vertices(true)
}

/// Read `data` as `format` strictly, with every repair, and with welding;
/// every mesh that comes out must validate, and a file that reads strictly
/// must come back unchanged under repair.
fn read_format(format: Format, data: &[u8]) {
    let strict = io::read_bytes(format, data, &ReadOptions::strict());
    if let Ok((m, _)) = &strict {
        m.validate().expect("a strict read validates");
    }
    for repair in [RepairOptions::all(), weld_all()] {
        let options = ReadOptions::strict().repair(repair);
        let Ok((m, report)) = io::read_bytes(format, data, &options) else {
            continue;
        };
        m.validate().expect("a repaired read validates");
        // Welding a valid file is asked for; the other policies must not
        // touch it.
        if let (Ok((s, _)), false) = (&strict, repair.weld_vertices) {
            assert!(report.is_clean(), "repair changed a valid file: {report}");
            assert_eq!(
                m.to_polygons().0,
                s.to_polygons().0,
                "repair changed a valid file"
            );
        }
    }
}

/// OBJ reader.
pub fn obj(data: &[u8]) {
    read_format(Format::Obj, data);
}

/// OFF reader.
pub fn off(data: &[u8]) {
    read_format(Format::Off, data);
}

/// PLY reader (ascii and binary).
pub fn ply(data: &[u8]) {
    read_format(Format::Ply, data);
}

/// STL reader (ascii and binary).
pub fn stl(data: &[u8]) {
    read_format(Format::Stl, data);
}

/// The readers through `std::io::Read`, where gzip data is recognised by
/// its magic bytes: the first byte picks the format, the rest is the file
/// (gzipped in the seeds).
pub fn gzip(data: &[u8]) {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let options = ReadOptions::repair_all().max_bytes(1 << 24);
    let read = match pick % 4 {
        0 => io::read_obj_with(rest, &options),
        1 => io::read_off_with(rest, &options),
        2 => io::read_ply_with(rest, &options),
        _ => io::read_stl_with(rest, &options),
    };
    if let Ok((m, _)) = read {
        m.validate().expect("a gzip read validates");
    }
}

/// glTF reader (JSON or GLB, from bytes), strict and with every repair:
/// every mesh read validates, and writes as GLB that reads back strictly
/// (welded by its `_VERTEX_ID`s) with the same vertex and face counts
/// (unless the writer refuses a position 32-bit floats cannot hold).
pub fn gltf(data: &[u8]) {
    use meshloom::io::gltf::{read_gltf_bytes, write_gltf, GltfEncoding, GltfOptions};
    let pick = GltfOptions::default();
    for repair in [RepairOptions::none(), RepairOptions::all()] {
        let options = ReadOptions::default().repair(repair).max_bytes(1 << 20);
        let Ok((m, _)) = read_gltf_bytes(data, &options, &pick) else {
            continue;
        };
        m.validate().expect("a glTF read validates");
        let mut bytes = Vec::new();
        if write_gltf(&m, &mut bytes, GltfEncoding::Binary).is_err() {
            continue;
        }
        let (back, _) = read_gltf_bytes(&bytes, &ReadOptions::strict(), &pick)
            .expect("meshloom's own glTF reads back");
        back.validate().expect("a glTF read validates");
        assert_eq!(
            (back.vertex_count(), back.face_count()),
            (m.vertex_count(), m.face_count()),
            "a glTF round trip changed the counts"
        );
    }
}

/// Bytes taken one at a time; zeros once they run out.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// Polygons decoded from bytes: a flags byte, a vertex count, positions
/// (small integers; 255 is NaN), then faces (a degree and that many
/// indices; 255 is `u32::MAX`, 254 is 2^31), with offsets bent by the
/// flags (not starting at 0, decreasing, past the end).
pub fn decode_polygons(data: &[u8]) -> Polygons {
    let mut b = Bytes(data);
    let flags = b.byte();
    let topology_only = flags & 1 != 0;
    let nv = usize::from(b.byte() % 48);
    let mut positions = Vec::new();
    if !topology_only {
        for _ in 0..nv {
            let mut p = [0.0; 3];
            for c in &mut p {
                let x = b.byte();
                *c = if x == 255 { f64::NAN } else { f64::from(x % 8) };
            }
            positions.push(p);
        }
    }
    let mut offsets = vec![0u32];
    let mut indices = Vec::new();
    while !b.is_empty() && offsets.len() < 256 {
        let degree = b.byte() % 9;
        for _ in 0..degree {
            indices.push(match b.byte() {
                255 => u32::MAX,
                254 => 1 << 31,
                x => u32::from(x) % (nv as u32 + 2),
            });
        }
        offsets.push(indices.len() as u32);
    }
    match flags >> 5 {
        1 => offsets[0] = 1,
        2 if offsets.len() > 2 => offsets.swap(1, 2),
        3 => {
            if let Some(last) = offsets.last_mut() {
                *last += 2;
            }
        }
        4 => offsets.clear(),
        _ => {}
    }
    Polygons {
        positions,
        offsets,
        indices,
    }
}

/// The builder from buffers: any decoded input builds into a valid mesh or
/// is an error; a built mesh survives `to_polygons` and back.
pub fn buffers(data: &[u8]) {
    let p = decode_polygons(data);
    if let Ok(m) = Mesh::from_buffers(&p) {
        m.validate().expect("a built mesh validates");
        let (q, _) = m.to_polygons();
        let again = Mesh::from_buffers(&q).expect("to_polygons builds again");
        // An empty mesh's buffers cannot say whether it had a position
        // column (no vertices, no positions): compare the rest.
        let (mut a, mut b) = (again.stats(), m.stats());
        if m.vertex_count() == 0 {
            (a.has_positions, b.has_positions) = (false, false);
        }
        assert_eq!(a, b);
    }
}

/// Repair: malformed input is refused with the builder's own error and
/// left untouched; with every policy the result builds, a valid input
/// comes back as it was, and repairing again changes nothing.
pub fn repair_target(data: &[u8]) {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let p = decode_polygons(rest);
    let options = match pick % 4 {
        0 => RepairOptions::all(),
        1 => weld_all(),
        2 => RepairOptions::none(),
        _ => RepairOptions::default()
            .weld_vertices(pick & 4 != 0)
            .drop_degenerate_faces(pick & 8 != 0)
            .drop_duplicate_faces(pick & 16 != 0)
            .orient_faces(pick & 32 != 0)
            .split_nonmanifold_edges(pick & 64 != 0)
            .split_nonmanifold_vertices(pick & 128 != 0)
            .drop_unreferenced_vertices(true),
    };
    let mut q = p.clone();
    match repair(&mut q, &options) {
        Err(e) => {
            assert_eq!(
                format!("{q:?}"),
                format!("{p:?}"),
                "a refused repair changed the input"
            );
            let malformed = |e: &meshloom::Error| {
                matches!(
                    e,
                    meshloom::Error::Build(
                        BuildError::MalformedOffsets { .. }
                            | BuildError::IndexOutOfRange { .. }
                            | BuildError::NonFinitePosition { .. }
                            | BuildError::TooLarge { .. }
                    )
                )
            };
            assert!(malformed(&e), "repair refused well-formed input: {e}");
            // Keeping the unreferenced vertices of a topology-only soup
            // lists every implied vertex, so repair refuses a huge index
            // (documented) where the builder, which drops them, builds.
            let keeps_implied = p.positions.is_empty()
                && !options.drop_unreferenced_vertices
                && matches!(e, meshloom::Error::Build(BuildError::TooLarge { .. }));
            if keeps_implied {
                return;
            }
            // The builder may stop earlier, at a defect repair fixes (a
            // repeated corner before a NaN position); where it names a
            // malformation, it is the same one.
            let built = Mesh::from_buffers(&p).expect_err("repair refused what builds");
            if malformed(&built) {
                assert_eq!(
                    format!("{e:?}"),
                    format!("{built:?}"),
                    "not the builder's error"
                );
            }
        }
        Ok(_) if pick % 4 < 2 => {
            let m = Mesh::from_buffers(&q).expect("every policy's result builds");
            m.validate().expect("repaired mesh validates");
            // Welding a valid mesh is asked for; the other policies must
            // leave it alone.
            if !options.weld_vertices {
                if let Ok(valid) = Mesh::from_buffers(&p) {
                    if valid.vertex_count() == p.positions.len() && !p.positions.is_empty() {
                        assert_eq!(q, p, "repair changed a valid mesh");
                    }
                }
            }
            let mut r = q.clone();
            let (again, _) = repair(&mut r, &options).expect("repaired output is well formed");
            assert!(again.is_clean(), "repair is not idempotent: {again}");
            assert_eq!(r, q, "repair is not idempotent");
        }
        Ok(_) => {}
    }
}

/// serde: any JSON that deserializes is a valid mesh, and it serializes to
/// JSON that reads back to the same JSON.
pub fn serde(data: &[u8]) {
    let Ok(m) = serde_json::from_slice::<Mesh>(data) else {
        return;
    };
    m.validate().expect("a deserialized mesh validates");
    let json = serde_json::to_string(&m).expect("a valid mesh serializes");
    let back: Mesh = serde_json::from_str(&json).expect("its own JSON reads back");
    assert_eq!(serde_json::to_string(&back).unwrap(), json);
}

/// Keys seen so far (live and stale), capped.
#[derive(Default)]
struct Pool {
    v: Vec<VertexKey>,
    h: Vec<HalfedgeKey>,
    e: Vec<EdgeKey>,
    f: Vec<FaceKey>,
    seen: (
        std::collections::HashSet<VertexKey>,
        std::collections::HashSet<HalfedgeKey>,
        std::collections::HashSet<EdgeKey>,
        std::collections::HashSet<FaceKey>,
    ),
}

impl Pool {
    const CAP: usize = 1024;

    fn see(&mut self, m: &Mesh) {
        // Keys are added while the pool is small; a set keeps it duplicate
        // free in O(1) per key.
        fn add<K: Eq + std::hash::Hash + Copy>(
            to: &mut Vec<K>,
            seen: &mut std::collections::HashSet<K>,
            keys: impl Iterator<Item = K>,
        ) {
            for k in keys {
                if to.len() >= Pool::CAP {
                    return;
                }
                if seen.insert(k) {
                    to.push(k);
                }
            }
        }
        let s = &mut self.seen;
        add(&mut self.v, &mut s.0, m.vertices().take(64));
        add(&mut self.h, &mut s.1, m.halfedges().take(64));
        add(&mut self.e, &mut s.2, m.edges().take(64));
        add(&mut self.f, &mut s.3, m.faces_and_holes().take(64));
    }

    fn pick<K: Copy>(keys: &[K], b: u8) -> Option<K> {
        (!keys.is_empty()).then(|| keys[usize::from(b) % keys.len()])
    }
}

/// One operator and its arguments, decoded from four bytes.
#[derive(Debug)]
enum Op {
    SplitEdge(u8, u8),
    SplitFace(u8, u8, u8),
    Poke(u8),
    Collapse(u8),
    CollapseAt(u8, u8),
    Flip(u8),
    RemoveEdge(u8),
    MergeFaces(u8, u8),
    RemoveVertex(u8),
    RemoveFace(u8),
    FillHole(u8),
    Triangulate(u8),
    TriangulateAll,
    Compact,
    Extrude(u8, u8),
    SplitVertex(u8, u8),
    InsertEdge(u8, u8),
    SetWeight(u8, u8),
    SetColour(u8, u8),
    ClearWeight(u8),
}

impl Op {
    fn decode(b: &mut Bytes<'_>) -> Op {
        let (k, x, y, z) = (b.byte(), b.byte(), b.byte(), b.byte());
        match k % 20 {
            0 => Op::SplitEdge(x, y),
            1 => Op::SplitFace(x, y, z),
            2 => Op::Poke(x),
            3 => Op::Collapse(x),
            4 => Op::CollapseAt(x, y),
            5 => Op::Flip(x),
            6 => Op::RemoveEdge(x),
            7 => Op::MergeFaces(x, y),
            8 => Op::RemoveVertex(x),
            9 => Op::RemoveFace(x),
            10 => Op::FillHole(x),
            11 => Op::Triangulate(x),
            12 => Op::TriangulateAll,
            13 => Op::Compact,
            14 => Op::Extrude(x, y),
            15 => Op::SplitVertex(x, y),
            16 => Op::InsertEdge(x, y),
            17 => Op::SetWeight(x, y),
            18 => Op::SetColour(x, y),
            _ => Op::ClearWeight(x),
        }
    }
}

/// A float from a byte: small values, and NaN and the infinities.
fn float(b: u8) -> f64 {
    match b {
        255 => f64::NAN,
        254 => f64::INFINITY,
        253 => f64::NEG_INFINITY,
        x => f64::from(x) / 16.0,
    }
}

/// Random operator streams on small shapes with attribute columns: after
/// every operator the mesh validates; an operator that refuses leaves the
/// mesh exactly as it was (compared through its full serde form: links,
/// generations and every attribute value); stale keys are refused.
pub fn ops(data: &[u8]) {
    let mut b = Bytes(data);
    let mut m = match b.byte() % 6 {
        0 => shapes::tetrahedron(),
        1 => shapes::cube(),
        2 => shapes::octahedron(),
        3 => shapes::disk(6),
        4 => shapes::grid(3, 2, shapes::GridFaces::Quads),
        _ => shapes::icosahedron(),
    };
    let weight = m
        .add_attr_with_rule::<VertexKey, f64, Conserved>("weight")
        .expect("new column");
    let colour = m.add_face_attr::<[f32; 3]>("colour").expect("new column");
    let label = m
        .add_dynamic_attr::<EdgeKey>("label", ValueType::F64)
        .expect("new column");
    let vs: Vec<_> = m.vertices().collect();
    for (i, v) in vs.into_iter().enumerate() {
        m.set_attr(&weight, v, i as f64).expect("live key");
    }
    let es: Vec<_> = m.edges().collect();
    for (i, e) in es.into_iter().enumerate() {
        m.set_attr(&label, e, Value::F64(i as f64))
            .expect("live key");
    }
    let mut pool = Pool::default();
    pool.see(&m);
    let mut steps = 0;
    while !b.is_empty() && steps < 32 && m.halfedge_count() < 1024 {
        steps += 1;
        let op = Op::decode(&mut b);
        // A clone is cheap; the full serde form is compared only when the
        // operator refuses.
        let before = m.clone();
        let v = |x: u8| Pool::pick(&pool.v, x);
        let h = |x: u8| Pool::pick(&pool.h, x);
        let e = |x: u8| Pool::pick(&pool.e, x);
        let f = |x: u8| Pool::pick(&pool.f, x);
        let refused: Option<bool> = match op {
            Op::SplitEdge(x, t) => e(x).map(|e| m.split_edge(e, float(t)).is_err()),
            Op::SplitFace(x, y, z) => match (f(x), v(y), v(z)) {
                (Some(f), Some(a), Some(c)) => Some(m.split_face(f, a, c).is_err()),
                _ => None,
            },
            Op::Poke(x) => f(x).map(|f| m.poke_face(f).is_err()),
            Op::Collapse(x) => h(x).map(|h| m.collapse_edge(h).is_err()),
            Op::CollapseAt(x, t) => h(x).map(|h| m.collapse_edge_at(h, float(t)).is_err()),
            Op::Flip(x) => e(x).map(|e| m.flip_edge(e).is_err()),
            Op::RemoveEdge(x) => e(x).map(|e| m.remove_edge(e).is_err()),
            Op::MergeFaces(x, y) => match (f(x), f(y)) {
                (Some(a), Some(c)) => Some(m.merge_faces(a, c).is_err()),
                _ => None,
            },
            Op::RemoveVertex(x) => v(x).map(|v| m.remove_vertex(v).is_err()),
            Op::RemoveFace(x) => f(x).map(|f| m.remove_face(f).is_err()),
            Op::FillHole(x) => f(x).map(|f| m.fill_hole(f).is_err()),
            Op::Triangulate(x) => f(x).map(|f| m.triangulate(f).is_err()),
            Op::TriangulateAll => {
                m.triangulate_all();
                None
            }
            Op::Compact => {
                m.compact();
                None
            }
            Op::Extrude(x, d) => f(x).map(|f| m.extrude_face(f, float(d)).is_err()),
            Op::SplitVertex(x, y) => match (h(x), h(y)) {
                (Some(a), Some(c)) => Some(m.split_vertex(a, c).is_err()),
                _ => None,
            },
            Op::InsertEdge(x, y) => match (v(x), v(y)) {
                (Some(a), Some(c)) => Some(m.insert_edge(a, c).is_err()),
                _ => None,
            },
            Op::SetWeight(x, w) => v(x).map(|v| m.set_attr(&weight, v, float(w)).is_err()),
            Op::SetColour(x, c) => f(x).map(|f| {
                let c = float(c) as f32;
                m.set_attr(&colour, f, [c, 0.5, c]).is_err()
            }),
            Op::ClearWeight(x) => v(x).map(|v| m.clear_attr(&weight, v).is_err()),
        };
        m.validate()
            .unwrap_or_else(|err| panic!("{op:?} left an invalid mesh: {err}"));
        if refused == Some(true) {
            let same = serde_json::to_string(&m).expect("a valid mesh serializes")
                == serde_json::to_string(&before).expect("a valid mesh serializes");
            assert!(same, "{op:?} refused but changed the mesh");
        }
        pool.see(&m);
    }
    // The mesh, attributes and all, survives serde.
    let json = serde_json::to_string(&m).expect("a valid mesh serializes");
    let back: Mesh = serde_json::from_str(&json).expect("its own JSON reads back");
    back.validate().expect("a deserialized mesh validates");
}

/// Seeds made in code for the targets whose input is not a file format:
/// (target, file name, bytes). Includes the minimal inputs of issue 10.
pub fn synthetic_seeds() -> Vec<(&'static str, String, Vec<u8>)> {
    let mut out = Vec::new();
    // Buffers: a quad and a triangle; a malformed index; offsets past the
    // end; a NaN position; a topology-only soup with a huge index.
    let shapes: [&[u8]; 6] = [
        &[
            0, 5, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 1, 0, 4, 0, 1, 2, 3, 3, 1, 4, 2,
        ],
        &[0, 3, 0, 0, 0, 1, 0, 0, 0, 1, 0, 3, 0, 1, 3],
        &[96, 3, 0, 0, 0, 1, 0, 0, 0, 1, 0, 3, 0, 1, 2],
        &[0, 3, 0, 0, 0, 255, 0, 0, 0, 1, 0, 3, 0, 1, 2],
        &[1, 3, 3, 0, 1, 255],
        &[
            0, 4, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 3, 0, 2, 1, 3, 0, 1, 3, 3, 1, 2, 3, 3, 0, 3,
            2, 3, 2, 1, 0,
        ],
    ];
    for (i, s) in shapes.iter().enumerate() {
        out.push(("buffers", format!("seed{i}"), s.to_vec()));
        for pick in [0u8, 1, 3, 0xFF] {
            let mut r = vec![pick];
            r.extend_from_slice(s);
            out.push(("repair", format!("seed{i}-{pick}"), r));
        }
    }
    for (i, m) in [shapes::tetrahedron(), shapes::cube(), shapes::disk(5)]
        .iter()
        .enumerate()
    {
        let mut m = m.clone();
        let w = m.add_vertex_attr::<f64>("w").expect("new column");
        let v = m.vertices().next().expect("a vertex");
        m.set_attr(&w, v, f64::NAN).expect("live key");
        let json = serde_json::to_vec(&m).expect("serializes");
        out.push(("serde", format!("shape{i}.json"), json));
    }
    for shape in 0u8..6 {
        let mut ops = vec![shape];
        for k in 0u8..20 {
            ops.extend_from_slice(&[k, k.wrapping_mul(7), k.wrapping_mul(13), 128]);
        }
        out.push(("ops", format!("shape{shape}"), ops));
    }
    // glTF as meshloom writes it: both encodings, with a face column and
    // materials on the GLB.
    use meshloom::io::gltf::{write_gltf, GltfEncoding};
    let mut cube = shapes::cube();
    let faces: Vec<FaceKey> = cube.faces().collect();
    let weight = cube.add_face_attr::<f64>("weight").expect("new column");
    let material = cube
        .add_face_attr::<String>("material")
        .expect("new column");
    for (i, &f) in faces.iter().enumerate() {
        cube.set_attr(&weight, f, i as f64).expect("live key");
        let name = if i % 2 == 0 { "red" } else { "blue" };
        cube.set_attr(&material, f, name.to_owned())
            .expect("live key");
    }
    for (mesh, name, encoding) in [
        (&cube, "meshloom_cube.glb", GltfEncoding::Binary),
        (
            &shapes::tetrahedron(),
            "meshloom_tetrahedron.gltf",
            GltfEncoding::Json,
        ),
    ] {
        let mut bytes = Vec::new();
        write_gltf(mesh, &mut bytes, encoding).expect("writes");
        out.push(("gltf", name.to_owned(), bytes));
    }
    out
}

/// Run `target` on every file named on the command line (directories: on
/// every file inside), for replaying crashes without AFL.
pub fn replay_args(target: fn(&[u8])) {
    for arg in std::env::args_os().skip(1) {
        let path = std::path::PathBuf::from(arg);
        let files: Vec<_> = if path.is_dir() {
            let mut v: Vec<_> = std::fs::read_dir(&path)
                .expect("a readable directory")
                .map(|e| e.expect("an entry").path())
                .filter(|p| p.is_file())
                .collect();
            v.sort();
            v
        } else {
            vec![path]
        };
        for f in files {
            let data = std::fs::read(&f).expect("a readable file");
            eprintln!("{}", f.display());
            target(&data);
        }
    }
}
