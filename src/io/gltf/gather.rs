//! The welded instances gathered into the soup every reader ends in:
//! positions, triangles (with where each was read), attribute columns
//! (vertex, corner or face, by how their values fall), materials; then the
//! soup's own repair and build.

use std::collections::BTreeMap;

use super::super::attrs::{Data, SoupColumn};
use super::super::error::{Error, Location};
use super::super::soup::Soup;
use super::super::{ReadOptions, RepairReport};
use super::read::unsupported;
use super::scene::{Attr, Instance};
use super::weld::Welded;
use super::{FACE_PREFIX, MATERIAL};
use crate::mesh::Mesh;

/// One attribute gathered over the whole file.
struct Gathered {
    /// Whether it may be a vertex column (`COLOR_n`, custom).
    vertex_kind: bool,
    comps: usize,
    /// Where it was first met, for errors.
    first_seen: String,
    corner: Vec<f64>,
    corner_present: Vec<bool>,
    vertex: Vec<f64>,
    vertex_present: Vec<bool>,
    /// Copies of a welded vertex disagree: not a vertex column.
    disagree: bool,
}

/// The soup being filled, instance after instance.
pub(super) struct Gather {
    soup: Soup,
    face_at: Vec<u64>,
    vertex_at: Vec<u64>,
    /// Whether every face and vertex has a byte offset in the file read.
    all_in_file: bool,
    /// Whether every buffer is the GLB's `BIN` chunk.
    in_glb: bool,
    materials: Vec<Option<String>>,
    gathered: BTreeMap<String, Gathered>,
    /// What welding by position did, for the report.
    welds: RepairReport,
}

impl Gather {
    pub(super) fn new(in_glb: bool) -> Gather {
        Gather {
            soup: Soup::new(false),
            face_at: Vec::new(),
            vertex_at: Vec::new(),
            all_in_file: true,
            in_glb,
            materials: Vec::new(),
            gathered: BTreeMap::new(),
            welds: RepairReport::default(),
        }
    }

    /// Face corners gathered so far.
    pub(super) fn corner_count(&self) -> usize {
        self.soup.polygons.indices.len()
    }

    /// Add a welded instance of mesh `mesh`: its vertices, its kept
    /// triangles, its attributes.
    pub(super) fn add(&mut self, inst: &Instance, w: &Welded, mesh: usize) -> Result<(), Error> {
        self.welds.welded_vertices += w.welded;
        self.welds.weld_refused += w.refused;
        self.welds.degenerate_faces += w.degenerate;
        let first_copy = self.add_vertices(inst, w)?;
        self.add_vertex_values(inst, w, &first_copy, mesh)?;
        self.add_triangles(inst, w);
        // Attributes this instance lacks stay absent here.
        let (corners, vertices) = (self.corner_count(), self.soup.polygons.positions.len());
        for (name, g) in self.gathered.iter_mut() {
            if !inst.attrs.contains_key(name) {
                g.corner.resize(corners * g.comps, 0.0);
                g.corner_present.resize(corners, false);
                g.vertex.resize(vertices * g.comps, 0.0);
                g.vertex_present.resize(vertices, false);
            }
        }
        Ok(())
    }

    /// The welded positions and where each was read; the first instance
    /// vertex of each welded vertex.
    fn add_vertices(&mut self, inst: &Instance, w: &Welded) -> Result<Vec<usize>, Error> {
        let mut first_copy = vec![usize::MAX; w.positions.len()];
        for (i, &r) in w.rep.iter().enumerate() {
            match first_copy.get_mut(r as usize) {
                Some(f) if *f == usize::MAX => *f = i,
                Some(_) => {}
                None => return Err(weld_lost()),
            }
        }
        if first_copy.contains(&usize::MAX) {
            return Err(weld_lost());
        }
        self.soup.polygons.positions.extend_from_slice(&w.positions);
        for &i in &first_copy {
            match inst.position_at[i] {
                Some(b) => self.vertex_at.push(b),
                None => {
                    self.all_in_file = false;
                    self.vertex_at.push(0);
                }
            }
        }
        Ok(first_copy)
    }

    /// Each attribute's values at the welded vertices (the first copy's),
    /// and whether the copies agree.
    fn add_vertex_values(
        &mut self,
        inst: &Instance,
        w: &Welded,
        first_copy: &[usize],
        mesh: usize,
    ) -> Result<(), Error> {
        let corners_before = self.corner_count();
        let vertices_before = self.soup.polygons.positions.len() - w.positions.len();
        for (name, a) in &inst.attrs {
            let comps = a.comps;
            let g = self
                .gathered
                .entry(name.clone())
                .or_insert_with(|| Gathered {
                    vertex_kind: a.vertex_kind,
                    comps,
                    first_seen: format!("mesh {mesh}"),
                    corner: vec![0.0; corners_before * comps],
                    corner_present: vec![false; corners_before],
                    vertex: vec![0.0; vertices_before * comps],
                    vertex_present: vec![false; vertices_before],
                    disagree: false,
                });
            if g.comps != comps {
                return Err(unsupported(format!(
                    "attribute {name:?} has {comps} values per vertex in mesh {mesh} and {} in {}; read one mesh with GltfOptions::mesh",
                    g.comps, g.first_seen
                )));
            }
            for &i in first_copy {
                g.vertex.extend_from_slice(a.get(i));
                g.vertex_present.push(a.present[i]);
            }
            for (i, &r) in w.rep.iter().enumerate() {
                let j = first_copy[r as usize];
                if a.present[i] != a.present[j] || a.get(i) != a.get(j) {
                    g.disagree = true;
                }
            }
        }
        Ok(())
    }

    /// The kept triangles, turned over when the transform mirrors, with
    /// their corner values and materials.
    fn add_triangles(&mut self, inst: &Instance, w: &Welded) {
        let base = (self.soup.polygons.positions.len() - w.positions.len()) as u32;
        let kept = inst.triangles.iter().zip(&w.keep).filter(|&(_, &k)| k);
        for ((c, at, material), _) in kept {
            let mut c = *c;
            if inst.mirrored {
                c.swap(1, 2);
            }
            let v = c.map(|x| w.rep[x as usize]);
            if v[0] == v[1] || v[1] == v[2] || v[2] == v[0] {
                continue;
            }
            let polygons = &mut self.soup.polygons;
            polygons.indices.extend(v.map(|x| x + base));
            polygons.offsets.push(polygons.indices.len() as u32);
            match at {
                Some(b) if self.in_glb => self.face_at.push(*b),
                _ => {
                    self.all_in_file = false;
                    self.face_at.push(0);
                }
            }
            self.materials.push(material.clone());
            for (name, a) in &inst.attrs {
                if let Some(g) = self.gathered.get_mut(name) {
                    push_corners(g, a, &c);
                }
            }
        }
    }

    /// The soup's columns, then its repair and build by `options`; the
    /// report adds what welding by position did.
    pub(super) fn finish(mut self, options: &ReadOptions) -> Result<(Mesh, RepairReport), Error> {
        if self.all_in_file {
            self.soup.record = true;
            self.soup.binary = true;
            self.soup.face_at = std::mem::take(&mut self.face_at);
            self.soup.vertex_at = std::mem::take(&mut self.vertex_at);
        }
        for (name, g) in std::mem::take(&mut self.gathered) {
            self.push_column(name, g);
        }
        self.push_materials();
        let (mesh, mut report) = self.soup.finish(options)?;
        report.welded_vertices += self.welds.welded_vertices;
        report.weld_refused += self.welds.weld_refused;
        report.degenerate_faces += self.welds.degenerate_faces;
        Ok((mesh, report))
    }

    /// A gathered attribute as a face, vertex or corner column.
    fn push_column(&mut self, name: String, g: Gathered) {
        if let Some(column) = face_column(&name, &g) {
            self.soup.attrs.face.push(column);
            return;
        }
        let vertex = g.vertex_kind && !g.disagree;
        let (values, present) = if vertex {
            (g.vertex, g.vertex_present)
        } else {
            (g.corner, g.corner_present)
        };
        let column = SoupColumn {
            name,
            data: data_of(values, g.comps),
            present: (!present.iter().all(|&p| p)).then_some(present),
        };
        if vertex {
            self.soup.attrs.vertex.push(column);
        } else {
            self.soup.attrs.corner.push(column);
        }
    }

    /// The materials' names as the text face column `material` (unless a
    /// face column of that name was read).
    fn push_materials(&mut self) {
        let materials = std::mem::take(&mut self.materials);
        let taken = self.soup.attrs.face.iter().any(|c| c.name == MATERIAL);
        if taken || !materials.iter().any(Option::is_some) {
            return;
        }
        let present: Vec<bool> = materials.iter().map(Option::is_some).collect();
        let names: Vec<String> = materials
            .into_iter()
            .map(Option::unwrap_or_default)
            .collect();
        self.soup.attrs.face.push(SoupColumn {
            name: MATERIAL.into(),
            data: Data::Text(names),
            present: (!present.iter().all(|&p| p)).then_some(present),
        });
    }
}

/// A weld that left a welded vertex without a copy, or named a vertex
/// past them (a bug, reported rather than panicking).
fn weld_lost() -> Error {
    Error::Header {
        at: Location::whole(),
        message: "internal: welding the glTF vertices lost track of one".into(),
    }
}

/// The values of `a` at the corners `c` (instance vertices).
fn push_corners(g: &mut Gathered, a: &Attr, c: &[u32; 3]) {
    for &x in c {
        let x = x as usize;
        g.corner.extend_from_slice(a.get(x));
        g.corner_present.push(a.present[x]);
    }
}

/// Values of `comps` numbers apiece as soup data.
fn data_of(values: Vec<f64>, comps: usize) -> Data {
    match comps {
        1 => Data::Scalar(values),
        2 => Data::Vec2(values.chunks_exact(2).map(|c| [c[0], c[1]]).collect()),
        3 => Data::Vec3(values.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()),
        _ => Data::Vec4(
            values
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2], c[3]])
                .collect(),
        ),
    }
}

/// A custom attribute `_FACE_NAME` (as meshloom writes a face column) as
/// the face column `NAME`, when its values are the same at the three
/// corners of every triangle; `None` otherwise (it is then read as any
/// other custom attribute, under the name `FACE_NAME`).
fn face_column(name: &str, g: &Gathered) -> Option<SoupColumn> {
    let face = name.strip_prefix(FACE_PREFIX).filter(|f| !f.is_empty())?;
    if !g.vertex_kind {
        return None;
    }
    let k = g.comps;
    let corner = |c: usize| (g.corner_present[c], &g.corner[c * k..(c + 1) * k]);
    let same = |a: (bool, &[f64]), b: (bool, &[f64])| {
        a.0 == b.0 && a.1.iter().zip(b.1).all(|(x, y)| x.to_bits() == y.to_bits())
    };
    let triangles = g.corner_present.len() / 3;
    let constant = (0..triangles)
        .all(|t| same(corner(3 * t), corner(3 * t + 1)) && same(corner(3 * t), corner(3 * t + 2)));
    if !constant {
        return None;
    }
    let mut values = Vec::with_capacity(triangles * k);
    let mut present = Vec::with_capacity(triangles);
    for t in 0..triangles {
        let (has, v) = corner(3 * t);
        values.extend_from_slice(v);
        present.push(has);
    }
    Some(SoupColumn {
        name: face.to_owned(),
        data: data_of(values, k),
        present: (!present.iter().all(|&p| p)).then_some(present),
    })
}
