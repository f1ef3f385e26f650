//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod pov;
pub mod povray;

use std::path::PathBuf;
use tracer::{BruteForce, Count, RenderOptions, Rendered, Sampling, Scene, ShadingMode, load_nff};

/// `../shared/spd` beside the project root (as in CI's fresh clone).
pub fn spd_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/spd");
    assert!(
        dir.is_dir(),
        "the SPD scenes are expected at {} (shared/ beside the project)",
        dir.display()
    );
    dir
}

pub fn load_spd(name: &str) -> Scene {
    let path = spd_dir().join(format!("{name}.nff"));
    load_nff(&path).unwrap_or_else(|e| panic!("{e}"))
}

pub fn options(width: u32, height: u32, sampling: Sampling) -> RenderOptions {
    RenderOptions::new(width, height, sampling, ShadingMode::Color)
}

/// A counted render in a pool of `threads` workers.
pub fn render_counted(scene: &Scene, options: &RenderOptions, threads: usize) -> Rendered<Count> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let accel = BruteForce::new(scene);
    pool.install(|| {
        tracer::render::<Count, _>(
            scene,
            &accel,
            options,
            &tracer::RenderMethod::default(),
            &|_| {},
        )
    })
    .unwrap_or_else(|e| panic!("{e}"))
}
