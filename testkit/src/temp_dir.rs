//! A scratch directory for a test: fresh when made, removed when dropped.

use std::path::{Path, PathBuf};

/// A fresh directory under the system temp dir, named after the test and the process,
/// removed on drop.
pub struct TempDir(PathBuf);

impl TempDir {
    /// `rtprof-<tag>-<pid>` under the temp dir, emptied first.
    pub fn new(tag: &str) -> std::io::Result<Self> {
        let dir = std::env::temp_dir().join(format!("rtprof-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir)?;
        Ok(TempDir(dir))
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
