//! Inferring an absent value from neighbours, on demand (the halfedges
//! package's `_infer_value`).

use super::handle::{Attr, Element};
use crate::error::Result;
use crate::keys::ElementKind;
use crate::layout::{Eid, Fid, Hid, Vid};
use crate::mesh::Mesh;
use crate::store::rule::Rule;
use crate::store::Attribute;

impl Mesh {
    /// The value of `key`'s element, or, if it has none, the value its
    /// rule infers from its neighbours ([`Rule::infer`]): for
    /// [`Interpolate`](super::Interpolate), the mean of the neighbours that
    /// have one. Nothing is stored.
    ///
    /// Neighbours, in ring order with equal weights: of a vertex, the
    /// vertices joined to it; of a face (or hole), the faces across its
    /// edges; of an edge, the other edges at its two ends; of a half-edge
    /// (a corner), the other half-edges leaving the same vertex.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey),
    /// [`Error::AttributeHandle`](crate::Error::AttributeHandle).
    ///
    /// # Complexity
    /// O(number of neighbours).
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let t = mesh.add_vertex_attr::<f64>("temperature")?;
    /// let v: Vec<_> = mesh.vertices().collect();
    /// mesh.set_attr(&t, v[1], 10.0)?;
    /// mesh.set_attr(&t, v[2], 20.0)?;
    /// assert_eq!(mesh.attr(&t, v[0])?, None);
    /// assert_eq!(mesh.infer_attr(&t, v[0])?, Some(15.0));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn infer_attr<K: Element, T: Attribute, R: Rule<T>>(
        &self,
        h: &Attr<K, T, R>,
        key: K,
    ) -> Result<Option<T>> {
        if let Some(v) = self.attr(h, key)? {
            return Ok(Some(v.clone()));
        }
        let view = self.attr_view(h)?;
        let neighbours = self.neighbour_slots(K::KIND, key.slot());
        let w = 1.0 / neighbours.len().max(1) as f64;
        let values: Vec<(Option<&T>, f64)> = neighbours
            .iter()
            .map(|&(i, g)| (view.get(K::from_parts(i, g)), w))
            .collect();
        Ok(R::infer(&values))
    }

    /// `(slot, generation)` of the neighbours of a live element.
    fn neighbour_slots(&self, kind: ElementKind, s: u32) -> Vec<(u32, u32)> {
        match kind {
            ElementKind::Vertex => self
                .outgoing(Vid::new(s))
                .map(|h| {
                    let d = self.dest(h);
                    (d.raw(), self.vkey(d).generation)
                })
                .collect(),
            ElementKind::Face => self
                .face_halfedges(Fid::new(s))
                .map(|h| {
                    let f = self.face_of(h.twin());
                    (f.raw(), self.fkey(f).generation)
                })
                .collect(),
            ElementKind::Edge => {
                let e = Eid::new(s);
                let mut out = Vec::new();
                for end in e.halfedges() {
                    for h in self.outgoing(self.origin(end)) {
                        if h.edge() != e {
                            out.push((h.edge().raw(), self.ekey(h.edge()).generation));
                        }
                    }
                }
                out
            }
            ElementKind::Halfedge => {
                let s = Hid::new(s);
                self.outgoing(self.origin(s))
                    .filter(|&h| h != s)
                    .map(|h| (h.raw(), self.hkey(h).generation))
                    .collect()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::attr::{Conserved, Incompatible};
    use crate::keys::{EdgeKey, FaceKey};

    #[test]
    fn faces_infer_from_faces_across_edges() {
        let mut mesh = crate::shapes::cube();
        let c = mesh.add_face_attr::<[f32; 3]>("colour").unwrap();
        let f = mesh.faces().next().unwrap();
        let across: Vec<FaceKey> = mesh.face(f).unwrap().neighbors().collect();
        assert_eq!(across.len(), 4);
        mesh.set_attr(&c, across[0], [1.0, 0.0, 0.0]).unwrap();
        mesh.set_attr(&c, across[1], [0.0, 1.0, 0.0]).unwrap();
        assert_eq!(mesh.infer_attr(&c, f).unwrap(), Some([0.5, 0.5, 0.0]));
    }

    #[test]
    fn rules_without_inference_infer_nothing() {
        let mut mesh = crate::shapes::cube();
        let m = mesh
            .add_attr_with_rule::<EdgeKey, f64, Conserved>("mass")
            .unwrap();
        let id = mesh
            .add_attr_with_rule::<EdgeKey, u32, Incompatible>("id")
            .unwrap();
        let e: Vec<EdgeKey> = mesh.edges().collect();
        mesh.fill_attr(&m, 1.0).unwrap();
        mesh.fill_attr(&id, 1).unwrap();
        mesh.clear_attr(&m, e[0]).unwrap();
        mesh.clear_attr(&id, e[0]).unwrap();
        assert_eq!(mesh.infer_attr(&m, e[0]).unwrap(), None);
        assert_eq!(mesh.infer_attr(&id, e[0]).unwrap(), None);
        assert_eq!(mesh.infer_attr(&m, e[1]).unwrap(), Some(1.0));
    }
}
