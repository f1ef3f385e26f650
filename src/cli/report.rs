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
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let results = Results::from_json(&text).with_context(|| path.display().to_string())?;
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
