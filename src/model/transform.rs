//! `transform_vertices` and `transform_faces`: move a selection by a
//! scale, a rotation and a translation about a pivot, as one step.

use crate::error::{Error, Refusal, Result};
use crate::keys::{FaceKey, VertexKey};
use crate::layout::{Fid, Vid};
use crate::mesh::Mesh;
use crate::ops::refuse;
use crate::vec3::{self, V3};

const OP: &str = "transform";

/// The point a [`Transform`] scales and rotates about.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Pivot {
    /// The mean of the moved vertices' positions (of each region's, with
    /// `individual`).
    #[default]
    Centroid,
    /// A given point.
    Point([f64; 3]),
}

/// An affine map about a pivot: `p ↦ pivot + rotate · (scale ∘ (p −
/// pivot)) + translate`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// Per axis scale factors, applied first.
    pub scale: [f64; 3],
    /// A 3 × 3 matrix (rows), applied second: a rotation, or any linear
    /// map.
    pub rotate: [[f64; 3]; 3],
    /// Added last.
    pub translate: [f64; 3],
    /// What to scale and rotate about.
    pub pivot: Pivot,
    /// For faces: each region of faces sharing an edge about its own
    /// centroid (Blender's "individual origins"); ignored for vertices and
    /// with a given pivot point.
    pub individual: bool,
}

impl Default for Transform {
    fn default() -> Transform {
        Transform {
            scale: [1.0; 3],
            rotate: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            translate: [0.0; 3],
            pivot: Pivot::Centroid,
            individual: false,
        }
    }
}

impl Transform {
    /// The rotation by `angle` radians about `axis` (right-handed), or
    /// `None` for a zero or non-finite axis.
    ///
    /// ```
    /// use meshloom::model::Transform;
    /// let r = Transform::rotation([0.0, 0.0, 2.0], std::f64::consts::FRAC_PI_2).unwrap();
    /// assert!((r[0][1] + 1.0).abs() < 1e-15 && (r[1][0] - 1.0).abs() < 1e-15);
    /// ```
    pub fn rotation(axis: [f64; 3], angle: f64) -> Option<[[f64; 3]; 3]> {
        let [x, y, z] = vec3::normalize(axis).filter(|_| angle.is_finite())?;
        let (s, c) = angle.sin_cos();
        let t = 1.0 - c;
        Some([
            [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
        ])
    }

    /// `p` mapped about `pivot`.
    fn apply(&self, p: V3, pivot: V3) -> V3 {
        let d = vec3::sub(p, pivot);
        let s = [
            d[0] * self.scale[0],
            d[1] * self.scale[1],
            d[2] * self.scale[2],
        ];
        let r = self.rotate.map(|row| vec3::dot(row, s));
        vec3::add(vec3::add(pivot, r), self.translate)
    }

    /// Whether every number is finite.
    fn is_finite(&self) -> bool {
        let point = match self.pivot {
            Pivot::Point(p) => p,
            Pivot::Centroid => [0.0; 3],
        };
        self.scale
            .iter()
            .chain(self.rotate.iter().flatten())
            .chain(&self.translate)
            .chain(&point)
            .all(|c| c.is_finite())
    }
}

impl Mesh {
    /// Move `vertices` (repeats count once) by `t`, as one edit and one
    /// undo step. Positions only: no link or other value changes.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey);
    /// [`Error::NoPositions`]; [`Refusal::Parameter`] for a non-finite
    /// transform; [`Error::NonFinitePosition`] when a moved position would
    /// not be finite (nothing moves then).
    ///
    /// # Complexity
    /// O(selected vertices).
    ///
    /// ```
    /// use meshloom::model::{Pivot, Transform};
    /// let mut mesh = meshloom::shapes::cube(); // [0, 1]³
    /// let all: Vec<_> = mesh.vertices().collect();
    /// let t = Transform { scale: [2.0; 3], ..Default::default() };
    /// mesh.transform_vertices(&all, &t)?; // about the centroid (½, ½, ½)
    /// let xs: Vec<f64> = all.iter().map(|&v| mesh.position(v).unwrap()[0]).collect();
    /// assert!(xs.iter().all(|&x| x == -0.5 || x == 1.5));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn transform_vertices(&mut self, vertices: &[VertexKey], t: &Transform) -> Result<()> {
        let vs = self.unique_vertices(vertices)?;
        self.move_groups(&[vs], t, vertices.first().copied())
    }

    /// Move the vertices of `faces` by `t` (with `individual`, each region
    /// of faces sharing an edge about its own centroid), as one edit and
    /// one undo step.
    ///
    /// # Errors
    /// As [`transform_vertices`](Mesh::transform_vertices);
    /// [`Refusal::Hole`] for a hole.
    ///
    /// # Complexity
    /// O(the faces' corners).
    ///
    /// ```
    /// use meshloom::model::Transform;
    /// use meshloom::shapes::{grid, GridFaces};
    /// let mut mesh = grid(4, 1, GridFaces::Quads);
    /// let ends = [mesh.faces().next().unwrap(), mesh.faces().last().unwrap()];
    /// let t = Transform { scale: [0.5; 3], individual: true, ..Default::default() };
    /// mesh.transform_faces(&ends, &t)?; // each end quad shrinks about its own centre
    /// assert!((mesh.face_area(ends[0])? - 0.25).abs() < 1e-12);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn transform_faces(&mut self, faces: &[FaceKey], t: &Transform) -> Result<()> {
        let mut fs = Vec::with_capacity(faces.len());
        for &fk in faces {
            let f = self.check_face(fk)?;
            if self.is_hole(f) {
                return Err(refuse(OP, fk, Refusal::Hole));
            }
            fs.push(f);
        }
        let groups = if t.individual && t.pivot == Pivot::Centroid {
            self.region_vertex_groups(&fs)
        } else {
            let keys: Vec<VertexKey> = fs
                .iter()
                .flat_map(|&f| self.face_halfedges(f).map(|h| self.vkey(self.origin(h))))
                .collect();
            vec![self.unique_vertices(&keys)?]
        };
        let name = faces.first().map(|&f| {
            let h = self.face_halfedge(self.check_face(f).expect("checked"));
            self.vkey(self.origin(h))
        });
        self.move_groups(&groups, t, name)
    }

    /// The slots of `vertices`, checked, without repeats.
    fn unique_vertices(&self, vertices: &[VertexKey]) -> Result<Vec<Vid>> {
        let mut seen = std::collections::HashSet::with_capacity(vertices.len());
        let mut out = Vec::with_capacity(vertices.len());
        for &v in vertices {
            let v = self.check_vertex(v)?;
            if seen.insert(v) {
                out.push(v);
            }
        }
        Ok(out)
    }

    /// The vertices of each region of `fs` (faces joined through a shared
    /// edge), without repeats.
    fn region_vertex_groups(&self, fs: &[Fid]) -> Vec<Vec<Vid>> {
        let chosen: std::collections::HashSet<Fid> = fs.iter().copied().collect();
        let mut done = std::collections::HashSet::new();
        let mut groups = Vec::new();
        for &f in fs {
            if !done.insert(f) {
                continue;
            }
            let (mut stack, mut group, mut seen) =
                (vec![f], Vec::new(), std::collections::HashSet::new());
            while let Some(g) = stack.pop() {
                for h in self.face_halfedges(g) {
                    let v = self.origin(h);
                    if seen.insert(v) {
                        group.push(v);
                    }
                    let n = self.face_of(h.twin());
                    if chosen.contains(&n) && done.insert(n) {
                        stack.push(n);
                    }
                }
            }
            groups.push(group);
        }
        groups
    }

    /// Move each group about its pivot; all positions computed and checked
    /// before any is written.
    fn move_groups(
        &mut self,
        groups: &[Vec<Vid>],
        t: &Transform,
        name: Option<VertexKey>,
    ) -> Result<()> {
        let name = name.unwrap_or(VertexKey::new(0, 0));
        if !t.is_finite() {
            return Err(refuse(
                OP,
                name,
                Refusal::Parameter("the transform must be finite"),
            ));
        }
        let pos = self.position_slots().ok_or(Error::NoPositions)?;
        let mut moved = Vec::new();
        for group in groups.iter().filter(|g| !g.is_empty()) {
            let pivot = match t.pivot {
                Pivot::Point(p) => p,
                Pivot::Centroid => {
                    let sum = group
                        .iter()
                        .fold([0.0; 3], |s, v| vec3::add(s, pos[v.index()]));
                    vec3::scale(sum, 1.0 / group.len() as f64)
                }
            };
            for &v in group {
                let p = t.apply(pos[v.index()], pivot);
                if !p.iter().all(|c| c.is_finite()) {
                    return Err(Error::NonFinitePosition {
                        key: self.vkey(v).into(),
                        position: p,
                    });
                }
                moved.push((v, p));
            }
        }
        let mut w = self.writer::<crate::record::Recorded>();
        for (v, p) in moved {
            w.attrs.set_position_saved(v.index(), p);
        }
        self.end_edit();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::journal::HistoryLimits;
    use crate::shapes::{self, GridFaces};

    fn positions(mesh: &Mesh) -> Vec<[u64; 3]> {
        mesh.vertices()
            .map(|v| mesh.position(v).unwrap().map(f64::to_bits))
            .collect()
    }

    #[test]
    fn rotation_scale_and_translation_about_a_pivot() {
        let mut mesh = shapes::cube();
        let all: Vec<VertexKey> = mesh.vertices().collect();
        let t = Transform {
            rotate: Transform::rotation([0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2).unwrap(),
            translate: [10.0, 0.0, 0.0],
            pivot: Pivot::Point([0.0; 3]),
            ..Default::default()
        };
        let before: Vec<V3> = all.iter().map(|&v| mesh.position(v).unwrap()).collect();
        mesh.transform_vertices(&all, &t).unwrap();
        for (&v, p) in all.iter().zip(&before) {
            let q = mesh.position(v).unwrap();
            let want = [10.0 - p[1], p[0], p[2]];
            assert!(
                (0..3).all(|k| (q[k] - want[k]).abs() < 1e-12),
                "{q:?} {want:?}"
            );
        }
        mesh.validate().unwrap();
    }

    #[test]
    fn individual_faces_scale_about_their_regions_centres() {
        let mut mesh = shapes::grid(5, 1, GridFaces::Quads);
        let fs: Vec<FaceKey> = mesh.faces().collect();
        // Faces 0–1 (one region) and 3 (another).
        let chosen = [fs[0], fs[1], fs[3]];
        let areas: Vec<f64> = chosen.iter().map(|&f| mesh.face_area(f).unwrap()).collect();
        let t = Transform {
            scale: [0.5, 0.5, 1.0],
            individual: true,
            ..Default::default()
        };
        mesh.transform_faces(&chosen, &t).unwrap();
        for (&f, a) in chosen.iter().zip(&areas) {
            assert!((mesh.face_area(f).unwrap() - a / 4.0).abs() < 1e-12);
        }
        // The region 0–1 kept its shared edge; face 3's centre stayed.
        let c3 = mesh.face_centroid(chosen[2]).unwrap();
        assert!(
            (c3[0] - 3.5).abs() < 1e-12 && (c3[1] - 0.5).abs() < 1e-12,
            "{c3:?}"
        );
    }

    #[test]
    fn a_refused_transform_moves_nothing_and_a_transform_is_one_undo_step() {
        let mut mesh = shapes::cube();
        mesh.history_mut().enable(HistoryLimits::default());
        let all: Vec<VertexKey> = mesh.vertices().collect();
        let before = positions(&mesh);
        let bad = [
            Transform {
                scale: [f64::NAN, 1.0, 1.0],
                ..Default::default()
            },
            Transform {
                translate: [f64::INFINITY, 0.0, 0.0],
                ..Default::default()
            },
            Transform {
                scale: [1e308, 1.0, 1.0],
                translate: [1.5e308, 0.0, 0.0],
                ..Default::default()
            },
        ];
        for t in bad {
            assert!(mesh.transform_vertices(&all, &t).is_err());
            assert_eq!(positions(&mesh), before);
        }
        let mut open = mesh.clone();
        let f = open.faces().next().unwrap();
        open.remove_face(f).unwrap();
        let h = open.holes().next().unwrap();
        let err = open
            .transform_faces(&[h], &Transform::default())
            .unwrap_err();
        assert!(matches!(
            err,
            Error::Refused {
                reason: Refusal::Hole,
                ..
            }
        ));
        let undo = mesh.history().undo_len();
        mesh.transform_vertices(
            &all,
            &Transform {
                translate: [1.0, 2.0, 3.0],
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(mesh.history().undo_len(), undo + 1);
        assert!(mesh.undo());
        assert_eq!(positions(&mesh), before);
    }
}
