//! The policies themselves, each a pass over the soup that keeps its
//! provenance.

use std::collections::HashMap;

use super::split;
use super::Provenance;
use crate::build::Polygons;
use crate::mesh::Mesh;

const NONE: u32 = u32::MAX;

/// The soup under repair, with its provenance.
pub(super) struct Soup {
    pub(super) positions: Vec<[f64; 3]>,
    pub(super) vertex_count: usize,
    pub(super) offsets: Vec<u32>,
    pub(super) indices: Vec<u32>,
    pub(super) prov: Provenance,
}

impl Soup {
    pub(super) fn face_count(&self) -> usize {
        self.offsets.len() - 1
    }

    fn face(&self, f: usize) -> std::ops::Range<usize> {
        self.offsets[f] as usize..self.offsets[f + 1] as usize
    }

    /// Add a copy of vertex `v`; returns its index.
    fn copy_vertex(&mut self, v: u32) -> u32 {
        let n = self.vertex_count as u32;
        if !self.positions.is_empty() {
            self.positions.push(self.positions[v as usize]);
        }
        let src = self.prov.vertex_source[v as usize];
        self.prov.vertex_source.push(src);
        self.vertex_count += 1;
        n
    }

    /// Keep the vertices with `keep[v]`, renumbered densely.
    fn compact_vertices(&mut self, new_of: &[u32]) {
        let mut positions = Vec::new();
        let mut source = Vec::new();
        for (v, &n) in new_of.iter().enumerate() {
            if n != NONE && n as usize == source.len() {
                if !self.positions.is_empty() {
                    positions.push(self.positions[v]);
                }
                source.push(self.prov.vertex_source[v]);
            }
        }
        for i in &mut self.indices {
            *i = new_of[*i as usize];
        }
        self.vertex_count = source.len();
        self.positions = positions;
        self.prov.vertex_source = source;
    }

    /// Rebuild the faces from per-face corner lists (input corner indices).
    fn rebuild_faces(&mut self, faces: impl Iterator<Item = (u32, Vec<u32>)>) {
        let mut offsets = vec![0u32];
        let mut indices = Vec::with_capacity(self.indices.len());
        let mut face_source = Vec::with_capacity(self.face_count());
        let mut corner_source = Vec::with_capacity(self.indices.len());
        let faces: Vec<_> = faces.collect();
        for (f, corners) in faces {
            for c in corners {
                indices.push(self.indices[c as usize]);
                corner_source.push(self.prov.corner_source[c as usize]);
            }
            offsets.push(indices.len() as u32);
            face_source.push(self.prov.face_source[f as usize]);
        }
        self.offsets = offsets;
        self.indices = indices;
        self.prov.face_source = face_source;
        self.prov.corner_source = corner_source;
    }

    /// Weld bit-identical positions of one class where the result stays
    /// manifold; returns (vertices welded away, vertices left apart).
    ///
    /// Every group of coincident vertices is merged, then each merged
    /// vertex that is not manifold in the result (see
    /// [`nonmanifold_vertices`]) has its group taken apart again, until no
    /// merged vertex is left non-manifold: a few rounds, each O(C log C);
    /// after 16 the weld is given up whole.
    pub(super) fn weld(&mut self, class: &[u32]) -> (usize, usize) {
        if self.positions.is_empty() {
            return (0, 0);
        }
        let nv = self.positions.len();
        let mut first: HashMap<([u64; 3], u32), u32> = HashMap::with_capacity(nv);
        let mut rep = vec![0u32; nv];
        let mut size = vec![0u32; nv];
        for (v, p) in self.positions.iter().enumerate() {
            let key = (
                [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()],
                class.get(v).copied().unwrap_or(0),
            );
            let r = *first.entry(key).or_insert(v as u32);
            rep[v] = r;
            size[r as usize] += 1;
        }
        drop(first);
        let coincident = (0..nv).filter(|&v| rep[v] as usize != v).count();
        if coincident == 0 {
            return (0, 0);
        }
        // Groups still merged: `active[r]` for the first vertex r of each.
        let mut active: Vec<bool> = size.iter().map(|&s| s > 1).collect();
        let next = self.next_corners();
        let face_of = self.corner_faces();
        let mut mapped = vec![0u32; self.indices.len()];
        let mut settled = false;
        for _round in 0..16 {
            for (m, &i) in mapped.iter_mut().zip(&self.indices) {
                let r = rep[i as usize];
                *m = if active[r as usize] { r } else { i };
            }
            let bad = nonmanifold_vertices(&mapped, &next, &face_of, nv);
            let mut undone = false;
            for r in 0..nv {
                if bad[r] && active[r] {
                    active[r] = false;
                    undone = true;
                }
            }
            if !undone {
                settled = true;
                break;
            }
        }
        if !settled {
            active.iter_mut().for_each(|a| *a = false);
        }
        let mut new_of = vec![NONE; nv];
        let mut n = 0u32;
        for v in 0..nv {
            let r = rep[v] as usize;
            if r == v || !active[r] {
                new_of[v] = n;
                n += 1;
            }
        }
        for v in 0..nv {
            let r = rep[v] as usize;
            if r != v && active[r] {
                new_of[v] = new_of[r];
            }
        }
        let welded = nv - n as usize;
        if welded > 0 {
            self.compact_vertices(&new_of);
        }
        (welded, coincident - welded)
    }

    /// Whether the builder refuses these polygons (then the defect
    /// policies run). Unreferenced vertices alone are no reason: the
    /// builder drops them.
    pub(super) fn needs_repair(&mut self) -> bool {
        let p = Polygons {
            positions: std::mem::take(&mut self.positions),
            offsets: std::mem::take(&mut self.offsets),
            indices: std::mem::take(&mut self.indices),
        };
        let refused = Mesh::from_buffers(&p).is_err();
        self.positions = p.positions;
        self.offsets = p.offsets;
        self.indices = p.indices;
        refused
    }

    /// Give a renumbered topology-only soup its caller's numbering back:
    /// the first `dense` vertices are the input's (their sources are their
    /// indices), copies made since follow index `implied - 1`.
    pub(super) fn restore_numbering(&mut self, implied: usize, dense: usize) {
        let src = std::mem::take(&mut self.prov.vertex_source);
        let new_of: Vec<u32> = (0..self.vertex_count)
            .map(|d| {
                if d < dense {
                    src[d]
                } else {
                    (implied + d - dense) as u32
                }
            })
            .collect();
        for i in &mut self.indices {
            *i = new_of[*i as usize];
        }
        let mut source: Vec<u32> = (0..implied as u32).collect();
        source.extend_from_slice(&src[dense..]);
        self.vertex_count = source.len();
        self.prov.vertex_source = source;
    }

    /// Collapse runs of one vertex in a face, split faces that visit a
    /// vertex twice into simple ones ([`split::simple_pieces`]), and drop
    /// faces left with no area; returns (corners collapsed, faces dropped,
    /// faces split).
    pub(super) fn drop_degenerate(&mut self) -> (usize, usize, usize) {
        let mut collapsed = 0;
        let mut dropped = 0;
        let mut split_faces = 0;
        let mut kept = Vec::with_capacity(self.face_count());
        let mut changed = false;
        for f in 0..self.face_count() {
            let r = self.face(f);
            let n = r.len();
            // Keep a corner unless the corner after it (cyclically) is the
            // same vertex: the last of each run stays, the first corner of
            // the face stays first.
            let corners: Vec<u32> = r
                .clone()
                .filter(|&c| {
                    let next = if c + 1 == r.end { r.start } else { c + 1 };
                    n < 2 || self.indices[c] != self.indices[next]
                })
                .map(|c| c as u32)
                .collect();
            // A face whose corners are all one vertex keeps none above.
            let distinct = corners.len() >= 3 && {
                let mut vs: Vec<u32> = corners.iter().map(|&c| self.indices[c as usize]).collect();
                vs.sort_unstable();
                vs.windows(2).all(|w| w[0] != w[1])
            };
            // Corners collapsed count for faces that stay (whole or in
            // pieces).
            let runs = n - corners.len();
            if distinct {
                collapsed += runs;
                changed |= runs > 0;
                kept.push((f as u32, corners));
                continue;
            }
            // A vertex at two separate corners: simple pieces over the
            // same area, each keeping the face's own corners.
            changed = true;
            let pieces = split::simple_pieces(&corners, &self.indices, &self.positions);
            if pieces.is_empty() {
                dropped += 1;
            } else {
                collapsed += runs;
                split_faces += 1;
            }
            kept.extend(pieces.into_iter().map(|p| (f as u32, p)));
        }
        if changed {
            self.rebuild_faces(kept.into_iter());
        }
        (collapsed, dropped, split_faces)
    }

    pub(super) fn drop_duplicates(&mut self) -> usize {
        let mut sorted = self.indices.clone();
        for f in 0..self.face_count() {
            sorted[self.face(f)].sort_unstable();
        }
        let mut seen: HashMap<&[u32], ()> = HashMap::with_capacity(self.face_count());
        let mut keep = vec![true; self.face_count()];
        let mut dropped = 0;
        for (f, k) in keep.iter_mut().enumerate() {
            if seen.insert(&sorted[self.face(f)], ()).is_some() {
                *k = false;
                dropped += 1;
            }
        }
        drop(seen);
        if dropped > 0 {
            let faces: Vec<(u32, Vec<u32>)> = (0..self.face_count())
                .filter(|&f| keep[f])
                .map(|f| (f as u32, self.face(f).map(|c| c as u32).collect()))
                .collect();
            self.rebuild_faces(faces.into_iter());
        }
        dropped
    }

    /// The corner after `c` in its face, for every corner.
    fn next_corners(&self) -> Vec<u32> {
        let mut next = vec![0u32; self.indices.len()];
        for f in 0..self.face_count() {
            let r = self.face(f);
            for c in r.clone() {
                next[c] = if c + 1 == r.end { r.start } else { c + 1 } as u32;
            }
        }
        next
    }

    /// Corners grouped by their undirected edge: `(order, starts)` where
    /// group `g` is `order[starts[g]..starts[g + 1]]`, each in corner order.
    fn edge_groups(&self, next: &[u32]) -> (Vec<u32>, Vec<u32>) {
        edge_groups(&self.indices, next)
    }

    /// The face of every corner.
    fn corner_faces(&self) -> Vec<u32> {
        let mut face_of = vec![0u32; self.indices.len()];
        for f in 0..self.face_count() {
            for c in self.face(f) {
                face_of[c] = f as u32;
            }
        }
        face_of
    }

    pub(super) fn orient(&mut self) -> (usize, usize) {
        let next = self.next_corners();
        let (order, starts) = self.edge_groups(&next);
        let face_of = self.corner_faces();
        // Partner corner across each edge used by exactly two faces.
        let mut partner = vec![NONE; self.indices.len()];
        for g in starts.windows(2) {
            if g[1] - g[0] == 2 {
                let (c, d) = (order[g[0] as usize], order[g[0] as usize + 1]);
                if face_of[c as usize] != face_of[d as usize] {
                    partner[c as usize] = d;
                    partner[d as usize] = c;
                }
            }
        }
        let nf = self.face_count();
        let mut flip: Vec<u8> = vec![2; nf]; // 2 = not reached
        let mut conflicts = 0;
        let mut queue = Vec::new();
        let mut flips = 0;
        for seed in 0..nf {
            if flip[seed] != 2 {
                continue;
            }
            flip[seed] = 0;
            queue.clear();
            queue.push(seed as u32);
            let mut head = 0;
            let mut flipped_here = 0;
            while head < queue.len() {
                let f = queue[head] as usize;
                head += 1;
                for c in self.face(f) {
                    let p = partner[c];
                    if p == NONE {
                        continue;
                    }
                    let g = face_of[p as usize] as usize;
                    let same = self.indices[c] == self.indices[p as usize];
                    let want = flip[f] ^ u8::from(same);
                    if flip[g] == 2 {
                        flip[g] = want;
                        flipped_here += usize::from(want);
                        queue.push(g as u32);
                    } else if flip[g] != want && f < g {
                        conflicts += 1;
                    }
                }
            }
            if 2 * flipped_here > queue.len() {
                for &f in &queue {
                    flip[f as usize] ^= 1;
                }
                flipped_here = queue.len() - flipped_here;
            }
            flips += flipped_here;
        }
        if flips > 0 {
            let faces: Vec<(u32, Vec<u32>)> = (0..nf)
                .map(|f| {
                    let r = self.face(f);
                    let mut corners: Vec<u32> = r.clone().map(|c| c as u32).collect();
                    if flip[f] == 1 {
                        corners[1..].reverse();
                    }
                    (f as u32, corners)
                })
                .collect();
            self.rebuild_faces(faces.into_iter());
        }
        (flips, conflicts)
    }

    pub(super) fn split_edges(&mut self) -> (usize, usize) {
        let next = self.next_corners();
        let (order, starts) = self.edge_groups(&next);
        let face_of = self.corner_faces();
        let mut bad = 0;
        // (face, vertex) pairs that get their own copy.
        let mut detach: Vec<(u32, u32)> = Vec::new();
        for g in starts.windows(2) {
            let group = &order[g[0] as usize..g[1] as usize];
            if group.len() < 2 {
                continue;
            }
            let dir = |c: u32| self.indices[c as usize] < self.indices[next[c as usize] as usize];
            let distinct_faces =
                group.len() == 2 && face_of[group[0] as usize] != face_of[group[1] as usize];
            if group.len() == 2 && dir(group[0]) != dir(group[1]) && distinct_faces {
                continue;
            }
            bad += 1;
            // Keep the first pair of opposite uses, or the first use alone.
            let mut keep = [group[0], NONE];
            'pair: for (i, &c) in group.iter().enumerate() {
                for &d in &group[i + 1..] {
                    if dir(c) != dir(d) && face_of[c as usize] != face_of[d as usize] {
                        keep = [c, d];
                        break 'pair;
                    }
                }
            }
            for &c in group {
                if !keep.contains(&c) {
                    let f = face_of[c as usize];
                    detach.push((f, self.indices[c as usize]));
                    detach.push((f, self.indices[next[c as usize] as usize]));
                }
            }
        }
        detach.sort_unstable();
        detach.dedup();
        let copies = detach.len();
        for &(f, v) in &detach {
            let nv = self.copy_vertex(v);
            for c in self.face(f as usize) {
                if self.indices[c] == v {
                    self.indices[c] = nv;
                }
            }
        }
        (bad, copies)
    }

    pub(super) fn split_vertices(&mut self) -> (usize, usize) {
        let next = self.next_corners();
        let (order, starts) = self.edge_groups(&next);
        let nc = self.indices.len();
        // Union corners at one vertex across each edge shared by two faces
        // in opposite directions: corner c (a->b) and partner d (b->a) make
        // corner next(d) at a the neighbour of c.
        let mut parent: Vec<u32> = (0..nc as u32).collect();
        let mut paired_out = vec![false; nc];
        for g in starts.windows(2) {
            if g[1] - g[0] != 2 {
                continue;
            }
            let (c, d) = (order[g[0] as usize], order[g[0] as usize + 1]);
            if self.indices[c as usize] == self.indices[d as usize] {
                continue;
            }
            paired_out[c as usize] = true;
            paired_out[d as usize] = true;
            union(&mut parent, c, next[d as usize]);
            union(&mut parent, d, next[c as usize]);
        }
        // prev corner of each corner: its incoming edge.
        let mut prev = vec![0u32; nc];
        for c in 0..nc {
            prev[next[c] as usize] = c as u32;
        }
        // Per vertex: its fans (roots) and whether each is open.
        let mut corners_by_vertex: Vec<(u32, u32, u32)> = (0..nc as u32)
            .map(|c| (self.indices[c as usize], find(&mut parent, c), c))
            .collect();
        corners_by_vertex.sort_unstable();
        let mut split = 0;
        let mut copies = 0;
        let mut i = 0;
        while i < nc {
            let v = corners_by_vertex[i].0;
            let mut j = i;
            while j < nc && corners_by_vertex[j].0 == v {
                j += 1;
            }
            let fans = &corners_by_vertex[i..j];
            let fan_count = 1 + fans.windows(2).filter(|w| w[0].1 != w[1].1).count();
            if fan_count > 1 {
                let any_closed = fans.chunk_by(|a, b| a.1 == b.1).any(|fan| {
                    fan.iter().all(|&(_, _, c)| {
                        paired_out[c as usize] && paired_out[prev[c as usize] as usize]
                    })
                });
                if any_closed {
                    split += 1;
                    for fan in fans.chunk_by(|a, b| a.1 == b.1).skip(1) {
                        let nv = self.copy_vertex(v);
                        copies += 1;
                        for &(_, _, c) in fan {
                            self.indices[c as usize] = nv;
                        }
                    }
                }
            }
            i = j;
        }
        (split, copies)
    }

    pub(super) fn drop_unreferenced(&mut self) -> usize {
        let mut used = vec![false; self.vertex_count];
        for &i in &self.indices {
            used[i as usize] = true;
        }
        let dropped = used.iter().filter(|&&u| !u).count();
        if dropped > 0 {
            let mut n = 0u32;
            let new_of: Vec<u32> = used
                .iter()
                .map(|&u| {
                    if u {
                        n += 1;
                        n - 1
                    } else {
                        NONE
                    }
                })
                .collect();
            self.compact_vertices(&new_of);
        }
        dropped
    }
}

/// Corners of `indices` grouped by their undirected edge (see
/// [`Soup::edge_groups`]).
fn edge_groups(indices: &[u32], next: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let key = |c: usize| {
        let (a, b) = (indices[c], indices[next[c] as usize]);
        (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
    };
    let mut order: Vec<u32> = (0..indices.len() as u32).collect();
    order.sort_unstable_by_key(|&c| (key(c as usize), c));
    let mut starts = Vec::new();
    for (i, &c) in order.iter().enumerate() {
        if i == 0 || key(c as usize) != key(order[i - 1] as usize) {
            starts.push(i as u32);
        }
    }
    starts.push(order.len() as u32);
    (order, starts)
}

/// The vertices of `indices` (renumbered, every one below `n`) that are
/// not manifold: on an edge used by more than two faces or twice in one
/// direction or twice by one face, repeated in a face, or with more than
/// one fan of faces (open fans too). `marked[v]` is set for each.
fn nonmanifold_vertices(indices: &[u32], next: &[u32], face_of: &[u32], n: usize) -> Vec<bool> {
    let nc = indices.len();
    let mut marked = vec![false; n];
    let (order, starts) = edge_groups(indices, next);
    let mut parent: Vec<u32> = (0..nc as u32).collect();
    for g in starts.windows(2) {
        let group = &order[g[0] as usize..g[1] as usize];
        let (c, d) = (
            group[0] as usize,
            *group.last().unwrap_or(&group[0]) as usize,
        );
        let (a, b) = (indices[c], indices[next[c] as usize]);
        if a == b {
            marked[a as usize] = true;
            continue;
        }
        let opposite = group.len() == 2 && indices[c] == indices[next[d] as usize];
        if group.len() > 2 || (group.len() == 2 && (!opposite || face_of[c] == face_of[d])) {
            marked[a as usize] = true;
            marked[b as usize] = true;
        } else if group.len() == 2 {
            union(&mut parent, c as u32, next[d]);
            union(&mut parent, d as u32, next[c]);
        }
    }
    // One root per fan: a vertex whose corners have two roots has two fans;
    // a face with a vertex at two corners repeats it.
    let mut root_of_vertex = vec![NONE; n];
    for (c, &v) in indices.iter().enumerate() {
        let v = v as usize;
        let r = find(&mut parent, c as u32);
        if root_of_vertex[v] == NONE {
            root_of_vertex[v] = r;
        } else if root_of_vertex[v] != r {
            marked[v] = true;
        }
    }
    let mut last_face = vec![NONE; n];
    for (&v, &f) in indices.iter().zip(face_of) {
        let v = v as usize;
        if last_face[v] == f {
            marked[v] = true;
        }
        last_face[v] = f;
    }
    marked
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[parent[x as usize] as usize];
        parent[x as usize] = p;
        x = p;
    }
    x
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        parent[hi as usize] = lo;
    }
}
