//! [`FaceTree::update`]: bring a tree up to date from the journal's change
//! set instead of rebuilding it.
//!
//! The faces the change set names (created, removed, modified) and the
//! faces around its modified vertices are *dirty*: their fan triangles leave
//! the tree, and those that are faces now (not holes) are cut into fans
//! again and inserted, each into the leaf whose box grows least (in surface
//! area) on the way down from the root.
//!
//! The tree is edited in place, so an update costs what changed plus one
//! pass over the leaves (to find the dirty triangles): a leaf that only
//! loses triangles keeps the survivors at the front of its slots; a leaf
//! that gains moves to new slots at the end of the arrays, as a leaf or,
//! past [`SPLIT_LEAF`] triangles, as a binned-SAH subtree whose root takes
//! the leaf's place; an emptied leaf disappears (its sibling takes its
//! parent's place). Only the touched nodes and their ancestors are
//! recomputed. The slots left behind are counted, and the rebuild rule
//! below bounds them.
//!
//! # When it rebuilds instead
//!
//! Greedy insertion keeps the answers exact but lets the hierarchy's quality
//! drift, so the whole tree is rebuilt when
//! - the change set says the mesh was [rebuilt](crate::journal::Changes::rebuilt),
//! - the triangles removed plus inserted by this update exceed a quarter of
//!   the tree's, or
//! - those reinserted since the last full build exceed half of the tree's
//!   (the drift bound, which also keeps the slots left behind below half of
//!   the arrays).

use std::collections::{BTreeMap, HashSet};

use super::{build, wide, Dipole, FaceTree, Node, QueryError, TriMeta, GONE};
use crate::journal::Changes;
use crate::keys::{FaceKey, VertexKey};
use crate::mesh::Mesh;
use crate::vec3::{self, V3};

/// A touched leaf with more triangles than this is rebuilt as a subtree.
pub(super) const SPLIT_LEAF: usize = 16;

/// What [`FaceTree::update`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UpdateReport {
    /// Fan triangles taken out (of dirty faces).
    pub removed_triangles: usize,
    /// Fan triangles put in (of dirty faces that are faces now).
    pub inserted_triangles: usize,
    /// Leaves rebuilt as subtrees because insertions overfilled them.
    pub split_leaves: usize,
    /// The whole tree was rebuilt (see [`FaceTree::update`] for when).
    pub full_rebuild: bool,
}

impl FaceTree {
    /// Bring the tree up to date with `mesh` from `changes`, the change set
    /// of every edit since the tree's [revision](FaceTree::revision) (from
    /// [`HistoryMut::take_changes`](crate::journal::HistoryMut::take_changes)
    /// with tracking on). The answers afterwards equal a fresh build's.
    ///
    /// # Errors
    /// [`QueryError::ChangesMismatch`] when `changes` does not start at the
    /// tree's revision or does not end at the mesh's current one (a change
    /// set skipped, applied twice, or edits after it was taken; the tree is
    /// left as it was: rebuild it); [`QueryError::StaleTree`] for another
    /// mesh; [`QueryError::NoPositions`].
    ///
    /// # Complexity
    /// One read of the leaves and the face records (O(n), no copying) plus
    /// O(k log n) for k dirty triangles, far below a rebuild's O(n log n). It rebuilds the whole
    /// tree instead when `changes.rebuilt` is set, when one update removes
    /// and inserts more than a quarter of the tree's triangles, or when the
    /// triangles reinserted since the last full build pass half of them.
    ///
    /// ```
    /// use meshloom::query::{FaceTree, QueryError, Ray};
    /// let mut mesh = meshloom::shapes::icosphere(3);
    /// mesh.history_mut().track_changes(true);
    /// let mut tree = FaceTree::build(&mesh)?;
    /// let f = mesh.faces().next().unwrap();
    /// mesh.poke_face(f).unwrap();
    /// let changes = mesh.history_mut().take_changes();
    /// let report = tree.update(&mesh, &changes)?;
    /// assert!(report.inserted_triangles >= 3 && !report.full_rebuild);
    /// assert_eq!(tree.triangle_count(), mesh.face_count());
    /// // The same change set again does not start at the tree's revision.
    /// assert!(matches!(tree.update(&mesh, &changes), Err(QueryError::ChangesMismatch { .. })));
    /// # Ok::<(), QueryError>(())
    /// ```
    pub fn update(&mut self, mesh: &Mesh, changes: &Changes) -> Result<UpdateReport, QueryError> {
        let now = mesh.stamp();
        if now.mesh != self.stamp.mesh {
            return Err(self.stale(mesh));
        }
        if changes.from_revision != self.stamp.edits || changes.to_revision != now.edits {
            return Err(QueryError::ChangesMismatch {
                tree: self.stamp.edits,
                from: changes.from_revision,
                to: changes.to_revision,
                now: now.edits,
            });
        }
        let pos = mesh.position_slots().ok_or(QueryError::NoPositions)?;
        if changes.rebuilt || self.nodes.is_empty() {
            return self.rebuild(mesh);
        }
        let (named, suspect) = dirty_marks(mesh, changes);
        let (parent, lost, dmark) = self.dirty_leaves(named, &suspect, pos);
        let (mut fresh, new_faces, new_corners) = fresh_fans(mesh, changes, &dmark, pos);
        let removed: usize = lost.iter().map(|l| l.1).sum();
        let live = self.triangle_count();
        let churn = removed + fresh.tris.len();
        self.churn += churn;
        if churn * 4 > live || self.churn * 2 > live {
            return self.rebuild(mesh);
        }
        let mut touched: BTreeMap<u32, Vec<u32>> = lost.iter().map(|l| (l.0, Vec::new())).collect();
        for (leaf, new) in self.place(&fresh.tris) {
            touched.entry(leaf).or_default().extend(new);
        }
        let mut emptied = Vec::new();
        for (&leaf, new) in &touched {
            if self.refill(leaf as usize, &dmark, new, &mut fresh) {
                emptied.push(leaf as usize);
            }
        }
        let mut recompute: Vec<usize> = touched.keys().map(|&l| l as usize).collect();
        self.drop_leaves(&emptied, parent, &mut recompute);
        if self.nodes.is_empty() {
            return self.rebuild(mesh);
        }
        self.recompute(&recompute);
        wide::collapse(&self.nodes, &mut self.wide);
        self.update_faces(&dmark, new_faces, &new_corners);
        self.stamp = now;
        Ok(UpdateReport {
            removed_triangles: removed,
            inserted_triangles: fresh.tris.len(),
            split_leaves: fresh.split,
            full_rebuild: false,
        })
    }

    /// The full rebuild branch of [`update`](FaceTree::update).
    fn rebuild(&mut self, mesh: &Mesh) -> Result<UpdateReport, QueryError> {
        *self = FaceTree::build(mesh)?;
        Ok(UpdateReport {
            inserted_triangles: self.tris.len(),
            full_rebuild: true,
            ..UpdateReport::default()
        })
    }

    /// Every reachable node's parent (`u32::MAX` for the root and
    /// unreachable nodes), the leaves holding dirty triangles with how many
    /// they hold, and the dirty faces: the `named` ones, and the `suspect`
    /// ones (around a modified vertex) whose triangles in the tree are not
    /// where their corners are now (a vertex counts as modified when only
    /// its links changed, too: those faces stay).
    fn dirty_leaves(
        &self,
        named: Vec<bool>,
        suspect: &[bool],
        pos: &[V3],
    ) -> (Vec<u32>, Vec<(u32, usize)>, Vec<bool>) {
        let mut parent = vec![u32::MAX; self.nodes.len()];
        let mut dmark = named;
        let mut seen = Vec::new();
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let n = self.nodes[i];
            if n.is_leaf() {
                let range = n.first as usize..(n.first + n.count) as usize;
                let mut any = false;
                for t in range {
                    let m = &self.meta[t];
                    if marked(&dmark, m.face) {
                        any = true;
                    } else if marked(suspect, m.face) {
                        any = true;
                        let now = m.v.map(|v| pos.get(v.index()).copied());
                        if now.iter().zip(&self.tris[t]).any(|(a, b)| *a != Some(*b)) {
                            set(&mut dmark, m.face.index());
                        }
                    }
                }
                if any {
                    seen.push(i as u32);
                }
            } else {
                let (a, b) = n.children(i);
                parent[a] = i as u32;
                parent[b] = i as u32;
                stack.push(b);
                stack.push(a);
            }
        }
        // A face found moved late in the walk may have triangles in
        // leaves seen before: count again with the marks complete.
        let lost = seen
            .into_iter()
            .filter_map(|i| {
                let n = self.nodes[i as usize];
                let range = n.first as usize..(n.first + n.count) as usize;
                let dead = self.meta[range]
                    .iter()
                    .filter(|m| marked(&dmark, m.face))
                    .count();
                (dead > 0).then_some((i, dead))
            })
            .collect();
        (parent, lost, dmark)
    }

    /// For each new triangle, the leaf it goes into: down from the root,
    /// into the child whose box's area grows least.
    fn place(&self, tris: &[[V3; 3]]) -> BTreeMap<u32, Vec<u32>> {
        let mut inserts: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
        for (i, t) in tris.iter().enumerate() {
            let (lo, hi) = build::bounds(std::slice::from_ref(t));
            let mut n = 0usize;
            while !self.nodes[n].is_leaf() {
                let (a, b) = self.nodes[n].children(n);
                let grow = |c: usize| {
                    let c = self.nodes[c];
                    let u = half_area(vec3::min(c.lo(), lo), vec3::max(c.hi(), hi));
                    (u - half_area(c.lo(), c.hi()), u)
                };
                n = if grow(a) <= grow(b) { a } else { b };
            }
            inserts.entry(n as u32).or_default().push(i as u32);
        }
        inserts
    }

    /// Take leaf `leaf`'s dirty triangles out (the survivors move to the
    /// front of its slots) and put fresh triangles `new` in (the leaf moves
    /// to new slots at the end, as a leaf or a subtree). Returns whether
    /// the leaf is left empty.
    fn refill(&mut self, leaf: usize, dmark: &[bool], new: &[u32], fresh: &mut Fresh) -> bool {
        let n = self.nodes[leaf];
        let (first, count) = (n.first as usize, n.count as usize);
        let mut live = first;
        for i in first..first + count {
            if !marked(dmark, self.meta[i].face) {
                self.tris[live] = self.tris[i];
                self.meta[live] = self.meta[i];
                live += 1;
            }
        }
        let live = live - first;
        if new.is_empty() {
            self.dead_tris += count - live;
            self.nodes[leaf].count = live as u32;
            return live == 0;
        }
        self.dead_tris += count;
        let mut tris = self.tris[first..first + live].to_vec();
        let mut meta = self.meta[first..first + live].to_vec();
        tris.extend(new.iter().map(|&i| fresh.tris[i as usize]));
        meta.extend(new.iter().map(|&i| fresh.meta[i as usize]));
        let base = self.tris.len() as u32;
        if tris.len() <= SPLIT_LEAF {
            self.tris.extend_from_slice(&tris);
            self.meta.extend_from_slice(&meta);
            self.nodes[leaf] = Node {
                first: base,
                count: tris.len() as u32,
                ..n
            };
            return false;
        }
        fresh.split += 1;
        let (nodes, order) = build::build(&tris);
        let at = self.nodes.len();
        for mut node in nodes {
            if node.is_leaf() {
                node.first += base;
            } else {
                node.first += at as u32;
            }
            self.nodes.push(node);
        }
        self.tris.extend(order.iter().map(|&i| tris[i as usize]));
        self.meta.extend(order.iter().map(|&i| meta[i as usize]));
        if let Some(d) = self.dipoles.get_mut() {
            d.resize(self.nodes.len(), Dipole::default());
        }
        for i in (at..self.nodes.len()).rev() {
            self.bound(i);
        }
        // The subtree's root takes the leaf's place (its old slot stays
        // unreached).
        self.nodes[leaf] = self.nodes[at].moved(at, leaf);
        false
    }

    /// Take the emptied leaves out: each one's sibling takes its parent's
    /// place. The nodes whose boxes shrink join `recompute`.
    fn drop_leaves(&mut self, emptied: &[usize], mut parent: Vec<u32>, recompute: &mut Vec<usize>) {
        for &leaf in emptied {
            let p = parent[leaf];
            let p = p as usize;
            let sibling = match p {
                _ if p == u32::MAX as usize => None,
                _ => {
                    let (a, b) = self.nodes[p].children(p);
                    Some(if a == leaf { b } else { a })
                }
            };
            let Some(sibling) = sibling.filter(|s| !emptied.contains(s) || parent[p] != u32::MAX)
            else {
                // The root, or both children of the root, emptied: the tree
                // is empty.
                self.nodes.clear();
                return;
            };
            let g = parent[p];
            if g == u32::MAX {
                // The parent is the root, which stays at index 0.
                let s = self.nodes[sibling].moved(sibling, 0);
                self.nodes[0] = s;
                if !s.is_leaf() {
                    let (x, y) = s.children(0);
                    for c in [x, y] {
                        if let Some(pc) = parent.get_mut(c) {
                            *pc = 0;
                        }
                    }
                }
                recompute.push(0);
                continue;
            }
            let g = g as usize;
            let (ga, _) = self.nodes[g].children(g);
            if ga == p {
                self.nodes[g].count = Node::inner(g, sibling);
            } else {
                self.nodes[g].first = sibling as u32;
            }
            parent[sibling] = g as u32;
            recompute.push(g);
        }
    }

    /// Recompute the boxes and far-field data of `nodes` and of every node
    /// above them, children before parents (a child's index is above its
    /// parent's).
    fn recompute(&mut self, nodes: &[usize]) {
        let mut parent = vec![u32::MAX; self.nodes.len()];
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let n = self.nodes[i];
            if !n.is_leaf() {
                let (a, b) = n.children(i);
                parent[a] = i as u32;
                parent[b] = i as u32;
                stack.push(b);
                stack.push(a);
            }
        }
        let mut all: HashSet<usize> = HashSet::new();
        // Nodes no longer reached (emptied leaves, replaced parents) are
        // left alone.
        for &i in nodes.iter().filter(|&&i| i == 0 || parent[i] != u32::MAX) {
            let mut i = i;
            while all.insert(i) {
                match parent[i] {
                    u32::MAX => break,
                    p => i = p as usize,
                }
            }
        }
        let mut all: Vec<usize> = all.into_iter().collect();
        all.sort_unstable_by(|a, b| b.cmp(a));
        for i in all {
            self.bound(i);
        }
    }

    /// Node `i`'s box from its triangles or children, and its far-field
    /// data if the tree has made it.
    fn bound(&mut self, i: usize) {
        self.fit_box(i);
        if let Some(dipoles) = self.dipoles.get_mut() {
            dipoles[i] = super::node_dipole(&self.nodes, &self.tris, dipoles, i);
        }
    }

    /// Mark the dirty faces' records gone and append the re-added ones;
    /// compact the records when the gone ones outnumber the live.
    fn update_faces(
        &mut self,
        dmark: &[bool],
        added: Vec<(FaceKey, u32, u32)>,
        added_corners: &[VertexKey],
    ) {
        for r in self.faces.iter_mut() {
            if r.2 != GONE && marked(dmark, r.0) {
                r.2 = GONE;
                self.dead_faces += 1;
            }
        }
        let base = self.corners.len() as u32;
        self.corners.extend_from_slice(added_corners);
        self.faces
            .extend(added.into_iter().map(|(f, s, l)| (f, s + base, l)));
        if self.dead_faces * 2 <= self.faces.len() {
            return;
        }
        let mut corners = Vec::with_capacity(self.corners.len());
        self.faces.retain(|r| r.2 != GONE);
        for r in self.faces.iter_mut() {
            let s = corners.len() as u32;
            corners.extend_from_slice(&self.corners[r.1 as usize..(r.1 + r.2) as usize]);
            r.1 = s;
        }
        self.corners = corners;
        self.dead_faces = 0;
    }
}

/// The fresh fan triangles of an update, and the leaves it split.
#[derive(Default)]
struct Fresh {
    tris: Vec<[V3; 3]>,
    meta: Vec<TriMeta>,
    split: usize,
}

/// Two bits per face slot: the faces the change set names (dirty), and
/// the faces now around its modified vertices (suspect: dirty if a corner
/// moved). A face whose corner moved is around that vertex now (had its
/// corners changed, the change set would name it), and a face with a
/// removed corner was removed or modified, so the two hold every face
/// whose fan triangles in the tree are out of date.
fn dirty_marks(mesh: &Mesh, changes: &Changes) -> (Vec<bool>, Vec<bool>) {
    let mut named = Vec::new();
    let f = &changes.faces;
    for &k in f.created.iter().chain(&f.removed).chain(&f.modified) {
        set(&mut named, k.index());
    }
    let mut suspect = Vec::new();
    for &v in &changes.vertices.modified {
        if let Ok(view) = mesh.vertex(v) {
            for k in view.faces() {
                set(&mut suspect, k.index());
            }
        }
    }
    (named, suspect)
}

/// The fan triangles of the dirty faces that are faces now (live, not
/// holes), with their face records and corners.
fn fresh_fans(
    mesh: &Mesh,
    changes: &Changes,
    dmark: &[bool],
    pos: &[V3],
) -> (Fresh, Vec<(FaceKey, u32, u32)>, Vec<VertexKey>) {
    let f = &changes.faces;
    let mut cands: Vec<FaceKey> = f.created.iter().chain(&f.modified).copied().collect();
    for &v in &changes.vertices.modified {
        if let Ok(view) = mesh.vertex(v) {
            cands.extend(view.faces());
        }
    }
    let mut seen = HashSet::new();
    let mut fresh = Fresh::default();
    let (mut faces, mut corners) = (Vec::new(), Vec::new());
    for k in cands {
        if !marked(dmark, k) || !seen.insert(k) {
            continue;
        }
        let Ok(view) = mesh.face(k) else { continue };
        if view.is_hole() {
            continue;
        }
        let start = corners.len();
        corners.extend(view.vertices());
        faces.push((k, start as u32, (corners.len() - start) as u32));
        fan(k, &corners[start..], pos, &mut fresh.tris, &mut fresh.meta);
    }
    (fresh, faces, corners)
}

/// Append face `f`'s fan triangles (corners `cs`).
fn fan(f: FaceKey, cs: &[VertexKey], pos: &[V3], tris: &mut Vec<[V3; 3]>, meta: &mut Vec<TriMeta>) {
    for i in 1..cs.len().saturating_sub(1) {
        let v = [cs[0], cs[i], cs[i + 1]];
        tris.push(v.map(|v| pos[v.index()]));
        meta.push(TriMeta {
            face: f,
            v,
            fan: i as u32,
        });
    }
}

fn set(bits: &mut Vec<bool>, i: usize) {
    if bits.len() <= i {
        bits.resize(i + 1, false);
    }
    bits[i] = true;
}

fn marked(bits: &[bool], f: FaceKey) -> bool {
    bits.get(f.index()) == Some(&true)
}

/// Half the surface area of a box.
fn half_area(lo: V3, hi: V3) -> f64 {
    let d = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}
