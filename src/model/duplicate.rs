//! `duplicate_faces` and `separate`: copies of a selection of faces, in
//! the same mesh (with the copies' keys beside their sources') or as a
//! mesh of their own.
//!
//! A copy is a patch of its own: every copied edge whose other side was
//! not selected borders a new hole, and each vertex gets one copy per fan
//! of selected faces round it (faces meeting only at a corner come apart
//! there). Every column copies its values: a copied vertex, edge, face or
//! corner has its source's values (conserved quantities are copied too,
//! as Blender's duplicate copies custom data), and the new holes'
//! corners interpolate nothing.

use std::collections::HashMap;

use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::{EdgeKey, FaceKey, VertexKey};
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::Mesh;
use crate::ops::refuse;

/// What [`Mesh::duplicate_faces`] made: each copy beside its source.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Duplicate {
    /// `(source, copy)` per selected face, in selection order.
    pub faces: Vec<(FaceKey, FaceKey)>,
    /// `(source, copy)` per vertex copy (a vertex the selection meets in
    /// several fans has several copies).
    pub vertices: Vec<(VertexKey, VertexKey)>,
    /// `(source, copy)` per copied edge.
    pub edges: Vec<(EdgeKey, EdgeKey)>,
    /// The holes round the copies.
    pub holes: Vec<FaceKey>,
}

/// The copy, planned against the mesh as it is; local numbers index the
/// new elements.
struct Plan {
    faces: Vec<Fid>,
    /// The selected faces' corners (half-edges), face by face.
    corners: Vec<Hid>,
    corner_of: HashMap<Hid, u32>,
    /// Per corner: its vertex copy.
    copy_of: Vec<u32>,
    /// Per vertex copy: its source.
    sources: Vec<Vid>,
    /// Per new edge: its source edge.
    edge_source: Vec<Eid>,
    /// Per corner: its new edge and side.
    half_of: Vec<(u32, u32)>,
}

impl Mesh {
    /// Whether [`duplicate_faces`](Mesh::duplicate_faces) would succeed;
    /// changes nothing.
    ///
    /// # Errors
    /// As [`duplicate_faces`](Mesh::duplicate_faces).
    pub fn check_duplicate_faces(&self, faces: &[FaceKey]) -> Result<()> {
        self.plan_duplicate(faces).map(|_| ())
    }

    /// Copy `faces` in place: the copies sit on their sources, joined to
    /// each other where the sources share edges and to nothing else (a
    /// new hole runs round them). One undo step.
    ///
    /// Attributes: every copy (vertex, edge, face, corner) has its
    /// source's values, whatever the column's rule; the holes' corners
    /// interpolate nothing.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Hole`] for a
    /// hole in `faces`; [`Refusal::Empty`] for no faces. A refused call
    /// changes nothing.
    ///
    /// # Complexity
    /// O(corners of the selection × their degrees), whatever the mesh's size.
    ///
    /// ```
    /// let mut cube = meshloom::shapes::cube();
    /// let top = cube.faces().next().unwrap();
    /// let made = cube.duplicate_faces(&[top])?;
    /// assert_eq!((made.vertices.len(), made.edges.len(), made.holes.len()), (4, 4, 1));
    /// assert_eq!(cube.face_count(), 7);
    /// assert_eq!(cube.split_components(false).len(), 2);
    /// cube.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn duplicate_faces(&mut self, faces: &[FaceKey]) -> Result<Duplicate> {
        let plan = self.plan_duplicate(faces)?;
        self.transaction(|m| journaled!(m.commit_duplicate(&plan)))
    }

    /// Move `faces` into a mesh of their own: the result holds them with
    /// every column and their keys (the source's keys, so it maps back to
    /// the source; [`compact`](Mesh::compact) it for dense indices), and
    /// they become holes here, their lone edges and vertices removed (as
    /// [`remove_face`](Mesh::remove_face) does). One undo step here.
    ///
    /// # Errors
    /// As [`duplicate_faces`](Mesh::duplicate_faces). A refused call
    /// changes nothing.
    ///
    /// # Complexity
    /// O(the mesh): the part starts as a copy of the whole mesh.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mut mesh = grid(3, 1, GridFaces::Quads);
    /// let first = mesh.faces().next().unwrap();
    /// let part = mesh.separate(&[first])?;
    /// assert_eq!((part.face_count(), mesh.face_count()), (1, 2));
    /// assert!(part.contains_face(first) && !mesh.contains_face(first));
    /// part.validate()?;
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn separate(&mut self, faces: &[FaceKey]) -> Result<Mesh> {
        let plan = self.plan_duplicate(faces)?;
        let mut part = self.clone();
        let keep: std::collections::HashSet<Fid> = plan.faces.iter().copied().collect();
        let others: Vec<FaceKey> = part
            .fids()
            .filter(|f| !keep.contains(f) && !part.is_hole(*f))
            .map(|f| part.fkey(f))
            .collect();
        for f in others {
            part.remove_face(f)?;
        }
        self.transaction(|m| {
            for &f in &plan.faces {
                let f = m.fkey(f);
                m.remove_face(f)?;
            }
            Ok(())
        })?;
        Ok(part)
    }

    /// Check the selection and number the copies.
    fn plan_duplicate(&self, faces: &[FaceKey]) -> Result<Plan> {
        const OP: &str = "duplicate_faces";
        if faces.is_empty() {
            // No face to name: generation 0 is never live.
            return Err(refuse(OP, FaceKey::new(0, 0), Refusal::Empty));
        }
        let mut plan = Plan {
            faces: Vec::with_capacity(faces.len()),
            corners: Vec::new(),
            corner_of: HashMap::new(),
            copy_of: Vec::new(),
            sources: Vec::new(),
            edge_source: Vec::new(),
            half_of: Vec::new(),
        };
        let mut selected = HashMap::new();
        for &fk in faces {
            let f = self.check_face(fk)?;
            if self.is_hole(f) {
                return Err(refuse(OP, fk, Refusal::Hole));
            }
            if selected.insert(f, ()).is_none() {
                plan.faces.push(f);
            }
        }
        for &f in &plan.faces {
            for h in self.face_halfedges(f) {
                plan.corner_of.insert(h, plan.corners.len() as u32);
                plan.corners.push(h);
            }
        }
        self.number_vertex_copies(&mut plan);
        self.number_edge_copies(&mut plan);
        Ok(plan)
    }

    /// One vertex copy per fan: corners at a vertex whose faces share an
    /// edge there join the same copy (union–find over the corners).
    fn number_vertex_copies(&self, plan: &mut Plan) {
        let n = plan.corners.len();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        fn root(parent: &mut [u32], mut i: u32) -> u32 {
            while parent[i as usize] != i {
                let up = parent[parent[i as usize] as usize];
                parent[i as usize] = up;
                i = up;
            }
            i
        }
        for (i, &h) in plan.corners.iter().enumerate() {
            // The corner across the edge that ends at h's origin.
            if let Some(&j) = plan.corner_of.get(&self.prev(h).twin()) {
                let (a, b) = (root(&mut parent, i as u32), root(&mut parent, j));
                parent[a.max(b) as usize] = a.min(b);
            }
        }
        let mut copy_of_root: HashMap<u32, u32> = HashMap::new();
        plan.copy_of = (0..n as u32)
            .map(|i| {
                let r = root(&mut parent, i);
                *copy_of_root.entry(r).or_insert_with(|| {
                    plan.sources.push(self.origin(plan.corners[r as usize]));
                    plan.sources.len() as u32 - 1
                })
            })
            .collect();
    }

    /// One new edge per source edge of the selection; a corner takes half
    /// 0 of its edge, or half 1 when its twin was numbered first.
    fn number_edge_copies(&self, plan: &mut Plan) {
        plan.half_of = vec![(0, 0); plan.corners.len()];
        for (i, &h) in plan.corners.iter().enumerate() {
            match plan.corner_of.get(&h.twin()) {
                Some(&j) if (j as usize) < i => {
                    plan.half_of[i] = (plan.half_of[j as usize].0, 1);
                }
                _ => {
                    plan.half_of[i] = (plan.edge_source.len() as u32, 0);
                    plan.edge_source.push(h.edge());
                }
            }
        }
    }

    /// [`duplicate_faces`](Mesh::duplicate_faces)'s body.
    fn commit_duplicate<J: Journaling>(&mut self, plan: &Plan) -> Result<Duplicate> {
        let mut w = self.writer::<J>();
        let vs: Vec<Vid> = plan.sources.iter().map(|_| w.alloc_vertex()).collect();
        let es: Vec<Eid> = plan.edge_source.iter().map(|_| w.alloc_edge()).collect();
        let fs: Vec<Fid> = plan.faces.iter().map(|_| w.alloc_face(false)).collect();
        let new_half = |i: usize| {
            let (k, side) = plan.half_of[i];
            es[k as usize].halfedge(side)
        };
        // The copied faces.
        let mut c = 0;
        for (&f, &g) in plan.faces.iter().zip(&fs) {
            let start = c;
            let n = w.face_halfedges(f).count();
            for i in start..start + n {
                let next = if i + 1 == start + n { start } else { i + 1 };
                *w.he_mut(new_half(i)) = HalfedgeRecord {
                    origin: vs[plan.copy_of[i] as usize],
                    next: new_half(next),
                    face: g,
                };
                *w.v_halfedge_mut(vs[plan.copy_of[i] as usize]) = new_half(i);
            }
            w.set_face_link(g, new_half(start));
            c += n;
        }
        let holes = link_duplicate_holes(&mut w, plan, &vs, new_half);
        duplicate_attributes(&mut w, plan, &vs, &es, &fs, new_half);
        w.end_op();
        Ok(Duplicate {
            faces: plan
                .faces
                .iter()
                .zip(&fs)
                .map(|(&a, &b)| (w.fkey(a), w.fkey(b)))
                .collect(),
            vertices: plan
                .sources
                .iter()
                .zip(&vs)
                .map(|(&a, &b)| (w.vkey(a), w.vkey(b)))
                .collect(),
            edges: plan
                .edge_source
                .iter()
                .zip(&es)
                .map(|(&a, &b)| (w.ekey(a), w.ekey(b)))
                .collect(),
            holes: holes.into_iter().map(|h| w.fkey(h)).collect(),
        })
    }
}

/// The hole half-edges round the copies: the other half of every copied
/// edge with one selected side. Each runs from the copy of its source's
/// dest back to the copy of its origin and continues, round that vertex's
/// fan, on the next unshared edge. Each loop becomes a hole.
fn link_duplicate_holes<J: Journaling>(
    w: &mut crate::mesh::Writer<'_, J>,
    plan: &Plan,
    vs: &[Vid],
    new_half: impl Fn(usize) -> Hid,
) -> Vec<Fid> {
    let mut open = Vec::new();
    for (i, &h) in plan.corners.iter().enumerate() {
        if plan.corner_of.contains_key(&h.twin()) {
            continue;
        }
        let g = new_half(i).twin();
        // Round h's origin inside the fan to the corner y whose edge
        // ends there unshared.
        let mut y = w.prev(h);
        while let Some(&j) = plan.corner_of.get(&y.twin()) {
            y = w.prev(plan.corners[j as usize]);
        }
        let j = plan.corner_of[&y] as usize;
        let next_corner = plan.corner_of[&w.next(h)] as usize;
        *w.he_mut(g) = HalfedgeRecord {
            origin: vs[plan.copy_of[next_corner] as usize],
            next: new_half(j).twin(),
            face: Fid::NONE,
        };
        // A copy on a hole names its hole half-edge.
        *w.v_halfedge_mut(vs[plan.copy_of[next_corner] as usize]) = g;
        open.push(g);
    }
    let mut holes = Vec::new();
    for g in open {
        if w.face_of(g) != Fid::NONE {
            continue;
        }
        let hole = w.alloc_face(true);
        w.relabel_loop(g, hole);
        holes.push(hole);
    }
    holes
}

/// Every copy takes its source's values; hole corners get nothing.
fn duplicate_attributes<J: Journaling>(
    w: &mut crate::mesh::Writer<'_, J>,
    plan: &Plan,
    vs: &[Vid],
    es: &[Eid],
    fs: &[Fid],
    new_half: impl Fn(usize) -> Hid,
) {
    for (&src, &v) in plan.sources.iter().zip(vs) {
        w.attrs.vertex.interpolate(v.index(), &[(src.index(), 1.0)]);
    }
    for (&src, &e) in plan.edge_source.iter().zip(es) {
        w.attrs.edge.copy(src.index(), e.index());
    }
    for (&src, &f) in plan.faces.iter().zip(fs) {
        w.attrs.face.copy(src.index(), f.index());
    }
    for (i, &h) in plan.corners.iter().enumerate() {
        let copy = new_half(i);
        w.attrs.halfedge.copy(h.index(), copy.index());
        if !plan.corner_of.contains_key(&h.twin()) {
            w.attrs.halfedge.interpolate(copy.twin().index(), &[]);
        }
    }
}

#[cfg(test)]
mod tests;
