//! What an algorithm keeps: boundaries, seams, feature edges and pinned
//! vertices, in one vocabulary for every algorithm that moves vertices or
//! edits edges, and the one classifier that turns them into vertex kinds
//! and edge bits (the idea of pmp-library's `features.cpp`, typed).
//!
//! **Lines.** Three kinds of edge form *lines*: the **boundary** (an edge
//! beside a hole), the **seams** (an edge across which a corner column's
//! values differ, such as a UV seam; decimation adds the borders of a
//! material column) and the **features** (an edge whose faces meet at more
//! than [`Constraints::feature_angle`], or one marked `true` in the edge
//! column [`Constraints::features`]). [`Keep`] says how the boundary and
//! the seams are kept, one meaning each:
//!
//! - **lock**: the line's vertices do not move and its edges stay (neither
//!   split nor collapsed);
//! - **slide**: the line's vertices stay on the input's line (the polyline
//!   of its edges) and move only along it; a vertex where the line turns
//!   by more than the feature angle (45° without one), ends, or meets
//!   another line is a *corner* and does not move;
//! - **free**: no constraint; the line's edges are like any other.
//!
//! Feature lines are held as each algorithm needs: decimation locks them
//! (their vertices never move); remeshing, smoothing and fairing slide
//! along them. **Pinned** vertices ([`Constraints::pinned`], a boolean
//! vertex column, `true` = pinned) never move, in every algorithm.
//!
//! | algorithm | boundary default | seams default |
//! |---|---|---|
//! | [`decimate`](super::decimate::decimate) | slide | slide |
//! | [`remesh`](super::remesh::remesh) | slide | slide (the resampled corner columns) |
//! | [`smooth`](super::smooth::smooth) | lock | free |
//! | [`fair`](super::fair::fair) | lock | free |
//!
//! Each of those options structs carries the same five fields
//! (`boundary`, `seams`, `feature_angle`, `features`, `pinned`) with the
//! meanings of [`Constraints`]; [`Constraints`] is what the classifier
//! reads, and what an algorithm added later takes.
//!
//! **The classifier** (crate-internal) gives every vertex a kind, *free*,
//! *line* (on exactly two kept line edges that do not turn at it: it may
//! slide) or *fixed* (pinned, on a locked line, a corner, an end or a
//! crossing of lines), and every edge two bits: *line* (a sliding line)
//! and *locked* (a locked line, or an edge at a pinned vertex). One pass
//! over the edges and one over the vertices: O(V + E), a byte a vertex
//! and two bits an edge.
//!
//! ```
//! use meshloom::algo::{Constraints, Keep};
//! let c = Constraints { boundary: Keep::Lock, ..Constraints::default() };
//! assert_eq!(c.seams, Keep::Slide);
//! assert_eq!("slide".parse::<Keep>()?, Keep::Slide);
//! assert_eq!(Keep::WORDS, &["free", "slide", "lock"]);
//! # Ok::<(), meshloom::choice::UnknownChoice>(())
//! ```

mod polyline;

pub(crate) use polyline::Polylines;

use crate::attr::{AttrView, EdgeAttr, VertexAttr};
use crate::error::{Error, Result};
use crate::keys::{EdgeKey, VertexKey};
use crate::layout::{Eid, Hid, Vid};
use crate::mesh::Mesh;
use crate::store::ErasedColumn;
use crate::vec3::{cross, dot, sub, V3};

/// `constraints()` and `with_constraints(c)` for an options struct with
/// the five constraint fields (`boundary`, `seams`, `feature_angle`,
/// `features`, `pinned`) and their setters: written once for decimate,
/// remesh, smooth and fair (the caller imports `Constraints`).
macro_rules! constrained {
    ($ty:ident) => {
        impl $ty {
            /// The constraints these options name.
            pub fn constraints(&self) -> Constraints {
                Constraints {
                    boundary: self.boundary,
                    seams: self.seams,
                    feature_angle: self.feature_angle,
                    features: self.features.clone(),
                    pinned: self.pinned.clone(),
                }
            }

            /// These options with the five fields of `c` (the setters
            /// `boundary`, `seams`, `feature_angle`, `features` and
            /// `pinned` in one): the inverse of
            /// [`constraints`](Self::constraints).
            #[must_use]
            pub fn with_constraints(self, c: Constraints) -> Self {
                self.boundary(c.boundary)
                    .seams(c.seams)
                    .feature_angle(c.feature_angle)
                    .features(c.features)
                    .pinned(c.pinned)
            }
        }
    };
}
pub(crate) use constrained;

/// How a kind of line (the boundary, the seams) is kept (see the
/// [module](self) for the three meanings).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Default)]
pub enum Keep {
    /// No constraint: the line's edges are like any other.
    Free,
    /// The line's vertices stay on the input's line, moving only along
    /// it; its corners and ends do not move.
    #[default]
    Slide,
    /// The line's vertices do not move and its edges stay.
    Lock,
}

crate::choice::choices!(Keep {
    Free = "free",
    Slide = "slide",
    Lock = "lock",
});

/// What an algorithm keeps: the boundary, the seams, the feature edges
/// and the pinned vertices (see the [module](self)). The options of
/// [`decimate`](super::decimate::decimate), [`remesh`](super::remesh::remesh),
/// [`smooth`](super::smooth::smooth) and [`fair`](super::fair::fair) carry
/// these five fields under the same names (with their own defaults for
/// `boundary` and `seams`) and give them back through their
/// `constraints()`.
///
/// ```
/// use meshloom::algo::{Constraints, Keep};
/// use meshloom::algo::smooth::SmoothOptions;
/// let o = SmoothOptions::default().boundary(Keep::Slide);
/// let c: Constraints = o.constraints();
/// assert_eq!((c.boundary, c.seams), (Keep::Slide, Keep::Free));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Constraints {
    /// The boundary loops (default [`Keep::Slide`]).
    pub boundary: Keep,
    /// The seams: edges across which a corner column's values differ
    /// (default [`Keep::Slide`]). Which corner columns count is the
    /// algorithm's (every one, or the ones it resamples).
    pub seams: Keep,
    /// Edges whose faces meet at more than this dihedral angle (radians)
    /// are feature edges; it is also the turn that makes a line's vertex
    /// a corner (45° without it). Default: none.
    pub feature_angle: Option<f64>,
    /// A boolean edge column: edges whose value is `true` are feature
    /// edges. Default: none.
    pub features: Option<EdgeAttr<bool>>,
    /// A boolean vertex column: vertices whose value is `true` are pinned
    /// and never move. Default: none.
    pub pinned: Option<VertexAttr<bool>>,
}

impl Default for Constraints {
    fn default() -> Self {
        Constraints {
            boundary: Keep::Slide,
            seams: Keep::Slide,
            feature_angle: None,
            features: None,
            pinned: None,
        }
    }
}

impl Constraints {
    /// Refuse a feature angle that is not finite.
    pub(crate) fn check(&self, algorithm: &'static str) -> Result<()> {
        match self.feature_angle {
            Some(a) if !a.is_finite() => Err(Error::Unsuitable {
                algorithm,
                key: None,
                reason: format!("feature_angle {a} is not finite"),
            }),
            _ => Ok(()),
        }
    }
}

/// The vertex kinds the classifier gives (a byte a vertex slot).
pub(crate) const FREE: u8 = 0;
/// On exactly two sliding line edges that do not turn at it.
pub(crate) const LINE: u8 = 1;
/// Never moves: pinned, on a locked line, a corner, end or crossing.
pub(crate) const FIXED: u8 = 2;

/// One bit an edge slot.
#[derive(Clone, Debug, Default)]
pub(crate) struct EdgeBits(Vec<u64>);

impl EdgeBits {
    /// Room for `n` edge slots, every bit clear.
    pub(crate) fn new(n: usize) -> EdgeBits {
        EdgeBits(vec![0; n.div_ceil(64)])
    }

    #[inline(always)]
    pub(crate) fn get(&self, e: Eid) -> bool {
        let i = e.index();
        self.0[i / 64] >> (i % 64) & 1 == 1
    }

    #[inline(always)]
    fn set(&mut self, e: Eid) {
        let i = e.index();
        self.0[i / 64] |= 1 << (i % 64);
    }
}

/// The classifier's result over the whole mesh.
pub(crate) struct Classified {
    /// Per vertex slot: [`FREE`], [`LINE`] or [`FIXED`] (dead slots: fixed).
    pub(crate) kinds: Vec<u8>,
    /// Per edge slot: on a sliding line.
    pub(crate) lines: EdgeBits,
    /// Per edge slot: neither split nor collapsed (a locked line, or an
    /// edge at a pinned vertex). Filled only when the caller asked for
    /// edge bits ([`LineSources::edge_bits`]).
    pub(crate) locked: EdgeBits,
    /// Live vertices of kind [`FIXED`].
    pub(crate) fixed: usize,
    /// Edges found to be features (by angle or column; boundary edges are
    /// never features).
    pub(crate) feature_edges: usize,
}

/// What an algorithm adds to the [`Constraints`]: where its seams come
/// from and how it holds feature lines.
pub(crate) struct LineSources<'m> {
    /// Corner columns whose discontinuities are seams.
    pub(crate) seam_columns: Vec<&'m dyn ErasedColumn>,
    /// A face column whose borders are seams too (decimation's material).
    pub(crate) material: Option<&'m dyn ErasedColumn>,
    /// How feature lines are held: [`Keep::Lock`] or [`Keep::Slide`].
    pub(crate) features: Keep,
    /// Whether the caller reads the edge bits; when it does not and no
    /// line can slide, the pass over the edges is skipped.
    pub(crate) edge_bits: bool,
}

impl<'m> LineSources<'m> {
    /// Every corner column of `mesh` as a seam source, features held as
    /// `features`, edge bits as asked.
    pub(crate) fn all_corner_columns(mesh: &'m Mesh, features: Keep, edge_bits: bool) -> Self {
        LineSources {
            seam_columns: mesh
                .attrs()
                .halfedge
                .cols
                .iter()
                .map(|(_, c)| &**c)
                .collect(),
            material: None,
            features,
            edge_bits,
        }
    }
}

/// How one edge is kept.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct EdgeClass {
    /// On a sliding line.
    pub(crate) line: bool,
    /// On a locked line: its ends are fixed.
    pub(crate) lock: bool,
    /// A feature edge.
    pub(crate) feature: bool,
}

impl EdgeClass {
    #[inline(always)]
    fn keep(&mut self, k: Keep) {
        match k {
            Keep::Free => {}
            Keep::Slide => self.line = true,
            Keep::Lock => self.lock = true,
        }
    }
}

/// Per-vertex state while classifying: the count of sliding line edges
/// (saturating) and two flags.
const COUNT: u8 = 0x3f;
const FIX: u8 = 0x40;
const PIN: u8 = 0x80;

/// The one classifier: [`Constraints`] and an algorithm's
/// [`LineSources`] read against a mesh. [`Classifier::classify`] covers
/// the whole mesh; [`Classifier::edge`] and [`Classifier::vertex`] answer
/// for one element from its neighbourhood (the same answers), for work
/// that must cost what a region costs.
pub(crate) struct Classifier<'m> {
    mesh: &'m Mesh,
    pos: &'m [V3],
    boundary: Keep,
    seams: Keep,
    features: Keep,
    seam_columns: Vec<&'m dyn ErasedColumn>,
    material: Option<&'m dyn ErasedColumn>,
    feature_column: Option<AttrView<'m, EdgeKey, bool>>,
    cos_feature: Option<f64>,
    corner_cos: f64,
    pinned: Option<AttrView<'m, VertexKey, bool>>,
    edge_bits: bool,
}

impl<'m> Classifier<'m> {
    /// Read `c` and `sources` against `mesh` (positions `pos`).
    ///
    /// # Errors
    /// The errors of a column handle ([`Error::AttributeHandle`]).
    pub(crate) fn new(
        mesh: &'m Mesh,
        pos: &'m [V3],
        c: &Constraints,
        sources: LineSources<'m>,
    ) -> Result<Classifier<'m>> {
        let feature_column = match &c.features {
            None => None,
            Some(h) => Some(mesh.attr_view(h)?),
        };
        let pinned = match &c.pinned {
            None => None,
            Some(h) => Some(mesh.attr_view(h)?),
        };
        let seams_on = c.seams != Keep::Free;
        Ok(Classifier {
            mesh,
            pos,
            boundary: c.boundary,
            seams: c.seams,
            features: sources.features,
            seam_columns: if seams_on {
                sources.seam_columns
            } else {
                Vec::new()
            },
            material: sources.material.filter(|_| seams_on),
            feature_column,
            cos_feature: c.feature_angle.map(f64::cos),
            corner_cos: c.feature_angle.unwrap_or(std::f64::consts::FRAC_PI_4).cos(),
            pinned,
            edge_bits: sources.edge_bits,
        })
    }

    /// Whether any edge away from the boundary can be a line.
    fn interior_lines(&self) -> bool {
        let seams = !self.seam_columns.is_empty() || self.material.is_some();
        let features = self.feature_column.is_some() || self.cos_feature.is_some();
        seams || (features && self.features != Keep::Free)
    }

    /// Whether the edges must be visited: edge bits asked for, or a line
    /// that can slide or lock away from the boundary.
    fn edge_pass(&self) -> bool {
        self.edge_bits || self.boundary == Keep::Slide || self.interior_lines()
    }

    /// Whether `v` is pinned.
    #[inline]
    pub(crate) fn pinned(&self, v: Vid) -> bool {
        self.pinned
            .as_ref()
            .is_some_and(|p| p.get(self.mesh.vkey(v)).copied() == Some(true))
    }

    /// How edge `e` is kept.
    #[inline]
    pub(crate) fn edge(&self, e: Eid) -> EdgeClass {
        let mesh = self.mesh;
        let [h, t] = e.halfedges();
        let mut out = EdgeClass::default();
        if mesh.in_hole(h) || mesh.in_hole(t) {
            out.keep(self.boundary);
            return out;
        }
        let seam = self.seam_columns.iter().any(|c| {
            !c.same(h.index(), mesh.next(t).index()) || !c.same(mesh.next(h).index(), t.index())
        });
        let material = self
            .material
            .is_some_and(|c| !c.same(mesh.face_of(h).index(), mesh.face_of(t).index()));
        if seam || material {
            out.keep(self.seams);
        }
        if self.is_feature(e, h, t) {
            out.feature = true;
            out.keep(self.features);
        }
        out
    }

    /// Whether the interior edge `e` (half-edges `h`, `t`) is a feature.
    #[inline]
    fn is_feature(&self, e: Eid, h: Hid, t: Hid) -> bool {
        if self
            .feature_column
            .as_ref()
            .is_some_and(|c| c.get(self.mesh.ekey(e)).copied() == Some(true))
        {
            return true;
        }
        let Some(cf) = self.cos_feature else {
            return false;
        };
        let (nh, nt) = (self.face_normal(h), self.face_normal(t));
        let l = (dot(nh, nh) * dot(nt, nt)).sqrt();
        l > 0.0 && dot(nh, nt) < cf * l
    }

    /// The normal of `h`'s face, unnormalised (twice the area vector for a
    /// triangle; Newell's sum for a polygon).
    fn face_normal(&self, h: Hid) -> V3 {
        let (mesh, pos) = (self.mesh, self.pos);
        let n1 = mesh.next(h);
        let n2 = mesh.next(n1);
        if mesh.next(n2) == h {
            let a = pos[mesh.origin(h).index()];
            let b = pos[mesh.origin(n1).index()];
            let c = pos[mesh.origin(n2).index()];
            return cross(sub(b, a), sub(c, a));
        }
        let mut n = [0.0; 3];
        for x in mesh.face_halfedges_from(h) {
            let p = pos[mesh.origin(x).index()];
            let q = pos[mesh.dest(x).index()];
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        n
    }

    /// Whether the two line edges at `v` (as `is_line` says) turn by more
    /// than the corner angle there (more or fewer than two: yes).
    fn corner(&self, v: Vid, is_line: impl Fn(Eid) -> bool) -> bool {
        let (mesh, pos) = (self.mesh, self.pos);
        let p = pos[v.index()];
        let mut dirs = [[0.0; 3]; 2];
        let mut n = 0;
        for o in mesh.outgoing(v) {
            if is_line(o.edge()) {
                if n == 2 {
                    return true;
                }
                dirs[n] = sub(pos[mesh.dest(o).index()], p);
                n += 1;
            }
        }
        if n < 2 {
            return true;
        }
        let (a, b) = (dirs[0], dirs[1]);
        let l = (dot(a, a) * dot(b, b)).sqrt();
        // Straight on: the directions point opposite ways (turn 0).
        l.is_nan() || l <= 0.0 || -dot(a, b) < self.corner_cos * l
    }

    /// The kind of vertex `v`, from its neighbourhood alone (what
    /// [`Classifier::classify`] gives it).
    pub(crate) fn vertex(&self, v: Vid) -> u8 {
        if self.pinned(v) {
            return FIXED;
        }
        if !self.edge_pass() {
            let held = self.boundary == Keep::Lock && self.mesh.on_boundary(v);
            return if held { FIXED } else { FREE };
        }
        let mut count = 0;
        for o in self.mesh.outgoing(v) {
            let c = self.edge(o.edge());
            if c.lock {
                return FIXED;
            }
            count += usize::from(c.line);
        }
        match count {
            0 => FREE,
            2 if !self.corner(v, |e| self.edge(e).line) => LINE,
            _ => FIXED,
        }
    }

    /// Every vertex's kind and every edge's bits.
    pub(crate) fn classify(&self) -> Classified {
        if !self.edge_pass() {
            return self.classify_vertices();
        }
        let mesh = self.mesh;
        let [nv, _, ne, _] = mesh.slot_counts();
        let mut state = vec![0u8; nv];
        if self.pinned.is_some() {
            for v in mesh.vids() {
                if self.pinned(v) {
                    state[v.index()] |= PIN;
                }
            }
        }
        let bits = if self.edge_pass() { ne } else { 0 };
        let mut lines = EdgeBits::new(bits);
        let mut locked = EdgeBits::new(bits);
        let mut feature_edges = 0;
        if self.edge_pass() {
            feature_edges = self.edge_states(&mut state, &mut lines, &mut locked);
        } else if self.boundary == Keep::Lock {
            for v in mesh.vids() {
                if mesh.on_boundary(v) {
                    state[v.index()] |= FIX;
                }
            }
        }
        let mut fixed = 0;
        for (i, s) in state.iter_mut().enumerate() {
            if !mesh.vertex_live(i) {
                *s = FIXED;
                continue;
            }
            let v = Vid::new(i as u32);
            *s = if *s & (FIX | PIN) != 0 {
                FIXED
            } else {
                match *s & COUNT {
                    0 => FREE,
                    2 if !self.corner(v, |e| lines.get(e)) => LINE,
                    _ => FIXED,
                }
            };
            fixed += usize::from(*s == FIXED);
        }
        Classified {
            kinds: state,
            lines,
            locked,
            fixed,
            feature_edges,
        }
    }

    /// [`classify`](Self::classify) when no edge is kept (no features, no
    /// seams, the boundary free to slide or move): one pass over the vertex
    /// slots, every vertex fixed or free.
    fn classify_vertices(&self) -> Classified {
        let mesh = self.mesh;
        let lock = self.boundary == Keep::Lock;
        let mut fixed = 0;
        let kinds = (0..mesh.vertex_slots())
            .map(|i| {
                let v = Vid::new(i as u32);
                let keep = !mesh.vertex_live(i)
                    || (lock && mesh.on_boundary(v))
                    || (self.pinned.is_some() && self.pinned(v));
                fixed += usize::from(keep && mesh.vertex_live(i));
                if keep {
                    FIXED
                } else {
                    FREE
                }
            })
            .collect();
        Classified {
            kinds,
            lines: EdgeBits::new(0),
            locked: EdgeBits::new(0),
            fixed,
            feature_edges: 0,
        }
    }

    /// The pass over the edges: line and locked bits, line counts and the
    /// fixed flag at their ends. Returns the feature edges found.
    fn edge_states(&self, state: &mut [u8], lines: &mut EdgeBits, locked: &mut EdgeBits) -> usize {
        let mesh = self.mesh;
        let mut feature_edges = 0;
        for e in mesh.eids() {
            let c = self.edge(e);
            let [h, t] = e.halfedges();
            let (a, b) = (mesh.origin(h).index(), mesh.origin(t).index());
            feature_edges += usize::from(c.feature);
            if c.line {
                lines.set(e);
                for i in [a, b] {
                    if state[i] & COUNT < COUNT {
                        state[i] += 1;
                    }
                }
            }
            if c.lock {
                state[a] |= FIX;
                state[b] |= FIX;
            }
            if c.lock || (state[a] | state[b]) & PIN != 0 {
                locked.set(e);
            }
        }
        feature_edges
    }
}
