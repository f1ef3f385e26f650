//! Memory in blocks, not bits: each memory of a design takes whole RAM blocks (M9K on
//! Cyclone IV E), however few of a block's bits it uses.
//!
//! A memory of `depth` words of `width` bits is built from blocks in one of the block's
//! shapes (`depth × width`: an M9K is 8K × 1, 4K × 2, 2K × 4, 1K × 9, 512 × 18 or
//! 256 × 36); the fitter picks the shape that takes fewest blocks, ⌈depth / d⌉ ·
//! ⌈width / w⌉ ([`blocks_for`]). A design's memories ([`design_memories`]):
//! - the frame buffer, W·H words of the pixel's bits (640×480 at 8 bits: 300 M9K in 1K × 9,
//!   the figure Yosys maps the RTL's frame memory to);
//! - the scene memory, one 32-bit memory per word of a primitive (the fields are read
//!   by different blocks in the same cycle), n deep;
//! - every delay line long enough to go to memory (the library's
//!   `memory_delay_min_cycles`), `cycles` deep and as wide as its value, in each block
//!   and each intersection unit;
//! - every operator instance whose row has memory (ALTFP_DIV's reciprocal table, 4,608
//!   bits): whole blocks each.
//!
//! Bits count what the memories hold; blocks what the device gives up for them. The
//! device fit checks both ([`crate::device::fit`]).

use serde::Serialize;

use crate::blocks::{Block, Pipeline};
use crate::library::{Library, blocks_for};

/// One memory of a design.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Memory {
    /// What it holds: `frame buffer`, `scene word 3`, `intersection: delay of d`, …
    pub what: String,
    /// How many of it the design has (K intersection units each carry their own).
    pub copies: u64,
    pub depth: u64,
    pub width: u64,
    /// Blocks one copy takes.
    pub blocks: u64,
}

impl Memory {
    fn new(lib: &Library, what: String, copies: u64, depth: u64, width: u64) -> Self {
        Self {
            what,
            copies,
            depth,
            width,
            blocks: blocks_for(&lib.memory_block, depth, width),
        }
    }

    /// Blocks of every copy.
    pub fn total_blocks(&self) -> u64 {
        self.blocks * self.copies
    }
}

/// Every memory of `pipeline` for a scene of `primitives` and a `width`×`height` frame.
pub fn design_memories(
    lib: &Library,
    pipeline: &Pipeline,
    primitives: u64,
    width: u32,
    height: u32,
) -> Vec<Memory> {
    let design = &pipeline.design;
    let mut out = vec![Memory::new(
        lib,
        "frame buffer".into(),
        1,
        u64::from(width) * u64::from(height),
        u64::from(design.frame_bits_per_pixel),
    )];
    for word in 0..design.words_per_primitive() {
        out.push(Memory::new(
            lib,
            format!("scene word {word}"),
            1,
            primitives.max(1),
            u64::from(lib.word_bits),
        ));
    }
    let units = u64::from(design.units.max(1));
    let mut per_block = |block: &Block, copies: u64| {
        for line in block.schedule.delay_lines.iter().filter(|l| l.in_memory) {
            out.push(Memory::new(
                lib,
                format!("{}: delay of {}", block.name, line.producer),
                copies,
                u64::from(line.cycles),
                u64::from(line.bits),
            ));
        }
        for (op, count) in &block.schedule.op_counts {
            let bits = lib.op(*op).resources.mem_bits;
            if bits > 0 {
                // A core's own table: whole blocks for each instance.
                out.push(Memory {
                    what: format!("{}: {} table", block.name, lib.op(*op).name),
                    copies: copies * u64::from(*count),
                    depth: 1,
                    width: bits,
                    blocks: bits.div_ceil(lib.memory_block.bits),
                });
            }
        }
    };
    per_block(&pipeline.primary_ray, 1);
    per_block(&pipeline.intersection, units);
    per_block(&pipeline.min_distance, units);
    if let Some(tree) = &pipeline.min_tree {
        per_block(tree, 1);
    }
    per_block(&pipeline.shading, 1);
    out
}

/// Blocks of every memory of the design.
pub fn design_blocks(
    lib: &Library,
    pipeline: &Pipeline,
    primitives: u64,
    width: u32,
    height: u32,
) -> u64 {
    design_memories(lib, pipeline, primitives, width, height)
        .iter()
        .map(Memory::total_blocks)
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::Design;
    use crate::library::{MemoryBlock, OpKind};

    fn m9k() -> MemoryBlock {
        Library::cyclone_iv_e().memory_block
    }

    #[test]
    fn a_memory_takes_the_fewest_blocks_of_any_shape() {
        let b = m9k();
        assert_eq!(b.bits, 9216);
        // 640×480 bytes: 307,200 words of 8 bits. 1K × 9: ⌈307200 / 1024⌉ = 300 blocks;
        // 8K × 1 would need 38 × 8 = 304.
        assert_eq!(blocks_for(&b, 640 * 480, 8), 300);
        // A 32-bit word per primitive, 7 primitives: one block (256 × 36).
        assert_eq!(blocks_for(&b, 7, 32), 1);
        // A 40-cycle delay of a 96-bit vector: 256 × 36 → ⌈96 / 36⌉ = 3 blocks.
        assert_eq!(blocks_for(&b, 40, 96), 3);
        // 300 words of 32 bits: 512 × 18 → 2 blocks (256 × 36 would need 2 × 1 = 2 too).
        assert_eq!(blocks_for(&b, 300, 32), 2);
        assert_eq!(blocks_for(&b, 0, 32), 0);
    }

    #[test]
    fn the_thesis_design_counts_its_frame_scene_delays_and_tables() {
        let lib = Library::cyclone_iv_e();
        let p = Pipeline::build(&lib, &Design::thesis());
        let memories = design_memories(&lib, &p, 7, 640, 480);
        let frame = &memories[0];
        assert_eq!((frame.what.as_str(), frame.blocks), ("frame buffer", 300));
        // Nine scene words, one block each at 7 primitives.
        let scene: u64 = memories
            .iter()
            .filter(|m| m.what.starts_with("scene word"))
            .map(Memory::total_blocks)
            .sum();
        assert_eq!(scene, 9);
        // Each divider instance keeps ALTFP_DIV's 4,608-bit table in one whole M9K.
        let dividers: u32 = p
            .blocks_in_order()
            .iter()
            .map(|b| b.schedule.count(OpKind::Divide))
            .sum();
        let tables: u64 = memories
            .iter()
            .filter(|m| m.what.ends_with("table"))
            .map(Memory::total_blocks)
            .sum();
        assert_eq!(tables, u64::from(dividers));
        // The total is the sum of its parts, and at least the frame, scene and tables.
        let total = design_blocks(&lib, &p, 7, 640, 480);
        assert_eq!(
            total,
            memories.iter().map(Memory::total_blocks).sum::<u64>()
        );
        assert!(total >= 300 + 9 + tables);
    }

    #[test]
    fn each_intersection_unit_carries_its_own_delay_lines() {
        let lib = Library::cyclone_iv_e();
        let one = Pipeline::build(&lib, &Design::thesis());
        let two = Pipeline::build(
            &lib,
            &Design {
                units: 2,
                ..Design::thesis()
            },
        );
        let unit_blocks = |p: &Pipeline| -> u64 {
            design_memories(&lib, p, 7, 640, 480)
                .iter()
                .filter(|m| m.what.starts_with("intersection"))
                .map(Memory::total_blocks)
                .sum()
        };
        assert!(unit_blocks(&one) > 0);
        assert_eq!(unit_blocks(&two), 2 * unit_blocks(&one));
    }
}
