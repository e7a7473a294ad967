//! Operators: the Surface_mesh paper's split-and-collapse test and flipping
//! every flippable edge, against pmp-library; triangulating a UV sphere of
//! 90k quads, against Plexus.
//!
//! The meshes are made here (a triangle grid of 499 × 499 cells = 250,000
//! vertices, an icosphere of 7 subdivisions = 163,842 vertices, a UV sphere
//! of 300 × 300 quads) so the section does not depend on other sections'
//! generators.

use std::collections::HashMap;

use crate::harness::{Peer, Report};
use meshloom::{FaceKey, Mesh, VertexKey};

/// A flat triangle grid of `n × n` cells ((n + 1)² vertices).
pub fn triangle_grid(n: u32) -> Mesh {
    let mut p = Vec::with_capacity(((n + 1) * (n + 1)) as usize);
    for y in 0..=n {
        for x in 0..=n {
            p.push([f64::from(x), f64::from(y), 0.0]);
        }
    }
    let mut faces = Vec::with_capacity(2 * (n * n) as usize);
    for y in 0..n {
        for x in 0..n {
            let v = y * (n + 1) + x;
            faces.push([v, v + 1, v + n + 2]);
            faces.push([v, v + n + 2, v + n + 1]);
        }
    }
    Mesh::from_polygons(&p, &faces).expect("grid")
}

/// An icosphere: an icosahedron subdivided `levels` times (each triangle
/// into four), projected on the unit sphere.
pub fn icosphere(levels: u32) -> Mesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut p: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut next = Vec::with_capacity(f.len() * 4);
        let mut midpoint = |a: u32, b: u32, p: &mut Vec<[f64; 3]>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (x, y) = (p[a as usize], p[b as usize]);
                p.push([
                    (x[0] + y[0]) / 2.0,
                    (x[1] + y[1]) / 2.0,
                    (x[2] + y[2]) / 2.0,
                ]);
                (p.len() - 1) as u32
            })
        };
        for &[a, b, c] in &f {
            let ab = midpoint(a, b, &mut p);
            let bc = midpoint(b, c, &mut p);
            let ca = midpoint(c, a, &mut p);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    for x in &mut p {
        let l = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
        *x = [x[0] / l, x[1] / l, x[2] / l];
    }
    Mesh::from_polygons(&p, &f).expect("icosphere")
}

/// A UV sphere with `segments × (rings − 2)` quads and a triangle fan at
/// each pole.
pub fn uv_sphere(segments: u32, rings: u32) -> Mesh {
    let mut p = vec![[0.0, 0.0, 1.0]];
    for r in 1..rings {
        let th = std::f64::consts::PI * f64::from(r) / f64::from(rings);
        for s in 0..segments {
            let ph = std::f64::consts::TAU * f64::from(s) / f64::from(segments);
            p.push([th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()]);
        }
    }
    p.push([0.0, 0.0, -1.0]);
    let south = (p.len() - 1) as u32;
    let at = |r: u32, s: u32| 1 + (r - 1) * segments + s % segments;
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for s in 0..segments {
        faces.push(vec![0, at(1, s), at(1, s + 1)]);
        faces.push(vec![south, at(rings - 1, s + 1), at(rings - 1, s)]);
    }
    for r in 1..rings - 1 {
        for s in 0..segments {
            faces.push(vec![at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s + 1)]);
        }
    }
    Mesh::from_polygons(&p, &faces).expect("uv sphere")
}

/// Poke every face, then collapse every new centre into a corner.
fn split_collapse(mut m: Mesh) -> Mesh {
    let faces: Vec<FaceKey> = m.faces().collect();
    let mut centres: Vec<VertexKey> = Vec::with_capacity(faces.len());
    for f in faces {
        centres.push(m.poke_face(f).expect("poke"));
    }
    for c in centres {
        let h = m.vertex(c).expect("live").halfedge().key();
        m.collapse_edge(h).expect("collapse back");
    }
    m
}

/// Flip every edge that can be flipped, and flip it back at once: two
/// flips per flippable edge, twice pmp's work. (Flipping each edge once in
/// key order piles the flipped edges into fans: on the grid, degrees pass
/// 20,000 and the run measures the fans, not the flips.)
fn flip_all(mut m: Mesh) -> (Mesh, usize) {
    let edges: Vec<_> = m.edges().collect();
    let mut flipped = 0;
    for e in edges {
        if m.flip_edge(e).is_ok() {
            m.flip_edge(e).expect("flips back");
            flipped += 1;
        }
    }
    (m, flipped)
}

/// Run the operator rows.
pub fn run(r: &mut Report) {
    let grid = triangle_grid(499);
    let ico = icosphere(7);
    assert_eq!(grid.vertex_count(), 250_000);
    assert_eq!(ico.vertex_count(), 163_842);
    for (name, mesh, split_peer, flip_peer) in [
        ("grid 250k", &grid, 0.145, 0.014),
        ("icosphere 7", &ico, 0.096, 0.009),
    ] {
        let out = split_collapse(mesh.clone());
        assert_eq!(
            (out.vertex_count(), out.face_count()),
            (mesh.vertex_count(), mesh.face_count())
        );
        r.time(
            &format!("ops: split 1-to-3 + collapse back, {name}"),
            Some(Peer {
                name: "pmp-library",
                seconds: split_peer,
                ratio: 1.0,
            }),
            || mesh.clone(),
            split_collapse,
        );
        r.time(
            &format!("ops: flip every flippable edge and back, {name}"),
            Some(Peer {
                name: "pmp-library x2",
                seconds: 2.0 * flip_peer,
                ratio: 1.0,
            }),
            || mesh.clone(),
            flip_all,
        );
    }
    let uv = uv_sphere(300, 302);
    assert_eq!(
        uv.faces()
            .filter(|&f| uv.face(f).map_or(0, |v| v.degree()) == 4)
            .count(),
        90_000
    );
    r.time(
        "ops: triangulate a 90k-quad UV sphere",
        Some(Peer {
            name: "Plexus (target 30 ms)",
            seconds: 3.0,
            ratio: 0.01,
        }),
        || uv.clone(),
        |mut m| {
            let left = m.triangulate_all();
            assert!(left.is_empty());
            m
        },
    );
}
