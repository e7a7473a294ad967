//! Engine buffers: a mesh as flat triangle arrays for a renderer or a game
//! engine, and back.
//!
//! [`Mesh::to_triangle_buffers`](crate::Mesh::to_triangle_buffers) gives
//! `f32` positions, optional normals, any chosen vertex or corner columns
//! (UVs, colours) as flat arrays, and triangle indices (`u16` when they
//! fit, else `u32`). A mesh vertex is split into several buffer vertices
//! exactly where the chosen corner columns or the normals differ between
//! its corners (a UV seam, a crease, a hard edge), compared at the output
//! precision; everywhere else its corners share one buffer vertex.
//! Polygons are cut into triangles for the output by the crate's own ear
//! clipping ([`Mesh::triangulate`](crate::Mesh::triangulate), run on a
//! copy: the mesh is not changed).
//! [`Mesh::to_triangle_buffers_f64`](crate::Mesh::to_triangle_buffers_f64)
//! gives the same in `f64`.
//!
//! [`Mesh::from_triangle_buffers`](crate::Mesh::from_triangle_buffers) goes
//! back: buffer vertices are welded by position (exactly, or within a
//! tolerance, [`Weld`]), and columns come back as columns: a corner column
//! (and the normals) as half-edge values, so a UV seam becomes corner
//! values that differ across an edge; a vertex column as a vertex column
//! where all copies of a welded vertex agree.
//!
//! Every array is a `Vec` of `f32`/`f64`, `[f32; 3]`, `u16` or `u32`: plain
//! data that `bytemuck::cast_slice` turns into bytes, so a GPU buffer or an
//! engine mesh is filled with no per-vertex code.
//! [`TriangleBuffers::interleaved`] packs every attribute of a vertex side
//! by side (one vertex buffer, wgpu style); `examples/engine_buffers.rs`
//! fills wgpu-style byte buffers that way.
//!
//! ```
//! use meshloom::buffers::TriangleBufferOptions;
//! let cube = meshloom::shapes::cube();
//! // Default options: angle-weighted normals split at edges sharper than
//! // 30°, so every corner of the cube is its own vertex.
//! let b = cube.to_triangle_buffers(&TriangleBufferOptions::default())?;
//! assert_eq!((b.vertex_count(), b.triangle_count()), (24, 12));
//! assert!(matches!(b.indices, meshloom::buffers::Indices::U16(_)));
//! // Straight to bytes (this is what bytemuck::cast_slice does, by hand):
//! let bytes: Vec<u8> = b.positions.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
//! assert_eq!(bytes.len(), 24 * 12);
//! # Ok::<(), meshloom::buffers::BufferError>(())
//! ```
//!
//! # Bevy
//!
//! A bevy `Mesh` takes each attribute as a `Vec<[f32; N]>` and the
//! indices as `Indices::U16` or `Indices::U32`; nothing needs converting per
//! vertex (bevy is not a dependency of meshloom; this is not compiled):
//!
//! ```ignore
//! use bevy::render::mesh::{Indices, Mesh, PrimitiveTopology};
//! use bevy::render::render_asset::RenderAssetUsages;
//! use meshloom::buffers::{ColumnChoice, TriangleBufferOptions};
//!
//! let options = TriangleBufferOptions::default().columns(vec![ColumnChoice::corner("texcoord")]);
//! let b = my_mesh.to_triangle_buffers(&options)?;
//! let mut mesh = Mesh::new(PrimitiveTopology::TriangleList, RenderAssetUsages::default());
//! mesh.insert_attribute(Mesh::ATTRIBUTE_POSITION, b.positions.clone());
//! mesh.insert_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals.clone());
//! mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, b.columns[0].to_arrays::<2>());
//! mesh.insert_indices(match b.indices {
//!     meshloom::buffers::Indices::U16(i) => Indices::U16(i),
//!     meshloom::buffers::Indices::U32(i) => Indices::U32(i),
//! });
//! ```
//!
//! # Parallel
//!
//! With the `parallel` feature the corner normals (the costly part on
//! large meshes) are computed on rayon's threads
//! ([`algo::normals`](crate::algo::normals)); the vertex split itself is one
//! serial pass over the corners.

mod export;
mod import;
mod read;

pub use import::{FromBuffers, FromBuffersOptions, Weld};
#[cfg(feature = "gltf")]
pub(crate) use read::Reader;

use crate::algo::normals::CornerNormalOptions;
use crate::error::{BuildError, Error};
use crate::keys::{FaceKey, VertexKey};

/// A floating-point type buffers are made of: `f32` or `f64`. Sealed.
pub trait Scalar:
    Copy + Default + PartialEq + std::fmt::Debug + Send + Sync + sealed::Sealed + 'static
{
    /// From `f64`, rounded to the type's precision.
    fn from_f64(x: f64) -> Self;
    /// To `f64`, exactly.
    fn to_f64(self) -> f64;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

impl Scalar for f32 {
    #[inline]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
}

impl Scalar for f64 {
    #[inline]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
}

/// Which arena a buffer column comes from (and goes back to).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum ColumnSource {
    /// A vertex column: every corner of a vertex has the vertex's value, so
    /// it never splits a vertex.
    Vertex,
    /// A half-edge (corner) column, such as OBJ's `texcoord`: a vertex is
    /// split where its corners' values differ.
    Corner,
}

crate::choice::choices!(ColumnSource {
    Vertex = "vertex",
    Corner = "corner",
});

/// A column to put in the buffers: its name and arena.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct ColumnChoice {
    /// The column's name.
    pub name: String,
    /// Its arena.
    pub source: ColumnSource,
}

impl ColumnChoice {
    /// A half-edge (corner) column, such as `texcoord`.
    pub fn corner(name: &str) -> ColumnChoice {
        ColumnChoice {
            name: name.to_owned(),
            source: ColumnSource::Corner,
        }
    }

    /// A vertex column, such as a colour.
    pub fn vertex(name: &str) -> ColumnChoice {
        ColumnChoice {
            name: name.to_owned(),
            source: ColumnSource::Vertex,
        }
    }
}

/// The width of the indices.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum IndexWidth {
    /// `u16` when there are at most 65,535 vertices (65,535 itself stays
    /// free, the primitive-restart value), else `u32`.
    #[default]
    Auto,
    /// Always `u32`.
    U32,
}

crate::choice::choices!(IndexWidth {
    Auto = "auto",
    U32 = "u32",
});

/// What [`Mesh::to_triangle_buffers`](crate::Mesh::to_triangle_buffers)
/// puts in the buffers.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct TriangleBufferOptions {
    /// Corner normals and where they split (`None`: no normals). Default:
    /// angle-weighted, split at edges sharper than 30°
    /// ([`CornerNormalOptions::default`]); hard edges from a boolean edge
    /// column can be added there.
    pub normals: Option<CornerNormalOptions>,
    /// Vertex and corner columns to add, in this order (each of `f32`,
    /// `f64`, `[f32; N]` or `[f64; N]` values, or dynamic numbers; absent
    /// values are written as zeros).
    pub columns: Vec<ColumnChoice>,
    /// Index width (default: `u16` when it fits).
    pub index_width: IndexWidth,
}

crate::choice::setters!(TriangleBufferOptions {
    normals: Option<CornerNormalOptions>,
    columns: Vec<ColumnChoice>,
    index_width: IndexWidth,
});

impl Default for TriangleBufferOptions {
    fn default() -> Self {
        TriangleBufferOptions {
            normals: Some(CornerNormalOptions::default()),
            columns: Vec::new(),
            index_width: IndexWidth::Auto,
        }
    }
}

/// Triangle indices, `u16` or `u32`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Indices {
    /// 16-bit indices.
    U16(Vec<u16>),
    /// 32-bit indices.
    U32(Vec<u32>),
}

impl Indices {
    /// Number of indices (three per triangle).
    pub fn len(&self) -> usize {
        match self {
            Indices::U16(i) => i.len(),
            Indices::U32(i) => i.len(),
        }
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Index `i`, widened.
    pub fn get(&self, i: usize) -> Option<u32> {
        match self {
            Indices::U16(x) => x.get(i).map(|&v| u32::from(v)),
            Indices::U32(x) => x.get(i).copied(),
        }
    }

    /// Every index, widened.
    pub fn iter(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.len()).filter_map(move |i| self.get(i))
    }

    /// The indices as `u32`.
    pub fn to_u32(&self) -> Vec<u32> {
        match self {
            Indices::U16(x) => x.iter().map(|&v| u32::from(v)).collect(),
            Indices::U32(x) => x.clone(),
        }
    }

    /// Bytes per index: 2 or 4.
    pub fn width(&self) -> usize {
        match self {
            Indices::U16(_) => 2,
            Indices::U32(_) => 4,
        }
    }
}

/// One column in the buffers: `components` values per vertex, flat.
#[derive(Clone, Debug, PartialEq)]
pub struct BufferColumn<S = f32> {
    /// The column's name in the mesh.
    pub name: String,
    /// The arena it came from (and goes back to).
    pub source: ColumnSource,
    /// Values per vertex (1 to 4).
    pub components: usize,
    /// `components` values per buffer vertex, vertex after vertex.
    pub data: Vec<S>,
}

impl<S: Scalar> BufferColumn<S> {
    /// The values as `[S; N]` per vertex (`N` must be
    /// [`components`](Self::components); `None` otherwise).
    ///
    /// ```
    /// use meshloom::buffers::{BufferColumn, ColumnSource};
    /// let uv = BufferColumn { name: "uv".into(), source: ColumnSource::Corner, components: 2, data: vec![0.0f32, 1.0, 0.5, 0.5] };
    /// assert_eq!(uv.to_arrays::<2>(), Some(vec![[0.0, 1.0], [0.5, 0.5]]));
    /// assert_eq!(uv.to_arrays::<3>(), None);
    /// ```
    pub fn to_arrays<const N: usize>(&self) -> Option<Vec<[S; N]>> {
        if N != self.components || N == 0 {
            return None;
        }
        Some(
            self.data
                .chunks_exact(N)
                .map(|c| std::array::from_fn(|i| c[i]))
                .collect(),
        )
    }
}

/// A mesh as triangle buffers; see the [module docs](self).
#[derive(Clone, Debug, PartialEq)]
pub struct TriangleBuffers<S = f32> {
    /// One position per buffer vertex.
    pub positions: Vec<[S; 3]>,
    /// One unit normal per buffer vertex (empty when no normals were
    /// asked for; zero where the faces around a corner have no area).
    pub normals: Vec<[S; 3]>,
    /// The chosen columns, in the order asked.
    pub columns: Vec<BufferColumn<S>>,
    /// Three indices per triangle, counter-clockwise.
    pub indices: Indices,
    /// The mesh face each triangle was cut from (empty in buffers made by
    /// hand).
    pub triangle_faces: Vec<FaceKey>,
    /// The mesh vertex each buffer vertex is a copy of (empty in buffers
    /// made by hand).
    pub vertex_sources: Vec<VertexKey>,
}

impl<S: Scalar> TriangleBuffers<S> {
    /// Number of buffer vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The column of that name, if chosen.
    pub fn column(&self, name: &str) -> Option<&BufferColumn<S>> {
        self.columns.iter().find(|c| c.name == name)
    }

    /// Every attribute of a vertex side by side, vertex after vertex
    /// (position, then normal, then the columns in order): one vertex buffer
    /// with the layout a GPU pipeline declares.
    ///
    /// ```
    /// use meshloom::buffers::TriangleBufferOptions;
    /// let b = meshloom::shapes::cube().to_triangle_buffers(&TriangleBufferOptions::default())?;
    /// let (data, layout) = b.interleaved();
    /// assert_eq!(layout.stride, 6); // position and normal, in f32s
    /// assert_eq!(layout.attributes[1].name, "normal");
    /// assert_eq!(layout.attributes[1].offset, 3);
    /// assert_eq!(data.len(), 6 * b.vertex_count());
    /// assert_eq!(&data[6..9], &b.positions[1][..]);
    /// # Ok::<(), meshloom::buffers::BufferError>(())
    /// ```
    pub fn interleaved(&self) -> (Vec<S>, VertexLayout) {
        let mut attributes = vec![LayoutEntry {
            name: "position".into(),
            offset: 0,
            components: 3,
        }];
        let mut stride = 3;
        if !self.normals.is_empty() {
            attributes.push(LayoutEntry {
                name: "normal".into(),
                offset: stride,
                components: 3,
            });
            stride += 3;
        }
        for c in &self.columns {
            attributes.push(LayoutEntry {
                name: c.name.clone(),
                offset: stride,
                components: c.components,
            });
            stride += c.components;
        }
        let n = self.vertex_count();
        let mut data = Vec::with_capacity(n * stride);
        for i in 0..n {
            data.extend_from_slice(&self.positions[i]);
            if let Some(nr) = self.normals.get(i) {
                data.extend_from_slice(nr);
            }
            for c in &self.columns {
                let k = c.components;
                match c.data.get(i * k..(i + 1) * k) {
                    Some(v) => data.extend_from_slice(v),
                    None => data.extend(std::iter::repeat_n(S::default(), k)),
                }
            }
        }
        (data, VertexLayout { stride, attributes })
    }
}

/// Where each attribute sits in an interleaved vertex, counted in scalars
/// (multiply by `size_of::<S>()` for bytes).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VertexLayout {
    /// Scalars per vertex.
    pub stride: usize,
    /// The attributes, in order.
    pub attributes: Vec<LayoutEntry>,
}

/// One attribute of a [`VertexLayout`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LayoutEntry {
    /// `position`, `normal`, or the column's name.
    pub name: String,
    /// Its first scalar within the vertex.
    pub offset: usize,
    /// Its number of scalars.
    pub components: usize,
}

/// What can go wrong making buffers or a mesh from them. Every kind says
/// what was wrong and where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BufferError {
    /// Occurs when the mesh lacks what was asked (positions, a column) or a
    /// column holds values that are not numbers.
    #[error(transparent)]
    Mesh(#[from] Error),
    /// Occurs when a column has more than four values per vertex, or none.
    #[error("column {name:?} has {components} values per vertex; buffers take 1 to 4")]
    Components {
        /// The column.
        name: String,
        /// Its values per vertex.
        components: usize,
    },
    /// Occurs when the index buffer's length is not a multiple of three.
    #[error("the index buffer holds {len} indices, not a multiple of 3")]
    NotTriangles {
        /// Its length.
        len: usize,
    },
    /// Occurs when an index names no vertex.
    #[error("index {index} at position {at} of the index buffer is out of range (there are {count} vertices)")]
    IndexOutOfRange {
        /// Its position in the index buffer.
        at: usize,
        /// The index.
        index: u32,
        /// How many vertices there are.
        count: usize,
    },
    /// Occurs when an array does not have one entry (or `components`
    /// values) per vertex.
    #[error("{what} holds {len} values where {vertices} vertices need {expected}")]
    Length {
        /// `normals`, or the column's name.
        what: String,
        /// Its length.
        len: usize,
        /// How many vertices there are.
        vertices: usize,
        /// The length it should have.
        expected: usize,
    },
    /// Occurs when a position is NaN or infinite.
    #[error("vertex {vertex} has the non-finite position {position:?}")]
    NonFinite {
        /// The buffer vertex.
        vertex: usize,
        /// Its position.
        position: [f64; 3],
    },
    /// Occurs when the weld tolerance is negative or not finite.
    #[error("the weld tolerance {0} is not a finite number ≥ 0")]
    Tolerance(f64),
    /// Occurs when the welded triangles cannot form a half-edge mesh (an
    /// edge shared by three triangles, triangles that disagree in
    /// orientation, ...). `triangle` is the triangle (index buffer
    /// position / 3) where the builder stopped; the vertex numbers in
    /// `source` count welded vertices.
    #[error("triangle {triangle}: {source}")]
    Build {
        /// The triangle, counted in the input.
        triangle: usize,
        /// What the builder found.
        source: BuildError,
    },
    /// Occurs when more vertices or indices are needed than 32-bit indices
    /// address.
    #[error("too large: {what}")]
    TooLarge {
        /// What overflowed.
        what: &'static str,
    },
}

#[cfg(test)]
mod tests;
