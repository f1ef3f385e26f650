//! The sampler's tests: timers, signal-safe recording, stacks and their names.

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
        sum += black_box(seventy_percent_worker(slice)) + black_box(thirty_percent_worker(slice));
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
    let mut live_counts = Vec::new();
    let run = sample_repeated(&options, is_worker, |live| {
        runs_seen += 1;
        black_box(seventy_thirty(Duration::from_millis(5)));
        live_counts.push(live.signals());
        Ok::<(), std::fmt::Error>(())
    })
    .unwrap_or_else(|e| panic!("{e}"));
    // The live count a run reads grows with the runs and is what stopped them.
    assert!(
        live_counts.windows(2).all(|w| w[0] <= w[1]),
        "{live_counts:?}"
    );
    assert!(
        live_counts.last().is_some_and(|&n| n >= 40),
        "{live_counts:?}"
    );
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
    let run = sample_repeated(&capped, is_worker, |_| {
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
    let failed = sample_repeated(&capped, is_worker, |_| {
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
