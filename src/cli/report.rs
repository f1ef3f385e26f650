//! `rtprof report`: rebuilds report.html and report.pdf from saved results; with
//! several files (two machines, two commits) it adds a side-by-side comparison.

use anyhow::{Context, Result};
use results::Results;
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
    benchmarks: BenchmarkDirs,
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

// Where the benchmark harnesses saved their figures (`cargo bench -p benches`).
#[derive(clap::Args, Debug, Default)]
pub struct BenchmarkDirs {
    /// Add criterion's estimates (mean, median, 95 % intervals) from this directory,
    /// e.g. target/criterion [suite default: <target dir>/criterion when present].
    #[arg(long, value_name = "DIR")]
    pub criterion: Option<PathBuf>,
    /// Add gungraun's instruction counts from this directory [default: `gungraun`
    /// beside the criterion directory, when present].
    #[arg(long, value_name = "DIR")]
    pub instructions: Option<PathBuf>,
}

impl BenchmarkDirs {
    /// Refuses a given directory that does not exist, before any long work.
    pub fn check(&self) -> Result<()> {
        let (criterion, instructions) = (self.criterion.as_deref(), self.instructions.as_deref());
        Ok(runner::benchmarks::check_dirs(criterion, instructions)?)
    }

    /// Reads the benchmark figures into `results` (replacing any it had), saying what
    /// it added; `discover` looks in the cargo target directory when none is given.
    pub fn add_to(&self, results: &mut Results, discover: bool) -> Result<(), runner::RunError> {
        let (criterion, instructions) = (self.criterion.as_deref(), self.instructions.as_deref());
        let added = runner::benchmarks::add_to_results(results, criterion, instructions, discover)?;
        added.iter().for_each(|line| eprintln!("{line}"));
        Ok(())
    }
}

pub fn run(args: &ReportArgs) -> Result<()> {
    let mut runs = load_runs(&args.results)?;
    if let Some(main_run) = runs.first_mut() {
        args.benchmarks.add_to(&mut main_run.results, false)?;
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
