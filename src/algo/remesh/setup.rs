//! Everything the remesher checks and classifies before the first change:
//! the line and lock flags, the target lengths, the columns to resample.

use super::{unsuitable, Keep, RemeshOptions, Resample, Sizing, ALGORITHM};
use crate::algo::constraints::{Classifier, LineSources, FREE};
use crate::error::{Error, Result};
use crate::layout::Hid;
use crate::mesh::Mesh;
use crate::vec3::{cross, dist2, dot, sub, V3};

/// Edge flags.
pub(super) const E_LINE: u8 = 1;
pub(super) const E_LOCKED: u8 = 2;

/// A column to resample: its arena and index (the same in the input and
/// the copy).
pub(super) struct ResampleColumn {
    pub(super) name: String,
    pub(super) corner: bool,
    pub(super) index: usize,
}

/// Everything checked and classified before the first change.
pub(super) struct Setup {
    /// Per vertex slot of the input: target length.
    pub(super) sizing: Vec<f64>,
    pub(super) uniform: bool,
    pub(super) target_length: f64,
    /// Per vertex slot of the input: kind.
    pub(super) kinds: Vec<u8>,
    /// Per edge slot of the input: flags.
    pub(super) edges: Vec<u8>,
    pub(super) feature_edges: usize,
    pub(super) fixed: usize,
    pub(super) resample: Vec<ResampleColumn>,
}

impl Setup {
    /// Refuse a target that would make more than `max_faces` faces: each
    /// input triangle's area over that of an equilateral triangle whose
    /// side is its corners' shortest target length.
    pub(super) fn check_size(&self, mesh: &Mesh, max_faces: usize) -> Result<()> {
        let Some(pos) = mesh.position_slots() else {
            return Ok(());
        };
        let equilateral = 3f64.sqrt() / 4.0;
        let mut estimate = 0.0;
        for f in mesh.fids() {
            if mesh.is_hole(f) {
                continue;
            }
            let h = mesh.face_halfedge(f);
            let l = [h, mesh.next(h), mesh.prev_fast(h)]
                .map(|h| self.sizing[mesh.origin(h).index()])
                .into_iter()
                .fold(f64::INFINITY, f64::min);
            let n = triangle_normal(mesh, pos, h);
            let area = 0.5 * dot(n, n).sqrt();
            estimate += (area / (equilateral * l * l)).max(1.0);
        }
        if estimate > max_faces as f64 {
            return Err(Error::TooLarge {
                algorithm: ALGORITHM,
                estimate: estimate.min(u64::MAX as f64) as u64,
                limit: max_faces as u64,
                option: "max_faces",
            });
        }
        Ok(())
    }

    pub(super) fn new(mesh: &Mesh, options: &RemeshOptions) -> Result<Setup> {
        let pos = mesh.position_slots().ok_or(Error::NoPositions)?;
        crate::algo::check_triangles(mesh, ALGORITHM, "remeshing")?;
        let constraints = options.constraints();
        constraints.check(ALGORITHM)?;
        let resample = resample_columns(mesh, &options.resample)?;
        // The seams are those of the corner columns being resampled.
        let sources = LineSources {
            seam_columns: resample
                .iter()
                .filter(|c| c.corner)
                .map(|c| &*mesh.attrs().halfedge.cols[c.index].1)
                .collect(),
            material: None,
            features: Keep::Slide,
            edge_bits: true,
        };
        let classified = Classifier::new(mesh, pos, &constraints, sources)?.classify();
        let mut edges = vec![0u8; mesh.slot_counts()[2]];
        for e in mesh.eids() {
            let line = if classified.lines.get(e) { E_LINE } else { 0 };
            let locked = if classified.locked.get(e) {
                E_LOCKED
            } else {
                0
            };
            edges[e.index()] = line | locked;
        }
        let (sizing, uniform, target_length) =
            sizing(mesh, pos, options.sizing, &classified.kinds)?;
        Ok(Setup {
            sizing,
            uniform,
            target_length,
            kinds: classified.kinds,
            edges,
            feature_edges: classified.feature_edges,
            fixed: classified.fixed,
            resample,
        })
    }
}

/// Per input vertex slot, the target length; whether it is uniform; the
/// uniform length or the mean of the adaptive ones.
pub(super) fn sizing(
    mesh: &Mesh,
    pos: &[V3],
    sizing: Sizing,
    kinds: &[u8],
) -> Result<(Vec<f64>, bool, f64)> {
    let positive = |name: &str, x: f64| {
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(unsuitable(
                None,
                format!("{name} {x} is not a positive finite number"),
            ))
        }
    };
    let nv = mesh.slot_counts()[0];
    let mean = mean_edge_length(mesh, pos);
    let need_mean = |what: &str| {
        if mean > 0.0 && mean.is_finite() {
            Ok(mean)
        } else {
            Err(unsuitable(
                None,
                format!("the input has no edge of positive length to take the {what} from"),
            ))
        }
    };
    Ok(match sizing {
        Sizing::MeanEdgeLength => {
            let l = need_mean("mean edge length")?;
            (vec![l; nv], true, l)
        }
        Sizing::Uniform(l) => {
            let l = positive("the target edge length", l)?;
            (vec![l; nv], true, l)
        }
        Sizing::Adaptive {
            tolerance,
            min_length,
            max_length,
        } => {
            let tol = positive("the tolerance", tolerance)?;
            let lo = match min_length {
                Some(x) => positive("min_length", x)?,
                None => 0.25 * need_mean("default min_length")?,
            };
            let hi = match max_length {
                Some(x) => positive("max_length", x)?,
                None => 4.0 * need_mean("default max_length")?,
            };
            if lo > hi {
                return Err(unsuitable(
                    None,
                    format!("min_length {lo} is greater than max_length {hi}"),
                ));
            }
            let s = adaptive_sizing(mesh, kinds, tol, lo, hi)?;
            let n = mesh.vertex_count().max(1) as f64;
            let avg = mesh.vids().map(|v| s[v.index()]).sum::<f64>() / n;
            (s, false, avg)
        }
    })
}

/// The columns `what` names, checked.
pub(super) fn resample_columns(mesh: &Mesh, what: &Resample) -> Result<Vec<ResampleColumn>> {
    let position = mesh.attrs().position;
    let vertex = &mesh.attrs().vertex.cols;
    let corner = &mesh.attrs().halfedge.cols;
    let mut out = Vec::new();
    match what {
        Resample::Off => {}
        Resample::Linear => {
            for (i, (name, col)) in vertex.iter().enumerate() {
                if Some(i) != position && col.interpolates_linearly() {
                    out.push(ResampleColumn {
                        name: name.clone(),
                        corner: false,
                        index: i,
                    });
                }
            }
            for (i, (name, col)) in corner.iter().enumerate() {
                if col.interpolates_linearly() {
                    out.push(ResampleColumn {
                        name: name.clone(),
                        corner: true,
                        index: i,
                    });
                }
            }
        }
        Resample::Columns(names) => {
            for name in names {
                let (corner_col, index) = match mesh.attrs().vertex.find(name) {
                    Some(i) if Some(i) != position => (false, i),
                    Some(_) => {
                        return Err(unsuitable(
                            None,
                            "positions are projected, not resampled".into(),
                        ))
                    }
                    None => match mesh.attrs().halfedge.find(name) {
                        Some(i) => (true, i),
                        None => {
                            return Err(unsuitable(
                                None,
                                format!("no vertex or corner column named {name:?} to resample"),
                            ))
                        }
                    },
                };
                let col = if corner_col {
                    &corner[index].1
                } else {
                    &vertex[index].1
                };
                if !col.interpolates_linearly() {
                    return Err(unsuitable(
                        None,
                        format!(
                            "column {name:?} does not interpolate linearly; it cannot be resampled"
                        ),
                    ));
                }
                out.push(ResampleColumn {
                    name: name.clone(),
                    corner: corner_col,
                    index,
                });
            }
        }
    }
    Ok(out)
}

/// Whether the two triangles beside `h`'s edge have the same third
/// vertex (two triangles on the same three vertices, as in a closed
/// two-triangle "pillow"): splitting the edge would join the new vertex to
/// that apex twice.
pub(super) fn same_apex(mesh: &Mesh, h: Hid) -> bool {
    let t = h.twin();
    !mesh.is_hole(mesh.face_of(h))
        && !mesh.is_hole(mesh.face_of(t))
        && mesh.origin(mesh.prev_fast(h)) == mesh.origin(mesh.prev_fast(t))
}

/// Twice the area vector of the face of `h` (a triangle).
pub(super) fn triangle_normal(mesh: &Mesh, pos: &[V3], h: Hid) -> V3 {
    let n = mesh.next(h);
    let a = pos[mesh.origin(h).index()];
    let b = pos[mesh.origin(n).index()];
    let c = pos[mesh.origin(mesh.next(n)).index()];
    cross(sub(b, a), sub(c, a))
}

/// The mean length of the live edges.
pub(super) fn mean_edge_length(mesh: &Mesh, pos: &[V3]) -> f64 {
    let mut sum = 0.0;
    let mut n = 0usize;
    for e in mesh.eids() {
        let [h, t] = e.halfedges();
        sum += dist2(pos[mesh.origin(h).index()], pos[mesh.origin(t).index()]).sqrt();
        n += 1;
    }
    if n == 0 {
        0.0
    } else {
        sum / n as f64
    }
}

/// Target lengths from curvature (see the module docs).
pub(super) fn adaptive_sizing(
    mesh: &Mesh,
    kinds: &[u8],
    tol: f64,
    lo: f64,
    hi: f64,
) -> Result<Vec<f64>> {
    use crate::algo::curvature::{curvature, CurvatureOptions};
    let c = curvature(mesh, &CurvatureOptions::default())?;
    let nv = mesh.slot_counts()[0];
    // Curvature of lines and corners is not the surface's: leave it out.
    let mut k = vec![-1.0f64; nv];
    for v in mesh.vids() {
        let i = v.index();
        if kinds[i] == FREE && !mesh.on_boundary(v) {
            k[i] = c.max[i].abs().max(c.min[i].abs());
        }
    }
    // Two rounds of neighbour averaging (noise; and to give line vertices
    // the curvature of the surface beside them).
    for _ in 0..2 {
        let mut next = k.clone();
        for v in mesh.vids() {
            let (mut sum, mut n) = (0.0, 0.0);
            if k[v.index()] >= 0.0 {
                sum += k[v.index()];
                n += 1.0;
            }
            for o in mesh.outgoing(v) {
                let w = k[mesh.dest(o).index()];
                if w >= 0.0 {
                    sum += w;
                    n += 1.0;
                }
            }
            next[v.index()] = if n > 0.0 { sum / n } else { k[v.index()] };
        }
        k = next;
    }
    Ok(k.into_iter()
        .map(|c| {
            let h = if c <= 0.0 {
                hi
            } else {
                let r = 1.0 / c;
                if tol < r {
                    (6.0 * tol * r - 3.0 * tol * tol).sqrt()
                } else {
                    tol * 3f64.sqrt()
                }
            };
            h.clamp(lo, hi)
        })
        .collect())
}
