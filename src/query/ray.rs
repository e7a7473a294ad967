//! Rays against the tree: the first hit, every hit, any hit.

use super::error::{check_bound, QueryError};
use super::{FaceCoords, FaceTree, Node};
use crate::keys::FaceKey;
use crate::mesh::Mesh;
use crate::vec3::{self, V3};

/// Widening of box tests, relative: a box is never refused for a point the
/// triangle test would accept.
const SLACK: f64 = 1e-12;

/// A ray: the points `origin + t · direction` for `t ≥ 0`. The direction
/// need not be unit length; `t` is measured in its lengths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: [f64; 3],
    /// Its direction (not zero).
    pub direction: [f64; 3],
}

impl Ray {
    /// The ray from `origin` along `direction`.
    pub fn new(origin: [f64; 3], direction: [f64; 3]) -> Ray {
        Ray { origin, direction }
    }

    /// `Ok` if the ray is finite with a non-zero direction.
    pub(super) fn check(&self, index: usize) -> Result<(), QueryError> {
        if !self
            .origin
            .iter()
            .chain(&self.direction)
            .all(|c| c.is_finite())
        {
            return Err(QueryError::NonFiniteRay {
                index,
                origin: self.origin,
                direction: self.direction,
            });
        }
        if self.direction == [0.0; 3] {
            return Err(QueryError::ZeroDirection { index });
        }
        Ok(())
    }
}

/// Where a ray meets a face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The face hit.
    pub face: FaceKey,
    /// The ray parameter: the hit is `origin + t · direction`.
    pub t: f64,
    /// The point hit.
    pub point: [f64; 3],
    /// Where on the face (see [`FaceCoords`]).
    pub coords: FaceCoords,
}

/// A ray prepared for box tests.
struct Prepared {
    o: V3,
    d: V3,
    inv: V3,
    /// Whether a component of `1 / d` is infinite (`d` has a zero): then
    /// `0 · ∞ = NaN` can arise and the box test takes the careful path.
    flat: bool,
}

/// The smaller, in one instruction (NaN is never passed on the fast path).
#[inline(always)]
fn fmin(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

/// The larger, as [`fmin`].
#[inline(always)]
fn fmax(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

impl Prepared {
    fn new(r: &Ray) -> Prepared {
        let d = r.direction;
        let inv = [1.0 / d[0], 1.0 / d[1], 1.0 / d[2]];
        Prepared {
            o: r.origin,
            d,
            inv,
            flat: !inv.iter().all(|x| x.is_finite()),
        }
    }

    /// The entry parameter of the box if the ray meets it within
    /// `[0, t_max]` (widened by [`SLACK`]), else `+∞`.
    #[inline(always)]
    fn enter(&self, n: &Node, t_max: f64) -> f64 {
        if self.flat {
            return self.enter_flat(n, t_max);
        }
        // `inv` is finite: no product is NaN, and the one-instruction
        // min and max are exact.
        let mut near = 0.0f64;
        let mut far = t_max;
        for k in 0..3 {
            let a = (f64::from(n.lo[k]) - self.o[k]) * self.inv[k];
            let b = (f64::from(n.hi[k]) - self.o[k]) * self.inv[k];
            near = fmax(near, fmin(a, b));
            far = fmin(far, fmax(a, b));
        }
        if near <= far + SLACK * fmax(far.abs(), near) {
            near
        } else {
            f64::INFINITY
        }
    }

    /// [`enter`](Prepared::enter) for a ray parallel to an axis.
    #[cold]
    fn enter_flat(&self, n: &Node, t_max: f64) -> f64 {
        let mut near = 0.0f64;
        let mut far = t_max;
        for k in 0..3 {
            let a = (f64::from(n.lo[k]) - self.o[k]) * self.inv[k];
            let b = (f64::from(n.hi[k]) - self.o[k]) * self.inv[k];
            if a.is_nan() || b.is_nan() {
                // 0 · ∞: the ray runs in a plane of the slab, so inside
                // it; the axis does not restrict.
                continue;
            }
            near = near.max(a.min(b));
            far = far.min(a.max(b));
        }
        if near <= far + SLACK * far.abs().max(near.abs()) {
            near
        } else {
            f64::INFINITY
        }
    }
}

/// Möller–Trumbore, both sides: `(t, u, v)` with the hit at
/// `(1 − u − v)·p₀ + u·p₁ + v·p₂`, or `None` (parallel or degenerate
/// triangle, a miss, or `t < 0`).
#[inline(always)]
fn hit_triangle(o: V3, d: V3, p: &[V3; 3]) -> Option<(f64, f64, f64)> {
    let e1 = vec3::sub(p[1], p[0]);
    let e2 = vec3::sub(p[2], p[0]);
    let pv = vec3::cross(d, e2);
    let det = vec3::dot(e1, pv);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let tv = vec3::sub(o, p[0]);
    let u = vec3::dot(tv, pv) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qv = vec3::cross(tv, e1);
    let v = vec3::dot(d, qv) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = vec3::dot(e2, qv) * inv;
    (t >= 0.0).then_some((t, u, v))
}

/// The first hit of ray `r` with one triangle, by brute force: for tests
/// and for checking the tree.
#[doc(hidden)]
pub fn triangle_hit(r: &Ray, p: &[[f64; 3]; 3]) -> Option<(f64, f64, f64)> {
    hit_triangle(r.origin, r.direction, p)
}

impl FaceTree {
    /// The first face `ray` meets: the least `t ≥ 0` (on a tie, either
    /// face), or `None`.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`] when `mesh` changed since the build;
    /// [`QueryError::NonFiniteRay`], [`QueryError::ZeroDirection`].
    ///
    /// # Complexity
    /// O(log n) for a well-shaped mesh.
    ///
    /// ```
    /// use meshloom::query::{FaceTree, Ray};
    /// let mesh = meshloom::shapes::cube(); // [0, 1]³
    /// let tree = FaceTree::build(&mesh)?;
    /// let hit = tree.ray_cast(&mesh, Ray::new([0.25, 0.75, 3.5], [0.0, 0.0, -2.0]))?.unwrap();
    /// assert!((hit.t - 1.25).abs() < 1e-12 && (hit.point[2] - 1.0).abs() < 1e-12);
    /// let w = hit.coords.weights;
    /// assert!((w[0] + w[1] + w[2] - 1.0).abs() < 1e-12);
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn ray_cast(&self, mesh: &Mesh, ray: Ray) -> Result<Option<Hit>, QueryError> {
        self.check(mesh)?;
        ray.check(0)?;
        Ok(self.first_hit(&ray, &mut Vec::new()))
    }

    /// [`ray_cast`](FaceTree::ray_cast) for many rays (on rayon's threads
    /// with the `parallel` feature).
    ///
    /// # Errors
    /// As [`ray_cast`](FaceTree::ray_cast), naming the first bad ray by
    /// index; nothing is cast then.
    pub fn ray_cast_batch(
        &self,
        mesh: &Mesh,
        rays: &[Ray],
    ) -> Result<Vec<Option<Hit>>, QueryError> {
        self.check(mesh)?;
        for (i, r) in rays.iter().enumerate() {
            r.check(i)?;
        }
        Ok(batch(rays, |r, stack| self.first_hit(r, stack)))
    }

    /// Every face `ray` meets, by increasing `t` (a face hit twice at one
    /// point, on a diagonal of its fan, is listed once).
    ///
    /// # Errors
    /// As [`ray_cast`](FaceTree::ray_cast).
    ///
    /// ```
    /// use meshloom::query::{FaceTree, Ray};
    /// let mesh = meshloom::shapes::icosphere(2);
    /// let tree = FaceTree::build(&mesh)?;
    /// let hits = tree.ray_hits(&mesh, Ray::new([0.01, 0.02, -5.0], [0.0, 0.0, 1.0]))?;
    /// assert_eq!(hits.len(), 2); // in and out
    /// assert!(hits[0].t < hits[1].t);
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn ray_hits(&self, mesh: &Mesh, ray: Ray) -> Result<Vec<Hit>, QueryError> {
        self.check(mesh)?;
        ray.check(0)?;
        let r = Prepared::new(&ray);
        let mut found: Vec<(f64, usize, f64, f64)> = Vec::new();
        self.walk_ray(&r, f64::INFINITY, &mut Vec::new(), |tri, t, u, v| {
            found.push((t, tri, u, v));
            None
        });
        found.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut hits: Vec<Hit> = Vec::with_capacity(found.len());
        for (t, tri, u, v) in found {
            let face = self.meta[tri].face;
            let twice = hits
                .iter()
                .rev()
                .take_while(|h| h.t >= t - SLACK * t.abs())
                .any(|h| h.face == face);
            if !twice {
                hits.push(self.hit(&r, tri, t, u, v));
            }
        }
        Ok(hits)
    }

    /// Whether `ray` meets any face with `t` in `[0, max_t]` (a shadow
    /// test: it stops at the first hit found, not the nearest).
    ///
    /// # Errors
    /// As [`ray_cast`](FaceTree::ray_cast); [`QueryError::InvalidBound`]
    /// for a NaN or negative `max_t`.
    ///
    /// ```
    /// use meshloom::query::{FaceTree, Ray};
    /// let mesh = meshloom::shapes::cube(); // [0, 1]³
    /// let tree = FaceTree::build(&mesh)?;
    /// let ray = Ray::new([0.5, 0.5, 3.5], [0.0, 0.0, -1.0]);
    /// assert!(tree.any_hit(&mesh, ray, f64::INFINITY)?);
    /// assert!(!tree.any_hit(&mesh, ray, 2.0)?); // the cube starts at t = 2.5
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn any_hit(&self, mesh: &Mesh, ray: Ray, max_t: f64) -> Result<bool, QueryError> {
        self.check(mesh)?;
        ray.check(0)?;
        check_bound("max_t", max_t)?;
        let r = Prepared::new(&ray);
        let mut any = false;
        self.walk_ray(&r, max_t, &mut Vec::new(), |_, t, _, _| {
            any = t <= max_t;
            any.then_some(-1.0)
        });
        Ok(any)
    }

    /// The nearest hit of a checked ray.
    fn first_hit(&self, ray: &Ray, stack: &mut Vec<u32>) -> Option<Hit> {
        let r = Prepared::new(ray);
        let mut best: Option<(f64, usize, f64, f64)> = None;
        self.walk_ray(&r, f64::INFINITY, stack, |tri, t, u, v| {
            if best.is_none_or(|b| t < b.0) {
                best = Some((t, tri, u, v));
            }
            best.map(|b| b.0)
        });
        best.map(|(t, tri, u, v)| self.hit(&r, tri, t, u, v))
    }

    fn hit(&self, r: &Prepared, tri: usize, t: f64, u: f64, v: f64) -> Hit {
        Hit {
            face: self.meta[tri].face,
            t,
            point: vec3::axpy(r.o, t, r.d),
            coords: self.coords(tri, [1.0 - u - v, u, v]),
        }
    }

    /// Visit every triangle whose box the ray meets within `[0, t_max]`
    /// and that it hits; `visit(tri, t, u, v)` returns a new `t_max` to
    /// shrink the search (a negative one stops it), or `None`.
    #[inline]
    fn walk_ray(
        &self,
        r: &Prepared,
        t_max: f64,
        stack: &mut Vec<u32>,
        mut visit: impl FnMut(usize, f64, f64, f64) -> Option<f64>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let mut t_max = t_max;
        stack.clear();
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if n.is_leaf() {
                let first = n.first as usize;
                for (i, p) in self.tris[first..first + n.count as usize]
                    .iter()
                    .enumerate()
                {
                    if let Some((t, u, v)) = hit_triangle(r.o, r.d, p) {
                        if t <= t_max {
                            if let Some(m) = visit(first + i, t, u, v) {
                                if m < 0.0 {
                                    return;
                                }
                                t_max = m;
                            }
                        }
                    }
                }
            } else {
                let (a, b) = n.children(node);
                let ta = r.enter(&self.nodes[a], t_max);
                let tb = r.enter(&self.nodes[b], t_max);
                if ta < f64::INFINITY {
                    if tb < f64::INFINITY {
                        let (near, far) = if ta <= tb { (a, b) } else { (b, a) };
                        stack.push(far as u32);
                        node = near;
                    } else {
                        node = a;
                    }
                    continue;
                }
                if tb < f64::INFINITY {
                    node = b;
                    continue;
                }
            }
            // Pop, skipping nodes the shrunk `t_max` rules out.
            loop {
                let Some(next) = stack.pop() else { return };
                let m = &self.nodes[next as usize];
                if r.enter(m, t_max) < f64::INFINITY {
                    node = next as usize;
                    break;
                }
            }
        }
    }

    /// Whether the root box meets the ray (an empty tree: no).
    #[cfg(test)]
    pub(super) fn root_met(&self, ray: &Ray) -> bool {
        self.nodes
            .first()
            .is_some_and(|n| Prepared::new(ray).enter(n, f64::INFINITY) < f64::INFINITY)
    }
}

/// `f` over `items` with a traversal stack per thread (rayon's with the
/// `parallel` feature, else one).
pub(super) fn batch<I: Sync, O: Send>(
    items: &[I],
    f: impl Fn(&I, &mut Vec<u32>) -> O + Sync,
) -> Vec<O> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items
            .par_iter()
            .map_init(Vec::new, |stack, item| f(item, stack))
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        let mut stack = Vec::new();
        items.iter().map(|item| f(item, &mut stack)).collect()
    }
}
