//! `rtprof`: profiles a Whitted ray tracer and finds its bottlenecks.
//!
//! The command line lives in `cli/`, one file per command; the work itself lives in the
//! workspace crates (`tracer` for rendering and counting).

mod cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) if error.downcast_ref::<cli::CheckFailed>().is_some() => {
            eprintln!("rtprof: {error:#}");
            ExitCode::from(1)
        }
        Err(error) => {
            eprintln!("rtprof: error: {error:#}");
            // Bad input or usage: exit code 2 (1 is kept for failed checks).
            ExitCode::from(2)
        }
    }
}
