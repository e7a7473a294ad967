//! The column names every reader writes and every writer reads, so that a
//! program can make a mesh whose materials, UVs and normals reach a file
//! (and come back) without knowing each format.
//!
//! | name | arena | type | OBJ | PLY | OFF | glTF | STL |
//! |---|---|---|---|---|---|---|---|
//! | [`MATERIAL`] | face | text (`String`) | `usemtl` | — | — | one primitive and named material per value | — |
//! | [`GROUP`], [`OBJECT`] | face | text | `g`, `o` | — | — | — | — |
//! | [`TEXCOORD`] | corner | `[f64; 2]` | `vt` | written as `s t` (read back as columns `s`, `t`) | vertex | `TEXCOORD_0` | — |
//! | [`NORMAL`] | corner | `[f64; 3]` | `vn` | written as `nx ny nz` (read back as `nx`, `ny`, `nz`) | vertex | `NORMAL` (written only if the column exists) | from positions |
//! | [`COLOR`] | vertex | numbers | — | — | vertex | `COLOR_0` | — |
//!
//! Positions are the vertex column [`POSITION`](crate::attr::POSITION).
//! Other columns go where a format has room for them (glTF: `_NAME`
//! custom attributes; PLY: properties) and
//! [`dropped_columns`](super::dropped_columns) names those a format drops.
//!
//! ```
//! use meshloom::io::names::{self, MATERIAL};
//! let mut mesh = meshloom::shapes::cube();
//! let faces: Vec<_> = mesh.faces().collect();
//! mesh.set_face_material(faces[0], "glass")?;
//! mesh.set_face_material(faces[1], "brick")?;
//! assert_eq!(mesh.face_material(faces[0]).as_deref(), Some("glass"));
//! assert_eq!(mesh.face_material(faces[2]), None);
//! assert!(mesh.attr_info(meshloom::ElementKind::Face).iter().any(|c| c.name == MATERIAL));
//! # let _ = names::TEXCOORD;
//! # Ok::<(), meshloom::Error>(())
//! ```

use crate::attr::Value;
use crate::error::Result;
use crate::keys::FaceKey;
use crate::mesh::Mesh;
use crate::ElementKind;

/// Face column: the face's material name (text).
pub const MATERIAL: &str = "material";
/// Face column: the OBJ group (`g`) a face belongs to (text).
pub const GROUP: &str = "group";
/// Face column: the OBJ object (`o`) a face belongs to (text).
pub const OBJECT: &str = "object";
/// Corner (half-edge) column: texture coordinates, `[f64; 2]`; corners of
/// one vertex hold different values across a UV seam.
pub const TEXCOORD: &str = "texcoord";
/// Corner (half-edge) column: normals, `[f64; 3]`; corners of one vertex
/// hold different values across a hard edge.
pub const NORMAL: &str = "normal";
/// Vertex column: colours.
pub const COLOR: &str = "color";

impl Mesh {
    /// Name face `f`'s material (the [`MATERIAL`] face column, added as a
    /// text column if the mesh has none): OBJ writes it as `usemtl`, glTF
    /// as one primitive and material per name. One undo step.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); a [`MATERIAL`] column
    /// that does not hold text ([`Error::AttributeType`](crate::Error::AttributeType)).
    pub fn set_face_material(&mut self, f: FaceKey, name: &str) -> Result<()> {
        self.face(f)?;
        let exists = self
            .attr_info(ElementKind::Face)
            .iter()
            .any(|c| c.name == MATERIAL);
        if !exists {
            self.add_face_attr::<String>(MATERIAL)?;
        }
        self.set_attr_value(MATERIAL, f, Some(&Value::Text(name.to_owned())))
    }

    /// Face `f`'s material name, if the mesh has a [`MATERIAL`] text column
    /// and `f` has a value in it.
    pub fn face_material(&self, f: FaceKey) -> Option<String> {
        match self.attr_value(MATERIAL, f) {
            Ok(Some(Value::Text(s))) => Some(s),
            _ => None,
        }
    }
}
