//! `meshloom sample IN OUT.csv --inside N [--seed S]`: points uniformly
//! distributed inside a closed mesh, by rejection in its bounding box with
//! the face tree's inside test (`FaceTree::contains_batch`).
//!
//! Candidates are drawn and tested in batches of at most [`BATCH`], so
//! memory is bounded by N; the number of candidates is bounded too
//! ([`attempts_for`]), so a mesh that encloses almost no volume (an open
//! sheet, a flat box) stops with an error instead of looping.

use std::fs::File;
use std::io::{BufWriter, Write};

use meshloom::query::FaceTree;
use meshloom::Mesh;

use crate::cli::SampleArgs;
use crate::{input, Failure};

/// Candidates tested at a time.
pub const BATCH: usize = 1 << 16;

/// The candidates drawn at most for `n` points: enough when the mesh fills
/// at least about 1/1000 of its bounding box.
pub fn attempts_for(n: usize) -> usize {
    n.saturating_mul(1000).max(1_000_000)
}

/// A small deterministic generator (SplitMix64): the same seed gives the
/// same points on every platform.
struct SplitMix(u64);

impl SplitMix {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Write the points as CSV.
pub fn run(args: &SampleArgs) -> Result<(), Failure> {
    let (mesh, _) = input::read(&args.input, args.read, false)?;
    let points = inside(&mesh, args.inside, args.seed)
        .map_err(|e| Failure::input(format!("{}: {e}", args.input.display())))?;
    let out = &args.output;
    let fail = |e: std::io::Error| Failure::input(format!("{}: {e}", out.display()));
    let mut w = BufWriter::new(File::create(out).map_err(fail)?);
    writeln!(w, "x,y,z").map_err(fail)?;
    for [x, y, z] in &points {
        writeln!(w, "{x},{y},{z}").map_err(fail)?;
    }
    w.flush().map_err(fail)?;
    eprintln!(
        "{} points inside, written to {}",
        points.len(),
        out.display()
    );
    Ok(())
}

/// `n` points uniformly inside `mesh` (where its winding number exceeds
/// 1/2), from the generator seeded with `seed`.
///
/// # Errors
/// A message when the mesh has no positions or no faces, or when
/// [`attempts_for`]`(n)` candidates gave fewer than `n` points (the mesh
/// encloses almost no volume).
pub fn inside(mesh: &Mesh, n: usize, seed: u64) -> Result<Vec<[f64; 3]>, String> {
    if mesh.face_count() == 0 {
        return Err("the mesh has no faces, so nothing is inside it".into());
    }
    let tree = FaceTree::build(mesh).map_err(|e| e.to_string())?;
    let (lo, hi) = bounds(mesh)?;
    let mut rng = SplitMix(seed);
    let limit = attempts_for(n);
    let mut points = Vec::with_capacity(n);
    let mut drawn = 0usize;
    while points.len() < n {
        if drawn >= limit {
            return Err(format!(
                "{drawn} random points in the bounding box gave {} inside, {n} wanted: \
                 the mesh encloses (almost) no volume; is it closed?",
                points.len()
            ));
        }
        let want = (n - points.len()).saturating_mul(2).clamp(64, BATCH);
        let batch: Vec<[f64; 3]> = (0..want.min(limit - drawn))
            .map(|_| std::array::from_fn(|k| lo[k] + rng.unit() * (hi[k] - lo[k])))
            .collect();
        drawn += batch.len();
        let inside = tree
            .contains_batch(mesh, &batch)
            .map_err(|e| e.to_string())?;
        let kept = batch.into_iter().zip(inside).filter(|(_, i)| *i);
        points.extend(kept.map(|(p, _)| p).take(n - points.len()));
    }
    Ok(points)
}

/// The bounding box of the vertices.
fn bounds(mesh: &Mesh) -> Result<([f64; 3], [f64; 3]), String> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in mesh.vertices() {
        let p = mesh.position(v).map_err(|e| e.to_string())?;
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    Ok((lo, hi))
}
