//! The sampling profiler: SIGPROF at a chosen rate while the profiled work runs, from
//! per-thread perf cpu-clock events or pprof's setitimer ([`super::timer`]),
//! stacks resolved with the binary's debug info (so inlined functions keep their own
//! frames), cleaned into [`StackSamples`]; and, from the same signals, the phase the
//! interrupted thread was in (a [`PhaseProbe`]), so that attribution need not depend on
//! what the optimizer inlined.
//!
//! - Only the work is sampled: the profiler starts right before it and the report
//!   is taken right after, so parsing and start-up do not show.
//! - Seconds per sample = process CPU time spent in the work / samples taken. setitimer
//!   delivers fewer signals than asked for at high rates (the kernel's tick), so
//!   1/frequency would misstate every time in the profile; [`SampledRun::samples_asked`]
//!   keeps what was asked and [`SampledRun::timer`] which timer ran, so a report can
//!   state both.
//! - Frames above the outermost frame of the profiled code (thread start, rayon's
//!   scheduler, `main`) are dropped, and so are foreign frames between profiled ones
//!   (rayon's joins). Below the innermost profiled frame, foreign Rust frames (inlined
//!   iterator and intrinsic helpers) fold into it; C functions it calls (`powf`) stay.
//!   Samples without any profiled frame (idle workers stealing work) are kept as one
//!   stack, [`SCHEDULER_FRAME`].
//! - Phases: pprof installs its SIGPROF handler; ours replaces it for the run, reads
//!   the probe into a fixed lock-free table (no allocation, no lock: async-signal-safe),
//!   then calls pprof's, so every signal gives both a phase key and a native stack.
//! - One sampling run at a time per process (the signal handler and pprof's profiler
//!   are process-wide): a second concurrent run gets [`ProfileError::Busy`].

use super::names::clean_symbol;
use super::session::Sampling;
use super::timer::Timer;
use super::{Stack, StackSamples};
use std::collections::BTreeMap;
use std::time::{Duration, Instant};

// The sampler's inputs and errors, where callers have always found them.
pub use super::error::{ProfileError, RepeatedError};
pub use super::sample_options::{
    DEFAULT_MAX_RUNS, DEFAULT_MAX_WALL, DEFAULT_MIN_SAMPLES, PhaseProbe, SampleOptions,
};
pub use super::session::{process_cpu_time, process_peak_resident_bytes};

/// The one frame of samples that caught no profiled code.
pub const SCHEDULER_FRAME: &str = "[scheduler and idle]";

/// The sampling run as it goes, for work that decides itself when it has done enough.
pub struct LiveSamples {
    _private: (),
}

impl LiveSamples {
    /// SIGPROF signals seen so far in this run (each is one native sample unless
    /// pprof dropped it, e.g. in a blocklisted library, and one phase sample).
    pub fn signals(&self) -> u64 {
        super::phase_handler::signals_so_far()
    }
}

/// How often [`sample_repeated`] ran the work and why it stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Repeats {
    pub runs: u64,
    pub stop: Stop,
}

/// Why the repeats stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// `min_samples` signals were seen.
    EnoughSamples,
    /// `max_runs` runs were made first.
    MaxRuns,
    /// `max_wall` passed first.
    MaxWall,
}

/// What one sampling run measured.
#[derive(Clone, Debug)]
pub struct SampledRun<T> {
    /// The closure's result.
    pub output: T,
    /// Native stacks (symbol names from the debug info).
    pub samples: StackSamples,
    /// Phase key (what the probe returned; 0 = outside any phase) -> signals that
    /// read it. Empty without a probe. With one, the counts plus
    /// `phase_keys_dropped` add up to `signals`.
    pub phase_keys: BTreeMap<u64, u64>,
    /// Signals whose key found no room in the handler's fixed table (0 in practice).
    pub phase_keys_dropped: u64,
    /// SIGPROF signals our handler saw during the work. The native samples can be
    /// a few fewer (pprof skips signals that land in blocklisted libraries).
    pub signals: u64,
    /// Samples asked for: frequency x CPU seconds, rounded. Taken / asked shows how
    /// far the timer fell short of the rate.
    pub samples_asked: u64,
    /// The timer that sent the signals.
    pub timer: Timer,
    /// The rate asked of it, Hz of CPU time.
    pub frequency: i32,
    /// Wall time of the closure.
    pub wall: Duration,
    /// Process CPU time (user + system, all threads) during the closure.
    pub cpu: Duration,
}

impl<T> SampledRun<T> {
    /// Signals per CPU second of the work: the rate the timer delivered.
    pub fn effective_rate(&self) -> f64 {
        effective_rate(self.signals, self.cpu.as_secs_f64())
    }
}

/// Samples per CPU second (0 for no CPU time).
pub fn effective_rate(samples: u64, cpu_seconds: f64) -> f64 {
    if cpu_seconds > 0.0 {
        samples as f64 / cpu_seconds
    } else {
        0.0
    }
}

/// Runs `work` once under the sampling profiler at `frequency` Hz, without a phase
/// probe. `is_profiled` tells, for a cleaned function name, whether it belongs to the
/// profiled code (e.g. starts with `tracer::`); it decides which frames are scheduler
/// frames.
pub fn sample<T>(
    frequency: i32,
    is_profiled: impl Fn(&str) -> bool,
    work: impl FnOnce() -> T,
) -> Result<SampledRun<T>, ProfileError> {
    let options = SampleOptions {
        min_samples: 0,
        ..SampleOptions::new(frequency)
    };
    sample_with(&options, is_profiled, |_| work())
}

/// Runs `run_once` under the sampling profiler again and again until enough is
/// sampled: at least once, then until the signals seen reach `options.min_samples`,
/// or `options.max_runs` runs were made, or `options.max_wall` has passed (whichever
/// comes first; [`Repeats::stop`] says which). Every run is sampled, so a profile of
/// `runs` renders stands for all of them: divide counts of work by `runs` for
/// per-render figures. The first failing run ends the profile with its error.
/// `run_once` is given the live count of signals (for a progress display: the
/// fraction of `min_samples` gathered, read during a run too).
pub fn sample_repeated<E>(
    options: &SampleOptions,
    is_profiled: impl Fn(&str) -> bool,
    mut run_once: impl FnMut(&LiveSamples) -> Result<(), E>,
) -> Result<SampledRun<Repeats>, RepeatedError<E>> {
    let run = sample_unchecked(options, is_profiled, |live| {
        let start = Instant::now();
        let mut runs = 0u64;
        loop {
            runs += 1;
            run_once(live).map_err(|error| (runs, error))?;
            let stop = if live.signals() >= options.min_samples {
                Some(Stop::EnoughSamples)
            } else if runs >= options.max_runs {
                Some(Stop::MaxRuns)
            } else if start.elapsed() >= options.max_wall {
                Some(Stop::MaxWall)
            } else {
                None
            };
            if let Some(stop) = stop {
                return Ok(Repeats { runs, stop });
            }
        }
    })
    .map_err(RepeatedError::Profile)?;
    // A failing run says so first: the few samples it left do not matter.
    let run = match run.output {
        Ok(repeats) => SampledRun {
            output: repeats,
            samples: run.samples,
            phase_keys: run.phase_keys,
            phase_keys_dropped: run.phase_keys_dropped,
            signals: run.signals,
            samples_asked: run.samples_asked,
            timer: run.timer,
            frequency: run.frequency,
            wall: run.wall,
            cpu: run.cpu,
        },
        Err((run, error)) => return Err(RepeatedError::Work { run, error }),
    };
    with_samples(run).map_err(RepeatedError::Profile)
}

/// Runs `work` once under the sampling profiler with `options` (frequency and phase
/// probe; `min_samples` and the caps are for `work` to read, through the
/// [`LiveSamples`] it is given, as [`sample_repeated`] does).
pub fn sample_with<T>(
    options: &SampleOptions,
    is_profiled: impl Fn(&str) -> bool,
    work: impl FnOnce(&LiveSamples) -> T,
) -> Result<SampledRun<T>, ProfileError> {
    with_samples(sample_unchecked(options, is_profiled, work)?)
}

/// The run, or [`ProfileError::NoSamples`] if it has no native sample.
fn with_samples<T>(run: SampledRun<T>) -> Result<SampledRun<T>, ProfileError> {
    if run.samples.total() == 0 {
        return Err(ProfileError::NoSamples(run.wall));
    }
    Ok(run)
}

/// [`sample_with`], also when no sample was taken (seconds per sample 0 then).
fn sample_unchecked<T>(
    options: &SampleOptions,
    is_profiled: impl Fn(&str) -> bool,
    work: impl FnOnce(&LiveSamples) -> T,
) -> Result<SampledRun<T>, ProfileError> {
    let sampling = Sampling::start(options)?;
    let output = work(&LiveSamples { _private: () });
    let stopped = sampling.stop()?;
    let (cpu, wall) = (stopped.cpu, stopped.wall);
    let report = &stopped.report;
    let phases = stopped.phases;
    let merged = clean_stacks(report, is_profiled);
    let total: u64 = merged.values().sum();
    Ok(SampledRun {
        output,
        samples: StackSamples {
            stacks: merged
                .into_iter()
                .map(|(frames, count)| Stack { frames, count })
                .collect(),
            seconds_per_sample: if total == 0 {
                0.0
            } else {
                cpu.as_secs_f64() / total as f64
            },
        },
        phase_keys: phases.keys,
        phase_keys_dropped: phases.dropped,
        signals: phases.signals,
        samples_asked: (f64::from(stopped.frequency.max(0)) * cpu.as_secs_f64()).round() as u64,
        timer: stopped.timer,
        frequency: stopped.frequency,
        wall,
        cpu,
    })
}

/// The report's stacks, cleaned (see the module doc) and merged.
fn clean_stacks(
    report: &pprof::Report,
    is_profiled: impl Fn(&str) -> bool,
) -> BTreeMap<Vec<String>, u64> {
    let mut merged: BTreeMap<Vec<String>, u64> = BTreeMap::new();
    for (frames, &count) in &report.data {
        let names = root_first_names(frames);
        let stack = match (
            names.iter().position(|n| is_profiled(n)),
            names.iter().rposition(|n| is_profiled(n)),
        ) {
            (Some(first), Some(last)) => {
                // Between the outermost and innermost profiled frames, foreign frames
                // are scheduling glue (rayon's bridges and joins). Below the innermost,
                // foreign Rust frames (paths with `::`: core iterators, glam's SIMD
                // intrinsics) are code inlined into the profiled function and count as
                // its own; C functions (no path: libm's `powf`, `memcpy`) are real
                // calls and keep their frames.
                let kept = names[first..]
                    .iter()
                    .enumerate()
                    .filter(|&(i, n)| is_profiled(n) || (first + i > last && !n.contains("::")))
                    .map(|(_, n)| n.clone())
                    .collect();
                collapse_repeats(kept)
            }
            _ => vec![SCHEDULER_FRAME.to_string()],
        };
        *merged.entry(stack).or_default() += count.max(0) as u64;
    }
    merged
}

/// Drops a frame that repeats its caller's name: a function split by the compiler
/// (a closure or an outlined part resolving to the same name) is one function.
fn collapse_repeats(mut frames: Vec<String>) -> Vec<String> {
    frames.dedup();
    frames
}

/// Frames of signal delivery: the kernel's return trampoline, then the handlers. pprof
/// drops its own handler's frame and the one after it, which, with ours chained in
/// front, is ours, not the trampoline.
const SIGNAL_FRAMES: [&str; 2] = ["__restore_rt", "on_sigprof"];

/// The cleaned symbol names of one sampled stack, root first. pprof lists frames
/// innermost first, and the symbols of one frame (inlined functions first) innermost
/// first too: both are reversed. Frames from the signal trampoline inwards are the
/// signal's, not the interrupted code's, and are cut.
pub fn root_first_names(frames: &pprof::Frames) -> Vec<String> {
    let mut names: Vec<String> = frames
        .frames
        .iter()
        .rev()
        .flat_map(|frame| {
            frame
                .iter()
                .rev()
                .map(|symbol| clean_symbol(&symbol.name()))
        })
        .collect();
    if let Some(signal) = names.iter().position(|n| is_signal_frame(n)) {
        names.truncate(signal);
    }
    names
}

fn is_signal_frame(name: &str) -> bool {
    SIGNAL_FRAMES.iter().any(|s| {
        name.strip_suffix(s)
            .is_some_and(|path| path.is_empty() || path.ends_with("::"))
    })
}

#[cfg(test)]
mod tests;
