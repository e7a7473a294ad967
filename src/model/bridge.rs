//! `bridge_loops`: join two loops or chains of boundary edges by a band of
//! faces (BMesh's `bmo_bridge.cc`).
//!
//! A selection is read as one run of hole half-edges: consecutive in their
//! hole, either the hole's whole cycle (a closed loop) or a part of it (an
//! open chain). The band's faces take those half-edges, so its winding is
//! the one the faces beside the loops already have: loop A is walked in
//! its hole's order and loop B against its own, which is the only pairing
//! that makes an oriented surface. Loops of different lengths are paired
//! by arc length (each step advances the longer loop, and the shorter one
//! where its next vertex is nearer), so the band has quads where both
//! advance and triangles where only the longer one does; BMesh pads the
//! shorter loop alike and then triangulates and beautifies the band,
//! which meshloom leaves to the caller.

use std::collections::HashSet;

use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::{EdgeKey, FaceKey, VertexKey};
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::Mesh;
use crate::ops::refuse;
use crate::vec3::{self, V3};

const OP: &str = "bridge_loops";

/// The most cuts one [`Mesh::bridge_loops`] makes inside its band.
pub const MAX_BRIDGE_CUTS: usize = 1 << 12;

/// Options of [`Mesh::bridge_loops`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BridgeOptions {
    /// How many loops of new vertices run inside the band, between the two
    /// loops (0 to [`MAX_BRIDGE_CUTS`]).
    pub cuts: usize,
    /// For closed loops: how many vertices further along loop B its first
    /// paired vertex sits after the best (shortest) pairing; any sign.
    /// Open chains pair end to end and ignore it.
    pub twist: isize,
}

/// What [`Mesh::bridge_loops`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Bridge {
    /// The band's faces, column by column along loop A, each column from
    /// loop A's side to loop B's (`cuts + 1` faces a column).
    pub faces: Vec<FaceKey>,
    /// The new vertices inside the band, column by column (pair by pair),
    /// each from loop A's side (`cuts` a pair).
    pub vertices: Vec<VertexKey>,
    /// The new edges: per pair, the `cuts + 1` rungs from loop A to loop B;
    /// then per column the `cuts` edges along the band.
    pub edges: Vec<EdgeKey>,
    /// The holes beside the band: none for closed loops (their holes are
    /// gone); for open chains one when they were on two holes, two when
    /// they were on one.
    pub holes: Vec<FaceKey>,
    /// Whether the two loops were closed.
    pub closed: bool,
}

/// A selection read as one run of hole half-edges, in hole order.
pub(super) struct Run {
    pub(super) hs: Vec<Hid>,
    pub(super) closed: bool,
    pub(super) hole: Fid,
}

/// One side of the band: its vertices in pairing order and the half-edge
/// between vertices `i` and `i + 1` (loop A: `vs[i] → vs[i+1]`; loop B:
/// `vs[i+1] → vs[i]`).
struct Side {
    vs: Vec<Vid>,
    hs: Vec<Hid>,
}

/// A checked bridge.
struct Plan {
    a: Side,
    b: Side,
    closed: bool,
    cuts: usize,
    /// The pairs `(i, j)` of A's and B's vertices, one per rung, in order
    /// (for closed loops the last pair is the first one again).
    pairs: Vec<(usize, usize)>,
    /// Open chains: the hole half-edges before and after each chain.
    around: Option<[Hid; 4]>,
    holes: [Fid; 2],
}

impl Mesh {
    /// Whether [`bridge_loops`](Mesh::bridge_loops) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`bridge_loops`](Mesh::bridge_loops).
    pub fn check_bridge_loops(
        &self,
        edges_a: &[EdgeKey],
        edges_b: &[EdgeKey],
        options: &BridgeOptions,
    ) -> Result<()> {
        self.plan_bridge(edges_a, edges_b, options).map(|_| ())
    }

    /// Join two loops of boundary edges by a band of quads: `edges_a` and
    /// `edges_b` each a closed loop (a hole's whole boundary; the holes are
    /// consumed) or an open chain of consecutive boundary edges (the holes
    /// beside the band are joined or split). Vertex `k` of loop A is paired
    /// with vertex `k` of loop B (closed loops: rotated for the shortest
    /// rungs, then by `twist`); loops of different lengths get triangles
    /// where only the longer one advances. `cuts` loops of new vertices
    /// run inside the band, spaced evenly on the straight rungs.
    ///
    /// The band takes the loops' boundary half-edges, so it is oriented as
    /// the faces beside them (BMesh votes on the winding the same way).
    ///
    /// Attributes (BMesh's `BM_face_copy_shared` idea): a band face copies
    /// the face beside its column's edge of loop A (its material); a band
    /// corner at a loop vertex copies the corner of the face across the
    /// loop edge at that vertex (so each side of the band continues the UV
    /// island beside it; where the column has no edge on that loop, the
    /// loop's nearest edge at the vertex); a cut vertex interpolates its
    /// pair's two vertices, and its corners the two loop corners of their
    /// column; new edges get `interpolate` of nothing. One undo step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Empty`] for
    /// an empty selection; [`Refusal::Boundary`] for an edge with no hole
    /// beside it; [`Refusal::Parameter`] when a selection is not one run of
    /// boundary edges, for one closed loop and one open chain, and for
    /// `cuts` over [`MAX_BRIDGE_CUTS`]; [`Refusal::NonManifold`] for a
    /// loop passing a vertex twice; [`Refusal::Adjacent`] when the loops
    /// share a vertex; [`Refusal::EdgeExists`] when a rung (with no cuts)
    /// would join two vertices already joined.
    ///
    /// # Complexity
    /// O(loop length × (cuts + 1)), plus O(hole sizes) for open chains and
    /// O(loop length²) at worst for choosing the rotation of closed loops.
    ///
    /// ```
    /// use meshloom::model::BridgeOptions;
    /// use meshloom::Mesh;
    /// // Two strips of three quads, at y in [0, 1] and [2, 3].
    /// let p: Vec<[f64; 3]> = (0..16).map(|i| [(i % 4) as f64, (i / 4) as f64, 0.0]).collect();
    /// let quad = |i: u32| vec![i, i + 1, i + 5, i + 4];
    /// let mut mesh = Mesh::from_polygons(&p, &[quad(0), quad(1), quad(2), quad(8), quad(9), quad(10)])?;
    /// let vs: Vec<_> = mesh.vertices().collect();
    /// let chain = |m: &Mesh, row: usize| -> Vec<_> {
    ///     (0..3).map(|x| {
    ///         let h = m.find_halfedge(vs[4 * row + x], vs[4 * row + x + 1]).unwrap().unwrap();
    ///         m.halfedge(h).unwrap().edge().key()
    ///     }).collect()
    /// };
    /// let (a, b) = (chain(&mesh, 1), chain(&mesh, 2));
    /// let made = mesh.bridge_loops(&a, &b, &BridgeOptions { cuts: 1, ..Default::default() })?;
    /// // One strip of three rows: two new rows of quads, four new vertices.
    /// assert_eq!((made.faces.len(), made.vertices.len()), (6, 4));
    /// assert_eq!((mesh.face_count(), mesh.hole_count()), (12, 1));
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn bridge_loops(
        &mut self,
        edges_a: &[EdgeKey],
        edges_b: &[EdgeKey],
        options: &BridgeOptions,
    ) -> Result<Bridge> {
        let plan = self.plan_bridge(edges_a, edges_b, options)?;
        journaled!(self.commit_bridge(&plan))
    }

    /// Check the selections and options; pair the loops.
    fn plan_bridge(&self, ea: &[EdgeKey], eb: &[EdgeKey], o: &BridgeOptions) -> Result<Plan> {
        let ra = self.boundary_run(ea, OP)?;
        let rb = self.boundary_run(eb, OP)?;
        let name = ea[0];
        if o.cuts > MAX_BRIDGE_CUTS {
            return Err(refuse(
                OP,
                name,
                Refusal::Parameter("cuts must be at most 4096"),
            ));
        }
        if ra.closed != rb.closed {
            return Err(refuse(
                OP,
                name,
                Refusal::Parameter("both loops must be closed or both open"),
            ));
        }
        let a = self.side(&ra, false);
        let mut b = self.side(&rb, true);
        let in_a: HashSet<Vid> = a.vs.iter().copied().collect();
        if b.vs.iter().any(|v| in_a.contains(v)) {
            return Err(refuse(OP, name, Refusal::Adjacent));
        }
        let closed = ra.closed;
        let pairs = if closed {
            let r = self.best_rotation(&a, &b);
            let n = b.vs.len() as isize;
            rotate(&mut b, (r as isize + o.twist).rem_euclid(n) as usize);
            pair_up(&self.arc_params(&a.vs, true), &self.arc_params(&b.vs, true))
        } else {
            pair_up(
                &self.arc_params(&a.vs, false),
                &self.arc_params(&b.vs, false),
            )
        };
        let at = |s: &Side, i: usize| s.vs[i % s.vs.len()];
        if o.cuts == 0 {
            for &(i, j) in &pairs {
                if self.find_halfedge_raw(at(&a, i), at(&b, j)).is_some() {
                    return Err(refuse(OP, name, Refusal::EdgeExists));
                }
            }
        }
        let around = (!closed).then(|| {
            let (a0, an) = (ra.hs[0], ra.hs[ra.hs.len() - 1]);
            let (b0, bn) = (rb.hs[0], rb.hs[rb.hs.len() - 1]);
            [self.prev(a0), self.next(an), self.prev(b0), self.next(bn)]
        });
        Ok(Plan {
            a,
            b,
            closed,
            cuts: o.cuts,
            pairs,
            around,
            holes: [ra.hole, rb.hole],
        })
    }

    /// `edges` as one run of hole half-edges, checked.
    pub(super) fn boundary_run(&self, edges: &[EdgeKey], op: &'static str) -> Result<Run> {
        let Some(&name) = edges.first() else {
            return Err(refuse(op, EdgeKey::new(0, 0), Refusal::Empty));
        };
        let mut set = HashSet::with_capacity(edges.len());
        let mut first = None;
        for &ek in edges {
            let e = self.check_edge(ek)?;
            let h = e
                .halfedges()
                .into_iter()
                .find(|&h| self.in_hole(h))
                .ok_or_else(|| refuse(op, ek, Refusal::Boundary))?;
            first.get_or_insert(h);
            set.insert(h);
        }
        let not_a_run = || {
            refuse(
                op,
                name,
                Refusal::Parameter("the edges must be one run of consecutive boundary edges"),
            )
        };
        let followers: HashSet<Hid> = set.iter().map(|&h| self.next(h)).collect();
        let mut starts = set.iter().filter(|h| !followers.contains(h));
        let (start, closed) = match (starts.next(), starts.next()) {
            (Some(&s), None) => (s, false),
            // A closed loop starts at the first edge given.
            (None, _) => (first.expect("not empty"), true),
            _ => return Err(not_a_run()),
        };
        let mut hs = vec![start];
        let mut h = self.next(start);
        while h != start && set.contains(&h) && hs.len() <= set.len() {
            hs.push(h);
            h = self.next(h);
        }
        if hs.len() != set.len() || closed && h != start {
            return Err(not_a_run());
        }
        let mut vs: Vec<Vid> = hs.iter().map(|&h| self.origin(h)).collect();
        if !closed {
            vs.push(self.dest(hs[hs.len() - 1]));
        }
        vs.sort_unstable();
        if vs.windows(2).any(|w| w[0] == w[1]) {
            return Err(refuse(op, name, Refusal::NonManifold));
        }
        Ok(Run {
            hole: self.face_of(start),
            hs,
            closed,
        })
    }

    /// A run as a side of the band: loop A in hole order, loop B against it.
    fn side(&self, run: &Run, reverse: bool) -> Side {
        let mut vs: Vec<Vid> = run.hs.iter().map(|&h| self.origin(h)).collect();
        if !run.closed {
            vs.push(self.dest(run.hs[run.hs.len() - 1]));
        }
        let mut hs = run.hs.clone();
        if reverse {
            vs.reverse();
            hs.reverse();
            if run.closed {
                // vs[0] stays first: hs[i] must join vs[i] and vs[i + 1].
                vs.rotate_right(1);
            }
        }
        Side { vs, hs }
    }

    /// Normalized arc-length parameters of a loop's vertices (closed: the
    /// first vertex again at 1); by index without positions or length.
    fn arc_params(&self, vs: &[Vid], closed: bool) -> Vec<f64> {
        let n = vs.len() + usize::from(closed);
        let uniform = |k: usize| (0..k).map(|i| i as f64 / (k - 1) as f64).collect();
        let Some(pos) = self.position_slots() else {
            return uniform(n);
        };
        let mut s = vec![0.0];
        for i in 1..n {
            let d = vec3::dist2(pos[vs[i - 1].index()], pos[vs[i % vs.len()].index()]).sqrt();
            s.push(s[i - 1] + d);
        }
        let total = s[n - 1];
        if !(total > 0.0 && total.is_finite()) {
            return uniform(n);
        }
        s.iter().map(|x| x / total).collect()
    }

    /// The rotation of closed loop B whose pairing with A has the shortest
    /// rungs in total (BMesh's `bm_bridge_best_rotation`).
    fn best_rotation(&self, a: &Side, b: &Side) -> usize {
        let Some(pos) = self.position_slots() else {
            return 0;
        };
        let pa = self.arc_params(&a.vs, true);
        let pb = self.arc_params(&b.vs, true);
        let (na, nb) = (a.vs.len(), b.vs.len());
        let mut best = (f64::INFINITY, 0);
        for r in 0..nb {
            // B's parameters from vertex r on.
            let shifted: Vec<f64> = (0..=nb)
                .map(|k| {
                    let x = pb[(r + k) % nb] - pb[r];
                    if k == nb {
                        1.0
                    } else if x < 0.0 {
                        x + 1.0
                    } else {
                        x
                    }
                })
                .collect();
            let mut cost = 0.0;
            let pairs = pair_up(&pa, &shifted);
            // The last pair is the first again.
            for &(i, j) in &pairs[..pairs.len() - 1] {
                let (va, vb) = (a.vs[i % na], b.vs[(r + j) % nb]);
                cost += vec3::dist2(pos[va.index()], pos[vb.index()]).sqrt();
                if cost >= best.0 {
                    break;
                }
            }
            if cost < best.0 {
                best = (cost, r);
            }
        }
        best.1
    }
}

/// Side `s` (closed) starting at its vertex `r`.
fn rotate(s: &mut Side, r: usize) {
    s.vs.rotate_left(r);
    s.hs.rotate_left(r);
}

/// Pair two polylines' vertices by their parameters `pa`, `pb` (each from 0
/// to 1): from `(0, 0)` to the last pair, each step advances the longer one
/// and the shorter one exactly as often as it has edges, preferring the
/// step that keeps the parameters nearest.
fn pair_up(pa: &[f64], pb: &[f64]) -> Vec<(usize, usize)> {
    let (na, nb) = (pa.len() - 1, pb.len() - 1);
    let swap = nb > na;
    let (long, short) = if swap { (pb, pa) } else { (pa, pb) };
    let (nl, ns) = (long.len() - 1, short.len() - 1);
    let mut pairs = vec![(0, 0)];
    let mut j = 0;
    for i in 0..nl {
        let (left_l, left_s) = (nl - i, ns - j);
        let advance = left_s == left_l
            || left_s > 0 && (short[j + 1] - long[i + 1]).abs() <= (short[j] - long[i + 1]).abs();
        if advance {
            j += 1;
        }
        pairs.push((i + 1, j));
    }
    if swap {
        pairs.iter_mut().for_each(|p| *p = (p.1, p.0));
    }
    pairs
}

/// The new elements of a bridge, by slot.
struct Made {
    /// Per pair, per cut: the new vertex.
    verts: Vec<Vid>,
    /// Per pair, per row: the rung from row `r` to `r + 1` (half-edge 0
    /// going up, from loop A's side).
    rungs: Vec<Eid>,
    /// Per column, per cut: the edge along the band (half-edge 0 going
    /// along loop A).
    rows: Vec<Eid>,
    /// Per column, per row: the face.
    faces: Vec<Fid>,
}

impl Mesh {
    /// Build the band, relink the holes, run the attribute rules (the
    /// plan's body, in journaling mode `J`).
    fn commit_bridge<J: Journaling>(&mut self, plan: &Plan) -> Result<Bridge> {
        let mut w = self.writer::<J>();
        let c = plan.cuts;
        let columns = plan.pairs.len() - 1;
        let rungs_n = if plan.closed { columns } else { columns + 1 };
        let made = Made {
            verts: (0..rungs_n * c).map(|_| w.alloc_vertex()).collect(),
            rungs: (0..rungs_n * (c + 1)).map(|_| w.alloc_edge()).collect(),
            rows: (0..columns * c).map(|_| w.alloc_edge()).collect(),
            faces: (0..columns * (c + 1))
                .map(|_| w.alloc_face(false))
                .collect(),
        };
        let g = Grid { plan, made: &made };
        for k in 0..columns {
            for r in 0..=c {
                let cycle = g.cell(k, r);
                let f = made.faces[k * (c + 1) + r];
                for (n, x) in cycle.iter().enumerate() {
                    let next = cycle[(n + 1) % cycle.len()].h;
                    w.set_he(
                        x.h,
                        HalfedgeRecord {
                            origin: x.v,
                            next,
                            face: f,
                        },
                    );
                }
                w.set_face_link(f, cycle[0].h);
            }
        }
        for k in 0..rungs_n {
            for r in 1..=c {
                let up = made.rungs[k * (c + 1) + r].halfedge(0);
                *w.v_halfedge_mut(made.verts[k * c + r - 1]) = up;
            }
        }
        let holes = w.relink_holes(plan, &g);
        // Open chains: the new vertices on the outer rungs.
        let ends = if plan.closed { 0 } else { c };
        let outer = made.verts[..ends]
            .iter()
            .chain(&made.verts[made.verts.len() - ends..]);
        for v in plan.a.vs.iter().chain(&plan.b.vs).chain(outer) {
            w.point_at_hole(*v);
        }
        bridge_attributes(&mut w, &g);
        w.end_op();
        Ok(Bridge {
            faces: made.faces.iter().map(|&f| w.fkey(f)).collect(),
            vertices: made.verts.iter().map(|&v| w.vkey(v)).collect(),
            edges: made
                .rungs
                .iter()
                .chain(&made.rows)
                .map(|&e| w.ekey(e))
                .collect(),
            holes: holes.into_iter().map(|h| w.fkey(h)).collect(),
            closed: plan.closed,
        })
    }
}

impl<J: Journaling> crate::mesh::Writer<'_, J> {
    /// Closed loops: free both holes. Open chains: the outer rungs join
    /// the holes' remaining boundaries (one hole from two, or two from
    /// one); returns the holes beside the band.
    fn relink_holes(&mut self, plan: &Plan, g: &Grid<'_>) -> Vec<Fid> {
        let [ha, hb] = plan.holes;
        let Some([prev_a, next_a, prev_b, next_b]) = plan.around else {
            self.free_face(ha);
            self.free_face(hb);
            return Vec::new();
        };
        let c = plan.cuts;
        let last = plan.pairs.len() - 1;
        // Up the first rung column, down the last one.
        let up: Vec<Hid> = (0..=c).map(|r| g.rung(0, r).halfedge(0)).collect();
        let down: Vec<Hid> = (0..=c).rev().map(|r| g.rung(last, r).halfedge(1)).collect();
        let chain =
            |w: &mut Self, from: Hid, hs: &[Hid], to: Hid, origin: &dyn Fn(usize) -> Vid| {
                w.set_next(from, hs[0]);
                for (n, &h) in hs.iter().enumerate() {
                    let next = hs.get(n + 1).copied().unwrap_or(to);
                    w.set_he(
                        h,
                        HalfedgeRecord {
                            origin: origin(n),
                            next,
                            face: ha,
                        },
                    );
                }
            };
        chain(self, prev_a, &up, next_b, &|n| g.vertex(0, n));
        chain(self, prev_b, &down, next_a, &|n| g.vertex(last, c + 1 - n));
        self.set_face_link(ha, up[0]);
        // One hole from two (B's half-edges join A's), or two from one
        // (the cycle through the down rungs gets a new hole).
        let (other, kept) = if ha == hb {
            let h2 = self.alloc_face(true);
            self.set_face_link(h2, down[0]);
            (h2, vec![ha, h2])
        } else {
            (ha, vec![ha])
        };
        let mut h = down[0];
        loop {
            self.he_mut(h).face = other;
            h = self.next(h);
            if h == down[0] {
                break;
            }
        }
        if ha != hb {
            self.free_face(hb);
        }
        kept
    }
}

/// The band's grid: rows `0..=cuts + 1` from loop A to loop B, pairs along.
struct Grid<'a> {
    plan: &'a Plan,
    made: &'a Made,
}

impl Grid<'_> {
    /// Pair `k`'s indices into A and B (wrapped for closed loops).
    fn pair(&self, k: usize) -> (usize, usize) {
        let (i, j) = self.plan.pairs[k];
        (i % self.plan.a.vs.len(), j % self.plan.b.vs.len())
    }

    /// The rung pair index of pair `k` (the last pair of closed loops is
    /// the first).
    fn rung_pair(&self, k: usize) -> usize {
        if self.plan.closed && k == self.plan.pairs.len() - 1 {
            0
        } else {
            k
        }
    }

    /// The vertex at pair `k`, row `r`.
    fn vertex(&self, k: usize, r: usize) -> Vid {
        let (i, j) = self.pair(k);
        let c = self.plan.cuts;
        match r {
            0 => self.plan.a.vs[i],
            _ if r == c + 1 => self.plan.b.vs[j],
            _ => self.made.verts[self.rung_pair(k) * c + r - 1],
        }
    }

    /// The rung at pair `k` from row `r` to `r + 1`.
    fn rung(&self, k: usize, r: usize) -> Eid {
        self.made.rungs[self.rung_pair(k) * (self.plan.cuts + 1) + r]
    }

    /// Whether column `k` advances on loop A, on loop B.
    fn advances(&self, k: usize) -> (bool, bool) {
        let (p, q) = (self.plan.pairs[k], self.plan.pairs[k + 1]);
        (p.0 != q.0, p.1 != q.1)
    }

    /// The half-edges of cell (column `k`, row `r`) in order, each with
    /// the corner it is: its vertex, whether at pair `k + 1` (else `k`),
    /// and its row.
    fn cell(&self, k: usize, r: usize) -> Vec<CellCorner> {
        let c = self.plan.cuts;
        let (on_a, on_b) = self.advances(k);
        let corner = |h: Hid, side: usize, row: usize| CellCorner {
            h,
            v: self.vertex(k + side, row),
            side,
            row,
        };
        let (a, b) = (&self.plan.a.hs, &self.plan.b.hs);
        let mut out = Vec::with_capacity(4);
        if r > 0 {
            out.push(corner(self.made.rows[k * c + r - 1].halfedge(0), 0, r));
        } else if on_a {
            out.push(corner(a[self.plan.pairs[k].0 % a.len()], 0, 0));
        }
        out.push(corner(self.rung(k + 1, r).halfedge(0), 1, r));
        if r < c {
            out.push(corner(self.made.rows[k * c + r].halfedge(1), 1, r + 1));
        } else if on_b {
            out.push(corner(b[self.plan.pairs[k].1 % b.len()], 1, c + 1));
        }
        out.push(corner(self.rung(k, r).halfedge(1), 0, r + 1));
        out
    }
}

/// A corner of a band cell: its half-edge and vertex, whether it sits at
/// the column's second pair, and its row.
struct CellCorner {
    h: Hid,
    v: Vid,
    side: usize,
    row: usize,
}

/// The corners copied into column `k` at its two pairs from loop A's
/// faces (`[at pair k, at pair k + 1]`) and from loop B's, and the face
/// its cells copy; read before the commit changed nothing they name (the
/// faces beside the loops keep their half-edges).
fn column_sources(m: &Mesh, g: &Grid<'_>, k: usize) -> ([Hid; 2], [Hid; 2], Fid) {
    let (on_a, on_b) = g.advances(k);
    let (i, j) = g.plan.pairs[k];
    let a = &g.plan.a;
    let b = &g.plan.b;
    let wrap = |s: &Side, x: usize| x % s.hs.len();
    // A's edge i joins vs[i] → vs[i+1]; the face across has twin(h), which
    // leaves vs[i+1], and next(twin(h)), which leaves vs[i].
    let a_corners = if on_a {
        let t = a.hs[wrap(a, i)].twin();
        [m.next(t), t]
    } else {
        let x = if i > 0 || g.plan.closed {
            a.hs[wrap(a, i + a.hs.len() - 1)].twin()
        } else {
            m.next(a.hs[0].twin())
        };
        [x, x]
    };
    // B's edge j joins vs[j+1] → vs[j]: twin(h) leaves vs[j].
    let b_corners = if on_b {
        let t = b.hs[wrap(b, j)].twin();
        [t, m.next(t)]
    } else {
        let x = if j > 0 || g.plan.closed {
            m.next(b.hs[wrap(b, j + b.hs.len() - 1)].twin())
        } else {
            b.hs[0].twin()
        };
        [x, x]
    };
    (a_corners, b_corners, m.face_of(a_corners[0]))
}

/// The band's values (see [`Mesh::bridge_loops`]).
fn bridge_attributes<J: Journaling>(w: &mut crate::mesh::Writer<'_, J>, g: &Grid<'_>) {
    let c = g.plan.cuts;
    let t = |r: usize| r as f64 / (c + 1) as f64;
    let lerp = |x: usize, y: usize, r: usize| -> Vec<(usize, f64)> {
        match r {
            0 => vec![(x, 1.0)],
            _ if r == c + 1 => vec![(y, 1.0)],
            _ => vec![(x, 1.0 - t(r)), (y, t(r))],
        }
    };
    let pos = w.position_slots().map(|p| p.to_vec());
    let rungs_n = g.made.verts.len().checked_div(c).unwrap_or(0);
    for k in 0..rungs_n {
        let (i, j) = g.pair(k);
        let (va, vb) = (g.plan.a.vs[i], g.plan.b.vs[j]);
        for r in 1..=c {
            let v = g.made.verts[k * c + r - 1];
            w.attrs
                .vertex
                .interpolate(v.index(), &lerp(va.index(), vb.index(), r));
            if let Some(pos) = &pos {
                let (pa, pb) = (pos[va.index()], pos[vb.index()]);
                let p: V3 = vec3::axpy(pa, t(r), vec3::sub(pb, pa));
                w.attrs.set_position_saved(v.index(), p);
            }
        }
    }
    for &e in g.made.rungs.iter().chain(&g.made.rows) {
        w.attrs.edge.interpolate(e.index(), &[]);
    }
    let columns = g.plan.pairs.len() - 1;
    for k in 0..columns {
        let (ca, cb, face) = column_sources(w, g, k);
        for r in 0..=c {
            let f = g.made.faces[k * (c + 1) + r];
            w.attrs.face.interpolate(f.index(), &[(face.index(), 1.0)]);
            for x in g.cell(k, r) {
                let inputs = lerp(ca[x.side].index(), cb[x.side].index(), x.row);
                w.attrs.halfedge.interpolate(x.h.index(), &inputs);
            }
        }
    }
}

#[cfg(test)]
mod tests;
