//! Edge loops, edge rings and face loops: the selections an editor makes
//! from one edge (Blender's loop and ring select, Houdini's loop groups),
//! and the paths the loop cut and bridge tools run along.
//!
//! The rules are stated in the [`traverse`](crate::traverse) module.
//!
//! Each walks both ways from the edge and returns its run in order, end to
//! end, with whether it closed (came back to where it started). The cost
//! is the run's length times the degrees met.

use crate::error::Result;
use crate::keys::{EdgeKey, FaceKey};
use crate::mesh::Mesh;
use crate::view::HalfedgeView;

/// An ordered run of elements walked from one edge.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Chain<K> {
    /// The elements, end to end (for a closed chain, starting with or
    /// beside the edge it was walked from).
    pub keys: Vec<K>,
    /// Whether the run closed on itself (a loop round a cylinder, a ring
    /// round a torus): its last element meets its first.
    pub closed: bool,
}

impl Mesh {
    /// The edge loop through edge `e` (see the [`traverse`](crate::traverse) module
    /// documentation), `e` among its edges.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) for a removed edge.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mesh = grid(4, 3, GridFaces::Quads); // 4 × 3 quads
    /// // An inner edge's loop runs straight across the grid.
    /// let e = mesh.edges().find(|&e| !mesh.edge(e).unwrap().is_boundary()).unwrap();
    /// let run = mesh.edge_loop(e)?;
    /// assert!(!run.closed && run.keys.contains(&e));
    /// assert!(run.keys.len() == 4 || run.keys.len() == 3);
    /// // A torus's loops close.
    /// let torus = meshloom::shapes::torus(8, 5, 1.0, 0.3).unwrap();
    /// let run = torus.edge_loop(torus.edges().next().unwrap())?;
    /// assert!(run.closed && (run.keys.len() == 8 || run.keys.len() == 5));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn edge_loop(&self, e: EdgeKey) -> Result<Chain<EdgeKey>> {
        let h = self.edge(e)?.halfedge(0);
        let step = if h.is_boundary() || h.twin().is_boundary() {
            boundary_step
        } else {
            loop_step
        };
        Ok(walk_both_ways(self, h, step).map(|h| h.edge().key()))
    }

    /// The edge ring through edge `e` (see the [`traverse`](crate::traverse) module
    /// documentation), `e` among its edges.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) for a removed edge.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mesh = grid(4, 3, GridFaces::Quads);
    /// let e = mesh.edges().next().unwrap();
    /// let ring = mesh.edge_ring(e)?;
    /// // Across the grid: 5 edges over 4 quads, or 4 over 3.
    /// assert!(!ring.closed && (ring.keys.len() == 5 || ring.keys.len() == 4));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn edge_ring(&self, e: EdgeKey) -> Result<Chain<EdgeKey>> {
        Ok(self.edge_ring_halfedges(e)?.map(|h| h.edge().key()))
    }

    /// The edge ring through `e` as half-edges pointing along it, each
    /// lying in the face after it (the last one of an open ring in the face
    /// where it stopped), the first at or before `e`'s first half-edge.
    pub(crate) fn edge_ring_halfedges(&self, e: EdgeKey) -> Result<Chain<HalfedgeView<'_>>> {
        Ok(walk_both_ways(self, self.edge(e)?.halfedge(0), ring_step))
    }

    /// The face loop across edge `e`: the quads its edge ring crosses, in
    /// order (empty when neither side of `e` is a quad).
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) for a removed edge.
    ///
    /// ```
    /// let torus = meshloom::shapes::torus(8, 5, 1.0, 0.3).unwrap();
    /// let faces = torus.face_loop(torus.edges().next().unwrap())?;
    /// assert!(faces.closed && (faces.keys.len() == 8 || faces.keys.len() == 5));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn face_loop(&self, e: EdgeKey) -> Result<Chain<FaceKey>> {
        let mut ring = self.edge_ring_halfedges(e)?;
        if !ring.closed {
            // The last half-edge's face is where the ring stopped.
            ring.keys.pop();
        }
        // Each half-edge's face is the quad after it.
        Ok(ring.map(|h| h.face().key()))
    }
}

impl<K> Chain<K> {
    /// The chain with `f` applied to every element.
    fn map<L>(self, f: impl FnMut(K) -> L) -> Chain<L> {
        Chain {
            keys: self.keys.into_iter().map(f).collect(),
            closed: self.closed,
        }
    }
}

/// The run through half-edge `h`, walked forwards from `h` and forwards from
/// its twin and joined end to end: half-edges pointing along the run
/// (`step` takes one to the next, or `None` at an end). At most one more
/// than the mesh's edges are walked each way.
fn walk_both_ways<'m>(
    mesh: &'m Mesh,
    h: HalfedgeView<'m>,
    step: fn(HalfedgeView<'m>) -> Option<HalfedgeView<'m>>,
) -> Chain<HalfedgeView<'m>> {
    let start = h.edge().key();
    let limit = mesh.edge_count();
    let mut ahead = vec![h];
    while let Some(next) = step(ahead[ahead.len() - 1]).filter(|_| ahead.len() <= limit) {
        if next.edge().key() == start {
            return Chain {
                keys: ahead,
                closed: true,
            };
        }
        ahead.push(next);
    }
    let mut behind = Vec::new();
    let mut at = h.twin();
    while let Some(next) = step(at).filter(|_| behind.len() <= limit) {
        if next.edge().key() == start {
            break; // only a guard: an open run does not come back
        }
        behind.push(next.twin());
        at = next;
    }
    behind.reverse();
    behind.extend(ahead);
    Chain {
        keys: behind,
        closed: false,
    }
}

/// An edge loop's next half-edge after `h` (pointing along the walk): on
/// through `h`'s head if it is inside the mesh with degree 4.
fn loop_step(h: HalfedgeView<'_>) -> Option<HalfedgeView<'_>> {
    let v = h.dest();
    (!v.is_boundary() && v.degree() == 4).then(|| h.next().twin().next())
}

/// A boundary loop's next half-edge after `h`: the next boundary edge at
/// `h`'s head, if the head has degree 3 (the boundary runs straight on).
/// The hole's half-edges run along the boundary, so the next one is the
/// hole's next after `h`, or before `h`'s twin.
fn boundary_step(h: HalfedgeView<'_>) -> Option<HalfedgeView<'_>> {
    if h.dest().degree() != 3 {
        None
    } else if h.is_boundary() {
        Some(h.next())
    } else {
        Some(h.twin().prev().twin())
    }
}

/// An edge ring's next half-edge after `h` (whose face the walk enters):
/// the opposite side of that face, seen from the face beyond, if the face
/// is a quad.
fn ring_step(h: HalfedgeView<'_>) -> Option<HalfedgeView<'_>> {
    let f = h.face();
    (!f.is_hole() && f.degree() == 4).then(|| h.next().next().twin())
}

#[cfg(test)]
mod tests;
