//! `extrude_faces`: push a region of faces out, with side walls along its
//! boundary (or each face on its own).

use std::collections::HashMap;

use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::{FaceKey, VertexKey};
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::Mesh;
use crate::ops::refuse;
use crate::vec3::{self, V3};

const OP: &str = "extrude_faces";

/// Options of [`Mesh::extrude_faces`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExtrudeOptions {
    /// How far to move the extruded faces (any finite value; 0 makes the
    /// walls with no height, to move the top afterwards).
    pub distance: f64,
    /// The direction to move along (normalized here); `None`: each
    /// connected region's area-weighted mean normal (each face's own
    /// normal with `individual`).
    pub direction: Option<[f64; 3]>,
    /// Extrude each face on its own, with walls on all its sides, instead
    /// of connected faces together.
    pub individual: bool,
}

impl Default for ExtrudeOptions {
    fn default() -> ExtrudeOptions {
        ExtrudeOptions {
            distance: 0.0,
            direction: None,
            individual: false,
        }
    }
}

/// What [`Mesh::extrude_faces`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Extrusion {
    /// The extruded faces (the selection, keeping their keys), now on top.
    pub top: Vec<FaceKey>,
    /// The side walls, one quad per boundary edge of the region.
    pub sides: Vec<FaceKey>,
    /// The new vertices (copies of the region's boundary vertices, on top).
    pub vertices: Vec<VertexKey>,
}

/// A half-edge of a top face that is not on the boundary.
pub(super) const NOT_BOUNDARY: u32 = u32::MAX;

/// What [`Mesh::commit_extrude`] made, by slot: per fan its copy and its
/// rail (the vertical edge, half-edge 0 going up), per boundary half-edge
/// its cap (half-edge 0 in the top face) and its wall.
pub(super) struct Made {
    pub(super) tops: Vec<Vid>,
    pub(super) rails: Vec<Eid>,
    pub(super) caps: Vec<Eid>,
    pub(super) sides: Vec<Fid>,
}

/// The selected faces around a boundary vertex between two boundary
/// half-edges: `first` leaves `v` along the boundary, `inner` (turning
/// from it) leave it between two selected faces (they move to the copy),
/// and `incoming` comes in along the boundary.
pub(super) struct Fan {
    pub(super) v: Vid,
    pub(super) first: Hid,
    pub(super) inner: Vec<Hid>,
    pub(super) incoming: Hid,
    pub(super) region: usize,
}

/// A checked extrusion.
pub(super) struct Plan {
    pub(super) faces: Vec<Fid>,
    /// Each face's region.
    pub(super) face_region: Vec<usize>,
    /// The region's boundary: half-edges of selected faces whose twin is
    /// not in a selected face.
    pub(super) boundary: Vec<Hid>,
    /// Per boundary half-edge: its face, its original next (its face's
    /// corner at its head), and the fans at its origin and its head.
    pub(super) face: Vec<Fid>,
    pub(super) next: Vec<Hid>,
    pub(super) fan_at: Vec<(usize, usize)>,
    pub(super) fans: Vec<Fan>,
    /// The selected faces that touch the boundary, with their half-edges.
    /// Each half-edge with its place in `boundary` (`NOT_BOUNDARY` if it
    /// is not there).
    pub(super) cycles: Vec<(Fid, Vec<(Hid, u32)>)>,
    /// Vertices inside the region (moved, not copied), with their region.
    pub(super) inner: Vec<(Vid, usize)>,
    /// Per region, the offset to move by.
    pub(super) offsets: Vec<V3>,
}

impl Mesh {
    /// Whether [`extrude_faces`](Mesh::extrude_faces) would succeed;
    /// changes nothing.
    ///
    /// # Errors
    /// As [`extrude_faces`](Mesh::extrude_faces).
    pub fn check_extrude_faces(&self, faces: &[FaceKey], options: &ExtrudeOptions) -> Result<()> {
        if options.individual {
            self.selected_faces(faces)?;
            for &f in faces {
                self.plan_extrude_region(&[f], options)?;
            }
            Ok(())
        } else {
            self.plan_extrude_region(faces, options).map(|_| ())
        }
    }

    /// Extrude `faces`: connected faces (sharing an edge) move together as
    /// a region, with a wall of quads along its boundary, and the edges
    /// between them stay shared; with `individual`, each face moves on its
    /// own with a wall on every side. A region's boundary vertices are
    /// copied (one copy per fan of selected faces around it), its inner
    /// vertices move. The faces keep their keys and end on top.
    ///
    /// Attributes (BMesh's and Blender's Extrude Mesh node's rules): a
    /// copied vertex interpolates its original (weight 1), then moves; a
    /// top edge copies the edge it came from, a wall's vertical edge
    /// interpolates the two boundary edges at its foot; a wall quad
    /// interpolates the face it stands on the edge of (a material id
    /// follows), and its corners copy that face's corners at the same
    /// vertices, bottom and top alike (a UV strip of no height, so a UV
    /// island stays connected to the wall). One undo step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Hole`] for a
    /// hole in `faces`; [`Refusal::Empty`] for no faces;
    /// [`Refusal::Parameter`] for a non-finite distance or direction or a
    /// zero direction; [`Refusal::ZeroArea`] when moving along a region's
    /// mean normal that is zero (a closed surface selected whole).
    ///
    /// # Complexity
    /// O(selected faces' corners + degrees of their vertices), whatever the
    /// mesh's size.
    ///
    /// ```
    /// use meshloom::model::ExtrudeOptions;
    /// let mut cube = meshloom::shapes::cube();
    /// let top = cube.faces().next().unwrap();
    /// let made = cube.extrude_faces(&[top], &ExtrudeOptions { distance: 1.0, ..Default::default() })?;
    /// assert_eq!(made.sides.len(), 4);
    /// assert_eq!((cube.vertex_count(), cube.edge_count(), cube.face_count()), (12, 20, 10));
    /// cube.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn extrude_faces(
        &mut self,
        faces: &[FaceKey],
        options: &ExtrudeOptions,
    ) -> Result<Extrusion> {
        if options.individual {
            self.selected_faces(faces)?;
            return self.transaction(|m| {
                let mut all = Extrusion {
                    top: Vec::new(),
                    sides: Vec::new(),
                    vertices: Vec::new(),
                };
                for &f in faces {
                    let plan = m.plan_extrude_region(&[f], options)?;
                    let made = journaled!(m.commit_extrude(&plan))?;
                    let one = m.extrusion(&plan, &made);
                    all.top.extend(one.top);
                    all.sides.extend(one.sides);
                    all.vertices.extend(one.vertices);
                }
                Ok(all)
            });
        }
        let plan = self.plan_extrude_region(faces, options)?;
        let made = journaled!(self.commit_extrude(&plan))?;
        Ok(self.extrusion(&plan, &made))
    }

    /// Check the selection and options; find the boundary, the fans and
    /// the regions' offsets.
    pub(super) fn plan_extrude_region(
        &self,
        faces: &[FaceKey],
        o: &ExtrudeOptions,
    ) -> Result<Plan> {
        let fs = self.selected_faces(faces)?;
        if let [f] = fs[..] {
            return self.plan_one_face(f, o, faces[0]);
        }
        // Per face slot: 0 unselected, else its region + 1 (zeroed memory
        // is mapped lazily: the cost follows the selection).
        let [vertex_slots, _, _, face_slots] = self.slot_counts();
        let mut mark = vec![0u32; face_slots];
        let regions = self.face_regions(&fs, &mut mark);
        let in_s = |h: Hid| mark[self.face_of(h).index()] != 0;
        let region_of = |f: Fid| mark[f.index()] as usize - 1;
        let mut boundary = Vec::new();
        let mut cycles = Vec::new();
        for &f in &fs {
            let before = boundary.len();
            let cycle: Vec<(Hid, u32)> = self
                .face_halfedges(f)
                .map(|h| {
                    if in_s(h.twin()) {
                        (h, NOT_BOUNDARY)
                    } else {
                        boundary.push(h);
                        (h, boundary.len() as u32 - 1)
                    }
                })
                .collect();
            if boundary.len() > before {
                cycles.push((f, cycle));
            }
        }
        let (fans, fan_at) = self.boundary_fans(&boundary, &in_s, &region_of);
        let next = boundary.iter().map(|&h| self.next(h)).collect();
        let face = boundary.iter().map(|&h| self.face_of(h)).collect();
        // Per vertex slot: 1 copied, 2 inner and listed.
        let mut vmark = vec![0u8; vertex_slots];
        for fan in &fans {
            vmark[fan.v.index()] = 1;
        }
        let mut inner = Vec::new();
        for &f in &fs {
            for h in self.face_halfedges(f) {
                let v = self.origin(h);
                if vmark[v.index()] == 0 {
                    vmark[v.index()] = 2;
                    inner.push((v, region_of(f)));
                }
            }
        }
        let face_region: Vec<usize> = fs.iter().map(|&f| region_of(f)).collect();
        let offsets = self.region_offsets(&fs, &face_region, regions, o, faces[0])?;
        Ok(Plan {
            face_region,
            faces: fs,
            boundary,
            face,
            next,
            fan_at,
            fans,
            cycles,
            inner,
            offsets,
        })
    }

    /// [`plan_extrude_region`](Mesh::plan_extrude_region) of one face: its
    /// every side is boundary, each corner a fan of its own.
    fn plan_one_face(&self, f: Fid, o: &ExtrudeOptions, name: FaceKey) -> Result<Plan> {
        let cycle: Vec<Hid> = self.face_halfedges(f).collect();
        let n = cycle.len();
        let fans = (0..n)
            .map(|j| Fan {
                v: self.origin(cycle[j]),
                first: cycle[j],
                inner: Vec::new(),
                incoming: cycle[(j + n - 1) % n],
                region: 0,
            })
            .collect();
        let offsets = self.region_offsets(&[f], &[0], 1, o, name)?;
        Ok(Plan {
            face_region: vec![0],
            faces: vec![f],
            boundary: cycle.clone(),
            face: vec![f; n],
            next: (0..n).map(|j| cycle[(j + 1) % n]).collect(),
            fan_at: (0..n).map(|j| (j, (j + 1) % n)).collect(),
            fans,
            cycles: vec![(f, (0..n as u32).map(|j| (cycle[j as usize], j)).collect())],
            inner: Vec::new(),
            offsets,
        })
    }

    /// The selection's face slots, checked, without repeats.
    pub(super) fn selected_faces(&self, faces: &[FaceKey]) -> Result<Vec<Fid>> {
        if faces.is_empty() {
            // Generation 0 is never live: this key names no element.
            return Err(refuse(OP, FaceKey::new(0, 0), Refusal::Empty));
        }
        let mut seen = std::collections::HashSet::new();
        let mut fs = Vec::with_capacity(faces.len());
        for &fk in faces {
            let f = self.check_face(fk)?;
            if self.is_hole(f) {
                return Err(refuse(OP, fk, Refusal::Hole));
            }
            if seen.insert(f) {
                fs.push(f);
            }
        }
        Ok(fs)
    }

    /// Label each selected face's region (faces joined through edges with
    /// a selected face on both sides) in `mark` (by face slot, region + 1);
    /// the number of regions.
    fn face_regions(&self, fs: &[Fid], mark: &mut [u32]) -> usize {
        const SELECTED: u32 = u32::MAX;
        for &f in fs {
            mark[f.index()] = SELECTED;
        }
        let mut count = 0;
        let mut stack = Vec::new();
        for &f in fs {
            if mark[f.index()] != SELECTED {
                continue;
            }
            count += 1;
            mark[f.index()] = count as u32;
            stack.push(f);
            while let Some(g) = stack.pop() {
                for h in self.face_halfedges(g) {
                    let n = self.face_of(h.twin());
                    if mark[n.index()] == SELECTED {
                        mark[n.index()] = count as u32;
                        stack.push(n);
                    }
                }
            }
        }
        count
    }

    /// The fans of selected faces at the boundary's vertices, one per
    /// boundary half-edge leaving a vertex; per boundary half-edge, the
    /// fans at its origin and at its head.
    fn boundary_fans(
        &self,
        boundary: &[Hid],
        in_s: &impl Fn(Hid) -> bool,
        region_of: &impl Fn(Fid) -> usize,
    ) -> (Vec<Fan>, Vec<(usize, usize)>) {
        let index: HashMap<Hid, usize> =
            boundary.iter().enumerate().map(|(i, &h)| (h, i)).collect();
        let mut fans = Vec::with_capacity(boundary.len());
        let mut fan_at = vec![(0, 0); boundary.len()];
        for (i, &h) in boundary.iter().enumerate() {
            // Turn from `h` across its predecessors' edges while the face
            // beyond is selected.
            let mut inner = Vec::new();
            let mut o = h;
            loop {
                let p = self.prev(o);
                if !in_s(p.twin()) {
                    let incoming = p;
                    fan_at[i].0 = fans.len();
                    fan_at[index[&incoming]].1 = fans.len();
                    fans.push(Fan {
                        v: self.origin(h),
                        first: h,
                        inner,
                        incoming,
                        region: region_of(self.face_of(h)),
                    });
                    break;
                }
                o = p.twin();
                inner.push(o);
            }
        }
        (fans, fan_at)
    }

    /// Per region, the offset: `distance` along the given direction or the
    /// region's area-weighted mean normal.
    fn region_offsets(
        &self,
        fs: &[Fid],
        face_region: &[usize],
        regions: usize,
        o: &ExtrudeOptions,
        name: FaceKey,
    ) -> Result<Vec<V3>> {
        if !o.distance.is_finite() {
            return Err(refuse(
                OP,
                name,
                Refusal::Parameter("distance must be finite"),
            ));
        }
        if let Some(d) = o.direction {
            let unit = d
                .iter()
                .all(|c| c.is_finite())
                .then(|| vec3::normalize(d))
                .flatten()
                .ok_or_else(|| {
                    refuse(
                        OP,
                        name,
                        Refusal::Parameter("direction must be finite and not zero"),
                    )
                })?;
            return Ok(vec![vec3::scale(unit, o.distance); regions]);
        }
        // Per region, the normals' sum and their lengths' sum: a sum below
        // 1e-9 of the lengths' is no direction (a closed surface).
        let mut sums = vec![([0.0; 3], 0.0); regions];
        if !self.has_positions() {
            return Ok(vec![[0.0; 3]; regions]);
        }
        for (&f, &r) in fs.iter().zip(face_region) {
            if let Some(n) = self.loop_normal(self.face_halfedge(f)) {
                let s = &mut sums[r];
                *s = (vec3::add(s.0, n), s.1 + vec3::norm(n));
            }
        }
        sums.into_iter()
            .map(
                |(s, total)| match vec3::normalize(s).filter(|_| vec3::norm(s) > 1e-9 * total) {
                    Some(n) => Ok(vec3::scale(n, o.distance)),
                    None if o.distance == 0.0 => Ok([0.0; 3]),
                    None => Err(refuse(OP, name, Refusal::ZeroArea)),
                },
            )
            .collect()
    }
}

impl Mesh {
    /// Make the walls, re-home the fans, move the region (the plan's body,
    /// in journaling mode `J`).
    pub(super) fn commit_extrude<J: Journaling>(&mut self, plan: &Plan) -> Result<Made> {
        let mut w = self.writer::<J>();
        let tops: Vec<Vid> = plan.fans.iter().map(|_| w.alloc_vertex()).collect();
        let rails: Vec<Eid> = plan.fans.iter().map(|_| w.alloc_edge()).collect();
        let caps: Vec<Eid> = plan.boundary.iter().map(|_| w.alloc_edge()).collect();
        let sides: Vec<Fid> = plan.boundary.iter().map(|_| w.alloc_face(false)).collect();
        // The fans' inner half-edges leave the copies.
        for (fan, &top) in plan.fans.iter().zip(&tops) {
            for &o in &fan.inner {
                w.he_mut(o).origin = top;
            }
        }
        // The top faces: each boundary half-edge replaced by its cap.
        for (f, cycle) in &plan.cycles {
            let cap = |&(h, j): &(Hid, u32)| {
                if j == NOT_BOUNDARY {
                    h
                } else {
                    caps[j as usize].halfedge(0)
                }
            };
            let now: Vec<Hid> = cycle.iter().map(cap).collect();
            for (i, &h) in now.iter().enumerate() {
                w.he_mut(h).next = now[(i + 1) % now.len()];
                w.he_mut(h).face = *f;
            }
            w.set_face_link(*f, now[0]);
        }
        for (j, &h) in plan.boundary.iter().enumerate() {
            let (fa, fb) = plan.fan_at[j];
            let [c, ct] = caps[j].halfedges();
            let up_b = rails[fb].halfedge(0);
            let down_a = rails[fa].halfedge(1);
            let s = sides[j];
            w.he_mut(c).origin = tops[fa];
            *w.he_mut(h) = HalfedgeRecord {
                origin: w.origin(h),
                next: up_b,
                face: s,
            };
            *w.he_mut(up_b) = HalfedgeRecord {
                origin: plan.fans[fb].v,
                next: ct,
                face: s,
            };
            *w.he_mut(ct) = HalfedgeRecord {
                origin: tops[fb],
                next: down_a,
                face: s,
            };
            *w.he_mut(down_a) = HalfedgeRecord {
                origin: tops[fa],
                next: h,
                face: s,
            };
            w.set_face_link(s, h);
        }
        for (i, fan) in plan.fans.iter().enumerate() {
            *w.v_halfedge_mut(tops[i]) = rails[i].halfedge(1);
            *w.v_halfedge_mut(fan.v) = rails[i].halfedge(0);
        }
        for fan in &plan.fans {
            w.point_at_hole(fan.v);
        }
        extrusion_attributes(&mut w, plan, &tops, &rails, &caps, &sides);
        move_region(&mut w, plan, &tops);
        w.end_op();
        Ok(Made {
            tops,
            rails,
            caps,
            sides,
        })
    }

    /// The public account of an extrusion.
    pub(super) fn extrusion(&self, plan: &Plan, made: &Made) -> Extrusion {
        Extrusion {
            top: plan.faces.iter().map(|&f| self.fkey(f)).collect(),
            sides: made.sides.iter().map(|&s| self.fkey(s)).collect(),
            vertices: made.tops.iter().map(|&v| self.vkey(v)).collect(),
        }
    }
}

/// The new elements' values (see [`Mesh::extrude_faces`]).
fn extrusion_attributes<J: Journaling>(
    w: &mut crate::mesh::Writer<'_, J>,
    plan: &Plan,
    tops: &[Vid],
    rails: &[Eid],
    caps: &[Eid],
    sides: &[Fid],
) {
    for (i, fan) in plan.fans.iter().enumerate() {
        w.attrs
            .vertex
            .interpolate(tops[i].index(), &[(fan.v.index(), 1.0)]);
        let (a, b) = (fan.first.edge().index(), fan.incoming.edge().index());
        w.attrs
            .edge
            .interpolate(rails[i].index(), &[(a, 0.5), (b, 0.5)]);
    }
    for (j, &h) in plan.boundary.iter().enumerate() {
        let (fa, fb) = plan.fan_at[j];
        let [c, ct] = caps[j].halfedges();
        w.attrs
            .edge
            .interpolate(caps[j].index(), &[(h.edge().index(), 1.0)]);
        w.attrs
            .face
            .interpolate(sides[j].index(), &[(plan.face[j].index(), 1.0)]);
        let n0 = plan.next[j];
        w.attrs.halfedge.copy(h.index(), c.index());
        w.attrs
            .halfedge
            .copy(h.index(), rails[fa].halfedge(1).index());
        w.attrs
            .halfedge
            .copy(n0.index(), rails[fb].halfedge(0).index());
        w.attrs.halfedge.copy(n0.index(), ct.index());
    }
}

/// Copies at their originals plus the offset, inner vertices moved by it.
fn move_region<J: Journaling>(w: &mut crate::mesh::Writer<'_, J>, plan: &Plan, tops: &[Vid]) {
    let Some(pos) = w.position_slots() else {
        return;
    };
    let copies = plan
        .fans
        .iter()
        .zip(tops)
        .map(|(fan, &top)| (top, fan.v, fan.region));
    let inner = plan.inner.iter().map(|&(v, region)| (v, v, region));
    let moved: Vec<(Vid, V3)> = copies
        .chain(inner)
        .map(|(to, from, region)| (to, vec3::add(pos[from.index()], plan.offsets[region])))
        .collect();
    for (v, p) in moved {
        w.attrs.set_position_saved(v.index(), p);
    }
}

#[cfg(test)]
mod tests;
