//! Mesh → triangle buffers.

use super::read::Reader;
use super::{
    BufferColumn, BufferError, ColumnSource, IndexWidth, Indices, Scalar, TriangleBufferOptions,
    TriangleBuffers,
};
use crate::algo::normals::corner_normals;
use crate::error::Error;
use crate::keys::{FaceKey, HalfedgeKey, VertexKey};
use crate::layout::Hid;
use crate::mesh::Mesh;

/// One corner of an output triangle: its vertex, its half-edge in the mesh
/// the corner columns are read from, and its half-edge slot in the input
/// mesh (for the normals).
#[derive(Clone, Copy)]
struct Corner {
    v: VertexKey,
    work: HalfedgeKey,
    orig: usize,
}

/// A chosen column being read.
enum Source<'m> {
    Vertex(Reader<'m, VertexKey>),
    Corner(Reader<'m, HalfedgeKey>),
}

impl Mesh {
    /// The mesh as `f32` triangle buffers for a renderer or an engine; see
    /// [`buffers`](crate::buffers).
    ///
    /// # Errors
    /// [`BufferError::Mesh`] with [`Error::NoPositions`],
    /// [`Error::AttributeMissing`] or [`Error::AttributeType`] (a chosen
    /// column that is missing or holds no numbers), or a stale hard-edge
    /// handle; [`BufferError::Components`] for a column of more than four
    /// values; [`BufferError::TooLarge`] past 2³² − 1 buffer vertices.
    ///
    /// # Complexity
    /// O(corners) plus the corner normals; a mesh with polygons is copied
    /// once and its polygons cut on the copy (O(n²) per polygon of degree n).
    ///
    /// ```
    /// use meshloom::buffers::{ColumnChoice, TriangleBufferOptions};
    /// use meshloom::shapes::{grid, GridFaces};
    /// // A flat grid of 2 × 1 quads with a UV seam down the middle edge.
    /// let mut mesh = grid(2, 1, GridFaces::Quads);
    /// let uv = mesh.add_halfedge_attr::<[f64; 2]>("texcoord")?;
    /// let corners: Vec<_> = mesh.faces().flat_map(|f| mesh.face(f).unwrap().halfedges().collect::<Vec<_>>()).collect();
    /// for (i, h) in corners.into_iter().enumerate() {
    ///     let x = mesh.halfedge(h)?.origin().position().unwrap()[0];
    ///     let island = if i < 4 { 0.0 } else { 10.0 }; // one UV island per quad
    ///     mesh.set_attr(&uv, h, [x + island, 0.0])?;
    /// }
    /// let options = TriangleBufferOptions::default().columns(vec![ColumnChoice::corner("texcoord")]);
    /// let b = mesh.to_triangle_buffers(&options)?;
    /// // 6 mesh vertices; the 2 on the seam are split: 8 buffer vertices.
    /// assert_eq!((b.vertex_count(), b.triangle_count()), (8, 4));
    /// assert_eq!(b.column("texcoord").unwrap().data.len(), 16);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_triangle_buffers(
        &self,
        options: &TriangleBufferOptions,
    ) -> Result<TriangleBuffers<f32>, BufferError> {
        export(self, options)
    }

    /// [`to_triangle_buffers`](Mesh::to_triangle_buffers) in `f64`: the
    /// positions come out exactly.
    ///
    /// # Errors
    /// As [`to_triangle_buffers`](Mesh::to_triangle_buffers).
    pub fn to_triangle_buffers_f64(
        &self,
        options: &TriangleBufferOptions,
    ) -> Result<TriangleBuffers<f64>, BufferError> {
        export(self, options)
    }
}

/// The triangles of every face, in face order: a triangle as it is, a
/// polygon cut as [`Mesh::triangulate`] would cut it (ear clipping in its
/// plane), read from the mesh in one pass: no copy, no edit.
fn triangles(mesh: &Mesh) -> Vec<([Corner; 3], FaceKey)> {
    let mut out = Vec::with_capacity(mesh.face_count() * 2);
    let mut sides: Vec<Hid> = Vec::with_capacity(8);
    let mut cuts: Vec<[u32; 3]> = Vec::with_capacity(8);
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        cuts.clear();
        mesh.triangles_of(f, &mut sides, &mut cuts);
        let corner = |i: u32| {
            let h = sides[i as usize];
            Corner {
                v: mesh.vkey(mesh.origin(h)),
                work: mesh.hkey(h),
                orig: h.index(),
            }
        };
        let key = mesh.fkey(f);
        out.extend(cuts.iter().map(|t| (t.map(corner), key)));
    }
    out
}

fn export<S: Scalar>(
    mesh: &Mesh,
    options: &TriangleBufferOptions,
) -> Result<TriangleBuffers<S>, BufferError> {
    let p = mesh.position_slots().ok_or(Error::NoPositions)?;
    let normals = match &options.normals {
        Some(o) => Some(corner_normals(mesh, o)?),
        None => None,
    };
    let tris = triangles(mesh);
    let (sources, columns) = open_columns(mesh, options)?;
    let mut out = TriangleBuffers::<S> {
        positions: Vec::new(),
        normals: Vec::new(),
        columns,
        indices: Indices::U32(Vec::new()),
        triangle_faces: Vec::with_capacity(tris.len()),
        vertex_sources: Vec::new(),
    };
    let indices = weld_corners(mesh, p, normals.as_deref(), &tris, &sources, &mut out)?;
    out.indices = if options.index_width == IndexWidth::Auto && out.positions.len() < 65_536 {
        Indices::U16(indices.into_iter().map(|i| i as u16).collect())
    } else {
        Indices::U32(indices)
    };
    Ok(out)
}

/// The chosen columns, each with its reader and its empty output column.
fn open_columns<'m, S: Scalar>(
    mesh: &'m Mesh,
    options: &TriangleBufferOptions,
) -> Result<(Vec<Source<'m>>, Vec<BufferColumn<S>>), BufferError> {
    let mut sources = Vec::with_capacity(options.columns.len());
    let mut columns = Vec::with_capacity(options.columns.len());
    for c in &options.columns {
        let source = match c.source {
            ColumnSource::Vertex => Source::Vertex(Reader::new(mesh, &c.name, mesh.vertices())?),
            ColumnSource::Corner => Source::Corner(Reader::new(mesh, &c.name, mesh.halfedges())?),
        };
        let components = match &source {
            Source::Vertex(r) => r.components(),
            Source::Corner(r) => r.components(),
        };
        if !(1..=4).contains(&components) {
            return Err(BufferError::Components {
                name: c.name.clone(),
                components,
            });
        }
        sources.push(source);
        columns.push(BufferColumn {
            name: c.name.clone(),
            source: c.source,
            components,
            data: Vec::new(),
        });
    }
    Ok((sources, columns))
}

/// Buffer vertices of one mesh vertex are chained: `head[v]` is the last
/// made, `chain[o]` the one made before `o`.
const NONE: u32 = u32::MAX;

/// Give every triangle corner a buffer vertex: an earlier one of its mesh
/// vertex with the same split values (normal, corner columns), or a new
/// one. Fills `out`'s vertices and triangle faces; returns the indices.
fn weld_corners<S: Scalar>(
    mesh: &Mesh,
    p: &[[f64; 3]],
    normals: Option<&[[f64; 3]]>,
    tris: &[([Corner; 3], FaceKey)],
    sources: &[Source<'_>],
    out: &mut TriangleBuffers<S>,
) -> Result<Vec<u32>, BufferError> {
    let mut head = vec![NONE; mesh.slot_counts()[0]];
    let mut chain: Vec<u32> = Vec::new();
    let mut indices: Vec<u32> = Vec::with_capacity(3 * tris.len());
    // The values that split a vertex: the normal, then the corner columns.
    let mut split: Vec<S> = Vec::with_capacity(16);
    let mut tmp = [0.0f64; 4];
    for (tri, f) in tris {
        out.triangle_faces.push(*f);
        for c in tri {
            split_values(c, normals, sources, &mut split, &mut tmp);
            let v = c.v.index();
            let mut o = head[v];
            while o != NONE && !same(out, o as usize, &split) {
                o = chain[o as usize];
            }
            if o == NONE {
                o = u32::try_from(out.positions.len())
                    .ok()
                    .filter(|&o| o != NONE)
                    .ok_or(BufferError::TooLarge {
                        what: "more than 2^32 - 1 buffer vertices",
                    })?;
                push_vertex(out, c, p[v], normals.is_some(), sources, &split, &mut tmp);
                chain.push(head[v]);
                head[v] = o;
            }
            indices.push(o);
        }
    }
    Ok(indices)
}

/// The values of corner `c` that split its vertex: its normal, then its
/// corner columns.
#[inline]
fn split_values<S: Scalar>(
    c: &Corner,
    normals: Option<&[[f64; 3]]>,
    sources: &[Source<'_>],
    split: &mut Vec<S>,
    tmp: &mut [f64; 4],
) {
    split.clear();
    if let Some(n) = normals {
        split.extend(n[c.orig].map(S::from_f64));
    }
    for s in sources {
        if let Source::Corner(r) = s {
            let k = r.components();
            r.read(c.work, &mut tmp[..k]);
            split.extend(tmp[..k].iter().map(|&x| S::from_f64(x)));
        }
    }
}

/// A new buffer vertex for corner `c` at `position`: the normal and corner
/// columns from `split`, the vertex columns read.
#[inline]
fn push_vertex<S: Scalar>(
    out: &mut TriangleBuffers<S>,
    c: &Corner,
    position: [f64; 3],
    with_normal: bool,
    sources: &[Source<'_>],
    split: &[S],
    tmp: &mut [f64; 4],
) {
    out.positions.push(position.map(S::from_f64));
    out.vertex_sources.push(c.v);
    let mut at = 0;
    if with_normal {
        out.normals.push([split[0], split[1], split[2]]);
        at = 3;
    }
    for (s, col) in sources.iter().zip(&mut out.columns) {
        let k = col.components;
        match s {
            Source::Corner(_) => {
                col.data.extend_from_slice(&split[at..at + k]);
                at += k;
            }
            Source::Vertex(r) => {
                r.read(c.v, &mut tmp[..k]);
                col.data.extend(tmp[..k].iter().map(|&x| S::from_f64(x)));
            }
        }
    }
}

/// Whether buffer vertex `o` has the split values `split`.
#[inline]
fn same<S: Scalar>(out: &TriangleBuffers<S>, o: usize, split: &[S]) -> bool {
    let mut at = 0;
    if let Some(n) = out.normals.get(o) {
        if n[..] != split[..3] {
            return false;
        }
        at = 3;
    }
    for col in &out.columns {
        if col.source == ColumnSource::Corner {
            let k = col.components;
            if col.data[o * k..(o + 1) * k] != split[at..at + k] {
                return false;
            }
            at += k;
        }
    }
    true
}
