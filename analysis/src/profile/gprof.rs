//! GNU gprof's two text reports, the flat profile and the call graph, built from
//! sampled call stacks (SIGPROF with full stacks) instead of gprof's instrumentation.
//! They use gprof's own layout (binutils `gprof/hist.c` and `gprof/cg_print.c`,
//! non-BSD style), so anyone who reads gprof output can read them. The same figures are
//! available as serde data for JSON, and parsers read both texts back column by column.
//!
//! # Figures
//! - *self* of a function: samples whose last (running) frame is that function.
//! - *inclusive* (self + children): samples whose stack holds the function anywhere,
//!   counted once per sample however often recursion repeats it, so no figure can
//!   exceed 100%. *children* = inclusive − self.
//! - Seconds = samples × `seconds_per_sample`, over all the renders sampled.
//!   Percentages are of all samples whose stack has at least one frame (stacks without
//!   frames are ignored).
//! - Call counts are exact calls per render ([`ProfileInput`]); the text says how many
//!   renders were sampled. A count of 0 is treated as no count and left blank, as
//!   gprof does. Functions with a non-zero count but no samples are listed with zero
//!   time.
//!
//! The flat profile lives in [`super::flat`] (re-exported here).
//!
//! # Call graph
//! - Arcs are caller → callee pairs that are adjacent in some stack.
//! - Arc times: in each sample, every function gives the sample to exactly one arc,
//!   the one into its *outermost* occurrence in that stack. The sample is self time
//!   on that arc when the function is the running frame, and children time otherwise.
//!   So the arcs into a function add up to its own self and children, except for
//!   samples in which it is the outermost frame (sibling arcs count too, though
//!   their times are only in the data, not the text). Outermost rather than
//!   innermost, so that the caller from outside a recursion carries all of it, as in
//!   gprof. Only recursive functions (always cycle members, see below) can occur
//!   twice in a stack, and their arcs among themselves are printed without times.
//! - Cycles are strongly connected components of the arc graph with more than one
//!   member or with a self-arc (`f` calling `f` directly), numbered from 1 in the
//!   order of their entries. Members are printed as `name <cycle N>`. The
//!   `<cycle N as a whole>` entry has self = the members' self time and children =
//!   the time spent in functions outside the cycle called from it (samples holding
//!   any member, counted once, minus those where a member runs). Its parent lines
//!   are the arcs entering the cycle from outside, credited at the first member on
//!   the stack. Its lines below are the members (gprof lists members there), each
//!   with its own self and children and its call count. A member keeps its own
//!   once-per-sample figures, which include time spent in the other members it
//!   calls; gprof would show only time propagated from outside the cycle there.
//!   Arcs between members of one cycle are printed in gprof's "call among siblings"
//!   form, without times.
//! - Entries are numbered by decreasing inclusive time. Ties go to the cycle entry
//!   first (as in gprof), then to the function met nearer the root of a stack (so
//!   a caller comes before a callee with the same time; gprof compares call counts
//!   here), then to the name.
//! - Parent lines run from the smallest to the largest arc time, with siblings
//!   first. Child lines run from the largest to the smallest, with siblings last.
//!   A function without callers gets the `<spontaneous>` line.
//! - Arc call counts are unknown with sampling, so the `called` column of arcs is
//!   blank. So is gprof's `+N` self-call column.
//! - The granularity line keeps gprof's shape but says `one call stack` instead of
//!   a number of bytes. The line after it says how many renders were sampled
//!   (free text above the column headings, where gprof prints its own).
//! - Index by function name: functions by name, then cycles (`<cycle N>`), three per
//!   row and running down the columns as gprof does, each cell `%6.6s %-19.19s`.
//!   Longer names are printed in full and push the rest of their row to the right.
//!   The `[index]` column is never cut to 6 characters either.

pub use super::flat::{
    FlatProfile, FlatRow, WHOLE_RUN_PERCENT, bottleneck, flat_profile, largest_inclusive,
};
pub use super::tally::ProfileInput;
use super::tally::{Tally, percent_of};
use serde::{Deserialize, Serialize};
use std::cmp::Reverse;
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;

/// The line gprof prints after each call-graph entry.
const SEPARATOR: &str = "-----------------------------------------------";

/// Width of one cell in the index by function name (`%6.6s %-19.19s`).
const INDEX_CELL_WIDTH: usize = 26;

const CALL_GRAPH_NOTES: &str = "
Callers are listed above each function's own line, callees below, with the time
that flowed along each call (self: function running; children: its callees). A
sample counts once per function, recursion included. Arc call counts are unknown
with sampling. A <cycle N> entry sums its members and lists them below it.
";

/// gprof's call graph.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CallGraph {
    pub total_seconds: f64,
    /// Samples behind `total_seconds`, for the granularity line.
    pub total_samples: u64,
    /// Renders the samples cover (at least 1); `calls` are per render.
    pub renders: u64,
    /// In index order: `entries[i].index == i + 1`.
    pub entries: Vec<CallGraphEntry>,
}

/// One entry of the call graph: a function or a cycle as a whole.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CallGraphEntry {
    pub index: usize,
    /// Function name, or `<cycle N as a whole>` for a cycle entry.
    pub name: String,
    /// Share of all samples holding this function (or cycle), in percent.
    pub percent: f64,
    pub self_seconds: f64,
    pub children_seconds: f64,
    pub calls: Option<u64>,
    /// Callers, in printed order.
    pub parents: Vec<CallArc>,
    /// Callees in printed order; for a cycle entry, its members.
    pub children: Vec<CallArc>,
    /// Number of the cycle this function belongs to (or that this entry is).
    pub cycle: Option<u32>,
    /// True for the `<cycle N as a whole>` entry.
    pub whole_cycle: bool,
}

/// A caller or callee of an entry, with the time that flowed along the call.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CallArc {
    pub name: String,
    /// Index of the caller's or callee's own entry.
    pub index: usize,
    pub self_seconds: f64,
    pub children_seconds: f64,
}

/// Samples of one arc or cycle entry, split by whether the function (cycle) was running.
#[derive(Clone, Copy, Debug, Default)]
struct Split {
    self_samples: u64,
    children_samples: u64,
}

impl Split {
    fn add(&mut self, running: bool, samples: u64) {
        let slot = if running {
            &mut self.self_samples
        } else {
            &mut self.children_samples
        };
        *slot = slot.saturating_add(samples);
    }

    fn total(self) -> u64 {
        self.self_samples.saturating_add(self.children_samples)
    }
}

/// Builds gprof's call graph from sampled stacks and exact calls per render.
pub fn call_graph(input: &ProfileInput<'_>) -> CallGraph {
    let tally = Tally::new(input);
    let function_count = tally.names.len();
    let seconds = |count: u64| count as f64 * input.samples.seconds_per_sample;

    // Arcs: each sample goes, per function, to the arc into its outermost occurrence.
    let mut arcs: BTreeMap<(usize, usize), Split> = BTreeMap::new();
    let mut credited_in = vec![usize::MAX; function_count];
    for (stack_number, (frames, weight)) in tally.stacks.iter().enumerate() {
        let running = frames.last().copied();
        let mut caller = None;
        for &function in frames {
            let first = credited_in[function] != stack_number;
            credited_in[function] = stack_number;
            if let Some(caller) = caller {
                let arc = arcs.entry((caller, function)).or_default();
                if first {
                    arc.add(running == Some(function), *weight);
                }
            }
            caller = Some(function);
        }
    }

    // Cycles: strongly connected components with several members or a self-arc.
    let mut callees = vec![Vec::new(); function_count];
    for &(caller, callee) in arcs.keys() {
        callees[caller].push(callee);
    }
    let mut components: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (function, component) in strongly_connected_components(&callees)
        .into_iter()
        .enumerate()
    {
        components.entry(component).or_default().push(function);
    }
    let cycles: Vec<Vec<usize>> = components
        .into_values()
        .filter(|members| match members.as_slice() {
            [only] => arcs.contains_key(&(*only, *only)),
            _ => true,
        })
        .collect();
    let mut cycle_of = vec![None; function_count];
    for (cycle, members) in cycles.iter().enumerate() {
        for &member in members {
            cycle_of[member] = Some(cycle);
        }
    }

    // Cycle figures: every sample counts once per cycle, at its first member on the stack.
    let mut cycle_split = vec![Split::default(); cycles.len()];
    let mut cycle_entering: Vec<BTreeMap<usize, Split>> = vec![BTreeMap::new(); cycles.len()];
    let mut counted_in = vec![usize::MAX; cycles.len()];
    for (stack_number, (frames, weight)) in tally.stacks.iter().enumerate() {
        let running_cycle = frames.last().and_then(|&f| cycle_of[f]);
        let mut caller = None;
        for &function in frames {
            if let Some(cycle) = cycle_of[function]
                && counted_in[cycle] != stack_number
            {
                counted_in[cycle] = stack_number;
                let running = running_cycle == Some(cycle);
                cycle_split[cycle].add(running, *weight);
                if let Some(caller) = caller {
                    let entering = cycle_entering[cycle].entry(caller).or_default();
                    entering.add(running, *weight);
                }
            }
            caller = Some(function);
        }
    }

    // Entry order: time, cycle entries first, nearer the stack root, name.
    #[derive(Clone, Copy)]
    enum Node {
        Function(usize),
        Cycle(usize),
    }
    let function_key = |f: usize| (Reverse(tally.inclusive_samples[f]), true, tally.depth[f], f);
    let cycle_key = |c: usize| {
        let first_member = cycles[c].first().copied().unwrap_or(0);
        (Reverse(cycle_split[c].total()), false, 0, first_member)
    };
    let mut nodes: Vec<Node> = (0..function_count)
        .map(Node::Function)
        .chain((0..cycles.len()).map(Node::Cycle))
        .collect();
    nodes.sort_by_key(|&node| match node {
        Node::Function(f) => function_key(f),
        Node::Cycle(c) => cycle_key(c),
    });
    // Indexes from 1 in entry order; cycles are numbered in the same order.
    let mut function_index = vec![0; function_count];
    let mut cycle_number = vec![None; cycles.len()];
    let mut cycles_seen = 0u32;
    for (position, node) in nodes.iter().enumerate() {
        match *node {
            Node::Function(f) => function_index[f] = position + 1,
            Node::Cycle(c) => {
                cycles_seen = cycles_seen.saturating_add(1);
                cycle_number[c] = Some(cycles_seen);
            }
        }
    }

    let mut parents_of: Vec<Vec<(usize, Split)>> = vec![Vec::new(); function_count];
    let mut children_of: Vec<Vec<(usize, Split)>> = vec![Vec::new(); function_count];
    for (&(caller, callee), &split) in &arcs {
        parents_of[callee].push((caller, split));
        children_of[caller].push((callee, split));
    }
    let same_cycle = |a: usize, b: usize| cycle_of[a].is_some() && cycle_of[a] == cycle_of[b];
    let arc_to = |f: usize, split: Split| CallArc {
        name: tally.names[f].clone(),
        index: function_index[f],
        self_seconds: seconds(split.self_samples),
        children_seconds: seconds(split.children_samples),
    };
    let own_split = |f: usize| Split {
        self_samples: tally.self_samples[f],
        children_samples: tally.children_samples(f),
    };

    let entries = nodes
        .iter()
        .enumerate()
        .map(|(position, &node)| match node {
            Node::Function(f) => {
                let mut parents = parents_of[f].clone();
                parents.sort_by_key(|&(p, s)| {
                    if same_cycle(p, f) {
                        (false, 0, p)
                    } else {
                        (true, s.total(), p)
                    }
                });
                let mut children = children_of[f].clone();
                children.sort_by_key(|&(c, s)| (same_cycle(c, f), Reverse(s.total()), c));
                CallGraphEntry {
                    index: position + 1,
                    name: tally.names[f].clone(),
                    percent: percent_of(tally.inclusive_samples[f], tally.total_samples),
                    self_seconds: seconds(tally.self_samples[f]),
                    children_seconds: seconds(tally.children_samples(f)),
                    calls: tally.calls[f],
                    parents: parents.into_iter().map(|(p, s)| arc_to(p, s)).collect(),
                    children: children.into_iter().map(|(c, s)| arc_to(c, s)).collect(),
                    cycle: cycle_of[f].and_then(|c| cycle_number[c]),
                    whole_cycle: false,
                }
            }
            Node::Cycle(c) => {
                let mut parents: Vec<(usize, Split)> =
                    cycle_entering[c].iter().map(|(&p, &s)| (p, s)).collect();
                parents.sort_by_key(|&(p, s)| (s.total(), p));
                let mut members = cycles[c].clone();
                members.sort_by_key(|&m| (Reverse(tally.inclusive_samples[m]), tally.depth[m], m));
                let number = cycle_number[c].unwrap_or(0);
                CallGraphEntry {
                    index: position + 1,
                    name: format!("<cycle {number} as a whole>"),
                    percent: percent_of(cycle_split[c].total(), tally.total_samples),
                    self_seconds: seconds(cycle_split[c].self_samples),
                    children_seconds: seconds(cycle_split[c].children_samples),
                    calls: None,
                    parents: parents.into_iter().map(|(p, s)| arc_to(p, s)).collect(),
                    children: members
                        .into_iter()
                        .map(|m| arc_to(m, own_split(m)))
                        .collect(),
                    cycle: Some(number),
                    whole_cycle: true,
                }
            }
        })
        .collect();
    CallGraph {
        total_seconds: seconds(tally.total_samples),
        total_samples: tally.total_samples,
        renders: input.renders(),
        entries,
    }
}

/// Tarjan's strongly connected components, iterative so that deep graphs cannot
/// overflow the stack. Returns a component number per node.
fn strongly_connected_components(callees: &[Vec<usize>]) -> Vec<usize> {
    const UNSEEN: usize = usize::MAX;
    let count = callees.len();
    let mut order = vec![UNSEEN; count];
    let mut low = vec![0; count];
    let mut on_stack = vec![false; count];
    let mut component = vec![UNSEEN; count];
    let mut stack = Vec::new();
    let mut work: Vec<(usize, usize)> = Vec::new(); // (node, next callee to visit)
    let (mut next_order, mut next_component) = (0, 0);
    for root in 0..count {
        if order[root] != UNSEEN {
            continue;
        }
        work.push((root, 0));
        while let Some(&(node, edge)) = work.last() {
            if edge == 0 && order[node] == UNSEEN {
                order[node] = next_order;
                low[node] = next_order;
                next_order += 1;
                stack.push(node);
                on_stack[node] = true;
            }
            if let Some(&callee) = callees[node].get(edge) {
                if let Some(top) = work.last_mut() {
                    top.1 += 1;
                }
                if order[callee] == UNSEEN {
                    work.push((callee, 0));
                } else if on_stack[callee] {
                    low[node] = low[node].min(order[callee]);
                }
                continue;
            }
            work.pop();
            if let Some(&(parent, _)) = work.last() {
                low[parent] = low[parent].min(low[node]);
            }
            if low[node] == order[node] {
                while let Some(member) = stack.pop() {
                    on_stack[member] = false;
                    component[member] = next_component;
                    if member == node {
                        break;
                    }
                }
                next_component += 1;
            }
        }
    }
    component
}

impl CallGraph {
    /// The call graph as gprof prints it: entries, a short explanation, the index.
    pub fn to_text(&self) -> String {
        let by_index: HashMap<usize, &CallGraphEntry> =
            self.entries.iter().map(|e| (e.index, e)).collect();
        // How an arc's target is named: with its cycle, as gprof's print_name does.
        let label = |arc: &CallArc| match by_index.get(&arc.index) {
            Some(target) if !target.whole_cycle => {
                format!("{} [{}]", display_name(target), arc.index)
            }
            _ => format!("{} [{}]", arc.name, arc.index),
        };
        let sibling = |entry: &CallGraphEntry, arc: &CallArc| {
            !entry.whole_cycle
                && entry.cycle.is_some()
                && by_index
                    .get(&arc.index)
                    .is_some_and(|t| !t.whole_cycle && t.cycle == entry.cycle)
        };

        let mut out = String::from("\t\t     Call graph (explanation follows)\n\n\n");
        out.push_str("granularity: each sample hit covers one call stack");
        if self.total_samples > 0 {
            let one_sample = 100.0 / self.total_samples as f64;
            let _ = writeln!(
                out,
                " for {one_sample:.2}% of {:.2} seconds",
                self.total_seconds
            );
        } else {
            out.push_str(" no time propagated\n");
        }
        let renders = self.renders.max(1);
        if renders == 1 {
            out.push_str("1 render sampled; calls are per render, seconds for that render.\n\n");
        } else {
            let _ = writeln!(
                out,
                "{renders} renders sampled; calls are per render, seconds for all {renders} renders.\n"
            );
        }
        out.push_str("index % time    self  children    called     name\n");
        for entry in &self.entries {
            if entry.parents.is_empty() {
                let _ = writeln!(out, "{:49}<spontaneous>", "");
            }
            for parent in &entry.parents {
                let times = (!sibling(entry, parent))
                    .then_some((parent.self_seconds, parent.children_seconds));
                push_arc_line(&mut out, times, None, &label(parent));
            }
            let _ = write!(
                out,
                "{:<6} {:5.1} {:7.2} {:7.2}",
                format!("[{}]", entry.index),
                entry.percent,
                entry.self_seconds,
                entry.children_seconds
            );
            let _ = match entry.calls {
                Some(calls) if calls != 0 => write!(out, " {calls:7} {:7} ", ""),
                _ => write!(out, " {:7} {:7} ", "", ""),
            };
            let _ = writeln!(out, "{} [{}]", display_name(entry), entry.index);
            for child in &entry.children {
                let times = (!sibling(entry, child))
                    .then_some((child.self_seconds, child.children_seconds));
                // Under a cycle entry the lines are members, which show their call count.
                let calls = if entry.whole_cycle {
                    by_index.get(&child.index).and_then(|m| m.calls)
                } else {
                    None
                };
                push_arc_line(&mut out, times, calls, &label(child));
            }
            out.push_str(SEPARATOR);
            out.push('\n');
        }
        out.push_str(CALL_GRAPH_NOTES);
        out.push_str("\nIndex by function name\n\n");
        self.push_index(&mut out);
        out
    }

    /// gprof's index: names in order, three columns filled top to bottom.
    fn push_index(&self, out: &mut String) {
        let mut listed: Vec<&CallGraphEntry> = self.entries.iter().collect();
        listed.sort_by(|a, b| {
            let key =
                |e: &CallGraphEntry| (e.whole_cycle, if e.whole_cycle { e.cycle } else { None });
            key(a).cmp(&key(b)).then_with(|| a.name.cmp(&b.name))
        });
        let rows = listed.len().div_ceil(3);
        for row in 0..rows {
            let mut line = String::new();
            for (column, entry) in listed.iter().skip(row).step_by(rows).enumerate() {
                let name = match (entry.whole_cycle, entry.cycle) {
                    (true, Some(number)) => format!("<cycle {number}>"),
                    _ => display_name(entry),
                };
                // A long name in front pushes this cell right; keep at least one space.
                let start = column * INDEX_CELL_WIDTH;
                let width = line.chars().count();
                if width < start {
                    line.extend(std::iter::repeat_n(' ', start - width));
                } else if width > start {
                    line.push(' ');
                }
                let _ = write!(line, "{:>6} {name:<19}", format!("[{}]", entry.index));
            }
            out.push_str(line.trim_end());
            out.push('\n');
        }
    }
}

/// Name as gprof prints it: members of a cycle carry ` <cycle N>`.
fn display_name(entry: &CallGraphEntry) -> String {
    match entry.cycle {
        Some(number) if !entry.whole_cycle => format!("{} <cycle {number}>", entry.name),
        _ => entry.name.clone(),
    }
}

/// A parent, child or member line: `%6.6s %5.5s %7.2f %7.2f %7.7s %7.7s     name`, with
/// blank times for calls among siblings and the count in the first `called` column.
fn push_arc_line(out: &mut String, times: Option<(f64, f64)>, calls: Option<u64>, label: &str) {
    let _ = match times {
        Some((own, children)) => write!(out, "{:6} {:5} {own:7.2} {children:7.2}", "", ""),
        None => write!(out, "{:6} {:5} {:7} {:7}", "", "", "", ""),
    };
    let _ = match calls {
        Some(calls) => write!(out, " {calls:7} {:7}", ""),
        None => write!(out, " {:7} {:7}", "", ""),
    };
    let _ = writeln!(out, "     {label}");
}

#[cfg(test)]
pub(crate) mod tests;
