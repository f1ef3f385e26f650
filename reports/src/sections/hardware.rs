//! The hardware chapter: the model against the thesis's tables 7 and 8, the device
//! fit, and software against hardware on each scene.
//!
//! [`hw_table`] is public: `rtprof hw table` prints the same table model as text.

use super::GRID_COLUMNS;
use crate::document::{
    Block, Builder, Cell, Column, ImageGrid, Inline, Section, Table, Tile, Tone,
};
use crate::findings::{fit_state, headroom_warning_of};
use crate::format;
use crate::results::{DeviceUse, HwColumn, HwRow, HwRowKind, SceneResult};
use hwmodel::device::{
    FitState, MEMORY_BLOCK_HEADROOM_PERCENT, ROUTING_HEADROOM_PERCENT, above_headroom,
    headroom_percent,
};

/// Tables 7 or 8: each cell the model's figure, its detail the thesis's figure and the
/// model's signed error, its tone the size of that error ([`Tone::of_error`]).
pub fn hw_table(rows: &[HwRow]) -> Table {
    let mut columns = vec![Column::text("name"), Column::text("kind")];
    columns
        .extend(HwColumn::ALL.map(|c| Column::number(c.label()).detail("model / thesis (error)")));
    let mut t = Table::new(columns).sortable();
    for row in rows {
        let mut cells = vec![Cell::text(&row.name).code(), Cell::text(row.kind.name())];
        for (column, model) in row.model.columns() {
            let thesis = row.thesis.map(|t| t.get(column));
            let error = row.error_pct.as_ref().and_then(|e| e.get(column));
            // Where the thesis has none and the model some, no percentage exists: the
            // two differ in kind, which is coloured as the worst error band.
            let differs_in_kind = thesis == Some(0) && model > 0;
            let detail = match (thesis, error) {
                (Some(t), Some(e)) => {
                    format!("/ {} ({})", format::count(t), format::signed_change(e, 1))
                }
                (Some(0), None) if differs_in_kind => "/ 0 (the thesis has none)".to_string(),
                (Some(t), None) => format!("/ {} ({})", format::count(t), format::DASH),
                (None, _) if row.kind == HwRowKind::IpCore => "(the library's)".to_string(),
                (None, _) => "(no thesis figure)".to_string(),
            };
            let tone = if differs_in_kind {
                Tone::Bad
            } else {
                Tone::of_error(error)
            };
            cells.push(Cell::count(model).detail(detail).tone(tone));
        }
        t.rows.push(cells);
    }
    t
}

/// The hardware chapter: its finding, then the model against tables 7 and 8, the
/// thesis's optimizations costed, the device fit, and software against hardware.
pub fn hardware(b: &mut Builder) -> Section {
    let mut s = b.section("hardware", None);
    let r = b.results();
    if r.hardware.is_none() && r.scenes.iter().all(|s| s.hardware.is_none()) {
        return s.empty("No hardware model in this run.");
    }
    if let Some(text) = crate::findings::hardware_finding(r) {
        s.text(text);
    }
    s.absorb(hardware_tables(b));
    if r.hardware.as_ref().is_some_and(|h| h.synthesis.is_some()) {
        s.absorb(super::synthesis::synthesis_section(b));
    } else {
        s.blocks.push(Block::note(
            Tone::Muted,
            "The generated RTL has not been synthesized on this machine: `rtprof hw synth` (Yosys, a few minutes) records its cells, logic depth and clock, and the next run shows them here.",
        ));
    }
    s.absorb(optimizations(b));
    s.absorb(device_utilization(b));
    s.absorb(super::fpga_answer::design_space(b));
    s.absorb(sw_hw(b));
    s
}

/// The scene the optimizations are costed on: the test bench's largest (7 primitives,
/// the fit's scene too) at the thesis's 640×480.
pub const COSTED_SCENE: (u64, u32, u32) = (hwmodel::optimizations::BENCH_PRIMITIVES, 640, 480);

/// The thesis's optimizations costed in the pipeline's cycles and the device's logic
/// (see [`hwmodel::optimizations`]), on the validated device.
pub fn optimizations(b: &mut Builder) -> Section {
    let mut s = b.section(
        "hw-optimizations",
        Some("ch. 8.3's proposals (fast sqrt, orthographic camera, sqrt-free shading, parallel units), never costed in hardware"),
    );
    let lib = hwmodel::library::Library::cyclone_iv_e();
    let Some(device) = lib.devices.iter().find(|d| d.validated).cloned() else {
        return s.empty("The operator library has no validated device to cost the designs on.");
    };
    let (n, width, height) = COSTED_SCENE;
    let rows = hwmodel::optimizations::thesis_optimizations(
        &lib,
        &device,
        n,
        width,
        height,
        hwmodel::frame_timing::THESIS_CLOCK_HZ,
    );
    if let Some(text) = optimizations_sentence(&rows, &device.name) {
        s.text(text);
    }
    let r = b.results();
    let picture = |d: &hwmodel::design::Design| {
        let relied: Vec<String> = [
            (d.fast_sqrt, "fast-sqrt"),
            (d.ortho, "ortho"),
            (d.no_rsqrt_shading, "no-rsqrt-shading"),
        ]
        .into_iter()
        .filter(|(on, _)| *on)
        .map(|(_, v)| match super::fpga_answer::worst_rms(r, v) {
            Some(rms) => format!("{v} RMS {}", format::fixed(rms, 1)),
            None => format!("{v} not run"),
        })
        .collect();
        if relied.is_empty() {
            "none".to_string()
        } else {
            relied.join(", ")
        }
    };
    s.blocks.push(Block::Table(optimizations_table(
        &rows,
        &device.name,
        &picture,
    )));
    s.blocks.push(Block::note(
        Tone::Muted,
        "Pixel averaging (8.3.5) is not costed in hardware: the pipeline would trace every other pixel (half the frame's cycles) and fill the rest from the neighbours through a line buffer (one RAM block a row and a few adders); its picture cost is the software variant's (pixel-avg in the variants chapter).",
    ));
    s
}

/// What the logic-saving optimizations buy: fill cycles and logic, and the frame only
/// through more units.
pub fn optimizations_sentence(
    rows: &[hwmodel::optimizations::OptimizationCost],
    device: &str,
) -> Option<String> {
    let thesis = rows.first()?;
    let saving = rows.iter().find(|r| {
        r.design.fast_sqrt && r.design.ortho && r.design.no_rsqrt_shading && r.design.units == 1
    })?;
    // The last row: the three together with the most units that fit.
    let most = rows.last()?;
    let (n, width, height) = COSTED_SCENE;
    let le_saved = thesis.used.le as f64 - saving.used.le as f64;
    Some(format!(
        "At {n} primitives and {}, the thesis's pipeline takes {} a frame on the {device}. Its three logic-saving optimizations together free {} logic elements ({} of the design's) and shorten the fill by {} cycles, but the frame only by {}: a frame is one pixel every 3 cycles per primitive per unit, which they do not change. What they can buy is room for more intersection units: {}",
        format::size(width, height),
        format::seconds(thesis.frame_seconds),
        format::count(le_saved.max(0.0) as u64),
        format::percent(le_saved / thesis.used.le.max(1) as f64 * 100.0, 0),
        format::count(thesis.fill_cycles.saturating_sub(saving.fill_cycles)),
        format::seconds(thesis.frame_seconds - saving.frame_seconds),
        if most.design.units > 1 {
            let on_paper = most.state == FitState::FitsOnPaper;
            format!(
                "with them, {} {} the frame to {}.",
                format::plural(most.design.units as usize, "unit"),
                if on_paper {
                    "fit, but only on paper (above the routing headroom), and would take"
                        .to_string()
                } else {
                    "fit and take".to_string()
                },
                format::seconds(most.frame_seconds)
            )
        } else {
            "but even with them a second unit does not fit.".to_string()
        },
    ))
}

/// The designs side by side: cycles, frame time, logic, multipliers, memory, fit.
pub fn optimizations_table(
    rows: &[hwmodel::optimizations::OptimizationCost],
    device: &str,
    picture: &dyn Fn(&hwmodel::design::Design) -> String,
) -> Table {
    let mut t = Table::new(vec![
        Column::text("design"),
        Column::number("fill").detail("cycles"),
        Column::number("per pixel").detail("cycles"),
        Column::number("frame"),
        Column::number("logic elements").detail("change"),
        Column::number("9-bit multipliers").detail("asked"),
        Column::number("memory bits"),
        Column::text(format!("fits the {device}")),
        Column::text("picture cost").detail("worst RMS of the software variant"),
    ]);
    let Some(thesis) = rows.first() else {
        return t;
    };
    for r in rows {
        let change = (r.used.le as f64 / thesis.used.le.max(1) as f64 - 1.0) * 100.0;
        let (fits, tone) = match r.state {
            FitState::Fits => ("yes", Tone::Good),
            FitState::FitsOnPaper => ("on paper only", Tone::Warning),
            FitState::DoesNotFit => ("no", Tone::Bad),
        };
        t.rows.push(vec![
            Cell::text(&r.label),
            Cell::count(r.fill_cycles),
            Cell::count(r.cycles_per_pixel),
            Cell::number(format::seconds(r.frame_seconds), r.frame_seconds),
            Cell::count(r.used.le).detail(format::signed_change(change, 1)),
            Cell::count(r.used.mult).detail(format::count(r.multipliers_asked)),
            Cell::count(r.used.mem_bits),
            Cell::text(fits).tone(tone),
            Cell::text(picture(&r.design)),
        ]);
    }
    t.caption(format!(
        "Each design at {} primitives, {}, 50 MHz; logic elements include multipliers built in logic when the device's run out",
        COSTED_SCENE.0,
        format::size(COSTED_SCENE.1, COSTED_SCENE.2)
    ))
}

pub fn hardware_tables(b: &mut Builder) -> Section {
    let mut s = b.section(
        "hardware-tables",
        Some("table 7 (per operation) and table 8 (per block), Quartus figures on the Cyclone IV EP4CE115"),
    );
    let Some(hw) = &b.results().hardware else {
        return s.empty("No hardware model in this run.");
    };
    let mut legend = vec![Inline::text(format!(
        "The FPGA model of the thesis's ray caster, operator library {}. Each cell: the model's figure / the thesis's (signed error). Cell colour by |error|: ",
        hw.family
    ))];
    for (tone, text) in Tone::ERROR_LEGEND {
        legend.push(Inline::Chip {
            text: text.to_string(),
            tone,
        });
        legend.push(Inline::text(" "));
    }
    s.blocks.push(Block::Paragraph { content: legend });
    for (title, rows, empty) in [
        (
            "Table 7: operations",
            &hw.ops,
            "The model produced no operation rows.",
        ),
        (
            "Table 8: blocks",
            &hw.blocks,
            "The model produced no block rows.",
        ),
    ] {
        s.blocks.push(Block::heading(title));
        if rows.is_empty() {
            s.blocks.push(Block::empty(empty));
        } else {
            s.blocks.push(Block::Table(hw_table(rows)));
        }
    }
    s.blocks.push(Block::note(
        Tone::Muted,
        "Rows without a thesis figure have nothing to compare with: the IP-core rows are the thesis's own figures, the input the model builds everything else from.",
    ));
    s
}

pub fn device_utilization(b: &mut Builder) -> Section {
    let mut s = b.section(
        "device-utilization",
        Some("ch. 8.2: about 100,000 LEs (78 %), all 532 multipliers, 2,412 Kbits of memory, 2 PLLs on the EP4CE115"),
    );
    s.short = true;
    let devices = b
        .results()
        .hardware
        .as_ref()
        .map(|h| h.devices.as_slice())
        .unwrap_or(&[]);
    if devices.is_empty() {
        return s.empty("No device fit in this run (no hardware model).");
    }
    s.text(format!("The thesis's design fitted to each device: used and available resources, and the largest number of intersection units that still fits. A design that fits but uses more than {ROUTING_HEADROOM_PERCENT} % of the logic elements or memory bits, or more than {MEMORY_BLOCK_HEADROOM_PERCENT} % of the RAM blocks, fits on paper only: Quartus rarely routes a device that full, or meets timing on it (the routing-headroom rules, docs/hardware-model.md). Memory takes whole blocks: each delay line, scene word and the frame buffer its own."));
    let mut t = Table::new(vec![
        Column::text("device"),
        Column::text("fits"),
        Column::number("logic elements"),
        Column::number("9-bit multipliers"),
        Column::number("memory bits"),
        Column::number("memory blocks"),
        Column::number("PLLs"),
        Column::number("largest K that fits").detail("on paper"),
    ]);
    for d in devices {
        t.rows.push(device_row(d));
    }
    s.blocks.push(Block::Table(t));
    for d in devices {
        if let Some(warning) = headroom_warning_of(d) {
            s.blocks.push(Block::note(
                Tone::Warning,
                format!("{}: {warning}.", d.device),
            ));
        }
    }
    if let Some(figure) = b.chart("device-utilization", 10.0) {
        s.blocks.push(figure);
    }
    s
}

fn device_row(d: &DeviceUse) -> Vec<Cell> {
    let usage = |used: u64, capacity: u64, over: bool| {
        Cell::number(
            format::usage(used, capacity),
            format::percent_of(used, capacity),
        )
        .tone(if over { Tone::Bad } else { Tone::Neutral })
    };
    // Logic and memory: a warning above the routing headroom, bad when they run out.
    let headroom_usage = |resource: &str, used: u64, capacity: u64| {
        let cell = usage(used, capacity, used >= capacity);
        if used < capacity && above_headroom(resource, used, capacity) {
            cell.tone(Tone::Warning).detail(format!(
                "above the {} % headroom",
                headroom_percent(resource)
            ))
        } else {
            cell
        }
    };
    let state = fit_state(d);
    let state_tone = match state {
        FitState::Fits => Tone::Good,
        FitState::FitsOnPaper => Tone::Warning,
        FitState::DoesNotFit => Tone::Bad,
    };
    let mut mult = usage(
        d.mult,
        d.mult_capacity,
        d.mult + d.soft_mult_elements >= d.mult_capacity,
    );
    if d.soft_mult_elements > 0 {
        mult = mult.detail(format!(
            "+ {} built in logic",
            format::count(d.soft_mult_elements)
        ));
    }
    let mut device = Cell::text(&d.device);
    if !d.validated {
        device = device.detail("(unvalidated)");
    }
    vec![
        device,
        Cell::text(state.label()).tone(state_tone),
        headroom_usage("le", d.le, d.le_capacity),
        mult,
        headroom_usage("mem_bits", d.mem_bits, d.mem_capacity),
        if d.mem_block_capacity > 0 {
            headroom_usage("mem_blocks", d.mem_blocks, d.mem_block_capacity)
        } else {
            Cell::dash()
        },
        usage(
            u64::from(d.plls),
            u64::from(d.pll_capacity),
            d.plls >= d.pll_capacity,
        ),
        match d.largest_units {
            Some(k) => Cell::count(u64::from(k)),
            None => Cell::dash(),
        },
    ]
}

pub fn sw_hw(b: &mut Builder) -> Section {
    let mut s = b.section(
        "sw-hw",
        Some("fig. 49 (software and hardware times), fig. 50 (gain per scene: 4.6 to 18), ch. 7's software-vs-hardware RMS (26.6 on both5)"),
    );
    let r = b.results();
    let scenes: Vec<&SceneResult> = r.scenes.iter().filter(|s| s.hardware.is_some()).collect();
    if scenes.is_empty() {
        return s.empty("No scene ran on the hardware model (it takes spheres and cylinders only: the test-bench scenes).");
    }
    s.text("The software's diffuse-only gray render (baseline) against the hardware model's frame time, and the emulator's image against the software's. The emulator keeps the thesis's sphere and cylinder arithmetic (its discriminant b² - c in single precision, the pipeline being studied), while the software's tests compute the discriminant without cancellation: on small or far primitives part of the image difference is the thesis formula's rounding.");
    for id in ["sw-hw-times", "hw-speedup"] {
        if let Some(figure) = b.chart(id, 10.0) {
            s.blocks.push(figure);
        }
    }
    let mut t = Table::new(vec![
        Column::text("scene"),
        Column::number("primitives"),
        Column::number("cycles"),
        Column::number("hardware time"),
        Column::number("software time").detail("[95 % interval]"),
        Column::number("speed-up"),
        Column::text("fits"),
        Column::number("emulator RMS"),
        Column::text("band"),
    ])
    .sortable();
    for scene in &scenes {
        let Some(h) = &scene.hardware else { continue };
        let band = h.emulator_band;
        t.rows.push(vec![
            Cell::text(&scene.name),
            Cell::count(h.primitives),
            Cell::count(h.cycles),
            Cell::number(format::seconds(h.seconds), h.seconds),
            Cell::estimate(
                h.software_seconds.median,
                h.software_seconds.low,
                h.software_seconds.high,
            ),
            Cell::number(format::speedup(h.speedup), h.speedup),
            Cell::text(if h.fits { "yes" } else { "no" }).tone(Tone::of_yes(h.fits)),
            Cell::number(format::fixed(h.emulator_rms, 2), h.emulator_rms),
            Cell::text(band.name()).tone(Tone::of_band(band)),
        ]);
    }
    s.blocks.push(Block::Table(t));
    s.blocks
        .push(Block::heading("Emulator and software images"));
    s.text("Each column: the software's diffuse-only gray render above the hardware emulator's image of the same scene.");
    let columns = scenes.len().min(GRID_COLUMNS);
    for chunk in scenes.chunks(GRID_COLUMNS) {
        let mut software = Vec::new();
        let mut emulator = Vec::new();
        for scene in chunk {
            let Some(h) = &scene.hardware else { continue };
            let size = (scene.width, scene.height);
            let band = h.emulator_band;
            software.push(Tile {
                visual: b.picture(
                    h.software_image.as_deref(),
                    &format!("{} software", scene.name),
                    size,
                ),
                caption: scene.name.clone(),
                tone: Tone::Neutral,
            });
            emulator.push(Tile {
                visual: b.picture(
                    h.emulator_image.as_deref(),
                    &format!("{} emulator", scene.name),
                    size,
                ),
                caption: format!("RMS {} ({})", format::fixed(h.emulator_rms, 1), band.name()),
                tone: Tone::of_band(band),
            });
        }
        s.blocks.push(Block::ImageGrid(ImageGrid::from_rows(
            columns,
            vec!["software".to_string(), "emulator".to_string()],
            vec![software, emulator],
        )));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use hwmodel::library::Resources;
    use hwmodel::optimizations::OptimizationCost;

    fn row(label: &str, design: hwmodel::design::Design, fill: u64, le: u64) -> OptimizationCost {
        let per_pixel = 3 * 7_u64.div_ceil(u64::from(design.units));
        let cycles = 640 * 480 * per_pixel + fill;
        OptimizationCost {
            label: label.to_string(),
            design,
            fill_cycles: fill,
            cycles_per_pixel: per_pixel,
            frame_cycles: cycles,
            frame_seconds: cycles as f64 / 50e6,
            used: Resources {
                le,
                ..Resources::default()
            },
            multipliers_asked: 0,
            state: FitState::Fits,
        }
    }

    #[test]
    fn the_optimizations_sentence_is_a_hand_computation() {
        let thesis = hwmodel::design::Design::thesis();
        let saving = hwmodel::design::Design {
            fast_sqrt: true,
            ortho: true,
            no_rsqrt_shading: true,
            ..thesis
        };
        let rows = [
            row("thesis", thesis, 324, 100_000),
            row("the three together", saving, 224, 75_000),
            row(
                "the three together, 2 units",
                hwmodel::design::Design { units: 2, ..saving },
                330,
                140_000,
            ),
        ];
        let said = optimizations_sentence(&rows, "EP4CE115").unwrap_or_default();
        // 640·480·21 + 324 = 6,451,524 cycles at 50 MHz: 129.03 ms; 25,000 LEs are
        // 25 % of 100,000; the fill shortens by 100 cycles, which is 2 µs of the frame;
        // two units: 640·480·12 + 330 = 3,686,730 cycles, 73.7 ms.
        assert!(said.contains("takes 129 ms a frame"), "{said}");
        assert!(
            said.contains("free 25,000 logic elements (25 % of the design's)"),
            "{said}"
        );
        assert!(
            said.contains("shorten the fill by 100 cycles, but the frame only by 2.00 µs"),
            "{said}"
        );
        assert!(
            said.contains("with them, 2 units fit and take the frame to 73.7 ms"),
            "{said}"
        );
        // Above the routing headroom the units fit on paper only, and the sentence says so.
        let mut on_paper = rows.clone();
        on_paper[2].state = FitState::FitsOnPaper;
        let said = optimizations_sentence(&on_paper, "EP4CE115").unwrap_or_default();
        assert!(
            said.contains("with them, 2 units fit, but only on paper (above the routing headroom), and would take the frame to 73.7 ms"),
            "{said}"
        );
    }

    #[test]
    fn a_figure_the_thesis_does_not_have_is_coloured_not_dashed() {
        let mut hw = testkit::sample_results().hardware.expect("hardware");
        let row = &mut hw.blocks[0];
        // The thesis has no memory bits in this block; the model has 4,320.
        row.thesis.as_mut().unwrap().mem_bits = 0;
        row.model.mem_bits = 4_320;
        if let Some(e) = row.error_pct.as_mut() {
            e.mem_bits = None;
        }
        let t = hw_table(&hw.blocks[..1]);
        let mem = HwColumn::ALL
            .iter()
            .position(|c| *c == HwColumn::MemBits)
            .unwrap()
            + 2;
        let cell = &t.rows[0][mem];
        assert_eq!(cell.text, "4,320");
        assert_eq!(cell.detail.as_deref(), Some("/ 0 (the thesis has none)"));
        assert_eq!(cell.tone, Tone::Bad);
    }

    #[test]
    fn a_device_row_marks_logic_above_the_routing_headroom() {
        let mut d = testkit::sample_results()
            .hardware
            .expect("hardware")
            .devices[0]
            .clone();
        assert_eq!(d.le_capacity, 114_480);
        // The rule applied to the figures, as for a file written before `fit_state`.
        d.fit_state = None;
        // 50 %: fits, the LE cell neutral.
        d.le = 57_240;
        let row = device_row(&d);
        assert_eq!((row[1].text.as_str(), row[1].tone), ("yes", Tone::Good));
        assert_eq!(
            (row[2].tone, row[2].detail.as_deref()),
            (Tone::Neutral, None)
        );
        // 99 %: fits on paper only, the LE cell a warning that says why.
        d.le = 113_335;
        let row = device_row(&d);
        assert_eq!(
            (row[1].text.as_str(), row[1].tone),
            ("on paper only", Tone::Warning)
        );
        assert_eq!(
            (row[2].tone, row[2].detail.as_deref()),
            (Tone::Warning, Some("above the 85 % headroom"))
        );
        // Over the device: does not fit, the LE cell bad.
        d.le = 114_481;
        d.fits = false;
        let row = device_row(&d);
        assert_eq!((row[1].text.as_str(), row[1].tone), ("no", Tone::Bad));
        assert_eq!(row[2].tone, Tone::Bad);
    }
}
