//! The HTML report: one self-contained HTML5 file.
//!
//! Everything is inline: CSS, the charts of [`crate::charts`] as SVG, images as
//! `data:image/png;base64,…` URIs read from the run's directory, flamegraph SVGs in
//! `<iframe srcdoc="…">`, and a few lines of JavaScript that sort tables of class
//! `sortable` when a header is clicked. The file makes no network reference: no `src` or
//! `href` points outside the document.
//!
//! The detailed sections show the first run; with several runs a comparison section
//! sets every scene × variant of all runs side by side. Each section names its thesis
//! counterpart, and an empty section says why it is empty. A missing file gives a
//! visible note, never an error.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use crate::Run;
use crate::charts::{self, Chart};
use crate::findings::{
    benchmark_rows, headline_findings, instruction_time_disagreements, measured_span, repeats_text,
};
use crate::gallery::{self, Picture};
use crate::results::{
    Band, Estimate, HwColumn, HwRow, HwRowKind, Profile, Results, SceneFamily, SceneResult,
    VariantName, VariantResult,
};

/// A report that cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum HtmlError {
    #[error("no runs to report: give at least one results file")]
    NoRuns,
}

/// The report's sections: id and heading, in order (the comparison only with several
/// runs).
pub const SECTIONS: [(&str, &str); 16] = [
    ("summary", "Summary"),
    ("profile", "Flat profile and call graph"),
    ("profile-charts", "Calls and self time per function"),
    ("flamegraphs", "Flamegraphs"),
    (
        "amdahl",
        "Amdahl's law: what speeding up a function would give",
    ),
    ("variants", "Optimization variants"),
    ("images", "Images, difference heat maps and histograms"),
    ("hardware-tables", "Hardware model: tables 7 and 8"),
    ("device-utilization", "Device utilization"),
    ("sw-hw", "Software against hardware"),
    ("time-vs-primitives", "Render time against primitive count"),
    ("spd", "SPD scene statistics"),
    ("criterion", "Micro-benchmarks: time and instructions"),
    ("failures", "Failures"),
    ("reproduce", "How to reproduce"),
    ("comparison", "Side-by-side comparison of runs"),
];

/// Counters shown as deltas against baseline in the variants tables: key and header.
const MAIN_COUNTERS: [(&str, &str); 5] = [
    ("ops.dot", "dot"),
    ("ops.sqrt", "sqrt"),
    ("ops.normalize", "normalize"),
    ("calls.intersect", "intersect calls"),
    ("rays.primary", "primary rays"),
];

/// Renders the report of `runs` (the first is shown in detail).
pub fn render_html(runs: &[Run]) -> Result<String, HtmlError> {
    let main = runs.first().ok_or(HtmlError::NoRuns)?;
    let r = &main.results;
    let charts = charts::all(r);
    let mut page = Page {
        out: String::with_capacity(1 << 20),
    };
    page.head(runs);
    page.nav(runs.len() > 1);
    page.summary(runs);
    page.profile(main);
    page.profile_charts(r, &charts);
    page.flamegraphs(main);
    page.amdahl(r);
    page.variants(r, &charts);
    page.images(main);
    page.hardware_tables(r);
    page.device_utilization(r, &charts);
    page.sw_hw(main, &charts);
    page.time_vs_primitives(r, &charts);
    page.spd(r);
    page.criterion(r);
    page.failures(r);
    page.reproduce(runs);
    if runs.len() > 1 {
        page.comparison(runs);
    }
    page.foot();
    Ok(page.out)
}

/// Escapes text for HTML content and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

/// Standard base64 (RFC 4648, with padding).
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(char::from(ALPHABET[((n >> (18 - 6 * i)) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Seconds with a unit that keeps 3 significant digits.
fn seconds(s: f64) -> String {
    if !s.is_finite() {
        "–".to_string()
    } else if s >= 1.0 {
        format!("{s:.3} s")
    } else if s >= 1e-3 {
        format!("{:.3} ms", s * 1e3)
    } else {
        format!("{:.3} µs", s * 1e6)
    }
}

/// The unit that shows `s` seconds with 3 significant digits: (name, scale).
fn time_unit(s: f64) -> (&'static str, f64) {
    if s.abs() >= 1.0 {
        ("s", 1.0)
    } else if s.abs() >= 1e-3 {
        ("ms", 1e3)
    } else if s.abs() >= 1e-6 {
        ("µs", 1e6)
    } else {
        ("ns", 1e9)
    }
}

/// "8.217 ms [8.074 – 8.439]": the interval in the median's unit.
fn estimate_text(e: &Estimate) -> String {
    if !e.median.is_finite() {
        return "–".to_string();
    }
    let (unit, scale) = time_unit(e.median);
    format!(
        "{} {unit} <span class=\"interval\">[{} – {}]</span>",
        number(e.median * scale, 3),
        number(e.low * scale, 3),
        number(e.high * scale, 3)
    )
}

/// "1 sphere", "2 spheres" from a plural kind name.
fn kind_count(n: u64, kind: &str) -> String {
    if n == 1 {
        format!("1 {}", kind.strip_suffix('s').unwrap_or(kind))
    } else {
        format!("{n} {kind}")
    }
}

fn number(v: f64, decimals: usize) -> String {
    if v.is_finite() {
        format!("{v:.decimals$}")
    } else {
        "–".to_string()
    }
}

/// An integer with thin-space thousands separators.
fn count(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push('\u{2009}');
        }
        out.push(c);
    }
    out
}

fn percent_of(used: u64, capacity: u64) -> f64 {
    if capacity == 0 {
        f64::NAN
    } else {
        used as f64 / capacity as f64 * 100.0
    }
}

/// Variant names separated by commas.
pub(crate) fn join_names(names: &[crate::results::VariantName]) -> String {
    names
        .iter()
        .map(|n| n.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// CSS class of an RMS band.
fn band_class(band: Band) -> &'static str {
    match band {
        Band::VisuallyIdentical => "band-identical",
        Band::Similar => "band-similar",
        Band::NotableChanges => "band-notable",
        Band::Different => "band-different",
    }
}

/// CSS class of a model-vs-thesis error.
fn error_class(error: Option<f64>) -> &'static str {
    match error.map(f64::abs) {
        Some(e) if e.is_finite() && e < 5.0 => "err0",
        Some(e) if e.is_finite() && e < 15.0 => "err1",
        Some(e) if e.is_finite() && e < 50.0 => "err2",
        Some(e) if e.is_finite() => "err3",
        _ => "errn",
    }
}

/// What a file read gave.
enum FileRead {
    Bytes(Vec<u8>),
    Missing(String),
}

fn read_file(base: &Path, rel: &str) -> FileRead {
    match std::fs::read(base.join(rel)) {
        Ok(bytes) => FileRead::Bytes(bytes),
        Err(e) => FileRead::Missing(e.kind().to_string()),
    }
}

/// A note for a file that cannot be shown.
fn missing_note(what: &str, rel: &str, reason: &str) -> String {
    format!(
        "<div class=\"missing\">{} missing: {} <span class=\"reason\">({})</span></div>",
        escape(what),
        escape(rel),
        escape(reason)
    )
}

/// An `<img>` with the PNG at `base/rel` as a data URI (a thumbnail, see
/// [`crate::gallery`]), or a note. `size` (width, height) gives the box its aspect
/// ratio before the image loads.
fn embed_image(base: &Path, rel: Option<&str>, alt: &str, size: (u32, u32)) -> String {
    let Some(rel) = rel else {
        return format!(
            "<div class=\"missing\">no image recorded for {}</div>",
            escape(alt)
        );
    };
    match gallery::thumbnail(base, rel) {
        Picture::Png(bytes) => {
            let aspect = if size.0 > 0 && size.1 > 0 {
                format!(" style=\"aspect-ratio: {} / {}\"", size.0, size.1)
            } else {
                String::new()
            };
            format!(
                "<img src=\"data:image/png;base64,{}\" alt=\"{}\" title=\"{} (full size next to this report)\"{aspect}>",
                base64(&bytes),
                escape(alt),
                escape(rel)
            )
        }
        Picture::Unusable(reason) => missing_note("image", rel, &reason),
    }
}

/// A text file in a `<pre>`, or a note.
fn embed_text(base: &Path, rel: &str, what: &str) -> String {
    match read_file(base, rel) {
        FileRead::Bytes(bytes) => format!(
            "<pre class=\"text\">{}</pre>",
            escape(&String::from_utf8_lossy(&bytes))
        ),
        FileRead::Missing(reason) => missing_note(what, rel, &reason),
    }
}

/// The value of attribute `name` in the first `<svg …>` tag of `svg`.
fn svg_attribute(svg: &str, name: &str) -> Option<f64> {
    let start = svg.find("<svg")?;
    let tag = &svg[start..start + svg[start..].find('>')?];
    let key = format!(" {name}=\"");
    let at = tag.find(&key)? + key.len();
    let value = &tag[at..at + tag[at..].find('"')?];
    value
        .trim_end_matches("px")
        .parse()
        .ok()
        .filter(|v: &f64| v.is_finite() && *v > 0.0)
}

/// The SVG without its XML prologue, doctype and the comments before its first script
/// (they name web addresses and mean nothing inside an HTML document).
fn strip_svg_prologue(svg: &str) -> String {
    let body = svg.find("<svg").map_or(svg, |i| &svg[i..]);
    let script = body.find("<script").unwrap_or(body.len());
    let (head, tail) = body.split_at(script);
    let mut out = String::with_capacity(body.len());
    let mut rest = head;
    while let Some(open) = rest.find("<!--") {
        out.push_str(&rest[..open]);
        match rest[open..].find("-->") {
            Some(close) => rest = &rest[open + close + 3..],
            None => {
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out.push_str(tail);
    without_xmlns(&out)
}

/// The SVG with the namespace declarations of its root tag removed: an HTML parser
/// places inline `<svg>` in the SVG namespace by itself, and the declarations are web
/// addresses a reader of the report should never see as references.
fn without_xmlns(svg: &str) -> String {
    let Some(start) = svg.find("<svg") else {
        return svg.to_string();
    };
    let Some(len) = svg[start..].find('>') else {
        return svg.to_string();
    };
    let tag = &svg[start..start + len];
    let mut cleaned = String::with_capacity(tag.len());
    let mut rest = tag;
    while let Some(at) = rest.find(" xmlns") {
        cleaned.push_str(&rest[..at]);
        let attribute = &rest[at + 1..];
        // Skip `xmlns[:prefix]="value"` (or single quotes).
        let end = attribute
            .find('=')
            .and_then(|eq| {
                let quote = attribute[eq + 1..].chars().next()?;
                if quote != '"' && quote != '\'' {
                    return None;
                }
                let close = attribute[eq + 2..].find(quote)?;
                Some(eq + 2 + close + 1)
            })
            .unwrap_or(attribute.len());
        rest = &attribute[end..];
    }
    cleaned.push_str(rest);
    format!("{}{cleaned}{}", &svg[..start], &svg[start + len..])
}

/// A flamegraph SVG in an `<iframe srcdoc>` (its own scripts run sandboxed, its size
/// follows the SVG's aspect ratio), or a note.
fn embed_flamegraph(base: &Path, rel: &str, title: &str) -> String {
    match read_file(base, rel) {
        FileRead::Bytes(bytes) => {
            let svg = String::from_utf8_lossy(&bytes);
            let aspect = match (svg_attribute(&svg, "width"), svg_attribute(&svg, "height")) {
                (Some(w), Some(h)) => format!(" style=\"aspect-ratio: {w} / {h}\""),
                _ => String::new(),
            };
            let document = format!(
                "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><style>html,body{{margin:0;overflow:hidden}}svg{{display:block;width:100%;height:auto}}</style></head><body>{}</body></html>",
                strip_svg_prologue(&svg)
            );
            format!(
                "<iframe class=\"flame\" sandbox=\"allow-scripts\" title=\"{}\"{aspect} srcdoc=\"{}\"></iframe>",
                escape(title),
                escape(&document)
            )
        }
        FileRead::Missing(reason) => missing_note("flamegraph", rel, &reason),
    }
}

fn chart_figure(chart: &Chart) -> String {
    format!(
        "<figure class=\"chart\" id=\"chart-{}\">{}<figcaption><b>{}.</b> {}</figcaption></figure>\n",
        chart.id,
        without_xmlns(&chart.svg),
        escape(&chart.title),
        escape(&chart.caption)
    )
}

fn find_chart<'a>(charts: &'a [Chart], id: &str) -> Option<&'a Chart> {
    charts.iter().find(|c| c.id == id)
}

fn empty_note(text: &str) -> String {
    format!("<p class=\"empty\">{}</p>\n", escape(text))
}

struct Page {
    out: String,
}

impl Page {
    fn push(&mut self, s: &str) {
        self.out.push_str(s);
    }

    fn section_start(&mut self, id: &str, thesis: Option<&str>) {
        let heading = SECTIONS.iter().find(|s| s.0 == id).map_or(id, |s| s.1);
        self.push(&format!(
            "<section id=\"{id}\">\n<h2>{}</h2>\n",
            escape(heading)
        ));
        if let Some(t) = thesis {
            self.push(&format!("<p class=\"thesis\">Thesis: {}</p>\n", escape(t)));
        }
    }

    fn section_end(&mut self) {
        self.push("</section>\n");
    }

    fn head(&mut self, runs: &[Run]) {
        let main = &runs[0];
        self.push(&format!(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>rtprof report: {} ({})</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<header><h1>rtprof report</h1><p class=\"sub\">{} · {} · {} · {}</p></header>\n",
            escape(&main.results.suite.name),
            escape(&main.label),
            escape(&main.label),
            escape(&main.results.machine.cpu_model),
            escape(&main.results.created),
            if runs.len() > 1 {
                format!("{} runs compared", runs.len())
            } else {
                "one run".to_string()
            }
        ));
    }

    fn nav(&mut self, comparison: bool) {
        self.push("<nav><ol>");
        for (id, heading) in SECTIONS {
            if id == "comparison" && !comparison {
                continue;
            }
            self.push(&format!(
                "<li><a href=\"#{id}\">{}</a></li>",
                escape(heading)
            ));
        }
        self.push("</ol></nav>\n<main>\n");
    }

    fn summary(&mut self, runs: &[Run]) {
        let main = &runs[0];
        let r = &main.results;
        self.section_start(
            "summary",
            Some("the GUI's report (ch. 7): what ran, on what, and what it found"),
        );
        if runs.len() > 1 {
            self.push(&format!(
                "<p>The sections below show run <b>{}</b> in detail; <a href=\"#comparison\">the comparison</a> sets all {} runs side by side.</p>\n",
                escape(&main.label),
                runs.len()
            ));
        }
        let findings = headline_findings(r);
        self.push("<h3>Headline findings</h3>\n");
        if findings.is_empty() {
            self.push(&empty_note(
                "No findings: the run has no profile, variants, hardware model or failures to speak of.",
            ));
        } else {
            self.push("<ul class=\"findings\">");
            for f in &findings {
                self.push(&format!("<li>{}</li>", escape(f)));
            }
            self.push("</ul>\n");
        }
        let m = &r.machine;
        let b = &r.build;
        let s = &r.suite;
        self.push("<table class=\"kv\">");
        let rows = [
            ("Run", main.label.clone()),
            ("Created", r.created.clone()),
            (
                "Machine",
                format!(
                    "{} · {} logical CPUs · {} · host {}",
                    m.cpu_model, m.cores, m.os, m.hostname
                ),
            ),
            (
                "Build",
                format!(
                    "rtprof {} · {} · commit {} · {} profile",
                    b.rtprof_version, b.rustc, b.git_commit, b.profile
                ),
            ),
            (
                "Suite",
                format!(
                    "{}{} · {} · {} threads · {} s wall time",
                    s.name,
                    if s.quick { " (quick)" } else { "" },
                    repeats_text(s),
                    s.threads,
                    number(s.wall_seconds, 1)
                ),
            ),
            ("Variants", join_names(&s.variants)),
            ("Schema", r.schema.clone()),
        ];
        for (k, v) in rows {
            self.push(&format!("<tr><th>{k}</th><td>{}</td></tr>", escape(&v)));
        }
        self.push("</table>\n");
        self.push(&format!("<h3>Scenes ({})</h3>\n", r.scenes.len()));
        if r.scenes.is_empty() {
            self.push(&empty_note("No scene ran (see Failures)."));
        } else {
            self.push("<table class=\"sortable\"><thead><tr><th>scene</th><th>family</th><th>primitives</th><th>kinds</th><th>size</th><th>variants run</th><th>baseline time</th><th>source</th></tr></thead><tbody>");
            for scene in &r.scenes {
                let kinds = scene
                    .primitive_counts
                    .iter()
                    .filter(|(_, n)| **n > 0)
                    .map(|(k, n)| kind_count(*n, k))
                    .collect::<Vec<_>>()
                    .join(", ");
                let base = r.baseline(scene);
                self.push(&format!(
                    "<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td><td>{}</td><td>{}x{}{}</td><td class=\"num\">{}</td><td class=\"num\" data-v=\"{}\">{}</td><td>{}</td></tr>",
                    escape(&scene.name),
                    escape(scene.family.name()),
                    scene.primitives,
                    escape(&kinds),
                    scene.width,
                    scene.height,
                    if scene.spd { " (SPD sampling)" } else { "" },
                    scene.variants.len(),
                    base.map_or(f64::NAN, |b| b.time.median),
                    base.map_or_else(|| "no baseline".to_string(), |b| seconds(b.time.median)),
                    escape(&scene.source)
                ));
            }
            self.push("</tbody></table>\n");
        }
        if runs.len() > 1 {
            self.push("<h3>Runs</h3>\n<table><thead><tr><th>run</th><th>host</th><th>CPU</th><th>cores</th><th>commit</th><th>created</th><th>scenes</th></tr></thead><tbody>");
            for run in runs {
                let r = &run.results;
                self.push(&format!(
                    "<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{}</td><td><code>{}</code></td><td>{}</td><td class=\"num\">{}</td></tr>",
                    escape(&run.label),
                    escape(&r.machine.hostname),
                    escape(&r.machine.cpu_model),
                    r.machine.cores,
                    escape(&r.build.git_commit),
                    escape(&r.created),
                    r.scenes.len()
                ));
            }
            self.push("</tbody></table>\n");
        }
        self.section_end();
    }

    fn flat_table(&mut self, profile: &Profile) {
        self.push(&format!(
            "<p>{} samples at {} s each ({} s sampled). Calls are exact, from the counters; blank where the function is not counted.</p>\n",
            profile.samples,
            charts::format_number(profile.seconds_per_sample),
            number(profile.samples as f64 * profile.seconds_per_sample, 2)
        ));
        if profile.flat.is_empty() {
            self.push(&empty_note(
                "The flat profile has no rows (no samples landed in the tracer).",
            ));
            return;
        }
        let mut rows: Vec<_> = profile.flat.iter().collect();
        rows.sort_by(|a, b| b.self_seconds.total_cmp(&a.self_seconds));
        self.push("<table class=\"sortable\"><thead><tr><th>% time</th><th>cumulative s</th><th>self s</th><th>calls</th><th>self ns/call</th><th>total ns/call</th><th>name</th></tr></thead><tbody>");
        let mut cumulative = 0.0;
        for row in rows {
            if row.self_seconds.is_finite() {
                cumulative += row.self_seconds;
            }
            let per_call = |s: f64| match row.calls {
                Some(c) if c > 0 && s.is_finite() => s / c as f64 * 1e9,
                _ => f64::NAN,
            };
            let (self_ns, total_ns) = (per_call(row.self_seconds), per_call(row.total_seconds));
            self.push(&format!(
                "<tr><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\" data-v=\"{}\">{}</td><td class=\"num\" data-v=\"{self_ns}\">{}</td><td class=\"num\" data-v=\"{total_ns}\">{}</td><td><code title=\"{}\">{}</code></td></tr>",
                number(row.percent, 2),
                number(cumulative, 3),
                number(row.self_seconds, 3),
                row.calls.map_or(-1.0, |c| c as f64),
                row.calls.map_or_else(String::new, count),
                if self_ns.is_finite() { number(self_ns, 2) } else { String::new() },
                if total_ns.is_finite() { number(total_ns, 2) } else { String::new() },
                escape(&row.name),
                escape(&row.name)
            ));
        }
        self.push("</tbody></table>\n");
    }

    fn profile(&mut self, run: &Run) {
        let r = &run.results;
        self.section_start(
            "profile",
            Some("table 6 (gprof flat profile of SPD rings, 640x480, Core i5-4570) and fig. 53 (call tree)"),
        );
        let Some(p) = &r.profile else {
            self.push(&empty_note(
                "No profile in this run: the suite ran without profiling, or the profile failed (see Failures).",
            ));
            self.section_end();
            return;
        };
        self.push(&format!(
            "<p>Scene <b>{}</b> at {}x{}, the heaviest of the run.</p>\n",
            escape(&p.scene),
            p.width,
            p.height
        ));
        for profile in std::iter::once(&p.baseline).chain(p.best.iter()) {
            self.push(&format!(
                "<h3>Flat profile: {}</h3>\n",
                escape(&profile.variant)
            ));
            self.flat_table(profile);
            self.push(&format!(
                "<details><summary>gprof-layout flat profile text ({})</summary>{}</details>\n",
                escape(&profile.flat_text),
                embed_text(&run.base_dir, &profile.flat_text, "flat profile text")
            ));
            self.push(&format!(
                "<h4>Call graph: {} (fig. 53)</h4>\n{}",
                escape(&profile.variant),
                embed_text(&run.base_dir, &profile.callgraph_text, "call graph text")
            ));
        }
        if p.best.is_none() {
            self.push(&empty_note(
                "Only the baseline was profiled (no best variant).",
            ));
        }
        self.section_end();
    }

    fn profile_charts(&mut self, r: &Results, charts: &[Chart]) {
        self.section_start(
            "profile-charts",
            Some("fig. 51 (calls per function) and fig. 52 (self seconds per function)"),
        );
        let mut any = false;
        for id in ["calls", "self-seconds"] {
            if let Some(c) = find_chart(charts, id) {
                self.push(&chart_figure(c));
                any = true;
            }
        }
        if !any {
            self.push(&empty_note(if r.profile.is_none() {
                "No profile in this run, so no calls or self-time charts."
            } else {
                "The profile has no counted calls or self time to chart."
            }));
        }
        self.section_end();
    }

    fn flamegraphs(&mut self, run: &Run) {
        self.section_start(
            "flamegraphs",
            Some("no counterpart (the thesis used gprof's call tree, fig. 53); hover a frame for its name and share, click to zoom"),
        );
        let Some(p) = &run.results.profile else {
            self.push(&empty_note("No profile in this run, so no flamegraphs."));
            self.section_end();
            return;
        };
        for profile in std::iter::once(&p.baseline).chain(p.best.iter()) {
            self.push(&format!(
                "<h3>{} · {}</h3>\n{}\n",
                escape(&p.scene),
                escape(&profile.variant),
                embed_flamegraph(
                    &run.base_dir,
                    &profile.flame_svg,
                    &format!("flamegraph of {} ({})", p.scene, profile.variant)
                )
            ));
        }
        self.push("<h3>Differential flamegraph</h3>\n");
        match (&p.diff_flame_svg, &p.best) {
            (Some(diff), Some(best)) => {
                self.push(&format!(
                    "<p>Frames of the {} profile, coloured by the change from baseline to {}: red grew, blue shrank.</p>\n{}\n",
                    escape(&best.variant),
                    escape(&best.variant),
                    embed_flamegraph(&run.base_dir, diff, "differential flamegraph")
                ));
            }
            (Some(diff), None) => self.push(&embed_flamegraph(
                &run.base_dir,
                diff,
                "differential flamegraph",
            )),
            (None, _) => self.push(&empty_note(
                "No differential flamegraph: only one variant was profiled.",
            )),
        }
        self.section_end();
    }

    fn amdahl(&mut self, r: &Results) {
        self.section_start(
            "amdahl",
            Some("ch. 8.1's conclusion that the intersection test is the bottleneck, made quantitative"),
        );
        let Some(p) = &r.profile else {
            self.push(&empty_note("No profile in this run, so no Amdahl table."));
            self.section_end();
            return;
        };
        for profile in std::iter::once(&p.baseline).chain(p.best.iter()) {
            self.push(&format!(
                "<h3>{} · {}</h3>\n",
                escape(&p.scene),
                escape(&profile.variant)
            ));
            if profile.amdahl.is_empty() {
                self.push(&empty_note("The profile has no Amdahl rows."));
                continue;
            }
            self.push("<table class=\"sortable\"><thead><tr><th>function</th><th>share of time</th><th>whole program if 2× faster</th><th>if 10× faster</th><th>if free (limit)</th></tr></thead><tbody>");
            for a in &profile.amdahl {
                self.push(&format!(
                    "<tr><td><code title=\"{}\">{}</code></td><td class=\"num\" data-v=\"{}\">{} %</td><td class=\"num\">{}×</td><td class=\"num\">{}×</td><td class=\"num\" data-v=\"{}\">{}</td></tr>",
                    escape(&a.name),
                    escape(&charts::short_name(&a.name)),
                    a.fraction,
                    number(a.fraction * 100.0, 1),
                    number(a.speedup_2x, 3),
                    number(a.speedup_10x, 3),
                    if a.speedup_limit.is_finite() { a.speedup_limit } else { 1e300 },
                    if a.speedup_limit.is_finite() {
                        format!("{}×", number(a.speedup_limit, 3))
                    } else {
                        "∞".to_string()
                    }
                ));
            }
            self.push("</tbody></table>\n");
        }
        self.section_end();
    }

    fn variant_row(&mut self, v: &VariantResult, base: Option<&VariantResult>) {
        let q = v.quality.as_ref();
        let quality_cells = match q {
            Some(q) => format!(
                "<td class=\"num\" data-v=\"{}\">{}</td><td class=\"{}\">{}</td><td class=\"num\" data-v=\"{}\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>",
                q.rms,
                number(q.rms, 2),
                band_class(q.band),
                escape(q.band.name()),
                q.psnr.unwrap_or(1e300),
                q.psnr
                    .map_or_else(|| "∞".to_string(), |p| format!("{} dB", number(p, 1))),
                number(q.ssim, 4),
                q.max_abs_diff
            ),
            None if v.variant.is_reference() => {
                "<td colspan=\"5\" class=\"muted\">reference image</td>".to_string()
            }
            None => "<td colspan=\"5\" class=\"muted\">no image metrics</td>".to_string(),
        };
        let mut counter_cells = String::new();
        for (key, _) in MAIN_COUNTERS {
            let value = v.counts.get(key).copied();
            let reference = base.and_then(|b| b.counts.get(key).copied());
            let cell = match (value, reference) {
                (Some(n), _) if v.variant.is_reference() => {
                    format!("<td class=\"num\" data-v=\"{n}\">{}</td>", count(n))
                }
                (Some(n), Some(b)) if n == b => {
                    format!(
                        "<td class=\"num same\" data-v=\"0\" title=\"{}\">=</td>",
                        count(n)
                    )
                }
                (Some(n), Some(b)) if b > 0 => {
                    let delta = (n as f64 - b as f64) / b as f64 * 100.0;
                    format!(
                        "<td class=\"num {}\" data-v=\"{delta}\" title=\"{} (baseline {})\">{:+.1} %</td>",
                        if delta < 0.0 { "fewer" } else { "more" },
                        count(n),
                        count(b),
                        delta
                    )
                }
                (Some(n), _) => format!("<td class=\"num\" data-v=\"{n}\">{}</td>", count(n)),
                (None, _) => "<td class=\"muted\">–</td>".to_string(),
            };
            counter_cells.push_str(&cell);
        }
        self.push(&format!(
            "<tr><td>{}</td><td class=\"num\" data-v=\"{}\">{}</td><td class=\"num\" data-v=\"{}\">{}</td>{quality_cells}{counter_cells}</tr>",
            escape(&v.variant),
            v.time.median,
            estimate_text(&v.time),
            v.speedup.unwrap_or(f64::NAN),
            if let Some(s) = v.speedup.filter(|s| s.is_finite()) {
                format!("{}×", number(s, 2))
            } else {
                "–".to_string()
            }
        ));
    }

    fn variants(&mut self, r: &Results, charts: &[Chart]) {
        self.section_start(
            "variants",
            Some("ch. 8.3's proposed optimizations, each measured on every scene (the thesis tried them on one sphere)"),
        );
        if r.scenes.iter().all(|s| s.variants.is_empty()) {
            self.push(&empty_note("No scene has a variant result (see Failures)."));
            self.section_end();
            return;
        }
        self.push("<p>Time: median of the timed repeats with its 95 % bootstrap interval. Speed-up: baseline median / variant median. RMS, PSNR, SSIM: the image against baseline (PSNR ∞: identical); the band is the thesis's table 2. Count columns: baseline's exact count, and each variant's change from it.</p>\n");
        if let Some(c) = find_chart(charts, "quality-speed") {
            self.push(&chart_figure(c));
        }
        for scene in &r.scenes {
            self.push(&format!(
                "<h3 id=\"variants-{}\">{} <span class=\"muted\">({}, {} primitive{}, {}x{})</span></h3>\n",
                escape(&slug(&scene.name)),
                escape(&scene.name),
                escape(scene.family.name()),
                scene.primitives,
                if scene.primitives == 1 { "" } else { "s" },
                scene.width,
                scene.height
            ));
            if scene.variants.is_empty() {
                self.push(&empty_note("No variant of this scene ran (see Failures)."));
                continue;
            }
            let base = r.baseline(scene);
            let mut header = String::from(
                "<table class=\"sortable variants\"><thead><tr><th>variant</th><th>time [95 % interval]</th><th>speed-up</th><th>RMS</th><th>band</th><th>PSNR</th><th>SSIM</th><th>max diff</th>",
            );
            for (_, name) in MAIN_COUNTERS {
                header.push_str(&format!("<th>{name}</th>"));
            }
            header.push_str("</tr></thead><tbody>");
            self.push(&header);
            for v in &scene.variants {
                self.variant_row(v, base);
            }
            self.push("</tbody></table>\n");
            if base.is_none() {
                self.push(&empty_note(
                    "Baseline did not run on this scene: no speed-ups or count deltas to compare.",
                ));
            }
        }
        self.section_end();
    }

    fn images(&mut self, run: &Run) {
        let r = &run.results;
        self.section_start(
            "images",
            Some("fig. 35-37 (gray histograms) and fig. 42-45 (image comparisons)"),
        );
        if r.scenes.iter().all(|s| s.variants.is_empty()) {
            self.push(&empty_note("No images: no scene produced a result."));
            self.section_end();
            return;
        }
        self.push("<p>For each scene: one column per variant, its image above its difference heat map against baseline (the brighter, the larger the difference), then the gray-level histograms.</p>\n");
        let omitted = gallery::omitted_scenes(r);
        if !omitted.is_empty() {
            self.push(&format!(
                "<p class=\"muted\">Shown: the scene with the largest difference and the largest scenes. The images of the other {} ({}) are in <code>images/</code> next to this report; the variants table has their metrics.</p>\n",
                omitted.len(),
                escape(&omitted.join(", "))
            ));
        }
        for scene in gallery::showcase_scenes(r) {
            let size = (scene.width, scene.height);
            self.push(&format!(
                "<h3>{}</h3>\n<div class=\"scene-images\" style=\"grid-template-columns: repeat({}, minmax(0, 1fr))\">",
                escape(&scene.name),
                scene.variants.len().max(1)
            ));
            for v in &scene.variants {
                let label = match &v.quality {
                    Some(q) => format!("{} · RMS {} ({})", v.variant, number(q.rms, 1), q.band),
                    None => v.variant.to_string(),
                };
                self.push(&format!(
                    "<figure class=\"tile\">{}<figcaption>{}</figcaption></figure>",
                    embed_image(
                        &run.base_dir,
                        v.image.as_deref(),
                        &format!("{} {}", scene.name, v.variant),
                        size
                    ),
                    escape(&label)
                ));
            }
            for v in &scene.variants {
                if v.variant.is_reference() {
                    self.push("<div class=\"tile reference\">reference image: no heat map</div>");
                    continue;
                }
                let heat = match &v.heat_map {
                    Some(path) => embed_image(
                        &run.base_dir,
                        Some(path),
                        &format!("{} {} difference", scene.name, v.variant),
                        size,
                    ),
                    None => "<div class=\"missing\">no heat map recorded</div>".to_string(),
                };
                self.push(&format!(
                    "<figure class=\"tile\">{heat}<figcaption>{} − baseline</figcaption></figure>",
                    escape(&v.variant)
                ));
            }
            self.push("</div>\n");
            match charts::scene_histograms(r, scene) {
                Some(c) => self.push(&chart_figure(&c)),
                None => self.push(&empty_note(
                    "No histogram: baseline has no gray histogram for this scene.",
                )),
            }
        }
        self.section_end();
    }

    fn hw_table(&mut self, rows: &[HwRow]) {
        self.push("<table class=\"hw sortable\"><thead><tr><th>name</th><th>kind</th>");
        for c in HwColumn::ALL.map(HwColumn::label) {
            self.push(&format!(
                "<th>{c}<br><span class=\"muted\">model / thesis (error)</span></th>"
            ));
        }
        self.push("</tr></thead><tbody>");
        for row in rows {
            self.push(&format!(
                "<tr><td><code>{}</code></td><td>{}</td>",
                escape(&row.name),
                escape(row.kind.name())
            ));
            for (c, model) in row.model.columns() {
                let error = row.error_pct.as_ref().and_then(|e| e.get(c));
                let thesis = row.thesis.map(|t| t.get(c));
                let detail = match (thesis, error) {
                    (Some(t), Some(e)) => format!(
                        " <span class=\"thesis-v\">/ {} ({:+.1} %)</span>",
                        count(t),
                        e
                    ),
                    (Some(t), None) => {
                        format!(" <span class=\"thesis-v\">/ {} (—)</span>", count(t))
                    }
                    // The IP-core rows are table 7's own figures: the model's input.
                    (None, _) if row.kind == HwRowKind::IpCore => {
                        " <span class=\"thesis-v\">(thesis input)</span>".to_string()
                    }
                    (None, _) => " <span class=\"thesis-v\">(no thesis figure)</span>".to_string(),
                };
                self.push(&format!(
                    "<td class=\"num {}\" data-v=\"{}\">{}{detail}</td>",
                    error_class(error),
                    model,
                    count(model)
                ));
            }
            self.push("</tr>");
        }
        self.push("</tbody></table>\n");
    }

    fn hardware_tables(&mut self, r: &Results) {
        self.section_start(
            "hardware-tables",
            Some("table 7 (per operation) and table 8 (per block), Quartus figures on the Cyclone IV EP4CE115"),
        );
        let Some(hw) = &r.hardware else {
            self.push(&empty_note("No hardware model in this run."));
            self.section_end();
            return;
        };
        self.push(&format!(
            "<p>Operator library: {}. Each cell: the model's figure / the thesis's (signed error). Cell colour by |error|: <span class=\"err0 chip\">&lt; 5 %</span> <span class=\"err1 chip\">&lt; 15 %</span> <span class=\"err2 chip\">&lt; 50 %</span> <span class=\"err3 chip\">≥ 50 %</span> <span class=\"errn chip\">no error (thesis 0)</span>.</p>\n",
            escape(&hw.family)
        ));
        self.push("<h3>Table 7: operations</h3>\n");
        if hw.ops.is_empty() {
            self.push(&empty_note("The model produced no operation rows."));
        } else {
            self.hw_table(&hw.ops);
        }
        self.push("<h3>Table 8: blocks</h3>\n");
        if hw.blocks.is_empty() {
            self.push(&empty_note("The model produced no block rows."));
        } else {
            self.hw_table(&hw.blocks);
        }
        self.section_end();
    }

    fn device_utilization(&mut self, r: &Results, charts: &[Chart]) {
        self.section_start(
            "device-utilization",
            Some("ch. 8.2: about 100,000 LEs (78 %), all 532 multipliers, 2,412 Kbits of memory, 2 PLLs on the EP4CE115"),
        );
        let devices = r
            .hardware
            .as_ref()
            .map(|h| h.devices.as_slice())
            .unwrap_or(&[]);
        if devices.is_empty() {
            self.push(&empty_note(
                "No device fit in this run (no hardware model).",
            ));
            self.section_end();
            return;
        }
        self.push("<table><thead><tr><th>device</th><th>fits</th><th>logic elements</th><th>9-bit multipliers</th><th>memory bits</th><th>PLLs</th><th>largest K that fits</th></tr></thead><tbody>");
        for d in devices {
            let cell = |used: u64, cap: u64| {
                let p = percent_of(used, cap);
                format!(
                    "<td class=\"num{}\">{} / {} ({} %)</td>",
                    if p >= 100.0 { " over" } else { "" },
                    count(used),
                    count(cap),
                    number(p, 1)
                )
            };
            let mult = format!(
                "<td class=\"num{}\">{} / {} ({} %){}</td>",
                if d.mult + d.soft_mult_elements >= d.mult_capacity {
                    " over"
                } else {
                    ""
                },
                count(d.mult),
                count(d.mult_capacity),
                number(percent_of(d.mult, d.mult_capacity), 1),
                if d.soft_mult_elements > 0 {
                    format!(" + {} built in logic", count(d.soft_mult_elements))
                } else {
                    String::new()
                }
            );
            self.push(&format!(
                "<tr><td>{}{}</td><td class=\"{}\">{}</td>{}{mult}{}{}<td class=\"num\">{}</td></tr>",
                escape(&d.device),
                if d.validated { "" } else { " <span class=\"muted\">(unvalidated)</span>" },
                if d.fits { "band-identical" } else { "band-different" },
                if d.fits { "yes" } else { "no" },
                cell(d.le, d.le_capacity),
                cell(d.mem_bits, d.mem_capacity),
                cell(u64::from(d.plls), u64::from(d.pll_capacity)),
                d.largest_units.map_or_else(|| "–".to_string(), |k| k.to_string())
            ));
        }
        self.push("</tbody></table>\n");
        if let Some(c) = find_chart(charts, "device-utilization") {
            self.push(&chart_figure(c));
        }
        self.section_end();
    }

    fn sw_hw(&mut self, run: &Run, charts: &[Chart]) {
        let r = &run.results;
        self.section_start(
            "sw-hw",
            Some("fig. 49 (software and hardware times), fig. 50 (gain per scene: 4.6 to 18), ch. 7's software-vs-hardware RMS (26.6 on both5)"),
        );
        let scenes: Vec<&SceneResult> = r.scenes.iter().filter(|s| s.hardware.is_some()).collect();
        if scenes.is_empty() {
            self.push(&empty_note(
                "No scene ran on the hardware model (it takes spheres and cylinders only: the test-bench scenes).",
            ));
            self.section_end();
            return;
        }
        for id in ["sw-hw-times", "hw-speedup"] {
            if let Some(c) = find_chart(charts, id) {
                self.push(&chart_figure(c));
            }
        }
        self.push("<table class=\"sortable\"><thead><tr><th>scene</th><th>primitives</th><th>cycles</th><th>hardware time</th><th>software time [95 % interval]</th><th>speed-up</th><th>fits</th><th>emulator RMS</th><th>band</th></tr></thead><tbody>");
        for scene in &scenes {
            let Some(h) = &scene.hardware else { continue };
            self.push(&format!(
                "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\" data-v=\"{}\">{}</td><td class=\"num\" data-v=\"{}\">{}</td><td class=\"num\" data-v=\"{}\">{}</td><td class=\"num\" data-v=\"{}\">{}×</td><td>{}</td><td class=\"num\" data-v=\"{}\">{}</td><td class=\"{}\">{}</td></tr>",
                escape(&scene.name),
                h.primitives,
                h.cycles,
                count(h.cycles),
                h.seconds,
                seconds(h.seconds),
                h.software_seconds.median,
                estimate_text(&h.software_seconds),
                h.speedup,
                number(h.speedup, 2),
                if h.fits { "yes" } else { "no" },
                h.emulator_rms,
                number(h.emulator_rms, 2),
                band_class(h.emulator_band),
                escape(h.emulator_band.name())
            ));
        }
        self.push("</tbody></table>\n<h3>Emulator and software images</h3>\n<p>Each pair: the software's diffuse-only gray render and the hardware emulator's image of the same scene.</p>\n<div class=\"scene-images\" style=\"grid-template-columns: repeat(6, minmax(0, 1fr))\">");
        for scene in &scenes {
            let Some(h) = &scene.hardware else { continue };
            self.push(&format!(
                "<figure class=\"tile\">{}<figcaption>{} · software (diffuse gray)</figcaption></figure><figure class=\"tile\">{}<figcaption>{} · hardware emulator (RMS {})</figcaption></figure>",
                embed_image(&run.base_dir, h.software_image.as_deref(), &format!("{} software", scene.name), (scene.width, scene.height)),
                escape(&scene.name),
                embed_image(&run.base_dir, h.emulator_image.as_deref(), &format!("{} emulator", scene.name), (scene.width, scene.height)),
                escape(&scene.name),
                number(h.emulator_rms, 1)
            ));
        }
        self.push("</div>\n");
        self.section_end();
    }

    fn time_vs_primitives(&mut self, r: &Results, charts: &[Chart]) {
        self.section_start(
            "time-vs-primitives",
            Some("fig. 47 and 48 (box plots of render time per primitive count)"),
        );
        match find_chart(charts, "time-vs-primitives") {
            Some(c) => {
                self.push(&chart_figure(c));
                let mut medians: BTreeMap<(SceneFamily, u64), f64> = BTreeMap::new();
                for s in r.scenes.iter().filter(|s| SceneFamily::TEST_BENCHES.contains(&s.family)) {
                    if let Some(b) = r.baseline(s) {
                        medians.insert((s.family, s.primitives), b.time.median);
                    }
                }
                self.push("<table><thead><tr><th>family</th>");
                for n in 1..=7 {
                    self.push(&format!("<th>{n}</th>"));
                }
                self.push("</tr></thead><tbody>");
                for family in SceneFamily::TEST_BENCHES {
                    self.push(&format!("<tr><td>{family}</td>"));
                    for n in 1..=7u64 {
                        let cell = medians
                            .get(&(family, n))
                            .map_or_else(|| "<span class=\"muted\">–</span>".to_string(), |m| seconds(*m));
                        self.push(&format!("<td class=\"num\">{cell}</td>"));
                    }
                    self.push("</tr>");
                }
                self.push("</tbody></table>\n<p class=\"muted\">Baseline median render time per family and primitive count.</p>\n");
            }
            None => self.push(&empty_note(
                "No test-bench scene (balls, cylinder or both with 1 to 7 primitives) ran with baseline.",
            )),
        }
        self.section_end();
    }

    fn spd(&mut self, r: &Results) {
        self.section_start(
            "spd",
            Some("ch. 8.1: SPD rings, about 1.0056e6 intersection calls and 4.22e9 sphere and cylinder tests"),
        );
        let scenes: Vec<&SceneResult> = r
            .scenes
            .iter()
            .filter(|s| s.spd || s.family == SceneFamily::Spd)
            .collect();
        if scenes.is_empty() {
            self.push(&empty_note(
                "No SPD scene ran in this suite (add them with --scenes ../shared/spd).",
            ));
            self.section_end();
            return;
        }
        let ray_kinds = [
            ("rays.primary", "primary rays"),
            ("rays.primary_hit", "hits"),
            ("rays.shadow", "shadow rays"),
            ("rays.shadow_blocked", "blocked"),
            ("rays.reflection", "reflection rays"),
            ("rays.refraction", "refraction rays"),
        ];
        self.push("<p>Exact counts of the baseline render of each SPD scene.</p>\n<table class=\"sortable\"><thead><tr><th>scene</th><th>primitives</th><th>size</th>");
        for (_, name) in ray_kinds {
            self.push(&format!("<th>{name}</th>"));
        }
        self.push("<th>rays per pixel</th><th>intersection tests</th><th>tests per ray</th></tr></thead><tbody>");
        for scene in scenes {
            let kinds = scene
                .primitive_counts
                .iter()
                .filter(|(_, n)| **n > 0)
                .map(|(k, n)| kind_count(*n, k))
                .collect::<Vec<_>>()
                .join(", ");
            self.push(&format!(
                "<tr><td>{}</td><td class=\"wrap\">{}<br><span class=\"muted\">{}</span></td><td>{}x{}</td>",
                escape(&scene.name),
                scene.primitives,
                escape(&kinds),
                scene.width,
                scene.height
            ));
            match r.baseline(scene) {
                Some(b) => {
                    let get = |k: &str| b.counts.get(k).copied().unwrap_or(0);
                    for (key, _) in ray_kinds {
                        self.push(&format!("<td class=\"num\" data-v=\"{}\">{}</td>", get(key), count(get(key))));
                    }
                    let rays = get("rays.primary") + get("rays.shadow") + get("rays.reflection") + get("rays.refraction");
                    let tests: u64 = b
                        .counts
                        .iter()
                        .filter(|(k, _)| k.starts_with("tests.") && k.ends_with(".tests"))
                        .map(|(_, v)| *v)
                        .sum();
                    let pixels = u64::from(scene.width) * u64::from(scene.height);
                    let per_pixel = if pixels > 0 { rays as f64 / pixels as f64 } else { f64::NAN };
                    let per_ray = if rays > 0 { tests as f64 / rays as f64 } else { f64::NAN };
                    self.push(&format!(
                        "<td class=\"num\">{}</td><td class=\"num\" data-v=\"{tests}\">{}</td><td class=\"num\">{}</td></tr>",
                        number(per_pixel, 2),
                        count(tests),
                        number(per_ray, 1)
                    ));
                }
                None => self.push("<td colspan=\"9\" class=\"muted\">baseline did not run on this scene</td></tr>"),
            }
        }
        self.push("</tbody></table>\n");
        self.section_end();
    }

    fn criterion(&mut self, r: &Results) {
        self.section_start("criterion", None);
        let rows = benchmark_rows(r);
        if rows.is_empty() {
            self.push(&empty_note(
                "No benchmark estimates in this run: run `cargo bench -p benches` (and `scripts/instruction-counts.sh` for instruction counts) first; the suite picks up target/criterion and target/gungraun, `rtprof report --criterion DIR` adds them to a saved run.",
            ));
            self.section_end();
            return;
        }
        self.push(&format!(
            "<p>Time: criterion's point estimate and its 95 % confidence interval, per iteration{}. Instructions: valgrind's count for the same work (gungraun), the same on every run; they are not time, and the two can disagree.</p>\n",
            measured_span(r)
        ));
        let said = instruction_time_disagreements(r);
        if !said.is_empty() {
            self.push("<ul class=\"findings\">");
            for sentence in said {
                self.push(&format!("<li>{}</li>", escape(&sentence)));
            }
            self.push("</ul>\n");
        }
        self.push("<table class=\"sortable\"><thead><tr><th>benchmark</th><th>mean [95 % interval]</th><th>median [95 % interval]</th><th>instructions</th><th>estimated cycles</th></tr></thead><tbody>");
        let time = |e: Option<&Estimate>| match e {
            Some(e) => format!(
                "<td class=\"num\" data-v=\"{}\">{}</td>",
                e.median,
                estimate_text(&e.scaled(1e-9))
            ),
            None => "<td class=\"num\" data-v=\"0\">—</td>".to_string(),
        };
        let counted = |n: Option<u64>| match n {
            Some(n) => format!("<td class=\"num\" data-v=\"{n}\">{}</td>", count(n)),
            None => "<td class=\"num\" data-v=\"0\">—</td>".to_string(),
        };
        for row in &rows {
            self.push(&format!(
                "<tr><td><code>{}</code></td>{}{}{}{}</tr>",
                escape(row.id),
                time(row.time.map(|t| &t.mean)),
                time(row.time.map(|t| &t.median)),
                counted(row.instructions.map(|i| i.instructions)),
                counted(row.instructions.and_then(|i| i.estimated_cycles)),
            ));
        }
        self.push("</tbody></table>\n");
        self.section_end();
    }

    fn failures(&mut self, r: &Results) {
        self.section_start("failures", None);
        if r.failures.is_empty() {
            self.push("<p>No failures: every scene and variant of the suite ran.</p>\n");
        } else {
            self.push(&format!(
                "<p class=\"warn\">{} of the run failed; the rest of the results stand.</p>\n<table><thead><tr><th>where</th><th>message</th></tr></thead><tbody>",
                if r.failures.len() == 1 {
                    "1 part".to_string()
                } else {
                    format!("{} parts", r.failures.len())
                }
            ));
            for f in &r.failures {
                self.push(&format!(
                    "<tr><td>{}</td><td>{}</td></tr>",
                    escape(&f.place()),
                    escape(&f.message)
                ));
            }
            self.push("</tbody></table>\n");
        }
        self.section_end();
    }

    fn reproduce(&mut self, runs: &[Run]) {
        self.section_start("reproduce", None);
        for run in runs {
            let r = &run.results;
            self.push(&format!(
                "<h3>{}</h3>\n<p>On {} ({} logical CPUs, {}), at commit <code>{}</code> with {} ({} build):</p>\n<pre class=\"command\">git checkout {}\n{}</pre>\n",
                escape(&run.label),
                escape(&r.machine.cpu_model),
                r.machine.cores,
                escape(&r.machine.os),
                escape(&r.build.git_commit),
                escape(&r.build.rustc),
                escape(&r.build.profile),
                escape(&r.build.git_commit),
                escape(&r.command)
            ));
        }
        self.push("<p class=\"muted\">Rebuild this report from saved results with <code>rtprof report results.json</code>; give several files to compare machines.</p>\n");
        self.section_end();
    }

    fn comparison(&mut self, runs: &[Run]) {
        self.section_start("comparison", None);
        let first = &runs[0];
        self.push(&format!(
            "<p>Median time of each scene × variant in every run, and its ratio to <b>{}</b> (above 1: slower). Counts are exact, so any difference means a different program or scene: such cells are flagged.</p>\n",
            escape(&first.label)
        ));
        let keys = crate::findings::comparison_keys(runs);
        if keys.is_empty() {
            self.push(&empty_note("No scene results in any run to compare."));
            self.section_end();
            return;
        }
        let lookup = |run: &Run, key: &(String, u32, u32, VariantName)| -> Option<VariantResult> {
            run.results
                .scenes
                .iter()
                .find(|s| s.name == key.0 && s.width == key.1 && s.height == key.2)
                .and_then(|s| s.variants.iter().find(|v| v.variant == key.3))
                .cloned()
        };
        self.push("<table class=\"sortable\"><thead><tr><th>scene</th><th>variant</th>");
        for run in runs {
            self.push(&format!("<th>{} median</th>", escape(&run.label)));
        }
        for run in &runs[1..] {
            self.push(&format!(
                "<th>{} / {}</th><th>counts {}</th>",
                escape(&run.label),
                escape(&first.label),
                escape(&run.label)
            ));
        }
        self.push("</tr></thead><tbody>");
        let mut flagged = 0usize;
        for key in &keys {
            let results: Vec<Option<VariantResult>> =
                runs.iter().map(|run| lookup(run, key)).collect();
            self.push(&format!(
                "<tr><td>{} <span class=\"muted\">{}x{}</span></td><td>{}</td>",
                escape(&key.0),
                key.1,
                key.2,
                escape(&key.3)
            ));
            for v in &results {
                match v {
                    Some(v) => self.push(&format!(
                        "<td class=\"num\" data-v=\"{}\">{}</td>",
                        v.time.median,
                        estimate_text(&v.time)
                    )),
                    None => self.push("<td class=\"muted\">not run</td>"),
                }
            }
            for v in &results[1..] {
                match (&results[0], v) {
                    (Some(a), Some(b)) => {
                        let ratio = b.time.median / a.time.median;
                        let class = if !ratio.is_finite() {
                            ""
                        } else if b.time.low > a.time.high {
                            " more"
                        } else if b.time.high < a.time.low {
                            " fewer"
                        } else {
                            ""
                        };
                        self.push(&format!(
                            "<td class=\"num{class}\" data-v=\"{ratio}\">{}</td>",
                            if ratio.is_finite() {
                                format!("{}×", number(ratio, 3))
                            } else {
                                "–".to_string()
                            }
                        ));
                        let names: BTreeSet<&String> =
                            a.counts.keys().chain(b.counts.keys()).collect();
                        let differing: Vec<String> = names
                            .into_iter()
                            .filter_map(|k| {
                                let (x, y) = (
                                    a.counts.get(k).copied().unwrap_or(0),
                                    b.counts.get(k).copied().unwrap_or(0),
                                );
                                (x != y).then(|| format!("{k}: {x} → {y}"))
                            })
                            .collect();
                        if differing.is_empty() {
                            self.push("<td class=\"same\" data-v=\"0\">identical</td>");
                        } else {
                            flagged += 1;
                            self.push(&format!(
                                "<td class=\"flag\" data-v=\"{}\" title=\"{}\">⚑ {} differ</td>",
                                differing.len(),
                                escape(&differing.join("\n")),
                                differing.len()
                            ));
                        }
                    }
                    _ => self.push("<td class=\"muted\">–</td><td class=\"muted\">–</td>"),
                }
            }
            self.push("</tr>");
        }
        self.push("</tbody></table>\n");
        self.push(&format!(
            "<p>{} scene × variant pair(s) with differing counts (hover a flag for the counters).</p>\n",
            flagged
        ));
        self.section_end();
    }

    fn foot(&mut self) {
        self.push(&format!(
            "</main>\n<footer>Made by rtprof from results.json; self-contained, no network access.</footer>\n<script>{SCRIPT}</script>\n</body>\n</html>\n"
        ));
    }
}

/// An id- and file-name-safe form of a name (ASCII letters, digits and '-'; the
/// rest become '_').
pub fn slug(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

const STYLE: &str = r#"
:root { --ink: #222; --muted: #666; --line: #ddd; --accent: #0b5394; --bg-alt: #f6f7f9; }
* { box-sizing: border-box; }
body { margin: 0; font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; color: var(--ink); background: #fff; }
header { padding: 18px 32px 10px; border-bottom: 3px solid var(--accent); }
header h1 { margin: 0; font-size: 26px; }
header .sub { margin: 4px 0 0; color: var(--muted); }
nav { padding: 8px 32px; background: var(--bg-alt); border-bottom: 1px solid var(--line); }
nav ol { margin: 0; padding-left: 20px; columns: 3; column-gap: 32px; }
nav a { color: var(--accent); text-decoration: none; }
nav a:hover { text-decoration: underline; }
main { max-width: 1400px; padding: 0 32px 40px; }
section { margin-top: 28px; padding-top: 6px; border-top: 1px solid var(--line); }
h2 { font-size: 22px; margin: 10px 0 4px; color: var(--accent); }
h3 { font-size: 17px; margin: 22px 0 6px; }
h4 { font-size: 15px; margin: 16px 0 6px; }
p.thesis { margin: 0 0 10px; color: var(--muted); font-style: italic; }
p.empty { padding: 10px 14px; background: #fff8e1; border-left: 4px solid #f0b400; }
p.warn { padding: 10px 14px; background: #fdecea; border-left: 4px solid #c62828; }
ul.findings li { margin: 4px 0; }
table { border-collapse: collapse; margin: 8px 0 14px; font-size: 13.5px; }
th, td { border: 1px solid var(--line); padding: 4px 8px; vertical-align: top; }
thead th { background: var(--bg-alt); text-align: left; }
tbody tr:nth-child(even) { background: #fbfbfc; }
table.kv th { text-align: left; background: var(--bg-alt); white-space: nowrap; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
table.sortable { display: block; max-width: 100%; overflow-x: auto; }
table.sortable td { white-space: nowrap; }
table.variants { font-size: 12.5px; }
table.variants th, table.variants td { padding: 3px 6px; }
table.sortable th { cursor: pointer; user-select: none; }
table.sortable th:hover { background: #e8edf3; }
table.sortable th[data-sort=asc]::after { content: " ▲"; }
table.sortable th[data-sort=desc]::after { content: " ▼"; }
.interval { color: var(--muted); font-size: 12px; }
.muted { color: var(--muted); }
code { font: 12.5px/1.3 ui-monospace, SFMono-Regular, Menlo, Consolas, monospace; }
pre { background: var(--bg-alt); border: 1px solid var(--line); padding: 10px; overflow-x: auto; font: 12px/1.35 ui-monospace, SFMono-Regular, Menlo, Consolas, monospace; max-height: 520px; }
pre.command { max-height: none; }
.band-identical { background: #e3f4e3; }
.band-similar { background: #fff4c9; }
.band-notable { background: #ffe0c2; }
.band-different { background: #f9d0d0; }
.err0 { background: #e3f4e3; } .err1 { background: #fff4c9; } .err2 { background: #ffe0c2; } .err3 { background: #f9d0d0; } .errn { background: #eeeeee; }
.chip { padding: 1px 6px; border: 1px solid var(--line); border-radius: 3px; white-space: nowrap; }
table.sortable td.wrap { white-space: normal; }
.thesis-v { color: var(--muted); font-size: 12px; }
td.same { color: var(--muted); }
td.fewer { color: #1b6e20; }
td.more { color: #b23c17; }
td.over { background: #f9d0d0; }
td.flag { background: #f9d0d0; font-weight: 600; }
figure { margin: 12px 0; }
figure.chart svg { max-width: 100%; height: auto; display: block; border: 1px solid var(--line); }
figure.chart figcaption { font-size: 13px; color: var(--muted); max-width: 800px; margin-top: 4px; }
.grid { display: flex; flex-wrap: wrap; gap: 10px; }
figure.tile { margin: 0; width: 190px; }
figure.tile img { width: 100%; height: auto; display: block; border: 1px solid var(--line); background: #000; }
.scene-images { display: grid; gap: 8px 10px; margin-bottom: 6px; }
.scene-images figure.tile { width: auto; }
.tile.reference { display: flex; align-items: center; justify-content: center; border: 1px dashed var(--line); color: var(--muted); font-size: 12px; text-align: center; min-height: 60px; }
figure.tile figcaption { font-size: 12px; color: var(--muted); }
.missing { padding: 8px; border: 1px dashed #c62828; color: #c62828; font-size: 12px; background: #fff6f6; word-break: break-all; }
.missing .reason { color: var(--muted); }
iframe.flame { display: block; width: 100%; height: auto; min-height: 200px; border: 1px solid var(--line); }
details summary { cursor: pointer; color: var(--accent); margin: 6px 0; }
footer { padding: 14px 32px; color: var(--muted); font-size: 12px; border-top: 1px solid var(--line); }
@media print {
  nav, footer { display: none; }
  body { font-size: 11pt; }
  main { max-width: none; padding: 0; }
  section { break-before: auto; }
  figure, table, .grid { break-inside: avoid; }
  iframe.flame { height: 360px; }
  pre { max-height: none; white-space: pre-wrap; }
  details { display: block; }
}
"#;

/// Sorts `table.sortable` by the clicked header: numbers (from `data-v` when present)
/// numerically, text alphabetically; a second click reverses.
const SCRIPT: &str = r#"
document.querySelectorAll("table.sortable thead th").forEach(function (th) {
  th.addEventListener("click", function () {
    var table = th.closest("table");
    var body = table.tBodies[0];
    var column = Array.prototype.indexOf.call(th.parentNode.children, th);
    var ascending = th.getAttribute("data-sort") !== "asc";
    table.querySelectorAll("thead th").forEach(function (h) { h.removeAttribute("data-sort"); });
    th.setAttribute("data-sort", ascending ? "asc" : "desc");
    function key(row) {
      var cell = row.cells[column];
      if (!cell) { return ""; }
      var raw = cell.hasAttribute("data-v") ? cell.getAttribute("data-v") : cell.textContent.trim();
      var n = parseFloat(raw);
      return isNaN(n) ? raw.toLowerCase() : n;
    }
    var rows = Array.prototype.slice.call(body.rows);
    rows.sort(function (a, b) {
      var x = key(a), y = key(b);
      if (typeof x !== typeof y) { return typeof x === "number" ? -1 : 1; }
      return (x < y ? -1 : x > y ? 1 : 0) * (ascending ? 1 : -1);
    });
    rows.forEach(function (row) { body.appendChild(row); });
  });
});
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, encoded) in cases {
            assert_eq!(base64(plain.as_bytes()), encoded);
        }
    }

    #[test]
    fn escaping_covers_markup_and_quotes() {
        assert_eq!(
            escape("<a href=\"x\">&'"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;"
        );
        assert_eq!(count(1_234_567), "1\u{2009}234\u{2009}567");
        assert_eq!(seconds(0.0123), "12.300 ms");
        assert_eq!(seconds(f64::NAN), "–");
    }

    #[test]
    fn namespace_declarations_leave_the_root_tag_only() {
        let svg = "<?xml version=\"1.0\"?><!-- see http://example.org --><svg width=\"10\" xmlns=\"http://www.w3.org/2000/svg\" xmlns:fg='http://x' height=\"5\"><text>xmlns</text></svg>";
        let cleaned = strip_svg_prologue(svg);
        assert_eq!(
            cleaned,
            "<svg width=\"10\" height=\"5\"><text>xmlns</text></svg>"
        );
        assert_eq!(svg_attribute(svg, "height"), Some(5.0));
        assert_eq!(without_xmlns("no svg here"), "no svg here");
    }

    #[test]
    fn no_runs_is_an_error() {
        assert!(matches!(render_html(&[]), Err(HtmlError::NoRuns)));
    }
}
