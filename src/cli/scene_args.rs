//! Arguments shared by the commands that render a scene, and the render driver they
//! share: load, build, run in a thread pool with a progress bar, time each phase.

use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::time::{Duration, Instant};
use tracer::{
    Counter, Limits, RenderOptions, Rendered, Sampling, Scene, ShadingMode, VariantSet,
    load_nff_with_limits, render_variant,
};

#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    /// NFF scene file.
    pub scene: PathBuf,
    /// Optimization variants, combined: e.g. bvh,fast-sqrt (`rtprof variants` lists them).
    #[arg(long, default_value = "baseline", value_name = "V")]
    pub variant: String,
    /// Image size WxH (default: the scene's resolution).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// SPD procedure: rays through pixel corners ((W+1)x(H+1)), each pixel the mean of four.
    #[arg(long)]
    pub spd: bool,
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Option<u16>,
    /// Ray-tree depth: the eye ray is level 1, each reflection or refraction one more
    /// (default: 5, the SPD rule; at most --max-ray-depth).
    #[arg(long, value_name = "N")]
    pub depth: Option<u32>,
    #[command(flatten)]
    pub limits: LimitArgs,
}

/// The --help heading of the limit flags.
const LIMITS: &str = "Limits (raise them for very large inputs)";

/// The input limits, checked before anything is allocated; each error names the flag
/// that raises it. Defaults: `tracer::Limits::default()`. Listed under their own
/// heading in --help.
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

    /// Loads an NFF scene within these limits.
    pub fn load(&self, path: &std::path::Path) -> Result<Scene> {
        Ok(load_nff_with_limits(path, &self.limits())?)
    }
}

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

/// A rayon pool of `threads` workers (default: one per core), named `rtprof-worker-N`
/// so that profiles and debuggers show whose stack is whose.
pub fn thread_pool(threads: Option<u16>) -> Result<rayon::ThreadPool> {
    let mut pool = rayon::ThreadPoolBuilder::new().thread_name(|i| format!("rtprof-worker-{i}"));
    if let Some(n) = threads {
        pool = pool.num_threads(usize::from(n));
    }
    pool.build().context("cannot start the worker threads")
}

/// A finished render with its timings.
pub struct Run<C> {
    pub scene: Scene,
    pub rendered: Rendered<C>,
    pub preprocessing: Duration,
    pub tracing: Duration,
    pub threads: usize,
    pub variants: VariantSet,
}

impl SceneArgs {
    /// Loads the scene, renders it with counter `C` and reports progress on stderr.
    pub fn run<C: Counter>(&self, mode: ShadingMode) -> Result<Run<C>> {
        let variants = VariantSet::parse(&self.variant)?;
        let start = Instant::now();
        let scene = self.limits.load(&self.scene)?;
        let parsing = start.elapsed();

        let (width, height) = self.size.unwrap_or((scene.view.width, scene.view.height));
        let sampling = if self.spd {
            Sampling::SpdCorners
        } else {
            Sampling::PixelCenters
        };
        let mut options = RenderOptions::new(width, height, sampling, mode);
        options.limits = self.limits.limits();
        if let Some(depth) = self.depth {
            options.max_depth = depth;
        }
        options
            .limits
            .check_ray_depth(options.max_depth)
            .map_err(anyhow::Error::msg)?;
        // Refused before the progress bar and the framebuffer exist.
        options
            .limits
            .check_size(u64::from(width), u64::from(height))
            .map_err(anyhow::Error::msg)?;
        let pool = thread_pool(self.threads)?;
        let threads = pool.current_num_threads();

        let bar = ProgressBar::new(options.sample_rows());
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} tracing [{bar:40}] {pos}/{len} rows, {elapsed} (eta {eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        let rendered =
            pool.install(|| render_variant::<C>(&scene, &options, &variants, &|n| bar.inc(n)));
        bar.finish_and_clear();
        let out = match rendered {
            Ok(r) => r,
            Err(e) => bail!("{}: {e}", self.scene.display()),
        };
        Ok(Run {
            scene,
            rendered: out.rendered,
            preprocessing: parsing + out.preprocessing,
            tracing: out.tracing,
            threads,
            variants,
        })
    }
}

impl<C> Run<C> {
    /// The SPD-style timing report: preprocessing vs tracing, rays per second.
    pub fn timing_report(&self, scene_path: &std::path::Path) -> String {
        let rays = self.rendered.rays;
        let secs = self.tracing.as_secs_f64().max(1e-9);
        format!(
            "{}: {}, variant {}\npreprocessing {:.3} s (parse + build), tracing {:.3} s on {} thread{}\n{} rays ({} eye), {:.0} rays/s",
            scene_path.display(),
            self.scene.summary(),
            self.variants,
            self.preprocessing.as_secs_f64(),
            self.tracing.as_secs_f64(),
            self.threads,
            if self.threads == 1 { "" } else { "s" },
            rays.total(),
            rays.primary,
            rays.total() as f64 / secs,
        )
    }
}
