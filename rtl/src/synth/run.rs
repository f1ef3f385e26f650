//! Running a synthesis or place-and-route tool with a time limit.

use std::path::Path;
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use super::spawn_error;
use crate::RtlError;

/// Runs `program` with `args` in `dir` (output discarded: the tools write logs) and
/// waits at most `timeout`; a run that takes longer is stopped (it is our own child)
/// and reported as an error naming `what`. Returns the exit status and the seconds.
pub(super) fn run_limited(
    tool: &'static str,
    program: &str,
    args: &[&str],
    dir: &Path,
    timeout: Duration,
    what: &str,
) -> Result<(ExitStatus, f64), RtlError> {
    let start = Instant::now();
    let mut child = Command::new(program)
        .current_dir(dir)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|e| spawn_error(tool, &e))?;
    loop {
        if let Some(status) = child.try_wait().map_err(|e| spawn_error(tool, &e))? {
            return Ok((status, start.elapsed().as_secs_f64()));
        }
        if start.elapsed() > timeout {
            let _ = child.kill();
            let _ = child.wait();
            return Err(RtlError::Tool {
                tool,
                message: format!("{what} did not finish in {} s", timeout.as_secs()),
            });
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}
