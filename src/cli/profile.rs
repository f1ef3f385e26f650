//! `rtprof profile`: samples a render and writes the evidence of the thesis's table 6
//! and call tree in gprof's own format, plus what gprof cannot give: folded stacks,
//! a flamegraph, a differential flamegraph against another variant, and Amdahl
//! projections. Calls come from a counted render of the same scene and variant.

use super::scene_args::{LimitArgs, parse_size, thread_pool};
use analysis::profile::amdahl::{AmdahlRow, amdahl_table, amdahl_text};
use analysis::profile::folded::{differential_svg, flamegraph_svg, folded};
use analysis::profile::gprof::{CallGraph, FlatProfile, call_graph, flat_profile};
use analysis::profile::names::{BareMethods, display_name};
use analysis::profile::sampler::sample;
use analysis::profile::{CallCounts, Stack, StackSamples};
use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tracer::image_io::write_atomically;
use tracer::{
    Count, NoCount, RenderOptions, Sampling, Scene, ShadingMode, VariantSet, render_variant,
};

#[derive(clap::Args, Debug)]
pub struct ProfileArgs {
    /// NFF scene file.
    scene: PathBuf,
    /// Variant to profile (combine with ',' or '+').
    #[arg(long, default_value = "baseline", value_name = "V")]
    variant: String,
    /// Also profile this variant and draw a differential flamegraph against it.
    #[arg(long, value_name = "V")]
    diff_with: Option<String>,
    /// Image size WxH (default: the scene's resolution).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// SPD procedure: rays through pixel corners.
    #[arg(long)]
    spd: bool,
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    threads: Option<u16>,
    #[command(flatten)]
    limits: LimitArgs,
    /// Sampling rate asked of the kernel, Hz (it may deliver fewer; times use the
    /// measured CPU time per sample).
    #[arg(long, default_value_t = 1000, value_name = "HZ",
          value_parser = clap::value_parser!(i32).range(10..=10_000))]
    frequency: i32,
    /// Also time the same render without the profiler and report the overhead.
    #[arg(long)]
    measure_overhead: bool,
    /// Output directory for flat.txt, callgraph.txt, folded.txt, flame.svg, amdahl.txt.
    #[arg(short, long, value_name = "DIR")]
    output: Option<PathBuf>,
    /// Print everything as JSON on stdout.
    #[arg(long)]
    json: bool,
}

/// One variant's profile, as data.
#[derive(Serialize)]
pub(super) struct VariantProfile {
    pub(super) variant: String,
    /// Renders sampled (a fast render is repeated to gather samples); calls cover all.
    pub(super) renders: u64,
    pub(super) samples: u64,
    pub(super) seconds_per_sample: f64,
    cpu_seconds: f64,
    wall_seconds: f64,
    pub(super) flat: FlatProfile,
    call_graph: CallGraph,
    pub(super) amdahl: Vec<AmdahlRow>,
    pub(super) folded: String,
    #[serde(skip)]
    pub(super) flat_text: String,
    #[serde(skip)]
    pub(super) call_graph_text: String,
}

#[derive(Serialize)]
struct ProfileReport {
    scene: String,
    width: u32,
    height: u32,
    threads: usize,
    frequency: i32,
    /// Wall time of the same render without the profiler (with --measure-overhead).
    unprofiled_seconds: Option<f64>,
    /// Profiled / unprofiled wall time.
    overhead: Option<f64>,
    profile: VariantProfile,
    diff: Option<VariantProfile>,
}

/// Least sampled time per profile of `rtprof profile`: below it a render is repeated.
pub(super) const MIN_SAMPLED: std::time::Duration = std::time::Duration::from_millis(300);
/// Most renders per profile, however fast.
const MAX_RENDERS: u64 = 10_000;

pub(super) struct Job<'a> {
    pub(super) scene: &'a Scene,
    pub(super) options: RenderOptions,
    pub(super) pool: rayon::ThreadPool,
    pub(super) frequency: i32,
    pub(super) path: &'a Path,
    /// Least sampled time: a faster render is repeated until it is reached.
    pub(super) min_sampled: std::time::Duration,
}

impl Job<'_> {
    fn spinner(&self, message: String) -> ProgressBar {
        let bar = ProgressBar::new_spinner();
        bar.set_style(
            ProgressStyle::with_template("{spinner} {msg} {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        bar.set_message(message);
        bar.enable_steady_tick(std::time::Duration::from_millis(120));
        bar
    }

    fn fail(&self, e: tracer::RenderError) -> anyhow::Error {
        anyhow::anyhow!("{}: {e}", self.path.display())
    }

    /// Counted render (calls), then the sampled render.
    pub(super) fn profile(&self, list: &str) -> Result<VariantProfile> {
        let set = VariantSet::parse(list)?;
        let bar = self.spinner(format!("counting {set}"));
        let counted = self
            .pool
            .install(|| render_variant::<Count>(self.scene, &self.options, &set, &|_| {}))
            .map_err(|e| self.fail(e))?;
        let counts = counted
            .rendered
            .counts()
            .context("the counted render returned no counts")?;
        bar.set_message(format!("sampling {set}"));
        // A fast render (a BVH on a small image) can finish between two samples: render
        // again until the sampler has had `min_sampled` time, and scale the calls to match.
        let run = sample(
            self.frequency,
            |name| name.starts_with("tracer::"),
            || {
                let start = Instant::now();
                let mut renders = 0u64;
                loop {
                    renders += 1;
                    let out = self.pool.install(|| {
                        render_variant::<NoCount>(self.scene, &self.options, &set, &|_| {})
                    });
                    if out.is_err() || start.elapsed() >= self.min_sampled || renders >= MAX_RENDERS
                    {
                        return out.map(|_| renders);
                    }
                }
            },
        )?;
        bar.finish_and_clear();
        let renders = run.output.map_err(|e| self.fail(e))?;
        if renders > 1 {
            eprintln!(
                "{set}: rendered {renders} times to gather samples (calls are for all {renders})"
            );
        }
        let samples = shorten(&run.samples);
        let calls: CallCounts = counts
            .function_calls()
            .into_iter()
            .map(|(name, n)| (name.to_string(), n * renders))
            .collect();
        Ok(build_profile(
            set.to_string(),
            renders,
            &samples,
            &calls,
            run.cpu.as_secs_f64(),
            run.wall.as_secs_f64(),
        ))
    }

    fn unprofiled_seconds(&self, list: &str) -> Result<f64> {
        let set = VariantSet::parse(list)?;
        let bar = self.spinner(format!("timing {set} without the profiler"));
        let start = Instant::now();
        self.pool
            .install(|| render_variant::<NoCount>(self.scene, &self.options, &set, &|_| {}))
            .map_err(|e| self.fail(e))?;
        bar.finish_and_clear();
        Ok(start.elapsed().as_secs_f64())
    }
}

/// Stacks with the reports' short names; stacks that become equal merge.
fn shorten(samples: &StackSamples) -> StackSamples {
    let operations = tracer::counter::counted_operations();
    let bare = BareMethods {
        owners: &tracer::counter::COUNTING_LAYER,
        methods: &operations,
    };
    let mut merged: BTreeMap<Vec<String>, u64> = BTreeMap::new();
    for stack in &samples.stacks {
        let mut frames: Vec<String> = stack
            .frames
            .iter()
            .map(|f| display_name(f, &bare))
            .collect();
        frames.dedup();
        *merged.entry(frames).or_default() += stack.count;
    }
    StackSamples {
        stacks: merged
            .into_iter()
            .map(|(frames, count)| Stack { frames, count })
            .collect(),
        seconds_per_sample: samples.seconds_per_sample,
    }
}

fn build_profile(
    variant: String,
    renders: u64,
    samples: &StackSamples,
    calls: &CallCounts,
    cpu_seconds: f64,
    wall_seconds: f64,
) -> VariantProfile {
    // Counts for functions this run never entered (another accelerator's queries) would
    // list them with zero time; keep the counts of the functions the samples saw.
    let seen: std::collections::BTreeSet<&String> = samples
        .stacks
        .iter()
        .flat_map(|s| s.frames.iter())
        .collect();
    let calls: CallCounts = calls
        .iter()
        .filter(|(name, _)| seen.contains(name))
        .map(|(name, n)| (name.clone(), *n))
        .collect();
    let flat = flat_profile(samples, &calls);
    let graph = call_graph(samples, &calls);
    let self_times: Vec<(String, f64)> = flat
        .rows
        .iter()
        .map(|r| (r.name.clone(), r.self_seconds))
        .collect();
    VariantProfile {
        variant,
        renders,
        samples: samples.total(),
        seconds_per_sample: samples.seconds_per_sample,
        cpu_seconds,
        wall_seconds,
        flat_text: flat.to_text(),
        call_graph_text: graph.to_text(),
        amdahl: amdahl_table(&self_times, 10),
        folded: folded(samples),
        flat,
        call_graph: graph,
    }
}

fn write(dir: &Path, name: &str, text: &str) -> Result<()> {
    let path = dir.join(name);
    write_atomically(&path, text.as_bytes())
        .with_context(|| format!("cannot write {}", path.display()))
}

pub fn run(args: &ProfileArgs) -> Result<()> {
    // Check both variant lists before any work.
    VariantSet::parse(&args.variant)?;
    if let Some(other) = &args.diff_with {
        VariantSet::parse(other)?;
    }
    let scene = args.limits.load(&args.scene)?;
    let (width, height) = args.size.unwrap_or((scene.view.width, scene.view.height));
    let sampling = if args.spd {
        Sampling::SpdCorners
    } else {
        Sampling::PixelCenters
    };
    let dir = match &args.output {
        Some(dir) => dir.clone(),
        None => {
            let Some(stem) = args.scene.file_stem() else {
                bail!(
                    "cannot name the output directory after {}: pass -o DIR",
                    args.scene.display()
                );
            };
            PathBuf::from(format!("profile-{}", stem.to_string_lossy()))
        }
    };
    std::fs::create_dir_all(&dir)
        .with_context(|| format!("cannot create directory {}", dir.display()))?;
    let job = Job {
        scene: &scene,
        options: RenderOptions {
            limits: args.limits.limits(),
            ..RenderOptions::new(width, height, sampling, ShadingMode::Color)
        },
        pool: thread_pool(args.threads)?,
        frequency: args.frequency,
        path: &args.scene,
        min_sampled: MIN_SAMPLED,
    };

    let unprofiled = if args.measure_overhead {
        Some(job.unprofiled_seconds(&args.variant)?)
    } else {
        None
    };
    let profile = job.profile(&args.variant)?;
    let diff = match &args.diff_with {
        Some(other) => Some(job.profile(other)?),
        None => None,
    };

    let title = format!(
        "{} ({}x{}, {})",
        args.scene.display(),
        width,
        height,
        profile.variant
    );
    write(&dir, "flat.txt", &profile.flat_text)?;
    write(&dir, "callgraph.txt", &profile.call_graph_text)?;
    write(&dir, "folded.txt", &profile.folded)?;
    write(&dir, "flame.svg", &flamegraph_svg(&profile.folded, &title)?)?;
    write(&dir, "amdahl.txt", &amdahl_text(&profile.amdahl))?;
    if let Some(d) = &diff {
        write(&dir, &format!("folded-{}.txt", d.variant), &d.folded)?;
        write(&dir, &format!("flat-{}.txt", d.variant), &d.flat_text)?;
        let diff_title = format!(
            "{}: {} → {} (red grew, blue shrank)",
            args.scene.display(),
            profile.variant,
            d.variant
        );
        write(
            &dir,
            "flame-diff.svg",
            &differential_svg(&profile.folded, &d.folded, &diff_title)?,
        )?;
    }

    let report = ProfileReport {
        scene: args.scene.display().to_string(),
        width,
        height,
        threads: job.pool.current_num_threads(),
        frequency: args.frequency,
        unprofiled_seconds: unprofiled,
        overhead: unprofiled.map(|u| profile.wall_seconds / u.max(1e-9)),
        profile,
        diff,
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_summary(&report, &dir);
    }
    Ok(())
}

fn print_summary(r: &ProfileReport, dir: &Path) {
    let p = &r.profile;
    println!(
        "{} {}x{}, variant {}, {} thread{}: {} samples, {:.3} s CPU, {:.3} s wall ({:.2} ms of CPU per sample)",
        r.scene,
        r.width,
        r.height,
        p.variant,
        r.threads,
        if r.threads == 1 { "" } else { "s" },
        p.samples,
        p.cpu_seconds,
        p.wall_seconds,
        p.seconds_per_sample * 1e3
    );
    if let (Some(u), Some(o)) = (r.unprofiled_seconds, r.overhead) {
        println!("without the profiler: {u:.3} s wall; overhead {o:.3}x");
    }
    println!();
    for line in p.flat_text.lines().take(18) {
        println!("{line}");
    }
    println!();
    print!("{}", amdahl_text(&p.amdahl));
    println!(
        "\nwrote {}/{{flat.txt, callgraph.txt, folded.txt, flame.svg, amdahl.txt{}}}",
        dir.display(),
        if r.diff.is_some() {
            ", flame-diff.svg"
        } else {
            ""
        }
    );
}
