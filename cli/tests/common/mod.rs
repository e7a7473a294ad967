//! Scratch directories for the CLI tests: one per test, removed when the
//! test ends, passed or failed.

use std::path::{Path, PathBuf};

/// A directory that removes itself when dropped.
pub struct Scratch(PathBuf);

/// A fresh, empty scratch directory named after the test.
pub fn scratch(test: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("meshloom-cli-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    Scratch(dir)
}

impl Scratch {
    /// The path of file `name` inside.
    pub fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    /// The directory.
    #[allow(dead_code)] // not every test file asks for it
    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
