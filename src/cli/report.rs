//! `rtprof report`: rebuilds report.html and report.pdf from saved results; with
//! several files (two machines, two commits) it adds a side-by-side comparison.

use anyhow::{Context, Result};
use runner::report_files::{Pdf, load_runs, write_reports};
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

// `--no-pdf`, the same for every command that writes the reports.
#[derive(clap::Args, Debug, Default)]
pub struct PdfFlag {
    /// Leave out report.pdf (typesetting it takes seconds; report.html has the same
    /// content). A report.pdf left in the directory by an earlier run is removed.
    #[arg(long)]
    no_pdf: bool,
}

impl PdfFlag {
    pub fn choice(&self) -> Pdf {
        if self.no_pdf { Pdf::Skip } else { Pdf::Write }
    }
}

pub fn run(args: &ReportArgs) -> Result<()> {
    let mut runs = load_runs(&args.results)?;
    if let Some(main_run) = runs.first_mut() {
        for line in args.benchmarks.add_to(&mut main_run.results, false)? {
            eprintln!("{line}");
        }
    }
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| runs[0].base_dir.clone());
    let dir = if dir.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        dir
    };
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let pdf = args.pdf.choice();
    let pages = write_reports(&runs, &dir, pdf)?;
    let plural = if runs.len() == 1 { "" } else { "s" };
    eprintln!(
        "wrote {}/{{{}, variants.csv, summary.md}} from {} run{plural}",
        dir.display(),
        pdf.documents(),
        runs.len()
    );
    if let Some(p) = pages {
        eprintln!("{}", reports::format::pdf_pages(p.total, p.main_body));
    }
    Ok(())
}
