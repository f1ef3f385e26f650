//! Command-line definition and dispatch (the stable contract of docs/design.md).

mod count;
mod render;
mod scene_args;

use clap::{Parser, Subcommand};

/// Profiles a Whitted ray tracer on NFF scenes and finds its bottlenecks.
#[derive(Parser, Debug)]
#[command(name = "rtprof", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render an NFF scene to PNG or PPM (uncounted, full speed).
    Render(render::RenderArgs),
    /// Render an NFF scene counting every operation, test and ray.
    Count(count::CountArgs),
}

/// Runs one command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Count(args) => count::run(&args),
    }
}
