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

use std::collections::HashMap;
use std::fmt;

use crate::build::Polygons;

const NONE: u32 = u32::MAX;

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

/// The soup under repair, with its provenance.
struct Soup {
    positions: Vec<[f64; 3]>,
    vertex_count: usize,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    prov: Provenance,
}

impl Soup {
    fn face_count(&self) -> usize {
        self.offsets.len() - 1
    }

    fn face(&self, f: usize) -> std::ops::Range<usize> {
        self.offsets[f] as usize..self.offsets[f + 1] as usize
    }

    /// Add a copy of vertex `v`; returns its index.
    fn copy_vertex(&mut self, v: u32) -> u32 {
        let n = self.vertex_count as u32;
        if !self.positions.is_empty() {
            self.positions.push(self.positions[v as usize]);
        }
        let src = self.prov.vertex_source[v as usize];
        self.prov.vertex_source.push(src);
        self.vertex_count += 1;
        n
    }

    /// Keep the vertices with `keep[v]`, renumbered densely.
    fn compact_vertices(&mut self, new_of: &[u32]) {
        let mut positions = Vec::new();
        let mut source = Vec::new();
        for (v, &n) in new_of.iter().enumerate() {
            if n != NONE && n as usize == source.len() {
                if !self.positions.is_empty() {
                    positions.push(self.positions[v]);
                }
                source.push(self.prov.vertex_source[v]);
            }
        }
        for i in &mut self.indices {
            *i = new_of[*i as usize];
        }
        self.vertex_count = source.len();
        self.positions = positions;
        self.prov.vertex_source = source;
    }

    /// Rebuild the faces from per-face corner lists (input corner indices).
    fn rebuild_faces(&mut self, faces: impl Iterator<Item = (u32, Vec<u32>)>) {
        let mut offsets = vec![0u32];
        let mut indices = Vec::with_capacity(self.indices.len());
        let mut face_source = Vec::with_capacity(self.face_count());
        let mut corner_source = Vec::with_capacity(self.indices.len());
        let faces: Vec<_> = faces.collect();
        for (f, corners) in faces {
            for c in corners {
                indices.push(self.indices[c as usize]);
                corner_source.push(self.prov.corner_source[c as usize]);
            }
            offsets.push(indices.len() as u32);
            face_source.push(self.prov.face_source[f as usize]);
        }
        self.offsets = offsets;
        self.indices = indices;
        self.prov.face_source = face_source;
        self.prov.corner_source = corner_source;
    }

    fn weld(&mut self, class: &[u32]) -> usize {
        if self.positions.is_empty() {
            return 0;
        }
        let mut first: HashMap<([u64; 3], u32), u32> = HashMap::with_capacity(self.positions.len());
        let mut new_of = vec![NONE; self.positions.len()];
        let mut n = 0u32;
        let mut rep = vec![0u32; self.positions.len()];
        for (v, p) in self.positions.iter().enumerate() {
            let key = (
                [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()],
                class.get(v).copied().unwrap_or(0),
            );
            let r = *first.entry(key).or_insert(v as u32);
            rep[v] = r;
            if r == v as u32 {
                new_of[v] = n;
                n += 1;
            }
        }
        let welded = self.positions.len() - n as usize;
        if welded == 0 {
            return 0;
        }
        for v in 0..rep.len() {
            new_of[v] = new_of[rep[v] as usize];
        }
        self.compact_vertices(&new_of);
        welded
    }

    fn drop_degenerate(&mut self) -> (usize, usize) {
        let mut collapsed = 0;
        let mut dropped = 0;
        let mut kept = Vec::with_capacity(self.face_count());
        let mut changed = false;
        for f in 0..self.face_count() {
            let r = self.face(f);
            let n = r.len();
            // Keep a corner unless the corner after it (cyclically) is the
            // same vertex: the last of each run stays, the first corner of
            // the face stays first.
            let corners: Vec<u32> = r
                .clone()
                .filter(|&c| {
                    let next = if c + 1 == r.end { r.start } else { c + 1 };
                    n < 2 || self.indices[c] != self.indices[next]
                })
                .map(|c| c as u32)
                .collect();
            // A face whose corners are all one vertex keeps none above.
            let distinct_ok = corners.len() >= 3 && {
                let mut vs: Vec<u32> = corners.iter().map(|&c| self.indices[c as usize]).collect();
                vs.sort_unstable();
                vs.windows(2).all(|w| w[0] != w[1])
            };
            if !distinct_ok {
                dropped += 1;
                changed = true;
                continue;
            }
            if corners.len() != n {
                collapsed += n - corners.len();
                changed = true;
            }
            kept.push((f as u32, corners));
        }
        if changed {
            self.rebuild_faces(kept.into_iter());
        }
        (collapsed, dropped)
    }

    fn drop_duplicates(&mut self) -> usize {
        let mut sorted = self.indices.clone();
        for f in 0..self.face_count() {
            sorted[self.face(f)].sort_unstable();
        }
        let mut seen: HashMap<&[u32], ()> = HashMap::with_capacity(self.face_count());
        let mut keep = vec![true; self.face_count()];
        let mut dropped = 0;
        for (f, k) in keep.iter_mut().enumerate() {
            if seen.insert(&sorted[self.face(f)], ()).is_some() {
                *k = false;
                dropped += 1;
            }
        }
        drop(seen);
        if dropped > 0 {
            let faces: Vec<(u32, Vec<u32>)> = (0..self.face_count())
                .filter(|&f| keep[f])
                .map(|f| (f as u32, self.face(f).map(|c| c as u32).collect()))
                .collect();
            self.rebuild_faces(faces.into_iter());
        }
        dropped
    }

    /// The corner after `c` in its face, for every corner.
    fn next_corners(&self) -> Vec<u32> {
        let mut next = vec![0u32; self.indices.len()];
        for f in 0..self.face_count() {
            let r = self.face(f);
            for c in r.clone() {
                next[c] = if c + 1 == r.end { r.start } else { c + 1 } as u32;
            }
        }
        next
    }

    /// Corners grouped by their undirected edge: `(order, starts)` where
    /// group `g` is `order[starts[g]..starts[g + 1]]`, each in corner order.
    fn edge_groups(&self, next: &[u32]) -> (Vec<u32>, Vec<u32>) {
        let key = |c: usize| {
            let (a, b) = (self.indices[c], self.indices[next[c] as usize]);
            (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
        };
        let mut order: Vec<u32> = (0..self.indices.len() as u32).collect();
        order.sort_unstable_by_key(|&c| (key(c as usize), c));
        let mut starts = Vec::new();
        for (i, &c) in order.iter().enumerate() {
            if i == 0 || key(c as usize) != key(order[i - 1] as usize) {
                starts.push(i as u32);
            }
        }
        starts.push(order.len() as u32);
        (order, starts)
    }

    /// The face of every corner.
    fn corner_faces(&self) -> Vec<u32> {
        let mut face_of = vec![0u32; self.indices.len()];
        for f in 0..self.face_count() {
            for c in self.face(f) {
                face_of[c] = f as u32;
            }
        }
        face_of
    }

    fn orient(&mut self) -> (usize, usize) {
        let next = self.next_corners();
        let (order, starts) = self.edge_groups(&next);
        let face_of = self.corner_faces();
        // Partner corner across each edge used by exactly two faces.
        let mut partner = vec![NONE; self.indices.len()];
        for g in starts.windows(2) {
            if g[1] - g[0] == 2 {
                let (c, d) = (order[g[0] as usize], order[g[0] as usize + 1]);
                if face_of[c as usize] != face_of[d as usize] {
                    partner[c as usize] = d;
                    partner[d as usize] = c;
                }
            }
        }
        let nf = self.face_count();
        let mut flip: Vec<u8> = vec![2; nf]; // 2 = not reached
        let mut conflicts = 0;
        let mut queue = Vec::new();
        let mut flips = 0;
        for seed in 0..nf {
            if flip[seed] != 2 {
                continue;
            }
            flip[seed] = 0;
            queue.clear();
            queue.push(seed as u32);
            let mut head = 0;
            let mut flipped_here = 0;
            while head < queue.len() {
                let f = queue[head] as usize;
                head += 1;
                for c in self.face(f) {
                    let p = partner[c];
                    if p == NONE {
                        continue;
                    }
                    let g = face_of[p as usize] as usize;
                    let same = self.indices[c] == self.indices[p as usize];
                    let want = flip[f] ^ u8::from(same);
                    if flip[g] == 2 {
                        flip[g] = want;
                        flipped_here += usize::from(want);
                        queue.push(g as u32);
                    } else if flip[g] != want && f < g {
                        conflicts += 1;
                    }
                }
            }
            if 2 * flipped_here > queue.len() {
                for &f in &queue {
                    flip[f as usize] ^= 1;
                }
                flipped_here = queue.len() - flipped_here;
            }
            flips += flipped_here;
        }
        if flips > 0 {
            let faces: Vec<(u32, Vec<u32>)> = (0..nf)
                .map(|f| {
                    let r = self.face(f);
                    let mut corners: Vec<u32> = r.clone().map(|c| c as u32).collect();
                    if flip[f] == 1 {
                        corners[1..].reverse();
                    }
                    (f as u32, corners)
                })
                .collect();
            self.rebuild_faces(faces.into_iter());
        }
        (flips, conflicts)
    }

    fn split_edges(&mut self) -> (usize, usize) {
        let next = self.next_corners();
        let (order, starts) = self.edge_groups(&next);
        let face_of = self.corner_faces();
        let mut bad = 0;
        // (face, vertex) pairs that get their own copy.
        let mut detach: Vec<(u32, u32)> = Vec::new();
        for g in starts.windows(2) {
            let group = &order[g[0] as usize..g[1] as usize];
            if group.len() < 2 {
                continue;
            }
            let dir = |c: u32| self.indices[c as usize] < self.indices[next[c as usize] as usize];
            let distinct_faces =
                group.len() == 2 && face_of[group[0] as usize] != face_of[group[1] as usize];
            if group.len() == 2 && dir(group[0]) != dir(group[1]) && distinct_faces {
                continue;
            }
            bad += 1;
            // Keep the first pair of opposite uses, or the first use alone.
            let mut keep = [group[0], NONE];
            'pair: for (i, &c) in group.iter().enumerate() {
                for &d in &group[i + 1..] {
                    if dir(c) != dir(d) && face_of[c as usize] != face_of[d as usize] {
                        keep = [c, d];
                        break 'pair;
                    }
                }
            }
            for &c in group {
                if !keep.contains(&c) {
                    let f = face_of[c as usize];
                    detach.push((f, self.indices[c as usize]));
                    detach.push((f, self.indices[next[c as usize] as usize]));
                }
            }
        }
        detach.sort_unstable();
        detach.dedup();
        let copies = detach.len();
        for &(f, v) in &detach {
            let nv = self.copy_vertex(v);
            for c in self.face(f as usize) {
                if self.indices[c] == v {
                    self.indices[c] = nv;
                }
            }
        }
        (bad, copies)
    }

    fn split_vertices(&mut self) -> (usize, usize) {
        let next = self.next_corners();
        let (order, starts) = self.edge_groups(&next);
        let nc = self.indices.len();
        // Union corners at one vertex across each edge shared by two faces
        // in opposite directions: corner c (a->b) and partner d (b->a) make
        // corner next(d) at a the neighbour of c.
        let mut parent: Vec<u32> = (0..nc as u32).collect();
        let mut paired_out = vec![false; nc];
        for g in starts.windows(2) {
            if g[1] - g[0] != 2 {
                continue;
            }
            let (c, d) = (order[g[0] as usize], order[g[0] as usize + 1]);
            if self.indices[c as usize] == self.indices[d as usize] {
                continue;
            }
            paired_out[c as usize] = true;
            paired_out[d as usize] = true;
            union(&mut parent, c, next[d as usize]);
            union(&mut parent, d, next[c as usize]);
        }
        // prev corner of each corner: its incoming edge.
        let mut prev = vec![0u32; nc];
        for c in 0..nc {
            prev[next[c] as usize] = c as u32;
        }
        // Per vertex: its fans (roots) and whether each is open.
        let mut corners_by_vertex: Vec<(u32, u32, u32)> = (0..nc as u32)
            .map(|c| (self.indices[c as usize], find(&mut parent, c), c))
            .collect();
        corners_by_vertex.sort_unstable();
        let mut split = 0;
        let mut copies = 0;
        let mut i = 0;
        while i < nc {
            let v = corners_by_vertex[i].0;
            let mut j = i;
            while j < nc && corners_by_vertex[j].0 == v {
                j += 1;
            }
            let fans = &corners_by_vertex[i..j];
            let fan_count = 1 + fans.windows(2).filter(|w| w[0].1 != w[1].1).count();
            if fan_count > 1 {
                let any_closed = fans.chunk_by(|a, b| a.1 == b.1).any(|fan| {
                    fan.iter().all(|&(_, _, c)| {
                        paired_out[c as usize] && paired_out[prev[c as usize] as usize]
                    })
                });
                if any_closed {
                    split += 1;
                    for fan in fans.chunk_by(|a, b| a.1 == b.1).skip(1) {
                        let nv = self.copy_vertex(v);
                        copies += 1;
                        for &(_, _, c) in fan {
                            self.indices[c as usize] = nv;
                        }
                    }
                }
            }
            i = j;
        }
        (split, copies)
    }

    fn drop_unreferenced(&mut self) -> usize {
        let mut used = vec![false; self.vertex_count];
        for &i in &self.indices {
            used[i as usize] = true;
        }
        let dropped = used.iter().filter(|&&u| !u).count();
        if dropped > 0 {
            let mut n = 0u32;
            let new_of: Vec<u32> = used
                .iter()
                .map(|&u| {
                    if u {
                        n += 1;
                        n - 1
                    } else {
                        NONE
                    }
                })
                .collect();
            self.compact_vertices(&new_of);
        }
        dropped
    }
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[parent[x as usize] as usize];
        parent[x as usize] = p;
        x = p;
    }
    x
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        parent[hi as usize] = lo;
    }
}

#[cfg(test)]
mod tests;
