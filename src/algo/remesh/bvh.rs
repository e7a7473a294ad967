//! A small bounding-volume hierarchy for closest-point queries on the input
//! surface of [`remesh`](super::remesh): axis-aligned boxes, median split
//! of the primitives' centroids along the longest axis, up to four
//! primitives a leaf, stored flat (a node's left child follows it).
//!
//! Primitives are triangles (the surface) and segments (boundary and
//! feature lines). A query walks the nearer child first and prunes every
//! box farther than the best distance so far; a *hint* (the primitive a
//! vertex was projected onto last time) gives a tight first bound, so a
//! vertex that moved a little costs a handful of box tests.
//!
//! Why our own: the remesher needs the primitive, the closest point and
//! its barycentric coordinates, a warm start and a filter (corners of a UV
//! island look only at the island's triangles); the tree is ~250 lines.
//! Building is O(n log n); a query is about O(log n) box tests, fewer with
//! the hint (the ignored test `measure_bvh` times both; `BENCHMARKS.md`).

use crate::vec3::{axpy, dot, sub, V3};

/// What the tree holds: something with a box and a closest point.
pub(crate) trait Primitive {
    /// The corners of its box.
    fn bounds(&self) -> (V3, V3);
    /// The closest point to `p`, its barycentric coordinates (a segment's
    /// third is 0) and the squared distance.
    fn closest(&self, p: V3) -> (V3, [f64; 3], f64);
}

/// A triangle `[a, b, c]`.
pub(crate) type Triangle = [V3; 3];
/// A segment `[a, b]`.
pub(crate) type Segment = [V3; 2];

impl Primitive for Triangle {
    fn bounds(&self) -> (V3, V3) {
        let mut lo = self[0];
        let mut hi = self[0];
        for q in &self[1..] {
            for i in 0..3 {
                lo[i] = lo[i].min(q[i]);
                hi[i] = hi[i].max(q[i]);
            }
        }
        (lo, hi)
    }

    #[inline]
    fn closest(&self, p: V3) -> (V3, [f64; 3], f64) {
        let (q, bary) = closest_on_triangle(p, self[0], self[1], self[2]);
        let d = sub(p, q);
        (q, bary, dot(d, d))
    }
}

impl Primitive for Segment {
    fn bounds(&self) -> (V3, V3) {
        let (a, b) = (self[0], self[1]);
        (
            [a[0].min(b[0]), a[1].min(b[1]), a[2].min(b[2])],
            [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])],
        )
    }

    #[inline]
    fn closest(&self, p: V3) -> (V3, [f64; 3], f64) {
        let (a, b) = (self[0], self[1]);
        let ab = sub(b, a);
        let l2 = dot(ab, ab);
        let t = if l2 > 0.0 {
            (dot(sub(p, a), ab) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = axpy(a, t, ab);
        let d = sub(p, q);
        (q, [1.0 - t, t, 0.0], dot(d, d))
    }
}

/// The closest point of triangle `abc` to `p` and its barycentric
/// coordinates, by the Voronoi regions of the corners, sides and inside
/// (as in Ericson, *Real-Time Collision Detection*, 5.1.5). Degenerate
/// triangles fall back to the closest of their sides.
pub(crate) fn closest_on_triangle(p: V3, a: V3, b: V3, c: V3) -> (V3, [f64; 3]) {
    let ab = sub(b, a);
    let ac = sub(c, a);
    let ap = sub(p, a);
    let d1 = dot(ab, ap);
    let d2 = dot(ac, ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, [1.0, 0.0, 0.0]);
    }
    let bp = sub(p, b);
    let d3 = dot(ab, bp);
    let d4 = dot(ac, bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, [0.0, 1.0, 0.0]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (axpy(a, v, ab), [1.0 - v, v, 0.0]);
    }
    let cp = sub(p, c);
    let d5 = dot(ab, cp);
    let d6 = dot(ac, cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, [0.0, 0.0, 1.0]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (axpy(a, w, ac), [1.0 - w, 0.0, w]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (axpy(b, w, sub(c, b)), [0.0, 1.0 - w, w]);
    }
    let sum = va + vb + vc;
    if sum.is_nan() || sum <= 0.0 || !sum.is_finite() {
        // Degenerate: the best of the three sides.
        let mut best = (a, [1.0, 0.0, 0.0], f64::INFINITY);
        for (s, map) in [([a, b], [0, 1]), ([b, c], [1, 2]), ([c, a], [2, 0])] {
            let (q, w, d) = s.closest(p);
            if d < best.2 {
                let mut bary = [0.0; 3];
                bary[map[0]] = w[0];
                bary[map[1]] = w[1];
                best = (q, bary, d);
            }
        }
        return (best.0, best.1);
    }
    let denom = 1.0 / sum;
    let v = vb * denom;
    let w = vc * denom;
    let q = [
        a[0] + ab[0] * v + ac[0] * w,
        a[1] + ab[1] * v + ac[1] * w,
        a[2] + ab[2] * v + ac[2] * w,
    ];
    (q, [1.0 - v - w, v, w])
}

/// One node: its box and either two children (`count == 0`: the left one
/// follows, the right one is at `start`) or `count` primitives from
/// `start` in the tree's order.
#[derive(Copy, Clone, Debug)]
struct Node {
    lo: V3,
    hi: V3,
    start: u32,
    count: u32,
}

/// The answer to a query.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Hit {
    /// The primitive's index in the input order.
    pub(crate) prim: u32,
    /// The closest point.
    pub(crate) point: V3,
    /// Its barycentric coordinates on the primitive.
    pub(crate) bary: [f64; 3],
    /// The squared distance.
    pub(crate) dist2: f64,
}

const LEAF: usize = 4;

/// A bounding-volume hierarchy over primitives `P`.
pub(crate) struct Bvh<P> {
    nodes: Vec<Node>,
    /// The primitives in tree order, with their input indices.
    prims: Vec<P>,
    ids: Vec<u32>,
    /// Input index -> tree order.
    order_of: Vec<u32>,
}

impl<P: Primitive + Copy> Bvh<P> {
    /// Build over `prims` (input order kept for the answers).
    pub(crate) fn new(prims: Vec<P>) -> Bvh<P> {
        let n = prims.len();
        let boxes: Vec<(V3, V3)> = prims.iter().map(Primitive::bounds).collect();
        let centres: Vec<V3> = boxes
            .iter()
            .map(|(lo, hi)| {
                [
                    0.5 * (lo[0] + hi[0]),
                    0.5 * (lo[1] + hi[1]),
                    0.5 * (lo[2] + hi[2]),
                ]
            })
            .collect();
        let mut idx: Vec<u32> = (0..n as u32).collect();
        let mut nodes = Vec::with_capacity(2 * n.div_ceil(LEAF) + 1);
        if n > 0 {
            build(&mut nodes, &mut idx, 0, &boxes, &centres);
        }
        let mut order_of = vec![0u32; n];
        for (k, &i) in idx.iter().enumerate() {
            order_of[i as usize] = k as u32;
        }
        Bvh {
            nodes,
            prims: idx.iter().map(|&i| prims[i as usize]).collect(),
            ids: idx,
            order_of,
        }
    }

    /// Whether the tree holds nothing.
    pub(crate) fn is_empty(&self) -> bool {
        self.prims.is_empty()
    }

    /// The closest point to `p` on the primitives `keep` accepts (by input
    /// index), starting from primitive `hint` (input index) when given.
    /// `None` when no primitive is accepted.
    pub(crate) fn closest_filtered(
        &self,
        p: V3,
        hint: Option<u32>,
        keep: &dyn Fn(u32) -> bool,
    ) -> Option<Hit> {
        self.query(p, hint, Some(keep))
    }

    /// The closest point to `p` on any primitive, starting from `hint`.
    pub(crate) fn closest(&self, p: V3, hint: Option<u32>) -> Option<Hit> {
        self.query(p, hint, None)
    }

    #[inline]
    fn query(&self, p: V3, hint: Option<u32>, keep: Option<&dyn Fn(u32) -> bool>) -> Option<Hit> {
        if self.nodes.is_empty() {
            return None;
        }
        let mut best: Option<Hit> = None;
        let mut best_d = f64::INFINITY;
        let mut hinted = u32::MAX;
        if let Some(h) = hint {
            if (h as usize) < self.order_of.len() && keep.is_none_or(|k| k(h)) {
                let k = self.order_of[h as usize];
                let (q, bary, d) = self.prims[k as usize].closest(p);
                best = Some(Hit {
                    prim: h,
                    point: q,
                    bary,
                    dist2: d,
                });
                best_d = d;
                hinted = k;
            }
        }
        let mut stack = [0u32; 96];
        let mut top = 1usize;
        stack[0] = 0;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if box_dist2(node, p) >= best_d {
                continue;
            }
            if node.count > 0 {
                let s = node.start as usize;
                for k in s..s + node.count as usize {
                    if k as u32 == hinted {
                        continue;
                    }
                    let id = self.ids[k];
                    if let Some(keep) = keep {
                        if !keep(id) {
                            continue;
                        }
                    }
                    let (q, bary, d) = self.prims[k].closest(p);
                    if d < best_d {
                        best_d = d;
                        best = Some(Hit {
                            prim: id,
                            point: q,
                            bary,
                            dist2: d,
                        });
                    }
                }
                continue;
            }
            let me = stack[top] as usize;
            let (l, r) = (me + 1, node.start as usize);
            let (dl, dr) = (box_dist2(&self.nodes[l], p), box_dist2(&self.nodes[r], p));
            // Push the farther first so the nearer is walked first.
            let (near, far, dfar) = if dl <= dr { (l, r, dr) } else { (r, l, dl) };
            if top + 2 > stack.len() {
                // Deeper than any median split gets; walk it the slow way.
                return self.query_slow(p, best, keep);
            }
            if dfar < best_d {
                stack[top] = far as u32;
                top += 1;
            }
            stack[top] = near as u32;
            top += 1;
        }
        best
    }

    /// Every primitive, for the (never seen) case of a too deep stack.
    fn query_slow(
        &self,
        p: V3,
        mut best: Option<Hit>,
        keep: Option<&dyn Fn(u32) -> bool>,
    ) -> Option<Hit> {
        for (k, prim) in self.prims.iter().enumerate() {
            let id = self.ids[k];
            if keep.is_some_and(|f| !f(id)) {
                continue;
            }
            let (q, bary, d) = prim.closest(p);
            if best.is_none_or(|b| d < b.dist2) {
                best = Some(Hit {
                    prim: id,
                    point: q,
                    bary,
                    dist2: d,
                });
            }
        }
        best
    }
}

#[inline(always)]
fn box_dist2(n: &Node, p: V3) -> f64 {
    let mut d = 0.0;
    for ((lo, hi), x) in n.lo.iter().zip(&n.hi).zip(&p) {
        let e = (lo - x).max(x - hi).max(0.0);
        d += e * e;
    }
    d
}

/// Build the subtree over `idx` (a slice of the index array starting at
/// `offset`), appending nodes depth-first; returns its node index.
fn build(
    nodes: &mut Vec<Node>,
    idx: &mut [u32],
    offset: usize,
    boxes: &[(V3, V3)],
    centres: &[V3],
) -> usize {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let mut clo = [f64::INFINITY; 3];
    let mut chi = [f64::NEG_INFINITY; 3];
    for &i in idx.iter() {
        let (a, b) = boxes[i as usize];
        let c = centres[i as usize];
        for k in 0..3 {
            lo[k] = lo[k].min(a[k]);
            hi[k] = hi[k].max(b[k]);
            clo[k] = clo[k].min(c[k]);
            chi[k] = chi[k].max(c[k]);
        }
    }
    let me = nodes.len();
    nodes.push(Node {
        lo,
        hi,
        start: offset as u32,
        count: idx.len() as u32,
    });
    if idx.len() <= LEAF {
        return me;
    }
    let ext = [chi[0] - clo[0], chi[1] - clo[1], chi[2] - clo[2]];
    let axis = if ext[0] >= ext[1] && ext[0] >= ext[2] {
        0
    } else if ext[1] >= ext[2] {
        1
    } else {
        2
    };
    let mid = idx.len() / 2;
    idx.select_nth_unstable_by(mid, |&x, &y| {
        centres[x as usize][axis].total_cmp(&centres[y as usize][axis])
    });
    let (left, right) = idx.split_at_mut(mid);
    build(nodes, left, offset, boxes, centres);
    let r = build(nodes, right, offset + mid, boxes, centres);
    nodes[me].start = r as u32;
    nodes[me].count = 0;
    me
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute(tris: &[Triangle], p: V3) -> f64 {
        tris.iter()
            .map(|t| t.closest(p).2)
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn matches_brute_force() {
        // A wavy strip of triangles and scattered query points.
        let mut tris = Vec::new();
        let f = |x: f64, y: f64| [x, y, 0.3 * (3.0 * x).sin() * (2.0 * y).cos()];
        for i in 0..20 {
            for j in 0..20 {
                let (x, y) = (i as f64 * 0.1, j as f64 * 0.1);
                tris.push([f(x, y), f(x + 0.1, y), f(x, y + 0.1)]);
                tris.push([f(x + 0.1, y), f(x + 0.1, y + 0.1), f(x, y + 0.1)]);
            }
        }
        let bvh = Bvh::new(tris.clone());
        let mut s = 12345u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..300 {
            let p = [rnd() * 2.4 - 0.2, rnd() * 2.4 - 0.2, rnd() - 0.5];
            let hint = (k % 3 == 0).then_some((k * 7 % tris.len()) as u32);
            let hit = bvh.closest(p, hint).unwrap();
            assert!((hit.dist2 - brute(&tris, p)).abs() < 1e-12);
            let t = tris[hit.prim as usize];
            let b = hit.bary;
            for (i, want) in hit.point.iter().enumerate() {
                let q = b[0] * t[0][i] + b[1] * t[1][i] + b[2] * t[2][i];
                assert!((q - want).abs() < 1e-9);
            }
        }
        // A filter: only even triangles.
        let p = [1.0, 1.0, 1.0];
        let hit = bvh.closest_filtered(p, Some(1), &|i| i % 2 == 0).unwrap();
        assert_eq!(hit.prim % 2, 0);
        let even: Vec<Triangle> = tris.iter().step_by(2).copied().collect();
        assert!((hit.dist2 - brute(&even, p)).abs() < 1e-12);
    }

    #[test]
    fn segments() {
        let segs: Vec<Segment> = (0..10)
            .map(|i| [[i as f64, 0.0, 0.0], [i as f64 + 1.0, 0.0, 0.0]])
            .collect();
        let bvh = Bvh::new(segs);
        let hit = bvh.closest([3.25, 1.0, 0.0], None).unwrap();
        assert_eq!(hit.prim, 3);
        assert!((hit.point[0] - 3.25).abs() < 1e-12);
        assert!((hit.dist2 - 1.0).abs() < 1e-12);
    }

    /// A measurement, not a check (`cargo test --release --lib
    /// measure_bvh -- --ignored --nocapture`): build time on the kit's
    /// 250k-vertex grid (498,002 triangles) and the cost of a query, warm
    /// (hint = the triangle under the point), cold, and by brute force.
    #[test]
    #[ignore]
    fn measure_bvh() {
        let n = 500;
        let f = |i: usize, j: usize| {
            let (x, y) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            [x, y, 0.1 * (6.0 * x).sin() * (6.0 * y).cos()]
        };
        let mut tris = Vec::with_capacity(2 * (n - 1) * (n - 1));
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                tris.push([f(i, j), f(i + 1, j), f(i + 1, j + 1)]);
                tris.push([f(i, j), f(i + 1, j + 1), f(i, j + 1)]);
            }
        }
        let t0 = std::time::Instant::now();
        let bvh = Bvh::new(tris.clone());
        let build = t0.elapsed().as_secs_f64();
        // Query points: centroids lifted a little off the surface.
        let queries: Vec<(V3, u32)> = (0..tris.len())
            .step_by(5)
            .map(|k| {
                let t = tris[k];
                let c = [0, 1, 2].map(|a| (t[0][a] + t[1][a] + t[2][a]) / 3.0 + 1e-4);
                (c, k as u32)
            })
            .collect();
        let t0 = std::time::Instant::now();
        let mut sum = 0.0;
        for &(p, k) in &queries {
            sum += bvh.closest(p, Some(k)).unwrap().dist2;
        }
        let warm = t0.elapsed().as_secs_f64() / queries.len() as f64;
        let t0 = std::time::Instant::now();
        for &(p, _) in &queries {
            sum += bvh.closest(p, None).unwrap().dist2;
        }
        let cold = t0.elapsed().as_secs_f64() / queries.len() as f64;
        let t0 = std::time::Instant::now();
        for &(p, _) in queries.iter().take(20) {
            sum += brute(&tris, p);
        }
        let brute_each = t0.elapsed().as_secs_f64() / 20.0;
        println!(
            "bvh: {} triangles, build {build:.3} s; query warm {:.0} ns, cold {:.0} ns, brute force {:.2} ms ({} queries; {sum:.3e})",
            tris.len(),
            warm * 1e9,
            cold * 1e9,
            brute_each * 1e3,
            queries.len()
        );
    }
}
