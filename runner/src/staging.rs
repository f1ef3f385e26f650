//! Staged output: a run writes everything into `<output>/.rtprof-suite-<pid>.partial`
//! and moves the files into place only when complete, so an interrupted or failed run
//! leaves the previous one whole. Every file is written atomically (temporary file,
//! then rename).

use std::path::{Path, PathBuf};

use analysis::RgbImage;
use tracer::image_io::{encode_png_rgb8, write_atomically};

use crate::error::RunError;

/// The staging directory: removed with whatever is left in it when dropped (after an
/// error, a panic or Ctrl-C).
pub struct Staging {
    dir: PathBuf,
}

impl Staging {
    /// Creates the staging directory inside `output`.
    pub fn create(output: &Path) -> Result<Self, RunError> {
        let dir = output.join(format!(".rtprof-suite-{}.partial", std::process::id()));
        std::fs::create_dir_all(&dir).map_err(|e| RunError::io("create", &dir, &e))?;
        Ok(Staging { dir })
    }

    /// Where files are staged.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Moves every staged file to the same place under `output` (one rename each,
    /// replacing the previous run's file).
    pub fn publish(&self, output: &Path) -> Result<(), RunError> {
        let mut pending = vec![self.dir.clone()];
        while let Some(dir) = pending.pop() {
            let entries = std::fs::read_dir(&dir).map_err(|e| RunError::io("read", &dir, &e))?;
            for entry in entries {
                let path = entry.map_err(|e| RunError::io("read", &dir, &e))?.path();
                if path.is_dir() {
                    pending.push(path);
                    continue;
                }
                let rel = path.strip_prefix(&self.dir).unwrap_or(&path);
                let target = output.join(rel);
                if let Some(parent) = target.parent() {
                    std::fs::create_dir_all(parent)
                        .map_err(|e| RunError::io("create", parent, &e))?;
                }
                std::fs::rename(&path, &target)
                    .map_err(|e| RunError::io("move into place", &target, &e))?;
            }
        }
        Ok(())
    }
}

impl Staging {
    /// Keeps what was staged as `partial` (an unfinished run's outputs, named as
    /// such) instead of removing it: one rename; `partial` must not exist.
    pub fn keep_as(self, partial: &Path) -> Result<(), RunError> {
        std::fs::rename(&self.dir, partial)
            .map_err(|e| RunError::io("keep the partial outputs as", partial, &e))
        // Dropped here: the staging directory is gone, so its removal does nothing.
    }
}

/// What a user is told when a run into `output` was stopped after `done` of `total`
/// scenes and its staged files discarded.
pub fn discarded_message(output: &Path, done: usize, total: usize) -> String {
    let previous = if output.join("report.html").is_file() {
        format!(
            "the previous results and reports in {} are intact",
            output.display()
        )
    } else {
        format!("nothing was written to {}", output.display())
    };
    format!(
        "interrupted after {done} of {total} scenes; this run's outputs were discarded and {previous}"
    )
}

impl Drop for Staging {
    fn drop(&mut self) {
        // Best effort: a leftover directory is named as partial and harmless.
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Writes `bytes` at `dir/rel` (atomically, creating directories) and returns `rel`.
pub fn save(dir: &Path, rel: &str, bytes: &[u8]) -> Result<String, RunError> {
    let path = dir.join(rel);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|e| RunError::io("create", parent, &e))?;
    }
    write_atomically(&path, bytes).map_err(|e| RunError::io("write", &path, &e))?;
    Ok(rel.to_string())
}

/// Writes `img` as PNG at `dir/rel` and returns `rel`.
pub fn save_png(dir: &Path, rel: &str, img: &RgbImage) -> Result<String, RunError> {
    let bytes = encode_png_rgb8(img.width, img.height, &img.data).map_err(|e| RunError::Io {
        action: "encode",
        path: dir.join(rel),
        message: e.to_string(),
    })?;
    save(dir, rel, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn staged_files_replace_the_previous_ones_only_when_published() {
        let out = std::env::temp_dir().join(format!("rtprof-staging-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&out);
        std::fs::create_dir_all(&out).unwrap();
        std::fs::write(out.join("results.json"), "old").unwrap();
        {
            let staging = Staging::create(&out).unwrap();
            save(staging.dir(), "results.json", b"new").unwrap();
            save(staging.dir(), "images/a.png", b"png").unwrap();
            // Dropped without publishing: the old file stays, the staging goes.
        }
        assert_eq!(
            std::fs::read_to_string(out.join("results.json")).unwrap(),
            "old"
        );
        assert_eq!(std::fs::read_dir(&out).unwrap().count(), 1);
        let staging = Staging::create(&out).unwrap();
        save(staging.dir(), "results.json", b"new").unwrap();
        save(staging.dir(), "images/a.png", b"png").unwrap();
        staging.publish(&out).unwrap();
        drop(staging);
        assert_eq!(
            std::fs::read_to_string(out.join("results.json")).unwrap(),
            "new"
        );
        assert_eq!(std::fs::read(out.join("images/a.png")).unwrap(), b"png");
        std::fs::remove_dir_all(&out).unwrap();
    }
}
