//! `rtprof`: profiles a Whitted ray tracer and finds its bottlenecks.
//!
//! The command line lives in `cli/`, one file per command; the work itself lives in the
//! workspace crates (`tracer` for rendering and counting).

mod cli;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    // Output piped into `head` ends quietly, as other Unix tools do, not with a panic.
    // SAFETY: restoring the default action of SIGPIPE before any thread starts.
    unsafe { libc::signal(libc::SIGPIPE, libc::SIG_DFL) };
    let args = match cli::Cli::try_parse() {
        Ok(args) => args,
        Err(error) => return usage_error(&error),
    };
    let Err(error) = cli::run(args) else {
        return ExitCode::SUCCESS;
    };
    let message = one_line(&format!("{error:#}"));
    match error.downcast_ref::<cli::Outcome>() {
        Some(outcome) => {
            eprintln!("rtprof: {message}");
            ExitCode::from(outcome.exit_code)
        }
        None => {
            eprintln!("rtprof: error: {message}");
            // Bad input or usage: exit code 2 (1 is kept for failed checks).
            ExitCode::from(2)
        }
    }
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
    let text = error.render().to_string();
    let message = text
        .lines()
        .next()
        .unwrap_or("invalid command line")
        .trim_start_matches("error: ");
    let usage = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("Usage: "))
        .map(|u| format!(" (usage: {u}; see --help)"))
        .unwrap_or_else(|| " (see rtprof --help)".to_string());
    eprintln!("rtprof: error: {message}{usage}");
    ExitCode::from(2)
}

/// An error message on one line: any line breaks of a nested message become "; ".
fn one_line(message: &str) -> String {
    message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}
