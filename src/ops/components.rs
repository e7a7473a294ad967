//! `split_components`: one mesh per connected piece.

// The pieces are fresh copies (a clone has no journal): nothing records.
use crate::journal::Unrecorded;
use crate::layout::{IdVec, Vid};
use crate::mesh::Mesh;

impl Mesh {
    /// The connected component of every vertex slot (`UNSEEN` for vacant
    /// slots), numbered from 0 in slot order of their first vertex, and the
    /// number of components.
    fn component_labels(&self) -> (IdVec<Vid, u32>, u32) {
        const UNSEEN: u32 = u32::MAX;
        let mut label = IdVec::filled(UNSEEN, self.v_halfedge.len());
        let mut count = 0;
        let mut stack = Vec::new();
        for v in self.vids() {
            if label[v] != UNSEEN {
                continue;
            }
            label[v] = count;
            stack.push(v);
            while let Some(x) = stack.pop() {
                for o in self.outgoing(x) {
                    let y = self.dest(o);
                    if label[y] == UNSEEN {
                        label[y] = count;
                        stack.push(y);
                    }
                }
            }
            count += 1;
        }
        (label, count)
    }

    /// Split the mesh into its connected pieces (vertices joined by edges),
    /// one mesh each, in the slot order of their first vertex. Each piece
    /// keeps its elements' keys, every attribute column and its values, and
    /// is [compacted](Mesh::compact) only if `compact` is true (then keys
    /// change; the maps are not returned).
    ///
    /// # Complexity
    /// O(pieces · slots).
    ///
    /// # Examples
    /// ```
    /// use meshloom::Mesh;
    /// let two = Mesh::from_faces(6, &[[0u32, 1, 2], [3, 4, 5]])?;
    /// let parts = two.split_components(false);
    /// assert_eq!(parts.len(), 2);
    /// assert!(parts.iter().all(|p| p.face_count() == 1 && p.validate().is_ok()));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn split_components(&self, compact: bool) -> Vec<Mesh> {
        let (label, count) = self.component_labels();
        if count <= 1 {
            let mut m = self.clone();
            if compact {
                m.compact();
            }
            return if self.is_empty() { Vec::new() } else { vec![m] };
        }
        let mut out = Vec::with_capacity(count as usize);
        for c in 0..count {
            let mut m = self.clone();
            let edges: Vec<_> = m.eids().collect();
            for e in edges {
                if label[m.origin(e.halfedge(0))] != c {
                    m.writer::<Unrecorded>().free_edge(e);
                }
            }
            let faces: Vec<_> = m.fids().collect();
            for f in faces {
                let h = self.face_halfedge(f);
                if label[self.origin(h)] != c {
                    m.writer::<Unrecorded>().free_face(f);
                }
            }
            let vertices: Vec<_> = m.vids().collect();
            for v in vertices {
                if label[v] != c {
                    m.writer::<Unrecorded>().free_vertex(v);
                }
            }
            if compact {
                m.compact();
            }
            m.debug_validate();
            out.push(m);
        }
        out
    }
}
