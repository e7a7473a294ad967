//! Rays against the tree: the first hit, every hit, any hit.

use super::error::{check_bound, QueryError};
use super::wide::{WideNode, LANES};
use super::{round_down, round_up, FaceCoords, FaceTree};
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
    /// Per axis, which of a box's corners the ray enters its slab at: 0
    /// the low one (the direction is not negative), 1 the high one.
    entry: [usize; 3],
    /// The origin in `f32`, rounded so that the entry parameters come out
    /// low (`near`) and the exit parameters high (`far`).
    o_near: [f32; 3],
    o_far: [f32; 3],
    /// `1 / d` in `f32`.
    inv32: [f32; 3],
    /// Whether the `f32` test is unsafe: a component of `d` is zero (then
    /// `0 · ∞ = NaN` can arise), or the ray is beyond `f32`'s range. Box
    /// tests take the careful path then.
    careful: bool,
}

/// The relative widening of `f32` box tests: a few units in the last place
/// of every rounding on the way (the origin's, the difference's, the
/// reciprocal's, the product's), far above [`SLACK`].
const SLACK32: f32 = 1.0 / (1 << 20) as f32;

impl Prepared {
    fn new(r: &Ray) -> Prepared {
        let (o, d) = (r.origin, r.direction);
        let inv = [1.0 / d[0], 1.0 / d[1], 1.0 / d[2]];
        let inv32 = inv.map(|x| x as f32);
        let o32 = o.map(bracket);
        let positive = d.map(|c| c > 0.0);
        Prepared {
            o,
            d,
            inv,
            entry: d.map(|c| usize::from(c.is_sign_negative())),
            o_near: std::array::from_fn(|k| if positive[k] { o32[k].1 } else { o32[k].0 }),
            o_far: std::array::from_fn(|k| if positive[k] { o32[k].0 } else { o32[k].1 }),
            inv32,
            careful: d.contains(&0.0)
                || !inv32.iter().all(|x| x.is_normal())
                || !o32.iter().all(|b| b.0.is_finite() && b.1.is_finite()),
        }
    }

    /// Which lanes of `n` the ray meets within `[0, t_max]` (a bit a lane;
    /// never an unused lane), widened by [`SLACK32`], and where it enters
    /// each (low by at most the widening). `t_max` is `f32`, rounded up.
    #[inline(always)]
    fn enter(&self, n: &WideNode, t_max: f32) -> ([f32; LANES], u32) {
        if self.careful {
            return self.enter_careful(n, t_max);
        }
        // In `f32`, four lanes at once. Each slab is entered at the near
        // corner (an unused lane's empty box gives `near = +∞`, `far =
        // −∞`); `inv32` is finite and no difference is NaN.
        let mut near = [0.0f32; LANES];
        let mut far = [t_max; LANES];
        for k in 0..3 {
            let lo = &n.bounds[self.entry[k]][k];
            let hi = &n.bounds[1 - self.entry[k]][k];
            for l in 0..LANES {
                near[l] = near[l].max((lo[l] - self.o_near[k]) * self.inv32[k]);
                far[l] = far[l].min((hi[l] - self.o_far[k]) * self.inv32[k]);
            }
        }
        let mut mask = 0;
        for l in 0..LANES {
            mask |= u32::from(near[l] <= far[l] + SLACK32 * (near[l] + far[l].abs())) << l;
        }
        (near, mask)
    }

    /// [`enter`](Prepared::enter) in `f64`, for a ray parallel to a
    /// coordinate plane (on an axis it does not move along, it is inside a
    /// slab or never) or beyond `f32`'s range.
    #[cold]
    fn enter_careful(&self, n: &WideNode, t_max: f32) -> ([f32; LANES], u32) {
        let mut mask = 0;
        let near = std::array::from_fn(|l| {
            if n.bounds[0][0][l] > n.bounds[1][0][l] {
                return f32::INFINITY; // an unused lane
            }
            let mut near = 0.0f64;
            let mut far = f64::from(t_max);
            for k in 0..3 {
                let (lo, hi) = (f64::from(n.bounds[0][k][l]), f64::from(n.bounds[1][k][l]));
                if self.d[k] == 0.0 {
                    if !(lo <= self.o[k] && self.o[k] <= hi) {
                        return f32::INFINITY;
                    }
                    continue;
                }
                let a = (lo - self.o[k]) * self.inv[k];
                let b = (hi - self.o[k]) * self.inv[k];
                near = near.max(a.min(b));
                far = far.min(a.max(b));
            }
            if near <= far + SLACK * far.abs().max(near.abs()) {
                mask |= 1 << l;
            }
            round_down(near)
        });
        (near, mask)
    }
}

/// The `f32` values next below and above `x` (both `x` when it is one;
/// an infinity beyond the range).
pub(super) fn bracket(x: f64) -> (f32, f32) {
    let y = x as f32;
    let up = |y: f32| {
        if y == 0.0 {
            f32::from_bits(1)
        } else if y > 0.0 {
            f32::from_bits(y.to_bits() + 1)
        } else {
            f32::from_bits(y.to_bits() - 1)
        }
    };
    match f64::from(y).partial_cmp(&x) {
        Some(std::cmp::Ordering::Less) if y.is_finite() => (y, up(y)),
        Some(std::cmp::Ordering::Greater) if y.is_finite() => (-up(-y), y),
        _ => (y, y),
    }
}

/// A child to visit: where the ray enters its box (low, as
/// [`Prepared::enter`] gives it), and a wide node (`count` 0) or `count`
/// triangles from `child`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Entry {
    t: f32,
    child: u32,
    count: u32,
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
    fn first_hit(&self, ray: &Ray, stack: &mut Vec<Entry>) -> Option<Hit> {
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
    /// shrink the search (a negative one stops it), or `None`. Children
    /// are visited nearest entry first; a child waiting on the stack is
    /// dropped when the shrunk `t_max` is below its entry.
    #[inline]
    fn walk_ray(
        &self,
        r: &Prepared,
        t_max: f64,
        stack: &mut Vec<Entry>,
        mut visit: impl FnMut(usize, f64, f64, f64) -> Option<f64>,
    ) {
        if self.wide.is_empty() {
            return;
        }
        let (mut t_max, mut t_max32) = (t_max, round_up(t_max));
        stack.clear();
        let mut at = Entry {
            t: 0.0,
            child: 0,
            count: 0,
        };
        loop {
            if at.count > 0 {
                let first = at.child as usize;
                for (i, p) in self.tris[first..first + at.count as usize]
                    .iter()
                    .enumerate()
                {
                    if let Some((t, u, v)) = hit_triangle(r.o, r.d, p) {
                        if t <= t_max {
                            if let Some(m) = visit(first + i, t, u, v) {
                                if m < 0.0 {
                                    return;
                                }
                                (t_max, t_max32) = (m, round_up(m));
                            }
                        }
                    }
                }
            } else if let Some(next) = descend(&self.wide[at.child as usize], r, t_max32, stack) {
                at = next;
                continue;
            }
            loop {
                let Some(next) = stack.pop() else { return };
                if next.t <= t_max32 + SLACK32 * (next.t + t_max32) {
                    at = next;
                    break;
                }
            }
        }
    }

    /// Whether the root box meets the ray (an empty tree: no).
    #[cfg(test)]
    pub(super) fn root_met(&self, ray: &Ray) -> bool {
        self.wide
            .first()
            .is_some_and(|n| Prepared::new(ray).enter(n, f32::INFINITY).1 != 0)
    }
}

/// The children of `n` the ray meets, nearest first: the nearest is
/// returned, the others pushed (farthest first, so the next nearest is
/// popped next). The lanes are sorted in a loop over all of them, which
/// branches more predictably than a loop over the met lanes' bits.
#[inline(always)]
fn descend(n: &WideNode, r: &Prepared, t_max: f32, stack: &mut Vec<Entry>) -> Option<Entry> {
    let (t, mask) = r.enter(n, t_max);
    let entry = |l: usize| Entry {
        t: t[l],
        child: n.child[l],
        count: n.count[l],
    };
    let mut met = [0usize; LANES];
    let mut len = 0;
    for l in 0..LANES {
        if mask & (1 << l) != 0 {
            let mut j = len;
            while j > 0 && t[met[j - 1]] > t[l] {
                met[j] = met[j - 1];
                j -= 1;
            }
            met[j] = l;
            len += 1;
        }
    }
    for &l in met[1..len.max(1)].iter().rev() {
        stack.push(entry(l));
    }
    (len > 0).then(|| entry(met[0]))
}

/// `f` over `items` with a traversal stack per thread (rayon's with the
/// `parallel` feature, else one).
pub(super) fn batch<I: Sync, O: Send, S: Default + Send>(
    items: &[I],
    f: impl Fn(&I, &mut S) -> O + Sync,
) -> Vec<O> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items
            .par_iter()
            .map_init(S::default, |stack, item| f(item, stack))
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        let mut stack = S::default();
        items.iter().map(|item| f(item, &mut stack)).collect()
    }
}
