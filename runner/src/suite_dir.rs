//! A prepared suite run into a directory: the one sequence of `rtprof suite` and of the
//! web app's jobs. The outputs are staged beside the directory's files
//! ([`crate::staging`]), the suite runs, results.json and the reports are written, and
//! only a finished run is published into the directory (one rename per file, the
//! previous run's files replaced). A run that fails or is stopped leaves the directory
//! as it was: its staged files are discarded, or kept under another name when the
//! caller asks (the web app's `partial/`).

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use results::Results;

use crate::report_files::{Pdf, write_run};
use crate::staging::Staging;
use crate::suite::{RunContext, Suite};
use crate::{Progress, RunError};
use reports::pdf::PageCount;

/// How a suite runs into its directory.
pub struct DirRun<'a> {
    /// Worker threads for the renders (default: one per core).
    pub threads: Option<u16>,
    pub progress: &'a dyn Progress,
    /// Set when the user asks the run to stop; checked before every render, after the
    /// last one and after the reports.
    pub stop: &'a AtomicBool,
    pub pdf: Pdf,
    /// Where a failed, stopped or panicking run's staged outputs are kept (without a
    /// results.json: only a finished run has one); `None` discards them.
    pub keep_partial: Option<&'a Path>,
}

/// A finished run, published.
pub struct RunWritten {
    pub results: Results,
    /// report.pdf's pages, when it was written.
    pub pages: Option<PageCount>,
}

/// Runs `suite` into `dir` (created if missing). `amend` changes the results before
/// they are written (the suite command adds the benchmark figures). A stop after the
/// last render or during the reports is [`RunError::Stopped`].
pub fn run_into_dir(
    suite: &Suite,
    dir: &Path,
    run: &DirRun<'_>,
    amend: &mut dyn FnMut(&mut Results) -> Result<(), RunError>,
) -> Result<RunWritten, RunError> {
    std::fs::create_dir_all(dir).map_err(|e| RunError::io("create", dir, &e))?;
    let staging = Staging::create(dir)?;
    let stopped = || match run.stop.load(Ordering::SeqCst) {
        true => Err(RunError::Stopped),
        false => Ok(()),
    };
    let mut stage = || -> Result<RunWritten, RunError> {
        let ctx = RunContext {
            out: staging.dir(),
            threads: run.threads,
            progress: run.progress,
            stop: run.stop,
            pdf: run.pdf,
        };
        let mut results = suite.run(&ctx)?;
        stopped()?;
        amend(&mut results)?;
        run.progress.begin("reports", 0);
        run.progress
            .message(&format!("writing results.json, {}", run.pdf.documents()));
        let pages = write_run(&results, staging.dir(), run.pdf);
        run.progress.end();
        let pages = pages?;
        stopped()?;
        Ok(RunWritten { results, pages })
    };
    let Some(partial) = run.keep_partial else {
        // Dropped on any error: the staged files go with it.
        let written = stage()?;
        staging.publish(dir)?;
        run.pdf.remove_stale(dir)?;
        return Ok(written);
    };
    // Outputs worth keeping are kept through a panic too (a server outlives its jobs).
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(stage))
        .unwrap_or(Err(RunError::Panicked));
    match outcome {
        Ok(written) => {
            staging.publish(dir)?;
            run.pdf.remove_stale(dir)?;
            Ok(written)
        }
        Err(error) => {
            // Never a results.json among partial outputs.
            let _ = std::fs::remove_file(staging.dir().join("results.json"));
            if let Err(kept) = staging.keep_as(partial) {
                // The run's own error is the one to report; this one is said aside.
                run.progress.note(&format!("warning: {kept}"));
            }
            Err(error)
        }
    }
}
