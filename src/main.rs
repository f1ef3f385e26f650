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

/// The long help (--help) of the commands that draw progress bars.
const PROGRESS_HELP: &str = "Progress bars draw on stderr when it is a terminal (a render \
    only once it has run a second). RTPROF_PROGRESS=always draws them anyway, as plain \
    lines in a pipe or log (CI); RTPROF_PROGRESS=never turns them off; auto is the default.";

fn main() -> ExitCode {
    terminal::startup::start();
    let code = run();
    terminal::startup::finish();
    code
}

fn run() -> ExitCode {
    // Output piped into `head` ends quietly, as other Unix tools do, not with a panic.
    // SAFETY: restoring the default action of SIGPIPE before any thread starts.
    unsafe { libc::signal(libc::SIGPIPE, libc::SIG_DFL) };
    let mut command = cli::Cli::command();
    for name in ["suite", "render", "count", "profile", "compare"] {
        command = command.mut_subcommand(name, |c| c.after_long_help(PROGRESS_HELP));
    }
    let parsed = command.try_get_matches();
    let args = match parsed.and_then(|m| cli::Cli::from_arg_matches(&m)) {
        Ok(args) => args,
        Err(error) => return usage_error(&error),
    };
    terminal::startup::mark("args");
    let Err(error) = cli::run(args) else {
        return ExitCode::SUCCESS;
    };
    ExitCode::from(terminal::exit::report(error.as_ref()))
}

/// Help and version go to stdout as clap prints them (exit 0); a usage mistake is one
/// line on stderr with the command's usage and a pointer to --help (exit 2), so that a
/// script's log shows what was wrong without clap's multi-line layout.
fn usage_error(error: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(
        error.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        // Printing help cannot fail in a way worth reporting.
        let _ = error.print();
        let code = if error.use_stderr() { 2 } else { 0 };
        return ExitCode::from(code);
    }
    let message = runner::messages::usage_error(&error.render().to_string());
    eprintln!("rtprof: error: {message}");
    ExitCode::from(2)
}
