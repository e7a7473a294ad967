//! `dissolve_vertices`, `dissolve_edges`, `dissolve_faces`: remove
//! elements and merge the faces around them into one, as BMesh's dissolve
//! operators do (`bmo_dissolve.cc`).
//!
//! The steps, the rules and the attributes are told with [`Dissolved`].

use std::collections::{HashMap, HashSet};

use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::{AnyKey, EdgeKey, FaceKey, VertexKey};
use crate::layout::{Eid, Fid, Hid, Vid};
use crate::mesh::{Mesh, Writer};
use crate::ops::refuse;
use crate::vec3;

/// Options of [`Mesh::dissolve_edges`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DissolveEdgesOptions {
    /// Also dissolve the vertices the dissolve leaves between exactly two
    /// edges (that had another count before), where that leaves every
    /// face at least three sides and makes no second edge between two
    /// vertices (BMesh's `use_verts`, on in Blender's menu).
    pub vertices: bool,
}

impl Default for DissolveEdgesOptions {
    fn default() -> DissolveEdgesOptions {
        DissolveEdgesOptions { vertices: true }
    }
}

/// What a dissolve left and removed.
///
/// All three come down to the same two steps. First, **regions**: groups
/// of faces joined through the edges to dissolve become one face each;
/// every edge with a region face on both sides goes (as `BM_faces_join`
/// removes every edge two joined faces share), and so does every vertex
/// with only region faces around it. A region must be a disk: one simple
/// boundary loop (no hole inside, an annulus; no vertex met twice; no
/// handle), else the call is refused, where BMesh skips the region or
/// keeps a last edge: a meshloom face has one boundary and meets a vertex
/// once. Second, **joins**: a vertex left between exactly two edges is
/// taken out and its two edges become one (BMesh's
/// `BM_vert_collapse_edge`).
///
/// Each tool plans both steps on the mesh as it is (a refused call changes
/// nothing), then commits them as one edit (one undo step). Attributes:
/// a region's face is the `merge` of its faces (the survivor first, then
/// the others, weighted by area), so conserved totals are kept, an
/// `incompatible` column (a material id) keeps a value its faces agree on;
/// surviving corners and edges keep their values; two joined edges `merge`
/// by length (the kept one first), and the corner that moves onto the
/// kept half-edge copies its value.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Dissolved {
    /// The faces that merged faces became, one per region (each keeps the
    /// key of one of its faces).
    pub faces: Vec<FaceKey>,
    /// The edges that two edges became where a vertex between them was
    /// dissolved (each keeps the key of one of them).
    pub edges: Vec<EdgeKey>,
    /// How many vertices were removed.
    pub removed_vertices: usize,
    /// How many edges were removed.
    pub removed_edges: usize,
    /// How many faces were removed (merged into others).
    pub removed_faces: usize,
}

/// A group of faces that becomes one face.
pub(super) struct Region {
    /// The faces, the survivor first.
    pub(super) faces: Vec<Fid>,
    /// Their merge weights (area shares, or equal).
    pub(super) weights: Vec<f64>,
    /// The merged face's loop, in order.
    pub(super) boundary: Vec<Hid>,
    /// Boundary vertices whose half-edge goes, with the one they take.
    pub(super) repoint: Vec<(Vid, Hid)>,
    /// The edges and vertices inside the region.
    pub(super) edges: Vec<Eid>,
    pub(super) vertices: Vec<Vid>,
}

/// A checked dissolve: the regions, then the vertices to join.
pub(super) struct Plan {
    pub(super) regions: Vec<Region>,
    pub(super) joins: Vec<Vid>,
}

/// The regions' merge as the vertex joins see it: which edges and
/// vertices go, and which face a region face becomes.
struct Merged<'p> {
    gone_e: HashSet<Eid>,
    gone_v: HashSet<Vid>,
    /// Face slot → region survivor (faces of no region absent).
    rep: HashMap<Fid, Fid>,
    regions: &'p [Region],
}

impl Mesh {
    /// Whether [`dissolve_vertices`](Mesh::dissolve_vertices) would
    /// succeed; changes nothing.
    ///
    /// # Errors
    /// As [`dissolve_vertices`](Mesh::dissolve_vertices).
    pub fn check_dissolve_vertices(&self, vertices: &[VertexKey]) -> Result<()> {
        self.plan_dissolve_vertices(vertices).map(|_| ())
    }

    /// Dissolve `vertices`: the faces around each one merge into one face
    /// (its edges go, as [`remove_vertex`](Mesh::remove_vertex) does; faces
    /// around neighbouring selected vertices merge together), and a vertex
    /// then left between two edges (on the boundary, or one that had two
    /// edges to start with) is taken out of its edge chain: its two edges
    /// become one. See [`Dissolved`] for the steps and the attributes. One undo
    /// step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Empty`] for
    /// no vertices; [`Refusal::NonManifold`] when a merged face would not
    /// be a disk (a vertex met twice, a hole inside, or a closed surface)
    /// or a vertex keeps more than two edges (several holes meet there);
    /// [`Refusal::Degenerate`] when taking a vertex out of its chain would
    /// leave a face or hole with two sides, [`Refusal::EdgeExists`] when
    /// it would make a second edge between two vertices.
    ///
    /// # Complexity
    /// O(faces around the vertices × their degree), whatever the mesh's
    /// size.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::grid(2, 2, meshloom::shapes::GridFaces::Quads);
    /// // The centre vertex: its four quads become one.
    /// let centre = mesh.vertices().find(|&v| !mesh.vertex(v).unwrap().is_boundary()).unwrap();
    /// let d = mesh.dissolve_vertices(&[centre])?;
    /// assert_eq!((mesh.face_count(), mesh.face(d.faces[0])?.degree()), (1, 8));
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn dissolve_vertices(&mut self, vertices: &[VertexKey]) -> Result<Dissolved> {
        let plan = self.plan_dissolve_vertices(vertices)?;
        journaled!(self.commit_dissolve(&plan))
    }

    /// Whether [`dissolve_edges`](Mesh::dissolve_edges) would succeed;
    /// changes nothing.
    ///
    /// # Errors
    /// As [`dissolve_edges`](Mesh::dissolve_edges).
    pub fn check_dissolve_edges(
        &self,
        edges: &[EdgeKey],
        options: &DissolveEdgesOptions,
    ) -> Result<()> {
        self.plan_dissolve_edges(edges, options).map(|_| ())
    }

    /// Dissolve `edges`: the faces on the two sides of each one merge
    /// (faces joined through several selected edges become one face, and
    /// every edge between them goes, as BMesh's join does). Boundary edges
    /// have no face beyond them and are skipped, as BMesh skips them. With
    /// `options.vertices`, vertices left between two edges are then taken
    /// out of their chains where that is valid (see
    /// [`DissolveEdgesOptions`]). See [`Dissolved`] for the
    /// steps and the attributes. One undo step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Empty`] for
    /// no edges; [`Refusal::NonManifold`] when a merged face would not be
    /// a disk: a closed ring of dissolved edges around a band (an
    /// annulus), a vertex met twice, or a whole closed surface.
    ///
    /// # Complexity
    /// O(faces merged × their degree), whatever the mesh's size.
    ///
    /// ```
    /// use meshloom::model::DissolveEdgesOptions;
    /// let mut mesh = meshloom::shapes::cube();
    /// let e = mesh.edges().next().unwrap();
    /// let d = mesh.dissolve_edges(&[e], &DissolveEdgesOptions::default())?;
    /// // Two squares into one; the edge's ends, left between two edges, go
    /// // too (the faces beside them become triangles).
    /// assert_eq!((mesh.face_count(), mesh.face(d.faces[0])?.degree()), (5, 4));
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn dissolve_edges(
        &mut self,
        edges: &[EdgeKey],
        options: &DissolveEdgesOptions,
    ) -> Result<Dissolved> {
        let plan = self.plan_dissolve_edges(edges, options)?;
        journaled!(self.commit_dissolve(&plan))
    }

    /// Whether [`dissolve_faces`](Mesh::dissolve_faces) would succeed;
    /// changes nothing.
    ///
    /// # Errors
    /// As [`dissolve_faces`](Mesh::dissolve_faces).
    pub fn check_dissolve_faces(&self, faces: &[FaceKey]) -> Result<()> {
        self.plan_dissolve_faces(faces).map(|_| ())
    }

    /// Dissolve `faces` into regions: each connected group of them
    /// (sharing edges) becomes one face, in one pass (BMesh's
    /// `BM_faces_join`): the edges between them go, and the vertices with
    /// only them around. A face alone stays as it is. See the
    /// [`Dissolved`] for the steps and the attributes. One undo step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Empty`] for
    /// no faces; [`Refusal::Hole`] for a hole; [`Refusal::NonManifold`]
    /// when a region is not a disk: a ring of faces around unselected ones
    /// (the face would have a hole inside), faces meeting at a vertex
    /// only, or a whole closed surface.
    ///
    /// # Complexity
    /// O(Σ degree of the faces), whatever the mesh's size.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mut mesh = grid(3, 3, GridFaces::Quads);
    /// let all: Vec<_> = mesh.faces().collect();
    /// let d = mesh.dissolve_faces(&all)?;
    /// assert_eq!((mesh.face_count(), mesh.face(d.faces[0])?.degree()), (1, 12));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn dissolve_faces(&mut self, faces: &[FaceKey]) -> Result<Dissolved> {
        let plan = self.plan_dissolve_faces(faces)?;
        journaled!(self.commit_dissolve(&plan))
    }

    /// The regions around the selected vertices (of other than two edges),
    /// then every selected vertex left with two edges joined.
    fn plan_dissolve_vertices(&self, vertices: &[VertexKey]) -> Result<Plan> {
        const OP: &str = "dissolve_vertices";
        let first = *vertices
            .first()
            .ok_or_else(|| refuse(OP, VertexKey::new(0, 0), Refusal::Empty))?;
        let mut vs = Vec::with_capacity(vertices.len());
        let mut seen = HashSet::new();
        for &vk in vertices {
            let v = self.check_vertex(vk)?;
            if seen.insert(v) {
                vs.push(v);
            }
        }
        let mut merge = HashSet::new();
        for &v in &vs {
            if self.outgoing(v).count() == 2 {
                continue;
            }
            for h in self.outgoing(v) {
                if !self.in_hole(h) && !self.in_hole(h.twin()) {
                    merge.insert(h.edge());
                }
            }
        }
        let seeds: Vec<Hid> = vs
            .iter()
            .flat_map(|&v| self.outgoing(v).filter(|&h| merge.contains(&h.edge())))
            .collect();
        let (regions, rep) = self.plan_regions(OP, first.into(), &seeds, |e| merge.contains(&e))?;
        let merged = self.merged(&regions, rep);
        let survivors: Vec<Vid> = vs
            .into_iter()
            .filter(|v| !merged.gone_v.contains(v))
            .collect();
        let joins = self.plan_joins(OP, &survivors, true, &merged)?;
        Ok(Plan { regions, joins })
    }

    /// The regions through the selected interior edges, then (with
    /// `vertices`) the joins where vertices are left with two edges.
    fn plan_dissolve_edges(&self, edges: &[EdgeKey], o: &DissolveEdgesOptions) -> Result<Plan> {
        const OP: &str = "dissolve_edges";
        let first = *edges
            .first()
            .ok_or_else(|| refuse(OP, EdgeKey::new(0, 0), Refusal::Empty))?;
        let mut merge = HashSet::new();
        let mut seeds = Vec::new();
        for &ek in edges {
            let e = self.check_edge(ek)?;
            let [h, t] = e.halfedges();
            if !self.in_hole(h) && !self.in_hole(t) && merge.insert(e) {
                seeds.push(h);
            }
        }
        let (regions, rep) = self.plan_regions(OP, first.into(), &seeds, |e| merge.contains(&e))?;
        let merged = self.merged(&regions, rep);
        let joins = if o.vertices {
            let mut candidates = Vec::new();
            let mut seen = HashSet::new();
            for r in &regions {
                for &h in &r.boundary {
                    let v = self.origin(h);
                    if seen.insert(v) && self.outgoing(v).count() != 2 {
                        candidates.push(v);
                    }
                }
            }
            self.plan_joins(OP, &candidates, false, &merged)?
        } else {
            Vec::new()
        };
        Ok(Plan { regions, joins })
    }

    /// The regions of connected selected faces.
    fn plan_dissolve_faces(&self, faces: &[FaceKey]) -> Result<Plan> {
        const OP: &str = "dissolve_faces";
        let first = *faces
            .first()
            .ok_or_else(|| refuse(OP, FaceKey::new(0, 0), Refusal::Empty))?;
        let mut sel = HashSet::new();
        let mut seeds = Vec::new();
        for &fk in faces {
            let f = self.check_face(fk)?;
            if self.is_hole(f) {
                return Err(refuse(OP, fk, Refusal::Hole));
            }
            if sel.insert(f) {
                seeds.push(self.face_halfedge(f));
            }
        }
        let joined = |e: Eid| {
            let [h, t] = e.halfedges();
            sel.contains(&self.face_of(h)) && sel.contains(&self.face_of(t))
        };
        let (regions, _) = self.plan_regions(OP, first.into(), &seeds, joined)?;
        Ok(Plan {
            regions,
            joins: Vec::new(),
        })
    }

    /// Group the faces reached from the faces of `seeds` through edges
    /// where `joined` holds (each group's survivor: the face of the first
    /// seed that reached it), and check each group of two faces or more
    /// as a region. Also the face → group survivor map.
    fn plan_regions(
        &self,
        op: &'static str,
        name: AnyKey,
        seeds: &[Hid],
        joined: impl Fn(Eid) -> bool,
    ) -> Result<(Vec<Region>, HashMap<Fid, Fid>)> {
        let mut rep: HashMap<Fid, Fid> = HashMap::new();
        let mut regions = Vec::new();
        for &s in seeds {
            let f0 = self.face_of(s);
            if rep.contains_key(&f0) {
                continue;
            }
            rep.insert(f0, f0);
            let mut faces = vec![f0];
            let mut i = 0;
            while i < faces.len() {
                for h in self.face_halfedges(faces[i]) {
                    let g = self.face_of(h.twin());
                    if !self.is_hole(g) && !rep.contains_key(&g) && joined(h.edge()) {
                        rep.insert(g, f0);
                        faces.push(g);
                    }
                }
                i += 1;
            }
            if faces.len() > 1 {
                regions.push(self.plan_region(op, name, faces, |f| rep.get(&f) == Some(&f0))?);
            }
        }
        Ok((regions, rep))
    }

    /// Check that `faces` (with `in_region` telling its faces) form a disk
    /// and find its loop, inner edges and inner vertices.
    fn plan_region(
        &self,
        op: &'static str,
        name: AnyKey,
        faces: Vec<Fid>,
        in_region: impl Fn(Fid) -> bool,
    ) -> Result<Region> {
        let not_disk = || refuse(op, name, Refusal::NonManifold);
        let mut out: HashMap<Vid, Hid> = HashMap::new();
        let mut edges = Vec::new();
        let mut count = 0;
        for &f in &faces {
            for h in self.face_halfedges(f) {
                if in_region(self.face_of(h.twin())) {
                    if h.edge().halfedges()[0] == h {
                        edges.push(h.edge());
                    }
                } else {
                    count += 1;
                    if out.insert(self.origin(h), h).is_some() {
                        return Err(not_disk());
                    }
                }
            }
        }
        let Some(&start) = out.values().next() else {
            return Err(not_disk());
        };
        let mut boundary = vec![start];
        let mut h = out[&self.dest(start)];
        while h != start && boundary.len() <= count {
            boundary.push(h);
            h = out[&self.dest(h)];
        }
        if boundary.len() != count {
            return Err(not_disk());
        }
        if count < 3 {
            return Err(refuse(op, name, Refusal::Degenerate));
        }
        let mut vertices = Vec::new();
        let mut seen = HashSet::new();
        for &f in &faces {
            for h in self.face_halfedges(f) {
                let v = self.origin(h);
                if !out.contains_key(&v) && seen.insert(v) {
                    vertices.push(v);
                }
            }
        }
        if faces.len() + vertices.len() != edges.len() + 1 {
            return Err(not_disk());
        }
        let repoint = boundary
            .iter()
            .filter_map(|&h| {
                let v = self.origin(h);
                let x = self.vertex_halfedge(v);
                (in_region(self.face_of(x)) && in_region(self.face_of(x.twin()))).then_some((v, h))
            })
            .collect();
        let weights = self.area_weights(&faces);
        Ok(Region {
            faces,
            weights,
            boundary,
            repoint,
            edges,
            vertices,
        })
    }

    /// Merge weights of `faces`: area shares when positions give a
    /// positive total, else equal.
    pub(super) fn area_weights(&self, faces: &[Fid]) -> Vec<f64> {
        let areas: Option<Vec<f64>> = faces
            .iter()
            .map(|&f| self.loop_area(self.face_halfedge(f)))
            .collect();
        let total: f64 = areas.as_ref().map_or(0.0, |a| a.iter().sum());
        match areas {
            Some(a) if total > 0.0 && total.is_finite() => a.iter().map(|x| x / total).collect(),
            _ => vec![1.0 / faces.len() as f64; faces.len()],
        }
    }

    /// What the regions remove, and the face each region face becomes.
    fn merged<'p>(&self, regions: &'p [Region], rep: HashMap<Fid, Fid>) -> Merged<'p> {
        Merged {
            gone_e: regions
                .iter()
                .flat_map(|r| r.edges.iter().copied())
                .collect(),
            gone_v: regions
                .iter()
                .flat_map(|r| r.vertices.iter().copied())
                .collect(),
            rep,
            regions,
        }
    }

    /// Of `candidates` (vertices the regions keep), those to take out of
    /// their edge chains, in order, after the regions' merge: each must
    /// then have two edges, leave its two faces (or holes) at least three
    /// sides and join two vertices no edge joins yet. A candidate that
    /// fails refuses the call when `required`, else stays.
    fn plan_joins(
        &self,
        op: &'static str,
        candidates: &[Vid],
        required: bool,
        m: &Merged<'_>,
    ) -> Result<Vec<Vid>> {
        let pair = |a: Vid, b: Vid| if a < b { (a, b) } else { (b, a) };
        let mut degree: HashMap<Fid, usize> = HashMap::new();
        for r in m.regions {
            degree.insert(r.faces[0], r.boundary.len());
        }
        let mut neighbours: HashMap<Vid, [Vid; 2]> = HashMap::new();
        let (mut removed, mut made) = (HashSet::new(), HashSet::new());
        let mut joins = Vec::new();
        for &v in candidates {
            let fail = |reason| {
                if required {
                    Err(refuse(op, self.vkey(v), reason))
                } else {
                    Ok(())
                }
            };
            let outs: Vec<Hid> = self
                .outgoing(v)
                .filter(|h| !m.gone_e.contains(&h.edge()))
                .collect();
            if outs.len() != 2 {
                fail(Refusal::NonManifold)?;
                continue;
            }
            let side = |h: Hid| {
                let f = self.face_of(h);
                m.rep.get(&f).copied().unwrap_or(f)
            };
            let (x, y) = (side(outs[0]), side(outs[1]));
            let [u, w] = *neighbours
                .entry(v)
                .or_insert_with(|| [self.dest(outs[0]), self.dest(outs[1])]);
            let dx = *degree.entry(x).or_insert_with(|| self.face_degree(x));
            let dy = *degree.entry(y).or_insert_with(|| self.face_degree(y));
            if u == w || dx < 4 || dy < 4 {
                fail(Refusal::Degenerate)?;
                continue;
            }
            let exists = self
                .find_halfedge_raw(u, w)
                .is_some_and(|h| !m.gone_e.contains(&h.edge()) && !removed.contains(&pair(u, w)));
            if exists || made.contains(&pair(u, w)) {
                fail(Refusal::EdgeExists)?;
                continue;
            }
            for (a, b) in [(u, w), (w, u)] {
                if let Some(n) = self.two_neighbours(a, m, &neighbours) {
                    neighbours.insert(a, n.map(|z| if z == v { b } else { z }));
                }
            }
            for p in [pair(u, v), pair(v, w)] {
                if !made.remove(&p) {
                    removed.insert(p);
                }
            }
            made.insert(pair(u, w));
            *degree.get_mut(&x).expect("counted") -= 1;
            *degree.get_mut(&y).expect("counted") -= 1;
            joins.push(v);
        }
        Ok(joins)
    }

    /// The two neighbours of `a` after the regions' merge and the joins so
    /// far, if it has two edges.
    fn two_neighbours(
        &self,
        a: Vid,
        m: &Merged<'_>,
        known: &HashMap<Vid, [Vid; 2]>,
    ) -> Option<[Vid; 2]> {
        if let Some(&n) = known.get(&a) {
            return Some(n);
        }
        let mut outs = self.outgoing(a).filter(|h| !m.gone_e.contains(&h.edge()));
        let (p, q) = (outs.next()?, outs.next()?);
        outs.next().is_none().then(|| [self.dest(p), self.dest(q)])
    }

    /// Merge the regions, then join the vertices (the plan's body, in
    /// journaling mode `J`).
    fn commit_dissolve<J: Journaling>(&mut self, plan: &Plan) -> Result<Dissolved> {
        let mut w = self.writer::<J>();
        let mut out = Dissolved::default();
        for r in &plan.regions {
            commit_region(&mut w, r);
            out.removed_vertices += r.vertices.len();
            out.removed_edges += r.edges.len();
            out.removed_faces += r.faces.len() - 1;
        }
        let kept: Vec<Eid> = plan.joins.iter().map(|&v| join_at(&mut w, v)).collect();
        out.removed_vertices += kept.len();
        out.removed_edges += kept.len();
        w.end_op();
        out.faces = plan.regions.iter().map(|r| self.fkey(r.faces[0])).collect();
        out.edges = live_edges(self, &kept);
        Ok(out)
    }
}

/// The live edges of `kept` (a chain of joins removes some), once each.
pub(super) fn live_edges(mesh: &Mesh, kept: &[Eid]) -> Vec<EdgeKey> {
    let mut seen = HashSet::new();
    kept.iter()
        .filter(|e| mesh.edge_live(e.index()) && seen.insert(**e))
        .map(|&e| mesh.ekey(e))
        .collect()
}

/// Make region `r` one face: merge the face values, link its loop, free
/// what is inside.
fn commit_region<J: Journaling>(w: &mut Writer<'_, J>, r: &Region) {
    let keep = r.faces[0];
    let inputs: Vec<(usize, f64)> = r
        .faces
        .iter()
        .zip(&r.weights)
        .map(|(f, &x)| (f.index(), x))
        .collect();
    w.attrs.face.merge(keep.index(), &inputs);
    let n = r.boundary.len();
    for (i, &h) in r.boundary.iter().enumerate() {
        let next = r.boundary[(i + 1) % n];
        let rec = w.he_mut(h);
        rec.next = next;
        rec.face = keep;
    }
    w.set_face_link(keep, r.boundary[0]);
    for &(v, h) in &r.repoint {
        w.set_vertex_halfedge(v, h);
    }
    for &e in &r.edges {
        w.free_edge(e);
    }
    for &v in &r.vertices {
        w.free_vertex(v);
    }
    for &f in &r.faces[1..] {
        w.free_face(f);
    }
}

/// Take vertex `v` (two edges) out of its chain: its first edge (`v →
/// u`) becomes `w – u` and the other goes. The corner at `w` moves onto
/// the kept edge's half-edge and keeps its value; the edge values merge
/// by length. The kept edge.
pub(super) fn join_at<J: Journaling>(w: &mut Writer<'_, J>, v: Vid) -> Eid {
    let o1 = w.vertex_halfedge(v);
    let t1 = o1.twin();
    let o2 = w.next(t1);
    let t2 = o2.twin();
    let (x, y) = (w.face_of(o1), w.face_of(o2));
    let (u, far) = (w.dest(o1), w.dest(o2));
    let (keep, gone) = (o1.edge(), o2.edge());
    let shares = match w.position_slots() {
        Some(p) => {
            let l1 = vec3::norm(vec3::sub(p[u.index()], p[v.index()]));
            let l2 = vec3::norm(vec3::sub(p[far.index()], p[v.index()]));
            if l1 + l2 > 0.0 {
                [l1 / (l1 + l2), l2 / (l1 + l2)]
            } else {
                [0.5, 0.5]
            }
        }
        None => [0.5, 0.5],
    };
    w.attrs.edge.merge(
        keep.index(),
        &[(keep.index(), shares[0]), (gone.index(), shares[1])],
    );
    w.attrs.halfedge.copy(t2.index(), o1.index());
    // Face y: … t1 (u → v) → o2 (v → far) → n …  becomes  t1 → n.
    let n = w.next(o2);
    w.set_next(t1, n);
    // Face x: … p → t2 (far → v) → o1 (v → u) …  becomes  p → o1.
    let p = w.prev_fast(t2);
    w.set_next(p, o1);
    w.he_mut(o1).origin = far;
    if w.face_halfedge(x) == t2 {
        w.set_face_link(x, o1);
    }
    if w.face_halfedge(y) == o2 {
        w.set_face_link(y, t1);
    }
    if w.vertex_halfedge(far) == t2 {
        w.set_vertex_halfedge(far, o1);
    }
    w.free_edge(gone);
    w.free_vertex(v);
    keep
}

#[cfg(test)]
mod tests;
