//! How a command ends: success, a failed check (1), bad input (2), parts failed (3), a
//! recorded program that failed (4) or an interrupt (130), and the one line it prints on stderr. Commands return
//! [`Outcome`] for the ends that are not bad input; [`report`] turns any error into its
//! line and exit code.

use std::error::Error;

/// An end that is neither success nor bad input (exit 2), with its exit code.
#[derive(Debug)]
pub struct Outcome {
    pub exit_code: u8,
    pub message: String,
}

impl Outcome {
    /// A check that ran and failed (the regression gate).
    pub const CHECK_FAILED: u8 = 1;
    /// The program `rtprof record` ran failed (non-zero exit, killed by a signal, timed
    /// out); its profile was written.
    pub const COMMAND_FAILED: u8 = 4;
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

/// Prints `error` on stderr as one line and returns the exit code: an [`Outcome`]'s
/// own, 130 for a render stopped by Ctrl-C, 2 (bad input or usage) for anything else
/// (1 is kept for failed checks). The line joins the error's causes with ": " and
/// names the flag that raises a limit.
pub fn report(error: &(dyn Error + 'static)) -> u8 {
    let message = causes(error)
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(": ");
    let mut message = runner::messages::one_line(&message);
    if let Some(limit) = limit_of(error) {
        message = runner::messages::raise_with(&message, limit, &flag_of(limit));
    }
    if causes(error).any(|e| matches!(e.downcast_ref(), Some(runner::RunError::Stopped))) {
        // Ctrl-C during a render: it stopped within a row, and wrote nothing.
        eprintln!("rtprof: interrupted: the render was cancelled; no output was written");
        return Outcome::INTERRUPTED;
    }
    match error.downcast_ref::<Outcome>() {
        Some(outcome) => {
            eprintln!("rtprof: {message}");
            outcome.exit_code
        }
        None => {
            eprintln!("rtprof: error: {message}");
            2
        }
    }
}

/// Output piped into `head` ends quietly, as other Unix tools do, not with a panic:
/// restores the default action of SIGPIPE. Call it first, before any thread starts.
pub fn quiet_on_broken_pipe() {
    // SAFETY: setting a signal's action to its default while only this thread runs.
    unsafe { libc::signal(libc::SIGPIPE, libc::SIG_DFL) };
}

/// Prints a command-line parse error and returns its exit code. Help and version go to
/// stdout as clap prints them (exit 0); a usage mistake is one line on stderr with the
/// command's usage and a pointer to --help (exit 2), so that a script's log shows what
/// was wrong without clap's multi-line layout.
pub fn usage_error(error: &clap::Error) -> u8 {
    use clap::error::ErrorKind;
    if matches!(
        error.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        // Printing help cannot fail in a way worth reporting.
        let _ = error.print();
        return if error.use_stderr() { 2 } else { 0 };
    }
    let message = runner::messages::usage_error(&error.render().to_string());
    eprintln!("rtprof: error: {message}");
    2
}

/// The limit `error` or one of its causes exceeded, from the typed errors that carry
/// one.
fn limit_of(error: &(dyn Error + 'static)) -> Option<tracer::Limit> {
    causes(error).find_map(|e| {
        let run = e
            .downcast_ref::<runner::RunError>()
            .and_then(runner::RunError::limit);
        run.or_else(|| e.downcast_ref::<tracer::LoadError>()?.limit())
            .or_else(|| e.downcast_ref::<tracer::NffError>()?.limit)
            .or_else(|| e.downcast_ref::<tracer::RenderError>()?.limit())
            .or_else(|| e.downcast_ref::<tracer::LimitError>()?.limit)
    })
}

/// The flag that raises `limit`: the one `tracer::Limits` declares for its field.
fn flag_of(limit: tracer::Limit) -> String {
    use clap::Args;
    let flags = tracer::Limits::augment_args(clap::Command::new("limits"));
    let long = flags
        .get_arguments()
        .find(|a| a.get_id() == limit.field())
        .and_then(clap::Arg::get_long);
    long.map_or_else(
        || format!("tracer::Limits::{}", limit.field()),
        |long| format!("--{long}"),
    )
}

/// The error and its sources, outermost first.
fn causes<'a>(error: &'a (dyn Error + 'static)) -> impl Iterator<Item = &'a (dyn Error + 'static)> {
    std::iter::successors(Some(error), |&e| e.source())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_limit_is_raised_by_its_own_flag() {
        let flags: Vec<String> = tracer::Limit::ALL.into_iter().map(flag_of).collect();
        assert_eq!(
            flags,
            [
                "--max-side",
                "--max-pixels",
                "--max-framebuffer-bytes",
                "--max-polygon-vertices",
                "--max-primitives",
                "--max-ray-depth",
                "--max-file-bytes"
            ]
        );
    }

    #[test]
    fn a_limit_is_found_through_the_error_chain() {
        let limits = tracer::Limits {
            max_ray_depth: 3,
            ..tracer::Limits::default()
        };
        let refused = limits.check_ray_depth(9).unwrap_err();
        let run = runner::RunError::refused("scene.nff", &refused);
        assert_eq!(limit_of(&run), Some(tracer::Limit::MaxRayDepth));
        let parse = tracer::nff::parse_nff_with_limits("v\nfrom 0 0 0\n", "a.nff", &limits);
        assert_eq!(parse.err().and_then(|e| e.limit), None);
        assert_eq!(limit_of(&runner::RunError::Input("x".into())), None);
    }
}
