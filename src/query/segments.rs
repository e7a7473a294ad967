//! A tree over line segments for closest points, for the remesher's
//! boundary and feature lines (a vertex on a line slides along it and is
//! projected back onto the input's lines).
//!
//! It is [`FaceTree`](super::FaceTree)'s hierarchy, not another one: the
//! same binned SAH build (a segment `ab` goes in as the flat triangle
//! `abb`, whose box and centroid are the segment's), the same nodes and the
//! same nearest-first walk; only the leaves hold segments. Queries take a
//! hint (the segment a point was answered with last time), as
//! [`FaceTree`](super::FaceTree)'s hinted ones do.

use super::closest::{box_dist2, walk_nodes};
use super::{build, Node};
use crate::vec3::{self, V3};

/// A closest point on the segments.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SegmentNear {
    /// The segment, by its place in the tree (pass it back as the hint).
    pub(crate) seg: u32,
    /// The closest point.
    pub(crate) point: V3,
}

/// A hierarchy over segments.
#[derive(Clone, Debug)]
pub(crate) struct SegmentTree {
    /// Depth-first, as a face tree's.
    nodes: Vec<Node>,
    /// The segments in leaf order.
    segs: Vec<[V3; 2]>,
}

/// The closest point of segment `s` to `q`: the point and its parameter.
#[inline]
fn closest_on_segment(q: V3, s: &[V3; 2]) -> V3 {
    let ab = vec3::sub(s[1], s[0]);
    let l2 = vec3::dot(ab, ab);
    let t = if l2 > 0.0 {
        (vec3::dot(vec3::sub(q, s[0]), ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    vec3::axpy(s[0], t, ab)
}

impl SegmentTree {
    /// Build over `segs`.
    pub(crate) fn build(segs: &[[V3; 2]]) -> SegmentTree {
        let flat: Vec<[V3; 3]> = segs.iter().map(|s| [s[0], s[1], s[1]]).collect();
        let (nodes, order) = build::build(&flat);
        SegmentTree {
            nodes,
            segs: order.iter().map(|&i| segs[i as usize]).collect(),
        }
    }

    /// The closest point of the segments to `q`, starting from segment
    /// `hint` (a place in the tree, as [`SegmentNear::seg`]); `stack` is
    /// scratch space. `None` for an empty tree.
    pub(crate) fn closest(
        &self,
        q: V3,
        hint: Option<u32>,
        stack: &mut Vec<u32>,
    ) -> Option<SegmentNear> {
        let mut best: Option<SegmentNear> = None;
        let mut bound = f64::INFINITY;
        let mut hinted = usize::MAX;
        if let Some(h) = hint.filter(|&h| (h as usize) < self.segs.len()) {
            let x = closest_on_segment(q, &self.segs[h as usize]);
            bound = vec3::dist2(q, x);
            best = Some(SegmentNear { seg: h, point: x });
            hinted = h as usize;
        }
        walk_nodes(
            &self.nodes,
            |lo, hi| box_dist2(q, lo, hi),
            bound,
            stack,
            |seg| {
                if seg == hinted {
                    return bound;
                }
                let x = closest_on_segment(q, &self.segs[seg]);
                let d2 = vec3::dist2(q, x);
                if d2 < bound {
                    bound = d2;
                    best = Some(SegmentNear {
                        seg: seg as u32,
                        point: x,
                    });
                }
                bound
            },
        );
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_equal_brute_force() {
        // A helix of short segments, and a few long ones across it.
        let mut segs: Vec<[V3; 2]> = (0..200)
            .map(|i| {
                let p = |k: f64| [(0.1 * k).cos(), (0.1 * k).sin(), 0.01 * k];
                [p(i as f64), p(i as f64 + 1.0)]
            })
            .collect();
        segs.push([[-2.0, 0.0, 0.5], [2.0, 0.0, 0.5]]);
        segs.push([[0.0, -2.0, 1.5], [0.0, 2.0, 1.5]]);
        segs.push([[0.3, 0.3, 0.3], [0.3, 0.3, 0.3]]); // a point
        let tree = SegmentTree::build(&segs);
        let mut stack = Vec::new();
        let mut s = 99u64;
        let mut rnd = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut last = None;
        for k in 0..400 {
            let q = [4.0 * rnd() - 2.0, 4.0 * rnd() - 2.0, 3.0 * rnd() - 0.5];
            let hint = [None, last, Some(k * 13 % 203), Some(999)][k as usize % 4];
            let near = tree.closest(q, hint, &mut stack).unwrap();
            let want = segs
                .iter()
                .map(|s| vec3::dist2(q, closest_on_segment(q, s)))
                .fold(f64::INFINITY, f64::min);
            assert!((vec3::dist2(q, near.point) - want).abs() < 1e-12);
            // The point lies on the segment named.
            let on = closest_on_segment(near.point, &tree.segs[near.seg as usize]);
            assert!(vec3::dist2(on, near.point) < 1e-20);
            last = Some(near.seg);
        }
        assert!(SegmentTree::build(&[])
            .closest([0.0; 3], None, &mut stack)
            .is_none());
    }
}
