//! Spatial queries over a mesh's faces: [`FaceTree`], a bounding volume
//! hierarchy for picking (ray casts), projection (closest points), radius
//! searches, snapping (nearest vertex or edge), picking under a cursor
//! (the vertex or edge nearest a [`Cone`]'s axis, optionally only those the
//! surface does not hide) and inside tests (generalized winding numbers).
//!
//! # How it is built
//!
//! Every face (holes are not faces) is cut into the fan of triangles
//! `(c₀, cᵢ, cᵢ₊₁)` over its corners `c₀ … cₙ₋₁` in
//! [`FaceView::vertices`](crate::FaceView::vertices) order; a query's answer
//! names the face and its fan triangle's corners ([`FaceCoords`]). The
//! triangles' corner positions are copied into the tree in leaf order (72
//! bytes a triangle), so a query reads the tree's memory only. The tree is
//! a binned surface-area-heuristic (SAH) hierarchy with 16 bins per axis,
//! stored as a flat array of nodes, children after their parent and side
//! by side (a walk tests both, and loads them together), built in one pass
//! with an explicit stack. Node boxes are `f32`, rounded outwards: a ray
//! cast is bound by loading nodes, and 32-byte nodes load faster than
//! 56-byte ones. Ray casts walk a 4-wide copy of the hierarchy (four
//! children's boxes side by side, tested together in `f32`), made afresh
//! after every build, refit and update.
//!
//! # Kept honest under edits
//!
//! A tree records the mesh it was built for and that mesh's
//! [`revision`](crate::Mesh::revision). Every query takes the mesh and
//! compares: a mesh that changed since (or another mesh) is refused with
//! [`QueryError::StaleTree`], never answered from old geometry. After
//! positions move, [`FaceTree::refit`] recomputes the boxes in O(n)
//! (checking that the faces did not change); after any edit with change
//! tracking on, [`FaceTree::update`] applies the journal's change set
//! (refusing one that does not cover exactly the edits since the tree's
//! revision); otherwise rebuild.
//!
//! # Precision
//!
//! Triangle tests and distances are computed in `f64`. Box tests are
//! widened (by a relative 1e-12 in `f64`; a ray's `f32` box tests round
//! its origin outwards and widen by a relative 2⁻²⁰, and fall back to
//! `f64` for rays beyond `f32`'s range or parallel to an axis plane), so
//! the tree never prunes a triangle that the triangle test would accept: the first hit and the closest point equal a brute-force loop's
//! over the same triangles (on ties, the distance is equal and the face may
//! be either of the tied ones). Rays are tested against both sides of each
//! triangle (Möller–Trumbore); a degenerate triangle is never hit by a
//! ray, but it still has closest points.
//!
//! ```
//! use meshloom::query::{FaceTree, Ray};
//! let mesh = meshloom::shapes::icosphere(3);
//! let tree = FaceTree::build(&mesh)?;
//! let hit = tree.ray_cast(&mesh, Ray::new([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]))?.expect("a hit");
//! assert!((hit.t - 4.0).abs() < 0.01); // the unit sphere's near side
//! assert!(tree.contains(&mesh, [0.1, 0.2, 0.3])?);
//! assert!(!tree.contains(&mesh, [2.0, 0.0, 0.0])?);
//! # Ok::<(), meshloom::query::QueryError>(())
//! ```

mod build;
mod closest;
mod error;
mod hinted;
mod intersect;
mod pick;
mod ray;
mod segments;
mod update;
mod wide;
mod winding;

pub use closest::{Closest, Nearest};
pub use error::QueryError;
pub use pick::{Cone, NearestEdge, Occlusion, Pick};
pub use ray::{Hit, Ray};
pub use update::UpdateReport;
pub use winding::WindingMode;

pub(crate) use segments::SegmentTree;
#[doc(hidden)]
pub use {
    closest::triangle_closest,
    intersect::{intersect_beyond_shared, triangles_meet},
    pick::{point_in_cone, segment_in_cone},
    ray::triangle_hit,
};

use crate::keys::{FaceKey, VertexKey};
use crate::mesh::{Mesh, Stamp};
use crate::vec3::V3;

/// A bounding volume hierarchy over a mesh's faces, for ray casts, closest
/// points, radius queries and winding numbers (see the [module](self)).
///
/// ```
/// use meshloom::query::{FaceTree, QueryError, Ray};
/// let mut mesh = meshloom::shapes::cube();
/// let mut tree = FaceTree::build(&mesh)?;
/// let v = mesh.vertices().next().unwrap();
/// mesh.set_position(v, [-0.7, -0.7, -0.7]).unwrap();
/// let ray = Ray::new([0.0, 0.0, -3.0], [0.0, 0.0, 1.0]);
/// // The mesh moved: the tree refuses until refitted.
/// assert!(matches!(tree.ray_cast(&mesh, ray), Err(QueryError::StaleTree { .. })));
/// tree.refit(&mesh)?;
/// assert!(tree.ray_cast(&mesh, ray)?.is_some());
/// # Ok::<(), QueryError>(())
/// ```
#[derive(Clone, Debug)]
pub struct FaceTree {
    /// The mesh and revision the boxes were computed for.
    stamp: Stamp,
    /// Depth-first: an inner node's first child is the next node.
    nodes: Vec<Node>,
    /// The fan triangles' corner positions, in leaf order.
    tris: Vec<[V3; 3]>,
    /// What each triangle is part of, in leaf order.
    meta: Vec<TriMeta>,
    /// Per node: the far-field data of the winding number, made by the
    /// first winding-number query (a tree for rays or closest points never
    /// pays for it), kept by refits and updates once made.
    dipoles: std::sync::OnceLock<Vec<Dipole>>,
    /// The ray casts' 4-wide copy of `nodes` (see the `wide` module).
    wide: Vec<wide::WideNode>,
    /// The faces in build order, with their corners' span in `corners`
    /// (for the refit's check that the faces did not change).
    faces: Vec<(FaceKey, u32, u32)>,
    /// Every face's corners, face after face.
    corners: Vec<VertexKey>,
    /// Triangles reinserted by [`update`](FaceTree::update) since the
    /// build (see the `update` module's rebuild rule).
    churn: usize,
    /// Slots of `tris` and `meta` no leaf holds any more (left behind by
    /// [`update`](FaceTree::update), which edits in place).
    dead_tris: usize,
    /// Records of `faces` of faces gone or re-added since (their length is
    /// [`GONE`]).
    dead_faces: usize,
}

/// The length of a face record whose face is gone.
const GONE: u32 = u32::MAX;

/// A node: a box, then either a leaf's triangles `first .. first + count`
/// (`0 < count < INNER`), or an inner node (`count ≥ INNER`) whose children
/// are the node `count − INNER` places after it (the next node, as a build
/// lays them out; farther where [`FaceTree::update`] rewired it) and node
/// `first`. A child's index is always above its parent's.
///
/// The box is kept in `f32`, rounded outwards (so it still holds every
/// `f64` point it was made from): 32 bytes a node instead of 56, which is
/// what a ray cast pays for, as it is bound by loading nodes.
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: [f32; 3],
    hi: [f32; 3],
    first: u32,
    count: u32,
}

/// The flag of an inner node, above the offset of its first child.
const INNER: u32 = 1 << 31;

impl Node {
    /// Whether the node is a leaf.
    #[inline(always)]
    fn is_leaf(&self) -> bool {
        (self.count as i32) > 0
    }

    /// An inner node's children, the node being at index `at`.
    #[inline(always)]
    fn children(&self, at: usize) -> (usize, usize) {
        (at + (self.count - INNER) as usize, self.first as usize)
    }

    /// The count of an inner node at `at` whose first child is `a`.
    fn inner(at: usize, a: usize) -> u32 {
        INNER | (a - at) as u32
    }

    /// The node at `from` moved to `to` (below it): an inner node keeps
    /// its first child.
    fn moved(mut self, from: usize, to: usize) -> Node {
        if !self.is_leaf() {
            self.count = Node::inner(to, from + (self.count - INNER) as usize);
        }
        self
    }

    /// A node with the box `lo`–`hi` (rounded outwards).
    fn new(lo: V3, hi: V3, first: u32, count: u32) -> Node {
        let mut n = Node {
            lo: [0.0; 3],
            hi: [0.0; 3],
            first,
            count,
        };
        n.set_box(lo, hi);
        n
    }

    /// The box's low corner.
    #[inline(always)]
    fn lo(&self) -> V3 {
        self.lo.map(f64::from)
    }

    /// The box's high corner.
    #[inline(always)]
    fn hi(&self) -> V3 {
        self.hi.map(f64::from)
    }

    /// Set the box to hold `lo`–`hi`.
    fn set_box(&mut self, lo: V3, hi: V3) {
        self.lo = lo.map(round_down);
        self.hi = hi.map(round_up);
    }
}

/// `f(node, triangles)` for every leaf reachable from the root of `nodes`.
fn for_each_leaf(nodes: &[Node], mut f: impl FnMut(usize, std::ops::Range<usize>)) {
    let mut stack = Vec::new();
    if !nodes.is_empty() {
        stack.push(0);
    }
    while let Some(i) = stack.pop() {
        let n = nodes[i];
        if n.is_leaf() {
            f(i, n.first as usize..(n.first + n.count) as usize);
        } else {
            let (a, b) = n.children(i);
            stack.push(b);
            stack.push(a);
        }
    }
}

/// The largest `f32` at most `x` (−∞ below the `f32` range).
fn round_down(x: f64) -> f32 {
    -round_up(-x)
}

/// The smallest `f32` at least `x` (+∞ above the `f32` range).
fn round_up(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) >= x || y.is_nan() {
        return y;
    }
    // One step up from a finite `y` below `x` (`f32::next_up` needs Rust
    // 1.86).
    if y == 0.0 {
        f32::from_bits(1)
    } else if y > 0.0 {
        f32::from_bits(y.to_bits() + 1)
    } else {
        f32::from_bits(y.to_bits() - 1)
    }
}

/// A fan triangle's face, corners and place in the face's fan.
#[derive(Clone, Copy, Debug)]
struct TriMeta {
    face: FaceKey,
    /// Its corners' vertices.
    v: [VertexKey; 3],
    /// The face corner index of its second corner (its corners are the
    /// face's `0`, `fan`, `fan + 1`).
    fan: u32,
}

/// A node's triangles seen from far away (Barill et al. 2018): their total
/// area vector, area-weighted centroid, a radius about it that holds them
/// all, and the next two terms of their field's Taylor series about the
/// centre (`f32`: they only correct the far field).
#[derive(Clone, Copy, Debug, Default)]
struct Dipole {
    area: V3,
    centre: V3,
    /// The triangles' total (unsigned) area, the centre's weight.
    weight: f64,
    radius: f64,
    /// The symmetric part of `∫ (x - centre) ⊗ n dA`: `xx, yy, zz, xy, yz,
    /// zx`.
    moment: [f32; 6],
    /// The symmetric part of `∫ (x - centre) ⊗ (x - centre) ⊗ n dA`: `xxx,
    /// yyy, zzz, xxy, xxz, yyx, yyz, zzx, zzy, xyz`.
    tensor: [f32; 10],
}

impl FaceTree {
    /// Build the tree over `mesh`'s faces.
    ///
    /// # Errors
    /// [`QueryError::NoPositions`] when the mesh has no position column.
    ///
    /// # Complexity
    /// O(n log n) time for n fan triangles; about 72 + 40 bytes a triangle,
    /// 32 a node, 128 a node of the rays' 4-wide copy (about one for three
    /// triangles), plus 8 bytes a corner; the first winding-number query
    /// adds 128 a node of far-field data (O(n) once).
    ///
    /// ```
    /// let mesh = meshloom::shapes::torus(24, 12, 1.0, 0.3).unwrap();
    /// let tree = meshloom::query::FaceTree::build(&mesh)?;
    /// assert_eq!(tree.triangle_count(), 2 * mesh.face_count()); // quads, two triangles each
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn build(mesh: &Mesh) -> Result<FaceTree, QueryError> {
        let pos = mesh.position_slots().ok_or(QueryError::NoPositions)?;
        let mut faces = Vec::with_capacity(mesh.face_count());
        let mut corners = Vec::with_capacity(mesh.face_count() * 3);
        let mut tris = Vec::with_capacity(mesh.face_count());
        let mut meta = Vec::with_capacity(mesh.face_count());
        for f in mesh.faces() {
            let start = corners.len();
            let view = mesh.face(f).expect("a listed face is live");
            corners.extend(view.vertices());
            let cs = &corners[start..];
            faces.push((f, start as u32, cs.len() as u32));
            for i in 1..cs.len().saturating_sub(1) {
                let v = [cs[0], cs[i], cs[i + 1]];
                tris.push(v.map(|v| pos[v.index()]));
                meta.push(TriMeta {
                    face: f,
                    v,
                    fan: i as u32,
                });
            }
        }
        let (nodes, order) = build::build(&tris);
        let tris: Vec<[V3; 3]> = order.iter().map(|&i| tris[i as usize]).collect();
        let meta: Vec<TriMeta> = order.iter().map(|&i| meta[i as usize]).collect();
        let mut tree = FaceTree {
            stamp: mesh.stamp(),
            nodes,
            tris,
            meta,
            dipoles: std::sync::OnceLock::new(),
            wide: Vec::with_capacity(order.len() / 3 + 1),
            faces,
            corners,
            churn: 0,
            dead_tris: 0,
            dead_faces: 0,
        };
        wide::collapse(&tree.nodes, &mut tree.wide);
        Ok(tree)
    }

    /// Recompute the boxes after `mesh`'s positions moved, without
    /// rebuilding: O(n). The faces must be the ones the tree was built over
    /// with the same corners; only positions may have changed. Afterwards
    /// the tree answers for `mesh` as it is.
    ///
    /// The hierarchy keeps its shape, so after large motions a rebuild may
    /// answer faster; the answers are the same.
    ///
    /// # Errors
    /// [`QueryError::NoPositions`]; [`QueryError::StaleTree`] (with
    /// `same_mesh` false) for another mesh; [`QueryError::FaceCountChanged`]
    /// or [`QueryError::TopologyChanged`] when the faces changed (the tree
    /// is left as it was).
    ///
    /// ```
    /// use meshloom::query::FaceTree;
    /// let mut mesh = meshloom::shapes::icosphere(2);
    /// let mut tree = FaceTree::build(&mesh)?;
    /// for p in mesh.position_slots_mut().unwrap() {
    ///     p[0] += 10.0;
    /// }
    /// tree.refit(&mesh)?;
    /// let c = tree.closest_point(&mesh, [10.0, 0.0, 3.0], None)?.unwrap();
    /// assert!((c.distance - 2.0).abs() < 0.01);
    /// # Ok::<(), meshloom::query::QueryError>(())
    /// ```
    pub fn refit(&mut self, mesh: &Mesh) -> Result<(), QueryError> {
        if mesh.stamp().mesh != self.stamp.mesh {
            return Err(self.stale(mesh));
        }
        let pos = mesh.position_slots().ok_or(QueryError::NoPositions)?;
        if mesh.face_count() != self.face_count() {
            return Err(QueryError::FaceCountChanged {
                built: self.face_count(),
                now: mesh.face_count(),
            });
        }
        for &(f, start, len) in self.faces.iter().filter(|r| r.2 != GONE) {
            let view = mesh
                .face(f)
                .map_err(|_| QueryError::TopologyChanged { face: f })?;
            let was = &self.corners[start as usize..(start + len) as usize];
            let mut now = view.vertices();
            if !was.iter().all(|&v| now.next() == Some(v)) || now.next().is_some() {
                return Err(QueryError::TopologyChanged { face: f });
            }
        }
        let (tris, meta) = (&mut self.tris, &self.meta);
        for_each_leaf(&self.nodes, |_, range| {
            for (t, m) in tris[range.clone()].iter_mut().zip(&meta[range]) {
                *t = m.v.map(|v| pos[v.index()]);
            }
        });
        let order = self.bottom_up();
        for &i in &order {
            self.fit_box(i as usize);
        }
        if let Some(dipoles) = self.dipoles.get_mut() {
            for &i in &order {
                dipoles[i as usize] = node_dipole(&self.nodes, &self.tris, dipoles, i as usize);
            }
        }
        wide::collapse(&self.nodes, &mut self.wide);
        self.stamp = mesh.stamp();
        Ok(())
    }

    /// Number of fan triangles (a face of n corners gives n − 2).
    pub fn triangle_count(&self) -> usize {
        self.tris.len() - self.dead_tris
    }

    /// Number of faces the tree was built over.
    pub fn face_count(&self) -> usize {
        self.faces.len() - self.dead_faces
    }

    /// Number of nodes of the hierarchy.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Heap bytes the tree holds.
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of;
        self.nodes.capacity() * size_of::<Node>()
            + self.tris.capacity() * size_of::<[V3; 3]>()
            + self.meta.capacity() * size_of::<TriMeta>()
            + self.dipoles.get().map_or(0, Vec::capacity) * size_of::<Dipole>()
            + self.wide.capacity() * size_of::<wide::WideNode>()
            + self.faces.capacity() * size_of::<(FaceKey, u32, u32)>()
            + self.corners.capacity() * size_of::<VertexKey>()
    }

    /// The revision of the mesh the tree answers for (see
    /// [`Mesh::revision`]).
    pub fn revision(&self) -> u64 {
        self.stamp.edits
    }

    /// Whether the tree answers for `mesh` as it is now (the same mesh, no
    /// edit since the build or the last refit).
    pub fn is_current(&self, mesh: &Mesh) -> bool {
        mesh.stamp() == self.stamp
    }

    /// `Ok` if the tree answers for `mesh`.
    fn check(&self, mesh: &Mesh) -> Result<(), QueryError> {
        if mesh.stamp() == self.stamp {
            Ok(())
        } else {
            Err(self.stale(mesh))
        }
    }

    fn stale(&self, mesh: &Mesh) -> QueryError {
        QueryError::StaleTree {
            built: self.stamp.edits,
            now: mesh.stamp().edits,
            same_mesh: mesh.stamp().mesh == self.stamp.mesh,
        }
    }

    /// The nodes reachable from the root, children before parents.
    fn bottom_up(&self) -> Vec<u32> {
        let mut order = Vec::with_capacity(self.nodes.len());
        if !self.nodes.is_empty() {
            order.push(0);
        }
        let mut at = 0;
        while at < order.len() {
            let i = order[at] as usize;
            if !self.nodes[i].is_leaf() {
                let (a, b) = self.nodes[i].children(i);
                order.extend([a as u32, b as u32]);
            }
            at += 1;
        }
        order.reverse();
        order
    }

    /// Node `i`'s box from its triangles or its children's boxes.
    fn fit_box(&mut self, i: usize) {
        let n = self.nodes[i];
        if n.is_leaf() {
            let (lo, hi) =
                build::bounds(&self.tris[n.first as usize..(n.first + n.count) as usize]);
            self.nodes[i].set_box(lo, hi);
        } else {
            let (na, nb) = (self.nodes[n.children(i).0], self.nodes[n.children(i).1]);
            self.nodes[i].lo = std::array::from_fn(|k| na.lo[k].min(nb.lo[k]));
            self.nodes[i].hi = std::array::from_fn(|k| na.hi[k].max(nb.hi[k]));
        }
    }

    /// The winding number's far-field data of every node (made on first
    /// use).
    fn far_field(&self) -> &[Dipole] {
        self.dipoles.get_or_init(|| self.far_field_afresh())
    }

    /// The far-field data of every reachable node from the triangles,
    /// children before parents (unreachable slots hold a default).
    fn far_field_afresh(&self) -> Vec<Dipole> {
        let mut dipoles = vec![Dipole::default(); self.nodes.len()];
        for i in self.bottom_up() {
            dipoles[i as usize] = node_dipole(&self.nodes, &self.tris, &dipoles, i as usize);
        }
        dipoles
    }

    /// `f(node, triangles)` for every leaf reachable from the root.
    fn for_each_leaf(&self, f: impl FnMut(usize, std::ops::Range<usize>)) {
        for_each_leaf(&self.nodes, f);
    }

    /// The face coordinates of fan triangle `tri` with weights `w`.
    fn coords(&self, tri: usize, w: [f64; 3]) -> FaceCoords {
        let fan = self.meta[tri].fan as usize;
        FaceCoords {
            corners: [0, fan, fan + 1],
            weights: w,
        }
    }
}

/// Node `i`'s far-field data from its triangles or its children's (in
/// `dipoles`), with a radius about its centre that holds its box.
fn node_dipole(nodes: &[Node], tris: &[[V3; 3]], dipoles: &[Dipole], i: usize) -> Dipole {
    let n = nodes[i];
    let d = if n.is_leaf() {
        winding::leaf_dipole(&tris[n.first as usize..(n.first + n.count) as usize])
    } else {
        let (a, b) = n.children(i);
        winding::merge_dipoles(dipoles[a], dipoles[b])
    };
    winding::with_radius(d, n.lo(), n.hi())
}

/// Where on a face a point lies: weights of three of the face's corners
/// (indices into its corners in [`FaceView::vertices`](crate::FaceView::vertices)
/// order) that sum to 1 and give the point as their weighted sum. For a
/// triangle the corners are `[0, 1, 2]` and the weights its barycentric
/// coordinates; for a polygon they are the corners `0, i, i + 1` of the fan
/// triangle the point lies in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceCoords {
    /// Indices of three of the face's corners.
    pub corners: [usize; 3],
    /// Their weights, summing to 1.
    pub weights: [f64; 3],
}

#[cfg(test)]
mod tests;
