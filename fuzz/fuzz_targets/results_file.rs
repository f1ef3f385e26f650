//! Fuzz target: arbitrary bytes as a results file through reading and validation, the
//! regression gate and the HTML report (`reports::fuzz_check`). A panic, a run that
//! fails the gate against itself, a changed count the gate misses, results that cannot
//! be read back after writing, or a failed report is a finding; so is a hang
//! (`-timeout`), which is how the 1e308 samples showed.

#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::OnceLock;

/// An empty directory as the results directory: every file the input names is missing.
fn empty_dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("rtprof-fuzz-results-{}", std::process::id()));
        std::fs::create_dir_all(&dir)
            .unwrap_or_else(|e| panic!("cannot create {}: {e}", dir.display()));
        dir
    })
}

/// With `RESULTS_FILE_SHOW=1` every input's outcome is printed (for triage).
fn show() -> bool {
    static SHOW: OnceLock<bool> = OnceLock::new();
    *SHOW.get_or_init(|| std::env::var_os("RESULTS_FILE_SHOW").is_some_and(|v| v == "1"))
}

fuzz_target!(|data: &[u8]| {
    match reports::fuzz_check::read_gate_and_render(data, empty_dir()) {
        Err(defect) => panic!("{defect}"),
        Ok(outcome) if show() => eprintln!("outcome: {outcome:?}"),
        Ok(_) => {}
    }
});
