//! Fuzz target: arbitrary bytes as NFF text through the parser, the scene builders, the
//! three intersection structures and a tiny render of each (`tracer::fuzz_check`).
//! A panic, a parse error naming no line of the text, a render error after a successful
//! parse, or a NaN/infinite pixel is a finding.
//!
//! The bytes are read as UTF-8 with invalid sequences replaced (U+FFFD): every input
//! then reaches the parser (no execution is spent on inputs rejected before it), and
//! `parse_nff` takes any `&str`, non-ASCII text included. (`load_nff` refuses invalid
//! UTF-8 before parsing; that check is tested by the tracer's own unit tests.)

#![no_main]

use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;

/// One single-thread rayon pool for every execution: the renderer's parallel rows then
/// run on the thread that entered the pool, with one hand-off per execution instead of
/// one per render.
fn pool() -> &'static rayon::ThreadPool {
    static POOL: OnceLock<rayon::ThreadPool> = OnceLock::new();
    POOL.get_or_init(|| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap_or_else(|e| panic!("cannot build the rayon pool: {e}"))
    })
}

/// With `NFF_SCENE_SHOW=1` every input's outcome is printed (for triage: running the
/// binary on files executes each once).
fn show() -> bool {
    static SHOW: OnceLock<bool> = OnceLock::new();
    *SHOW.get_or_init(|| std::env::var_os("NFF_SCENE_SHOW").is_some_and(|v| v == "1"))
}

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    match pool().install(|| tracer::fuzz_check::parse_and_render_tiny(&text, "fuzz.nff")) {
        Err(defect) => panic!("{defect}"),
        Ok(outcome) if show() => eprintln!("outcome: {outcome:?}"),
        Ok(_) => {}
    }
});
