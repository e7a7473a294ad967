//! Topological editing operators: checked, all-or-nothing, attribute-aware.
//!
//! # Index
//!
//! | operator | file | returns | χ = V − E + F changes by |
//! |---|---|---|---|
//! | [`Mesh::split_edge`] | `split.rs` | the new vertex | 0 |
//! | [`Mesh::split_face`] | `split.rs` | the new half-edge `a → b` | 0 |
//! | [`Mesh::insert_edge`] | `split.rs` | the new half-edge `a → b` | 0 |
//! | [`Mesh::poke_face`] | `split.rs` | the new centre vertex | 0 |
//! | [`Mesh::collapse_edge`] | `collapse.rs` | the surviving vertex | 0, or +1 when a triangular hole closes |
//! | [`Mesh::collapse_edge_to`] | `collapse.rs` | the surviving vertex, at the given point | as `collapse_edge` |
//! | [`Mesh::flip_edge`] | `flip.rs` | the same edge, turned | 0 |
//! | [`Mesh::remove_edge`] | `remove.rs` | the merged face (or hole) | 0 |
//! | [`Mesh::remove_edge_allowing_bridge`] | `remove.rs` | the merged face, or the holes | as `remove_edge` / `remove_face` |
//! | [`Mesh::merge_faces`] | `remove.rs` | the merged face | 0 |
//! | [`Mesh::remove_vertex`] | `remove.rs` | the merged face | 0 |
//! | [`Mesh::remove_face`] | `holes.rs` | the holes now covering it | −1 + edges removed − vertices removed |
//! | [`Mesh::fill_hole`] | `holes.rs` | the new face | +1 |
//! | [`Mesh::fill_hole_triangulated`] | `triangulate.rs` | the triangles | +1 |
//! | [`Mesh::triangulate`] | `triangulate.rs` | the triangles | 0 |
//! | [`Mesh::triangulate_all`] | `triangulate.rs` | faces left as they were | 0 |
//! | [`Mesh::extrude_face`] | `extrude.rs` | the side quads | 0 |
//! | [`Mesh::split_vertex`] | `vertex_split.rs` | the new half-edge `a → b` | 0 |
//! | [`Mesh::cut_path`] | `cut.rs` | the new holes | −1 (open path), 0 (closed) |
//! | [`Mesh::split_components`] | `components.rs` | one mesh per piece | — |
//! | [`Mesh::compact`] | `compact.rs` | old → new key maps | 0 |
//!
//! # Check, then commit
//!
//! Every operator `x` has a twin `check_x` taking the same arguments that
//! returns `Ok(())` exactly when `x` would succeed and never changes the
//! mesh. Inside, `x` runs a private planning phase (`&self`: gather every
//! element into role-named locals named after the doc diagram, and refuse
//! with [`Error::Refused`] or [`Error::StaleKey`]); then a commit phase
//! that cannot fail, written through one `Writer` (the mesh's link
//! mutators and slot births and deaths, recording or not as the
//! `journaled!` macro chose once for the call); then the attribute rules; then, in debug
//! builds, [`Mesh::validate`]. On any error the mesh is exactly as it was.
//!
//! # Attribute rules per operator
//!
//! Every column of every arena runs its rule ([`attr::Rule`](crate::attr::Rule)).
//! Where elements merge, **the surviving element is always the first
//! contributor**, then the others in the order listed below, so
//! [`KeepFirst`](crate::attr::KeepFirst) keeps the survivor's value:
//!
//! - **split_edge** at `t`: new vertex = `interpolate(a: 1−t, b: t)`; the old
//!   edge splits into its two halves with shares `1−t` (the half at `b`) and
//!   `t` (the half at `a`); corner values (half-edge columns: a half-edge's
//!   value belongs to the corner at its origin) of the new corners are
//!   interpolated along the edge, the old corners keep theirs.
//! - **split_face**, **poke_face**, **triangulate**: the face splits; each
//!   piece's share is its area when positions are present (equal shares
//!   otherwise). New edges get `interpolate` of nothing (absent for
//!   [`Interpolate`](crate::attr::Interpolate)). A new corner copies the
//!   corner of the same vertex in the old face; the centre of `poke_face`
//!   interpolates all corners with equal weights (positions: the centroid).
//! - **collapse_edge** (`a` into `b`): `b = merge(b: 1, a: 0)`
//!   (`collapse_edge_at` takes `t`: `merge(b: t, a: 1−t)`); where a triangle
//!   disappears its side at `b` is kept and merges with its side at `a`
//!   (`merge(kept: ½, removed: ½)`), and the triangle's values merge into
//!   the face that receives the kept side (`merge(that face: 1, triangle:
//!   0)`: conserved totals are kept, interpolated values unchanged).
//!   **collapse_edge_to** `(h, p)`: the same with `t` the projection of `p`
//!   on the edge (clamped to 0..=1), and the position column set to `p`.
//!   Corners, in all three: on each side of the edge that is a face,
//!   `merge(b's corner: t, a's corner: 1−t)` goes to every corner of the
//!   wedges (fans of equal values) at `a` and `b` that hold that side's
//!   corners; other wedges keep their values, so a UV seam stays a seam.
//! - **flip_edge**: both faces merge (`merge(face of h: ½, face of twin: ½)`)
//!   and split again (equal shares); the edge keeps its values; the two new
//!   corners copy the corners they replace at the same vertex.
//! - **remove_edge**: `merge(face of the first half-edge: ½, other face: ½)`,
//!   kept in the first; **merge_faces** `(f, g)`: `merge(f: ½, g: ½)`;
//!   **remove_vertex**: `merge` of the faces around the vertex, equal
//!   weights, in ring order from the face of its first outgoing half-edge
//!   (the kept one). Removed edges and vertices lose their values.
//! - **remove_face**: the face's values are dropped (it becomes a hole).
//!   **fill_hole**: the new face gets `interpolate` of nothing.
//!
//! - **extrude_face**: new corners `interpolate` the corners below them;
//!   side faces, new edges and corners get `interpolate` of nothing.
//! - **split_vertex**: the new vertex is `interpolate(b: 1)`; new edges,
//!   faces and corners get `interpolate` of nothing.
//! - **cut_path**: a vertex copy is `interpolate` of the original; each cut
//!   edge splits into its two copies with equal shares.
//!
//! With a conserved rule (sum on merge, share on split, nothing from
//! interpolate), totals over faces (holes excluded) are kept by every
//! operator except `remove_face` and `remove_edge` on a boundary edge, where
//! a face is deleted; totals over vertices by every operator except
//! `remove_vertex` and `remove_face`, which delete vertices. Edge values
//! merge where two edges become one (a disappearing triangle) and split
//! where one becomes two (`split_edge`, `cut_path`); an edge that is removed
//! takes its value with it. The model tests (`tests/ops_model.rs`) check
//! face and vertex totals after every step.
//!
//! # Writing your own
//!
//! The reflecting setters in [`link`](crate::link) edit raw links; check the
//! result with [`RawEdit::validate`](crate::link::RawEdit::validate).

mod collapse;
mod compact;
mod components;
mod cut;
pub(crate) mod ear_clip;
mod extrude;
mod flip;
mod holes;
mod remove;
mod split;
mod triangulate;
mod vertex_split;

pub use compact::KeyMaps;

use crate::error::{Error, Refusal};
use crate::journal::Journaling;
use crate::keys::AnyKey;
use crate::layout::{Eid, Fid, HalfedgeRecord, Hid};
use crate::mesh::{Mesh, Writer};
use crate::vec3::{newell_edge, norm};

/// A refusal error.
#[inline]
pub(crate) fn refuse(op: &'static str, key: impl Into<AnyKey>, reason: Refusal) -> Error {
    Error::Refused {
        op,
        key: key.into(),
        reason,
    }
}

/// What [`Mesh::remove_edge_raw`] did to the faces.
pub(crate) struct EdgeRemoval {
    /// A face that was freed (merged into the survivor, or emptied).
    pub(crate) freed_face: Option<Fid>,
    /// A face made for the second loop when one loop split in two.
    pub(crate) new_face: Option<Fid>,
}

impl Mesh {
    /// [`Writer::split_face_raw`] in journaling mode `J`, for code that
    /// holds no writer (the remesher, with no journal).
    #[inline]
    pub(crate) fn split_face_raw<J: Journaling>(
        &mut self,
        pa: Hid,
        ha: Hid,
        pb: Hid,
        hb: Hid,
    ) -> (Hid, Fid) {
        self.writer::<J>().split_face_raw(pa, ha, pb, hb)
    }

    /// Number of half-edges in the loop of face `f`.
    #[inline]
    pub(crate) fn face_degree(&self, f: Fid) -> usize {
        self.face_halfedges(f).count()
    }

    /// Twice the vector area (Newell) of the `next` cycle through `start`.
    pub(crate) fn loop_normal(&self, start: Hid) -> Option<[f64; 3]> {
        let p = self.position_slots()?;
        let mut n = [0.0; 3];
        for h in crate::circulate::FaceHalfedges::from_halfedge(self, start) {
            let a = p[self.origin(h).index()];
            let b = p[self.dest(h).index()];
            newell_edge(&mut n, a, b);
        }
        Some(n)
    }

    /// Area of the `next` cycle through `start`, if positions exist.
    pub(crate) fn loop_area(&self, start: Hid) -> Option<f64> {
        self.loop_normal(start).map(|n| 0.5 * norm(n))
    }

    /// Split face `src`'s attribute values over `pieces` (faces, `src` among
    /// them or not), by area when positions give a positive total, else in
    /// equal shares.
    pub(crate) fn split_face_values(&mut self, src: Fid, pieces: &[Fid]) {
        if self.attrs.face.cols.is_empty() || pieces.is_empty() {
            return;
        }
        let areas: Option<Vec<f64>> = pieces
            .iter()
            .map(|&f| self.loop_area(self.face_halfedge(f)))
            .collect();
        let total: f64 = areas.as_ref().map_or(0.0, |a| a.iter().sum());
        let shares: Vec<(usize, f64)> = match areas {
            Some(a) if total > 0.0 && total.is_finite() => pieces
                .iter()
                .zip(a)
                .map(|(&f, x)| (f.index(), x / total))
                .collect(),
            _ => pieces
                .iter()
                .map(|&f| (f.index(), 1.0 / pieces.len() as f64))
                .collect(),
        };
        self.attrs.face.split(src.index(), &shares);
    }

    /// The half-edge before `h` in its face: a few steps along the face
    /// when it is small (triangles, quads), else by turning around
    /// `origin(h)` ([`prev`](Mesh::prev)).
    #[inline]
    pub(crate) fn prev_fast(&self, h: Hid) -> Hid {
        let mut x = self.next(h);
        for _ in 0..6 {
            let n = self.next(x);
            if n == h {
                return x;
            }
            x = n;
        }
        self.prev(h)
    }
}

impl<J: Journaling> Writer<'_, J> {
    /// The end of one operator: validate in debug builds (see
    /// [`Mesh::debug_validate`]), then close the journal's open step, if a
    /// journal records and no step group or transaction is open
    /// ([`Mesh::end_edit`]).
    #[inline(always)]
    pub(crate) fn end_op(&mut self) {
        self.bump_revision();
        self.debug_validate();
        if J::ON {
            self.end_edit();
        }
    }

    /// Give every half-edge of the `next` cycle through `start` the face `f`
    /// and point `f` at `start`. When `f` is a hole, every vertex on the
    /// cycle is pointed at its half-edge there (rule 11: its corners are
    /// now on the boundary).
    pub(crate) fn relabel_loop(&mut self, start: Hid, f: Fid) {
        let hole = self.is_hole(f);
        let mut h = start;
        for _ in 0..self.he.len() {
            self.he_mut(h).face = f;
            if hole {
                let o = self.he[h].origin;
                *self.v_halfedge_mut(o) = h;
            }
            h = self.he[h].next;
            if h == start {
                break;
            }
        }
        self.set_face_link(f, start);
    }

    /// Cut face `f` with a new edge from `a = origin(ha)` to `b = origin(hb)`,
    /// where `pa` and `pb` are the half-edges before `ha` and `hb` in `f`.
    /// The new half-edge `a → b` (returned first) lies in a new face (returned
    /// second) with `hb .. pa`; its twin stays in `f` with `ha .. pb`. Corner
    /// and edge rules run; the face rule is the caller's.
    pub(crate) fn split_face_raw(&mut self, pa: Hid, ha: Hid, pb: Hid, hb: Hid) -> (Hid, Fid) {
        let f = self.face_of(ha);
        let a = self.origin(ha);
        let b = self.origin(hb);
        let e = self.alloc_edge();
        let g = self.alloc_face(false);
        let [n0, n1] = e.halfedges();
        *self.he_mut(n0) = HalfedgeRecord {
            origin: a,
            next: hb,
            face: g,
        };
        *self.he_mut(n1) = HalfedgeRecord {
            origin: b,
            next: ha,
            face: f,
        };
        self.set_next(pa, n0);
        self.set_next(pb, n1);
        self.relabel_loop(n0, g);
        self.set_face_link(f, n1);
        self.attrs.edge.interpolate(e.index(), &[]);
        self.attrs.halfedge.copy(ha.index(), n0.index());
        self.attrs.halfedge.copy(hb.index(), n1.index());
        (n0, g)
    }

    /// Take edge `e` out of the `next` structure. Where its two sides lie in
    /// different faces they merge and `survivor` (one of them) is kept;
    /// where they lie in the same loop it splits in two (a new face with the
    /// same hole flag takes the second), and vertices left without edges are
    /// removed. Attribute values of the freed elements are dropped: run the
    /// merge rules before. Must be called on a consistent mesh.
    pub(crate) fn remove_edge_raw(&mut self, e: Eid, survivor: Fid) -> EdgeRemoval {
        let [x, y] = e.halfedges();
        let (fx, fy) = (self.face_of(x), self.face_of(y));
        let (a, b) = (self.origin(x), self.origin(y));
        let (nx, ny) = (self.next(x), self.next(y));
        let mut out = EdgeRemoval {
            freed_face: None,
            new_face: None,
        };
        if nx == y && ny == x {
            // An isolated edge: everything goes.
            self.free_face(fx);
            out.freed_face = Some(fx);
            self.free_vertex(a);
            self.free_vertex(b);
            self.free_edge(e);
            return out;
        }
        if nx == y {
            // b has degree 1: ... px -> x -> y -> ny ...
            let px = self.prev_fast(x);
            self.set_next(px, ny);
            self.free_vertex(b);
            if self.v_halfedge[a] == x {
                *self.v_halfedge_mut(a) = ny;
            }
            let fl = self.face_halfedge(fx);
            if fl == x || fl == y {
                self.set_face_link(fx, ny);
            }
            self.free_edge(e);
            return out;
        }
        if ny == x {
            let py = self.prev_fast(y);
            self.set_next(py, nx);
            self.free_vertex(a);
            if self.v_halfedge[b] == y {
                *self.v_halfedge_mut(b) = nx;
            }
            let fl = self.face_halfedge(fy);
            if fl == x || fl == y {
                self.set_face_link(fy, nx);
            }
            self.free_edge(e);
            return out;
        }
        let px = self.prev_fast(x);
        let py = self.prev_fast(y);
        self.set_next(px, ny);
        self.set_next(py, nx);
        if self.v_halfedge[a] == x {
            *self.v_halfedge_mut(a) = ny;
        }
        if self.v_halfedge[b] == y {
            *self.v_halfedge_mut(b) = nx;
        }
        if fx != fy {
            let gone = if survivor == fx { fy } else { fx };
            self.relabel_loop(nx, survivor);
            self.free_face(gone);
            out.freed_face = Some(gone);
        } else {
            self.set_face_link(fx, nx);
            let g = self.alloc_face(self.is_hole(fx));
            self.relabel_loop(ny, g);
            self.attrs.face.copy(fx.index(), g.index());
            out.new_face = Some(g);
        }
        self.free_edge(e);
        out
    }
}
