//! The micro-benchmarks section: criterion's times beside gungraun's instruction
//! counts, and where the two disagree.

use crate::document::{Block, Builder, Cell, Column, Section, Table};
use crate::findings::{benchmark_rows, instruction_time_disagreements, measured_span};
use crate::results::Estimate;

pub fn criterion(b: &mut Builder) -> Section {
    let mut s = b.section("criterion", None);
    s.short = true;
    let r = b.results();
    let rows = benchmark_rows(r);
    if rows.is_empty() {
        return s.empty("No benchmark estimates in this run: run cargo bench -p benches (and scripts/instruction-counts.sh for instruction counts) first; the suite picks up target/criterion and target/gungraun, rtprof report --criterion DIR adds them to a saved run.");
    }
    s.blocks.push(Block::text(format!(
        "Time: criterion's point estimate and its 95 % confidence interval, per iteration{}. Instructions: valgrind's count for the same work (gungraun), the same on every run; they are not time, and the two can disagree.",
        measured_span(r)
    )));
    let said = instruction_time_disagreements(r);
    if !said.is_empty() {
        s.blocks.push(Block::List { items: said });
    }
    let mut t = Table::new(vec![
        Column::text("benchmark").grow(),
        Column::number("mean").detail("[95 % interval]"),
        Column::number("median").detail("[95 % interval]"),
        Column::number("instructions"),
        Column::number("estimated cycles"),
    ])
    .sortable();
    // Criterion writes nanoseconds.
    let time = |e: Option<&Estimate>| match e {
        Some(e) => Cell::estimate(e.median * 1e-9, e.low * 1e-9, e.high * 1e-9),
        None => Cell::dash(),
    };
    let counted = |n: Option<u64>| n.map_or_else(Cell::dash, Cell::count);
    for row in &rows {
        t.rows.push(vec![
            Cell::text(row.id).code(),
            time(row.time.map(|t| &t.mean)),
            time(row.time.map(|t| &t.median)),
            counted(row.instructions.map(|i| i.instructions)),
            counted(row.instructions.and_then(|i| i.estimated_cycles)),
        ]);
    }
    s.blocks.push(Block::Table(t));
    s
}
