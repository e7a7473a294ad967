//! Level-of-detail chains: one decimation through several targets, with
//! each level kept as a mesh, a replayable record of collapses, or both.

use super::{setup, Collapse, DecimateOptions, DecimateReport, Stop, Target, ALGORITHM};
use crate::algo::Progress;
use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// Options of [`lod_chain`]: the levels' targets, in order, and what to
/// keep of each.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct LodOptions {
    /// The levels, coarser and coarser (each target at most as many
    /// vertices and faces as the one before it). Default: ratios 0.5,
    /// 0.25 and 0.1.
    pub targets: Vec<Target>,
    /// Everything else, as for [`decimate`](super::decimate); its
    /// `target` is ignored.
    pub decimate: DecimateOptions,
    /// Keep a copy of the mesh at each level (default: true).
    pub meshes: bool,
    /// Keep the record of collapses (default: true).
    pub record: bool,
}

crate::choice::setters!(LodOptions {
    targets: Vec<Target>,
    decimate: DecimateOptions,
    meshes: bool,
    record: bool,
});

impl Default for LodOptions {
    fn default() -> Self {
        LodOptions {
            targets: vec![Target::Ratio(0.5), Target::Ratio(0.25), Target::Ratio(0.1)],
            decimate: DecimateOptions::default(),
            meshes: true,
            record: true,
        }
    }
}

/// One level of a [`LodChain`].
#[derive(Clone, Debug)]
pub struct LodLevel {
    /// The mesh at this level, when [`LodOptions::meshes`] asked for it.
    pub mesh: Option<Mesh>,
    /// The decimation up to this level, from the input.
    pub report: DecimateReport,
    /// How many collapses of [`LodChain::record`] lead from the input to
    /// this level.
    pub collapses: usize,
}

/// What [`lod_chain`] made.
#[derive(Clone, Debug)]
pub struct LodChain {
    /// One per target, in order.
    pub levels: Vec<LodLevel>,
    /// Every collapse made, in order (empty unless
    /// [`LodOptions::record`]): the first `levels[i].collapses` of them,
    /// [`replay`]ed on the input, give level `i`.
    pub record: Vec<Collapse>,
}

/// Decimate `mesh` once through several targets and return each level:
/// the levels are nested (each is the one before it, decimated further),
/// and cost one decimation in all, plus a copy of each kept level.
///
/// The input is not changed (the chain works on a copy).
///
/// # Errors
/// As [`decimate`](super::decimate); [`Error::Unsuitable`] for no targets
/// or targets that do not shrink in order. On an error nothing is returned
/// and the input is, as always, unchanged.
///
/// # Examples
/// ```
/// use meshloom::algo::decimate::{lod_chain, replay, LodOptions};
/// use meshloom::algo::Progress;
/// let mesh = meshloom::shapes::icosphere(3); // 642 vertices
/// let chain = lod_chain(&mesh, &LodOptions::default(), Progress::none())?;
/// let counts: Vec<usize> = chain.levels.iter().map(|l| l.report.output.vertices).collect();
/// assert_eq!(counts, [321, 161, 65]);
/// // Replaying the record up to a level gives that level's mesh.
/// let mut again = mesh.clone();
/// replay(&mut again, &chain.record[..chain.levels[1].collapses])?;
/// assert_eq!(again.vertex_count(), 161);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn lod_chain(
    mesh: &Mesh,
    options: &LodOptions,
    mut progress: Progress<'_>,
) -> Result<LodChain> {
    let unsuitable = |reason: String| Error::Unsuitable {
        algorithm: ALGORITHM,
        key: None,
        reason,
    };
    if options.targets.is_empty() {
        return Err(unsuitable(
            "a level-of-detail chain needs at least one target".into(),
        ));
    }
    let mut stops = Vec::with_capacity(options.targets.len());
    for &target in &options.targets {
        let o = DecimateOptions {
            target,
            ..options.decimate.clone()
        };
        let s = Stop::from_target(mesh, &o)?;
        if let Some(prev) = stops.last() {
            let prev: &Stop = prev;
            // Of one kind (vertex counts, or face counts), a later stop may
            // not ask for more than an earlier one.
            let same_kind = (s.faces == 0) == (prev.faces == 0);
            if same_kind && (s.vertices > prev.vertices || s.faces > prev.faces) {
                return Err(unsuitable(format!(
                    "the level-of-detail targets must shrink in order: {target:?} after {:?}",
                    options.targets[stops.len() - 1]
                )));
            }
        }
        stops.push(s);
    }
    let mut work = mesh.clone();
    let mut record = Vec::new();
    let mut levels: Vec<LodLevel> = Vec::with_capacity(stops.len());
    let keep_meshes = options.meshes;
    let mut hook = |m: &Mesh, _level: usize, r: &DecimateReport| {
        levels.push(LodLevel {
            mesh: keep_meshes.then(|| m.clone()),
            report: r.clone(),
            collapses: r.collapses,
        });
    };
    // The copy is ours: decimate it in place whatever the callback (a
    // cancel drops it).
    let engine = setup::prepare(&work, &options.decimate)?;
    let final_report = engine.run(
        &mut work,
        &options.decimate,
        &stops,
        &mut progress,
        &mut hook,
        Some(&mut record),
        false,
    )?;
    // Levels the decimation could not reach (no collapses left) all get
    // the final mesh.
    while levels.len() < stops.len() {
        levels.push(LodLevel {
            mesh: keep_meshes.then(|| work.clone()),
            report: final_report.clone(),
            collapses: final_report.collapses,
        });
    }
    if !options.record {
        record = Vec::new();
    }
    Ok(LodChain { levels, record })
}

/// Replay `collapses` (a [`LodChain::record`], or a prefix of it) on
/// `mesh`, which must be the mesh they were recorded on (or a clone):
/// each half-edge collapses to its recorded position through
/// [`Mesh::collapse_edge_to`], with every column's rule.
///
/// Returns the number of collapses made (all of them).
///
/// # Errors
/// The first collapse's error (a stale key, a refused collapse: the record
/// belongs to another mesh); the mesh is then unchanged.
///
/// # Complexity
/// O(degree) per collapse, no search, and one copy of the mesh (the
/// collapses are made on it and handed over at the end, so an error
/// leaves `mesh` as it was).
pub fn replay(mesh: &mut Mesh, collapses: &[Collapse]) -> Result<usize> {
    mesh.as_one_step("Replay collapses", |mesh| replay_run(mesh, collapses))
}

/// [`replay`] itself, outside the journal's step.
fn replay_run(mesh: &mut Mesh, collapses: &[Collapse]) -> Result<usize> {
    let mut work = mesh.clone();
    for c in collapses {
        work.collapse_edge_to(c.halfedge, c.position)?;
    }
    mesh.replace_with(work);
    Ok(collapses.len())
}
