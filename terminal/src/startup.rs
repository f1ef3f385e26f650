//! `RTPROF_TRACE_STARTUP=1`: where a short command's time goes. The command records a
//! time stamp at each phase boundary (main entered, arguments parsed, scene rendered,
//! image written, ...) and, at the end of `main`, prints them on stderr in one write:
//!
//! ```text
//! rtprof startup: at main +0.000 ms (CLOCK_MONOTONIC 123456789012 ns)
//! rtprof startup: at args +0.085 ms
//! rtprof startup: took render.tracing 0.012 ms
//! ```
//!
//! `at` lines are milliseconds since main; `took` lines are durations measured inside
//! a phase. The first line's CLOCK_MONOTONIC stamp lets a caller on the same clock
//! (scripts/startup-cost.py) measure what comes before main (exec, dynamic loading,
//! runtime init) and after the last mark (exit). Unset, each mark is one relaxed
//! atomic load.

use reports::format::fixed;
use std::io::Write;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// The environment variable that turns the trace on (`1`).
pub const VARIABLE: &str = "RTPROF_TRACE_STARTUP";

static ON: AtomicBool = AtomicBool::new(false);

enum Entry {
    /// A phase boundary: CLOCK_MONOTONIC nanoseconds.
    At(&'static str, u64),
    /// A duration measured inside a phase.
    Took(&'static str, Duration),
}

static ENTRIES: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

/// Reads the variable and, when it is `1`, records the start of main.
pub fn start() {
    if std::env::var_os(VARIABLE).is_some_and(|v| v == "1") {
        ON.store(true, Ordering::Relaxed);
        mark("main");
    }
}

/// Records the end of the phase `label` names (the time since main is the phase's end).
pub fn mark(label: &'static str) {
    if ON.load(Ordering::Relaxed) {
        push(Entry::At(label, monotonic_ns()));
    }
}

/// Records a duration measured inside the current phase.
pub fn took(label: &'static str, duration: Duration) {
    if ON.load(Ordering::Relaxed) {
        push(Entry::Took(label, duration));
    }
}

fn push(entry: Entry) {
    if let Ok(mut entries) = ENTRIES.lock() {
        entries.push(entry);
    }
}

/// Marks `exit` and prints the trace on stderr, in one write.
pub fn finish() {
    if !ON.load(Ordering::Relaxed) {
        return;
    }
    mark("exit");
    let Ok(entries) = ENTRIES.lock() else {
        return;
    };
    let main = entries.iter().find_map(|e| match e {
        Entry::At(_, ns) => Some(*ns),
        Entry::Took(..) => None,
    });
    let Some(main) = main else {
        return;
    };
    let mut text = String::new();
    for entry in entries.iter() {
        let line = match entry {
            Entry::At(label, ns) if *ns == main => {
                format!("at {label} +0.000 ms (CLOCK_MONOTONIC {ns} ns)")
            }
            Entry::At(label, ns) => {
                let ms = ns.saturating_sub(main) as f64 / 1e6;
                format!("at {label} +{} ms", fixed(ms, 3))
            }
            Entry::Took(label, d) => format!("took {label} {} ms", fixed(d.as_secs_f64() * 1e3, 3)),
        };
        text.push_str("rtprof startup: ");
        text.push_str(&line);
        text.push('\n');
    }
    // A trace that cannot be printed is not worth failing the command for.
    let _ = std::io::stderr().lock().write_all(text.as_bytes());
}

/// CLOCK_MONOTONIC, the clock of `std::time::Instant` and of Python's `time.monotonic_ns`.
fn monotonic_ns() -> u64 {
    let mut now = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec through a valid pointer.
    unsafe { libc::clock_gettime(libc::CLOCK_MONOTONIC, &mut now) };
    (now.tv_sec as u64)
        .saturating_mul(1_000_000_000)
        .saturating_add(now.tv_nsec as u64)
}
