//! Welding one mesh instance: glTF has no connectivity, so a vertex is
//! split into one element per corner value (UV seam, normal crease), and
//! the reader joins the copies again.
//!
//! - **By `_VERTEX_ID`** (what meshloom writes): copies with the same ID
//!   are one vertex, and nothing else is joined, so meshloom's own files
//!   come back with their vertices, components and holes. Copies of one ID
//!   at different positions are an error.
//! - **By position** (every other file): copies at bit-identical positions
//!   are joined through the repair module's weld (`weld_vertices`), which
//!   keeps apart every group whose joining would make an edge or vertex
//!   non-manifold. So two parts that only touch at a point stay apart, and
//!   so do distinct vertices of one surface that share a position. Parts
//!   that share an edge are joined (as the faces of a box split at its
//!   seams must be). Triangles with two corners at one position (no area)
//!   are dropped first. The counts go to the read's [`RepairReport`]:
//!   `welded_vertices`, `weld_refused`, `degenerate_faces`.
//!
//! [`RepairReport`]: crate::repair::RepairReport

use std::collections::HashMap;

use super::super::error::{Error, Location};
use super::read::header;
use super::scene::Instance;
use crate::build::Polygons;
use crate::repair::{repair_with, RepairOptions};

/// An instance's vertices after welding.
pub(super) struct Welded {
    /// The welded vertex of each instance vertex.
    pub(super) rep: Vec<u32>,
    /// The welded vertices' positions.
    pub(super) positions: Vec<[f64; 3]>,
    /// Whether each triangle is kept (not degenerate).
    pub(super) keep: Vec<bool>,
    /// Instance vertices joined to an earlier one by position.
    pub(super) welded: usize,
    /// Instance vertices left apart from a coincident one.
    pub(super) refused: usize,
    /// Triangles dropped for two corners at one position.
    pub(super) degenerate: usize,
}

/// Weld by `_VERTEX_ID` when the instance has them, else by position.
pub(super) fn weld(inst: &Instance) -> Result<Welded, Error> {
    match &inst.ids {
        Some(ids) if ids.len() == inst.positions.len() => by_id(inst, ids),
        _ => by_position(inst),
    }
}

fn bits(p: &[f64; 3]) -> [u64; 3] {
    p.map(f64::to_bits)
}

/// One vertex per ID; copies of an ID must agree on the position.
fn by_id(inst: &Instance, ids: &[u32]) -> Result<Welded, Error> {
    let mut of_id: HashMap<u32, u32> = HashMap::with_capacity(ids.len());
    let mut rep = Vec::with_capacity(ids.len());
    let mut positions: Vec<[f64; 3]> = Vec::new();
    for (v, (&id, p)) in ids.iter().zip(&inst.positions).enumerate() {
        let r = *of_id.entry(id).or_insert_with(|| {
            positions.push(*p);
            (positions.len() - 1) as u32
        });
        if bits(&positions[r as usize]) != bits(p) {
            return Err(header(
                Location::whole(),
                format!(
                    "two glTF vertices with _VERTEX_ID {id} are at different positions ({:?} and {p:?}, instance vertex {v})",
                    positions[r as usize]
                ),
            ));
        }
        rep.push(r);
    }
    Ok(Welded {
        rep,
        positions,
        keep: vec![true; inst.triangles.len()],
        welded: 0,
        refused: 0,
        degenerate: 0,
    })
}

/// Join coincident copies where the result stays manifold.
fn by_position(inst: &Instance) -> Result<Welded, Error> {
    let n = inst.positions.len();
    let at_position = |v: u32| bits(&inst.positions[v as usize]);
    let keep: Vec<bool> = inst
        .triangles
        .iter()
        .map(|(c, _, _)| {
            let [a, b, d] = c.map(at_position);
            a != b && b != d && d != a
        })
        .collect();
    let mut p = Polygons {
        positions: inst.positions.clone(),
        offsets: vec![0],
        indices: Vec::new(),
    };
    for ((c, _, _), _) in inst.triangles.iter().zip(&keep).filter(|&(_, &k)| k) {
        p.indices.extend_from_slice(c);
        p.offsets.push(p.indices.len() as u32);
    }
    let weld_only = RepairOptions {
        weld_vertices: true,
        ..RepairOptions::none()
    };
    let (report, prov) = repair_with(&mut p, &weld_only, &[])
        .map_err(|e| header(Location::whole(), format!("welding by position: {e}")))?;
    // Corners keep their order (welding rebuilds no face): each names the
    // welded vertex of the instance vertex it named.
    let mut rep = vec![u32::MAX; n];
    let kept = inst.triangles.iter().zip(&keep).filter(|&(_, &k)| k);
    for (((c, _, _), _), w) in kept.zip(p.indices.chunks_exact(3)) {
        for k in 0..3 {
            rep[c[k] as usize] = w[k];
        }
    }
    // Vertices only degenerate triangles use: their own welded vertex, or
    // the one at their position.
    for (w, &s) in prov.vertex_source.iter().enumerate() {
        if let Some(r) = rep.get_mut(s as usize).filter(|r| **r == u32::MAX) {
            *r = w as u32;
        }
    }
    let mut by_bits: HashMap<[u64; 3], u32> = HashMap::new();
    for (w, q) in p.positions.iter().enumerate() {
        by_bits.entry(bits(q)).or_insert(w as u32);
    }
    for (v, r) in rep.iter_mut().enumerate() {
        if *r == u32::MAX {
            *r = by_bits.get(&bits(&inst.positions[v])).copied().unwrap_or(0);
        }
    }
    Ok(Welded {
        rep,
        positions: p.positions,
        degenerate: keep.iter().filter(|&&k| !k).count(),
        keep,
        welded: report.welded_vertices,
        refused: report.weld_refused,
    })
}
