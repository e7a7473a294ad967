//! Transactions, undo/redo and change tracking: what a modelling editor
//! needs from its mesh kernel.
//!
//! Three services share one recorder, which is off until one of them is
//! asked for (then [`Mesh`] carries it). With it off, the journal costs
//! one test per operator call: the operator then runs a body compiled
//! without any recording hook (see `mesh/writer.rs`), the same code as if the
//! journal did not exist:
//!
//! - **Transactions.** [`Mesh::transaction`] runs a closure; if it returns
//!   an error or panics, the mesh is put back exactly as it was (links,
//!   attribute columns and their values, which keys are valid), and the
//!   error or panic goes on to the caller. Nested transactions are one.
//! - **Undo and redo.** [`HistoryMut::enable`] keeps every committed edit
//!   as a compact delta (the links, births and deaths, hole count and
//!   attribute values it changed, as varint bytes), not a copy.
//!   [`Mesh::undo`] and [`Mesh::redo`] restore the exact state, keys
//!   included: keys valid before an edit are valid after undoing it; keys
//!   of elements the undone edit created are stale, and never name another
//!   element later (an undone birth leaves its slot one generation above
//!   the element; a new edit takes the slot at a later generation); redo
//!   revives the same slots at the same generations, so an editor's
//!   selection survives undo/redo. [`HistoryMut::begin_step`]/[`HistoryMut::end_step`]
//!   (or [`Mesh::step`]) group edits under one name; [`HistoryLimits`]
//!   bounds depth and memory; a new edit after undos drops the redo branch.
//! - **Change tracking.** [`HistoryMut::take_changes`] reports which vertices,
//!   edges, faces and attribute columns were created, removed or modified
//!   since the last call, after edits, transactions, undos and redos.
//!
//! [`Mesh::undo`], [`Mesh::redo`], [`Mesh::step`] and [`Mesh::transaction`]
//! are on the mesh; the bookkeeping (turning the history and change
//! tracking on, limits, unit counts and names for a menu, manual step
//! brackets, taking the changes) sits behind [`Mesh::history`] and
//! [`Mesh::history_mut`]: an editor calls the four verbs once per user
//! action and reads or sets the rest around them, once or for its UI.
//!
//! The recorder and its step log belong to the storage (`record`, a layer
//! under the mesh: the mesh holds the recorder, and its link mutators and
//! column setters write it); this module is the layer above the mesh that
//! applies them: undo, redo, transactions and change reports.
//!
//! # What is one edit
//!
//! Every public operator, attribute setter and [`RawEdit`] session
//! (closed by [`RawEdit::finish`]) is one step; each undo takes back one
//! *unit*: one step, or every step of a [`HistoryMut::begin_step`] group or of a
//! transaction. Composite operators ([`Mesh::triangulate_all`],
//! [`Mesh::fill_hole_triangulated`], [`Mesh::cut_path`]) are one step. An
//! algorithm run ([`algo::smooth`](crate::algo::smooth::smooth),
//! [`algo::fair`](crate::algo::fair::fair),
//! [`algo::decimate`](crate::algo::decimate()) in place, `replay`, the
//! subdivisions, `add_*_normals`, `add_curvature`) is one unit named after
//! it ([`History::undo_name`] gives `"Decimate"`, `"Smooth"`, ..., unless a
//! group of yours is open, whose name wins).
//!
//! Inside a group or a transaction the edits share one open step, sealed
//! when the group ends (or when something needs it closed: a bulk view, a
//! column added or removed, [`HistoryMut::take_changes`]): each slot's old value
//! is saved once however often the group writes it, slots the group
//! created are never saved (undo makes them vacant), and the delta is
//! encoded once.
//!
//! Wholesale rebuilds ([`Mesh::compact`], algorithms that rebuild the mesh
//! through the crate's one door for that, `Mesh::replace_with`) are kept as
//! one step holding the whole prior mesh (memory: one copy); undo swaps it
//! back, and the rebuilt mesh's keys stay stale after that undo. Change
//! tracking reports them as [`Changes::rebuilt`].
//!
//! # Cost
//!
//! Off, the journal costs one test per operator call (above). On, its
//! cost follows what an edit touches, not the size of the mesh.
//!
//! A link write saves its slot's whole page of the link array (32 slots)
//! on the first write to that page in the open step; later writes to the
//! page cost one table lookup. The page copies come in blocks of 128
//! pages, never one buffer of the array's size. The seal walks the copied
//! pages in slot order (an unchanged page is passed over in one slice
//! compare) and keeps the slots, and of a half-edge the fields, that differ
//! from the live arrays, so a dense edit costs about a copy of the pages
//! it touched, and a sparse one at most a page per slot written. A column
//! merge saves a slot's old value only when the merged value differs from
//! it ([`Attribute::same_value`](crate::attr::Attribute::same_value)). While the
//! step is kept and no change tracking reads the records, the half-edge
//! records go straight from the copied pages into the undo log, with no
//! vector of their own; the log reserves a step's room at once (no
//! regrowth by doubling, which would copy and fault a large buffer again).
//!
//! Slots created in the open step are never saved, and their removals and
//! reuses in that step record nothing: a poke collapsed back in the same
//! step leaves no trace but a run-length map, made at the seal from the
//! arena, of which new slots are still live. Undo makes every new slot
//! vacant (a dead one keeps its generation, already above every key it
//! had) and holds them off the free list; redo revives the live ones at
//! their generations and puts the others back on the free list.
//!
//! `BENCHMARKS.md` measures it: the `journal` row of `examples/ml_bench.rs`
//! pokes every face of a large mesh and collapses every new vertex back,
//! as one step, with the journal off and on.
//!
//! # Bulk writes (the rule for algorithm writers)
//!
//! Raw mutable access to a whole column, [`Mesh::position_slots_mut`] and
//! [`Mesh::attr_view_mut`], saves the whole column when it is taken while
//! the recorder is on (O(slots), once per call), closes the open step, and
//! the writes become one step of their own (holding only the values that
//! changed) at the next edit or journal call. So: take the view once per
//! pass, not once per element; for a few elements use
//! [`Mesh::set_position`] or [`Mesh::set_attr`], which save one value.
//! Inside the crate, every link write goes through the mutators in
//! `mesh/writer.rs` (the link arrays have no `IndexMut`), every column
//! write through the `Columns` rule methods, which save first; a slot born
//! in the open step needs no saving (undo makes it vacant).
//!
//! # Equality, precisely
//!
//! After undoing everything, the mesh equals its starting snapshot in:
//! every live element's links (as compacted polygons), every attribute
//! column (names, order, types, values and absences of live elements), and
//! the set of valid keys. What may differ: vacant slots (an undone birth
//! leaves its slot vacant at a higher generation, and its old content), the
//! order of the free lists, and the arenas' slot counts (slots stay, held
//! for a redo). The journal is not serialised or cloned: a clone or a
//! deserialised copy has no history, and the slots held for a redo are
//! free in it.
//!
//! # An editor loop
//!
//! ```
//! use meshloom::{shapes, journal::HistoryLimits, buffers::TriangleBufferOptions};
//! let mut mesh = shapes::cube();
//! mesh.history_mut().enable(HistoryLimits::default());
//! mesh.history_mut().track_changes(true);
//! let upload = |m: &meshloom::Mesh| m.to_triangle_buffers(&TriangleBufferOptions::default());
//! let _gpu = upload(&mesh).unwrap(); // first upload
//!
//! // The user selects an edge and runs "Split" twice, as one menu item.
//! let e = mesh.edges().next().unwrap();
//! let v = mesh.step("Split twice", |m| {
//!     let v = m.split_edge(e, 0.5)?;
//!     let h = m.vertex(v)?.outgoing().next().unwrap();
//!     let e2 = m.halfedge(h)?.edge().key();
//!     m.split_edge(e2, 0.5)
//! })?;
//! assert_eq!(mesh.history().undo_name(), Some("Split twice"));
//!
//! // Re-upload only what changed (here: rebuild the buffers; an engine
//! // would patch the listed vertices and faces).
//! let changes = mesh.history_mut().take_changes();
//! assert_eq!(changes.vertices.created.len(), 2);
//! assert!(changes.vertices.created.contains(&v));
//! let _gpu = upload(&mesh).unwrap();
//!
//! // Undo: the new vertices go, and their keys are stale.
//! assert!(mesh.undo());
//! assert!(mesh.vertex(v).is_err());
//! assert_eq!(mesh.history_mut().take_changes().vertices.removed.len(), 2);
//! // Redo: the same keys come back.
//! assert!(mesh.redo());
//! assert!(mesh.vertex(v).is_ok());
//!
//! // A tool that fails half-way changes nothing.
//! let before = mesh.vertex_count();
//! let r: Result<(), _> = mesh.transaction(|m| {
//!     let e = m.edges().next().unwrap();
//!     m.split_edge(e, 0.5)?;
//!     Err(meshloom::Error::Cancelled { algorithm: "Split" }) // the user pressed Escape
//! });
//! assert!(r.is_err());
//! assert_eq!(mesh.vertex_count(), before);
//! # Ok::<(), meshloom::Error>(())
//! ```
//!
//! [`RawEdit`]: crate::link::RawEdit
//! [`RawEdit::finish`]: crate::link::RawEdit::finish

mod apply;
mod history;

pub use history::{History, HistoryMut};

// The operators name their journaling mode by these paths.
pub(crate) use crate::record::{journaled, Journaling, Unrecorded};
use apply::Dir;

use std::collections::HashMap;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};

use crate::error::Result;
use crate::keys::{EdgeKey, ElementKind, FaceKey, VertexKey};
use crate::layout::{Eid, Fid, Vid};
use crate::mesh::Mesh;
use crate::record::{Arena, PerArena};

/// Bounds on the undo history. `None`: unbounded.
///
/// When a bound is passed, the oldest units go first (never the one just
/// recorded, nor any while a transaction or step group is open).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HistoryLimits {
    /// At most this many undo units.
    pub max_steps: Option<usize>,
    /// At most about this many bytes of undo log (bytes and side records).
    pub max_bytes: Option<usize>,
}

/// Keys of one kind of element that changed since the last
/// [`HistoryMut::take_changes`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ElementChanges<K> {
    /// Live now, not live at the last call (sorted by slot).
    pub created: Vec<K>,
    /// Live at the last call, stale now.
    pub removed: Vec<K>,
    /// Live at both with the same key, and written since: its links, an
    /// attribute value, or (for faces and vertices) a half-edge of its
    /// loop or star. A write that put back the same value may still count.
    pub modified: Vec<K>,
}

impl<K> Default for ElementChanges<K> {
    fn default() -> Self {
        ElementChanges {
            created: Vec::new(),
            removed: Vec::new(),
            modified: Vec::new(),
        }
    }
}

impl<K> ElementChanges<K> {
    /// Whether nothing changed.
    pub fn is_empty(&self) -> bool {
        self.created.is_empty() && self.removed.is_empty() && self.modified.is_empty()
    }
}

/// What happened to an attribute column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColumnChangeKind {
    /// Added since the last call.
    Created,
    /// Removed since the last call.
    Removed,
    /// Some value written.
    Modified,
}

/// An attribute column that changed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ColumnChange {
    /// Its arena.
    pub kind: ElementKind,
    /// Its name.
    pub name: String,
    /// What happened.
    pub change: ColumnChangeKind,
}

/// What changed since the last [`HistoryMut::take_changes`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Changes {
    /// Vertices.
    pub vertices: ElementChanges<VertexKey>,
    /// Edges (half-edge attribute writes count for their edge).
    pub edges: ElementChanges<EdgeKey>,
    /// Faces and holes, by key. A face and the hole it becomes are one
    /// element: [`Mesh::remove_face`] keeps the key (now a hole) and
    /// reports it as *modified*, as does filling a hole that keeps its
    /// key. A renderer that draws faces and not holes re-reads
    /// [`FaceView::is_hole`](crate::view::FaceView::is_hole) for each
    /// modified key: a hole now is a face it stops drawing.
    pub faces: ElementChanges<FaceKey>,
    /// Attribute columns.
    pub columns: Vec<ColumnChange>,
    /// The mesh was rebuilt wholesale ([`Mesh::compact`], an undo or redo
    /// of one): every key may have changed; the lists above cover only
    /// what happened after the last rebuild. Re-upload everything.
    pub rebuilt: bool,
    /// The [`Mesh::revision`] this change set starts from: the revision at
    /// the previous [`HistoryMut::take_changes`] (or when
    /// [`HistoryMut::track_changes`] turned tracking on). A consumer that
    /// holds state for revision `r` may apply this set only if
    /// `from_revision == r` (otherwise a set was skipped).
    pub from_revision: u64,
    /// The [`Mesh::revision`] this change set brings a consumer to: the
    /// mesh's revision when it was taken. With tracking off both
    /// revisions are the mesh's current one and the lists are empty.
    pub to_revision: u64,
}

impl Changes {
    /// Whether nothing changed.
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
            && self.edges.is_empty()
            && self.faces.is_empty()
            && self.columns.is_empty()
            && !self.rebuilt
    }
}

impl Mesh {
    /// [`HistoryMut::enable`]'s body.
    fn enable_history(&mut self, limits: HistoryLimits) {
        let r = self.ensure_recorder();
        r.history = true;
        r.max_units = limits.max_steps;
        r.max_bytes = limits.max_bytes;
        self.r().trim();
    }

    /// [`HistoryMut::disable`]'s body.
    fn disable_history(&mut self) {
        self.clear_history();
        if let Some(r) = self.rec.as_deref_mut() {
            r.history = false;
        }
        self.maybe_stop();
    }

    /// [`History::enabled`]'s body.
    fn history_enabled(&self) -> bool {
        self.rec.as_ref().is_some_and(|r| r.history)
    }

    /// [`HistoryMut::clear`]'s body.
    fn clear_history(&mut self) {
        if self.rec.as_ref().is_none_or(|r| r.tx_depth > 0) {
            return;
        }
        self.seal();
        self.drop_redo();
        let r = self.rec.as_deref_mut().expect("recorder");
        r.undo = Default::default();
    }

    /// Undo the last unit (one edit, or one named step or transaction).
    /// Returns `false` if there is nothing to undo, or while a transaction
    /// or step group is open (undo then would tear it).
    ///
    /// # Complexity
    /// O(size of the unit's delta).
    pub fn undo(&mut self) -> bool {
        if !self.can_act() {
            return false;
        }
        let done = self.move_unit(Dir::Undo);
        self.debug_validate();
        done
    }

    /// Redo the last undone unit. Returns `false` if there is nothing to
    /// redo (a new edit after undos dropped the redo branch), or while a
    /// transaction or step group is open.
    pub fn redo(&mut self) -> bool {
        if !self.can_act() {
            return false;
        }
        let done = self.move_unit(Dir::Redo);
        self.debug_validate();
        done
    }

    fn can_act(&self) -> bool {
        self.rec
            .as_ref()
            .is_some_and(|r| r.history && r.tx_depth == 0 && r.group_depth == 0)
    }

    /// [`History::undo_len`]'s body.
    fn undo_len(&self) -> usize {
        self.rec.as_ref().map_or(0, |r| r.undo.units)
    }

    /// [`HistoryMut::commit_writes`]'s body.
    fn commit_writes(&mut self) {
        self.seal_if_on();
    }

    /// [`History::redo_len`]'s body.
    fn redo_len(&self) -> usize {
        self.rec.as_ref().map_or(0, |r| r.redo.units)
    }

    /// [`History::undo_name`]'s body.
    fn undo_name(&self) -> Option<&str> {
        self.rec.as_deref()?.undo_name()
    }

    /// [`History::redo_name`]'s body.
    fn redo_name(&self) -> Option<&str> {
        self.rec.as_deref()?.redo_name()
    }

    /// [`History::bytes`]'s body.
    fn history_bytes(&self) -> usize {
        self.rec
            .as_ref()
            .map_or(0, |r| r.undo.memory() + r.redo.memory())
    }

    /// [`HistoryMut::begin_step`]'s body.
    fn begin_step(&mut self, name: &str) {
        self.seal_if_on();
        let r = self.ensure_recorder();
        if r.group_depth == 0 {
            r.group_name = Some(name.to_owned());
            r.group_started = false;
        }
        r.group_depth += 1;
    }

    /// [`HistoryMut::end_step`]'s body.
    fn end_step(&mut self) {
        let Some(r) = self.rec.as_deref() else { return };
        if r.group_depth == 0 {
            return;
        }
        self.seal();
        let r = self.rec.as_deref_mut().expect("recorder");
        r.group_depth -= 1;
        if r.group_depth == 0 {
            r.group_started = false;
            r.group_name = None;
            self.r().trim();
        }
        self.maybe_stop();
    }

    /// Run `f` as one named undo unit and as a [transaction](Mesh::transaction).
    ///
    /// # Errors
    /// Whatever `f` returns (the mesh is then as before).
    pub fn step<R>(&mut self, name: &str, f: impl FnOnce(&mut Mesh) -> Result<R>) -> Result<R> {
        self.begin_step(name);
        let out = catch_unwind(AssertUnwindSafe(|| self.transaction(f)));
        self.end_step();
        match out {
            Ok(r) => r,
            Err(p) => resume_unwind(p),
        }
    }

    /// An operator's body on a mesh with a column whose rule can fail, as a
    /// transaction (see `journaled!`); out of line, so that the other
    /// meshes' operators pay one test.
    #[cold]
    #[inline(never)]
    pub(crate) fn guarded<R>(
        &mut self,
        body: impl FnOnce(&mut Mesh) -> crate::error::Result<R>,
    ) -> crate::error::Result<R> {
        self.transaction(body)
    }

    /// Run `f` all or nothing: if it returns an error or panics, the mesh
    /// (links, attribute columns and values, valid keys) is exactly as
    /// before, and the error is returned (the panic resumed). Nested
    /// transactions are one: an inner failure that the outer closure
    /// swallows rolls back only the inner part. With history on, a
    /// committed transaction is one undo unit.
    ///
    /// A [rule that can fail](crate::attr::Rule::FALLIBLE) and fails inside
    /// `f` fails the transaction with [`Error::Rule`](crate::Error::Rule),
    /// and every transaction around it, even where `f` ignored the error.
    ///
    /// Built on the undo log: rollback undoes to a mark, so its cost is
    /// the size of what was done, not of the mesh. A committed transaction
    /// that edited drops the redo branch, as any edit does; a failed one
    /// leaves the history as it was, redo branch included.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// let f = mesh.faces().next().unwrap();
    /// let r = mesh.transaction(|m| {
    ///     let c = m.poke_face(f)?;
    ///     m.remove_vertex(c)?;
    ///     Err::<(), _>(meshloom::Error::Cancelled { algorithm: "tool" })
    /// });
    /// assert!(r.is_err());
    /// assert_eq!((mesh.vertex_count(), mesh.face_count()), (8, 6));
    /// assert!(mesh.face(f).is_ok());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    ///
    /// # Errors
    /// Whatever `f` returns.
    pub fn transaction<R>(&mut self, f: impl FnOnce(&mut Mesh) -> Result<R>) -> Result<R> {
        self.seal_if_on();
        let r = self.ensure_recorder();
        // The outermost transaction sets the redo branch aside (its held
        // slots stay held): only a committed edit may drop it.
        let redo = (r.tx_depth == 0).then(|| std::mem::take(&mut r.redo));
        r.tx_depth += 1;
        r.group_depth += 1;
        let mark = (
            r.undo.bytes.len(),
            r.undo.units,
            r.undo.names.len(),
            r.group_started,
        );
        let out = catch_unwind(AssertUnwindSafe(|| f(self)));
        // A rule that failed fails the transaction, whatever `f` made of
        // it (read before the rollback, which may drop the columns); the
        // outermost transaction takes it, so that it fails every one.
        let out = match out {
            Ok(r) => {
                let outermost = self.rec.as_deref().is_some_and(|r| r.tx_depth == 1);
                Ok(self.attrs.rule_failure(outermost).map_or(r, Err))
            }
            panicked => panicked,
        };
        let failed = !matches!(out, Ok(Ok(_)));
        if failed {
            self.roll_back_to(mark.0);
        } else {
            self.seal();
        }
        let r = self.rec.as_deref_mut().expect("recorder");
        if failed {
            r.undo.units = mark.1;
            r.undo.names.truncate(mark.2);
            r.group_started = mark.3;
        }
        if let Some(redo) = redo {
            let edited = r.undo.bytes.len() != mark.0 || r.undo.units != mark.1;
            r.redo = redo;
            if edited {
                self.drop_redo();
            }
        }
        let r = self.rec.as_deref_mut().expect("recorder");
        r.tx_depth -= 1;
        r.group_depth -= 1;
        if r.group_depth == 0 {
            r.group_started = false;
            r.group_name = None;
        }
        if r.tx_depth == 0 && !r.history {
            r.undo = Default::default();
        }
        if r.group_depth == 0 {
            self.r().trim();
        }
        self.maybe_stop();
        // The whole-mesh check of the crate's own tests runs once per
        // outermost transaction, committed or rolled back (see
        // `debug_validate`).
        self.debug_validate();
        match out {
            Ok(r) => r,
            Err(p) => resume_unwind(p),
        }
    }

    /// [`History::in_transaction`]'s body.
    fn in_transaction(&self) -> bool {
        self.rec.as_ref().is_some_and(|r| r.tx_depth > 0)
    }

    /// [`HistoryMut::track_changes`]'s body.
    fn track_changes(&mut self, on: bool) {
        if on {
            let was = self.rec.as_ref().is_some_and(|r| r.tracking);
            self.ensure_recorder().tracking = true;
            if !was {
                let now = self.revision();
                self.r().taken_at = now;
            }
        } else if let Some(r) = self.rec.as_deref_mut() {
            r.tracking = false;
            r.touched = Default::default();
            r.cols.clear();
            r.rebuilt = false;
            self.maybe_stop();
        }
    }

    /// [`HistoryMut::take_changes`]'s body.
    fn take_changes(&mut self) -> Changes {
        if !self.rec.as_ref().is_some_and(|r| r.tracking) {
            return Changes {
                from_revision: self.revision(),
                to_revision: self.revision(),
                ..Changes::default()
            };
        }
        self.seal();
        let to_revision = self.revision();
        let r = self.r();
        let from_revision = std::mem::replace(&mut r.taken_at, to_revision);
        let touched = std::mem::take(&mut r.touched);
        let cols = std::mem::take(&mut r.cols);
        let rebuilt = std::mem::take(&mut r.rebuilt);
        let PerArena([lv, le, lf]) = self.element_changes(&touched);
        let vk = |l: &[(u32, u32)]| l.iter().map(|&(s, g)| Vid::new(s).key(g)).collect();
        let ek = |l: &[(u32, u32)]| l.iter().map(|&(s, g)| Eid::new(s).key(g)).collect();
        let fk = |l: &[(u32, u32)]| l.iter().map(|&(s, g)| Fid::new(s).key(g)).collect();
        Changes {
            vertices: ElementChanges {
                created: vk(&lv[0]),
                removed: vk(&lv[1]),
                modified: vk(&lv[2]),
            },
            edges: ElementChanges {
                created: ek(&le[0]),
                removed: ek(&le[1]),
                modified: ek(&le[2]),
            },
            faces: ElementChanges {
                created: fk(&lf[0]),
                removed: fk(&lf[1]),
                modified: fk(&lf[2]),
            },
            columns: self.column_changes(cols),
            rebuilt,
            from_revision,
            to_revision,
        }
    }

    /// Per arena, the (created, removed, modified) slots as (slot,
    /// generation), sorted, from the slots written since the last take
    /// (`touched`: slot -> generation then).
    fn element_changes(
        &self,
        touched: &PerArena<HashMap<u32, u32>>,
    ) -> PerArena<[Vec<(u32, u32)>; 3]> {
        let mut lists: PerArena<[Vec<(u32, u32)>; 3]> = Default::default();
        for (a, map) in Arena::ALL.into_iter().zip(touched.iter()) {
            for (&slot, &g0) in map {
                let now = self.gen_now(a, slot);
                let (live0, live1) = (g0 & 1 == 1, now & 1 == 1);
                if live0 && live1 && g0 == now {
                    lists[a][2].push((slot, now));
                } else {
                    if live0 {
                        lists[a][1].push((slot, g0));
                    }
                    if live1 {
                        lists[a][0].push((slot, now));
                    }
                }
            }
        }
        // Faces and vertices around a written live edge changed too.
        let mut extra_f = Vec::new();
        let mut extra_v = Vec::new();
        for (&slot, _) in touched[Arena::Edge].iter() {
            let e = Eid::new(slot);
            if self.gen_now(Arena::Edge, slot) & 1 == 0 {
                continue;
            }
            for h in e.halfedges() {
                let rec = self.he[h];
                if !rec.face.is_none() {
                    extra_f.push(rec.face.raw());
                }
                if !rec.origin.is_none() {
                    extra_v.push(rec.origin.raw());
                }
            }
        }
        for (a, extra) in [(Arena::Face, extra_f), (Arena::Vertex, extra_v)] {
            for slot in extra {
                if !touched[a].contains_key(&slot) {
                    let g = self.gen_now(a, slot);
                    if g & 1 == 1 {
                        lists[a][2].push((slot, g));
                    }
                }
            }
        }
        for l in lists.iter_mut().flatten() {
            l.sort_unstable();
            l.dedup();
        }
        lists
    }

    /// The columns touched since the last take (`(set, id) -> (existed
    /// then, name then)`), as they stand now, sorted by arena and name.
    fn column_changes(
        &self,
        cols: HashMap<(ElementKind, u64), (bool, String)>,
    ) -> Vec<ColumnChange> {
        let mut columns: Vec<ColumnChange> = cols
            .into_iter()
            .filter_map(|((kind, id), (existed, name))| {
                let cols = self.attrs.columns(kind);
                let now = cols.meta.iter().position(|m| m.id == id);
                let change = match (existed, now) {
                    (true, Some(_)) => ColumnChangeKind::Modified,
                    (true, None) => ColumnChangeKind::Removed,
                    (false, Some(_)) => ColumnChangeKind::Created,
                    (false, None) => return None,
                };
                let name = now.map_or(name, |i| cols.cols[i].0.clone());
                Some(ColumnChange { kind, name, change })
            })
            .collect();
        columns.sort_by(|a, b| (a.kind as u8, &a.name).cmp(&(b.kind as u8, &b.name)));
        columns
    }

    fn gen_now(&self, a: Arena, slot: u32) -> u32 {
        let s = match a {
            Arena::Vertex => &self.v_slots,
            Arena::Edge => &self.e_slots,
            Arena::Face => &self.f_slots,
        };
        s.generation(slot as usize).unwrap_or(0)
    }

    /// Run `f` (an algorithm, a composite operator) as one undo unit named
    /// `name` while a journal records; with none, just run it (nothing
    /// else: the check is one test). The run's edits share one open step
    /// (see [`end_edit`](Mesh::end_edit)), so each slot is saved once.
    ///
    /// On a mesh with a column whose rule can fail, it runs as a
    /// [`step`](Mesh::step), all or nothing (see
    /// [`Rule::FALLIBLE`](crate::attr::Rule::FALLIBLE)).
    pub(crate) fn as_one_step<R>(
        &mut self,
        name: &str,
        f: impl FnOnce(&mut Mesh) -> Result<R>,
    ) -> Result<R> {
        if self.attrs.may_fail() {
            return self.step(name, f);
        }
        if self.rec.is_none() {
            return f(self);
        }
        self.begin_step(name);
        let out = catch_unwind(AssertUnwindSafe(|| f(self)));
        self.end_step();
        match out {
            Ok(r) => r,
            Err(p) => resume_unwind(p),
        }
    }

    /// Close the open step if a recorder is on.
    #[inline]
    fn seal_if_on(&mut self) {
        if self.rec.is_some() {
            self.seal();
        }
    }
}
