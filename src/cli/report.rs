//! `rtprof report`: rebuilds report.html and report.pdf from saved results; with
//! several files (two machines, two commits) it adds a side-by-side comparison (the
//! work is `runner::report_files`).

use anyhow::Result;
use runner::report_files::{PdfFlag, report_from_files};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct ReportArgs {
    /// results.json files (the first is the main run; others are compared with it).
    #[arg(required = true, value_name = "RESULTS.json")]
    results: Vec<PathBuf>,
    /// Output directory (default: the first file's directory).
    #[arg(short, long, value_name = "DIR")]
    output: Option<PathBuf>,
    #[command(flatten)]
    benchmarks: runner::benchmarks::BenchmarkDirs,
    #[command(flatten)]
    pdf: PdfFlag,
}

pub fn run(args: &ReportArgs) -> Result<()> {
    let output = args.output.as_deref();
    let pdf = args.pdf.choice();
    for line in report_from_files(&args.results, output, &args.benchmarks, pdf)? {
        eprintln!("{line}");
    }
    Ok(())
}
