//! The scene as an outside tracer reads it, written once into the directory of its
//! runs: NFF through rtprof's NFF writer (what rtprof itself parsed, so every program
//! sees the same numbers), POV-Ray's language, or Tachyon's (whose camera is written
//! for the size the program renders).

use std::path::{Path, PathBuf};

use tracer::Scene;

use super::definition::SceneFormat;
use super::failure::{Failure, FailureKind};

/// Writes `scene` for a program reading `format` into `dir`, for a picture of `size`
/// (width, height); `None` for a program that draws its own scene.
pub fn write_scene(
    scene: &Scene,
    format: SceneFormat,
    dir: &Path,
    (width, height): (u32, u32),
) -> Result<Option<PathBuf>, Failure> {
    let (name, text) = match format {
        SceneFormat::Own => return Ok(None),
        SceneFormat::Nff => ("scene.nff", tracer::nff_writer::scene_to_nff(scene)),
        SceneFormat::Pov => ("scene.pov", tracer::scene_to_pov(scene)),
        SceneFormat::Tachyon => (
            "scene.dat",
            tracer::scene_to_tachyon_at(scene, width, height),
        ),
    };
    let path = dir.join(name);
    let failed = |e: &dyn std::fmt::Display| Failure {
        kind: FailureKind::Setup,
        reason: format!("cannot write the scene to {}: {e}", path.display()),
        stderr_tail: Vec::new(),
    };
    std::fs::create_dir_all(dir).map_err(|e| failed(&e))?;
    tracer::image_io::write_atomically(&path, text.as_bytes()).map_err(|e| failed(&e))?;
    let path = std::path::absolute(&path).map_err(|e| failed(&e))?;
    Ok(Some(path))
}
