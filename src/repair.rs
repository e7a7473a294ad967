//! Repair of dirty polygon soups before they are built into a mesh.
//!
//! Scanners, CAD exports and other tools write meshes that a half-edge
//! structure cannot hold as they are: faces with a repeated corner, the same
//! face twice, faces whose orientations disagree, edges shared by three or
//! more faces, vertices where separate fans of faces meet. [`repair`] runs
//! the chosen policies on [`Polygons`] in this order and reports what each
//! did ([`RepairReport`]):
//!
//! 1. **Weld** (only when asked: [`RepairOptions::all`] leaves it off)
//!    vertices whose positions are bit-identical (`-0.0` and `0.0` are
//!    different bits and stay apart), where the welded result stays
//!    manifold: a group of coincident vertices whose merge would make an
//!    edge used by more than two faces or twice in one direction, a face
//!    with a repeated corner, or a vertex with more than one fan of faces,
//!    stays apart and is counted in [`RepairReport::weld_refused`].
//! 2. **Degenerate faces.** Runs of one vertex in a face (`a b b c`) are
//!    collapsed to one corner; a face left with fewer than three corners is
//!    dropped. A face with a vertex at two separate corners is replaced by
//!    simple faces over the same area, never dropped whole: a figure eight
//!    is cut where it touches itself; a face that walks an edge both ways
//!    (an outline and a hole joined by a bridge, as LightWave writes them)
//!    is triangulated in its plane as a polygon with a hole. The pieces
//!    keep the face's corners (and so their UVs), and are counted in
//!    [`RepairReport::split_faces`].
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
//! # Repair never harms
//!
//! - Input that already builds into a valid mesh (every vertex referenced,
//!   or the unreferenced ones dropped by step 7) is returned as it is:
//!   steps 2 to 6 run only when the builder would refuse the polygons, so a
//!   valid mesh keeps its counts, genus and components.
//! - Welding joins only where the result stays manifold, and only when
//!   asked: parts that touch at coincident vertices may be separate on
//!   purpose (seams of texture charts, parts of an assembly).
//! - Repair is idempotent: the policies run in passes until a pass changes
//!   nothing (at most 8, each O(C log C)), so repairing the output again
//!   changes nothing; with [`RepairOptions::all`] the output builds.
//! - Malformed input (offsets that do not cut the indices, an index past
//!   the positions, a non-finite position of a used vertex) is refused with
//!   the error [`Mesh::from_buffers`](crate::Mesh::from_buffers) gives, and
//!   the polygons are left untouched.
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
//! let (report, _) = repair(&mut p, &RepairOptions::all())?;
//! assert_eq!((report.duplicate_faces, report.flipped_faces), (1, 1));
//! let tet = Mesh::from_buffers(&p)?;
//! assert!(tet.is_closed());
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::fmt;

use crate::build::Polygons;
use crate::error::{BuildError, Result};

mod policies;
mod split;

use policies::Soup;

/// Which repairs to run. [`RepairOptions::all`] turns on every repair of a
/// defect (welding is not one: add it with `weld_vertices: true`),
/// [`RepairOptions::none`] (the default) none.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct RepairOptions {
    /// Weld vertices with bit-identical positions, where the result stays
    /// manifold. Off in [`RepairOptions::all`]: coincident vertices may
    /// keep parts apart on purpose.
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

crate::choice::setters!(RepairOptions {
    weld_vertices: bool,
    drop_degenerate_faces: bool,
    drop_duplicate_faces: bool,
    orient_faces: bool,
    split_nonmanifold_edges: bool,
    split_nonmanifold_vertices: bool,
    drop_unreferenced_vertices: bool,
});

impl RepairOptions {
    /// Every repair of a defect on; welding off (see
    /// [`RepairOptions::weld_vertices`]).
    ///
    /// ```
    /// use meshloom::repair::RepairOptions;
    /// let weld_too = RepairOptions::all().weld_vertices(true);
    /// assert!(!RepairOptions::all().weld_vertices && weld_too.any());
    /// ```
    pub fn all() -> RepairOptions {
        RepairOptions {
            weld_vertices: false,
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

/// What the repairs did, in counts, and what a reader accepted with a
/// warning.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct RepairReport {
    /// Vertices merged into an earlier vertex at the same position.
    pub welded_vertices: usize,
    /// Vertices left apart from a coincident vertex because welding them
    /// would have made an edge or vertex non-manifold (or a face repeat a
    /// corner).
    pub weld_refused: usize,
    /// Repeated corners removed from faces that were kept.
    pub collapsed_corners: usize,
    /// Faces dropped as degenerate.
    pub degenerate_faces: usize,
    /// Faces that visited a vertex twice, replaced by simple faces over
    /// the same area (cut where they touch themselves, or triangulated
    /// where they walk an edge both ways: a polygon with a hole).
    pub split_faces: usize,
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
    /// What a reader accepted though its format does not allow it, each
    /// with its place (a PLY header line that is not a keyword, say). The
    /// repairs themselves add none.
    pub warnings: Vec<String>,
}

impl RepairReport {
    /// Whether nothing was changed and nothing was warned about
    /// ([`weld_refused`](Self::weld_refused) counts what was left as it
    /// was, so it may be non-zero on a clean report).
    pub fn is_clean(&self) -> bool {
        *self
            == RepairReport {
                weld_refused: self.weld_refused,
                ..RepairReport::default()
            }
    }

    /// Whether the polygons were changed (what was left as it was, the
    /// vertices left apart and the orientation conflicts, is no change).
    fn changed(&self) -> bool {
        let unchanged = RepairReport {
            weld_refused: 0,
            orientation_conflicts: 0,
            ..self.clone()
        };
        !unchanged.is_clean()
    }

    /// Add a later pass's counts (the vertices left apart are the last
    /// pass's: they describe the result).
    fn add(&mut self, pass: RepairReport) {
        self.welded_vertices += pass.welded_vertices;
        self.weld_refused = pass.weld_refused;
        self.collapsed_corners += pass.collapsed_corners;
        self.degenerate_faces += pass.degenerate_faces;
        self.split_faces += pass.split_faces;
        self.duplicate_faces += pass.duplicate_faces;
        self.flipped_faces += pass.flipped_faces;
        // Conflicts are found again in every pass that orients; the most
        // found in one pass is the figure.
        self.orientation_conflicts = self.orientation_conflicts.max(pass.orientation_conflicts);
        self.nonmanifold_edges += pass.nonmanifold_edges;
        self.nonmanifold_vertices += pass.nonmanifold_vertices;
        self.added_vertices += pass.added_vertices;
        self.unreferenced_vertices += pass.unreferenced_vertices;
        self.warnings.extend(pass.warnings);
    }

    fn rows(&self) -> [(&'static str, usize); 12] {
        [
            ("vertices welded", self.welded_vertices),
            (
                "coincident vertices left apart (welding would make an edge or vertex non-manifold)",
                self.weld_refused,
            ),
            ("repeated corners collapsed", self.collapsed_corners),
            ("degenerate faces dropped", self.degenerate_faces),
            (
                "faces visiting a vertex twice split into simple faces",
                self.split_faces,
            ),
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
    /// let mut r = meshloom::repair::RepairReport::default();
    /// r.duplicate_faces = 2;
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
        for w in &self.warnings {
            if !first {
                writeln!(f)?;
            }
            write!(f, "warning: {w}")?;
            first = false;
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
/// topology-only soup, whose vertex count is one past its largest index);
/// then welding does nothing.
///
/// # Errors
/// [`Error::Build`](crate::Error::Build) with the error [`Mesh::from_buffers`](crate::Mesh::from_buffers) gives for the
/// same malformed input, and `polygons` left as they were: offsets that do
/// not start at 0, decrease or end past the indices
/// ([`BuildError::MalformedOffsets`]); an index past the positions
/// ([`BuildError::IndexOutOfRange`], naming the face); a NaN or infinite
/// position of a vertex some face uses ([`BuildError::NonFinitePosition`]);
/// more than 2^29 corners or faces, or a topology-only soup whose largest
/// index claims more vertices than a kept vertex list can hold in memory
/// bounded by the input ([`BuildError::TooLarge`]).
///
/// # Complexity
/// O(C log C) time and O(C + V) memory for C corners and V positions
/// (edges are grouped by sorting; a topology-only soup is renumbered
/// densely first, so a huge index costs nothing).
///
/// ```
/// use meshloom::repair::{repair, RepairOptions};
/// use meshloom::{BuildError, Error, Polygons};
/// let mut p = Polygons {
///     positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
///     offsets: vec![0, 3],
///     indices: vec![0, 1, 3],
/// };
/// let err = repair(&mut p, &RepairOptions::all()).unwrap_err();
/// assert!(matches!(err, Error::Build(BuildError::IndexOutOfRange { face: 0, index: 3, .. })));
/// ```
pub fn repair(
    polygons: &mut Polygons,
    options: &RepairOptions,
) -> Result<(RepairReport, Provenance)> {
    repair_with(polygons, options, &[])
}

/// [`repair`], where vertices weld only when their positions are identical
/// and their `weld_class` is the same (one class per distinct set of
/// attribute values, say); an empty `weld_class` puts every vertex in one.
///
/// # Errors
/// As [`repair`].
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
/// let weld = RepairOptions::all().weld_vertices(true);
/// let (report, _) = repair_with(&mut p, &weld, &[0, 0, 0, 1, 1, 1])?;
/// assert_eq!(report.welded_vertices, 0);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn repair_with(
    polygons: &mut Polygons,
    options: &RepairOptions,
    weld_class: &[u32],
) -> Result<(RepairReport, Provenance)> {
    let input = check_input(polygons, options)?;
    let (mut soup, implied) = take_soup(polygons, input);
    // Passes until one changes nothing, so that repairing the result again
    // changes nothing either: a later policy can clear what kept an earlier
    // weld apart. Each pass is O(C log C); real files settle in two.
    let mut report = RepairReport::default();
    for _pass in 0..MAX_PASSES {
        let pass = repair_pass(&mut soup, options, weld_class);
        let settled = !pass.changed();
        report.add(pass);
        if settled {
            break;
        }
    }
    if options.drop_unreferenced_vertices {
        // The implied vertices no index names were never renumbered in.
        report.unreferenced_vertices += implied.map_or(0, |(n, dense)| n - dense);
    } else if let Some((n, dense)) = implied {
        // Keep the caller's numbering: original vertices keep their index,
        // copies follow the largest one.
        soup.restore_numbering(n, dense);
    }
    polygons.positions = soup.positions;
    polygons.offsets = soup.offsets;
    polygons.indices = soup.indices;
    Ok((report, soup.prov))
}

/// The polygons, taken out of `polygons` into a soup with provenance. A
/// topology-only soup is renumbered densely (its vertex count is one past
/// its largest index, which may be anything up to 2^32 - 1); then also
/// returns the vertex count it implied and the dense one.
fn take_soup(polygons: &mut Polygons, input: Input) -> (Soup, Option<(usize, usize)>) {
    let mut soup = Soup {
        positions: std::mem::take(&mut polygons.positions),
        vertex_count: 0,
        offsets: std::mem::take(&mut polygons.offsets),
        indices: std::mem::take(&mut polygons.indices),
        prov: Provenance::default(),
    };
    if soup.offsets.is_empty() {
        soup.offsets.push(0);
    }
    let implied = match input {
        Input::Positions => {
            soup.vertex_count = soup.positions.len();
            soup.prov.vertex_source = (0..soup.vertex_count as u32).collect();
            None
        }
        Input::TopologyOnly { implied } => {
            let mut used = soup.indices.clone();
            used.sort_unstable();
            used.dedup();
            for i in &mut soup.indices {
                *i = used.partition_point(|&u| u < *i) as u32;
            }
            soup.vertex_count = used.len();
            soup.prov.vertex_source = used;
            Some((implied, soup.vertex_count))
        }
    };
    soup.prov.face_source = (0..soup.face_count() as u32).collect();
    soup.prov.corner_source = (0..soup.indices.len() as u32).collect();
    (soup, implied)
}

/// One pass of the chosen policies: weld, then (only when the builder
/// would refuse the polygons) the defect policies, then drop unreferenced
/// vertices.
fn repair_pass(soup: &mut Soup, options: &RepairOptions, weld_class: &[u32]) -> RepairReport {
    let mut pass = RepairReport::default();
    if options.weld_vertices {
        // Classes follow the vertices through earlier passes.
        let classes: Vec<u32> = if weld_class.is_empty() {
            Vec::new()
        } else {
            soup.prov
                .vertex_source
                .iter()
                .map(|&s| weld_class.get(s as usize).copied().unwrap_or(0))
                .collect()
        };
        (pass.welded_vertices, pass.weld_refused) = soup.weld(&classes);
    }
    // Valid input is left as it is: the defect policies run only when the
    // builder would refuse the polygons.
    if soup.needs_repair() {
        if options.drop_degenerate_faces {
            (
                pass.collapsed_corners,
                pass.degenerate_faces,
                pass.split_faces,
            ) = soup.drop_degenerate();
        }
        if options.drop_duplicate_faces {
            pass.duplicate_faces = soup.drop_duplicates();
        }
        if options.orient_faces {
            (pass.flipped_faces, pass.orientation_conflicts) = soup.orient();
        }
        if options.split_nonmanifold_edges {
            let (edges, copies) = soup.split_edges();
            pass.nonmanifold_edges = edges;
            pass.added_vertices += copies;
        }
        if options.split_nonmanifold_vertices {
            let (vertices, copies) = soup.split_vertices();
            pass.nonmanifold_vertices = vertices;
            pass.added_vertices += copies;
        }
    }
    if options.drop_unreferenced_vertices {
        pass.unreferenced_vertices = soup.drop_unreferenced();
    }
    pass
}

/// The most passes of the policies (see [`repair_with`]).
const MAX_PASSES: usize = 8;

/// What kind of soup passed the checks.
enum Input {
    Positions,
    TopologyOnly { implied: usize },
}

/// The checks [`Mesh::from_buffers`](crate::Mesh::from_buffers) makes of malformed input, made before
/// anything is touched, with its errors.
fn check_input(p: &Polygons, options: &RepairOptions) -> Result<Input> {
    crate::build::check_offsets(&p.offsets, &p.indices)?;
    if p.indices.len() >= (1 << 29) || p.offsets.len() > (1 << 29) {
        return Err(BuildError::TooLarge {
            what: "more than 2^29 corners or faces",
        }
        .into());
    }
    let face_of = |c: usize| {
        p.offsets
            .partition_point(|&o| o as usize <= c)
            .saturating_sub(1)
    };
    if p.positions.is_empty() {
        let implied = p.indices.iter().max().map_or(0, |&m| m as usize + 1);
        // Kept unreferenced vertices (and their provenance) are listed one
        // by one: refuse a count the input's size does not pay for.
        let affordable = (16 * p.indices.len() + 4096).min(1 << 31);
        if !options.drop_unreferenced_vertices && implied > affordable {
            return Err(BuildError::TooLarge {
                what: "a topology-only soup's largest index implies more vertices than 16 per corner; \
                       give positions or drop unreferenced vertices",
            }
            .into());
        }
        return Ok(Input::TopologyOnly { implied });
    }
    let n = p.positions.len();
    if n >= (1 << 31) {
        return Err(BuildError::TooLarge {
            what: "2^31 vertices or more",
        }
        .into());
    }
    if let Some(c) = p.indices.iter().position(|&i| i as usize >= n) {
        return Err(BuildError::IndexOutOfRange {
            face: face_of(c),
            index: i64::from(p.indices[c]),
            vertex_count: n,
        }
        .into());
    }
    // The builder checks the vertices it keeps; so does this, in the same
    // order (by index).
    let mut used = vec![false; n];
    for &i in &p.indices {
        used[i as usize] = true;
    }
    if let Some(v) = (0..n).find(|&v| used[v] && !p.positions[v].iter().all(|c| c.is_finite())) {
        return Err(BuildError::NonFinitePosition {
            vertex: v,
            position: p.positions[v],
        }
        .into());
    }
    Ok(Input::Positions)
}

#[cfg(test)]
mod tests;
