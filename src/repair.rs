//! Repair of dirty polygon soups before they are built into a mesh.
//!
//! Scanners, CAD exports and other tools write meshes that a half-edge
//! structure cannot hold as they are: faces with a repeated corner, the same
//! face twice, faces whose orientations disagree, edges shared by three or
//! more faces, vertices where separate fans of faces meet. [`repair`] runs
//! the chosen policies on [`Polygons`] in this order and reports what each
//! did ([`RepairReport`]):
//!
//! 1. **Weld** vertices whose positions are bit-identical (`-0.0` and `0.0`
//!    are different bits and stay apart).
//! 2. **Degenerate faces.** Runs of one vertex in a face (`a b b c`) are
//!    collapsed to one corner; a face left with fewer than three corners, or
//!    with a vertex at two separate corners, is dropped.
//! 3. **Duplicate faces.** A face with the same vertex set as an earlier
//!    face (in either orientation) is dropped; the first one stays.
//! 4. **Orientation.** Faces are visited breadth-first across edges shared
//!    by exactly two faces, and flipped to agree with the face they were
//!    reached from. Per component, the orientation most faces already had
//!    wins. A flipped face keeps its first corner (`a b c d` becomes
//!    `a d c b`). A non-orientable component (a Möbius band) keeps its
//!    conflicts; the edge split below then cuts them.
//! 5. **Non-manifold edges.** Where an edge is used by more than two faces,
//!    or by two faces in the same direction, the first two uses in opposite
//!    directions keep the edge; every other face on it gets its own copies
//!    of the edge's two vertices.
//! 6. **Non-manifold vertices.** The faces around a vertex form fans (faces
//!    joined through shared edges). The builder holds a vertex with several
//!    open fans (holes meet there, the hole face passes once per fan), but
//!    not a closed fan beside another fan: such a vertex gets one copy per
//!    fan after the first.
//! 7. **Unreferenced vertices** are dropped.
//!
//! Every step keeps track of where each output vertex, face and corner came
//! from ([`Provenance`]), so the attributes read with the polygons follow.
//!
//! ```
//! use meshloom::repair::{repair, RepairOptions};
//! use meshloom::{Mesh, Polygons};
//! // A tetrahedron with one face flipped and one face listed twice.
//! let mut p = Polygons {
//!     positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
//!     offsets: vec![0, 3, 6, 9, 12, 15],
//!     indices: vec![0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 2, 3, 3, 2, 0],
//! };
//! assert!(Mesh::from_buffers(&p).is_err());
//! let (report, _) = repair(&mut p, &RepairOptions::all());
//! assert_eq!((report.duplicate_faces, report.flipped_faces), (1, 1));
//! let tet = Mesh::from_buffers(&p)?;
//! assert!(tet.is_closed());
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::fmt;

use crate::build::Polygons;

mod policies;

use policies::Soup;

/// Which repairs to run. [`RepairOptions::all`] turns every one on,
/// [`RepairOptions::none`] (the default) none.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RepairOptions {
    /// Weld vertices with bit-identical positions.
    pub weld_vertices: bool,
    /// Collapse repeated corners; drop faces left degenerate.
    pub drop_degenerate_faces: bool,
    /// Drop faces with the vertex set of an earlier face.
    pub drop_duplicate_faces: bool,
    /// Flip faces to one orientation per component.
    pub orient_faces: bool,
    /// Give faces beyond two on an edge their own copies of its vertices.
    pub split_nonmanifold_edges: bool,
    /// Give each extra fan at a vertex its own copy of the vertex.
    pub split_nonmanifold_vertices: bool,
    /// Drop vertices no face uses.
    pub drop_unreferenced_vertices: bool,
}

impl RepairOptions {
    /// Every policy on.
    pub fn all() -> RepairOptions {
        RepairOptions {
            weld_vertices: true,
            drop_degenerate_faces: true,
            drop_duplicate_faces: true,
            orient_faces: true,
            split_nonmanifold_edges: true,
            split_nonmanifold_vertices: true,
            drop_unreferenced_vertices: true,
        }
    }

    /// Every policy off: input is taken as it is.
    pub fn none() -> RepairOptions {
        RepairOptions::default()
    }

    /// Whether any policy is on.
    pub fn any(&self) -> bool {
        *self != RepairOptions::none()
    }
}

/// What the repairs did, in counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct RepairReport {
    /// Vertices merged into an earlier vertex at the same position.
    pub welded_vertices: usize,
    /// Repeated corners removed from faces that were kept.
    pub collapsed_corners: usize,
    /// Faces dropped as degenerate.
    pub degenerate_faces: usize,
    /// Faces dropped as duplicates.
    pub duplicate_faces: usize,
    /// Faces flipped to agree with their neighbours.
    pub flipped_faces: usize,
    /// Edges whose faces could not be made to agree (non-orientable parts).
    pub orientation_conflicts: usize,
    /// Edges used by more than two faces, or twice in one direction, that
    /// were split.
    pub nonmanifold_edges: usize,
    /// Vertices with a closed fan beside another fan, that were split.
    pub nonmanifold_vertices: usize,
    /// Vertex copies made by the two splits.
    pub added_vertices: usize,
    /// Vertices dropped because no face used them.
    pub unreferenced_vertices: usize,
}

impl RepairReport {
    /// Whether nothing was changed.
    pub fn is_clean(&self) -> bool {
        *self == RepairReport::default()
    }

    fn rows(&self) -> [(&'static str, usize); 10] {
        [
            ("vertices welded", self.welded_vertices),
            ("repeated corners collapsed", self.collapsed_corners),
            ("degenerate faces dropped", self.degenerate_faces),
            ("duplicate faces dropped", self.duplicate_faces),
            ("faces flipped", self.flipped_faces),
            (
                "orientation conflicts left to the edge split",
                self.orientation_conflicts,
            ),
            ("non-manifold edges split", self.nonmanifold_edges),
            ("non-manifold vertices split", self.nonmanifold_vertices),
            ("vertex copies added", self.added_vertices),
            ("unreferenced vertices dropped", self.unreferenced_vertices),
        ]
    }
}

impl fmt::Display for RepairReport {
    /// One line per repair that changed something, or "no repairs needed".
    ///
    /// ```
    /// let r = meshloom::repair::RepairReport { duplicate_faces: 2, ..Default::default() };
    /// assert_eq!(r.to_string(), "duplicate faces dropped: 2");
    /// ```
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut first = true;
        for (name, n) in self.rows() {
            if n > 0 {
                if !first {
                    writeln!(f)?;
                }
                write!(f, "{name}: {n}")?;
                first = false;
            }
        }
        if first {
            write!(f, "no repairs needed")?;
        }
        Ok(())
    }
}

/// Where each output element came from: indices into the input of
/// [`repair`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Provenance {
    /// The input vertex each output vertex copies.
    pub vertex_source: Vec<u32>,
    /// The input face each output face is.
    pub face_source: Vec<u32>,
    /// The input corner (index into the input's `indices`) each output
    /// corner is.
    pub corner_source: Vec<u32>,
}

/// Run the chosen repairs on `polygons`, in place. Returns what was done
/// and where every output element came from. Positions may be empty (a
/// topology-only soup); then welding does nothing.
///
/// # Complexity
/// O(C log C) for C corners (edges are grouped by sorting).
pub fn repair(polygons: &mut Polygons, options: &RepairOptions) -> (RepairReport, Provenance) {
    repair_with(polygons, options, &[])
}

/// [`repair`], where vertices weld only when their positions are identical
/// and their `weld_class` is the same (one class per distinct set of
/// attribute values, say); an empty `weld_class` puts every vertex in one.
///
/// ```
/// use meshloom::repair::{repair_with, RepairOptions};
/// use meshloom::Polygons;
/// // Two triangles touching at two copies of one position, with different
/// // colours: they stay apart.
/// let mut p = Polygons {
///     positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0; 3], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]],
///     offsets: vec![0, 3, 6],
///     indices: vec![0, 1, 2, 3, 4, 5],
/// };
/// let (report, _) = repair_with(&mut p, &RepairOptions::all(), &[0, 0, 0, 1, 1, 1]);
/// assert_eq!(report.welded_vertices, 0);
/// ```
pub fn repair_with(
    polygons: &mut Polygons,
    options: &RepairOptions,
    weld_class: &[u32],
) -> (RepairReport, Provenance) {
    let nv = if polygons.positions.is_empty() {
        polygons.indices.iter().max().map_or(0, |&m| m as usize + 1)
    } else {
        polygons.positions.len()
    };
    let mut soup = Soup {
        positions: std::mem::take(&mut polygons.positions),
        vertex_count: nv,
        offsets: std::mem::take(&mut polygons.offsets),
        indices: std::mem::take(&mut polygons.indices),
        prov: Provenance {
            vertex_source: (0..nv as u32).collect(),
            face_source: Vec::new(),
            corner_source: Vec::new(),
        },
    };
    if soup.offsets.is_empty() {
        soup.offsets.push(0);
    }
    soup.prov.face_source = (0..soup.face_count() as u32).collect();
    soup.prov.corner_source = (0..soup.indices.len() as u32).collect();
    let mut report = RepairReport::default();
    if options.weld_vertices {
        report.welded_vertices = soup.weld(weld_class);
    }
    if options.drop_degenerate_faces {
        (report.collapsed_corners, report.degenerate_faces) = soup.drop_degenerate();
    }
    if options.drop_duplicate_faces {
        report.duplicate_faces = soup.drop_duplicates();
    }
    if options.orient_faces {
        (report.flipped_faces, report.orientation_conflicts) = soup.orient();
    }
    if options.split_nonmanifold_edges {
        let (edges, copies) = soup.split_edges();
        report.nonmanifold_edges = edges;
        report.added_vertices += copies;
    }
    if options.split_nonmanifold_vertices {
        let (vertices, copies) = soup.split_vertices();
        report.nonmanifold_vertices = vertices;
        report.added_vertices += copies;
    }
    if options.drop_unreferenced_vertices {
        report.unreferenced_vertices = soup.drop_unreferenced();
    }
    polygons.positions = soup.positions;
    polygons.offsets = soup.offsets;
    polygons.indices = soup.indices;
    (report, soup.prov)
}

#[cfg(test)]
mod tests;
