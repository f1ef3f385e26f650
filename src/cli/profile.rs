//! `rtprof profile`: samples a render and writes the evidence of the thesis's table 6
//! and call tree in gprof's own format, plus what gprof cannot give: folded stacks,
//! a flamegraph, a differential flamegraph against another variant, and Amdahl
//! projections. Calls come from a counted render of the same scene and variant.

use anyhow::{Context, Result};
use runner::pool::thread_pool;
use runner::profile_job::{DEFAULT_MIN_SAMPLES, ProfileJob};
use runner::render_job::{RenderSettings, ShadingFlags};
use runner::scene_input::SceneInput;
use std::path::PathBuf;
use terminal::progress::Bars;
use tracer::VariantSet;

#[derive(clap::Args, Debug)]
pub struct ProfileArgs {
    #[arg(value_name = "SCENE", value_parser = SceneInput::parse_arg, help = SceneInput::HELP)]
    scene: SceneInput,
    /// Variant to profile (combine with ',' or '+').
    #[arg(long, default_value = "baseline", value_name = "V")]
    variant: String,
    /// Also profile this variant and draw a differential flamegraph against it.
    #[arg(long, value_name = "V")]
    diff_with: Option<String>,
    #[command(flatten)]
    render: RenderSettings,
    #[command(flatten)]
    shading: ShadingFlags,
    /// Sampling rate asked of the timer, Hz of CPU time [default: 4000 with the perf
    /// cpu-clock timer, 1000 with setitimer, which delivers at most the kernel's tick
    /// rate; times use the measured CPU time per sample]. RTPROF_SAMPLER=auto|perf|setitimer
    /// picks the timer (auto: perf where perf_event_open works).
    #[arg(long, value_name = "HZ",
          value_parser = clap::value_parser!(i32).range(10..=10_000))]
    frequency: Option<i32>,
    /// Samples to gather at least: a fast render is repeated until there are (calls
    /// stay per render).
    #[arg(long, default_value_t = DEFAULT_MIN_SAMPLES, value_name = "N",
          value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    min_samples: u64,
    /// Also time the render without the profiler (repeated) and report the overhead.
    #[arg(long)]
    measure_overhead: bool,
    /// Output directory [default: profile-<scene>]: flat-<variant>.txt,
    /// callgraph-<variant>.txt, flame-<variant>.svg (phase view; -native for native
    /// symbols), amdahl-<variant>.txt, profile-<variant>.pb.gz, speedscope-<variant>.json.
    #[arg(short, long, value_name = "DIR")]
    output: Option<PathBuf>,
    /// Print everything as JSON on stdout.
    #[arg(long)]
    json: bool,
}

pub fn run(args: &ProfileArgs) -> Result<()> {
    // Check both variant lists before any work.
    let set = VariantSet::parse(&args.variant)?;
    let other = args
        .diff_with
        .as_deref()
        .map(VariantSet::parse)
        .transpose()?;
    let scene = args.scene.load(&args.render.limits)?;
    let options = args.render.options(&scene, args.shading.mode());
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| args.scene.named_after("profile-", ""));
    std::fs::create_dir_all(&dir)
        .with_context(|| format!("cannot create directory {}", dir.display()))?;
    let pool = thread_pool(args.render.threads)?;
    let name = args.scene.to_string();
    let job = ProfileJob {
        scene: &scene,
        options,
        pool: &pool,
        frequency: args.frequency,
        name: &name,
        min_samples: args.min_samples,
        stop: terminal::interrupt::install(),
    };

    let progress = Bars::delayed();
    runner::estimate::note_if_slow(&scene, &options, &set, args.render.threads, &progress)?;
    let report = job.report(&set, other.as_ref(), args.measure_overhead, &progress)?;
    let saved = report.save(&dir, "")?;
    if args.json {
        let mut json = serde_json::to_value(&report)?;
        json["files"] = serde_json::to_value(&saved)?;
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        print!("{}", report.to_text(&dir, &saved));
    }
    Ok(())
}
