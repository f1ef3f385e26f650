//! One sampling run as a value: [`Sampling::start`] picks the timer ([`super::timer`]),
//! starts pprof's profiler and our phase handler in front of it, then the timer;
//! [`Sampling::stop`] stops them in the reverse order and hands back pprof's raw report,
//! the phase counts and the CPU and wall time between. The closure-based runs of
//! [`super::sampler`] are built on it, and so is a start/stop caller such as criterion's
//! profiler hook.
//!
//! With the perf timer, pprof's own `setitimer(ITIMER_PROF)` is switched off right
//! after pprof starts it (pprof 0.15 has no way to start without it: a frequency of 0
//! divides by zero), so only the per-thread events send SIGPROF. pprof is started at
//! 1 Hz then, so its timer could not fire before it is switched off.

use std::time::{Duration, Instant};

use super::error::ProfileError;
use super::perf_clock::{ThreadClocks, period_ns};
use super::phase_handler::{BusyFlag, PhaseCounts, PhaseHandler};
use super::sample_options::SampleOptions;
use super::timer::{PERF_DEFAULT_FREQUENCY, SAMPLER_ENV, Timer, TimerChoice};

/// Libraries a signal handler must not unwind through (it can deadlock; pprof's advice).
pub const UNWIND_BLOCKLIST: [&str; 4] = ["libc", "libgcc", "pthread", "vdso"];

/// A sampling run under way. Dropped without [`Sampling::stop`] (an error or a panic
/// in the work), it stops the timer, puts pprof's handler back and stops pprof.
pub struct Sampling {
    // Dropped in this order: the timer first, then our handler, then pprof's profiler.
    clocks: Option<ThreadClocks>,
    handler: PhaseHandler,
    guard: pprof::ProfilerGuard<'static>,
    _busy: BusyFlag,
    timer: Timer,
    frequency: i32,
    cpu_start: Duration,
    start: Instant,
}

/// What a stopped run gives.
pub struct Stopped {
    /// pprof's stacks, unresolved names and all.
    pub report: pprof::Report,
    pub(crate) phases: PhaseCounts,
    pub timer: Timer,
    /// The rate asked, Hz of CPU time.
    pub frequency: i32,
    /// Wall time between start and stop.
    pub wall: Duration,
    /// Process CPU time (user + system, all threads) between start and stop.
    pub cpu: Duration,
}

impl Stopped {
    /// SIGPROF signals our handler saw.
    pub fn signals(&self) -> u64 {
        self.phases.signals
    }
}

impl Sampling {
    /// Starts sampling with `options`' timer choice (`None`: as [`SAMPLER_ENV`] says),
    /// rate (`None`: the timer's default) and probe; under perf, the calling thread and
    /// `options.threads` are sampled.
    pub fn start(options: &SampleOptions<'_>) -> Result<Self, ProfileError> {
        let busy = BusyFlag::take()?;
        let choice = match options.timer {
            Some(choice) => choice,
            None => TimerChoice::from_env().map_err(|e| ProfileError::Start(e.to_string()))?,
        };
        let clocks = match choice {
            TimerChoice::Setitimer => None,
            TimerChoice::Auto | TimerChoice::Perf => {
                let frequency = options.frequency.unwrap_or(PERF_DEFAULT_FREQUENCY);
                match ThreadClocks::open(period_ns(frequency), libc::SIGPROF, options.threads) {
                    Ok(clocks) => Some(clocks),
                    Err(e) if choice == TimerChoice::Perf => {
                        return Err(ProfileError::Start(format!(
                            "the perf timer was asked for ({SAMPLER_ENV}=perf or the caller) but {e}"
                        )));
                    }
                    // auto: the whole run on setitimer.
                    Err(_) => None,
                }
            }
        };
        let timer = if clocks.is_some() {
            Timer::PerfCpuClock
        } else {
            Timer::Setitimer
        };
        let frequency = options
            .frequency
            .unwrap_or_else(|| timer.default_frequency());
        let guard = pprof::ProfilerGuardBuilder::default()
            .frequency(if clocks.is_some() { 1 } else { frequency })
            .blocklist(&UNWIND_BLOCKLIST)
            .build()
            .map_err(|e| ProfileError::Start(e.to_string()))?;
        if clocks.is_some() {
            stop_itimer_prof()?;
        }
        let handler = PhaseHandler::install(options.probe)?;
        if let Some(clocks) = &clocks {
            clocks
                .enable()
                .map_err(|e| ProfileError::Start(e.to_string()))?;
        }
        Ok(Sampling {
            clocks,
            handler,
            guard,
            _busy: busy,
            timer,
            frequency,
            cpu_start: process_cpu_time(),
            start: Instant::now(),
        })
    }

    /// The timer this run uses.
    pub fn timer(&self) -> Timer {
        self.timer
    }

    /// The rate asked of it, Hz.
    pub fn frequency(&self) -> i32 {
        self.frequency
    }

    /// Threads with a perf event (`None` under setitimer, which samples the process).
    pub fn perf_threads(&self) -> Option<usize> {
        self.clocks.as_ref().map(ThreadClocks::threads)
    }

    /// Stops the timer, puts pprof's handler back, takes pprof's report, stops pprof.
    pub fn stop(self) -> Result<Stopped, ProfileError> {
        let Sampling {
            clocks,
            handler,
            guard,
            _busy,
            timer,
            frequency,
            cpu_start,
            start,
        } = self;
        if let Some(clocks) = &clocks {
            clocks.disable();
        }
        let wall = start.elapsed();
        let cpu = process_cpu_time().saturating_sub(cpu_start);
        let phases = handler.finish()?;
        let report = guard
            .report()
            .build()
            .map_err(|e| ProfileError::Report(e.to_string()))?;
        drop(guard);
        drop(clocks);
        Ok(Stopped {
            report,
            phases,
            timer,
            frequency,
            wall,
            cpu,
        })
    }
}

/// Switches the process's ITIMER_PROF off (pprof's, while the perf timer runs).
fn stop_itimer_prof() -> Result<(), ProfileError> {
    let off = libc::itimerval {
        it_interval: libc::timeval {
            tv_sec: 0,
            tv_usec: 0,
        },
        it_value: libc::timeval {
            tv_sec: 0,
            tv_usec: 0,
        },
    };
    // SAFETY: setitimer reads a complete itimerval; no old value is asked for.
    if unsafe { libc::setitimer(libc::ITIMER_PROF, &off, std::ptr::null_mut()) } != 0 {
        return Err(ProfileError::Start(format!(
            "cannot stop the setitimer timer: {}",
            std::io::Error::last_os_error()
        )));
    }
    Ok(())
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
