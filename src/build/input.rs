//! Stages 1 and 2 of the builder: the flat input, its checks (size, index
//! range, faces of three or more distinct corners, finite positions), and
//! the vertices some face uses, numbered densely.

use std::borrow::Cow;

use crate::error::{BuildError, Result};
use crate::geometry::Point;
use crate::layout::Vid;

/// Flat faces: face `f` is `indices[offsets[f]..offsets[f + 1]]`.
#[derive(Copy, Clone)]
pub(super) struct Flat<'a> {
    pub(super) offsets: &'a [u32],
    pub(super) indices: &'a [u32],
}

impl<'a> Flat<'a> {
    /// Number of faces.
    pub(super) fn face_count(self) -> usize {
        self.offsets.len() - 1
    }

    /// Face `f`'s corners.
    pub(super) fn face(self, f: usize) -> &'a [u32] {
        &self.indices[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }

    /// The same faces over other (renumbered) indices.
    pub(super) fn with_indices(self, indices: &'a [u32]) -> Flat<'a> {
        Flat {
            offsets: self.offsets,
            indices,
        }
    }

    /// Call `f(corner, origin, dest)` for every side of every face (faces
    /// have at least three corners: checked first).
    #[inline]
    pub(super) fn for_each_side(self, mut f: impl FnMut(usize, u32, u32)) {
        let indices = self.indices;
        for w in self.offsets.windows(2) {
            let (s, e) = (w[0] as usize, w[1] as usize);
            for c in s..e - 1 {
                f(c, indices[c], indices[c + 1]);
            }
            f(e - 1, indices[e - 1], indices[s]);
        }
    }

    /// The face a corner belongs to (error paths only).
    pub(super) fn face_of_corner(self, c: usize) -> usize {
        self.offsets.partition_point(|&o| o as usize <= c) - 1
    }
}

/// Refuse input whose corners would not fit the 32-bit links.
pub(super) fn check_size(input: Flat<'_>) -> Result<()> {
    if input.indices.len() >= (1 << 29) {
        return Err(BuildError::TooLarge {
            what: "more than 2^29 corners",
        }
        .into());
    }
    Ok(())
}

/// Every index must name one of the `n_in` input vertices.
pub(super) fn check_index_range(input: Flat<'_>, n_in: usize) -> Result<()> {
    if let Some(c) = input.indices.iter().position(|&i| i as usize >= n_in) {
        return Err(BuildError::IndexOutOfRange {
            face: input.face_of_corner(c),
            index: i64::from(input.indices[c]),
            vertex_count: n_in,
        }
        .into());
    }
    Ok(())
}

/// Stage 1, per face: at least three corners, no corner twice.
pub(super) fn check_faces(input: Flat<'_>) -> Result<()> {
    let mut scratch: Vec<u32> = Vec::new();
    for f in 0..input.face_count() {
        let face = input.face(f);
        if face.len() < 3 {
            return Err(BuildError::TooFewVertices {
                face: f,
                degree: face.len(),
            }
            .into());
        }
        let repeated = if face.len() <= 8 {
            (1..face.len()).find_map(|i| face[..i].contains(&face[i]).then_some(face[i]))
        } else {
            scratch.clear();
            scratch.extend_from_slice(face);
            scratch.sort_unstable();
            scratch
                .windows(2)
                .find_map(|w| (w[0] == w[1]).then_some(w[0]))
        };
        if let Some(v) = repeated {
            return Err(BuildError::RepeatedVertex {
                face: f,
                vertex: v as usize,
            }
            .into());
        }
    }
    Ok(())
}

/// Stages 1 and 2 in one pass over the corners, for good input: every
/// index in range, every face with three or more distinct corners, and the
/// used vertices marked as it goes. `None` when some face is bad (the
/// separate stages then name the first defect) or when the indices are
/// spread too wide for a bitset (the sorting path).
pub(super) fn scan_corners(input: Flat<'_>, n_in: usize) -> Option<UsedVertices<'_>> {
    let span = n_in.min(UsedVertices::dense_span_limit(input.indices.len()));
    let mut used = vec![0u64; span.div_ceil(64)];
    let mut mark = |v: u32| used[v as usize / 64] |= 1 << (v % 64);
    for w in input.offsets.windows(2) {
        let face = input.indices.get(w[0] as usize..w[1] as usize)?;
        match *face {
            [a, b, c] => {
                if a == b || b == c || c == a || a.max(b).max(c) as usize >= span {
                    return None;
                }
                mark(a);
                mark(b);
                mark(c);
            }
            _ => {
                if face.len() < 3 || face.len() > 8 {
                    return None;
                }
                for (i, &v) in face.iter().enumerate() {
                    if v as usize >= span || face[..i].contains(&v) {
                        return None;
                    }
                    mark(v);
                }
            }
        }
    }
    Some(UsedVertices::from_bitset(input.indices, n_in, span, &used))
}

/// Stage 2: the input vertices some face uses, numbered densely (a vertex
/// exists only while an edge touches it), and the corners renumbered.
pub(super) struct UsedVertices<'a> {
    /// Number of used vertices: the vertex slots.
    pub(super) count: usize,
    /// Input index of each slot; `None` when it is the identity (no vertex
    /// unused).
    pub(super) input_of_slot: Option<Vec<u32>>,
    /// The corners, by slot.
    pub(super) indices: Cow<'a, [u32]>,
}

impl<'a> UsedVertices<'a> {
    /// Memory and time stay linear in the corners whatever the indices: a
    /// dense bitset over the index span when the span is at most a few
    /// times the corner count, else a sort of the corners (a caller may
    /// claim billions of vertices and use three).
    pub(super) fn of(input: Flat<'a>, n_in: usize) -> Self {
        let indices = input.indices;
        let span = indices.iter().max().map_or(0, |&m| m as usize + 1);
        if span > Self::dense_span_limit(indices.len()) {
            return Self::sparse(indices);
        }
        let mut used = vec![0u64; span.div_ceil(64)];
        for &i in indices {
            used[i as usize / 64] |= 1 << (i % 64);
        }
        Self::from_bitset(indices, n_in, span, &used)
    }

    /// The used vertices from a bitset over the index span `0..span`.
    pub(super) fn from_bitset(indices: &'a [u32], n_in: usize, span: usize, used: &[u64]) -> Self {
        let count = used.iter().map(|w| w.count_ones() as usize).sum::<usize>();
        if count == n_in {
            return UsedVertices {
                count,
                input_of_slot: None,
                indices: Cow::Borrowed(indices),
            };
        }
        let input_of_slot: Vec<u32> = (0..span)
            .filter(|&i| used[i / 64] >> (i % 64) & 1 == 1)
            .map(|i| i as u32)
            .collect();
        let mut slot_of = vec![u32::MAX; span];
        for (slot, &i) in input_of_slot.iter().enumerate() {
            slot_of[i as usize] = slot as u32;
        }
        let renumbered = indices.iter().map(|&i| slot_of[i as usize]).collect();
        UsedVertices {
            count: input_of_slot.len(),
            input_of_slot: Some(input_of_slot),
            indices: Cow::Owned(renumbered),
        }
    }

    /// The largest index span the dense path takes for `corners` corners.
    pub(super) fn dense_span_limit(corners: usize) -> usize {
        2 * corners + 64
    }

    /// Used vertices of indices spread far wider than their number.
    pub(super) fn sparse(indices: &'a [u32]) -> Self {
        let mut input_of_slot = indices.to_vec();
        input_of_slot.sort_unstable();
        input_of_slot.dedup();
        let renumbered = indices
            .iter()
            .map(|i| input_of_slot.binary_search(i).unwrap_or(0) as u32)
            .collect();
        UsedVertices {
            count: input_of_slot.len(),
            input_of_slot: Some(input_of_slot),
            indices: Cow::Owned(renumbered),
        }
    }

    /// The input index of vertex slot `slot` (slots are `u32` as stored).
    pub(super) fn input(&self, slot: u32) -> usize {
        self.input_of_slot
            .as_ref()
            .map_or(slot, |m| m[slot as usize]) as usize
    }

    /// The input index of vertex `v`.
    pub(super) fn input_of(&self, v: Vid) -> usize {
        self.input(v.raw())
    }
}

/// Every used vertex needs a finite position.
pub(super) fn check_positions<P: Point>(
    positions: Option<&[P]>,
    vertices: &UsedVertices<'_>,
) -> Result<()> {
    if let Some(p) = positions {
        for slot in 0..vertices.count as u32 {
            let q = p[vertices.input(slot)].xyz();
            if !q.iter().all(|c| c.is_finite()) {
                return Err(BuildError::NonFinitePosition {
                    vertex: vertices.input(slot),
                    position: q,
                }
                .into());
            }
        }
    }
    Ok(())
}
