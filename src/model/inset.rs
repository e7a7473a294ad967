//! `inset_faces`: a smaller copy of a region (or of each face) inside it,
//! joined to its old outline by a rim of quads.
//!
//! An inset is an extrusion of no height whose top then moves inwards:
//! it reuses the extrusion's plan and commit (`extrude`), moves the
//! region's boundary copies along the bisectors of their corners, and
//! re-interpolates the moved corners inside the faces they were in
//! ([`FaceSnapshot`]).

use std::collections::HashMap;

use super::extrude::{ExtrudeOptions, Extrusion, Made, Plan};
use super::interp::FaceSnapshot;
use crate::error::{Refusal, Result};
use crate::journal::journaled;
use crate::keys::FaceKey;
use crate::layout::{Fid, Vid};
use crate::mesh::Mesh;
use crate::ops::refuse;
use crate::record::Recorded;
use crate::vec3::{self, V3};

const OP: &str = "inset_faces";

/// Options of [`Mesh::inset_faces`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InsetOptions {
    /// How far in the new outline runs from the old one (negative: an
    /// outset); finite.
    pub thickness: f64,
    /// How far the inner faces move along their region's mean normal;
    /// finite.
    pub depth: f64,
    /// Keep the thickness at sharp corners (a corner moves `thickness /
    /// sin(angle / 2)` along its bisector, at most 20 × `thickness`)
    /// instead of moving every corner `thickness` along its bisector.
    pub even: bool,
    /// Inset each face on its own instead of connected faces together.
    pub individual: bool,
}

impl Default for InsetOptions {
    fn default() -> InsetOptions {
        InsetOptions {
            thickness: 0.0,
            depth: 0.0,
            even: true,
            individual: false,
        }
    }
}

/// What [`Mesh::inset_faces`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Inset {
    /// The inset faces (the selection, keeping their keys).
    pub inner: Vec<FaceKey>,
    /// The rim: one quad per boundary edge of each region.
    pub rim: Vec<FaceKey>,
    /// The new vertices (the inner outline's corners).
    pub vertices: Vec<crate::keys::VertexKey>,
}

impl Mesh {
    /// Whether [`inset_faces`](Mesh::inset_faces) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`inset_faces`](Mesh::inset_faces).
    pub fn check_inset_faces(&self, faces: &[FaceKey], options: &InsetOptions) -> Result<()> {
        self.plan_inset(faces, options)?;
        if options.individual {
            for &f in faces {
                self.plan_extrude_region(&[f], &ExtrudeOptions::default())?;
            }
        } else {
            self.plan_extrude_region(faces, &ExtrudeOptions::default())?;
        }
        Ok(())
    }

    /// Inset `faces`: each region of connected faces (each face, with
    /// `individual`) gets a copy of its outline moved `thickness` inwards
    /// (along each corner's bisector, in the planes of the faces beside
    /// it) and `depth` along its mean normal, joined to the old outline by
    /// a rim of quads. The faces keep their keys and become the inner
    /// part; the rim is made of pieces of them.
    ///
    /// Attributes (BMesh's inset with interpolation, always on): a moved
    /// corner takes the values its face had at the corner's new position
    /// (mean-value weights of the point in the face as it was), so a UV
    /// island and a linear field stay continuous across the rim; the
    /// rim's outer corners keep the face's corners, its inner corners
    /// match the inner face's; a face and its rim quads split the face's
    /// values by area; new vertices interpolate their face's vertices at
    /// their position. One undo step.
    ///
    /// # Errors
    /// As [`extrude_faces`](Mesh::extrude_faces); [`Refusal::Parameter`]
    /// for a non-finite thickness or depth.
    ///
    /// # Complexity
    /// O(selected faces' corners + degrees of their vertices).
    ///
    /// ```
    /// use meshloom::model::InsetOptions;
    /// let mut cube = meshloom::shapes::cube();
    /// let all: Vec<_> = cube.faces().collect();
    /// let made = cube.inset_faces(&all, &InsetOptions { thickness: 0.1, individual: true, ..Default::default() })?;
    /// assert_eq!((made.rim.len(), cube.face_count()), (24, 30));
    /// cube.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn inset_faces(&mut self, faces: &[FaceKey], options: &InsetOptions) -> Result<Inset> {
        self.plan_inset(faces, options)?;
        let groups: Vec<Vec<FaceKey>> = if options.individual {
            faces.iter().map(|&f| vec![f]).collect()
        } else {
            vec![faces.to_vec()]
        };
        self.transaction(|m| {
            let mut all = Inset {
                inner: Vec::new(),
                rim: Vec::new(),
                vertices: Vec::new(),
            };
            for group in &groups {
                let one = m.inset_region(group, options)?;
                all.inner.extend(one.top);
                all.rim.extend(one.sides);
                all.vertices.extend(one.vertices);
            }
            Ok(all)
        })
    }

    /// Check the options (the selection is checked by the extrusion's
    /// plan).
    fn plan_inset(&self, faces: &[FaceKey], o: &InsetOptions) -> Result<()> {
        self.selected_faces(faces)?;
        let name = faces[0];
        if !o.thickness.is_finite() || !o.depth.is_finite() {
            return Err(refuse(
                OP,
                name,
                Refusal::Parameter("thickness and depth must be finite"),
            ));
        }
        Ok(())
    }

    /// One region's inset: an extrusion of no height, then the moves and
    /// the values.
    fn inset_region(&mut self, faces: &[FaceKey], o: &InsetOptions) -> Result<Extrusion> {
        let plan = self.plan_extrude_region(faces, &ExtrudeOptions::default())?;
        // The faces whose corners move: those on the boundary, and those
        // around its vertices.
        let mut snapshots: HashMap<Fid, FaceSnapshot> = HashMap::new();
        let touched = plan.cycles.iter().map(|c| c.0);
        let around = plan
            .fans
            .iter()
            .flat_map(|fan| fan.inner.iter().map(|&h| self.face_of(h)));
        for f in touched.chain(around) {
            if let std::collections::hash_map::Entry::Vacant(e) = snapshots.entry(f) {
                if let Some(s) = FaceSnapshot::new(self, f) {
                    e.insert(s);
                }
            }
        }
        let lift = if o.depth == 0.0 {
            vec![[0.0; 3]; plan.offsets.len()]
        } else {
            self.region_lift(&plan, o.depth)
        };
        let targets = self.inset_targets(&plan, o, &lift);
        let made = journaled!(self.commit_extrude(&plan))?;
        self.inset_values(&plan, &made, &targets, &snapshots);
        let lifted: Vec<(Vid, V3)> = match self.position_slots() {
            Some(pos) if o.depth != 0.0 => plan
                .inner
                .iter()
                .map(|&(v, region)| (v, vec3::add(pos[v.index()], lift[region])))
                .collect(),
            _ => Vec::new(),
        };
        let mut w = self.writer::<Recorded>();
        for (&v, p) in made.tops.iter().zip(&targets) {
            w.attrs.set_position_saved(v.index(), *p);
        }
        for (v, p) in lifted {
            w.attrs.set_position_saved(v.index(), p);
        }
        self.split_by_area(&plan, &made);
        self.end_edit();
        Ok(self.extrusion(&plan, &made))
    }
}

impl Mesh {
    /// Per region, `depth` along its area-weighted mean normal (nothing
    /// where that is zero).
    fn region_lift(&self, plan: &Plan, depth: f64) -> Vec<V3> {
        let mut sums = vec![[0.0; 3]; plan.offsets.len()];
        for (&f, &r) in plan.faces.iter().zip(&plan.face_region) {
            if let Some(n) = self.loop_normal(self.face_halfedge(f)) {
                sums[r] = vec3::add(sums[r], n);
            }
        }
        sums.into_iter()
            .map(|s| vec3::normalize(s).map_or([0.0; 3], |n| vec3::scale(n, depth)))
            .collect()
    }

    /// Where each fan's copy goes: along the bisector of the inward
    /// normals of its two boundary edges (each in its own face's plane),
    /// by the thickness (`even`: by the thickness over the bisector's
    /// cosine with the edges' normals, at most 20 times it), then lifted.
    /// Empty without positions.
    fn inset_targets(&self, plan: &Plan, o: &InsetOptions, lift: &[V3]) -> Vec<V3> {
        let Some(pos) = self.position_slots() else {
            return Vec::new();
        };
        let unit_normal = |h| {
            self.loop_normal(self.face_halfedge(self.face_of(h)))
                .and_then(vec3::normalize)
                .unwrap_or([0.0; 3])
        };
        plan.fans
            .iter()
            .map(|fan| {
                let (out, inc) = (fan.first, fan.incoming);
                let p = pos[fan.v.index()];
                let ahead = pos[self.origin(self.next(out)).index()];
                let behind = pos[self.origin(inc).index()];
                let d_out = vec3::normalize(vec3::sub(ahead, p)).unwrap_or([0.0; 3]);
                let d_in = vec3::normalize(vec3::sub(p, behind)).unwrap_or([0.0; 3]);
                let m_out = vec3::cross(unit_normal(out), d_out);
                let m_in = vec3::cross(unit_normal(inc), d_in);
                let b = vec3::normalize(vec3::add(m_in, m_out)).unwrap_or(m_out);
                let along = if o.even {
                    o.thickness / vec3::dot(b, m_out).max(0.05)
                } else {
                    o.thickness
                };
                vec3::add(vec3::axpy(p, along, b), lift[fan.region])
            })
            .collect()
    }

    /// The corners at the moved copies (in the inner faces and the rim)
    /// and the copies' vertex values, from the faces as they were at the
    /// copies' new positions. A copy's corners: its outgoing boundary
    /// half-edge's cap and the fan's inner half-edges (in their faces), its
    /// rail going down (in the wall on the outgoing boundary half-edge) and
    /// the incoming boundary half-edge's cap's twin (in that wall): the
    /// walls take the values of the faces they stand on.
    fn inset_values(
        &mut self,
        plan: &Plan,
        made: &Made,
        targets: &[V3],
        snapshots: &HashMap<Fid, FaceSnapshot>,
    ) {
        if targets.is_empty() {
            return;
        }
        let mut by_fan = vec![(0, 0); plan.fans.len()];
        for (j, &(a, b)) in plan.fan_at.iter().enumerate() {
            by_fan[a].0 = j;
            by_fan[b].1 = j;
        }
        let (mut corners, mut corner_inputs) = (Vec::new(), Vec::new());
        let (mut vertices, mut vertex_inputs) = (Vec::new(), Vec::new());
        let mut cache: Vec<(Fid, Vec<(usize, f64)>)> = Vec::with_capacity(2);
        for (i, fan) in plan.fans.iter().enumerate() {
            let (j_out, j_in) = by_fan[i];
            let (home, behind) = (plan.face[j_out], plan.face[j_in]);
            let cap = made.caps[j_out].halfedge(0);
            let fixed = [
                (cap, home),
                (made.rails[i].halfedge(1), home),
                (made.caps[j_in].halfedge(1), behind),
            ];
            let inner = fan.inner.iter().map(|&o| (o, self.face_of(o)));
            cache.clear();
            for (corner, face) in fixed.into_iter().chain(inner) {
                let Some(snap) = snapshots.get(&face) else {
                    continue;
                };
                let k = match cache.iter().position(|c| c.0 == face) {
                    Some(k) => k,
                    None => {
                        cache.push((face, snap.weights(targets[i])));
                        cache.len() - 1
                    }
                };
                let w = &cache[k].1;
                let start = corner_inputs.len() as u32;
                corner_inputs.extend(w.iter().map(|&(k, x)| (snap.corners[k].index(), x)));
                corners.push((corner.index(), start, corner_inputs.len() as u32));
                if corner == cap {
                    let start = vertex_inputs.len() as u32;
                    vertex_inputs.extend(w.iter().map(|&(k, x)| (snap.vertices[k].index(), x)));
                    vertices.push((made.tops[i].index(), start, vertex_inputs.len() as u32));
                }
            }
        }
        let mut w = self.writer::<Recorded>();
        w.attrs.halfedge.interpolate_all(&corners, &corner_inputs);
        w.attrs.vertex.interpolate_all(&vertices, &vertex_inputs);
    }

    /// Split each face with walls among itself and its walls, by area.
    fn split_by_area(&mut self, plan: &Plan, made: &Made) {
        let mut pieces: HashMap<Fid, Vec<(usize, f64)>> = HashMap::new();
        for (j, &side) in made.sides.iter().enumerate() {
            pieces
                .entry(plan.face[j])
                .or_default()
                .push((side.index(), self.face_area_of(side)));
        }
        for (f, mut parts) in pieces {
            parts.push((f.index(), self.face_area_of(f)));
            let total: f64 = parts.iter().map(|p| p.1).sum();
            if total > 0.0 && total.is_finite() {
                parts.iter_mut().for_each(|p| p.1 /= total);
            } else {
                let n = parts.len() as f64;
                parts.iter_mut().for_each(|p| p.1 = 1.0 / n);
            }
            self.writer::<Recorded>()
                .attrs
                .face
                .split(f.index(), &parts);
        }
    }

    /// Face `f`'s area (half its Newell normal's length; 0 without
    /// positions).
    fn face_area_of(&self, f: Fid) -> f64 {
        self.loop_normal(self.face_halfedge(f))
            .map_or(0.0, |n| 0.5 * vec3::norm(n))
    }
}

#[cfg(test)]
mod tests;
