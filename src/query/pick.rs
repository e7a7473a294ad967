//! Snapping and picking of vertices and edges: the edges within a radius of
//! a point, the nearest edge, and the vertex or edge under an editor's
//! cursor.
//!
//! A cursor with a pixel radius is a [`Cone`] around the ray through the
//! pixel (a cylinder for an orthographic view). The element picked is the
//! one nearest the cone's axis *as the screen shows it*: its
//! [`offset`](Pick::offset) is its distance from the axis over the cone's
//! width at its depth, which is proportional to its distance in pixels from
//! the cursor, in perspective and orthographic views alike. An edge counts
//! by its point of least offset. With [`Occlusion::Visible`], elements
//! hidden behind the surface (the line of sight to them meets a face first)
//! are passed over, as an editor's solid view does; [`Occlusion::XRay`]
//! sees through.
//!
//! Edges are found through the faces' fan triangles, whose sides are the
//! faces' edges and, in polygons, diagonals; a diagonal is not an edge and
//! is never answered.

use super::error::{check_bound, check_point, QueryError};
use super::ray::Ray;
use super::FaceTree;
use crate::keys::{EdgeKey, VertexKey};
use crate::mesh::Mesh;
use crate::vec3::{self, V3};

/// Widening of box bounds, relative (see the ray's).
const SLACK: f64 = 1e-12;

/// Hits on the line of sight this close to the element (relative to the
/// sight line's length) do not hide it: they are the element's own faces.
const SIGHT_SLACK: f64 = 1e-6;

/// A cone around a ray: the points `x` in front of the ray's origin
/// (`t(x) ≥ 0`, `t(x)` the distance of `x` along the axis) whose distance
/// from the axis is at most `radius + spread · t(x)`. A perspective view's
/// cursor is a cone with `radius` 0; an orthographic view's is a cylinder
/// with `spread` 0.
///
/// For a cursor of `r` pixels in a perspective view of vertical field of
/// view `fov_y` over `height` pixels, the cone's half-angle is
/// `atan(r · tan(fov_y / 2) / (height / 2))`:
///
/// ```
/// use meshloom::query::{Cone, Ray};
/// let (r, fov_y, height) = (8.0_f64, 50f64.to_radians(), 1080.0);
/// let half_angle = (r * (fov_y / 2.0).tan() / (height / 2.0)).atan();
/// let cone = Cone::perspective(Ray::new([0.0, 0.0, 5.0], [0.0, 0.0, -1.0]), half_angle);
/// assert!((cone.spread - 0.006908).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    /// The axis: the ray through the cursor.
    pub ray: Ray,
    /// The width at the ray's origin.
    pub radius: f64,
    /// The width's growth per unit of distance along the axis (the tangent
    /// of the half-angle).
    pub spread: f64,
}

impl Cone {
    /// A perspective view's cursor: the cone of half-angle `half_angle`
    /// (radians, below π/2) around `ray`.
    pub fn perspective(ray: Ray, half_angle: f64) -> Cone {
        Cone {
            ray,
            radius: 0.0,
            spread: half_angle.tan(),
        }
    }

    /// An orthographic view's cursor: the cylinder of `radius` around `ray`.
    pub fn orthographic(ray: Ray, radius: f64) -> Cone {
        Cone {
            ray,
            radius,
            spread: 0.0,
        }
    }

    /// The cone prepared for tests, or the error naming what is wrong.
    fn axis(&self) -> Result<Axis, QueryError> {
        self.ray.check(0)?;
        check_finite_bound("cone radius", self.radius)?;
        check_finite_bound("cone spread", self.spread)?;
        if self.radius == 0.0 && self.spread == 0.0 {
            return Err(QueryError::InvalidBound {
                what: "cone radius and spread (both zero)",
                value: 0.0,
            });
        }
        let len = vec3::norm(self.ray.direction);
        Ok(Axis {
            o: self.ray.origin,
            d: vec3::scale(self.ray.direction, 1.0 / len),
            len,
            radius: self.radius,
            spread: self.spread,
        })
    }
}

/// `value` as a finite bound, or the error naming it.
fn check_finite_bound(what: &'static str, value: f64) -> Result<(), QueryError> {
    check_bound(what, value)?;
    if value.is_finite() {
        Ok(())
    } else {
        Err(QueryError::InvalidBound { what, value })
    }
}

/// Whether elements behind the surface can be picked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Occlusion {
    /// Only elements the surface does not hide (an editor's solid view).
    Visible,
    /// Elements behind the surface too (an editor's X-ray view).
    XRay,
}

/// A picked vertex or edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick<K> {
    /// The element (on a tie in offset, the nearer; then either).
    pub key: K,
    /// The vertex's position, or the edge's point of least offset.
    pub point: [f64; 3],
    /// The point's depth: its projection on the ray is
    /// `origin + t · direction`.
    pub t: f64,
    /// The point's distance from the axis over the cone's width there, 0
    /// to 1 (proportional to its distance in pixels from the cursor).
    pub offset: f64,
}

/// The nearest edge to a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearestEdge {
    /// The edge (on a tie, either).
    pub edge: EdgeKey,
    /// Its point nearest to the query point.
    pub point: [f64; 3],
    /// The distance between the two.
    pub distance: f64,
}

/// A cone prepared for tests: a unit axis.
#[derive(Clone, Copy, Debug)]
struct Axis {
    o: V3,
    /// Unit length.
    d: V3,
    /// The ray direction's length (to give `t` in its units).
    len: f64,
    radius: f64,
    spread: f64,
}

impl Axis {
    /// `(offset, depth)` of `x` (depth along the unit axis), or `None`
    /// behind the origin or at the apex.
    #[inline]
    fn offset(&self, x: V3) -> Option<(f64, f64)> {
        let w = vec3::sub(x, self.o);
        let t = vec3::dot(w, self.d);
        let width = self.radius + self.spread * t;
        if t < 0.0 || width <= 0.0 {
            return None;
        }
        let perp = vec3::norm(vec3::axpy(w, -t, self.d));
        Some((perp / width, t))
    }

    /// A lower bound of the offset of the points in the box `lo`–`hi`
    /// (through its bounding sphere), +∞ when none is in front.
    #[inline]
    fn box_key(&self, lo: V3, hi: V3) -> f64 {
        let c = vec3::scale(vec3::add(lo, hi), 0.5);
        let r = 0.5 * vec3::norm(vec3::sub(hi, lo)) * (1.0 + SLACK);
        let w = vec3::sub(c, self.o);
        let t = vec3::dot(w, self.d);
        if t + r < 0.0 {
            return f64::INFINITY;
        }
        let gap = vec3::norm(vec3::axpy(w, -t, self.d)) - r;
        if gap <= 0.0 {
            return 0.0;
        }
        let width = self.radius + self.spread * (t + r);
        if width <= 0.0 {
            return f64::INFINITY;
        }
        gap / width * (1.0 - 4.0 * SLACK)
    }

    /// The point of least offset on the segment `a`–`b`: `(offset, depth,
    /// point)`, or `None` when no point is in front. The offset is
    /// quasi-convex along the segment (its sub-level sets are cones), so a
    /// golden-section search over the part in front finds it.
    fn segment(&self, a: V3, b: V3) -> Option<(f64, f64, V3)> {
        let (ta, tb) = (
            vec3::dot(vec3::sub(a, self.o), self.d),
            vec3::dot(vec3::sub(b, self.o), self.d),
        );
        // The part in front (t ≥ 0), as a parameter range on a → b.
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        if ta < 0.0 && tb < 0.0 {
            return None;
        } else if ta < 0.0 {
            lo = ta / (ta - tb);
        } else if tb < 0.0 {
            hi = ta / (ta - tb);
        }
        let ab = vec3::sub(b, a);
        let at = |s: f64| {
            let x = vec3::axpy(a, s, ab);
            self.offset(x)
                .map_or((f64::INFINITY, 0.0, x), |(o, t)| (o, t, x))
        };
        let mut best = least(at(lo), at(hi));
        const G: f64 = 0.381_966_011_250_105_1; // 2 − φ
        let (mut x1, mut x2) = (lo + G * (hi - lo), hi - G * (hi - lo));
        let (mut f1, mut f2) = (at(x1), at(x2));
        for _ in 0..80 {
            if f1.0 <= f2.0 {
                hi = x2;
                (x2, f2) = (x1, f1);
                x1 = lo + G * (hi - lo);
                f1 = at(x1);
            } else {
                lo = x1;
                (x1, f1) = (x2, f2);
                x2 = hi - G * (hi - lo);
                f2 = at(x2);
            }
        }
        best = least(best, least(f1, f2));
        best.0.is_finite().then_some(best)
    }

    /// Where the line of sight to `x` (depth `t`) starts: on the plane
    /// through the origin across the axis, on the line from the cone's
    /// apex (for a cylinder, along the axis).
    fn eye(&self, x: V3, t: f64) -> V3 {
        if self.spread == 0.0 {
            return vec3::axpy(x, -t, self.d);
        }
        let back = self.radius / self.spread; // the apex's distance behind
        let apex = vec3::axpy(self.o, -back, self.d);
        vec3::axpy(apex, back / (t + back), vec3::sub(x, apex))
    }
}

/// The lower in offset, then in depth.
fn least(a: (f64, f64, V3), b: (f64, f64, V3)) -> (f64, f64, V3) {
    if (b.0, b.1) < (a.0, a.1) {
        b
    } else {
        a
    }
}

/// The point of segment `a`–`b` nearest to `q`.
#[inline]
fn segment_closest(q: V3, a: V3, b: V3) -> V3 {
    let d = vec3::sub(b, a);
    let len2 = vec3::norm2(d);
    let s = if len2 > 0.0 {
        (vec3::dot(vec3::sub(q, a), d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    vec3::axpy(a, s, d)
}

/// The sides of a triangle as corner index pairs.
const SIDES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];

/// The edge joining `u` and `v`, if there is one (a polygon's diagonal is
/// not an edge).
fn edge_between(mesh: &Mesh, u: VertexKey, v: VertexKey) -> Option<EdgeKey> {
    let h = mesh.find_halfedge(u, v).ok()??;
    Some(mesh.halfedge(h).ok()?.edge().key())
}

/// A candidate pick: offset, depth, key, point.
type Candidate<K> = (f64, f64, K, V3);

impl FaceTree {
    /// The edges with a point within `radius` of `point` (inclusive), in
    /// key order, each once. Only edges of faces count.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`]; [`QueryError::NonFinitePoint`];
    /// [`QueryError::InvalidBound`] for a NaN or negative radius.
    ///
    /// ```
    /// use meshloom::query::FaceTree;
    /// let mesh = meshloom::shapes::cube(); // [0, 1]³, quads
    /// let tree = FaceTree::build(&mesh)?;
    /// assert_eq!(tree.edges_within(&mesh, [1.1, 1.1, 0.5], 0.2)?.len(), 1);
    /// assert_eq!(tree.edges_within(&mesh, [1.1, 1.1, 1.1], 0.2)?.len(), 3); // a corner
    /// assert!(tree.edges_within(&mesh, [0.5, 0.5, 1.1], 0.2)?.is_empty()); // a quad's middle
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn edges_within(
        &self,
        mesh: &Mesh,
        point: [f64; 3],
        radius: f64,
    ) -> Result<Vec<EdgeKey>, QueryError> {
        self.check(mesh)?;
        check_point(0, point)?;
        check_bound("radius", radius)?;
        let r2 = radius * radius;
        let mut pairs = Vec::new();
        self.walk_point(point, r2, &mut Vec::new(), |tree, tri| {
            let (p, v) = (&tree.tris[tri], &tree.meta[tri].v);
            for (i, j) in SIDES {
                if vec3::dist2(point, segment_closest(point, p[i], p[j])) <= r2 {
                    pairs.push(if v[i] < v[j] {
                        (v[i], v[j])
                    } else {
                        (v[j], v[i])
                    });
                }
            }
            r2
        });
        pairs.sort_unstable();
        pairs.dedup();
        let mut out: Vec<EdgeKey> = pairs
            .into_iter()
            .filter_map(|(u, v)| edge_between(mesh, u, v))
            .collect();
        out.sort_unstable();
        out.dedup();
        Ok(out)
    }

    /// The edge nearest to `point`, or `None` for a mesh without faces.
    /// Only edges of faces count.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`]; [`QueryError::NonFinitePoint`].
    ///
    /// ```
    /// use meshloom::query::FaceTree;
    /// let mesh = meshloom::shapes::cube(); // [0, 1]³, quads
    /// let tree = FaceTree::build(&mesh)?;
    /// let e = tree.nearest_edge(&mesh, [0.5, 0.45, 1.0])?.unwrap(); // nearer a side than the diagonal
    /// assert!((e.distance - 0.45).abs() < 1e-12);
    /// assert_eq!(e.point, [0.5, 0.0, 1.0]);
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn nearest_edge(
        &self,
        mesh: &Mesh,
        point: [f64; 3],
    ) -> Result<Option<NearestEdge>, QueryError> {
        self.check(mesh)?;
        check_point(0, point)?;
        let mut best: Option<(f64, EdgeKey, V3)> = None;
        self.walk_point(point, f64::INFINITY, &mut Vec::new(), |tree, tri| {
            let (p, v) = (&tree.tris[tri], &tree.meta[tri].v);
            for (i, j) in SIDES {
                let x = segment_closest(point, p[i], p[j]);
                let d2 = vec3::dist2(point, x);
                if best.is_none_or(|b| d2 < b.0) {
                    if let Some(e) = edge_between(mesh, v[i], v[j]) {
                        best = Some((d2, e, x));
                    }
                }
            }
            best.map_or(f64::INFINITY, |b| b.0)
        });
        Ok(best.map(|(d2, edge, point)| NearestEdge {
            edge,
            point,
            distance: d2.sqrt(),
        }))
    }

    /// The vertex under a cursor: of the faces' corners inside `cone`, the
    /// one of least [`offset`](Pick::offset) (then the nearer), passing
    /// over hidden ones with [`Occlusion::Visible`]; `None` if there is
    /// none.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`]; [`QueryError::NonFiniteRay`] or
    /// [`QueryError::ZeroDirection`] for the cone's ray;
    /// [`QueryError::InvalidBound`] for a negative or non-finite radius or
    /// spread, or both zero.
    ///
    /// ```
    /// use meshloom::query::{Cone, FaceTree, Occlusion, Ray};
    /// let mesh = meshloom::shapes::cube(); // [0, 1]³
    /// let tree = FaceTree::build(&mesh)?;
    /// // Looking down at the top face, the cursor near its corner (1, 1, 1).
    /// let ray = Ray::new([0.9, 0.95, 5.0], [0.0, 0.0, -1.0]);
    /// let pick = tree.pick_vertex(&mesh, Cone::perspective(ray, 0.05), Occlusion::Visible)?.unwrap();
    /// assert_eq!(mesh.position(pick.key).unwrap(), [1.0, 1.0, 1.0]);
    /// // Seen through the top face, the bottom corner (1, 1, 0) is nearer the axis.
    /// let xray = tree.pick_vertex(&mesh, Cone::perspective(ray, 0.05), Occlusion::XRay)?.unwrap();
    /// assert_eq!(mesh.position(xray.key).unwrap(), [1.0, 1.0, 0.0]);
    /// assert!(xray.offset < pick.offset);
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn pick_vertex(
        &self,
        mesh: &Mesh,
        cone: Cone,
        occlusion: Occlusion,
    ) -> Result<Option<Pick<VertexKey>>, QueryError> {
        self.check(mesh)?;
        let axis = cone.axis()?;
        let candidates = |tree: &FaceTree, tri: usize, out: &mut Vec<Candidate<VertexKey>>| {
            for (p, v) in tree.tris[tri].iter().zip(tree.meta[tri].v) {
                if let Some((o, t)) = axis.offset(*p) {
                    out.push((o, t, v, *p));
                }
            }
        };
        self.pick(mesh, &axis, occlusion, candidates)
    }

    /// The edge under a cursor: of the edges meeting `cone`, the one whose
    /// point of least [`offset`](Pick::offset) is least (then the nearer),
    /// passing over hidden ones (judged at that point) with
    /// [`Occlusion::Visible`]; `None` if there is none.
    ///
    /// # Errors
    /// As [`pick_vertex`](FaceTree::pick_vertex).
    ///
    /// ```
    /// use meshloom::query::{Cone, FaceTree, Occlusion, Ray};
    /// let mesh = meshloom::shapes::cube(); // [0, 1]³
    /// let tree = FaceTree::build(&mesh)?;
    /// let ray = Ray::new([0.5, 0.97, 5.0], [0.0, 0.0, -1.0]);
    /// let pick = tree.pick_edge(&mesh, Cone::perspective(ray, 0.02), Occlusion::Visible)?.unwrap();
    /// let [x, y, z] = pick.point; // on the top face's edge at y = 1, not the hidden one below
    /// assert!((x - 0.5).abs() < 1e-9 && y == 1.0 && z == 1.0);
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn pick_edge(
        &self,
        mesh: &Mesh,
        cone: Cone,
        occlusion: Occlusion,
    ) -> Result<Option<Pick<EdgeKey>>, QueryError> {
        self.check(mesh)?;
        let axis = cone.axis()?;
        let candidates = |tree: &FaceTree, tri: usize, out: &mut Vec<Candidate<_>>| {
            let (p, v) = (&tree.tris[tri], &tree.meta[tri].v);
            for (i, j) in SIDES {
                if axis.box_key(vec3::min(p[i], p[j]), vec3::max(p[i], p[j])) > 1.0 {
                    continue;
                }
                if let Some((o, t, x)) = axis.segment(p[i], p[j]) {
                    let pair = if v[i] < v[j] {
                        (v[i], v[j])
                    } else {
                        (v[j], v[i])
                    };
                    out.push((o, t, pair, x));
                }
            }
        };
        Ok(
            self.pick_where(mesh, &axis, occlusion, candidates, |&(u, v)| {
                edge_between(mesh, u, v)
            }),
        )
    }

    /// [`pick_where`](FaceTree::pick_where) for candidates that are
    /// elements already.
    fn pick<K: Copy + Ord>(
        &self,
        mesh: &Mesh,
        axis: &Axis,
        occlusion: Occlusion,
        candidates: impl Fn(&FaceTree, usize, &mut Vec<Candidate<K>>),
    ) -> Result<Option<Pick<K>>, QueryError> {
        Ok(self.pick_where(mesh, axis, occlusion, candidates, |k| Some(*k)))
    }

    /// The candidate of least offset (then depth) with offset at most 1
    /// that names an element (`element`) and, with
    /// [`Occlusion::Visible`], is not hidden. Without occlusion the search
    /// narrows the cone to the best offset so far; with it, every
    /// candidate in the cone is gathered, sorted and tried in order.
    fn pick_where<C: Copy + Ord, K>(
        &self,
        mesh: &Mesh,
        axis: &Axis,
        occlusion: Occlusion,
        candidates: impl Fn(&FaceTree, usize, &mut Vec<Candidate<C>>),
        element: impl Fn(&C) -> Option<K>,
    ) -> Option<Pick<K>> {
        let mut found: Vec<Candidate<C>> = Vec::new();
        let mut best: Option<(f64, f64, K, V3)> = None;
        let narrow = occlusion == Occlusion::XRay;
        self.walk_nearest(
            |lo, hi| axis.box_key(lo, hi),
            1.0,
            &mut Vec::new(),
            |tree, tri| {
                let start = found.len();
                candidates(tree, tri, &mut found);
                if !narrow {
                    return 1.0;
                }
                for &(o, t, c, x) in &found[start..] {
                    if o <= 1.0 && best.as_ref().is_none_or(|b| (o, t) < (b.0, b.1)) {
                        if let Some(k) = element(&c) {
                            best = Some((o, t, k, x));
                        }
                    }
                }
                found.truncate(start);
                best.as_ref().map_or(1.0, |b| b.0)
            },
        );
        if !narrow {
            best = self.first_visible(mesh, axis, found, element);
        }
        best.map(|(offset, t, key, point)| Pick {
            key,
            point,
            t: t / axis.len,
            offset,
        })
    }

    /// Of `found`, the first by offset, depth and candidate that is within
    /// the cone, names an element and is not hidden.
    fn first_visible<C: Copy + Ord, K>(
        &self,
        mesh: &Mesh,
        axis: &Axis,
        mut found: Vec<Candidate<C>>,
        element: impl Fn(&C) -> Option<K>,
    ) -> Option<(f64, f64, K, V3)> {
        found.retain(|c| c.0 <= 1.0);
        found.sort_unstable_by(|a, b| {
            a.0.total_cmp(&b.0)
                .then(a.1.total_cmp(&b.1))
                .then(a.2.cmp(&b.2))
        });
        let mut seen = std::collections::BTreeSet::new();
        for (o, t, c, x) in found {
            if !seen.insert(c) {
                continue;
            }
            let Some(k) = element(&c) else { continue };
            if !self.hidden(mesh, axis, x, t) {
                return Some((o, t, k, x));
            }
        }
        None
    }

    /// Whether the surface meets the line of sight to `x` (depth `t`)
    /// before it reaches `x`.
    fn hidden(&self, mesh: &Mesh, axis: &Axis, x: V3, t: f64) -> bool {
        let eye = axis.eye(x, t);
        let d = vec3::sub(x, eye);
        if vec3::norm2(d) == 0.0 {
            return false;
        }
        self.any_hit(mesh, Ray::new(eye, d), 1.0 - SIGHT_SLACK)
            .unwrap_or(false)
    }
}

/// The point of least offset from the cone's axis on segment `a`–`b`, its
/// offset and depth (`t` in the ray's direction lengths), or `None` when no
/// point is in front: for tests and for checking the tree.
#[doc(hidden)]
pub fn segment_in_cone(cone: &Cone, a: [f64; 3], b: [f64; 3]) -> Option<([f64; 3], f64, f64)> {
    let axis = cone.axis().ok()?;
    axis.segment(a, b).map(|(o, t, x)| (x, o, t / axis.len))
}

/// A point's offset from the cone's axis and depth, or `None` behind it:
/// for tests and for checking the tree.
#[doc(hidden)]
pub fn point_in_cone(cone: &Cone, x: [f64; 3]) -> Option<(f64, f64)> {
    let axis = cone.axis().ok()?;
    axis.offset(x).map(|(o, t)| (o, t / axis.len))
}
