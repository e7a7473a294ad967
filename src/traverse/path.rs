//! Shortest paths along edges (Dijkstra).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::error::{Error, Refusal, Result};
use crate::keys::{AnyKey, HalfedgeKey, VertexKey};
use crate::layout::{Hid, IdVec, Vid};
use crate::mesh::Mesh;

/// A path along edges: the vertices passed, the half-edges taken and the
/// total cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Path {
    /// The vertices from the start to the end, both included.
    pub vertices: Vec<VertexKey>,
    /// The half-edges walked, one fewer than the vertices: half-edge `i`
    /// leaves `vertices[i]` and enters `vertices[i + 1]`.
    pub halfedges: Vec<HalfedgeKey>,
    /// The sum of the half-edges' costs.
    pub cost: f64,
}

/// A heap entry ordered by smallest cost first (a min-heap on a max-heap).
#[derive(Copy, Clone, Debug)]
struct Entry {
    cost: f64,
    v: Vid,
}

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .cost
            .total_cmp(&self.cost)
            .then_with(|| other.v.cmp(&self.v))
    }
}

/// The cheapest path along edges from `from` to `to` (Dijkstra's algorithm
/// with a binary heap), with the cost of each step given by the caller.
///
/// # Arguments
/// - `from`, `to`: the end vertices (the same vertex gives a path of one
///   vertex and cost 0).
/// - `cost`: the cost of walking a half-edge (a direction: the two
///   half-edges of an edge may cost differently). Called lazily, at most
///   once per half-edge, only for half-edges leaving vertices the search
///   settles. `+∞` makes a half-edge impassable.
///
/// # Returns
/// `Ok(Some(path))` with a cheapest path, `Ok(None)` if no finite-cost path
/// joins the vertices (other components, or walled off by infinite costs).
///
/// # Errors
/// - [`Error::StaleKey`] if `from` or `to` was removed.
/// - [`Error::Refused`] with [`Refusal::Parameter`], naming the half-edge,
///   if a cost is negative or NaN. The search stops there.
///
/// # Complexity
/// O((V + E) log V) time, O(V) memory besides the heap.
///
/// # Examples
/// ```
/// use meshloom::shapes::{grid, GridFaces};
/// use meshloom::traverse::shortest_path;
///
/// let mesh = grid(4, 3, GridFaces::Quads);
/// let v: Vec<_> = mesh.vertices().collect();
/// let (corner, far) = (v[0], v[v.len() - 1]);
/// let path = shortest_path(&mesh, corner, far, |_| 1.0)?.expect("the grid is connected");
/// assert_eq!(path.cost, 7.0); // Manhattan distance: 4 + 3
/// assert_eq!(path.halfedges.len(), 7);
/// assert_eq!(path.vertices[0], corner);
///
/// // Euclidean edge lengths from positions:
/// let length = |h| {
///     let h = mesh.halfedge(h).unwrap();
///     let (a, b) = (h.origin().position().unwrap(), h.dest().position().unwrap());
///     ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
/// };
/// assert_eq!(shortest_path(&mesh, corner, far, length)?.unwrap().cost, 7.0);
/// assert!(shortest_path(&mesh, corner, far, |_| -1.0).is_err());
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn shortest_path(
    mesh: &Mesh,
    from: VertexKey,
    to: VertexKey,
    mut cost: impl FnMut(HalfedgeKey) -> f64,
) -> Result<Option<Path>> {
    let s = mesh.check_vertex(from)?;
    let t = mesh.check_vertex(to)?;
    let n = mesh.vertex_slots();
    let mut dist = IdVec::filled(f64::INFINITY, n);
    // The half-edge by which each vertex was reached.
    let mut via = IdVec::filled(Hid::NONE, n);
    let mut settled = IdVec::filled(false, n);
    let mut heap = BinaryHeap::new();
    dist[s] = 0.0;
    heap.push(Entry { cost: 0.0, v: s });
    while let Some(Entry { cost: d, v: u }) = heap.pop() {
        if settled[u] {
            continue;
        }
        settled[u] = true;
        if u == t {
            break;
        }
        for h in mesh.outgoing(u) {
            let w = mesh.dest(h);
            if settled[w] {
                continue;
            }
            let c = cost(mesh.hkey(h));
            if c.is_nan() || c < 0.0 {
                return Err(Error::Refused {
                    op: "shortest_path",
                    key: AnyKey::Halfedge(mesh.hkey(h)),
                    reason: Refusal::Parameter("an edge cost is negative or NaN"),
                });
            }
            let nd = d + c;
            if nd < dist[w] {
                dist[w] = nd;
                via[w] = h;
                heap.push(Entry { cost: nd, v: w });
            }
        }
    }
    if !settled[t] {
        return Ok(None);
    }
    let mut halfedges = Vec::new();
    let mut vertices = vec![mesh.vkey(t)];
    let mut v = t;
    while v != s {
        let h = via[v];
        halfedges.push(mesh.hkey(h));
        v = mesh.origin(h);
        vertices.push(mesh.vkey(v));
    }
    halfedges.reverse();
    vertices.reverse();
    Ok(Some(Path {
        vertices,
        halfedges,
        cost: dist[t],
    }))
}

impl Mesh {
    /// The cheapest path along edges: see [`shortest_path`].
    ///
    /// # Errors
    /// As [`shortest_path`].
    pub fn shortest_path(
        &self,
        from: VertexKey,
        to: VertexKey,
        cost: impl FnMut(HalfedgeKey) -> f64,
    ) -> Result<Option<Path>> {
        shortest_path(self, from, to, cost)
    }
}
