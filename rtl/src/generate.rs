//! The RTL generator: the pipeline's Verilog, written from the same scheduled dataflow
//! graphs the model times ([`hwmodel::blocks::Pipeline`]).
//!
//! Each graph block (primary ray, intersection, shading, the comparator tree) becomes
//! one module: every operator node an instance of the Verilog library at its library
//! latency, every producer one tapped delay line as long as its largest wait (the
//! scheduler's), in registers or, when the library puts the line in memory, in
//! circular buffers (`fp_delay_ram.v`); frame constants and literals are never
//! delayed; a row register loads once per image row. The minimum-distance block is
//! written by hand (it feeds its own result back: the kept distance is forwarded to the
//! next compare), with the model's latency (compare + register). The top module adds
//! the screen iterator (one pixel every 3c cycles, c = ⌈n/K⌉), the scene memory (one
//! RAM per word, written by a loader port, read with the library's 2 cycles), K
//! intersection units fed primitive k of their chunk 3k cycles after the ray, and the
//! frame-buffer write port.
//!
//! Control (which slot is valid, first or last of a pixel) travels beside the data in
//! short delay lines of the blocks' latencies. For the simulation, every block also
//! carries a *monitor* valid bit through its generated structure (the AND of its
//! operands' valid bits, delayed like the data): its first rise after the first input
//! is the block's latency as built, which the testbench reports. Monitors are
//! `ifndef SYNTHESIS`: Yosys does not count them.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::Path;

use hwmodel::blocks::{ADDRESS_BITS, Block, Pipeline};
use hwmodel::graph::{AddSubMode, Detail, FRAME_CONSTANT, Graph, NodeKind};
use hwmodel::hw_scene::HwPrimitive;
use hwmodel::library::{Library, OpKind};

use crate::RtlError;
use crate::operators::write_atomically;
use crate::operators::{self, Operator, SourceFile};

/// The circular-buffer delay line for lines in memory.
pub const DELAY_RAM: SourceFile = SourceFile {
    name: "fp_delay_ram.v",
    text: include_str!("../verilog/fp_delay_ram.v"),
};

/// The Verilator testbench: runs one frame, writes the image and the measurements.
pub const TESTBENCH: SourceFile = SourceFile {
    name: "tb_pipeline.cpp",
    text: include_str!("../verilog/tb/tb_pipeline.cpp"),
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

/// The Verilog operator a graph operator is built from (`None`: written inline).
fn operator_for(kind: OpKind) -> Option<Operator> {
    Some(match kind {
        OpKind::AddSub => Operator::AddSub,
        OpKind::Multiply | OpKind::MultiplyRegistered => Operator::Multiply,
        OpKind::Sqrt => Operator::Sqrt,
        OpKind::Divide => Operator::Divide,
        OpKind::InvSqrt => Operator::InvSqrt,
        OpKind::Compare => Operator::Compare,
        OpKind::Convert => Operator::ToU8,
        OpKind::FastSqrt => Operator::FastSqrt,
        OpKind::Mux | OpKind::Register | OpKind::RamRead => return None,
    })
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

/// How a node's value is reached from a consumer.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Timing {
    /// Frame constants, literals, row registers: read directly.
    Constant,
    /// Valid at the node's finish time, delayed on demand.
    Timed,
}

/// One block module generated from its graph.
struct BlockWriter<'a> {
    lib: &'a Library,
    block: &'a Block,
    body: String,
    monitor: String,
    ports: Vec<String>,
    /// Delay taps each producer needs: producer → set of delays.
    taps: BTreeMap<usize, BTreeSet<u32>>,
}

impl<'a> BlockWriter<'a> {
    fn graph(&self) -> &'a Graph {
        &self.block.graph
    }

    fn timing(&self, id: usize) -> Result<Timing, RtlError> {
        let node = &self.graph().nodes()[id];
        match node.kind {
            NodeKind::Input {
                hold: FRAME_CONSTANT,
            }
            | NodeKind::RowRegister => Ok(Timing::Constant),
            NodeKind::Input { hold: 0 } | NodeKind::Op(_) => Ok(Timing::Timed),
            NodeKind::Input { hold } => Err(malformed(
                self.block.name,
                format!(
                    "input `{}` is held {hold} cycles: only the minimum-distance block has held inputs",
                    node.label
                ),
            )),
        }
    }

    /// The expression of `producer`'s value at time `at` (a consumer's start).
    fn tap(&mut self, producer: usize, at: u32) -> Result<(String, String), RtlError> {
        if self.timing(producer)? == Timing::Constant {
            return Ok((format!("n{producer}"), "1'b1".to_string()));
        }
        let finish = self.block.schedule.finish[producer];
        let delay = at.checked_sub(finish).ok_or_else(|| {
            malformed(
                self.block.name,
                format!("node {producer} is read before it is ready"),
            )
        })?;
        if delay == 0 {
            return Ok((format!("n{producer}"), format!("ok{producer}")));
        }
        self.taps.entry(producer).or_default().insert(delay);
        Ok((
            format!("n{producer}_d{delay}"),
            format!("ok{producer}_d{delay}"),
        ))
    }

    fn write(mut self, module: &str) -> Result<String, RtlError> {
        let graph = self.graph();
        let schedule = &self.block.schedule;
        let nodes = graph.nodes();
        let has_row_registers = nodes.iter().any(|n| n.kind == NodeKind::RowRegister);
        self.ports.push("input clk".into());
        self.ports.push("input in_valid".into());
        if has_row_registers {
            self.ports.push("input row_load".into());
        }
        let mut input_names = BTreeSet::new();
        for (id, node) in nodes.iter().enumerate() {
            let bits = node.bits;
            let width = format!("[{}:0]", bits - 1);
            match (node.kind, node.detail) {
                (NodeKind::Input { .. }, Detail::Literal(value)) => {
                    writeln!(
                        self.body,
                        "    wire {width} n{id} = {bits}'h{value:X}; // {}",
                        node.label
                    )
                    .ok();
                }
                (NodeKind::Input { hold }, _) => {
                    let name = identifier(&node.label);
                    if !input_names.insert(name.clone()) {
                        return Err(malformed(
                            self.block.name,
                            format!("two inputs named `{name}`"),
                        ));
                    }
                    let (prefix, valid) = if hold == FRAME_CONSTANT {
                        ("k_", "1'b1")
                    } else {
                        ("in_", "in_valid")
                    };
                    self.ports.push(format!("input {width} {prefix}{name}"));
                    writeln!(self.body, "    wire {width} n{id} = {prefix}{name};").ok();
                    writeln!(self.monitor, "    wire ok{id} = {valid};").ok();
                }
                (NodeKind::RowRegister, _) => {
                    let src = node.inputs.first().copied().ok_or_else(|| {
                        malformed(self.block.name, "row register without input".into())
                    })?;
                    writeln!(
                        self.body,
                        "    reg {width} n{id}; // {}\n    always @(posedge clk) if (row_load) n{id} <= n{src};",
                        node.label
                    )
                    .ok();
                }
                (NodeKind::Op(kind), detail) => {
                    self.op(id, kind, detail)?;
                }
            }
        }
        let mut outputs = Vec::new();
        for (k, &o) in graph.outputs().iter().enumerate() {
            let (value, valid) = self.tap(o, schedule.latency)?;
            let bits = nodes[o].bits;
            self.ports.push(format!("output [{}:0] out_{k}", bits - 1));
            writeln!(self.body, "    assign out_{k} = {value};").ok();
            outputs.push(valid);
        }
        self.ports.push("output out_valid".into());
        writeln!(
            self.monitor,
            "    assign out_valid = {};",
            if outputs.is_empty() {
                "1'b0".to_string()
            } else {
                outputs.join(" & ")
            }
        )
        .ok();
        self.delay_lines()?;

        let mut text = format!(
            "// Generated by rtprof from the `{}` block's scheduled graph: {} cycles.\nmodule {module} (\n    {}\n);\n",
            self.block.name,
            schedule.latency,
            self.ports.join(",\n    ")
        );
        text += &self.body;
        text += "`ifndef SYNTHESIS\n    // Monitor: the items' valid bits through the block's own structure.\n";
        text += &self.monitor;
        text += "`else\n    assign out_valid = 1'b0;\n`endif\nendmodule\n";
        Ok(text)
    }

    fn op(&mut self, id: usize, kind: OpKind, detail: Detail) -> Result<(), RtlError> {
        let node = &self.graph().nodes()[id];
        let start = self.block.schedule.start[id];
        let bits = node.bits;
        let label = node.label.clone();
        let mut args = Vec::new();
        for &i in &node.inputs {
            args.push(self.tap(i, start)?);
        }
        let arg = |k: usize| -> Result<(String, String), RtlError> {
            args.get(k)
                .cloned()
                .ok_or_else(|| malformed(self.block.name, format!("`{label}` lacks operand {k}")))
        };
        let latency = self.lib.op(kind).latency;
        writeln!(self.body, "    wire [{}:0] n{id}; // {label}", bits - 1).ok();
        match (kind, operator_for(kind)) {
            (OpKind::Mux, _) => {
                let (s, a, b) = (arg(0)?.0, arg(1)?.0, arg(2)?.0);
                writeln!(self.body, "    assign n{id} = {s} ? {b} : {a};").ok();
            }
            (OpKind::Register, _) => {
                if node.inputs.len() != 1 {
                    return Err(malformed(
                        self.block.name,
                        format!(
                            "`{label}`: a register with an enable is the minimum-distance block's"
                        ),
                    ));
                }
                writeln!(
                    self.body,
                    "    fp_delay #(.WIDTH({bits}), .LATENCY({latency})) u{id} (.clk(clk), .d({}), .q(n{id}));",
                    arg(0)?.0
                )
                .ok();
            }
            (OpKind::RamRead, _) => {
                let Detail::Field(field) = detail else {
                    return Err(malformed(
                        self.block.name,
                        format!("`{label}` reads no field"),
                    ));
                };
                let address = arg(0)?.0;
                self.ports
                    .push(format!("output [{}:0] rd{id}_addr", ADDRESS_BITS - 1));
                self.ports
                    .push(format!("input [{}:0] rd{id}_f{field}", bits - 1));
                writeln!(
                    self.body,
                    "    assign rd{id}_addr = {address};\n    assign n{id} = rd{id}_f{field}; // {latency} cycles in the memory port"
                )
                .ok();
            }
            (_, Some(op)) => {
                let lat = op.latency_as(self.lib, kind)?;
                let (a, _) = arg(0)?;
                let y = if op == Operator::Compare { "lt" } else { "y" };
                let mut conn = vec![format!(".clk(clk)")];
                match (op, detail) {
                    (Operator::AddSub, Detail::AddSub(mode)) => {
                        let negate_a = matches!(mode, AddSubMode::NegAdd | AddSubMode::NegSub);
                        let subtract = matches!(mode, AddSubMode::Sub | AddSubMode::NegSub);
                        let a = if negate_a {
                            format!("{{~{a}[31], {a}[30:0]}}")
                        } else {
                            a
                        };
                        conn.push(format!(".a({a})"));
                        conn.push(format!(".b({})", arg(1)?.0));
                        conn.push(format!(".sub(1'b{})", u8::from(subtract)));
                    }
                    (Operator::AddSub, _) => {
                        return Err(malformed(
                            self.block.name,
                            format!("`{label}`: add or subtract?"),
                        ));
                    }
                    (Operator::Multiply | Operator::Divide | Operator::Compare, _) => {
                        conn.push(format!(".a({a})"));
                        conn.push(format!(".b({})", arg(1)?.0));
                    }
                    _ => conn.push(format!(".a({a})")),
                }
                conn.push(format!(".{y}(n{id})"));
                writeln!(
                    self.body,
                    "    {} #(.LATENCY({lat})) u{id} ({});",
                    op.module_name(),
                    conn.join(", ")
                )
                .ok();
            }
            (_, None) => {
                return Err(malformed(
                    self.block.name,
                    format!("`{label}`: no operator"),
                ));
            }
        }
        // Monitor: valid when every timed operand is, `latency` later.
        let valid = args
            .iter()
            .map(|(_, v)| v.as_str())
            .filter(|v| *v != "1'b1")
            .collect::<Vec<_>>();
        let valid = if valid.is_empty() {
            "1'b1".to_string()
        } else {
            valid.join(" & ")
        };
        writeln!(
            self.monitor,
            "    wire ok{id};\n    fp_delay #(.WIDTH(1), .LATENCY({latency})) v{id} (.clk(clk), .d({valid}), .q(ok{id}));"
        )
        .ok();
        Ok(())
    }

    /// One tapped line per producer: segments between consecutive taps.
    fn delay_lines(&mut self) -> Result<(), RtlError> {
        let nodes = self.graph().nodes();
        let taps = std::mem::take(&mut self.taps);
        for (producer, delays) in &taps {
            let bits = nodes[*producer].bits;
            let longest = delays.iter().max().copied().unwrap_or(0);
            let in_memory = self
                .lib
                .delay_line(u64::from(bits), u64::from(longest))
                .mem_bits
                > 0;
            let mut previous = (0u32, format!("n{producer}"), format!("ok{producer}"));
            writeln!(
                self.body,
                "    // Delay line of `{}`: {bits} bits × {longest} cycles{}.",
                nodes[*producer].label,
                if in_memory { ", in memory" } else { "" }
            )
            .ok();
            for &delay in delays {
                let length = delay - previous.0;
                let (q, v) = (
                    format!("n{producer}_d{delay}"),
                    format!("ok{producer}_d{delay}"),
                );
                let data = if in_memory && length >= RAM_SEGMENT_MIN {
                    format!("fp_delay_ram #(.WIDTH({bits}), .DELAY({length}))")
                } else {
                    format!("fp_delay #(.WIDTH({bits}), .LATENCY({length}))")
                };
                writeln!(
                    self.body,
                    "    wire [{}:0] {q};\n    {data} dl{producer}_{delay} (.clk(clk), .d({}), .q({q}));",
                    bits - 1,
                    previous.1
                )
                .ok();
                writeln!(
                    self.monitor,
                    "    wire {v};\n    fp_delay #(.WIDTH(1), .LATENCY({length})) vl{producer}_{delay} (.clk(clk), .d({}), .q({v}));",
                    previous.2
                )
                .ok();
                previous = (delay, q, v);
            }
        }
        Ok(())
    }
}

/// The Verilog module of a graph block, named `module`.
pub fn block_module(lib: &Library, block: &Block, module: &str) -> Result<String, RtlError> {
    BlockWriter {
        lib,
        block,
        body: String::new(),
        monitor: String::new(),
        ports: Vec::new(),
        taps: BTreeMap::new(),
    }
    .write(module)
}

/// The delay lines a generated block builds, `(producer label, bits, cycles)`, for the
/// check against the schedule's.
pub fn built_delay_lines(
    lib: &Library,
    block: &Block,
) -> Result<Vec<(String, u32, u32)>, RtlError> {
    let text = block_module(lib, block, "probe")?;
    let mut lines = Vec::new();
    for line in text.lines() {
        if let Some(rest) = line.trim().strip_prefix("// Delay line of `") {
            let (label, rest) = rest.split_once("`: ").unwrap_or((rest, ""));
            let mut numbers = rest
                .split(|c: char| !c.is_ascii_digit())
                .filter(|s| !s.is_empty())
                .filter_map(|s| s.parse::<u32>().ok());
            if let (Some(bits), Some(cycles)) = (numbers.next(), numbers.next()) {
                lines.push((label.to_string(), bits, cycles));
            }
        }
    }
    Ok(lines)
}

/// The hand-written minimum-distance block (thesis fig. 25) at the library's compare
/// and register latencies.
fn min_distance_module(lib: &Library) -> String {
    let compare = lib.op(OpKind::Compare).latency;
    let register = lib.op(OpKind::Register).latency;
    let a = ADDRESS_BITS;
    format!(
        r#"// The minimum-distance block (thesis fig. 25), written by hand: compare the incoming
// distance with the kept one ({compare} cycles) and load distance, P, m and address into the
// registers ({register} cycle): {total} cycles from a pixel's last primitive to its minimum.
// Primitives arrive every 3 cycles, so the next compare starts in the cycle the previous
// result appears: the kept value is forwarded to it (`kept_next`). The first primitive
// of a pixel compares against infinity. The payload waits beside the compare: the model
// holds the inputs 3 cycles instead (the 3n pacing), these are its registers.
module min_distance (
    input clk,
    input in_valid,
    input in_first,
    input in_last,
    input [31:0] in_distance,
    input [31:0] in_P_x,
    input [31:0] in_P_y,
    input [31:0] in_P_z,
    input [31:0] in_m,
    input [{ab}:0] in_address,
    output [31:0] out_0,
    output [31:0] out_1,
    output [31:0] out_2,
    output [31:0] out_3,
    output [31:0] out_4,
    output [{ab}:0] out_5,
    output out_valid
);
    localparam W = 5 * 32 + {a};
    localparam [31:0] INF = 32'h7F800000;
    wire [W-1:0] payload = {{in_distance, in_P_x, in_P_y, in_P_z, in_m, in_address}};
    wire [W-1:0] payload_d;
    wire [2:0] flags_d; // valid, first, last
    fp_delay #(.WIDTH(W), .LATENCY({compare})) payload_line (.clk(clk), .d(payload), .q(payload_d));
    fp_delay #(.WIDTH(3), .LATENCY({compare})) flag_line (.clk(clk), .d({{in_valid, in_first, in_last}}), .q(flags_d));
    reg [W-1:0] kept = {{INF, {{(W - 32){{1'b0}}}}}};
    wire lt;
    wire [W-1:0] kept_next = (flags_d[2] & lt) ? payload_d
        : (flags_d[2] & flags_d[1]) ? {{INF, {{(W - 32){{1'b0}}}}}} : kept;
    wire [31:0] against = in_first ? INF : kept_next[W-1 -: 32];
    fp_compare #(.LATENCY({compare})) closer (.clk(clk), .a(in_distance), .b(against), .lt(lt));
    reg done = 1'b0;
    always @(posedge clk) begin
        kept <= kept_next;
        done <= flags_d[2] & flags_d[0];
    end
    assign {{out_0, out_1, out_2, out_3, out_4, out_5}} = kept;
    assign out_valid = done;
endmodule
"#,
        ab = a - 1,
        total = compare + register,
    )
}

/// Scene-memory words the design reads: (field, bits).
fn fields(design_no_rsqrt: bool) -> Vec<(u32, u32)> {
    let mut f: Vec<(u32, u32)> = (0..HwPrimitive::WORDS as u32)
        .map(|i| (i, if i == 8 { 1 } else { 32 }))
        .collect();
    if design_no_rsqrt {
        f.extend((9..FIELDS).map(|i| (i, 32)));
    }
    f
}

/// Ports of a generated block module, parsed back from its text: `(direction, width,
/// name)`.
fn module_ports(text: &str) -> Vec<(String, u32, String)> {
    let mut ports = Vec::new();
    let Some(start) = text.find('(') else {
        return ports;
    };
    let Some(end) = text.find(");") else {
        return ports;
    };
    for item in text[start + 1..end].split(',') {
        let words: Vec<&str> = item.split_whitespace().collect();
        match words.as_slice() {
            [dir, name] => ports.push((dir.to_string(), 1, name.to_string())),
            [dir, width, name] => {
                let bits = width
                    .trim_start_matches('[')
                    .split(':')
                    .next()
                    .and_then(|s| s.parse::<u32>().ok())
                    .map_or(1, |b| b + 1);
                ports.push((dir.to_string(), bits, name.to_string()))
            }
            _ => {}
        }
    }
    ports
}

/// The top module's input for a block's frame-constant port `k_<name>`.
fn constant_source(name: &str, block: &str) -> Result<String, RtlError> {
    let (base, axis) = match name.rsplit_once('_') {
        Some((b, a)) if ["x", "y", "z"].contains(&a) => (b, Some(a)),
        _ => (name, None),
    };
    let top = match base {
        "scan_line" | "row_step" | "column_step" | "light" => base.to_string(),
        "O" => "eye".into(),
        "Lhat" => "light_dir".into(),
        "i" => return Ok("row_i".into()),
        "background" => return Ok("background".into()),
        "R" => "view_dir".into(),
        _ => {
            return Err(RtlError::Generate(format!(
                "{block}: no top-level source for frame constant `{name}`"
            )));
        }
    };
    Ok(match axis {
        Some(a) => format!("{top}_{a}"),
        None => top,
    })
}

/// Instantiates a generated block in the top: connects its ports by rule.
fn instance(
    module_text: &str,
    module: &str,
    name: &str,
    block: &str,
    connect: &dyn Fn(&str) -> Option<String>,
    memory_ports: &mut Vec<(u32, String, String, u32)>,
    decls: &mut String,
) -> Result<String, RtlError> {
    let mut conns = Vec::new();
    for (dir, bits, port) in module_ports(module_text) {
        let expr = if let Some(e) = connect(&port) {
            e
        } else if let Some(k) = port.strip_prefix("k_") {
            constant_source(k, block)?
        } else if let Some(rest) = port.strip_prefix("rd") {
            // rd<id>_addr (output) / rd<id>_f<field> (input)
            let (id, what) = rest.split_once('_').unwrap_or((rest, ""));
            let wire = format!("{name}_rd{id}");
            if what == "addr" {
                format!("{wire}_addr")
            } else {
                let field = what.trim_start_matches('f').parse::<u32>().map_err(|_| {
                    RtlError::Generate(format!("{block}: bad memory port `{port}`"))
                })?;
                writeln!(decls, "    wire [{}:0] {wire}_addr;", ADDRESS_BITS - 1).ok();
                memory_ports.push((field, format!("{wire}_addr"), format!("{wire}_q"), bits));
                format!("{wire}_q")
            }
        } else if dir == "output" {
            let wire = format!("{name}_{port}");
            writeln!(decls, "    wire [{}:0] {wire};", bits - 1).ok();
            wire
        } else {
            return Err(RtlError::Generate(format!(
                "{block}: nothing drives input port `{port}`"
            )));
        };
        conns.push(format!(".{port}({expr})"));
    }
    Ok(format!(
        "    {module} {name} (\n        {}\n    );\n",
        conns.join(",\n        ")
    ))
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
    let mut texts = BTreeMap::new();
    for (block, module) in &graph_blocks {
        let text = block_module(lib, block, module)?;
        texts.insert(block.name, text.clone());
        files.push((format!("{module}.v"), text));
    }
    files.push(("min_distance.v".into(), min_distance_module(lib)));
    for b in pipeline.blocks_in_order() {
        blocks.push(BlockRtl {
            name: b.name,
            module: b.name.to_string(),
            latency: b.latency(),
        });
    }

    // The row path: the primary ray's row registers load at their consumers' start.
    let pr = &pipeline.primary_ray;
    let nodes = pr.graph.nodes();
    let mut row_starts = BTreeSet::new();
    let mut row_path = 0;
    for (id, node) in nodes.iter().enumerate() {
        if node.kind == NodeKind::RowRegister {
            if let Some(&src) = node.inputs.first() {
                row_path = row_path.max(pr.schedule.finish[src]);
            }
            for (c, consumer) in nodes.iter().enumerate() {
                if consumer.inputs.contains(&id) {
                    row_starts.insert(pr.schedule.start[c]);
                }
            }
        }
    }
    let row_start = match (row_starts.first(), row_starts.last()) {
        (Some(&a), Some(&b)) if a == b && a >= 1 => a,
        (None, None) => 1,
        _ => {
            return Err(RtlError::Generate(format!(
                "primary_ray: the row registers' readers start at {row_starts:?}: one start ≥ 1 is needed"
            )));
        }
    };
    // i as a float (registered int-to-float), then the row path, then a margin.
    let prologue = row_path + 4;

    let top = top_module(
        lib,
        pipeline,
        &texts,
        TopTiming {
            units,
            depth_bits,
            row_load_delay: row_start - 1,
            prologue,
            row_path,
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

struct TopTiming {
    units: u32,
    depth_bits: u32,
    row_load_delay: u32,
    prologue: u32,
    row_path: u32,
}

fn top_module(
    lib: &Library,
    pipeline: &Pipeline,
    texts: &BTreeMap<&str, String>,
    t: TopTiming,
) -> Result<String, RtlError> {
    let design = pipeline.design;
    let ab = ADDRESS_BITS;
    let l_ray = pipeline.primary_ray.latency();
    let l_int = pipeline.intersection.latency();
    let l_min = pipeline.min_distance.latency();
    let l_tree = pipeline.min_tree.as_ref().map_or(0, Block::latency);
    let l_shade = pipeline.shading.latency();
    let l_mem = lib.op(OpKind::RamRead).latency;
    if l_ray < l_mem {
        return Err(RtlError::Generate(format!(
            "the primary ray ({l_ray} cycles) is shorter than a memory read ({l_mem})"
        )));
    }
    let text = |name: &str| {
        texts
            .get(name)
            .cloned()
            .ok_or_else(|| RtlError::Generate(format!("no generated `{name}` block")))
    };
    let mut decls = String::new();
    let mut body = String::new();
    let mut memory_ports: Vec<(u32, String, String, u32)> = Vec::new();

    let vec3 = |name: &str| {
        ["x", "y", "z"]
            .map(|a| format!("input [31:0] {name}_{a}"))
            .join(", ")
    };
    let ports = [
        "input clk".to_string(),
        "input start".into(),
        "input load_we".into(),
        format!("input [{}:0] load_addr", ab - 1),
        "input [3:0] load_field".into(),
        "input [31:0] load_data".into(),
        "input [15:0] width".into(),
        "input [15:0] height".into(),
        "input [15:0] per_unit".into(),
        "input [15:0] prim_count".into(),
        vec3("scan_line"),
        vec3("row_step"),
        vec3("column_step"),
        vec3("eye"),
        vec3("view_dir"),
        vec3("light"),
        vec3("light_dir"),
        "input [7:0] background".into(),
        "output fb_we".into(),
        "output [31:0] fb_addr".into(),
        "output [7:0] fb_data".into(),
        "output done".into(),
        "output issuing".into(),
        "output [7:0] mon_in".into(),
        "output [7:0] mon_out".into(),
    ];

    // Screen iterator: one slot every 3 cycles; primitive k of c per pixel.
    writeln!(
        body,
        r#"    // Screen iterator (thesis 6.1.2): after the prologue (row 0's base), one slot
    // every 3 cycles, primitive k of per_unit, pixels in rows, top row first.
    reg running = 1'b0, finished = 1'b0;
    reg [15:0] prologue = 16'd0;
    reg [1:0] phase = 2'd0;
    reg [15:0] k = 16'd0, col = 16'd0, row = 16'd0;
    wire slot = running & (phase == 2'd0);
    wire issue = slot & (k == 16'd0);
    wire last_k = (k == per_unit - 16'd1);
    always @(posedge clk) begin
        if (start & ~running & ~finished) begin
            if (prologue == 16'd{prologue}) running <= 1'b1;
            else prologue <= prologue + 16'd1;
        end
        if (running) begin
            phase <= (phase == 2'd2) ? 2'd0 : phase + 2'd1;
            if (phase == 2'd2) begin
                if (last_k) begin
                    k <= 16'd0;
                    if (col == width - 16'd1) begin
                        col <= 16'd0;
                        if (row == height - 16'd1) begin
                            running <= 1'b0;
                            finished <= 1'b1;
                        end
                        row <= row + 16'd1;
                    end else col <= col + 16'd1;
                end else k <= k + 16'd1;
            end
        end
    end
    assign issuing = running;
    // j as a float for the pixel issued now; i (the row whose base is computed next)
    // registered, loaded with row r's base {row_load_delay} cycles after r's first issue.
    wire [31:0] col_f;
    fp_from_int #(.LATENCY(0)) col_to_float (.clk(clk), .a({{16'd0, col}}), .y(col_f));
    reg [15:0] next_row = 16'd0;
    wire row_first_issue = issue & (col == 16'd0);
    wire row_load;
    fp_delay #(.WIDTH(1), .LATENCY({row_load_delay})) row_load_line (.clk(clk), .d(row_first_issue), .q(row_load));
    always @(posedge clk) if (row_load) next_row <= next_row + 16'd1;
    wire [31:0] next_row_f;
    reg [31:0] row_i = 32'd0;
    fp_from_int #(.LATENCY(0)) row_to_float (.clk(clk), .a({{16'd0, next_row}}), .y(next_row_f));
    always @(posedge clk) row_i <= next_row_f;
"#,
        prologue = t.prologue,
        row_load_delay = t.row_load_delay,
    )
    .ok();
    let _ = t.row_path;

    // Primary ray.
    let pr_text = text("primary_ray")?;
    body += &instance(
        &pr_text,
        "primary_ray",
        "ray",
        "primary_ray",
        &|p| match p {
            "clk" => Some("clk".into()),
            "in_valid" => Some("issue".into()),
            "row_load" => Some("row_load".into()),
            "in_j" => Some("col_f".into()),
            _ => None,
        },
        &mut memory_ports,
        &mut decls,
    )?;
    writeln!(
        body,
        r#"    // The ray is ready {l_ray} cycles after its issue and held for the pixel's slots.
    wire ray_ready;
    fp_delay #(.WIDTH(1), .LATENCY({l_ray})) ray_ready_line (.clk(clk), .d(issue), .q(ray_ready));
    reg [95:0] ray_held = 96'd0;
    wire [95:0] ray_now = ray_ready ? {{ray_out_0, ray_out_1, ray_out_2}} : ray_held;
    always @(posedge clk) ray_held <= ray_now;
    // Slots: valid, first, last, k; the memory address {l_mem} cycles before the ray.
    wire [18:0] slot_info = {{slot, k == 16'd0, last_k, k}};
    wire [18:0] slot_at_memory, slot_at_unit;
    fp_delay #(.WIDTH(19), .LATENCY({mem_lead})) slot_to_memory (.clk(clk), .d(slot_info), .q(slot_at_memory));
    fp_delay #(.WIDTH(19), .LATENCY({l_mem})) slot_to_unit (.clk(clk), .d(slot_at_memory), .q(slot_at_unit));
    wire unit_valid = slot_at_unit[18];
    wire unit_first = slot_at_unit[17];
    wire unit_last = slot_at_unit[16];
"#,
        mem_lead = l_ray - l_mem,
    )
    .ok();

    // K intersection units, each with its minimum-distance block.
    let int_text = text("intersection")?;
    for u in 0..t.units {
        writeln!(
            body,
            r#"    // Unit {u}: primitives {u}·c … {u}·c + c − 1 (padding past n: a NaN centre hits nothing).
    wire [15:0] addr{u}_full = 16'd{u} * per_unit + slot_at_memory[15:0];
    wire [{a1}:0] addr{u} = addr{u}_full[{a1}:0];
    reg [{a1}:0] addr{u}_r1 = 0, addr{u}_r2 = 0;
    always @(posedge clk) begin addr{u}_r1 <= addr{u}; addr{u}_r2 <= addr{u}_r1; end
    wire pad{u} = ({{{pad_zeros}'d0, addr{u}_r2}} >= prim_count);"#,
            a1 = ab - 1,
            pad_zeros = 16 - ab,
        )
        .ok();
        let mut unit_fields = BTreeMap::new();
        for (field, bits) in fields(false) {
            let q = format!("u{u}_f{field}");
            memory_ports.push((field, format!("addr{u}"), q.clone(), bits));
            unit_fields.insert(field, q);
        }
        let f = |i: u32| unit_fields.get(&i).cloned().unwrap_or_default();
        let connect = |p: &str| -> Option<String> {
            Some(match p {
                "clk" => "clk".into(),
                "in_valid" => "unit_valid".into(),
                "in_R_x" => "ray_now[95:64]".into(),
                "in_R_y" => "ray_now[63:32]".into(),
                "in_R_z" => "ray_now[31:0]".into(),
                "in_O_x" => "ray_now[95:64]".into(),
                "in_O_y" => "ray_now[63:32]".into(),
                "in_O_z" => "ray_now[31:0]".into(),
                "in_C_x" => format!("pad{u} ? 32'h7FC00000 : {}", f(0)),
                "in_C_y" => f(1),
                "in_C_z" => f(2),
                "in_r" => f(3),
                "in_V_x" => f(4),
                "in_V_y" => f(5),
                "in_V_z" => f(6),
                "in_Mmax" => f(7),
                "in_type" => format!("pad{u} ? 1'b0 : {}", f(8)),
                "in_address" => format!("addr{u}_r2"),
                _ => return None,
            })
        };
        body += &instance(
            &int_text,
            "intersection",
            &format!("unit{u}"),
            "intersection",
            &connect,
            &mut memory_ports,
            &mut decls,
        )?;
        writeln!(
            body,
            r#"    wire [2:0] unit{u}_flags;
    fp_delay #(.WIDTH(3), .LATENCY({l_int})) unit{u}_flag_line (.clk(clk), .d({{unit_valid, unit_first, unit_last}}), .q(unit{u}_flags));
    wire [31:0] min{u}_out_0, min{u}_out_1, min{u}_out_2, min{u}_out_3, min{u}_out_4;
    wire [{a1}:0] min{u}_out_5;
    wire min{u}_out_valid;
    min_distance min{u} (
        .clk(clk), .in_valid(unit{u}_flags[2]), .in_first(unit{u}_flags[1]), .in_last(unit{u}_flags[0]),
        .in_distance(unit{u}_out_0), .in_P_x(unit{u}_out_1), .in_P_y(unit{u}_out_2), .in_P_z(unit{u}_out_3),
        .in_m(unit{u}_out_4), .in_address(unit{u}_out_5),
        .out_0(min{u}_out_0), .out_1(min{u}_out_1), .out_2(min{u}_out_2), .out_3(min{u}_out_3),
        .out_4(min{u}_out_4), .out_5(min{u}_out_5), .out_valid(min{u}_out_valid)
    );"#,
            a1 = ab - 1,
        )
        .ok();
    }

    // The tree joining the units' minima.
    let (nearest, nearest_valid) = if let Some(tree) = &pipeline.min_tree {
        let tree_text = text("min_tree")?;
        let connect = |p: &str| -> Option<String> {
            if p == "clk" {
                return Some("clk".into());
            }
            if p == "in_valid" {
                return Some("min0_out_valid".into());
            }
            let rest = p.strip_prefix("in_")?;
            let digits = |s: &str| s.parse::<u32>().ok();
            let (unit, slot) = if let Some(u) = rest.strip_prefix("distance") {
                (digits(u)?, 0)
            } else if let Some(u) = rest.strip_prefix("address") {
                (digits(u)?, 5)
            } else if let Some(u) = rest.strip_prefix('m') {
                (digits(u)?, 4)
            } else if let Some(u) = rest.strip_prefix('P') {
                let (u, axis) = u.split_once('_')?;
                (
                    digits(u)?,
                    1 + ["x", "y", "z"].iter().position(|a| *a == axis)?,
                )
            } else {
                return None;
            };
            Some(format!("min{unit}_out_{slot}"))
        };
        let _ = tree;
        body += &instance(
            &tree_text,
            "min_tree",
            "tree",
            "min_tree",
            &connect,
            &mut memory_ports,
            &mut decls,
        )?;
        writeln!(
            body,
            "    wire tree_valid;\n    fp_delay #(.WIDTH(1), .LATENCY({l_tree})) tree_valid_line (.clk(clk), .d(min0_out_valid), .q(tree_valid));"
        )
        .ok();
        ("tree_out", "tree_valid")
    } else {
        ("min0_out", "min0_out_valid")
    };

    // Shading.
    let sh_text = text("shading")?;
    let connect = |p: &str| -> Option<String> {
        Some(match p {
            "clk" => "clk".into(),
            "in_valid" => nearest_valid.into(),
            "in_distance" => format!("{nearest}_0"),
            "in_P_x" => format!("{nearest}_1"),
            "in_P_y" => format!("{nearest}_2"),
            "in_P_z" => format!("{nearest}_3"),
            "in_address" => format!("{nearest}_5"),
            _ => return None,
        })
    };
    body += &instance(
        &sh_text,
        "shading",
        "shade",
        "shading",
        &connect,
        &mut memory_ports,
        &mut decls,
    )?;
    writeln!(
        body,
        r#"    // The frame-buffer write port: one gray level per pixel, in issue order.
    wire pixel_ready;
    fp_delay #(.WIDTH(1), .LATENCY({l_shade})) pixel_ready_line (.clk(clk), .d({nearest_valid}), .q(pixel_ready));
    reg [31:0] written = 32'd0;
    always @(posedge clk) if (pixel_ready) written <= written + 32'd1;
    assign fb_we = pixel_ready;
    assign fb_addr = written;
    assign fb_data = shade_out_0;
    assign done = finished & (written == width * height);
    // Monitors: each block's input and output valid (bit: 0 ray, 1 unit 0, 2 minimum
    // distance 0 (its input: a pixel's last primitive), 3 tree, 4 shading).
    assign mon_in = {{3'd0, {nearest_valid}, {tree_in}, unit0_flags[2] & unit0_flags[0], unit_valid, issue}};
    assign mon_out = {{3'd0, shade_out_valid, {tree_out}, min0_out_valid, unit0_out_valid, ray_out_valid}};
"#,
        tree_in = if pipeline.min_tree.is_some() {
            "min0_out_valid"
        } else {
            "1'b0"
        },
        tree_out = if pipeline.min_tree.is_some() {
            "tree_out_valid"
        } else {
            "1'b0"
        },
    )
    .ok();
    let _ = l_min;

    // Scene memory: one RAM per word, a loader write port, 2-cycle read ports.
    let mut memory = String::new();
    writeln!(
        memory,
        "    // Scene memory: 2^{db} primitives, one RAM per word (thesis 6.1.1), written by\n    // the loader; each read port registers its address and its word ({l_mem} cycles).",
        db = t.depth_bits
    )
    .ok();
    let all_fields = fields(design.no_rsqrt_shading);
    for (field, bits) in &all_fields {
        writeln!(
            memory,
            "    reg [{b1}:0] scene_f{field} [0:{d1}];\n    always @(posedge clk) if (load_we && load_field == 4'd{field}) scene_f{field}[load_addr[{db1}:0]] <= load_data[{b1}:0];",
            b1 = bits - 1,
            d1 = (1u32 << t.depth_bits) - 1,
            db1 = t.depth_bits - 1,
        )
        .ok();
    }
    for (i, (field, addr, q, bits)) in memory_ports.iter().enumerate() {
        if !all_fields.iter().any(|(f, _)| f == field) {
            return Err(RtlError::Generate(format!(
                "a block reads scene word {field}, which this design does not store"
            )));
        }
        writeln!(
            memory,
            "    reg [{db1}:0] port{i}_a = 0;\n    reg [{b1}:0] {q} = 0;\n    always @(posedge clk) begin port{i}_a <= {addr}[{db1}:0]; {q} <= scene_f{field}[port{i}_a]; end",
            db1 = t.depth_bits - 1,
            b1 = bits - 1,
        )
        .ok();
    }

    Ok(format!(
        "// Generated by rtprof: the {label} pipeline, {units} intersection unit(s).\n// Latencies (model schedule): primary ray {l_ray}, intersection {l_int}, minimum distance {l_min}, tree {l_tree}, shading {l_shade}.\nmodule {TOP} (\n    {ports}\n);\n{decls}{body}{memory}endmodule\n",
        label = design.label(),
        units = t.units,
        ports = ports.join(",\n    "),
    ))
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
    use hwmodel::design::Design;

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
        ]
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
        let text = block_module(&lib, &p.intersection, "intersection").unwrap();
        let count = |needle: &str| text.matches(needle).count() as u32;
        let s = &p.intersection.schedule;
        assert_eq!(count("fp_add_sub #(.LATENCY(7))"), s.count(OpKind::AddSub));
        assert_eq!(
            count("fp_mul #(.LATENCY(5))") + count("fp_mul #(.LATENCY(7))"),
            s.count(OpKind::Multiply) + s.count(OpKind::MultiplyRegistered)
        );
        assert_eq!(count("fp_sqrt #(.LATENCY(16))"), 1);
        assert_eq!(count("fp_div #(.LATENCY(6))"), 2);
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
    fn identifiers_are_verilog_names() {
        assert_eq!(identifier("R.x"), "R_x");
        assert_eq!(identifier("L̂.y"), "Lhat_y");
        assert_eq!(identifier("scan_line.z"), "scan_line_z");
        assert_eq!(identifier("0 (bit)"), "0_bit");
    }
}
