//! `grid_fill`: a hole with an even number of sides filled by a grid of
//! quads (BMesh's `bmo_grid_fill.cc`).
//!
//! The hole's boundary is cut into four sides at four corners: the first
//! corner, `span` edges on, half the loop on and `span` edges after that.
//! The grid between them has `span × (n / 2 − span)` quads; its inner
//! vertices sit on the Coons patch of the four sides (the bilinear blend
//! of the opposite sides' straight interpolations, less the corners'),
//! which puts them back exactly on a hole cut out of a regular grid.

use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::{EdgeKey, FaceKey, VertexKey};
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::Mesh;
use crate::ops::refuse;
use crate::vec3::{self, V3};

const OP: &str = "grid_fill";

/// Options of [`Mesh::grid_fill`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GridFillOptions {
    /// How many edges the first and third sides have (`1..n / 2` for a
    /// hole of `n` edges); `None`: chosen with the corners (the four
    /// sharpest turns of the boundary that cut it into opposite sides of
    /// equal lengths, nearest a square on ties).
    pub span: Option<usize>,
    /// Where the first corner sits: this many edges along the hole from
    /// its first half-edge; `None`: chosen with the span.
    pub offset: Option<usize>,
}

/// What [`Mesh::grid_fill`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GridFill {
    /// The quads, row by row from the first side (`span` a row); the first
    /// is the hole's key, now a face.
    pub faces: Vec<FaceKey>,
    /// The new vertices inside, row by row (`span − 1` a row).
    pub vertices: Vec<VertexKey>,
    /// The new edges inside.
    pub edges: Vec<EdgeKey>,
    /// The span used (the first side's edge count) and the first corner's
    /// offset along the hole.
    pub span: usize,
    /// See [`span`](Self::span).
    pub offset: usize,
}

/// A checked grid fill.
struct Plan {
    hole: Fid,
    /// The hole's half-edges from the first corner on.
    hs: Vec<Hid>,
    /// Edges along the first side (`s`) and the second (`m`).
    s: usize,
    m: usize,
    offset: usize,
}

impl Mesh {
    /// Whether [`grid_fill`](Mesh::grid_fill) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`grid_fill`](Mesh::grid_fill).
    pub fn check_grid_fill(&self, hole: FaceKey, options: &GridFillOptions) -> Result<()> {
        self.plan_grid_fill(hole, options).map(|_| ())
    }

    /// Fill hole `hole` (a loop of `n` edges, `n` even and at least 4)
    /// with a grid of `span × (n / 2 − span)` quads: the boundary is cut
    /// into four sides at four corners and the inner vertices are placed
    /// on the Coons patch of the sides. The hole's key becomes the first
    /// quad.
    ///
    /// Attributes (as BMesh's grid fill): an inner vertex interpolates the
    /// four boundary vertices in line with it (weights `(1 − v)/2`,
    /// `v/2`, `(1 − u)/2`, `u/2` at grid parameters `u`, `v`); a corner at
    /// a boundary vertex copies the corner of the face across the boundary
    /// edge (the first of the cell's boundary edges at a grid corner), so
    /// the rim continues the islands beside it; an inner corner
    /// interpolates, with the same weights, the corners of the faces
    /// across the four boundary edges in line with its cell. A linear UV
    /// field across the rim is kept exactly on a regular hole; where the
    /// rim crosses a UV seam the inner corners blend the islands, as
    /// BMesh's do. Each quad copies the face across its nearest boundary
    /// edge (a material id follows); new edges get `interpolate` of
    /// nothing. One undo step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::NotHole`];
    /// [`Refusal::Parameter`] for an odd number of edges or fewer than 4,
    /// a `span` outside `1..n / 2`, an `offset` not below `n`;
    /// [`Refusal::NonManifold`] when the hole passes a vertex twice;
    /// [`Refusal::EdgeExists`] when an inner edge would join two boundary
    /// vertices joined already.
    ///
    /// # Complexity
    /// O(n²) to choose the corners, O(`span × (n / 2 − span)`) to fill.
    ///
    /// ```
    /// use meshloom::model::GridFillOptions;
    /// use meshloom::shapes::{grid, GridFaces};
    /// // A 6 × 6 grid without its middle 4 × 4 quads: a hole of 16 edges.
    /// let mut mesh = grid(6, 6, GridFaces::Quads);
    /// let middle: Vec<_> = mesh.faces().filter(|&f| {
    ///     mesh.face(f).unwrap().vertices().all(|v| {
    ///         let p = mesh.position(v).unwrap();
    ///         (1.0..=5.0).contains(&p[0]) && (1.0..=5.0).contains(&p[1])
    ///     })
    /// }).collect();
    /// assert_eq!(middle.len(), 16);
    /// let mut hole = None;
    /// for f in middle {
    ///     hole = mesh.remove_face(f)?.first().copied().or(hole);
    /// }
    /// let made = mesh.grid_fill(hole.unwrap(), &GridFillOptions::default())?;
    /// assert_eq!((made.faces.len(), made.vertices.len(), made.span), (16, 9, 4));
    /// assert_eq!((mesh.face_count(), mesh.hole_count()), (36, 1));
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn grid_fill(&mut self, hole: FaceKey, options: &GridFillOptions) -> Result<GridFill> {
        let plan = self.plan_grid_fill(hole, options)?;
        journaled!(self.commit_grid_fill(&plan))
    }

    /// Check the hole and options; choose the corners.
    fn plan_grid_fill(&self, hk: FaceKey, o: &GridFillOptions) -> Result<Plan> {
        let hole = self.check_face(hk)?;
        if !self.is_hole(hole) {
            return Err(refuse(OP, hk, Refusal::NotHole));
        }
        let hs: Vec<Hid> = self.face_halfedges(hole).collect();
        let n = hs.len();
        if n < 4 || n % 2 == 1 {
            return Err(refuse(
                OP,
                hk,
                Refusal::Parameter("a grid fill needs an even number of edges, at least 4"),
            ));
        }
        let mut vs: Vec<Vid> = hs.iter().map(|&h| self.origin(h)).collect();
        vs.sort_unstable();
        if vs.windows(2).any(|w| w[0] == w[1]) {
            return Err(refuse(OP, hk, Refusal::NonManifold));
        }
        if o.span.is_some_and(|s| s == 0 || s >= n / 2) {
            return Err(refuse(
                OP,
                hk,
                Refusal::Parameter("span must be in 1..n/2 for a hole of n edges"),
            ));
        }
        if o.offset.is_some_and(|x| x >= n) {
            return Err(refuse(
                OP,
                hk,
                Refusal::Parameter("offset must be below the hole's edge count"),
            ));
        }
        let (offset, s) = self.grid_corners(&hs, o);
        let mut hs = hs;
        hs.rotate_left(offset);
        let plan = Plan {
            hole,
            hs,
            s,
            m: n / 2 - s,
            offset,
        };
        // Inner edges between two boundary vertices (a side of one edge).
        let g = FillGrid {
            plan: &plan,
            mesh: self,
        };
        for (a, b) in g.inner_edges() {
            if let (Some(a), Some(b)) = (g.rim_vertex(a.0, a.1), g.rim_vertex(b.0, b.1)) {
                if self.find_halfedge_raw(a, b).is_some() {
                    return Err(refuse(OP, hk, Refusal::EdgeExists));
                }
            }
        }
        Ok(plan)
    }

    /// The first corner and the span: given, or the ones whose four
    /// corners turn the most (ties: nearest a square, then first).
    fn grid_corners(&self, hs: &[Hid], o: &GridFillOptions) -> (usize, usize) {
        let n = hs.len();
        let turn: Vec<f64> = match self.position_slots() {
            Some(pos) => (0..n)
                .map(|i| {
                    let p = |h: Hid| pos[self.origin(h).index()];
                    let (a, b, c) = (p(hs[(i + n - 1) % n]), p(hs[i]), p(hs[(i + 1) % n]));
                    let angle = vec3::angle(vec3::sub(b, a), vec3::sub(c, b));
                    if angle.is_finite() {
                        angle
                    } else {
                        0.0
                    }
                })
                .collect(),
            None => vec![0.0; n],
        };
        let half = n / 2;
        let spans: Vec<usize> = o.span.map_or_else(|| (1..half).collect(), |s| vec![s]);
        let offsets: Vec<usize> = o.offset.map_or_else(|| (0..n).collect(), |x| vec![x]);
        let mut best = (f64::NEG_INFINITY, usize::MAX, 0, 0);
        for &s in &spans {
            let squareness = (2 * s).abs_diff(half);
            for &x in &offsets {
                let score: f64 = [x, x + s, x + half, x + half + s]
                    .iter()
                    .map(|&i| turn[i % n])
                    .sum();
                // Round so that equal turns (a regular hole) tie exactly.
                let score = (score * 1e9).round() / 1e9;
                if score > best.0 || score == best.0 && squareness < best.1 {
                    best = (score, squareness, x, s);
                }
            }
        }
        (best.2, best.3)
    }
}

/// The fill's grid: vertex `(i, j)` for `i` in `0..=s`, `j` in `0..=m`;
/// row `j = 0` is the first side, column `i = s` the second.
struct FillGrid<'a> {
    plan: &'a Plan,
    mesh: &'a Mesh,
}

impl FillGrid<'_> {
    /// The boundary half-edge's index (in `plan.hs`) of the side edge of
    /// cell `(i, j)` on side `side` (0 bottom, 1 right, 2 top, 3 left),
    /// if the cell touches that side.
    fn rim_edge(&self, i: usize, j: usize, side: usize) -> Option<usize> {
        let (s, m) = (self.plan.s, self.plan.m);
        match side {
            0 if j == 0 => Some(i),
            1 if i == s - 1 => Some(s + j),
            2 if j == m - 1 => Some(s + m + (s - 1 - i)),
            3 if i == 0 => Some(2 * s + m + (m - 1 - j)),
            _ => None,
        }
    }

    /// The boundary index of vertex `(i, j)`, if it is on the boundary.
    fn rim_index(&self, i: usize, j: usize) -> Option<usize> {
        let (s, m) = (self.plan.s, self.plan.m);
        if j == 0 {
            Some(i)
        } else if i == s {
            Some(s + j)
        } else if j == m {
            Some(s + m + (s - i))
        } else if i == 0 {
            Some((2 * s + m + (m - j)) % (2 * (s + m)))
        } else {
            None
        }
    }

    /// The boundary vertex `(i, j)`, if it is one.
    fn rim_vertex(&self, i: usize, j: usize) -> Option<Vid> {
        self.rim_index(i, j)
            .map(|x| self.mesh.origin(self.plan.hs[x]))
    }

    /// The inner edges' ends: rows `j` in `1..m` (along `i`), then columns
    /// `i` in `1..s` (along `j`).
    fn inner_edges(&self) -> Vec<((usize, usize), (usize, usize))> {
        let (s, m) = (self.plan.s, self.plan.m);
        let rows = (1..m).flat_map(|j| (0..s).map(move |i| ((i, j), (i + 1, j))));
        let cols = (1..s).flat_map(|i| (0..m).map(move |j| ((i, j), (i, j + 1))));
        rows.chain(cols).collect()
    }
}

/// The new elements of a grid fill, by slot.
struct Made {
    /// Inner vertices, `(i, j)` at `(j − 1)(s − 1) + i − 1`.
    verts: Vec<Vid>,
    /// Row edges, `(i, j)–(i + 1, j)` at `(j − 1) s + i`; half-edge 0
    /// along `i`.
    rows: Vec<Eid>,
    /// Column edges, `(i, j)–(i, j + 1)` at `(i − 1) m + j`; half-edge 0
    /// along `j`.
    cols: Vec<Eid>,
    /// Cells, `(i, j)` at `j s + i`.
    faces: Vec<Fid>,
}

impl Made {
    /// The vertex `(i, j)`.
    fn vertex(&self, g: &FillGrid<'_>, i: usize, j: usize) -> Vid {
        g.rim_vertex(i, j)
            .unwrap_or_else(|| self.verts[(j - 1) * (g.plan.s - 1) + i - 1])
    }

    /// Cell `(i, j)`'s half-edges from its corner `(i, j)`, anticlockwise
    /// in the grid, each with the grid vertex it leaves and the side it is
    /// on (0 bottom, 1 right, 2 top, 3 left).
    fn cell(&self, g: &FillGrid<'_>, i: usize, j: usize) -> [(Hid, (usize, usize), usize); 4] {
        let (s, m) = (g.plan.s, g.plan.m);
        let rim = |side| g.rim_edge(i, j, side).map(|x| g.plan.hs[x]);
        let bottom = rim(0).unwrap_or_else(|| self.rows[(j - 1) * s + i].halfedge(0));
        let right = rim(1).unwrap_or_else(|| self.cols[i * m + j].halfedge(0));
        let top = rim(2).unwrap_or_else(|| self.rows[j * s + i].halfedge(1));
        let left = rim(3).unwrap_or_else(|| self.cols[(i - 1) * m + j].halfedge(1));
        [
            (bottom, (i, j), 0),
            (right, (i + 1, j), 1),
            (top, (i + 1, j + 1), 2),
            (left, (i, j + 1), 3),
        ]
    }
}

impl Mesh {
    /// Build the grid and run the attribute rules (the plan's body, in
    /// journaling mode `J`).
    fn commit_grid_fill<J: Journaling>(&mut self, plan: &Plan) -> Result<GridFill> {
        let (s, m) = (plan.s, plan.m);
        let sources = self.fill_sources(plan);
        let mut w = self.writer::<J>();
        let mut faces = vec![plan.hole];
        w.set_hole(plan.hole, false);
        faces.extend((1..s * m).map(|_| w.alloc_face(false)));
        let made = Made {
            verts: (0..(s - 1) * (m - 1)).map(|_| w.alloc_vertex()).collect(),
            rows: (0..s * (m - 1)).map(|_| w.alloc_edge()).collect(),
            cols: (0..(s - 1) * m).map(|_| w.alloc_edge()).collect(),
            faces,
        };
        for j in 0..m {
            for i in 0..s {
                let f = made.faces[j * s + i];
                let cycle = {
                    let g = FillGrid { plan, mesh: &w };
                    made.cell(&g, i, j)
                        .map(|(h, (a, b), _)| (h, made.vertex(&g, a, b)))
                };
                for (k, &(h, v)) in cycle.iter().enumerate() {
                    let next = cycle[(k + 1) % 4].0;
                    w.set_he(
                        h,
                        HalfedgeRecord {
                            origin: v,
                            next,
                            face: f,
                        },
                    );
                }
                w.set_face_link(f, cycle[0].0);
            }
        }
        for j in 1..m {
            for i in 1..s {
                let v = made.verts[(j - 1) * (s - 1) + i - 1];
                *w.v_halfedge_mut(v) = made.rows[(j - 1) * s + i].halfedge(0);
            }
        }
        let rim: Vec<Vid> = plan.hs.iter().map(|&h| w.origin(h)).collect();
        for v in rim {
            w.point_at_hole(v);
        }
        fill_attributes(&mut w, plan, &made, &sources);
        w.end_op();
        Ok(GridFill {
            faces: made.faces.iter().map(|&f| w.fkey(f)).collect(),
            vertices: made.verts.iter().map(|&v| w.vkey(v)).collect(),
            edges: made
                .rows
                .iter()
                .chain(&made.cols)
                .map(|&e| w.ekey(e))
                .collect(),
            span: s,
            offset: plan.offset,
        })
    }

    /// Per boundary half-edge (in `plan.hs` order): the face across it and
    /// its corners at the half-edge's origin and destination.
    fn fill_sources(&self, plan: &Plan) -> Vec<(Fid, Hid, Hid)> {
        plan.hs
            .iter()
            .map(|&h| {
                let t = h.twin();
                (self.face_of(t), self.next(t), t)
            })
            .collect()
    }
}

/// The fill's values (see [`Mesh::grid_fill`]).
fn fill_attributes<J: Journaling>(
    w: &mut crate::mesh::Writer<'_, J>,
    plan: &Plan,
    made: &Made,
    sources: &[(Fid, Hid, Hid)],
) {
    let (s, m) = (plan.s, plan.m);
    let rim: Vec<Vid> = plan.hs.iter().map(|&h| w.origin(h)).collect();
    let pos: Option<Vec<V3>> = w
        .position_slots()
        .map(|p| rim.iter().map(|v| p[v.index()]).collect());
    let g = FillGrid { plan, mesh: w };
    let at = |i, j| g.rim_index(i, j).expect("a boundary vertex");
    // The four boundary vertices in line with (i, j) and their weights.
    let rails = |i: usize, j: usize| {
        let (u, v) = (i as f64 / s as f64, j as f64 / m as f64);
        [
            (at(i, 0), (1.0 - v) / 2.0),
            (at(i, m), v / 2.0),
            (at(0, j), (1.0 - u) / 2.0),
            (at(s, j), u / 2.0),
        ]
    };
    let mut vertex_jobs = Vec::new();
    for j in 1..m {
        for i in 1..s {
            let v = made.verts[(j - 1) * (s - 1) + i - 1];
            let inputs: Vec<(usize, f64)> = rails(i, j)
                .iter()
                .map(|&(x, wt)| (rim[x].index(), wt))
                .collect();
            let p = pos.as_ref().map(|pos| coons(pos, &g, i, j));
            vertex_jobs.push((v, inputs, p));
        }
    }
    let mut corner_jobs = Vec::new();
    let mut face_jobs = Vec::new();
    for j in 0..m {
        for i in 0..s {
            face_jobs.push((made.faces[j * s + i], nearest_rim_face(&g, sources, i, j)));
            for (h, (a, b), _) in made.cell(&g, i, j) {
                corner_jobs.push((h, corner_inputs(&g, sources, (i, j), (a, b))));
            }
        }
    }
    for (v, inputs, p) in vertex_jobs {
        w.attrs.vertex.interpolate(v.index(), &inputs);
        if let Some(p) = p {
            w.attrs.set_position_saved(v.index(), p);
        }
    }
    for &e in made.rows.iter().chain(&made.cols) {
        w.attrs.edge.interpolate(e.index(), &[]);
    }
    for (f, src) in face_jobs {
        w.attrs.face.interpolate(f.index(), &[(src.index(), 1.0)]);
    }
    for (h, inputs) in corner_jobs {
        w.attrs.halfedge.interpolate(h.index(), &inputs);
    }
}

/// Point `(i, j)` of the Coons patch of the boundary `pos` (by boundary
/// index).
fn coons(pos: &[V3], g: &FillGrid<'_>, i: usize, j: usize) -> V3 {
    let (s, m) = (g.plan.s, g.plan.m);
    let (u, v) = (i as f64 / s as f64, j as f64 / m as f64);
    let p = |a, b| pos[g.rim_index(a, b).expect("a boundary vertex")];
    let mut out = [0.0; 3];
    for (q, wt) in [
        (p(i, 0), 1.0 - v),
        (p(i, m), v),
        (p(0, j), 1.0 - u),
        (p(s, j), u),
        (p(0, 0), -(1.0 - u) * (1.0 - v)),
        (p(s, 0), -u * (1.0 - v)),
        (p(0, m), -(1.0 - u) * v),
        (p(s, m), -u * v),
    ] {
        vec3::add_scaled(&mut out, q, wt);
    }
    out
}

/// The face across the boundary edge nearest cell `(i, j)` (ties: bottom,
/// right, top, left).
fn nearest_rim_face(g: &FillGrid<'_>, sources: &[(Fid, Hid, Hid)], i: usize, j: usize) -> Fid {
    let (s, m) = (g.plan.s, g.plan.m);
    let sides = [
        (j, 0, (i, 0)),
        (s - 1 - i, 1, (s - 1, j)),
        (m - 1 - j, 2, (i, m - 1)),
        (i, 3, (0, j)),
    ];
    let &(_, side, (a, b)) = sides.iter().min_by_key(|x| x.0).expect("four sides");
    sources[g.rim_edge(a, b, side).expect("a boundary cell")].0
}

/// The inputs of cell `cell`'s corner at grid vertex `(a, b)`: at a
/// boundary vertex, the face across the cell's first boundary edge there;
/// inside, the rails' corners in line with the cell.
fn corner_inputs(
    g: &FillGrid<'_>,
    sources: &[(Fid, Hid, Hid)],
    cell: (usize, usize),
    (a, b): (usize, usize),
) -> Vec<(usize, f64)> {
    let (s, m) = (g.plan.s, g.plan.m);
    let (i, j) = cell;
    // Boundary edge index `x`'s corner at grid vertex (a, b): its origin's
    // or its destination's.
    let corner = |x: usize, a: usize, b: usize| {
        let (_, at_origin, at_dest) = sources[x];
        if g.rim_index(a, b) == Some(x) {
            at_origin
        } else {
            at_dest
        }
    };
    // The cell's boundary edges (and the same rails in line with it).
    let rail = |side: usize| -> usize {
        match side {
            0 => g.rim_edge(i, 0, 0),
            1 => g.rim_edge(s - 1, j, 1),
            2 => g.rim_edge(i, m - 1, 2),
            _ => g.rim_edge(0, j, 3),
        }
        .expect("a rail")
    };
    let touches = [b == 0, a == s, b == m, a == 0];
    if let Some(side) = (0..4).find(|&x| touches[x] && g.rim_edge(i, j, x).is_some()) {
        return vec![(corner(rail(side), a, b).index(), 1.0)];
    }
    let (u, v) = (a as f64 / s as f64, b as f64 / m as f64);
    [
        (corner(rail(0), a, 0), (1.0 - v) / 2.0),
        (corner(rail(2), a, m), v / 2.0),
        (corner(rail(3), 0, b), (1.0 - u) / 2.0),
        (corner(rail(1), s, b), u / 2.0),
    ]
    .iter()
    .map(|&(h, wt)| (h.index(), wt))
    .collect()
}

#[cfg(test)]
mod tests;
