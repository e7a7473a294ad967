//! Helpers shared by the modelling tools' tests: a fingerprint of
//! everything a tool may touch, a textured grid, the meshes and random
//! selections of the property tests.

use crate::shapes::{self, GridFaces};
use crate::vec3::V3;
use crate::{AnyKey, ElementKind, FaceKey, Mesh};

/// Keys, links, positions and every column's values: equal fingerprints
/// mean a refused tool left the mesh as it was.
pub(crate) fn fingerprint(mesh: &Mesh) -> String {
    let mut out = String::new();
    for f in mesh.faces_and_holes() {
        let face = mesh.face(f).unwrap();
        let hs: Vec<_> = face.halfedges().collect();
        let vs: Vec<_> = face.vertices().collect();
        out += &format!("{f:?}{hs:?}{vs:?}");
    }
    for h in mesh.halfedges() {
        let view = mesh.halfedge(h).unwrap();
        out += &format!("{h:?}{:?}{:?}", view.origin().key(), view.next().key());
    }
    let keys: [(ElementKind, Vec<AnyKey>); 4] = [
        (
            ElementKind::Vertex,
            mesh.vertices().map(AnyKey::Vertex).collect(),
        ),
        (
            ElementKind::Halfedge,
            mesh.halfedges().map(AnyKey::Halfedge).collect(),
        ),
        (ElementKind::Edge, mesh.edges().map(AnyKey::Edge).collect()),
        (
            ElementKind::Face,
            mesh.faces_and_holes().map(AnyKey::Face).collect(),
        ),
    ];
    for (kind, keys) in keys {
        for info in mesh.attr_info(kind) {
            out += &info.name;
            for &k in &keys {
                out += &format!("{:?}", mesh.attr_value_at(&info.name, k).unwrap());
            }
        }
    }
    out
}

/// The linear UV field the textured tests sample:
/// `uv(x, y) = (0.25 x + 0.5 y + 1, −0.5 x + 0.125 y)`.
pub(crate) fn field(p: V3) -> [f64; 2] {
    [0.25 * p[0] + 0.5 * p[1] + 1.0, -0.5 * p[0] + 0.125 * p[1]]
}

/// The closed and open meshes of mixed face kinds the random-selection
/// property tests run on.
pub(crate) fn mixed_meshes() -> [Mesh; 4] {
    [
        shapes::uv_sphere(8, 5),
        shapes::grid(5, 4, GridFaces::Triangles),
        shapes::torus(7, 4, 1.0, 0.3).unwrap(),
        shapes::icosphere(1),
    ]
}

/// About a third of `mesh`'s faces, chosen by the xorshift state `seed`.
pub(crate) fn random_faces(mesh: &Mesh, seed: &mut u64) -> Vec<FaceKey> {
    mesh.faces()
        .filter(|_| next_random(seed) % 3 == 0)
        .collect()
}

/// One step of a xorshift generator.
pub(crate) fn next_random(seed: &mut u64) -> u64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    *seed
}
