//! Faces that visit a vertex twice, made simple without losing area.
//!
//! Two shapes are common. A *figure eight* touches itself at a vertex: it
//! is cut there into two faces, each of which is repaired again until
//! every piece is simple. A *bridged* face walks an edge both ways (an
//! outline and an inner loop joined by a bridge, as LightWave and other
//! exporters write a polygon with a hole): cutting it at the repeated
//! vertices would give the outline and the hole as two overlapping faces,
//! so it is triangulated in its plane as the weakly simple polygon it is
//! (ear clipping, the corners of one vertex never blocking each other),
//! and each triangle keeps the face's own corners. Where that fails
//! (no positions, or a face too degenerate to clip), it is cut like a
//! figure eight. Pieces of fewer than three corners (a spike `a b a`) have
//! no area and are left out.

use std::collections::HashMap;

use crate::ops::ear_clip::clip_ears;
use crate::vec3::newell;

/// The simple faces covering the face with corners `corners` (corner
/// indices; `vertex[c]` is corner `c`'s vertex, with no run of one vertex
/// left), as lists of its corners; `positions` may be empty.
pub(super) fn simple_pieces(
    corners: &[u32],
    vertex: &[u32],
    positions: &[[f64; 3]],
) -> Vec<Vec<u32>> {
    let mut done = Vec::new();
    let mut todo = vec![corners.to_vec()];
    while let Some(face) = todo.pop() {
        if face.len() < 3 {
            continue;
        }
        let Some((i, j)) = first_repeat(&face, vertex) else {
            done.push(face);
            continue;
        };
        if !positions.is_empty() && walks_an_edge_both_ways(&face, vertex) {
            if let Some(triangles) = triangulate(&face, vertex, positions) {
                done.extend(triangles);
                continue;
            }
        }
        // Cut at the vertex met twice: corners i..j and j..i round.
        todo.push(face[j..].iter().chain(&face[..i]).copied().collect());
        todo.push(face[i..j].to_vec());
    }
    done.reverse();
    done
}

/// The first two places `i < j` of one vertex in `face`.
fn first_repeat(face: &[u32], vertex: &[u32]) -> Option<(usize, usize)> {
    let mut seen: HashMap<u32, usize> = HashMap::with_capacity(face.len());
    for (j, &c) in face.iter().enumerate() {
        if let Some(&i) = seen.get(&vertex[c as usize]) {
            return Some((i, j));
        }
        seen.insert(vertex[c as usize], j);
    }
    None
}

/// Whether some side `a → b` of `face` has a side `b → a` in it too.
fn walks_an_edge_both_ways(face: &[u32], vertex: &[u32]) -> bool {
    let n = face.len();
    let side = |k: usize| (vertex[face[k] as usize], vertex[face[(k + 1) % n] as usize]);
    let mut sides: Vec<(u32, u32)> = (0..n).map(side).collect();
    sides.sort_unstable();
    (0..n).any(|k| {
        let (a, b) = side(k);
        sides.binary_search(&(b, a)).is_ok()
    })
}

/// The triangles of `face` by ear clipping in the plane of its Newell
/// normal, as lists of its corners; `None` when the clipper is stuck or
/// the triangles would use an edge more than once in one direction.
fn triangulate(face: &[u32], vertex: &[u32], positions: &[[f64; 3]]) -> Option<Vec<Vec<u32>>> {
    let pts: Vec<[f64; 3]> = face
        .iter()
        .map(|&c| positions[vertex[c as usize] as usize])
        .collect();
    let q = project(&pts)?;
    let key: Vec<u32> = face.iter().map(|&c| vertex[c as usize]).collect();
    let clipped = clip_ears(&q, &key, |l, r| key[l as usize] == key[r as usize]);
    if clipped.rest.len() != 3 {
        return None;
    }
    let mut triangles: Vec<[u32; 3]> = clipped.ears.iter().map(|e| [e[1], e[2], e[3]]).collect();
    let r = &clipped.rest;
    triangles.push([r[0], r[1], r[2]]);
    let mut sides: Vec<(u32, u32)> = Vec::with_capacity(3 * triangles.len());
    for t in &triangles {
        for k in 0..3 {
            sides.push((key[t[k] as usize], key[t[(k + 1) % 3] as usize]));
        }
    }
    sides.sort_unstable();
    if sides.windows(2).any(|w| w[0] == w[1]) {
        return None;
    }
    Some(
        triangles
            .iter()
            .map(|t| t.iter().map(|&i| face[i as usize]).collect())
            .collect(),
    )
}

/// The points in the plane of their Newell normal, turning
/// counter-clockwise; `None` for a face with no area.
fn project(pts: &[[f64; 3]]) -> Option<Vec<[f64; 2]>> {
    let n = newell(pts);
    let k = (0..3).max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))?;
    if n[k] == 0.0 || !n[k].is_finite() {
        return None;
    }
    let (u, v) = ((k + 1) % 3, (k + 2) % 3);
    let flip = n[k] < 0.0;
    Some(
        pts.iter()
            .map(|p| if flip { [p[v], p[u]] } else { [p[u], p[v]] })
            .collect(),
    )
}
