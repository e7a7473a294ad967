//! Breadth- and depth-first walkers over vertices or faces.

use std::collections::VecDeque;
use std::marker::PhantomData;

use crate::error::{Error, Refusal, Result};
use crate::keys::{AnyKey, FaceKey, VertexKey};
use crate::layout::{Fid, Vid};
use crate::mesh::Mesh;

mod sealed {
    pub trait Sealed {}
    impl Sealed for crate::keys::VertexKey {}
    impl Sealed for crate::keys::FaceKey {}
}

/// What a walk can visit: [`VertexKey`] (neighbours through edges) or
/// [`FaceKey`] (neighbours through shared edges, holes never visited).
/// Sealed: the walkers are defined for these two kinds only.
pub trait Node: Copy + sealed::Sealed {
    /// The slot of `key`, checked: [`Error::StaleKey`] for a removed
    /// element; for faces also [`Refusal::Hole`] (a walk over faces does not
    /// enter holes). `op` names the caller in the error.
    #[doc(hidden)]
    fn start_slot(mesh: &Mesh, key: Self, op: &'static str) -> Result<usize>;
    /// Whether slot `i` holds an element a walk may visit.
    #[doc(hidden)]
    fn visitable(mesh: &Mesh, i: usize) -> bool;
    /// The key of visitable slot `i`.
    #[doc(hidden)]
    fn key_of(mesh: &Mesh, i: usize) -> Self;
    /// Append the slots of the neighbours of visitable slot `i`, in ring
    /// order (counter-clockwise for faces, clockwise around a vertex).
    #[doc(hidden)]
    fn neighbors(mesh: &Mesh, i: usize, out: &mut Vec<usize>);
}

impl Node for VertexKey {
    fn start_slot(mesh: &Mesh, key: Self, _op: &'static str) -> Result<usize> {
        Ok(mesh.check_vertex(key)?.index())
    }
    fn visitable(mesh: &Mesh, i: usize) -> bool {
        mesh.vertex_live(i)
    }
    fn key_of(mesh: &Mesh, i: usize) -> Self {
        mesh.vkey(Vid::new(i as u32))
    }
    fn neighbors(mesh: &Mesh, i: usize, out: &mut Vec<usize>) {
        out.extend(
            mesh.outgoing(Vid::new(i as u32))
                .map(|h| mesh.dest(h).index()),
        );
    }
}

impl Node for FaceKey {
    fn start_slot(mesh: &Mesh, key: Self, op: &'static str) -> Result<usize> {
        let f = mesh.check_face(key)?;
        if mesh.is_hole(f) {
            return Err(Error::Refused {
                op,
                key: AnyKey::Face(key),
                reason: Refusal::Hole,
            });
        }
        Ok(f.index())
    }
    fn visitable(mesh: &Mesh, i: usize) -> bool {
        mesh.face_live(i) && !mesh.is_hole(Fid::new(i as u32))
    }
    fn key_of(mesh: &Mesh, i: usize) -> Self {
        mesh.fkey(Fid::new(i as u32))
    }
    fn neighbors(mesh: &Mesh, i: usize, out: &mut Vec<usize>) {
        out.extend(
            mesh.face_halfedges(Fid::new(i as u32))
                .map(|h| mesh.face_of(h.twin()))
                .filter(|&g| !mesh.is_hole(g))
                .map(|g| g.index()),
        );
    }
}

/// A visited set that grows with the mesh.
#[derive(Clone, Debug, Default)]
struct Visited(Vec<bool>);

impl Visited {
    /// Mark `i`; whether it was unmarked.
    fn insert(&mut self, i: usize) -> bool {
        if i >= self.0.len() {
            self.0.resize(i + 1, false);
        }
        !std::mem::replace(&mut self.0[i], true)
    }

    fn contains(&self, i: usize) -> bool {
        self.0.get(i).copied().unwrap_or(false)
    }
}

/// A breadth-first walk: elements in order of their distance (in edges, or
/// in shared sides for faces) from the start, each once, the start first.
///
/// Holds only a queue and a visited set; pass the mesh to each
/// [`next`](Bfs::next).
///
/// # Complexity
/// O(V + E) for a whole walk over vertices, O(F + E) over faces; O(slots)
/// memory.
///
/// # Examples
/// ```
/// use meshloom::traverse::Bfs;
/// let mesh = meshloom::shapes::octahedron();
/// let top = mesh.vertices().nth(4).unwrap(); // +z
/// let mut bfs = Bfs::new(&mesh, top)?;
/// let depths: Vec<usize> = std::iter::from_fn(|| bfs.next_with_depth(&mesh))
///     .map(|(_, d)| d)
///     .collect();
/// assert_eq!(depths, [0, 1, 1, 1, 1, 2]);
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Bfs<K> {
    queue: VecDeque<(usize, usize)>,
    visited: Visited,
    scratch: Vec<usize>,
    kind: PhantomData<K>,
}

impl<K: Node> Bfs<K> {
    /// A walk from `start` (a vertex or a face).
    ///
    /// # Errors
    /// [`Error::StaleKey`] if `start` was removed;
    /// [`Error::Refused`] with [`Refusal::Hole`] if it is a hole.
    pub fn new(mesh: &Mesh, start: K) -> Result<Self> {
        let s = K::start_slot(mesh, start, "bfs")?;
        let mut visited = Visited(vec![false; 0]);
        visited.insert(s);
        Ok(Bfs {
            queue: VecDeque::from([(s, 0)]),
            visited,
            scratch: Vec::new(),
            kind: PhantomData,
        })
    }

    /// The next element, or `None` when the walk is done.
    pub fn next(&mut self, mesh: &Mesh) -> Option<K> {
        self.next_with_depth(mesh).map(|(k, _)| k)
    }

    /// The next element and its distance from the start (in steps).
    pub fn next_with_depth(&mut self, mesh: &Mesh) -> Option<(K, usize)> {
        while let Some((i, depth)) = self.queue.pop_front() {
            if !K::visitable(mesh, i) {
                continue;
            }
            self.scratch.clear();
            K::neighbors(mesh, i, &mut self.scratch);
            for &j in &self.scratch {
                if self.visited.insert(j) {
                    self.queue.push_back((j, depth + 1));
                }
            }
            return Some((K::key_of(mesh, i), depth));
        }
        None
    }

    /// The rest of the walk as an iterator borrowing the mesh.
    pub fn iter(mut self, mesh: &Mesh) -> impl Iterator<Item = K> + '_
    where
        K: 'static,
    {
        std::iter::from_fn(move || self.next(mesh))
    }
}

/// A depth-first walk in preorder: each element once, the start first,
/// then as deep as possible along the first unvisited neighbour (in ring
/// order) before backing up.
///
/// Holds only a stack and a visited set; pass the mesh to each
/// [`next`](Dfs::next).
///
/// # Complexity
/// O(V + E) for a whole walk over vertices, O(F + E) over faces; O(slots +
/// E) memory for the stack.
///
/// # Examples
/// ```
/// use meshloom::traverse::Dfs;
/// let mesh = meshloom::shapes::cube();
/// let f = mesh.faces().next().unwrap();
/// let order: Vec<_> = Dfs::new(&mesh, f)?.iter(&mesh).collect();
/// assert_eq!(order.len(), 6);
/// assert_eq!(order[0], f);
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Dfs<K> {
    stack: Vec<usize>,
    visited: Visited,
    scratch: Vec<usize>,
    kind: PhantomData<K>,
}

impl<K: Node> Dfs<K> {
    /// A walk from `start` (a vertex or a face).
    ///
    /// # Errors
    /// [`Error::StaleKey`] if `start` was removed;
    /// [`Error::Refused`] with [`Refusal::Hole`] if it is a hole.
    pub fn new(mesh: &Mesh, start: K) -> Result<Self> {
        let s = K::start_slot(mesh, start, "dfs")?;
        Ok(Dfs {
            stack: vec![s],
            visited: Visited::default(),
            scratch: Vec::new(),
            kind: PhantomData,
        })
    }

    /// The next element, or `None` when the walk is done.
    pub fn next(&mut self, mesh: &Mesh) -> Option<K> {
        while let Some(i) = self.stack.pop() {
            if !K::visitable(mesh, i) || !self.visited.insert(i) {
                continue;
            }
            self.scratch.clear();
            K::neighbors(mesh, i, &mut self.scratch);
            // Reversed, so the first neighbour is the first popped.
            for &j in self.scratch.iter().rev() {
                if !self.visited.contains(j) {
                    self.stack.push(j);
                }
            }
            return Some(K::key_of(mesh, i));
        }
        None
    }

    /// The rest of the walk as an iterator borrowing the mesh.
    pub fn iter(mut self, mesh: &Mesh) -> impl Iterator<Item = K> + '_
    where
        K: 'static,
    {
        std::iter::from_fn(move || self.next(mesh))
    }
}

impl Mesh {
    /// Vertices in breadth-first order from `start` (through edges): see
    /// [`Bfs`].
    ///
    /// # Errors
    /// [`Error::StaleKey`] if `start` was removed.
    ///
    /// ```
    /// let mesh = meshloom::shapes::icosahedron();
    /// let v = mesh.vertices().next().unwrap();
    /// assert_eq!(mesh.bfs_vertices(v)?.count(), 12);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn bfs_vertices(&self, start: VertexKey) -> Result<impl Iterator<Item = VertexKey> + '_> {
        Ok(Bfs::new(self, start)?.iter(self))
    }

    /// Vertices in depth-first preorder from `start`: see [`Dfs`].
    ///
    /// # Errors
    /// [`Error::StaleKey`] if `start` was removed.
    pub fn dfs_vertices(&self, start: VertexKey) -> Result<impl Iterator<Item = VertexKey> + '_> {
        Ok(Dfs::new(self, start)?.iter(self))
    }

    /// Faces in breadth-first order from `start`, across shared edges;
    /// holes are never visited: see [`Bfs`].
    ///
    /// # Errors
    /// [`Error::StaleKey`] if `start` was removed; [`Error::Refused`] with
    /// [`Refusal::Hole`] if it is a hole.
    ///
    /// ```
    /// let mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// assert_eq!(mesh.bfs_faces(f)?.count(), 6);
    /// let hole = meshloom::shapes::disk(5).holes().next().unwrap();
    /// assert!(meshloom::shapes::disk(5).bfs_faces(hole).is_err());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn bfs_faces(&self, start: FaceKey) -> Result<impl Iterator<Item = FaceKey> + '_> {
        Ok(Bfs::new(self, start)?.iter(self))
    }

    /// Faces in depth-first preorder from `start`: see [`Dfs`].
    ///
    /// # Errors
    /// As [`Mesh::bfs_faces`].
    pub fn dfs_faces(&self, start: FaceKey) -> Result<impl Iterator<Item = FaceKey> + '_> {
        Ok(Dfs::new(self, start)?.iter(self))
    }
}
