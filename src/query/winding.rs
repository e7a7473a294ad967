//! The generalized winding number (Jacobson et al. 2013): the solid angle
//! the surface subtends at a point, over 4π. 1 inside a closed outward
//! surface, 0 outside, a fraction near holes, so it tells inside from
//! outside on imperfect meshes too.
//!
//! Exactly it sums every triangle's signed solid angle (Van Oosterom and
//! Strackee's formula). Fast, it follows Barill et al. 2018: a node whose
//! triangles are far from the point (its distance from their area-weighted
//! centre above `accuracy` times their radius about it) counts as one
//! dipole, its total area vector at that centre; near nodes are opened,
//! leaves summed exactly. The far-field error falls with the accuracy
//! factor; the default 2 is libigl's.

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
    /// Far nodes as dipoles (Barill et al. 2018): a node counts as one
    /// when the point is farther than `accuracy` times the node's radius
    /// from its centre (`accuracy` ≥ 1; larger is slower and closer).
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

/// The far-field data of a leaf's triangles (radius left 0).
pub(super) fn leaf_dipole(tris: &[[V3; 3]]) -> Dipole {
    let mut area = [0.0; 3];
    let mut weight = 0.0;
    let mut centre = [0.0; 3];
    let mut mean = [0.0; 3];
    for t in tris {
        let n = vec3::scale(
            vec3::cross(vec3::sub(t[1], t[0]), vec3::sub(t[2], t[0])),
            0.5,
        );
        let a = vec3::norm(n);
        let c = vec3::scale(vec3::add(t[0], vec3::add(t[1], t[2])), 1.0 / 3.0);
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
    Dipole {
        area,
        centre,
        weight,
        radius: 0.0,
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
    Dipole {
        area: vec3::add(a.area, b.area),
        centre,
        weight,
        radius: 0.0,
    }
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
    /// [`WindingMode::Exact`]: O(n); approximate: about O(log n).
    ///
    /// ```
    /// use meshloom::query::{FaceTree, WindingMode};
    /// let mesh = meshloom::shapes::icosphere(3);
    /// let tree = FaceTree::build(&mesh)?;
    /// let inside = tree.winding_number(&mesh, [0.2, 0.1, 0.0], WindingMode::Exact)?;
    /// assert!((inside - 1.0).abs() < 1e-9);
    /// let outside = tree.winding_number(&mesh, [3.0, 0.0, 0.0], WindingMode::default())?;
    /// assert!(outside.abs() < 2e-2); // the far field (order 1): 0.0136 here
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
        if self.nodes.is_empty() {
            return 0.0;
        }
        let mut sum = 0.0;
        stack.clear();
        stack.push(0);
        while let Some(i) = stack.pop() {
            let i = i as usize;
            let d = &self.dipoles[i];
            let r = vec3::sub(d.centre, q);
            let dist2 = vec3::norm2(r);
            if dist2 > beta * beta * d.radius * d.radius {
                sum += vec3::dot(r, d.area) / (dist2 * dist2.sqrt());
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
