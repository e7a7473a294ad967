//! The scene walk (mesh instances with their world matrices) and the
//! reading of one instance: each primitive's triangles, the vertices they
//! use (placed by the matrix), their attributes and `_VERTEX_ID`s.

use std::collections::BTreeMap;

use gltf::mesh::{Mode, Semantic};

use super::super::error::{Error, Location};
use super::read::{header, read_accessor, unsupported, Buffer, Values};
use super::{GltfOptions, VERTEX_ID};
use crate::vec3::normalize;

type M4 = [[f64; 4]; 4];
const IDENTITY: M4 = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// A mesh instance's world transform: positions by `m`, normals by the
/// cofactor matrix `normals` (flipped when `det` is negative).
pub(super) struct Xf {
    m: M4,
    normals: [[f64; 3]; 3],
    /// The determinant of the upper 3×3: negative mirrors, so triangles
    /// are turned over.
    pub(super) det: f64,
}

impl Xf {
    fn new(m: M4) -> Xf {
        let (normals, det) = normal_matrix(&m);
        Xf { m, normals, det }
    }

    fn point(&self, p: [f64; 3]) -> [f64; 3] {
        let m = &self.m;
        std::array::from_fn(|r| m[0][r] * p[0] + m[1][r] * p[1] + m[2][r] * p[2] + m[3][r])
    }

    /// A normal, transformed and made unit length again (zero stays zero).
    fn normal(&self, v: [f64; 3]) -> [f64; 3] {
        let (n, s) = (&self.normals, self.det.signum());
        let t: [f64; 3] =
            std::array::from_fn(|r| s * (n[r][0] * v[0] + n[r][1] * v[1] + n[r][2] * v[2]));
        normalize(t).unwrap_or(t)
    }
}

/// A node's matrix, column-major, in f64.
fn matrix(node: &gltf::Node) -> M4 {
    node.transform().matrix().map(|c| c.map(f64::from))
}

fn mul(a: &M4, b: &M4) -> M4 {
    let mut m = [[0.0; 4]; 4];
    for (c, col) in m.iter_mut().enumerate() {
        for (r, x) in col.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[k][r] * b[c][k]).sum();
        }
    }
    m
}

/// The cofactor matrix of the upper 3×3 (rows), and its determinant:
/// normals go by it (the inverse transpose up to a positive scale when
/// the determinant is positive).
fn normal_matrix(m: &M4) -> ([[f64; 3]; 3], f64) {
    let a = |r: usize, c: usize| m[c][r];
    let cof = |r: usize, c: usize| {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
        a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1)
    };
    let n: [[f64; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|c| cof(r, c)));
    let det = a(0, 0) * n[0][0] + a(0, 1) * n[0][1] + a(0, 2) * n[0][2];
    (n, det)
}

/// The mesh instances to read, in scene order, with their transforms: the
/// default scene (else the first; else every mesh once), or only the
/// instances of the picked mesh.
pub(super) fn instances<'a>(
    doc: &'a gltf::Document,
    pick: &GltfOptions,
) -> Result<Vec<(Xf, gltf::Mesh<'a>)>, Error> {
    let mut out: Vec<(Xf, gltf::Mesh)> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => walk(doc, scene)?,
        None => doc.meshes().map(|m| (Xf::new(IDENTITY), m)).collect(),
    };
    if let Some(i) = pick.mesh {
        let Some(mesh) = doc.meshes().nth(i) else {
            return Err(unsupported(format!(
                "there is no mesh {i} to pick (the file has {})",
                doc.meshes().len()
            )));
        };
        out.retain(|(_, m)| m.index() == i);
        if out.is_empty() {
            out.push((Xf::new(IDENTITY), mesh));
        }
    }
    Ok(out)
}

/// The mesh instances of a scene, depth first from its root nodes, each
/// node's matrix applied; a hierarchy that is not a tree is an error.
fn walk<'a>(
    doc: &'a gltf::Document,
    scene: gltf::Scene<'a>,
) -> Result<Vec<(Xf, gltf::Mesh<'a>)>, Error> {
    let mut out = Vec::new();
    let mut stack: Vec<(gltf::Node, M4)> = scene.nodes().map(|n| (n, IDENTITY)).collect();
    stack.reverse();
    let limit = doc.nodes().len().saturating_mul(4) + 16;
    let mut visits = 0usize;
    while let Some((node, parent)) = stack.pop() {
        visits += 1;
        if visits > limit {
            return Err(header(
                Location::whole(),
                format!(
                    "node {} is reached again and again: the node hierarchy is not a tree",
                    node.index()
                ),
            ));
        }
        let m = mul(&parent, &matrix(&node));
        if let Some(mesh) = node.mesh() {
            out.push((Xf::new(m), mesh));
        }
        let children: Vec<_> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|c| (c, m)));
    }
    Ok(out)
}

/// One attribute over an instance's vertices.
pub(super) struct Attr {
    /// Whether it may be a vertex column (`COLOR_n`, custom).
    pub(super) vertex_kind: bool,
    pub(super) comps: usize,
    /// `comps` values per vertex (zeros where absent).
    pub(super) values: Vec<f64>,
    pub(super) present: Vec<bool>,
}

impl Attr {
    pub(super) fn get(&self, v: usize) -> &[f64] {
        self.values
            .get(v * self.comps..(v + 1) * self.comps)
            .unwrap_or(&[])
    }
}

/// A triangle of an instance: its corners (instance vertices), where its
/// first corner's index was read, its material's name.
pub(super) type Triangle = ([u32; 3], Option<u64>, Option<String>);

/// One mesh instance as read, before welding: the file elements its
/// triangles use (each primitive's own, in first-use order), placed in the
/// world.
pub(super) struct Instance {
    pub(super) positions: Vec<[f64; 3]>,
    /// Byte offset of each vertex's position in the GLB (`None`: not in
    /// the file read).
    pub(super) position_at: Vec<Option<u64>>,
    pub(super) triangles: Vec<Triangle>,
    pub(super) attrs: BTreeMap<String, Attr>,
    /// Each vertex's `_VERTEX_ID`, while every primitive has one.
    pub(super) ids: Option<Vec<u32>>,
    /// Whether the transform mirrors (triangles are turned over).
    pub(super) mirrored: bool,
    /// Elements read and corners made, against the reader's budget.
    pub(super) work: usize,
}

/// Read one mesh instance: every primitive's triangles and the vertices
/// they use; `budget` bounds the elements read and corners made.
pub(super) fn read_instance(
    mesh: &gltf::Mesh,
    xf: &Xf,
    bufs: &[Buffer],
    budget: usize,
) -> Result<Instance, Error> {
    let mut inst = Instance {
        positions: Vec::new(),
        position_at: Vec::new(),
        triangles: Vec::new(),
        attrs: BTreeMap::new(),
        ids: Some(Vec::new()),
        mirrored: xf.det < 0.0,
        work: 0,
    };
    for prim in mesh.primitives() {
        let what = format!("mesh {} primitive {}", mesh.index(), prim.index());
        read_primitive(&prim, &what, bufs, xf, &mut inst, budget)?;
    }
    Ok(inst)
}

/// Stages of one primitive: its positions, its triangles, the vertices
/// they use (renumbered into the instance), their IDs and attributes.
fn read_primitive(
    prim: &gltf::Primitive,
    what: &str,
    bufs: &[Buffer],
    xf: &Xf,
    inst: &mut Instance,
    budget: usize,
) -> Result<(), Error> {
    let mode = prim.mode();
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        return Err(unsupported(format!(
            "{what} has mode {mode:?}: only triangles, strips and fans hold faces"
        )));
    }
    let pos_acc = prim
        .get(&Semantic::Positions)
        .ok_or_else(|| header(Location::whole(), format!("{what} has no POSITION")))?;
    let pos = read_accessor(&pos_acc, bufs, &format!("{what} POSITION"))?;
    if pos.comps != 3 {
        return Err(header(
            Location::whole(),
            format!("{what}: POSITION is not VEC3"),
        ));
    }
    let n = pos.count();
    let (idx, idx_at) = corner_indices(prim, bufs, what, n)?;
    let mut tris = triangles(mode, &idx, idx_at.as_ref());
    let attributes = prim.attributes().count();
    let work = n
        .saturating_mul(attributes.max(1))
        .saturating_add(idx.len())
        .saturating_add(tris.len().saturating_mul(3));
    inst.work = inst.work.saturating_add(work);
    if inst.work > budget {
        return Err(Error::TooLarge {
            at: Location::whole(),
            what: format!(
                "{what}: more vertex values and triangles than the byte limit allows (each instance of a mesh counts)"
            ),
        });
    }
    let used = renumber(&mut tris, n, inst.positions.len());
    push_positions(&pos, &used, xf, inst)?;
    push_ids(prim, bufs, what, n, &used, inst)?;
    let material = prim.material().name().map(str::to_owned);
    inst.triangles
        .extend(tris.into_iter().map(|(c, at)| (c, at, material.clone())));
    push_attributes(prim, bufs, what, n, &used, xf, inst)
}

/// The primitive's corners as element numbers (below `n`, checked), and
/// the index accessor's values for locations (`None`: no indices, the
/// elements in order).
fn corner_indices(
    prim: &gltf::Primitive,
    bufs: &[Buffer],
    what: &str,
    n: usize,
) -> Result<(Vec<u32>, Option<Values>), Error> {
    let Some(acc) = prim.indices() else {
        let n = u32::try_from(n).map_err(|_| Error::TooLarge {
            at: Location::whole(),
            what: format!("{what}: more than 2^32 vertices"),
        })?;
        return Ok(((0..n).collect(), None));
    };
    let v = read_accessor(&acc, bufs, &format!("{what} indices"))?;
    if v.comps != 1 || !v.integer {
        return Err(header(
            v.location(0),
            format!(
                "{what}: the indices (accessor {}) are not unsigned integer scalars",
                acc.index()
            ),
        ));
    }
    let list: Vec<u32> = v.data.iter().map(|&x| x as u32).collect();
    if let Some(k) = list.iter().position(|&x| x as usize >= n) {
        return Err(Error::IndexOutOfRange {
            at: v.location(k),
            what: "vertex",
            index: i64::from(list[k]),
            count: n,
        });
    }
    Ok((list, Some(v)))
}

/// Triangles of a list, strip or fan, each with the byte offset of its
/// first corner's index.
fn triangles(mode: Mode, idx: &[u32], at: Option<&Values>) -> Vec<([u32; 3], Option<u64>)> {
    let corner_at = |k: usize| at.and_then(|v| v.offset(k));
    let mut out = Vec::new();
    match mode {
        Mode::Triangles => {
            for (t, c) in idx.chunks_exact(3).enumerate() {
                out.push(([c[0], c[1], c[2]], corner_at(3 * t)));
            }
        }
        Mode::TriangleStrip => {
            for (i, w) in idx.windows(3).enumerate() {
                let c = if i % 2 == 0 {
                    [w[0], w[1], w[2]]
                } else {
                    [w[1], w[0], w[2]]
                };
                out.push((c, corner_at(i)));
            }
        }
        _ => {
            if let Some((&first, rest)) = idx.split_first() {
                for (i, w) in rest.windows(2).enumerate() {
                    out.push(([first, w[0], w[1]], corner_at(i + 1)));
                }
            }
        }
    }
    out
}

/// Renumber the triangles' corners (elements below `n`) into instance
/// vertices from `first` on, in first-use order; the elements used, in
/// that order.
fn renumber(tris: &mut [([u32; 3], Option<u64>)], n: usize, first: usize) -> Vec<usize> {
    let mut remap = vec![u32::MAX; n];
    let mut used: Vec<usize> = Vec::new();
    for (c, _) in tris.iter_mut() {
        for x in c.iter_mut() {
            let r = &mut remap[*x as usize];
            if *r == u32::MAX {
                *r = (first + used.len()) as u32;
                used.push(*x as usize);
            }
            *x = *r;
        }
    }
    used
}

/// The used elements' positions, placed in the world; non-finite ones
/// (in the file or after the transform) are an error.
fn push_positions(pos: &Values, used: &[usize], xf: &Xf, inst: &mut Instance) -> Result<(), Error> {
    for &e in used {
        let q = pos.get(e);
        let p = [q[0], q[1], q[2]];
        let world = xf.point(p);
        if !p.iter().chain(&world).all(|c| c.is_finite()) {
            return Err(Error::NonFinite {
                at: pos.location(e),
                vertex: e,
                position: if p.iter().all(|c| c.is_finite()) {
                    world
                } else {
                    p
                },
            });
        }
        inst.positions.push(world);
        inst.position_at
            .push(pos.offset(e).filter(|_| pos.path.is_none()));
    }
    Ok(())
}

/// The used elements' `_VERTEX_ID`s (see the module documentation of
/// [`super`]); a primitive without them turns them off for the instance.
fn push_ids(
    prim: &gltf::Primitive,
    bufs: &[Buffer],
    what: &str,
    n: usize,
    used: &[usize],
    inst: &mut Instance,
) -> Result<(), Error> {
    let Some(ids) = inst.ids.as_mut() else {
        return Ok(());
    };
    let Some(acc) = prim.get(&Semantic::Extras(VERTEX_ID.into())) else {
        inst.ids = None;
        return Ok(());
    };
    let vals = read_accessor(&acc, bufs, &format!("{what} _{VERTEX_ID}"))?;
    if vals.comps != 1 || vals.count() != n {
        return Err(header(
            Location::whole(),
            format!(
                "{what}: _{VERTEX_ID} is not one scalar per vertex ({} elements of {} values, POSITION {n})",
                vals.count(),
                vals.comps
            ),
        ));
    }
    for &e in used {
        let x = vals.get(e)[0];
        if !((0.0..4_294_967_296.0).contains(&x) && x.fract() == 0.0) {
            return Err(header(
                vals.location(e),
                format!("{what}: _{VERTEX_ID} of element {e} is {x}, not a vertex number"),
            ));
        }
        ids.push(x as u32);
    }
    Ok(())
}

/// The column name of an attribute, and whether it may be a vertex column
/// (`_VERTEX_ID` is not a column).
fn column_of(semantic: &Semantic) -> Option<(String, bool)> {
    let numbered = |base: &str, n: u32| {
        if n == 0 {
            base.to_owned()
        } else {
            format!("{base}{n}")
        }
    };
    match semantic {
        Semantic::Normals => Some(("normal".into(), false)),
        Semantic::TexCoords(n) => Some((numbered("texcoord", *n), false)),
        Semantic::Colors(n) => Some((numbered("color", *n), true)),
        Semantic::Extras(name) if name == VERTEX_ID => None,
        Semantic::Extras(name) => Some((name.clone(), true)),
        _ => None,
    }
}

/// The attributes of the used elements; an attribute earlier primitives
/// lacked is absent there, one this primitive lacks is absent here.
fn push_attributes(
    prim: &gltf::Primitive,
    bufs: &[Buffer],
    what: &str,
    n: usize,
    used: &[usize],
    xf: &Xf,
    inst: &mut Instance,
) -> Result<(), Error> {
    let before = inst.positions.len() - used.len();
    let mut seen: Vec<String> = Vec::new();
    for (semantic, acc) in prim.attributes() {
        let Some((name, vertex_kind)) = column_of(&semantic) else {
            continue;
        };
        let label = format!("{what} {}", semantic.to_string());
        let vals = read_accessor(&acc, bufs, &label)?;
        let normal = semantic == Semantic::Normals;
        if vals.count() != n || (normal && vals.comps != 3) {
            return Err(header(
                Location::whole(),
                format!(
                    "{label} has {} elements of {} values; POSITION has {n} (NORMAL: of 3)",
                    vals.count(),
                    vals.comps
                ),
            ));
        }
        let entry = inst.attrs.entry(name.clone()).or_insert_with(|| Attr {
            vertex_kind,
            comps: vals.comps,
            values: vec![0.0; before * vals.comps],
            present: vec![false; before],
        });
        if entry.comps != vals.comps || seen.contains(&name) {
            return Err(unsupported(format!(
                "{label} has {} values per vertex where another attribute of the column {name:?} has {}; read one mesh with GltfOptions::mesh",
                vals.comps, entry.comps
            )));
        }
        for &e in used {
            let v = vals.get(e);
            if normal {
                entry.values.extend(xf.normal([v[0], v[1], v[2]]));
            } else {
                entry.values.extend_from_slice(v);
            }
            entry.present.push(true);
        }
        seen.push(name);
    }
    for (name, entry) in inst.attrs.iter_mut() {
        if !seen.contains(name) {
            entry
                .values
                .extend(std::iter::repeat_n(0.0, used.len() * entry.comps));
            entry.present.extend(std::iter::repeat_n(false, used.len()));
        }
    }
    Ok(())
}
