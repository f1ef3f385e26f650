//! `rtprof profile`'s flags, declared with the profile job they set (behind the `clap`
//! feature): the scene, variants, render settings, sampling rate and minimum, output.

use std::path::PathBuf;

use crate::profile_job::DEFAULT_MIN_SAMPLES;
use crate::render_job::{RenderSettings, ShadingFlags};
use crate::scene_input::SceneInput;

// What `rtprof profile` samples, how, and where its files go. (A plain comment: a doc
// comment here would replace the command's help line.)
#[derive(clap::Args, Debug)]
pub struct ProfileSettings {
    #[arg(value_name = "SCENE", value_parser = SceneInput::parse_arg, help = SceneInput::HELP)]
    pub scene: SceneInput,
    /// Variant to profile (combine with ',' or '+').
    #[arg(long, default_value = "baseline", value_name = "V")]
    pub variant: String,
    /// Also profile this variant and draw a differential flamegraph against it.
    #[arg(long, value_name = "V")]
    pub diff_with: Option<String>,
    #[command(flatten)]
    pub render: RenderSettings,
    #[command(flatten)]
    pub shading: ShadingFlags,
    /// Sampling rate asked of the timer, Hz of CPU time [default: 4000 with the perf
    /// cpu-clock timer, 1000 with setitimer, which delivers at most the kernel's tick
    /// rate; times use the measured CPU time per sample]. RTPROF_SAMPLER=auto|perf|setitimer
    /// picks the timer (auto: perf where perf_event_open works).
    #[arg(long, value_name = "HZ",
          value_parser = clap::value_parser!(i32).range(10..=10_000))]
    pub frequency: Option<i32>,
    /// Samples to gather at least: a fast render is repeated until there are (calls
    /// stay per render).
    #[arg(long, default_value_t = DEFAULT_MIN_SAMPLES, value_name = "N",
          value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    pub min_samples: u64,
    /// Also time the render without the profiler (repeated) and report the overhead.
    #[arg(long)]
    pub measure_overhead: bool,
    // The angle brackets are for `--help` (clap reads this doc), not HTML.
    #[allow(rustdoc::invalid_html_tags)]
    /// Output directory [default: profile-<scene>]: flat-<variant>.txt,
    /// callgraph-<variant>.txt, flame-<variant>.svg (phase view; -native for native
    /// symbols), amdahl-<variant>.txt, profile-<variant>.pb.gz, speedscope-<variant>.json.
    #[arg(short, long, value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// Print everything as JSON on stdout.
    #[arg(long)]
    pub json: bool,
}
