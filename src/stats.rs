//! Whole-mesh figures: counts, boundary, components, Euler characteristic,
//! genus and the face-degree histogram, in one pass each.
//!
//! ```
//! let s = meshloom::shapes::cube().stats();
//! assert_eq!((s.vertices, s.edges, s.faces), (8, 12, 6));
//! assert_eq!((s.components, s.euler_characteristic, s.genus), (1, 2, Some(0)));
//! assert_eq!(s.face_degrees.get(&4), Some(&6));
//! ```

use std::collections::BTreeMap;
use std::fmt;

use crate::mesh::Mesh;

/// Figures describing a mesh, from [`Mesh::stats`].
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct Stats {
    /// Number of vertices.
    pub vertices: usize,
    /// Number of edges.
    pub edges: usize,
    /// Number of faces, holes excluded.
    pub faces: usize,
    /// Number of hole faces (the outside of each boundary loop).
    pub holes: usize,
    /// Number of edges with a hole on one side.
    pub boundary_edges: usize,
    /// Number of closed cycles of boundary half-edges, found by walking
    /// them. On a valid mesh this equals [`holes`](Self::holes).
    pub boundary_loops: usize,
    /// Number of connected components (vertices joined by edges).
    pub components: usize,
    /// V − E + F, holes not counted as faces.
    pub euler_characteristic: i64,
    /// The genus, where the mesh is closed: the sum over its components of
    /// (2 − χ)/2, which for a connected mesh is the usual genus. `None` for a
    /// mesh with boundary or an empty mesh.
    pub genus: Option<u64>,
    /// How many faces have each number of sides (holes excluded).
    pub face_degrees: BTreeMap<usize, usize>,
    /// Whether the mesh carries vertex positions.
    pub has_positions: bool,
    /// The axis-aligned bounding box `[min, max]` of the vertex positions;
    /// `None` without positions or vertices.
    pub bounding_box: Option<[[f64; 3]; 2]>,
}

impl Stats {
    /// Whether the mesh has faces and no boundary (an empty mesh is not
    /// called closed).
    pub fn is_closed(&self) -> bool {
        self.holes == 0 && self.faces > 0
    }
}

impl fmt::Display for Stats {
    /// One figure per line, name then value, names padded to one column.
    ///
    /// ```
    /// let text = meshloom::shapes::cube().stats().to_string();
    /// assert!(text.contains("faces                 6\n"));
    /// assert!(text.contains("face degrees          4: 6\n"));
    /// ```
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let yes_no = |b: bool| if b { "yes" } else { "no" };
        let degrees = self
            .face_degrees
            .iter()
            .map(|(d, n)| format!("{d}: {n}"))
            .collect::<Vec<_>>()
            .join(", ");
        let genus = match self.genus {
            Some(g) => g.to_string(),
            None if self.vertices == 0 => "-".into(),
            None => "- (the mesh has boundary)".into(),
        };
        let rows: [(&str, String); 13] = [
            ("vertices", self.vertices.to_string()),
            ("edges", self.edges.to_string()),
            ("faces", self.faces.to_string()),
            ("holes", self.holes.to_string()),
            ("boundary edges", self.boundary_edges.to_string()),
            ("boundary loops", self.boundary_loops.to_string()),
            ("components", self.components.to_string()),
            (
                "Euler characteristic",
                self.euler_characteristic.to_string(),
            ),
            ("genus", genus),
            ("closed", yes_no(self.is_closed()).into()),
            (
                "face degrees",
                if degrees.is_empty() {
                    "-".into()
                } else {
                    degrees
                },
            ),
            ("positions", yes_no(self.has_positions).into()),
            (
                "bounding box",
                match self.bounding_box {
                    Some([lo, hi]) => format!(
                        "[{}, {}, {}] to [{}, {}, {}]",
                        lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
                    ),
                    None => "-".into(),
                },
            ),
        ];
        for (name, value) in rows {
            writeln!(f, "{name:<22}{value}")?;
        }
        Ok(())
    }
}

impl Mesh {
    /// Counts, boundary, components, Euler characteristic, genus and the
    /// face-degree histogram.
    ///
    /// # Complexity
    /// O(V + E + F), with a union-find over vertex slots for the components.
    ///
    /// ```
    /// use meshloom::Mesh;
    /// // Two separate triangles: two components, two holes.
    /// let p = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [5.0, 0.0, 0.0], [6.0, 0.0, 0.0], [5.0, 1.0, 0.0]];
    /// let mesh = Mesh::from_polygons(&p, &[[0u32, 1, 2], [3, 4, 5]])?;
    /// let s = mesh.stats();
    /// assert_eq!((s.components, s.holes, s.boundary_loops, s.boundary_edges), (2, 2, 2, 6));
    /// assert_eq!(s.genus, None); // not closed
    /// assert_eq!(s.bounding_box, Some([[0.0, 0.0, 0.0], [6.0, 1.0, 0.0]]));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn stats(&self) -> Stats {
        let mut face_degrees = BTreeMap::new();
        for f in self.f_slots.live_indices() {
            if !self.is_hole_raw(f) {
                *face_degrees
                    .entry(self.face_loop_raw(f).count())
                    .or_insert(0) += 1;
            }
        }
        let boundary_edges = self
            .e_slots
            .live_indices()
            .filter(|&e| self.in_hole_raw(2 * e) || self.in_hole_raw(2 * e + 1))
            .count();
        let components = self.component_count();
        let euler_characteristic = self.euler_characteristic();
        let genus = if self.is_closed() && components > 0 {
            let twice = 2 * components as i64 - euler_characteristic;
            (twice >= 0 && twice % 2 == 0).then_some((twice / 2) as u64)
        } else {
            None
        };
        Stats {
            vertices: self.vertex_count(),
            edges: self.edge_count(),
            faces: self.face_count(),
            holes: self.hole_count(),
            boundary_edges,
            boundary_loops: self.boundary_loop_count(),
            components,
            euler_characteristic,
            genus,
            face_degrees,
            has_positions: self.has_positions(),
            bounding_box: self.bounding_box(),
        }
    }

    /// The axis-aligned bounding box `[min, max]` of the vertex positions;
    /// `None` for a topology-only or empty mesh.
    ///
    /// ```
    /// let b = meshloom::shapes::cube().bounding_box();
    /// assert_eq!(b, Some([[0.0; 3], [1.0; 3]]));
    /// ```
    pub fn bounding_box(&self) -> Option<[[f64; 3]; 2]> {
        let column = self.position_slots()?;
        let mut live = self
            .v_slots
            .live_indices()
            .filter_map(|v| column.get(v as usize));
        let first = *live.next()?;
        Some(live.fold([first, first], |[lo, hi], p| {
            [
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            ]
        }))
    }

    /// Number of connected components: classes of vertices joined by edges.
    fn component_count(&self) -> usize {
        let n = self.v_slots.slot_count();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        fn find(parent: &mut [u32], mut x: u32) -> u32 {
            while parent[x as usize] != x {
                let up = parent[parent[x as usize] as usize];
                parent[x as usize] = up;
                x = up;
            }
            x
        }
        let mut components = self.vertex_count();
        for e in self.e_slots.live_indices() {
            let a = find(&mut parent, self.origin_of(2 * e));
            let b = find(&mut parent, self.origin_of(2 * e + 1));
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
                components -= 1;
            }
        }
        components
    }

    /// Number of cycles among the half-edges that lie in holes, following
    /// `next`.
    fn boundary_loop_count(&self) -> usize {
        let mut seen = vec![false; self.he.len()];
        let mut loops = 0;
        for e in self.e_slots.live_indices() {
            for h in [2 * e, 2 * e + 1] {
                if seen[h as usize] || !self.in_hole_raw(h) {
                    continue;
                }
                loops += 1;
                for g in crate::circulate::FaceHalfedges::from_halfedge(self, h) {
                    seen[g as usize] = true;
                }
            }
        }
        loops
    }
}

#[cfg(test)]
mod tests {
    use crate::{shapes, Mesh};

    #[test]
    fn empty_mesh_has_zero_everything() {
        let s = Mesh::new().stats();
        assert_eq!((s.vertices, s.edges, s.faces, s.components), (0, 0, 0, 0));
        assert_eq!(s.genus, None);
        assert_eq!(s.bounding_box, None);
        assert!(s.face_degrees.is_empty());
        assert!(!s.is_closed());
        assert!(s.to_string().contains("closed                no\n"));
    }

    #[test]
    fn closed_shapes_have_genus_zero() {
        for m in [shapes::tetrahedron(), shapes::cube(), shapes::icosahedron()] {
            let s = m.stats();
            assert_eq!(s.genus, Some(0));
            assert_eq!((s.holes, s.boundary_edges, s.boundary_loops), (0, 0, 0));
            assert_eq!(s.components, 1);
        }
    }

    #[test]
    fn two_closed_components_sum_genus() {
        // Two disjoint tetrahedra: χ = 4, two components, genus 0.
        let faces = [[0u32, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]];
        let mut all: Vec<[u32; 3]> = faces.to_vec();
        all.extend(faces.iter().map(|f| f.map(|i| i + 4)));
        let m = Mesh::from_faces(8, &all).unwrap();
        let s = m.stats();
        assert_eq!(
            (s.components, s.euler_characteristic, s.genus),
            (2, 4, Some(0))
        );
        assert!(!s.has_positions);
        assert_eq!(s.bounding_box, None);
    }

    #[test]
    fn open_quad_strip_counts_boundary() {
        // 2x1 quads sharing an edge: one boundary loop of 6 edges.
        let m = Mesh::from_faces(6, &[[0u32, 1, 4, 3], [1, 2, 5, 4]]).unwrap();
        let s = m.stats();
        assert_eq!((s.vertices, s.edges, s.faces), (6, 7, 2));
        assert_eq!((s.holes, s.boundary_loops, s.boundary_edges), (1, 1, 6));
        assert_eq!(s.euler_characteristic, 1);
        assert_eq!(s.face_degrees.get(&4), Some(&2));
        assert!(!s.is_closed());
    }
}
