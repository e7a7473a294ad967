//! `split_components`: one mesh per connected piece.

use crate::mesh::{Mesh, NONE};

impl Mesh {
    /// The connected component of every vertex slot (`NONE` for vacant
    /// slots), numbered from 0 in slot order of their first vertex, and the
    /// number of components.
    fn component_labels(&self) -> (Vec<u32>, u32) {
        let mut label = vec![NONE; self.v_halfedge.len()];
        let mut count = 0;
        let mut stack = Vec::new();
        for v in self.v_slots.live_indices() {
            if label[v as usize] != NONE {
                continue;
            }
            label[v as usize] = count;
            stack.push(v);
            while let Some(x) = stack.pop() {
                for o in self.outgoing_raw(x) {
                    let y = self.dest_of(o);
                    if label[y as usize] == NONE {
                        label[y as usize] = count;
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
            let edges: Vec<u32> = m.e_slots.live_indices().collect();
            for e in edges {
                if label[m.origin_of(2 * e) as usize] != c {
                    m.free_edge(e);
                }
            }
            let faces: Vec<u32> = m.f_slots.live_indices().collect();
            for f in faces {
                let h = self.face_halfedge_raw(f);
                if label[self.origin_of(h) as usize] != c {
                    m.free_face(f);
                }
            }
            let vertices: Vec<u32> = m.v_slots.live_indices().collect();
            for v in vertices {
                if label[v as usize] != c {
                    m.free_vertex(v);
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
