//! `extrude_face`: push a face out along its normal, with side quads.

use super::refuse;
use crate::error::{Refusal, Result};
use crate::journal::{journaled, Journaling};
use crate::keys::FaceKey;
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid, Vid};
use crate::mesh::Mesh;
use crate::vec3::normalize;

impl Mesh {
    /// The unit normal to move along (`None` without positions).
    fn plan_extrude(&self, fk: FaceKey, distance: f64) -> Result<(Fid, Option<[f64; 3]>)> {
        const OP: &str = "extrude_face";
        let f = self.check_face(fk)?;
        if self.is_hole(f) {
            return Err(refuse(OP, fk, Refusal::Hole));
        }
        if !distance.is_finite() {
            return Err(refuse(
                OP,
                fk,
                Refusal::Parameter("distance must be finite"),
            ));
        }
        let normal = match self.loop_normal(self.face_halfedge(f)) {
            None => None,
            Some(n) => Some(normalize(n).ok_or_else(|| refuse(OP, fk, Refusal::ZeroArea))?),
        };
        Ok((f, normal))
    }

    /// Whether [`extrude_face`](Mesh::extrude_face) would succeed; changes
    /// nothing.
    ///
    /// # Errors
    /// As [`extrude_face`](Mesh::extrude_face).
    pub fn check_extrude_face(&self, f: FaceKey, distance: f64) -> Result<()> {
        self.plan_extrude(f, distance).map(|_| ())
    }

    /// Push face `f` out along its unit normal by `distance`, joining its
    /// old and new outline with one quad per side.
    ///
    /// ```text
    ///                         w3 ----- w2
    ///                        / |  f   / |
    ///   v3 ----- v2         v3 ----- v2 |
    ///   |   f    |    =>    |  w0 ---|- w1     (sides: v_i, v_i+1, w_i+1, w_i)
    ///   v0 ----- v1         v0 ----- v1
    /// ```
    ///
    /// Returns the side quads, in the order of `f`'s half-edges; `f` keeps
    /// its key and becomes the cap on the new corners `w_i`. Without
    /// positions only the topology is made. Attributes: `w_i =
    /// interpolate(v_i: 1)` then moved; the cap keeps `f`'s values, the
    /// sides get `interpolate` of nothing; a cap edge copies the edge below
    /// it, a cap corner the corner below it. χ is unchanged.
    ///
    /// # Errors
    /// [`Error::StaleKey`](crate::Error::StaleKey); [`Refusal::Hole`];
    /// [`Refusal::Parameter`] for a non-finite distance;
    /// [`Refusal::ZeroArea`] for a face of zero area (no normal).
    ///
    /// # Complexity
    /// O(degree of `f`).
    ///
    /// # Examples
    /// ```
    /// use meshloom::Mesh;
    /// let mut m = Mesh::from_polygons(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]], &[[0u32, 1, 2, 3]])?;
    /// let f = m.faces().next().unwrap();
    /// let sides = m.extrude_face(f, 2.0)?;
    /// assert_eq!((sides.len(), m.face_count(), m.vertex_count()), (4, 5, 8));
    /// let cap: Vec<_> = m.face(f)?.vertices().map(|v| m.position(v).unwrap()[2]).collect();
    /// assert_eq!(cap, vec![2.0; 4]);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn extrude_face(&mut self, fk: FaceKey, distance: f64) -> Result<Vec<FaceKey>> {
        journaled!(self.extrude_face_with(fk, distance))
    }
}

impl Mesh {
    /// [`extrude_face`](Mesh::extrude_face)'s body, in journaling mode `J`.
    fn extrude_face_with<J: Journaling>(
        &mut self,
        fk: FaceKey,
        distance: f64,
    ) -> Result<Vec<FaceKey>> {
        let mut w = self.writer::<J>();
        let (f, normal) = w.plan_extrude(fk, distance)?;
        let ring: Vec<Hid> = w.face_halfedges(f).collect();
        let n = ring.len();
        let tops: Vec<Vid> = (0..n).map(|_| w.alloc_vertex()).collect();
        let cap: Vec<Eid> = (0..n).map(|_| w.alloc_edge()).collect();
        let up: Vec<Eid> = (0..n).map(|_| w.alloc_edge()).collect();
        let sides: Vec<Fid> = (0..n).map(|_| w.alloc_face(false)).collect();
        for i in 0..n {
            let j = (i + 1) % n;
            let h = ring[i];
            let [c, ct] = cap[i].halfedges(); // w_i -> w_j, w_j -> w_i
            let up_j = up[j].halfedge(0); // v_j -> w_j
            let down_i = up[i].halfedge(1); // w_i -> v_i
            let s = sides[i];
            *w.he_mut(c) = HalfedgeRecord {
                origin: tops[i],
                next: cap[j].halfedge(0),
                face: f,
            };
            *w.he_mut(ct) = HalfedgeRecord {
                origin: tops[j],
                next: down_i,
                face: s,
            };
            *w.he_mut(up_j) = HalfedgeRecord {
                origin: w.origin(ring[j]),
                next: ct,
                face: s,
            };
            *w.he_mut(down_i) = HalfedgeRecord {
                origin: tops[i],
                next: h,
                face: s,
            };
            w.he_mut(h).next = up_j;
            w.he_mut(h).face = s;
            w.set_face_link(s, h);
            *w.v_halfedge_mut(tops[i]) = c;
        }
        w.set_face_link(f, cap[0].halfedge(0));
        for i in 0..n {
            let v = w.origin(ring[i]).index();
            w.attrs.vertex.interpolate(tops[i].index(), &[(v, 1.0)]);
            w.attrs.edge.copy(ring[i].edge().index(), cap[i].index());
            w.attrs.edge.interpolate(up[i].index(), &[]);
            let [c, ct] = cap[i].halfedges();
            w.attrs.halfedge.copy(ring[i].index(), c.index());
            for x in [ct, up[i].halfedge(0), up[i].halfedge(1)] {
                w.attrs.halfedge.interpolate(x.index(), &[]);
            }
            w.attrs.face.interpolate(sides[i].index(), &[]);
        }
        // The lifted vertices were born in this edit (a reused slot's old
        // value was saved when it was reused): raw writes need no journal.
        if let (Some(nrm), Some(p)) = (normal, w.attrs.positions_mut().map(|c| c.raw_mut())) {
            for &x in &tops {
                let q = &mut p[x.index()];
                for k in 0..3 {
                    q[k] += distance * nrm[k];
                }
            }
        }
        w.end_op();
        Ok(sides.into_iter().map(|s| w.fkey(s)).collect())
    }
}
