//! `rtprof report`: rebuilds report.html and report.pdf from saved results; with
//! several files (two machines, two commits) it adds a side-by-side comparison.

use anyhow::{Context, Result};
use reports::Run;
use results::Results;
use std::path::{Path, PathBuf};
use tracer::image_io::write_atomically;

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
}

/// Where the benchmark harnesses saved their figures (`cargo bench -p benches`).
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
    /// Reads the benchmark figures into `results`, replacing any it had. Says on
    /// stderr what it added.
    pub fn add_to(&self, results: &mut Results, discover: bool) -> Result<()> {
        let (criterion, instructions) = runner::benchmarks::resolve_dirs(
            self.criterion.as_deref(),
            self.instructions.as_deref(),
            discover,
        );
        if let Some(dir) = criterion {
            results.criterion = runner::benchmarks::read_criterion_dir(&dir)
                .context("cannot add the criterion estimates (--criterion)")?;
            eprintln!(
                "added {} criterion estimates from {}",
                results.criterion.len(),
                dir.display()
            );
        }
        if let Some(dir) = instructions {
            results.instructions = runner::benchmarks::read_gungraun_dir(&dir)
                .context("cannot add the instruction counts (--instructions)")?;
            eprintln!(
                "added {} instruction counts from {}",
                results.instructions.len(),
                dir.display()
            );
        }
        Ok(())
    }
}

/// Writes report.html and report.pdf for `runs` into `dir` (each atomically).
pub fn write_reports(runs: &[Run], dir: &Path) -> Result<()> {
    // The two documents are independent: typeset the PDF while the HTML is built.
    let (html, pdf) = std::thread::scope(|scope| {
        let pdf = scope.spawn(|| reports::pdf::render_pdf(runs));
        let html = reports::html::render_html(runs);
        (html, pdf.join())
    });
    let html = html.context("cannot build report.html")?;
    write_atomically(&dir.join("report.html"), html.as_bytes())
        .with_context(|| format!("cannot write {}/report.html", dir.display()))?;
    let pdf = match pdf {
        Ok(pdf) => pdf.context("cannot build report.pdf")?,
        Err(_) => {
            anyhow::bail!("typesetting report.pdf failed unexpectedly (report.html is written)")
        }
    };
    write_atomically(&dir.join("report.pdf"), &pdf)
        .with_context(|| format!("cannot write {}/report.pdf", dir.display()))?;
    Ok(())
}

/// Reads a results file (any supported schema version), validated.
pub fn load_results(path: &Path) -> Result<Results> {
    Ok(Results::read_file(path)?)
}

pub fn run(args: &ReportArgs) -> Result<()> {
    let mut runs = Vec::new();
    for path in &args.results {
        let results = load_results(path)?;
        let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        // Label by machine, then by file when two runs share a machine.
        let mut label = results.machine.hostname.clone();
        if runs.iter().any(|r: &Run| r.label == label) {
            label = format!("{label} ({})", path.display());
        }
        runs.push(Run {
            label,
            results,
            base_dir,
        });
    }
    if let Some(main_run) = runs.first_mut() {
        args.benchmarks.add_to(&mut main_run.results, false)?;
    }
    let dir = match &args.output {
        Some(d) => d.clone(),
        None => runs.first().map(|r| r.base_dir.clone()).unwrap_or_default(),
    };
    let dir = if dir.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        dir
    };
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    write_reports(&runs, &dir)?;
    eprintln!(
        "wrote {}/report.html and report.pdf from {} run{}",
        dir.display(),
        runs.len(),
        if runs.len() == 1 { "" } else { "s" }
    );
    Ok(())
}
