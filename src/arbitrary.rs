//! `quickcheck::Arbitrary` for valid random meshes (feature `quickcheck`),
//! for property tests of your own invariants.
//!
//! [`ArbitraryMesh`] draws one of: a named [shape](crate::shapes) with
//! random parameters, a shape with random faces removed (holes, bowtie
//! vertices and several pieces follow), two pieces side by side, or a
//! bowtie of triangle fans around one vertex; its vertices are renumbered
//! at random and every face list starts at a random corner, so slot order
//! differs from the shapes'. Every mesh is non-empty, passes
//! [`Mesh::validate`] and has positions. Shrinking removes faces (half of
//! them, or one at a time), which keeps the mesh valid.
//!
//! ```
//! use meshloom::arbitrary::ArbitraryMesh;
//! use quickcheck::{QuickCheck, TestResult};
//!
//! fn halfedges_pair_up(m: ArbitraryMesh) -> bool {
//!     m.0.validate().is_ok() && m.0.halfedge_count() == 2 * m.0.edge_count()
//! }
//! QuickCheck::new().tests(20).quickcheck(halfedges_pair_up as fn(ArbitraryMesh) -> bool);
//! ```

use std::fmt;

use quickcheck::{Arbitrary, Gen};

use crate::shapes::{self, GridFaces};
use crate::{Mesh, Polygons};

/// A valid, non-empty random mesh with positions. See the
/// [module docs](self) for what it draws.
#[derive(Clone)]
pub struct ArbitraryMesh(pub Mesh);

impl fmt::Debug for ArbitraryMesh {
    /// Counts and the face lists (enough to rebuild the topology with
    /// [`Mesh::from_faces`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let m = &self.0;
        let (p, _) = m.to_polygons();
        let faces: Vec<&[u32]> = p.faces().collect();
        f.debug_struct("ArbitraryMesh")
            .field("vertices", &m.vertex_count())
            .field("edges", &m.edge_count())
            .field("faces", &m.face_count())
            .field("holes", &m.hole_count())
            .field("polygons", &faces)
            .finish()
    }
}

/// A number in `lo..=hi`.
fn between(g: &mut Gen, lo: usize, hi: usize) -> usize {
    lo + usize::arbitrary(g) % (hi - lo + 1)
}

/// Parameters grow gently with the generator's size.
fn scale(g: &Gen, k: usize) -> usize {
    (g.size() / k).clamp(1, 12)
}

/// The buffers of a random named shape.
fn shape(g: &mut Gen) -> Polygons {
    match between(g, 0, 8) {
        0 => shapes::tetrahedron_polygons(),
        1 => shapes::cube_polygons(),
        2 => shapes::octahedron_polygons(),
        3 => shapes::icosahedron_polygons(),
        4 => shapes::icosphere_polygons(between(g, 0, 1 + usize::from(g.size() > 50)) as u32),
        5 => shapes::uv_sphere_polygons(between(g, 3, 3 + scale(g, 10)), between(g, 2, 6)),
        6 => shapes::torus_polygons(between(g, 3, 3 + scale(g, 15)), between(g, 3, 6), 1.0, 0.3),
        7 => {
            let faces = if bool::arbitrary(g) {
                GridFaces::Quads
            } else {
                GridFaces::Triangles
            };
            let s = scale(g, 10);
            shapes::grid_polygons(between(g, 1, s), between(g, 1, s), faces)
        }
        _ => shapes::disk_polygons(between(g, 3, 3 + scale(g, 10))),
    }
}

/// Several triangle fans around vertex 0, each open, meeting only there.
fn bowtie(g: &mut Gen) -> Polygons {
    let mut p = Polygons {
        positions: vec![[0.0; 3]],
        offsets: vec![0],
        indices: Vec::new(),
    };
    let fans = between(g, 2, 4);
    let total = fans * 4;
    for fan in 0..fans {
        let triangles = between(g, 1, 3);
        let first = p.positions.len() as u32;
        for k in 0..=triangles {
            let a = std::f64::consts::TAU * (fan * 4 + k) as f64 / total as f64;
            p.positions.push([a.cos(), a.sin(), 0.0]);
        }
        for k in 0..triangles as u32 {
            p.indices.extend_from_slice(&[0, first + k, first + k + 1]);
            p.offsets.push(p.indices.len() as u32);
        }
    }
    p
}

/// `a` and `b` side by side.
fn union(a: &Polygons, b: &Polygons) -> Polygons {
    let mut out = a.clone();
    let base = out.positions.len() as u32;
    out.positions.extend_from_slice(&b.positions);
    for f in b.faces() {
        out.indices.extend(f.iter().map(|&i| i + base));
        out.offsets.push(out.indices.len() as u32);
    }
    out
}

/// The faces of `p` for which `keep` says yes (the first one if none).
fn subset(p: &Polygons, mut keep: impl FnMut(usize) -> bool) -> Polygons {
    let mut out = Polygons {
        positions: p.positions.clone(),
        offsets: vec![0],
        indices: Vec::new(),
    };
    for (i, f) in p.faces().enumerate() {
        if keep(i) {
            out.indices.extend_from_slice(f);
            out.offsets.push(out.indices.len() as u32);
        }
    }
    if out.indices.is_empty() {
        if let Some(f) = p.faces().next() {
            out.indices.extend_from_slice(f);
            out.offsets.push(out.indices.len() as u32);
        }
    }
    out
}

/// Renumber the vertices at random and start each face at a random corner.
fn shuffle(g: &mut Gen, p: &Polygons) -> Polygons {
    let n = p.positions.len();
    let mut order: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        order.swap(i, between(g, 0, i));
    }
    // Old index i becomes order[i].
    let mut positions = vec![[0.0; 3]; n];
    for (i, &q) in p.positions.iter().enumerate() {
        positions[order[i] as usize] = q;
    }
    let mut indices = Vec::with_capacity(p.indices.len());
    for f in p.faces() {
        let r = between(g, 0, f.len() - 1);
        indices.extend((0..f.len()).map(|k| order[f[(k + r) % f.len()] as usize]));
    }
    Polygons {
        positions,
        offsets: p.offsets.clone(),
        indices,
    }
}

/// Random valid buffers (before shuffling).
fn polygons(g: &mut Gen) -> Polygons {
    match between(g, 0, 9) {
        0..=4 => shape(g),
        5..=7 => {
            let p = shape(g);
            let percent = *g.choose(&[10, 30, 50, 70]).unwrap_or(&30);
            subset(&p, |_| between(g, 1, 100) > percent)
        }
        8 => union(&shape(g), &shape(g)),
        _ => bowtie(g),
    }
}

impl Arbitrary for ArbitraryMesh {
    fn arbitrary(g: &mut Gen) -> Self {
        let p = polygons(g);
        let shuffled = shuffle(g, &p);
        // Every generator above gives valid buffers; fall back to the
        // unshuffled ones and then to a tetrahedron rather than panic.
        let mesh = Mesh::from_buffers(&shuffled)
            .or_else(|_| Mesh::from_buffers(&p))
            .unwrap_or_else(|_| shapes::tetrahedron());
        ArbitraryMesh(mesh)
    }

    fn shrink(&self) -> Box<dyn Iterator<Item = Self>> {
        let (p, _) = self.0.to_polygons();
        let nf = p.face_count();
        if nf <= 1 {
            return Box::new(std::iter::empty());
        }
        // Keep the first half, the second half, or drop one face (up to
        // eight evenly spread choices).
        let mut drops: Vec<(usize, usize)> = vec![(nf / 2, nf), (0, nf / 2)];
        let step = nf.div_ceil(8);
        drops.extend((0..nf).step_by(step).map(|i| (i, i + 1)));
        Box::new(drops.into_iter().filter_map(move |(lo, hi)| {
            let q = subset(&p, |i| i < lo || i >= hi);
            Mesh::from_buffers(&q).ok().map(ArbitraryMesh)
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_and_shrunk_meshes_are_valid() {
        let mut g = Gen::new(60);
        for _ in 0..200 {
            let m = ArbitraryMesh::arbitrary(&mut g);
            assert!(!m.0.is_empty());
            assert_eq!(m.0.validate(), Ok(()), "{m:?}");
            for s in m.shrink().take(4) {
                assert_eq!(s.0.validate(), Ok(()), "{s:?}");
                assert!(s.0.face_count() < m.0.face_count());
            }
        }
    }

    #[test]
    fn generated_soups_are_valid_before_fallback() {
        let mut g = Gen::new(60);
        for _ in 0..200 {
            let p = polygons(&mut g);
            let q = shuffle(&mut g, &p);
            assert!(Mesh::from_buffers(&p).is_ok());
            assert!(Mesh::from_buffers(&q).is_ok());
        }
    }
}
