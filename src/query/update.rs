//! [`FaceTree::update`]: bring a tree up to date from the journal's change
//! set instead of rebuilding it.
//!
//! The faces the change set names (created, removed, modified) and the
//! faces with a corner at a modified or removed vertex are *dirty*: their
//! fan triangles leave the tree, and those that are faces now (not holes)
//! are cut into fans again and inserted, each into the leaf whose box grows
//! least (in surface area) on the way down from the root. Only the touched
//! leaves and their ancestors are recomputed; a touched leaf that grows past
//! [`SPLIT_LEAF`] triangles is rebuilt as a binned-SAH subtree, an emptied
//! leaf disappears (its sibling takes its parent's place).
//!
//! # When it rebuilds instead
//!
//! Greedy insertion keeps the answers exact but lets the hierarchy's quality
//! drift, so the whole tree is rebuilt when
//! - the change set says the mesh was [rebuilt](crate::journal::Changes::rebuilt),
//! - the triangles removed plus inserted by this update exceed a quarter of
//!   the tree's, or
//! - those reinserted since the last full build exceed half of the tree's
//!   (the drift bound).

use std::collections::{HashMap, HashSet};

use super::{build, winding, Dipole, FaceTree, Node, QueryError, TriMeta};
use crate::journal::Changes;
use crate::keys::{FaceKey, VertexKey};
use crate::mesh::Mesh;
use crate::vec3::V3;

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

/// The new arrays, emitted depth-first.
struct Out {
    nodes: Vec<Node>,
    tris: Vec<[V3; 3]>,
    meta: Vec<TriMeta>,
    dipoles: Vec<Dipole>,
    split: usize,
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
    /// O(n) copying of the tree's arrays plus O(k log n) for k dirty
    /// triangles, far below a rebuild's O(n log n). It rebuilds the whole
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
        let (dmark, dirty) = self.dirty_faces(changes);
        let added = readd(mesh, changes, &dmark, dirty);
        let mut new_tris = Vec::new();
        let mut new_meta = Vec::new();
        let mut new_corners = Vec::new();
        let mut new_faces = Vec::new();
        for (f, cs) in &added {
            let start = new_corners.len();
            new_corners.extend_from_slice(cs);
            new_faces.push((*f, start as u32, cs.len() as u32));
            fan(*f, cs, pos, &mut new_tris, &mut new_meta);
        }
        let dead: Vec<bool> = self.meta.iter().map(|m| marked(&dmark, m.face)).collect();
        let removed = dead.iter().filter(|&&d| d).count();
        let churn = removed + new_tris.len();
        self.churn += churn;
        if churn * 4 > self.tris.len() || self.churn * 2 > self.tris.len() {
            return self.rebuild(mesh);
        }
        let inserts = self.place(&new_tris);
        let out = self.emit(&dead, &inserts, &new_tris, &new_meta);
        self.nodes = out.nodes;
        self.tris = out.tris;
        self.meta = out.meta;
        self.dipoles = out.dipoles;
        self.update_faces(&dmark, new_faces, &new_corners);
        self.stamp = now;
        Ok(UpdateReport {
            removed_triangles: removed,
            inserted_triangles: new_tris.len(),
            split_leaves: out.split,
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

    /// The dirty faces' slots (a bit per face slot) and the keys of the
    /// dirty faces the tree holds.
    fn dirty_faces(&self, changes: &Changes) -> (Vec<bool>, Vec<FaceKey>) {
        let mut vmark = Vec::new();
        for &v in changes
            .vertices
            .modified
            .iter()
            .chain(&changes.vertices.removed)
        {
            set(&mut vmark, v.index());
        }
        let mut dmark = Vec::new();
        let f = &changes.faces;
        for &k in f.created.iter().chain(&f.removed).chain(&f.modified) {
            set(&mut dmark, k.index());
        }
        let mut dirty = Vec::new();
        for &(f, start, len) in &self.faces {
            let cs = &self.corners[start as usize..(start + len) as usize];
            if marked(&dmark, f) || cs.iter().any(|v| vmark.get(v.index()) == Some(&true)) {
                dirty.push(f);
            }
        }
        for &f in &dirty {
            set(&mut dmark, f.index());
        }
        (dmark, dirty)
    }

    /// For each new triangle, the leaf it goes into: down from the root,
    /// into the child whose box's area grows least.
    fn place(&self, tris: &[[V3; 3]]) -> HashMap<u32, Vec<u32>> {
        let mut inserts: HashMap<u32, Vec<u32>> = HashMap::new();
        for (i, t) in tris.iter().enumerate() {
            let (lo, hi) = build::bounds(std::slice::from_ref(t));
            let mut n = 0usize;
            while self.nodes[n].count == 0 {
                let (a, b) = (n + 1, self.nodes[n].first as usize);
                let grow = |c: usize| {
                    let c = self.nodes[c];
                    let u = half_area(build::min3(c.lo(), lo), build::max3(c.hi(), hi));
                    (u - half_area(c.lo(), c.hi()), u)
                };
                n = if grow(a) <= grow(b) { a } else { b };
            }
            inserts.entry(n as u32).or_default().push(i as u32);
        }
        inserts
    }

    /// The tree's arrays without the dead triangles and with the inserted
    /// ones, untouched subtrees copied as blocks.
    fn emit(
        &self,
        dead: &[bool],
        inserts: &HashMap<u32, Vec<u32>>,
        new_tris: &[[V3; 3]],
        new_meta: &[TriMeta],
    ) -> Out {
        // Touched nodes: leaves losing or gaining triangles, and their
        // ancestors; per touched node, its triangle count afterwards.
        let mut parent = vec![u32::MAX; self.nodes.len()];
        let mut after: HashMap<u32, usize> = HashMap::new();
        for (i, n) in self.nodes.iter().enumerate() {
            if n.count == 0 {
                parent[i + 1] = i as u32;
                parent[n.first as usize] = i as u32;
            } else {
                let r = n.first as usize..(n.first + n.count) as usize;
                let lost = dead[r].iter().filter(|&&d| d).count();
                let gained = inserts.get(&(i as u32)).map_or(0, Vec::len);
                if lost > 0 || gained > 0 {
                    after.insert(i as u32, n.count as usize - lost + gained);
                }
            }
        }
        let mut ancestors = HashSet::new();
        for &leaf in after.keys() {
            let mut p = parent[leaf as usize];
            while p != u32::MAX && ancestors.insert(p) {
                p = parent[p as usize];
            }
        }
        let mut inner: Vec<u32> = ancestors.into_iter().collect();
        // Children before parents: a child's index is above its parent's.
        inner.sort_unstable_by(|a, b| b.cmp(a));
        for p in inner {
            let (a, b) = (p + 1, self.nodes[p as usize].first);
            // An untouched subtree is not empty.
            let count = |c: u32| after.get(&c).copied().unwrap_or(1);
            let c = count(a) + count(b);
            after.insert(p, c);
        }
        let mut out = Out {
            nodes: Vec::with_capacity(self.nodes.len() + new_tris.len()),
            tris: Vec::with_capacity(self.tris.len() + new_tris.len()),
            meta: Vec::with_capacity(self.tris.len() + new_tris.len()),
            dipoles: Vec::with_capacity(self.nodes.len() + new_tris.len()),
            split: 0,
        };
        let ctx = Emit {
            tree: self,
            dead,
            inserts,
            new_tris,
            new_meta,
            after: &after,
        };
        if after.get(&0).is_none_or(|&c| c > 0) {
            ctx.node(0, &mut out);
        }
        out
    }

    /// The face records without the dirty faces, plus the re-added ones.
    fn update_faces(
        &mut self,
        dmark: &[bool],
        added: Vec<(FaceKey, u32, u32)>,
        added_corners: &[VertexKey],
    ) {
        let mut faces = Vec::with_capacity(self.faces.len() + added.len());
        let mut corners = Vec::with_capacity(self.corners.len() + added_corners.len());
        for &(f, start, len) in &self.faces {
            if !marked(dmark, f) {
                let s = corners.len() as u32;
                corners.extend_from_slice(&self.corners[start as usize..(start + len) as usize]);
                faces.push((f, s, len));
            }
        }
        let base = corners.len() as u32;
        corners.extend_from_slice(added_corners);
        faces.extend(added.into_iter().map(|(f, s, l)| (f, s + base, l)));
        self.faces = faces;
        self.corners = corners;
    }
}

/// The recursive emission of [`FaceTree::emit`].
struct Emit<'a> {
    tree: &'a FaceTree,
    dead: &'a [bool],
    inserts: &'a HashMap<u32, Vec<u32>>,
    new_tris: &'a [[V3; 3]],
    new_meta: &'a [TriMeta],
    /// Touched nodes' triangle counts afterwards.
    after: &'a HashMap<u32, usize>,
}

impl Emit<'_> {
    /// Emit old node `n`'s subtree (not empty); returns its new index.
    fn node(&self, n: u32, out: &mut Out) -> usize {
        let t = self.tree;
        let node = t.nodes[n as usize];
        if !self.after.contains_key(&n) {
            return self.copy(n, out);
        }
        if node.count > 0 {
            return self.leaf(n, out);
        }
        let (a, b) = (n + 1, node.first);
        let empty = |c: u32| self.after.get(&c) == Some(&0);
        if empty(a) {
            return self.node(b, out);
        }
        if empty(b) {
            return self.node(a, out);
        }
        let me = out.nodes.len();
        out.nodes.push(node);
        out.dipoles.push(Dipole::default());
        let na = self.node(a, out);
        let nb = self.node(b, out);
        let (ca, cb) = (out.nodes[na], out.nodes[nb]);
        let (lo, hi) = (build::min3(ca.lo(), cb.lo()), build::max3(ca.hi(), cb.hi()));
        out.nodes[me] = Node::new(lo, hi, nb as u32, 0);
        let d = winding::merge_dipoles(out.dipoles[na], out.dipoles[nb]);
        out.dipoles[me] = winding::with_radius(d, lo, hi);
        me
    }

    /// Copy untouched subtree `n` as a block.
    fn copy(&self, n: u32, out: &mut Out) -> usize {
        let t = self.tree;
        let (mut first, mut last) = (n as usize, n as usize);
        while t.nodes[first].count == 0 {
            first += 1;
        }
        while t.nodes[last].count == 0 {
            last = t.nodes[last].first as usize;
        }
        let tri0 = t.nodes[first].first as usize;
        let tri1 = (t.nodes[last].first + t.nodes[last].count) as usize;
        let me = out.nodes.len();
        let (dn, dt) = (me as i64 - n as i64, out.tris.len() as i64 - tri0 as i64);
        for node in &t.nodes[n as usize..=last] {
            let mut node = *node;
            let d = if node.count == 0 { dn } else { dt };
            node.first = (node.first as i64 + d) as u32;
            out.nodes.push(node);
        }
        out.dipoles.extend_from_slice(&t.dipoles[n as usize..=last]);
        out.tris.extend_from_slice(&t.tris[tri0..tri1]);
        out.meta.extend_from_slice(&t.meta[tri0..tri1]);
        me
    }

    /// Emit touched leaf `n`: its live triangles and the inserted ones, as
    /// a leaf or (when over [`SPLIT_LEAF`]) a subtree.
    fn leaf(&self, n: u32, out: &mut Out) -> usize {
        let t = self.tree;
        let node = t.nodes[n as usize];
        let mut tris = Vec::new();
        let mut meta = Vec::new();
        for i in node.first as usize..(node.first + node.count) as usize {
            if !self.dead[i] {
                tris.push(t.tris[i]);
                meta.push(t.meta[i]);
            }
        }
        for &i in self.inserts.get(&n).map_or(&[][..], Vec::as_slice) {
            tris.push(self.new_tris[i as usize]);
            meta.push(self.new_meta[i as usize]);
        }
        let me = out.nodes.len();
        let base = out.tris.len() as u32;
        if tris.len() > SPLIT_LEAF {
            out.split += 1;
            let (nodes, order) = build::build(&tris);
            for mut node in nodes {
                node.first += if node.count == 0 { me as u32 } else { base };
                out.nodes.push(node);
            }
            out.tris.extend(order.iter().map(|&i| tris[i as usize]));
            out.meta.extend(order.iter().map(|&i| meta[i as usize]));
        } else {
            let (lo, hi) = build::bounds(&tris);
            out.nodes.push(Node::new(lo, hi, base, tris.len() as u32));
            out.tris.extend_from_slice(&tris);
            out.meta.extend_from_slice(&meta);
        }
        out.dipoles.resize(out.nodes.len(), Dipole::default());
        for i in (me..out.nodes.len()).rev() {
            let k = out.nodes[i];
            let d = if k.count > 0 {
                winding::leaf_dipole(&out.tris[k.first as usize..(k.first + k.count) as usize])
            } else {
                winding::merge_dipoles(out.dipoles[i + 1], out.dipoles[k.first as usize])
            };
            out.dipoles[i] = winding::with_radius(d, k.lo(), k.hi());
        }
        me
    }
}

/// The dirty faces that are faces now, with their corners: the change
/// set's faces, the dirty faces the tree held and the faces around changed
/// vertices, if live, not holes and at a marked slot.
fn readd(
    mesh: &Mesh,
    changes: &Changes,
    dmark: &[bool],
    dirty: Vec<FaceKey>,
) -> Vec<(FaceKey, Vec<VertexKey>)> {
    let f = &changes.faces;
    let mut cands: Vec<FaceKey> = dirty;
    cands.extend(f.created.iter().chain(&f.modified));
    for &v in &changes.vertices.modified {
        if let Ok(view) = mesh.vertex(v) {
            cands.extend(view.faces());
        }
    }
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for k in cands {
        if !marked(dmark, k) || !seen.insert(k) {
            continue;
        }
        if let Ok(view) = mesh.face(k) {
            if !view.is_hole() {
                out.push((k, view.vertices().collect()));
            }
        }
    }
    out
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
