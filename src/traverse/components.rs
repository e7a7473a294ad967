//! Connected components.

use crate::keys::{FaceKey, VertexKey};
use crate::mesh::Mesh;

/// A vacant slot's component.
const NONE: u32 = u32::MAX; // not a link: a component number

/// The connected components of a mesh: which vertices, faces and holes
/// hang together through edges. Two pieces touching at one (bowtie) vertex
/// are one component.
///
/// A snapshot: it does not follow later edits, and reports `None` for keys
/// of elements that did not exist when it was taken.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Components {
    /// Per vertex slot: (generation, component), `NONE` component if vacant.
    vertex: Vec<(u32, u32)>,
    /// Per face slot (holes included): (generation, component).
    face: Vec<(u32, u32)>,
    /// Vertices per component.
    sizes: Vec<usize>,
}

/// The connected components of `mesh`, numbered from 0 in the slot order
/// of their first vertex.
///
/// # Arguments
/// - `mesh`: any mesh; an empty one has no components.
///
/// # Returns
/// A [`Components`] answering, for every vertex, face and hole, which
/// component it belongs to.
///
/// # Complexity
/// O(V + E) time, O(V + F) memory.
///
/// # Examples
/// ```
/// use meshloom::{shapes, traverse, Mesh};
/// // Two separate triangles and a quad.
/// let mesh = Mesh::from_faces(10, &[vec![0u32, 1, 2], vec![3, 4, 5], vec![6, 7, 8, 9]])?;
/// let parts = traverse::components(&mesh);
/// assert_eq!(parts.count(), 3);
/// assert_eq!(parts.vertex_counts(), [3, 3, 4]);
/// let v = mesh.vertices().next().unwrap();
/// assert_eq!(parts.of_vertex(v), Some(0));
/// assert_eq!(traverse::components(&shapes::torus(6, 4, 1.0, 0.3)?).count(), 1);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn components(mesh: &Mesh) -> Components {
    let nv = mesh.vertex_slots();
    let mut vertex = vec![(0, NONE); nv];
    let mut sizes = Vec::new();
    let mut stack = Vec::new();
    for v in mesh.vids() {
        if vertex[v.index()].1 != NONE {
            continue;
        }
        let id = sizes.len() as u32;
        let mut size = 0;
        vertex[v.index()] = (mesh.vkey(v).generation(), id);
        stack.push(v);
        while let Some(u) = stack.pop() {
            size += 1;
            for h in mesh.outgoing(u) {
                let w = mesh.dest(h);
                if vertex[w.index()].1 == NONE {
                    vertex[w.index()] = (mesh.vkey(w).generation(), id);
                    stack.push(w);
                }
            }
        }
        sizes.push(size);
    }
    let mut face = vec![(0, NONE); mesh.face_slots()];
    for f in mesh.fids() {
        let a = mesh.origin(mesh.face_halfedge(f));
        face[f.index()] = (mesh.fkey(f).generation(), vertex[a.index()].1);
    }
    Components {
        vertex,
        face,
        sizes,
    }
}

impl Components {
    /// Number of components.
    pub fn count(&self) -> usize {
        self.sizes.len()
    }

    /// The component of vertex `v`; `None` if `v` was not in the mesh.
    pub fn of_vertex(&self, v: VertexKey) -> Option<usize> {
        match self.vertex.get(v.index()) {
            Some(&(g, c)) if c != NONE && g == v.generation() => Some(c as usize),
            _ => None,
        }
    }

    /// The component of face (or hole) `f`; `None` if `f` was not in the
    /// mesh.
    pub fn of_face(&self, f: FaceKey) -> Option<usize> {
        match self.face.get(f.index()) {
            Some(&(g, c)) if c != NONE && g == f.generation() => Some(c as usize),
            _ => None,
        }
    }

    /// Number of vertices in each component, by component number.
    pub fn vertex_counts(&self) -> &[usize] {
        &self.sizes
    }

    /// The vertices of component `c`, in slot order (none if `c` is out of
    /// range).
    pub fn vertices(&self, c: usize) -> impl Iterator<Item = VertexKey> + '_ {
        self.vertex
            .iter()
            .enumerate()
            .filter(move |&(_, &(_, id))| id as usize == c && id != NONE)
            .map(|(i, &(g, _))| VertexKey::new(i as u32, g))
    }
}

impl Mesh {
    /// The connected components: see [`components`].
    pub fn components(&self) -> Components {
        components(self)
    }
}
