//! Resampling vertex and corner columns from the input surface, each
//! corner on its own side of the seams.

use super::engine::{positions, Engine};
use crate::layout::{Fid, Hid};
use crate::mesh::Mesh;
use crate::vec3::V3;

impl Engine {
    /// Resample the chosen vertex and corner columns of `work` from
    /// `input` (see the module docs).
    pub(super) fn resample(&mut self, input: &Mesh, work: &mut Mesh) {
        if self.resample.is_empty() || self.reference.tree.triangle_count() == 0 {
            return;
        }
        self.fit(work);
        let pos = positions(work).to_vec();
        // Each vertex's triangle and barycentric coordinates.
        let nv = work.slot_counts()[0];
        let mut at: Vec<(u32, [f64; 3])> = vec![(u32::MAX, [0.0; 3]); nv];
        for v in work.vids() {
            let i = v.index();
            let hint = Some(self.hint[i]);
            if let Some(near) = self
                .reference
                .tree
                .closest_near(pos[i], hint, &mut self.stack)
            {
                at[i] = (near.tri, near.weights);
            }
        }
        self.resample_vertex_columns(input, work, &at);
        let corner_cols: Vec<usize> = self
            .resample
            .iter()
            .filter(|c| c.corner)
            .map(|c| c.index)
            .collect();
        if !corner_cols.is_empty() {
            self.resample_corner_columns(input, work, &pos, &at, &corner_cols);
        }
    }

    /// The vertex columns: each vertex's value interpolated on the input
    /// triangle under it (`at`).
    pub(super) fn resample_vertex_columns(
        &self,
        input: &Mesh,
        work: &mut Mesh,
        at: &[(u32, [f64; 3])],
    ) {
        let reference = &self.reference;
        let tri_vertices = |t: u32| reference.corners[t as usize].map(|h| input.origin(h));
        for col in &self.resample {
            if col.corner {
                continue;
            }
            let src = &*input.attrs().vertex.cols[col.index].1;
            let (live, attrs) = work.vertex_arena_and_attrs_mut();
            let dst = &mut attrs.vertex.cols[col.index].1;
            for v in live.live_indices() {
                let (t, b) = at[v as usize];
                if t == u32::MAX {
                    continue;
                }
                let vs = tri_vertices(t);
                let inputs = [
                    (vs[0].index(), b[0]),
                    (vs[1].index(), b[1]),
                    (vs[2].index(), b[2]),
                ];
                dst.interpolate_from(src, v as usize, &inputs);
            }
        }
    }

    /// The corner columns `cols`: each corner's value interpolated on the
    /// input triangle under its vertex, on its own face's side of the
    /// column's seams.
    pub(super) fn resample_corner_columns(
        &mut self,
        input: &Mesh,
        work: &mut Mesh,
        pos: &[V3],
        at: &[(u32, [f64; 3])],
        cols: &[usize],
    ) {
        let reference = &self.reference;
        let stack = &mut self.stack;
        // Per face of the result: the triangle under its centroid.
        let faces: Vec<(Fid, [Hid; 3])> = work
            .fids()
            .filter(|&f| !work.is_hole(f))
            .map(|f| {
                let h0 = work.face_halfedge(f);
                let h1 = work.next(h0);
                (f, [h0, h1, work.next(h1)])
            })
            .collect();
        let under_face: Vec<u32> = faces
            .iter()
            .map(|(_, hs)| {
                let ps = hs.map(|h| pos[work.origin(h).index()]);
                let c = [0, 1, 2].map(|k| (ps[0][k] + ps[1][k] + ps[2][k]) / 3.0);
                let hint = at[work.origin(hs[0]).index()].0;
                reference
                    .tree
                    .closest_near(c, (hint != u32::MAX).then_some(hint), stack)
                    .map_or(u32::MAX, |near| near.tri)
            })
            .collect();
        for &ci in cols {
            let islands = reference.islands(input, ci);
            let mut writes: Vec<(Hid, u32, [f64; 3])> = Vec::with_capacity(3 * faces.len());
            for ((_, hs), &tf) in faces.iter().zip(&under_face) {
                if tf == u32::MAX {
                    continue;
                }
                let island = islands[tf as usize];
                for &h in hs {
                    let v = work.origin(h);
                    let (tv, bv) = at[v.index()];
                    let (t, b) = if tv != u32::MAX && islands[tv as usize] == island {
                        (tv, bv)
                    } else {
                        let keep = |t: u32| islands[t as usize] == island;
                        match reference.tree.closest_near_where(
                            pos[v.index()],
                            Some(tf),
                            keep,
                            stack,
                        ) {
                            Some(near) => (near.tri, near.weights),
                            None => continue,
                        }
                    };
                    writes.push((h, t, b));
                }
            }
            let src = &*input.attrs().halfedge.cols[ci].1;
            let dst = &mut work.attrs_mut().halfedge.cols[ci].1;
            for (h, t, b) in writes {
                let cs = reference.corners[t as usize];
                let inputs = [
                    (cs[0].index(), b[0]),
                    (cs[1].index(), b[1]),
                    (cs[2].index(), b[2]),
                ];
                dst.interpolate_from(src, h.index(), &inputs);
            }
        }
    }
}
