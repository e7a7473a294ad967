//! The input surface the remesher projects onto and resamples from:
//! the shared face tree over its triangles, a segment tree over its lines,
//! and each corner column's islands.
//!
//! A *triangle* here is a fan triangle by its place in the face tree
//! ([`FaceTree::closest_near`] answers with it); the tables below are
//! indexed by it.

use crate::error::{Error, Result};
use crate::layout::Hid;
use crate::mesh::Mesh;
use crate::query::{FaceTree, SegmentTree};
use crate::vec3::V3;

/// The input surface: triangles and lines in hierarchies, with what
/// resampling needs.
pub(super) struct Reference {
    /// The input's faces (the input is never edited while it is used).
    pub(super) tree: FaceTree,
    /// Per triangle: its three corners (half-edges, origin = vertex) in the
    /// input, in the order of the tree's barycentric weights.
    pub(super) corners: Vec<[Hid; 3]>,
    /// Per triangle: its three input vertex slots.
    pub(super) tri_vertices: Vec<[u32; 3]>,
    /// Per input face slot: its first triangle (u32::MAX for holes).
    pub(super) tri_of_face: Vec<u32>,
    /// The input's boundary and feature lines.
    pub(super) lines: SegmentTree,
    /// Per input vertex slot: target length (adaptive).
    pub(super) sizing: Vec<f64>,
}

impl Reference {
    /// The reference for `input`, with `segs` its lines and `sizing` its
    /// per vertex slot target length.
    pub(super) fn new(input: &Mesh, segs: &[[V3; 2]], sizing: Vec<f64>) -> Result<Reference> {
        let tree = FaceTree::build(input).map_err(|_| Error::NoPositions)?;
        let n = tree.triangle_count() as u32;
        let mut corners = Vec::with_capacity(n as usize);
        let mut tri_vertices = Vec::with_capacity(n as usize);
        for t in 0..n {
            let h0 = input.face_halfedge(tree.triangle_face(t).id());
            let mut h1 = input.next(h0);
            for _ in 1..tree.triangle_fan(t) {
                h1 = input.next(h1);
            }
            let hs = [h0, h1, input.next(h1)];
            debug_assert_eq!(
                hs.map(|h| input.origin(h).index()),
                tree.triangle_vertices(t).map(|v| v.index())
            );
            corners.push(hs);
            tri_vertices.push(hs.map(|h| input.origin(h).raw()));
        }
        Ok(Reference {
            tri_of_face: tree.first_triangles(input.slot_counts()[3]),
            tree,
            corners,
            tri_vertices,
            lines: SegmentTree::build(segs),
            sizing,
        })
    }

    /// The target length at barycentric `b` of triangle `t`.
    pub(super) fn interpolate_sizing(&self, t: u32, b: [f64; 3]) -> f64 {
        let vs = self.tri_vertices[t as usize];
        b[0] * self.sizing[vs[0] as usize]
            + b[1] * self.sizing[vs[1] as usize]
            + b[2] * self.sizing[vs[2] as usize]
    }

    /// Per triangle, the island (a representative triangle) of corner
    /// column `ci`: triangles joined by edges across which the corner
    /// values agree at both ends.
    pub(super) fn islands(&self, input: &Mesh, ci: usize) -> Vec<u32> {
        let col = &*input.attrs().halfedge.cols[ci].1;
        let n = self.corners.len();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        fn find(parent: &mut [u32], mut x: u32) -> u32 {
            while parent[x as usize] != x {
                let p = parent[parent[x as usize] as usize];
                parent[x as usize] = p;
                x = p;
            }
            x
        }
        for e in input.eids() {
            let [h, t] = e.halfedges();
            if input.in_hole(h) || input.in_hole(t) {
                continue;
            }
            // Corner at a in h's face is h; in t's face it is next(t).
            if !col.same(h.index(), input.next(t).index())
                || !col.same(input.next(h).index(), t.index())
            {
                continue;
            }
            let (x, y) = (
                self.tri_of_face[input.face_of(h).index()],
                self.tri_of_face[input.face_of(t).index()],
            );
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            if rx != ry {
                parent[rx as usize] = ry;
            }
        }
        (0..n as u32).map(|x| find(&mut parent, x)).collect()
    }
}
