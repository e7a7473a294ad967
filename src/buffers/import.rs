//! Triangle buffers → mesh: weld by position, build, recover the columns.

use std::collections::HashMap;

use super::{BufferError, ColumnSource, Scalar, TriangleBuffers};
use crate::algo::normals::NORMAL;
use crate::attr::Element;
use crate::error::{BuildError, Error};
use crate::keys::{FaceKey, HalfedgeKey, VertexKey};
use crate::mesh::Mesh;

/// Which buffer vertices become one mesh vertex.
///
/// Its words: `exact`, or the tolerance as a number (`0.001`): the variant
/// that carries data is spelled by its data.
///
/// ```
/// use meshloom::buffers::Weld;
/// assert_eq!("exact".parse::<Weld>()?, Weld::Exact);
/// assert_eq!("0.5".parse::<Weld>()?, Weld::Tolerance(0.5));
/// assert_eq!(Weld::Tolerance(0.5).to_string(), "0.5");
/// assert!("-1".parse::<Weld>().is_err());
/// # Ok::<(), meshloom::choice::UnknownChoice>(())
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub enum Weld {
    /// Those at exactly the same position (`-0.0` and `0.0` are the same).
    #[default]
    Exact,
    /// Those within this distance of the first vertex of their weld (in
    /// buffer order): each vertex joins the earliest weld whose first
    /// vertex is within the tolerance, or starts its own. Triangles whose
    /// corners weld together are dropped.
    Tolerance(f64),
}

impl Weld {
    /// The word of [`Weld::Exact`]; a tolerance is spelled as its number.
    pub const WORDS: &'static [&'static str] = &["exact"];
}

impl std::fmt::Display for Weld {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Weld::Exact => f.write_str("exact"),
            Weld::Tolerance(t) => write!(f, "{t}"),
        }
    }
}

impl std::str::FromStr for Weld {
    type Err = crate::choice::UnknownChoice;

    /// `exact`, or a finite number `≥ 0`: the tolerance.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if crate::choice::spells(s, "exact") {
            return Ok(Weld::Exact);
        }
        match s.trim().parse::<f64>() {
            Ok(t) if t.is_finite() && t >= 0.0 => Ok(Weld::Tolerance(t)),
            _ => Err(crate::choice::UnknownChoice {
                option: "Weld",
                given: s.to_owned(),
                choices: &["exact", "a tolerance (a number >= 0)"],
            }),
        }
    }
}

/// How [`Mesh::from_triangle_buffers`] builds.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct FromBuffersOptions {
    /// How vertices weld (default: exact positions).
    pub weld: Weld,
}

crate::choice::setters!(FromBuffersOptions { weld: Weld });

/// A mesh built from buffers, with where each buffer element went.
#[derive(Clone, Debug)]
pub struct FromBuffers {
    /// The mesh.
    pub mesh: Mesh,
    /// The mesh vertex of each buffer vertex (`None` for one no kept
    /// triangle uses).
    pub vertices: Vec<Option<VertexKey>>,
    /// The face of each triangle (`None` for one whose corners welded
    /// together).
    pub triangles: Vec<Option<FaceKey>>,
    /// How many triangles were dropped because their corners welded
    /// together.
    pub collapsed: usize,
}

impl Mesh {
    /// Build a mesh from triangle buffers (made by
    /// [`to_triangle_buffers`](Mesh::to_triangle_buffers), an engine or a
    /// file): buffer vertices weld by position ([`Weld`]); the normals
    /// become the half-edge column `normal`; a corner column becomes a
    /// half-edge column, so a UV seam comes back as corner values that
    /// differ across an edge; a vertex column stays a vertex column where
    /// every copy of each welded vertex has the same value, and becomes a
    /// half-edge column otherwise. Columns hold `f64`, `[f64; 2]`,
    /// `[f64; 3]` or `[f64; 4]` by their width.
    ///
    /// # Errors
    /// [`BufferError`]: arrays of the wrong length, an index out of range, a
    /// non-finite position, a bad tolerance, or welded triangles that do not
    /// form a half-edge mesh ([`BufferError::Build`], naming the triangle).
    ///
    /// # Complexity
    /// O(vertices + indices), expected (hashing).
    ///
    /// ```
    /// use meshloom::buffers::{FromBuffersOptions, TriangleBufferOptions};
    /// use meshloom::Mesh;
    /// let cube = meshloom::shapes::cube();
    /// let b = cube.to_triangle_buffers_f64(&TriangleBufferOptions::default())?;
    /// assert_eq!(b.vertex_count(), 24); // split by the flat normals
    /// let back = Mesh::from_triangle_buffers(&b, &FromBuffersOptions::default())?;
    /// assert_eq!((back.vertex_count(), back.face_count()), (8, 12));
    /// assert!(back.is_closed());
    /// # Ok::<(), meshloom::buffers::BufferError>(())
    /// ```
    pub fn from_triangle_buffers<S: Scalar>(
        buffers: &TriangleBuffers<S>,
        options: &FromBuffersOptions,
    ) -> Result<Mesh, BufferError> {
        Ok(Mesh::build_triangle_buffers(buffers, options)?.mesh)
    }

    /// [`from_triangle_buffers`](Mesh::from_triangle_buffers), also telling
    /// where each buffer vertex and triangle went.
    ///
    /// # Errors
    /// As [`from_triangle_buffers`](Mesh::from_triangle_buffers).
    pub fn build_triangle_buffers<S: Scalar>(
        buffers: &TriangleBuffers<S>,
        options: &FromBuffersOptions,
    ) -> Result<FromBuffers, BufferError> {
        let b = buffers;
        let n = b.positions.len();
        check(b)?;
        let positions: Vec<[f64; 3]> = b.positions.iter().map(|q| q.map(S::to_f64)).collect();
        let (rep, welded) = weld(&positions, options.weld)?;
        let indices = b.indices.to_u32();
        let mut tris: Vec<[u32; 3]> = Vec::with_capacity(indices.len() / 3);
        let mut kept: Vec<usize> = Vec::with_capacity(indices.len() / 3);
        for (t, c) in indices.chunks_exact(3).enumerate() {
            let w = [rep[c[0] as usize], rep[c[1] as usize], rep[c[2] as usize]];
            if w[0] != w[1] && w[1] != w[2] && w[2] != w[0] {
                tris.push(w);
                kept.push(t);
            }
        }
        let built = Mesh::build(Some(&welded), welded.len(), &tris).map_err(|e| match e {
            Error::Build(source) => BufferError::Build {
                triangle: first_face(&source)
                    .and_then(|f| kept.get(f).copied())
                    .unwrap_or(0),
                source,
            },
            other => BufferError::Mesh(other),
        })?;
        let mut mesh = built.mesh;
        let mut triangles = vec![None; indices.len() / 3];
        // The half-edge of every kept corner, and its buffer vertex.
        let mut corners: Vec<(HalfedgeKey, usize)> = Vec::with_capacity(3 * tris.len());
        for (k, &f) in built.faces.iter().enumerate() {
            let t = kept[k];
            triangles[t] = Some(f);
            let Ok(face) = mesh.face(f) else { continue };
            for (c, h) in face.halfedges().enumerate().take(3) {
                corners.push((h, indices[3 * t + c] as usize));
            }
        }
        let vertices: Vec<Option<VertexKey>> = (0..n)
            .map(|i| built.vertices.get(rep[i] as usize).copied().flatten())
            .collect();
        // A buffer vertex that no kept triangle uses has no corner: it
        // gives no value to its welded vertex.
        let mut used = vec![false; n];
        for &(_, i) in &corners {
            used[i] = true;
        }
        if !b.normals.is_empty() {
            let flat: Vec<S> = b.normals.iter().flatten().copied().collect();
            attach(&mut mesh, NORMAL, 3, &flat, &corners)?;
        }
        for col in &b.columns {
            let k = col.components;
            let agree = col.source == ColumnSource::Vertex && {
                let mut first: Vec<Option<usize>> = vec![None; welded.len()];
                (0..n).filter(|&i| used[i]).all(|i| {
                    let w = rep[i] as usize;
                    match first[w] {
                        None => {
                            first[w] = Some(i);
                            true
                        }
                        Some(j) => col.data[i * k..(i + 1) * k] == col.data[j * k..(j + 1) * k],
                    }
                })
            };
            if agree {
                let targets: Vec<(VertexKey, usize)> = (0..n)
                    .filter(|&i| used[i])
                    .filter_map(|i| vertices[i].map(|v| (v, i)))
                    .collect();
                attach(&mut mesh, &col.name, k, &col.data, &targets)?;
            } else {
                attach(&mut mesh, &col.name, k, &col.data, &corners)?;
            }
        }
        let collapsed = indices.len() / 3 - tris.len();
        Ok(FromBuffers {
            mesh,
            vertices,
            triangles,
            collapsed,
        })
    }
}

/// Lengths, ranges and finiteness.
fn check<S: Scalar>(b: &TriangleBuffers<S>) -> Result<(), BufferError> {
    let n = b.positions.len();
    if u32::try_from(n).is_err() {
        return Err(BufferError::TooLarge {
            what: "more than 2^32 buffer vertices",
        });
    }
    if b.indices.len() % 3 != 0 {
        return Err(BufferError::NotTriangles {
            len: b.indices.len(),
        });
    }
    if let Some((at, index)) = b.indices.iter().enumerate().find(|&(_, i)| i as usize >= n) {
        return Err(BufferError::IndexOutOfRange {
            at,
            index,
            count: n,
        });
    }
    if !b.normals.is_empty() && b.normals.len() != n {
        return Err(BufferError::Length {
            what: "normals".into(),
            len: b.normals.len(),
            vertices: n,
            expected: n,
        });
    }
    for c in &b.columns {
        if !(1..=4).contains(&c.components) {
            return Err(BufferError::Components {
                name: c.name.clone(),
                components: c.components,
            });
        }
        if c.data.len() != n * c.components {
            return Err(BufferError::Length {
                what: format!("column {:?}", c.name),
                len: c.data.len(),
                vertices: n,
                expected: n * c.components,
            });
        }
    }
    if let Some((vertex, q)) = b
        .positions
        .iter()
        .enumerate()
        .find(|(_, q)| !q.iter().all(|c| c.to_f64().is_finite()))
    {
        return Err(BufferError::NonFinite {
            vertex,
            position: q.map(S::to_f64),
        });
    }
    Ok(())
}

/// The weld of each vertex, and each weld's position (its first vertex's).
pub(crate) fn weld(
    positions: &[[f64; 3]],
    rule: Weld,
) -> Result<(Vec<u32>, Vec<[f64; 3]>), BufferError> {
    let mut rep = Vec::with_capacity(positions.len());
    let mut welded: Vec<[f64; 3]> = Vec::new();
    // `+ 0.0` turns -0.0 into 0.0, so both hash alike.
    let bits = |q: [f64; 3]| q.map(|c| (c + 0.0).to_bits());
    match rule {
        Weld::Tolerance(t) if !(t.is_finite() && t >= 0.0) => {
            return Err(BufferError::Tolerance(t))
        }
        Weld::Exact | Weld::Tolerance(0.0) => {
            let mut ids: HashMap<[u64; 3], u32> = HashMap::with_capacity(positions.len());
            for &q in positions {
                let next = welded.len() as u32;
                let id = *ids.entry(bits(q)).or_insert(next);
                if id == next {
                    welded.push(q);
                }
                rep.push(id);
            }
        }
        Weld::Tolerance(t) => {
            // Cells of side t: a weld within t of a point has its first
            // vertex in one of the 27 cells around it.
            let cell = |q: [f64; 3]| q.map(|c| (c / t).floor() as i64);
            let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
            for &q in positions {
                let c = cell(q);
                let mut best: Option<u32> = None;
                for dx in -1..=1i64 {
                    for dy in -1..=1i64 {
                        for dz in -1..=1i64 {
                            let key = [
                                c[0].saturating_add(dx),
                                c[1].saturating_add(dy),
                                c[2].saturating_add(dz),
                            ];
                            for &w in grid.get(&key).into_iter().flatten() {
                                let p = welded[w as usize];
                                let d2 = (0..3).map(|i| (p[i] - q[i]).powi(2)).sum::<f64>();
                                if d2 <= t * t && best.is_none_or(|b| w < b) {
                                    best = Some(w);
                                }
                            }
                        }
                    }
                }
                let id = match best {
                    Some(w) => w,
                    None => {
                        let w = welded.len() as u32;
                        welded.push(q);
                        grid.entry(c).or_default().push(w);
                        w
                    }
                };
                rep.push(id);
            }
        }
    }
    Ok((rep, welded))
}

/// The face a build error names first.
fn first_face(e: &BuildError) -> Option<usize> {
    match *e {
        BuildError::IndexOutOfRange { face, .. }
        | BuildError::TooFewVertices { face, .. }
        | BuildError::RepeatedVertex { face, .. }
        | BuildError::NonManifoldVertex { face, .. } => Some(face),
        BuildError::NonManifoldEdge { faces, .. } => Some(faces[2]),
        BuildError::InconsistentOrientation { faces, .. } => Some(faces[1]),
        _ => None,
    }
}

/// Add column `name` on `K`'s arena, `k` values wide, and give each target
/// key the values of its buffer vertex.
fn attach<K: Element, S: Scalar>(
    mesh: &mut Mesh,
    name: &str,
    k: usize,
    data: &[S],
    targets: &[(K, usize)],
) -> Result<(), Error> {
    macro_rules! go {
        ($t:ty, $conv:expr) => {{
            let h = mesh.add_attr::<K, $t>(name)?;
            let mut view = mesh.attr_view_mut(&h)?;
            for &(key, i) in targets {
                view.set(key, Some($conv(&data[i * k..(i + 1) * k])))?;
            }
        }};
    }
    fn arr<const N: usize, S: Scalar>(s: &[S]) -> [f64; N] {
        std::array::from_fn(|j| s[j].to_f64())
    }
    match k {
        1 => go!(f64, |s: &[S]| s[0].to_f64()),
        2 => go!([f64; 2], arr::<2, S>),
        3 => go!([f64; 3], arr::<3, S>),
        _ => go!([f64; 4], arr::<4, S>),
    }
    Ok(())
}
