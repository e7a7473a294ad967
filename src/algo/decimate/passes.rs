//! The collapse passes: each scores every edge, keeps each vertex's
//! cheapest edge, sorts those and collapses them in order, skipping edges
//! whose ends were touched earlier in the pass, until the stop or the
//! error bound (see the [module](super) for why passes).

use super::{
    closes_hole, Collapse, DecimateOptions, DecimateReport, Engine, Guard, Keep, LevelHook,
    Refused, Stop, StopReason, ALGORITHM, TOUCHED,
};
use crate::algo::progress::Progress;
use crate::algo::subdivision::Counts;
use crate::error::{Error, Result};
use crate::layout::{Eid, Hid};
use crate::mesh::Mesh;

/// The running state of [`Engine::run`]: the report so far, the error
/// bound (squared, unit box), the worst error made and the progress total.
struct Pass {
    report: DecimateReport,
    max_err: Option<f64>,
    worst: f64,
    total: u64,
}

impl Pass {
    /// The report's error and counts as the mesh stands.
    fn finish(&mut self, mesh: &Mesh, scale: f64) {
        self.report.error = self.worst.sqrt() * scale;
        self.report.output = Counts::of(mesh);
    }
}

/// How a pass ended.
enum PassEnd {
    /// With this many collapses made.
    Made(usize),
    /// With the run over, for this reason.
    Stop(StopReason),
}

impl Engine {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn run(
        mut self,
        mesh: &mut Mesh,
        options: &DecimateOptions,
        stops: &[Stop],
        progress: &mut Progress<'_>,
        on_level: &mut LevelHook<'_>,
        mut record: Option<&mut Vec<Collapse>>,
        on_copy: bool,
    ) -> Result<DecimateReport> {
        let mut state = Pass {
            report: DecimateReport {
                stopped_by: StopReason::NoCollapses,
                error: 0.0,
                input: Counts::of(mesh),
                output: Counts::of(mesh),
                collapses: 0,
                passes: 0,
                refused: Refused::default(),
                fixed: self.fixed,
                on_copy,
            },
            max_err: options
                .max_error
                .map(|e| (e * self.inv_scale) * (e * self.inv_scale)),
            worst: 0.0,
            total: stops.last().map_or(0, |s| s.remaining(mesh)).max(1) as u64,
        };
        let mut level = 0;
        let mut cands: Vec<u64> = Vec::new();
        loop {
            // Levels reached (also before the first collapse).
            while level < stops.len() && stops[level].reached(mesh) {
                state.finish(mesh, self.scale);
                state.report.stopped_by = StopReason::Target;
                on_level(mesh, level, &state.report);
                level += 1;
            }
            if level == stops.len() {
                break;
            }
            self.candidates(mesh, &mut cands)?;
            if cands.is_empty() {
                state.report.stopped_by = StopReason::NoCollapses;
                break;
            }
            state.report.passes += 1;
            for f in &mut self.flags {
                *f &= !TOUCHED;
            }
            let made = self.pass(
                mesh,
                options,
                stops[level],
                &cands,
                &mut state,
                &mut record,
                progress,
            )?;
            match made {
                PassEnd::Stop(why) => {
                    state.report.stopped_by = why;
                    break;
                }
                PassEnd::Made(0) => {
                    state.report.stopped_by = StopReason::NoCollapses;
                    break;
                }
                PassEnd::Made(_) => {}
            }
        }
        state.finish(mesh, self.scale);
        let done = state.report.collapses as u64;
        progress.report(ALGORITHM, "collapses", done.min(state.total), state.total)?;
        #[cfg(debug_assertions)]
        if let Err(e) = mesh.validate() {
            panic!("decimate broke the mesh: {e}");
        }
        Ok(state.report)
    }

    /// Score every edge and keep each vertex's cheapest: `cands` becomes
    /// the sorted, distinct keys (error bits above the half-edge).
    fn candidates(&self, mesh: &Mesh, cands: &mut Vec<u64>) -> Result<()> {
        let nv = mesh.vertex_slots();
        cands.clear();
        cands.resize(nv, u64::MAX);
        let pos = mesh.position_slots().ok_or(Error::NoPositions)?;
        for e in mesh.edge_arena().live_indices() {
            let e = Eid::new(e);
            let Some(c) = self.evaluate(mesh, pos, e) else {
                continue;
            };
            let key = (u64::from((c.err as f32).to_bits()) << 32) | u64::from(c.h.raw());
            let a = mesh.origin(c.h).index();
            let b = mesh.origin(c.h.twin()).index();
            cands[a] = cands[a].min(key);
            cands[b] = cands[b].min(key);
        }
        let mut n = 0;
        for i in 0..cands.len() {
            if cands[i] != u64::MAX {
                cands[n] = cands[i];
                n += 1;
            }
        }
        cands.truncate(n);
        cands.sort_unstable();
        cands.dedup();
        Ok(())
    }

    /// One pass: collapse the candidates in order until the stop is
    /// reached, errors climb well past the error at the rank the target
    /// needs (most candidates get locked by their neighbours' collapses,
    /// hence 1.5×, once a sixth of it is done), or `max_error` stops.
    #[allow(clippy::too_many_arguments)]
    fn pass(
        &mut self,
        mesh: &mut Mesh,
        options: &DecimateOptions,
        stop: Stop,
        cands: &[u64],
        state: &mut Pass,
        record: &mut Option<&mut Vec<Collapse>>,
        progress: &mut Progress<'_>,
    ) -> Result<PassEnd> {
        let needed = stop.remaining(mesh).max(1);
        let goal_err = cands
            .get(needed - 1)
            .map_or(f32::INFINITY, |&k| 1.5 * f32::from_bits((k >> 32) as u32));
        let mut made = 0usize;
        for &key in cands {
            let err32 = f32::from_bits((key >> 32) as u32);
            if let Some(m) = state.max_err {
                if f64::from(err32) > m {
                    if made == 0 {
                        return Ok(PassEnd::Stop(StopReason::MaxError));
                    }
                    break;
                }
            }
            if err32 > goal_err && f64::from(err32) > state.worst && made > needed / 6 {
                break;
            }
            let Some(c) = self.try_collapse(mesh, options, Hid::new(key as u32), state)? else {
                continue;
            };
            if let Some(r) = record.as_deref_mut() {
                r.push(c);
            }
            made += 1;
            state.report.collapses += 1;
            if state.report.collapses % 4096 == 0 {
                let done = state.report.collapses as u64;
                progress.report(ALGORITHM, "collapses", done.min(state.total), state.total)?;
            }
            if stop.reached(mesh) {
                break;
            }
        }
        Ok(PassEnd::Made(made))
    }

    /// Collapse the candidate half-edge `h` if it is still live, untouched
    /// this pass, within `max_error`, and passes the kept boundary, the
    /// guards and the operator; counts the refusals.
    fn try_collapse(
        &mut self,
        mesh: &mut Mesh,
        options: &DecimateOptions,
        h: Hid,
        state: &mut Pass,
    ) -> Result<Option<Collapse>> {
        if !mesh.edge_live(h.edge().index()) {
            return Ok(None);
        }
        let (a, b) = (mesh.origin(h), mesh.origin(h.twin()));
        if (self.flags[a.index()] | self.flags[b.index()]) & TOUCHED != 0 {
            return Ok(None);
        }
        let pos = mesh.position_slots().ok_or(Error::NoPositions)?;
        let Some(c) = self.evaluate(mesh, pos, h.edge()) else {
            return Ok(None);
        };
        if state.max_err.is_some_and(|m| c.err > m) {
            return Ok(None);
        }
        // A kept boundary never loses a loop: no collapse of an edge of a
        // triangular hole (which would close it).
        if options.boundary != Keep::Free && closes_hole(mesh, c.h) {
            state.report.refused.topology += 1;
            return Ok(None);
        }
        if let Some(g) = self.guards(mesh, pos, &c, options) {
            let r = &mut state.report.refused;
            match g {
                Guard::Normal => r.normal += 1,
                Guard::Quality => r.quality += 1,
                Guard::Valence => r.valence += 1,
            }
            return Ok(None);
        }
        let (a, b) = (mesh.origin(c.h), mesh.origin(c.h.twin()));
        let hk = mesh.hkey(c.h);
        match crate::journal::journaled!(mesh.collapse_unvalidated(c.h, c.t, Some(c.p))) {
            Ok(_) => {}
            // A column's rule failed: so does the decimation.
            Err(e @ Error::Rule(_)) => return Err(e),
            Err(_) => {
                state.report.refused.topology += 1;
                return Ok(None);
            }
        }
        let qa = self.quadrics[a.index()];
        self.quadrics[b.index()].add_assign(&qa);
        self.flags[b.index()] |= TOUCHED;
        if let Some(at) = &mut self.attrs {
            at.after_collapse(mesh, a, b);
        }
        state.worst = state.worst.max(c.err);
        Ok(Some(Collapse {
            halfedge: hk,
            position: c.p,
        }))
    }
}
