//! `loop_cut`: new edge loops across an edge ring's quads.

use crate::error::{Refusal, Result};
use crate::keys::{EdgeKey, FaceKey, HalfedgeKey, VertexKey};
use crate::mesh::Mesh;
use crate::ops::refuse;
use crate::vec3::{self, V3};

const OP: &str = "loop_cut";

/// The most cuts one [`Mesh::loop_cut`] makes across each quad.
pub const MAX_CUTS: usize = 1 << 16;

/// Options of [`Mesh::loop_cut`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopCutOptions {
    /// How many loops to cut (1 to [`MAX_CUTS`]).
    pub cuts: usize,
    /// Where the cuts sit along each ring edge, in `(0, 1)` from the start
    /// edge's first half-edge's origin: the parameters `i / (cuts + 1)`
    /// are mapped piecewise linearly so that ½ goes to `factor` (one cut
    /// sits at `factor`; at ½ the cuts are evenly spaced).
    pub factor: f64,
    /// How far the new vertices bulge towards the curve through each ring
    /// edge's ends that leaves them along the surface (a cubic with
    /// tangents perpendicular to the ends' vertex normals): 0 keeps them on
    /// the edge (Blender's "smoothness"); finite.
    pub smoothness: f64,
}

impl Default for LoopCutOptions {
    fn default() -> LoopCutOptions {
        LoopCutOptions {
            cuts: 1,
            factor: 0.5,
            smoothness: 0.0,
        }
    }
}

/// What [`Mesh::loop_cut`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoopCut {
    /// The new vertices, ring edge by ring edge in ring order, `cuts` on
    /// each from its start (ring edge `k`'s cut `i` is `k · cuts + i`).
    pub vertices: Vec<VertexKey>,
    /// The new edges of the loops, quad by quad in ring order, `cuts` in
    /// each (quad `k`'s cut `i` joins ring edges `k` and `k + 1`).
    pub edges: Vec<EdgeKey>,
    /// The ring's edges as they were (each is now the last piece of its
    /// edge), and whether the ring closed.
    pub ring: Vec<EdgeKey>,
    /// Whether the ring closed on itself (then every cut is a closed loop).
    pub closed: bool,
}

/// A checked loop cut.
struct Plan {
    /// The ring's half-edges, each pointing the way its cuts count (its
    /// face is the quad after it).
    ring: Vec<HalfedgeKey>,
    closed: bool,
    /// The quads, `quads[k]` between ring half-edges `k` and `k + 1`.
    quads: Vec<FaceKey>,
    /// The cut parameters, increasing in `(0, 1)`.
    ts: Vec<f64>,
    /// Per ring half-edge, per cut: where its new vertex goes (with
    /// smoothness), if the mesh has positions.
    points: Option<Vec<V3>>,
}

impl Mesh {
    /// Whether [`loop_cut`](Mesh::loop_cut) would succeed; changes nothing.
    ///
    /// # Errors
    /// As [`loop_cut`](Mesh::loop_cut).
    pub fn check_loop_cut(&self, e: EdgeKey, options: &LoopCutOptions) -> Result<()> {
        self.plan_loop_cut(e, options).map(|_| ())
    }

    /// Cut the quads of the edge ring through `e` (see
    /// [`Mesh::edge_ring`]) with `options.cuts` new edge loops: every ring
    /// edge is split at the cut parameters and each quad between two ring
    /// edges is split along the new vertices. The faces where an open ring
    /// stops (not quads, or holes) just gain the new vertices as corners.
    ///
    /// Attributes follow [`split_edge`](Mesh::split_edge) and
    /// [`split_face`](Mesh::split_face): new vertices and their corners
    /// interpolate the ring edge's ends (so a UV island stays continuous
    /// and a seam stays a seam), ring edges split by length, quads by area,
    /// and the loops' edges get `interpolate` of nothing. One undo step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey);
    /// [`Refusal::Parameter`] for `cuts` outside `1..=MAX_CUTS`, a
    /// `factor` outside `(0, 1)` or a non-finite `smoothness`;
    /// [`Refusal::NotQuads`] when neither side of `e` is a quad;
    /// [`Refusal::Crossing`] when the ring passes through a quad or an edge
    /// twice, or comes back reversed (a Möbius band).
    ///
    /// # Complexity
    /// O(ring length × (cuts + degrees met)), whatever the mesh's size.
    ///
    /// ```
    /// use meshloom::model::LoopCutOptions;
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mut mesh = grid(4, 4, GridFaces::Quads);
    /// let e = mesh.edges().next().unwrap();
    /// let cut = mesh.loop_cut(e, &LoopCutOptions { cuts: 2, ..Default::default() })?;
    /// // Five ring edges across four quads: 2 × 5 vertices, 2 × 4 edges.
    /// assert_eq!((cut.vertices.len(), cut.edges.len()), (10, 8));
    /// assert_eq!((mesh.vertex_count(), mesh.face_count()), (25 + 10, 16 + 8));
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn loop_cut(&mut self, e: EdgeKey, options: &LoopCutOptions) -> Result<LoopCut> {
        let plan = self.plan_loop_cut(e, options)?;
        self.transaction(|m| m.commit_loop_cut(&plan))
    }

    /// Check `e` and `options` and walk the ring.
    fn plan_loop_cut(&self, e: EdgeKey, o: &LoopCutOptions) -> Result<Plan> {
        self.edge(e)?;
        if !(1..=MAX_CUTS).contains(&o.cuts) {
            return Err(refuse(
                OP,
                e,
                Refusal::Parameter("cuts must be in 1..=65536"),
            ));
        }
        if !(o.factor > 0.0 && o.factor < 1.0) {
            return Err(refuse(
                OP,
                e,
                Refusal::Parameter("factor must be in (0, 1)"),
            ));
        }
        if !o.smoothness.is_finite() {
            return Err(refuse(
                OP,
                e,
                Refusal::Parameter("smoothness must be finite"),
            ));
        }
        let (ring, closed, quads) = self.ring_quads(e)?;
        let ts = cut_parameters(o.cuts, o.factor);
        let points = self.has_positions().then(|| {
            let mut points = Vec::with_capacity(ring.len() * ts.len());
            for &h in &ring {
                let h = self.halfedge(h).expect("a ring half-edge is live");
                let ends = [h.origin().key(), h.dest().key()];
                let [p0, p1] = ends.map(|v| self.position(v).expect("positions"));
                let [n0, n1] = ends.map(|v| self.corner_normal_sum(v));
                for &t in &ts {
                    points.push(smooth_point(p0, p1, n0, n1, t, o.smoothness));
                }
            }
            points
        });
        Ok(Plan {
            ring,
            closed,
            quads,
            ts,
            points,
        })
    }

    /// The ring through `e` as half-edges pointing the way its cuts count,
    /// whether it closed, and its quads; refused if it crosses itself.
    fn ring_quads(&self, e: EdgeKey) -> Result<(Vec<HalfedgeKey>, bool, Vec<FaceKey>)> {
        let chain = self.edge_ring_halfedges(e)?;
        let ring: Vec<HalfedgeKey> = chain.keys.iter().map(|h| h.key()).collect();
        let mut quads: Vec<FaceKey> = chain.keys.iter().map(|h| h.face().key()).collect();
        if !chain.closed {
            quads.pop();
        }
        if quads.is_empty() {
            return Err(refuse(OP, e, Refusal::NotQuads));
        }
        let last = chain.keys[chain.keys.len() - 1];
        let reversed = chain.closed && last.next().next().twin().key() != ring[0];
        let mut edges: Vec<EdgeKey> = chain.keys.iter().map(|h| h.edge().key()).collect();
        edges.sort_unstable();
        edges.dedup();
        let mut faces = quads.clone();
        faces.sort_unstable();
        faces.dedup();
        if reversed || edges.len() != ring.len() || faces.len() != quads.len() {
            return Err(refuse(OP, e, Refusal::Crossing));
        }
        Ok((ring, chain.closed, quads))
    }

    /// The sum of the unit normals of the faces around `v` (zero without
    /// any), for the smooth cut's tangents.
    fn corner_normal_sum(&self, v: VertexKey) -> V3 {
        let mut n = [0.0; 3];
        let Ok(v) = self.check_vertex(v) else {
            return n;
        };
        for h in self.outgoing(v).filter(|&h| !self.in_hole(h)) {
            if let Some(unit) = self.loop_normal(h).and_then(vec3::normalize) {
                n = vec3::add(n, unit);
            }
        }
        n
    }

    /// Split the ring's edges, then its quads (inside a transaction).
    fn commit_loop_cut(&mut self, plan: &Plan) -> Result<LoopCut> {
        let cuts = plan.ts.len();
        let ring_edges: Vec<EdgeKey> = plan
            .ring
            .iter()
            .map(|&h| self.halfedge(h).map(|h| h.edge().key()))
            .collect::<Result<_>>()?;
        let mut vertices = Vec::with_capacity(plan.ring.len() * cuts);
        for (k, &h) in plan.ring.iter().enumerate() {
            let made = self.split_along(h, &plan.ts)?;
            if let Some(points) = &plan.points {
                for (i, &v) in made.iter().enumerate() {
                    self.set_position(v, points[k * cuts + i])?;
                }
            }
            vertices.extend(made);
        }
        let mut edges = Vec::with_capacity(plan.quads.len() * cuts);
        for (k, &q) in plan.quads.iter().enumerate() {
            let next = (k + 1) % plan.ring.len();
            let a = &vertices[k * cuts..(k + 1) * cuts];
            let b = &vertices[next * cuts..(next + 1) * cuts];
            self.split_quad_along(q, a, b, &mut edges)?;
        }
        Ok(LoopCut {
            vertices,
            edges,
            ring: ring_edges,
            closed: plan.closed,
        })
    }

    /// Split the edge of half-edge `h` at parameters `ts` (increasing,
    /// from `h`'s origin); the new vertices in that order.
    fn split_along(&mut self, h: HalfedgeKey, ts: &[f64]) -> Result<Vec<VertexKey>> {
        let (a, b) = {
            let h = self.halfedge(h)?;
            (h.origin().key(), h.dest().key())
        };
        let mut made = Vec::with_capacity(ts.len());
        let (mut from, mut done) = (a, 0.0);
        for &t in ts {
            // The piece from `from` to `b`, split at the share of it that
            // reaches `t`.
            let piece = self.find_halfedge(from, b)?.expect("the remaining piece");
            let s = (t - done) / (1.0 - done);
            let e = self.halfedge(piece)?.edge();
            let forward = e.halfedge(0).key() == piece;
            let v = self.split_edge(e.key(), if forward { s } else { 1.0 - s })?;
            made.push(v);
            (from, done) = (v, t);
        }
        Ok(made)
    }

    /// Split quad `q` (with the cut vertices `a` on one ring side and `b`
    /// on the other, in matching order) by the edges `a[i]–b[i]`.
    fn split_quad_along(
        &mut self,
        q: FaceKey,
        a: &[VertexKey],
        b: &[VertexKey],
        edges: &mut Vec<EdgeKey>,
    ) -> Result<()> {
        let mut f = q;
        for (i, (&x, &y)) in a.iter().zip(b).enumerate() {
            let h = self.split_face(f, x, y)?;
            edges.push(self.halfedge(h)?.edge().key());
            // The rest to cut holds the next pair: on one side of the new
            // edge or the other.
            if let Some(&nx) = a.get(i + 1) {
                let h = self.halfedge(h)?;
                let g = h.face();
                f = if g.vertices().any(|v| v == nx) {
                    g.key()
                } else {
                    h.twin().face().key()
                };
            }
        }
        Ok(())
    }
}

/// The cut parameters: `i / (cuts + 1)`, mapped piecewise linearly so that
/// ½ goes to `factor`.
fn cut_parameters(cuts: usize, factor: f64) -> Vec<f64> {
    (1..=cuts)
        .map(|i| {
            let t = i as f64 / (cuts + 1) as f64;
            if t <= 0.5 {
                2.0 * factor * t
            } else {
                factor + (t - 0.5) * 2.0 * (1.0 - factor)
            }
        })
        .collect()
}

/// The point at `t` from `p0` to `p1`, moved by `smoothness` towards the
/// cubic Hermite curve whose tangents at the ends are the edge with its
/// part along the end's normal sum (`n0`, `n1`) taken out.
fn smooth_point(p0: V3, p1: V3, n0: V3, n1: V3, t: f64, smoothness: f64) -> V3 {
    let line = vec3::axpy(p0, t, vec3::sub(p1, p0));
    if smoothness == 0.0 {
        return line;
    }
    let d = vec3::sub(p1, p0);
    let tangent = |n: V3| match vec3::normalize(n) {
        Some(n) => {
            let along = vec3::sub(d, vec3::scale(n, vec3::dot(d, n)));
            vec3::normalize(along).map_or(d, |u| vec3::scale(u, vec3::norm(d)))
        }
        None => d,
    };
    let (m0, m1) = (tangent(n0), tangent(n1));
    let (t2, t3) = (t * t, t * t * t);
    let (h00, h10, h01, h11) = (
        2.0 * t3 - 3.0 * t2 + 1.0,
        t3 - 2.0 * t2 + t,
        -2.0 * t3 + 3.0 * t2,
        t3 - t2,
    );
    let curve: V3 = std::array::from_fn(|k| h00 * p0[k] + h10 * m0[k] + h01 * p1[k] + h11 * m1[k]);
    vec3::axpy(line, smoothness, vec3::sub(curve, line))
}

#[cfg(test)]
mod tests;
