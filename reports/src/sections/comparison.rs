//! The comparison of several runs: machines side by side, and every scene × variant's
//! time in each run with its change against the first and whether the counts agree.

use std::collections::BTreeSet;

use super::summary::run_pairs;
use crate::Run;
use crate::document::{Block, Builder, Cell, Column, Inline, Section, Table, Tone};
use crate::findings::comparison_keys;
use crate::format;
use crate::results::{VariantName, VariantResult};

/// Differing counters a counts cell names before leaving the rest to the hover text.
const COUNTERS_NAMED: usize = 2;

pub fn comparison(b: &mut Builder) -> Section {
    let mut s = b.section("comparison", None);
    let runs = b.runs;
    let first = b.run;
    s.blocks.push(Block::Paragraph {
        content: vec![
            Inline::text("Median time of each scene × variant in every run, and its change against "),
            Inline::strong(&first.label),
            Inline::text(
                " (coloured when the 95 % intervals do not overlap: red slower, green faster). Counts are exact, so any difference means a different program or scene: such cells are flagged.",
            ),
        ],
    });
    s.blocks.push(Block::heading("Machines and builds"));
    s.blocks.push(Block::Table(machines(runs)));
    let keys = comparison_keys(runs);
    if keys.is_empty() {
        return s.empty("No scene results in any run to compare.");
    }
    s.blocks
        .push(Block::heading("Tracing time, median per run"));
    let mut columns = vec![Column::text("scene"), Column::text("variant")];
    columns.extend(
        runs.iter()
            .map(|run| Column::number(format!("{} median", run.label))),
    );
    for run in &runs[1..] {
        columns.push(Column::number(format!("{} vs {}", run.label, first.label)));
        columns.push(Column::text(format!("counts {}", run.label)));
    }
    let mut t = Table::new(columns).sortable().dense();
    let mut flagged = 0usize;
    for key in &keys {
        let found: Vec<Option<&VariantResult>> = runs.iter().map(|run| lookup(run, key)).collect();
        let mut row = vec![
            Cell::text(&key.0).detail(format::size(key.1, key.2)),
            Cell::text(key.3.as_str()),
        ];
        for v in &found {
            row.push(match v {
                Some(v) => Cell::estimate(v.time.median, v.time.low, v.time.high),
                None => Cell::text("not run").tone(Tone::Muted),
            });
        }
        for v in &found[1..] {
            match (found[0], v) {
                (Some(a), Some(b)) => {
                    row.push(change_cell(a, b));
                    let cell = counts_cell(a, b);
                    if cell.tone == Tone::Bad {
                        flagged += 1;
                    }
                    row.push(cell);
                }
                _ => row.extend([Cell::dash(), Cell::dash()]),
            }
        }
        t.rows.push(row);
    }
    s.blocks.push(Block::Table(t));
    s.blocks.push(Block::text(format!(
        "{flagged} scene × variant pair(s) with differing counts (the HTML report lists the counters on hover)."
    )));
    s
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

/// The relative change of `new`'s median against `old`'s, toned when the intervals do
/// not overlap.
fn change_cell(old: &VariantResult, new: &VariantResult) -> Cell {
    if old.time.median.is_nan() || old.time.median <= 0.0 {
        return Cell::dash();
    }
    let pct = (new.time.median / old.time.median - 1.0) * 100.0;
    Cell::number(format::signed_percent(pct, 1), pct)
        .tone(Tone::of_change(
            (old.time.low, old.time.high),
            (new.time.low, new.time.high),
        ))
        .hover(format!(
            "{} of the first run's time",
            format::speedup(new.time.median / old.time.median)
        ))
}

/// Whether two runs counted the same; the differing counters when not.
fn counts_cell(a: &VariantResult, b: &VariantResult) -> Cell {
    let names: BTreeSet<&String> = a.counts.keys().chain(b.counts.keys()).collect();
    let differing: Vec<String> = names
        .into_iter()
        .filter_map(|k| {
            let (x, y) = (
                a.counts.get(k).copied().unwrap_or(0),
                b.counts.get(k).copied().unwrap_or(0),
            );
            (x != y).then(|| format!("{k}: {} → {}", format::count(x), format::count(y)))
        })
        .collect();
    if differing.is_empty() {
        return Cell::number("identical", 0.0).tone(Tone::Muted);
    }
    let named: Vec<&str> = differing
        .iter()
        .take(COUNTERS_NAMED)
        .map(|d| d.split(':').next().unwrap_or(d))
        .collect();
    let more = differing.len().saturating_sub(COUNTERS_NAMED);
    Cell::number(
        format!("⚑ {} differ", differing.len()),
        differing.len() as f64,
    )
    .tone(Tone::Bad)
    .detail(if more > 0 {
        format!("{} and {more} more", named.join(", "))
    } else {
        named.join(", ")
    })
    .hover(differing.join("\n"))
}
