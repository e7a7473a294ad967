//! Named iterators over a mesh's elements, in slot order, with exact
//! lengths: [`Mesh::vertices`], [`Mesh::halfedges`], [`Mesh::edges`],
//! [`Mesh::faces`], [`Mesh::holes`] and [`Mesh::faces_and_holes`] return
//! these, so their types can be named in a struct field or a signature and
//! `len()` is the count without walking.
//!
//! ```
//! use meshloom::iter::Faces;
//! let cube = meshloom::shapes::cube();
//! let faces: Faces<'_> = cube.faces();
//! assert_eq!(faces.len(), 6);
//! let mut edges = cube.edges();
//! edges.next();
//! assert_eq!(edges.len(), 11);
//! let halfedges: Vec<_> = cube.halfedges().collect();
//! assert_eq!(halfedges.len(), cube.halfedge_count());
//! ```

use std::iter::FusedIterator;

use crate::keys::{EdgeKey, FaceKey, HalfedgeKey, VertexKey};
use crate::layout::{Eid, Fid};
use crate::mesh::Mesh;

/// The element iterators (keys, in slot order). They live here, beside
/// the iterator types, so that `mesh.rs` does not import this module.
impl Mesh {
    /// Every vertex key, in slot order; `len()` is exact.
    #[inline]
    pub fn vertices(&self) -> Vertices<'_> {
        Vertices::new(self)
    }

    /// Every half-edge key, in slot order (twins adjacent); `len()` is
    /// exact.
    #[inline]
    pub fn halfedges(&self) -> Halfedges<'_> {
        Halfedges::new(self)
    }

    /// Every edge key, in slot order; `len()` is exact.
    #[inline]
    pub fn edges(&self) -> Edges<'_> {
        Edges::new(self)
    }

    /// Every face key, holes excluded, in slot order; `len()` is exact.
    ///
    /// ```
    /// let cube = meshloom::shapes::cube();
    /// let faces = cube.faces();
    /// assert_eq!(faces.len(), cube.face_count());
    /// ```
    #[inline]
    pub fn faces(&self) -> Faces<'_> {
        Faces::not_holes(self)
    }

    /// Every hole face key, in slot order; `len()` is exact.
    #[inline]
    pub fn holes(&self) -> Faces<'_> {
        Faces::holes(self)
    }

    /// Every face key, holes included, in slot order; `len()` is exact.
    #[inline]
    pub fn faces_and_holes(&self) -> Faces<'_> {
        Faces::both(self)
    }
}

/// Which faces a face iterator yields.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Which {
    Faces,
    Holes,
    Both,
}

/// Every vertex key of a mesh, in slot order ([`Mesh::vertices`]).
#[derive(Clone, Debug)]
pub struct Vertices<'m> {
    mesh: &'m Mesh,
    slot: usize,
    left: usize,
}

impl<'m> Vertices<'m> {
    fn new(mesh: &'m Mesh) -> Self {
        Vertices {
            mesh,
            slot: 0,
            left: mesh.vertex_count(),
        }
    }
}

impl Iterator for Vertices<'_> {
    type Item = VertexKey;

    #[inline]
    fn next(&mut self) -> Option<VertexKey> {
        let end = self.mesh.vertex_slots();
        while self.left > 0 && self.slot < end {
            let i = self.slot;
            self.slot += 1;
            if let Some(k) = self.mesh.vertex_at(i) {
                self.left -= 1;
                return Some(k);
            }
        }
        None
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl ExactSizeIterator for Vertices<'_> {}
impl FusedIterator for Vertices<'_> {}

/// Every edge key of a mesh, in slot order ([`Mesh::edges`]).
#[derive(Clone, Debug)]
pub struct Edges<'m> {
    mesh: &'m Mesh,
    slot: usize,
    left: usize,
}

impl<'m> Edges<'m> {
    fn new(mesh: &'m Mesh) -> Self {
        Edges {
            mesh,
            slot: 0,
            left: mesh.edge_count(),
        }
    }

    /// The next live edge slot.
    #[inline]
    fn next_eid(&mut self) -> Option<(Eid, u32)> {
        let end = self.mesh.edge_slots();
        while self.left > 0 && self.slot < end {
            let i = self.slot;
            self.slot += 1;
            if let Some((i, g)) = self.mesh.edge_arena().live_at(i) {
                self.left -= 1;
                return Some((Eid::new(i), g));
            }
        }
        None
    }
}

impl Iterator for Edges<'_> {
    type Item = EdgeKey;

    #[inline]
    fn next(&mut self) -> Option<EdgeKey> {
        self.next_eid().map(|(e, g)| e.key(g))
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl ExactSizeIterator for Edges<'_> {}
impl FusedIterator for Edges<'_> {}

/// Every half-edge key of a mesh, in slot order, twins adjacent
/// ([`Mesh::halfedges`]).
#[derive(Clone, Debug)]
pub struct Halfedges<'m> {
    edges: Edges<'m>,
    /// The second half-edge of the last edge, not yet yielded.
    pending: Option<HalfedgeKey>,
}

impl<'m> Halfedges<'m> {
    fn new(mesh: &'m Mesh) -> Self {
        Halfedges {
            edges: Edges::new(mesh),
            pending: None,
        }
    }
}

impl Iterator for Halfedges<'_> {
    type Item = HalfedgeKey;

    #[inline]
    fn next(&mut self) -> Option<HalfedgeKey> {
        if let Some(h) = self.pending.take() {
            return Some(h);
        }
        let (e, g) = self.edges.next_eid()?;
        let [a, b] = e.halfedges();
        self.pending = Some(b.key(g));
        Some(a.key(g))
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = 2 * self.edges.left + usize::from(self.pending.is_some());
        (n, Some(n))
    }
}

impl ExactSizeIterator for Halfedges<'_> {}
impl FusedIterator for Halfedges<'_> {}

/// Face keys of a mesh, in slot order: the faces ([`Mesh::faces`]), the
/// holes ([`Mesh::holes`]) or both ([`Mesh::faces_and_holes`]).
#[derive(Clone, Debug)]
pub struct Faces<'m> {
    mesh: &'m Mesh,
    which: Which,
    slot: usize,
    left: usize,
}

impl<'m> Faces<'m> {
    fn not_holes(mesh: &'m Mesh) -> Self {
        Faces::of(mesh, Which::Faces, mesh.face_count())
    }

    fn holes(mesh: &'m Mesh) -> Self {
        Faces::of(mesh, Which::Holes, mesh.hole_count())
    }

    fn both(mesh: &'m Mesh) -> Self {
        Faces::of(mesh, Which::Both, mesh.face_count() + mesh.hole_count())
    }

    fn of(mesh: &'m Mesh, which: Which, left: usize) -> Self {
        Faces {
            mesh,
            which,
            slot: 0,
            left,
        }
    }
}

impl Iterator for Faces<'_> {
    type Item = FaceKey;

    #[inline]
    fn next(&mut self) -> Option<FaceKey> {
        let end = self.mesh.face_slots();
        while self.left > 0 && self.slot < end {
            let i = self.slot;
            self.slot += 1;
            let Some((i, g)) = self.mesh.face_arena().live_at(i) else {
                continue;
            };
            let f = Fid::new(i);
            let wanted = match self.which {
                Which::Faces => !self.mesh.is_hole(f),
                Which::Holes => self.mesh.is_hole(f),
                Which::Both => true,
            };
            if wanted {
                self.left -= 1;
                return Some(f.key(g));
            }
        }
        None
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl ExactSizeIterator for Faces<'_> {}
impl FusedIterator for Faces<'_> {}

#[cfg(test)]
mod tests {

    /// Lengths stay exact while walking, and agree with the counts, after
    /// removals have left vacant slots.
    #[test]
    fn lengths_are_exact_with_vacant_slots() {
        let mut mesh = crate::shapes::icosphere(1);
        let faces: Vec<_> = mesh.faces().take(3).collect();
        for f in faces {
            mesh.remove_face(f).unwrap();
        }
        assert!(mesh.hole_count() > 0);
        let check = |mut it: Box<dyn ExactSizeIterator<Item = usize> + '_>, n: usize| {
            assert_eq!(it.len(), n);
            let mut seen = 0;
            while it.next().is_some() {
                seen += 1;
                assert_eq!(it.len(), n - seen);
            }
            assert_eq!(seen, n);
            assert_eq!(it.next(), None);
        };
        check(
            Box::new(mesh.vertices().map(|k| k.index())),
            mesh.vertex_count(),
        );
        check(Box::new(mesh.edges().map(|k| k.index())), mesh.edge_count());
        check(
            Box::new(mesh.halfedges().map(|k| k.index())),
            mesh.halfedge_count(),
        );
        check(Box::new(mesh.faces().map(|k| k.index())), mesh.face_count());
        check(Box::new(mesh.holes().map(|k| k.index())), mesh.hole_count());
        check(
            Box::new(mesh.faces_and_holes().map(|k| k.index())),
            mesh.face_count() + mesh.hole_count(),
        );
        // Every key the iterators give is live, and faces are not holes.
        for f in mesh.faces() {
            assert!(!mesh.face(f).unwrap().is_hole());
        }
        for h in mesh.holes() {
            assert!(mesh.face(h).unwrap().is_hole());
        }
        let hs: Vec<_> = mesh.halfedges().collect();
        assert!(hs
            .chunks(2)
            .all(|p| mesh.halfedge(p[0]).unwrap().twin().key() == p[1]));
    }
}
