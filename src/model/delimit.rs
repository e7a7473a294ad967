//! Delimiters: the edges a merging tool (limited dissolve, join triangles)
//! keeps, whatever the geometry says, as Blender's `delimit` sets do.
//!
//! An edge delimits when the faces on its two sides differ in the
//! [`Delimit::material`] face column (any type, compared by value), when
//! it is a seam of the [`Delimit::seams`] corner column (the values at one
//! of its ends differ across it: a UV seam), or when the
//! [`Delimit::sharp`] boolean edge column is `true` on it. Boundary edges
//! always delimit (they have a hole on one side). The columns are named as
//! the algorithms' options name theirs (`material` as decimation's; the
//! seams of a column as the constraints' seams).

use crate::attr::{AttrView, EdgeAttr};
use crate::error::{Error, Result};
use crate::keys::{EdgeKey, ElementKind};
use crate::layout::Eid;
use crate::mesh::Mesh;
use crate::store::ErasedColumn;

/// Which columns stop a merge. An edge delimits when the faces on its
/// two sides differ in the `material` face column (any type, compared by
/// value), when it is a seam of the `seams` corner column (the values at
/// one of its ends differ across it: a UV seam), or when the `sharp`
/// boolean edge column is `true` on it; boundary edges always delimit.
/// The default delimits nothing but the boundary.
///
/// ```
/// use meshloom::model::Delimit;
/// let d = Delimit { material: Some("material".into()), ..Delimit::default() };
/// assert!(d.seams.is_none() && d.sharp.is_none());
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Delimit {
    /// A face column: two faces with different values are not merged.
    pub material: Option<String>,
    /// A corner (half-edge) column: an edge across which its values differ
    /// at either end is kept.
    pub seams: Option<String>,
    /// A boolean edge column: edges where it is `true` are kept.
    pub sharp: Option<EdgeAttr<bool>>,
}

impl Delimit {
    /// The edges of `mesh` that `self` keeps: the boundary, the borders
    /// of the material column, the seams of the corner column, the sharp
    /// edges. With [`Mesh::split_edges`] it rips a mesh along its UV seams.
    ///
    /// # Errors
    /// [`Error::AttributeMissing`] for a named column the mesh lacks; the
    /// errors of [`Mesh::attr_view`] for a stale `sharp` handle.
    ///
    /// ```
    /// use meshloom::model::Delimit;
    /// let cube = meshloom::shapes::cube();
    /// assert!(Delimit::default().edges(&cube)?.is_empty());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn edges(&self, mesh: &Mesh) -> Result<Vec<EdgeKey>> {
        let d = Delimiters::new(mesh, self)?;
        Ok(mesh
            .eids()
            .filter(|&e| d.delimits(e))
            .map(|e| mesh.ekey(e))
            .collect())
    }
}

/// [`Delimit`] resolved against one mesh: the columns found, ready to ask
/// edge by edge.
pub(crate) struct Delimiters<'m> {
    mesh: &'m Mesh,
    material: Option<&'m dyn ErasedColumn>,
    seams: Option<&'m dyn ErasedColumn>,
    sharp: Option<AttrView<'m, EdgeKey, bool>>,
}

impl<'m> Delimiters<'m> {
    /// Find `d`'s columns in `mesh`.
    ///
    /// # Errors
    /// [`Error::AttributeMissing`] for a named column the mesh lacks;
    /// the errors of [`Mesh::attr_view`] for a stale `sharp` handle.
    pub(crate) fn new(mesh: &'m Mesh, d: &Delimit) -> Result<Delimiters<'m>> {
        Ok(Delimiters {
            mesh,
            material: column(mesh, ElementKind::Face, &d.material)?,
            seams: column(mesh, ElementKind::Halfedge, &d.seams)?,
            sharp: match &d.sharp {
                None => None,
                Some(h) => Some(mesh.attr_view(h)?),
            },
        })
    }

    /// Whether edge `e` must be kept: a boundary edge, a material border,
    /// a seam or a sharp edge.
    #[inline]
    pub(crate) fn delimits(&self, e: Eid) -> bool {
        let mesh = self.mesh;
        let [h, t] = e.halfedges();
        if mesh.in_hole(h) || mesh.in_hole(t) {
            return true;
        }
        if let Some(c) = self.material {
            if !c.same(mesh.face_of(h).index(), mesh.face_of(t).index()) {
                return true;
            }
        }
        if let Some(c) = self.seams {
            let (nh, nt) = (mesh.next(h), mesh.next(t));
            if !c.same(h.index(), nt.index()) || !c.same(nh.index(), t.index()) {
                return true;
            }
        }
        self.sharp
            .as_ref()
            .is_some_and(|s| s.get(mesh.ekey(e)).copied() == Some(true))
    }
}

/// The column of arena `kind` named `name`, if a name is given.
fn column<'m>(
    mesh: &'m Mesh,
    kind: ElementKind,
    name: &Option<String>,
) -> Result<Option<&'m dyn ErasedColumn>> {
    let Some(name) = name else {
        return Ok(None);
    };
    let cols = mesh.columns_of(kind);
    let i = cols.find(name).ok_or_else(|| Error::AttributeMissing {
        kind,
        name: name.clone(),
    })?;
    Ok(Some(&*cols.cols[i].1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{self, GridFaces};

    /// The edges of `mesh` that `d` keeps.
    fn kept(mesh: &Mesh, d: &Delimit) -> usize {
        let ds = Delimiters::new(mesh, d).unwrap();
        mesh.eids().filter(|&e| ds.delimits(e)).count()
    }

    #[test]
    fn boundary_material_seams_and_sharp_edges_delimit() {
        // 4 × 4 unit quads: 40 edges, 16 on the boundary, 24 inside.
        let mut mesh = shapes::grid(4, 4, GridFaces::Quads);
        assert_eq!(kept(&mesh, &Delimit::default()), 16);
        // Material by column of quads: 3 interior columns of 4 edges.
        let m = mesh.add_face_attr::<u32>("material").unwrap();
        let uv = mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
        for f in mesh.faces().collect::<Vec<_>>() {
            let x = mesh
                .face(f)
                .unwrap()
                .vertices()
                .map(|v| mesh.position(v).unwrap()[0]);
            let x = x.sum::<f64>() / 4.0;
            mesh.set_attr(&m, f, (x * 4.0) as u32).unwrap();
            // A UV seam between the lower and the upper half.
            for h in mesh.face(f).unwrap().halfedges().collect::<Vec<_>>() {
                let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
                let y = mesh
                    .face(f)
                    .unwrap()
                    .vertices()
                    .map(|v| mesh.position(v).unwrap()[1]);
                let island = if y.sum::<f64>() / 4.0 < 2.0 {
                    0.0
                } else {
                    10.0
                };
                mesh.set_attr(&uv, h, [p[0] + island, p[1]]).unwrap();
            }
        }
        let material = Delimit {
            material: Some("material".into()),
            ..Delimit::default()
        };
        assert_eq!(kept(&mesh, &material), 16 + 12);
        let seams = Delimit {
            seams: Some("uv".into()),
            ..Delimit::default()
        };
        assert_eq!(kept(&mesh, &seams), 16 + 4);
        let sharp = mesh.add_edge_attr::<bool>("sharp").unwrap();
        let plain = {
            let (m, s) = (
                Delimiters::new(&mesh, &material).unwrap(),
                Delimiters::new(&mesh, &seams).unwrap(),
            );
            mesh.eids()
                .find(|&e| !m.delimits(e) && !s.delimits(e))
                .unwrap()
        };
        mesh.set_attr(&sharp, mesh.ekey(plain), true).unwrap();
        let all = Delimit {
            material: Some("material".into()),
            seams: Some("uv".into()),
            sharp: Some(sharp),
        };
        assert_eq!(kept(&mesh, &all), 16 + 12 + 4 + 1);
        let missing = Delimit {
            seams: Some("nope".into()),
            ..Delimit::default()
        };
        assert!(matches!(
            Delimiters::new(&mesh, &missing),
            Err(Error::AttributeMissing { .. })
        ));
    }
}
