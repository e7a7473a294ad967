//! Closest points for a caller that asks again and again near where it
//! asked last: a *hint* (the fan triangle a point was answered with last
//! time) is tested first, so its distance bounds the walk from the start
//! and a point that moved a little costs a handful of box tests; a *filter*
//! keeps the answer on the fan triangles it accepts. The remesher projects
//! every moved vertex this way each round, and resamples corners on their
//! own side of a seam through the filter.
//!
//! Crate-private: the hint names a fan triangle by its place in the tree
//! (what [`Near::tri`] gives back), which an [`update`](FaceTree::update)
//! moves; a build or a [`refit`](FaceTree::refit) keeps it. After an update
//! (while slots of dead triangles are left behind) hints are ignored, never
//! trusted. The caller keeps the mesh the tree was built for unchanged
//! (the remesher's input is never edited): these queries take no mesh to
//! check the tree against.

use super::closest::closest_on_triangle;
use super::FaceTree;
use crate::keys::{FaceKey, VertexKey};
use crate::vec3::{self, V3};

/// A closest point, with the fan triangle to pass back as the next hint.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Near {
    /// The fan triangle, by its place in the tree.
    pub(crate) tri: u32,
    /// The closest point.
    pub(crate) point: V3,
    /// Its barycentric weights on the fan triangle's corners
    /// ([`FaceTree::triangle_vertices`] order).
    pub(crate) weights: [f64; 3],
}

impl FaceTree {
    /// The closest point of the surface to `q`, starting from fan triangle
    /// `hint` (see the module docs); `stack` is scratch space. `None` for a
    /// tree without triangles.
    #[inline]
    pub(crate) fn closest_near(
        &self,
        q: V3,
        hint: Option<u32>,
        stack: &mut Vec<u32>,
    ) -> Option<Near> {
        self.closest_near_where(q, hint, |_| true, stack)
    }

    /// [`closest_near`](FaceTree::closest_near) over the fan triangles
    /// `keep` accepts (by their place in the tree) only; a hint it refuses
    /// is not used. `None` when it accepts none. The hint's distance is
    /// the walk's first bound, and the hint is not tested twice.
    #[inline]
    pub(crate) fn closest_near_where(
        &self,
        q: V3,
        hint: Option<u32>,
        keep: impl Fn(u32) -> bool,
        stack: &mut Vec<u32>,
    ) -> Option<Near> {
        let mut best: Option<Near> = None;
        let mut bound = f64::INFINITY;
        let mut hinted = usize::MAX;
        if let Some(h) = hint {
            let h = h as usize;
            if self.dead_tris == 0 && h < self.tris.len() && keep(h as u32) {
                let (x, w) = closest_on_triangle(q, &self.tris[h]);
                let d2 = vec3::dist2(q, x);
                best = Some(Near {
                    tri: h as u32,
                    point: x,
                    weights: w,
                });
                bound = d2;
                hinted = h;
            }
        }
        self.walk_point(q, bound, stack, |tree, tri| {
            if tri == hinted || !keep(tri as u32) {
                return bound;
            }
            let (x, w) = closest_on_triangle(q, &tree.tris[tri]);
            let d2 = vec3::dist2(q, x);
            if d2 < bound {
                bound = d2;
                best = Some(Near {
                    tri: tri as u32,
                    point: x,
                    weights: w,
                });
            }
            bound
        });
        best
    }

    /// The face of fan triangle `tri` (a place in the tree, as
    /// [`Near::tri`]).
    #[inline]
    pub(crate) fn triangle_face(&self, tri: u32) -> FaceKey {
        self.meta[tri as usize].face
    }

    /// The corners of fan triangle `tri`, in the order of
    /// [`Near::weights`].
    #[inline]
    pub(crate) fn triangle_vertices(&self, tri: u32) -> [VertexKey; 3] {
        self.meta[tri as usize].v
    }

    /// The face corner index of fan triangle `tri`'s second corner: its
    /// corners are its face's corners `0`, `fan` and `fan + 1`, counted
    /// from the face's half-edge.
    #[inline]
    pub(crate) fn triangle_fan(&self, tri: u32) -> u32 {
        self.meta[tri as usize].fan
    }

    /// Per face slot below `slots`, the place of the face's first fan
    /// triangle (`u32::MAX` for slots without a face in the tree): hints to
    /// start from a face.
    pub(crate) fn first_triangles(&self, slots: usize) -> Vec<u32> {
        let mut out = vec![u32::MAX; slots];
        self.for_each_leaf(|_, range| {
            for tri in range {
                let m = &self.meta[tri];
                if m.fan == 1 && m.face.index() < slots {
                    out[m.face.index()] = tri as u32;
                }
            }
        });
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    /// The closest distance over the faces `keep` accepts, by brute force.
    fn brute(tree: &FaceTree, q: V3, keep: impl Fn(u32) -> bool) -> f64 {
        (0..tree.tris.len())
            .filter(|&t| keep(t as u32))
            .map(|t| vec3::dist2(q, closest_on_triangle(q, &tree.tris[t]).0))
            .fold(f64::INFINITY, f64::min)
    }

    /// Deterministic points in `[lo, hi)³`.
    fn points(n: usize, lo: f64, hi: f64) -> Vec<V3> {
        let mut s = 12345u64;
        let mut rnd = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            lo + (hi - lo) * ((s >> 11) as f64 / (1u64 << 53) as f64)
        };
        (0..n).map(|_| [rnd(), rnd(), rnd()]).collect()
    }

    #[test]
    fn hinted_answers_equal_brute_force_from_any_hint() {
        // Quads and triangles, so fan triangles of n-gons are hinted too.
        for mesh in [
            shapes::torus(16, 8, 1.0, 0.3).unwrap(),
            shapes::icosphere(2),
        ] {
            let tree = FaceTree::build(&mesh).unwrap();
            let n = tree.tris.len() as u32;
            let mut stack = Vec::new();
            let mut last = None;
            for (k, q) in points(300, -1.6, 1.6).into_iter().enumerate() {
                // No hint, the last answer, a far triangle, out of range.
                let hint = [None, last, Some(k as u32 * 7 % n), Some(n + 3)][k % 4];
                let near = tree.closest_near(q, hint, &mut stack).unwrap();
                assert!((vec3::dist2(q, near.point) - brute(&tree, q, |_| true)).abs() < 1e-12);
                let t = tree.tris[near.tri as usize];
                let w = near.weights;
                for (i, want) in near.point.iter().enumerate() {
                    let x = w[0] * t[0][i] + w[1] * t[1][i] + w[2] * t[2][i];
                    assert!((x - want).abs() < 1e-9);
                }
                let face = mesh.face(tree.triangle_face(near.tri)).unwrap();
                let corners: Vec<VertexKey> = face.vertices().collect();
                for v in tree.triangle_vertices(near.tri) {
                    assert!(corners.contains(&v));
                }
                last = Some(near.tri);
            }
        }
    }

    #[test]
    fn the_filter_keeps_the_answer_on_the_faces_it_accepts() {
        let mesh = shapes::icosphere(2);
        let tree = FaceTree::build(&mesh).unwrap();
        let even = |t: u32| tree.triangle_face(t).index() % 2 == 0;
        let mut stack = Vec::new();
        for (k, q) in points(100, -1.5, 1.5).into_iter().enumerate() {
            // A hint on a refused face is skipped, not used.
            let hint = Some(k as u32 % tree.tris.len() as u32);
            let near = tree.closest_near_where(q, hint, even, &mut stack).unwrap();
            assert!(even(near.tri));
            assert!((vec3::dist2(q, near.point) - brute(&tree, q, even)).abs() < 1e-12);
        }
        let none = tree.closest_near_where([0.0; 3], Some(0), |_| false, &mut stack);
        assert!(none.is_none());
    }

    #[test]
    fn first_triangles_name_each_face_once() {
        let mesh = shapes::torus(12, 6, 1.0, 0.3).unwrap();
        let tree = FaceTree::build(&mesh).unwrap();
        let first = tree.first_triangles(mesh.slot_counts()[3]);
        for f in mesh.faces() {
            let t = first[f.index()];
            assert_eq!(tree.triangle_face(t), f);
            assert_eq!(tree.meta[t as usize].fan, 1);
        }
        let named = first.iter().filter(|&&t| t != u32::MAX).count();
        assert_eq!(named, mesh.face_count());
    }
}
