//! `rtprof record [-o DIR] [--freq HZ] [--call-graph fp|dwarf] -- CMD [ARGS...]`: any
//! program (a user's own tracer) sampled under Linux perf into rtprof's profile files
//! (the flags are `runner::record::RecordSettings`); `--import FILE`: a perf.data or
//! gprof output recorded elsewhere into the same files (`runner::record_import`).

use super::Outcome;
use anyhow::Result;
use runner::record::{Failure, RecordSettings};

pub fn run(args: &RecordSettings) -> Result<()> {
    if let Some(file) = &args.import {
        // No program shares the terminal: the summary goes to stdout.
        print!("{}", runner::record_import::import_into(file, args)?);
        return Ok(());
    }
    let dir = args.dir();
    let recording = runner::record::record(&args.plan(&dir, terminal::interrupt::install()))?;
    let summary = recording.save(&dir)?;
    // stdout is the program's (an image written there stays whole): ours goes to stderr.
    eprint!("{}", recording.to_text(&dir, &summary));
    match recording.failure() {
        None => Ok(()),
        Some(Failure::Interrupted(m)) => Err(Outcome::new(Outcome::INTERRUPTED, m).into()),
        Some(Failure::CommandFailed(m)) => Err(Outcome::new(Outcome::COMMAND_FAILED, m).into()),
        Some(Failure::BadProbeFile(m)) => Err(anyhow::anyhow!(m)),
    }
}
