//! The generated RTL through Yosys beside the model and table 8: each block's LUT4,
//! flip-flops, logic depth and estimated clock, where the design would not close the
//! thesis's 50 MHz, and why the three sources' figures differ.
//!
//! [`synthesis_table`] and [`synthesis_text`] are public: `rtprof hw synth` and
//! `rtprof hw table` print the same table model as text.

use crate::document::{Block, Builder, Cell, Column, Section, Table, Tone};
use crate::format;
use crate::results::{HwRow, SynthBlock, Synthesis};

/// Why Yosys's figures are neither Quartus's (the thesis's) nor the model's, and what
/// the model takes in from the synthesis (issue 38, item 5).
pub const SYNTH_REASONS: &[&str] = &[
    "Yosys's synth_intel (experimental) maps logic to LUT4s without arithmetic-mode carry chains: an adder or comparator costs more cells than in Quartus, where one logic element is one bit of an adder.",
    "No DSP inference: multipliers are built of LUTs (the mult LUT4 column) where Quartus uses the embedded 9×9 multipliers; subtract them to compare with the model's logic elements.",
    "These are rtprof's own operators (rtl/verilog), pipelined over their stages with prefix adders for a 12-level path, not the ALTFP cores the model's library rows (table 7) were measured on; their pipeline registers and prefix adders are the operators' own cost, which the model does not take in: its rows are the thesis's measured cores, and a model of the RTL would no longer be a model of the thesis's hardware.",
    "A logic element holds one LUT4 and one flip-flop: a design needs between max(LUT4, FF) and LUT4 + FF of them.",
    "The minimum-distance block carries its payload (173 bits) beside its 3-cycle compare where the model, like the thesis's 173 registers, holds the inputs for the pacing; the top adds the screen iterator, the scene memory's ports and the control delay lines, which table 8's blocks do not include.",
];

/// Yosys's figures per block beside the model's and the thesis's (`model` is table 8's
/// rows of the same design), with the depth and the estimated clock, toned by whether
/// it reaches the synthesis's clock.
pub fn synthesis_table(synth: &Synthesis, model: &[HwRow]) -> Table {
    let clock = format::quantity(synth.clock_mhz);
    let mut t = Table::new(vec![
        Column::text("block"),
        Column::number("LUT4").detail("Yosys"),
        Column::number("mult LUT4").detail("of LUT4"),
        Column::number("FF").detail("Yosys"),
        Column::number("mem bits").detail("Yosys"),
        Column::number("LUT levels").detail("longest path"),
        Column::number("est. Fmax").detail(format!("MHz, goal {clock}")),
        Column::number("model LE"),
        Column::number("model regs"),
        Column::number("thesis LE"),
        Column::number("thesis regs"),
    ]);
    for block in synth.blocks.iter().chain(std::iter::once(&synth.total)) {
        let row = model.iter().find(|r| r.name == block.name);
        let optional = |v: Option<u64>| v.map_or_else(Cell::dash, Cell::count);
        let mut cells = synth_cells(block);
        cells.extend([
            optional(row.map(|r| r.model.le)),
            optional(row.map(|r| r.model.regs)),
            optional(row.and_then(|r| r.thesis).map(|t| t.le)),
            optional(row.and_then(|r| r.thesis).map(|t| t.regs)),
        ]);
        t.rows.push(cells);
    }
    t.caption(format!(
        "{}, {} ({}); one instance of each block; the whole design adds the top's iterator, scene memory and control. Est. Fmax: {} ns + {} ns per LUT level (docs/hardware-model.md)",
        synth.tool,
        synth.flow,
        format::seconds(synth.seconds),
        format::significant(synth.register_ns),
        format::significant(synth.level_ns),
    ))
}

/// A block's Yosys columns: LUT4, multiplier LUT4, FF, memory bits, depth, Fmax.
fn synth_cells(block: &SynthBlock) -> Vec<Cell> {
    let tone = if block.closes { Tone::Good } else { Tone::Bad };
    vec![
        Cell::text(&block.name).code(),
        Cell::count(block.lut4),
        Cell::count(block.mult_lut4),
        Cell::count(block.ff),
        Cell::count(block.mem_bits),
        Cell::count(block.levels)
            .hover(format!("{} → {}", block.path_from, block.path_to))
            .tone(tone),
        Cell::number(format::quantity(block.fmax_mhz), block.fmax_mhz).tone(tone),
    ]
}

/// Where the design would not close its clock, or that it would everywhere.
pub fn closing_sentence(synth: &Synthesis) -> String {
    let clock = format::quantity(synth.clock_mhz);
    let failing = synth.not_closing();
    if failing.is_empty() {
        return format!(
            "Every block's longest path between registers is at most {} LUT levels (the whole design's: {}), an estimated {} MHz or more: by the estimate the {} design closes {clock} MHz everywhere.",
            format::count(synth.max_levels),
            format::count(synth.total.levels),
            format::quantity(
                synth
                    .blocks
                    .iter()
                    .chain(std::iter::once(&synth.total))
                    .map(|b| b.fmax_mhz)
                    .fold(f64::INFINITY, f64::min)
            ),
            synth.design,
        );
    }
    let list: Vec<String> = failing
        .iter()
        .map(|b| {
            format!(
                "{} ({} levels, from {} to {}: {} MHz)",
                b.name,
                format::count(b.levels),
                b.path_from,
                b.path_to,
                format::quantity(b.fmax_mhz)
            )
        })
        .collect();
    format!(
        "The {} design would not close {clock} MHz (more than {} LUT levels between registers) in {}.",
        synth.design,
        format::count(synth.max_levels),
        format::join_list(&list)
    )
}

/// `rtprof hw synth`'s text: the heading, the table, where the clock is not met, and why
/// the columns differ.
pub fn synthesis_text(synth: &Synthesis, model: &[HwRow]) -> String {
    let mut text = format!(
        "{}: the {} design through {} in {}\n",
        synth.tool,
        synth.design,
        synth.flow,
        format::seconds(synth.seconds)
    );
    text += &crate::text::table(&synthesis_table(synth, model));
    text += &closing_sentence(synth);
    text += "\nWhy the columns differ:\n";
    for reason in SYNTH_REASONS {
        text += &format!("  - {reason}\n");
    }
    text
}

/// The report's synthesis section (inside the hardware chapter), when the run carries
/// a synthesis of its design.
pub fn synthesis_section(b: &mut Builder) -> Section {
    let mut s = b.section("hardware-synthesis", None);
    let Some(hw) = &b.results().hardware else {
        return s.empty("No hardware model in this run.");
    };
    let Some(synth) = &hw.synthesis else {
        return s.empty(
            "No synthesis of this design's RTL on this machine: `rtprof hw synth` (Yosys, minutes) records one, and the next run shows it here.",
        );
    };
    s.text(closing_sentence(synth));
    s.blocks
        .push(Block::Table(synthesis_table(synth, &hw.blocks)));
    for reason in SYNTH_REASONS {
        s.blocks.push(Block::note(Tone::Muted, *reason));
    }
    s
}
