//! The render job of `rtprof render` and `rtprof count`: load a scene within limits,
//! render it once with the chosen counter and variants, and time the two phases
//! (preprocessing = parse + build, tracing) as the SPD rules ask.

use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use tracer::accel::BvhStats;
use tracer::{
    Counts, Limits, RenderOptions, Rendered, Sampling, Scene, ShadingMode, VariantSet,
    render_variant_until,
};

use crate::error::RunError;
use crate::pool::{Workers, workers_for};
use crate::progress::Progress;
use crate::scene_input::SceneInput;

/// What to render and how.
pub struct RenderRequest<'a> {
    pub scene: &'a SceneInput,
    pub variants: VariantSet,
    pub settings: RenderSettings,
    pub mode: ShadingMode,
    /// Set to stop the render (Ctrl-C): it ends within a row with [`RunError::Stopped`].
    pub stop: &'a AtomicBool,
}

// How to render a scene: the settings every rendering command takes. With the `clap`
// feature they are the command line's render flags, declared here once. (A plain
// comment: clap would take a doc comment as the about of every command that
// flattens these flags.)
#[derive(Clone, Debug, Default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct RenderSettings {
    /// Image size WxH [default: the scene's resolution].
    #[cfg_attr(feature = "clap", arg(long, value_name = "WxH", value_parser = parse_size))]
    pub size: Option<(u32, u32)>,
    /// SPD procedure: rays through pixel corners ((W+1)x(H+1)), each pixel the mean of four.
    #[cfg_attr(feature = "clap", arg(long))]
    pub spd: bool,
    /// Worker threads (default: one per core).
    #[cfg_attr(feature = "clap", arg(long, value_name = "N", value_parser = crate::pool::parse_threads))]
    pub threads: Option<u16>,
    /// Ray-tree depth: the eye ray is level 1, each reflection or refraction one more
    /// (default: 5, the SPD rule; at most --max-ray-depth).
    #[cfg_attr(feature = "clap", arg(long, value_name = "N"))]
    pub depth: Option<u32>,
    /// How the bvh variant builds its tree: binned_sah (surface area heuristic) or
    /// midpoint (the middle of the widest axis).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "B", default_value = "binned_sah")
    )]
    pub bvh_builder: tracer::BvhBuilder,
    #[cfg_attr(feature = "clap", command(flatten))]
    pub limits: Limits,
    /// Record each sample's work ([`tracer::SampleStats`], for per-pixel maps).
    #[cfg_attr(feature = "clap", arg(skip))]
    pub per_sample: bool,
}

/// The help of every command's `--size`: one rule for all of them.
pub const SIZE_HELP: &str = "Image size WxH [default: the scene's resolution]";

// How to shade: full colour unless one of these is given. (A plain comment: clap would
// take a doc comment as the about of every command that flattens these flags.)
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct ShadingFlags {
    /// Full shading converted to gray.
    #[cfg_attr(feature = "clap", arg(long))]
    pub gray: bool,
    /// The thesis hardware's shading: Lambert term of the first light only, gray
    /// (with or without --gray: it is gray either way).
    #[cfg_attr(feature = "clap", arg(long))]
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

/// Largest scene whose end-point overlap `rtprof count` computes (it clips every
/// primitive against the boxes it overlaps: seconds at this size).
const EPO_MAX_PRIMITIVES: usize = 200_000;

impl RenderSettings {
    /// The render options for `scene` (limits are checked when rendering).
    pub fn options(&self, scene: &Scene, mode: ShadingMode) -> RenderOptions {
        let (width, height) = self.size.unwrap_or((scene.view.width, scene.view.height));
        let sampling = if self.spd {
            Sampling::SpdCorners
        } else {
            Sampling::PixelCenters
        };
        let mut options = RenderOptions::new(width, height, sampling, mode);
        options.limits = self.limits;
        if let Some(depth) = self.depth {
            options.max_depth = depth;
        }
        options.per_sample = self.per_sample;
        options.bvh_builder = self.bvh_builder;
        options
    }
}

/// A finished render with its timings.
pub struct SceneRender<C> {
    pub scene: Scene,
    pub rendered: Rendered<C>,
    /// Parse + scene preparation + structure build.
    pub preprocessing: Duration,
    pub tracing: Duration,
    pub threads: usize,
    pub variants: VariantSet,
    /// The shading it used (`rtprof count --pixel-stats` renders its maps the same way,
    /// so that they sum to its counters).
    pub mode: ShadingMode,
    /// Bytes of the intersection structure the variant built (0: none).
    pub accelerator_bytes: usize,
    /// The BVH's figures when the variant built one.
    pub bvh: Option<BvhStats>,
}

/// Loads and renders; progress counts sample rows.
pub fn render_scene<C: tracer::RenderWith>(
    req: &RenderRequest<'_>,
    progress: &dyn Progress,
) -> Result<SceneRender<C>, RunError> {
    let start = Instant::now();
    let scene = req.scene.load(&req.settings.limits)?;
    let parsing = start.elapsed();
    let options = req.settings.options(&scene, req.mode);
    let (width, height) = (options.width, options.height);
    // Refused before the progress bar and the framebuffer exist.
    let refuse = |e: tracer::LimitError| RunError::refused(req.scene, &e);
    options
        .limits
        .check_ray_depth(options.max_depth)
        .map_err(refuse)?;
    options
        .limits
        .check_size(u64::from(width), u64::from(height))
        .map_err(refuse)?;
    // A long brute-force render first says how long it will take.
    crate::estimate::note_if_slow(
        &scene,
        &options,
        &req.variants,
        req.settings.threads,
        progress,
    )?;
    let rows = options.sample_rows();
    let workers = Workers::new(workers_for(req.settings.threads, rows))?;
    progress.begin("tracing", rows);
    let out = workers.install(|| {
        render_variant_until::<C>(
            &scene,
            &options,
            &req.variants,
            &|n| progress.advance(n),
            req.stop,
        )
    });
    progress.end();
    let out = out.map_err(|e| RunError::render(req.scene, &e))?;
    Ok(SceneRender {
        scene,
        rendered: out.rendered,
        preprocessing: parsing + out.preprocessing,
        tracing: out.tracing,
        threads: workers.threads(),
        variants: req.variants.clone(),
        mode: req.mode,
        accelerator_bytes: out.accelerator_bytes,
        bvh: out.bvh,
    })
}

impl<C> SceneRender<C> {
    /// The SPD-style timing report: preprocessing vs tracing, rays per second.
    pub fn timing_report(&self, input: &SceneInput) -> String {
        use reports::format::{count, plural, quantity, seconds};
        let rays = self.rendered.rays;
        let secs = self.tracing.as_secs_f64().max(1e-9);
        format!(
            "{}: {}, variant {}\npreprocessing {} (parse + build), tracing {} on {}\n{} rays ({} eye), {} rays/s",
            input,
            self.scene.summary(),
            self.variants,
            seconds(self.preprocessing.as_secs_f64()),
            seconds(self.tracing.as_secs_f64()),
            plural(self.threads, "thread"),
            count(rays.total()),
            count(rays.primary),
            quantity(rays.total() as f64 / secs),
        ) + &format!("\n{}", self.memory_line())
    }

    /// How good the structure is, from its own figures and the render's `counts`: for a
    /// BVH, its size, SAH cost and the boxes, leaves and tests per ray the surface
    /// area model predicts against those measured; for SIMD lanes, how many of the
    /// lanes issued held a primitive. Nothing for brute force.
    pub fn structure_lines(&self, counts: &Counts) -> Vec<String> {
        use reports::format::{count, fixed, percent, plural};
        let mut lines = Vec::new();
        let per_ray = crate::bvh_study::PerRay::of(counts);
        if let Some(b) = &self.bvh {
            let tree = tracer::Bvh::build_with(&self.scene, b.builder);
            let epo = if self.scene.primitive_count() <= EPO_MAX_PRIMITIVES {
                fixed(tree.end_point_overlap(), 2)
            } else {
                format!(
                    "not computed (more than {} primitives)",
                    count(EPO_MAX_PRIMITIVES as u64)
                )
            };
            let histogram = |h: &[u64], offset: usize| {
                h.iter()
                    .enumerate()
                    .filter(|&(_, &n)| n > 0)
                    .map(|(i, n)| format!("{}:{}", i + offset, count(*n)))
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            lines.push(format!(
                "bvh ({} builder): {} nodes ({} leaves of at most {}), depth {}; SAH cost {}, end-point overlap {epo}",
                b.builder,
                count(b.nodes as u64),
                count(b.leaves as u64),
                plural(b.max_leaf_size, "primitive"),
                b.max_depth,
                fixed(b.sah_cost, 2)
            ));
            lines.push(format!(
                "bvh leaves by depth (root 1): {}; by size: {}",
                histogram(&tree.shape().depth_histogram, 1),
                histogram(&tree.shape().leaf_size_histogram, 0)
            ));
            lines.push(format!(
                "bvh per ray, measured / predicted: boxes {} / {}, leaves {} / {}, tests {} / {} (predicted for random lines through the root box, searched to the end)",
                fixed(per_ray.nodes, 1),
                fixed(b.predicted_nodes_per_ray, 1),
                fixed(per_ray.leaves, 2),
                fixed(b.predicted_leaves_per_ray, 2),
                fixed(per_ray.tests, 2),
                fixed(b.predicted_tests_per_ray, 2),
            ));
        }
        if counts.accel.lanes_issued > 0 {
            lines.push(format!(
                "simd lanes: {} of {} issued held a primitive or a child box ({})",
                count(counts.accel.lanes_active),
                count(counts.accel.lanes_issued),
                percent(
                    100.0 * counts.accel.lanes_active as f64 / counts.accel.lanes_issued as f64,
                    1
                )
            ));
        }
        lines
    }

    /// What the render held: scene, structure and framebuffer, and the process's peak.
    pub fn memory_line(&self) -> String {
        use reports::format::bytes;
        let scene = self.scene.memory_bytes() as u64;
        let structure = self.accelerator_bytes as u64;
        let frame = self.rendered.frame.memory_bytes() as u64;
        let process = analysis::profile::sampler::process_peak_resident_bytes()
            .map(|b| format!("; process peak resident {}", bytes(b)))
            .unwrap_or_default();
        format!(
            "memory: scene {} + structure {} + framebuffer {} = {}{process}",
            bytes(scene),
            bytes(structure),
            bytes(frame),
            bytes(scene + structure + frame)
        )
    }
}
