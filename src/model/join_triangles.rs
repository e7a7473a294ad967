//! `join_triangles`: pair adjacent triangles into quads (Blender's "Tris
//! to Quads"), best pairs first.
//!
//! Every interior edge between two selected triangles is a candidate
//! unless a [`Delimit`] keeps it, the triangles' normals differ by more
//! than the face angle, a corner of the quad they would make is further
//! from 90° than the shape angle, or that quad is concave or degenerate.
//! Candidates are ranked by BMesh's error (`bmo_join_triangles`: the
//! bending between the quad's two triangulations, the corners' distance
//! from right angles, and the difference between the two triangulations'
//! areas, each scaled to about [0, 1]) and taken greedily, lowest error
//! first, each triangle joining at most once; ties go to the lower edge
//! slot. The counts then follow BMesh's (Blender 3.4, which ranks the same
//! way; later versions also reprioritise around existing quads).
//!
//! BMesh's `cmp_materials`, `cmp_uvs` (or `cmp_vcols`: a corner colour
//! column) and `cmp_sharp` are [`Delimit`]'s `material`, `seams` and
//! `sharp`; its `cmp_seam` (an edge flag) is a boolean edge column given as
//! `sharp`.
//!
//! The commit removes every chosen diagonal in one pass of the low-level
//! writer: one undo step.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::{Delimit, Delimiters};
use crate::error::{Error, Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::FaceKey;
use crate::layout::{Eid, Fid, Hid};
use crate::mesh::Mesh;
use crate::ops::refuse;
use crate::vec3::{self, V3};

const OP: &str = "join_triangles";

/// Options of [`Mesh::join_triangles`]; the default is Blender's (40° for
/// both angles, no delimiter but the boundary, every face).
#[derive(Clone, Debug, PartialEq)]
pub struct JoinTrianglesOptions {
    /// The largest angle (radians) between the two triangles' normals; π
    /// or more: no limit.
    pub face_angle: f64,
    /// The largest distance (radians) of any corner of the quad from a
    /// right angle; π or more: no limit (the quad must still be convex).
    pub shape_angle: f64,
    /// The edges never removed: a material border, a UV seam, a sharp edge
    /// (the boundary always).
    pub delimit: Delimit,
    /// The faces to join among (triangles only count; others are left
    /// alone); `None`: every face.
    pub faces: Option<Vec<FaceKey>>,
}

impl Default for JoinTrianglesOptions {
    fn default() -> JoinTrianglesOptions {
        JoinTrianglesOptions {
            face_angle: 40f64.to_radians(),
            shape_angle: 40f64.to_radians(),
            delimit: Delimit::default(),
            faces: None,
        }
    }
}

/// What [`Mesh::join_triangles`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Joined {
    /// The quads, each keeping the key of its first triangle (the face of
    /// the removed diagonal's first half-edge), best pair first.
    pub quads: Vec<FaceKey>,
    /// How many selected triangles stayed triangles.
    pub triangles_left: usize,
}

/// The angle limits, `None` where the option sets none.
struct Limits {
    cos_face: Option<f64>,
    shape: Option<f64>,
}

/// A checked join: the diagonals to remove, in the order chosen.
struct Plan {
    diagonals: Vec<Eid>,
    triangles_left: usize,
}

impl Mesh {
    /// Whether [`join_triangles`](Mesh::join_triangles) would succeed;
    /// changes nothing.
    ///
    /// # Errors
    /// As [`join_triangles`](Mesh::join_triangles).
    pub fn check_join_triangles(&self, options: &JoinTrianglesOptions) -> Result<()> {
        self.plan_join_triangles(options).map(|_| ())
    }

    /// Join pairs of adjacent triangles into quads (see the
    /// [module](crate::model) table): the diagonal between them is removed
    /// where the triangles bend by at most `face_angle`, the quad's corners
    /// are within `shape_angle` of right angles, the quad is convex, and no
    /// delimiter keeps the edge; the best pairs (BMesh's error) go first,
    /// each triangle joining once. An empty selection joins nothing.
    ///
    /// Attributes: the quad is its first triangle (same key), its face
    /// values the `merge` of both triangles', survivor first, equal
    /// weights (a conserved quantity sums; a material id, delimited or
    /// equal, stays); its corners keep their values (the diagonal's two
    /// corners go with it); edges and vertices keep theirs. One undo step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Hole`] for a
    /// hole among `faces`; [`Refusal::Parameter`] for an angle that is NaN
    /// or negative; [`Error::AttributeMissing`] for a delimiting column the
    /// mesh lacks; [`Error::NoPositions`].
    ///
    /// # Complexity
    /// O(s log s) for s selected triangles (the candidates are sorted).
    ///
    /// ```
    /// use meshloom::model::JoinTrianglesOptions;
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mut mesh = grid(3, 3, GridFaces::Triangles);
    /// let joined = mesh.join_triangles(&JoinTrianglesOptions::default())?;
    /// assert_eq!((joined.quads.len(), mesh.face_count()), (9, 9));
    /// assert!(mesh.faces().all(|f| mesh.face(f).unwrap().degree() == 4));
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn join_triangles(&mut self, options: &JoinTrianglesOptions) -> Result<Joined> {
        let plan = self.plan_join_triangles(options)?;
        journaled!(self.commit_join_triangles(&plan))
    }

    /// Check the options and selection; rank the candidate diagonals and
    /// choose them greedily.
    fn plan_join_triangles(&self, o: &JoinTrianglesOptions) -> Result<Plan> {
        let limits = limits(o)?;
        let delimiters = Delimiters::new(self, &o.delimit)?;
        let pos = self.position_slots().ok_or(Error::NoPositions)?;
        // Per face slot: 0 not selected, 1 a selected triangle, 2 joined
        // (zeroed memory is mapped lazily: the cost follows the selection).
        let mut mark = vec![0u8; self.slot_counts()[3]];
        let triangles = self.selected_triangles(o.faces.as_deref(), &mut mark)?;
        let mut ranked: Vec<(f64, Eid)> = Vec::new();
        for &f in &triangles {
            for h in self.face_halfedges(f) {
                let e = h.edge();
                let t = h.twin();
                if e.halfedges()[0] != h || mark[self.face_of(t).index()] != 1 {
                    continue;
                }
                if delimiters.delimits(e) {
                    continue;
                }
                if let Some(error) = self.pair_error(h, pos, &limits) {
                    ranked.push((error, e));
                }
            }
        }
        ranked.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut diagonals = Vec::new();
        for (_, e) in ranked {
            let [h, t] = e.halfedges();
            let (fa, fb) = (self.face_of(h).index(), self.face_of(t).index());
            if mark[fa] == 1 && mark[fb] == 1 {
                mark[fa] = 2;
                mark[fb] = 2;
                diagonals.push(e);
            }
        }
        Ok(Plan {
            triangles_left: triangles.len() - 2 * diagonals.len(),
            diagonals,
        })
    }

    /// The selected triangles (every triangle for `None`), marked 1 in
    /// `mark` by face slot, without repeats.
    fn selected_triangles(&self, faces: Option<&[FaceKey]>, mark: &mut [u8]) -> Result<Vec<Fid>> {
        let is_triangle = |f: Fid| {
            let h = self.face_halfedge(f);
            self.next(self.next(self.next(h))) == h
        };
        let mut out = Vec::new();
        match faces {
            None => {
                for f in self.fids() {
                    if !self.is_hole(f) && is_triangle(f) {
                        mark[f.index()] = 1;
                        out.push(f);
                    }
                }
            }
            Some(faces) => {
                for &fk in faces {
                    let f = self.check_face(fk)?;
                    if self.is_hole(f) {
                        return Err(refuse(OP, fk, Refusal::Hole));
                    }
                    if mark[f.index()] == 0 && is_triangle(f) {
                        mark[f.index()] = 1;
                        out.push(f);
                    }
                }
            }
        }
        Ok(out)
    }

    /// The error of joining the triangles on both sides of `h` (both
    /// triangles, distinct faces), or `None` where the pair may not join.
    fn pair_error(&self, h: Hid, pos: &[V3], limits: &Limits) -> Option<f64> {
        let t = h.twin();
        let (a, b) = (self.origin(h), self.origin(t));
        let c = self.dest(self.next(h));
        let d = self.dest(self.next(t));
        if c == d || c == a || c == b || d == a || d == b || a == b {
            return None;
        }
        // The quad in the faces' winding: b → c → a → d.
        let q = [
            pos[b.index()],
            pos[c.index()],
            pos[a.index()],
            pos[d.index()],
        ];
        quad_error(q, limits)
    }

    /// Remove the plan's diagonals (the body, in journaling mode `J`).
    fn commit_join_triangles<J: Journaling>(&mut self, plan: &Plan) -> Result<Joined> {
        let mut w = self.writer::<J>();
        let mut quads = Vec::with_capacity(plan.diagonals.len());
        for &e in &plan.diagonals {
            let [h, t] = e.halfedges();
            let (fa, fb) = (w.face_of(h), w.face_of(t));
            w.attrs
                .face
                .merge(fa.index(), &[(fa.index(), 0.5), (fb.index(), 0.5)]);
            w.remove_edge_raw(e, fa);
            quads.push(fa);
        }
        w.end_op();
        Ok(Joined {
            quads: quads.into_iter().map(|f| self.fkey(f)).collect(),
            triangles_left: plan.triangles_left,
        })
    }
}

/// The options' angle limits, checked.
fn limits(o: &JoinTrianglesOptions) -> Result<Limits> {
    let check = |a: f64, what: &'static str| {
        if a.is_nan() || a < 0.0 {
            Err(refuse(OP, FaceKey::new(0, 0), Refusal::Parameter(what)))
        } else {
            Ok((a < PI).then_some(a))
        }
    };
    Ok(Limits {
        cos_face: check(o.face_angle, "face_angle must be a number of radians ≥ 0")?.map(f64::cos),
        shape: check(o.shape_angle, "shape_angle must be a number of radians ≥ 0")?,
    })
}

/// The unnormalized normal of triangle `(p, q, r)`.
#[inline]
fn tri_normal(p: V3, q: V3, r: V3) -> V3 {
    vec3::cross(vec3::sub(q, p), vec3::sub(r, p))
}

/// The error of quad `q` made of triangles `(q0, q1, q2)` and `(q0, q2,
/// q3)`, or `None` when a triangle is degenerate, the triangles bend by
/// more than the face angle, a corner is further from 90° than the shape
/// angle, or the quad is not strictly convex. The error is BMesh's: the
/// bending of both triangulations, the corners' distances from 90° (both
/// over 2π) and one less the ratio of the triangulations' areas.
fn quad_error(q: [V3; 4], limits: &Limits) -> Option<f64> {
    let na = tri_normal(q[0], q[1], q[2]);
    let nb = tri_normal(q[0], q[2], q[3]);
    let (ua, ub) = (vec3::normalize(na)?, vec3::normalize(nb)?);
    if limits.cos_face.is_some_and(|c| vec3::dot(ua, ub) < c) {
        return None;
    }
    let n = vec3::normalize(vec3::add(ua, ub))?;
    let mut off_square = 0.0;
    for i in 0..4 {
        let (p, c, x) = (q[(i + 3) % 4], q[i], q[(i + 1) % 4]);
        let (u, v) = (vec3::sub(c, p), vec3::sub(x, c));
        // Strictly convex: every corner turns the same way about `n`.
        let turn = vec3::dot(vec3::cross(u, v), n);
        if turn.is_nan() || turn <= 1e-12 * vec3::norm(u) * vec3::norm(v) {
            return None;
        }
        let off = (vec3::angle(vec3::sub(p, c), v) - FRAC_PI_2).abs();
        if limits.shape.is_some_and(|s| off > s) {
            return None;
        }
        off_square += off;
    }
    let nc = tri_normal(q[1], q[2], q[3]);
    let nd = tri_normal(q[3], q[0], q[1]);
    let bend = (vec3::angle(na, nb) + vec3::angle(nc, nd)) / TAU;
    let (area_a, area_b) = (
        vec3::norm(na) + vec3::norm(nb),
        vec3::norm(nc) + vec3::norm(nd),
    );
    let uneven = 1.0 - area_a.min(area_b) / area_a.max(area_b);
    Some(bend + off_square / TAU + uneven)
}

#[cfg(test)]
mod tests;
