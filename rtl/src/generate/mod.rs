//! The RTL generator: the pipeline's Verilog, written from the same scheduled dataflow
//! graphs the model times ([`hwmodel::blocks::Pipeline`]).
//!
//! Each graph block (primary ray, intersection, shading, the comparator tree) becomes
//! one module: every operator node an instance of the Verilog library at its library
//! latency, every producer one tapped delay line as long as its largest wait (the
//! scheduler's), in registers or, when the library puts the line in memory, in
//! circular buffers (`fp_delay_ram.v`); frame constants and literals are never
//! delayed; a row register loads once per image row. The minimum-distance block is
//! written by hand (it feeds its own result back), with the model's latency (compare +
//! register): the thesis's float compare in `rtl/verilog/min_distance.v` (the kept
//! distance forwarded to the next compare), the integer compare in
//! `min_distance_int.v`. The top module adds the screen iterator (one pixel every r·c
//! cycles, r the design's cycles per primitive, c = ⌈n/K⌉), the scene memory (one RAM
//! per word, written by a loader port, read with the library's 2 cycles), K
//! intersection units fed primitive k of their chunk r·k cycles after the ray, and the
//! frame-buffer write port.
//!
//! Control (which slot is valid, first or last of a pixel) travels beside the data in
//! short delay lines of the blocks' latencies. For the simulation, every block also
//! carries a *monitor* valid bit through its generated structure (the AND of its
//! operands' valid bits, delayed like the data): its first rise after the first input
//! is the block's latency as built, which the testbench reports. Monitors are
//! `ifndef SYNTHESIS`: Yosys does not count them.
//!
//! `block.rs` writes a graph block's module, `top.rs` the top module and the
//! minimum-distance block; this module joins them into the design's files.

mod block;
mod top;

use std::collections::{BTreeMap, BTreeSet};
use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::Path;

use hwmodel::blocks::{ADDRESS_BITS, Block, Pipeline};
use hwmodel::graph::{FRAME_CONSTANT, NodeKind};
use hwmodel::library::Library;

use crate::RtlError;
use crate::operators::write_atomically;
use crate::operators::{self, SourceFile};

pub use block::{block_module, built_delay_lines};
use top::{TopTiming, min_distance_module, top_module};

/// The circular-buffer delay line for lines in memory.
pub const DELAY_RAM: SourceFile = SourceFile {
    name: "fp_delay_ram.v",
    text: include_str!("../../verilog/fp_delay_ram.v"),
};

/// The Verilator testbench: runs one frame, writes the image and the measurements.
pub const TESTBENCH: SourceFile = SourceFile {
    name: "tb_pipeline.cpp",
    text: include_str!("../../verilog/tb/tb_pipeline.cpp"),
};

/// The top module's name.
pub const TOP: &str = "raycaster_top";

/// Scene-memory words per primitive the RTL can hold (9 words, then the rsqrt-free
/// shading's 5).
pub const FIELDS: u32 = 14;

/// Most intersection units the generator builds (the comparator tree's width).
pub const MAX_UNITS: u32 = 64;

/// Memory delay-line segments shorter than this stay in registers (a circular buffer
/// needs at least 2 words).
const RAM_SEGMENT_MIN: u32 = 3;

/// A generated design: its files and what the testbench and the synthesis need.
#[derive(Clone, Debug)]
pub struct GeneratedRtl {
    /// `(file name, text)`: the generated modules, then the operator library.
    pub files: Vec<(String, String)>,
    /// Per block: its module name and its latency in the model's schedule.
    pub blocks: Vec<BlockRtl>,
    /// Address bits of the scene memory (2^bits primitives).
    pub depth_bits: u32,
    /// Cycles the top needs after `start` before the first pixel (row 0's base).
    pub prologue: u32,
}

impl GeneratedRtl {
    /// A hash of the design's files: which RTL a Verilator build or a synthesis is of.
    pub fn hash(&self) -> String {
        let mut hasher = DefaultHasher::new();
        self.files.hash(&mut hasher);
        format!("{:016x}", hasher.finish())
    }
}

/// One generated block.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BlockRtl {
    /// The model's block name (`primary_ray`, `intersection`, …).
    pub name: &'static str,
    /// Its Verilog module.
    pub module: String,
    /// Its latency in the model's schedule.
    pub latency: u32,
}

/// One port of a generated module, as the generator declares it (the top connects a
/// block by its ports, never by reading its text back).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Port {
    /// An output (else an input).
    pub output: bool,
    /// Its width in bits.
    pub bits: u32,
    pub name: String,
}

impl Port {
    pub fn input(bits: u32, name: impl Into<String>) -> Port {
        Port {
            output: false,
            bits,
            name: name.into(),
        }
    }

    pub fn output(bits: u32, name: impl Into<String>) -> Port {
        Port {
            output: true,
            bits,
            name: name.into(),
        }
    }

    /// Its declaration in a Verilog-2005 port list: `input [31:0] in_x`, `input clk`.
    pub fn declaration(&self) -> String {
        let direction = if self.output { "output" } else { "input" };
        if self.bits == 1 {
            format!("{direction} {}", self.name)
        } else {
            format!("{direction} [{}:0] {}", self.bits - 1, self.name)
        }
    }
}

/// A generated block's module: its text and its ports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BlockModule {
    pub text: String,
    pub ports: Vec<Port>,
}

/// A Verilog identifier for a graph label (`L̂.x` → `Lhat_x`, `∞` → `inf`).
pub fn identifier(label: &str) -> String {
    let label = label.replace('̂', "hat").replace('∞', "inf");
    let mut out = String::new();
    for c in label.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c);
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    out.trim_matches('_').to_string()
}

fn malformed(block: &str, problem: String) -> RtlError {
    RtlError::Generate(format!("{block}: {problem}"))
}

/// The whole design for `pipeline`, with a scene memory of 2^`depth_bits` primitives.
pub fn generate(
    lib: &Library,
    pipeline: &Pipeline,
    depth_bits: u32,
) -> Result<GeneratedRtl, RtlError> {
    let design = pipeline.design;
    let units = design.units.max(1);
    if units > MAX_UNITS {
        return Err(RtlError::TooManyUnits {
            units,
            max: MAX_UNITS,
        });
    }
    if depth_bits == 0 || depth_bits > ADDRESS_BITS {
        return Err(RtlError::Generate(format!(
            "scene memory of 2^{depth_bits} primitives: the address has {ADDRESS_BITS} bits"
        )));
    }
    let mut files = Vec::new();
    let mut blocks = Vec::new();
    let mut graph_blocks: Vec<(&Block, String)> = vec![
        (&pipeline.primary_ray, "primary_ray".to_string()),
        (&pipeline.intersection, "intersection".to_string()),
        (&pipeline.shading, "shading".to_string()),
    ];
    if let Some(tree) = &pipeline.min_tree {
        graph_blocks.push((tree, "min_tree".to_string()));
    }
    let mut modules = BTreeMap::new();
    for (block, name) in &graph_blocks {
        let module = block_module(lib, block, name)?;
        files.push((format!("{name}.v"), module.text.clone()));
        modules.insert(block.name, module);
    }
    files.push(("min_distance.v".into(), min_distance_module(lib, &design)?));
    for b in pipeline.blocks_in_order() {
        blocks.push(BlockRtl {
            name: b.name,
            module: b.name.to_string(),
            latency: b.latency(),
        });
    }

    let (row_start, row_path, row_lead) = row_timing(&pipeline.primary_ray)?;
    // i as a float (registered int-to-float), then the row path, then a margin.
    let prologue = row_path + 4;

    let top = top_module(
        lib,
        pipeline,
        &modules,
        TopTiming {
            units,
            depth_bits,
            row_load_delay: row_start - 1,
            prologue,
            row_lead,
        },
    )?;
    files.push((format!("{TOP}.v"), top));
    for source in operators::SOURCES.iter().chain([&DELAY_RAM]) {
        files.push((source.name.to_string(), source.text.to_string()));
    }
    files.push((TESTBENCH.name.to_string(), TESTBENCH.text.to_string()));
    Ok(GeneratedRtl {
        files,
        blocks,
        depth_bits,
        prologue,
    })
}

/// The primary ray's row path: `(row_start, row_path, row_lead)`. Its row registers
/// load at their readers' start (`row_start`, ≥ 1), from sources that finish
/// `row_path` cycles into the block; `row_lead` is how far ahead of the iterator the
/// top's row count runs so that each source sees its row's `i` (the top's
/// [`TopTiming::row_lead`]).
fn row_timing(pr: &Block) -> Result<(u32, u32, u32), RtlError> {
    let nodes = pr.graph.nodes();
    let readers = |id: usize| {
        nodes
            .iter()
            .enumerate()
            .filter(move |(_, n)| n.inputs.contains(&id))
            .map(|(c, _)| pr.schedule.start[c])
    };
    let mut row_starts = BTreeSet::new();
    let mut row_finishes = BTreeSet::new();
    let mut index_reads = BTreeSet::new();
    for (id, node) in nodes.iter().enumerate() {
        if node.kind == NodeKind::RowRegister {
            if let Some(&src) = node.inputs.first() {
                row_finishes.insert(pr.schedule.finish[src]);
            }
            row_starts.extend(readers(id));
        }
        let frame_constant = node.kind
            == (NodeKind::Input {
                hold: FRAME_CONSTANT,
            });
        if frame_constant && identifier(&node.label) == "i" {
            index_reads.extend(readers(id));
        }
    }
    let row_path = row_finishes.last().copied().unwrap_or(0);
    let row_start = match (row_starts.first(), row_starts.last()) {
        (Some(&a), Some(&b)) if a == b && a >= 1 => a,
        (None, None) => 1,
        _ => {
            return Err(RtlError::Generate(format!(
                "primary_ray: the row registers' readers start at {row_starts:?}: one start ≥ 1 is needed"
            )));
        }
    };
    // Rows may be one pixel a cycle long (one pixel wide, one primitive a cycle): each
    // register's value then comes from one cycle's `i`, so every source must read `i`
    // at one offset and finish at one.
    let row_lead = match (index_reads.first(), index_reads.last(), row_finishes.len()) {
        (None, None, 0) => 0,
        (Some(&read), Some(&last), 1) if read == last && read < row_path => {
            // `i` is read row_path − read cycles before the registers load, which is
            // row_start − 1 cycles after the row's first issue; the top registers it
            // a cycle after the count, so the count runs this far ahead.
            (row_path - read + 1).checked_sub(row_start - 1).ok_or_else(|| {
                RtlError::Generate(format!(
                    "primary_ray: the row path ({} cycles) ends more than a cycle before the row registers load ({row_start} after the issue): the row index would lag the iterator",
                    row_path - read
                ))
            })?
        }
        _ => {
            return Err(RtlError::Generate(format!(
                "primary_ray: the row index is read at {index_reads:?} and the row sources finish at {row_finishes:?}: one of each is needed"
            )));
        }
    };
    Ok((row_start, row_path, row_lead))
}

/// Writes `rtl`'s files into `dir` (created if needed), each atomically.
pub fn write(rtl: &GeneratedRtl, dir: &Path) -> Result<(), RtlError> {
    std::fs::create_dir_all(dir).map_err(|source| RtlError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    for (name, text) in &rtl.files {
        write_atomically(&dir.join(name), text)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use hwmodel::design::{Design, MinDistance};
    use hwmodel::library::OpKind;

    fn designs() -> Vec<Design> {
        let t = Design::thesis();
        vec![
            t,
            Design { units: 2, ..t },
            Design { units: 3, ..t },
            Design {
                fast_sqrt: true,
                ..t
            },
            Design { ortho: true, ..t },
            Design {
                no_rsqrt_shading: true,
                ..t
            },
            Design {
                min_distance: MinDistance::IntegerCompare,
                ..t
            },
            Design {
                units: 2,
                min_distance: MinDistance::IntegerCompare,
                ..t
            },
        ]
    }

    fn file<'a>(rtl: &'a GeneratedRtl, name: &str) -> &'a str {
        rtl.files
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, t)| t.as_str())
            .unwrap_or_else(|| panic!("no {name}"))
    }

    #[test]
    fn the_minimum_distance_block_and_the_slots_follow_the_designs_compare() {
        let lib = Library::cyclone_iv_e();
        for (min_distance, rate) in [
            (MinDistance::FloatCompare, 3),
            (MinDistance::IntegerCompare, 1),
        ] {
            let design = Design {
                min_distance,
                ..Design::thesis()
            };
            let rtl = generate(&lib, &Pipeline::build(&lib, &design), 6).unwrap();
            let block = file(&rtl, "min_distance.v");
            let float = min_distance == MinDistance::FloatCompare;
            assert_eq!(block.contains("fp_compare #(.LATENCY(3))"), float);
            assert_eq!(block.contains("in_distance[30:0] < against"), !float);
            for placeholder in ["{compare}", "{register}", "{total}", "{a}", "{ab}"] {
                assert!(!block.contains(placeholder), "{placeholder}");
            }
            // The iterator's slot phase counts to the rate: a slot every `rate` cycles.
            let top = file(&rtl, "raycaster_top.v");
            let last = format!("(phase == {}'d{})", if float { 2 } else { 1 }, rate - 1);
            assert!(top.contains(&last), "{last}");
        }
        // A library whose integer compare takes a cycle would not be the block built.
        let text = include_str!("../../../hwmodel/data/cyclone_iv_e.toml");
        let at = text.find("[ops.int_compare]").unwrap();
        let slow = format!(
            "{}{}",
            &text[..at],
            text[at..].replacen("latency = 0", "latency = 1", 1)
        );
        let slow = Library::from_toml(&slow, "slow.toml").unwrap();
        let design = Design {
            min_distance: MinDistance::IntegerCompare,
            ..Design::thesis()
        };
        let err = generate(&slow, &Pipeline::build(&slow, &design), 6).unwrap_err();
        assert!(err.to_string().contains("integer compare takes 1"), "{err}");
    }

    #[test]
    fn the_row_index_runs_ahead_by_the_row_path_less_the_load_delay() {
        // The thesis's primary ray: i read at 0, the row sources finish at 14, the row
        // registers load 6 cycles after the issue: i runs 14 + 1 − 6 = 9 cycles ahead,
        // started 9 cycles before the end of the 18-cycle prologue.
        let lib = Library::cyclone_iv_e();
        let rtl = generate(&lib, &Pipeline::build(&lib, &Design::thesis()), 6).unwrap();
        let top = file(&rtl, "raycaster_top.v");
        assert_eq!(rtl.prologue, 18);
        assert!(top.contains("(prologue == 16'd18)) running <= 1'b1"));
        assert!(top.contains("(prologue == 16'd9)) lead_running <= 1'b1"));
        assert!(top.contains(".LATENCY(6)) row_load_line"));
    }

    #[test]
    fn every_block_builds_the_delay_lines_the_model_costs() {
        let lib = Library::cyclone_iv_e();
        for design in designs() {
            let p = Pipeline::build(&lib, &design);
            let blocks = [
                Some(&p.primary_ray),
                Some(&p.intersection),
                Some(&p.shading),
                p.min_tree.as_ref(),
            ];
            for block in blocks.into_iter().flatten() {
                let mut built = built_delay_lines(&lib, block).unwrap();
                let mut model: Vec<(String, u32, u32)> = block
                    .schedule
                    .delay_lines
                    .iter()
                    .map(|l| (l.producer.clone(), l.bits, l.cycles))
                    .collect();
                built.sort();
                model.sort();
                assert_eq!(built, model, "{} of {}", block.name, design.label());
            }
        }
    }

    #[test]
    fn every_operator_node_is_one_instance_at_its_library_latency() {
        let lib = Library::cyclone_iv_e();
        let p = Pipeline::build(&lib, &Design::thesis());
        let module = block_module(&lib, &p.intersection, "intersection").unwrap();
        let text = module.text;
        let count = |needle: &str| text.matches(needle).count() as u32;
        let s = &p.intersection.schedule;
        assert_eq!(count("fp_add_sub #(.LATENCY(7))"), s.count(OpKind::AddSub));
        assert_eq!(
            count("fp_mul #(.LATENCY(5))") + count("fp_mul #(.LATENCY(7))"),
            s.count(OpKind::Multiply) + s.count(OpKind::MultiplyRegistered)
        );
        assert_eq!(count("fp_sqrt #(.LATENCY(16))"), 1);
        assert_eq!(count("fp_div #(.LATENCY(15))"), 2);
        assert_eq!(count("fp_compare #(.LATENCY(3))"), s.count(OpKind::Compare));
        // −b − √disc and −b + √disc: the sign of b flipped on the wire.
        assert_eq!(count("{~n"), 2);
    }

    #[test]
    fn the_whole_design_generates_for_every_what_if() {
        let lib = Library::cyclone_iv_e();
        for design in designs() {
            let p = Pipeline::build(&lib, &design);
            let rtl = generate(&lib, &p, 6).unwrap_or_else(|e| panic!("{}: {e}", design.label()));
            let top = rtl
                .files
                .iter()
                .find(|(n, _)| n == "raycaster_top.v")
                .map(|(_, t)| t.clone())
                .unwrap();
            let units = top.matches("    intersection unit").count() as u32;
            assert_eq!(units, design.units, "{}", design.label());
            assert_eq!(
                top.matches("    min_distance min").count() as u32,
                design.units
            );
            assert_eq!(top.contains("    min_tree tree"), design.units > 1);
        }
    }

    #[test]
    fn a_block_declares_the_ports_it_carries() {
        let lib = Library::cyclone_iv_e();
        let p = Pipeline::build(&lib, &Design::thesis());
        let module = block_module(&lib, &p.primary_ray, "primary_ray").unwrap();
        let list: Vec<String> = module.ports.iter().map(Port::declaration).collect();
        assert!(
            module.text.contains(&format!(
                "module primary_ray (\n    {}\n);",
                list.join(",\n    ")
            )),
            "{}",
            module.text
        );
        // The ray's direction: three 32-bit outputs, then the valid bit.
        let outputs: Vec<(u32, &str)> = module
            .ports
            .iter()
            .filter(|p| p.output)
            .map(|p| (p.bits, p.name.as_str()))
            .collect();
        assert_eq!(
            outputs,
            [
                (32, "out_0"),
                (32, "out_1"),
                (32, "out_2"),
                (1, "out_valid")
            ]
        );
        assert_eq!(module.ports[0], Port::input(1, "clk"));
        assert_eq!(Port::input(32, "in_j").declaration(), "input [31:0] in_j");
    }

    #[test]
    fn identifiers_are_verilog_names() {
        assert_eq!(identifier("R.x"), "R_x");
        assert_eq!(identifier("L̂.y"), "Lhat_y");
        assert_eq!(identifier("scan_line.z"), "scan_line_z");
        assert_eq!(identifier("0 (bit)"), "0_bit");
    }
}
