//! Dataflow graphs of operators: ASAP scheduling and delay balancing.
//!
//! A graph is a list of nodes in topological order (a node's inputs are added before
//! it). Every operator starts as soon as its last input is ready (ASAP); the graph's
//! latency is the latest finish among its outputs, and all outputs leave together. In a
//! pipeline every value must travel alongside the others, so a value that is ready
//! before its consumer starts waits in a delay line: one line per producer, as long as
//! its largest slack, tapped for the nearer consumers (slack = consumer start − producer
//! finish, or latency − finish for an output). The library decides whether a line sits
//! in registers or in memory ([`Library::delay_line`]).
//!
//! Values that do not change with every item need no balancing: frame constants (eye,
//! light, camera steps) and values a block holds stable for a while (the minimum
//! distance block's inputs are held 3 cycles by the 3n pacing) are inputs with a
//! `hold` time; a row register is loaded once per image row, long before the pixels
//! that read it, so it starts every pixel's timing path at zero.

use serde::Serialize;

use crate::library::{Library, OpKind, Resources};

/// Index of a node in its graph.
pub type NodeId = usize;

/// A value held for the whole frame.
pub const FRAME_CONSTANT: u32 = u32::MAX;

/// What a node is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeKind {
    /// A block input, valid from cycle 0 for `hold` cycles (0: changes every cycle,
    /// [`FRAME_CONSTANT`]: never changes during a frame).
    Input { hold: u32 },
    /// An operator instance.
    Op(OpKind),
    /// A register loaded once per image row from its input (off the per-pixel path).
    RowRegister,
}

/// What an add/sub core computes from its inputs `[a, b]`. A negated operand is a
/// flipped sign bit on the wire (no logic, exact), so all four are one IP core.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AddSubMode {
    /// `a + b`.
    Add,
    /// `a − b`.
    Sub,
    /// `−a + b`.
    NegAdd,
    /// `−a − b`.
    NegSub,
}

/// What a node means beyond its operator kind: the part of the graph the scheduler
/// ignores and the RTL generator and the graph evaluator need.
///
/// Operand order is meaning too: a compare's inputs `[a, b]` give `a < b`; a select's
/// `[sel, a, b]` give `sel ? b : a`; a register's `[value, enable]` load `value` when
/// `enable` is set (no enable: every cycle).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Detail {
    /// Nothing more (block inputs, multipliers, roots, compares, selects, registers).
    #[default]
    None,
    /// A literal frame constant: its IEEE-754 bit pattern (or integer value).
    Literal(u32),
    /// An add/sub core and what it computes.
    AddSub(AddSubMode),
    /// A scene-memory read: word `field` of the primitive at the address input
    /// (`HwPrimitive::WORD_NAMES` order, then the shading extras).
    Field(u32),
}

/// One node.
#[derive(Clone, Debug)]
pub struct Node {
    pub kind: NodeKind,
    pub inputs: Vec<NodeId>,
    /// Width of the value it produces.
    pub bits: u32,
    pub label: String,
    pub detail: Detail,
}

/// A dataflow graph under construction or finished.
#[derive(Clone, Debug, Default)]
pub struct Graph {
    nodes: Vec<Node>,
    outputs: Vec<NodeId>,
}

/// A delay line inserted to balance a path.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct DelayLine {
    pub producer: String,
    pub bits: u32,
    pub cycles: u32,
    /// True when the library puts it in memory.
    pub in_memory: bool,
}

/// The result of scheduling a graph.
#[derive(Clone, Debug)]
pub struct Schedule {
    /// Start cycle of every node (0 for inputs and row registers).
    pub start: Vec<u32>,
    /// Cycle at which every node's value is ready.
    pub finish: Vec<u32>,
    /// Cycles from the inputs to the outputs.
    pub latency: u32,
    /// Delay lines, longest first.
    pub delay_lines: Vec<DelayLine>,
    /// Sum of the operator instances.
    pub operators: Resources,
    /// Delay lines and row registers.
    pub balancing: Resources,
    /// Operator instances per kind.
    pub op_counts: Vec<(OpKind, u32)>,
}

impl Schedule {
    /// Operators plus balancing.
    pub fn resources(&self) -> Resources {
        self.operators + self.balancing
    }

    /// Number of instances of `op`.
    pub fn count(&self, op: OpKind) -> u32 {
        self.op_counts
            .iter()
            .find(|(k, _)| *k == op)
            .map_or(0, |(_, n)| *n)
    }
}

impl Graph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    fn push(&mut self, kind: NodeKind, inputs: Vec<NodeId>, bits: u32, label: &str) -> NodeId {
        debug_assert!(inputs.iter().all(|&i| i < self.nodes.len()));
        self.nodes.push(Node {
            kind,
            inputs,
            bits,
            label: label.to_string(),
            detail: Detail::None,
        });
        self.nodes.len() - 1
    }

    fn with_detail(&mut self, id: NodeId, detail: Detail) -> NodeId {
        self.nodes[id].detail = detail;
        id
    }

    /// A 32-bit input that changes with every item.
    pub fn input(&mut self, label: &str) -> NodeId {
        self.push(NodeKind::Input { hold: 0 }, Vec::new(), 32, label)
    }

    /// An input of `bits` valid for `hold` cycles.
    pub fn input_held(&mut self, label: &str, bits: u32, hold: u32) -> NodeId {
        self.push(NodeKind::Input { hold }, Vec::new(), bits, label)
    }

    /// A 32-bit frame constant (eye, light, camera step, literal).
    pub fn constant(&mut self, label: &str) -> NodeId {
        self.input_held(label, 32, FRAME_CONSTANT)
    }

    /// A literal 32-bit frame constant (0, 1, 2, 4, 255, ∞ …).
    pub fn literal(&mut self, label: &str, value: f32) -> NodeId {
        let id = self.constant(label);
        self.with_detail(id, Detail::Literal(value.to_bits()))
    }

    /// A literal frame constant of `bits` (a flag or a small integer).
    pub fn literal_bits(&mut self, label: &str, bits: u32, value: u32) -> NodeId {
        let id = self.input_held(label, bits, FRAME_CONSTANT);
        self.with_detail(id, Detail::Literal(value))
    }

    /// An add/sub core computing `mode` of `[a, b]`.
    pub fn add_sub(&mut self, mode: AddSubMode, a: NodeId, b: NodeId, label: &str) -> NodeId {
        let id = self.op(OpKind::AddSub, &[a, b], label);
        self.with_detail(id, Detail::AddSub(mode))
    }

    /// `a + b`.
    pub fn add(&mut self, a: NodeId, b: NodeId, label: &str) -> NodeId {
        self.add_sub(AddSubMode::Add, a, b, label)
    }

    /// `a − b`.
    pub fn sub(&mut self, a: NodeId, b: NodeId, label: &str) -> NodeId {
        self.add_sub(AddSubMode::Sub, a, b, label)
    }

    /// `a < b` (one bit).
    pub fn less(&mut self, a: NodeId, b: NodeId, label: &str) -> NodeId {
        self.op_bits(OpKind::Compare, &[a, b], 1, label)
    }

    /// `a < b` for non-negative floats, compared as integers (one bit).
    pub fn less_int(&mut self, a: NodeId, b: NodeId, label: &str) -> NodeId {
        self.op_bits(OpKind::IntCompare, &[a, b], 1, label)
    }

    /// `sel ? b : a`, as wide as `a`.
    pub fn select(&mut self, sel: NodeId, a: NodeId, b: NodeId, label: &str) -> NodeId {
        let bits = self.nodes[a].bits;
        self.op_bits(OpKind::Mux, &[sel, a, b], bits, label)
    }

    /// A read of word `field` of the primitive at `address` from the scene memory.
    pub fn ram_read(&mut self, address: NodeId, field: u32, bits: u32, label: &str) -> NodeId {
        let id = self.op_bits(OpKind::RamRead, &[address], bits, label);
        self.with_detail(id, Detail::Field(field))
    }

    /// An operator producing a 32-bit value.
    pub fn op(&mut self, op: OpKind, inputs: &[NodeId], label: &str) -> NodeId {
        self.op_bits(op, inputs, 32, label)
    }

    /// An operator producing a value of `bits` (flags: 1).
    pub fn op_bits(&mut self, op: OpKind, inputs: &[NodeId], bits: u32, label: &str) -> NodeId {
        self.push(NodeKind::Op(op), inputs.to_vec(), bits, label)
    }

    /// A row register loaded from `input`.
    pub fn row_register(&mut self, input: NodeId, label: &str) -> NodeId {
        let bits = self.nodes[input].bits;
        self.push(NodeKind::RowRegister, vec![input], bits, label)
    }

    /// Marks `node` as a block output.
    pub fn output(&mut self, node: NodeId) {
        self.outputs.push(node);
    }

    /// The nodes, in insertion (topological) order.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The outputs.
    pub fn outputs(&self) -> &[NodeId] {
        &self.outputs
    }

    /// ASAP schedule, latency and resources under `lib`.
    pub fn schedule(&self, lib: &Library) -> Schedule {
        let n = self.nodes.len();
        let mut start = vec![0u32; n];
        let mut finish = vec![0u32; n];
        for (id, node) in self.nodes.iter().enumerate() {
            if let NodeKind::Op(op) = node.kind {
                start[id] = node.inputs.iter().map(|&i| finish[i]).max().unwrap_or(0);
                finish[id] = start[id] + lib.op(op).latency;
            }
        }
        let latency = self.outputs.iter().map(|&o| finish[o]).max().unwrap_or(0);

        // Largest wait of every value: before a consumer starts, or before the outputs
        // leave. Row registers read their input once per row: no wait counted there.
        let mut wait = vec![0u32; n];
        for (id, node) in self.nodes.iter().enumerate() {
            if node.kind == NodeKind::RowRegister {
                continue;
            }
            for &i in &node.inputs {
                wait[i] = wait[i].max(start[id] - finish[i]);
            }
        }
        for &o in &self.outputs {
            wait[o] = wait[o].max(latency - finish[o]);
        }

        let word = u64::from(lib.word_bits);
        let mut operators = Resources::default();
        let mut balancing = Resources::default();
        let mut delay_lines = Vec::new();
        let mut op_counts: Vec<(OpKind, u32)> = Vec::new();
        for (id, node) in self.nodes.iter().enumerate() {
            let hold = match node.kind {
                NodeKind::Input { hold } => hold,
                NodeKind::Op(op) => {
                    let spec = lib.op(op);
                    // Selects and registers are as wide as their value; IP cores are
                    // fixed single-precision instances.
                    operators += if matches!(op, OpKind::Mux | OpKind::Register) {
                        scale_by_width(spec.resources, u64::from(node.bits), word)
                    } else {
                        spec.resources
                    };
                    match op_counts.iter_mut().find(|(k, _)| *k == op) {
                        Some((_, c)) => *c += 1,
                        None => op_counts.push((op, 1)),
                    }
                    0
                }
                NodeKind::RowRegister => {
                    balancing += lib.delay_line(u64::from(node.bits), 1);
                    FRAME_CONSTANT
                }
            };
            let cycles = wait[id].saturating_sub(hold);
            if cycles > 0 {
                let cost = lib.delay_line(u64::from(node.bits), u64::from(cycles));
                balancing += cost;
                delay_lines.push(DelayLine {
                    producer: node.label.clone(),
                    bits: node.bits,
                    cycles,
                    in_memory: cost.mem_bits > 0,
                });
            }
        }
        delay_lines.sort_by_key(|l| std::cmp::Reverse((l.cycles, l.bits)));
        op_counts.sort();
        Schedule {
            start,
            finish,
            latency,
            delay_lines,
            operators,
            balancing,
            op_counts,
        }
    }
}

/// `r` for a value of `bits` when the row is for `word` bits (rounded up).
fn scale_by_width(r: Resources, bits: u64, word: u64) -> Resources {
    let s = |v: u64| (v * bits).div_ceil(word);
    Resources {
        le: s(r.le),
        comb: s(r.comb),
        regs: s(r.regs),
        mem_bits: s(r.mem_bits),
        mult: s(r.mult),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lib() -> Library {
        Library::cyclone_iv_e()
    }

    #[test]
    fn a_chain_schedules_to_the_sum_of_its_latencies_without_balancing() {
        // x·y then + z then sqrt: 5 + 7 + 16 = 28 cycles. z is needed at cycle 5:
        // it waits 5 cycles (160 register bits).
        let mut g = Graph::new();
        let x = g.input("x");
        let y = g.input("y");
        let z = g.input("z");
        let p = g.op(OpKind::Multiply, &[x, y], "x·y");
        let s = g.op(OpKind::AddSub, &[p, z], "x·y+z");
        let r = g.op(OpKind::Sqrt, &[s], "sqrt");
        g.output(r);
        let sch = g.schedule(&lib());
        assert_eq!(sch.latency, 28);
        assert_eq!((sch.start[p], sch.start[s], sch.start[r]), (0, 5, 12));
        assert_eq!(sch.delay_lines.len(), 1);
        assert_eq!(sch.delay_lines[0].cycles, 5);
        assert_eq!(sch.balancing.regs, 5 * 32);
        assert_eq!(sch.balancing.le, 5 * 32);
        assert_eq!(sch.operators.le, 301 + 906 + 1207);
        assert_eq!(sch.operators.mult, 7);
    }

    #[test]
    fn the_shorter_of_two_paths_gets_a_delay_line_of_the_difference() {
        // a+b (7) and c·d (5) feed a multiply: the product waits 2 cycles. A second
        // output, the sum itself, leaves with the final product at cycle 12: it waits 5.
        let mut g = Graph::new();
        let a = g.input("a");
        let b = g.input("b");
        let c = g.input("c");
        let d = g.input("d");
        let sum = g.op(OpKind::AddSub, &[a, b], "a+b");
        let prod = g.op(OpKind::Multiply, &[c, d], "c·d");
        let out = g.op(OpKind::Multiply, &[sum, prod], "(a+b)·c·d");
        g.output(out);
        g.output(sum);
        let sch = g.schedule(&lib());
        assert_eq!(sch.latency, 12);
        let lines: Vec<(String, u32)> = sch
            .delay_lines
            .iter()
            .map(|l| (l.producer.clone(), l.cycles))
            .collect();
        assert_eq!(lines, vec![("a+b".to_string(), 5), ("c·d".to_string(), 2)]);
        assert_eq!(sch.balancing.regs, (5 + 2) * 32);
    }

    #[test]
    fn one_tapped_line_serves_every_consumer_of_a_value() {
        // v feeds consumers starting at 0, 7 and 14: one line of 14, not 7 + 14.
        let mut g = Graph::new();
        let v = g.input("v");
        let w = g.input("w");
        let s1 = g.op(OpKind::AddSub, &[v, w], "s1");
        let s2 = g.op(OpKind::AddSub, &[s1, v], "s2");
        let s3 = g.op(OpKind::AddSub, &[s2, v], "s3");
        g.output(s3);
        let sch = g.schedule(&lib());
        assert_eq!(sch.latency, 21);
        let v_line = sch.delay_lines.iter().find(|l| l.producer == "v").unwrap();
        assert_eq!(v_line.cycles, 14);
        // w is used at cycle 0 only.
        assert!(sch.delay_lines.iter().all(|l| l.producer != "w"));
    }

    #[test]
    fn long_delays_go_to_memory_and_constants_are_never_delayed() {
        // v waits for a sqrt and an inverse sqrt (16 + 28 = 44 cycles): memory.
        let mut g = Graph::new();
        let v = g.input("v");
        let k = g.constant("k");
        let s = g.op(OpKind::Sqrt, &[v], "sqrt");
        let r = g.op(OpKind::InvSqrt, &[s], "rsqrt");
        let m = g.op(OpKind::Multiply, &[r, v], "v·r");
        let n = g.op(OpKind::Multiply, &[m, k], "·k");
        g.output(n);
        let sch = g.schedule(&lib());
        assert_eq!(sch.latency, 16 + 28 + 5 + 5);
        assert_eq!(sch.delay_lines.len(), 1);
        assert!(sch.delay_lines[0].in_memory);
        assert_eq!(sch.balancing.mem_bits, 44 * 32);
        assert_eq!(sch.balancing.regs, 0);
    }

    #[test]
    fn held_inputs_wait_only_beyond_their_hold_time() {
        // Held 3 cycles, needed at 5 (after a multiply): 2 cycles of delay.
        let mut g = Graph::new();
        let a = g.input("a");
        let h = g.input_held("h", 32, 3);
        let p = g.op(OpKind::Multiply, &[a, a], "a²");
        let s = g.op(OpKind::AddSub, &[p, h], "a²+h");
        g.output(s);
        let sch = g.schedule(&lib());
        assert_eq!(sch.delay_lines[0].cycles, 2);
        assert_eq!(sch.balancing.regs, 64);
    }

    #[test]
    fn a_row_register_takes_its_path_off_the_pixel_latency() {
        // Row path: i·step (5) + base (7) = 12 cycles, registered once per row; the
        // pixel path j·step (5) + row (7) = 12, not 5 + 7 + 7 = 19.
        let mut g = Graph::new();
        let i = g.constant("i");
        let step = g.constant("step");
        let base = g.constant("base");
        let j = g.input("j");
        let row_term = g.op(OpKind::Multiply, &[i, step], "i·step");
        let row = g.op(OpKind::AddSub, &[base, row_term], "row");
        let row_reg = g.row_register(row, "row base");
        let col = g.op(OpKind::Multiply, &[j, step], "j·step");
        let out = g.op(OpKind::AddSub, &[row_reg, col], "dir");
        g.output(out);
        let sch = g.schedule(&lib());
        assert_eq!(sch.latency, 12);
        // The register itself: 32 bits; no delay line for the row path.
        assert_eq!(sch.balancing.regs, 32);
        assert!(sch.delay_lines.is_empty());
        assert_eq!(sch.count(OpKind::Multiply), 2);
        assert_eq!(sch.count(OpKind::AddSub), 2);
    }

    #[test]
    fn selects_and_registers_cost_by_width() {
        let mut g = Graph::new();
        let a = g.input_held("addr", 13, 3);
        let r = g.op_bits(OpKind::Register, &[a], 13, "addr reg");
        g.output(r);
        let sch = g.schedule(&lib());
        assert_eq!(sch.operators.regs, 13);
        assert_eq!(sch.latency, 1);
    }
}
