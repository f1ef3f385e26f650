//! What both gprof reports read: the sampled stacks with the exact calls per render
//! ([`ProfileInput`]), and the per-function sample counts taken from them (self:
//! running; inclusive: anywhere on the stack, once per sample).

use super::{CallCounts, StackSamples};
use std::collections::{BTreeSet, HashMap};

/// A sampled profile with its exact call counts.
///
/// The samples cover all `renders` renders the profiler ran (a fast render is
/// repeated to gather enough samples); `calls` are the counts of ONE render (identical
/// for every render, so exact). Times per call are therefore
/// `seconds / renders / calls`.
#[derive(Clone, Copy, Debug)]
pub struct ProfileInput<'a> {
    pub samples: &'a StackSamples,
    /// Exact calls per render by function name.
    pub calls: &'a CallCounts,
    /// Renders the samples cover; 0 is read as 1.
    pub renders: u64,
}

impl ProfileInput<'_> {
    /// Renders sampled, at least 1.
    pub fn renders(&self) -> u64 {
        self.renders.max(1)
    }
}

/// Per-function sample counts shared by both reports.
pub(super) struct Tally {
    /// Function names in name order; a function's id is its position here.
    pub(super) names: Vec<String>,
    /// Stacks as function ids (never empty) with their sample counts.
    pub(super) stacks: Vec<(Vec<usize>, u64)>,
    pub(super) self_samples: Vec<u64>,
    pub(super) inclusive_samples: Vec<u64>,
    /// Smallest stack position at which each function occurs (`usize::MAX`: none).
    pub(super) depth: Vec<usize>,
    pub(super) total_samples: u64,
    /// Non-zero call counts per render by id.
    pub(super) calls: Vec<Option<u64>>,
}

impl Tally {
    pub(super) fn new(input: &ProfileInput<'_>) -> Self {
        let (samples, calls) = (input.samples, input.calls);
        let mut all: BTreeSet<&str> = calls
            .iter()
            .filter(|&(_, &count)| count != 0)
            .map(|(name, _)| name.as_str())
            .collect();
        for stack in &samples.stacks {
            all.extend(stack.frames.iter().map(String::as_str));
        }
        let ids: HashMap<&str, usize> = all
            .iter()
            .enumerate()
            .map(|(id, &name)| (name, id))
            .collect();
        let count = all.len();
        let mut tally = Tally {
            names: all.iter().map(|&name| name.to_owned()).collect(),
            stacks: Vec::with_capacity(samples.stacks.len()),
            self_samples: vec![0; count],
            inclusive_samples: vec![0; count],
            depth: vec![usize::MAX; count],
            total_samples: 0,
            calls: all
                .iter()
                .map(|&name| calls.get(name).copied().filter(|&c| c != 0))
                .collect(),
        };
        // The stack that last counted each function, so that recursion counts once.
        let mut counted_in = vec![usize::MAX; count];
        for (stack_number, stack) in samples.stacks.iter().enumerate() {
            let frames: Vec<usize> = stack
                .frames
                .iter()
                .filter_map(|frame| ids.get(frame.as_str()).copied())
                .collect();
            let Some(&running) = frames.last() else {
                continue;
            };
            let weight = stack.count;
            tally.total_samples = tally.total_samples.saturating_add(weight);
            tally.self_samples[running] = tally.self_samples[running].saturating_add(weight);
            for (position, &function) in frames.iter().enumerate() {
                tally.depth[function] = tally.depth[function].min(position);
                if counted_in[function] != stack_number {
                    counted_in[function] = stack_number;
                    tally.inclusive_samples[function] =
                        tally.inclusive_samples[function].saturating_add(weight);
                }
            }
            tally.stacks.push((frames, weight));
        }
        tally
    }

    pub(super) fn children_samples(&self, function: usize) -> u64 {
        self.inclusive_samples[function].saturating_sub(self.self_samples[function])
    }
}

/// Percentage of `part` in `total` samples; 0 when there are none.
pub(super) fn percent_of(part: u64, total: u64) -> f64 {
    if total == 0 {
        0.0
    } else {
        100.0 * part as f64 / total as f64
    }
}
