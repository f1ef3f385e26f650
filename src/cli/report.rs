//! `rtprof report`: rebuilds report.html and report.pdf from saved results; with
//! several files (two machines, two commits) it adds a side-by-side comparison.

use anyhow::{Context, Result};
use reports::Run;
use reports::results::Results;
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
    /// The directories to read: the ones given, else (when `discover`) those of the
    /// cargo target directory: `$CARGO_TARGET_DIR`, else the one this binary was built
    /// in, else ./target.
    fn resolve(&self, discover: bool) -> (Option<PathBuf>, Option<PathBuf>) {
        let beside_criterion = || {
            self.criterion
                .as_ref()
                .and_then(|c| c.parent())
                .map(|target| reports::benchmarks::harness_dirs(target).1)
                .unwrap_or_default()
        };
        match (&self.criterion, &self.instructions) {
            (Some(c), Some(i)) => (Some(c.clone()), Some(i.clone())),
            (Some(c), None) => (Some(c.clone()), beside_criterion()),
            (None, Some(i)) => (None, Some(i.clone())),
            (None, None) if discover => match target_dir() {
                Some(target) => reports::benchmarks::harness_dirs(&target),
                None => (None, None),
            },
            (None, None) => (None, None),
        }
    }

    /// Reads the benchmark figures into `results`, replacing any it had. Says on
    /// stderr what it added.
    pub fn add_to(&self, results: &mut Results, discover: bool) -> Result<()> {
        let (criterion, instructions) = self.resolve(discover);
        if let Some(dir) = criterion {
            results.criterion = reports::benchmarks::read_criterion_dir(&dir)
                .context("cannot add the criterion estimates (--criterion)")?;
            eprintln!(
                "added {} criterion estimates from {}",
                results.criterion.len(),
                dir.display()
            );
        }
        if let Some(dir) = instructions {
            results.instructions = reports::benchmarks::read_gungraun_dir(&dir)
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

/// The cargo target directory whose harness output to pick up, if one exists.
fn target_dir() -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os("CARGO_TARGET_DIR") {
        return Some(PathBuf::from(dir));
    }
    // <target>/<profile>/rtprof
    let built_in = std::env::current_exe()
        .ok()
        .and_then(|exe| Some(exe.parent()?.parent()?.to_path_buf()));
    built_in
        .into_iter()
        .chain([PathBuf::from("target")])
        .find(|t| t.join("criterion").is_dir() || t.join("gungraun").is_dir())
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

pub fn run(args: &ReportArgs) -> Result<()> {
    let mut runs = Vec::new();
    for path in &args.results {
        let results = Results::read_file(path)?;
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
