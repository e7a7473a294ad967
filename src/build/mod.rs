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
//!
//! Here: the buffers and the constructors, and `build_flat`, the stages in
//! order; `input` checks the input and numbers the used vertices, `pair`
//! pairs the twins, `link` links the half-edges and holes.

mod input;
mod link;
mod pair;

use input::{
    check_faces, check_index_range, check_positions, check_size, scan_corners, Flat, UsedVertices,
};
use link::{assemble, check_vertex_rings, input_keys, link_boundary, link_faces, make_hole_faces};
use pair::{bucket_sides, pair_triangle_twins, pair_twins};

use crate::error::{BuildError, Error, Result};
use crate::geometry::Point;
use crate::keys::{FaceKey, VertexKey};
use crate::mesh::Mesh;

/// An index of [`IndexMaps`] for a slot that was not exported.
const UNMAPPED: u32 = u32::MAX;

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

impl<'a> From<&'a Polygons> for PolygonsRef<'a> {
    /// The owned buffers, borrowed ([`Polygons::borrowed`]).
    fn from(polygons: &'a Polygons) -> Self {
        polygons.borrowed()
    }
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

    /// Build from flat buffers: positions, `faces + 1` offsets starting at
    /// 0, and the vertex indices of every face. Takes the owned
    /// [`Polygons`] (as [`Mesh::to_polygons`] returns them) or a borrowed
    /// [`PolygonsRef`] whose positions are any [`Point`] type, so an
    /// engine's or a file's arrays go in as they are. A topology-only mesh
    /// results when `positions` is empty; then the vertex count is one past
    /// the largest index, and the vertices no face uses are dropped as
    /// always.
    ///
    /// # Errors
    /// As [`Mesh::from_polygons`]; [`BuildError::MalformedOffsets`] when the
    /// offsets do not cut the indices into faces;
    /// [`BuildError::IndexOutOfRange`] (naming the face) for an index past
    /// the positions; [`BuildError::NonFinitePosition`] (naming the vertex)
    /// for a NaN or infinite coordinate, also in `f32`.
    ///
    /// # Complexity
    /// O(corners) time and memory whatever the index values (O(corners ·
    /// log corners) when they are spread far wider than their number: the
    /// used indices are then compacted by sorting), never proportional to
    /// the largest index.
    ///
    /// ```
    /// use meshloom::{BuildError, Error, Mesh, Polygons, PolygonsRef};
    /// // Claims four billion vertices and uses three: builds a triangle.
    /// let p = Polygons { positions: vec![], offsets: vec![0, 3], indices: vec![0, 1, u32::MAX] };
    /// let m = Mesh::from_buffers(&p)?;
    /// assert_eq!((m.vertex_count(), m.face_count()), (3, 1));
    ///
    /// // Borrowed `f32` arrays, as an engine holds them.
    /// let p: Vec<[f32; 3]> = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    /// let quad = Mesh::from_buffers(PolygonsRef::new(&p, &[0, 4], &[0, 1, 2, 3]))?;
    /// assert_eq!((quad.vertex_count(), quad.face_count()), (4, 1));
    ///
    /// let bad = Mesh::from_buffers(PolygonsRef::new(&p, &[0, 3], &[0, 1, 7])).unwrap_err();
    /// assert!(matches!(bad, Error::Build(BuildError::IndexOutOfRange { face: 0, index: 7, .. })));
    /// let nan = [[0.0f32, 0.0, 0.0], [f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let bad = Mesh::from_buffers(PolygonsRef::new(&nan, &[0, 3], &[0, 1, 2])).unwrap_err();
    /// assert!(matches!(bad, Error::Build(BuildError::NonFinitePosition { vertex: 1, .. })));
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
let tet = Mesh::from_buffers(PolygonsRef::new(&p, &offsets, &indices))?;
assert!(tet.is_closed());
# Ok::<(), meshloom::Error>(())
```
"#
    )]
    pub fn from_buffers<'a, P: Point + 'a>(
        polygons: impl Into<PolygonsRef<'a, P>>,
    ) -> Result<Mesh> {
        Ok(build_buffers(polygons.into(), false)?.mesh)
    }

    /// [`Mesh::from_buffers`], also returning the input's keys.
    ///
    /// # Errors
    /// As `from_buffers`; and [`BuildError::TooLarge`] for topology-only
    /// buffers whose largest index is more than twice the number of
    /// indices (plus 64): the returned key map has an entry per input
    /// vertex, and would not be bounded by the input's size.
    pub fn build_buffers<'a, P: Point + 'a>(
        polygons: impl Into<PolygonsRef<'a, P>>,
    ) -> Result<Built> {
        build_buffers(polygons.into(), true)
    }

    /// Renamed: [`Mesh::from_buffers`] takes a [`PolygonsRef`] too.
    #[doc(hidden)]
    #[deprecated(
        since = "0.2.0",
        note = "use Mesh::from_buffers, which takes a PolygonsRef too"
    )]
    pub fn from_buffers_ref<P: Point>(polygons: PolygonsRef<'_, P>) -> Result<Mesh> {
        Mesh::from_buffers(polygons)
    }

    /// Renamed: `Mesh::from_buffers(PolygonsRef::new(positions, offsets, indices))`.
    #[doc(hidden)]
    #[deprecated(
        since = "0.2.0",
        note = "use Mesh::from_buffers(PolygonsRef::new(positions, offsets, indices))"
    )]
    pub fn from_flat_faces<P: Point>(
        positions: &[P],
        offsets: &[u32],
        indices: &[u32],
    ) -> Result<Mesh> {
        Mesh::from_buffers(PolygonsRef::new(positions, offsets, indices))
    }

    /// Renamed: [`Mesh::build_buffers`] takes a [`PolygonsRef`] too.
    #[doc(hidden)]
    #[deprecated(
        since = "0.2.0",
        note = "use Mesh::build_buffers, which takes a PolygonsRef too"
    )]
    pub fn build_buffers_ref<P: Point>(polygons: PolygonsRef<'_, P>) -> Result<Built> {
        Mesh::build_buffers(polygons)
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
            for h in self.face_halfedges(f.id()) {
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
    check_offsets(p.offsets, p.indices)?;
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

/// Refuse offsets that do not start at 0, decrease, or end short of or
/// past the indices ([`BuildError::MalformedOffsets`]); no offsets and no
/// indices are no faces.
pub(crate) fn check_offsets(offsets: &[u32], indices: &[u32]) -> Result<()> {
    if offsets.first().is_some_and(|&o| o != 0)
        || offsets.windows(2).any(|w| w[1] < w[0])
        || offsets
            .last()
            .map_or(!indices.is_empty(), |&o| o as usize != indices.len())
    {
        return Err(Error::Build(BuildError::MalformedOffsets {
            offsets: offsets.len(),
            indices: indices.len(),
        }));
    }
    Ok(())
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
