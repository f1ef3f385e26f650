//! The generated pipeline through Yosys (`synth_intel -family cycloneive`): it maps to
//! device cells without errors, and each block's flip-flops cover the registers its
//! structure must hold.
//!
//! Needs `yosys` (`scripts/install-rtl-tools.sh`): `cargo test -p rtl --test synthesis
//! -- --ignored`.

use hwmodel::blocks::{ADDRESS_BITS, Pipeline};
use hwmodel::design::Design;
use hwmodel::library::{Library, OpKind};
use rtl::{generate, synth};

fn synthesize(design: Design, block: Option<&str>) -> synth::SynthReport {
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &design);
    let dir = std::env::temp_dir().join(format!(
        "rtprof-synth-test-{}-{}-{}",
        block.unwrap_or(generate::TOP),
        design.label(),
        std::process::id()
    ));
    let report =
        synth::synthesize_design(&lib, &pipeline, block, &dir).unwrap_or_else(|e| panic!("{e}"));
    let top = &report.top;
    eprintln!(
        "{top} ({}): {:?} in {:.0} s; blocks {:?}",
        design.label(),
        report.total,
        report.seconds,
        report
            .blocks
            .iter()
            .map(|b| (b.block.as_str(), b.figures))
            .collect::<Vec<_>>()
    );
    assert!(report.unmapped.is_empty(), "{:?}", report.unmapped);
    assert_eq!(report.check_problems, 0);
    report
}

#[test]
#[ignore = "needs yosys"]
fn the_minimum_distance_block_synthesizes_with_its_registers() {
    let report = synthesize(Design::thesis(), Some("min_distance"));
    let lib = Library::cyclone_iv_e();
    // The kept registers (5 words and the address: 173 bits, fig. 25) and the payload
    // beside the compare (compare latency × the same 173 bits, plus 3 flag bits).
    let word = 5 * 32 + u64::from(ADDRESS_BITS);
    let compare = u64::from(lib.op(OpKind::Compare).latency);
    assert!(
        report.total.ff >= word * (1 + compare),
        "{} flip-flops < {}",
        report.total.ff,
        word * (1 + compare)
    );
    assert!(report.total.lut4 > 0);
    assert_eq!(report.total.mult_lut4, 0, "no multiplier in this block");
}

#[test]
#[ignore = "needs yosys; several minutes"]
fn the_whole_thesis_design_synthesizes_block_by_block() {
    let blocks = ["primary_ray", "intersection", "min_distance", "shading"];
    let report = synthesize(Design::thesis(), None);
    assert_eq!(report.top, generate::TOP);
    for name in blocks {
        let b = report
            .block(name)
            .unwrap_or_else(|| panic!("no figures for {name}"));
        assert!(
            b.figures.lut4 > 0 && b.figures.ff > 0,
            "{name}: {:?}",
            b.figures
        );
    }
    // Multipliers: 3 + 21·... every block but the minimum distance has some.
    for name in ["primary_ray", "intersection", "shading"] {
        let b = report.block(name).map(|b| b.figures.mult_lut4).unwrap_or(0);
        assert!(b > 0, "{name}: no multiplier logic");
    }
}
