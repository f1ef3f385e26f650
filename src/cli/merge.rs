//! `rtprof merge`: joins the results of `rtprof suite --shard I/N` runs into one
//! results.json with its reports (the work is `runner::merge`), written through a
//! staging directory as the suite writes.

use super::Outcome;
use anyhow::Result;
use runner::merge::{MergeOptions, merge, read_part};
use runner::suite::Suite;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The shards' results: results.json files or directories holding one.
    #[arg(required = true, value_name = "PART")]
    parts: Vec<PathBuf>,
    /// Output directory.
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    /// Merge parts from different suites, binaries or machine classes anyway.
    #[arg(long)]
    allow_mixed: bool,
    #[command(flatten)]
    pdf: runner::report_files::PdfFlag,
}

pub fn run(args: &MergeArgs) -> Result<()> {
    let parts: Vec<_> = args
        .parts
        .iter()
        .map(|p| read_part(p))
        .collect::<Result<_, _>>()?;
    let allow_mixed = args.allow_mixed;
    let merged = merge(&parts, MergeOptions { allow_mixed })?;
    for warning in &merged.warnings {
        eprintln!("rtprof: warning: {warning}");
    }
    let pdf = args.pdf.choice();
    let pages = merged.write_into(&args.output, pdf)?;
    eprint!("{}", merged.summary(&args.output, pdf));
    if let Some(p) = pages {
        eprintln!("{}", reports::format::pdf_pages(p.total, p.main_body));
    }
    match Suite::failures_message(&merged.results) {
        Some(message) => Err(Outcome::new(Outcome::PARTS_FAILED, message).into()),
        None => Ok(()),
    }
}
