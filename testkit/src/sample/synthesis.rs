//! The sample run's synthesis of the thesis design's RTL.

/// A synthesis of the thesis design's four blocks (made-up figures of the size Yosys
/// gives, consistent with the estimate's rule: 1 + 1.5 × levels ns), with the whole
/// design's deepest path one level over the 50 MHz limit, so that the report names it.
pub(super) fn sample_synthesis() -> results::Synthesis {
    let block = |name: &str, lut4: u64, mult_lut4: u64, ff: u64, mem_bits: u64, levels: u64| {
        let fmax_mhz = 1000.0 / (1.0 + 1.5 * levels as f64);
        results::SynthBlock {
            name: name.to_string(),
            lut4,
            mult_lut4,
            ff,
            mem_bits,
            m9k: mem_bits.div_ceil(9216),
            levels,
            path_from: format!("\\{name}.a [0]"),
            path_to: format!("\\{name}.r [0]"),
            fmax_mhz,
            closes: fmax_mhz >= 50.0,
        }
    };
    results::Synthesis {
        design: "thesis".to_string(),
        tool: "Yosys 0.23 (git sha1 7ce5011c24b)".to_string(),
        flow: "synth_intel -family cycloneive (the default script), hierarchy kept".to_string(),
        seconds: 612.0,
        rtl_hash: "0123456789abcdef".to_string(),
        clock_mhz: 50.0,
        level_ns: 1.5,
        register_ns: 1.0,
        max_levels: 12,
        blocks: vec![
            block("primary_ray", 52_000, 24_000, 9_000, 4_320, 11),
            block("intersection", 140_000, 56_000, 26_000, 53_758, 11),
            block("min_distance", 400, 0, 700, 0, 9),
            block("shading", 105_000, 44_000, 19_000, 30_000, 11),
        ],
        total: block("whole design", 300_000, 124_000, 56_000, 1_000_000, 13),
    }
}
