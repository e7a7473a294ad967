//! `split_edges` (rip): disconnect the faces along chosen edges, so that
//! each chosen edge becomes two boundary edges with a hole between them
//! and each vertex where the cut separates its faces splits into one copy
//! per side, as Blender's Edge Split (`BM_mesh_edgesplit`) does.
//!
//! The selection is cut as a set of paths: each walk follows unvisited
//! chosen edges from an end (a vertex on a hole, or where the selection
//! stops) until it reaches a hole, closes on itself or runs out, and each
//! path is one [`cut_path`](crate::Mesh::cut_path), so the attribute rules
//! are that operator's: a vertex copy copies its vertex's values, a corner
//! keeps its value (a UV seam becomes the rim of two islands), an edge's
//! values split equally between its two copies, and the new holes get
//! `interpolate` of nothing.

use std::collections::{HashMap, HashSet};

use crate::error::{Refusal, Result};
use crate::keys::{EdgeKey, FaceKey, VertexKey};
use crate::layout::{Eid, Vid};
use crate::mesh::Mesh;
use crate::ops::refuse;

const OP: &str = "split_edges";

/// What [`Mesh::split_edges`] made.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SplitEdges {
    /// The holes along the cuts (a hole the cut joined counts once).
    pub holes: Vec<FaceKey>,
    /// The vertex copies, on the far side of the cuts.
    pub vertices: Vec<VertexKey>,
    /// The edge copies, one per split edge.
    pub edges: Vec<EdgeKey>,
}

/// One path of chosen edges, in walk order.
struct Path {
    edges: Vec<Eid>,
    closed: bool,
}

impl Mesh {
    /// Whether [`split_edges`](Mesh::split_edges) would plan a cut;
    /// changes nothing.
    ///
    /// # Errors
    /// The plan's errors of [`split_edges`](Mesh::split_edges).
    pub fn check_split_edges(&self, edges: &[EdgeKey]) -> Result<()> {
        self.plan_split_edges(edges).map(|_| ())
    }

    /// Disconnect the faces on the two sides of each of `edges` (rip):
    /// every chosen edge inside the surface becomes two edges on a hole,
    /// and every vertex where the chosen edges separate its faces splits
    /// into one vertex per side. Edges already on a hole are left as they
    /// are. A closed loop of chosen edges cuts a closed surface in two; a
    /// slit inside a surface opens a hole. One undo step.
    ///
    /// Attributes follow [`cut_path`](Mesh::cut_path): vertex copies copy
    /// their vertex's values, corners keep theirs (so seams chosen from a
    /// UV column, [`Delimit::edges`](crate::model::Delimit::edges), become
    /// the boundaries of the islands), edge values split equally between
    /// the two copies, the holes interpolate nothing.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) for a key not in the
    /// mesh; [`Refusal::Parameter`] for a chosen edge that is alone inside
    /// the surface (its two copies would join the same two vertices);
    /// [`Refusal::NonManifold`] when a cut would end where several holes
    /// meet. A refused call changes nothing.
    ///
    /// # Complexity
    /// O(Σ degree of the chosen edges' vertices), whatever the mesh's size.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mut mesh = grid(4, 4, GridFaces::Quads);
    /// // The middle row of vertical edges, y = 2, from boundary to boundary.
    /// let cut: Vec<_> = mesh
    ///     .edges()
    ///     .filter(|&e| {
    ///         let [a, b] = mesh.edge(e).unwrap().vertices().map(|v| mesh.position(v).unwrap());
    ///         a[1] == 2.0 && b[1] == 2.0
    ///     })
    ///     .collect();
    /// let made = mesh.split_edges(&cut)?;
    /// assert_eq!((made.edges.len(), made.vertices.len()), (4, 5));
    /// assert_eq!(mesh.split_components(true).len(), 2);
    /// mesh.validate()?;
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn split_edges(&mut self, edges: &[EdgeKey]) -> Result<SplitEdges> {
        let paths = self.plan_split_edges(edges)?;
        self.transaction(|m| m.commit_split_edges(&paths))
    }

    /// Check the keys and cut the chosen edges inside the surface into
    /// paths that [`cut_path`](Mesh::cut_path) takes, in an order where
    /// each path's inner vertices are off every hole.
    fn plan_split_edges(&self, edges: &[EdgeKey]) -> Result<Vec<Path>> {
        let mut adjacent: HashMap<Vid, Vec<Eid>> = HashMap::new();
        let mut seen = HashSet::new();
        for &e in edges {
            let eid = self.check_edge(e)?;
            let [h, t] = eid.halfedges();
            if self.in_hole(h) || self.in_hole(t) || !seen.insert(eid) {
                continue;
            }
            adjacent.entry(self.origin(h)).or_default().push(eid);
            adjacent.entry(self.origin(t)).or_default().push(eid);
        }
        let mut walk = Walk {
            mesh: self,
            touched: adjacent
                .keys()
                .copied()
                .filter(|&v| self.on_boundary(v))
                .collect(),
            adjacent,
        };
        let mut paths = Vec::new();
        while let Some(start) = walk.start() {
            let path = walk.path_from(start);
            if path.edges.len() == 1 && !walk.touched.contains(&start) {
                let at = walk.other_end(path.edges[0], start);
                if !walk.touched.contains(&at) {
                    return Err(refuse(
                        OP,
                        self.ekey(path.edges[0]),
                        Refusal::Parameter("a chosen edge alone inside the surface cannot split"),
                    ));
                }
            }
            walk.touch(&path);
            paths.push(path);
        }
        Ok(paths)
    }

    /// Cut the paths in order (inside a transaction).
    fn commit_split_edges(&mut self, paths: &[Path]) -> Result<SplitEdges> {
        let mut made = SplitEdges::default();
        for path in paths {
            let vs = self.path_vertices(path);
            let cut = self.cut_path_made(&vs)?;
            made.holes.extend(cut.holes);
            made.vertices.extend(cut.vertices);
            made.edges.extend(cut.edges);
        }
        let mut seen = HashSet::new();
        made.holes
            .retain(|&f| self.contains_face(f) && seen.insert(f));
        Ok(made)
    }

    /// A path's vertices as they are now (earlier cuts may have moved its
    /// ends to copies): `v_0 … v_k`, with `v_k = v_0` when closed.
    fn path_vertices(&self, path: &Path) -> Vec<VertexKey> {
        let ends = |e: Eid| {
            let h = e.halfedge(0);
            [self.origin(h), self.dest(h)]
        };
        let es = &path.edges;
        let shared = |a: Eid, b: Eid| {
            let [p, q] = ends(a);
            if ends(b).contains(&p) {
                p
            } else {
                q
            }
        };
        let other = |e: Eid, v: Vid| {
            let [p, q] = ends(e);
            if p == v {
                q
            } else {
                p
            }
        };
        let k = es.len();
        let mut vs = Vec::with_capacity(k + 1);
        if k == 1 {
            vs.extend(ends(es[0]));
        } else {
            let first = if path.closed {
                shared(es[k - 1], es[0])
            } else {
                other(es[0], shared(es[0], es[1]))
            };
            vs.push(first);
            for i in 0..k {
                let v = other(es[i], vs[i]);
                vs.push(v);
            }
        }
        vs.into_iter().map(|v| self.vkey(v)).collect()
    }
}

/// The walk that cuts the selection into paths.
struct Walk<'m> {
    mesh: &'m Mesh,
    /// Per vertex, its chosen edges not yet on a path.
    adjacent: HashMap<Vid, Vec<Eid>>,
    /// Vertices on a hole: on the boundary, or on a path planned earlier.
    touched: HashSet<Vid>,
}

impl Walk<'_> {
    fn other_end(&self, e: Eid, v: Vid) -> Vid {
        let h = e.halfedge(0);
        let o = self.mesh.origin(h);
        if o == v {
            self.mesh.dest(h)
        } else {
            o
        }
    }

    /// Where the next path starts: a vertex on a hole, else an end of the
    /// selection, else any vertex with chosen edges left (a closed loop).
    fn start(&self) -> Option<Vid> {
        let left = |v: &&Vid| self.adjacent.get(*v).is_some_and(|es| !es.is_empty());
        if let Some(&v) = self.touched.iter().filter(left).min() {
            return Some(v);
        }
        let mut open: Vec<Vid> = self
            .adjacent
            .iter()
            .filter(|(_, es)| !es.is_empty())
            .map(|(&v, es)| (es.len(), v))
            .min()
            .map(|(_, v)| v)
            .into_iter()
            .collect();
        open.pop()
    }

    /// Follow chosen edges from `start` until a hole, the start again, or
    /// no edge that keeps the path simple.
    fn path_from(&mut self, start: Vid) -> Path {
        let mut on_path = HashSet::from([start]);
        let mut edges = Vec::new();
        let mut v = start;
        loop {
            let es = &self.adjacent[&v];
            let pick = es.iter().position(|&e| {
                let w = self.other_end(e, v);
                !on_path.contains(&w)
                    || (w == start && edges.len() >= 2 && !self.touched.contains(&start))
            });
            let Some(i) = pick else {
                return Path {
                    edges,
                    closed: false,
                };
            };
            let e = self.adjacent.get_mut(&v).unwrap().swap_remove(i);
            let w = self.other_end(e, v);
            let back = self.adjacent.get_mut(&w).unwrap();
            back.retain(|&x| x != e);
            edges.push(e);
            if w == start {
                return Path {
                    edges,
                    closed: true,
                };
            }
            if self.touched.contains(&w) || self.adjacent[&w].is_empty() {
                return Path {
                    edges,
                    closed: false,
                };
            }
            on_path.insert(w);
            v = w;
        }
    }

    /// Every vertex of `path` is on a hole once it is cut.
    fn touch(&mut self, path: &Path) {
        for &e in &path.edges {
            let h = e.halfedge(0);
            self.touched.insert(self.mesh.origin(h));
            self.touched.insert(self.mesh.dest(h));
        }
    }
}

#[cfg(test)]
mod tests;
