//! `dissolve_limited`: merge nearly coplanar faces, then take out the
//! vertices left on nearly straight edge chains, as BMesh's limited
//! dissolve does (`bmesh_decimate_dissolve.cc`,
//! `BM_mesh_decimate_dissolve_ex`).
//!
//! The steps, the rules and the attributes are told with [`DissolveLimitedOptions`].

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::f64::consts::FRAC_PI_2;

use super::delimit::{Delimit, Delimiters};
use super::dissolve::{join_at, live_edges, Dissolved};
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::{EdgeKey, ElementKind, FaceKey, VertexKey};
use crate::layout::{Eid, Fid, Hid, Vid};
use crate::mesh::{Mesh, Writer};
use crate::ops::refuse;
use crate::vec3::{self, V3};

const OP: &str = "dissolve_limited";

/// Options of [`Mesh::dissolve_limited`].
///
/// **Faces.** Every edge with a face on both sides that no delimiter keeps
/// is a candidate, ordered by the angle between its faces' normals,
/// smallest first; below the limit, its two faces merge (every edge they
/// share goes). A merged face's normal is the sum of its parts' vector
/// areas (exact for any polygon), and an edge's angle is measured again
/// when the queue reaches it: if it grew, the edge is queued again at its
/// new angle (or dropped past the limit). BMesh re-measures every edge of
/// a merged face at once; measuring when reached keeps the cost to the
/// merged region (the smaller face's loop is walked and relabelled at each
/// merge), not to its whole boundary at every step. A merge that would not
/// leave one simple loop (a hole inside, a vertex met twice) is skipped,
/// as BMesh's join fails there.
///
/// **Vertices.** A vertex left between two edges is then taken out of its
/// chain, smallest angle first: its angle is how far the chain bends there,
/// times the angle between its two faces over 90° when both are faces and
/// neither edge delimits (BMesh's product, so a chain between two nearly
/// coplanar faces goes). With `boundaries`, every such vertex goes, bend
/// or not (BMesh's "all boundaries"). A join is skipped where a face or
/// hole would keep fewer than three sides, two vertices would get a second
/// edge, or the cut-off corner holds another corner of its face or flips a
/// neighbouring one (BMesh's degenerate check), so no face folds or loses
/// its area.
///
/// **Delimiters**: the [`Delimit`] columns, the boundary, and every face
/// column whose rule is `incompatible` (a material id): such a value is
/// never merged away. Attributes follow [`Mesh::dissolve_faces`]: a merged
/// face is the `merge` of its faces by area (the one whose key survives
/// first), joined edges merge by length, corners keep their values.
#[derive(Clone, Debug, PartialEq)]
pub struct DissolveLimitedOptions {
    /// The angle limit in radians (default 5°): faces whose normals differ
    /// by less merge, chains that bend by less lose their vertex. At least
    /// 0; more than 90° acts as 90°, as in BMesh.
    pub angle: f64,
    /// The columns that keep edges (see [`Delimit`]).
    pub delimit: Delimit,
    /// Dissolve every vertex left between two edges, whatever the angle.
    pub boundaries: bool,
    /// Only these edges may merge their faces (`None`: every edge).
    pub edges: Option<Vec<EdgeKey>>,
    /// Only these vertices may be taken out (`None`: every vertex).
    pub vertices: Option<Vec<VertexKey>>,
}

impl Default for DissolveLimitedOptions {
    fn default() -> DissolveLimitedOptions {
        DissolveLimitedOptions {
            angle: 5f64.to_radians(),
            delimit: Delimit::default(),
            boundaries: false,
            edges: None,
            vertices: None,
        }
    }
}

/// A queued edge or vertex, ordered by its key (then its slot).
#[derive(Clone, Copy, PartialEq)]
struct Queued<T> {
    key: f64,
    item: T,
    version: u32,
}

impl<T: Ord + Copy> Eq for Queued<T> {}

impl<T: Ord + Copy> Ord for Queued<T> {
    /// Reversed, so that the max-heap pops the smallest key.
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .key
            .total_cmp(&self.key)
            .then_with(|| other.item.cmp(&self.item))
    }
}

impl<T: Ord + Copy> PartialOrd for Queued<T> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A checked limited dissolve.
struct Plan {
    limit: f64,
    boundaries: bool,
    /// The candidate edges below the limit (key: −cos of their angle).
    edges: Vec<Queued<Eid>>,
    /// Per edge slot: whether it delimits (known for the candidates and
    /// the edges around the candidate vertices).
    delim: Vec<bool>,
    /// Per face slot: twice the vector area (Newell), and the area.
    newell: Vec<V3>,
    area: Vec<f64>,
    /// The candidate vertices (`None`: every vertex).
    vertices: Option<Vec<Vid>>,
}

/// The commit's running state.
struct State {
    newell: Vec<V3>,
    delim: Vec<bool>,
    /// Per face slot: its loop's length (0: not counted yet).
    degree: Vec<u32>,
    /// Per face slot: the face it merged into (`u32::MAX`: none).
    parent: Vec<u32>,
    dead: Vec<Fid>,
    removed: [usize; 2],
}

impl Mesh {
    /// Whether [`dissolve_limited`](Mesh::dissolve_limited) would succeed;
    /// changes nothing.
    ///
    /// # Errors
    /// As [`dissolve_limited`](Mesh::dissolve_limited).
    pub fn check_dissolve_limited(&self, options: &DissolveLimitedOptions) -> Result<()> {
        self.plan_dissolve_limited(options).map(|_| ())
    }

    /// Merge the faces across edges whose faces' normals differ by less
    /// than `options.angle` and which no delimiter keeps, smallest angle
    /// first, then take out the vertices left on chains of two edges that
    /// bend by less (see [`DissolveLimitedOptions`] for the order, the rules and
    /// where meshloom differs from BMesh). Faces stay simple polygons with
    /// one boundary and an area. One undo step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) in the selections;
    /// [`Refusal::Parameter`] for a negative or non-finite angle;
    /// [`Error::AttributeMissing`](crate::Error::AttributeMissing) for a
    /// delimiter column the mesh lacks.
    ///
    /// # Complexity
    /// O(n log n) in the candidate edges and vertices, plus the merged
    /// faces' loops at each merge (the smaller one's).
    ///
    /// ```
    /// use meshloom::model::DissolveLimitedOptions;
    /// use meshloom::shapes::{grid, GridFaces};
    /// // A flat triangulated grid becomes one quad.
    /// let mut mesh = grid(4, 4, GridFaces::Triangles);
    /// let d = mesh.dissolve_limited(&DissolveLimitedOptions::default())?;
    /// assert_eq!((mesh.face_count(), mesh.vertex_count()), (1, 4));
    /// assert_eq!(d.faces.len(), 1);
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn dissolve_limited(&mut self, options: &DissolveLimitedOptions) -> Result<Dissolved> {
        let plan = self.plan_dissolve_limited(options)?;
        journaled!(self.commit_dissolve_limited(&plan))
    }

    /// Check the options, resolve the delimiters, measure the candidates.
    fn plan_dissolve_limited(&self, o: &DissolveLimitedOptions) -> Result<Plan> {
        if !(o.angle.is_finite() && o.angle >= 0.0) {
            return Err(refuse(
                OP,
                FaceKey::new(0, 0),
                Refusal::Parameter("angle must be finite and at least 0"),
            ));
        }
        let limit = o.angle.min(FRAC_PI_2);
        let ds = Delimiters::new(self, &o.delimit)?;
        let faces = self.columns_of(ElementKind::Face);
        let incompatible: Vec<_> = faces
            .cols
            .iter()
            .filter(|(_, c)| c.rule_name() == "Incompatible")
            .map(|(_, c)| &**c)
            .collect();
        let delimits = |e: Eid| {
            let [h, t] = e.halfedges();
            ds.delimits(e)
                || incompatible
                    .iter()
                    .any(|c| !c.same(self.face_of(h).index(), self.face_of(t).index()))
        };
        let edges: Vec<Eid> = match &o.edges {
            Some(keys) => keys
                .iter()
                .map(|&k| self.check_edge(k))
                .collect::<Result<_>>()?,
            None => self.eids().collect(),
        };
        let vertices: Option<Vec<Vid>> = match &o.vertices {
            Some(keys) => Some(
                keys.iter()
                    .map(|&k| self.check_vertex(k))
                    .collect::<Result<_>>()?,
            ),
            None => None,
        };
        let [_, _, edge_slots, face_slots] = self.slot_counts();
        let mut plan = Plan {
            limit,
            boundaries: o.boundaries,
            edges: Vec::new(),
            delim: vec![false; edge_slots],
            newell: vec![[0.0; 3]; face_slots],
            area: vec![0.0; face_slots],
            vertices,
        };
        let mut known = vec![false; face_slots];
        let mut measure = |plan: &mut Plan, f: Fid| {
            if !known[f.index()] {
                known[f.index()] = true;
                let n = self.loop_normal(self.face_halfedge(f)).unwrap_or([0.0; 3]);
                plan.newell[f.index()] = n;
                plan.area[f.index()] = 0.5 * vec3::norm(n);
            }
        };
        let limit_key = -limit.cos();
        for &e in &edges {
            let [h, t] = e.halfedges();
            plan.delim[e.index()] = delimits(e);
            if plan.delim[e.index()] {
                continue;
            }
            let (a, b) = (self.face_of(h), self.face_of(t));
            measure(&mut plan, a);
            measure(&mut plan, b);
            if let Some(key) = angle_key(plan.newell[a.index()], plan.newell[b.index()]) {
                if key < limit_key {
                    plan.edges.push(Queued {
                        key,
                        item: e,
                        version: 0,
                    });
                }
            }
        }
        // The vertex pass reads the delimiters and normals around its
        // candidates.
        if let Some(vs) = &plan.vertices.clone() {
            for &v in vs {
                for h in self.outgoing(v) {
                    plan.delim[h.edge().index()] = delimits(h.edge());
                    for f in [self.face_of(h), self.face_of(h.twin())] {
                        measure(&mut plan, f);
                    }
                }
            }
        } else {
            if o.edges.is_some() {
                for e in self.eids() {
                    plan.delim[e.index()] = delimits(e);
                }
            }
            for f in self.fids() {
                measure(&mut plan, f);
            }
        }
        Ok(plan)
    }

    /// Merge faces, then join vertices, then merge the face values (the
    /// plan's body, in journaling mode `J`).
    fn commit_dissolve_limited<J: Journaling>(&mut self, plan: &Plan) -> Result<Dissolved> {
        let face_slots = plan.newell.len();
        let mut st = State {
            newell: plan.newell.clone(),
            delim: plan.delim.clone(),
            degree: vec![0; face_slots],
            parent: vec![u32::MAX; face_slots],
            dead: Vec::new(),
            removed: [0, 0],
        };
        let mut w = self.writer::<J>();
        merge_faces(&mut w, &mut st, plan);
        let kept = join_vertices(&mut w, &mut st, plan);
        let faces = merge_face_values(&mut w, &mut st, &plan.area);
        w.end_op();
        Ok(Dissolved {
            faces: faces.iter().map(|&f| self.fkey(f)).collect(),
            edges: live_edges(self, &kept),
            removed_vertices: st.removed[0] + kept.len(),
            removed_edges: st.removed[1] + kept.len(),
            removed_faces: st.dead.len(),
        })
    }
}

/// −cos of the angle between two face normals (Newell vectors), `None`
/// when one is zero.
fn angle_key(a: V3, b: V3) -> Option<f64> {
    let (a, b) = (vec3::normalize(a)?, vec3::normalize(b)?);
    Some(-vec3::dot(a, b))
}

/// The angle between two vectors, in `[0, π]` (π/2 when one is zero).
fn angle_between(a: V3, b: V3) -> f64 {
    let c = vec3::norm(vec3::cross(a, b));
    let d = vec3::dot(a, b);
    if c == 0.0 && d == 0.0 {
        FRAC_PI_2
    } else {
        c.atan2(d)
    }
}

impl State {
    /// The loop length of face `f`, counted once.
    fn degree(&mut self, mesh: &Mesh, f: Fid) -> usize {
        let d = &mut self.degree[f.index()];
        if *d == 0 {
            *d = mesh.face_degree(f) as u32;
        }
        *d as usize
    }

    /// The face `f` merged into, in the end.
    fn root(&mut self, f: Fid) -> Fid {
        let mut r = f.index();
        while self.parent[r] != u32::MAX {
            r = self.parent[r] as usize;
        }
        let mut x = f.index();
        while self.parent[x] != u32::MAX {
            let next = self.parent[x] as usize;
            if next != r {
                self.parent[x] = r as u32;
            }
            x = next;
        }
        Fid::new(r as u32)
    }
}

/// The face pass: pop edges smallest angle first, re-measure, merge.
fn merge_faces<J: Journaling>(w: &mut Writer<'_, J>, st: &mut State, plan: &Plan) {
    let limit_key = -plan.limit.cos();
    let mut heap = BinaryHeap::from(plan.edges.clone());
    while let Some(q) = heap.pop() {
        let e = q.item;
        if !w.edge_live(e.index()) {
            continue;
        }
        let [h, t] = e.halfedges();
        let (a, b) = (w.face_of(h), w.face_of(t));
        let Some(now) = angle_key(st.newell[a.index()], st.newell[b.index()]) else {
            continue;
        };
        if now > q.key + 1e-12 {
            if now < limit_key {
                heap.push(Queued { key: now, ..q });
            }
            continue;
        }
        join_faces(w, st, h);
    }
}

/// Merge the faces on the two sides of `h` (all the edges they share go),
/// relabelling the smaller loop; false (nothing changed) when the merged
/// loop would not be simple.
fn join_faces<J: Journaling>(w: &mut Writer<'_, J>, st: &mut State, h: Hid) -> bool {
    let (fa, fb) = (w.face_of(h), w.face_of(h.twin()));
    let (da, db) = (st.degree(w, fa), st.degree(w, fb));
    let (start, small, large, dl) = if da <= db {
        (h, fa, fb, db)
    } else {
        (h.twin(), fb, fa, da)
    };
    let mut ring: Vec<Hid> = w.face_halfedges_from(start).collect();
    let len = ring.len();
    let shared: Vec<bool> = ring.iter().map(|&x| w.face_of(x.twin()) == large).collect();
    let ahead = shared.iter().take_while(|&&s| s).count();
    if ahead == len {
        return false;
    }
    let behind = shared.iter().rev().take_while(|&&s| s).count();
    let k = ahead + behind;
    if shared.iter().filter(|&&s| s).count() != k || len + dl < 2 * k + 3 {
        return false;
    }
    ring.rotate_right(behind);
    let on_large = |u: Vid| w.outgoing(u).any(|o| w.face_of(o) == large);
    if ring[k + 1..].iter().any(|&x| on_large(w.origin(x))) {
        return false;
    }
    let (n, p) = (ring[k], ring[len - 1]);
    let tk = ring[k - 1].twin();
    let m = w.next(ring[0].twin());
    let q = w.prev(tk);
    let (a, b) = (w.origin(ring[0]), w.origin(n));
    if w.vertex_halfedge(a) == ring[0] {
        w.set_vertex_halfedge(a, m);
    }
    if w.vertex_halfedge(b) == tk {
        w.set_vertex_halfedge(b, n);
    }
    w.set_next(p, m);
    w.set_next(q, n);
    for &x in &ring[k..] {
        w.he_mut(x).face = large;
    }
    w.set_face_link(large, n);
    for &x in &ring[1..k] {
        let v = w.origin(x);
        w.free_vertex(v);
    }
    for &x in &ring[..k] {
        w.free_edge(x.edge());
    }
    st.removed[0] += k - 1;
    st.removed[1] += k;
    st.degree[large.index()] = (len + dl - 2 * k) as u32;
    st.newell[large.index()] = vec3::add(st.newell[large.index()], st.newell[small.index()]);
    st.parent[small.index()] = large.index() as u32;
    st.dead.push(small);
    true
}

/// The vertex pass: the candidates with two edges, by angle (or all with
/// `boundaries`), joined where valid; the kept edges.
fn join_vertices<J: Journaling>(w: &mut Writer<'_, J>, st: &mut State, plan: &Plan) -> Vec<Eid> {
    let vertex_slots = w.slot_counts()[0];
    let candidates: Vec<Vid> = match &plan.vertices {
        Some(vs) => vs.clone(),
        None => w.vids().collect(),
    };
    let mut kept = Vec::new();
    if plan.boundaries {
        for &v in &candidates {
            if w.vertex_live(v.index()) && can_join(w, st, v) {
                kept.push(join(w, st, v));
            }
        }
        return kept;
    }
    let mut is_candidate = vec![false; vertex_slots];
    let mut version = vec![0u32; vertex_slots];
    let mut heap = BinaryHeap::new();
    for &v in &candidates {
        is_candidate[v.index()] = true;
        if let Some(c) = bend(w, st, v).filter(|&c| c < plan.limit) {
            heap.push(Queued {
                key: c,
                item: v,
                version: 0,
            });
        }
    }
    while let Some(q) = heap.pop() {
        let v = q.item;
        if q.version != version[v.index()] || !w.vertex_live(v.index()) || !can_join(w, st, v) {
            continue;
        }
        let ends = {
            let o = w.vertex_halfedge(v);
            [w.dest(o), w.dest(w.next(o.twin()))]
        };
        kept.push(join(w, st, v));
        for u in ends {
            if !is_candidate[u.index()] {
                continue;
            }
            version[u.index()] += 1;
            if let Some(c) = bend(w, st, u).filter(|&c| c < plan.limit) {
                heap.push(Queued {
                    key: c,
                    item: u,
                    version: version[u.index()],
                });
            }
        }
    }
    kept
}

/// The two outgoing half-edges of `v` if it has exactly two edges.
fn two_edges(mesh: &Mesh, v: Vid) -> Option<(Hid, Hid)> {
    let o1 = mesh.vertex_halfedge(v);
    let o2 = mesh.next(o1.twin());
    (mesh.next(o2.twin()) == o1 && o2 != o1).then_some((o1, o2))
}

/// How far the chain through `v` (two edges) bends, times the angle
/// between its two faces over 90° when both are faces and neither edge
/// delimits; `None` without two edges or positions.
fn bend(mesh: &Mesh, st: &State, v: Vid) -> Option<f64> {
    let (o1, o2) = two_edges(mesh, v)?;
    let p = mesh.position_slots()?;
    let pv = p[v.index()];
    let a = vec3::sub(p[mesh.dest(o1).index()], pv);
    let b = vec3::sub(p[mesh.dest(o2).index()], pv);
    let bend = std::f64::consts::PI - angle_between(a, b);
    let (x, y) = (mesh.face_of(o1), mesh.face_of(o2));
    let smooth = !mesh.is_hole(x)
        && !mesh.is_hole(y)
        && !st.delim[o1.edge().index()]
        && !st.delim[o2.edge().index()];
    Some(if smooth {
        bend * angle_between(st.newell[x.index()], st.newell[y.index()]) / FRAC_PI_2
    } else {
        bend
    })
}

/// Whether `v` (two edges) can be taken out: both sides keep three sides,
/// no second edge between its neighbours, no folded corner.
fn can_join<J: Journaling>(w: &mut Writer<'_, J>, st: &mut State, v: Vid) -> bool {
    let Some((o1, o2)) = two_edges(w, v) else {
        return false;
    };
    let (u, far) = (w.dest(o1), w.dest(o2));
    let (x, y) = (w.face_of(o1), w.face_of(o2));
    if u == far
        || st.degree(w, x) < 4
        || st.degree(w, y) < 4
        || w.find_halfedge_raw(u, far).is_some()
    {
        return false;
    }
    let Some(p) = w.position_slots() else {
        return true;
    };
    let (a, b) = (
        vec3::sub(p[u.index()], p[v.index()]),
        vec3::sub(p[far.index()], p[v.index()]),
    );
    let (la, lb) = (vec3::norm(a), vec3::norm(b));
    if la == 0.0 || lb == 0.0 {
        return false;
    }
    if (vec3::dot(a, b) / (la * lb)).abs() >= 1.0 - f64::from(f32::EPSILON) {
        return true;
    }
    [(o1, x), (o2, y)]
        .into_iter()
        .all(|(h, f)| w.is_hole(f) || !ear_folds(w, st.newell[f.index()], h))
}

/// Take `v` out (see [`join_at`]), keeping the faces' normals, degrees and
/// the kept edge's delimiter up to date.
fn join<J: Journaling>(w: &mut Writer<'_, J>, st: &mut State, v: Vid) -> Eid {
    let (o1, o2) = two_edges(w, v).expect("checked");
    let (u, far) = (w.dest(o1), w.dest(o2));
    let (x, y) = (w.face_of(o1), w.face_of(o2));
    if let Some(p) = w.position_slots() {
        let (pu, pv, pf) = (p[u.index()], p[v.index()], p[far.index()]);
        // x: far → v → u becomes far → u; y: u → v → far becomes u → far.
        for (f, [a, b, c]) in [(x, [pf, pv, pu]), (y, [pu, pv, pf])] {
            let n = &mut st.newell[f.index()];
            let mut gone = [0.0; 3];
            vec3::newell_edge(&mut gone, a, b);
            vec3::newell_edge(&mut gone, b, c);
            let mut made = [0.0; 3];
            vec3::newell_edge(&mut made, a, c);
            *n = vec3::add(vec3::sub(*n, gone), made);
        }
    }
    let d = st.delim[o1.edge().index()] || st.delim[o2.edge().index()];
    st.delim[o1.edge().index()] = d;
    for f in [x, y] {
        st.degree(w, f);
        st.degree[f.index()] -= 1;
    }
    join_at(w, v)
}

/// Whether cutting the corner at `v` (half-edge `h` leaving it in a face
/// with Newell vector `n`) folds the face: a neighbouring corner flips, or
/// another corner lies in the cut-off triangle (in the face's plane).
fn ear_folds(mesh: &Mesh, n: V3, h: Hid) -> bool {
    let Some(n) = vec3::normalize(n) else {
        return true;
    };
    let p = mesh.position_slots().expect("positions");
    let e1 = vec3::normalize_or_zero(vec3::cross(
        n,
        if n[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        },
    ));
    let e2 = vec3::cross(n, e1);
    let centre = p[mesh.origin(h).index()];
    let at = |v: Vid| {
        let d = vec3::sub(p[v.index()], centre);
        [vec3::dot(d, e1), vec3::dot(d, e2)]
    };
    let hp = mesh.prev_fast(h);
    let (u, w) = (mesh.origin(hp), mesh.dest(h));
    let (pu, pw) = (at(u), at(w));
    let o = [0.0, 0.0];
    if two_edges(mesh, u).is_none() {
        let adj = at(mesh.origin(mesh.prev_fast(hp)));
        if side(adj, pu, o) != side(adj, pu, pw) {
            return true;
        }
    }
    if two_edges(mesh, w).is_none() {
        let adj = at(mesh.dest(mesh.next(h)));
        if side(adj, pw, o) != side(adj, pw, pu) {
            return true;
        }
    }
    let (a, b, c) = if cross2(pu, o, pw) < 0.0 {
        (pw, o, pu)
    } else {
        (pu, o, pw)
    };
    let mut x = mesh.next(h);
    while mesh.dest(x) != u {
        let q = at(mesh.dest(x));
        if cross2(a, b, q) >= 0.0 && cross2(b, c, q) >= 0.0 && cross2(c, a, q) >= 0.0 {
            return true;
        }
        x = mesh.next(x);
    }
    false
}

/// Twice the signed area of the triangle `a b c`.
fn cross2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The sign of [`cross2`].
fn side(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> i8 {
    let s = cross2(a, b, c);
    (s > 0.0) as i8 - (s < 0.0) as i8
}

/// Merge each merged face's values (its parts by area, the survivor
/// first), then free the parts; the merged faces.
fn merge_face_values<J: Journaling>(
    w: &mut Writer<'_, J>,
    st: &mut State,
    area: &[f64],
) -> Vec<Fid> {
    let mut groups: Vec<(Fid, Fid)> = st
        .dead
        .clone()
        .into_iter()
        .map(|f| (st.root(f), f))
        .collect();
    groups.sort_unstable();
    let mut faces = Vec::new();
    let mut i = 0;
    while i < groups.len() {
        let root = groups[i].0;
        let mut members = vec![root];
        while i < groups.len() && groups[i].0 == root {
            members.push(groups[i].1);
            i += 1;
        }
        let total: f64 = members.iter().map(|f| area[f.index()]).sum();
        let inputs: Vec<(usize, f64)> = members
            .iter()
            .map(|f| {
                let share = if total > 0.0 {
                    area[f.index()] / total
                } else {
                    1.0 / members.len() as f64
                };
                (f.index(), share)
            })
            .collect();
        w.attrs.face.merge(root.index(), &inputs);
        faces.push(root);
    }
    for &f in &st.dead {
        w.free_face(f);
    }
    faces
}

#[cfg(test)]
mod tests;
