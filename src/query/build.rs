//! The binned SAH build: 16 bins of triangle centroids along the axis of
//! their widest extent, the split
//! of least estimated cost `1 + (A_L·N_L + A_R·N_R) / A`, a leaf when that
//! is no cheaper than testing the triangles (or at most two are left).
//! With the `parallel` feature, large subtrees build their halves on two
//! threads; the tree is the same node for node.

use super::{round_down, round_up, Node};
use crate::vec3::{self, V3};

const BINS: usize = 16;
/// Above this many triangles a node is split even when the SAH would not
/// (by halves when the centroids coincide), so leaves stay short.
const MAX_LEAF: usize = 8;

/// An empty box (`lo` above `hi`, so any union replaces it).
const EMPTY: (V3, V3) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);

/// The box of `tris`.
pub(super) fn bounds(tris: &[[V3; 3]]) -> (V3, V3) {
    let (mut lo, mut hi) = EMPTY;
    for t in tris {
        for p in t {
            lo = vec3::min(lo, *p);
            hi = vec3::max(hi, *p);
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

/// A box in `f32`, rounded outwards from the triangle's `f64` corners.
type B3 = [f32; 3];

/// One triangle's box (outwards in `f32`: the union of such boxes is the
/// outward rounding of the union, so node boxes come out as `f64` boxes
/// rounded would). Its centroid is `lo + hi`, twice the true one: bins and
/// splits only compare centroids.
#[derive(Clone, Copy)]
struct Prim {
    lo: B3,
    hi: B3,
    index: u32,
}

impl Prim {
    /// Twice the centroid's coordinate on `axis`.
    #[inline(always)]
    fn c(&self, axis: usize) -> f32 {
        self.lo[axis] + self.hi[axis]
    }
}

/// The componentwise minimum in `f32`, where a NaN in `b` (never in `a`,
/// which starts empty) is passed over as `f32::min` would, in one
/// instruction a lane instead of `f32::min`'s several.
#[inline(always)]
fn min3f(a: B3, b: B3) -> B3 {
    let m = |x: f32, y: f32| if y < x { y } else { x };
    [m(a[0], b[0]), m(a[1], b[1]), m(a[2], b[2])]
}

/// The componentwise maximum in `f32`, as [`min3f`].
#[inline(always)]
fn max3f(a: B3, b: B3) -> B3 {
    let m = |x: f32, y: f32| if y > x { y } else { x };
    [m(a[0], b[0]), m(a[1], b[1]), m(a[2], b[2])]
}

/// An empty `f32` box.
const EMPTY_F: (B3, B3) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);

/// A node over the box `lo`–`hi`.
fn node(lo: B3, hi: B3, first: u32, count: u32) -> Node {
    Node::new(lo.map(f64::from), hi.map(f64::from), first, count)
}

/// The nodes (siblings side by side, see [`pair_siblings`]) and the
/// triangles' leaf order.
pub(super) fn build(tris: &[[V3; 3]]) -> (Vec<Node>, Vec<u32>) {
    let mut prims = prims(tris);
    if prims.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let nodes = subtree(&mut prims, 0);
    (
        pair_siblings(&nodes),
        prims.iter().map(|p| p.index).collect(),
    )
}

/// `nodes` laid out again with each inner node's two children side by
/// side, after it, in depth-first order of the pairs: a walk that tests
/// both children loads one 64-byte stretch instead of two distant nodes
/// (the second child's load was the largest cost of a ray cast). Leaves
/// keep their triangles.
fn pair_siblings(old: &[Node]) -> Vec<Node> {
    let mut new = Vec::with_capacity(old.len());
    new.push(old[0]);
    // (index in `old`, index in `new`) of nodes whose children are due.
    let mut stack = vec![(0usize, 0usize)];
    while let Some((o, n)) = stack.pop() {
        if old[o].is_leaf() {
            continue;
        }
        let (a, b) = old[o].children(o);
        let c = new.len();
        new.push(old[a]);
        new.push(old[b]);
        new[n].count = Node::inner(n, c);
        new[n].first = (c + 1) as u32;
        stack.push((b, c + 1));
        stack.push((a, c));
    }
    new
}

/// Each triangle's box.
fn prims(tris: &[[V3; 3]]) -> Vec<Prim> {
    tris.iter()
        .enumerate()
        .map(|(i, t)| {
            let (lo, hi) = bounds(std::slice::from_ref(t));
            Prim {
                lo: lo.map(round_down),
                hi: hi.map(round_up),
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
            nodes.push(node(lo, hi, (1 + a.len()) as u32, Node::inner(0, 1)));
            let right = 1 + a.len();
            nodes.extend(a.into_iter().map(|n| shift(n, 1)));
            nodes.extend(b.into_iter().map(|n| shift(n, right)));
            return nodes;
        }
        // A leaf after all: the serial path decides the same.
    }
    serial(prims, base)
}

/// The box and (doubled) centroid box of `prims`.
fn extent(prims: &[Prim]) -> (B3, B3, B3, B3) {
    let (mut lo, mut hi) = EMPTY_F;
    let (mut clo, mut chi) = EMPTY_F;
    for p in prims {
        lo = min3f(lo, p.lo);
        hi = max3f(hi, p.hi);
        let c = [p.c(0), p.c(1), p.c(2)];
        clo = min3f(clo, c);
        chi = max3f(chi, c);
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
                nodes.push(node(lo, hi, 0, Node::inner(me, me + 1)));
                stack.push((start + mid, end, Some(me)));
                stack.push((start, start + mid, None));
            }
            None => nodes.push(node(lo, hi, (base + start) as u32, (end - start) as u32)),
        }
    }
    nodes
}

/// One bin: the box and count of the triangles whose centroids fall in it.
#[derive(Clone, Copy)]
struct Bin {
    lo: B3,
    hi: B3,
    n: u32,
}

const EMPTY_BIN: Bin = Bin {
    lo: EMPTY_F.0,
    hi: EMPTY_F.1,
    n: 0,
};

/// Partition `prims` at the best binned SAH split and return the size of
/// the first part, or `None` for a leaf.
fn split(prims: &mut [Prim], lo: B3, hi: B3, clo: B3, chi: B3) -> Option<usize> {
    let n = prims.len();
    if n <= 2 {
        return None;
    }
    // Per axis: the scale to bins, or 0 for a flat (or NaN) extent.
    // Only the axis of widest centroid extent is binned, as pbrt does:
    // binning all three cost 1.8 times the build's instructions for 2 %
    // fewer in a ray cast (the 100k torus, 1M random rays).
    let widest = (0..3)
        .max_by(|&a, &b| (chi[a] - clo[a]).total_cmp(&(chi[b] - clo[b])))
        .unwrap_or(0);
    let scale = [0, 1, 2].map(|axis| {
        let extent = chi[axis] - clo[axis];
        if extent > 0.0 && axis == widest {
            BINS as f32 / extent
        } else {
            0.0
        }
    });
    let bins = fill_bins(prims, clo, scale);
    let mut best: Option<(f64, usize, usize)> = None; // (cost, axis, bins left)
    for axis in (0..3).filter(|&a| scale[a] > 0.0) {
        if let Some((cost, k)) = best_cut(&bins[axis]) {
            if best.is_none_or(|b| cost < b.0) {
                best = Some((cost, axis, k));
            }
        }
    }
    let area = half_area(lo.map(f64::from), hi.map(f64::from));
    match best {
        Some((cost, axis, k)) => {
            // Relative to one triangle test: traversal 1, leaf cost n.
            let split_cost = 1.0 + if area > 0.0 { cost / area } else { n as f64 };
            if split_cost >= n as f64 && n <= MAX_LEAF {
                return None;
            }
            let (c0, s) = (clo[axis], scale[axis]);
            Some(partition(prims, |p| bin_of(p.c(axis), c0, s) < k))
        }
        None if n > MAX_LEAF => {
            // Every centroid coincides: split by halves.
            Some(n / 2)
        }
        None => None,
    }
}

/// The bins of all three axes in one pass over `prims` (an axis of scale
/// 0 is skipped).
fn fill_bins(prims: &[Prim], clo: B3, scale: [f32; 3]) -> [[Bin; BINS]; 3] {
    let mut bins = [[EMPTY_BIN; BINS]; 3];
    for p in prims {
        for axis in 0..3 {
            if scale[axis] > 0.0 {
                let e = &mut bins[axis][bin_of(p.c(axis), clo[axis], scale[axis])];
                e.lo = min3f(e.lo, p.lo);
                e.hi = max3f(e.hi, p.hi);
                e.n += 1;
            }
        }
    }
    bins
}

/// The cut between bins of least SAH cost `A_L·N_L + A_R·N_R` and the
/// number of bins left of it, if any cut leaves triangles on both sides.
fn best_cut(bins: &[Bin; BINS]) -> Option<(f64, usize)> {
    // Sweep from the right: the area and count of bins k.. for each k.
    // Empty bins change nothing, so they cost nothing (a small node fills
    // few of its bins).
    let mut right = [(0.0f64, 0u32); BINS];
    let (mut rlo, mut rhi, mut rn, mut ra) = (EMPTY_F.0, EMPTY_F.1, 0, 0.0);
    for k in (1..BINS).rev() {
        if bins[k].n > 0 {
            rlo = min3f(rlo, bins[k].lo);
            rhi = max3f(rhi, bins[k].hi);
            rn += bins[k].n;
            ra = half_area(rlo.map(f64::from), rhi.map(f64::from));
        }
        right[k] = (ra, rn);
    }
    let (mut llo, mut lhi, mut ln) = (EMPTY_F.0, EMPTY_F.1, 0);
    let mut best: Option<(f64, usize)> = None;
    for k in 1..BINS {
        // A cut just right of an empty bin costs what the cut left of it
        // did: the first of them is kept, as a strict `<` would.
        if bins[k - 1].n == 0 {
            continue;
        }
        llo = min3f(llo, bins[k - 1].lo);
        lhi = max3f(lhi, bins[k - 1].hi);
        ln += bins[k - 1].n;
        let (ra, rn) = right[k];
        if rn == 0 {
            break;
        }
        let l_area = half_area(llo.map(f64::from), lhi.map(f64::from));
        let cost = l_area * f64::from(ln) + ra * f64::from(rn);
        if best.is_none_or(|b| cost < b.0) {
            best = Some((cost, k));
        }
    }
    best
}

/// The bin of (doubled) centroid coordinate `c`.
#[inline(always)]
fn bin_of(c: f32, lo: f32, scale: f32) -> usize {
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
