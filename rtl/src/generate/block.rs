//! One graph block as a Verilog module: every operator node an instance of the
//! library at its latency, every producer one tapped delay line (registers, or a
//! circular buffer in memory), a monitor valid bit beside the data.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

use hwmodel::blocks::{ADDRESS_BITS, Block};
use hwmodel::graph::{AddSubMode, Detail, FRAME_CONSTANT, Graph, NodeKind};
use hwmodel::library::{Library, OpKind};

use super::{BlockModule, Port, RAM_SEGMENT_MIN, identifier, malformed};
use crate::RtlError;
use crate::operators::Operator;

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
        // The integer compare lives only in the minimum-distance block, which is
        // written by hand (`verilog/min_distance.v`).
        OpKind::Mux | OpKind::Register | OpKind::RamRead | OpKind::IntCompare => return None,
    })
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
    ports: Vec<Port>,
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

    fn write(mut self, module: &str) -> Result<BlockModule, RtlError> {
        let graph = self.graph();
        let schedule = &self.block.schedule;
        let nodes = graph.nodes();
        let has_row_registers = nodes.iter().any(|n| n.kind == NodeKind::RowRegister);
        self.ports.push(Port::input(1, "clk"));
        self.ports.push(Port::input(1, "in_valid"));
        if has_row_registers {
            self.ports.push(Port::input(1, "row_load"));
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
                    self.ports
                        .push(Port::input(bits, format!("{prefix}{name}")));
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
            self.ports.push(Port::output(bits, format!("out_{k}")));
            writeln!(self.body, "    assign out_{k} = {value};").ok();
            outputs.push(valid);
        }
        self.ports.push(Port::output(1, "out_valid"));
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
            self.ports
                .iter()
                .map(Port::declaration)
                .collect::<Vec<_>>()
                .join(",\n    ")
        );
        text += &self.body;
        text += "`ifndef SYNTHESIS\n    // Monitor: the items' valid bits through the block's own structure.\n";
        text += &self.monitor;
        text += "`else\n    assign out_valid = 1'b0;\n`endif\nendmodule\n";
        Ok(BlockModule {
            text,
            ports: self.ports,
        })
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
                    .push(Port::output(ADDRESS_BITS, format!("rd{id}_addr")));
                self.ports
                    .push(Port::input(bits, format!("rd{id}_f{field}")));
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
pub fn block_module(lib: &Library, block: &Block, module: &str) -> Result<BlockModule, RtlError> {
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
    let text = block_module(lib, block, "probe")?.text;
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
