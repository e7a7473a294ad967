//! `triangulate` and `triangulate_all`: ear clipping with positions, a fan
//! without.

use super::ear_clip::{self, clip_ears, inside, QUEUED_FROM};
use super::refuse;
use crate::error::{Refusal, Result};
use crate::keys::FaceKey;
use crate::layout::{Fid, Hid};
use crate::mesh::{Mesh, Writer};
use crate::record::{journaled, Journaling, Recorded};
use crate::vec3::{dist2, newell};

/// One ear: corners `l, m, r` (indices into the face's corner list) and the
/// corner before `l` in what remains; the diagonal `r → l` is cut.
#[derive(Clone, Copy)]
struct Ear {
    pl: u32,
    l: u32,
    m: u32,
    r: u32,
}

impl Mesh {
    /// The ears that triangulate face `f`, in cutting order.
    fn plan_triangulate(
        &self,
        fk: FaceKey,
        sides: &mut Vec<Hid>,
        ears: &mut Vec<Ear>,
    ) -> Result<()> {
        self.plan_triangulate_loop(fk, sides, ears, false, true)
    }

    /// The triangles of face `f` as [`triangulate`](Mesh::triangulate)
    /// would cut it, as corner indices (0 = the face's first half-edge), for
    /// output that needs triangles and changes nothing (engine buffers,
    /// glTF, STL): no copy and no edit, and a diagonal that is an edge
    /// elsewhere in the mesh does not matter. Appends to `out`; `sides`
    /// receives the face's half-edges.
    pub(crate) fn triangles_of(&self, f: Fid, sides: &mut Vec<Hid>, out: &mut Vec<[u32; 3]>) {
        let mut ears = Vec::new();
        let planned = self.plan_triangulate_loop(self.fkey(f), sides, &mut ears, true, false);
        let n = sides.len() as u32;
        if planned.is_err() || n < 3 {
            // Only a stale key fails without the edge test: nothing to cut.
            return;
        }
        // Each ear cuts off its middle corner; the three never cut are
        // the last triangle, in loop order.
        let mut cut = vec![false; n as usize];
        for ear in &ears {
            out.push([ear.l, ear.m, ear.r]);
            cut[ear.m as usize] = true;
        }
        let mut rest = (0..n).filter(|&c| !cut[c as usize]);
        if let (Some(a), Some(b), Some(c)) = (rest.next(), rest.next(), rest.next()) {
            out.push([a, b, c]);
        }
    }

    /// As `plan_triangulate`; with `hole_ok` a hole is planned as if it were
    /// a face (for `fill_hole_triangulated`); with `avoid_edges` a diagonal
    /// that is an edge already is never cut (else it may be).
    fn plan_triangulate_loop(
        &self,
        fk: FaceKey,
        sides: &mut Vec<Hid>,
        ears: &mut Vec<Ear>,
        hole_ok: bool,
        avoid_edges: bool,
    ) -> Result<()> {
        const OP: &str = "triangulate";
        let f = self.check_face(fk)?;
        if self.is_hole(f) && !hole_ok {
            return Err(refuse(OP, fk, Refusal::Hole));
        }
        sides.clear();
        ears.clear();
        sides.extend(self.face_halfedges(f));
        let n = sides.len();
        if n <= 3 {
            return Ok(());
        }
        let corner = |i: u32| self.origin(sides[i as usize]);
        let joined =
            |i: u32, j: u32| avoid_edges && self.find_halfedge_raw(corner(i), corner(j)).is_some();
        let planned = match self.position_slots() {
            Some(p) => {
                let pts: Vec<[f64; 3]> = (0..n as u32).map(|i| p[corner(i).index()]).collect();
                if n == 4 {
                    quad_ear(&pts, joined).map(|ear| ears.push(ear)).is_some()
                } else {
                    clip_polygon(&pts, joined, ears)
                }
            }
            None => fan(n as u32, joined, ears),
        };
        if planned {
            Ok(())
        } else {
            Err(refuse(OP, fk, Refusal::EdgeExists))
        }
    }

    /// Whether [`triangulate`](Mesh::triangulate) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`triangulate`](Mesh::triangulate).
    pub fn check_triangulate(&self, f: FaceKey) -> Result<()> {
        self.plan_triangulate(f, &mut Vec::new(), &mut Vec::new())
    }

    /// Cut face `f` into triangles. With positions, by ear clipping in the
    /// plane of the face's (Newell) normal, so a non-convex polygon gives
    /// triangles that do not overlap; a quad is cut along the diagonal at its
    /// reflex corner, or the shorter one if convex. Without positions, a fan
    /// from the first corner whose diagonals are all new edges.
    ///
    /// ```text
    ///   v3 ------ v2        v3 ------ v2
    ///   |          |        |  .       |
    ///   |    f     |   =>   |     .    |
    ///   |          |        |        . |
    ///   v0 ------ v1        v0 ------ v1
    /// ```
    ///
    /// Returns the triangles, `f` first (a triangle is returned as it is).
    /// Attributes: the face splits over the triangles by area; each new
    /// corner copies the corner of its vertex in `f`. χ is unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Hole`];
    /// [`Refusal::EdgeExists`] when every way to cut needs a diagonal that
    /// is an edge already.
    ///
    /// # Complexity
    /// With positions, near O(n log n) for a face of degree n ≥ 64 (ears
    /// queued shortest cut first, each checked against the reflex corners
    /// under it in a grid; what that leaves, on degenerate faces, as
    /// below); O(n²) below 64 (O(n³) worst case for non-convex ones); plus
    /// the degree of the corners.
    ///
    /// # Examples
    /// ```
    /// use meshloom::Mesh;
    /// // An L-shaped hexagon: a fan from corner 0 would leave the polygon.
    /// let p = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 2.0, 0.0]];
    /// let mut mesh = Mesh::from_polygons(&p, &[[0u32, 1, 2, 3, 4, 5]])?;
    /// let f = mesh.faces().next().unwrap();
    /// let tris = mesh.triangulate(f)?;
    /// assert_eq!(tris.len(), 4);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn triangulate(&mut self, f: FaceKey) -> Result<Vec<FaceKey>> {
        journaled!(self.triangulate_with(f))
    }

    /// Triangulate every face of degree above three (see
    /// [`triangulate`](Mesh::triangulate)).
    ///
    /// Returns the faces that could not be cut (every way needed an existing
    /// edge); they are left as they were. χ is unchanged. When a column's
    /// [rule fails](crate::attr::Rule::FALLIBLE), no face is cut: all are
    /// returned.
    ///
    /// # Complexity
    /// O(Σ cost of `triangulate` per face).
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// assert!(mesh.triangulate_all().is_empty());
    /// assert_eq!(mesh.face_count(), 12);
    /// ```
    pub fn triangulate_all(&mut self) -> Vec<FaceKey> {
        if self.attrs.may_fail() {
            let all = self
                .faces()
                .filter(|&f| self.face_degree(f.id()) > 3)
                .collect();
            return self
                .transaction(|m| Ok(m.triangulate_all_with::<Recorded>()))
                .unwrap_or(all);
        }
        journaled!(unguarded self.triangulate_all_with())
    }
}

impl Mesh {
    /// Whether [`fill_hole_triangulated`](Mesh::fill_hole_triangulated)
    /// would succeed; changes nothing.
    ///
    /// # Errors
    /// As [`fill_hole_triangulated`](Mesh::fill_hole_triangulated).
    pub fn check_fill_hole_triangulated(&self, hole: FaceKey) -> Result<()> {
        self.check_fill_hole(hole)?;
        self.plan_triangulate_loop(hole, &mut Vec::new(), &mut Vec::new(), true, true)
    }

    /// [`fill_hole`](Mesh::fill_hole) and [`triangulate`](Mesh::triangulate)
    /// the new face, all or nothing: both are planned before either
    /// changes the mesh.
    ///
    /// Returns the triangles, the hole's key (now a face) first. χ grows by
    /// 1.
    ///
    /// # Errors
    /// As `fill_hole`, then as `triangulate`.
    ///
    /// # Complexity
    /// As `triangulate` on a face of the hole's degree.
    ///
    /// # Examples
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let hole = mesh.remove_face(f)?[0];
    /// let tris = mesh.fill_hole_triangulated(hole)?;
    /// assert_eq!((tris.len(), mesh.face_count()), (2, 7));
    /// assert!(mesh.is_closed());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn fill_hole_triangulated(&mut self, hole: FaceKey) -> Result<Vec<FaceKey>> {
        journaled!(self.fill_hole_triangulated_with(hole))
    }
}

/// The ear that cuts a quad with corners `pts`: the diagonal from the
/// reflex corner (if any) is the only valid one; for a convex quad take the
/// shorter. `None` when the diagonal it needs (and, for a convex quad, the
/// other one too) is `joined` already.
fn quad_ear(pts: &[[f64; 3]], joined: impl Fn(u32, u32) -> bool) -> Option<Ear> {
    let proj = projector(pts);
    let q = [proj(pts[0]), proj(pts[1]), proj(pts[2]), proj(pts[3])];
    let turn = |i: usize| ear_clip::turn(q[(i + 3) % 4], q[i], q[(i + 1) % 4]);
    let reflex_13 = turn(1) < 0.0 || turn(3) < 0.0;
    let reflex_02 = turn(0) < 0.0 || turn(2) < 0.0;
    let d02 = dist2(pts[0], pts[2]);
    let d13 = dist2(pts[1], pts[3]);
    let mut prefer_02 = if reflex_02 != reflex_13 {
        reflex_02
    } else {
        d02 <= d13
    };
    if prefer_02 && joined(0, 2) || !prefer_02 && joined(1, 3) {
        prefer_02 = !prefer_02;
    }
    if prefer_02 && joined(0, 2) || !prefer_02 && joined(1, 3) {
        return None;
    }
    // Ear at 1 cuts 2 -> 0; ear at 0 cuts 1 -> 3.
    Some(if prefer_02 {
        Ear {
            pl: 3,
            l: 0,
            m: 1,
            r: 2,
        }
    } else {
        Ear {
            pl: 2,
            l: 3,
            m: 0,
            r: 1,
        }
    })
}

/// The ears that cut the polygon with corners `pts` (more than four), by
/// ear clipping in its plane; `false` when every way left needs a diagonal
/// that is `joined` already.
fn clip_polygon(
    pts: &[[f64; 3]],
    joined: impl Fn(u32, u32) -> bool + Copy,
    ears: &mut Vec<Ear>,
) -> bool {
    let n = pts.len();
    let proj = projector(pts);
    let q: Vec<[f64; 2]> = pts.iter().map(|&x| proj(x)).collect();
    let rest: Vec<u32> = if n >= QUEUED_FROM {
        // Large faces and holes: the queued clipper, near O(n log n); the
        // scan takes what it leaves.
        let key: Vec<u32> = (0..n as u32).collect();
        let clipped = clip_ears(&q, &key, joined);
        ears.extend(
            clipped
                .ears
                .iter()
                .map(|&[pl, l, m, r]| Ear { pl, l, m, r }),
        );
        clipped.rest
    } else {
        (0..n as u32).collect()
    };
    scan_ears(&q, rest, joined, ears)
}

/// Cut the corners `rest` of the projected polygon `q` down to a triangle,
/// each time the first strict ear, else the first weak one, else the first
/// corner whose diagonal is new; `false` when no diagonal is.
fn scan_ears(
    q: &[[f64; 2]],
    mut rest: Vec<u32>,
    joined: impl Fn(u32, u32) -> bool,
    ears: &mut Vec<Ear>,
) -> bool {
    while rest.len() > 3 {
        let k = rest.len();
        let at = |i: usize| rest[i % k];
        let is_ear = |i: usize, strict: bool| {
            let (l, m, r) = (at(i + k - 1), at(i), at(i + 1));
            let turn = ear_clip::turn(q[l as usize], q[m as usize], q[r as usize]);
            if strict && turn <= 0.0 || !strict && turn < 0.0 {
                return false;
            }
            if joined(l, r) {
                return false;
            }
            !strict
                || !rest.iter().any(|&o| {
                    o != l
                        && o != m
                        && o != r
                        && inside(q[o as usize], q[l as usize], q[m as usize], q[r as usize])
                })
        };
        let found = (0..k)
            .find(|&i| is_ear(i, true))
            .or_else(|| (0..k).find(|&i| is_ear(i, false)))
            .or_else(|| (0..k).find(|&i| !joined(at(i + k - 1), at(i + 1))));
        let Some(i) = found else {
            return false;
        };
        ears.push(Ear {
            pl: at(i + k - 2),
            l: at(i + k - 1),
            m: at(i),
            r: at(i + 1),
        });
        rest.remove(i % k);
    }
    true
}

/// Without positions: a fan of the `n` corners from the first corner whose
/// diagonals are all new; `false` when there is none.
fn fan(n: u32, joined: impl Fn(u32, u32) -> bool, ears: &mut Vec<Ear>) -> bool {
    let Some(apex) = (0..n).find(|&k| (2..n - 1).all(|j| !joined(k, (k + j) % n))) else {
        return false;
    };
    let at = |j: u32| (apex + j) % n;
    for j in 1..n - 2 {
        ears.push(Ear {
            pl: at(n - 1),
            l: apex,
            m: at(j),
            r: at(j + 1),
        });
    }
    true
}

/// A map from 3D points to the plane of their Newell normal, keeping the
/// polygon's orientation counter-clockwise.
fn projector(pts: &[[f64; 3]]) -> impl Fn([f64; 3]) -> [f64; 2] + use<> {
    let n = newell(pts);
    let k = if n[0].abs() >= n[1].abs() && n[0].abs() >= n[2].abs() {
        0
    } else if n[1].abs() >= n[2].abs() {
        1
    } else {
        2
    };
    let (u, v) = ((k + 1) % 3, (k + 2) % 3);
    let flip = n[k] < 0.0;
    move |p: [f64; 3]| {
        if flip {
            [p[v], p[u]]
        } else {
            [p[u], p[v]]
        }
    }
}

impl Mesh {
    /// [`triangulate`](Mesh::triangulate)'s body, in journaling mode `J`.
    fn triangulate_with<J: Journaling>(&mut self, f: FaceKey) -> Result<Vec<FaceKey>> {
        let mut w = self.writer::<J>();
        let mut sides = Vec::new();
        let mut ears = Vec::new();
        w.plan_triangulate(f, &mut sides, &mut ears)?;
        let mut pieces = Vec::new();
        w.cut_ears(&mut sides, &ears, &mut pieces);
        w.end_op();
        Ok(pieces.into_iter().map(|g| w.fkey(g)).collect())
    }

    /// [`triangulate_all`](Mesh::triangulate_all)'s body, in journaling mode `J`.
    fn triangulate_all_with<J: Journaling>(&mut self) -> Vec<FaceKey> {
        let mut w = self.writer::<J>();
        let faces: Vec<FaceKey> = w.faces().filter(|&f| w.face_degree(f.id()) > 3).collect();
        let mut left = Vec::new();
        let (mut sides, mut ears, mut pieces) = (Vec::new(), Vec::new(), Vec::new());
        for f in faces {
            if w.plan_triangulate(f, &mut sides, &mut ears).is_err() {
                left.push(f);
                continue;
            }
            w.cut_ears(&mut sides, &ears, &mut pieces);
        }
        w.end_op();
        left
    }

    /// [`fill_hole_triangulated`](Mesh::fill_hole_triangulated)'s body, in journaling mode `J`.
    fn fill_hole_triangulated_with<J: Journaling>(
        &mut self,
        hole: FaceKey,
    ) -> Result<Vec<FaceKey>> {
        let mut w = self.writer::<J>();
        w.check_fill_hole(hole)?;
        let mut sides = Vec::new();
        let mut ears = Vec::new();
        w.plan_triangulate_loop(hole, &mut sides, &mut ears, true, true)?;
        // One edit: the fill does not end its own (one journal step).
        w.fill_hole_open(hole)?;
        let mut pieces = Vec::new();
        w.cut_ears(&mut sides, &ears, &mut pieces);
        w.end_op();
        Ok(pieces.into_iter().map(|g| w.fkey(g)).collect())
    }
}

impl<J: Journaling> Writer<'_, J> {
    /// Apply planned ears; `sides[i]` is the half-edge leaving corner `i` in
    /// what remains of the face. `pieces` receives the triangles.
    fn cut_ears(&mut self, sides: &mut [Hid], ears: &[Ear], pieces: &mut Vec<Fid>) {
        let f = self.face_of(sides[0]);
        pieces.clear();
        pieces.push(f);
        for ear in ears {
            let (pa, ha) = (sides[ear.m as usize], sides[ear.r as usize]);
            let (pb, hb) = (sides[ear.pl as usize], sides[ear.l as usize]);
            let (n0, g) = self.split_face_raw(pa, ha, pb, hb);
            sides[ear.l as usize] = n0.twin();
            pieces.push(g);
        }
        if ears.is_empty() {
            return;
        }
        self.split_face_values(f, pieces);
    }
}
