//! Cutting a flattened, pipelined netlist at its registers: which register level every
//! flip-flop bit is at, and the logic between two levels as a netlist of its own.
//!
//! The input is Yosys's JSON of one flattened module after `proc; flatten;
//! opt -nosdff -nodffe` (so that every register is a plain `$dff` and the logic in
//! front of it stays logic, to be mapped again by the flow that places the piece).
//! A flip-flop bit's *level* is one more than the highest level among the flip-flop
//! bits its D input depends on through logic (an input port is level 0): in a
//! feed-forward pipeline the registers after stage k are at level k, whatever path
//! the signals took. A loop through registers has no level and is an error.
//!
//! [`Netlist::piece`] keeps the logic in front of the flip-flops of levels
//! `first..=last` (their D cones, which stop at flip-flops and inputs) and the
//! flip-flops of levels `first..last` themselves, and makes the rest ports of a new
//! module `pnr_piece`: every bit the kept cells read and do not drive is an input,
//! every bit they drive that something outside reads (the level-`last` flip-flops'
//! D, a later stage's logic) an output. The place-and-route harness
//! ([`super::stages`]) registers both sides, so the piece's paths run from register
//! to register as they do in the whole operator. Cells keep their parameters and
//! attributes, and the nets their names and attributes (`keep` on the prefix adders'
//! levels matters: without it ABC folds them back into ripple adders).

use std::collections::{BTreeMap, BTreeSet, HashMap};

use serde_json::{Map, Value, json};

/// The module name of a piece.
pub const PIECE: &str = "pnr_piece";
/// A piece's ports.
pub const PIECE_IN: &str = "piece_in";
pub const PIECE_OUT: &str = "piece_out";
pub const PIECE_CLK: &str = "clk";

/// Register cells other than `$dff` (and memories): the cut does not handle them, so
/// a netlist that has one is refused rather than cut wrongly.
const OTHER_SEQUENTIAL: &[&str] = &[
    "$dffe",
    "$sdff",
    "$sdffe",
    "$sdffce",
    "$adff",
    "$adffe",
    "$aldff",
    "$aldffe",
    "$dffsr",
    "$dffsre",
    "$sr",
    "$ff",
    "$dlatch",
    "$adlatch",
    "$dlatchsr",
    "$mem",
    "$mem_v2",
    "$memrd",
    "$memrd_v2",
    "$memwr",
    "$memwr_v2",
    "$meminit",
    "$meminit_v2",
    "$fsm",
];

/// One bit of a connection: a net, or a constant (`"0"`, `"1"`, `"x"`, `"z"`).
fn net(bit: &Value) -> Option<u64> {
    bit.as_u64()
}

/// A logic (not register) cell.
struct Logic {
    name: String,
    json: Value,
    inputs: Vec<u64>,
    outputs: Vec<u64>,
}

/// One flip-flop bit: its D (a net or a constant) and its clock.
struct FlipFlop {
    d: Value,
    clk: u64,
    polarity: Value,
}

/// A flattened module, ready to be cut.
pub struct Netlist {
    logic: Vec<Logic>,
    /// Flip-flop bits by their Q net.
    flops: BTreeMap<u64, FlipFlop>,
    /// The logic cell that drives a net.
    driver: HashMap<u64, usize>,
    /// The logic cells that read a net.
    readers: HashMap<u64, Vec<usize>>,
    /// Nets the flip-flops' D inputs read, with how many times.
    read_by_flops: HashMap<u64, usize>,
    /// Nets of the module's output ports.
    port_outputs: BTreeSet<u64>,
    netnames: Map<String, Value>,
    /// Each flip-flop bit's level, by its Q net.
    levels: BTreeMap<u64, u32>,
}

/// The logic between two register levels, as a module of its own.
#[derive(Debug)]
pub struct Piece {
    /// Yosys JSON of module [`PIECE`].
    pub json: String,
    /// Its logic cells (Yosys's coarse cells), flip-flop bits, input and output bits.
    pub logic_cells: usize,
    pub flip_flops: usize,
    pub inputs: usize,
    pub outputs: usize,
    /// The indices of its logic cells (for the coverage check).
    pub cells: BTreeSet<usize>,
}

impl Netlist {
    /// Reads module `top` of a Yosys JSON netlist; `clock` is its clock port.
    pub fn parse(text: &str, top: &str, clock: &str) -> Result<Netlist, String> {
        let root: Value = serde_json::from_str(text).map_err(|e| format!("not JSON: {e}"))?;
        let module = root
            .get("modules")
            .and_then(|m| m.get(top))
            .and_then(Value::as_object)
            .ok_or_else(|| format!("no module `{top}`"))?;
        let ports = module
            .get("ports")
            .and_then(Value::as_object)
            .ok_or("no ports")?;
        let bits = |v: &Value| -> Vec<Value> {
            v.get("bits")
                .and_then(Value::as_array)
                .cloned()
                .unwrap_or_default()
        };
        let clk_bits = ports
            .get(clock)
            .map(bits)
            .ok_or_else(|| format!("no clock port `{clock}`"))?;
        let clk = match clk_bits.as_slice() {
            [b] => net(b).ok_or("the clock is a constant")?,
            _ => return Err("the clock port is not one bit".into()),
        };
        let mut port_outputs = BTreeSet::new();
        for port in ports.values() {
            if port.get("direction").and_then(Value::as_str) == Some("output") {
                port_outputs.extend(bits(port).iter().filter_map(net));
            }
        }
        let cells = module
            .get("cells")
            .and_then(Value::as_object)
            .ok_or("no cells")?;
        let mut netlist = Netlist {
            logic: Vec::new(),
            flops: BTreeMap::new(),
            driver: HashMap::new(),
            readers: HashMap::new(),
            read_by_flops: HashMap::new(),
            port_outputs,
            netnames: module
                .get("netnames")
                .and_then(Value::as_object)
                .cloned()
                .unwrap_or_default(),
            levels: BTreeMap::new(),
        };
        for (name, cell) in cells {
            let kind = cell.get("type").and_then(Value::as_str).unwrap_or("");
            let connections = cell
                .get("connections")
                .and_then(Value::as_object)
                .ok_or_else(|| format!("cell `{name}` has no connections"))?;
            let port = |p: &str| -> Vec<Value> {
                connections
                    .get(p)
                    .and_then(Value::as_array)
                    .cloned()
                    .unwrap_or_default()
            };
            if kind == "$dff" {
                let (d, q, c) = (port("D"), port("Q"), port("CLK"));
                if d.len() != q.len() || c.len() != 1 {
                    return Err(format!("`$dff` `{name}`: ports of unequal widths"));
                }
                let cell_clk = net(&c[0]).ok_or_else(|| format!("`{name}`: constant clock"))?;
                if cell_clk != clk {
                    return Err(format!("`{name}`: clocked by another net than `{clock}`"));
                }
                let polarity = cell
                    .get("parameters")
                    .and_then(|p| p.get("CLK_POLARITY"))
                    .cloned()
                    .unwrap_or(json!(1));
                for (d, q) in d.into_iter().zip(q) {
                    let q = net(&q).ok_or_else(|| format!("`{name}`: a constant Q"))?;
                    if let Some(n) = net(&d) {
                        *netlist.read_by_flops.entry(n).or_default() += 1;
                    }
                    let ff = FlipFlop {
                        d,
                        clk,
                        polarity: polarity.clone(),
                    };
                    if netlist.flops.insert(q, ff).is_some() {
                        return Err(format!("net {q} is driven twice"));
                    }
                }
                continue;
            }
            if !kind.starts_with('$') || OTHER_SEQUENTIAL.contains(&kind) {
                return Err(format!(
                    "cell `{name}` of type `{kind}`: only logic and `$dff` can be cut"
                ));
            }
            let directions = cell
                .get("port_directions")
                .and_then(Value::as_object)
                .ok_or_else(|| format!("cell `{name}` has no port directions"))?;
            let index = netlist.logic.len();
            let mut logic = Logic {
                name: name.clone(),
                json: cell.clone(),
                inputs: Vec::new(),
                outputs: Vec::new(),
            };
            for (p, dir) in directions {
                let nets = port(p).iter().filter_map(net).collect::<Vec<_>>();
                match dir.as_str() {
                    Some("output") => logic.outputs.extend(nets),
                    _ => logic.inputs.extend(nets),
                }
            }
            for &n in &logic.outputs {
                if netlist.driver.insert(n, index).is_some() || netlist.flops.contains_key(&n) {
                    return Err(format!("net {n} is driven twice"));
                }
            }
            for &n in &logic.inputs {
                netlist.readers.entry(n).or_default().push(index);
            }
            netlist.logic.push(logic);
        }
        if let Some(n) = netlist
            .flops
            .keys()
            .find(|q| netlist.driver.contains_key(q))
        {
            return Err(format!("net {n} is driven twice"));
        }
        netlist.levels = netlist.compute_levels()?;
        Ok(netlist)
    }

    /// Every flip-flop bit's level (see the module doc), by an iterative depth-first
    /// walk over nets (a pipeline's logic is too deep for recursion).
    fn compute_levels(&self) -> Result<BTreeMap<u64, u32>, String> {
        // The level of the launching register of a net: 0 for an input or a constant.
        let mut level: HashMap<u64, u32> = HashMap::new();
        let mut open: HashMap<u64, bool> = HashMap::new();
        for &start in self.flops.keys() {
            let mut stack = vec![(start, false)];
            while let Some((n, expanded)) = stack.pop() {
                if level.contains_key(&n) {
                    continue;
                }
                let deps: Vec<u64> = if let Some(ff) = self.flops.get(&n) {
                    net(&ff.d).into_iter().collect()
                } else if let Some(&c) = self.driver.get(&n) {
                    self.logic[c].inputs.clone()
                } else {
                    Vec::new()
                };
                if expanded {
                    let below = deps.iter().map(|d| level[d]).max().unwrap_or(0);
                    let own = if self.flops.contains_key(&n) {
                        below + 1
                    } else {
                        below
                    };
                    level.insert(n, own);
                    open.remove(&n);
                    continue;
                }
                if open.insert(n, true).is_some() {
                    return Err(format!(
                        "net {n} depends on itself: a loop, not a feed-forward pipeline"
                    ));
                }
                stack.push((n, true));
                for d in deps {
                    if !level.contains_key(&d) {
                        if open.contains_key(&d) {
                            return Err(format!(
                                "net {d} depends on itself: a loop, not a feed-forward pipeline"
                            ));
                        }
                        stack.push((d, false));
                    }
                }
            }
        }
        Ok(self.flops.keys().map(|q| (*q, level[q])).collect())
    }

    /// The number of register levels (the highest level of a flip-flop bit).
    pub fn register_levels(&self) -> u32 {
        self.levels.values().copied().max().unwrap_or(0)
    }

    /// The number of logic cells.
    pub fn logic_cells(&self) -> usize {
        self.logic.len()
    }

    /// The logic cells in the D cones of the flip-flop bits at levels `first..=last`.
    fn cone(&self, first: u32, last: u32) -> BTreeSet<usize> {
        self.cone_of(
            self.levels
                .iter()
                .filter(|(_, l)| (first..=last).contains(*l))
                .filter_map(|(q, _)| net(&self.flops[q].d))
                .collect(),
        )
    }

    /// The logic cells some register or output port depends on: the rest drives
    /// nothing (a `keep` wire's unused driver) and lies on no path.
    pub fn live_cells(&self) -> BTreeSet<usize> {
        self.cone_of(
            self.flops
                .values()
                .filter_map(|ff| net(&ff.d))
                .chain(self.port_outputs.iter().copied())
                .collect(),
        )
    }

    /// The logic cells the nets `stack` depend on, back to registers and inputs.
    fn cone_of(&self, mut stack: Vec<u64>) -> BTreeSet<usize> {
        let mut cells = BTreeSet::new();
        while let Some(n) = stack.pop() {
            if let Some(&c) = self.driver.get(&n)
                && cells.insert(c)
            {
                stack.extend(self.logic[c].inputs.iter().copied());
            }
        }
        cells
    }

    /// The piece between register levels `first - 1` and `last` (see the module doc).
    pub fn piece(&self, first: u32, last: u32) -> Piece {
        let cells = self.cone(first, last);
        let kept: BTreeMap<u64, &FlipFlop> = self
            .levels
            .iter()
            .filter(|(_, l)| (first..last).contains(*l))
            .map(|(q, _)| (*q, &self.flops[q]))
            .collect();
        let mut driven: BTreeSet<u64> = kept.keys().copied().collect();
        for &c in &cells {
            driven.extend(self.logic[c].outputs.iter().copied());
        }
        let mut inputs = BTreeSet::new();
        let mut kept_reads: HashMap<u64, usize> = HashMap::new();
        for ff in kept.values() {
            if let Some(n) = net(&ff.d) {
                *kept_reads.entry(n).or_default() += 1;
                if !driven.contains(&n) {
                    inputs.insert(n);
                }
            }
        }
        for &c in &cells {
            inputs.extend(self.logic[c].inputs.iter().filter(|n| !driven.contains(n)));
        }
        // Read outside: by a cell not kept, a flip-flop not kept, or an output port.
        let outputs: BTreeSet<u64> = driven
            .iter()
            .copied()
            .filter(|n| {
                let by_cells = self
                    .readers
                    .get(n)
                    .is_some_and(|r| r.iter().any(|c| !cells.contains(c)));
                let by_flops = self.read_by_flops.get(n).copied().unwrap_or(0)
                    > kept_reads.get(n).copied().unwrap_or(0);
                by_cells || by_flops || self.port_outputs.contains(n)
            })
            .collect();
        let mut json_cells = Map::new();
        for &c in &cells {
            let logic = &self.logic[c];
            json_cells.insert(logic.name.clone(), logic.json.clone());
        }
        for (q, ff) in &kept {
            json_cells.insert(
                format!("$piece$dff${q}"),
                json!({
                    "hide_name": 1,
                    "type": "$dff",
                    "parameters": {"CLK_POLARITY": ff.polarity, "WIDTH": 1},
                    "attributes": {},
                    "port_directions": {"CLK": "input", "D": "input", "Q": "output"},
                    "connections": {"CLK": [ff.clk], "D": [ff.d], "Q": [q]},
                }),
            );
        }
        let clk = kept
            .values()
            .next()
            .map(|ff| ff.clk)
            .or_else(|| self.flops.values().next().map(|ff| ff.clk));
        let present: BTreeSet<u64> = inputs.union(&driven).copied().chain(clk).collect();
        let mut netnames = Map::new();
        for (name, value) in &self.netnames {
            let Some(bits) = value.get("bits").and_then(Value::as_array) else {
                continue;
            };
            if !bits
                .iter()
                .any(|b| net(b).is_some_and(|n| present.contains(&n)))
            {
                continue;
            }
            let mut value = value.clone();
            let bits: Vec<Value> = bits
                .iter()
                .map(|b| match net(b) {
                    Some(n) if !present.contains(&n) => json!("x"),
                    _ => b.clone(),
                })
                .collect();
            value["bits"] = json!(bits);
            netnames.insert(name.clone(), value);
        }
        let inputs: Vec<u64> = inputs.into_iter().collect();
        let outputs: Vec<u64> = outputs.into_iter().collect();
        let mut ports = Map::new();
        for (name, direction, bits) in [
            (PIECE_IN, "input", inputs.clone()),
            (PIECE_OUT, "output", outputs.clone()),
        ] {
            ports.insert(name.into(), json!({"direction": direction, "bits": bits}));
            netnames.insert(name.into(), json!({"hide_name": 0, "bits": bits}));
        }
        // The clock port, also when no flip-flop is kept (the harness connects it).
        let clk_bits: Vec<Value> = match clk {
            Some(c) if !inputs.contains(&c) && !outputs.contains(&c) => vec![json!(c)],
            _ => vec![json!("x")],
        };
        ports.insert(
            PIECE_CLK.into(),
            json!({"direction": "input", "bits": clk_bits}),
        );
        netnames.insert(PIECE_CLK.into(), json!({"hide_name": 0, "bits": clk_bits}));
        let module = json!({
            "attributes": {},
            "ports": ports,
            "cells": json_cells,
            "netnames": netnames,
        });
        let json = json!({"creator": "rtl::synth::stage_cut (rtprof)", "modules": {PIECE: module}})
            .to_string();
        Piece {
            json,
            logic_cells: cells.len(),
            flip_flops: kept.len(),
            inputs: inputs.len(),
            outputs: outputs.len(),
            cells,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A two-stage pipeline by hand: input a (net 3, 4) → r1 = a0 & a1 (level 1) →
    /// r2 = !r1 (level 2), with a bypass r2b = a0 registered twice (levels 1, 2).
    fn two_stages() -> String {
        json!({"modules": {"top": {
            "ports": {
                "clk": {"direction": "input", "bits": [2]},
                "a": {"direction": "input", "bits": [3, 4]},
                "y": {"direction": "output", "bits": [8, 10]},
            },
            "cells": {
                "and": {"type": "$and", "port_directions": {"A": "input", "B": "input", "Y": "output"},
                        "connections": {"A": [3], "B": [4], "Y": [5]}},
                "r1": {"type": "$dff", "parameters": {"CLK_POLARITY": 1, "WIDTH": 2},
                       "port_directions": {"CLK": "input", "D": "input", "Q": "output"},
                       "connections": {"CLK": [2], "D": [5, 3], "Q": [6, 9]}},
                "not": {"type": "$not", "port_directions": {"A": "input", "Y": "output"},
                        "connections": {"A": [6], "Y": [7]}},
                "r2": {"type": "$dff", "parameters": {"CLK_POLARITY": 1, "WIDTH": 2},
                       "port_directions": {"CLK": "input", "D": "input", "Q": "output"},
                       "connections": {"CLK": [2], "D": [7, 9], "Q": [8, 10]}},
            },
            "netnames": {"mid": {"hide_name": 0, "bits": [5, 6], "attributes": {"keep": 1}}},
        }}})
        .to_string()
    }

    #[test]
    fn flip_flops_get_the_level_of_their_stage() {
        let n = Netlist::parse(&two_stages(), "top", "clk").unwrap();
        assert_eq!(n.register_levels(), 2);
        assert_eq!(n.logic_cells(), 2);
        assert_eq!(n.live_cells().len(), 2);
    }

    #[test]
    fn a_piece_is_the_logic_between_its_registers() {
        let n = Netlist::parse(&two_stages(), "top", "clk").unwrap();
        // Stage 2 alone: the inverter, r1's Q in, r2's D out; the bypass is no logic.
        let p = n.piece(2, 2);
        assert_eq!(
            (p.logic_cells, p.flip_flops, p.inputs, p.outputs),
            (1, 0, 1, 1)
        );
        let v: Value = serde_json::from_str(&p.json).unwrap();
        let m = &v["modules"][PIECE];
        assert_eq!(m["ports"][PIECE_IN]["bits"], json!([6]));
        assert_eq!(m["ports"][PIECE_OUT]["bits"], json!([7]));
        // A net half inside keeps its name and attributes, the other half undriven.
        assert_eq!(m["netnames"]["mid"]["bits"], json!(["x", 6]));
        assert_eq!(m["netnames"]["mid"]["attributes"]["keep"], json!(1));
        // Both stages: r1 kept as two one-bit flip-flops, the inputs a in, r2's D out.
        let p = n.piece(1, 2);
        assert_eq!(
            (p.logic_cells, p.flip_flops, p.inputs, p.outputs),
            (2, 2, 2, 2)
        );
        assert_eq!(p.cells.len(), 2);
    }

    #[test]
    fn loops_and_other_registers_are_refused() {
        let looped = two_stages().replace("\"A\":[6]", "\"A\":[7]");
        assert!(looped != two_stages());
        let e = Netlist::parse(&looped, "top", "clk").err().unwrap();
        assert!(e.contains("loop"), "{e}");
        let enabled = two_stages().replace("\"type\":\"$dff\"", "\"type\":\"$dffe\"");
        assert!(Netlist::parse(&enabled, "top", "clk").is_err());
        assert!(Netlist::parse(&two_stages(), "top", "clock").is_err());
    }
}
