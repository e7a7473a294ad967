//! The binned SAH build: 16 bins of triangle centroids per axis, the split
//! of least estimated cost `1 + (A_L·N_L + A_R·N_R) / A`, a leaf when that
//! is no cheaper than testing the triangles (or at most two are left).
//! With the `parallel` feature, large subtrees build their halves on two
//! threads; the tree is the same node for node.

use super::Node;
use crate::vec3::V3;

const BINS: usize = 16;
/// Above this many triangles a node is split even when the SAH would not
/// (by halves when the centroids coincide), so leaves stay short.
const MAX_LEAF: usize = 8;

/// The componentwise minimum.
#[inline(always)]
pub(super) fn min3(a: V3, b: V3) -> V3 {
    [a[0].min(b[0]), a[1].min(b[1]), a[2].min(b[2])]
}

/// The componentwise maximum.
#[inline(always)]
pub(super) fn max3(a: V3, b: V3) -> V3 {
    [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])]
}

/// An empty box (`lo` above `hi`, so any union replaces it).
const EMPTY: (V3, V3) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);

/// The box of `tris`.
pub(super) fn bounds(tris: &[[V3; 3]]) -> (V3, V3) {
    let (mut lo, mut hi) = EMPTY;
    for t in tris {
        for p in t {
            lo = min3(lo, *p);
            hi = max3(hi, *p);
        }
    }
    (lo, hi)
}

/// Half the surface area of a box (0 for an empty one).
#[inline]
fn half_area(lo: V3, hi: V3) -> f64 {
    let d = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    if d[0] < 0.0 {
        return 0.0;
    }
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}

/// One triangle's box and centroid.
#[derive(Clone, Copy)]
struct Prim {
    lo: V3,
    hi: V3,
    c: V3,
    index: u32,
}

/// The nodes (depth-first) and the triangles' leaf order.
pub(super) fn build(tris: &[[V3; 3]]) -> (Vec<Node>, Vec<u32>) {
    let mut prims = prims(tris);
    if prims.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let nodes = subtree(&mut prims, 0);
    (nodes, prims.iter().map(|p| p.index).collect())
}

/// Each triangle's box and centroid.
fn prims(tris: &[[V3; 3]]) -> Vec<Prim> {
    tris.iter()
        .enumerate()
        .map(|(i, t)| {
            let (lo, hi) = bounds(std::slice::from_ref(t));
            let c = [
                (lo[0] + hi[0]) * 0.5,
                (lo[1] + hi[1]) * 0.5,
                (lo[2] + hi[2]) * 0.5,
            ];
            Prim {
                lo,
                hi,
                c,
                index: i as u32,
            }
        })
        .collect()
}

/// Subtrees over at least this many triangles build their two halves on
/// two of rayon's threads (with the `parallel` feature).
#[cfg(feature = "parallel")]
const PARALLEL_MIN: usize = 1 << 14;

/// The nodes of the subtree over `prims`, which start at triangle `base`
/// of the whole; the same tree on one thread or several.
fn subtree(prims: &mut [Prim], base: usize) -> Vec<Node> {
    #[cfg(feature = "parallel")]
    if prims.len() >= PARALLEL_MIN {
        let (lo, hi, clo, chi) = extent(prims);
        if let Some(mid) = split(prims, lo, hi, clo, chi) {
            let (l, r) = prims.split_at_mut(mid);
            let (a, b) = rayon::join(|| subtree(l, base), || subtree(r, base + mid));
            // Child offsets are relative: only second children move.
            let shift = |mut n: Node, by: usize| {
                if !n.is_leaf() {
                    n.first += by as u32;
                }
                n
            };
            let mut nodes = Vec::with_capacity(1 + a.len() + b.len());
            nodes.push(Node::new(lo, hi, (1 + a.len()) as u32, Node::inner(0, 1)));
            let right = 1 + a.len();
            nodes.extend(a.into_iter().map(|n| shift(n, 1)));
            nodes.extend(b.into_iter().map(|n| shift(n, right)));
            return nodes;
        }
        // A leaf after all: the serial path decides the same.
    }
    serial(prims, base)
}

/// The box and centroid box of `prims`.
fn extent(prims: &[Prim]) -> (V3, V3, V3, V3) {
    let (mut lo, mut hi) = EMPTY;
    let (mut clo, mut chi) = EMPTY;
    for p in prims {
        lo = min3(lo, p.lo);
        hi = max3(hi, p.hi);
        clo = min3(clo, p.c);
        chi = max3(chi, p.c);
    }
    (lo, hi, clo, chi)
}

/// The subtree over `prims` on this thread, with an explicit stack.
fn serial(prims: &mut [Prim], base: usize) -> Vec<Node> {
    let mut nodes = Vec::with_capacity((2 * prims.len() / 3).max(1));
    // (start, end, the parent whose second child this is).
    let mut stack: Vec<(usize, usize, Option<usize>)> = vec![(0, prims.len(), None)];
    while let Some((start, end, parent)) = stack.pop() {
        let me = nodes.len();
        if let Some(p) = parent {
            let n: &mut Node = &mut nodes[p];
            n.first = me as u32;
        }
        let slice = &mut prims[start..end];
        let (lo, hi, clo, chi) = extent(slice);
        match split(slice, lo, hi, clo, chi) {
            Some(mid) => {
                nodes.push(Node::new(lo, hi, 0, Node::inner(me, me + 1)));
                stack.push((start + mid, end, Some(me)));
                stack.push((start, start + mid, None));
            }
            None => nodes.push(Node::new(
                lo,
                hi,
                (base + start) as u32,
                (end - start) as u32,
            )),
        }
    }
    nodes
}

/// Partition `prims` at the best binned SAH split and return the size of
/// the first part, or `None` for a leaf.
fn split(prims: &mut [Prim], lo: V3, hi: V3, clo: V3, chi: V3) -> Option<usize> {
    let n = prims.len();
    if n <= 2 {
        return None;
    }
    let mut best: Option<(f64, usize, usize)> = None; // (cost, axis, bins left)
    for axis in 0..3 {
        let extent = chi[axis] - clo[axis];
        // Skips flat axes and NaN extents alike.
        if extent.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            continue;
        }
        let scale = BINS as f64 / extent;
        let mut bins = [(EMPTY.0, EMPTY.1, 0usize); BINS];
        for p in prims.iter() {
            let b = bin_of(p.c[axis], clo[axis], scale);
            let e = &mut bins[b];
            e.0 = min3(e.0, p.lo);
            e.1 = max3(e.1, p.hi);
            e.2 += 1;
        }
        // Sweep from the right: the area and count of bins k.. for each k.
        let mut right = [(0.0f64, 0usize); BINS];
        let (mut rlo, mut rhi, mut rn) = (EMPTY.0, EMPTY.1, 0);
        for k in (1..BINS).rev() {
            rlo = min3(rlo, bins[k].0);
            rhi = max3(rhi, bins[k].1);
            rn += bins[k].2;
            right[k] = (half_area(rlo, rhi), rn);
        }
        let (mut llo, mut lhi, mut ln) = (EMPTY.0, EMPTY.1, 0);
        for k in 1..BINS {
            llo = min3(llo, bins[k - 1].0);
            lhi = max3(lhi, bins[k - 1].1);
            ln += bins[k - 1].2;
            let (ra, rn) = right[k];
            if ln == 0 || rn == 0 {
                continue;
            }
            let cost = half_area(llo, lhi) * ln as f64 + ra * rn as f64;
            if best.is_none_or(|b| cost < b.0) {
                best = Some((cost, axis, k));
            }
        }
    }
    let area = half_area(lo, hi);
    match best {
        Some((cost, axis, k)) => {
            // Relative to one triangle test: traversal 1, leaf cost n.
            let split_cost = 1.0 + if area > 0.0 { cost / area } else { n as f64 };
            if split_cost >= n as f64 && n <= MAX_LEAF {
                return None;
            }
            let extent = chi[axis] - clo[axis];
            let scale = BINS as f64 / extent;
            let mid = partition(prims, |p| bin_of(p.c[axis], clo[axis], scale) < k);
            Some(mid)
        }
        None if n > MAX_LEAF => {
            // Every centroid coincides: split by halves.
            Some(n / 2)
        }
        None => None,
    }
}

/// The bin of centroid coordinate `c`.
#[inline(always)]
fn bin_of(c: f64, lo: f64, scale: f64) -> usize {
    // NaN or negative casts to 0; the top edge goes to the last bin.
    (((c - lo) * scale) as usize).min(BINS - 1)
}

/// Move the prims for which `left` holds to the front; returns how many.
fn partition(prims: &mut [Prim], left: impl Fn(&Prim) -> bool) -> usize {
    let mut i = 0;
    let mut j = prims.len();
    while i < j {
        if left(&prims[i]) {
            i += 1;
        } else {
            j -= 1;
            prims.swap(i, j);
        }
    }
    i
}

#[cfg(all(test, feature = "parallel"))]
mod tests {
    use super::*;

    #[test]
    fn the_parallel_build_makes_the_serial_tree_node_for_node() {
        let mesh = crate::shapes::torus(200, 100, 1.0, 0.3).unwrap();
        let pos = mesh.position_slots().unwrap();
        let tris: Vec<[V3; 3]> = mesh
            .faces()
            .flat_map(|f| {
                let c: Vec<V3> = mesh
                    .face(f)
                    .unwrap()
                    .vertices()
                    .map(|v| pos[v.index()])
                    .collect();
                (1..c.len() - 1).map(move |i| [c[0], c[i], c[i + 1]])
            })
            .collect();
        assert!(tris.len() >= 2 * PARALLEL_MIN);
        let (mut a, mut b) = (prims(&tris), prims(&tris));
        let (na, nb) = (subtree(&mut a, 0), serial(&mut b, 0));
        assert_eq!(na.len(), nb.len());
        for (x, y) in na.iter().zip(&nb) {
            assert_eq!(
                (x.lo, x.hi, x.first, x.count),
                (y.lo, y.hi, y.first, y.count)
            );
        }
        assert!(a.iter().zip(&b).all(|(x, y)| x.index == y.index));
    }
}
