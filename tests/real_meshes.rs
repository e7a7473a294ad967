//! Real meshes from `shared/data/meshes`, checked against the independent
//! figures of `manifest.tsv`: counts, boundary loops (holes), components,
//! Euler characteristic. The small readers here (ASCII OFF, binary PLY)
//! exist only for these tests.

use meshloom::traverse::components;
use meshloom::Mesh;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/meshes");

/// Positions and faces of an ASCII OFF file (colours after the data of a
/// line are ignored).
fn read_off(text: &str) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let mut lines = text
        .lines()
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .filter(|l| !l.is_empty());
    let first = lines.next().expect("header");
    let mut rest: Vec<&str> = first.split_whitespace().skip(1).collect();
    if rest.is_empty() {
        rest = lines.next().expect("counts").split_whitespace().collect();
    }
    let nv: usize = rest[0].parse().unwrap();
    let nf: usize = rest[1].parse().unwrap();
    let mut positions = Vec::with_capacity(nv);
    for _ in 0..nv {
        let t: Vec<f64> = lines
            .next()
            .unwrap()
            .split_whitespace()
            .take(3)
            .map(|x| x.parse().unwrap())
            .collect();
        positions.push([t[0], t[1], t[2]]);
    }
    let mut faces = Vec::with_capacity(nf);
    for _ in 0..nf {
        let mut t = lines.next().unwrap().split_whitespace();
        let n: usize = t.next().unwrap().parse().unwrap();
        faces.push(t.take(n).map(|x| x.parse().unwrap()).collect());
    }
    (positions, faces)
}

/// Positions and faces of a binary little-endian PLY with float x, y, z
/// and `list uchar int` faces (and nothing else).
fn read_ply_binary(bytes: &[u8]) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let end = b"end_header\n";
    let at = bytes.windows(end.len()).position(|w| w == end).unwrap() + end.len();
    let header = std::str::from_utf8(&bytes[..at]).unwrap();
    let count = |element: &str| -> usize {
        header
            .lines()
            .find_map(|l| l.strip_prefix(&format!("element {element} ")))
            .unwrap()
            .parse()
            .unwrap()
    };
    let (nv, nf) = (count("vertex"), count("face"));
    let mut data = &bytes[at..];
    let f32_at = |d: &mut &[u8]| {
        let x = f32::from_le_bytes(d[..4].try_into().unwrap());
        *d = &d[4..];
        f64::from(x)
    };
    let positions = (0..nv)
        .map(|_| [f32_at(&mut data), f32_at(&mut data), f32_at(&mut data)])
        .collect();
    let mut faces = Vec::with_capacity(nf);
    for _ in 0..nf {
        let n = usize::from(data[0]);
        data = &data[1..];
        let f = (0..n)
            .map(|k| u32::from_le_bytes(data[4 * k..4 * k + 4].try_into().unwrap()))
            .collect();
        data = &data[4 * n..];
        faces.push(f);
    }
    (positions, faces)
}

struct Expected {
    path: String,
    v: usize,
    f: usize,
    e: usize,
    loops: usize,
    unreferenced: usize,
    components: usize,
    chi: i64,
}

/// Manifest rows of meshes the builder must accept: manifold, oriented,
/// no duplicate or degenerate faces, in a format read here.
fn buildable() -> Vec<Expected> {
    let manifest = std::fs::read_to_string(format!("{DATA}/manifest.tsv")).unwrap();
    let mut lines = manifest.lines();
    let head: Vec<&str> = lines.next().unwrap().split('\t').collect();
    let col = |name: &str| head.iter().position(|&h| h == name).unwrap();
    let mut out = Vec::new();
    for line in lines {
        let r: Vec<&str> = line.split('\t').collect();
        let num = |name: &str| r[col(name)].parse::<i64>().unwrap_or(-1);
        let format = r[col("format")];
        let readable = format == "OFF ascii" || r[0] == "closed/pyvista_ant.ply";
        if !readable
            || r[col("manifold")] != "True"
            || r[col("oriented")] != "True"
            || num("duplicate_faces") != 0
            || num("degenerate_faces") != 0
        {
            continue;
        }
        out.push(Expected {
            path: r[0].to_string(),
            v: num("V") as usize,
            f: num("F") as usize,
            e: num("E") as usize,
            loops: num("boundary_loops") as usize,
            unreferenced: num("unreferenced_vertices") as usize,
            components: num("components") as usize,
            chi: num("euler_char"),
        });
    }
    out
}

#[test]
fn manifest_meshes_build_with_the_independent_figures() {
    let rows = buildable();
    assert!(rows.len() >= 20, "only {} rows", rows.len());
    for x in rows {
        let file = format!("{DATA}/{}", x.path);
        let (positions, faces) = if x.path.ends_with(".ply") {
            read_ply_binary(&std::fs::read(&file).unwrap())
        } else {
            read_off(&std::fs::read_to_string(&file).unwrap())
        };
        assert_eq!((positions.len(), faces.len()), (x.v, x.f), "{}", x.path);
        let built = Mesh::build(Some(&positions), positions.len(), &faces)
            .unwrap_or_else(|e| panic!("{}: {e}", x.path));
        let m = &built.mesh;
        m.validate().unwrap();
        let what = &x.path;
        assert_eq!(built.unreferenced, x.unreferenced, "{what}");
        assert_eq!(m.vertex_count(), x.v - x.unreferenced, "{what}");
        assert_eq!(m.edge_count(), x.e, "{what}");
        assert_eq!(m.face_count(), x.f, "{what}");
        assert_eq!(m.hole_count(), x.loops, "{what}");
        assert_eq!(m.euler_characteristic(), x.chi, "{what}");
        let parts = components(m);
        assert_eq!(parts.count(), x.components, "{what}");
        // Walks agree with the components.
        let v = m.vertices().next().unwrap();
        let size = parts.vertex_counts()[parts.of_vertex(v).unwrap()];
        assert_eq!(m.bfs_vertices(v).unwrap().count(), size, "{what}");
    }
}

#[test]
fn the_ant_has_fifteen_closed_pieces() {
    let bytes = std::fs::read(format!("{DATA}/closed/pyvista_ant.ply")).unwrap();
    let (positions, faces) = read_ply_binary(&bytes);
    let m = Mesh::from_polygons(&positions, &faces).unwrap();
    let parts = m.components();
    assert_eq!(parts.count(), 15);
    // Every piece is a closed sphere: its faces reachable from one face.
    for c in 0..parts.count() {
        let v = parts.vertices(c).next().unwrap();
        let f = m.vertex(v).unwrap().faces().next().unwrap();
        let faces = m.bfs_faces(f).unwrap().count();
        let verts = parts.vertex_counts()[c];
        let edges = faces * 3 / 2;
        assert_eq!(verts as i64 - edges as i64 + faces as i64, 2);
    }
}
