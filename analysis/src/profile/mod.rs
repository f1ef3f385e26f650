//! Profiles: call stacks sampled while a render runs, and what is made of them —
//! gprof's flat profile ([`flat`]) and call graph ([`gprof`]) with sampling errors
//! ([`share_interval`]), folded stacks and flamegraphs, Amdahl projections, exports
//! to pprof and speedscope ([`export`]). The sampler ([`sampler`], one run at a time
//! as a [`session`], its signals from the [`timer`] of [`perf_clock`] or setitimer)
//! produces [`StackSamples`], and so does a Linux perf recording of another program
//! ([`perf_data`], `rtprof record`); everything else reads it. GNU gprof's own output is
//! read into the same flat profile and call graph by [`gprof_import`]. The phases of
//! ray tracing of a program rtprof did not write come from name rules
//! ([`phase_rules`]) or from its probe, and the two are set side by side by
//! [`phase_compare`].

pub mod amdahl;
mod c_format;
mod error;
pub mod export;
pub mod flat;
pub mod folded;
pub mod gprof;
pub mod gprof_import;
#[cfg(any(test, feature = "gprof-text"))]
pub mod gprof_text;
pub mod names;
pub mod perf_clock;
pub mod perf_data;
pub mod phase_compare;
mod phase_handler;
pub mod phase_rules;
mod sample_options;
pub mod sampler;
pub mod session;
pub mod share_interval;
pub mod tally;
pub mod timer;

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One distinct call stack and how many samples landed on it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Stack {
    /// Function names, outermost caller first, the function that was running last.
    pub frames: Vec<String>,
    /// Samples taken with exactly this stack.
    pub count: u64,
}

/// Everything a sampling run produced.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StackSamples {
    pub stacks: Vec<Stack>,
    /// CPU seconds one sample stands for: measured CPU time / samples (not
    /// 1/frequency: the kernel caps the signal rate).
    pub seconds_per_sample: f64,
}

impl StackSamples {
    /// Total number of samples.
    pub fn total(&self) -> u64 {
        self.stacks.iter().map(|s| s.count).sum()
    }
}

/// Exact call counts by function name (the caller's: for rtprof, the tracer's counter
/// table, `tracer::Counts::function_calls`), for the `calls` columns; functions
/// without an entry have no count (blank, as in gprof).
pub type CallCounts = BTreeMap<String, u64>;

/// Where a flat profile's or call graph's figures come from: what their texts say
/// above the tables and what the call graph's arc counts are.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Origin {
    /// rtprof's sampler: stacks sampled, calls per render from the caller's counts.
    #[default]
    Sampled,
    /// GNU gprof's output ([`gprof_import`]): calls counted by a `-pg` build.
    Gprof,
    /// One run of another program, its stacks sampled by Linux perf (`rtprof record`,
    /// [`perf_data`]): no renders to count, no calls.
    Recorded,
}

impl Origin {
    /// Whether the call graph's arcs hold samples (not gprof's calls).
    pub fn sampled(self) -> bool {
        matches!(self, Origin::Sampled | Origin::Recorded)
    }
}
