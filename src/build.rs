//! Building a mesh from polygons, and getting polygons back.
//!
//! The builder runs in time linear in the input: corners are bucketed by
//! their lower vertex with a counting sort, each bucket (a vertex's edges,
//! a handful) is sorted to pair every directed edge with its twin, edges are
//! numbered in the order the faces first use them (as when faces are added
//! one by one, so edge slots follow the input's face order), and the
//! unpaired sides are linked into hole faces. Where several boundary loops meet at one vertex (a
//! bowtie), the hole passes through it once per fan and the fans are chained
//! so that turning around the vertex still visits every half-edge.

use crate::error::{BuildError, Error, Result};
use crate::geometry::Point;
use crate::keys::{FaceKey, VertexKey};
use crate::store::rules::Interpolate;
use crate::store::{Column, POSITION};
use std::borrow::Cow;

use crate::layout::{
    headroom, to_vec_with_headroom, with_headroom, Eid, FaceLink, Fid, HalfedgeRecord, Hid, IdVec,
    Vid,
};
use crate::mesh::Mesh;

/// An index of [`IndexMaps`] for a slot that was not exported.
const UNMAPPED: u32 = u32::MAX;
use crate::slots::Slots;

/// An integer type usable as a vertex index in face lists.
pub trait VertexIndex: Copy {
    /// The index as `usize`, or the raw value (for the error) if negative or
    /// too large.
    fn to_index(self) -> Result<usize, i64>;
}

macro_rules! vertex_index {
    ($($t:ty),*) => {$(
        impl VertexIndex for $t {
            #[inline]
            #[allow(clippy::unnecessary_fallible_conversions, irrefutable_let_patterns)]
            fn to_index(self) -> Result<usize, i64> {
                usize::try_from(self).map_err(|_| i64::try_from(self).unwrap_or(i64::MAX))
            }
        }
    )*};
}
vertex_index!(u8, u16, u32, u64, usize, i32, i64, isize);

/// Polygons in compact buffers: positions, and faces as one index array cut
/// by offsets (face `i` is `indices[offsets[i]..offsets[i + 1]]`).
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Polygons {
    /// One position per vertex (empty for a topology-only mesh).
    pub positions: Vec<[f64; 3]>,
    /// `faces + 1` offsets into `indices`, starting at 0.
    pub offsets: Vec<u32>,
    /// Vertex indices of every face, one face after the other.
    pub indices: Vec<u32>,
}

impl Polygons {
    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Face `i`'s vertex indices; `None` past the last face or where the
    /// offsets do not cut the index array.
    pub fn face(&self, i: usize) -> Option<&[u32]> {
        let (s, e) = (*self.offsets.get(i)?, *self.offsets.get(i + 1)?);
        self.indices.get(s as usize..e as usize)
    }

    /// Every face's vertex indices, in order.
    /// (Faces whose offsets do not cut the index array come out empty.)
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.offsets.windows(2).map(|w| {
            self.indices
                .get(w[0] as usize..w[1] as usize)
                .unwrap_or(&[])
        })
    }

    /// The same buffers borrowed, for [`Mesh::from_buffers_ref`].
    pub fn borrowed(&self) -> PolygonsRef<'_> {
        PolygonsRef {
            positions: &self.positions,
            offsets: &self.offsets,
            indices: &self.indices,
        }
    }
}

/// Compact buffers borrowed from the caller, with positions of any
/// [`Point`] type: `[f64; 3]` (the default), `[f32; 3]`, and with the
/// features `glam`, `nalgebra` or `mint` their points and vectors. Face `i`
/// is `indices[offsets[i]..offsets[i + 1]]`, as in [`Polygons`]; nothing is
/// copied or converted before the build (positions are converted to `f64`
/// once, for the vertices some face uses, as they are stored).
#[derive(Debug)]
pub struct PolygonsRef<'a, P = [f64; 3]> {
    /// One position per vertex (empty for a topology-only mesh).
    pub positions: &'a [P],
    /// `faces + 1` offsets into `indices`, starting at 0.
    pub offsets: &'a [u32],
    /// Vertex indices of every face, one face after the other.
    pub indices: &'a [u32],
}

impl<P> Clone for PolygonsRef<'_, P> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<P> Copy for PolygonsRef<'_, P> {}

impl<'a, P: Point> PolygonsRef<'a, P> {
    /// Borrow positions, offsets and indices.
    pub fn new(positions: &'a [P], offsets: &'a [u32], indices: &'a [u32]) -> Self {
        PolygonsRef {
            positions,
            offsets,
            indices,
        }
    }
}

/// Maps between a mesh's keys and the dense indices of [`Polygons`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IndexMaps {
    /// The key of each vertex index.
    pub vertices: Vec<VertexKey>,
    /// The key of each face index.
    pub faces: Vec<FaceKey>,
    vertex_slot: Vec<u32>,
    face_slot: Vec<u32>,
}

impl IndexMaps {
    /// The dense index of a vertex key, if it was exported.
    pub fn vertex_index(&self, v: VertexKey) -> Option<usize> {
        let i = *self.vertex_slot.get(v.index())?;
        (i != UNMAPPED && self.vertices[i as usize] == v).then_some(i as usize)
    }

    /// The dense index of a face key, if it was exported (holes are not).
    pub fn face_index(&self, f: FaceKey) -> Option<usize> {
        let i = *self.face_slot.get(f.index())?;
        (i != UNMAPPED && self.faces[i as usize] == f).then_some(i as usize)
    }
}

/// A built mesh with the keys of its input's vertices and faces.
#[derive(Clone, Debug)]
pub struct Built {
    /// The mesh.
    pub mesh: Mesh,
    /// The key of each input vertex; `None` for a vertex no face used.
    pub vertices: Vec<Option<VertexKey>>,
    /// The key of each input face, in input order.
    pub faces: Vec<FaceKey>,
    /// How many input vertices no face used (dropped: a vertex exists only
    /// while an edge touches it).
    pub unreferenced: usize,
}

impl Mesh {
    /// Build a mesh from positions and faces (index lists of any degree ≥ 3,
    /// counter-clockwise). Vertices no face uses are dropped.
    ///
    /// # Errors
    /// [`Error::Build`] naming the face and vertices: an index out of range,
    /// a face with fewer than three corners or a repeated vertex, an edge
    /// used by more than two faces or twice in one direction, a vertex whose
    /// faces form separate closed fans, a non-finite position.
    ///
    /// # Complexity
    /// O(corners), plus a sort of each vertex's edges.
    ///
    /// ```
    /// use meshloom::Mesh;
    /// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// let tet = Mesh::from_polygons(&p, &[[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]])?;
    /// assert_eq!(tet.euler_characteristic(), 2);
    /// assert!(tet.is_closed());
    ///
    /// let err = Mesh::from_polygons(&p, &[[0u32, 1, 9]]).unwrap_err();
    /// assert!(err.to_string().contains("face 0"));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    ///
    /// Positions are any [`Point`] type: `[f64; 3]` (borrowed as it is),
    /// `[f32; 3]`, and with the features `glam`, `nalgebra` or `mint` their
    /// points and vectors (converted to `f64` once, inside):
    ///
    /// ```
    /// use meshloom::Mesh;
    /// let p: Vec<[f32; 3]> = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let tri = Mesh::from_polygons(&p, &[[0u16, 1, 2]])?;
    /// assert_eq!(tri.position(tri.vertices().nth(1).unwrap())?, [1.0, 0.0, 0.0]);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn from_polygons<P, F, I>(positions: &[P], faces: &[F]) -> Result<Mesh>
    where
        P: Point,
        F: AsRef<[I]>,
        I: VertexIndex,
    {
        Ok(build_lists(Some(positions), positions.len(), faces, false)?.mesh)
    }

    /// Build a topology-only mesh (no positions) over `vertex_count`
    /// vertices. Errors as [`Mesh::from_polygons`].
    ///
    /// ```
    /// let quad = meshloom::Mesh::from_faces(4, &[vec![0usize, 1, 2, 3]])?;
    /// assert!(!quad.has_positions());
    /// assert_eq!(quad.face_count(), 1);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn from_faces<F, I>(vertex_count: usize, faces: &[F]) -> Result<Mesh>
    where
        F: AsRef<[I]>,
        I: VertexIndex,
    {
        Ok(build_lists::<[f64; 3], _, _>(None, vertex_count, faces, false)?.mesh)
    }

    /// Build from compact buffers, as [`Mesh::to_polygons`] returns them. A
    /// topology-only mesh results when `positions` is empty; then the vertex
    /// count is one past the largest index, and the vertices no face uses
    /// are dropped as always.
    ///
    /// # Errors
    /// As [`Mesh::from_polygons`]; [`BuildError::MalformedOffsets`] when the
    /// offsets do not cut the indices into faces;
    /// [`BuildError::IndexOutOfRange`] (naming the face) for an index past
    /// the positions.
    ///
    /// # Complexity
    /// O(corners) time and memory whatever the index values (O(corners ·
    /// log corners) when they are spread far wider than their number: the
    /// used indices are then compacted by sorting), never proportional to
    /// the largest index.
    ///
    /// ```
    /// use meshloom::{Mesh, Polygons};
    /// // Claims four billion vertices and uses three: builds a triangle.
    /// let p = Polygons { positions: vec![], offsets: vec![0, 3], indices: vec![0, 1, u32::MAX] };
    /// let m = Mesh::from_buffers(&p)?;
    /// assert_eq!((m.vertex_count(), m.face_count()), (3, 1));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn from_buffers(polygons: &Polygons) -> Result<Mesh> {
        Ok(build_buffers(polygons.borrowed(), false)?.mesh)
    }

    /// [`Mesh::from_buffers`] over borrowed flat buffers whose positions
    /// are any [`Point`] type: an engine's or a file's arrays go in as they
    /// are, with no copy loop in the caller. Errors and complexity as
    /// `from_buffers`; a non-finite position (also a NaN in `f32`) is
    /// [`BuildError::NonFinitePosition`].
    ///
    /// ```
    /// use meshloom::{Mesh, PolygonsRef};
    /// let p: Vec<[f32; 3]> = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    /// let quad = Mesh::from_buffers_ref(PolygonsRef::new(&p, &[0, 4], &[0, 1, 2, 3]))?;
    /// assert_eq!((quad.vertex_count(), quad.face_count()), (4, 1));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[cfg_attr(
        feature = "glam",
        doc = r#"
With the `glam` feature, `glam::Vec3` (or `DVec3`) positions:

```
use meshloom::{Mesh, PolygonsRef};
use glam::Vec3;
let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
let offsets = [0, 3, 6, 9, 12];
let indices = [0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3];
let tet = Mesh::from_buffers_ref(PolygonsRef::new(&p, &offsets, &indices))?;
assert!(tet.is_closed());
# Ok::<(), meshloom::Error>(())
```
"#
    )]
    pub fn from_buffers_ref<P: Point>(polygons: PolygonsRef<'_, P>) -> Result<Mesh> {
        Ok(build_buffers(polygons, false)?.mesh)
    }

    /// [`Mesh::from_buffers_ref`] with the three arrays given one by one:
    /// positions of any [`Point`] type, `faces + 1` offsets starting at 0,
    /// and the vertex indices of every face.
    ///
    /// # Errors
    /// As [`Mesh::from_buffers`]: [`BuildError::MalformedOffsets`],
    /// [`BuildError::IndexOutOfRange`] naming the face,
    /// [`BuildError::NonFinitePosition`] naming the vertex, and the
    /// topological errors of [`Mesh::from_polygons`].
    ///
    /// ```
    /// use meshloom::{BuildError, Error, Mesh};
    /// let p = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let tri = Mesh::from_flat_faces(&p, &[0, 3], &[0, 1, 2])?;
    /// assert_eq!(tri.face_count(), 1);
    ///
    /// let bad = Mesh::from_flat_faces(&p, &[0, 3], &[0, 1, 7]).unwrap_err();
    /// assert!(matches!(bad, Error::Build(BuildError::IndexOutOfRange { face: 0, index: 7, .. })));
    /// let nan = [[0.0f32, 0.0, 0.0], [f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let bad = Mesh::from_flat_faces(&nan, &[0, 3], &[0, 1, 2]).unwrap_err();
    /// assert!(matches!(bad, Error::Build(BuildError::NonFinitePosition { vertex: 1, .. })));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn from_flat_faces<P: Point>(
        positions: &[P],
        offsets: &[u32],
        indices: &[u32],
    ) -> Result<Mesh> {
        Mesh::from_buffers_ref(PolygonsRef::new(positions, offsets, indices))
    }

    /// [`Mesh::from_buffers`], also returning the input's keys.
    ///
    /// # Errors
    /// As `from_buffers`; and [`BuildError::TooLarge`] for topology-only
    /// buffers whose largest index is more than twice the number of
    /// indices (plus 64): the returned key map has an entry per input
    /// vertex, and would not be bounded by the input's size.
    pub fn build_buffers(polygons: &Polygons) -> Result<Built> {
        build_buffers(polygons.borrowed(), true)
    }

    /// [`Mesh::from_buffers_ref`], also returning the input's keys.
    ///
    /// # Errors
    /// As [`Mesh::build_buffers`].
    pub fn build_buffers_ref<P: Point>(polygons: PolygonsRef<'_, P>) -> Result<Built> {
        build_buffers(polygons, true)
    }

    /// Build, also returning the keys of the input's vertices and faces and
    /// the number of unreferenced vertices dropped. `positions`, when given,
    /// must have `vertex_count` entries.
    ///
    /// # Complexity
    /// O(corners) to build the mesh whatever `vertex_count` is; the returned
    /// key map has one entry per input vertex, O(`vertex_count`).
    pub fn build<F, I>(
        positions: Option<&[[f64; 3]]>,
        vertex_count: usize,
        faces: &[F],
    ) -> Result<Built>
    where
        F: AsRef<[I]>,
        I: VertexIndex,
    {
        build_lists::<[f64; 3], _, _>(positions, vertex_count, faces, true)
    }

    /// The mesh as compact buffers (vertices and faces numbered densely in
    /// slot order; holes are not faces here), with the maps between keys and
    /// indices.
    ///
    /// ```
    /// let cube = meshloom::shapes::cube();
    /// let (poly, maps) = cube.to_polygons();
    /// assert_eq!((poly.positions.len(), poly.face_count()), (8, 6));
    /// assert!(poly.faces().all(|f| f.len() == 4));
    /// assert_eq!(maps.vertex_index(maps.vertices[3]), Some(3));
    /// ```
    pub fn to_polygons(&self) -> (Polygons, IndexMaps) {
        let mut vertex_slot = vec![UNMAPPED; self.v_slots.slot_count()];
        let mut vertices = Vec::with_capacity(self.vertex_count());
        for v in self.vertices() {
            vertex_slot[v.index()] = vertices.len() as u32;
            vertices.push(v);
        }
        let positions = match self.attrs.positions() {
            Some(col) => vertices
                .iter()
                .map(|v| col.get(v.index()).copied().unwrap_or([f64::NAN; 3]))
                .collect(),
            None => Vec::new(),
        };
        let mut face_slot = vec![UNMAPPED; self.f_slots.slot_count()];
        let mut faces = Vec::with_capacity(self.face_count());
        let mut offsets = Vec::with_capacity(self.face_count() + 1);
        let mut indices = Vec::with_capacity(self.halfedge_count());
        offsets.push(0);
        for f in self.faces() {
            face_slot[f.index()] = faces.len() as u32;
            faces.push(f);
            for h in self.face_loop(f.id()) {
                indices.push(vertex_slot[self.origin(h).index()]);
            }
            offsets.push(indices.len() as u32);
        }
        (
            Polygons {
                positions,
                offsets,
                indices,
            },
            IndexMaps {
                vertices,
                faces,
                vertex_slot,
                face_slot,
            },
        )
    }
}

fn build_buffers<P: Point>(polygons: PolygonsRef<'_, P>, want_keys: bool) -> Result<Built> {
    let p = polygons;
    if p.offsets.first().is_some_and(|&o| o != 0)
        || p.offsets.windows(2).any(|w| w[1] < w[0])
        || p.offsets
            .last()
            .map_or(!p.indices.is_empty(), |&o| o as usize != p.indices.len())
    {
        return Err(Error::Build(BuildError::MalformedOffsets {
            offsets: p.offsets.len(),
            indices: p.indices.len(),
        }));
    }
    let (positions, n) = if p.positions.is_empty() {
        // One past the largest index: the builder stays linear in the
        // corners however large that is, but a key map per input vertex
        // would not.
        let n = p.indices.iter().max().map_or(0, |&m| m as usize + 1);
        if want_keys && n > UsedVertices::dense_span_limit(p.indices.len()) {
            return Err(BuildError::TooLarge {
                what: "the key map of topology-only buffers: their largest index claims more than two vertices per corner",
            }
            .into());
        }
        (None, n)
    } else {
        (Some(p.positions), p.positions.len())
    };
    let offsets: &[u32] = if p.offsets.is_empty() {
        &[0]
    } else {
        p.offsets
    };
    build_flat(positions, n, offsets, p.indices, want_keys)
}

/// Flatten face lists (checking index ranges) and build.
fn build_lists<P, F, I>(
    positions: Option<&[P]>,
    vertex_count: usize,
    faces: &[F],
    want_keys: bool,
) -> Result<Built>
where
    P: Point,
    F: AsRef<[I]>,
    I: VertexIndex,
{
    let n = positions.map_or(vertex_count, |p| p.len().min(vertex_count));
    let total: usize = faces.iter().map(|f| f.as_ref().len()).sum();
    if total >= (1 << 29) || faces.len() >= (1 << 29) || n >= (1 << 31) {
        return Err(BuildError::TooLarge {
            what: "more than 2^29 corners or faces, or 2^31 vertices",
        }
        .into());
    }
    let mut offsets = Vec::with_capacity(faces.len() + 1);
    let mut indices = Vec::with_capacity(total);
    offsets.push(0u32);
    for (fi, face) in faces.iter().enumerate() {
        for &i in face.as_ref() {
            match i.to_index() {
                Ok(i) if i < n => indices.push(i as u32),
                Ok(i) => {
                    return Err(BuildError::IndexOutOfRange {
                        face: fi,
                        index: i64::try_from(i).unwrap_or(i64::MAX),
                        vertex_count: n,
                    }
                    .into())
                }
                Err(raw) => {
                    return Err(BuildError::IndexOutOfRange {
                        face: fi,
                        index: raw,
                        vertex_count: n,
                    }
                    .into())
                }
            }
        }
        offsets.push(indices.len() as u32);
    }
    build_flat(positions.map(|p| &p[..n]), n, &offsets, &indices, want_keys)
}

/// Flat faces: face `f` is `indices[offsets[f]..offsets[f + 1]]`.
#[derive(Copy, Clone)]
struct Flat<'a> {
    offsets: &'a [u32],
    indices: &'a [u32],
}

impl<'a> Flat<'a> {
    /// Number of faces.
    fn face_count(self) -> usize {
        self.offsets.len() - 1
    }

    /// Face `f`'s corners.
    fn face(self, f: usize) -> &'a [u32] {
        &self.indices[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }

    /// The same faces over other (renumbered) indices.
    fn with_indices(self, indices: &'a [u32]) -> Flat<'a> {
        Flat {
            offsets: self.offsets,
            indices,
        }
    }

    /// Call `f(corner, origin, dest)` for every side of every face (faces
    /// have at least three corners: checked first).
    #[inline]
    fn for_each_side(self, mut f: impl FnMut(usize, u32, u32)) {
        let indices = self.indices;
        for w in self.offsets.windows(2) {
            let (s, e) = (w[0] as usize, w[1] as usize);
            for c in s..e - 1 {
                f(c, indices[c], indices[c + 1]);
            }
            f(e - 1, indices[e - 1], indices[s]);
        }
    }

    /// The face a corner belongs to (error paths only).
    fn face_of_corner(self, c: usize) -> usize {
        self.offsets.partition_point(|&o| o as usize <= c) - 1
    }
}

/// The builder proper, over flat input: checks, then builds in linear
/// time, one named stage after the other.
fn build_flat<P: Point>(
    positions: Option<&[P]>,
    n_in: usize,
    offsets: &[u32],
    indices: &[u32],
    want_keys: bool,
) -> Result<Built> {
    let input = Flat { offsets, indices };
    check_size(input)?;
    let vertices = match scan_corners(input, n_in) {
        Some(vertices) => vertices,
        None => {
            // Some face is bad: the stages one by one name the first defect.
            check_index_range(input, n_in)?;
            check_faces(input)?;
            UsedVertices::of(input, n_in)
        }
    };
    check_positions(positions, &vertices)?;
    let faces = input.with_indices(&vertices.indices);
    let mates = match pair_triangle_twins(faces, vertices.count) {
        Some(mates) => mates,
        None => pair_twins(faces, bucket_sides(faces, vertices.count), &vertices)?,
    };
    let (mut links, twins) = link_faces(faces, vertices.count, mates);
    link_boundary(&mut links, &twins.boundary, &vertices)?;
    let edges = twins.edges;
    let (f_halfedge, holes) = make_hole_faces(&mut links.he, faces, twins);
    check_vertex_rings(&links, &vertices)?;
    let mesh = assemble(links, edges, f_halfedge, holes, positions, &vertices);
    debug_assert_eq!(mesh.validate(), Ok(()));
    let (keys, face_keys) = if want_keys {
        input_keys(&mesh, n_in, faces.face_count(), &vertices)
    } else {
        (Vec::new(), Vec::new())
    };
    Ok(Built {
        mesh,
        vertices: keys,
        faces: face_keys,
        unreferenced: n_in - vertices.count,
    })
}

/// Refuse input whose corners would not fit the 32-bit links.
fn check_size(input: Flat<'_>) -> Result<()> {
    if input.indices.len() >= (1 << 29) {
        return Err(BuildError::TooLarge {
            what: "more than 2^29 corners",
        }
        .into());
    }
    Ok(())
}

/// Every index must name one of the `n_in` input vertices.
fn check_index_range(input: Flat<'_>, n_in: usize) -> Result<()> {
    if let Some(c) = input.indices.iter().position(|&i| i as usize >= n_in) {
        return Err(BuildError::IndexOutOfRange {
            face: input.face_of_corner(c),
            index: i64::from(input.indices[c]),
            vertex_count: n_in,
        }
        .into());
    }
    Ok(())
}

/// Stage 1, per face: at least three corners, no corner twice.
fn check_faces(input: Flat<'_>) -> Result<()> {
    let mut scratch: Vec<u32> = Vec::new();
    for f in 0..input.face_count() {
        let face = input.face(f);
        if face.len() < 3 {
            return Err(BuildError::TooFewVertices {
                face: f,
                degree: face.len(),
            }
            .into());
        }
        let repeated = if face.len() <= 8 {
            (1..face.len()).find_map(|i| face[..i].contains(&face[i]).then_some(face[i]))
        } else {
            scratch.clear();
            scratch.extend_from_slice(face);
            scratch.sort_unstable();
            scratch
                .windows(2)
                .find_map(|w| (w[0] == w[1]).then_some(w[0]))
        };
        if let Some(v) = repeated {
            return Err(BuildError::RepeatedVertex {
                face: f,
                vertex: v as usize,
            }
            .into());
        }
    }
    Ok(())
}

/// Stages 1 and 2 in one pass over the corners, for good input: every
/// index in range, every face with three or more distinct corners, and the
/// used vertices marked as it goes. `None` when some face is bad (the
/// separate stages then name the first defect) or when the indices are
/// spread too wide for a bitset (the sorting path).
fn scan_corners(input: Flat<'_>, n_in: usize) -> Option<UsedVertices<'_>> {
    let span = n_in.min(UsedVertices::dense_span_limit(input.indices.len()));
    let mut used = vec![0u64; span.div_ceil(64)];
    let mut mark = |v: u32| used[v as usize / 64] |= 1 << (v % 64);
    for w in input.offsets.windows(2) {
        let face = input.indices.get(w[0] as usize..w[1] as usize)?;
        match *face {
            [a, b, c] => {
                if a == b || b == c || c == a || a.max(b).max(c) as usize >= span {
                    return None;
                }
                mark(a);
                mark(b);
                mark(c);
            }
            _ => {
                if face.len() < 3 || face.len() > 8 {
                    return None;
                }
                for (i, &v) in face.iter().enumerate() {
                    if v as usize >= span || face[..i].contains(&v) {
                        return None;
                    }
                    mark(v);
                }
            }
        }
    }
    Some(UsedVertices::from_bitset(input.indices, n_in, span, &used))
}

/// Stage 2: the input vertices some face uses, numbered densely (a vertex
/// exists only while an edge touches it), and the corners renumbered.
struct UsedVertices<'a> {
    /// Number of used vertices: the vertex slots.
    count: usize,
    /// Input index of each slot; `None` when it is the identity (no vertex
    /// unused).
    input_of_slot: Option<Vec<u32>>,
    /// The corners, by slot.
    indices: Cow<'a, [u32]>,
}

impl<'a> UsedVertices<'a> {
    /// Memory and time stay linear in the corners whatever the indices: a
    /// dense bitset over the index span when the span is at most a few
    /// times the corner count, else a sort of the corners (a caller may
    /// claim billions of vertices and use three).
    fn of(input: Flat<'a>, n_in: usize) -> Self {
        let indices = input.indices;
        let span = indices.iter().max().map_or(0, |&m| m as usize + 1);
        if span > Self::dense_span_limit(indices.len()) {
            return Self::sparse(indices);
        }
        let mut used = vec![0u64; span.div_ceil(64)];
        for &i in indices {
            used[i as usize / 64] |= 1 << (i % 64);
        }
        Self::from_bitset(indices, n_in, span, &used)
    }

    /// The used vertices from a bitset over the index span `0..span`.
    fn from_bitset(indices: &'a [u32], n_in: usize, span: usize, used: &[u64]) -> Self {
        let count = used.iter().map(|w| w.count_ones() as usize).sum::<usize>();
        if count == n_in {
            return UsedVertices {
                count,
                input_of_slot: None,
                indices: Cow::Borrowed(indices),
            };
        }
        let input_of_slot: Vec<u32> = (0..span)
            .filter(|&i| used[i / 64] >> (i % 64) & 1 == 1)
            .map(|i| i as u32)
            .collect();
        let mut slot_of = vec![u32::MAX; span];
        for (slot, &i) in input_of_slot.iter().enumerate() {
            slot_of[i as usize] = slot as u32;
        }
        let renumbered = indices.iter().map(|&i| slot_of[i as usize]).collect();
        UsedVertices {
            count: input_of_slot.len(),
            input_of_slot: Some(input_of_slot),
            indices: Cow::Owned(renumbered),
        }
    }

    /// The largest index span the dense path takes for `corners` corners.
    fn dense_span_limit(corners: usize) -> usize {
        2 * corners + 64
    }

    /// Used vertices of indices spread far wider than their number.
    fn sparse(indices: &'a [u32]) -> Self {
        let mut input_of_slot = indices.to_vec();
        input_of_slot.sort_unstable();
        input_of_slot.dedup();
        let renumbered = indices
            .iter()
            .map(|i| input_of_slot.binary_search(i).unwrap_or(0) as u32)
            .collect();
        UsedVertices {
            count: input_of_slot.len(),
            input_of_slot: Some(input_of_slot),
            indices: Cow::Owned(renumbered),
        }
    }

    /// The input index of vertex slot `slot` (slots are `u32` as stored).
    fn input(&self, slot: u32) -> usize {
        self.input_of_slot
            .as_ref()
            .map_or(slot, |m| m[slot as usize]) as usize
    }

    /// The input index of vertex `v`.
    fn input_of(&self, v: Vid) -> usize {
        self.input(v.raw())
    }
}

/// Every used vertex needs a finite position.
fn check_positions<P: Point>(positions: Option<&[P]>, vertices: &UsedVertices<'_>) -> Result<()> {
    if let Some(p) = positions {
        for slot in 0..vertices.count as u32 {
            let q = p[vertices.input(slot)].xyz();
            if !q.iter().all(|c| c.is_finite()) {
                return Err(BuildError::NonFinitePosition {
                    vertex: vertices.input(slot),
                    position: q,
                }
                .into());
            }
        }
    }
    Ok(())
}

/// Stage 3's result: every side in a bucket of its lower vertex. Entry `x`
/// packs the higher vertex (`x >> 33`), the direction (bit 32: 1 when the
/// side runs from the higher vertex) and the corner (the low 32 bits), so a
/// bucket sorts as plain integers. Buckets lie in vertex order; the edges
/// are numbered later, in face order (stage 5).
struct Buckets {
    /// Bucket `v` is `entries[ends[v - 1]..ends[v]]` (from 0 for `v = 0`).
    ends: Vec<u32>,
    entries: Vec<u64>,
}

impl Buckets {
    fn higher(x: u64) -> u32 {
        (x >> 33) as u32
    }

    fn from_higher(x: u64) -> bool {
        (x >> 32) & 1 == 1
    }

    fn corner(x: u64) -> usize {
        (x & 0xffff_ffff) as usize
    }

    /// The entries of vertex `v`'s bucket.
    fn range(&self, v: usize) -> std::ops::Range<usize> {
        let begin = if v == 0 { 0 } else { self.ends[v - 1] };
        begin as usize..self.ends[v] as usize
    }
}

/// Stage 3: bucket the sides by their lower vertex (a counting sort). One
/// array of `nv` counts becomes the buckets' starts, and placing advances
/// each start to its bucket's end.
fn bucket_sides(faces: Flat<'_>, nv: usize) -> Buckets {
    let mut ends = vec![0u32; nv];
    faces.for_each_side(|_, a, b| ends[a.min(b) as usize] += 1);
    let mut at = 0u32;
    for slot in &mut ends {
        let n = *slot;
        *slot = at;
        at += n;
    }
    let mut entries = vec![0u64; faces.indices.len()];
    faces.for_each_side(|c, a, b| {
        let (lo, hi, dir) = if a < b { (a, b, 0) } else { (b, a, 1) };
        let slot = &mut ends[lo as usize];
        entries[*slot as usize] = (u64::from(hi) << 33) | (dir << 32) | c as u64;
        *slot += 1;
    });
    Buckets { ends, entries }
}

/// Stage 4's result: each corner's twin corner, one past it (`mate[c] = 0`:
/// the side starting at `c` has no twin, a hole lies beyond it).
struct Mates {
    mate: Vec<u32>,
    /// Number of paired sides (interior edges).
    pairs: usize,
    /// Sides leaving each vertex (its half-edges in faces; stage 6 adds
    /// those in holes).
    out_degree: Vec<u32>,
}

/// Stage 4: pair each directed side with its twin, bucket by bucket. On
/// bad input the error is the one met first when the buckets are taken in
/// the order in which the faces first use their vertex.
fn pair_twins(faces: Flat<'_>, mut sides: Buckets, vertices: &UsedVertices<'_>) -> Result<Mates> {
    let nv = sides.ends.len();
    let mut mates = Mates {
        mate: vec![0u32; faces.indices.len()],
        pairs: 0,
        out_degree: Vec::new(),
    };
    for v in 0..nv {
        let range = sides.range(v);
        let group = &mut sides.entries[range];
        if pair_bucket(faces, v as u32, group, &mut mates, vertices).is_err() {
            return Err(first_bucket_error(faces, &mut sides, vertices));
        }
    }
    drop(sides);
    let mut out_degree = vec![0u32; nv];
    for &v in faces.indices {
        out_degree[v as usize] += 1;
    }
    mates.out_degree = out_degree;
    Ok(mates)
}

/// Stages 3 and 4 for triangles only, with half the memory: the corners
/// are bucketed by their origin (a counting sort of `u32` corners; a
/// corner's destination is the next corner of its triangle), and each side
/// finds its twin in its destination's bucket. `None` when some directed
/// edge is used twice, or the input is not all triangles: the general
/// stages then run and name the defect exactly as they always have.
fn pair_triangle_twins(faces: Flat<'_>, nv: usize) -> Option<Mates> {
    let idx = faces.indices;
    let corners = idx.len();
    let all_triangles = corners == 3 * faces.face_count()
        && faces
            .offsets
            .iter()
            .enumerate()
            .all(|(f, &o)| o as usize == 3 * f);
    if !all_triangles {
        return None;
    }
    let by_origin = OriginBuckets::of(idx, nv);
    let mut mate = vec![0u32; corners];
    let mut pairs = 0;
    for c in 0..corners {
        if mate[c] != 0 {
            continue;
        }
        let (a, b) = (idx[c], triangle_dest(idx, c));
        // The first side b -> a. A second one is found when it looks for
        // its own twin: it finds this side taken, or (no side a -> b at
        // all) its double.
        match by_origin.sides(idx, b, a).next() {
            Some(d) if mate[d as usize] == 0 => {
                mate[c] = d + 1;
                mate[d as usize] = c as u32 + 1;
                pairs += 1;
            }
            Some(_) => return None, // a -> b twice, b -> a once or more
            None => {
                if by_origin.sides(idx, a, b).any(|k| k as usize != c) {
                    return None; // a -> b twice, on the boundary
                }
            }
        }
    }
    Some(Mates {
        mate,
        pairs,
        out_degree: by_origin.into_sizes(),
    })
}

#[cfg(test)]
thread_local! {
    /// Bucket entries the triangle path has looked at (tests only).
    static SCANNED: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Count one bucket entry looked at (tests only: nothing in a build).
#[inline(always)]
fn scanned() {
    #[cfg(test)]
    SCANNED.with(|s| s.set(s.get() + 1));
}

/// The vertex after corner `c` of a triangle list.
#[inline(always)]
fn triangle_dest(idx: &[u32], c: usize) -> u32 {
    idx[if c % 3 == 2 { c - 2 } else { c + 1 }]
}

/// The corner before corner `c` in its triangle.
#[inline(always)]
fn triangle_before(c: usize) -> usize {
    if c % 3 == 0 {
        c + 2
    } else {
        c - 1
    }
}

/// Corners bucketed by their origin vertex: bucket `v` is
/// `corners[ends[v - 1]..ends[v]]` (from 0 for `v = 0`).
struct OriginBuckets {
    ends: Vec<u32>,
    corners: Vec<u32>,
}

impl OriginBuckets {
    /// A counting sort of the corners by origin (`indices[c] < nv`).
    fn of(indices: &[u32], nv: usize) -> Self {
        let mut ends = vec![0u32; nv];
        for &v in indices {
            ends[v as usize] += 1;
        }
        let mut at = 0u32;
        for slot in &mut ends {
            let n = *slot;
            *slot = at;
            at += n;
        }
        let mut corners = vec![0u32; indices.len()];
        for (c, &v) in indices.iter().enumerate() {
            let slot = &mut ends[v as usize];
            corners[*slot as usize] = c as u32;
            *slot += 1;
        }
        OriginBuckets { ends, corners }
    }

    /// The corners leaving vertex `v`.
    #[inline(always)]
    fn bucket(&self, v: u32) -> &[u32] {
        let v = v as usize;
        let begin = if v == 0 { 0 } else { self.ends[v - 1] };
        &self.corners[begin as usize..self.ends[v] as usize]
    }

    /// The corners of the sides `a -> b` (triangles only), found in the
    /// smaller of the two buckets: those leaving `a` whose destination is
    /// `b`, or those leaving `b` whose corner before is `a` (the side is
    /// then that corner before). Scanning the smaller bucket keeps a vertex
    /// of high valence from being scanned once per neighbour (a fan of `N`
    /// triangles around one vertex would cost `N²`): the cost per side is
    /// the lower valence of its two ends.
    #[inline(always)]
    fn sides<'s>(&'s self, idx: &'s [u32], a: u32, b: u32) -> impl Iterator<Item = u32> + 's {
        let (from_a, into_b) = (self.bucket(a), self.bucket(b));
        let by_a = from_a.len() <= into_b.len();
        let leaving = if by_a { from_a } else { &[][..] };
        let entering = if by_a { &[][..] } else { into_b };
        leaving
            .iter()
            .copied()
            .filter(move |&k| {
                scanned();
                triangle_dest(idx, k as usize) == b
            })
            .chain(entering.iter().filter_map(move |&k| {
                scanned();
                let before = triangle_before(k as usize);
                (idx[before] == a).then_some(before as u32)
            }))
    }

    /// Each bucket's size (the sides leaving each vertex), in the same
    /// buffer.
    fn into_sizes(self) -> Vec<u32> {
        drop(self.corners);
        let mut ends = self.ends;
        for v in (1..ends.len()).rev() {
            ends[v] -= ends[v - 1];
        }
        ends
    }
}

/// Sort one bucket and pair its sides; an edge used by three sides or
/// twice in one direction is an error.
fn pair_bucket(
    faces: Flat<'_>,
    v: u32,
    group: &mut [u64],
    mates: &mut Mates,
    vertices: &UsedVertices<'_>,
) -> Result<()> {
    group.sort_unstable();
    let mut i = 0;
    while i < group.len() {
        let hi = Buckets::higher(group[i]);
        let mut j = i + 1;
        while j < group.len() && Buckets::higher(group[j]) == hi {
            j += 1;
        }
        match j - i {
            1 => {}
            2 => {
                let (c0, c1) = (group[i], group[i + 1]);
                if Buckets::from_higher(c0) == Buckets::from_higher(c1) {
                    let (lo, hi) = (vertices.input(v), vertices.input(hi));
                    let (a, b) = if Buckets::from_higher(c0) {
                        (hi, lo)
                    } else {
                        (lo, hi)
                    };
                    return Err(BuildError::InconsistentOrientation {
                        a,
                        b,
                        faces: [
                            faces.face_of_corner(Buckets::corner(c0)),
                            faces.face_of_corner(Buckets::corner(c1)),
                        ],
                    }
                    .into());
                }
                let (k0, k1) = (Buckets::corner(c0), Buckets::corner(c1));
                mates.mate[k0] = k1 as u32 + 1;
                mates.mate[k1] = k0 as u32 + 1;
                mates.pairs += 1;
            }
            _ => {
                let mut fs: Vec<usize> = group[i..j]
                    .iter()
                    .map(|&x| faces.face_of_corner(Buckets::corner(x)))
                    .collect();
                fs.sort_unstable();
                let (a, b) = (vertices.input(v), vertices.input(hi));
                return Err(BuildError::NonManifoldEdge {
                    a: a.min(b),
                    b: a.max(b),
                    faces: [fs[0], fs[1], fs[2]],
                }
                .into());
            }
        }
        i = j;
    }
    Ok(())
}

/// The error path of stage 4: the first bad bucket in the order in which
/// the faces first use their vertex (the order the builder reported in
/// before it paired in vertex order).
fn first_bucket_error(faces: Flat<'_>, sides: &mut Buckets, vertices: &UsedVertices<'_>) -> Error {
    let nv = sides.ends.len();
    let mut seen = vec![false; nv];
    let mut scratch = Mates {
        mate: vec![0u32; faces.indices.len()],
        pairs: 0,
        out_degree: Vec::new(),
    };
    for &v in faces.indices {
        if std::mem::replace(&mut seen[v as usize], true) {
            continue;
        }
        let range = sides.range(v as usize);
        let group = &mut sides.entries[range];
        if let Err(e) = pair_bucket(faces, v, group, &mut scratch, vertices) {
            return e;
        }
    }
    unreachable!("stage 4 found an error in some bucket")
}

/// Stage 5's result: the hole half-edges with their origins, the number of
/// edges, and each input face's half-edge.
struct Twins {
    /// Each unpaired side's twin (it lies in a hole) and its origin.
    boundary: Vec<(Hid, Vid)>,
    edges: usize,
    /// The half-edge of each input face's first corner (room is left for
    /// the holes of stage 7).
    f_halfedge: Vec<FaceLink>,
}

/// The links being built.
struct Links {
    he: IdVec<Hid, HalfedgeRecord>,
    v_halfedge: IdVec<Vid, Hid>,
    /// Half-edges leaving each vertex, to check its ring.
    out_degree: IdVec<Vid, u32>,
}

/// Numbering state of stage 5: `mate` as stage 4 left it, except that an
/// entry with the high bit set is the half-edge of a side whose twin was
/// numbered first.
struct Numbering {
    mate: Vec<u32>,
    edges: u32,
    boundary: Vec<(Hid, Vid)>,
}

impl Numbering {
    const NUMBERED: u32 = 1 << 31;

    /// The half-edge of the side from corner `c` to vertex `dest`: a new
    /// edge (its half-edge 0) unless its twin side came first. A new edge's
    /// two records are appended to `he` here, in numbering order, so the
    /// arena is written once as it grows (no fill pass before).
    #[inline(always)]
    fn halfedge(&mut self, c: usize, dest: u32, he: &mut IdVec<Hid, HalfedgeRecord>) -> Hid {
        let m = self.mate[c];
        if m & Self::NUMBERED != 0 {
            return Hid::new(m & !Self::NUMBERED);
        }
        let [inner, outer] = Eid::new(self.edges).halfedges();
        self.edges += 1;
        debug_assert_eq!(he.len(), inner.index());
        he.push(HalfedgeRecord::VACANT);
        he.push(HalfedgeRecord::VACANT);
        if m == 0 {
            self.boundary.push((outer, Vid::new(dest)));
        } else {
            self.mate[m as usize - 1] = outer.raw() | Self::NUMBERED;
        }
        inner
    }
}

impl Links {
    /// Link the half-edge of a face's side starting at `origin`.
    #[inline(always)]
    fn link(&mut self, h: Hid, origin: u32, next: Hid, face: Fid) {
        let origin = Vid::new(origin);
        self.he[h] = HalfedgeRecord { origin, next, face };
        self.v_halfedge[origin] = h;
    }
}

/// Stage 5: number the edges in face order, as the faces first use them
/// (half-edge 0 runs along that first side, as when faces are added one
/// by one), and link the half-edges of the faces; every vertex names a
/// half-edge. Consecutive faces get consecutive edges, so the arena
/// follows the input's face order.
fn link_faces(faces: Flat<'_>, nv: usize, mates: Mates) -> (Links, Twins) {
    let corners = faces.indices.len();
    let edges = corners - mates.pairs;
    let unpaired = corners - 2 * mates.pairs;
    let nf = faces.face_count();
    let mut links = Links {
        he: IdVec::from_vec(Vec::with_capacity(Eid::halfedge_slots(
            edges + headroom(edges),
        ))),
        v_halfedge: IdVec::filled_with_headroom(Hid::NONE, nv),
        out_degree: IdVec::from_vec(mates.out_degree),
    };
    let mut numbering = Numbering {
        mate: mates.mate,
        edges: 0,
        boundary: Vec::with_capacity(unpaired),
    };
    let mut f_halfedge = with_headroom(nf + unpaired);
    let idx = faces.indices;
    let mut ring: Vec<Hid> = Vec::new();
    for f in 0..nf {
        let (s, e) = (faces.offsets[f] as usize, faces.offsets[f + 1] as usize);
        let face = Fid::new(f as u32);
        if let [a, b, c] = idx[s..e] {
            let h0 = numbering.halfedge(s, b, &mut links.he);
            let h1 = numbering.halfedge(s + 1, c, &mut links.he);
            let h2 = numbering.halfedge(s + 2, a, &mut links.he);
            links.link(h0, a, h1, face);
            links.link(h1, b, h2, face);
            links.link(h2, c, h0, face);
            f_halfedge.push(FaceLink::new(h0, false));
            continue;
        }
        ring.clear();
        for c in s..e {
            let n = if c + 1 < e { c + 1 } else { s };
            ring.push(numbering.halfedge(c, idx[n], &mut links.he));
        }
        for (k, c) in (s..e).enumerate() {
            let next = ring.get(k + 1).copied().unwrap_or(ring[0]);
            links.link(ring[k], idx[c], next, face);
        }
        f_halfedge.push(FaceLink::new(ring[0], false));
    }
    debug_assert_eq!(numbering.edges as usize, edges);
    debug_assert_eq!(links.he.len(), Eid::halfedge_slots(edges));
    (
        links,
        Twins {
            boundary: numbering.boundary,
            edges,
            f_halfedge,
        },
    )
}

/// Stage 6: the hole half-edges' origins, and each one's `next`: the hole
/// half-edge leaving the vertex it enters (where several leave one vertex,
/// a bowtie, the fans there are chained).
fn link_boundary(
    links: &mut Links,
    boundary: &[(Hid, Vid)],
    vertices: &UsedVertices<'_>,
) -> Result<()> {
    let he = &mut links.he;
    // Vertices that several hole half-edges leave (one bit each); the
    // hole half-edge leaving any other boundary vertex is its
    // `v_halfedge`.
    let mut several = vec![0u64; links.v_halfedge.len().div_ceil(64)];
    for &(g, o) in boundary {
        he[g].origin = o;
        // Rule 11: a boundary vertex names a half-edge in a hole (hole
        // half-edges have no face yet: stage 7 gives them theirs).
        let before = links.v_halfedge[o];
        if he[before].face.is_none() {
            several[o.index() / 64] |= 1 << (o.index() % 64);
        }
        links.v_halfedge[o] = g;
        links.out_degree[o] += 1;
    }
    let mut bowtie = false;
    for &(g, _) in boundary {
        let a = he[g.twin()].origin; // g enters a
        if several[a.index() / 64] >> (a.index() % 64) & 1 == 1 {
            bowtie = true;
        } else {
            let k = links.v_halfedge[a];
            if he[k].face.is_none() {
                he[g].next = k;
            }
        }
    }
    if bowtie {
        link_bowties(he, boundary, vertices)?;
    }
    if let Some(&(g, _)) = boundary.iter().find(|&&(g, _)| he[g].next.is_none()) {
        let a = he[g.twin()].origin;
        return Err(BuildError::NonManifoldVertex {
            vertex: vertices.input_of(a),
            face: he[g.twin()].face.index(),
        }
        .into());
    }
    Ok(())
}

/// At each vertex with several hole half-edges leaving it, find the fan each
/// starts, and chain the fans: the hole half-edge ending fan `i` continues
/// with the one starting fan `i + 1`.
fn link_bowties(
    he: &mut IdVec<Hid, HalfedgeRecord>,
    boundary: &[(Hid, Vid)],
    vertices: &UsedVertices<'_>,
) -> Result<()> {
    // Hole half-edges leaving each bowtie vertex, grouped by vertex.
    let mut leaving: Vec<(Vid, Hid)> = boundary.iter().map(|&(k, o)| (o, k)).collect();
    leaving.sort_unstable();
    let mut kept = Vec::with_capacity(leaving.len());
    for (i, &(a, k)) in leaving.iter().enumerate() {
        let shared =
            (i > 0 && leaving[i - 1].0 == a) || leaving.get(i + 1).is_some_and(|n| n.0 == a);
        if shared {
            kept.push((a, k));
        }
    }
    let leaving = kept;
    let budget = he.len();
    let mut i = 0;
    while i < leaving.len() {
        let a = leaving[i].0;
        let mut j = i;
        while j < leaving.len() && leaving[j].0 == a {
            j += 1;
        }
        // The hole half-edge that ends the fan started by each k.
        let mut ends = Vec::with_capacity(j - i);
        for &(_, k) in &leaving[i..j] {
            let mut o = he[k.twin()].next; // first interior outgoing
            let mut end = Hid::NONE;
            for _ in 0..budget {
                let x = o.twin(); // enters a
                if he[x].face.is_none() {
                    end = x;
                    break;
                }
                o = he[x].next;
            }
            if end.is_none() {
                return Err(BuildError::NonManifoldVertex {
                    vertex: vertices.input_of(a),
                    face: he[k.twin()].face.index(),
                }
                .into());
            }
            ends.push(end);
        }
        let m = j - i;
        for (fan, &end) in ends.iter().enumerate() {
            he[end].next = leaving[i + (fan + 1) % m].1;
        }
        i = j;
    }
    Ok(())
}

/// Stage 7: a hole face for every boundary loop (numbered after the input
/// faces), and every face's link. Returns the links and the hole count.
fn make_hole_faces(
    he: &mut IdVec<Hid, HalfedgeRecord>,
    faces: Flat<'_>,
    twins: Twins,
) -> (IdVec<Fid, FaceLink>, usize) {
    let nf = faces.face_count();
    let boundary = &twins.boundary;
    let mut f_halfedge = twins.f_halfedge;
    for &(g, _) in boundary {
        if !he[g].face.is_none() {
            continue;
        }
        let f = Fid::new(f_halfedge.len() as u32);
        f_halfedge.push(FaceLink::new(g, true));
        let mut h = g;
        for _ in 0..=boundary.len() {
            he[h].face = f;
            h = he[h].next;
            if h == g || h.is_none() {
                break;
            }
        }
    }
    let holes = f_halfedge.len() - nf;
    (IdVec::from_vec(f_halfedge), holes)
}

/// Stage 8: every vertex's ring must reach all its half-edges (faces that
/// meet at a vertex in separate closed fans cannot share one ring).
fn check_vertex_rings(links: &Links, vertices: &UsedVertices<'_>) -> Result<()> {
    let Links {
        he,
        v_halfedge,
        out_degree,
    } = links;
    for v in v_halfedge.ids() {
        let start = v_halfedge[v];
        let (mut h, mut ring) = (start, 0u32);
        loop {
            ring += 1;
            h = he[h.twin()].next;
            if h == start || ring > out_degree[v] {
                break;
            }
        }
        if ring != out_degree[v] {
            return Err(BuildError::NonManifoldVertex {
                vertex: vertices.input_of(v),
                face: he[start].face.min(he[start.twin()].face).index(),
            }
            .into());
        }
    }
    Ok(())
}

/// The mesh from the links, with the positions of the used vertices.
fn assemble<P: Point>(
    links: Links,
    edges: usize,
    f_halfedge: IdVec<Fid, FaceLink>,
    holes: usize,
    positions: Option<&[P]>,
    vertices: &UsedVertices<'_>,
) -> Mesh {
    let faces = f_halfedge.len();
    let mut mesh = Mesh {
        v_halfedge: links.v_halfedge.into(),
        v_slots: Slots::full(vertices.count),
        he: links.he.into(),
        e_slots: Slots::full(edges),
        f_halfedge: f_halfedge.into(),
        f_slots: Slots::full(faces),
        holes,
        attrs: Default::default(),
        rec: None,
    };
    if let Some(p) = positions {
        let values: Vec<[f64; 3]> = match &vertices.input_of_slot {
            None => to_vec_with_headroom(&P::slice_xyz(&p[..vertices.count])),
            Some(map) => {
                let mut v = with_headroom(map.len());
                v.extend(map.iter().map(|&i| p[i as usize].xyz()));
                v
            }
        };
        mesh.attrs.position = Some(mesh.attrs.vertex.push(
            POSITION,
            Box::new(Column::<[f64; 3], Interpolate>::dense(values)),
        ));
    }
    mesh
}

/// The key of each input vertex (`None` for unused ones) and face: one entry
/// per input vertex, as the caller asked.
fn input_keys(
    mesh: &Mesh,
    n_in: usize,
    nf: usize,
    vertices: &UsedVertices<'_>,
) -> (Vec<Option<VertexKey>>, Vec<FaceKey>) {
    let mut keys = vec![None; n_in];
    for slot in 0..vertices.count as u32 {
        keys[vertices.input(slot)] = Some(mesh.vkey(Vid::new(slot)));
    }
    let faces = (0..nf as u32).map(|f| mesh.fkey(Fid::new(f))).collect();
    (keys, faces)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fan of `n` triangles around vertex 0, its rim open.
    fn fan(n: u32) -> Vec<[u32; 3]> {
        (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect()
    }

    /// The triangle path pairs each side by scanning the smaller of its
    /// two vertices' buckets: around one vertex of valence `n` the entries
    /// looked at grow with `n`, not `n²` (the quadratic read of a fan).
    #[test]
    fn triangle_pairing_is_linear_in_valence() {
        let looked_at = |n: u32| {
            SCANNED.with(|s| s.set(0));
            let mesh = Mesh::from_faces(n as usize + 1, &fan(n)).unwrap();
            assert_eq!(mesh.face_count(), n as usize);
            SCANNED.with(|s| s.get())
        };
        let (small, large) = (looked_at(1_000), looked_at(16_000));
        // Linear: 16 times the triangles, about 16 times the entries (the
        // quadratic scan looked at 256 times as many).
        assert!(large <= 20 * small, "{small} -> {large}");
        assert!(large <= 16 * 3 * 16_000, "{large} entries for 48,000 sides");
    }
}
