//! The generalized winding number (Jacobson et al. 2013): the solid angle
//! the surface subtends at a point, over 4π. 1 inside a closed outward
//! surface, 0 outside, a fraction near holes, so it tells inside from
//! outside on imperfect meshes too.
//!
//! Exactly it sums every triangle's signed solid angle (Van Oosterom and
//! Strackee's formula). Fast, it follows Barill et al. 2018: a node whose
//! triangles are far from the point (its distance from their area-weighted
//! centre above `accuracy` times their radius about it) counts as the
//! first three terms of the Taylor series of its triangles' field about
//! that centre (libigl's default order 2): the dipole (the total area
//! vector `∫ n dA`), the moment `∫ (x - c) ⊗ n dA` and the tensor
//! `∫ (x - c) ⊗ (x - c) ⊗ n dA`, contracted with the kernel's derivatives.
//! A triangle's moment about its centroid is zero, its tensor holds its own
//! second moment (a twelfth of its corners' offsets' outer products); a
//! parent's terms are its children's moved to its centre. Only the
//! symmetric parts count, so a node keeps 6 + 10 numbers, in `f32`. Near
//! nodes are opened, leaves summed exactly. The far-field error falls with
//! the accuracy factor; the default 2 is libigl's.

use super::error::{check_point, QueryError};
use super::ray::batch;
use super::{Dipole, FaceTree};
use crate::mesh::Mesh;
use crate::vec3::{self, V3};

/// How [`FaceTree::winding_number`] sums.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WindingMode {
    /// Every triangle's solid angle: O(n) a point.
    Exact,
    /// Far nodes by their field's first three Taylor terms (Barill et al.
    /// 2018): a node counts as them when the point is farther than
    /// `accuracy` times the node's radius from its centre (`accuracy` ≥ 1;
    /// larger is slower and closer).
    Approximate {
        /// The far-field factor β.
        accuracy: f64,
    },
}

impl Default for WindingMode {
    /// `Approximate { accuracy: 2.0 }`.
    fn default() -> WindingMode {
        WindingMode::Approximate { accuracy: 2.0 }
    }
}

/// The signed solid angle of triangle `p` seen from `q` (positive when
/// `q` is on the side its counter-clockwise normal points away from).
#[inline(always)]
fn solid_angle(q: V3, p: &[V3; 3]) -> f64 {
    let a = vec3::sub(p[0], q);
    let b = vec3::sub(p[1], q);
    let c = vec3::sub(p[2], q);
    let (la, lb, lc) = (vec3::norm(a), vec3::norm(b), vec3::norm(c));
    let num = vec3::dot(a, vec3::cross(b, c));
    let den = la * lb * lc + vec3::dot(a, b) * lc + vec3::dot(b, c) * la + vec3::dot(c, a) * lb;
    2.0 * num.atan2(den)
}

/// A symmetric matrix in [`Dipole::moment`]'s order: `xx, yy, zz, xy, yz,
/// zx`.
type Sym = [f64; 6];

/// The symmetric part of `d ⊗ a`.
#[inline]
fn sym_outer(d: V3, a: V3) -> Sym {
    [
        d[0] * a[0],
        d[1] * a[1],
        d[2] * a[2],
        0.5 * (d[0] * a[1] + d[1] * a[0]),
        0.5 * (d[1] * a[2] + d[2] * a[1]),
        0.5 * (d[2] * a[0] + d[0] * a[2]),
    ]
}

/// The symmetric part of `q ⊗ n` for a symmetric `q` (the mean of `q_ab n_c`
/// over the three places of `n`'s index), in [`Dipole::tensor`]'s order.
#[inline]
fn sym_tensor(q: &Sym, n: V3) -> [f64; 10] {
    let [xx, yy, zz, xy, yz, zx] = *q;
    let third = 1.0 / 3.0;
    [
        xx * n[0],
        yy * n[1],
        zz * n[2],
        third * (xx * n[1] + 2.0 * xy * n[0]),
        third * (xx * n[2] + 2.0 * zx * n[0]),
        third * (yy * n[0] + 2.0 * xy * n[1]),
        third * (yy * n[2] + 2.0 * yz * n[1]),
        third * (zz * n[0] + 2.0 * zx * n[2]),
        third * (zz * n[1] + 2.0 * yz * n[2]),
        third * (xy * n[2] + zx * n[1] + yz * n[0]),
    ]
}

/// `sum += add`.
fn accumulate<const N: usize>(sum: &mut [f64; N], add: [f64; N]) {
    for (s, a) in sum.iter_mut().zip(add) {
        *s += a;
    }
}

/// Stored (`f32`) far-field terms widened back to `f64`.
fn widen<const N: usize>(m: [f32; N]) -> [f64; N] {
    m.map(f64::from)
}

/// A triangle's area vector (half its corners' cross product) and centroid.
#[inline]
fn area_and_centroid(t: &[V3; 3]) -> (V3, V3) {
    let n = vec3::scale(
        vec3::cross(vec3::sub(t[1], t[0]), vec3::sub(t[2], t[0])),
        0.5,
    );
    let c = vec3::scale(vec3::add(t[0], vec3::add(t[1], t[2])), 1.0 / 3.0);
    (n, c)
}

/// `∫ (x - p) ⊗ (x - p) dA / area` over triangle `t` with centroid `c`:
/// `(c - p) ⊗ (c - p)` plus the triangle's own second moment about its
/// centroid, a twelfth of its corners' offsets' outer products.
fn second_moment(t: &[V3; 3], c: V3, p: V3) -> Sym {
    let mut q = sym_outer(vec3::sub(c, p), vec3::sub(c, p));
    for v in t {
        accumulate(
            &mut q,
            sym_outer(vec3::sub(*v, c), vec3::sub(*v, c)).map(|x| x / 12.0),
        );
    }
    q
}

/// The far-field data of a leaf's triangles (radius left 0).
pub(super) fn leaf_dipole(tris: &[[V3; 3]]) -> Dipole {
    let mut area = [0.0; 3];
    let mut weight = 0.0;
    let mut centre = [0.0; 3];
    let mut mean = [0.0; 3];
    for t in tris {
        let (n, c) = area_and_centroid(t);
        let a = vec3::norm(n);
        area = vec3::add(area, n);
        vec3::add_scaled(&mut centre, c, a);
        vec3::add_scaled(&mut mean, c, 1.0);
        weight += a;
    }
    let centre = if weight > 0.0 {
        vec3::scale(centre, 1.0 / weight)
    } else {
        vec3::scale(mean, 1.0 / tris.len().max(1) as f64)
    };
    let (mut moment, mut tensor) = ([0.0; 6], [0.0; 10]);
    for t in tris {
        let (n, c) = area_and_centroid(t);
        accumulate(&mut moment, sym_outer(vec3::sub(c, centre), n));
        accumulate(&mut tensor, sym_tensor(&second_moment(t, c, centre), n));
    }
    Dipole {
        area,
        centre,
        weight,
        radius: 0.0,
        moment: moment.map(|x| x as f32),
        tensor: tensor.map(|x| x as f32),
    }
}

/// The far-field data of two children together (radius left 0).
pub(super) fn merge_dipoles(a: Dipole, b: Dipole) -> Dipole {
    let weight = a.weight + b.weight;
    let centre = if weight > 0.0 {
        let mut c = vec3::scale(a.centre, a.weight);
        vec3::add_scaled(&mut c, b.centre, b.weight);
        vec3::scale(c, 1.0 / weight)
    } else {
        vec3::scale(vec3::add(a.centre, b.centre), 0.5)
    };
    // Each child's terms moved from its centre to the parent's, `e` away:
    // x - centre = (x - child) + e.
    let (mut moment, mut tensor) = ([0.0; 6], [0.0; 10]);
    for d in [a, b] {
        let e = vec3::sub(d.centre, centre);
        let m = widen(d.moment);
        accumulate(&mut tensor, widen(d.tensor));
        accumulate(&mut tensor, sym_tensor(&m, e).map(|x| 2.0 * x));
        accumulate(&mut tensor, sym_tensor(&sym_outer(e, e), d.area));
        accumulate(&mut moment, m);
        accumulate(&mut moment, sym_outer(e, d.area));
    }
    Dipole {
        area: vec3::add(a.area, b.area),
        centre,
        weight,
        radius: 0.0,
        moment: moment.map(|x| x as f32),
        tensor: tensor.map(|x| x as f32),
    }
}

/// Four π times the far field of `d` at the point `r = d.centre - q` away
/// (`dist2 = |r|²`), to `TERMS` terms of its Taylor series: the dipole
/// `r·a / |r|³`, the moment's `tr M / |r|³ - 3 rᵀMr / |r|⁵`, the tensor's
/// `7.5 T(r, r, r) / |r|⁷ - 4.5 r·tr T / |r|⁵`.
#[inline(always)]
fn far_field<const TERMS: u8>(d: &Dipole, r: V3, dist2: f64) -> f64 {
    let inv2 = 1.0 / dist2;
    let inv3 = inv2 * inv2.sqrt();
    let mut sum = vec3::dot(r, d.area) * inv3;
    if TERMS < 2 {
        return sum;
    }
    let m = widen(d.moment);
    let trace = m[0] + m[1] + m[2];
    let rmr = r[0] * r[0] * m[0]
        + r[1] * r[1] * m[1]
        + r[2] * r[2] * m[2]
        + 2.0 * (r[0] * r[1] * m[3] + r[1] * r[2] * m[4] + r[2] * r[0] * m[5]);
    sum += (trace - 3.0 * rmr * inv2) * inv3;
    if TERMS < 3 {
        return sum;
    }
    let t = widen(d.tensor);
    let [x, y, z] = r;
    let cubic = x * x * (x * t[0] + 3.0 * (y * t[3] + z * t[4]))
        + y * y * (y * t[1] + 3.0 * (x * t[5] + z * t[6]))
        + z * z * (z * t[2] + 3.0 * (x * t[7] + y * t[8]))
        + 6.0 * x * y * z * t[9];
    let traced = [t[0] + t[5] + t[7], t[3] + t[1] + t[8], t[4] + t[6] + t[2]];
    sum + (7.5 * cubic * inv2 - 4.5 * vec3::dot(r, traced)) * inv3 * inv2
}

/// `d` with the radius about its centre that holds the box `lo..hi`.
pub(super) fn with_radius(mut d: Dipole, lo: V3, hi: V3) -> Dipole {
    let mut r2: f64 = 0.0;
    for k in 0..8 {
        let corner = [
            if k & 1 == 0 { lo[0] } else { hi[0] },
            if k & 2 == 0 { lo[1] } else { hi[1] },
            if k & 4 == 0 { lo[2] } else { hi[2] },
        ];
        r2 = r2.max(vec3::dist2(corner, d.centre));
    }
    d.radius = r2.sqrt();
    d
}

impl FaceTree {
    /// The generalized winding number of the surface at `point`: about 1
    /// inside a closed surface whose faces wind counter-clockwise seen from
    /// outside, 0 outside, 0.5 on the plane of an open half-sphere's cut.
    ///
    /// # Errors
    /// [`QueryError::StaleTree`]; [`QueryError::NonFinitePoint`].
    ///
    /// # Complexity
    /// [`WindingMode::Exact`]: O(n); approximate: about O(log n), after the
    /// tree's first approximate query made its far-field data in O(n)
    /// (refits and updates keep it).
    ///
    /// ```
    /// use meshloom::query::{FaceTree, WindingMode};
    /// let mesh = meshloom::shapes::icosphere(3);
    /// let tree = FaceTree::build(&mesh)?;
    /// let inside = tree.winding_number(&mesh, [0.2, 0.1, 0.0], WindingMode::Exact)?;
    /// assert!((inside - 1.0).abs() < 1e-9);
    /// let outside = tree.winding_number(&mesh, [3.0, 0.0, 0.0], WindingMode::default())?;
    /// assert!(outside.abs() < 2e-3); // the far field (three terms): 0.0013 here
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn winding_number(
        &self,
        mesh: &Mesh,
        point: [f64; 3],
        mode: WindingMode,
    ) -> Result<f64, QueryError> {
        self.check(mesh)?;
        check_point(0, point)?;
        Ok(self.winding(point, mode, &mut Vec::new()))
    }

    /// [`winding_number`](FaceTree::winding_number) for many points (on
    /// rayon's threads with the `parallel` feature).
    ///
    /// # Errors
    /// As [`winding_number`](FaceTree::winding_number), naming the first
    /// bad point by index.
    pub fn winding_numbers(
        &self,
        mesh: &Mesh,
        points: &[[f64; 3]],
        mode: WindingMode,
    ) -> Result<Vec<f64>, QueryError> {
        self.check(mesh)?;
        for (i, p) in points.iter().enumerate() {
            check_point(i, *p)?;
        }
        Ok(batch(points, |p, stack| self.winding(*p, mode, stack)))
    }

    /// Whether `point` is inside: its winding number (approximate, default
    /// accuracy) above 0.5.
    ///
    /// # Errors
    /// As [`winding_number`](FaceTree::winding_number).
    pub fn contains(&self, mesh: &Mesh, point: [f64; 3]) -> Result<bool, QueryError> {
        Ok(self.winding_number(mesh, point, WindingMode::default())? > 0.5)
    }

    /// [`contains`](FaceTree::contains) for many points.
    ///
    /// # Errors
    /// As [`winding_numbers`](FaceTree::winding_numbers).
    pub fn contains_batch(
        &self,
        mesh: &Mesh,
        points: &[[f64; 3]],
    ) -> Result<Vec<bool>, QueryError> {
        let w = self.winding_numbers(mesh, points, WindingMode::default())?;
        Ok(w.into_iter().map(|w| w > 0.5).collect())
    }

    /// The winding number at a checked point.
    fn winding(&self, q: V3, mode: WindingMode, stack: &mut Vec<u32>) -> f64 {
        let beta = match mode {
            WindingMode::Exact => {
                let mut sum = 0.0;
                self.for_each_leaf(|_, range| {
                    sum += self.tris[range]
                        .iter()
                        .map(|t| solid_angle(q, t))
                        .sum::<f64>();
                });
                return sum / (4.0 * std::f64::consts::PI);
            }
            WindingMode::Approximate { accuracy } => accuracy.max(1.0),
        };
        self.approximate::<3>(q, beta, stack)
    }

    /// The far-field sum with factor `beta`, far nodes to `TERMS` terms.
    fn approximate<const TERMS: u8>(&self, q: V3, beta: f64, stack: &mut Vec<u32>) -> f64 {
        if self.nodes.is_empty() {
            return 0.0;
        }
        let dipoles = self.far_field();
        let mut sum = 0.0;
        stack.clear();
        stack.push(0);
        while let Some(i) = stack.pop() {
            let i = i as usize;
            let d = &dipoles[i];
            let r = vec3::sub(d.centre, q);
            let dist2 = vec3::norm2(r);
            if dist2 > beta * beta * d.radius * d.radius {
                sum += far_field::<TERMS>(d, r, dist2);
                continue;
            }
            let n = &self.nodes[i];
            if n.is_leaf() {
                let first = n.first as usize;
                for t in &self.tris[first..first + n.count as usize] {
                    sum += solid_angle(q, t);
                }
            } else {
                let (a, b) = n.children(i);
                stack.push(b as u32);
                stack.push(a as u32);
            }
        }
        sum / (4.0 * std::f64::consts::PI)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    /// A small deterministic generator of points in a box.
    struct Lcg(u64);

    impl Lcg {
        fn unit(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }

        fn in_box(&mut self, half: f64) -> V3 {
            [0, 1, 2].map(|_| (2.0 * self.unit() - 1.0) * half)
        }
    }

    /// The largest errors against the exact sum of the far field to one,
    /// two and three terms, at `count` points within `half` of the origin,
    /// with the default factor.
    fn max_errors(mesh: &Mesh, count: usize, half: f64, seed: u64) -> [f64; 3] {
        let tree = FaceTree::build(mesh).unwrap();
        let mut rng = Lcg(seed);
        let mut stack = Vec::new();
        let mut max = [0.0_f64; 3];
        for _ in 0..count {
            let q = rng.in_box(half);
            let exact = tree.winding(q, WindingMode::Exact, &mut stack);
            let terms = [
                tree.approximate::<1>(q, 2.0, &mut stack),
                tree.approximate::<2>(q, 2.0, &mut stack),
                tree.winding(q, WindingMode::default(), &mut stack),
            ];
            for (m, w) in max.iter_mut().zip(terms) {
                *m = m.max((w - exact).abs());
            }
        }
        max
    }

    #[test]
    fn three_terms_bring_the_far_field_closer_than_one_or_two() {
        let torus = shapes::torus(40, 20, 1.0, 0.3).unwrap();
        for (mesh, half) in [(shapes::icosphere(3), 2.0), (torus, 2.0)] {
            let [one, two, three] = max_errors(&mesh, 400, half, 5);
            assert!(three < 0.5 * one, "three terms {three}, one {one}");
            assert!(three < two, "three terms {three}, two {two}");
        }
    }

    #[test]
    fn a_far_point_of_a_sphere_is_near_zero_with_three_terms() {
        let mesh = shapes::icosphere(3);
        let tree = FaceTree::build(&mesh).unwrap();
        let q = [3.0, 0.0, 0.0];
        let mut stack = Vec::new();
        let one = tree.approximate::<1>(q, 2.0, &mut stack);
        let three = tree.winding(q, WindingMode::default(), &mut stack);
        // One term misses this bound (0.0136 against 0.0013); the exact value is 0.
        assert!(one.abs() > 1e-2, "one term {one}");
        assert!(three.abs() < 2e-3, "three terms {three}");
    }

    /// The moment and tensor of `tree`'s root against those of all its
    /// triangles as one leaf.
    fn check_root(tree: &FaceTree) -> Dipole {
        let root = tree.far_field()[0];
        let whole = leaf_dipole(&tree.tris);
        let (m, w) = (widen(root.moment), widen(whole.moment));
        for k in 0..6 {
            assert!((m[k] - w[k]).abs() < 1e-5, "{k}: {} vs {}", m[k], w[k]);
        }
        let (t, w) = (widen(root.tensor), widen(whole.tensor));
        for k in 0..10 {
            assert!((t[k] - w[k]).abs() < 1e-5, "{k}: {} vs {}", t[k], w[k]);
        }
        root
    }

    #[test]
    fn the_root_moment_of_a_closed_mesh_is_its_volume_times_the_identity() {
        let mesh = shapes::icosphere(3);
        let tree = FaceTree::build(&mesh).unwrap();
        let volume: f64 = tree
            .tris
            .iter()
            .map(|t| vec3::dot(t[0], vec3::cross(t[1], t[2])) / 6.0)
            .sum();
        let m = widen(check_root(&tree).moment);
        for (k, m) in m.iter().enumerate() {
            let want = if k < 3 { volume } else { 0.0 };
            assert!((m - want).abs() < 1e-5, "{k}: {m} vs {want}");
        }
    }

    #[test]
    fn the_terms_moved_up_the_tree_are_those_of_all_the_triangles() {
        let mut mesh = shapes::icosphere(3);
        let low: Vec<_> = mesh
            .faces()
            .filter(|&f| {
                mesh.face(f)
                    .unwrap()
                    .vertices()
                    .any(|v| mesh.position(v).unwrap()[2] < -0.2)
            })
            .collect();
        for f in low {
            mesh.remove_face(f).unwrap();
        }
        let tree = FaceTree::build(&mesh).unwrap();
        let t = widen(check_root(&tree).tensor);
        assert!(t.iter().any(|x| x.abs() > 1e-2), "{t:?}");
    }
}
