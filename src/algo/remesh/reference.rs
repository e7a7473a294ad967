//! The input surface the remesher projects onto and resamples from:
//! its triangles and lines in hierarchies, and each corner column's islands.

use super::bvh::{Bvh, Segment, Triangle};
use crate::layout::Hid;
use crate::mesh::Mesh;

/// The input surface: triangles and lines in hierarchies, with what
/// resampling needs.
pub(super) struct Reference {
    pub(super) tris: Bvh<Triangle>,
    /// Per triangle: its three corners (half-edges, origin = vertex) in the
    /// input.
    pub(super) corners: Vec<[Hid; 3]>,
    /// Per triangle: its three input vertex slots.
    pub(super) tri_vertices: Vec<[u32; 3]>,
    /// Per input face slot: its triangle (u32::MAX for holes).
    pub(super) tri_of_face: Vec<u32>,
    pub(super) lines: Bvh<Segment>,
    /// Per input vertex slot: target length (adaptive).
    pub(super) sizing: Vec<f64>,
}

impl Reference {
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
