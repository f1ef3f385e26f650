//! Arguments shared by the commands that render a scene, and the render driver they
//! share: load, build, run in a thread pool with a progress bar, time each phase.

use anyhow::Result;
use runner::render_job::{RenderRequest, RenderSettings, SceneRender, render_scene};
use runner::scene_input::SceneInput;
use std::path::{Path, PathBuf};
use terminal::progress::Bars;
use tracer::{Limits, RenderOptions, RenderWith, Scene, ShadingMode, VariantSet};

#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    #[arg(value_name = "SCENE", value_parser = parse_scene, help = SCENE_HELP)]
    pub scene: SceneInput,
    /// Optimization variants, combined: e.g. bvh,fast-sqrt (`rtprof variants` lists them).
    #[arg(long, default_value = "baseline", value_name = "V")]
    pub variant: String,
    #[command(flatten)]
    pub render: RenderFlags,
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

// How to render: the flags of every command that renders a scene.
#[derive(clap::Args, Debug)]
pub struct RenderFlags {
    #[arg(long, value_name = "WxH", value_parser = parse_size, help = SIZE_HELP)]
    pub size: Option<(u32, u32)>,
    /// SPD procedure: rays through pixel corners ((W+1)x(H+1)), each pixel the mean of four.
    #[arg(long)]
    pub spd: bool,
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<u16>,
    /// Ray-tree depth: the eye ray is level 1, each reflection or refraction one more
    /// (default: 5, the SPD rule; at most --max-ray-depth).
    #[arg(long, value_name = "N")]
    pub depth: Option<u32>,
    /// How the bvh variant builds its tree: binned_sah (surface area heuristic) or
    /// midpoint (the middle of the widest axis).
    #[arg(long, value_name = "B", default_value = "binned_sah", value_parser = parse_builder)]
    pub bvh_builder: tracer::BvhBuilder,
    #[command(flatten)]
    pub limits: LimitArgs,
}

impl RenderFlags {
    /// The render options for `scene`, full colour.
    pub fn options(&self, scene: &Scene) -> tracer::RenderOptions {
        self.settings().options(scene, ShadingMode::Color)
    }

    pub fn settings(&self) -> RenderSettings {
        RenderSettings {
            size: self.size,
            spd: self.spd,
            threads: self.threads,
            depth: self.depth,
            limits: self.limits.limits(),
            per_sample: false,
            bvh_builder: self.bvh_builder,
        }
    }
}

/// The --help heading of the limit flags.
const LIMITS: &str = "Limits (raise them for very large inputs)";

// The input limits, checked before anything is allocated; each error names the flag
// that raises it. Defaults: `tracer::Limits::default()`. Listed under their own
// heading in --help.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct LimitArgs {
    /// Largest scene file, bytes [default: 1 GiB].
    #[arg(long, help_heading = LIMITS, value_name = "BYTES")]
    pub max_file_bytes: Option<u64>,
    /// Most primitives in a scene [default: 10,000,000].
    #[arg(long, help_heading = LIMITS, value_name = "N")]
    pub max_primitives: Option<u64>,
    /// Most vertices of one polygon or patch [default: 65,536].
    #[arg(long, help_heading = LIMITS, value_name = "N")]
    pub max_polygon_vertices: Option<u64>,
    /// Largest image width or height [default: 16,384].
    #[arg(long, help_heading = LIMITS, value_name = "PIXELS")]
    pub max_side: Option<u32>,
    /// Largest image, width x height [default: 67,108,864].
    #[arg(long, help_heading = LIMITS, value_name = "PIXELS")]
    pub max_pixels: Option<u64>,
    /// Largest framebuffer, 12 bytes a pixel [default: 1 GiB].
    #[arg(long, help_heading = LIMITS, value_name = "BYTES")]
    pub max_framebuffer_bytes: Option<u64>,
    /// Ceiling of the ray-tree depth [default: 64].
    #[arg(long, help_heading = LIMITS, value_name = "N")]
    pub max_ray_depth: Option<u32>,
}

impl LimitArgs {
    /// The defaults with the given flags applied.
    pub fn limits(&self) -> Limits {
        let d = Limits::default();
        Limits {
            max_side: self.max_side.unwrap_or(d.max_side),
            max_pixels: self.max_pixels.unwrap_or(d.max_pixels),
            max_framebuffer_bytes: self
                .max_framebuffer_bytes
                .unwrap_or(d.max_framebuffer_bytes),
            max_polygon_vertices: self.max_polygon_vertices.unwrap_or(d.max_polygon_vertices),
            max_primitives: self.max_primitives.unwrap_or(d.max_primitives),
            max_ray_depth: self.max_ray_depth.unwrap_or(d.max_ray_depth),
            max_file_bytes: self.max_file_bytes.unwrap_or(d.max_file_bytes),
        }
    }

    /// Loads a scene within these limits.
    pub fn load(&self, input: &SceneInput) -> Result<Scene> {
        Ok(input.load(&self.limits())?)
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

/// Parses a `--threads` count; the limit is the library's one rule
/// (`runner::pool::check_threads`, the web app's too).
pub fn parse_threads(text: &str) -> Result<u16, String> {
    let n: u64 = text
        .trim()
        .parse()
        .map_err(|_| format!("'{text}' is not a thread count: give a whole number such as 2"))?;
    runner::pool::check_threads(n).map_err(|e| e.to_string())
}

/// The help of every command's --size: one rule for all of them.
pub const SIZE_HELP: &str = "Image size WxH [default: the scene's resolution]";

/// Parses `WxH` such as `640x480` (the size limits are checked when rendering, so
/// that `--max-side` and friends can raise them).
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{text}' is not a size: expected WxH such as 640x480");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 {
        return Err(format!("image size {w}x{h} must be positive"));
    }
    Ok((w, h))
}

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
                ..self.render.settings()
            },
            mode,
            stop: terminal::interrupt::install(),
        };
        // Loaded twice only without an accelerator, where the render costs far more.
        if request.variants.config().accel.tests_everything() {
            let scene = self.render.limits.load(&self.scene)?;
            let options = request.settings.options(&scene, mode);
            note_if_slow(&scene, &options, &request.variants, self.render.threads)?;
        }
        terminal::startup::mark("estimate");
        Ok(render_scene(&request, &Bars::delayed())?)
    }
}

/// Prints the estimate of a long brute-force render (`runner::estimate`) on stderr.
pub fn note_if_slow(
    scene: &Scene,
    options: &RenderOptions,
    variants: &VariantSet,
    threads: Option<u16>,
) -> Result<()> {
    let estimate = runner::estimate::brute_force(scene, options, variants, threads)?;
    if let Some(note) = estimate.and_then(|e| e.note()) {
        eprintln!("{note}");
    }
    Ok(())
}

/// The default output name for a command on `input`: `<prefix><scene name><suffix>`
/// in the current directory.
pub fn named_after(input: &SceneInput, prefix: &str, suffix: &str) -> PathBuf {
    PathBuf::from(format!("{prefix}{}{suffix}", input.name()))
}

/// A `--bvh-builder` name.
fn parse_builder(name: &str) -> Result<tracer::BvhBuilder, String> {
    tracer::BvhBuilder::parse(name).ok_or_else(|| {
        let names: Vec<&str> = tracer::BvhBuilder::ALL.iter().map(|b| b.name()).collect();
        format!(
            "unknown builder '{name}'; choose one of {}",
            names.join(", ")
        )
    })
}
