//! Ear clipping of large polygons in near O(n log n): the ears wait in a
//! priority queue (shortest cut first), and an ear's emptiness is checked
//! only against the reflex corners in the cells of a uniform grid that its
//! box covers (a convex corner can never lie inside an ear, and a corner
//! that is convex stays convex as ears are cut). Where no corner is an ear
//! any more (degenerate input), what is left is handed back for the
//! caller's exhaustive clipper.
//!
//! Corners with the same `key` (one vertex visited twice by a weakly simple
//! polygon, as a bridge to an inner loop) never block each other's ears.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Polygons with at least this many corners take the queued clipper in
/// [`Mesh::triangulate`](crate::Mesh::triangulate); smaller ones the
/// exhaustive scan, whose order of ears they have always had.
pub(crate) const QUEUED_FROM: usize = 64;

/// The ears cut and what is left.
pub(crate) struct Clipped {
    /// `[pl, l, m, r]`: the ear `l, m, r` and the corner before `l` when it
    /// was cut, in cutting order.
    pub(crate) ears: Vec<[u32; 4]>,
    /// The corners left, in polygon order: three when every ear was found,
    /// more when the clipper was stuck.
    pub(crate) rest: Vec<u32>,
}

/// Clip the ears of the counter-clockwise polygon `q` (a corner's
/// identity in `key`); `forbidden(l, r)` refuses a cut from corner `l` to
/// corner `r` (a diagonal that is an edge already).
pub(crate) fn clip_ears(
    q: &[[f64; 2]],
    key: &[u32],
    forbidden: impl FnMut(u32, u32) -> bool,
) -> Clipped {
    let n = q.len();
    let mut state = State::new(q, key, forbidden);
    let mut ears = Vec::with_capacity(n.saturating_sub(3));
    let mut alive = n;
    let mut stalled = false;
    while alive > 3 {
        let Some(Reverse((_, i, version))) = state.queue.pop() else {
            // Ears blocked when queued may be free now: look at every
            // corner once more; nothing found twice running means stuck.
            if stalled || !state.queue_all() {
                break;
            }
            stalled = true;
            continue;
        };
        let i = i as usize;
        if state.dead[i] || state.version[i] != version || !state.is_ear(i) {
            continue;
        }
        stalled = false;
        let (l, r) = (state.prev[i], state.next[i]);
        ears.push([state.prev[l as usize], l, i as u32, r]);
        state.cut(i);
        alive -= 1;
    }
    let start = (0..n).find(|&i| !state.dead[i]).unwrap_or(0);
    let mut rest = Vec::with_capacity(alive);
    let mut i = start;
    for _ in 0..alive {
        rest.push(i as u32);
        i = state.next[i] as usize;
    }
    Clipped { ears, rest }
}

/// The clipper's working state.
struct State<'a, F> {
    q: &'a [[f64; 2]],
    key: &'a [u32],
    forbidden: F,
    prev: Vec<u32>,
    next: Vec<u32>,
    dead: Vec<bool>,
    reflex: Vec<bool>,
    version: Vec<u32>,
    grid: Grid,
    /// `(squared length of the cut, corner, its version when queued)`.
    queue: BinaryHeap<Reverse<(u64, u32, u32)>>,
}

impl<'a, F: FnMut(u32, u32) -> bool> State<'a, F> {
    fn new(q: &'a [[f64; 2]], key: &'a [u32], forbidden: F) -> Self {
        let n = q.len();
        let prev: Vec<u32> = (0..n).map(|i| ((i + n - 1) % n) as u32).collect();
        let next: Vec<u32> = (0..n).map(|i| ((i + 1) % n) as u32).collect();
        let reflex: Vec<bool> = (0..n)
            .map(|i| turn(q[prev[i] as usize], q[i], q[next[i] as usize]) <= 0.0)
            .collect();
        let grid = Grid::new(q, &reflex);
        let mut state = State {
            q,
            key,
            forbidden,
            prev,
            next,
            dead: vec![false; n],
            reflex,
            version: vec![0; n],
            grid,
            queue: BinaryHeap::with_capacity(n),
        };
        state.queue_all();
        state
    }

    /// Queue every living corner that is an ear now; whether any was.
    fn queue_all(&mut self) -> bool {
        let mut any = false;
        for i in 0..self.q.len() {
            if !self.dead[i] && self.is_ear(i) {
                self.push(i);
                any = true;
            }
        }
        any
    }

    fn push(&mut self, i: usize) {
        let (l, r) = (self.prev[i] as usize, self.next[i] as usize);
        let (a, b) = (self.q[l], self.q[r]);
        let d2 = (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
        // Non-negative floats order as their bits.
        self.queue
            .push(Reverse((d2.to_bits(), i as u32, self.version[i])));
    }

    /// Whether corner `i` is an ear: strictly convex, its cut new, and no
    /// reflex corner (other than its own three, or corners of the same
    /// vertex) inside or on its triangle.
    fn is_ear(&mut self, i: usize) -> bool {
        let (l, r) = (self.prev[i] as usize, self.next[i] as usize);
        let (a, b, c) = (self.q[l], self.q[i], self.q[r]);
        if turn(a, b, c) <= 0.0 || (self.forbidden)(l as u32, r as u32) {
            return false;
        }
        let keys = [self.key[l], self.key[i], self.key[r]];
        let (dead, reflex, key, q) = (&self.dead, &self.reflex, self.key, self.q);
        !self.grid.any_in_box(a, b, c, |o| {
            let o = o as usize;
            !dead[o] && reflex[o] && !keys.contains(&key[o]) && inside(q[o], a, b, c)
        })
    }

    /// Cut the ear at `i`: unlink it, update its neighbours' convexity, and
    /// queue them again.
    fn cut(&mut self, i: usize) {
        let (l, r) = (self.prev[i] as usize, self.next[i] as usize);
        self.dead[i] = true;
        self.next[l] = r as u32;
        self.prev[r] = l as u32;
        for x in [l, r] {
            let t = turn(
                self.q[self.prev[x] as usize],
                self.q[x],
                self.q[self.next[x] as usize],
            );
            if t > 0.0 {
                self.reflex[x] = false;
            }
            self.version[x] = self.version[x].wrapping_add(1);
            if self.is_ear(x) {
                self.push(x);
            }
        }
    }
}

/// The reflex corners in the cells of a uniform grid over the polygon's
/// box (about one corner per cell).
struct Grid {
    min: [f64; 2],
    inv: [f64; 2],
    size: usize,
    /// Cell `c` holds `items[starts[c]..starts[c + 1]]`.
    starts: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    fn new(q: &[[f64; 2]], reflex: &[bool]) -> Self {
        let mut min = [f64::INFINITY; 2];
        let mut max = [f64::NEG_INFINITY; 2];
        for p in q {
            for k in 0..2 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        let count = reflex.iter().filter(|&&r| r).count();
        let size = ((count as f64).sqrt().ceil() as usize).clamp(1, 1024);
        let inv = [0, 1].map(|k| {
            let span = max[k] - min[k];
            if span > 0.0 {
                size as f64 / span
            } else {
                0.0
            }
        });
        let mut grid = Grid {
            min,
            inv,
            size,
            starts: vec![0; size * size + 1],
            items: vec![0; count],
        };
        let cells: Vec<usize> = q.iter().map(|&p| grid.cell(p)).collect();
        for (i, &c) in cells.iter().enumerate() {
            if reflex[i] {
                grid.starts[c + 1] += 1;
            }
        }
        for c in 0..size * size {
            grid.starts[c + 1] += grid.starts[c];
        }
        let mut at = grid.starts.clone();
        for (i, &c) in cells.iter().enumerate() {
            if reflex[i] {
                grid.items[at[c] as usize] = i as u32;
                at[c] += 1;
            }
        }
        grid
    }

    fn coord(&self, x: f64, k: usize) -> usize {
        let c = ((x - self.min[k]) * self.inv[k]).floor();
        if c.is_nan() || c < 0.0 {
            0
        } else {
            (c as usize).min(self.size - 1)
        }
    }

    fn cell(&self, p: [f64; 2]) -> usize {
        self.coord(p[1], 1) * self.size + self.coord(p[0], 0)
    }

    /// Whether `hit` holds for a corner in a cell under the box of `a, b,
    /// c`.
    fn any_in_box(
        &self,
        a: [f64; 2],
        b: [f64; 2],
        c: [f64; 2],
        mut hit: impl FnMut(u32) -> bool,
    ) -> bool {
        let lo = |k: usize| self.coord(a[k].min(b[k]).min(c[k]), k);
        let hi = |k: usize| self.coord(a[k].max(b[k]).max(c[k]), k);
        for y in lo(1)..=hi(1) {
            let row = y * self.size;
            let (from, to) = (
                self.starts[row + lo(0)] as usize,
                self.starts[row + hi(0) + 1] as usize,
            );
            if self.items[from..to].iter().any(|&o| hit(o)) {
                return true;
            }
        }
        false
    }
}

/// Twice the signed area of `a, b, c` (positive counter-clockwise).
#[inline]
pub(super) fn turn(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether `p` lies in triangle `a, b, c` (counter-clockwise) or on its
/// sides.
#[inline]
pub(super) fn inside(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    turn(a, b, p) >= 0.0 && turn(b, c, p) >= 0.0 && turn(c, a, p) >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(q: &[[f64; 2]], t: [u32; 3]) -> f64 {
        turn(q[t[0] as usize], q[t[1] as usize], q[t[2] as usize]) / 2.0
    }

    /// A comb: many reflex corners. Every ear is counter-clockwise and the
    /// areas add up to the polygon's.
    #[test]
    fn a_comb_is_cut_into_triangles_of_its_area() {
        let mut q = Vec::new();
        let teeth = 40;
        for t in 0..teeth {
            let x = t as f64 * 2.0;
            q.extend([[x, 0.0], [x + 1.0, 0.0], [x + 1.0, 5.0], [x + 2.0, 5.0]]);
        }
        let x = teeth as f64 * 2.0;
        q.extend([[x, 6.0], [0.0, 6.0]]);
        let key: Vec<u32> = (0..q.len() as u32).collect();
        let clipped = clip_ears(&q, &key, |_, _| false);
        assert_eq!(clipped.rest.len(), 3);
        assert_eq!(clipped.ears.len(), q.len() - 3);
        let mut sum = 0.0;
        for e in &clipped.ears {
            let a = area(&q, [e[1], e[2], e[3]]);
            assert!(a > 0.0);
            sum += a;
        }
        let r = &clipped.rest;
        sum += area(&q, [r[0], r[1], r[2]]);
        let whole: f64 = (0..q.len())
            .map(|i| {
                let (a, b) = (q[i], q[(i + 1) % q.len()]);
                (a[0] * b[1] - b[0] * a[1]) / 2.0
            })
            .sum();
        assert!(whole > 0.0);
        assert!((sum - whole).abs() < 1e-9 * whole, "{sum} vs {whole}");
    }
}
