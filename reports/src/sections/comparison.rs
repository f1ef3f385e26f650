//! The comparison of several runs, first in a report of several runs: what changed
//! against the first run (the regression gate's verdicts, the same rule and threshold
//! as `rtprof gate`), then the machines side by side and every scene × variant's time
//! in each run with its change and whether the counts agree.

use super::summary::run_pairs;
use crate::Run;
use crate::document::{Block, Builder, Cell, Column, Inline, Section, Table, Tone};
use crate::findings::comparison_keys;
use crate::format;
use crate::gate_text;
use crate::results::gate::{Entry, GateOptions, GateReport, gate};
use crate::results::{VariantName, VariantResult};

/// Entries the "what changed" list names before leaving the rest to the table.
const CHANGES_LISTED: usize = 12;

/// The gate of `run` against `first`; runs of other machines or suites are compared
/// anyway (that is what a comparison report is for) and say so.
pub fn gate_against(first: &Run, run: &Run) -> GateReport {
    let options = GateOptions {
        force: true,
        ..GateOptions::default()
    };
    match gate(&first.results, &run.results, options) {
        Ok(report) => report,
        // With `force` the gate always answers; an empty report keeps the section up.
        Err(_) => GateReport {
            threshold: options.threshold,
            instruction_threshold: crate::results::gate::INSTRUCTION_THRESHOLD,
            entries: Vec::new(),
            instructions: Vec::new(),
            unmatched: Vec::new(),
            failed_entries: Vec::new(),
            newly_failed: 0,
            instructions_unmatched: Vec::new(),
            strict: false,
            warnings: Vec::new(),
            covers_differ: None,
            forced_over: Vec::new(),
        },
    }
}

pub fn comparison(b: &mut Builder) -> Section {
    let mut s = b.section("comparison", None);
    let runs = b.runs;
    let first = b.run;
    let gates: Vec<GateReport> = runs[1..]
        .iter()
        .map(|run| gate_against(first, run))
        .collect();
    for (run, g) in runs[1..].iter().zip(&gates) {
        what_changed(&mut s, first, run, g);
    }
    s.blocks.push(Block::heading("Machines and builds"));
    s.blocks.push(Block::Table(machines(runs)));
    let keys = comparison_keys(runs);
    if keys.is_empty() {
        return s.empty("No scene results in any run to compare.");
    }
    s.blocks
        .push(Block::heading("Tracing time, median per run"));
    s.blocks.push(Block::Paragraph {
        content: vec![
            Inline::text("Median tracing time of each scene × variant in every run; the change against "),
            Inline::strong(&first.label),
            Inline::text(
                " is the gate's: the variant's time relative to a render of the same scene timed in the same rounds (baseline, or bvh where baseline did not run; baseline or bvh itself relative to the f64 reference renderer at a smaller frame, docs/gate.md), coloured only when the verdict is faster or slower. Counts are exact: any difference is flagged.",
            ),
        ],
    });
    let mut columns = vec![Column::text("scene"), Column::text("variant")];
    columns.extend(
        runs.iter()
            .map(|run| Column::number(format!("{} median", run.label))),
    );
    for run in &runs[1..] {
        columns.push(Column::number(format!("{} vs {}", run.label, first.label)));
        columns.push(Column::text(format!("verdict {}", run.label)));
        columns.push(Column::text(format!("counts {}", run.label)));
    }
    let mut t = Table::new(columns).sortable().dense();
    for key in &keys {
        let mut row = vec![
            Cell::text(&key.0).detail(format::size(key.1, key.2)),
            Cell::text(key.3.as_str()),
        ];
        for run in runs {
            row.push(match lookup(run, key) {
                Some(v) => Cell::estimate(v.time.median, v.time.low, v.time.high),
                None => Cell::text("not run").tone(Tone::Muted),
            });
        }
        for g in &gates {
            match entry(g, key) {
                Some(e) => row.extend([
                    gate_text::change_cell(e),
                    Cell::verdict(e.verdict),
                    gate_text::counts_cell(e),
                ]),
                None => row.extend([Cell::dash(), Cell::dash(), Cell::dash()]),
            }
        }
        t.rows.push(row);
    }
    s.blocks.push(Block::Table(t));
    s
}

/// The verdicts of one run against the first: the gate's headline, its rule, and the
/// entries that changed (slower, faster or counts), largest change first.
fn what_changed(s: &mut Section, first: &Run, run: &Run, g: &GateReport) {
    s.blocks.push(Block::heading(format!(
        "{} against {}",
        run.label, first.label
    )));
    let tone = if g.failed() { Tone::Bad } else { Tone::Good };
    s.blocks.push(Block::note(tone, gate_text::headline(g)));
    s.blocks.push(Block::text(gate_text::rule(g)));
    for w in &g.warnings {
        s.blocks.push(Block::note(Tone::Fair, w.clone()));
    }
    for reason in &g.forced_over {
        s.blocks.push(Block::note(
            Tone::Fair,
            format!("Compared although {reason}: read the verdicts with care."),
        ));
    }
    let mut changed: Vec<&Entry> = g
        .entries
        .iter()
        .filter(|e| e.failed() || e.verdict != crate::results::Verdict::WithinNoise)
        .collect();
    if changed.is_empty() {
        return;
    }
    changed.sort_by(|a, b| {
        let size = |e: &Entry| e.change.median.ln().abs();
        b.failed()
            .cmp(&a.failed())
            .then_with(|| size(b).total_cmp(&size(a)))
    });
    let mut t = Table::new(vec![
        Column::text("scene"),
        Column::text("variant"),
        Column::number("change").detail("[95 % interval]"),
        Column::text("verdict"),
        Column::text("counts").grow(),
    ]);
    for e in changed.iter().take(CHANGES_LISTED) {
        t.rows.push(vec![
            Cell::text(&e.scene).detail(format::size(e.width, e.height)),
            Cell::text(e.variant.as_str()),
            gate_text::change_cell(e),
            Cell::verdict(e.verdict),
            gate_text::counts_cell(e),
        ]);
    }
    s.blocks.push(Block::Table(t));
    if changed.len() > CHANGES_LISTED {
        s.blocks.push(Block::text(format!(
            "and {} more in the table below.",
            changed.len() - CHANGES_LISTED
        )));
    }
}

/// Machine, build and suite of each run in its own column.
fn machines(runs: &[Run]) -> Table {
    let mut columns = vec![Column::text("")];
    columns.extend(runs.iter().map(|run| Column::text(&run.label).grow()));
    let mut t = Table::new(columns);
    let all: Vec<_> = runs
        .iter()
        .map(|run| run_pairs(&run.label, &run.results))
        .collect();
    for (i, pair) in all[0].iter().enumerate().skip(1) {
        let mut row = vec![Cell::text(&pair.key)];
        for pairs in &all {
            row.push(Cell::text(pairs.get(i).map_or("", |p| p.value.as_str())));
        }
        t.rows.push(row);
    }
    t
}

/// The result of one scene × variant in a run.
fn lookup<'a>(run: &'a Run, key: &(String, u32, u32, VariantName)) -> Option<&'a VariantResult> {
    run.results
        .scenes
        .iter()
        .find(|s| s.name == key.0 && s.width == key.1 && s.height == key.2)
        .and_then(|s| s.variants.iter().find(|v| v.variant == key.3))
}

/// The gate's entry of one scene × variant.
fn entry<'a>(g: &'a GateReport, key: &(String, u32, u32, VariantName)) -> Option<&'a Entry> {
    g.entries
        .iter()
        .find(|e| e.scene == key.0 && e.width == key.1 && e.height == key.2 && e.variant == key.3)
}
