//! Before the first collapse: check the input, classify every vertex and
//! edge, fill the quadrics. Nothing here changes the mesh; every error the
//! decimator can return (but cancellation) comes from here.

use super::attributes::AttrError;
use super::quadric::{Quadric, Q64};
use super::{DecimateOptions, Engine, Keep, ALGORITHM, FIXED, FREE, LINE};
use crate::error::{Error, Result};
use crate::keys::{AnyKey, ElementKind};
use crate::layout::{Eid, Hid, Vid};
use crate::mesh::Mesh;
use crate::vec3::{add, cross, dot, scale, sub, V3};

/// How much a plane across a kept line weighs, against the faces' own
/// (per squared edge length, as a face's plane weighs its area).
const LINE_WEIGHT: f64 = 10.0;

fn unsuitable(key: Option<AnyKey>, reason: String) -> Error {
    Error::Unsuitable {
        algorithm: ALGORITHM,
        key,
        reason,
    }
}

fn unit_normal(a: V3, b: V3, c: V3) -> (V3, f64) {
    let n = cross(sub(b, a), sub(c, a));
    let l = dot(n, n).sqrt();
    if l > 0.0 && l.is_finite() {
        (scale(n, 1.0 / l), 0.5 * l)
    } else {
        ([0.0; 3], 0.0)
    }
}

pub(super) fn prepare(mesh: &Mesh, options: &DecimateOptions) -> Result<Engine> {
    let pos = mesh.position_slots().ok_or(Error::NoPositions)?;
    // Triangles only.
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        let h = mesh.face_halfedge(f);
        if mesh.next(mesh.next(mesh.next(h))) != h {
            return Err(unsuitable(
                Some(mesh.fkey(f).into()),
                format!(
                    "face {} has {} sides; decimation needs triangles (triangulate first)",
                    mesh.fkey(f),
                    mesh.face_degree(f)
                ),
            ));
        }
    }
    if let Some(e) = options.max_error {
        if e.is_nan() || e < 0.0 {
            return Err(unsuitable(
                None,
                format!("max_error {e} is not a number ≥ 0"),
            ));
        }
    }
    for (name, v) in [
        ("max_normal_deviation", options.max_normal_deviation),
        ("min_quality", options.min_quality),
        ("feature_angle", options.feature_angle),
    ] {
        if let Some(x) = v {
            if !x.is_finite() {
                return Err(unsuitable(None, format!("{name} {x} is not finite")));
            }
        }
    }
    let [nv, _, ne, _] = mesh.slot_counts();
    // The unit box.
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in mesh.vids() {
        let p = pos[v.index()];
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let (centre, extent) = if lo[0] <= hi[0] {
        let ext = (0..3).map(|i| hi[i] - lo[i]).fold(0.0, f64::max);
        (scale(add(lo, hi), 0.5), ext)
    } else {
        ([0.0; 3], 1.0)
    };
    let scale_ = if extent > 0.0 && extent.is_finite() {
        extent
    } else {
        1.0
    };
    let inv = 1.0 / scale_;
    let unit = |p: V3| scale(sub(p, centre), inv);

    // Lines and locks.
    let mut lines = vec![0u64; ne.div_ceil(64)];
    let mut count = vec![0u8; nv];
    let mut fixed = vec![false; nv];
    let seam_cols = &mesh.attrs.halfedge.cols;
    let material = match &options.material {
        None => None,
        Some(name) => Some(
            mesh.attrs
                .face
                .find(name)
                .ok_or_else(|| Error::AttributeMissing {
                    kind: ElementKind::Face,
                    name: name.clone(),
                })?,
        ),
    };
    let feature_col = match &options.feature_edges {
        None => None,
        Some(h) => Some(mesh.attr_view(h)?),
    };
    let cos_feature = options.feature_angle.map(f64::cos);
    for e in mesh.eids() {
        let [h, t] = e.halfedges();
        let (hole_h, hole_t) = (mesh.in_hole(h), mesh.in_hole(t));
        let (a, b) = (mesh.origin(h), mesh.origin(t));
        let mut line = None;
        if hole_h || hole_t {
            line = Some(options.boundary);
        } else {
            let seam = options.seams != Keep::Free
                && seam_cols.iter().any(|(_, c)| {
                    !c.same(h.index(), mesh.next(t).index())
                        || !c.same(mesh.next(h).index(), t.index())
                });
            let mat = material.is_some_and(|i| {
                !mesh.attrs.face.cols[i]
                    .1
                    .same(mesh.face_of(h).index(), mesh.face_of(t).index())
            });
            if seam || mat {
                line = Some(options.seams);
            }
            let mut feature = feature_col
                .as_ref()
                .is_some_and(|c| c.get(mesh.ekey(e)).copied() == Some(true));
            if let Some(cf) = cos_feature {
                let tri = |x: Hid| {
                    let n = mesh.next(x);
                    unit_normal(
                        pos[mesh.origin(x).index()],
                        pos[mesh.origin(n).index()],
                        pos[mesh.origin(mesh.next(n)).index()],
                    )
                    .0
                };
                if dot(tri(h), tri(t)) < cf {
                    feature = true;
                }
            }
            if feature {
                fixed[a.index()] = true;
                fixed[b.index()] = true;
            }
        }
        match line {
            None | Some(Keep::Free) => {}
            Some(Keep::Lock) => {
                fixed[a.index()] = true;
                fixed[b.index()] = true;
            }
            Some(Keep::Slide) => {
                let i = e.index();
                lines[i / 64] |= 1 << (i % 64);
                count[a.index()] = count[a.index()].saturating_add(1);
                count[b.index()] = count[b.index()].saturating_add(1);
            }
        }
    }
    if let Some(locked) = &options.locked {
        let view = mesh.attr_view(locked)?;
        for v in mesh.vids() {
            if view.get(mesh.vkey(v)).copied() == Some(true) {
                fixed[v.index()] = true;
            }
        }
    }
    let mut flags = vec![FIXED; nv];
    let mut n_fixed = 0;
    for v in mesh.vids() {
        let i = v.index();
        flags[i] = if fixed[i] {
            FIXED
        } else {
            match count[i] {
                0 => FREE,
                2 if !line_corner(mesh, pos, &lines, v) => LINE,
                _ => FIXED,
            }
        };
        n_fixed += usize::from(flags[i] == FIXED);
    }

    // Quadrics: each face's plane, weighted by its area, at its corners.
    let mut quadrics = vec![Quadric::default(); nv];
    for f in mesh.fids() {
        if mesh.is_hole(f) {
            continue;
        }
        let h0 = mesh.face_halfedge(f);
        let h1 = mesh.next(h0);
        let h2 = mesh.next(h1);
        let vs = [mesh.origin(h0), mesh.origin(h1), mesh.origin(h2)];
        let p = vs.map(|v| unit(pos[v.index()]));
        let (n, area) = unit_normal(p[0], p[1], p[2]);
        if area == 0.0 {
            continue;
        }
        let q = Q64::plane(n, -dot(n, p[0]), area).narrow();
        for v in vs {
            quadrics[v.index()].add_assign(&q);
        }
    }
    // Planes across kept lines, through the edge and perpendicular to each
    // face beside it, weighted by the squared length.
    for e in mesh.eids() {
        let i = e.index();
        if lines[i / 64] >> (i % 64) & 1 == 0 {
            continue;
        }
        add_line_planes(mesh, pos, &unit, e, &mut quadrics);
    }

    let attrs = AttrError::new(mesh, &options.attributes, &unit)?;
    Ok(Engine {
        quadrics,
        flags,
        lines,
        centre,
        inv_scale: inv,
        scale: scale_,
        attrs,
        fixed: n_fixed,
    })
}

/// A line turning by more than this at a vertex (cosine of 45°) makes the
/// vertex a corner of the line, which never moves.
const CORNER_COS: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Whether the two kept-line edges at `v` turn by more than 45° there (the
/// corner of a square's boundary): such a vertex is fixed, so the line's
/// corners stay sharp.
fn line_corner(mesh: &Mesh, pos: &[[f64; 3]], lines: &[u64], v: Vid) -> bool {
    let p = pos[v.index()];
    let mut dirs = [[0.0; 3]; 2];
    let mut n = 0;
    for o in mesh.outgoing(v) {
        let i = o.edge().index();
        if lines[i / 64] >> (i % 64) & 1 == 1 {
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
    // Straight on: the two directions point opposite ways.
    let (a, b) = (dirs[0], dirs[1]);
    let l = (dot(a, a) * dot(b, b)).sqrt();
    l.is_nan() || l <= 0.0 || -dot(a, b) < CORNER_COS * l
}

fn add_line_planes(
    mesh: &Mesh,
    pos: &[[f64; 3]],
    unit: &dyn Fn(V3) -> V3,
    e: Eid,
    quadrics: &mut [Quadric],
) {
    for x in e.halfedges() {
        if mesh.in_hole(x) {
            continue;
        }
        let n1 = mesh.next(x);
        let (a, b) = (mesh.origin(x), mesh.origin(n1));
        let c = mesh.origin(mesh.next(n1));
        let (pa, pb, pc) = (
            unit(pos[a.index()]),
            unit(pos[b.index()]),
            unit(pos[c.index()]),
        );
        let (n, _) = unit_normal(pa, pb, pc);
        let d = sub(pb, pa);
        let len2 = dot(d, d);
        let m = cross(d, n);
        let lm = dot(m, m).sqrt();
        if lm.is_nan() || lm <= 0.0 || len2.is_nan() || len2 <= 0.0 {
            continue;
        }
        let m = scale(m, 1.0 / lm);
        let q = Q64::plane(m, -dot(m, pa), LINE_WEIGHT * len2).narrow();
        quadrics[a.index()].add_assign(&q);
        quadrics[b.index()].add_assign(&q);
    }
}
