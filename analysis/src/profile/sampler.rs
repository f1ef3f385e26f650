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
use super::perf_clock::WorkThreads;
use super::session::Sampling;
use super::timer::{Timer, TimerChoice};
use super::{Stack, StackSamples};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// The one frame of samples that caught no profiled code.
pub const SCHEDULER_FRAME: &str = "[scheduler and idle]";

/// Why a profile could not be taken.
#[derive(Debug, thiserror::Error)]
pub enum ProfileError {
    #[error("cannot start the sampling profiler: {0}")]
    Start(String),
    #[error("cannot build the profile report: {0}")]
    Report(String),
    #[error(
        "no samples were taken: the profiled work ran for only {0:?}; give it more work (e.g. a larger --size)"
    )]
    NoSamples(Duration),
    #[error("another sampling run is under way in this process (one at a time)")]
    Busy,
}

/// Why a repeated sampling run failed: the profiler, or one run of the work.
#[derive(Debug, thiserror::Error)]
pub enum RepeatedError<E> {
    #[error(transparent)]
    Profile(ProfileError),
    #[error("run {run} of the sampled work failed: {error}")]
    Work { run: u64, error: E },
}

/// Read in the SIGPROF handler on the interrupted thread: a key for what that thread
/// is doing (for rtprof, `tracer::phase_stack_key`: its phase stack, 0 = none). Must
/// be async-signal-safe: no allocation, no lock, no lazily initialised thread-local.
pub type PhaseProbe = fn() -> u64;

/// Least samples a profile gathers by default ([`sample_repeated`] repeats the work
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
    /// ([`Timer::default_frequency`]).
    pub frequency: Option<i32>,
    /// Which timer; `None`: as `RTPROF_SAMPLER` says (auto when unset).
    pub timer: Option<TimerChoice>,
    /// The threads besides the calling one that run the work: each gets its own perf
    /// event. `None`: the work runs on the calling thread (setitimer samples the whole
    /// process either way).
    pub threads: Option<WorkThreads<'a>>,
    /// Repeat until at least this many signals were seen ([`sample_repeated`]).
    pub min_samples: u64,
    /// ... but at most this many runs,
    pub max_runs: u64,
    /// ... and no more runs once this much wall time has passed.
    pub max_wall: Duration,
    /// Read at each signal for [`SampledRun::phase_keys`]; `None`: no phase view.
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

/// The sampling run as it goes, for work that decides itself when it has done enough.
pub struct LiveSamples {
    _private: (),
}

impl LiveSamples {
    /// SIGPROF signals seen so far in this run (each is one native sample unless
    /// pprof dropped it, e.g. in a blocklisted library, and one phase sample).
    pub fn signals(&self) -> u64 {
        SIGNALS.load(Ordering::Relaxed)
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

/// The process's resource use so far, if the kernel tells.
fn own_usage() -> Option<libc::rusage> {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::uninit();
    // SAFETY: getrusage writes a complete `rusage` into the pointer on success.
    let ok = unsafe { libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr()) } == 0;
    // SAFETY: initialised by the successful call above.
    ok.then(|| unsafe { usage.assume_init() })
}

/// CPU time of the whole process so far (all threads, user + system).
pub fn process_cpu_time() -> Duration {
    let Some(usage) = own_usage() else {
        return Duration::ZERO;
    };
    let time = |t: libc::timeval| {
        Duration::from_secs(t.tv_sec.max(0) as u64) + Duration::from_micros(t.tv_usec.max(0) as u64)
    };
    time(usage.ru_utime) + time(usage.ru_stime)
}

/// The most memory the process has held resident so far, bytes (Linux reports the
/// maximum resident set size in KiB); `None` where the kernel does not say.
pub fn process_peak_resident_bytes() -> Option<u64> {
    let kib = own_usage()?.ru_maxrss;
    (kib > 0).then(|| kib as u64 * 1024)
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
pub fn sample_repeated<E>(
    options: &SampleOptions,
    is_profiled: impl Fn(&str) -> bool,
    mut run_once: impl FnMut() -> Result<(), E>,
) -> Result<SampledRun<Repeats>, RepeatedError<E>> {
    let run = sample_unchecked(options, is_profiled, |live| {
        let start = Instant::now();
        let mut runs = 0u64;
        loop {
            runs += 1;
            run_once().map_err(|error| (runs, error))?;
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

/// Held while a sampling run is under way; released on drop (also on a panic).
pub(super) struct BusyFlag;

static BUSY: AtomicBool = AtomicBool::new(false);

impl BusyFlag {
    pub(super) fn take() -> Result<Self, ProfileError> {
        BUSY.compare_exchange(false, true, Ordering::AcqRel, Ordering::Acquire)
            .map(|_| BusyFlag)
            .map_err(|_| ProfileError::Busy)
    }
}

impl Drop for BusyFlag {
    fn drop(&mut self) {
        BUSY.store(false, Ordering::Release);
    }
}

// The signal handler's state. Statics, because a signal handler has no other way in;
// written only while no handler of ours is installed or recording (see
// `PhaseHandler`), read in the handler with atomics only.

/// Slots of the phase-key table (a power of two). Keys are phase stacks (4 bits a
/// level), so a render has tens of distinct keys, not thousands.
const KEY_SLOTS: usize = 1 << KEY_SLOT_BITS;
const KEY_SLOT_BITS: u32 = 10;
/// Open addressing: a slot's key (0 = free), claimed by compare-and-swap.
static KEYS: [AtomicU64; KEY_SLOTS] = [const { AtomicU64::new(0) }; KEY_SLOTS];
static KEY_COUNTS: [AtomicU64; KEY_SLOTS] = [const { AtomicU64::new(0) }; KEY_SLOTS];
/// Samples whose key was 0 (outside any phase): 0 cannot be a table key.
static OUTSIDE_COUNT: AtomicU64 = AtomicU64::new(0);
/// Samples whose key found no free slot.
static DROPPED: AtomicU64 = AtomicU64::new(0);
/// Signals seen while recording.
static SIGNALS: AtomicU64 = AtomicU64::new(0);
/// The probe (a `PhaseProbe` as an address), 0 = none.
static PROBE: AtomicUsize = AtomicUsize::new(0);
/// Whether the handler records (cleared before the table is read).
static RECORDING: AtomicBool = AtomicBool::new(false);
/// Handlers of ours running now (the table is read only once this is 0).
static IN_HANDLER: AtomicUsize = AtomicUsize::new(0);
/// The handler ours replaced (pprof's): its address and whether it takes siginfo.
static PREVIOUS_HANDLER: AtomicUsize = AtomicUsize::new(0);
static PREVIOUS_SIGINFO: AtomicBool = AtomicBool::new(false);

/// What the phase handler recorded over one run.
pub(crate) struct PhaseCounts {
    pub(crate) keys: BTreeMap<u64, u64>,
    pub(crate) dropped: u64,
    pub(crate) signals: u64,
}

/// Our SIGPROF handler, installed over pprof's for the run; puts pprof's back on
/// `finish` or drop.
pub(super) struct PhaseHandler {
    /// pprof's action, restored as it was.
    previous: libc::sigaction,
    restored: bool,
}

impl PhaseHandler {
    pub(super) fn install(probe: Option<PhaseProbe>) -> Result<Self, ProfileError> {
        for (key, count) in KEYS.iter().zip(&KEY_COUNTS) {
            key.store(0, Ordering::Relaxed);
            count.store(0, Ordering::Relaxed);
        }
        OUTSIDE_COUNT.store(0, Ordering::Relaxed);
        DROPPED.store(0, Ordering::Relaxed);
        SIGNALS.store(0, Ordering::Relaxed);
        PROBE.store(probe.map_or(0, |p| p as usize), Ordering::Relaxed);
        // SAFETY: all-zero is a valid `sigaction` (no handler, empty mask, no flags).
        let mut previous: libc::sigaction = unsafe { std::mem::zeroed() };
        // SAFETY: a null new action only reads the current one into `previous`.
        if unsafe { libc::sigaction(libc::SIGPROF, std::ptr::null(), &mut previous) } != 0 {
            return Err(ProfileError::Start(format!(
                "cannot read the SIGPROF action: {}",
                std::io::Error::last_os_error()
            )));
        }
        // Stored before ours is installed, so its first signal already chains.
        PREVIOUS_HANDLER.store(previous.sa_sigaction, Ordering::SeqCst);
        PREVIOUS_SIGINFO.store(previous.sa_flags & libc::SA_SIGINFO != 0, Ordering::SeqCst);
        RECORDING.store(true, Ordering::SeqCst);
        // SAFETY: as above.
        let mut ours: libc::sigaction = unsafe { std::mem::zeroed() };
        ours.sa_sigaction = on_sigprof as *const () as usize;
        ours.sa_flags = libc::SA_SIGINFO | libc::SA_RESTART;
        // SAFETY: `ours` is a complete action whose handler has the 3-argument
        // signature SA_SIGINFO calls for; the mask is emptied in place.
        let installed = unsafe {
            libc::sigemptyset(&mut ours.sa_mask);
            libc::sigaction(libc::SIGPROF, &ours, std::ptr::null_mut())
        } == 0;
        if !installed {
            RECORDING.store(false, Ordering::SeqCst);
            return Err(ProfileError::Start(format!(
                "cannot install the phase handler: {}",
                std::io::Error::last_os_error()
            )));
        }
        Ok(PhaseHandler {
            previous,
            restored: false,
        })
    }

    /// Stops recording, waits out handlers still running, puts pprof's handler back
    /// and reads the table.
    pub(super) fn finish(mut self) -> Result<PhaseCounts, ProfileError> {
        self.restore()?;
        let mut keys = BTreeMap::new();
        for (key, count) in KEYS.iter().zip(&KEY_COUNTS) {
            let key = key.load(Ordering::Acquire);
            if key != 0 {
                *keys.entry(key).or_default() += count.load(Ordering::Acquire);
            }
        }
        let with_probe = PROBE.load(Ordering::Relaxed) != 0;
        let outside = OUTSIDE_COUNT.load(Ordering::Acquire);
        if with_probe && outside > 0 {
            keys.insert(0, outside);
        }
        Ok(PhaseCounts {
            keys,
            dropped: DROPPED.load(Ordering::Acquire),
            signals: SIGNALS.load(Ordering::Acquire),
        })
    }

    fn restore(&mut self) -> Result<(), ProfileError> {
        if self.restored {
            return Ok(());
        }
        self.restored = true;
        // A handler that starts after this sees RECORDING false and only chains; one
        // that started before has counted itself in IN_HANDLER (both SeqCst), so
        // once IN_HANDLER is 0 nothing writes the table any more.
        RECORDING.store(false, Ordering::SeqCst);
        while IN_HANDLER.load(Ordering::SeqCst) != 0 {
            std::hint::spin_loop();
        }
        // SAFETY: `previous` is the action read from the kernel at install.
        if unsafe { libc::sigaction(libc::SIGPROF, &self.previous, std::ptr::null_mut()) } != 0 {
            return Err(ProfileError::Report(format!(
                "cannot restore the profiler's SIGPROF handler: {}",
                std::io::Error::last_os_error()
            )));
        }
        Ok(())
    }
}

impl Drop for PhaseHandler {
    fn drop(&mut self) {
        // On the error and panic paths; `finish` has restored already otherwise.
        let _ = self.restore();
    }
}

/// The SIGPROF handler: count the signal, record the probe's key, call pprof's
/// handler (which takes the native stack). Async-signal-safe: atomics only, no
/// allocation, no lock; the probe must be async-signal-safe too.
extern "C" fn on_sigprof(
    signal: libc::c_int,
    info: *mut libc::siginfo_t,
    context: *mut libc::c_void,
) {
    IN_HANDLER.fetch_add(1, Ordering::SeqCst);
    if RECORDING.load(Ordering::SeqCst) {
        SIGNALS.fetch_add(1, Ordering::Relaxed);
        let probe = PROBE.load(Ordering::Relaxed);
        if probe != 0 {
            // SAFETY: PROBE holds a `PhaseProbe` stored as its address.
            let probe = unsafe { std::mem::transmute::<usize, PhaseProbe>(probe) };
            record_key(probe());
        }
    }
    let previous = PREVIOUS_HANDLER.load(Ordering::SeqCst);
    if previous != libc::SIG_DFL && previous != libc::SIG_IGN {
        if PREVIOUS_SIGINFO.load(Ordering::SeqCst) {
            type Action = extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void);
            // SAFETY: the kernel action had SA_SIGINFO, so its handler has this type.
            let action = unsafe { std::mem::transmute::<usize, Action>(previous) };
            action(signal, info, context);
        } else {
            type Handler = extern "C" fn(libc::c_int);
            // SAFETY: without SA_SIGINFO a handler takes the signal number only.
            let handler = unsafe { std::mem::transmute::<usize, Handler>(previous) };
            handler(signal);
        }
    }
    IN_HANDLER.fetch_sub(1, Ordering::SeqCst);
}

/// Counts one sample of `key` in the lock-free table (called from the handler).
fn record_key(key: u64) {
    if key == 0 {
        OUTSIDE_COUNT.fetch_add(1, Ordering::Relaxed);
        return;
    }
    // Fibonacci hashing: the top bits of key x 2^64/phi.
    let home = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - KEY_SLOT_BITS)) as usize;
    for step in 0..KEY_SLOTS {
        let slot = (home + step) & (KEY_SLOTS - 1);
        let current = KEYS[slot].load(Ordering::Acquire);
        let ours = current == key
            || (current == 0
                && match KEYS[slot].compare_exchange(0, key, Ordering::AcqRel, Ordering::Acquire) {
                    Ok(_) => true,
                    Err(claimed) => claimed == key,
                });
        if ours {
            KEY_COUNTS[slot].fetch_add(1, Ordering::Relaxed);
            return;
        }
    }
    DROPPED.fetch_add(1, Ordering::Relaxed);
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
