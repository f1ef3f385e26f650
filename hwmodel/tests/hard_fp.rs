//! The Arria 10 library (`hwmodel/data/arria_10.toml`): a family with hard
//! floating-point DSP blocks, from Intel's published figures, unvalidated.
//!
//! The expectations here are typed from the sources the file cites (one DSP block per
//! hard add/sub or multiply, the devices' published capacities) and summed by hand
//! from the pipeline's operator counts and delay lines; none is the model's own output
//! copied back.

use hwmodel::blocks::{Block, Pipeline};
use hwmodel::design::Design;
use hwmodel::device::{
    FitState, MEMORY_BLOCK_HEADROOM_PERCENT, PLLS_USED, ROUTING_HEADROOM_PERCENT, demand, fit,
    fit_design, headroom_limit, memory_bits,
};
use hwmodel::library::{ARRIA_10, Library, OpKind, find_device};
use hwmodel::memory::design_blocks;

fn arria_10() -> Library {
    Library::from_toml(ARRIA_10, "arria_10.toml").unwrap()
}

/// DSP blocks per instance, from the sources: one hard adder or multiplier a block
/// (Arria 10 handbook 683461, "Resources"); the FP_FUNCTIONS divider's 4 (Floating-Point
/// IP Cores User Guide, section 16.5, Arria V row); the inverse square root's 34
/// nine-bit elements as 17 18 x 18 multipliers, two a block: 9.
fn blocks_each(op: OpKind) -> u64 {
    match op {
        OpKind::AddSub | OpKind::Multiply | OpKind::MultiplyRegistered => 1,
        OpKind::Divide => 4,
        OpKind::InvSqrt => 9,
        _ => 0,
    }
}

/// LE equivalents per instance of the soft cores, from the sources: ALTFP_SQRT and
/// ALTFP_INV_SQRT as in table 7, the FP_FUNCTIONS divider's 456 ALMs at 2.69 LE/ALM,
/// the comparator and converter as in the Cyclone IV E file. Hard rows: no logic.
fn le_each(op: OpKind) -> u64 {
    match op {
        OpKind::Sqrt => 1207,
        OpKind::Divide => 1227,
        OpKind::InvSqrt => 1948,
        OpKind::Compare => 96,
        OpKind::Convert => 380,
        OpKind::IntCompare | OpKind::FastSqrt => 32,
        _ => 0,
    }
}

/// Each block with the number of times the device holds it (K intersection units and
/// minimum-distance blocks).
fn blocks_with_copies(p: &Pipeline) -> Vec<(&Block, u64)> {
    let k = u64::from(p.design.units);
    let mut out = vec![(&p.primary_ray, 1), (&p.shading, 1)];
    out.push((&p.intersection, k));
    out.push((&p.min_distance, k));
    if let Some(tree) = &p.min_tree {
        out.push((tree, 1));
    }
    out
}

/// DSP blocks the design needs: operator counts from the schedules times the blocks
/// each operator takes.
fn dsp_blocks_by_hand(p: &Pipeline) -> u64 {
    blocks_with_copies(p)
        .iter()
        .map(|(b, copies)| {
            copies
                * b.schedule
                    .op_counts
                    .iter()
                    .map(|&(op, n)| u64::from(n) * blocks_each(op))
                    .sum::<u64>()
        })
        .sum()
}

#[test]
fn the_library_parses_unvalidated_with_every_operator_sourced() {
    let lib = arria_10();
    assert_eq!(lib.family, "Arria 10");
    assert!(!lib.validated);
    assert!(
        lib.note
            .as_deref()
            .is_some_and(|n| n.contains("DSP blocks"))
    );
    assert!(lib.devices.iter().all(|d| !d.validated));
    assert_eq!(lib.validated_device(), None);
    for op in OpKind::ALL {
        let row = lib.op(op);
        // Every row says where its figures come from: a named Intel document and table,
        // or an assumption with its reason.
        let s = &row.source;
        assert!(
            s.starts_with("assumed") || (s.contains("(6837") && s.contains("table")),
            "{}: {s}",
            op.key()
        );
    }
    // A file without one of the operators is refused with the operator's name.
    let text = ARRIA_10.replace("[ops.multiply]", "[ops.not_multiply]");
    let err = Library::from_toml(&text, "a.toml").unwrap_err().to_string();
    assert!(err.contains("`multiply`"), "{err}");
    // It is embedded, and its devices are found by name.
    assert!(Library::embedded().iter().any(|l| l.family == "Arria 10"));
    let (family, device) = find_device("10ax115").unwrap();
    assert_eq!(
        (family.family.as_str(), device.name.as_str()),
        ("Arria 10", "10AX115")
    );
    assert_eq!(find_device("10CX220").unwrap().1.mult, 192);
}

#[test]
fn the_hard_rows_are_one_dsp_block_without_logic_and_the_devices_their_published_counts() {
    let lib = arria_10();
    for op in [OpKind::AddSub, OpKind::Multiply, OpKind::MultiplyRegistered] {
        let row = lib.op(op);
        // Fully registered: input, pipeline and output register of the block.
        assert_eq!(row.latency, 3, "{}", op.key());
        let r = row.resources;
        assert_eq!((r.le, r.comb, r.regs, r.mem_bits, r.mult), (0, 0, 0, 0, 1));
    }
    // The divider: FP_FUNCTIONS, Arria V, single: 18 cycles, 456 ALMs, 5 M10K, 4 DSP,
    // 771 + 100 registers.
    let div = lib.op(OpKind::Divide);
    let r = div.resources;
    assert_eq!(div.latency, 18);
    assert_eq!(r.le, (456.0_f64 * 2.69).round() as u64);
    assert_eq!((r.regs, r.mem_bits, r.mult), (771 + 100, 5 * 10_240, 4));
    assert_eq!(
        lib.op(OpKind::InvSqrt).resources.mult,
        (34_u64 / 2).div_ceil(2)
    );
    // The soft fallback for a DSP block: FP_FUNCTIONS' soft adder, 360 ALMs.
    assert_eq!(lib.soft_mult9_le, (360.0_f64 * 2.69).round() as u64);
    assert_eq!(lib.soft_mult9_regs, 507 + 29);
    let caps: Vec<_> = lib
        .devices
        .iter()
        .map(|d| (d.name.as_str(), d.le, d.mult, d.mem_bits, d.plls))
        .collect();
    assert_eq!(
        caps,
        vec![
            // GX 1150: 1,150K LEs, 1,518 DSP blocks, 2,713 M20K blocks, 16 I/O PLLs.
            ("10AX115", 1_150_000, 1_518, 2_713 * 20_480, 16),
            // Cyclone 10 GX 220: 220K LEs, 192 DSP blocks, 11,740 Kb of M20K (587
            // blocks), 4 fractional + 6 I/O PLLs.
            ("10CX220", 220_000, 192, 587 * 20_480, 4 + 6),
        ]
    );
}

#[test]
fn the_primary_ray_takes_one_dsp_block_per_hard_operation() {
    let lib = arria_10();
    let p = Pipeline::build(&lib, &Design::thesis());
    // The primary ray is two vector x scalar (registered multipliers, three lanes
    // each), two vector add/sub (three adders each) and a normalize: a three-lane dot
    // product (3 multipliers, 2 adders), an inverse square root and a three-lane scale
    // (3 multipliers).
    let s = &p.primary_ray.schedule;
    assert_eq!(s.count(OpKind::MultiplyRegistered), 2 * 3);
    assert_eq!(s.count(OpKind::AddSub), 2 * 3 + 2);
    assert_eq!(s.count(OpKind::Multiply), 3 + 3);
    assert_eq!(s.count(OpKind::InvSqrt), 1);
    // 6 + 8 + 6 hard operations at one block each, and the inverse square root's 9.
    assert_eq!(p.primary_ray.resources().mult, 6 + 8 + 6 + 9);
    // Its latency: vector x scalar 3, vector add/sub 3, then normalize = dot product
    // (multiply 3 + two adder levels 3 + 3) + inverse square root 26 + scale 3.
    assert_eq!(p.primary_ray.latency(), 3 + 3 + (3 + 3 + 3) + 26 + 3);
}

#[test]
fn the_thesis_design_fits_both_devices_with_the_dsp_blocks_summed_by_hand() {
    let lib = arria_10();
    let design = Design::thesis();
    let p = Pipeline::build(&lib, &design);
    let (n, w, h) = (7, 640, 480);
    let d = demand(&lib, &p, n, w, h);

    // DSP blocks: every hard add/sub and multiply one block, dividers 4, inverse
    // square roots 9.
    let dsp = dsp_blocks_by_hand(&p);
    assert_eq!(d.mult, dsp);
    let hard: u64 = blocks_with_copies(&p)
        .iter()
        .map(|(b, c)| {
            c * [OpKind::AddSub, OpKind::Multiply, OpKind::MultiplyRegistered]
                .iter()
                .map(|&op| u64::from(b.schedule.count(op)))
                .sum::<u64>()
        })
        .sum();
    let soft_blocks = 4 * u64::from(p.intersection.schedule.count(OpKind::Divide))
        + 9 * u64::from(
            p.primary_ray.schedule.count(OpKind::InvSqrt)
                + p.shading.schedule.count(OpKind::InvSqrt),
        );
    assert_eq!(dsp, hard + soft_blocks);

    // Memory: the 8-bit frame, 9 words of 32 bits per primitive, the dividers' 5 M10K
    // each and every delay line the library sends to memory (16 cycles or more).
    let lines_in_memory: u64 = blocks_with_copies(&p)
        .iter()
        .map(|(b, c)| {
            c * b
                .schedule
                .delay_lines
                .iter()
                .filter(|l| l.cycles >= 16)
                .map(|l| u64::from(l.bits) * u64::from(l.cycles))
                .sum::<u64>()
        })
        .sum();
    let dividers = u64::from(p.intersection.schedule.count(OpKind::Divide));
    let mem = 640 * 480 * 8 + 7 * 9 * 32 + dividers * 5 * 10_240 + lines_in_memory;
    assert_eq!(memory_bits(&design, n, w, h), 640 * 480 * 8 + 7 * 9 * 32);
    assert_eq!(d.mem_bits, mem);

    // Logic: the glue (800 + 90 + 250), the delay lines and row registers kept in
    // registers, the soft cores at their rows' LEs, the hard rows nothing; selects and
    // registers at most one LE a bit of a 32-bit word.
    let mut le_min = 800 + 90 + 250;
    let mut select_and_register_max = 0;
    for (b, c) in blocks_with_copies(&p) {
        le_min += c * b.schedule.balancing.le;
        for &(op, k) in &b.schedule.op_counts {
            le_min += c * u64::from(k) * le_each(op);
            if matches!(op, OpKind::Mux | OpKind::Register) {
                select_and_register_max += c * u64::from(k) * 32;
            }
        }
    }
    assert!(
        (le_min..=le_min + select_and_register_max).contains(&d.le),
        "{} not in {le_min}..={}",
        d.le,
        le_min + select_and_register_max
    );

    // RAM blocks: the 8-bit frame in M20Ks of 2,048 x 10 (640 x 480 / 2,048 = 150),
    // the primitives' 63 words in one 512 x 40; the dividers' tables and the delay
    // lines add to that.
    let blocks = design_blocks(&lib, &p, n, w, h);
    assert!(blocks > 150 + 1, "{blocks}");

    for device in &lib.devices {
        let f = fit_design(&lib, device, &p, n, w, h);
        assert_eq!(f, fit(&lib, device, d, blocks));
        // Every hard operation has its block: nothing built in logic.
        assert!(dsp <= device.mult, "{}", device.name);
        assert_eq!(f.soft_mult_elements, 0);
        assert_eq!((f.used.mult, f.used.le, f.used.mem_bits), (dsp, d.le, mem));
        assert!((f.utilization.mult - dsp as f64 / device.mult as f64).abs() < 1e-12);
        assert!((f.utilization.mem_bits - mem as f64 / device.mem_bits as f64).abs() < 1e-12);
        // Within the routing headroom on logic and memory, whatever the selects cost.
        assert!(
            le_min + select_and_register_max <= headroom_limit(device.le, ROUTING_HEADROOM_PERCENT)
        );
        assert!(mem <= headroom_limit(device.mem_bits, ROUTING_HEADROOM_PERCENT));
        assert!(blocks <= headroom_limit(lib.memory_blocks(device), MEMORY_BLOCK_HEADROOM_PERCENT));
        assert!(PLLS_USED <= device.plls);
        assert!(f.fits && f.over.is_empty(), "{}: {:?}", device.name, f.over);
        assert_eq!(f.state, FitState::Fits, "{}", device.name);
        assert!(!f.validated);
    }
}

#[test]
fn dsp_blocks_beyond_the_device_are_built_as_soft_adders() {
    // Two intersection units on the Cyclone 10 GX 220: the second unit's hard
    // operations and dividers need more blocks than its 192.
    let lib = arria_10();
    let device = lib.devices.iter().find(|d| d.name == "10CX220").unwrap();
    let design = Design {
        units: 2,
        ..Design::thesis()
    };
    let p = Pipeline::build(&lib, &design);
    let d = demand(&lib, &p, 7, 640, 480);
    let dsp = dsp_blocks_by_hand(&p);
    assert_eq!(d.mult, dsp);
    assert!(dsp > device.mult, "{dsp}");
    let blocks = design_blocks(&lib, &p, 7, 640, 480);
    let f = fit(&lib, device, d, blocks);
    let spill = dsp - device.mult;
    assert_eq!(f.soft_mult_elements, spill);
    assert_eq!(f.used.mult, device.mult);
    // Each at the soft adder's 360 ALMs x 2.69 LE equivalents and 536 registers.
    assert_eq!(f.used.le, d.le + spill * 968);
    assert_eq!(f.used.regs, d.regs + spill * 536);
    // The GX 1150 holds them all.
    let big = lib.devices.iter().find(|d| d.name == "10AX115").unwrap();
    assert_eq!(fit(&lib, big, d, blocks).soft_mult_elements, 0);
}
