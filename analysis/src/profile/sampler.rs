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
mod tests {
    use super::*;
    use std::cell::Cell;
    use std::hint::black_box;
    use std::sync::Mutex;

    /// One sampling run at a time per process: the tests that sample take turns
    /// (a concurrent one would get `ProfileError::Busy`).
    static SAMPLING: Mutex<()> = Mutex::new(());

    fn sampling_turn() -> std::sync::MutexGuard<'static, ()> {
        SAMPLING
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// CPU time of the calling thread (other tests run in parallel in this process).
    fn thread_cpu_time() -> Duration {
        let mut t = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: clock_gettime fills the timespec it is given.
        unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
        Duration::new(
            t.tv_sec.max(0) as u64,
            t.tv_nsec.clamp(0, 999_999_999) as u32,
        )
    }

    /// Spins for `$d` of this thread's CPU time on floating-point work whose result is
    /// returned (so it cannot be dropped). A macro, not a function: the loop must be
    /// the worker's own code for the samples' leaf frame to be the worker (an inlined
    /// helper would still show as its own frame through the debug info).
    macro_rules! burn {
        ($d:expr, $seed:expr) => {{
            let start = thread_cpu_time();
            let mut x: f64 = $seed;
            while thread_cpu_time().saturating_sub(start) < $d {
                for _ in 0..20_000 {
                    x = x * 1.000_000_1 + 1e-9;
                }
            }
            x
        }};
    }

    // The test workload's phase, read by `test_probe` (const-initialised: no lazy
    // set-up, so reading it in a signal handler is safe).
    thread_local! {
        static TEST_PHASE: Cell<u64> = const { Cell::new(0) };
    }

    fn test_probe() -> u64 {
        TEST_PHASE.with(Cell::get)
    }

    #[inline(never)]
    fn seventy_percent_worker(slice: Duration) -> f64 {
        TEST_PHASE.with(|p| p.set(1));
        let x = burn!(slice * 7, black_box(1.0));
        TEST_PHASE.with(|p| p.set(0));
        x
    }

    #[inline(never)]
    fn thirty_percent_worker(slice: Duration) -> f64 {
        TEST_PHASE.with(|p| p.set(2));
        let x = burn!(slice * 3, black_box(2.0));
        TEST_PHASE.with(|p| p.set(0));
        x
    }

    /// 70 % and 30 % of `total` CPU time in alternating slices of 7 : 3 ms, so a
    /// change of load on the shared machine during the test hits both alike.
    fn seventy_thirty(total: Duration) -> f64 {
        let slice = Duration::from_millis(1);
        let rounds = (total.as_millis() / 10).max(1);
        let mut sum = 0.0;
        for _ in 0..rounds {
            sum +=
                black_box(seventy_percent_worker(slice)) + black_box(thirty_percent_worker(slice));
        }
        sum
    }

    fn is_worker(name: &str) -> bool {
        name.contains("percent_worker")
    }

    /// Samples whose innermost frame is the function named by `needle`.
    fn leaf_hits(samples: &StackSamples, needle: &str) -> u64 {
        samples
            .stacks
            .iter()
            .filter(|s| s.frames.last().is_some_and(|f| f.contains(needle)))
            .map(|s| s.count)
            .sum()
    }

    /// `seventy` : `thirty` is 70 : 30 within ten points (over the two only: other
    /// tests share the process and its SIGPROF signals).
    fn assert_seventy_thirty(seventy: u64, thirty: u64, view: &str) {
        let workload = seventy + thirty;
        assert!(workload >= 100, "{view}: too few samples: {workload}");
        let share = seventy as f64 / workload as f64;
        assert!(
            (share - 0.7).abs() <= 0.10,
            "{view}: the 70 % worker got {share:.3} ({seventy} of {workload})"
        );
    }

    const WORKLOAD: Duration = Duration::from_millis(1000);

    #[test]
    fn a_known_seventy_thirty_split_is_attributed_within_ten_points() {
        let _turn = sampling_turn();
        let run =
            sample(1000, is_worker, || seventy_thirty(WORKLOAD)).unwrap_or_else(|e| panic!("{e}"));
        assert_seventy_thirty(
            leaf_hits(&run.samples, "seventy_percent"),
            leaf_hits(&run.samples, "thirty_percent"),
            "native",
        );
        // CPU seconds per sample: the samples add up to the measured CPU time.
        let accounted = run.samples.total() as f64 * run.samples.seconds_per_sample;
        assert!((accounted - run.cpu.as_secs_f64()).abs() < 1e-9);
        assert!(run.cpu >= WORKLOAD, "{:?}", run.cpu);
        // Self time: the leaf frame of the workload's samples is the worker itself.
        assert!(run.samples.stacks.iter().all(|s| !s.frames.is_empty()));
        // No probe, no phase view; signals were still counted, and each became at
        // most one native sample.
        assert!(run.phase_keys.is_empty());
        assert!(
            run.signals >= run.samples.total(),
            "{} signals, {} samples",
            run.signals,
            run.samples.total()
        );
        let asked = (1000.0 * run.cpu.as_secs_f64()).round() as u64;
        assert_eq!(run.samples_asked, asked);
    }

    #[test]
    fn the_phase_probe_attributes_the_same_split_from_the_same_signals() {
        let _turn = sampling_turn();
        let options = SampleOptions {
            probe: Some(test_probe),
            ..SampleOptions::new(1000)
        };
        let run = sample_with(&options, is_worker, |_| seventy_thirty(WORKLOAD))
            .unwrap_or_else(|e| panic!("{e}"));
        let phase = |key: u64| run.phase_keys.get(&key).copied().unwrap_or(0);
        eprintln!(
            "phase keys {:?}; native: 70 % worker {}, 30 % worker {}, {} samples of {} signals, {} asked, {:?} CPU",
            run.phase_keys,
            leaf_hits(&run.samples, "seventy_percent"),
            leaf_hits(&run.samples, "thirty_percent"),
            run.samples.total(),
            run.signals,
            run.samples_asked,
            run.cpu
        );
        assert_seventy_thirty(phase(1), phase(2), "phase");
        // Every signal recorded exactly one key (0 for threads outside the workload).
        assert_eq!(run.phase_keys_dropped, 0);
        assert_eq!(run.phase_keys.values().sum::<u64>(), run.signals);
        assert!(
            run.phase_keys.keys().all(|k| [0, 1, 2].contains(k)),
            "{:?}",
            run.phase_keys
        );
        // pprof's handler still ran on the same signals: native stacks were taken,
        // attribute the same split, and carry no frame of the signal handlers.
        assert_seventy_thirty(
            leaf_hits(&run.samples, "seventy_percent"),
            leaf_hits(&run.samples, "thirty_percent"),
            "native beside the phases",
        );
        assert!(run.signals >= run.samples.total());
        for stack in &run.samples.stacks {
            for frame in &stack.frames {
                assert!(
                    !SIGNAL_FRAMES.iter().any(|s| frame.contains(s)),
                    "signal frame in {:?}",
                    stack.frames
                );
            }
        }
    }

    #[test]
    fn repeated_work_runs_until_the_minimum_sample_count() {
        let _turn = sampling_turn();
        let options = SampleOptions {
            min_samples: 40,
            ..SampleOptions::new(1000)
        };
        // 5 ms of CPU a run: 40 samples take several runs at any rate the kernel gives.
        let mut runs_seen = 0u64;
        let run = sample_repeated(&options, is_worker, || {
            runs_seen += 1;
            black_box(seventy_thirty(Duration::from_millis(5)));
            Ok::<(), std::fmt::Error>(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(run.output.stop, Stop::EnoughSamples);
        assert_eq!(run.output.runs, runs_seen);
        assert!(run.output.runs > 1, "{:?}", run.output);
        assert!(run.signals >= 40, "{}", run.signals);
    }

    #[test]
    fn repeats_stop_at_the_run_cap_and_at_the_first_failure() {
        let _turn = sampling_turn();
        let capped = SampleOptions {
            min_samples: u64::MAX,
            max_runs: 3,
            ..SampleOptions::new(1000)
        };
        let mut runs_seen = 0u64;
        let run = sample_repeated(&capped, is_worker, || {
            runs_seen += 1;
            black_box(seventy_thirty(Duration::from_millis(20)));
            Ok::<(), std::fmt::Error>(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            run.output,
            Repeats {
                runs: 3,
                stop: Stop::MaxRuns
            }
        );
        assert_eq!(runs_seen, 3);

        let mut runs_seen = 0u64;
        let failed = sample_repeated(&capped, is_worker, || {
            runs_seen += 1;
            if runs_seen == 2 {
                Err("broken scene")
            } else {
                Ok(())
            }
        });
        match failed {
            Err(RepeatedError::Work {
                run: 2,
                error: "broken scene",
            }) => {}
            other => panic!("expected the second run's error, got {other:?}"),
        }
    }

    #[test]
    fn a_second_concurrent_run_is_refused_and_the_first_still_completes() {
        let _turn = sampling_turn();
        let run = sample(1000, is_worker, || {
            let inner = sample(1000, is_worker, || ());
            black_box(seventy_thirty(Duration::from_millis(50)));
            inner.map(|_| ())
        })
        .unwrap_or_else(|e| panic!("{e}"));
        assert!(
            matches!(run.output, Err(ProfileError::Busy)),
            "{:?}",
            run.output
        );
        // The flag is released: the next run starts.
        assert!(
            sample(1000, is_worker, || seventy_thirty(Duration::from_millis(
                50
            )))
            .is_ok()
        );
    }

    #[test]
    fn repeated_names_collapse() {
        let v = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        assert_eq!(
            collapse_repeats(v(&["a", "a", "b", "a"])),
            v(&["a", "b", "a"])
        );
    }
}
