//! The journal's bookkeeping behind two handles: [`Mesh::history`] reads
//! it ([`History`]), [`Mesh::history_mut`] configures and drives it
//! ([`HistoryMut`]).
//!
//! What stays on [`Mesh`] itself is what an editor calls once per user
//! action: [`Mesh::undo`] and [`Mesh::redo`] (the menu items),
//! [`Mesh::step`] (a named tool run as one unit) and
//! [`Mesh::transaction`] (a tool that may fail), the verbs that read as
//! edits of the mesh. Switching the history on, its limits, counting and
//! naming the units for a menu label, manual step brackets, change
//! tracking and committing raw writes are set up once or read by the UI
//! around the edits; behind one handle they stay out of the way of the
//! mesh's own page and are found together.
//!
//! ```
//! use meshloom::journal::HistoryLimits;
//! let mut mesh = meshloom::shapes::cube();
//! mesh.history_mut().enable(HistoryLimits::default());
//! let f = mesh.faces().next().unwrap();
//! mesh.step("Poke", |m| m.poke_face(f))?;
//! let history = mesh.history();
//! assert!(history.enabled());
//! assert_eq!((history.undo_len(), history.undo_name()), (1, Some("Poke")));
//! assert!(mesh.undo());
//! assert_eq!(mesh.history().redo_name(), Some("Poke"));
//! # Ok::<(), meshloom::Error>(())
//! ```

use super::{Changes, HistoryLimits};
use crate::mesh::Mesh;

/// The journal of a mesh, read: whether the undo history is on, what
/// [`Mesh::undo`] and [`Mesh::redo`] would do, its memory. Made by
/// [`Mesh::history`].
///
/// ```
/// let mut mesh = meshloom::shapes::cube();
/// assert!(!mesh.history().enabled());
/// mesh.history_mut().enable(Default::default());
/// let e = mesh.edges().next().unwrap();
/// mesh.split_edge(e, 0.5)?;
/// let h = mesh.history();
/// assert_eq!((h.undo_len(), h.redo_len()), (1, 0));
/// assert!(h.bytes() > 0);
/// assert!(!h.in_transaction());
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct History<'m> {
    mesh: &'m Mesh,
}

/// The journal of a mesh, to configure and drive: turn the undo history
/// and change tracking on and off, bracket named steps by hand, take the
/// changes, commit raw writes. Made by [`Mesh::history_mut`].
///
/// ```
/// use meshloom::journal::HistoryLimits;
/// let mut mesh = meshloom::shapes::cube();
/// let mut h = mesh.history_mut();
/// h.enable(HistoryLimits { max_steps: Some(10), max_bytes: None });
/// h.track_changes(true);
/// h.begin_step("Two pokes");
/// let faces: Vec<_> = mesh.faces().take(2).collect();
/// for f in faces {
///     mesh.poke_face(f)?;
/// }
/// let mut h = mesh.history_mut();
/// h.end_step();
/// assert_eq!(h.take_changes().vertices.created.len(), 2);
/// assert_eq!(mesh.history().undo_name(), Some("Two pokes"));
/// mesh.history_mut().clear();
/// assert_eq!(mesh.history().undo_len(), 0);
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Debug)]
pub struct HistoryMut<'m> {
    mesh: &'m mut Mesh,
}

impl Mesh {
    /// The journal's state, read (see [`History`]).
    pub fn history(&self) -> History<'_> {
        History { mesh: self }
    }

    /// The journal, to configure and drive (see [`HistoryMut`]).
    pub fn history_mut(&mut self) -> HistoryMut<'_> {
        HistoryMut { mesh: self }
    }
}

impl<'m> History<'m> {
    /// Whether the undo history is on.
    pub fn enabled(&self) -> bool {
        self.mesh.history_enabled()
    }

    /// How many units [`undo`](Mesh::undo) can take back. Raw writes
    /// through [`position_slots_mut`](Mesh::position_slots_mut) or
    /// [`attr_view_mut`](Mesh::attr_view_mut) count once committed (by
    /// [`commit_writes`](HistoryMut::commit_writes), the next edit or any
    /// journal call).
    pub fn undo_len(&self) -> usize {
        self.mesh.undo_len()
    }

    /// How many units [`redo`](Mesh::redo) can bring back.
    pub fn redo_len(&self) -> usize {
        self.mesh.redo_len()
    }

    /// The name of the unit [`undo`](Mesh::undo) would take back, if it
    /// was a named step (for a menu label: "Undo Bevel").
    pub fn undo_name(&self) -> Option<&'m str> {
        self.mesh.undo_name()
    }

    /// The name of the unit [`redo`](Mesh::redo) would bring back, if named.
    pub fn redo_name(&self) -> Option<&'m str> {
        self.mesh.redo_name()
    }

    /// Heap bytes the undo and redo logs hold (steps, side records, names).
    pub fn bytes(&self) -> usize {
        self.mesh.history_bytes()
    }

    /// Whether a [transaction](Mesh::transaction) is open.
    pub fn in_transaction(&self) -> bool {
        self.mesh.in_transaction()
    }
}

impl HistoryMut<'_> {
    /// Turn the undo history on (or change its limits). Edits from now on
    /// can be undone.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// mesh.history_mut().enable(Default::default());
    /// let f = mesh.faces().next().unwrap();
    /// mesh.poke_face(f)?;
    /// assert_eq!(mesh.vertex_count(), 9);
    /// assert!(mesh.undo());
    /// assert_eq!(mesh.vertex_count(), 8);
    /// assert!(mesh.redo());
    /// assert_eq!(mesh.vertex_count(), 9);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn enable(&mut self, limits: HistoryLimits) {
        self.mesh.enable_history(limits);
    }

    /// Turn the undo history off and drop it (undo and redo logs).
    pub fn disable(&mut self) {
        self.mesh.disable_history();
    }

    /// Drop every undo and redo step, keeping the history on. Refused
    /// (nothing happens) while a transaction is open.
    pub fn clear(&mut self) {
        self.mesh.clear_history();
    }

    /// Begin a named step: every edit until the matching
    /// [`end_step`](HistoryMut::end_step) is one undo unit, named `name`
    /// (the outermost name wins). Steps nest. [`Mesh::step`] does both
    /// around a closure, and rolls back when it fails.
    pub fn begin_step(&mut self, name: &str) {
        self.mesh.begin_step(name);
    }

    /// End the step [`begin_step`](HistoryMut::begin_step) began (a no-op
    /// with none open).
    pub fn end_step(&mut self) {
        self.mesh.end_step();
    }

    /// Turn change tracking on or off. On:
    /// [`take_changes`](HistoryMut::take_changes) reports from now on.
    pub fn track_changes(&mut self, on: bool) {
        self.mesh.track_changes(on);
    }

    /// What changed since the last call (or since
    /// [`track_changes`](HistoryMut::track_changes) turned tracking on):
    /// edits, transactions (a rolled-back one changes nothing), undos and
    /// redos. Empty with tracking off.
    ///
    /// # Complexity
    /// O(elements touched).
    pub fn take_changes(&mut self) -> Changes {
        self.mesh.take_changes()
    }

    /// Close the open journal step now: raw writes through
    /// [`position_slots_mut`](Mesh::position_slots_mut) or
    /// [`attr_view_mut`](Mesh::attr_view_mut) since the view was taken
    /// become one undo unit (if they changed anything; the redo branch
    /// then goes) and show in [`take_changes`](HistoryMut::take_changes).
    /// Otherwise that happens at the next edit or journal call.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::cube();
    /// mesh.history_mut().enable(Default::default());
    /// mesh.position_slots_mut().unwrap()[0][2] += 1.0;
    /// mesh.history_mut().commit_writes();
    /// assert_eq!(mesh.history().undo_len(), 1);
    /// assert!(mesh.undo());
    /// assert_eq!(mesh.position_slots().unwrap()[0], [0.0, 0.0, 0.0]);
    /// ```
    pub fn commit_writes(&mut self) {
        self.mesh.commit_writes();
    }

    /// The same journal, read (see [`History`]).
    pub fn read(&self) -> History<'_> {
        self.mesh.history()
    }
}
