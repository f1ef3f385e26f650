//! Command-line definition and dispatch. The commands, flags and JSON keys are a stable
//! contract (README.md lists them): tests and users depend on them.

mod compare;
mod count;
mod gate;
mod hw;
mod hw_rtl;
mod merge;
mod profile;
mod render;
mod report;
mod scaling;
mod scene;
mod scene_args;
mod serve;
mod suite;
mod variants;

use clap::{Parser, Subcommand};

/// Profiles a Whitted ray tracer on NFF scenes and finds its bottlenecks.
#[derive(Parser, Debug)]
#[command(name = "rtprof", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
// Each subcommand's arguments are built only when it runs (clap's `defer`): a start
// builds one command's, not all of them.
#[command(defer = true)]
enum Command {
    /// Render an NFF scene to PNG or PPM (uncounted, full speed).
    Render(render::RenderArgs),
    /// Render an NFF scene counting every operation, test and ray.
    Count(count::CountArgs),
    /// Sample a render: gprof flat profile and call graph, flamegraphs, Amdahl table.
    Profile(profile::ProfileArgs),
    /// Compare two images, or run variants of one scene side by side.
    Compare(compare::CompareArgs),
    /// List the optimization variants and the measured accuracy of the approximate ones.
    Variants(variants::VariantsArgs),
    /// The FPGA pipeline model: tables 7 and 8, frame time and fit, emulator, MIF.
    Hw(hw::HwArgs),
    /// The main job: every scene × variant, hardware model, profile; results.json,
    /// report.html, report.pdf; --baseline gates against an earlier run.
    Suite(suite::SuiteArgs),
    /// Join the results of `suite --shard I/N` runs into one results.json and reports.
    Merge(merge::MergeArgs),
    /// Gate NEW.json against OLD.json: exit 1 on a significant slow-down or any
    /// changed count.
    Gate(gate::GateArgs),
    /// Rebuild report.html and report.pdf from results.json files (several: compared).
    Report(report::ReportArgs),
    /// Scenes by name: list them, write any of them as NFF (SPD databases at any size).
    Scene(scene::SceneArgs),
    /// Growth study: time, tests and nodes per ray of each accelerator against scene
    /// size, tens to a million primitives, with fitted exponents; scaling.json, .svg.
    Scaling(scaling::ScalingArgs),
    /// The local web app: pick a scene, run variants, view images, counts, flamegraphs,
    /// hardware and the gate, open the reports (http://127.0.0.1:8080/).
    Serve(serve::ServeArgs),
}

/// How a table is printed: aligned text for a terminal, GitHub-flavoured Markdown (a
/// pull-request comment, a CI job summary), CSV or JSON.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Format {
    #[default]
    Text,
    Markdown,
    Csv,
    Json,
}

/// An end that is neither success nor bad input (exit 2), with its exit code.
#[derive(Debug)]
pub struct Outcome {
    pub exit_code: u8,
    pub message: String,
}

impl Outcome {
    /// A check that ran and failed (the regression gate).
    pub const CHECK_FAILED: u8 = 1;
    /// Some parts of a suite failed; the rest was measured and written.
    pub const PARTS_FAILED: u8 = 3;
    /// Stopped by Ctrl-C: 128 + SIGINT, as a shell reports it.
    pub const INTERRUPTED: u8 = 130;

    pub fn new(exit_code: u8, message: impl Into<String>) -> Self {
        let message = message.into();
        Outcome { exit_code, message }
    }
}

impl std::fmt::Display for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Outcome {}

/// Runs one command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Count(args) => count::run(&args),
        Command::Profile(args) => profile::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::Variants(args) => variants::run(&args),
        Command::Hw(args) => hw::run(&args),
        Command::Suite(args) => suite::run(&args),
        Command::Merge(args) => merge::run(&args),
        Command::Gate(args) => gate::run(&args),
        Command::Report(args) => report::run(&args),
        Command::Scene(args) => scene::run(&args),
        Command::Scaling(args) => scaling::run(&args),
        Command::Serve(args) => serve::run(&args),
    }
}
