//! The PDF report: the HTML report's content, typeset with typst.
//!
//! The report is typst markup written here in Rust. Text from the results (scene names,
//! commands, messages, function names, file paths) enters the markup only as typst
//! string literals ([`lit`]), so no character in it can change the markup. Charts
//! (SVG), images (PNG) and flamegraphs (SVG) are virtual files handed to typst in
//! memory and placed with `image(..)`; typst draws SVG as vectors. The fonts are the
//! ones `typst-assets` embeds (Libertinus Serif, New Computer Modern, DejaVu Sans
//! Mono): typesetting reads no system font and no network.
//!
//! A file typst cannot read (a damaged PNG, an SVG it rejects) costs only that figure:
//! when the whole document does not compile, every embedded file is tried on its own
//! and the ones that fail are replaced by a note.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::Path;

use typst_as_lib::TypstEngine;
use typst_layout::PagedDocument;

use crate::Run;
use crate::charts::{self, Chart};
use crate::findings;
use crate::gallery::{self, Picture};
use crate::results::{
    Estimate, HwRow, Profile, ProfileResult, Quality, Results, SceneFamily, SceneResult,
    VariantResult,
};

/// Why no PDF could be made.
#[derive(Debug, thiserror::Error)]
pub enum PdfError {
    #[error("nothing to report: no runs given")]
    NoRuns,
    #[error("typst could not typeset the report: {0}")]
    Typeset(String),
    #[error("typst could not write the PDF: {0}")]
    Export(String),
}

/// The main source's virtual path.
const MAIN: &str = "/report.typ";

/// Text width of the page (A4, 1.5 cm margins), cm.
const TEXT_WIDTH_CM: f64 = 18.0;

/// Lines of a call graph text shown before the rest is left to the file.
const CALLGRAPH_LINES: usize = 160;

/// Renders the report of `runs` (one run, or several side by side) to PDF bytes.
pub fn render_pdf(runs: &[Run]) -> Result<Vec<u8>, PdfError> {
    if runs.is_empty() {
        return Err(PdfError::NoRuns);
    }
    let doc = Document::build(runs, &Embedding::All);
    let first_error = match compile(&doc) {
        Ok(pdf) => return Ok(pdf),
        Err(err) => err,
    };
    // Find the files typst rejects and leave only them out.
    let rejected: BTreeSet<String> = doc
        .files
        .iter()
        .filter(|(path, bytes)| !file_typesets(path, bytes))
        .map(|(path, _)| path.clone())
        .collect();
    if !rejected.is_empty() {
        let doc = Document::build(runs, &Embedding::AllBut(rejected));
        if let Ok(pdf) = compile(&doc) {
            return Ok(pdf);
        }
    }
    // Last resort: the text and tables alone, with the reason on the title page.
    let doc = Document::build(runs, &Embedding::None(first_error.to_string()));
    compile(&doc).map_err(|_| first_error)
}

/// Compiles a document's markup and files to PDF.
fn compile(doc: &Document) -> Result<Vec<u8>, PdfError> {
    let engine = TypstEngine::builder()
        .fonts(typst_assets::fonts())
        .with_static_source_file_resolver([(MAIN, doc.markup.as_str())])
        .with_static_file_resolver(
            doc.files
                .iter()
                .map(|(path, bytes)| (path.as_str(), bytes.as_slice())),
        )
        .build();
    let document: PagedDocument = engine
        .compile(MAIN)
        .output
        .map_err(|err| PdfError::Typeset(describe(&err)))?;
    typst_pdf::pdf(&document, &typst_pdf::PdfOptions::default()).map_err(|diags| {
        PdfError::Export(
            diags
                .iter()
                .map(|d| d.message.to_string())
                .collect::<Vec<_>>()
                .join("; "),
        )
    })
}

/// Whether typst can place one file as an image.
fn file_typesets(path: &str, bytes: &[u8]) -> bool {
    let doc = Document {
        markup: format!("#image({}, width: 2cm)\n", lit(path)),
        files: vec![(path.to_string(), bytes.to_vec())],
    };
    compile(&doc).is_ok()
}

/// A typst error, readably.
fn describe(err: &typst_as_lib::TypstAsLibError) -> String {
    match err {
        typst_as_lib::TypstAsLibError::TypstSource(diags) => diags
            .iter()
            .map(|d| {
                let mut text = d.message.to_string();
                for hint in &d.hints {
                    let _ = write!(text, " (hint: {})", hint.v);
                }
                text
            })
            .collect::<Vec<_>>()
            .join("; "),
        other => other.to_string(),
    }
}

/// Which files the document embeds.
enum Embedding {
    All,
    /// All but these virtual paths (typst rejected them).
    AllBut(BTreeSet<String>),
    /// None: typesetting with them failed for this reason.
    None(String),
}

impl Embedding {
    fn allows(&self, path: &str) -> bool {
        match self {
            Embedding::All => true,
            Embedding::AllBut(rejected) => !rejected.contains(path),
            Embedding::None(_) => false,
        }
    }
}

/// Markup and the virtual files it refers to.
struct Document {
    markup: String,
    files: Vec<(String, Vec<u8>)>,
}

/// A typst string literal of `s`: safe for any text.
pub(crate) fn lit(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '"' => out.push_str("\\\""),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{{{:x}}}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// `s` as markup: a string literal in an embedded expression, closed with `;` so that
/// whatever markup follows cannot continue the expression.
fn txt(s: &str) -> String {
    format!("#{};", lit(s))
}

/// A function name that may break after `::` in narrow columns.
fn breakable_name(name: &str) -> String {
    name.replace("::", "::\u{200B}")
}

/// The typst preamble: page, fonts, and the helpers the body calls.
const PREAMBLE: &str = r##"
#set document(title: "rtprof report", author: "rtprof")
#set page(
  paper: "a4",
  margin: (x: 1.5cm, top: 1.8cm, bottom: 1.7cm),
  header: context {
    if counter(page).get().first() > 1 {
      set text(size: 7.5pt, fill: luma(120))
      [rtprof report #h(1fr) #report-subject]
      v(-0.5em)
      line(length: 100%, stroke: 0.4pt + luma(190))
    }
  },
  footer: context {
    set text(size: 7.5pt, fill: luma(120))
    h(1fr)
    counter(page).display("1 / 1", both: true)
    h(1fr)
  },
)
#set text(font: "Libertinus Serif", size: 10pt, lang: "en")
#set par(justify: false, leading: 0.58em, spacing: 0.9em)
#set heading(numbering: "1.1")
#show heading: set text(weight: "bold")
#show heading.where(level: 1): it => {
  set text(size: 15pt)
  block(above: 1.6em, below: 0.8em, it)
}
#show heading.where(level: 2): set text(size: 11.5pt)
#show heading.where(level: 3): set text(size: 10pt)
#show raw: set text(font: "DejaVu Sans Mono")
#show figure.caption: set text(size: 8.5pt)
#set figure(gap: 0.6em)

#let muted(body) = text(fill: luma(90), body)
#let note(body) = block(
  width: 100%, inset: 6pt, radius: 2pt, fill: luma(244), stroke: 0.5pt + luma(205),
  text(size: 8.5pt, fill: luma(60), body),
)
#let caption(body) = block(above: 1em, below: 0.5em, text(size: 9pt, weight: "bold", body))
#let tbl(columns: auto, align: auto, header: (), size: 8pt, ..rows) = {
  set text(size: size)
  set par(leading: 0.45em)
  table(
    columns: columns,
    align: align,
    inset: (x: 3.5pt, y: 2.8pt),
    stroke: (x, y) => (
      top: if y == 0 { 0.8pt } else if y == 1 { 0.5pt } else { 0pt },
      bottom: 0.4pt + luma(215),
    ),
    fill: (x, y) => if y > 0 and calc.even(y) { luma(247) },
    table.header(..header.map(h => text(weight: "bold", h))),
    ..rows.pos().flatten(),
  )
}
#let kv(..pairs) = grid(
  columns: (auto, 1fr), column-gutter: 1em, row-gutter: 0.55em,
  ..pairs.pos().flatten().enumerate().map(((i, c)) => if calc.even(i) { text(weight: "bold", c) } else { c }),
)
#let missing(what, height: 1.6cm) = box(
  width: 100%, height: height, fill: luma(236), stroke: 0.4pt + luma(200),
  align(center + horizon, text(size: 6.5pt, fill: luma(80), what)),
)
#let bad(body) = text(fill: rgb("#b3261e"), body)
#let good(body) = text(fill: rgb("#1b6e20"), body)
"##;

impl Document {
    fn build(runs: &[Run], embedding: &Embedding) -> Document {
        let mut b = Builder {
            out: String::new(),
            files: Vec::new(),
            next_file: 0,
            embedding,
        };
        b.preamble(runs);
        b.title_page(runs);
        b.scenes(&runs[0]);
        RunWriter::new(&mut b, &runs[0]).write();
        if runs.len() > 1 {
            b.comparison(runs);
        }
        Document {
            markup: b.out,
            files: b.files,
        }
    }
}

/// Accumulates markup and files.
struct Builder<'e> {
    out: String,
    files: Vec<(String, Vec<u8>)>,
    next_file: usize,
    embedding: &'e Embedding,
}

impl Builder<'_> {
    fn push(&mut self, markup: &str) {
        self.out.push_str(markup);
    }

    fn line(&mut self, markup: &str) {
        self.out.push_str(markup);
        self.out.push('\n');
    }

    /// Registers a file; returns its virtual path, or `None` when it is left out.
    fn file(&mut self, ext: &str, bytes: Vec<u8>) -> Option<String> {
        let path = format!("/files/{}.{ext}", self.next_file);
        self.next_file += 1;
        if !self.embedding.allows(&path) {
            return None;
        }
        self.files.push((path.clone(), bytes));
        Some(path)
    }

    /// A heading; `text` is plain text. Level 1 starts a new page.
    fn heading(&mut self, level: usize, text: &str) {
        if level == 1 {
            self.out.push_str("\n#pagebreak(weak: true)");
        }
        self.inline_heading(level, text);
    }

    /// A heading that does not start a new page.
    fn inline_heading(&mut self, level: usize, text: &str) {
        let _ = writeln!(self.out, "\n#heading(level: {level}, {})\n", lit(text));
    }

    /// A per-scene heading: not numbered, not in the contents.
    fn subheading(&mut self, text: &str) {
        let _ = writeln!(
            self.out,
            "\n#heading(level: 2, numbering: none, outlined: false, {})\n",
            lit(text)
        );
    }

    fn note(&mut self, text: &str) {
        let _ = writeln!(self.out, "#note({})\n", lit(text));
    }

    fn caption(&mut self, text: &str) {
        let _ = writeln!(self.out, "#caption({})", lit(text));
    }

    /// A table: header cells (plain text), column widths and alignments (typst code),
    /// rows of cells (typst expressions, see [`cell`]).
    fn table(&mut self, spec: &[(&str, &str, &str)], rows: &[Vec<String>], size: &str) {
        let columns: Vec<&str> = spec.iter().map(|(_, w, _)| *w).collect();
        let aligns: Vec<&str> = spec.iter().map(|(_, _, a)| *a).collect();
        let header: Vec<String> = spec.iter().map(|(h, _, _)| lit(h)).collect();
        let _ = write!(
            self.out,
            "#tbl(columns: ({},), align: ({},), header: ({},), size: {size}",
            columns.join(", "),
            aligns.join(", "),
            header.join(", ")
        );
        for row in rows {
            let _ = write!(self.out, ",\n  ({},)", row.join(", "));
        }
        self.out.push_str(")\n\n");
    }

    /// A vector figure from SVG text, scaled to the text width but at most `max_h_cm`
    /// high, with `title` (bold) and `caption` under it; a note when it is left out.
    fn svg_figure(&mut self, svg: &str, title: &str, caption: &str, max_h_cm: f64) {
        let size = svg_size(svg);
        match self.file("svg", svg.as_bytes().to_vec()) {
            Some(path) => {
                let sizing = fit_size(size, TEXT_WIDTH_CM, max_h_cm);
                let cap = if caption.is_empty() {
                    lit(title)
                } else {
                    format!("strong({}) + [ ] + {}", lit(title), lit(caption))
                };
                let _ = writeln!(
                    self.out,
                    "#figure(image({}, alt: {}, {sizing}), caption: {cap})\n",
                    lit(&path),
                    lit(title)
                );
            }
            None => self.note(&format!(
                "{title}: this chart could not be typeset here; it is in the HTML report."
            )),
        }
    }

    /// An image cell from a file under `base_dir`: the image, or a grey box saying why
    /// it is not there.
    fn image_cell(&mut self, base_dir: &Path, rel: Option<&str>, label: &str) -> String {
        let Some(rel) = rel else {
            return format!("missing({})", lit(&format!("no {label}")));
        };
        match read_png(base_dir, rel) {
            Ok(bytes) => match self.file("png", bytes) {
                Some(path) => format!(
                    "image({}, alt: {}, width: 100%)",
                    lit(&path),
                    lit(&format!("{label} {rel}"))
                ),
                None => format!("missing({})", lit(&format!("{rel}: unreadable"))),
            },
            Err(why) => format!("missing({})", lit(&format!("{rel}: {why}"))),
        }
    }

    fn preamble(&mut self, runs: &[Run]) {
        let subject = runs
            .iter()
            .map(|r| r.label.as_str())
            .collect::<Vec<_>>()
            .join(" vs ");
        let _ = writeln!(self.out, "#let report-subject = {}", lit(&subject));
        self.push(PREAMBLE);
    }

    fn title_page(&mut self, runs: &[Run]) {
        let main = &runs[0];
        let r = &main.results;
        self.line("#v(1.6cm)");
        self.line("#align(center)[");
        self.line("  #text(size: 26pt, weight: \"bold\")[rtprof report]");
        self.line("  #v(0.2em)");
        self.line(
            "  #text(size: 12pt)[Profile, optimization variants and FPGA model of a Whitted ray tracer]",
        );
        let sub = format!(
            "{} · {} · {}",
            main.label,
            r.created,
            if runs.len() > 1 {
                format!("{} runs compared", runs.len())
            } else {
                "one run".to_string()
            }
        );
        let _ = writeln!(self.out, "  #v(0.4em)\n  #muted({})", lit(&sub));
        self.line("]");
        self.line("#v(0.9cm)");
        if let Embedding::None(why) = self.embedding {
            let why = why.clone();
            self.note(&format!(
                "Figures and images are left out of this PDF because typst could not typeset them ({why}). The HTML report has them."
            ));
        }
        if runs.len() > 1 {
            self.note(&format!(
                "The sections show run {} in detail; the last section sets all {} runs side by side.",
                main.label,
                runs.len()
            ));
        }
        self.line("#heading(level: 2, numbering: none, outlined: false)[Summary]");
        let mut pairs = vec![("Run".to_string(), main.label.clone())];
        pairs.extend(summary_pairs(r));
        let cells: Vec<String> = pairs
            .iter()
            .map(|(k, v)| format!("({}, {})", lit(k), lit(v)))
            .collect();
        let _ = writeln!(self.out, "#text(size: 9.5pt, kv({}))\n", cells.join(", "));
        self.line("#heading(level: 2, numbering: none, outlined: false)[Headline findings]");
        let findings = findings::headline_findings(r);
        if findings.is_empty() {
            self.note("No findings: the run has no profile, variants, hardware model or failures to speak of.");
        } else {
            let items: Vec<String> = findings.iter().map(|f| lit(f)).collect();
            let _ = writeln!(self.out, "#list(spacing: 0.7em, {})\n", items.join(", "));
        }
        if runs.len() > 1 {
            self.line("#heading(level: 2, numbering: none, outlined: false)[Runs]");
            let spec = [
                ("Run", "auto", "left"),
                ("host", "auto", "left"),
                ("CPU", "1fr", "left"),
                ("cores", "auto", "right"),
                ("commit", "auto", "left"),
                ("created", "auto", "left"),
                ("scenes", "auto", "right"),
            ];
            let rows: Vec<Vec<String>> = runs
                .iter()
                .map(|run| {
                    let r = &run.results;
                    vec![
                        lit(&run.label),
                        lit(&r.machine.hostname),
                        lit(&r.machine.cpu_model),
                        lit(&r.machine.cores.to_string()),
                        lit(short_commit(&r.build.git_commit)),
                        lit(&r.created),
                        lit(&r.scenes.len().to_string()),
                    ]
                })
                .collect();
            self.table(&spec, &rows, "7.5pt");
        }
        self.line("#pagebreak()");
        self.line("#outline(depth: 2, indent: 1.2em)");
    }

    /// The scenes that ran.
    fn scenes(&mut self, run: &Run) {
        let r = &run.results;
        self.heading(1, &format!("Scenes ({})", r.scenes.len()));
        if r.scenes.is_empty() {
            self.note("No scene ran (see Failures).");
            return;
        }
        let spec = [
            ("Scene", "auto", "left"),
            ("family", "auto", "left"),
            ("primitives", "auto", "right"),
            ("kinds", "auto", "left"),
            ("size", "auto", "left"),
            ("variants", "auto", "right"),
            ("baseline time", "auto", "right"),
            ("source", "1fr", "left"),
        ];
        let rows: Vec<Vec<String>> = r
            .scenes
            .iter()
            .map(|scene| {
                let base = r.baseline(scene);
                vec![
                    lit(&scene.name),
                    lit(scene.family.name()),
                    lit(&group(scene.primitives)),
                    lit(&kinds(scene)),
                    lit(&format!(
                        "{}×{}{}",
                        scene.width,
                        scene.height,
                        if scene.spd { " (SPD sampling)" } else { "" }
                    )),
                    lit(&scene.variants.len().to_string()),
                    lit(&base.map_or_else(|| "no baseline".to_string(), |b| secs(b.time.median))),
                    lit(&scene.source),
                ]
            })
            .collect();
        self.table(&spec, &rows, "8pt");
    }

    /// Side-by-side tables of several runs.
    fn comparison(&mut self, runs: &[Run]) {
        self.heading(1, "Comparison of runs");
        let labels: Vec<&str> = runs.iter().map(|r| r.label.as_str()).collect();
        self.line(&format!(
            "Median time of each scene × variant in every run and its change against {} (coloured when the 95 % intervals do not overlap: red slower, green faster). Counts are exact, so any difference means a different program or scene.\n",
            txt(labels[0])
        ));
        // Machines side by side.
        let mut spec: Vec<(&str, &str, &str)> = vec![("", "auto", "left")];
        for label in &labels {
            spec.push((label, "1fr", "left"));
        }
        let all: Vec<Vec<(String, String)>> =
            runs.iter().map(|r| summary_pairs(&r.results)).collect();
        let rows: Vec<Vec<String>> = all[0]
            .iter()
            .enumerate()
            .map(|(i, (k, _))| {
                let mut row = vec![format!("strong({})", lit(k))];
                for pairs in &all {
                    row.push(lit(pairs.get(i).map_or("", |(_, v)| v.as_str())));
                }
                row
            })
            .collect();
        self.caption("Machines and builds");
        self.table(&spec, &rows, "7.5pt");

        let keys = crate::findings::comparison_keys(runs);
        if keys.is_empty() {
            self.note("No scene results in any run to compare.");
            return;
        }
        let headers: Vec<String> = labels
            .iter()
            .map(|l| (*l).to_string())
            .chain(
                labels
                    .iter()
                    .skip(1)
                    .map(|l| format!("{l} vs {}", labels[0])),
            )
            .collect();
        let mut spec: Vec<(&str, &str, &str)> =
            vec![("Scene", "auto", "left"), ("Variant", "auto", "left")];
        for h in &headers {
            spec.push((h, "auto", "right"));
        }
        spec.push(("counts", "1fr", "left"));
        let mut rows = Vec::new();
        for key in &keys {
            let found: Vec<Option<&VariantResult>> = runs
                .iter()
                .map(|run| {
                    run.results
                        .scenes
                        .iter()
                        .find(|s| s.name == key.0 && s.width == key.1 && s.height == key.2)
                        .and_then(|s| s.variants.iter().find(|v| v.variant == key.3))
                })
                .collect();
            let mut row = vec![lit(&key.0), lit(&key.3)];
            for f in &found {
                row.push(lit(
                    &f.map_or_else(|| "not run".to_string(), |x| secs(x.time.median))
                ));
            }
            for f in found.iter().skip(1) {
                row.push(match (found[0], f) {
                    (Some(a), Some(b)) => change_cell(&a.time, &b.time),
                    _ => lit("–"),
                });
            }
            let present: Vec<&VariantResult> = found.iter().flatten().copied().collect();
            let same = present.windows(2).all(|w| w[0].counts == w[1].counts);
            row.push(if present.len() < 2 {
                muted_lit("–")
            } else if same {
                lit("same")
            } else {
                format!("bad({})", lit("differ"))
            });
            rows.push(row);
        }
        self.caption("Tracing time, median per run");
        self.table(&spec, &rows, "7.5pt");
    }
}

fn muted_lit(s: &str) -> String {
    format!("muted({})", lit(s))
}

fn kinds(scene: &SceneResult) -> String {
    scene
        .primitive_counts
        .iter()
        .filter(|(_, n)| **n > 0)
        .map(|(k, n)| format!("{} {k}", group(*n)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A change cell: relative change of `new` against `old`, coloured when the intervals
/// do not overlap.
fn change_cell(old: &Estimate, new: &Estimate) -> String {
    if old.median <= 0.0 {
        return lit("–");
    }
    let pct = (new.median / old.median - 1.0) * 100.0;
    let text = lit(&format!("{} %", signed(pct, 1)));
    if new.low > old.high {
        format!("bad({text})")
    } else if new.high < old.low {
        format!("good({text})")
    } else {
        text
    }
}

/// Machine, build and suite as key-value pairs.
fn summary_pairs(r: &Results) -> Vec<(String, String)> {
    let s = &r.suite;
    vec![
        (
            "Machine".into(),
            format!(
                "{} ({} logical CPUs), {}, host {}",
                r.machine.cpu_model, r.machine.cores, r.machine.os, r.machine.hostname
            ),
        ),
        (
            "Build".into(),
            format!(
                "rtprof {} ({}), {}, commit {}",
                r.build.rtprof_version,
                r.build.profile,
                r.build.rustc,
                short_commit(&r.build.git_commit)
            ),
        ),
        (
            "Suite".into(),
            format!(
                "{}{}: {} scenes, {} variants, {}, {} threads, {} wall",
                s.name,
                if s.quick { " (quick)" } else { "" },
                r.scenes.len(),
                s.variants.len(),
                findings::repeats_text(s),
                s.threads,
                secs(s.wall_seconds)
            ),
        ),
        ("Variants".into(), crate::html::join_names(&s.variants)),
        ("Created".into(), r.created.clone()),
        (
            "Failures".into(),
            if r.failures.is_empty() {
                "none".into()
            } else {
                format!("{} (see the failures section)", r.failures.len())
            },
        ),
    ]
}

fn short_commit(commit: &str) -> &str {
    commit.get(..12).unwrap_or(commit)
}

/// Writes the sections of one run.
struct RunWriter<'a, 'e> {
    b: &'a mut Builder<'e>,
    run: &'a Run,
    charts: BTreeMap<&'static str, Chart>,
}

impl<'a, 'e> RunWriter<'a, 'e> {
    fn new(b: &'a mut Builder<'e>, run: &'a Run) -> Self {
        let charts = charts::all(&run.results)
            .into_iter()
            .map(|c| (c.id, c))
            .collect();
        RunWriter { b, run, charts }
    }

    fn r(&self) -> &'a Results {
        &self.run.results
    }

    /// The level-1 heading of section `id`, titled as in the HTML report.
    fn h1(&mut self, id: &str) {
        let title = crate::html::SECTIONS
            .iter()
            .find(|(sid, _)| *sid == id)
            .map_or(id, |(_, t)| t);
        // Short sections share a page with the one before.
        if matches!(
            id,
            "device-utilization" | "criterion" | "failures" | "reproduce"
        ) {
            self.b.inline_heading(1, title);
        } else {
            self.b.heading(1, title);
        }
    }

    /// Places the chart `id`, or a note when the charts module did not make it.
    fn chart_or_note(&mut self, id: &str, max_h_cm: f64, what: &str) {
        if !self.chart(id, max_h_cm) {
            self.b
                .note(&format!("No {what} chart: this run has no data for it."));
        }
    }

    /// Places the chart `id` if the charts module made it; returns whether it did.
    fn chart(&mut self, id: &str, max_h_cm: f64) -> bool {
        match self.charts.remove(id) {
            Some(c) => {
                self.b.svg_figure(&c.svg, &c.title, &c.caption, max_h_cm);
                true
            }
            None => false,
        }
    }

    fn write(mut self) {
        self.profile();
        self.variants();
        self.images();
        self.hardware();
        self.sw_vs_hw();
        self.primitive_scaling();
        self.spd();
        self.other_charts();
        self.criterion();
        self.failures();
        self.reproduce();
    }

    // ----- profile ---------------------------------------------------------------

    fn profile(&mut self) {
        self.h1("profile");
        let Some(p) = &self.r().profile else {
            self.b
                .note("This run has no profile (the suite did not profile any scene).");
            self.h1("profile-charts");
            self.chart_or_note("calls", 11.0, "calls");
            self.chart_or_note("self-seconds", 11.0, "self-seconds");
            for id in ["flamegraphs", "amdahl"] {
                self.h1(id);
                self.b.note("This run has no profile.");
            }
            return;
        };
        let best = p.best.as_ref().map_or_else(String::new, |b| {
            format!(" and the best variant, {},", b.variant)
        });
        self.b.line(&format!(
            "Sampled profile of the heaviest scene, {} at {}×{}: the baseline{best} in the layout of gprof (thesis table 6 and fig. 53).\n",
            txt(&p.scene),
            p.width,
            p.height
        ));
        for profile in std::iter::once(&p.baseline).chain(p.best.iter()) {
            self.flat_profile(p, profile);
        }
        for profile in std::iter::once(&p.baseline).chain(p.best.iter()) {
            self.call_graph(profile);
        }
        self.h1("profile-charts");
        self.b.line(&format!(
            "Exact calls and sampled self time of the functions of {}, baseline (thesis fig. 51 and 52).\n",
            txt(&p.scene)
        ));
        self.chart_or_note("calls", 10.5, "calls");
        self.chart_or_note("self-seconds", 10.5, "self-seconds");
        self.flamegraphs(p);
        self.amdahl(p);
    }

    fn flat_profile(&mut self, p: &ProfileResult, profile: &Profile) {
        self.b
            .heading(2, &format!("Flat profile: {}", profile.variant));
        self.b.line(&format!(
            "{} samples of {} each on {}; file {}.\n",
            profile.samples,
            secs(profile.seconds_per_sample),
            txt(&p.scene),
            txt(&profile.flat_text)
        ));
        let spec = [
            ("% time", "auto", "right"),
            ("cumulative s", "auto", "right"),
            ("self s", "auto", "right"),
            ("calls", "auto", "right"),
            ("self µs/call", "auto", "right"),
            ("total s", "auto", "right"),
            ("name", "1fr", "left"),
        ];
        let mut cumulative = 0.0;
        let rows: Vec<Vec<String>> = profile
            .flat
            .iter()
            .map(|row| {
                cumulative += row.self_seconds;
                let per_call = match row.calls {
                    Some(c) if c > 0 => format!("{:.4}", row.self_seconds / c as f64 * 1e6),
                    _ => String::new(),
                };
                vec![
                    lit(&format!("{:.2}", row.percent)),
                    lit(&format!("{cumulative:.3}")),
                    lit(&format!("{:.3}", row.self_seconds)),
                    lit(&row.calls.map_or_else(String::new, group)),
                    lit(&per_call),
                    lit(&format!("{:.3}", row.total_seconds)),
                    lit(&breakable_name(&row.name)),
                ]
            })
            .collect();
        self.b.caption(&format!(
            "Table 6 (thesis): flat profile of {}, {}",
            p.scene, profile.variant
        ));
        if rows.is_empty() {
            self.b.note("The profile has no samples.");
        } else {
            self.b.table(&spec, &rows, "7.5pt");
        }
    }

    fn call_graph(&mut self, profile: &Profile) {
        self.b
            .heading(2, &format!("Call graph: {}", profile.variant));
        match std::fs::read(self.run.base_dir.join(&profile.callgraph_text)) {
            Ok(bytes) => {
                let text = String::from_utf8_lossy(&bytes);
                let lines: Vec<&str> = text.lines().collect();
                let shown = lines.len().min(CALLGRAPH_LINES);
                let body = lines[..shown].join("\n");
                let _ = writeln!(
                    self.b.out,
                    "#block(width: 100%, inset: 5pt, fill: luma(248), stroke: 0.4pt + luma(210), text(size: 6pt, raw(block: true, {})))\n",
                    lit(&body)
                );
                if shown < lines.len() {
                    self.b.note(&format!(
                        "The first {shown} of {} lines; the whole call graph is in {}.",
                        lines.len(),
                        profile.callgraph_text
                    ));
                }
            }
            Err(err) => self.b.note(&format!(
                "The call graph text {} could not be read ({}).",
                profile.callgraph_text,
                io_reason(&err)
            )),
        }
    }

    fn flamegraphs(&mut self, p: &ProfileResult) {
        self.h1("flamegraphs");
        self.b.line("Each box is a function; its width is its share of the samples, the boxes above it are its callees. The HTML report has the interactive versions.\n");
        let mut items: Vec<(String, String)> = vec![(
            format!("Flamegraph of {}, {}", p.scene, p.baseline.variant),
            p.baseline.flame_svg.clone(),
        )];
        if let Some(best) = &p.best {
            items.push((
                format!("Flamegraph of {}, {}", p.scene, best.variant),
                best.flame_svg.clone(),
            ));
        }
        if let Some(diff) = &p.diff_flame_svg {
            let to = p.best.as_ref().map_or("best", |b| b.variant.as_str());
            items.push((
                format!(
                    "Differential flamegraph of {}, {} to {to} (red: more time, blue: less)",
                    p.scene, p.baseline.variant
                ),
                diff.clone(),
            ));
        }
        for (title, rel) in items {
            match std::fs::read(self.run.base_dir.join(&rel)) {
                Ok(bytes) => {
                    let svg = String::from_utf8_lossy(&bytes).into_owned();
                    self.b.svg_figure(&svg, &title, "", 21.0);
                }
                Err(err) => self.b.note(&format!(
                    "{title}: {rel} could not be read ({}).",
                    io_reason(&err)
                )),
            }
        }
    }

    fn amdahl(&mut self, p: &ProfileResult) {
        self.h1("amdahl");
        self.b.line("The whole program's speed-up if one function alone became 2×, 10× or infinitely faster.\n");
        for profile in std::iter::once(&p.baseline).chain(p.best.iter()) {
            self.b
                .caption(&format!("Amdahl table of {}, {}", p.scene, profile.variant));
            if profile.amdahl.is_empty() {
                self.b.note("No rows.");
                continue;
            }
            let spec = [
                ("Function", "1fr", "left"),
                ("share of time", "auto", "right"),
                ("2× faster", "auto", "right"),
                ("10× faster", "auto", "right"),
                ("limit", "auto", "right"),
            ];
            let rows: Vec<Vec<String>> = profile
                .amdahl
                .iter()
                .map(|a| {
                    vec![
                        lit(&breakable_name(&a.name)),
                        lit(&format!("{:.1} %", a.fraction * 100.0)),
                        lit(&times(a.speedup_2x)),
                        lit(&times(a.speedup_10x)),
                        lit(&times(a.speedup_limit)),
                    ]
                })
                .collect();
            self.b.table(&spec, &rows, "8pt");
        }
    }

    // ----- variants ----------------------------------------------------------------

    fn variants(&mut self) {
        self.h1("variants");
        self.b.line("Tracing time over the repeats (median and 95 % bootstrap interval), speed-up over baseline, and the image against baseline: RMS with the thesis's rating band, PSNR and SSIM. Count changes name the exact counts that differ from baseline.\n");
        self.chart_or_note("quality-speed", 11.0, "quality-vs-speed");
        let scenes = &self.r().scenes;
        if scenes.is_empty() {
            self.b.note("No scene ran.");
        }
        for scene in scenes {
            self.variant_table(scene);
        }
    }

    fn variant_table(&mut self, scene: &SceneResult) {
        let base = self.r().baseline(scene);
        self.b.subheading(&scene.name);
        self.b
            .line(&format!("#muted[{}]\n", txt(&scene_line(scene))));
        let spec = [
            ("Variant", "auto", "left"),
            ("median", "auto", "right"),
            ("95 % interval", "auto", "right"),
            ("speed-up", "auto", "right"),
            ("RMS", "auto", "right"),
            ("band", "auto", "left"),
            ("PSNR dB", "auto", "right"),
            ("SSIM", "auto", "right"),
            ("count changes", "1fr", "left"),
        ];
        let rows: Vec<Vec<String>> = scene
            .variants
            .iter()
            .map(|v| {
                let (rms, band, psnr, ssim) = quality_cells(v.quality.as_ref());
                vec![
                    lit(&v.variant),
                    lit(&secs(v.time.median)),
                    lit(&interval(&v.time)),
                    speedup_cell(v.speedup.unwrap_or(f64::NAN)),
                    lit(&rms),
                    lit(&band),
                    lit(&psnr),
                    lit(&ssim),
                    lit(&count_changes(base, v)),
                ]
            })
            .collect();
        if rows.is_empty() {
            self.b.note("No variant ran on this scene.");
        } else {
            self.b.table(&spec, &rows, "7.5pt");
        }
    }

    // ----- images -----------------------------------------------------------------

    fn images(&mut self) {
        self.h1("images");
        self.b.line("Every variant's image, its difference from baseline as a heat map (thesis fig. 35–37, 42–45) and its gray histogram (log scale; the tall bar is usually the background).\n");
        let scenes: Vec<SceneResult> = gallery::showcase_scenes(self.r())
            .into_iter()
            .cloned()
            .collect();
        if scenes.is_empty() {
            self.b.note("No scene ran.");
        }
        let omitted = gallery::omitted_scenes(self.r());
        if !omitted.is_empty() {
            self.b.note(&format!(
                "Shown: the scene with the largest difference and the largest scenes. The images of the other {} ({}) are in images/ next to this report; the variants table has their metrics.",
                omitted.len(),
                omitted.join(", ")
            ));
        }
        for scene in &scenes {
            self.image_grid(scene);
        }
        self.chart("histogram", 10.0);
    }

    fn image_grid(&mut self, scene: &SceneResult) {
        const PER_ROW: usize = 6;
        let base_dir = self.run.base_dir.clone();
        let mut block = String::new();
        let _ = writeln!(
            block,
            "#block(breakable: false, width: 100%)[\n#heading(level: 2, numbering: none, outlined: false, {})",
            lit(&scene.name)
        );
        if scene.variants.is_empty() {
            block.push_str("#note[No variant ran on this scene.]\n]\n");
            self.b.push(&block);
            return;
        }
        for chunk in scene.variants.chunks(PER_ROW) {
            let mut cells: Vec<String> = Vec::new();
            let names: Vec<String> = chunk
                .iter()
                .map(|v| format!("text(size: 7.5pt, weight: \"bold\", {})", lit(&v.variant)))
                .collect();
            let images: Vec<String> = chunk
                .iter()
                .map(|v| self.b.image_cell(&base_dir, v.image.as_deref(), "image"))
                .collect();
            let heat: Vec<String> = chunk
                .iter()
                .map(|v| {
                    if v.variant.is_reference() {
                        "muted(text(size: 6.5pt)[reference])".to_string()
                    } else {
                        self.b
                            .image_cell(&base_dir, v.heat_map.as_deref(), "heat map")
                    }
                })
                .collect();
            let hist: Vec<String> = chunk
                .iter()
                .map(|v| match histogram_svg(&v.histogram) {
                    Some(svg) => match self.b.file("svg", svg.into_bytes()) {
                        Some(path) => format!("image({}, width: 100%)", lit(&path)),
                        None => "missing(\"histogram\", height: 0.8cm)".to_string(),
                    },
                    None => "missing(\"no histogram\", height: 0.8cm)".to_string(),
                })
                .collect();
            let notes: Vec<String> = chunk
                .iter()
                .map(|v| {
                    let text = match &v.quality {
                        Some(q) => format!("RMS {:.1}, {}", q.rms, q.band),
                        None => "baseline".to_string(),
                    };
                    format!(
                        "text(size: 6.5pt, {} + \"\\n\" + {})",
                        lit(&text),
                        lit(&format!(
                            "{} · {}",
                            secs(v.time.median),
                            times(v.speedup.unwrap_or(f64::NAN))
                        ))
                    )
                })
                .collect();
            cells.extend(names);
            cells.extend(images);
            cells.extend(heat);
            cells.extend(hist);
            cells.extend(notes);
            let _ = writeln!(
                block,
                "#grid(columns: ({}), column-gutter: 4pt, row-gutter: 3pt, align: center + horizon,\n  {})\n#v(0.4em)",
                ["1fr"; PER_ROW].join(", "),
                pad_rows(&cells, chunk.len(), PER_ROW).join(",\n  ")
            );
        }
        block.push_str("]\n");
        self.b.push(&block);
    }

    // ----- hardware -------------------------------------------------------------------

    fn hardware(&mut self) {
        self.h1("hardware-tables");
        let Some(hw) = &self.r().hardware else {
            self.b.note("This run has no hardware model results.");
            self.h1("device-utilization");
            self.b.note("This run has no hardware model results.");
            return;
        };
        self.b.line(&format!(
            "The FPGA model of the thesis's ray caster ({}): each cell is the model's figure, under it the thesis's and the model's error against it.\n",
            txt(&hw.family)
        ));
        self.b
            .caption("Table 7 (thesis): floating-point operations and composite units");
        self.hw_table(&hw.ops);
        self.b.caption("Table 8 (thesis): pipeline blocks");
        self.hw_table(&hw.blocks);
        self.h1("device-utilization");
        self.b.line("The thesis's design fitted to each device: used and available resources; the largest number of intersection units that still fits.\n");
        if hw.devices.is_empty() {
            self.b.note("No device was fitted.");
            return;
        }
        let spec = [
            ("Device", "auto", "left"),
            ("validated", "auto", "left"),
            ("logic elements", "1fr", "right"),
            ("multipliers", "1fr", "right"),
            ("memory bits", "1fr", "right"),
            ("PLLs", "auto", "right"),
            ("fits", "auto", "left"),
            ("largest units", "auto", "right"),
        ];
        let rows: Vec<Vec<String>> = hw
            .devices
            .iter()
            .map(|d| {
                let mult = if d.soft_mult_elements > 0 {
                    format!(
                        "{} + {} soft",
                        usage(d.mult, d.mult_capacity),
                        group(d.soft_mult_elements)
                    )
                } else {
                    usage(d.mult, d.mult_capacity)
                };
                vec![
                    lit(&d.device),
                    lit(if d.validated {
                        "yes (thesis)"
                    } else {
                        "model only"
                    }),
                    lit(&usage(d.le, d.le_capacity)),
                    lit(&mult),
                    lit(&usage(d.mem_bits, d.mem_capacity)),
                    lit(&format!("{} / {}", d.plls, d.pll_capacity)),
                    if d.fits {
                        "good(\"yes\")".to_string()
                    } else {
                        "bad(\"no\")".to_string()
                    },
                    lit(&d
                        .largest_units
                        .map_or_else(|| "–".to_string(), |u| u.to_string())),
                ]
            })
            .collect();
        self.b.table(&spec, &rows, "7.5pt");
        self.chart("device-utilization", 10.0);
    }

    fn hw_table(&mut self, rows: &[HwRow]) {
        if rows.is_empty() {
            self.b.note("No rows.");
            return;
        }
        let without_thesis = rows.iter().filter(|r| r.thesis.is_none()).count();
        let spec = [
            ("Unit", "auto", "left"),
            ("kind", "auto", "left"),
            ("latency", "1fr", "right"),
            ("LEs", "1fr", "right"),
            ("comb.", "1fr", "right"),
            ("registers", "1fr", "right"),
            ("memory bits", "1fr", "right"),
            ("multipliers", "1fr", "right"),
        ];
        let body: Vec<Vec<String>> = rows
            .iter()
            .map(|row| {
                let mut cells = vec![lit(&row.name), lit(row.kind.name())];
                for (c, figure) in row.model.columns() {
                    let model = lit(&group(figure));
                    let sub = match (&row.thesis, &row.error_pct) {
                        (Some(t), Some(e)) => {
                            let err = match e.get(c) {
                                Some(x) => signed(x, 1) + " %",
                                None => "n/a".to_string(),
                            };
                            let text = lit(&format!("{} · {err}", group(t.get(c))));
                            if e.get(c).is_some_and(|x| x.abs() > 10.0) {
                                format!("bad(text(size: 6pt, {text}))")
                            } else {
                                format!("muted(text(size: 6pt, {text}))")
                            }
                        }
                        (Some(t), None) => {
                            format!("muted(text(size: 6pt, {}))", lit(&group(t.get(c))))
                        }
                        _ => {
                            cells.push(model);
                            continue;
                        }
                    };
                    cells.push(format!("stack(spacing: 2pt, {model}, {sub})"));
                }
                cells
            })
            .collect();
        self.b.table(&spec, &body, "7.5pt");
        if without_thesis > 0 {
            self.b.line("#muted(text(size: 8pt)[Rows with one figure per cell have nothing to compare with: the IP-core rows are the thesis's own figures, the input the model builds everything else from.])\n");
        }
    }

    // ----- SW vs HW -----------------------------------------------------------------------

    fn sw_vs_hw(&mut self) {
        self.h1("sw-hw");
        let scenes: Vec<SceneResult> = self
            .r()
            .scenes
            .iter()
            .filter(|s| s.hardware.is_some())
            .cloned()
            .collect();
        if scenes.is_empty() {
            self.b
                .note("No scene ran on the hardware model (it takes spheres and cylinders only).");
        } else {
            self.b.line("The software's diffuse-only gray render (baseline) against the hardware model's frame time, and the emulator's image against the software's (thesis fig. 49, 50).\n");
            let spec = [
                ("Scene", "auto", "left"),
                ("primitives", "auto", "right"),
                ("cycles", "auto", "right"),
                ("hardware", "auto", "right"),
                ("software", "auto", "right"),
                ("95 % interval", "auto", "right"),
                ("speed-up", "auto", "right"),
                ("emulator RMS", "1fr", "left"),
                ("fits", "auto", "left"),
            ];
            let rows: Vec<Vec<String>> = scenes
                .iter()
                .filter_map(|s| s.hardware.as_ref().map(|h| (s, h)))
                .map(|(s, h)| {
                    vec![
                        lit(&s.name),
                        lit(&group(h.primitives)),
                        lit(&group(h.cycles)),
                        lit(&secs(h.seconds)),
                        lit(&secs(h.software_seconds.median)),
                        lit(&interval(&h.software_seconds)),
                        speedup_cell(h.speedup),
                        lit(&format!("{:.1} ({})", h.emulator_rms, h.emulator_band)),
                        if h.fits {
                            "good(\"yes\")".to_string()
                        } else {
                            "bad(\"no\")".to_string()
                        },
                    ]
                })
                .collect();
            self.b.table(&spec, &rows, "7.5pt");
        }
        if !scenes.is_empty() {
            self.chart_or_note("sw-hw-times", 10.0, "software-vs-hardware time");
            self.chart_or_note("hw-speedup", 10.0, "hardware speed-up");
            self.emulator_grid(&scenes);
        }
    }

    fn emulator_grid(&mut self, scenes: &[SceneResult]) {
        const PER_ROW: usize = 6;
        self.b.heading(2, "Emulator and software images");
        let base_dir = self.run.base_dir.clone();
        for chunk in scenes.chunks(PER_ROW) {
            let mut cells = Vec::new();
            cells.extend(
                chunk
                    .iter()
                    .map(|s| format!("text(size: 7.5pt, weight: \"bold\", {})", lit(&s.name))),
            );
            let sw: Vec<String> = chunk
                .iter()
                .map(|s| {
                    let rel = s
                        .hardware
                        .as_ref()
                        .and_then(|h| h.software_image.as_deref());
                    self.b.image_cell(&base_dir, rel, "software image")
                })
                .collect();
            let emu: Vec<String> = chunk
                .iter()
                .map(|s| {
                    let rel = s
                        .hardware
                        .as_ref()
                        .and_then(|h| h.emulator_image.as_deref());
                    self.b.image_cell(&base_dir, rel, "emulator image")
                })
                .collect();
            cells.extend(sw);
            cells.extend(emu);
            let _ = writeln!(
                self.b.out,
                "#block(breakable: false, grid(columns: (auto, {}), column-gutter: 4pt, row-gutter: 3pt, align: center + horizon,\n  {}))\n",
                ["1fr"; PER_ROW].join(", "),
                with_row_labels(
                    &pad_rows(&cells, chunk.len(), PER_ROW),
                    PER_ROW,
                    &["", "software", "emulator"]
                )
                .join(",\n  ")
            );
        }
    }

    // ----- primitive scaling -------------------------------------------------------------

    fn primitive_scaling(&mut self) {
        self.h1("time-vs-primitives");
        self.b.line("Tracing time of the test-bench families against their number of primitives (thesis fig. 47, 48).\n");
        self.chart_or_note("time-vs-primitives", 12.0, "render-time");
        let spec = [
            ("Scene", "auto", "left"),
            ("family", "auto", "left"),
            ("primitives", "auto", "right"),
            ("size", "auto", "right"),
            ("baseline median", "auto", "right"),
            ("95 % interval", "auto", "right"),
            ("fastest variant", "1fr", "left"),
        ];
        let mut scenes: Vec<&SceneResult> = self.r().scenes.iter().collect();
        scenes.sort_by_key(|s| (s.family, s.primitives));
        let rows: Vec<Vec<String>> = scenes
            .iter()
            .map(|s| {
                let base = self.r().baseline(s);
                let fastest = s
                    .variants
                    .iter()
                    .filter(|v| v.time.median > 0.0)
                    .min_by(|a, b| a.time.median.total_cmp(&b.time.median))
                    .map_or_else(
                        || "–".to_string(),
                        |v| format!("{} ({})", v.variant, secs(v.time.median)),
                    );
                vec![
                    lit(&s.name),
                    lit(s.family.name()),
                    lit(&group(s.primitives)),
                    lit(&format!("{}×{}", s.width, s.height)),
                    lit(&base.map_or_else(|| "–".to_string(), |v| secs(v.time.median))),
                    lit(&base.map_or_else(|| "–".to_string(), |v| interval(&v.time))),
                    lit(&fastest),
                ]
            })
            .collect();
        if !rows.is_empty() {
            self.b.caption("Scenes by family and primitive count");
            self.b.table(&spec, &rows, "7.5pt");
        }
    }

    // ----- SPD --------------------------------------------------------------------------

    fn spd(&mut self) {
        let scenes: Vec<SceneResult> = self
            .r()
            .scenes
            .iter()
            .filter(|s| s.spd || s.family == SceneFamily::Spd)
            .cloned()
            .collect();
        self.h1("spd");
        if scenes.is_empty() {
            self.b
                .note("No SPD scene ran in this suite (add them with --scenes ../shared/spd).");
            return;
        }
        self.b.line("Ray and intersection statistics of the Standard Procedural Databases scenes, per variant (exact counts).\n");
        let spec = [
            ("Variant", "auto", "left"),
            ("primary", "1fr", "right"),
            ("hit", "1fr", "right"),
            ("shadow", "1fr", "right"),
            ("blocked", "1fr", "right"),
            ("reflection", "1fr", "right"),
            ("refraction", "1fr", "right"),
            ("tests", "1fr", "right"),
            ("tests/ray", "auto", "right"),
            ("BVH nodes", "1fr", "right"),
        ];
        for scene in &scenes {
            self.b.subheading(&scene.name);
            self.b
                .line(&format!("#muted[{}]\n", txt(&scene_line(scene))));
            let rows: Vec<Vec<String>> = scene
                .variants
                .iter()
                .map(|v| {
                    let c = |k: &str| v.counts.get(k).copied().unwrap_or(0);
                    let rays = c("rays.primary")
                        + c("rays.shadow")
                        + c("rays.reflection")
                        + c("rays.refraction");
                    let tests: u64 = v
                        .counts
                        .iter()
                        .filter(|(k, _)| k.starts_with("tests.") && k.ends_with(".tests"))
                        .map(|(_, n)| *n)
                        .sum();
                    let per_ray = if rays > 0 {
                        format!("{:.1}", tests as f64 / rays as f64)
                    } else {
                        "–".to_string()
                    };
                    vec![
                        lit(&v.variant),
                        lit(&group(c("rays.primary"))),
                        lit(&group(c("rays.primary_hit"))),
                        lit(&group(c("rays.shadow"))),
                        lit(&group(c("rays.shadow_blocked"))),
                        lit(&group(c("rays.reflection"))),
                        lit(&group(c("rays.refraction"))),
                        lit(&group(tests)),
                        lit(&per_ray),
                        lit(&group(c("accel.nodes_visited"))),
                    ]
                })
                .collect();
            if rows.is_empty() {
                self.b.note("No variant ran on this scene.");
            } else {
                self.b.table(&spec, &rows, "7pt");
            }
        }
    }

    // ----- the rest ------------------------------------------------------------------------

    /// Charts no section placed (new kinds of charts are not lost).
    fn other_charts(&mut self) {
        if self.charts.is_empty() {
            return;
        }
        self.b.heading(1, "More charts");
        let ids: Vec<&'static str> = self.charts.keys().copied().collect();
        for id in ids {
            self.chart(id, 11.0);
        }
    }

    fn criterion(&mut self) {
        self.h1("criterion");
        let r = self.r();
        let rows = findings::benchmark_rows(r);
        if rows.is_empty() {
            self.b.note("No benchmark estimates in this run: run cargo bench -p benches (and scripts/instruction-counts.sh for instruction counts) first; the suite picks up target/criterion and target/gungraun, rtprof report --criterion DIR adds them to a saved run.");
            return;
        }
        self.b.line(&format!(
            "#text(size: 9pt, {})\n",
            lit(&format!(
                "Time: criterion's point estimate and its 95 % confidence interval, per iteration{}. Instructions: valgrind's count for the same work (gungraun), the same on every run; they are not time, and the two can disagree.",
                findings::measured_span(r)
            ))
        ));
        let said = findings::instruction_time_disagreements(r);
        if !said.is_empty() {
            let items: Vec<String> = said.iter().map(|f| lit(f)).collect();
            let _ = writeln!(self.b.out, "#list(spacing: 0.7em, {})\n", items.join(", "));
        }
        let spec = [
            ("Benchmark", "1fr", "left"),
            ("mean", "auto", "right"),
            ("interval", "auto", "right"),
            ("median", "auto", "right"),
            ("interval", "auto", "right"),
            ("instructions", "auto", "right"),
        ];
        let dash = || lit("–");
        let table: Vec<Vec<String>> = rows
            .iter()
            .map(|row| {
                let (mean, median) = match row.time {
                    Some(t) => (t.mean.scaled(1e-9), t.median.scaled(1e-9)),
                    None => {
                        let none = Estimate {
                            median: f64::NAN,
                            low: f64::NAN,
                            high: f64::NAN,
                        };
                        (none, none)
                    }
                };
                vec![
                    lit(row.id),
                    lit(&secs(mean.median)),
                    lit(&interval(&mean)),
                    lit(&secs(median.median)),
                    lit(&interval(&median)),
                    row.instructions
                        .map_or_else(dash, |i| lit(&group(i.instructions))),
                ]
            })
            .collect();
        self.b.table(&spec, &table, "8pt");
    }

    fn failures(&mut self) {
        self.h1("failures");
        let failures = &self.r().failures;
        if failures.is_empty() {
            self.b.line("Every scene and variant ran.\n");
        } else {
            self.b
                .line("These parts of the run failed; the rest of the results stand.\n");
            let spec = [("Where", "auto", "left"), ("What happened", "1fr", "left")];
            let rows: Vec<Vec<String>> = failures
                .iter()
                .map(|f| vec![lit(&f.place()), lit(&f.message)])
                .collect();
            self.b.table(&spec, &rows, "8pt");
        }
    }

    fn reproduce(&mut self) {
        self.h1("reproduce");
        let r = self.r();
        self.b
            .line("Check out the commit, build it as the run did and run the command:\n");
        let script = format!("git checkout {}\n{}", r.build.git_commit, r.command);
        let _ = writeln!(
            self.b.out,
            "#block(width: 100%, inset: 6pt, fill: luma(246), stroke: 0.4pt + luma(210), text(size: 8pt, raw(block: true, lang: \"sh\", {})))\n",
            lit(&script)
        );
        let pairs = [
            ("Commit", r.build.git_commit.clone()),
            (
                "rtprof",
                format!("{} ({})", r.build.rtprof_version, r.build.profile),
            ),
            ("Compiler", r.build.rustc.clone()),
            (
                "Results",
                format!("schema {}, created {}", r.schema, r.created),
            ),
            (
                "Files",
                format!("relative to {}", self.run.base_dir.display()),
            ),
        ];
        let cells: Vec<String> = pairs
            .iter()
            .map(|(k, v)| format!("({}, {})", lit(k), lit(v)))
            .collect();
        let _ = writeln!(self.b.out, "#text(size: 9pt, kv({}))\n", cells.join(", "));
    }
}

// ----- cells and numbers -------------------------------------------------------------------

/// Pads a flat list of `rows × n` cells to `rows × width` (empty cells at each row's end).
fn pad_rows(cells: &[String], n: usize, width: usize) -> Vec<String> {
    let mut out = Vec::new();
    for row in cells.chunks(n.max(1)) {
        out.extend(row.iter().cloned());
        out.extend(std::iter::repeat_n("[]".to_string(), width - row.len()));
    }
    out
}

/// Puts a label cell in front of each row of `width` cells.
fn with_row_labels(cells: &[String], width: usize, labels: &[&str]) -> Vec<String> {
    let mut out = Vec::new();
    for (i, row) in cells.chunks(width).enumerate() {
        let label = labels.get(i).copied().unwrap_or("");
        out.push(format!("text(size: 7pt, fill: luma(90), {})", lit(label)));
        out.extend(row.iter().cloned());
    }
    out
}

fn scene_line(scene: &SceneResult) -> String {
    let kinds: Vec<String> = scene
        .primitive_counts
        .iter()
        .filter(|(_, n)| **n > 0)
        .map(|(k, n)| format!("{} {k}", group(*n)))
        .collect();
    format!(
        "{} · {} primitive{}{} · {}×{} · {}{}",
        scene.family,
        group(scene.primitives),
        if scene.primitives == 1 { "" } else { "s" },
        if kinds.is_empty() {
            String::new()
        } else {
            format!(" ({})", kinds.join(", "))
        },
        scene.width,
        scene.height,
        scene.source,
        if scene.spd { " · SPD sampling" } else { "" }
    )
}

fn quality_cells(q: Option<&Quality>) -> (String, String, String, String) {
    match q {
        None => ("–".into(), "reference".into(), "–".into(), "–".into()),
        Some(q) => (
            format!("{:.2}", q.rms),
            q.band.to_string(),
            q.psnr
                .map_or_else(|| "∞".to_string(), |p| format!("{p:.1}")),
            format!("{:.4}", q.ssim),
        ),
    }
}

fn speedup_cell(x: f64) -> String {
    let text = lit(&times(x));
    if x >= 1.05 {
        format!("good({text})")
    } else if x > 0.0 && x <= 0.95 {
        format!("bad({text})")
    } else {
        text
    }
}

/// The counts of `v` that differ from baseline, largest relative change first.
fn count_changes(base: Option<&VariantResult>, v: &VariantResult) -> String {
    let Some(base) = base else {
        return "no baseline".to_string();
    };
    if std::ptr::eq(base, v) {
        return "reference".to_string();
    }
    let keys: BTreeSet<&String> = base.counts.keys().chain(v.counts.keys()).collect();
    let mut changes: Vec<(f64, String)> = keys
        .into_iter()
        .filter_map(|k| {
            let old = base.counts.get(k).copied().unwrap_or(0);
            let new = v.counts.get(k).copied().unwrap_or(0);
            if old == new {
                return None;
            }
            Some(if old == 0 {
                (f64::INFINITY, format!("{k} +{}", group(new)))
            } else {
                let pct = (new as f64 / old as f64 - 1.0) * 100.0;
                (pct.abs(), format!("{k} {}", signed(pct, 0) + " %"))
            })
        })
        .collect();
    if changes.is_empty() {
        return "none".to_string();
    }
    changes.sort_by(|a, b| b.0.total_cmp(&a.0).then_with(|| a.1.cmp(&b.1)));
    let total = changes.len();
    let mut text: Vec<String> = changes.into_iter().take(3).map(|(_, t)| t).collect();
    if total > 3 {
        text.push(format!("{} more", total - 3));
    }
    text.join(", ")
}

/// `x` with its sign (a true minus sign) and `decimals` decimals.
fn signed(x: f64, decimals: usize) -> String {
    let text = format!("{:.*}", decimals, x.abs());
    if x < 0.0 && text.chars().any(|c| c.is_ascii_digit() && c != '0') {
        format!("−{text}")
    } else {
        format!("+{text}")
    }
}

/// Seconds with a unit that keeps three significant digits.
fn secs(s: f64) -> String {
    if !s.is_finite() || s < 0.0 {
        return "–".to_string();
    }
    let (value, unit) = if s == 0.0 {
        (0.0, "s")
    } else if s < 0.9995e-6 {
        (s * 1e9, "ns")
    } else if s < 0.9995e-3 {
        (s * 1e6, "µs")
    } else if s < 0.9995 {
        (s * 1e3, "ms")
    } else {
        (s, "s")
    };
    format!("{} {unit}", sig3(value))
}

/// An interval in the unit of its median.
fn interval(e: &Estimate) -> String {
    let unit_of = secs(e.median);
    let unit = unit_of.rsplit(' ').next().unwrap_or("s");
    let scale = match unit {
        "ns" => 1e9,
        "µs" => 1e6,
        "ms" => 1e3,
        _ => 1.0,
    };
    if !e.low.is_finite() || !e.high.is_finite() {
        return "–".to_string();
    }
    format!("{} – {} {unit}", sig3(e.low * scale), sig3(e.high * scale))
}

fn sig3(v: f64) -> String {
    if v >= 99.95 {
        format!("{v:.0}")
    } else if v >= 9.995 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

/// A speed-up factor.
fn times(x: f64) -> String {
    if x.is_infinite() {
        "∞".to_string()
    } else if !x.is_finite() {
        "–".to_string()
    } else if x >= 100.0 {
        format!("{x:.0}×")
    } else {
        format!("{x:.2}×")
    }
}

/// An integer with thousands separators.
fn group(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

fn usage(used: u64, capacity: u64) -> String {
    if capacity == 0 {
        return group(used);
    }
    format!(
        "{} / {} ({:.0} %)",
        group(used),
        group(capacity),
        used as f64 / capacity as f64 * 100.0
    )
}

fn io_reason(err: &std::io::Error) -> String {
    match err.kind() {
        std::io::ErrorKind::NotFound => "missing".to_string(),
        _ => err.to_string(),
    }
}

/// Reads a PNG under `base_dir`, checking it is one.
/// The PNG at `base_dir/rel` as a thumbnail (see [`crate::gallery`]), or why not.
fn read_png(base_dir: &Path, rel: &str) -> Result<Vec<u8>, String> {
    match gallery::thumbnail(base_dir, rel) {
        Picture::Png(bytes) => Ok(bytes),
        Picture::Unusable(why) => Err(why),
    }
}

// ----- SVG --------------------------------------------------------------------------------

/// The size of an SVG from its root element (viewBox, else width and height).
fn svg_size(svg: &str) -> Option<(f64, f64)> {
    let start = svg.find("<svg")?;
    let end = start + svg[start..].find('>')?;
    let tag = &svg[start..end];
    if let Some(vb) = attr(tag, "viewBox") {
        let nums: Vec<f64> = vb
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
            .filter_map(|s| s.parse().ok())
            .collect();
        if let [_, _, w, h] = nums[..]
            && w > 0.0
            && h > 0.0
        {
            return Some((w, h));
        }
    }
    let w = leading_number(attr(tag, "width")?)?;
    let h = leading_number(attr(tag, "height")?)?;
    (w > 0.0 && h > 0.0).then_some((w, h))
}

/// The value of attribute `name` in a start tag.
fn attr<'t>(tag: &'t str, name: &str) -> Option<&'t str> {
    let mut from = 0;
    while let Some(pos) = tag[from..].find(name) {
        let at = from + pos;
        from = at + name.len();
        let before_ok = tag[..at]
            .chars()
            .next_back()
            .is_some_and(char::is_whitespace);
        let rest = tag[from..].trim_start();
        if !before_ok || !rest.starts_with('=') {
            continue;
        }
        let rest = rest[1..].trim_start();
        let quote = rest.chars().next()?;
        if quote != '"' && quote != '\'' {
            continue;
        }
        let value = &rest[1..];
        return value.find(quote).map(|e| &value[..e]);
    }
    None
}

fn leading_number(s: &str) -> Option<f64> {
    let end = s
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(s.len());
    if s[end..].trim_start().starts_with('%') {
        return None;
    }
    s[..end].parse().ok()
}

/// `width: 100%` unless that makes the figure taller than `max_h_cm`.
fn fit_size(size: Option<(f64, f64)>, width_cm: f64, max_h_cm: f64) -> String {
    match size {
        Some((w, h)) if width_cm * h / w > max_h_cm => format!("height: {max_h_cm}cm"),
        _ => "width: 100%".to_string(),
    }
}

/// A small gray histogram as SVG (log scale), or `None` without bins.
fn histogram_svg(bins: &[u64]) -> Option<String> {
    let max = bins.iter().copied().max()?;
    if max == 0 {
        return None;
    }
    let n = bins.len();
    let (w, h) = (n as f64, n as f64 * 0.32);
    let top = (max as f64).ln_1p();
    let mut d = format!("M0 {h:.1}");
    for (i, &count) in bins.iter().enumerate() {
        let y = h - (count as f64).ln_1p() / top * (h - 1.0);
        let _ = write!(d, " L{i} {y:.1} L{} {y:.1}", i + 1);
    }
    let _ = write!(d, " L{w} {h:.1} Z");
    Some(format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h:.1}\" viewBox=\"0 0 {w} {h:.1}\"><rect width=\"{w}\" height=\"{h:.1}\" fill=\"#fafafa\" stroke=\"#cccccc\" stroke-width=\"1\"/><path d=\"{d}\" fill=\"#555555\"/></svg>"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_escape_everything_typst_reads() {
        assert_eq!(lit(r#"a"b\c"#), r#""a\"b\\c""#);
        assert_eq!(lit("x\ny"), r#""x\ny""#);
        assert_eq!(lit("\u{7}"), r#""\u{7}""#);
        assert_eq!(lit("#set *x* $y$ @z <w>"), "\"#set *x* $y$ @z <w>\"");
    }

    #[test]
    fn svg_sizes() {
        assert_eq!(
            svg_size(r#"<svg width="800" height="400" xmlns="x">"#),
            Some((800.0, 400.0))
        );
        assert_eq!(
            svg_size(r#"<?xml?><svg version="1.1" viewBox="0 0 1200 300" width="100%">"#),
            Some((1200.0, 300.0))
        );
        assert_eq!(
            svg_size(r#"<svg stroke-width="3" width="10px" height="5px">"#),
            Some((10.0, 5.0))
        );
        assert_eq!(svg_size("<svg>"), None);
        assert_eq!(fit_size(Some((100.0, 100.0)), 18.0, 10.0), "height: 10cm");
        assert_eq!(fit_size(Some((200.0, 100.0)), 18.0, 10.0), "width: 100%");
    }

    #[test]
    fn numbers() {
        assert_eq!(group(1_234_567), "1,234,567");
        assert_eq!(group(12), "12");
        assert_eq!(secs(0.0123), "12.3 ms");
        assert_eq!(secs(3.87), "3.87 s");
        assert_eq!(secs(2.5e-5), "25.0 µs");
        assert_eq!(secs(0.009_996), "10.0 ms");
        assert_eq!(secs(0.99996), "1.00 s");
        assert_eq!(times(2.0), "2.00×");
        let e = Estimate {
            median: 0.0123,
            low: 0.012,
            high: 0.0131,
        };
        assert_eq!(interval(&e), "12.0 – 13.1 ms");
    }
}
