//! The report files of a run: results files read back as labelled [`Run`]s, and
//! report.html, report.pdf, variants.csv and summary.md written from them (each
//! atomically), with results.json for a new run.

use reports::pdf::PageCount;
use std::path::{Path, PathBuf};

use reports::Run;
use results::Results;
use tracer::image_io::write_atomically;

use crate::error::RunError;

/// Reads results files (any supported schema version, validated) as runs labelled by
/// hostname, and by file as well when two share a hostname. Relative paths in each
/// start at its file's directory.
pub fn load_runs(paths: &[PathBuf]) -> Result<Vec<Run>, RunError> {
    let mut runs: Vec<Run> = Vec::new();
    for path in paths {
        let results = Results::read_file(path).map_err(|e| RunError::Input(e.to_string()))?;
        let mut label = results.machine.hostname.clone();
        if runs.iter().any(|r| r.label == label) {
            label = format!("{label} ({})", path.display());
        }
        let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        runs.push(Run {
            label,
            results,
            base_dir,
        });
    }
    Ok(runs)
}

/// Whether a run's reports include report.pdf. Typesetting it takes seconds (report.html
/// has the same content), so `--no-pdf` leaves it out, and removes a report.pdf left in
/// the output directory by an earlier run: it would describe other results.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Pdf {
    #[default]
    Write,
    Skip,
}

// `--no-pdf`, the same for every command that writes the reports. (A plain comment:
// clap would take a doc comment as the about of every command that flattens it.)
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct PdfFlag {
    /// Leave out report.pdf (typesetting it takes seconds; report.html has the same
    /// content). A report.pdf left in the directory by an earlier run is removed.
    #[cfg_attr(feature = "clap", arg(long))]
    pub no_pdf: bool,
}

impl PdfFlag {
    /// Whether to write report.pdf.
    pub fn choice(self) -> Pdf {
        if self.no_pdf { Pdf::Skip } else { Pdf::Write }
    }
}

impl Pdf {
    /// The report documents written, in the order a run's file list gives them.
    pub fn files(self) -> &'static [&'static str] {
        match self {
            Pdf::Write => &["report.html", "report.pdf"],
            Pdf::Skip => &["report.html"],
        }
    }

    /// The report documents written, for the messages that list a run's files.
    pub fn documents(self) -> String {
        self.files().join(", ")
    }

    /// With [`Pdf::Skip`], removes `output`'s report.pdf (an earlier run's) if there is one.
    pub fn remove_stale(self, output: &Path) -> Result<(), RunError> {
        if self == Pdf::Write {
            return Ok(());
        }
        let path = output.join("report.pdf");
        match std::fs::remove_file(&path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                Err(RunError::io("remove the earlier", &path, &e))
            }
            _ => Ok(()),
        }
    }
}

/// `rtprof report`: the runs of `paths` (the first the main one, with the benchmark
/// figures of `benchmarks` added) into reports in `output` [default: the first file's
/// directory]; returns the lines that say what was added and written.
pub fn report_from_files(
    paths: &[PathBuf],
    output: Option<&Path>,
    benchmarks: &crate::benchmarks::BenchmarkDirs,
    pdf: Pdf,
) -> Result<Vec<String>, RunError> {
    let mut runs = load_runs(paths)?;
    let mut lines = Vec::new();
    if let Some(main_run) = runs.first_mut() {
        lines = benchmarks.add_to(&mut main_run.results, false)?;
    }
    let dir = output
        .map(Path::to_path_buf)
        .or_else(|| runs.first().map(|r| r.base_dir.clone()))
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or_else(|| PathBuf::from("."));
    std::fs::create_dir_all(&dir).map_err(|e| RunError::io("create", &dir, &e))?;
    let pages = write_reports(&runs, &dir, pdf)?;
    lines.push(format!(
        "wrote {}/{{{}, variants.csv, summary.md}} from {}",
        dir.display(),
        pdf.documents(),
        reports::format::plural(runs.len(), "run")
    ));
    lines.extend(pages.map(|p| reports::format::pdf_pages(p.total, p.main_body)));
    Ok(lines)
}

/// Writes report.html, report.pdf (unless `pdf` says not), variants.csv (the first
/// run's) and summary.md for `runs` into `dir`; the PDF's page count when it wrote one.
pub fn write_reports(runs: &[Run], dir: &Path, pdf: Pdf) -> Result<Option<PageCount>, RunError> {
    if let Some(main) = runs.first() {
        let csv = reports::exports::variants_csv(&main.results);
        crate::staging::save(dir, "variants.csv", csv.as_bytes())?;
        let summary = reports::exports::summary_markdown(runs);
        crate::staging::save(dir, "summary.md", summary.as_bytes())?;
    }
    let failed = |what: &str, message: String| RunError::Report(format!("{what}: {message}"));
    // The two documents are independent: typeset the PDF while the HTML is built.
    let (html, typeset) = std::thread::scope(|scope| {
        let typeset =
            (pdf == Pdf::Write).then(|| scope.spawn(|| reports::pdf::render_pdf_counted(runs)));
        (reports::html::render_html(runs), typeset.map(|t| t.join()))
    });
    let html = html.map_err(|e| failed("cannot build report.html", e.to_string()))?;
    let html_path = dir.join("report.html");
    write_atomically(&html_path, html.as_bytes())
        .map_err(|e| RunError::io("write", &html_path, &e))?;
    let Some(typeset) = typeset else {
        return pdf.remove_stale(dir).map(|()| None);
    };
    let (pdf, pages) = typeset
        .map_err(|_| {
            failed(
                "typesetting report.pdf failed",
                "report.html is written".into(),
            )
        })?
        .map_err(|e| failed("cannot build report.pdf", e.to_string()))?;
    let pdf_path = dir.join("report.pdf");
    write_atomically(&pdf_path, &pdf).map_err(|e| RunError::io("write", &pdf_path, &e))?;
    Ok(Some(pages))
}

/// Writes one run's results.json and reports into `dir`; the PDF's page count when it
/// wrote one.
pub fn write_run(results: &Results, dir: &Path, pdf: Pdf) -> Result<Option<PageCount>, RunError> {
    let json = serde_json::to_string_pretty(results)
        .map_err(|e| RunError::Report(format!("cannot serialize results.json: {e}")))?;
    crate::staging::save(dir, "results.json", json.as_bytes())?;
    let run = Run {
        label: results.machine.hostname.clone(),
        results: results.clone(),
        base_dir: dir.to_path_buf(),
    };
    write_reports(&[run], dir, pdf)
}
