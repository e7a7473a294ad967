//! What every reader produces before a mesh exists: polygons, where each
//! face was read, and the attribute values read beside them. `finish`
//! repairs (by the caller's policies) and builds.

use crate::build::{Built, Polygons};
use crate::error::{BuildError, Error as MeshError};
use crate::mesh::Mesh;
use crate::repair::{repair_with, Provenance, RepairReport};

use super::attrs::SoupAttrs;
use super::error::{Error, Location};
use super::ReadOptions;

/// Polygons as read, with the line or byte offset of each face.
#[derive(Default)]
pub(crate) struct Soup {
    pub(crate) polygons: Polygons,
    /// Line (text) or byte offset (binary) each face was read at, kept
    /// only when `record` is set (readers parse a second time to place an
    /// error, so the common path stores nothing per face).
    pub(crate) face_at: Vec<u64>,
    /// Line or byte offset each vertex was read at (only when `record`).
    pub(crate) vertex_at: Vec<u64>,
    /// Whether to fill `face_at` and `vertex_at`.
    pub(crate) record: bool,
    /// Whether `face_at` holds byte offsets.
    pub(crate) binary: bool,
    /// Attribute values read with the elements, in file order.
    pub(crate) attrs: SoupAttrs,
    /// What the file holds that its format does not allow but other readers
    /// skip (a PLY header line that is not a keyword): where, and what. A
    /// strict read refuses the first; a repairing read reports each as a
    /// warning.
    pub(crate) nonstandard: Vec<(Location, String)>,
}

impl Soup {
    pub(crate) fn new(record: bool) -> Soup {
        let mut s = Soup {
            record,
            ..Soup::default()
        };
        s.polygons.offsets.push(0);
        s
    }

    /// Number of faces read so far.
    pub(crate) fn face_count(&self) -> usize {
        self.polygons.offsets.len() - 1
    }

    /// End the face whose corners were pushed since the last one.
    #[inline]
    pub(crate) fn end_face(&mut self, at: u64) {
        self.polygons
            .offsets
            .push(self.polygons.indices.len() as u32);
        if self.record {
            self.face_at.push(at);
        }
    }

    /// Note where the vertex just pushed was read (when recording).
    #[inline]
    pub(crate) fn vertex_read_at(&mut self, at: u64) {
        if self.record {
            self.vertex_at.push(at);
        }
    }

    /// Where vertex `vertex` was read, if recorded.
    pub(crate) fn location_of_vertex(&self, vertex: usize) -> Location {
        match self.vertex_at.get(vertex) {
            Some(&at) if self.binary => Location::byte(at),
            Some(&at) => Location::line(at),
            None => Location::whole(),
        }
    }

    pub(crate) fn location_of_face(&self, face: usize) -> Location {
        match self.face_at.get(face) {
            Some(&at) if self.binary => Location::byte(at),
            Some(&at) => Location::line(at),
            None => Location::whole(),
        }
    }

    /// Repair by `options`, build, attach the attributes.
    pub(crate) fn finish(mut self, options: &ReadOptions) -> Result<(Mesh, RepairReport), Error> {
        self.check_readable(options)?;
        let faces_read = self.polygons.face_count();
        let (mut report, prov) = self.repair(options)?;
        report.warnings = std::mem::take(&mut self.nonstandard)
            .into_iter()
            .map(|(at, what)| format!("{at}: {what}; skipped as a comment"))
            .collect();
        if self.polygons.face_count() == 0 {
            return Err(Error::NothingLeft {
                at: Location::whole(),
                faces: faces_read,
                why: report.to_string().replace('\n', "; "),
            });
        }
        // Keys of the input's elements are needed only to attach attributes.
        let with_keys = !self.attrs.is_empty();
        let built = self.build(with_keys, &prov)?;
        let mut mesh = built.mesh;
        if mesh.face_count() == 0 {
            return Err(Error::Empty {
                at: Location::whole(),
            });
        }
        if with_keys {
            self.attrs.attach(
                &mut mesh,
                &built.vertices,
                &built.faces,
                &self.polygons.offsets,
                &prov,
            )?;
        }
        Ok((mesh, report))
    }

    /// Refuse a soup with no faces, too many corners, or (unless repairing)
    /// a line its format does not allow.
    fn check_readable(&self, options: &ReadOptions) -> Result<(), Error> {
        if self.polygons.face_count() == 0 {
            return Err(Error::Empty {
                at: Location::whole(),
            });
        }
        if self.polygons.indices.len() >= (1 << 29) {
            return Err(Error::TooLarge {
                at: Location::whole(),
                what: "more than 2^29 face corners".into(),
            });
        }
        if let Some((at, what)) = self.nonstandard.first() {
            if !options.repair.any() {
                return Err(Error::NonStandard {
                    at: at.clone(),
                    what: what.clone(),
                });
            }
        }
        Ok(())
    }

    /// Run the repairs `options` ask for (none: an empty report).
    fn repair(&mut self, options: &ReadOptions) -> Result<(RepairReport, Provenance), Error> {
        if !options.repair.any() {
            return Ok((RepairReport::default(), Provenance::default()));
        }
        let classes = self.attrs.weld_classes(self.polygons.positions.len());
        repair_with(&mut self.polygons, &options.repair, &classes)
            .map_err(|e| self.mesh_error(e, &Provenance::default()))
    }

    /// The mesh, with the keys of the input's elements when `with_keys`;
    /// refused where a position no face uses would be dropped.
    fn build(&self, with_keys: bool, prov: &Provenance) -> Result<Built, Error> {
        let built = if with_keys {
            Mesh::build_buffers(&self.polygons)
        } else {
            Mesh::from_buffers(&self.polygons).map(|mesh| {
                let unreferenced = self
                    .polygons
                    .positions
                    .len()
                    .saturating_sub(mesh.vertex_count());
                Built {
                    mesh,
                    vertices: Vec::new(),
                    faces: Vec::new(),
                    unreferenced,
                }
            })
        };
        let built = built.map_err(|e| self.mesh_error(e, prov))?;
        if built.unreferenced > 0 {
            let mut used = vec![false; self.polygons.positions.len()];
            for &i in &self.polygons.indices {
                used[i as usize] = true;
            }
            let first = used.iter().position(|&u| !u).unwrap_or(0);
            return Err(Error::Unreferenced {
                at: Location::whole(),
                count: built.unreferenced,
                first: source(&prov.vertex_source, first),
            });
        }
        Ok(built)
    }

    /// A repair or build error, as the reader reports it.
    fn mesh_error(&self, e: MeshError, prov: &Provenance) -> Error {
        match e {
            MeshError::Build(e) => self.build_error(e, prov),
            other => Error::Header {
                at: Location::whole(),
                message: other.to_string(),
            },
        }
    }

    /// A builder error, its face and vertex numbers mapped back to the file.
    fn build_error(&self, e: BuildError, prov: &Provenance) -> Error {
        let f = |i: usize| source(&prov.face_source, i);
        let v = |i: usize| source(&prov.vertex_source, i);
        let (face, source) = match e {
            BuildError::IndexOutOfRange {
                face,
                index,
                vertex_count,
            } => (
                f(face),
                BuildError::IndexOutOfRange {
                    face: f(face),
                    index,
                    vertex_count,
                },
            ),
            BuildError::TooFewVertices { face, degree } => (
                f(face),
                BuildError::TooFewVertices {
                    face: f(face),
                    degree,
                },
            ),
            BuildError::RepeatedVertex { face, vertex } => (
                f(face),
                BuildError::RepeatedVertex {
                    face: f(face),
                    vertex: v(vertex),
                },
            ),
            BuildError::NonManifoldEdge { a, b, faces } => (
                f(faces[2]),
                BuildError::NonManifoldEdge {
                    a: v(a),
                    b: v(b),
                    faces: faces.map(f),
                },
            ),
            BuildError::InconsistentOrientation { a, b, faces } => (
                f(faces[1]),
                BuildError::InconsistentOrientation {
                    a: v(a),
                    b: v(b),
                    faces: faces.map(f),
                },
            ),
            BuildError::NonManifoldVertex { vertex, face } => (
                f(face),
                BuildError::NonManifoldVertex {
                    vertex: v(vertex),
                    face: f(face),
                },
            ),
            BuildError::NonFinitePosition { vertex, position } => {
                return Error::NonFinite {
                    at: Location::whole(),
                    vertex: v(vertex),
                    position,
                }
            }
            other => {
                return Error::TooLarge {
                    at: Location::whole(),
                    what: other.to_string(),
                }
            }
        };
        Error::Build {
            at: self.location_of_face(face),
            face,
            source,
        }
    }
}

/// `map[i]`, or `i` itself when no map was made (no repair ran).
fn source(map: &[u32], i: usize) -> usize {
    map.get(i).map_or(i, |&s| s as usize)
}
