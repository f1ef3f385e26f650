//! Every input in `tests/fuzz-regressions/` (inputs the `results_file` fuzz campaign
//! found, plus hand-written hostile ones; docs/fuzzing.md) runs through the fuzz
//! target's own path, `reports::fuzz_check::read_gate_and_render`. No input may panic
//! or break a check, and each must end as its name says: `refused-*` is refused with
//! an error, `reported-*` gets a report. The `/1` file written by main at d19ee0e
//! (results/tests/data) must get a report too.

use std::path::{Path, PathBuf};

use reports::fuzz_check::{Outcome, read_gate_and_render};

fn empty_dir() -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("rtprof-results-regressions-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

fn outcome(path: &Path, dir: &Path) -> Outcome {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let started = std::time::Instant::now();
    let outcome = read_gate_and_render(&bytes, dir)
        .unwrap_or_else(|defect| panic!("{}: {defect}", path.display()));
    // The 1e308 samples made a report run for minutes.
    assert!(
        started.elapsed().as_secs() < 20,
        "{}: took {:?}",
        path.display(),
        started.elapsed()
    );
    outcome
}

#[test]
fn every_results_regression_ends_as_its_name_says() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz-regressions");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.unwrap_or_else(|e| panic!("{e}")).path())
        .filter(|path| path.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    assert!(files.len() >= 6, "only {} regression inputs", files.len());
    let empty = empty_dir();
    for path in &files {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        match outcome(path, &empty) {
            Outcome::Refused(message) => {
                assert!(name.starts_with("refused-"), "{name}: refused: {message}");
            }
            Outcome::Reported(bytes) => {
                assert!(name.starts_with("reported-"), "{name}: reported");
                assert!(bytes > 1000, "{name}: a report of {bytes} bytes");
            }
        }
    }
    let v1 = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../results/tests/data/v1-main-d19ee0e/results.json");
    assert!(matches!(outcome(&v1, &empty), Outcome::Reported(_)));
    std::fs::remove_dir_all(&empty).ok();
}
