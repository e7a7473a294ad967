//! Progress on stderr for work that takes over a second, and only when
//! stderr is a terminal: piped or redirected output stays clean.

use std::io::IsTerminal;
use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long work runs before its progress shows.
const DELAY: Duration = Duration::from_secs(1);

/// A spinner or bar that appears after [`DELAY`] if the work is still
/// going, and disappears when dropped.
pub struct Progress {
    bar: ProgressBar,
    stop: Option<mpsc::Sender<()>>,
    waiter: Option<JoinHandle<()>>,
}

impl Progress {
    /// A spinner with a message, for work of unknown length.
    pub fn spinner(message: impl Into<String>) -> Progress {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} ({elapsed})") {
            bar.set_style(style);
        }
        Progress::start(bar, message.into())
    }

    /// A bar counting up to `total`.
    pub fn bar(message: impl Into<String>, total: usize) -> Progress {
        let bar = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::hidden());
        if let Ok(style) =
            ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} ({elapsed}, {eta} left)")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        Progress::start(bar, message.into())
    }

    fn start(bar: ProgressBar, message: String) -> Progress {
        bar.set_message(message);
        if !std::io::stderr().is_terminal() {
            return Progress {
                bar,
                stop: None,
                waiter: None,
            };
        }
        let (stop, stopped) = mpsc::channel::<()>();
        let shown = bar.clone();
        let waiter = std::thread::spawn(move || {
            if let Err(mpsc::RecvTimeoutError::Timeout) = stopped.recv_timeout(DELAY) {
                shown.set_draw_target(ProgressDrawTarget::stderr());
                shown.enable_steady_tick(Duration::from_millis(120));
                // Wait for the work to end (a message or a hang-up).
                let _ = stopped.recv();
            }
        });
        Progress {
            bar,
            stop: Some(stop),
            waiter: Some(waiter),
        }
    }

    /// Change the message (a spinner's stage).
    pub fn message(&self, message: String) {
        self.bar.set_message(message);
    }

    /// Change the total.
    pub fn set_length(&self, total: u64) {
        self.bar.set_length(total);
    }

    /// Report `done` units of the total.
    pub fn set(&self, done: usize) {
        self.bar.set_position(done as u64);
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        drop(self.stop.take());
        if let Some(w) = self.waiter.take() {
            let _ = w.join();
        }
        self.bar.finish_and_clear();
    }
}
