//! The mesh's door to its record ([`record`](crate::record)): lending its
//! storage to the recorder to open and seal steps, the one door for
//! wholesale rebuilds, and the saves that column writers (the attribute
//! API, bulk views) make before they write.
//!
//! Each is one test of [`Mesh::rec`] while no journal is on.

use super::Mesh;
use crate::keys::ElementKind;
use crate::record::{PerArena, Recorder, Side, Snapshot, Step, Storage};

impl Mesh {
    /// The recorder and the storage it records, borrowed apart (`None`
    /// while no journal is on).
    #[inline]
    pub(crate) fn recording(&mut self) -> Option<(&mut Recorder, Storage<'_>)> {
        let Mesh {
            v_halfedge,
            v_slots,
            he,
            e_slots,
            f_halfedge,
            f_slots,
            holes,
            attrs,
            rec,
            stamp: _,
        } = self;
        let r = rec.as_deref_mut()?;
        let s = Storage {
            v_halfedge,
            he,
            f_halfedge,
            slots: PerArena([v_slots, e_slots, f_slots]),
            holes: *holes,
            attrs,
        };
        Some((r, s))
    }

    /// Close the open step and open the next (a journal must be on).
    #[inline]
    pub(crate) fn seal(&mut self) {
        let (r, mut s) = self.recording().expect("no recorder");
        r.seal(&mut s);
    }

    /// Begin a new open step at the mesh as it is (a journal must be on).
    pub(crate) fn open_step(&mut self) {
        // Undo, redo and a rollback end here: the mesh changed.
        self.bump_revision();
        let (r, mut s) = self.recording().expect("no recorder");
        r.open_step(&mut s);
    }

    /// Drop the redo branch, if a journal is on: slots its births hold
    /// vacant go back on the free lists.
    pub(crate) fn drop_redo(&mut self) {
        if let Some((r, mut s)) = self.recording() {
            r.drop_redo(&mut s);
        }
    }

    /// Record a wholesale rebuild `f` as one step holding the prior mesh.
    pub(crate) fn wholesale(&mut self, f: impl FnOnce(&mut Mesh)) {
        self.bump_revision();
        let Some(r) = self.rec.as_deref() else {
            f(self);
            self.bump_revision();
            return;
        };
        let keeps = r.keeps_steps();
        self.seal();
        if keeps {
            self.drop_redo();
        }
        let prior = keeps.then(|| Box::new(self.snapshot()));
        // The rebuild itself records nothing (its operators' ends would
        // seal steps of their own).
        let rec = self.rec.take();
        f(self);
        self.rec = rec;
        let (r, mut s) = self.recording().expect("no recorder");
        if r.tracking {
            r.rebuilt = true;
            for t in r.touched.iter_mut() {
                t.clear();
            }
            r.cols.clear();
        }
        if let Some(prior) = prior {
            let mut step = Step {
                side: 1,
                ..Step::default()
            };
            r.push_forward(&mut s, &mut step, vec![Side::Whole(prior)], false);
        }
        r.open_step(&mut s);
    }

    /// A copy of the mesh's storage, for a wholesale step.
    fn snapshot(&self) -> Snapshot {
        let copy = self.clone();
        let bytes = copy.heap_bytes();
        // Every field named: a field added to `Mesh` must be added here.
        let Mesh {
            v_halfedge,
            v_slots,
            he,
            e_slots,
            f_halfedge,
            f_slots,
            holes,
            attrs,
            rec: _,
            stamp: _,
        } = copy;
        Snapshot {
            v_halfedge,
            v_slots,
            he,
            e_slots,
            f_halfedge,
            f_slots,
            holes,
            attrs,
            bytes,
        }
    }

    /// Swap the mesh's storage with a wholesale step's (the recorder
    /// stays); the snapshot then holds the storage swapped out.
    pub(crate) fn swap_storage(&mut self, snap: &mut Snapshot) {
        let bytes = self.heap_bytes();
        let Snapshot {
            v_halfedge,
            v_slots,
            he,
            e_slots,
            f_halfedge,
            f_slots,
            holes,
            attrs,
            bytes: held,
        } = snap;
        std::mem::swap(&mut self.v_halfedge, v_halfedge);
        std::mem::swap(&mut self.v_slots, v_slots);
        std::mem::swap(&mut self.he, he);
        std::mem::swap(&mut self.e_slots, e_slots);
        std::mem::swap(&mut self.f_halfedge, f_halfedge);
        std::mem::swap(&mut self.f_slots, f_slots);
        std::mem::swap(&mut self.holes, holes);
        std::mem::swap(&mut self.attrs, attrs);
        *held = bytes;
    }

    /// Save a column's values in `range` for a bulk writer (a raw mutable
    /// view), if a journal is on: the open step closes first, the writes
    /// become a step of their own at the next edit.
    fn save_bulk(&mut self, set: ElementKind, col: usize, range: std::ops::Range<usize>) {
        if let Some((r, mut s)) = self.recording() {
            r.save_bulk(&mut s, set, col, range);
        }
    }

    /// Before a column's structure changes (added, removed): close the
    /// open step, then record `side` as a step of its own.
    pub(crate) fn journal_column_added(&mut self, kind: ElementKind, col: usize) {
        if self.rec.is_none() {
            return;
        }
        self.push_structure(Side::Added {
            set: kind,
            col: col as u32,
        });
    }

    /// Record a removed column (the journal keeps it for undo). Returns
    /// `None` with no journal (the caller drops the column).
    pub(crate) fn journal_column_removed(&mut self, kind: ElementKind, col: usize) -> bool {
        if self.rec.is_none() {
            return false;
        }
        self.seal();
        let position = kind == ElementKind::Vertex && self.attrs.position == Some(col);
        let (name, column, meta) = self.attrs.take_column(kind as usize, col);
        self.push_structure(Side::Removed {
            set: kind,
            col: col as u32,
            name,
            column,
            meta,
            position,
        });
        true
    }

    fn push_structure(&mut self, s: Side) {
        self.rec.as_deref_mut().expect("no recorder").side.push(s);
        self.seal();
    }

    /// Save a column's values of every slot for a raw mutable view (see
    /// the journal's module docs).
    pub(crate) fn journal_bulk(&mut self, kind: ElementKind, col: usize) {
        if self.rec.is_some() {
            let n = self.slot_counts()[kind as usize];
            self.save_bulk(kind, col, 0..n);
        }
    }

    /// The position column, mutably, over `range` of slots, saved first
    /// while a journal records.
    pub(crate) fn bulk_positions_mut(
        &mut self,
        range: std::ops::Range<usize>,
    ) -> Option<&mut [[f64; 3]]> {
        let p = self.attrs.position?;
        self.bump_revision();
        if self.rec.is_some() {
            self.save_bulk(ElementKind::Vertex, p, range);
        }
        self.attrs.positions_mut().map(|c| c.raw_mut())
    }

    /// Save slot `i` of column `col` of `kind` before a single write.
    pub(crate) fn journal_attr_write(&mut self, kind: ElementKind, col: usize, i: usize) {
        if self.rec.is_some() {
            self.attrs.columns_mut(kind).save_one(col, i);
        }
    }

    /// Close the journal's open step, if a journal records (no validation:
    /// attribute setters; operators end through the writer's `end_op`).
    /// Inside a step group or a transaction the step stays open: the group
    /// is one undo unit anyway, and one step for the whole group saves
    /// each slot once (its oldest value) and seals once, where a step per
    /// edit would save and encode every edit's writes. Whatever needs the
    /// step closed (undo, a bulk view, a column change, `take_changes`,
    /// the group's end) seals it first.
    #[inline]
    pub(crate) fn end_edit(&mut self) {
        self.bump_revision();
        if let Some(r) = self.rec.as_deref() {
            if r.group_depth == 0 {
                self.seal();
            }
        }
    }
}
