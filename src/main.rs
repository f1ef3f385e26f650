//! `rtprof`: profiles a Whitted ray tracer and finds its bottlenecks.
//!
//! The command line lives in `cli/`, one file per command; the work itself lives in the
//! workspace crates (`tracer` for rendering and counting).

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

mod cli;

use clap::{CommandFactory, FromArgMatches};
use std::process::ExitCode;

fn main() -> ExitCode {
    terminal::startup::start();
    let code = run();
    terminal::startup::finish();
    code
}

fn run() -> ExitCode {
    terminal::exit::quiet_on_broken_pipe();
    let mut command = cli::Cli::command();
    for name in ["suite", "render", "count", "profile", "compare"] {
        command = command.mut_subcommand(name, |c| c.after_long_help(terminal::progress::HELP));
    }
    let parsed = command.try_get_matches();
    let args = match parsed.and_then(|m| cli::Cli::from_arg_matches(&m)) {
        Ok(args) => args,
        Err(error) => return ExitCode::from(terminal::exit::usage_error(&error)),
    };
    terminal::startup::mark("args");
    let Err(error) = cli::run(args) else {
        return ExitCode::SUCCESS;
    };
    ExitCode::from(terminal::exit::report(error.as_ref()))
}
