//! Arguments shared by the commands that render a scene, and the render driver they
//! share: load, build, run in a thread pool with a progress bar, time each phase.

use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::time::{Duration, Instant};
use tracer::{
    Counter, Limits, RenderOptions, Rendered, Sampling, Scene, ShadingMode, VariantSet, load_nff,
    render_variant,
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
}

/// Parses `WxH` such as `640x480`.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{text}' is not a size: expected WxH such as 640x480");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u64 = w.trim().parse().map_err(|_| bad())?;
    let h: u64 = h.trim().parse().map_err(|_| bad())?;
    Limits::default().check_size(w, h)?;
    Ok((w as u32, h as u32))
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
        let scene = load_nff(&self.scene)?;
        let parsing = start.elapsed();

        let (width, height) = self.size.unwrap_or((scene.view.width, scene.view.height));
        let sampling = if self.spd {
            Sampling::SpdCorners
        } else {
            Sampling::PixelCenters
        };
        let options = RenderOptions::new(width, height, sampling, mode);
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
