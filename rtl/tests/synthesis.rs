//! The generated pipeline through Yosys's default `synth_intel -family cycloneive`
//! script: it maps to device cells without errors, each block's flip-flops cover the
//! registers its structure must hold, and its longest path between registers is within
//! `rtl::synth::MAX_LUT_LEVELS`.
//!
//! Needs `yosys` (`scripts/install-rtl-tools.sh`): `cargo test -p rtl --test synthesis
//! -- --ignored`.

use hwmodel::blocks::{ADDRESS_BITS, Pipeline};
use hwmodel::design::{Design, MinDistance};
use hwmodel::library::{Library, OpKind};
use rtl::{generate, synth};

fn synthesize(design: Design, block: Option<&str>) -> synth::SynthComparison {
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &design);
    let dir = std::env::temp_dir().join(format!(
        "rtprof-synth-test-{}-{}-{}",
        block.unwrap_or(generate::TOP),
        design.label(),
        std::process::id()
    ));
    let comparison =
        synth::synthesize_design(&lib, &pipeline, block, &dir).unwrap_or_else(|e| panic!("{e}"));
    let s = &comparison.synthesis;
    eprintln!(
        "{} design ({}), {:.0} s: {:?}",
        s.design,
        block.unwrap_or("every block"),
        s.seconds,
        s.blocks
            .iter()
            .chain([&s.total])
            .map(|b| (
                b.name.as_str(),
                b.lut4,
                b.mult_lut4,
                b.ff,
                b.levels,
                b.fmax_mhz
            ))
            .collect::<Vec<_>>()
    );
    assert!(comparison.unmapped.is_empty(), "{:?}", comparison.unmapped);
    assert_eq!(comparison.check_problems, 0);
    // The estimate follows the depth by the documented rule.
    for b in s.blocks.iter().chain([&s.total]) {
        assert_eq!(b.closes, b.levels <= s.max_levels, "{b:?}");
        assert!(
            (b.fmax_mhz - 1000.0 / (s.register_ns + b.levels as f64 * s.level_ns)).abs() < 1e-9
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    comparison
}

/// The minimum-distance block alone (seconds: CI runs it) through the default script:
/// its registers, and its longest path within the 12 levels (the kept distance fed back
/// through the load select into the compare's first stage).
#[test]
#[ignore = "needs yosys"]
fn the_minimum_distance_block_synthesizes_with_its_registers_and_depth() {
    let comparison = synthesize(Design::thesis(), Some("min_distance"));
    let lib = Library::cyclone_iv_e();
    let s = &comparison.synthesis;
    // The kept registers (5 words and the address: 173 bits, fig. 25) and the payload
    // beside the compare (compare latency × the same 173 bits, plus 3 flag bits).
    let word = 5 * 32 + u64::from(ADDRESS_BITS);
    let compare = u64::from(lib.op(OpKind::Compare).latency);
    assert!(
        s.total.ff >= word * (1 + compare),
        "{} flip-flops < {}",
        s.total.ff,
        word * (1 + compare)
    );
    assert!(s.total.lut4 > 0);
    assert_eq!(s.total.mult_lut4, 0, "no multiplier in this block");
    assert_eq!(s.blocks.len(), 1);
    assert_eq!(s.blocks[0], synth_block_named(&s.total, "min_distance"));
    assert!(
        s.total.levels > 0 && s.total.levels <= synth::MAX_LUT_LEVELS,
        "{:?}",
        s.total
    );
    // The model's and the thesis's rows come with it.
    assert!(
        comparison
            .model
            .iter()
            .any(|r| r.name == "min_distance" && r.thesis.is_some())
    );
}

/// The integer compare's block (seconds): the 31-bit compare, the +∞ select and the
/// registers' load enable between the kept registers and themselves, within the 12
/// levels; only the kept registers (173 bits) and the done flag, no payload line.
#[test]
#[ignore = "needs yosys"]
fn the_integer_compare_block_is_its_kept_registers_within_the_depth() {
    let design = Design {
        min_distance: MinDistance::IntegerCompare,
        ..Design::thesis()
    };
    let s = synthesize(design, Some("min_distance")).synthesis;
    let word = 5 * 32 + u64::from(ADDRESS_BITS);
    assert_eq!(s.total.ff, word + 1, "{:?}", s.total);
    assert_eq!(s.total.mult_lut4, 0);
    assert!(
        s.total.levels > 0 && s.total.levels <= synth::MAX_LUT_LEVELS,
        "{:?}",
        s.total
    );
}

fn synth_block_named(b: &results::SynthBlock, name: &str) -> results::SynthBlock {
    results::SynthBlock {
        name: name.to_string(),
        ..b.clone()
    }
}

/// The top's own logic (iterator, scene memory ports, padding, control delay lines)
/// with every block a black box, K = 1 and 2, a slot every 3 cycles and every cycle
/// (seconds: CI runs it): its paths between
/// its registers, inputs and the blocks' ports within the 12 levels. A path that runs
/// on into a block (as the padding compare's did, 18 levels, before its flag was
/// registered) ends here at the block's input: the whole-design test below measures
/// those.
#[test]
#[ignore = "needs yosys"]
fn the_tops_own_logic_is_within_twelve_levels() {
    let designs = [1, 2].into_iter().flat_map(|units| {
        [MinDistance::FloatCompare, MinDistance::IntegerCompare].map(|min_distance| Design {
            units,
            min_distance,
            ..Design::thesis()
        })
    });
    for design in designs {
        let comparison = synthesize(design, Some(generate::TOP));
        let s = &comparison.synthesis;
        assert_eq!(s.blocks.len(), 1);
        assert_eq!(s.blocks[0].name, generate::TOP);
        // The blocks count in no figure: the top alone is a few thousand cells, not
        // the hundreds of thousands of the whole design, and has no multiplier.
        assert_eq!(s.total.mult_lut4, 0, "{:?}", s.total);
        assert!(s.total.lut4 > 0 && s.total.lut4 < 20_000, "{:?}", s.total);
        // The slot and flag delay lines alone are registers.
        assert!(s.total.ff > 0, "{:?}", s.total);
        assert!(
            s.total.levels > 0 && s.total.levels <= synth::MAX_LUT_LEVELS,
            "{}: {:?}",
            design.label(),
            s.total
        );
    }
}

/// The whole thesis design through the default script (about 1.5 minutes of CPU,
/// 3.1 GB): every block has logic and, but the minimum distance, multipliers; every
/// block and the whole design (flattened, across the blocks and the top's logic)
/// within the 12 levels.
#[test]
#[ignore = "needs yosys; minutes"]
fn the_whole_thesis_design_synthesizes_block_by_block() {
    let comparison = synthesize(Design::thesis(), None);
    let s = &comparison.synthesis;
    let names: Vec<&str> = s.blocks.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(
        names,
        ["primary_ray", "intersection", "min_distance", "shading"]
    );
    for b in &s.blocks {
        assert!(b.lut4 > 0 && b.ff > 0, "{b:?}");
        assert_eq!(b.mult_lut4 > 0, b.name != "min_distance", "{b:?}");
        assert!(b.lut4 <= s.total.lut4 && b.ff <= s.total.ff, "{b:?}");
        assert!(b.levels <= synth::MAX_LUT_LEVELS, "{b:?}");
    }
    // The flattened design's path is at least as deep as any block's, and the top's
    // own logic (the padding flag registered beside the slot) adds no level above 12.
    assert!(s.total.levels >= s.blocks.iter().map(|b| b.levels).max().unwrap_or(0));
    assert!(s.total.levels <= synth::MAX_LUT_LEVELS, "{:?}", s.total);
    assert!(s.total.closes, "{:?}", s.total);
}
