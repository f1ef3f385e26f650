//! `rtprof profile`: samples a render and writes the evidence of the thesis's table 6
//! and call tree in gprof's own format, plus what gprof cannot give: folded stacks,
//! a flamegraph, a differential flamegraph against another variant, and Amdahl
//! projections. Calls come from a counted render of the same scene and variant.

use super::progress::Bars;
use super::scene_args::{LimitArgs, parse_size};
use anyhow::{Context, Result, bail};
use runner::pool::thread_pool;
use runner::profile_job::{MIN_SAMPLED, ProfileJob, ProfileReport};
use std::path::PathBuf;
use tracer::{RenderOptions, Sampling, ShadingMode, VariantSet};

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

pub fn run(args: &ProfileArgs) -> Result<()> {
    // Check both variant lists before any work.
    let set = VariantSet::parse(&args.variant)?;
    let other = args
        .diff_with
        .as_deref()
        .map(VariantSet::parse)
        .transpose()?;
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
    let pool = thread_pool(args.threads)?;
    let name = args.scene.display().to_string();
    let job = ProfileJob {
        scene: &scene,
        options: RenderOptions {
            limits: args.limits.limits(),
            ..RenderOptions::new(width, height, sampling, ShadingMode::Color)
        },
        pool: &pool,
        frequency: args.frequency,
        name: &name,
        min_sampled: MIN_SAMPLED,
    };

    let progress = Bars::default();
    runner::Progress::begin(&progress, "profile", 0);
    let unprofiled = if args.measure_overhead {
        runner::Progress::message(&progress, &format!("timing {set} without the profiler"));
        Some(job.unprofiled_seconds(&set)?)
    } else {
        None
    };
    let profile = job.profile(&set, &progress)?;
    let diff = match &other {
        Some(other) => Some(job.profile(other, &progress)?),
        None => None,
    };
    runner::Progress::end(&progress);

    let report = ProfileReport {
        scene: args.scene.display().to_string(),
        width,
        height,
        threads: pool.current_num_threads(),
        frequency: args.frequency,
        unprofiled_seconds: unprofiled,
        overhead: unprofiled.map(|u| profile.wall_seconds / u.max(1e-9)),
        profile,
        diff,
    };
    report.write_files(&dir)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", report.to_text(&dir));
    }
    Ok(())
}
