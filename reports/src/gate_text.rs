//! The regression gate's report ([`results::gate::GateReport`]) as a document table and
//! its plain forms: aligned text for a terminal, GitHub-flavoured Markdown for a
//! pull-request comment or a CI job summary. The JSON form is the report's own serde.
//! The report's comparison section shows the same verdicts (`sections::comparison`).

use crate::document::{Cell, Column, Table, Tone};
use crate::format;
use crate::results::gate::{Clock, Entry, GateReport, Measure};
use crate::table_format::Exports;
use crate::text;

/// Count changes an entry's cell names before "and n more".
const COUNTERS_NAMED: usize = 3;

/// The measure of an entry in one run: a relative time as a ratio, seconds as a time.
fn measure_cell(measure: Measure, e: &results::Estimate) -> Cell {
    match measure {
        Measure::Seconds => Cell::estimate(e.median, e.low, e.high),
        _ => Cell::ratio(e.median, Some([e.low, e.high])),
    }
}

/// The clock of an entry's samples, as a header detail.
fn clock(c: Clock) -> &'static str {
    match c {
        Clock::Cpu => "(CPU)",
        Clock::Wall => "(wall)",
    }
}

/// The change of an entry, toned by its verdict.
pub fn change_cell(e: &Entry) -> Cell {
    let c = &e.change;
    let text = format::change_estimate(c.median, c.low, c.high);
    let cell = Cell::number(text.median, (c.median - 1.0) * 100.0);
    let cell = if text.interval.is_empty() {
        cell
    } else {
        cell.detail(text.interval)
    };
    cell.tone(Tone::of_verdict(e.verdict))
}

/// The count changes of an entry: "identical", or the counters that changed.
pub fn counts_cell(e: &Entry) -> Cell {
    if e.count_changes.is_empty() {
        return Cell::text("identical").tone(Tone::Muted);
    }
    let all: Vec<String> = e
        .count_changes
        .iter()
        .map(|c| {
            format!(
                "{}: {} → {}",
                c.counter,
                format::count(c.old),
                format::count(c.new)
            )
        })
        .collect();
    let mut shown: Vec<String> = all.iter().take(COUNTERS_NAMED).cloned().collect();
    if all.len() > COUNTERS_NAMED {
        shown.push(format!("and {} more", all.len() - COUNTERS_NAMED));
    }
    Cell::text(format!("changed: {}", shown.join(", ")))
        .tone(Tone::Bad)
        .hover(all.join("\n"))
}

/// Every entry: scene, variant, what it is measured against, both runs, the change,
/// the verdict and the counts. Failed entries first, then the rest in run order.
pub fn table(gate: &GateReport) -> Table {
    let mut t = Table::new(vec![
        Column::text("scene"),
        Column::text("variant"),
        Column::text("measure"),
        Column::number("old").detail("[95 % interval]"),
        Column::number("new").detail("[95 % interval]"),
        Column::number("change").detail("[95 % interval]"),
        Column::text("verdict"),
        Column::text("counts").grow(),
    ])
    .sortable()
    .dense();
    let mut entries: Vec<&Entry> = gate.entries.iter().collect();
    entries.sort_by_key(|e| !e.failed());
    for e in entries {
        t.rows.push(vec![
            Cell::text(&e.scene).detail(format::size(e.width, e.height)),
            Cell::text(e.variant.as_str()),
            Cell::text(e.measure.describe()).detail(clock(e.clock)),
            measure_cell(e.measure, &e.old),
            measure_cell(e.measure, &e.new),
            change_cell(e),
            Cell::verdict(e.verdict),
            counts_cell(e),
        ]);
    }
    t
}

/// The instruction counts compared (empty when neither run had them).
pub fn instruction_table(gate: &GateReport) -> Option<Table> {
    if gate.instructions.is_empty() {
        return None;
    }
    let mut t = Table::new(vec![
        Column::text("benchmark"),
        Column::number("old instructions"),
        Column::number("new instructions"),
        Column::number("change"),
    ]);
    for i in &gate.instructions {
        let pct = i.change * 100.0;
        let tone = if gate.instruction_failed(i) {
            Tone::Bad
        } else if i.improved {
            Tone::Good
        } else if i.change == 0.0 {
            Tone::Muted
        } else {
            Tone::Neutral
        };
        t.rows.push(vec![
            Cell::text(&i.id).code(),
            Cell::count(i.old),
            Cell::count(i.new),
            Cell::number(format::signed_change(pct, 2), pct).tone(tone),
        ]);
    }
    Some(t)
}

/// The first few of `names`, and how many more.
fn named(names: &[String]) -> String {
    const NAMED: usize = 5;
    let mut shown: Vec<String> = names.iter().take(NAMED).cloned().collect();
    if names.len() > NAMED {
        shown.push(format!("and {} more", names.len() - NAMED));
    }
    shown.join(", ")
}

/// The first line: passed or FAILED, what was compared, the verdicts and the threshold.
pub fn headline(gate: &GateReport) -> String {
    let t = gate.tally();
    let mut line = format!(
        "regression gate {}: {} compared: {} slower, {} faster, {} within noise; {} with changed counts",
        if gate.failed() { "FAILED" } else { "passed" },
        format::plural(gate.entries.len(), "scene × variant"),
        t.slower,
        t.faster,
        t.within_noise,
        t.count_changes
    );
    if !gate.instructions.is_empty() {
        let threshold = format::percent(gate.instruction_threshold * 100.0, 0);
        line += &if gate.strict {
            format!(
                "; {} of {} instruction counts grew and {} shrank more than {}",
                t.instructions_regressed,
                gate.instructions.len(),
                t.instructions_improved,
                threshold
            )
        } else {
            format!(
                "; {} of {} instruction counts grew more than {}",
                t.instructions_regressed,
                gate.instructions.len(),
                threshold
            )
        };
    }
    if gate.strict {
        let unmatched = gate.unmatched.len() + gate.instructions_unmatched.len();
        line += &format!(
            "; strict gate: {} of the scene × variants and benchmarks in one run only",
            format::count(unmatched as u64)
        );
    }
    if !gate.failed_entries.is_empty() {
        line += &format!(
            "; {} failed in one of the runs (not compared)",
            format::plural(gate.failed_entries.len(), "scene × variant")
        );
    }
    line
}

/// What the verdicts mean, in one paragraph.
pub fn rule(gate: &GateReport) -> String {
    format!(
        "Times are the process CPU time of each render (wall time for older files), gated relative to a render of the same scene timed in the same rounds (each variant ÷ baseline, or ÷ bvh on a scene run without baseline; baseline, or bvh there, ÷ the f64 reference renderer at a smaller frame, or ÷ the calibration kernel in older files), so a busier or slower machine moves both alike. A change is slower or faster only when it exceeds the noise threshold of {} (the run-to-run noise of relative times measured on a shared machine, docs/gate.md; wider for an entry whose own 95 % intervals are, their half-widths summed, and at least {} for renders shorter than {}) and its 95 % interval excludes no change. Any changed count fails.",
        format::percent(gate.threshold * 100.0, 1),
        format::percent(results::gate::SHORT_THRESHOLD * 100.0, 0),
        format::seconds(results::gate::SHORT_SECONDS)
    )
}

/// Notes below the table: warnings, unmatched entries, forced comparisons.
fn notes(gate: &GateReport) -> Vec<String> {
    let mut notes: Vec<String> = gate
        .warnings
        .iter()
        .map(|w| format!("warning: {w}"))
        .collect();
    for reason in &gate.forced_over {
        notes.push(format!("warning: gated with --force although {reason}"));
    }
    if let Some((old, new)) = gate.covers_differ {
        notes.push(format!(
            "note: the old run's times cover {}, the new run's {}: time changes include the difference",
            old.describe(),
            new.describe()
        ));
    }
    let short: Vec<&results::gate::Entry> = gate.entries.iter().filter(|e| e.short()).collect();
    if !short.is_empty() {
        notes.push(format!(
            "note: {} with renders shorter than {} gated at a threshold of {} at least: renders that short move by up to a third between runs with nothing changed ({})",
            match short.len() {
                1 => "1 entry".to_string(),
                n => format!("{} entries", format::count(n as u64)),
            },
            format::seconds(results::gate::SHORT_SECONDS),
            format::percent(results::gate::SHORT_THRESHOLD * 100.0, 0),
            named(&short.iter().map(|e| format!("{} / {}", e.scene, e.variant)).collect::<Vec<_>>()),
        ));
    }
    let widened: Vec<String> = gate
        .entries
        .iter()
        .filter(|e| e.threshold > gate.threshold && !e.short())
        .map(|e| {
            format!(
                "{} / {} {}",
                e.scene,
                e.variant,
                format::percent(e.threshold * 100.0, 1)
            )
        })
        .collect();
    if !widened.is_empty() {
        notes.push(format!(
            "note: {} {} gated at a wider threshold than {}, their own intervals being wider: {}",
            widened.len(),
            if widened.len() == 1 {
                "entry"
            } else {
                "entries"
            },
            format::percent(gate.threshold * 100.0, 1),
            named(&widened)
        ));
    }
    if let Some((e, change)) = gate.largest_change() {
        notes.push(format!(
            "largest change: {} / {} {} ({})",
            e.scene,
            e.variant,
            format::percent(change * 100.0, 1),
            e.verdict
        ));
    }
    for u in gate.unmatched.iter().chain(&gate.instructions_unmatched) {
        notes.push(format!("only in one run: {u}"));
    }
    for f in &gate.failed_entries {
        notes.push(format!("not compared: {f}"));
    }
    notes
}

/// The gate for a terminal.
pub fn to_text(gate: &GateReport) -> String {
    let mut out = headline(gate) + "\n" + &rule(gate) + "\n\n";
    out += &text::table(&table(gate));
    if let Some(t) = instruction_table(gate) {
        out += "\n";
        out += &text::table(&t);
    }
    for note in notes(gate) {
        out += &note;
        out.push('\n');
    }
    out
}

/// The gate as GitHub-flavoured Markdown: a heading with the verdict counts, the rule,
/// the failed entries' table (or every entry when nothing failed, folded away).
pub fn to_markdown(gate: &GateReport) -> String {
    let status = if gate.failed() { "❌" } else { "✅" };
    let mut out = format!("### {status} {}\n\n{}\n\n", headline(gate), rule(gate));
    let failed: Vec<Entry> = gate
        .entries
        .iter()
        .filter(|e| e.failed())
        .cloned()
        .collect();
    let rest = GateReport {
        entries: gate
            .entries
            .iter()
            .filter(|e| !e.failed())
            .cloned()
            .collect(),
        ..gate.clone()
    };
    if !failed.is_empty() {
        let only_failed = GateReport {
            entries: failed,
            ..gate.clone()
        };
        out += &text::markdown(&table(&only_failed));
        out += "\n";
    }
    if !rest.entries.is_empty() {
        out += &format!(
            "<details><summary>{} passed</summary>\n\n{}\n</details>\n\n",
            format::plural(rest.entries.len(), "scene × variant"),
            text::markdown(&table(&rest))
        );
    }
    if let Some(t) = instruction_table(gate) {
        out += &text::markdown(&t);
        out += "\n";
    }
    for note in notes(gate) {
        out += &format!("- {note}\n");
    }
    out
}

/// One CSV row per entry, plain numbers (relative times as ratios, seconds in full).
pub fn to_csv(gate: &GateReport) -> String {
    let header = [
        "scene",
        "width",
        "height",
        "variant",
        "measure",
        "clock",
        "old",
        "old_low",
        "old_high",
        "new",
        "new_low",
        "new_high",
        "old_seconds",
        "new_seconds",
        "change",
        "change_low",
        "change_high",
        "verdict",
        "changed_counters",
    ];
    let n = |x: f64| text::csv_number(Some(x));
    let rows: Vec<Vec<String>> = gate
        .entries
        .iter()
        .map(|e| {
            vec![
                e.scene.clone(),
                e.width.to_string(),
                e.height.to_string(),
                e.variant.to_string(),
                e.measure.describe().to_string(),
                clock(e.clock).trim_matches(['(', ')']).to_string(),
                n(e.old.median),
                n(e.old.low),
                n(e.old.high),
                n(e.new.median),
                n(e.new.low),
                n(e.new.high),
                n(e.old_seconds),
                n(e.new_seconds),
                n(e.change.median),
                n(e.change.low),
                n(e.change.high),
                e.verdict.label().to_string(),
                e.count_changes.len().to_string(),
            ]
        })
        .collect();
    text::csv(&header, &rows)
}

impl Exports for GateReport {
    fn to_text(&self) -> String {
        to_text(self)
    }
    fn to_markdown(&self) -> String {
        to_markdown(self)
    }
    fn to_csv(&self) -> String {
        to_csv(self)
    }
}
