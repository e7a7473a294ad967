//! Pairs of faces that intersect: within one mesh
//! ([`FaceTree::self_intersections`]) and between two meshes
//! ([`FaceTree::intersecting_pairs`]).
//!
//! The broad phase walks the tree against itself (or against the other
//! tree) on node boxes; as these are `f32` boxes rounded outwards, a box
//! test never drops a pair that touches. The narrow phase tests the fan
//! triangles of the two faces with exact predicates
//! ([`orient3d`](crate::predicates), and `orient2d` on a coordinate plane for
//! coplanar triangles), so every decision is that of exact arithmetic on the
//! stored `f64` positions.
//!
//! What counts is on [`FaceTree::self_intersections`].

use super::{FaceTree, Node};
use crate::keys::{FaceKey, VertexKey};
use crate::mesh::Mesh;
use crate::predicates::{drop_axis, orient2d, orient3d, projection_axis, V2};
use crate::vec3::V3;

use super::error::QueryError;

impl FaceTree {
    /// The pairs of faces of `mesh` that intersect (see below for what
    /// counts), each as `(a, b)` with `a.index() < b.index()`, once,
    /// sorted.
    ///
    /// # What counts
    ///
    /// Two faces intersect when their (closed) fan triangles have a common
    /// point that is not explained by the corners they share:
    ///
    /// - faces with no common vertex: any common point counts, touching
    ///   included (a vertex resting on another face, two edges crossing);
    /// - faces sharing one vertex: a common point other than that vertex (a
    ///   face passing through the other, or an edge of one running along the
    ///   other's plane inside its corner);
    /// - faces sharing an edge (two vertices): a common point off that edge,
    ///   which happens only when they are coplanar and on the same side of the
    ///   edge (a fold flat onto itself); a dihedral angle of any size, however
    ///   small, is not an intersection.
    ///
    /// "Common vertex" means the same [`VertexKey`],
    /// not the same position: two distinct vertices at one position are a
    /// touch. An n-gon is tested through its fan triangles, and a face's own
    /// fan triangles are never tested against each other. A degenerate fan
    /// triangle (collinear corners) intersects nothing, as it is never hit by a
    /// ray either.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`] when `mesh` changed since the build (or is
    /// another mesh).
    ///
    /// # Complexity
    /// A walk of the tree against itself: about O(n log n) for a mesh whose
    /// faces are not piled on each other, plus a constant number of exact
    /// predicates per pair of triangles whose boxes overlap.
    ///
    /// ```
    /// use meshloom::query::FaceTree;
    /// let mesh = meshloom::shapes::icosphere(2);
    /// let tree = FaceTree::build(&mesh)?;
    /// assert!(tree.self_intersections(&mesh)?.is_empty());
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn self_intersections(&self, mesh: &Mesh) -> Result<Vec<(FaceKey, FaceKey)>, QueryError> {
        self.check(mesh)?;
        let mut out = Vec::new();
        if self.nodes.is_empty() {
            return Ok(out);
        }
        let mut stack = vec![(0usize, 0usize)];
        while let Some((a, b)) = stack.pop() {
            let (na, nb) = (self.nodes[a], self.nodes[b]);
            if a == b {
                if na.is_leaf() {
                    let r = na.first as usize..(na.first + na.count) as usize;
                    for i in r.clone() {
                        for j in i + 1..r.end {
                            self.self_pair(i, j, &mut out);
                        }
                    }
                } else {
                    let (l, r) = na.children(a);
                    stack.extend([(l, l), (r, r), (l, r)]);
                }
            } else if overlap(&na, &nb) {
                descend(a, &na, b, &nb, &mut stack, |i, j| {
                    self.self_pair(i, j, &mut out)
                });
            }
        }
        Ok(finish(out))
    }

    /// The pairs `(face of mesh, face of other_mesh)` whose faces intersect,
    /// touching included (two meshes share no vertices), once each, sorted.
    /// `self` must answer for `mesh` and `other` for `other_mesh`.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`] when either tree does not answer for its
    /// mesh.
    ///
    /// ```
    /// use meshloom::query::FaceTree;
    /// let a = meshloom::shapes::cube();
    /// let mut b = meshloom::shapes::cube();
    /// for p in b.position_slots_mut().unwrap() {
    ///    p[0] += 0.5; // half-way through the first cube
    /// }
    /// let (ta, tb) = (FaceTree::build(&a)?, FaceTree::build(&b)?);
    /// assert!(!ta.intersecting_pairs(&a, &tb, &b)?.is_empty());
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn intersecting_pairs(
        &self,
        mesh: &Mesh,
        other: &FaceTree,
        other_mesh: &Mesh,
    ) -> Result<Vec<(FaceKey, FaceKey)>, QueryError> {
        self.check(mesh)?;
        other.check(other_mesh)?;
        let mut out = Vec::new();
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return Ok(out);
        }
        let mut stack = vec![(0usize, 0usize)];
        while let Some((a, b)) = stack.pop() {
            let (na, nb) = (self.nodes[a], other.nodes[b]);
            if overlap(&na, &nb) {
                descend(a, &na, b, &nb, &mut stack, |i, j| {
                    let (s, t) = (&self.tris[i], &other.tris[j]);
                    if boxes_touch(s, t) && triangles_meet(s, t) {
                        out.push((self.meta[i].face, other.meta[j].face));
                    }
                });
            }
        }
        out.sort_unstable();
        out.dedup();
        Ok(out)
    }

    /// Test leaf triangles `i` and `j` of this tree against each other.
    fn self_pair(&self, i: usize, j: usize, out: &mut Vec<(FaceKey, FaceKey)>) {
        let (mi, mj) = (&self.meta[i], &self.meta[j]);
        if mi.face == mj.face || !boxes_touch(&self.tris[i], &self.tris[j]) {
            return;
        }
        if intersect_beyond_shared(&self.tris[i], &mi.v, &self.tris[j], &mj.v) {
            out.push((mi.face, mj.face));
        }
    }
}

/// Pairs ordered `(lower index, higher index)`, sorted, once.
fn finish(mut out: Vec<(FaceKey, FaceKey)>) -> Vec<(FaceKey, FaceKey)> {
    for p in &mut out {
        if p.1.index() < p.0.index() {
            *p = (p.1, p.0);
        }
    }
    out.sort_unstable_by_key(|p| (p.0.index(), p.1.index()));
    out.dedup();
    out
}

/// Whether two nodes' boxes overlap (closed).
#[inline]
fn overlap(a: &Node, b: &Node) -> bool {
    (0..3).all(|k| a.lo[k] <= b.hi[k] && b.lo[k] <= a.hi[k])
}

/// For two overlapping nodes: test their triangles when both are leaves,
/// otherwise push the pairs one level down (splitting the inner node, or
/// the one with the larger box when both are inner).
fn descend(
    a: usize,
    na: &Node,
    b: usize,
    nb: &Node,
    stack: &mut Vec<(usize, usize)>,
    mut leaf: impl FnMut(usize, usize),
) {
    let split_a = match (na.is_leaf(), nb.is_leaf()) {
        (true, true) => {
            for i in na.first..na.first + na.count {
                for j in nb.first..nb.first + nb.count {
                    leaf(i as usize, j as usize);
                }
            }
            return;
        }
        (false, true) => true,
        (true, false) => false,
        (false, false) => extent(na) >= extent(nb),
    };
    if split_a {
        let (x, y) = na.children(a);
        stack.extend([(x, b), (y, b)]);
    } else {
        let (x, y) = nb.children(b);
        stack.extend([(a, x), (a, y)]);
    }
}

/// The sum of a node box's sides.
fn extent(n: &Node) -> f32 {
    (0..3).map(|k| n.hi[k] - n.lo[k]).sum()
}

/// Whether two triangles' (exact, closed) boxes overlap.
#[inline]
fn boxes_touch(s: &[V3; 3], t: &[V3; 3]) -> bool {
    (0..3).all(|k| {
        let (slo, shi) = min_max(s[0][k], s[1][k], s[2][k]);
        let (tlo, thi) = min_max(t[0][k], t[1][k], t[2][k]);
        slo <= thi && tlo <= shi
    })
}

fn min_max(a: f64, b: f64, c: f64) -> (f64, f64) {
    (a.min(b).min(c), a.max(b).max(c))
}

/// Whether triangles `s` and `t` (corners' vertices `sv`, `tv`) have a
/// common point beyond the corners they share (see the module's rules):
/// the narrow phase of [`FaceTree::self_intersections`].
pub fn intersect_beyond_shared(
    s: &[V3; 3],
    sv: &[VertexKey; 3],
    t: &[V3; 3],
    tv: &[VertexKey; 3],
) -> bool {
    // Shared corners: (index in s, index in t).
    let mut shared = [(0usize, 0usize); 3];
    let mut n = 0;
    for (i, a) in sv.iter().enumerate() {
        for (j, b) in tv.iter().enumerate() {
            if a == b && n < 3 {
                shared[n] = (i, j);
                n += 1;
            }
        }
    }
    match n {
        0 => triangles_meet(s, t),
        1 => {
            let (i, j) = shared[0];
            share_one_vertex(rotate(s, i), rotate(t, j))
        }
        2 => {
            let (i0, j0) = shared[0];
            let (i1, j1) = shared[1];
            let (a, b) = (s[3 - i0 - i1], t[3 - j0 - j1]);
            share_an_edge(s[i0], s[i1], a, b, s)
        }
        // The same three vertices: the same triangle twice.
        _ => projection_axis(s[0], s[1], s[2]).is_some(),
    }
}

/// `t` turned so that corner `i` comes first.
fn rotate(t: &[V3; 3], i: usize) -> [V3; 3] {
    [t[i], t[(i + 1) % 3], t[(i + 2) % 3]]
}

/// Whether the closed triangles `s` and `t` have a common point (false
/// when either is degenerate). Two closed triangles meet exactly when an
/// edge of one meets the other: their intersection is convex, and its
/// boundary lies on the triangles' boundaries. The narrow phase of
/// [`FaceTree::intersecting_pairs`].
pub fn triangles_meet(s: &[V3; 3], t: &[V3; 3]) -> bool {
    let (Some(_), Some(_)) = (
        projection_axis(s[0], s[1], s[2]),
        projection_axis(t[0], t[1], t[2]),
    ) else {
        return false;
    };
    // Early out: all of one triangle strictly on one side of the other's
    // plane.
    if strictly_one_side(s, t) || strictly_one_side(t, s) {
        return false;
    }
    (0..3).any(|k| segment_meets_triangle(s[k], s[(k + 1) % 3], t))
        || (0..3).any(|k| segment_meets_triangle(t[k], t[(k + 1) % 3], s))
}

/// Whether `t`'s corners all lie strictly on one side of `s`'s plane.
fn strictly_one_side(s: &[V3; 3], t: &[V3; 3]) -> bool {
    let o = t.map(|p| orient3d(s[0], s[1], s[2], p));
    (o[0] > 0.0 && o[1] > 0.0 && o[2] > 0.0) || (o[0] < 0.0 && o[1] < 0.0 && o[2] < 0.0)
}

/// Whether the closed segment `p q` meets the closed, non-degenerate
/// triangle `t`.
fn segment_meets_triangle(p: V3, q: V3, t: &[V3; 3]) -> bool {
    let [a, b, c] = *t;
    let (sp, sq) = (orient3d(a, b, c, p), orient3d(a, b, c, q));
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) {
        return false;
    }
    if sp == 0.0 && sq == 0.0 {
        let k = projection_axis(a, b, c).expect("a non-degenerate triangle");
        let f = |p| drop_axis(p, k);
        return segment_meets_triangle_2d(f(p), f(q), [f(a), f(b), f(c)]);
    }
    // The segment crosses (or ends on) the plane at one point: it is in the
    // triangle when the line p q passes each edge on the same side.
    let o = [
        orient3d(p, q, a, b),
        orient3d(p, q, b, c),
        orient3d(p, q, c, a),
    ];
    (o[0] >= 0.0 && o[1] >= 0.0 && o[2] >= 0.0) || (o[0] <= 0.0 && o[1] <= 0.0 && o[2] <= 0.0)
}

/// Whether the closed segment `p q` meets the closed, non-degenerate
/// triangle `t` in the plane.
fn segment_meets_triangle_2d(p: V2, q: V2, t: [V2; 3]) -> bool {
    point_in_triangle_2d(p, t)
        || point_in_triangle_2d(q, t)
        || (0..3).any(|k| segments_meet_2d(p, q, t[k], t[(k + 1) % 3]))
}

/// Whether `p` lies in the closed, non-degenerate triangle `t`.
fn point_in_triangle_2d(p: V2, t: [V2; 3]) -> bool {
    let o = [
        orient2d(t[0], t[1], p),
        orient2d(t[1], t[2], p),
        orient2d(t[2], t[0], p),
    ];
    (o[0] >= 0.0 && o[1] >= 0.0 && o[2] >= 0.0) || (o[0] <= 0.0 && o[1] <= 0.0 && o[2] <= 0.0)
}

/// Whether the closed segments `a b` and `c d` meet.
fn segments_meet_2d(a: V2, b: V2, c: V2, d: V2) -> bool {
    let (o1, o2) = (orient2d(a, b, c), orient2d(a, b, d));
    let (o3, o4) = (orient2d(c, d, a), orient2d(c, d, b));
    if o1 == 0.0 && o2 == 0.0 {
        // Collinear: overlapping extents on both axes.
        return (0..2)
            .all(|k| a[k].min(b[k]) <= c[k].max(d[k]) && c[k].min(d[k]) <= a[k].max(b[k]));
    }
    let opposite = |x: f64, y: f64| (x >= 0.0 && y <= 0.0) || (x <= 0.0 && y >= 0.0);
    opposite(o1, o2) && opposite(o3, o4)
}

/// Triangles `v a b` and `v c d` sharing corner `v`: whether they have a
/// common point other than `v`. That point's segment to `v` lies in both,
/// and its far end is on an edge of one of them: the edge opposite `v`
/// (which does not hold `v`) meeting the other triangle, or an edge out
/// of `v` running into the other's corner at `v`.
fn share_one_vertex(s: [V3; 3], t: [V3; 3]) -> bool {
    if projection_axis(s[0], s[1], s[2]).is_none() || projection_axis(t[0], t[1], t[2]).is_none() {
        return false;
    }
    segment_meets_triangle(s[1], s[2], &t)
        || segment_meets_triangle(t[1], t[2], &s)
        || [s[1], s[2]].iter().any(|&a| ray_in_corner(a, &t))
        || [t[1], t[2]].iter().any(|&a| ray_in_corner(a, &s))
}

/// Whether the ray from `t[0]` through `a` starts into the closed corner
/// of the triangle `t` at `t[0]` (in its plane, between its edges).
fn ray_in_corner(a: V3, t: &[V3; 3]) -> bool {
    let [v, c, d] = *t;
    if orient3d(v, c, d, a) != 0.0 {
        return false;
    }
    let k = projection_axis(v, c, d).expect("a non-degenerate triangle");
    let f = |p| drop_axis(p, k);
    let (v, c, d, a) = (f(v), f(c), f(d), f(a));
    let turn = orient2d(v, c, d);
    let (x, y) = (orient2d(v, c, a), orient2d(v, a, d));
    if turn > 0.0 {
        x >= 0.0 && y >= 0.0
    } else {
        x <= 0.0 && y <= 0.0
    }
}

/// Triangles `u w a` (`s`) and `u w b` sharing the edge `u w`: they meet
/// off the edge only when coplanar with `a` and `b` on the same side of it.
fn share_an_edge(u: V3, w: V3, a: V3, b: V3, s: &[V3; 3]) -> bool {
    let Some(k) = projection_axis(s[0], s[1], s[2]) else {
        return false;
    };
    if orient3d(u, w, a, b) != 0.0 {
        return false;
    }
    let f = |p| drop_axis(p, k);
    let (x, y) = (orient2d(f(u), f(w), f(a)), orient2d(f(u), f(w), f(b)));
    (x > 0.0 && y > 0.0) || (x < 0.0 && y < 0.0)
}
