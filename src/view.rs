//! Borrowed views: a key checked once, then infallible navigation.
//!
//! [`Mesh::halfedge`] and its siblings check the key's generation and hand
//! back a small `Copy` view holding the mesh and the slot. Every step from a
//! view (`twin`, `next`, `origin`, `face`, ...) follows the mesh's own links,
//! which are valid by construction, so it cannot fail and returns another
//! view:
//!
//! ```
//! use meshloom::shapes;
//! let mesh = shapes::tetrahedron();
//! let h = mesh.halfedges().next().unwrap();
//! let v = mesh.halfedge(h)?.twin().next().origin();
//! assert_eq!(v.key(), mesh.halfedge(h)?.origin().key());
//! # Ok::<(), meshloom::Error>(())
//! ```
//!
//! Orientation: the corners of a face run counter-clockwise seen from the
//! side its normal points to (the order given when building); a hole runs
//! the other way round, as the twins of its boundary's half-edges.

use crate::circulate::{FaceCorners, FaceHalfedges, VertexNeighbors, VertexOutgoing};
use crate::error::Result;
use crate::keys::{EdgeKey, FaceKey, HalfedgeKey, VertexKey};
use crate::layout::{Eid, Fid, Hid, Vid};
use crate::mesh::Mesh;

/// A checked half-edge.
///
/// Made by [`Mesh::halfedge`]. Every step from it is another view, so a walk
/// needs one `?`, at the start.
///
/// ```
/// let mesh = meshloom::shapes::tetrahedron();
/// let h = mesh.halfedge(mesh.halfedges().next().unwrap())?;
/// assert_eq!(h.next().next().next().key(), h.key()); // round a triangle
/// assert_eq!(h.twin().twin().key(), h.key()); // across and back
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Copy, Clone)]
pub struct HalfedgeView<'m> {
    pub(crate) mesh: &'m Mesh,
    pub(crate) h: Hid,
}

/// A checked vertex.
///
/// Made by [`Mesh::vertex`].
///
/// ```
/// let mesh = meshloom::shapes::icosahedron();
/// let v = mesh.vertex(mesh.vertices().next().unwrap())?;
/// assert_eq!((v.degree(), v.faces().count()), (5, 5));
/// assert!(!v.is_boundary());
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Copy, Clone)]
pub struct VertexView<'m> {
    pub(crate) mesh: &'m Mesh,
    pub(crate) v: Vid,
}

/// A checked face or hole.
///
/// Made by [`Mesh::face`], for faces and holes alike.
///
/// ```
/// let mesh = meshloom::shapes::cube();
/// let f = mesh.face(mesh.faces().next().unwrap())?;
/// assert_eq!((f.degree(), f.neighbors().count()), (4, 4));
/// assert!(!f.is_hole());
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Copy, Clone)]
pub struct FaceView<'m> {
    pub(crate) mesh: &'m Mesh,
    pub(crate) f: Fid,
}

/// A checked edge.
///
/// Made by [`Mesh::edge`].
///
/// ```
/// let mesh = meshloom::shapes::disk(6); // a fan of 6 triangles
/// let rim = mesh.edges().filter(|&e| mesh.edge(e).is_ok_and(|e| e.is_boundary()));
/// assert_eq!(rim.count(), 6);
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Copy, Clone)]
pub struct EdgeView<'m> {
    pub(crate) mesh: &'m Mesh,
    pub(crate) e: Eid,
}

impl Mesh {
    /// A view of half-edge `h`.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) if `h` was removed.
    ///
    /// ```
    /// use meshloom::Error;
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// assert_eq!(mesh.halfedge(h)?.key(), h);
    /// mesh.collapse_edge(h)?; // h's edge is gone
    /// assert!(matches!(mesh.halfedge(h), Err(Error::StaleKey(_))));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn halfedge(&self, h: HalfedgeKey) -> Result<HalfedgeView<'_>> {
        Ok(HalfedgeView {
            mesh: self,
            h: self.check_halfedge(h)?,
        })
    }

    /// A view of vertex `v`.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) if `v` was removed.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let (a, b) = (mesh.halfedge(h)?.origin().key(), mesh.halfedge(h)?.dest().key());
    /// assert_eq!(mesh.collapse_edge(h)?, b); // a goes into b
    /// assert!(mesh.vertex(a).is_err());
    /// assert_eq!(mesh.vertex(b)?.degree(), 5 + 5 - 4);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn vertex(&self, v: VertexKey) -> Result<VertexView<'_>> {
        Ok(VertexView {
            mesh: self,
            v: self.check_vertex(v)?,
        })
    }

    /// A view of face (or hole) `f`.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) if `f` was removed.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mesh = grid(2, 1, GridFaces::Quads);
    /// let hole = mesh.face(mesh.holes().next().unwrap())?; // holes have views too
    /// assert!(hole.is_hole());
    /// assert_eq!(hole.degree(), 6); // the boundary loop
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn face(&self, f: FaceKey) -> Result<FaceView<'_>> {
        Ok(FaceView {
            mesh: self,
            f: self.check_face(f)?,
        })
    }

    /// A view of edge `e`.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) if `e` was removed.
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let e = mesh.edges().next().unwrap();
    /// let [a, b] = mesh.edge(e)?.vertices();
    /// let h = mesh.find_halfedge(a, b)?.expect("an edge joins its ends");
    /// assert_eq!(h.edge_key(), e);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn edge(&self, e: EdgeKey) -> Result<EdgeView<'_>> {
        Ok(EdgeView {
            mesh: self,
            e: self.check_edge(e)?,
        })
    }

    /// The half-edge from `a` to `b`, if they are joined by an edge.
    /// O(degree of `a`).
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey) if either vertex was
    /// removed.
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let v: Vec<_> = mesh.vertices().collect();
    /// let h = mesh.find_halfedge(v[0], v[1])?.expect("tetrahedron vertices are all joined");
    /// assert_eq!(mesh.halfedge(h)?.dest().key(), v[1]);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn find_halfedge(&self, a: VertexKey, b: VertexKey) -> Result<Option<HalfedgeKey>> {
        let a = self.check_vertex(a)?;
        let b = self.check_vertex(b)?;
        Ok(self.find_halfedge_raw(a, b).map(|h| self.hkey(h)))
    }

    pub(crate) fn find_halfedge_raw(&self, a: Vid, b: Vid) -> Option<Hid> {
        VertexOutgoing::new(self, a).find(|&h| self.dest(h) == b)
    }
}

impl<'m> HalfedgeView<'m> {
    #[inline]
    fn at(self, h: Hid) -> HalfedgeView<'m> {
        HalfedgeView { mesh: self.mesh, h }
    }

    /// The key.
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let next: meshloom::HalfedgeKey = mesh.halfedge(h)?.next().key(); // to keep
    /// assert!(mesh.contains_halfedge(next) && next != h);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn key(self) -> HalfedgeKey {
        self.mesh.hkey(self.h)
    }

    /// The opposite half-edge of the same edge.
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let h = mesh.halfedge(mesh.halfedges().next().unwrap())?;
    /// let t = h.twin();
    /// assert_eq!((t.origin().key(), t.dest().key()), (h.dest().key(), h.origin().key()));
    /// assert_eq!(t.edge().key(), h.edge().key());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn twin(self) -> HalfedgeView<'m> {
        self.at(self.h.twin())
    }

    /// The next half-edge around the face.
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// let h = mesh.halfedge(mesh.halfedges().next().unwrap())?;
    /// assert_eq!(h.next().origin().key(), h.dest().key());
    /// assert_eq!(h.next().face().key(), h.face().key());
    /// assert_eq!(h.next().next().next().next().key(), h.key()); // round a quad
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn next(self) -> HalfedgeView<'m> {
        self.at(self.mesh.next(self.h))
    }

    /// The previous half-edge around the face. O(degree of the origin).
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// let h = mesh.halfedge(mesh.halfedges().next().unwrap())?;
    /// assert_eq!(h.next().prev().key(), h.key());
    /// assert_eq!(h.prev().dest().key(), h.origin().key());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn prev(self) -> HalfedgeView<'m> {
        self.at(self.mesh.prev(self.h))
    }

    /// The vertex it leaves.
    ///
    /// ```
    /// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let mesh = meshloom::Mesh::from_polygons(&p, &[[0u32, 1, 2]])?;
    /// let v: Vec<_> = mesh.vertices().collect();
    /// let h = mesh.find_halfedge(v[0], v[1])?.unwrap();
    /// assert_eq!(mesh.halfedge(h)?.origin().key(), v[0]);
    /// assert_eq!(mesh.halfedge(h)?.origin().position(), Some([0.0, 0.0, 0.0]));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn origin(self) -> VertexView<'m> {
        VertexView {
            mesh: self.mesh,
            v: self.mesh.origin(self.h),
        }
    }

    /// The vertex it enters.
    ///
    /// ```
    /// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let mesh = meshloom::Mesh::from_polygons(&p, &[[0u32, 1, 2]])?;
    /// let v: Vec<_> = mesh.vertices().collect();
    /// let h = mesh.find_halfedge(v[0], v[1])?.unwrap();
    /// assert_eq!(mesh.halfedge(h)?.dest().key(), v[1]);
    /// assert_eq!(mesh.halfedge(h)?.dest().position(), Some([1.0, 0.0, 0.0]));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn dest(self) -> VertexView<'m> {
        VertexView {
            mesh: self.mesh,
            v: self.mesh.dest(self.h),
        }
    }

    /// The face (or hole) on its left.
    ///
    /// ```
    /// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let mesh = meshloom::Mesh::from_polygons(&p, &[[0u32, 1, 2]])?;
    /// let v: Vec<_> = mesh.vertices().collect();
    /// let h = mesh.find_halfedge(v[0], v[1])?.unwrap();
    /// // Built counter-clockwise: 0 -> 1 has the triangle on its left, its twin
    /// // the hole.
    /// assert!(!mesh.halfedge(h)?.face().is_hole());
    /// assert!(mesh.halfedge(h)?.twin().face().is_hole());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn face(self) -> FaceView<'m> {
        FaceView {
            mesh: self.mesh,
            f: self.mesh.face_of(self.h),
        }
    }

    /// Its edge.
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let e = mesh.halfedge(h)?.edge();
    /// assert!(e.halfedge(0).key() == h || e.halfedge(1).key() == h);
    /// assert_eq!(e.key(), h.edge_key());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn edge(self) -> EdgeView<'m> {
        EdgeView {
            mesh: self.mesh,
            e: self.h.edge(),
        }
    }

    /// Whether it lies in a hole, i.e. has no real face (the OpenMesh and
    /// pmp-library meaning of a boundary half-edge).
    ///
    /// ```
    /// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let mesh = meshloom::Mesh::from_polygons(&p, &[[0u32, 1, 2]])?;
    /// let v: Vec<_> = mesh.vertices().collect();
    /// let h = mesh.find_halfedge(v[0], v[1])?.unwrap();
    /// assert!(!mesh.halfedge(h)?.is_boundary()); // in the triangle
    /// assert!(mesh.halfedge(h)?.twin().is_boundary()); // in the hole
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn is_boundary(self) -> bool {
        self.mesh.in_hole(self.h)
    }

    /// The half-edge turned once clockwise around its origin:
    /// `twin().next()`.
    ///
    /// ```
    /// let mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedge(mesh.halfedges().next().unwrap())?;
    /// assert_eq!(h.rotate_cw().origin().key(), h.origin().key());
    /// let mut g = h;
    /// for _ in 0..5 {
    ///     g = g.rotate_cw(); // five turns round a vertex of valence 5
    /// }
    /// assert_eq!(g.key(), h.key());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn rotate_cw(self) -> HalfedgeView<'m> {
        self.twin().next()
    }

    /// The half-edge turned once counter-clockwise around its origin:
    /// `prev().twin()`.
    ///
    /// ```
    /// let mesh = meshloom::shapes::icosahedron();
    /// let h = mesh.halfedge(mesh.halfedges().next().unwrap())?;
    /// assert_eq!(h.rotate_cw().rotate_ccw().key(), h.key());
    /// assert_eq!(h.rotate_ccw().origin().key(), h.origin().key());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn rotate_ccw(self) -> HalfedgeView<'m> {
        self.prev().twin()
    }
}

impl<'m> VertexView<'m> {
    /// The key.
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let v = mesh.vertices().next().unwrap();
    /// let keys: Vec<meshloom::VertexKey> = mesh.vertex(v)?.neighbor_views().map(|w| w.key()).collect();
    /// assert_eq!(keys, mesh.vertex(v)?.neighbors().collect::<Vec<_>>());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn key(self) -> VertexKey {
        self.mesh.vkey(self.v)
    }

    /// One outgoing half-edge: the first that [`outgoing`](Self::outgoing)
    /// yields. On a boundary vertex it lies in a hole.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mesh = grid(2, 2, GridFaces::Quads);
    /// for v in mesh.vertices() {
    ///     let view = mesh.vertex(v)?;
    ///     assert_eq!(view.halfedge().origin().key(), v);
    ///     assert_eq!(view.halfedge().is_boundary(), view.is_boundary());
    /// }
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn halfedge(self) -> HalfedgeView<'m> {
        HalfedgeView {
            mesh: self.mesh,
            h: self.mesh.vertex_halfedge(self.v),
        }
    }

    /// The position, if the mesh has positions.
    ///
    /// ```
    /// let cube = meshloom::shapes::cube();
    /// let v = cube.vertices().next().unwrap();
    /// assert_eq!(cube.vertex(v)?.position(), Some(cube.position(v)?));
    /// let bare = meshloom::Mesh::from_faces(3, &[[0u32, 1, 2]])?; // no positions
    /// let w = bare.vertices().next().unwrap();
    /// assert_eq!(bare.vertex(w)?.position(), None);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn position(self) -> Option<[f64; 3]> {
        self.mesh
            .attrs()
            .positions()
            .and_then(|c| c.get(self.v.index()).copied())
    }

    /// Outgoing half-edges, clockwise seen from the side face normals point
    /// to, starting at [`halfedge`](Self::halfedge). Half-edges in holes are
    /// included: every outgoing half-edge comes exactly once, also at a
    /// vertex where several boundary loops meet.
    ///
    /// ```
    /// let mesh = meshloom::shapes::icosahedron();
    /// let v = mesh.vertex(mesh.vertices().next().unwrap())?;
    /// let out: Vec<_> = v.outgoing().collect();
    /// assert_eq!(out.len(), 5);
    /// assert_eq!(out[0], v.halfedge().key());
    /// assert_eq!(out[1], v.halfedge().rotate_cw().key());
    /// assert!(out.iter().all(|&h| mesh.halfedge(h).is_ok_and(|h| h.origin().key() == v.key())));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn outgoing(self) -> impl Iterator<Item = HalfedgeKey> + 'm {
        let m = self.mesh;
        VertexOutgoing::new(m, self.v).map(move |h| m.hkey(h))
    }

    /// Incoming half-edges: the twins of [`outgoing`](Self::outgoing), same
    /// order.
    ///
    /// ```
    /// let mesh = meshloom::shapes::icosahedron();
    /// let v = mesh.vertex(mesh.vertices().next().unwrap())?;
    /// assert_eq!(v.incoming().next(), Some(v.halfedge().twin().key()));
    /// assert!(v.incoming().all(|h| mesh.halfedge(h).is_ok_and(|h| h.dest().key() == v.key())));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn incoming(self) -> impl Iterator<Item = HalfedgeKey> + 'm {
        let m = self.mesh;
        VertexOutgoing::new(m, self.v).map(move |h| m.hkey(h.twin()))
    }

    /// Neighbouring vertices (the ends of the outgoing half-edges), same
    /// order.
    ///
    /// ```
    /// let mesh = meshloom::shapes::disk(6); // vertex 0 is the centre
    /// let centre = mesh.vertices().next().unwrap();
    /// let ring: Vec<_> = mesh.vertex(centre)?.neighbors().collect();
    /// assert_eq!(ring.len(), 6);
    /// assert!(ring.iter().all(|&w| mesh.vertex(w).is_ok_and(|w| w.is_boundary())));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn neighbors(self) -> impl Iterator<Item = VertexKey> + 'm {
        let m = self.mesh;
        VertexNeighbors::new(m, self.v).map(move |w| m.vkey(w))
    }

    /// Neighbouring vertices as views, same order as
    /// [`neighbors`](Self::neighbors). A view needs no key to be made or
    /// checked, and [`AttrView::at`](crate::attr::AttrView::at) reads its
    /// value without a generation check: the fastest one-ring loop, faster
    /// than [`neighbors`](Self::neighbors) and
    /// [`AttrView::get`](crate::attr::AttrView::get).
    ///
    /// ```
    /// let mesh = meshloom::shapes::icosahedron();
    /// let pos = mesh.position_attr().unwrap();
    /// let view = mesh.attr_view(&pos)?;
    /// let v = mesh.vertex(mesh.vertices().next().unwrap())?;
    /// let mut centre = [0.0; 3];
    /// for w in v.neighbor_views() {
    ///     let p = view.at(w).unwrap();
    ///     (0..3).for_each(|i| centre[i] += p[i] / 5.0);
    /// }
    /// assert_eq!(v.neighbor_views().count(), 5);
    /// assert_eq!(
    ///     v.neighbor_views().map(|w| w.key()).collect::<Vec<_>>(),
    ///     v.neighbors().collect::<Vec<_>>()
    /// );
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn neighbor_views(self) -> impl Iterator<Item = VertexView<'m>> + 'm {
        let mesh = self.mesh;
        VertexNeighbors::new(mesh, self.v).map(move |v| VertexView { mesh, v })
    }

    /// Faces around the vertex (holes skipped), same order: the face left of
    /// each outgoing half-edge. A face is listed once per corner it has here.
    ///
    /// ```
    /// let mesh = meshloom::shapes::disk(6);
    /// let rim = mesh.vertex(mesh.vertices().nth(1).unwrap())?; // on the boundary
    /// assert_eq!((rim.degree(), rim.faces().count()), (3, 2)); // the hole is skipped
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn faces(self) -> impl Iterator<Item = FaceKey> + 'm {
        let m = self.mesh;
        VertexOutgoing::new(m, self.v)
            .map(move |h| m.face_of(h))
            .filter(move |&f| !m.is_hole(f))
            .map(move |f| m.fkey(f))
    }

    /// Edges at the vertex, same order.
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// let v = mesh.vertex(mesh.vertices().next().unwrap())?;
    /// assert_eq!(v.edges().count(), 3);
    /// assert!(v.edges().all(|e| mesh.edge(e).is_ok_and(|e| e.vertices().contains(&v.key()))));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn edges(self) -> impl Iterator<Item = EdgeKey> + 'm {
        let m = self.mesh;
        VertexOutgoing::new(m, self.v).map(move |h| m.ekey(h.edge()))
    }

    /// Number of edges at the vertex.
    ///
    /// ```
    /// let mesh = meshloom::shapes::octahedron();
    /// assert!(mesh.vertices().all(|v| mesh.vertex(v).is_ok_and(|v| v.degree() == 4)));
    /// ```
    #[inline]
    pub fn degree(self) -> usize {
        VertexOutgoing::new(self.mesh, self.v).count()
    }

    /// Whether a hole touches the vertex. O(1): a boundary vertex's
    /// [`halfedge`](Self::halfedge) lies in a hole (rule 11 of
    /// [`validate`](crate::validate)).
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::icosahedron();
    /// let v = mesh.vertices().next().unwrap();
    /// assert!(!mesh.vertex(v)?.is_boundary());
    /// let f = mesh.vertex(v)?.faces().next().unwrap();
    /// mesh.remove_face(f)?;
    /// assert!(mesh.vertex(v)?.is_boundary());
    /// assert!(mesh.vertex(v)?.halfedge().is_boundary());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn is_boundary(self) -> bool {
        self.mesh.on_boundary(self.v)
    }
}

impl<'m> FaceView<'m> {
    /// The key.
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let h = mesh.face(f)?.halfedge().twin();
    /// let across: meshloom::FaceKey = h.face().key(); // the neighbour, to keep
    /// assert!(mesh.face(f)?.neighbors().any(|g| g == across));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn key(self) -> FaceKey {
        self.mesh.fkey(self.f)
    }

    /// The face's first half-edge: the first that
    /// [`halfedges`](Self::halfedges) yields.
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// let f = mesh.face(mesh.faces().next().unwrap())?;
    /// assert_eq!(f.halfedge().face().key(), f.key());
    /// assert_eq!(f.halfedges().next(), Some(f.halfedge().key()));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn halfedge(self) -> HalfedgeView<'m> {
        HalfedgeView {
            mesh: self.mesh,
            h: self.mesh.face_halfedge(self.f),
        }
    }

    /// Whether this is a hole (the outside of a boundary loop).
    ///
    /// ```
    /// let mesh = meshloom::shapes::disk(4);
    /// let holes: Vec<_> = mesh.faces_and_holes().filter(|&f| mesh.face(f).is_ok_and(|f| f.is_hole())).collect();
    /// assert_eq!(holes, mesh.holes().collect::<Vec<_>>());
    /// assert_eq!(holes.len(), 1);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn is_hole(self) -> bool {
        self.mesh.is_hole(self.f)
    }

    /// The half-edges around the face, following `next`: counter-clockwise
    /// for a face, starting at [`halfedge`](Self::halfedge).
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// let f = mesh.face(mesh.faces().next().unwrap())?;
    /// let hs: Vec<_> = f.halfedges().collect();
    /// assert_eq!(hs.len(), 4);
    /// for (i, &h) in hs.iter().enumerate() {
    ///     assert_eq!(mesh.halfedge(h)?.next().key(), hs[(i + 1) % 4]);
    /// }
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn halfedges(self) -> impl Iterator<Item = HalfedgeKey> + 'm {
        let m = self.mesh;
        FaceHalfedges::new(m, self.f).map(move |h| m.hkey(h))
    }

    /// The corners (origins of [`halfedges`](Self::halfedges)), same order.
    ///
    /// ```
    /// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    /// let mesh = meshloom::Mesh::from_polygons(&p, &[[0u32, 1, 2, 3]])?;
    /// let f = mesh.faces().next().unwrap();
    /// let corners: Vec<_> = mesh.face(f)?.vertices().map(|v| mesh.position(v)).collect::<Result<_, _>>()?;
    /// assert_eq!(corners, p); // the order given when building
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn vertices(self) -> impl Iterator<Item = VertexKey> + 'm {
        let m = self.mesh;
        FaceCorners::new(m, self.f).map(move |v| m.vkey(v))
    }

    /// The sides, same order.
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// for e in mesh.face(f)?.edges() {
    ///     assert!(mesh.edge(e)?.faces().contains(&Some(f)));
    /// }
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn edges(self) -> impl Iterator<Item = EdgeKey> + 'm {
        let m = self.mesh;
        FaceHalfedges::new(m, self.f).map(move |h| m.ekey(h.edge()))
    }

    /// The faces across each side, same order, holes skipped. A face sharing
    /// two sides with this one is listed twice.
    ///
    /// ```
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mesh = grid(2, 2, GridFaces::Quads);
    /// let corner = mesh.face(mesh.faces().next().unwrap())?; // a corner cell
    /// assert_eq!((corner.degree(), corner.neighbors().count()), (4, 2)); // holes skipped
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn neighbors(self) -> impl Iterator<Item = FaceKey> + 'm {
        let m = self.mesh;
        FaceHalfedges::new(m, self.f)
            .map(move |h| m.face_of(h.twin()))
            .filter(move |&g| !m.is_hole(g))
            .map(move |g| m.fkey(g))
    }

    /// Number of sides.
    ///
    /// ```
    /// let mesh = meshloom::shapes::icosphere(1);
    /// assert!(mesh.faces().all(|f| mesh.face(f).is_ok_and(|f| f.degree() == 3)));
    /// ```
    #[inline]
    pub fn degree(self) -> usize {
        FaceHalfedges::new(self.mesh, self.f).count()
    }
}

impl<'m> EdgeView<'m> {
    /// The key.
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let h = mesh.halfedges().next().unwrap();
    /// let e: meshloom::EdgeKey = mesh.halfedge(h)?.edge().key();
    /// assert_eq!(e, h.edge_key());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn key(self) -> EdgeKey {
        self.mesh.ekey(self.e)
    }

    /// Half-edge `side` (0 or 1; taken modulo 2).
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let e = mesh.edge(mesh.edges().next().unwrap())?;
    /// assert_eq!(e.halfedge(0).twin().key(), e.halfedge(1).key());
    /// assert_eq!(e.halfedge(2).key(), e.halfedge(0).key());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn halfedge(self, side: u32) -> HalfedgeView<'m> {
        HalfedgeView {
            mesh: self.mesh,
            h: self.e.halfedge(side),
        }
    }

    /// The two ends: origin and dest of half-edge 0.
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let e = mesh.edge(mesh.edges().next().unwrap())?;
    /// let [a, b] = e.vertices();
    /// assert_eq!((a, b), (e.halfedge(0).origin().key(), e.halfedge(0).dest().key()));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn vertices(self) -> [VertexKey; 2] {
        let h = self.halfedge(0);
        [h.origin().key(), h.dest().key()]
    }

    /// The faces on either side, `None` for a hole.
    ///
    /// ```
    /// let mesh = meshloom::shapes::disk(6);
    /// for e in mesh.edges() {
    ///     let e = mesh.edge(e)?;
    ///     let [a, b] = e.faces();
    ///     // Boundary edges have a hole on one side; inner edges a face on both.
    ///     assert_eq!(a.is_none() || b.is_none(), e.is_boundary());
    /// }
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn faces(self) -> [Option<FaceKey>; 2] {
        self.e.halfedges().map(|h| {
            let f = self.mesh.face_of(h);
            (!self.mesh.is_hole(f)).then(|| self.mesh.fkey(f))
        })
    }

    /// Whether a hole lies on either side.
    ///
    /// ```
    /// let mesh = meshloom::shapes::disk(6); // 12 edges, 6 on the rim
    /// let rim = mesh.edges().filter(|&e| mesh.edge(e).is_ok_and(|e| e.is_boundary()));
    /// assert_eq!(rim.count(), 6);
    /// let closed = meshloom::shapes::cube();
    /// assert!(closed.edges().all(|e| closed.edge(e).is_ok_and(|e| !e.is_boundary())));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn is_boundary(self) -> bool {
        let [h, t] = self.e.halfedges();
        self.mesh.in_hole(h) || self.mesh.in_hole(t)
    }
}

impl std::fmt::Debug for HalfedgeView<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "HalfedgeView({:?})", self.key())
    }
}
impl std::fmt::Debug for VertexView<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "VertexView({:?})", self.key())
    }
}
impl std::fmt::Debug for FaceView<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "FaceView({:?})", self.key())
    }
}
impl std::fmt::Debug for EdgeView<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "EdgeView({:?})", self.key())
    }
}
