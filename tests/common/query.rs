//! Shared helpers for the spatial-query tests: a fixed random stream, the
//! meshes the tree is tried on, and the fan triangles it cuts faces into
//! (for brute-force answers).

use meshloom::shapes::{self, GridFaces};
use meshloom::{FaceKey, Mesh};

/// xorshift64*: a fixed stream of numbers in [0, 1).
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next() * n as f64) as usize).min(n.saturating_sub(1))
    }
    pub fn in_box(&mut self, lo: [f64; 3], hi: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|k| lo[k] + (hi[k] - lo[k]) * self.next())
    }
}

pub fn bbox(mesh: &Mesh) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in mesh.vertices() {
        let p = mesh.position(v).unwrap();
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// Every face's fan triangles, as the tree cuts them.
pub fn fans(mesh: &Mesh) -> Vec<(FaceKey, [[f64; 3]; 3])> {
    let mut out = Vec::new();
    for f in mesh.faces() {
        let c: Vec<[f64; 3]> = mesh
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| mesh.position(v).unwrap())
            .collect();
        for i in 1..c.len() - 1 {
            out.push((f, [c[0], c[i], c[i + 1]]));
        }
    }
    out
}

/// A hexagonal prism (two hexagons, six quads), its top bent out of plane.
pub fn prism() -> Mesh {
    let mut p = Vec::new();
    for z in [0.0, 1.0] {
        for i in 0..6 {
            let a = i as f64 * std::f64::consts::PI / 3.0;
            let bend = if z > 0.0 { 0.1 * (i % 2) as f64 } else { 0.0 };
            p.push([a.cos(), a.sin(), z + bend]);
        }
    }
    let mut faces: Vec<Vec<u32>> = vec![(0..6).rev().collect(), (6..12).collect()];
    for i in 0..6u32 {
        let j = (i + 1) % 6;
        faces.push(vec![i, j, 6 + j, 6 + i]);
    }
    Mesh::from_polygons(&p, &faces).unwrap()
}

/// A grid with cells removed (holes), and one squashed to slivers.
pub fn holed_grid() -> Mesh {
    let mut mesh = shapes::grid(12, 9, GridFaces::Triangles);
    let faces: Vec<FaceKey> = mesh.faces().collect();
    for f in faces.iter().step_by(17) {
        mesh.remove_face(*f).unwrap();
    }
    mesh
}

pub fn slivers() -> Mesh {
    let mut mesh = shapes::grid(10, 10, GridFaces::Triangles);
    let (lo, hi) = bbox(&mesh);
    let vs: Vec<_> = mesh.vertices().collect();
    for (i, v) in vs.into_iter().enumerate() {
        let mut p = mesh.position(v).unwrap();
        // Alternate columns collapse onto their neighbours: needle
        // triangles, some exactly degenerate.
        if i % 3 == 1 {
            p[0] -= (hi[0] - lo[0]) / 10.0 * if i % 2 == 0 { 1.0 } else { 1.0 - 1e-9 };
        }
        p[2] = 0.3 * (p[0] * 0.7).sin();
        mesh.set_position(v, p).unwrap();
    }
    mesh
}

pub fn meshes() -> Vec<(&'static str, Mesh)> {
    let positions = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.5, 1e-13, 0.0],
        [0.5, 1.0, 0.0],
    ];
    vec![
        ("icosphere", shapes::icosphere(3)),
        ("open grid", shapes::grid(15, 11, GridFaces::Quads)),
        ("uv sphere (quads, fans)", shapes::uv_sphere(17, 9)),
        ("prism (hexagons)", prism()),
        ("grid with holes", holed_grid()),
        ("slivers", slivers()),
        (
            "one sliver",
            Mesh::from_polygons(&positions, &[[0u32, 1, 2], [1, 3, 2], [0, 2, 3]]).unwrap(),
        ),
        ("torus", shapes::torus(30, 12, 1.0, 0.35).unwrap()),
    ]
}
