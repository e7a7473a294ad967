//! Stages 3 and 4 of the builder: pair every directed side with its twin,
//! by a counting sort into buckets of the lower vertex, or for triangles
//! only by buckets of the origin with half the memory. On bad input the
//! error named is the first one in the order the faces use their vertices.

use super::input::{Flat, UsedVertices};
use crate::error::{BuildError, Error, Result};

/// Stage 3's result: every side in a bucket of its lower vertex. Entry `x`
/// packs the higher vertex (`x >> 33`), the direction (bit 32: 1 when the
/// side runs from the higher vertex) and the corner (the low 32 bits), so a
/// bucket sorts as plain integers. Buckets lie in vertex order; the edges
/// are numbered later, in face order (stage 5).
pub(super) struct Buckets {
    /// Bucket `v` is `entries[ends[v - 1]..ends[v]]` (from 0 for `v = 0`).
    pub(super) ends: Vec<u32>,
    pub(super) entries: Vec<u64>,
}

impl Buckets {
    pub(super) fn higher(x: u64) -> u32 {
        (x >> 33) as u32
    }

    pub(super) fn from_higher(x: u64) -> bool {
        (x >> 32) & 1 == 1
    }

    pub(super) fn corner(x: u64) -> usize {
        (x & 0xffff_ffff) as usize
    }

    /// The entries of vertex `v`'s bucket.
    pub(super) fn range(&self, v: usize) -> std::ops::Range<usize> {
        let begin = if v == 0 { 0 } else { self.ends[v - 1] };
        begin as usize..self.ends[v] as usize
    }
}

/// Stage 3: bucket the sides by their lower vertex (a counting sort). One
/// array of `nv` counts becomes the buckets' starts, and placing advances
/// each start to its bucket's end.
pub(super) fn bucket_sides(faces: Flat<'_>, nv: usize) -> Buckets {
    let mut ends = vec![0u32; nv];
    faces.for_each_side(|_, a, b| ends[a.min(b) as usize] += 1);
    let mut at = 0u32;
    for slot in &mut ends {
        let n = *slot;
        *slot = at;
        at += n;
    }
    let mut entries = vec![0u64; faces.indices.len()];
    faces.for_each_side(|c, a, b| {
        let (lo, hi, dir) = if a < b { (a, b, 0) } else { (b, a, 1) };
        let slot = &mut ends[lo as usize];
        entries[*slot as usize] = (u64::from(hi) << 33) | (dir << 32) | c as u64;
        *slot += 1;
    });
    Buckets { ends, entries }
}

/// Stage 4's result: each corner's twin corner, one past it (`mate[c] = 0`:
/// the side starting at `c` has no twin, a hole lies beyond it).
pub(super) struct Mates {
    pub(super) mate: Vec<u32>,
    /// Number of paired sides (interior edges).
    pub(super) pairs: usize,
    /// Sides leaving each vertex (its half-edges in faces; stage 6 adds
    /// those in holes).
    pub(super) out_degree: Vec<u32>,
}

/// Stage 4: pair each directed side with its twin, bucket by bucket. On
/// bad input the error is the one met first when the buckets are taken in
/// the order in which the faces first use their vertex.
pub(super) fn pair_twins(
    faces: Flat<'_>,
    mut sides: Buckets,
    vertices: &UsedVertices<'_>,
) -> Result<Mates> {
    let nv = sides.ends.len();
    let mut mates = Mates {
        mate: vec![0u32; faces.indices.len()],
        pairs: 0,
        out_degree: Vec::new(),
    };
    for v in 0..nv {
        let range = sides.range(v);
        let group = &mut sides.entries[range];
        if pair_bucket(faces, v as u32, group, &mut mates, vertices).is_err() {
            return Err(first_bucket_error(faces, &mut sides, vertices));
        }
    }
    drop(sides);
    let mut out_degree = vec![0u32; nv];
    for &v in faces.indices {
        out_degree[v as usize] += 1;
    }
    mates.out_degree = out_degree;
    Ok(mates)
}

/// Stages 3 and 4 for triangles only, with half the memory: the corners
/// are bucketed by their origin (a counting sort of `u32` corners; a
/// corner's destination is the next corner of its triangle), and each side
/// finds its twin in its destination's bucket. `None` when some directed
/// edge is used twice, or the input is not all triangles: the general
/// stages then run and name the defect exactly as they always have.
pub(super) fn pair_triangle_twins(faces: Flat<'_>, nv: usize) -> Option<Mates> {
    let idx = faces.indices;
    let corners = idx.len();
    let all_triangles = corners == 3 * faces.face_count()
        && faces
            .offsets
            .iter()
            .enumerate()
            .all(|(f, &o)| o as usize == 3 * f);
    if !all_triangles {
        return None;
    }
    let by_origin = OriginBuckets::of(idx, nv);
    let mut mate = vec![0u32; corners];
    let mut pairs = 0;
    for c in 0..corners {
        if mate[c] != 0 {
            continue;
        }
        let (a, b) = (idx[c], triangle_dest(idx, c));
        // The first side b -> a. A second one is found when it looks for
        // its own twin: it finds this side taken, or (no side a -> b at
        // all) its double.
        match by_origin.sides(idx, b, a).next() {
            Some(d) if mate[d as usize] == 0 => {
                mate[c] = d + 1;
                mate[d as usize] = c as u32 + 1;
                pairs += 1;
            }
            Some(_) => return None, // a -> b twice, b -> a once or more
            None => {
                if by_origin.sides(idx, a, b).any(|k| k as usize != c) {
                    return None; // a -> b twice, on the boundary
                }
            }
        }
    }
    Some(Mates {
        mate,
        pairs,
        out_degree: by_origin.into_sizes(),
    })
}

#[cfg(test)]
thread_local! {
    /// Bucket entries the triangle path has looked at (tests only).
    static SCANNED: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Count one bucket entry looked at (tests only: nothing in a build).
#[inline(always)]
pub(super) fn scanned() {
    #[cfg(test)]
    SCANNED.with(|s| s.set(s.get() + 1));
}

/// The vertex after corner `c` of a triangle list.
#[inline(always)]
pub(super) fn triangle_dest(idx: &[u32], c: usize) -> u32 {
    idx[if c % 3 == 2 { c - 2 } else { c + 1 }]
}

/// The corner before corner `c` in its triangle.
#[inline(always)]
pub(super) fn triangle_before(c: usize) -> usize {
    if c % 3 == 0 {
        c + 2
    } else {
        c - 1
    }
}

/// Corners bucketed by their origin vertex: bucket `v` is
/// `corners[ends[v - 1]..ends[v]]` (from 0 for `v = 0`).
pub(super) struct OriginBuckets {
    pub(super) ends: Vec<u32>,
    pub(super) corners: Vec<u32>,
}

impl OriginBuckets {
    /// A counting sort of the corners by origin (`indices[c] < nv`).
    pub(super) fn of(indices: &[u32], nv: usize) -> Self {
        let mut ends = vec![0u32; nv];
        for &v in indices {
            ends[v as usize] += 1;
        }
        let mut at = 0u32;
        for slot in &mut ends {
            let n = *slot;
            *slot = at;
            at += n;
        }
        let mut corners = vec![0u32; indices.len()];
        for (c, &v) in indices.iter().enumerate() {
            let slot = &mut ends[v as usize];
            corners[*slot as usize] = c as u32;
            *slot += 1;
        }
        OriginBuckets { ends, corners }
    }

    /// The corners leaving vertex `v`.
    #[inline(always)]
    pub(super) fn bucket(&self, v: u32) -> &[u32] {
        let v = v as usize;
        let begin = if v == 0 { 0 } else { self.ends[v - 1] };
        &self.corners[begin as usize..self.ends[v] as usize]
    }

    /// The corners of the sides `a -> b` (triangles only), found in the
    /// smaller of the two buckets: those leaving `a` whose destination is
    /// `b`, or those leaving `b` whose corner before is `a` (the side is
    /// then that corner before). Scanning the smaller bucket keeps a vertex
    /// of high valence from being scanned once per neighbour (a fan of `N`
    /// triangles around one vertex would cost `N²`): the cost per side is
    /// the lower valence of its two ends.
    #[inline(always)]
    pub(super) fn sides<'s>(
        &'s self,
        idx: &'s [u32],
        a: u32,
        b: u32,
    ) -> impl Iterator<Item = u32> + 's {
        let (from_a, into_b) = (self.bucket(a), self.bucket(b));
        let by_a = from_a.len() <= into_b.len();
        let leaving = if by_a { from_a } else { &[][..] };
        let entering = if by_a { &[][..] } else { into_b };
        leaving
            .iter()
            .copied()
            .filter(move |&k| {
                scanned();
                triangle_dest(idx, k as usize) == b
            })
            .chain(entering.iter().filter_map(move |&k| {
                scanned();
                let before = triangle_before(k as usize);
                (idx[before] == a).then_some(before as u32)
            }))
    }

    /// Each bucket's size (the sides leaving each vertex), in the same
    /// buffer.
    pub(super) fn into_sizes(self) -> Vec<u32> {
        drop(self.corners);
        let mut ends = self.ends;
        for v in (1..ends.len()).rev() {
            ends[v] -= ends[v - 1];
        }
        ends
    }
}

/// Sort one bucket and pair its sides; an edge used by three sides or
/// twice in one direction is an error.
pub(super) fn pair_bucket(
    faces: Flat<'_>,
    v: u32,
    group: &mut [u64],
    mates: &mut Mates,
    vertices: &UsedVertices<'_>,
) -> Result<()> {
    group.sort_unstable();
    let mut i = 0;
    while i < group.len() {
        let hi = Buckets::higher(group[i]);
        let mut j = i + 1;
        while j < group.len() && Buckets::higher(group[j]) == hi {
            j += 1;
        }
        match j - i {
            1 => {}
            2 => {
                let (c0, c1) = (group[i], group[i + 1]);
                if Buckets::from_higher(c0) == Buckets::from_higher(c1) {
                    let (lo, hi) = (vertices.input(v), vertices.input(hi));
                    let (a, b) = if Buckets::from_higher(c0) {
                        (hi, lo)
                    } else {
                        (lo, hi)
                    };
                    return Err(BuildError::InconsistentOrientation {
                        a,
                        b,
                        faces: [
                            faces.face_of_corner(Buckets::corner(c0)),
                            faces.face_of_corner(Buckets::corner(c1)),
                        ],
                    }
                    .into());
                }
                let (k0, k1) = (Buckets::corner(c0), Buckets::corner(c1));
                mates.mate[k0] = k1 as u32 + 1;
                mates.mate[k1] = k0 as u32 + 1;
                mates.pairs += 1;
            }
            _ => {
                let mut fs: Vec<usize> = group[i..j]
                    .iter()
                    .map(|&x| faces.face_of_corner(Buckets::corner(x)))
                    .collect();
                fs.sort_unstable();
                let (a, b) = (vertices.input(v), vertices.input(hi));
                return Err(BuildError::NonManifoldEdge {
                    a: a.min(b),
                    b: a.max(b),
                    faces: [fs[0], fs[1], fs[2]],
                }
                .into());
            }
        }
        i = j;
    }
    Ok(())
}

/// The error path of stage 4: the first bad bucket in the order in which
/// the faces first use their vertex (the order the builder reported in
/// before it paired in vertex order).
pub(super) fn first_bucket_error(
    faces: Flat<'_>,
    sides: &mut Buckets,
    vertices: &UsedVertices<'_>,
) -> Error {
    let nv = sides.ends.len();
    let mut seen = vec![false; nv];
    let mut scratch = Mates {
        mate: vec![0u32; faces.indices.len()],
        pairs: 0,
        out_degree: Vec::new(),
    };
    for &v in faces.indices {
        if std::mem::replace(&mut seen[v as usize], true) {
            continue;
        }
        let range = sides.range(v as usize);
        let group = &mut sides.entries[range];
        if let Err(e) = pair_bucket(faces, v, group, &mut scratch, vertices) {
            return e;
        }
    }
    unreachable!("stage 4 found an error in some bucket")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;

    /// A fan of `n` triangles around vertex 0, its rim open.
    fn fan(n: u32) -> Vec<[u32; 3]> {
        (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect()
    }

    /// The triangle path pairs each side by scanning the smaller of its
    /// two vertices' buckets: around one vertex of valence `n` the entries
    /// looked at grow with `n`, not `n²` (the quadratic read of a fan).
    #[test]
    fn triangle_pairing_is_linear_in_valence() {
        let looked_at = |n: u32| {
            SCANNED.with(|s| s.set(0));
            let mesh = Mesh::from_faces(n as usize + 1, &fan(n)).unwrap();
            assert_eq!(mesh.face_count(), n as usize);
            SCANNED.with(|s| s.get())
        };
        let (small, large) = (looked_at(1_000), looked_at(16_000));
        // Linear: 16 times the triangles, about 16 times the entries (the
        // quadratic scan looked at 256 times as many).
        assert!(large <= 20 * small, "{small} -> {large}");
        assert!(large <= 16 * 3 * 16_000, "{large} entries for 48,000 sides");
    }
}
