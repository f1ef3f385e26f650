//! Command-line definition and dispatch. The commands, flags and JSON keys are a stable
//! contract (README.md lists them): tests and users depend on them.

mod compare;
mod count;
mod gate;
mod hw;
mod merge;
mod profile;
mod record;
mod render;
mod report;
mod scaling;
mod scene;
mod scene_args;
mod serve;
mod suite;
mod variants;

use clap::{Parser, Subcommand};
pub use reports::table_format::{Exports, Format};
pub use terminal::exit::Outcome;

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
    Profile(runner::profile_settings::ProfileSettings),
    /// Sample any program (your own tracer) under Linux perf: the same profile files.
    Record(runner::record::RecordSettings),
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

/// Runs one command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Count(args) => count::run(&args),
        Command::Profile(args) => profile::run(&args),
        Command::Record(args) => record::run(&args),
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
