//! Arguments shared by the commands that render a scene, and the render driver they
//! share: load, build, run in a thread pool with a progress bar, time each phase.

use anyhow::Result;
use runner::render_job::{RenderRequest, RenderSettings, SceneRender, render_scene};
use runner::scene_input::SceneInput;
use std::path::{Path, PathBuf};
use terminal::progress::Bars;
use tracer::{RenderWith, ShadingMode, VariantSet};

#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    #[arg(value_name = "SCENE", value_parser = parse_scene, help = SCENE_HELP)]
    pub scene: SceneInput,
    /// Optimization variants, combined: e.g. bvh,fast-sqrt (`rtprof variants` lists them).
    #[arg(long, default_value = "baseline", value_name = "V")]
    pub variant: String,
    #[command(flatten)]
    pub render: RenderSettings,
}

// How to shade: full colour unless one of these is given.
#[derive(clap::Args, Debug, Default)]
pub struct ShadingFlags {
    /// Full shading converted to gray.
    #[arg(long)]
    pub gray: bool,
    /// The thesis hardware's shading: Lambert term of the first light only, gray
    /// (with or without --gray: it is gray either way).
    #[arg(long)]
    pub diffuse_only: bool,
}

impl ShadingFlags {
    /// The shading mode the flags choose.
    pub fn mode(&self) -> ShadingMode {
        if self.diffuse_only {
            ShadingMode::DiffuseOnly
        } else if self.gray {
            ShadingMode::Gray
        } else {
            ShadingMode::Color
        }
    }
}

/// The help of every command's scene argument: one list of what a scene can be.
pub const SCENE_HELP: &str = "NFF file, built-in scene (balls3) or generated scene (spd:rings, \
                              spd:balls:2 = size factor 2, sphereflake:3); `rtprof scene list` \
                              names them all";

/// Reads a scene argument (relative paths from the current directory).
pub fn parse_scene(text: &str) -> Result<SceneInput, String> {
    SceneInput::parse(text, Path::new("")).map_err(|e| e.to_string())
}

/// The help of every command's --size: one rule for all of them.
pub const SIZE_HELP: &str = "Image size WxH [default: the scene's resolution]";

// The flags' parsers live with the settings they fill.
pub use runner::pool::parse_threads;
pub use runner::render_job::parse_size;

impl SceneArgs {
    /// Loads the scene and renders it with counter `C`, progress on stderr.
    /// A brute-force render of a big scene first says how long it will take.
    pub fn run<C: RenderWith>(&self, mode: ShadingMode) -> Result<SceneRender<C>> {
        self.run_with(mode, false)
    }

    /// [`SceneArgs::run`], recording each sample's work when `per_sample`.
    pub fn run_with<C: RenderWith>(
        &self,
        mode: ShadingMode,
        per_sample: bool,
    ) -> Result<SceneRender<C>> {
        let request = RenderRequest {
            scene: &self.scene,
            variants: VariantSet::parse(&self.variant)?,
            settings: RenderSettings {
                per_sample,
                ..self.render.clone()
            },
            mode,
            stop: terminal::interrupt::install(),
        };
        Ok(render_scene(&request, &Bars::delayed())?)
    }
}

/// The default output name for a command on `input`: `<prefix><scene name><suffix>`
/// in the current directory.
pub fn named_after(input: &SceneInput, prefix: &str, suffix: &str) -> PathBuf {
    PathBuf::from(format!("{prefix}{}{suffix}", input.name()))
}
