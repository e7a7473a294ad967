//! Progress reports and cancellation for long-running algorithms.
//!
//! Every algorithm that can take long takes a [`Progress`]: pass
//! [`Progress::none()`] to run silently, or [`Progress::new`] with a
//! callback that gets a [`ProgressInfo`] now and then and answers
//! [`Flow::Continue`] or [`Flow::Cancel`]. A cancelled algorithm returns
//! [`Error::Cancelled`] and leaves the mesh exactly as it was.
//!
//! ```
//! use meshloom::algo::{Flow, Progress, ProgressInfo};
//! let mut seen = 0;
//! let mut callback = |info: &ProgressInfo<'_>| {
//!     seen += 1;
//!     assert!(info.done <= info.total);
//!     Flow::Continue
//! };
//! let mut progress = Progress::new(&mut callback);
//! progress.report("example", "counting", 5, 10)?;
//! drop(progress);
//! assert_eq!(seen, 1);
//! # Ok::<(), meshloom::Error>(())
//! ```

use crate::error::{Error, Result};

/// What a progress callback tells the algorithm.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Go on.
    Continue,
    /// Stop as soon as possible; the mesh is left as it was.
    Cancel,
}

/// One progress report.
#[derive(Copy, Clone, Debug)]
pub struct ProgressInfo<'a> {
    /// The algorithm, as its function is named (`"loop_subdivide"`).
    pub algorithm: &'static str,
    /// The stage within it (`"level 2 of 3"`, `"collapses"`).
    pub stage: &'a str,
    /// Units of work done in this stage.
    pub done: u64,
    /// Units of work in this stage (`done == total` at its end).
    pub total: u64,
}

/// An optional progress callback that can cancel.
#[derive(Default)]
pub struct Progress<'a> {
    callback: Option<&'a mut dyn FnMut(&ProgressInfo<'_>) -> Flow>,
}

impl<'a> Progress<'a> {
    /// No reports, never cancelled.
    pub fn none() -> Progress<'static> {
        Progress { callback: None }
    }

    /// Reports go to `callback`.
    pub fn new(callback: &'a mut dyn FnMut(&ProgressInfo<'_>) -> Flow) -> Progress<'a> {
        Progress {
            callback: Some(callback),
        }
    }

    /// Whether anyone listens (algorithms may skip counting work when not).
    pub fn is_active(&self) -> bool {
        self.callback.is_some()
    }

    /// Report progress; algorithms call this between units of work and
    /// return the error it gives before changing the mesh.
    ///
    /// # Errors
    /// [`Error::Cancelled`] when the callback answers [`Flow::Cancel`].
    pub fn report(
        &mut self,
        algorithm: &'static str,
        stage: &str,
        done: u64,
        total: u64,
    ) -> Result<()> {
        let Some(callback) = self.callback.as_mut() else {
            return Ok(());
        };
        let info = ProgressInfo {
            algorithm,
            stage,
            done,
            total,
        };
        match callback(&info) {
            Flow::Continue => Ok(()),
            Flow::Cancel => Err(Error::Cancelled { algorithm }),
        }
    }
}

impl std::fmt::Debug for Progress<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Progress")
            .field("active", &self.is_active())
            .finish()
    }
}
