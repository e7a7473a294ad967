//! The ray casts' copy of the hierarchy: 4-wide nodes.
//!
//! A ray cast is bound by loading nodes. The binary tree makes it load a
//! node per box test; a wide node holds four children's boxes side by
//! side, one axis at a time (structure of arrays, two cache lines), so one
//! load tests four boxes and the four tests are the same arithmetic on
//! four lanes. The copy is collapsed from the binary tree (each wide node
//! takes the binary tree's nodes under it, opening the child of largest
//! surface area until it has four), at the end of every build, refit and
//! update: it costs a pass over the nodes, and the other queries keep the
//! binary tree they walk with their own bounds.

use super::Node;

/// Children a wide node holds.
pub(super) const LANES: usize = 4;

/// A wide node: the boxes of up to [`LANES`] children, by axis, and what
/// each child is. Unused lanes hold an empty box (low corner +∞, high
/// −∞), which no ray enters.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct WideNode {
    /// `bounds[0]` the low corners, `bounds[1]` the high ones; then the
    /// axis, then the lane. `f32`, as the binary nodes' (rounded outwards).
    pub(super) bounds: [[[f32; LANES]; 3]; 2],
    /// A lane's child: a wide node's index (`count` 0), or the first of its
    /// `count` triangles.
    pub(super) child: [u32; LANES],
    /// A lane's number of triangles (0: an inner child or an unused lane).
    pub(super) count: [u32; LANES],
}

/// A wide node with every lane unused.
const UNUSED: WideNode = WideNode {
    bounds: [[[f32::INFINITY; LANES]; 3], [[f32::NEG_INFINITY; LANES]; 3]],
    child: [0; LANES],
    count: [0; LANES],
};

/// A subtree of at most this many triangles, lying side by side in the
/// triangle array, is one lane's leaf: testing a few triangles more costs
/// less than loading a wide node for them.
const LEAF_TRIANGLES: u32 = 4;

/// Make `wide` the wide copy of the binary tree `nodes` (empty for an
/// empty tree), reusing its memory: the root first, a node's children
/// side by side. One pass from the root: nodes
/// [`FaceTree::update`](super::FaceTree::update) left unreached are not
/// read.
pub(super) fn collapse(nodes: &[Node], wide: &mut Vec<WideNode>) {
    wide.clear();
    if nodes.is_empty() {
        return;
    }
    wide.push(UNUSED);
    let mut work = vec![(0usize, 0usize)];
    while let Some((b, w)) = work.pop() {
        let (kids, len) = gather(nodes, b);
        let mut node = UNUSED;
        for (lane, &(c, leaf)) in kids[..len].iter().enumerate() {
            let n = &nodes[c];
            for k in 0..3 {
                node.bounds[0][k][lane] = n.lo[k];
                node.bounds[1][k][lane] = n.hi[k];
            }
            if let Some((first, count)) = leaf {
                node.child[lane] = first;
                node.count[lane] = count;
            } else {
                node.child[lane] = wide.len() as u32;
                work.push((c, wide.len()));
                wide.push(UNUSED);
            }
        }
        wide[w] = node;
    }
}

/// Node `i`'s triangles as one lane's leaf `(first, count)`: a leaf's, or
/// an inner node's when they lie side by side and are at most
/// [`LEAF_TRIANGLES`].
fn lane_leaf(nodes: &[Node], i: usize) -> Option<(u32, u32)> {
    let n = &nodes[i];
    if n.is_leaf() {
        Some((n.first, n.count))
    } else {
        small(nodes, i, LEAF_TRIANGLES)
    }
}

/// The triangles under node `i` as one span `(first, count)` if they lie
/// side by side and are at most `budget`; it reads at most `2 · budget`
/// nodes.
fn small(nodes: &[Node], i: usize, budget: u32) -> Option<(u32, u32)> {
    let n = &nodes[i];
    if n.is_leaf() {
        return (n.count <= budget).then_some((n.first, n.count));
    }
    if budget < 2 {
        return None;
    }
    let (a, b) = n.children(i);
    let (fa, ca) = small(nodes, a, budget - 1)?;
    let (fb, cb) = small(nodes, b, budget - ca)?;
    if fa + ca == fb {
        Some((fa, ca + cb))
    } else if fb + cb == fa {
        Some((fb, ca + cb))
    } else {
        None
    }
}

/// A binary node, with its span when it is a lane's leaf.
type Kid = (usize, Option<(u32, u32)>);

/// Up to [`LANES`] nodes under binary node `b` that hold its triangles
/// between them (`b` itself when it is one lane's leaf), each with its
/// span when it is a lane's leaf: its children, the one of largest surface
/// area that is not a leaf opened while there is room.
fn gather(nodes: &[Node], b: usize) -> ([Kid; LANES], usize) {
    let mut kids = [(b, None); LANES];
    if let Some(span) = lane_leaf(nodes, b) {
        kids[0].1 = Some(span);
        return (kids, 1);
    }
    let (x, y) = nodes[b].children(b);
    kids[0] = (x, lane_leaf(nodes, x));
    kids[1] = (y, lane_leaf(nodes, y));
    let mut len = 2;
    while len < LANES {
        let widest = (0..len)
            .filter(|&i| kids[i].1.is_none())
            .max_by(|&i, &j| half_area(&nodes[kids[i].0]).total_cmp(&half_area(&nodes[kids[j].0])));
        let Some(i) = widest else { break };
        let (x, y) = nodes[kids[i].0].children(kids[i].0);
        kids[i] = (x, lane_leaf(nodes, x));
        kids[len] = (y, lane_leaf(nodes, y));
        len += 1;
    }
    (kids, len)
}

/// Half a node box's surface area.
fn half_area(n: &Node) -> f32 {
    let d: [f32; 3] = std::array::from_fn(|k| n.hi[k] - n.lo[k]);
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}
