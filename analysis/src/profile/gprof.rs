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
//!   any member, counted once, minus those where a member runs). Its parents (in
//!   the data only: the text lists none, as gprof) are the arcs entering the cycle
//!   from outside, credited at the first member on the stack. Its lines below are
//!   the members (gprof lists members there), each with its own self and children
//!   and its call count. A member keeps its own
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
//! - Arc call counts are unknown with sampling: what flows along an arc is samples.
//!   See [Columns](#columns) for what the `called` column holds instead.
//! - The granularity line keeps gprof's shape but says `one call stack` instead of
//!   a number of bytes. The lines after it say how many renders were sampled and
//!   what the arcs' `called` column holds (free text above the column headings,
//!   where gprof prints its own).
//! - The entries end with a form feed line after the explanation, as in gprof's
//!   output: gprof2dot reads the call graph up to it.
//! - Index by function name: functions by name, then cycles (`<cycle N>`), three per
//!   row and running down the columns as gprof does, each cell `%6.6s %-19.19s`.
//!   Longer names are printed in full and push the rest of their row to the right.
//!   The `[index]` column is never cut to 6 characters either.
//!
//! # Columns
//! What each column of the call graph text holds, in rtprof's file (sampled,
//! [`Origin::Sampled`]) and for a graph read from gprof ([`Origin::Gprof`],
//! [`super::gprof_import`]), whose text is gprof's own. A recorded run of another
//! program ([`Origin::Recorded`], `rtprof record`) is sampled, without call counts.
//!
//! | line | column | sampled (rtprof) | read from gprof |
//! |---|---|---|---|
//! | primary | `% time` | share of samples holding the function (or cycle) | gprof's, the same |
//! | primary | `self`, `children` | seconds of samples with it running / below it, once per sample | gprof's: histogram time, children's time propagated by call counts |
//! | primary | `called` | exact calls per render (blank: not counted) | calls, `+N` calls from itself |
//! | parent, child | `self`, `children` | seconds that flowed along the call | the same, as gprof propagated them |
//! | parent, child | `called` | `S/T`: samples along this call / samples that entered the function (for a cycle member: its cycle) from outside its cycle | `C/T`: calls along this call / calls of the function (its cycle) from outside its cycle |
//! | sibling (same cycle, or itself) | `called` | samples along the call; no times | calls; no times |
//! | cycle member | `called` | the member's calls per render, `0` when not counted (gprof prints a count on every member line) | the member's calls, `+N` from itself |
//!
//! The parent and child lines must carry a count: gprof2dot (`-f prof`) reads every
//! such line as `count[/total]` and splits a callee's time among its callers in
//! proportion to those counts. With samples there, its split is the sampled one
//! (exact, where gprof's own split assumes every call costs the same). Writing
//! gprof's "no count" instead (`0/0`, what `gprof -c` writes for arcs it only saw
//! statically) makes gprof2dot give every caller the callee's whole time: callers
//! above 100 % and `ratio greater than one` warnings. A cycle's whole entry lists
//! no callers (gprof lists none; gprof2dot takes an entry with callers for a
//! function): they are in its members' entries, and in [`CallGraphEntry::parents`].

use super::Origin;
use super::flat::RECORDED_LINE;
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

/// The line above a sampled graph's headings saying what its arc counts are; the
/// importer refuses a text with it ([`super::gprof_import`]).
pub(super) const SAMPLED_COUNTS_LINE: &str =
    "On callers' and callees' lines `called` is samples, not calls (see below).";

/// The explanation after the entries of a sampled graph.
const SAMPLED_NOTES: &str = "
Callers are listed above each function's own line, callees below, with the time
that flowed along each call (self: function running; children: its callees). A
sample counts once per function, recursion included. A function's own `called` is
its exact calls per render (blank: not counted). On its callers' and callees'
lines `called` holds samples, not calls, which are not counted per call: S/T is
the S samples that flowed along the call out of the T that entered the function
(or its cycle) from outside its cycle. A <cycle N> entry sums its members and
lists them below it, each with its calls per render (0: not counted); the
cycle's callers are in its members' entries.
";

/// The explanation after the entries of a recorded run's graph: no calls counted.
const RECORDED_NOTES: &str = "
Callers are listed above each function's own line, callees below, with the time
that flowed along each call (self: function running; children: its callees). A
sample counts once per function, recursion included. One run of the program was
sampled and its calls were not counted: a function's own `called` is blank. On
its callers' and callees' lines `called` holds samples: S/T is the S samples
that flowed along the call out of the T that entered the function (or its cycle)
from outside its cycle. A <cycle N> entry sums its members and lists them below
it; the cycle's callers are in its members' entries.
";

/// The explanation after the entries of a graph read from gprof.
const GPROF_NOTES: &str = "
Read from gprof's output: calls are the exact counts of the -pg build, times as
gprof propagated them. Callers are listed above each function's own line, callees
below; `called` on their lines is calls along the call / all calls of the function
(or its cycle) from outside its cycle. A <cycle N> entry sums its members and
lists them below it; the cycle's callers are in its members' entries.
";

/// gprof's call graph.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CallGraph {
    /// Sampled by rtprof or read from gprof: what the arcs' counts are.
    #[serde(default)]
    pub origin: Origin,
    pub total_seconds: f64,
    /// Samples behind `total_seconds`, for the granularity line.
    pub total_samples: u64,
    /// Renders the samples cover (at least 1); `calls` are per render.
    pub renders: u64,
    /// In index order. rtprof numbers them without gaps (`entries[i].index == i + 1`);
    /// gprof skips the indexes of functions it does not print.
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
    /// Calls from itself (gprof's `+N`), read from gprof; rtprof's sampled graphs
    /// put a self-calling function in a cycle instead.
    #[serde(default)]
    pub self_calls: Option<u64>,
    /// Callers, in printed order (a cycle entry's are in the data only).
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
    /// Samples that flowed along the call (self + children); for a cycle entry's
    /// member lines, the member's own samples.
    #[serde(default)]
    pub samples: u64,
    /// Exact calls along the call, read from gprof; `None` when sampled.
    #[serde(default)]
    pub calls: Option<u64>,
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
        samples: split.total(),
        calls: None,
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
                    self_calls: None,
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
                    self_calls: None,
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
        origin: Origin::Sampled,
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
    /// The call graph as gprof prints it: entries, a short explanation, a form feed,
    /// the index. See [Columns](self#columns) for what each column holds.
    pub fn to_text(&self) -> String {
        let by_index: HashMap<usize, &CallGraphEntry> =
            self.entries.iter().map(|e| (e.index, e)).collect();
        let cycle_entries: HashMap<u32, &CallGraphEntry> = self
            .entries
            .iter()
            .filter(|e| e.whole_cycle)
            .filter_map(|e| e.cycle.map(|number| (number, e)))
            .collect();
        // How an arc's target is named: with its cycle, as gprof's print_name does.
        let label = |arc: &CallArc| match by_index.get(&arc.index) {
            Some(target) if !target.whole_cycle => {
                format!("{} [{}]", display_name(target), arc.index)
            }
            _ => format!("{} [{}]", arc.name, arc.index),
        };
        // A call among members of one cycle, or to itself: gprof prints no times.
        let sibling = |entry: &CallGraphEntry, arc: &CallArc| {
            !entry.whole_cycle
                && (arc.index == entry.index
                    || entry.cycle.is_some()
                        && by_index
                            .get(&arc.index)
                            .is_some_and(|t| !t.whole_cycle && t.cycle == entry.cycle))
        };
        let count = |arc: &CallArc| {
            if self.origin.sampled() {
                arc.samples
            } else {
                arc.calls.unwrap_or(0)
            }
        };
        // The denominator of `count/total`: what entered the function, or the cycle
        // it belongs to, from outside that cycle (gprof's cycle head's calls).
        let entered = |index: usize| -> u64 {
            let Some(&target) = by_index.get(&index) else {
                return 0;
            };
            let head = match target.cycle {
                Some(number) if !target.whole_cycle => {
                    cycle_entries.get(&number).copied().unwrap_or(target)
                }
                _ => target,
            };
            if self.origin.sampled() {
                head.parents
                    .iter()
                    .filter(|p| !sibling(head, p))
                    .fold(0u64, |sum, p| sum.saturating_add(p.samples))
            } else {
                head.calls.unwrap_or(0)
            }
        };
        let arc_line = |out: &mut String, entry: &CallGraphEntry, arc: &CallArc, total: u64| {
            if sibling(entry, arc) {
                push_arc_line(
                    out,
                    None,
                    &format!("{:7} {:7}", count(arc), ""),
                    &label(arc),
                );
            } else {
                let called = format!("{:7}/{:<7}", count(arc), total);
                let times = Some((arc.self_seconds, arc.children_seconds));
                push_arc_line(out, times, &called, &label(arc));
            }
        };

        let mut out = String::from("\t\t     Call graph (explanation follows)\n\n\n");
        out.push_str(match self.origin {
            Origin::Sampled | Origin::Recorded => {
                "granularity: each sample hit covers one call stack"
            }
            Origin::Gprof => "granularity: each sample hit covers one histogram bucket",
        });
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
        match self.origin {
            Origin::Sampled => {
                let renders = self.renders.max(1);
                if renders == 1 {
                    out.push_str(
                        "1 render sampled; calls are per render, seconds for that render.\n",
                    );
                } else {
                    let _ = writeln!(
                        out,
                        "{renders} renders sampled; calls are per render, seconds for all {renders} renders."
                    );
                }
                out.push_str(SAMPLED_COUNTS_LINE);
                out.push_str("\n\n");
            }
            Origin::Recorded => {
                out.push_str(RECORDED_LINE);
                out.push_str(SAMPLED_COUNTS_LINE);
                out.push_str("\n\n");
            }
            Origin::Gprof => out.push_str("Read from gprof's output; calls counted by -pg.\n\n"),
        }
        out.push_str("index % time    self  children    called     name\n");
        for entry in &self.entries {
            // A cycle's entry starts with its own line: its callers are its members'.
            if !entry.whole_cycle {
                if entry.parents.is_empty() {
                    let _ = writeln!(out, "{:49}<spontaneous>", "");
                }
                for parent in &entry.parents {
                    arc_line(&mut out, entry, parent, entered(entry.index));
                }
            }
            let _ = write!(
                out,
                "{:<6} {:5.1} {:7.2} {:7.2}",
                format!("[{}]", entry.index),
                entry.percent,
                entry.self_seconds,
                entry.children_seconds
            );
            let calls = entry.calls.filter(|&c| c != 0);
            let self_calls = entry.self_calls.filter(|&c| c != 0);
            let _ = match (calls, self_calls) {
                (None, None) => write!(out, " {:7} {:7} ", "", ""),
                (calls, None) => write!(out, " {:7} {:7} ", calls.unwrap_or(0), ""),
                (calls, Some(own)) => write!(out, " {:7}+{own:<7} ", calls.unwrap_or(0)),
            };
            let _ = writeln!(out, "{} [{}]", display_name(entry), entry.index);
            for child in &entry.children {
                if entry.whole_cycle {
                    // A member: its own times and calls (gprof prints a count on each).
                    let member = by_index.get(&child.index);
                    let calls = member.and_then(|m| m.calls).or(child.calls).unwrap_or(0);
                    let called = match member.and_then(|m| m.self_calls).filter(|&c| c != 0) {
                        Some(own) => format!("{calls:7}+{own:<7}"),
                        None => format!("{calls:7} {:7}", ""),
                    };
                    let times = Some((child.self_seconds, child.children_seconds));
                    push_arc_line(&mut out, times, &called, &label(child));
                } else {
                    arc_line(&mut out, entry, child, entered(child.index));
                }
            }
            out.push_str(SEPARATOR);
            out.push('\n');
        }
        out.push_str(match self.origin {
            Origin::Sampled => SAMPLED_NOTES,
            Origin::Recorded => RECORDED_NOTES,
            Origin::Gprof => GPROF_NOTES,
        });
        // gprof ends the call graph with a form feed; gprof2dot reads up to it.
        out.push_str("\x0c\nIndex by function name\n\n");
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

/// A parent, child or member line: `%6.6s %5.5s %7.2f %7.2f`, then the 15 columns of
/// `called` (`%7lu/%-7lu`, `%7lu %7.7s` or `%7lu+%-7lu`) and five spaces before the
/// name; blank times for calls among siblings.
fn push_arc_line(out: &mut String, times: Option<(f64, f64)>, called: &str, label: &str) {
    let _ = match times {
        Some((own, children)) => write!(out, "{:6} {:5} {own:7.2} {children:7.2}", "", ""),
        None => write!(out, "{:6} {:5} {:7} {:7}", "", "", "", ""),
    };
    let _ = writeln!(out, " {called}     {label}");
}

#[cfg(test)]
pub(crate) mod tests;
