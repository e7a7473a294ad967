//! Normals: per face, per vertex and per corner (half-edge), the normals a
//! renderer needs.
//!
//! - **Face normals** ([`face_normals`]): Newell's normal, so a non-planar
//!   or non-convex polygon gets its best-fit normal; unit length, or zero
//!   for a degenerate face (no area).
//! - **Vertex normals** ([`vertex_normals`]): the sum of the normals of the
//!   faces around the vertex, each weighted by [`NormalWeight`] (the angle
//!   of the face's corner at the vertex by default, as pmp-library and
//!   Thürmer & Wüthrich 1998), then normalised.
//! - **Corner normals** ([`corner_normals`]): one per half-edge, for the
//!   corner at its origin in its face. The faces around a vertex are cut
//!   into fans at *sharp* edges (a boundary, an edge whose two faces meet at
//!   more than [`CornerNormalOptions::feature_angle`], or one flagged in the
//!   boolean edge column [`CornerNormalOptions::features`]); the corners
//!   of one fan share the weighted sum of its faces' normals. Without sharp
//!   edges a corner normal is its vertex normal; across a crease, each side
//!   keeps its own.
//!
//! **Degenerate input.** Every output is finite. A face without area has a
//! zero normal and adds nothing; a vertex (or fan) whose faces all lack area
//! gets the zero vector, which callers can test for. Such a face does not
//! count as a crease, so its corners take the normal of the fan around them.
//!
//! **Results** come as plain `Vec`s indexed by slot
//! ([`VertexKey::index`], [`HalfedgeKey::index`](crate::HalfedgeKey::index),
//! [`FaceKey::index`]; vacant slots and hole corners hold zeros), the fast
//! form for engines and other passes, or as attribute columns named
//! [`NORMAL`] with the [`Interpolate`] rule ([`add_vertex_normals`],
//! [`add_corner_normals`], [`add_face_normals`]), which follow later edits
//! by interpolation (recompute after large edits). The OBJ writer writes a
//! half-edge column `normal` as `vn` lines.
//!
//! **Cost.** One pass over the faces (vertex and face normals; 2 corner
//! angles per triangle for angle weights, each an arctangent by a short
//! series rather than libm's `atan2`, the third angle is π minus the other
//! two). Corner normals add a pass over the edges to find the vertices at
//! sharp edges, a pass over the corners (elsewhere a corner takes its
//! vertex's normal), and a walk around each vertex at a sharp edge. With the `parallel` feature, face normals of
//! meshes of more than 20,000 faces are computed in blocks on rayon's
//! threads, as is the walk around vertices at sharp edges; vertex normals
//! stay serial: the pass is bound by memory, and summing into one array
//! per thread was slower on two threads (`bench/parallel.sh`;
//! `BENCHMARKS.md`).
//!
//! ```
//! use meshloom::algo::normals::{self, CornerNormalOptions, VertexNormalOptions};
//! let cube = meshloom::shapes::cube();
//! // Smooth: every corner of the cube points along its diagonal.
//! let vn = normals::vertex_normals(&cube, &VertexNormalOptions::default())?;
//! let k = 1.0 / 3f64.sqrt();
//! for v in cube.vertices() {
//!     let p = cube.position(v)?;
//!     let expected = p.map(|c| if c > 0.5 { k } else { -k });
//!     assert!((0..3).all(|i| (vn[v.index()][i] - expected[i]).abs() < 1e-12));
//! }
//! // Split at the 90° edges (sharper than the default 30° crease): every
//! // corner takes its face's normal.
//! let cn = normals::corner_normals(&cube, &CornerNormalOptions::default())?;
//! for f in cube.faces() {
//!     let n = cube.face_normal(f)?;
//!     for h in cube.face(f)?.halfedges() {
//!         assert_eq!(cn[h.index()], n);
//!     }
//! }
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::ops::Range;

use crate::attr::{Attr, EdgeAttr, Element, FaceAttr, HalfedgeAttr, Interpolate, VertexAttr};
use crate::error::{Error, Result};
use crate::keys::{FaceKey, HalfedgeKey, VertexKey};
use crate::layout::Fid;
use crate::mesh::Mesh;
use crate::vec3::{
    add_scaled, angle, cross, dot, newell_edge, norm, normalize_or_zero_recip as unit, sub, V3,
};

/// The name of the columns the `add_*` functions write.
pub const NORMAL: &str = "normal";

/// Meshes with fewer faces than this run serially even with the `parallel`
/// feature: below it, starting threads costs more than it saves.
#[cfg(feature = "parallel")]
const PARALLEL_MIN_FACES: usize = 20_000;

/// How each face around a vertex counts in the vertex's normal.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum NormalWeight {
    /// By the angle of the face's corner at the vertex: independent of how
    /// the surface is cut into faces (the default; pmp-library's choice).
    #[default]
    Angle,
    /// By the face's area: large faces dominate (the classic
    /// area-weighted average).
    Area,
    /// Every face counts once (OpenMesh's `update_vertex_normals`).
    Uniform,
}

crate::choice::choices!(NormalWeight {
    Angle = "angle",
    Area = "area",
    Uniform = "uniform",
});

/// Options of [`vertex_normals`] and [`add_vertex_normals`].
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct VertexNormalOptions {
    /// How faces are weighted (default: by corner angle).
    pub weight: NormalWeight,
}

crate::choice::setters!(VertexNormalOptions {
    weight: NormalWeight,
});

/// Options of [`corner_normals`] and [`add_corner_normals`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct CornerNormalOptions {
    /// How faces are weighted within a fan (default: by corner angle).
    pub weight: NormalWeight,
    /// Edges whose faces meet at more than this angle (radians) are
    /// feature edges (creases): the two faces do not share their corner
    /// normals across them. `None`: none by angle. Default: 30°
    /// (`30f64.to_radians()`). The word of
    /// [`Constraints::feature_angle`](super::Constraints::feature_angle).
    pub feature_angle: Option<f64>,
    /// A boolean edge column: edges whose value is `true` are feature
    /// (hard) edges: the normals split there whatever the angle. Default:
    /// none.
    pub features: Option<EdgeAttr<bool>>,
}

crate::choice::setters!(CornerNormalOptions {
    weight: NormalWeight,
    feature_angle: Option<f64>,
    features: Option<EdgeAttr<bool>>,
});

impl Default for CornerNormalOptions {
    fn default() -> Self {
        CornerNormalOptions {
            weight: NormalWeight::Angle,
            feature_angle: Some(30f64.to_radians()),
            features: None,
        }
    }
}

impl CornerNormalOptions {
    /// No splits but at boundaries: every corner gets the normal of its
    /// vertex's fan (its vertex normal, away from a boundary vertex that
    /// several holes touch).
    pub fn smooth() -> CornerNormalOptions {
        CornerNormalOptions {
            feature_angle: None,
            ..CornerNormalOptions::default()
        }
    }

    /// Every edge is a crease: flat shading, each corner gets its face's
    /// normal.
    pub fn flat() -> CornerNormalOptions {
        CornerNormalOptions {
            feature_angle: Some(0.0),
            ..CornerNormalOptions::default()
        }
    }
}

/// `(−1)^k / (2k + 1)`: `atan u ≈ u Σ ATAN_SERIES[k] u^2k` for small `u`
/// (six terms: the first omitted one, `u¹³ / 13`, bounds the error of this
/// alternating series).
const ATAN_SERIES: [f64; 6] = {
    let mut c = [0.0; 6];
    let mut k = 0;
    while k < 6 {
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        c[k] = sign / (2 * k + 1) as f64;
        k += 1;
    }
    c
};

/// `atan2(y, x)` for `y > 0` (a corner angle from the length of a cross
/// product and a dot product), in `(0, π)`, within 3·10⁻⁹ rad of the libm
/// value and within a relative 1.1·10⁻⁸ of it (`corner_angle_matches_atan2`
/// checks every branch against `atan2`): a weight's relative error `e`
/// turns a vertex normal by at most about `e`, far below the `f32`
/// precision normals end up in (pmp-library and OpenMesh work in `f32`).
/// The ratio is folded into `[0, 1]`, then into `[−tan 15°, tan 15°]` by
/// `atan t = 30° + atan((√3 t − 1) / (√3 + t))` (one division in all: the
/// fold is written on `y` and `x` directly), where six terms of the
/// arctangent series leave an error below `tan¹³ 15° / 13 < 2.9·10⁻⁹`
/// (relative: below `tan¹² 15° / 13 < 1.1·10⁻⁸` for `u` near 0, and the
/// folded angles are at least 15°). This is the hot call of
/// angle-weighted vertex normals (two per triangle); the fourteen terms
/// (2·10⁻¹⁵) used before cost 21% more instructions in `vertex_normals`
/// on a 250,000-vertex grid (189.4M against 156.5M) for no visible gain.
#[inline(always)]
fn corner_angle(y: f64, x: f64) -> f64 {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_6, PI};
    const SQRT_3: f64 = 1.732_050_807_568_877_2;
    const TAN_15: f64 = 0.267_949_192_431_122_7; // 2 − √3
    const TWO_POW_M64: f64 = 1.0 / 18_446_744_073_709_551_616.0;
    const C: [f64; 6] = ATAN_SERIES;
    let ax = x.abs();
    let steep = y > ax;
    // t = num / den in [0, 1].
    let (num, den) = if steep { (ax, y) } else { (y, ax) };
    // Keep √3 · den finite (an exact power-of-two scale, near f64::MAX only).
    let (num, den) = if den > 1e300 {
        (num * TWO_POW_M64, den * TWO_POW_M64)
    } else {
        (num, den)
    };
    // (√3 t − 1) / (√3 + t) with t = num / den, chosen without a branch
    // (both forms are cheap; the choice is unpredictable on real meshes).
    let fold = num > TAN_15 * den;
    let (folded_num, folded_den) = (SQRT_3 * num - den, SQRT_3 * den + num);
    let base = if fold { FRAC_PI_6 } else { 0.0 };
    let u = if fold { folded_num } else { num } / if fold { folded_den } else { den };
    let z = u * u;
    let z2 = z * z;
    let s = (C[0] + C[1] * z) + ((C[2] + C[3] * z) + (C[4] + C[5] * z) * z2) * z2;
    let a = base + u * s;
    let a = if steep { FRAC_PI_2 - a } else { a };
    if x < 0.0 {
        PI - a
    } else {
        a
    }
}

/// Newell's vector of a polygon: along its normal, twice its area long.
#[inline]
fn newell(p: &[V3], corners: &[usize]) -> V3 {
    let mut n = [0.0; 3];
    let k = corners.len();
    for i in 0..k {
        newell_edge(&mut n, p[corners[i]], p[corners[(i + 1) % k]]);
    }
    n
}

fn positions(mesh: &Mesh) -> Result<&[V3]> {
    mesh.position_slots().ok_or(Error::NoPositions)
}

// ----- face normals -------------------------------------------------------------

/// The unit normal of every face, indexed by face slot ([`FaceKey::index`];
/// holes and vacant slots hold zeros; a face without area has a zero
/// normal).
///
/// # Errors
/// [`Error::NoPositions`].
///
/// # Complexity
/// O(corners).
///
/// ```
/// let cube = meshloom::shapes::cube();
/// let n = meshloom::algo::face_normals(&cube)?;
/// let f = cube.faces().next().unwrap(); // the face at z = 0
/// assert_eq!(n[f.index()], [0.0, 0.0, -1.0]);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn face_normals(mesh: &Mesh) -> Result<Vec<V3>> {
    let p = positions(mesh)?;
    let mut out = newell_vectors(mesh, p);
    for n in &mut out {
        *n = unit(*n);
    }
    Ok(out)
}

/// Newell vectors by face slot.
fn newell_vectors(mesh: &Mesh, p: &[V3]) -> Vec<V3> {
    let nf = mesh.slot_counts()[3];
    let mut out = vec![[0.0; 3]; nf];
    let fill = |range: Range<usize>, out: &mut [V3]| {
        let mut corners = Vec::with_capacity(8);
        let start = range.start;
        for i in range {
            if let Some(view) = mesh.face_at(i).and_then(|f| mesh.face(f).ok()) {
                corners.clear();
                corners.extend(view.vertices().map(VertexKey::index));
                out[i - start] = newell(p, &corners);
            }
        }
    };
    #[cfg(feature = "parallel")]
    if nf >= PARALLEL_MIN_FACES {
        use rayon::prelude::*;
        let block = nf.div_ceil(rayon::current_num_threads().max(1));
        out.par_chunks_mut(block)
            .enumerate()
            .for_each(|(b, chunk)| fill(b * block..b * block + chunk.len(), chunk));
        return out;
    }
    fill(0..nf, &mut out);
    out
}

/// Face normals as the face column [`NORMAL`] (`[f64; 3]`), added or
/// overwritten; holes get no value.
///
/// # Errors
/// [`Error::NoPositions`]; [`Error::AttributeType`] if a face column of that
/// name holds another type.
///
/// ```
/// let mut cube = meshloom::shapes::cube();
/// let col = meshloom::algo::add_face_normals(&mut cube)?;
/// let f = cube.faces().next().unwrap();
/// assert_eq!(cube.attr(&col, f)?, Some(&[0.0, 0.0, -1.0]));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn add_face_normals(mesh: &mut Mesh) -> Result<FaceAttr<V3>> {
    mesh.as_one_step("Add face normals", add_face_normals_run)
}

/// [`add_face_normals`] itself, outside the journal's step.
fn add_face_normals_run(mesh: &mut Mesh) -> Result<FaceAttr<V3>> {
    let n = face_normals(mesh)?;
    let keys: Vec<FaceKey> = mesh.faces_and_holes().collect();
    let col = normal_column::<FaceKey>(mesh)?;
    let hole: Vec<bool> = keys
        .iter()
        .map(|&f| mesh.face(f).is_ok_and(|v| v.is_hole()))
        .collect();
    let mut view = mesh.attr_view_mut(&col)?;
    for (&f, hole) in keys.iter().zip(hole) {
        view.set(f, (!hole).then(|| n[f.index()]))?;
    }
    Ok(col)
}

// ----- vertex normals -------------------------------------------------------------

/// Face record: unit normal and twice the area (the Newell length).
type FaceRecord = (V3, f64);

/// Add the weighted normals of the faces in slots `range` to their corners'
/// vertices in `acc` (indexed by vertex slot); with `faces` (indexed from
/// `range.start`), also note each face's unit normal and twice its area.
fn accumulate(
    mesh: &Mesh,
    p: &[V3],
    weight: NormalWeight,
    range: Range<usize>,
    acc: &mut [V3],
    mut faces: Option<&mut [FaceRecord]>,
) {
    let mut c: Vec<usize> = Vec::with_capacity(8);
    let start = range.start;
    // One length for both (a slot per vertex, equal already): one bounds
    // check per corner instead of two.
    let n = acc.len().min(p.len());
    let (p, acc) = (&p[..n], &mut acc[..n]);
    // Typed slots straight from the arenas (the hot loop of the
    // `vertex_normals` benchmark row): a face's half-edge from its link, the
    // corners from `Mesh::he`, no key checks.
    for i in range {
        let f = Fid::new(i as u32);
        let link = mesh.face_link(f);
        if link.is_hole() || !mesh.face_live(i) {
            continue;
        }
        let h0 = link.halfedge();
        let h1 = mesh.next(h0);
        let h2 = mesh.next(h1);
        let tri = mesh.next(h2) == h0;
        if tri {
            let [a, b, d] = [h0, h1, h2].map(|h| mesh.origin(h).index());
            // A triangle: every corner's |cross| is twice the area.
            let (e0, e1, e2) = (sub(p[b], p[a]), sub(p[d], p[b]), sub(p[a], p[d]));
            let n = cross(e0, e1);
            let twice_area = norm(n);
            if !(twice_area > 0.0 && twice_area.is_finite()) {
                continue;
            }
            let inv = 1.0 / twice_area;
            let u = [n[0] * inv, n[1] * inv, n[2] * inv];
            if let Some(f) = faces.as_deref_mut() {
                f[i - start] = (u, twice_area);
            }
            match weight {
                NormalWeight::Angle => {
                    // The angles sum to π: two atan2 give the third.
                    let wa = corner_angle(twice_area, -dot(e0, e2));
                    let wb = corner_angle(twice_area, -dot(e1, e0));
                    let wd = (std::f64::consts::PI - wa - wb).max(0.0);
                    add_scaled(&mut acc[a], u, wa);
                    add_scaled(&mut acc[b], u, wb);
                    add_scaled(&mut acc[d], u, wd);
                }
                NormalWeight::Area => {
                    for v in [a, b, d] {
                        add_scaled(&mut acc[v], n, 0.5);
                    }
                }
                NormalWeight::Uniform => {
                    for v in [a, b, d] {
                        add_scaled(&mut acc[v], u, 1.0);
                    }
                }
            }
            continue;
        }
        c.clear();
        c.extend(mesh.face_halfedges_from(h0).map(|h| mesh.origin(h).index()));
        let n = newell(p, &c);
        let u = unit(n);
        if u == [0.0; 3] {
            continue;
        }
        if let Some(f) = faces.as_deref_mut() {
            f[i - start] = (u, norm(n));
        }
        let k = c.len();
        for j in 0..k {
            let v = c[j];
            let w = match weight {
                NormalWeight::Angle => {
                    let q = p[v];
                    angle(sub(p[c[(j + 1) % k]], q), sub(p[c[(j + k - 1) % k]], q))
                }
                NormalWeight::Area => 0.5 * norm(n),
                NormalWeight::Uniform => 1.0,
            };
            add_scaled(&mut acc[v], u, w);
        }
    }
}

/// The unit normal of every vertex, indexed by vertex slot
/// ([`VertexKey::index`]; vacant slots hold zeros; a vertex whose faces
/// all lack area gets zero).
///
/// # Errors
/// [`Error::NoPositions`].
///
/// # Complexity
/// O(corners): one pass over the faces.
///
/// ```
/// use meshloom::algo::{vertex_normals, NormalWeight, VertexNormalOptions};
/// let mesh = meshloom::shapes::grid(4, 3, meshloom::shapes::GridFaces::Triangles);
/// let n = vertex_normals(&mesh, &VertexNormalOptions::default().weight(NormalWeight::Area))?;
/// assert!(mesh.vertices().all(|v| n[v.index()] == [0.0, 0.0, 1.0]));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn vertex_normals(mesh: &Mesh, options: &VertexNormalOptions) -> Result<Vec<V3>> {
    Ok(vertex_and_face_normals(mesh, options.weight, false)?.0)
}

/// Vertex normals, and (with `want_faces`) every face's record by slot.
fn vertex_and_face_normals(
    mesh: &Mesh,
    weight: NormalWeight,
    want_faces: bool,
) -> Result<(Vec<V3>, Vec<FaceRecord>)> {
    let p = positions(mesh)?;
    let [nv, _, _, nf] = mesh.slot_counts();
    let mut faces = if want_faces {
        vec![([0.0; 3], 0.0); nf]
    } else {
        Vec::new()
    };
    // Serial even with `parallel`: one accumulator per thread, summed at
    // the end, measured 0.72x (slower) on 2 threads for the 2M-vertex grid
    // (`bench/parallel.sh`, 2026-11-25): the pass is bound by memory.
    let mut out = vec![[0.0; 3]; nv];
    let records = want_faces.then_some(&mut faces[..]);
    accumulate(mesh, p, weight, 0..nf, &mut out, records);
    for n in &mut out {
        *n = unit(*n);
    }
    Ok((out, faces))
}

/// Vertex normals ([`vertex_normals`]) as the vertex column [`NORMAL`]
/// (`[f64; 3]`), added or overwritten.
///
/// # Errors
/// [`Error::NoPositions`]; [`Error::AttributeType`] if a vertex column of
/// that name holds another type.
///
/// ```
/// use meshloom::algo::{add_vertex_normals, VertexNormalOptions};
/// let mut mesh = meshloom::shapes::grid(3, 3, meshloom::shapes::GridFaces::Quads);
/// let normal = add_vertex_normals(&mut mesh, &VertexNormalOptions::default())?;
/// let v = mesh.vertices().next().unwrap();
/// assert_eq!(mesh.attr(&normal, v)?, Some(&[0.0, 0.0, 1.0]));
/// // The column follows edits by interpolation.
/// let e = mesh.edges().next().unwrap();
/// let mid = mesh.split_edge(e, 0.5)?;
/// assert_eq!(mesh.attr(&normal, mid)?, Some(&[0.0, 0.0, 1.0]));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn add_vertex_normals(
    mesh: &mut Mesh,
    options: &VertexNormalOptions,
) -> Result<VertexAttr<V3>> {
    mesh.as_one_step("Add vertex normals", |mesh| {
        add_vertex_normals_run(mesh, options)
    })
}

/// [`add_vertex_normals`] itself, outside the journal's step.
fn add_vertex_normals_run(
    mesh: &mut Mesh,
    options: &VertexNormalOptions,
) -> Result<VertexAttr<V3>> {
    let n = vertex_normals(mesh, options)?;
    let keys: Vec<VertexKey> = mesh.vertices().collect();
    let col = normal_column::<VertexKey>(mesh)?;
    let mut view = mesh.attr_view_mut(&col)?;
    for v in keys {
        view.set(v, Some(n[v.index()]))?;
    }
    Ok(col)
}

// ----- corner normals ---------------------------------------------------------------

/// One outgoing half-edge of the vertex being walked.
#[derive(Clone, Copy)]
struct Spoke {
    h: usize,
    dest: usize,
    face: usize,
    hole: bool,
    hard: bool,
}

/// What the corner pass reads for every vertex.
struct CornerInput<'a> {
    mesh: &'a Mesh,
    p: &'a [V3],
    /// Unit normal and twice the area, by face slot.
    faces: &'a [FaceRecord],
    weight: NormalWeight,
    /// Cosine of the crease angle (`None`: no crease by angle).
    cos_crease: Option<f64>,
    hard: Option<crate::attr::AttrView<'a, crate::EdgeKey, bool>>,
}

impl CornerInput<'_> {
    /// Corner normals of the vertices in `slots`, as (half-edge slot,
    /// normal) pairs written by `put`.
    fn run(&self, slots: &[usize], mut put: impl FnMut(usize, V3)) {
        let mut ring: Vec<Spoke> = Vec::with_capacity(16);
        let mut scratch: Vec<(V3, bool)> = Vec::with_capacity(16);
        for &i in slots {
            let Some(view) = self
                .mesh
                .vertex_at(i)
                .and_then(|v| self.mesh.vertex(v).ok())
            else {
                continue;
            };
            ring.clear();
            for h in view.outgoing() {
                let Ok(hv) = self.mesh.halfedge(h) else {
                    continue;
                };
                let f = hv.face();
                ring.push(Spoke {
                    h: h.index(),
                    dest: hv.dest().key().index(),
                    face: f.key().index(),
                    hole: f.is_hole(),
                    hard: self
                        .hard
                        .as_ref()
                        .is_some_and(|a| a.get(h.edge_key()) == Some(&true)),
                });
            }
            self.vertex(i, &ring, &mut scratch, &mut put);
        }
    }

    /// The corners around vertex slot `v`, whose outgoing half-edges are
    /// `ring` (clockwise: corner `k + 1` lies across the edge of spoke `k`
    /// from corner `k`).
    fn vertex(
        &self,
        v: usize,
        ring: &[Spoke],
        scratch: &mut Vec<(V3, bool)>,
        put: &mut impl FnMut(usize, V3),
    ) {
        let k = ring.len();
        let q = self.p[v];
        // Per corner: its weighted normal, and whether the edge after it
        // (between it and the next corner) is sharp.
        scratch.clear();
        let mut any_sharp = false;
        for (j, s) in ring.iter().enumerate() {
            let next = &ring[(j + 1) % k];
            let sharp = s.hole
                || next.hole
                || s.hard
                || self.cos_crease.is_some_and(|c| {
                    let (na, nb) = (self.faces[s.face].0, self.faces[next.face].0);
                    na != [0.0; 3] && nb != [0.0; 3] && dot(na, nb) < c
                });
            any_sharp |= sharp;
            if s.hole {
                scratch.push(([0.0; 3], sharp));
                continue;
            }
            let (u, twice_area) = self.faces[s.face];
            // Corner j's other side runs to the previous spoke's end.
            let w = match self.weight {
                NormalWeight::Angle => angle(
                    sub(self.p[s.dest], q),
                    sub(self.p[ring[(j + k - 1) % k].dest], q),
                ),
                NormalWeight::Area => 0.5 * twice_area,
                NormalWeight::Uniform => 1.0,
            };
            scratch.push(([u[0] * w, u[1] * w, u[2] * w], sharp));
        }
        if !any_sharp {
            let mut sum = [0.0; 3];
            for (w, _) in scratch.iter() {
                add_scaled(&mut sum, *w, 1.0);
            }
            let n = unit(sum);
            for s in ring {
                put(s.h, n);
            }
            return;
        }
        // Walk once round from just after a sharp edge, one fan at a time.
        let first = scratch.iter().position(|&(_, sharp)| sharp).unwrap_or(0);
        let mut start = first + 1;
        while start <= first + k {
            let mut end = start;
            let mut sum = [0.0; 3];
            loop {
                let (w, sharp) = scratch[end % k];
                add_scaled(&mut sum, w, 1.0);
                if sharp {
                    break;
                }
                end += 1;
            }
            let n = unit(sum);
            for j in start..=end {
                let s = &ring[j % k];
                if !s.hole {
                    put(s.h, n);
                }
            }
            start = end + 1;
        }
    }
}

/// The unit normal of every corner, indexed by half-edge slot
/// ([`HalfedgeKey::index`]; half-edges in holes and vacant slots hold
/// zeros): the normal of the corner at the half-edge's origin in its face,
/// shared by the fan of faces between two sharp edges (see the module
/// docs).
///
/// # Errors
/// [`Error::NoPositions`]; [`Error::AttributeHandle`] if the hard-edge
/// column was removed.
///
/// # Complexity
/// O(corners): passes over the faces, edges and corners, then a walk
/// around each vertex at a sharp edge.
///
/// ```
/// use meshloom::algo::{corner_normals, CornerNormalOptions};
/// let cube = meshloom::shapes::cube();
/// // No crease: every corner takes its vertex normal.
/// let smooth = corner_normals(&cube, &CornerNormalOptions::smooth())?;
/// let h = cube.halfedges().find(|&h| !cube.halfedge(h).unwrap().is_boundary()).unwrap();
/// let k = 1.0 / 3f64.sqrt();
/// assert!(smooth[h.index()].iter().all(|c| (c.abs() - k).abs() < 1e-12));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn corner_normals(mesh: &Mesh, options: &CornerNormalOptions) -> Result<Vec<V3>> {
    let p = positions(mesh)?;
    let hard = match &options.features {
        Some(h) => Some(mesh.attr_view(h)?),
        None => None,
    };
    let weight = options.weight;
    let (vn, faces) = vertex_and_face_normals(mesh, weight, true)?;
    let cos_crease = options.feature_angle.map(f64::cos);
    let [nv, nh, ne, nf] = mesh.slot_counts();
    // The vertices at a sharp edge (a boundary, a hard edge, a crease).
    let mut split = vec![false; nv];
    for i in 0..ne {
        let Some(ev) = mesh.edge_at(i).and_then(|e| mesh.edge(e).ok()) else {
            continue;
        };
        let sharp = match ev.faces() {
            [Some(a), Some(b)] => {
                hard.as_ref()
                    .is_some_and(|h| h.get(ev.key()) == Some(&true))
                    || cos_crease.is_some_and(|c| {
                        let (na, nb) = (faces[a.index()].0, faces[b.index()].0);
                        na != [0.0; 3] && nb != [0.0; 3] && dot(na, nb) < c
                    })
            }
            _ => true,
        };
        if sharp {
            for v in ev.vertices() {
                split[v.index()] = true;
            }
        }
    }
    // Elsewhere a corner's normal is its vertex's.
    let mut out = vec![[0.0; 3]; nh];
    for i in 0..nf {
        if let Some(fv) = mesh.face_at(i).and_then(|f| mesh.face(f).ok()) {
            for (h, v) in fv.halfedges().zip(fv.vertices()) {
                if !split[v.index()] {
                    out[h.index()] = vn[v.index()];
                }
            }
        }
    }
    // At sharp edges, fan by fan around the vertex.
    let walk: Vec<usize> = (0..nv).filter(|&v| split[v]).collect();
    let input = CornerInput {
        mesh,
        p,
        faces: &faces,
        weight,
        cos_crease,
        hard,
    };
    #[cfg(feature = "parallel")]
    if walk.len() >= PARALLEL_MIN_FACES && rayon::current_num_threads() > 1 {
        use rayon::prelude::*;
        let parts: Vec<Vec<(usize, V3)>> = walk
            .par_chunks(4096)
            .map(|chunk| {
                let mut part = Vec::with_capacity(8 * chunk.len());
                input.run(chunk, |h, n| part.push((h, n)));
                part
            })
            .collect();
        for (h, n) in parts.into_iter().flatten() {
            out[h] = n;
        }
        return Ok(out);
    }
    input.run(&walk, |h, n| out[h] = n);
    Ok(out)
}

/// Corner normals ([`corner_normals`]) as the half-edge column [`NORMAL`]
/// (`[f64; 3]`), added or overwritten; half-edges in holes get no value.
/// The OBJ writer writes this column as `vn` lines.
///
/// # Errors
/// As [`corner_normals`]; [`Error::AttributeType`] if a half-edge column of
/// that name holds another type.
///
/// ```
/// use meshloom::algo::{add_corner_normals, CornerNormalOptions};
/// let mut cube = meshloom::shapes::cube();
/// let normal = add_corner_normals(&mut cube, &CornerNormalOptions::default())?;
/// let f = cube.faces().next().unwrap();
/// let h = cube.face(f)?.halfedges().next().unwrap();
/// assert_eq!(cube.attr(&normal, h)?, Some(&[0.0, 0.0, -1.0]));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn add_corner_normals(
    mesh: &mut Mesh,
    options: &CornerNormalOptions,
) -> Result<HalfedgeAttr<V3>> {
    mesh.as_one_step("Add corner normals", |mesh| {
        add_corner_normals_run(mesh, options)
    })
}

/// [`add_corner_normals`] itself, outside the journal's step.
fn add_corner_normals_run(
    mesh: &mut Mesh,
    options: &CornerNormalOptions,
) -> Result<HalfedgeAttr<V3>> {
    let n = corner_normals(mesh, options)?;
    let keys: Vec<(HalfedgeKey, bool)> = mesh
        .halfedges()
        .map(|h| (h, mesh.halfedge(h).is_ok_and(|v| v.is_boundary())))
        .collect();
    let col = normal_column::<HalfedgeKey>(mesh)?;
    let mut view = mesh.attr_view_mut(&col)?;
    for (h, in_hole) in keys {
        view.set(h, (!in_hole).then(|| n[h.index()]))?;
    }
    Ok(col)
}

/// The `[f64; 3]` column [`NORMAL`] of arena `K`, found or added.
fn normal_column<K: Element>(mesh: &mut Mesh) -> Result<Attr<K, V3>> {
    match mesh.attr_handle::<K, V3, Interpolate>(NORMAL) {
        Ok(h) => Ok(h),
        Err(Error::AttributeMissing { .. }) => mesh.add_attr::<K, V3>(NORMAL),
        Err(e) => Err(e),
    }
}

#[cfg(test)]
mod tests;
