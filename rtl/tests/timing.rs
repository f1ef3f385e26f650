//! Timing evidence: every operator of the Verilog library, at its latency in hwmodel's
//! Cyclone IV E library, has at most `rtl::synth::MAX_LUT_LEVELS` (12) LUT levels
//! between registers after Yosys's default `synth_intel -family cycloneive`, which the
//! estimated-Fmax rule (`rtl::synth::fmax`) puts at 50 MHz or more; and the depth tool
//! itself measures a design whose depth is known.
//!
//! The tests after them place and route with nextpnr-ice40 on an iCE40 HX8K: one
//! operator, every operator, and the two larger than the device stage by stage
//! (`rtl::synth::stages`), with the stage-by-stage cut checked against an operator
//! that fits whole.
//!
//! Needs `yosys` and `nextpnr-ice40` (`scripts/install-rtl-tools.sh`):
//! `cargo test -p rtl --test timing -- --ignored`.

use std::path::PathBuf;
use std::time::Duration;

use hwmodel::library::Library;
use rtl::Operator;
use rtl::synth::{self, fmax};

/// Per run; the deepest operators take about a minute on a loaded 2-core machine.
const TIMEOUT: Duration = Duration::from_secs(900);

fn dir(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("rtl-timing")
        .join(name)
}

fn check(op: Operator) {
    let lib = Library::cyclone_iv_e();
    let report = synth::operator_depth(op, &lib, &dir(op.module_name()), TIMEOUT)
        .unwrap_or_else(|e| panic!("{e}"));
    let fmax = report.estimated_fmax_mhz();
    eprintln!(
        "{} (LATENCY {}): {} LUT levels ({} -> {}), {} LUT4, {} FF, est. {fmax:.1} MHz, {:.0} s",
        op.module_name(),
        op.latency(&lib),
        report.levels,
        report.from,
        report.to,
        report.lut4,
        report.ff,
        report.seconds
    );
    assert!(
        report.other_cells.is_empty(),
        "{}: unmapped cells {:?}",
        op.module_name(),
        report.other_cells
    );
    assert!(
        report.levels <= synth::MAX_LUT_LEVELS,
        "{}: {} LUT levels between registers (from {} to {}), more than {}",
        op.module_name(),
        report.levels,
        report.from,
        report.to,
        synth::MAX_LUT_LEVELS
    );
    assert!(fmax >= fmax::THESIS_CLOCK_MHZ, "{fmax} MHz");
    // A clocked operator registers its result: at least one flip-flop per cycle of
    // latency (a constant output bit, like fp_fast_sqrt's sign, needs none).
    assert!(
        report.ff >= u64::from(op.latency(&lib)),
        "{}: {} flip-flops",
        op.module_name(),
        report.ff
    );
}

macro_rules! depth_tests {
    ($($name:ident: $op:expr;)*) => {$(
        #[test]
        #[ignore = "needs yosys"]
        fn $name() {
            check($op);
        }
    )*};
}

depth_tests! {
    fp_add_sub_is_within_the_depth: Operator::AddSub;
    fp_mul_is_within_the_depth: Operator::Multiply;
    fp_div_is_within_the_depth: Operator::Divide;
    fp_sqrt_is_within_the_depth: Operator::Sqrt;
    fp_inv_sqrt_is_within_the_depth: Operator::InvSqrt;
    fp_compare_is_within_the_depth: Operator::Compare;
    fp_from_int_is_within_the_depth: Operator::FromInt;
    fp_to_u8_is_within_the_depth: Operator::ToU8;
    fp_fast_sqrt_is_within_the_depth: Operator::FastSqrt;
    fp_select_is_within_the_depth: Operator::Select;
    fp_register_is_within_the_depth: Operator::Register;
}

/// The tool against designs of known depth: an AND of 16 registered bits needs two
/// levels of 4-input LUTs (16 → 4 → 1) and one of 64 bits three; the first is no
/// deeper because its inputs are registered apart from its output.
#[test]
#[ignore = "needs yosys"]
fn the_depth_of_a_wide_and_is_its_lut_tree() {
    for (bits, levels) in [(16, 2), (64, 3)] {
        let name = format!("and{bits}");
        let d = dir(&name);
        std::fs::create_dir_all(&d).unwrap();
        let file = d.join("and.v");
        std::fs::write(
            &file,
            "module wide_and #(parameter N = 16) (input clk, input [N-1:0] a, output reg y);\n\
             reg [N-1:0] r;\n\
             always @(posedge clk) begin r <= a; y <= &r; end\n\
             endmodule\n",
        )
        .unwrap();
        let report = synth::logic_depth(&d, &[file], "wide_and", &[("N", bits)], TIMEOUT)
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(report.levels, levels, "{bits} bits: {report:?}");
        assert_eq!(report.ff, bits as u64 + 1);
    }
}

/// Real place and route: the multiplier, inputs registered, on an iCE40 HX8K meets the
/// thesis's 50 MHz by nextpnr's own timing analysis (before issue 38 its path from the
/// inputs to the first register alone was 49.95 ns).
#[test]
#[ignore = "needs yosys and nextpnr-ice40"]
fn fp_mul_places_and_routes_at_50_mhz_on_an_ice40() {
    let lib = Library::cyclone_iv_e();
    let report = synth::place_and_route_ice40(
        Operator::Multiply,
        &lib,
        &dir("pnr-fp_mul"),
        fmax::THESIS_CLOCK_MHZ,
        TIMEOUT,
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .routed;
    eprintln!(
        "fp_mul on iCE40 {}: {:.2} MHz after routing, {} of {} logic cells, synthesis {:.0} s, place and route {:.0} s",
        synth::ice40::DEVICE,
        report.fmax_mhz,
        report.logic_cells,
        report.device_logic_cells,
        report.synth_seconds,
        report.pnr_seconds
    );
    assert!(report.logic_cells > 0 && report.logic_cells <= report.device_logic_cells);
    assert!(
        report.fmax_mhz >= fmax::THESIS_CLOCK_MHZ,
        "{:.2} MHz (log: {})",
        report.fmax_mhz,
        report.log.display()
    );
}

/// The minimum-distance block (written by hand, its kept distance fed back into its
/// own compare) within the depth too: the loop runs from the compare's result register
/// through the load select and the compare's first stage.
#[test]
#[ignore = "needs yosys"]
fn the_minimum_distance_block_is_within_the_depth() {
    let lib = Library::cyclone_iv_e();
    let pipeline = hwmodel::blocks::Pipeline::build(&lib, &hwmodel::design::Design::thesis());
    let rtl = rtl::generate::generate(&lib, &pipeline, 6).unwrap_or_else(|e| panic!("{e}"));
    let d = dir("min_distance");
    let src = d.join("src");
    rtl::generate::write(&rtl, &src).unwrap_or_else(|e| panic!("{e}"));
    let files: Vec<PathBuf> = rtl
        .files
        .iter()
        .filter(|(name, _)| name.ends_with(".v"))
        .map(|(name, _)| src.join(name))
        .collect();
    let report = synth::logic_depth(&d, &files, "min_distance", &[], TIMEOUT)
        .unwrap_or_else(|e| panic!("{e}"));
    eprintln!(
        "min_distance: {} LUT levels ({} -> {}), {} LUT4, {} FF",
        report.levels, report.from, report.to, report.lut4, report.ff
    );
    assert!(report.levels <= synth::MAX_LUT_LEVELS, "{report:?}");
}

/// The operators larger than the iCE40 HX8K's 7,680 logic cells: the divider's 13
/// stages of two quotient digits on prefix adders (8,266 cells after `synth_ice40`),
/// and the inverse square root, which holds a divider and a square root.
const LARGER_THAN_THE_HX8K: [Operator; 2] = [Operator::Divide, Operator::InvSqrt];

/// Every clocked operator placed and routed, inputs registered, on an iCE40 HX8K (the
/// combinational `fp_select` and the clockless `fp_const` have no path between
/// registers of their own): nextpnr's Fmax after routing at 50 MHz or more, printed
/// beside the depth and the estimated Fmax on Cyclone IV E (docs/hardware-model.md's
/// table); the operators too large for the device fail to place, as nextpnr says
/// (their figure comes stage by stage, below).
#[test]
#[ignore = "needs yosys and nextpnr-ice40; tens of minutes"]
fn every_clocked_operator_places_and_routes_on_an_ice40() {
    let lib = Library::cyclone_iv_e();
    let mut failures = Vec::new();
    for op in Operator::ALL {
        if matches!(op, Operator::Const | Operator::Select) {
            continue;
        }
        let name = op.module_name();
        // Directories of its own: the tests above run beside it on the same operators.
        let depth = synth::operator_depth(op, &lib, &dir(&format!("every-{name}")), TIMEOUT)
            .unwrap_or_else(|e| panic!("{e}"));
        let pnr = synth::place_and_route_ice40(
            op,
            &lib,
            &dir(&format!("every-pnr-{name}")),
            fmax::THESIS_CLOCK_MHZ,
            TIMEOUT,
        );
        let too_large = LARGER_THAN_THE_HX8K.contains(&op);
        match pnr.map(|p| p.routed) {
            Ok(r) => {
                eprintln!(
                    "| {name} | {} | {} | {} | {} | {:.1} MHz | {} | {:.1} MHz |",
                    op.latency(&lib),
                    depth.levels,
                    depth.lut4,
                    depth.ff,
                    depth.estimated_fmax_mhz(),
                    r.logic_cells,
                    r.fmax_mhz
                );
                if too_large {
                    failures.push(format!("{name}: fits the HX8K now ({r:?})"));
                } else if r.fmax_mhz < fmax::THESIS_CLOCK_MHZ {
                    failures.push(format!("{name}: {:.2} MHz", r.fmax_mhz));
                }
            }
            Err(e) => {
                let text = e.to_string();
                eprintln!(
                    "| {name} | {} | {} | {} | {} | {:.1} MHz | does not fit | |",
                    op.latency(&lib),
                    depth.levels,
                    depth.lut4,
                    depth.ff,
                    depth.estimated_fmax_mhz()
                );
                // nextpnr runs out of logic cells, and nothing else goes wrong.
                let out_of_cells =
                    text.contains("no BELs remaining to implement cell type 'ICESTORM_LC'");
                if !(too_large && out_of_cells) {
                    failures.push(format!("{name}: {text}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Places and routes `op` in pieces of `stages_per_piece` stages and prints them.
fn staged(op: Operator, name: &str, stages_per_piece: u32) -> synth::StagedPnrReport {
    let lib = Library::cyclone_iv_e();
    let report = synth::place_and_route_stages(
        op,
        &lib,
        &dir(name),
        stages_per_piece,
        fmax::THESIS_CLOCK_MHZ,
        TIMEOUT,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    for p in &report.pieces {
        match &p.routed {
            Some(r) => eprintln!(
                "{} stages {}..{}: {} coarse cells, {} in, {} out: {} logic cells, {:.2} MHz, {:.0} + {:.0} s",
                report.module,
                p.first_stage,
                p.last_stage,
                p.coarse_cells,
                p.inputs,
                p.outputs,
                r.logic_cells,
                r.fmax_mhz,
                r.synth_seconds,
                r.pnr_seconds
            ),
            None => eprintln!("{} stage {}: no logic", report.module, p.first_stage),
        }
    }
    eprintln!(
        "{}: {} pieces, worst {:?} MHz, {:.0} s in all; {} coarse cells, {} driving nothing",
        report.module,
        report.pieces.len(),
        report.fmax_mhz(),
        report.seconds,
        report.coarse_cells,
        report.dead_cells
    );
    // The cut is complete: the input registers, then one register level per stage of
    // the library's latency, every logic cell in a piece, every stage in one piece.
    let latency = op.latency(&lib);
    assert_eq!(report.register_levels, latency + 1, "{report:#?}");
    assert_eq!(report.logic_before_the_inputs, 0);
    assert_eq!(report.uncovered_cells, 0, "{report:#?}");
    assert_eq!(report.stages_covered(), (1..=latency).collect::<Vec<_>>());
    report
}

/// The operators larger than the HX8K get their Fmax from their stages placed and
/// routed apart (`rtl::synth::stages`): every stage at 50 MHz or more on the HX8K,
/// each inside the device. Optimistic for a stage inside the whole operator (less
/// congestion), conservative against the thesis's faster Cyclone IV E.
#[test]
#[ignore = "needs yosys and nextpnr-ice40; about 5 minutes"]
fn the_operators_larger_than_the_hx8k_close_50_mhz_stage_by_stage() {
    let mut failures = Vec::new();
    for op in LARGER_THAN_THE_HX8K {
        let name = op.module_name();
        let report = staged(op, &format!("stages-{name}"), 1);
        for p in &report.pieces {
            let Some(r) = &p.routed else {
                failures.push(format!("{name} stage {}: no logic", p.first_stage));
                continue;
            };
            assert!(r.logic_cells <= r.device_logic_cells, "{p:?}");
            if r.fmax_mhz < fmax::THESIS_CLOCK_MHZ {
                failures.push(format!(
                    "{name} stage {}: {:.2} MHz (log: {})",
                    p.first_stage,
                    r.fmax_mhz,
                    r.log.display()
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The cut against an operator that fits whole: the square root's stages placed and
/// routed apart. Its slowest stage is the whole operator's critical path, so the two
/// Fmax agree within nextpnr's placement noise (the piece meets less congestion, so
/// it may be somewhat faster, never much slower); and the pieces hold the operator's
/// logic: their logic cells, less the harness's registers, add up to the whole's.
#[test]
#[ignore = "needs yosys and nextpnr-ice40; about 3 minutes"]
fn stage_by_stage_agrees_with_the_whole_square_root() {
    let lib = Library::cyclone_iv_e();
    let whole = synth::place_and_route_ice40(
        Operator::Sqrt,
        &lib,
        &dir("stages-whole-fp_sqrt"),
        fmax::THESIS_CLOCK_MHZ,
        TIMEOUT,
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .routed;
    let report = staged(Operator::Sqrt, "stages-fp_sqrt", 1);
    let worst = report.fmax_mhz().expect("a stage with logic");
    eprintln!(
        "fp_sqrt: whole {:.2} MHz, {} logic cells; worst stage {worst:.2} MHz",
        whole.fmax_mhz, whole.logic_cells
    );
    assert!(
        worst >= 0.9 * whole.fmax_mhz && worst <= 1.3 * whole.fmax_mhz,
        "worst stage {worst:.2} MHz, whole {:.2} MHz",
        whole.fmax_mhz
    );
    // The pieces hold the operator's logic once: their logic cells are at least the
    // whole's, and at most the whole's plus their harnesses' registers (one per input,
    // two per output, the load; iCE40 packs some of them beside a LUT), within 10 %.
    let (mut cells, mut harness) = (0u64, 0u64);
    for p in &report.pieces {
        if let Some(r) = &p.routed {
            cells += r.logic_cells;
            harness += (p.inputs + 2 * p.outputs + 1) as u64;
        }
    }
    let whole_cells = whole.logic_cells as f64;
    eprintln!("fp_sqrt: pieces {cells} logic cells, harnesses at most {harness}");
    assert!(
        cells as f64 >= 0.9 * whole_cells && cells as f64 <= 1.1 * whole_cells + harness as f64,
        "pieces {cells} logic cells (harnesses {harness}), whole {}",
        whole.logic_cells
    );
}

/// Congestion: the operators larger than the HX8K in a few large pieces, each about
/// half of the device or more (the divider in 8 + 7 stages, the inverse square root in
/// 10 + 10 + 8), close 50 MHz as well; their stages placed one by one reach about
/// 65 MHz, so the figures show what routing congestion costs.
#[test]
#[ignore = "needs yosys and nextpnr-ice40; about 6 minutes"]
fn the_operators_larger_than_the_hx8k_close_50_mhz_in_large_pieces() {
    let mut failures = Vec::new();
    for (op, stages, pieces) in [(Operator::Divide, 8, 2), (Operator::InvSqrt, 10, 3)] {
        let name = op.module_name();
        let report = staged(op, &format!("stages-{stages}-{name}"), stages);
        assert_eq!(report.pieces.len(), pieces);
        for p in &report.pieces {
            let r = p.routed.as_ref().expect("logic in each piece");
            assert!(r.logic_cells <= r.device_logic_cells, "{p:?}");
            if r.fmax_mhz < fmax::THESIS_CLOCK_MHZ {
                failures.push(format!(
                    "{name} stages {}..{}: {:.2} MHz (log: {})",
                    p.first_stage,
                    p.last_stage,
                    r.fmax_mhz,
                    r.log.display()
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
