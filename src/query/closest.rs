//! Points against the tree: the closest point on the surface, the faces and
//! vertices within a radius, the nearest vertex.

use super::error::{check_bound, check_point, QueryError};
use super::ray::batch;
use super::{FaceCoords, FaceTree, Node};
use crate::keys::{FaceKey, VertexKey};
use crate::mesh::Mesh;
use crate::vec3::{self, V3};

/// Widening of box distance bounds, relative (see the ray's).
const SLACK: f64 = 1e-12;

/// The closest point of the surface to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Closest {
    /// The face it lies on (on a tie, either face).
    pub face: FaceKey,
    /// The closest point.
    pub point: [f64; 3],
    /// Its distance from the query point.
    pub distance: f64,
    /// Where on the face (see [`FaceCoords`]).
    pub coords: FaceCoords,
}

/// The nearest vertex to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    /// The vertex (on a tie, either).
    pub vertex: VertexKey,
    /// Its distance from the query point.
    pub distance: f64,
}

/// The closest point of triangle `p` to `q` and its barycentric weights
/// (Ericson, Real-Time Collision Detection, 5.1.5).
#[inline]
pub(super) fn closest_on_triangle(q: V3, p: &[V3; 3]) -> (V3, [f64; 3]) {
    let [a, b, c] = *p;
    let ab = vec3::sub(b, a);
    let ac = vec3::sub(c, a);
    let ap = vec3::sub(q, a);
    let d1 = vec3::dot(ab, ap);
    let d2 = vec3::dot(ac, ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, [1.0, 0.0, 0.0]);
    }
    let bp = vec3::sub(q, b);
    let d3 = vec3::dot(ab, bp);
    let d4 = vec3::dot(ac, bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, [0.0, 1.0, 0.0]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (vec3::axpy(a, v, ab), [1.0 - v, v, 0.0]);
    }
    let cp = vec3::sub(q, c);
    let d5 = vec3::dot(ab, cp);
    let d6 = vec3::dot(ac, cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, [0.0, 0.0, 1.0]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (vec3::axpy(a, w, ac), [1.0 - w, 0.0, w]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (vec3::axpy(b, w, vec3::sub(c, b)), [0.0, 1.0 - w, w]);
    }
    let denom = va + vb + vc;
    if !(denom.is_finite() && denom != 0.0) {
        // A degenerate triangle whose regions above did not catch `q`:
        // the closest of its three edges' points.
        return degenerate(q, p);
    }
    let inv = 1.0 / denom;
    let v = vb * inv;
    let w = vc * inv;
    let point = vec3::add(a, vec3::add(vec3::scale(ab, v), vec3::scale(ac, w)));
    (point, [1.0 - v - w, v, w])
}

/// The closest point over the three edges of a degenerate triangle.
fn degenerate(q: V3, p: &[V3; 3]) -> (V3, [f64; 3]) {
    let mut best = (f64::INFINITY, p[0], [1.0, 0.0, 0.0]);
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let d = vec3::sub(p[j], p[i]);
        let len2 = vec3::norm2(d);
        let s = if len2 > 0.0 {
            (vec3::dot(vec3::sub(q, p[i]), d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let x = vec3::axpy(p[i], s, d);
        let d2 = vec3::dist2(q, x);
        if d2 < best.0 {
            let mut w = [0.0; 3];
            w[i] = 1.0 - s;
            w[j] = s;
            best = (d2, x, w);
        }
    }
    (best.1, best.2)
}

/// The closest point of one triangle to `q` and its weights, by brute
/// force: for tests and for checking the tree.
#[doc(hidden)]
pub fn triangle_closest(q: [f64; 3], p: &[[f64; 3]; 3]) -> ([f64; 3], [f64; 3]) {
    closest_on_triangle(q, p)
}

/// Whether `c` lies within the optional maximum distance (inclusive).
fn within(c: &Closest, max_distance: Option<f64>) -> bool {
    max_distance.is_none_or(|m| c.distance <= m)
}

/// The squared distance from `q` to the box, shrunk by [`SLACK`].
#[inline(always)]
pub(super) fn box_dist2(q: V3, lo: V3, hi: V3) -> f64 {
    let mut s = 0.0;
    for k in 0..3 {
        let d = (lo[k] - q[k]).max(q[k] - hi[k]).max(0.0);
        s += d * d;
    }
    s * (1.0 - 4.0 * SLACK)
}

impl FaceTree {
    /// The closest point of the surface to `point`, or `None` when no face
    /// lies within `max_distance` (inclusive; `None`: no limit) or the
    /// mesh has no faces.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`]; [`QueryError::NonFinitePoint`];
    /// [`QueryError::InvalidBound`] for a NaN or negative `max_distance`.
    ///
    /// ```
    /// use meshloom::query::FaceTree;
    /// let mesh = meshloom::shapes::cube(); // [0, 1]³
    /// let tree = FaceTree::build(&mesh)?;
    /// let c = tree.closest_point(&mesh, [2.5, 0.25, 0.75], None)?.unwrap();
    /// assert!((c.distance - 1.5).abs() < 1e-12);
    /// assert_eq!(c.point, [1.0, 0.25, 0.75]);
    /// assert!(tree.closest_point(&mesh, [2.5, 0.25, 0.75], Some(1.0))?.is_none());
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn closest_point(
        &self,
        mesh: &Mesh,
        point: [f64; 3],
        max_distance: Option<f64>,
    ) -> Result<Option<Closest>, QueryError> {
        self.check(mesh)?;
        check_point(0, point)?;
        let limit = self.limit(max_distance)?;
        Ok(self
            .closest(point, limit, &mut Vec::new())
            .filter(|c| within(c, max_distance)))
    }

    /// [`closest_point`](FaceTree::closest_point) for many points (on
    /// rayon's threads with the `parallel` feature).
    ///
    /// # Errors
    /// As [`closest_point`](FaceTree::closest_point), naming the first bad
    /// point by index.
    pub fn closest_points(
        &self,
        mesh: &Mesh,
        points: &[[f64; 3]],
        max_distance: Option<f64>,
    ) -> Result<Vec<Option<Closest>>, QueryError> {
        self.check(mesh)?;
        for (i, p) in points.iter().enumerate() {
            check_point(i, *p)?;
        }
        let limit = self.limit(max_distance)?;
        Ok(batch(points, |p, stack| {
            self.closest(*p, limit, stack)
                .filter(|c| within(c, max_distance))
        }))
    }

    /// The squared distance limit of an optional maximum distance (widened:
    /// the answer is then held to the distance itself, see [`within`]).
    fn limit(&self, max_distance: Option<f64>) -> Result<f64, QueryError> {
        match max_distance {
            Some(d) => {
                check_bound("max_distance", d)?;
                Ok(d * d * (1.0 + 4.0 * SLACK))
            }
            None => Ok(f64::INFINITY),
        }
    }

    /// The closest point within squared distance `limit` of a checked point.
    fn closest(&self, q: V3, limit: f64, stack: &mut Vec<u32>) -> Option<Closest> {
        let mut best: Option<(f64, usize, V3, [f64; 3])> = None;
        let mut bound = limit;
        self.walk_point(q, limit, stack, |tree, tri| {
            let (x, w) = closest_on_triangle(q, &tree.tris[tri]);
            let d2 = vec3::dist2(q, x);
            if d2 <= bound && best.is_none_or(|b| d2 < b.0) {
                best = Some((d2, tri, x, w));
                bound = d2;
            }
            bound
        });
        best.map(|(d2, tri, x, w)| Closest {
            face: self.meta[tri].face,
            point: x,
            distance: d2.sqrt(),
            coords: self.coords(tri, w),
        })
    }

    /// The faces with a point within `radius` of `point` (inclusive), in
    /// key order, each once.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`]; [`QueryError::NonFinitePoint`];
    /// [`QueryError::InvalidBound`] for a NaN or negative radius.
    ///
    /// ```
    /// use meshloom::query::FaceTree;
    /// let mesh = meshloom::shapes::cube(); // [0, 1]³
    /// let tree = FaceTree::build(&mesh)?;
    /// assert_eq!(tree.faces_within(&mesh, [1.1, 0.5, 0.5], 0.2)?.len(), 1);
    /// assert_eq!(tree.faces_within(&mesh, [1.1, 1.1, 1.1], 0.2)?.len(), 3); // a corner
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn faces_within(
        &self,
        mesh: &Mesh,
        point: [f64; 3],
        radius: f64,
    ) -> Result<Vec<FaceKey>, QueryError> {
        self.check(mesh)?;
        check_point(0, point)?;
        check_bound("radius", radius)?;
        let r2 = radius * radius;
        let mut out = Vec::new();
        self.walk_point(point, r2, &mut Vec::new(), |tree, tri| {
            let (x, _) = closest_on_triangle(point, &tree.tris[tri]);
            if vec3::dist2(point, x) <= r2 {
                out.push(tree.meta[tri].face);
            }
            r2
        });
        out.sort_unstable();
        out.dedup();
        Ok(out)
    }

    /// The vertices of faces within `radius` of `point` (inclusive), in
    /// key order, each once.
    ///
    /// # Errors
    /// As [`faces_within`](FaceTree::faces_within).
    ///
    /// ```
    /// use meshloom::query::FaceTree;
    /// let mesh = meshloom::shapes::cube();
    /// let tree = FaceTree::build(&mesh)?;
    /// assert_eq!(tree.vertices_within(&mesh, [1.1, 1.1, 1.1], 0.2)?.len(), 1);
    /// assert_eq!(tree.vertices_within(&mesh, [0.5, 0.5, 0.5], 1.0)?.len(), 8);
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn vertices_within(
        &self,
        mesh: &Mesh,
        point: [f64; 3],
        radius: f64,
    ) -> Result<Vec<VertexKey>, QueryError> {
        self.check(mesh)?;
        check_point(0, point)?;
        check_bound("radius", radius)?;
        let r2 = radius * radius;
        let mut out = Vec::new();
        self.walk_point(point, r2, &mut Vec::new(), |tree, tri| {
            for (k, p) in tree.tris[tri].iter().enumerate() {
                if vec3::dist2(point, *p) <= r2 {
                    out.push(tree.meta[tri].v[k]);
                }
            }
            r2
        });
        out.sort_unstable();
        out.dedup();
        Ok(out)
    }

    /// The vertex nearest to `point` among the faces' corners, or `None`
    /// for a mesh without faces.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`]; [`QueryError::NonFinitePoint`].
    ///
    /// ```
    /// use meshloom::query::FaceTree;
    /// let mesh = meshloom::shapes::cube();
    /// let tree = FaceTree::build(&mesh)?;
    /// let n = tree.nearest_vertex(&mesh, [0.9, 1.1, 0.0])?.unwrap();
    /// assert_eq!(mesh.position(n.vertex).unwrap(), [1.0, 1.0, 0.0]);
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn nearest_vertex(
        &self,
        mesh: &Mesh,
        point: [f64; 3],
    ) -> Result<Option<Nearest>, QueryError> {
        self.check(mesh)?;
        check_point(0, point)?;
        let mut best: Option<(f64, VertexKey)> = None;
        let mut bound = f64::INFINITY;
        self.walk_point(point, f64::INFINITY, &mut Vec::new(), |tree, tri| {
            for (k, p) in tree.tris[tri].iter().enumerate() {
                let d2 = vec3::dist2(point, *p);
                if best.is_none_or(|b| d2 < b.0) {
                    best = Some((d2, tree.meta[tri].v[k]));
                    bound = d2;
                }
            }
            bound
        });
        Ok(best.map(|(d2, vertex)| Nearest {
            vertex,
            distance: d2.sqrt(),
        }))
    }

    /// Visit every triangle in a box within the bound of `q`, nearest box
    /// first; `visit(tree, tri)` returns the squared distance bound for the
    /// boxes still to visit.
    pub(super) fn walk_point(
        &self,
        q: V3,
        bound: f64,
        stack: &mut Vec<u32>,
        visit: impl FnMut(&FaceTree, usize) -> f64,
    ) {
        self.walk_nearest(|lo, hi| box_dist2(q, lo, hi), bound, stack, visit);
    }

    /// Visit every triangle in a box whose `key` (a lower bound of what
    /// the box's triangles can score) is within the bound, lowest key
    /// first; `visit(tree, tri)` returns the bound for the boxes still to
    /// visit.
    #[inline]
    pub(super) fn walk_nearest(
        &self,
        key: impl Fn(V3, V3) -> f64,
        bound: f64,
        stack: &mut Vec<u32>,
        mut visit: impl FnMut(&FaceTree, usize) -> f64,
    ) {
        walk_nodes(&self.nodes, key, bound, stack, |tri| visit(self, tri));
    }
}

/// [`FaceTree::walk_nearest`] over any hierarchy of [`Node`]s (the
/// segment tree's too): `visit(item)` gets each item of a leaf in reach.
#[inline]
pub(super) fn walk_nodes(
    nodes: &[Node],
    key: impl Fn(V3, V3) -> f64,
    bound: f64,
    stack: &mut Vec<u32>,
    mut visit: impl FnMut(usize) -> f64,
) {
    if nodes.is_empty() {
        return;
    }
    let mut bound = bound;
    stack.clear();
    let mut node = 0usize;
    loop {
        let n = &nodes[node];
        if n.is_leaf() {
            let first = n.first as usize;
            for item in first..first + n.count as usize {
                bound = visit(item);
            }
        } else {
            let (a, b) = n.children(node);
            let da = key(nodes[a].lo(), nodes[a].hi());
            let db = key(nodes[b].lo(), nodes[b].hi());
            let (near, dn, far, df) = if da <= db {
                (a, da, b, db)
            } else {
                (b, db, a, da)
            };
            if dn <= bound {
                if df <= bound {
                    stack.push(far as u32);
                }
                node = near;
                continue;
            }
        }
        loop {
            let Some(next) = stack.pop() else { return };
            let m = &nodes[next as usize];
            if key(m.lo(), m.hi()) <= bound {
                node = next as usize;
                break;
            }
        }
    }
}
