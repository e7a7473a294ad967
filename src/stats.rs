//! Whole-mesh figures: counts, boundary, components, Euler characteristic,
//! genus and the face-degree histogram, in one pass each; the same per
//! connected component.
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
    /// Number of hole faces. A hole face is the outside of one cycle of
    /// boundary half-edges; where boundary loops meet at a pinched vertex
    /// (a bowtie), the half-edge structure keeps one ring per vertex and so
    /// one hole passes through every loop that meets there: then there are
    /// fewer holes than [`boundary_loops`](Self::boundary_loops).
    pub holes: usize,
    /// Number of edges with a hole on one side.
    pub boundary_edges: usize,
    /// Number of boundary loops, counted as independent checkers count them
    /// on the face list (the shared `meshcheck.py`, libigl's
    /// `boundary_loop`): walk the boundary edges, each against its face's
    /// direction; at a vertex where several boundary edges leave, take the
    /// first one not yet walked, in face order (faces in slot order, each
    /// from its first half-edge); a walk ends where it finds none, and each
    /// walk counts one loop. Without pinched vertices this equals
    /// [`holes`](Self::holes); at a pinched vertex the count depends on
    /// that turning rule, and may be more or fewer than the hole faces
    /// (`geomview_cam.off`: 1 hole face, 2 loops).
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
        for f in self.fids() {
            if !self.is_hole(f) {
                *face_degrees
                    .entry(self.face_halfedges(f).count())
                    .or_insert(0) += 1;
            }
        }
        let boundary_edges = self
            .eids()
            .filter(|e| e.halfedges().iter().any(|&h| self.in_hole(h)))
            .count();
        let components = crate::traverse::components(self).count();
        let euler_characteristic = self.euler_characteristic();
        let genus = closed_genus(self.hole_count(), components, euler_characteristic);
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
        let mut live = self.vids().filter_map(|v| column.get(v.index()));
        let first = *live.next()?;
        Some(live.fold([first, first], |[lo, hi], p| {
            [
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            ]
        }))
    }

    /// Figures of each connected component, numbered as
    /// [`traverse::components`](crate::traverse::components) numbers them
    /// (in the slot order of their first vertex).
    ///
    /// # Complexity
    /// O(V + E + F).
    ///
    /// ```
    /// use meshloom::Mesh;
    /// // A closed tetrahedron and a separate open triangle.
    /// let faces = [vec![0u32, 1, 2], vec![0, 2, 3], vec![0, 3, 1], vec![1, 3, 2], vec![4, 5, 6]];
    /// let parts = Mesh::from_faces(7, &faces)?.component_stats();
    /// assert_eq!(parts.len(), 2);
    /// assert_eq!((parts[0].faces, parts[0].holes, parts[0].genus), (4, 0, Some(0)));
    /// assert_eq!((parts[1].faces, parts[1].holes, parts[1].genus), (1, 1, None));
    /// assert_eq!(parts[1].euler_characteristic, 1);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn component_stats(&self) -> Vec<ComponentStats> {
        let parts = crate::traverse::components(self);
        let mut out: Vec<ComponentStats> = parts
            .vertex_counts()
            .iter()
            .map(|&vertices| ComponentStats {
                vertices,
                ..ComponentStats::default()
            })
            .collect();
        for e in self.eids() {
            let a = self.vkey(self.origin(e.halfedge(0)));
            if let Some(c) = parts.of_vertex(a).and_then(|c| out.get_mut(c)) {
                c.edges += 1;
            }
        }
        for f in self.fids() {
            if let Some(c) = parts.of_face(self.fkey(f)).and_then(|c| out.get_mut(c)) {
                if self.is_hole(f) {
                    c.holes += 1;
                } else {
                    c.faces += 1;
                }
            }
        }
        for c in &mut out {
            c.euler_characteristic = c.vertices as i64 - c.edges as i64 + c.faces as i64;
            c.genus = closed_genus(c.holes, 1, c.euler_characteristic);
        }
        out
    }

    /// Boundary loops as [`Stats::boundary_loops`] defines them.
    ///
    /// # Complexity
    /// O(B log B) for B boundary half-edges, plus a pass over the faces.
    fn boundary_loop_count(&self) -> usize {
        // Every hole half-edge (origin, dest), in the order its face twin
        // comes: faces in slot order, each from its first half-edge.
        let mut sides: Vec<(u32, u32)> = Vec::new();
        for f in self.fids() {
            if self.is_hole(f) {
                continue;
            }
            for h in self.face_halfedges(f) {
                let t = h.twin();
                if self.in_hole(t) {
                    sides.push((self.origin(t).raw(), self.origin(h).raw()));
                }
            }
        }
        // The sides leaving each vertex, in that order; vertices in the
        // order their first leaving side comes.
        let mut order: Vec<u32> = (0..sides.len() as u32).collect();
        order.sort_by_key(|&i| (sides[i as usize].0, i));
        // Per vertex: (first, cursor, end) into `order`.
        let mut group: std::collections::HashMap<u32, (usize, usize, usize)> =
            std::collections::HashMap::with_capacity(sides.len());
        for (k, &i) in order.iter().enumerate() {
            let e = group.entry(sides[i as usize].0).or_insert((k, k, k));
            e.2 = k + 1;
        }
        let mut walked = vec![false; sides.len()];
        let mut loops = 0;
        for (i, &(a, _)) in sides.iter().enumerate() {
            let Some(&(start, _, end)) = group.get(&a) else {
                continue;
            };
            if order[start] as usize != i {
                continue; // not the first side leaving `a`: done with `a`
            }
            for k in start..end {
                let mut side = order[k] as usize;
                if walked[side] {
                    continue;
                }
                loops += 1;
                loop {
                    walked[side] = true;
                    let y = sides[side].1;
                    let Some(cursor) = group.get_mut(&y) else {
                        break;
                    };
                    // Sides at a vertex are walked in order, so the first
                    // not yet walked is at the front of its group.
                    while cursor.1 < cursor.2 && walked[order[cursor.1] as usize] {
                        cursor.1 += 1;
                    }
                    if cursor.1 == cursor.2 {
                        break;
                    }
                    side = order[cursor.1] as usize;
                }
            }
        }
        loops
    }
}

/// The genus of a closed surface of `components` pieces with Euler
/// characteristic `chi`: Σ (2 − χᵢ)/2 = (2·components − χ)/2. `None` with
/// holes, without components, or for a χ no closed orientable surface has.
fn closed_genus(holes: usize, components: usize, chi: i64) -> Option<u64> {
    if holes > 0 || components == 0 {
        return None;
    }
    let twice = 2 * components as i64 - chi;
    (twice >= 0 && twice % 2 == 0).then_some((twice / 2) as u64)
}

/// Figures of one connected component, from [`Mesh::component_stats`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct ComponentStats {
    /// Number of vertices.
    pub vertices: usize,
    /// Number of edges.
    pub edges: usize,
    /// Number of faces, holes excluded.
    pub faces: usize,
    /// Number of holes (boundary loops).
    pub holes: usize,
    /// V − E + F of the component.
    pub euler_characteristic: i64,
    /// (2 − χ)/2 where the component is closed; `None` with boundary.
    pub genus: Option<u64>,
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

#[cfg(test)]
mod component_tests {
    use crate::{shapes, Mesh};

    #[test]
    fn component_figures_add_up_to_the_whole() {
        // An open strip of two quads and a separate tetrahedron.
        let mut faces: Vec<Vec<u32>> = vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]];
        faces.extend([[6u32, 7, 8], [6, 8, 9], [6, 9, 7], [7, 9, 8]].map(|f| f.to_vec()));
        let mesh = Mesh::from_faces(10, &faces).unwrap();
        let parts = mesh.component_stats();
        let whole = mesh.stats();
        assert_eq!(parts.len(), whole.components);
        let sum = |f: fn(&super::ComponentStats) -> usize| parts.iter().map(f).sum::<usize>();
        assert_eq!(sum(|c| c.vertices), whole.vertices);
        assert_eq!(sum(|c| c.edges), whole.edges);
        assert_eq!(sum(|c| c.faces), whole.faces);
        assert_eq!(sum(|c| c.holes), whole.holes);
        assert_eq!(
            parts.iter().map(|c| c.euler_characteristic).sum::<i64>(),
            whole.euler_characteristic
        );
        assert_eq!(parts[0].genus, None);
        assert_eq!(parts[1].genus, Some(0));
        assert_eq!(shapes::cube().component_stats()[0].genus, Some(0));
        assert!(Mesh::new().component_stats().is_empty());
    }
}
