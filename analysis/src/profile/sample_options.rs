//! How to sample: the rate, the timer, the threads, how long to repeat, and the phase
//! probe read in the signal handler.

use super::perf_clock::WorkThreads;
use super::timer::TimerChoice;
use std::time::Duration;

/// Read in the SIGPROF handler on the interrupted thread: a key for what that thread
/// is doing (for rtprof, `tracer::phase_stack_key`: its phase stack, 0 = none). Must
/// be async-signal-safe: no allocation, no lock, no lazily initialised thread-local.
pub type PhaseProbe = fn() -> u64;

/// Least samples a profile gathers by default ([`sample_repeated`](super::sampler::sample_repeated) repeats the work
/// until the signals reach it).
pub const DEFAULT_MIN_SAMPLES: u64 = 1000;
/// Most runs of the work per profile by default, however fast it is.
pub const DEFAULT_MAX_RUNS: u64 = 10_000;
/// Longest a profile keeps repeating by default (a slow or starved machine still
/// ends, with fewer samples than asked).
pub const DEFAULT_MAX_WALL: Duration = Duration::from_secs(120);

/// How to sample.
#[derive(Clone, Copy, Debug)]
pub struct SampleOptions<'a> {
    /// Sampling rate asked of the timer, Hz of CPU time; `None`: the timer's default
    /// ([`Timer::default_frequency`](super::timer::Timer::default_frequency)).
    pub frequency: Option<i32>,
    /// Which timer; `None`: as `RTPROF_SAMPLER` says (auto when unset).
    pub timer: Option<TimerChoice>,
    /// The threads besides the calling one that run the work: each gets its own perf
    /// event. `None`: the work runs on the calling thread (setitimer samples the whole
    /// process either way).
    pub threads: Option<WorkThreads<'a>>,
    /// Repeat until at least this many signals were seen ([`sample_repeated`](super::sampler::sample_repeated)).
    pub min_samples: u64,
    /// ... but at most this many runs,
    pub max_runs: u64,
    /// ... and no more runs once this much wall time has passed.
    pub max_wall: Duration,
    /// Read at each signal for [`SampledRun::phase_keys`](super::sampler::SampledRun::phase_keys); `None`: no phase view.
    pub probe: Option<PhaseProbe>,
}

impl SampleOptions<'_> {
    /// `frequency` Hz, the default minimum and caps, no probe.
    pub fn new(frequency: i32) -> Self {
        SampleOptions {
            frequency: Some(frequency),
            ..SampleOptions::timer_default()
        }
    }

    /// The timer's own default rate, the default minimum and caps, no probe.
    pub fn timer_default() -> Self {
        SampleOptions {
            frequency: None,
            timer: None,
            threads: None,
            min_samples: DEFAULT_MIN_SAMPLES,
            max_runs: DEFAULT_MAX_RUNS,
            max_wall: DEFAULT_MAX_WALL,
            probe: None,
        }
    }
}
