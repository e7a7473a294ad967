//! Large plain OBJ files (only `v` and `f` with positive indices) are read
//! in two halves on two threads and joined; anything else in either half
//! sends the file to the one-pass parser, which reports errors exactly.

use crate::io::soup::Soup;
use crate::io::text::{is_space, parse_f64_at};

/// Inputs at least this large are parsed in two halves at once when both
/// are plain (see [`plain`]).
pub(super) const PARALLEL_MIN: usize = 4 << 20;

/// A chunk of plain OBJ: `v` and `f` statements with positive indices
/// only (and statements every reader skips).
struct Plain {
    positions: Vec<[f64; 3]>,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    /// The most vertices any index needed from before the chunk.
    needs: usize,
}

/// The two halves of a large file, split at a line end, parsed on two
/// threads and joined. `None` (the caller then parses serially, with full
/// error reporting) if either half holds anything but plain statements or
/// anything wrong.
pub(super) fn parse_halves(bytes: &[u8]) -> Option<Soup> {
    let mid = bytes.len() / 2;
    let cut = mid + bytes[mid..].iter().position(|&b| b == b'\n')? + 1;
    let (first, second) = bytes.split_at(cut);
    let (a, b) = std::thread::scope(|scope| {
        let other = std::thread::Builder::new()
            .spawn_scoped(scope, || plain(second))
            .ok()?;
        let a = plain(first);
        let b = other.join().ok()?;
        Some((a?, b?))
    })?;
    if a.needs > 0 || b.needs > a.positions.len() {
        return None;
    }
    let mut soup = Soup::new(false);
    let base = a.indices.len() as u32;
    let p = &mut soup.polygons;
    p.positions = join(a.positions, &b.positions);
    p.indices = join(a.indices, &b.indices);
    p.offsets = a.offsets;
    p.offsets.extend(b.offsets[1..].iter().map(|&o| o + base));
    Some(soup)
}

/// `first` then `second`, in `first`'s buffer when it has room.
fn join<T: Copy>(mut first: Vec<T>, second: &[T]) -> Vec<T> {
    if first.capacity() - first.len() < second.len() {
        let mut all = Vec::with_capacity(first.len() + second.len());
        all.extend_from_slice(&first);
        first = all;
    }
    first.extend_from_slice(second);
    first
}

/// The start of the next corner of an `f` statement from `i`, past spaces;
/// `None` at the end of the statement (line end, comment or input end).
#[inline]
pub(super) fn next_corner(bytes: &[u8], mut i: usize) -> Option<usize> {
    while i < bytes.len() && is_space(bytes[i]) {
        i += 1;
    }
    (i < bytes.len() && bytes[i] != b'\n' && bytes[i] != b'#').then_some(i)
}

/// A plain 1-based index at `start` (at most 9 digits): its value and end,
/// if it is digits alone up to a space or line end. `None` for anything
/// else (no digits, zero, `/`-separated references, signs, ...).
#[inline]
pub(super) fn plain_index(bytes: &[u8], start: usize) -> Option<(u32, usize)> {
    let (n, mut i, mut v) = (bytes.len(), start, 0u32);
    while i < n && i - start < 9 && bytes[i].is_ascii_digit() {
        v = v * 10 + u32::from(bytes[i] - b'0');
        i += 1;
    }
    let ends = i == n || is_space(bytes[i]) || bytes[i] == b'\n';
    (i > start && v > 0 && ends).then_some((v, i))
}

/// The start of the line after the one holding `i`.
#[inline]
pub(super) fn next_line(bytes: &[u8], i: usize) -> usize {
    let n = bytes.len();
    match bytes[i.min(n)..].iter().position(|&b| b == b'\n') {
        Some(k) => i + k + 1,
        None => n,
    }
}

/// Parse a chunk of plain OBJ; `None` at anything else.
fn plain(bytes: &[u8]) -> Option<Plain> {
    let n = bytes.len();
    let mut out = Plain {
        // Room for a chunk of only vertices, or only faces: capacity never
        // touched costs address space, not memory, and is bounded by the
        // chunk's size.
        positions: Vec::with_capacity(n / 24),
        offsets: Vec::with_capacity(n / 12),
        indices: Vec::with_capacity(n / 4),
        needs: 0,
    };
    out.offsets.push(0);
    let mut pos = 0;
    while pos < n {
        let mut i = pos;
        while i < n && is_space(bytes[i]) {
            i += 1;
        }
        let key_end = i + bytes[i..]
            .iter()
            .position(|&b| is_space(b) || b == b'\n')
            .unwrap_or(n - i);
        match &bytes[i..key_end] {
            b"v" => {
                i = key_end;
                let mut p = [0.0; 3];
                for c in &mut p {
                    while i < n && is_space(bytes[i]) {
                        i += 1;
                    }
                    *c = parse_f64_at(bytes, &mut i)?;
                }
                out.positions.push(p);
            }
            b"f" => {
                i = key_end;
                let start = out.indices.len();
                while let Some(st) = next_corner(bytes, i) {
                    let (v, end) = plain_index(bytes, st)?;
                    i = end;
                    out.needs = out
                        .needs
                        .max((v as usize).saturating_sub(out.positions.len()));
                    out.indices.push(v - 1);
                }
                if out.indices.len() == start {
                    return None;
                }
                out.offsets.push(out.indices.len() as u32);
            }
            b"" | b"s" | b"l" | b"p" | b"mtllib" => {}
            k if k.first() == Some(&b'#') => {}
            _ => return None,
        }
        pos = next_line(bytes, i);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use std::io::Write;

    use super::super::parse::{parse, parse_serial};
    use super::*;

    /// A plain grid OBJ of at least `PARALLEL_MIN` bytes.
    fn big_grid(n: usize) -> Vec<u8> {
        let mut out = Vec::new();
        for j in 0..n {
            for i in 0..n {
                writeln!(out, "v {} {} 0.{}", i as f64 / 7.0, j as f64 / 3.0, i * j).unwrap();
            }
        }
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let a = j * n + i + 1;
                writeln!(
                    out,
                    "f {a} {} {}\nf {a} {} {}",
                    a + 1,
                    a + n + 1,
                    a + n + 1,
                    a + n
                )
                .unwrap();
            }
        }
        assert!(out.len() >= PARALLEL_MIN);
        out
    }

    #[test]
    fn halves_read_the_same_as_one_pass() {
        let bytes = big_grid(260);
        let both = parse_halves(&bytes).expect("a plain file is read in halves");
        let one = parse_serial(&bytes, false).unwrap();
        assert_eq!(both.polygons, one.polygons);
    }

    #[test]
    fn anything_unusual_in_a_half_falls_back_to_one_pass() {
        let mut bytes = big_grid(260);
        // A negative index near the end, a group name, an out-of-range index.
        for tail in ["f -1 -2 -3\n", "g late\nf 1 2 3\n", "f 1 2 99999999\n"] {
            let mut b = bytes.clone();
            b.extend_from_slice(tail.as_bytes());
            assert!(parse_halves(&b).is_none(), "{tail}");
        }
        bytes.extend_from_slice(b"f 1 2 99999999\n");
        let lines = bytes.iter().filter(|&&b| b == b'\n').count() as u64;
        let err = parse(&bytes, false).err().expect("an index out of range");
        assert_eq!(err.line(), Some(lines));
    }
}
