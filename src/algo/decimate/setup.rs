//! Before the first collapse: check the input, classify every vertex and
//! edge (the shared classifier of [`constraints`](crate::algo::constraints)),
//! fill the quadrics. Nothing here changes the mesh; every error the
//! decimator can return (but cancellation) comes from here.

use super::attributes::AttrError;
use super::quadric::{Quadric, Q64};
use super::{DecimateOptions, Engine, Keep, ALGORITHM};
use crate::algo::constraints::{Classified, Classifier, EdgeBits, LineSources};
use crate::error::{Error, Result};
use crate::keys::{AnyKey, ElementKind};
use crate::layout::Eid;
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
    crate::algo::check_triangles(mesh, ALGORITHM, "decimation")?;
    check_numbers(options)?;
    let (centre, scale_) = unit_box(mesh, pos);
    let inv = 1.0 / scale_;
    let unit = |p: V3| scale(sub(p, centre), inv);
    let classified = classify(mesh, pos, options)?;
    let quadrics = quadrics(mesh, pos, &unit, &classified.lines);
    let attrs = AttrError::new(mesh, &options.attributes, &unit)?;
    Ok(Engine {
        quadrics,
        flags: classified.kinds,
        lines: classified.lines,
        centre,
        inv_scale: inv,
        scale: scale_,
        attrs,
        fixed: classified.fixed,
    })
}

/// Refuse a `max_error` below zero and a guard or feature angle that is
/// not finite.
fn check_numbers(options: &DecimateOptions) -> Result<()> {
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
    ] {
        if let Some(x) = v {
            if !x.is_finite() {
                return Err(unsuitable(None, format!("{name} {x} is not finite")));
            }
        }
    }
    options.constraints().check(ALGORITHM)
}

/// The centre of the bounding box and its largest extent (1 for an empty
/// or flat-to-a-point mesh): positions go to the unit box as
/// `(x − centre) / extent`.
fn unit_box(mesh: &Mesh, pos: &[V3]) -> (V3, f64) {
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
    let extent = if extent > 0.0 && extent.is_finite() {
        extent
    } else {
        1.0
    };
    (centre, extent)
}

/// The vertex kinds and sliding lines: the shared classifier, with every
/// corner column's discontinuities and the material column's borders as
/// seams, and feature lines locked.
fn classify(mesh: &Mesh, pos: &[V3], options: &DecimateOptions) -> Result<Classified> {
    let material = match &options.material {
        None => None,
        Some(name) => {
            Some(
                mesh.attrs()
                    .face
                    .find(name)
                    .ok_or_else(|| Error::AttributeMissing {
                        kind: ElementKind::Face,
                        name: name.clone(),
                    })?,
            )
        }
    };
    let mut sources = LineSources::all_corner_columns(mesh, Keep::Lock, true);
    sources.material = material.map(|i| &*mesh.attrs().face.cols[i].1);
    Ok(Classifier::new(mesh, pos, &options.constraints(), sources)?.classify())
}

/// Each face's plane, weighted by its area, at its corners; and planes
/// across the sliding lines.
fn quadrics(mesh: &Mesh, pos: &[V3], unit: &impl Fn(V3) -> V3, lines: &EdgeBits) -> Vec<Quadric> {
    let mut quadrics = vec![Quadric::default(); mesh.slot_counts()[0]];
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
        if lines.get(e) {
            add_line_planes(mesh, pos, unit, e, &mut quadrics);
        }
    }
    quadrics
}

fn add_line_planes(
    mesh: &Mesh,
    pos: &[[f64; 3]],
    unit: &impl Fn(V3) -> V3,
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
