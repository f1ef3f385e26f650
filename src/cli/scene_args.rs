//! Arguments shared by the commands that render a scene, and the render driver they
//! share: load, build, run in a thread pool with a progress bar, time each phase.

use anyhow::Result;
use runner::render_job::{RenderRequest, RenderSettings, SceneRender, render_scene};
use runner::scene_input::SceneInput;
use terminal::progress::Bars;
use tracer::{RenderWith, ShadingMode, VariantSet};

#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    #[arg(value_name = "SCENE", value_parser = SceneInput::parse_arg, help = SceneInput::HELP)]
    pub scene: SceneInput,
    /// Optimization variants, combined: e.g. bvh,fast-sqrt (`rtprof variants` lists them).
    #[arg(long, default_value = "baseline", value_name = "V")]
    pub variant: String,
    #[command(flatten)]
    pub render: RenderSettings,
}

// The flags' parsers and helps live with the settings they fill.
pub use runner::pool::parse_threads;
pub use runner::render_job::{SIZE_HELP, ShadingFlags, parse_size};

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
