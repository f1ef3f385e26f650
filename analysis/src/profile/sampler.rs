//! The sampling profiler: SIGPROF at a chosen rate (pprof) while one closure runs,
//! stacks resolved with the binary's debug info (so inlined functions keep their own
//! frames), cleaned into [`StackSamples`].
//!
//! - Only the closure is sampled: the profiler starts right before it and the report
//!   is taken right after, so parsing and start-up do not show.
//! - Seconds per sample = process CPU time spent in the closure / samples taken. The
//!   kernel delivers fewer signals than asked for at high rates, so 1/frequency would
//!   misstate every time in the profile.
//! - Frames above the outermost frame of the profiled code (thread start, rayon's
//!   scheduler, `main`) are dropped, and so are foreign frames between profiled ones
//!   (rayon's joins). Below the innermost profiled frame, foreign Rust frames (inlined
//!   iterator and intrinsic helpers) fold into it; C functions it calls (`powf`) stay. Samples without any profiled frame (idle
//!   workers stealing work) are kept as one stack, [`SCHEDULER_FRAME`].

use super::names::clean_symbol;
use super::{Stack, StackSamples};
use std::collections::BTreeMap;
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
}

/// What one sampling run measured.
#[derive(Clone, Debug)]
pub struct SampledRun<T> {
    /// The closure's result.
    pub output: T,
    pub samples: StackSamples,
    /// Wall time of the closure.
    pub wall: Duration,
    /// Process CPU time (user + system, all threads) during the closure.
    pub cpu: Duration,
}

/// CPU time of the whole process so far (all threads, user + system).
pub fn process_cpu_time() -> Duration {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::uninit();
    // SAFETY: getrusage writes a complete `rusage` into the pointer on success.
    let ok = unsafe { libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr()) } == 0;
    if !ok {
        return Duration::ZERO;
    }
    // SAFETY: initialised by the successful call above.
    let usage = unsafe { usage.assume_init() };
    let time = |t: libc::timeval| {
        Duration::from_secs(t.tv_sec.max(0) as u64) + Duration::from_micros(t.tv_usec.max(0) as u64)
    };
    time(usage.ru_utime) + time(usage.ru_stime)
}

/// Runs `work` under the sampling profiler at `frequency` Hz. `is_profiled` tells, for
/// a cleaned function name, whether it belongs to the profiled code (e.g. starts with
/// `tracer::`); it decides which frames are scheduler frames.
pub fn sample<T>(
    frequency: i32,
    is_profiled: impl Fn(&str) -> bool,
    work: impl FnOnce() -> T,
) -> Result<SampledRun<T>, ProfileError> {
    let guard = pprof::ProfilerGuardBuilder::default()
        .frequency(frequency)
        // Unwinding through these from a signal handler can deadlock (pprof's advice).
        .blocklist(&["libc", "libgcc", "pthread", "vdso"])
        .build()
        .map_err(|e| ProfileError::Start(e.to_string()))?;
    let cpu_start = process_cpu_time();
    let start = Instant::now();
    let output = work();
    let wall = start.elapsed();
    let cpu = process_cpu_time().saturating_sub(cpu_start);
    let report = guard
        .report()
        .build()
        .map_err(|e| ProfileError::Report(e.to_string()))?;
    drop(guard);

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
    let total: u64 = merged.values().sum();
    if total == 0 {
        return Err(ProfileError::NoSamples(wall));
    }
    Ok(SampledRun {
        output,
        samples: StackSamples {
            stacks: merged
                .into_iter()
                .map(|(frames, count)| Stack { frames, count })
                .collect(),
            seconds_per_sample: cpu.as_secs_f64() / total as f64,
        },
        wall,
        cpu,
    })
}

/// Drops a frame that repeats its caller's name: a function split by the compiler
/// (a closure or an outlined part resolving to the same name) is one function.
fn collapse_repeats(mut frames: Vec<String>) -> Vec<String> {
    frames.dedup();
    frames
}

/// The cleaned symbol names of one sampled stack, root first. pprof lists frames
/// innermost first, and the symbols of one frame (inlined functions first) innermost
/// first too: both are reversed.
pub fn root_first_names(frames: &pprof::Frames) -> Vec<String> {
    frames
        .frames
        .iter()
        .rev()
        .flat_map(|frame| {
            frame
                .iter()
                .rev()
                .map(|symbol| clean_symbol(&symbol.name()))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hint::black_box;

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
                for _ in 0..50_000 {
                    x = x * 1.000_000_1 + 1e-9;
                }
            }
            x
        }};
    }

    #[inline(never)]
    fn seventy_percent_worker() -> f64 {
        burn!(Duration::from_millis(1050), black_box(1.0))
    }

    #[inline(never)]
    fn thirty_percent_worker() -> f64 {
        burn!(Duration::from_millis(450), black_box(2.0))
    }

    #[test]
    fn a_known_seventy_thirty_split_is_attributed_within_ten_points() {
        let run = sample(
            1000,
            |name| name.contains("percent_worker"),
            || black_box(seventy_percent_worker()) + black_box(thirty_percent_worker()),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        // Other tests share the process (and its SIGPROF samples): the workload's
        // split is measured over the samples that caught one of its two functions.
        let hits = |needle: &str| -> u64 {
            run.samples
                .stacks
                .iter()
                .filter(|s| s.frames.last().is_some_and(|f| f.contains(needle)))
                .map(|s| s.count)
                .sum()
        };
        let (seventy, thirty) = (hits("seventy_percent"), hits("thirty_percent"));
        let workload = (seventy + thirty).max(1) as f64;
        assert!(workload > 100.0, "too few samples: {workload}");
        let (a, b) = (seventy as f64 / workload, thirty as f64 / workload);
        assert!((a - 0.7).abs() <= 0.10, "70 % worker got {a:.3}");
        assert!((b - 0.3).abs() <= 0.10, "30 % worker got {b:.3}");
        // CPU seconds per sample: the samples add up to the measured CPU time.
        let accounted = run.samples.total() as f64 * run.samples.seconds_per_sample;
        assert!((accounted - run.cpu.as_secs_f64()).abs() < 1e-9);
        assert!(run.cpu >= Duration::from_millis(1400), "{:?}", run.cpu);
        // Self time: the leaf frame of the workload's samples is the worker itself.
        assert!(run.samples.stacks.iter().all(|s| !s.frames.is_empty()));
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
