//! `rtprof`: profiles a Whitted ray tracer and finds its bottlenecks.
//!
//! The command line lives in `cli/`, one file per command; the work itself lives in the
//! workspace crates (`tracer` for rendering and counting).

mod cli;

use clap::{CommandFactory, FromArgMatches};
use std::process::ExitCode;

/// The long help (--help) of the commands that draw progress bars.
const PROGRESS_HELP: &str = "Progress bars draw on stderr when it is a terminal (a render \
    only once it has run a second). RTPROF_PROGRESS=always draws them anyway, as plain \
    lines in a pipe or log (CI); RTPROF_PROGRESS=never turns them off; auto is the default.";

fn main() -> ExitCode {
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
    let Err(error) = cli::run(args) else {
        return ExitCode::SUCCESS;
    };
    let message = name_the_flag(&one_line(&format!("{error:#}")));
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
    let message = clap_message(&text);
    let usage = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("Usage: "))
        .map(|u| format!(" (usage: {u}; see --help)"))
        .unwrap_or_else(|| " (see rtprof --help)".to_string());
    eprintln!("rtprof: error: {message}{usage}");
    ExitCode::from(2)
}

/// Clap's message (everything before its usage) on one line: the items it lists on
/// lines of their own follow the line's colon, and its tips follow after "; ".
fn clap_message(text: &str) -> String {
    let mut message = String::new();
    let lines = text.lines().take_while(|l| !l.starts_with("Usage:"));
    for line in lines.map(str::trim).filter(|l| !l.is_empty()) {
        let separator = if message.is_empty() {
            ""
        } else if message.ends_with(':') {
            " "
        } else if line.starts_with("tip:") {
            "; "
        } else {
            ", "
        };
        message.push_str(separator);
        message.push_str(line.trim_start_matches("error: "));
    }
    if message.is_empty() {
        message.push_str("invalid command line");
    }
    message
}

/// A limit error names the flag that raises it, not the library's field: the tracer
/// says "(limit max_side: raise it with rtprof's --max-side or tracer::Limits::max_side)".
fn name_the_flag(message: &str) -> String {
    let Some(start) = message.find("(limit ") else {
        return message.to_string();
    };
    let Some(end) = message[start..].find(')').map(|e| start + e) else {
        return message.to_string();
    };
    match message[start..end]
        .split_once("rtprof's ")
        .and_then(|(_, rest)| rest.split_once(" or tracer::Limits::"))
    {
        Some((flag, _)) => format!(
            "{}(raise it with {flag}){}",
            &message[..start],
            &message[end + 1..]
        ),
        None => message.to_string(),
    }
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
