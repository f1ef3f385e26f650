//! The gprof importer on gprof's output made here and now: tests/data/gprof/loops.c
//! built with `gcc -pg -O1`, run, and printed by `gprof -b` and plain `gprof`. The
//! call counts read back must be the program's, worked out below from its loops, not
//! from any gprof output. Ignored without gcc and gprof (binutils); `.ci/run` runs it.

use analysis::profile::gprof_import::{self, ImportedGprof};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// loops.c's loop bounds.
const F_CALLS: u64 = 1000; // main -> f
const G_PER_F: u64 = 3; // f -> g
const PARITY_ROUNDS: u64 = 100; // main -> even(10)
const PARITY_DEPTH: u64 = 10;
const FACT_ROUNDS: u64 = 100; // main -> fact(5)
const FACT_DEPTH: u64 = 5;

/// A scratch directory, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("rtprof-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn run(command: &mut Command) -> String {
    let out = command
        .output()
        .unwrap_or_else(|e| panic!("cannot run {command:?}: {e}"));
    assert!(
        out.status.success(),
        "{command:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Builds loops.c with -pg in `dir`, runs it there (gmon.out lands beside it) and
/// returns gprof's output with and without -b.
fn gprof_of_loops(dir: &Path) -> (String, String) {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gprof/loops.c");
    let binary = dir.join("loops");
    run(Command::new("gcc")
        .args(["-pg", "-O1", "-o"])
        .arg(&binary)
        .arg(&source));
    run(Command::new(&binary).current_dir(dir));
    let gprof = |brief: bool| {
        let mut command = Command::new("gprof");
        if brief {
            command.arg("-b");
        }
        run(command.arg(&binary).arg(dir.join("gmon.out")))
    };
    (gprof(true), gprof(false))
}

fn expected_calls() -> BTreeMap<String, u64> {
    // even(10) -> odd(9) -> ... -> even(0): the even arguments 10, 8, .., 0 and the
    // odd ones 9, 7, .., 1 each round.
    let evens = PARITY_DEPTH / 2 + 1;
    let odds = PARITY_DEPTH.div_ceil(2);
    [
        ("f", F_CALLS),
        ("g", F_CALLS * G_PER_F),
        ("even", PARITY_ROUNDS * evens),
        ("odd", PARITY_ROUNDS * odds),
        // gprof's `calls` leaves out a function's calls of itself.
        ("fact", FACT_ROUNDS),
    ]
    .into_iter()
    .map(|(name, calls)| (name.to_owned(), calls))
    .collect()
}

fn check(imported: &ImportedGprof) {
    let evens = PARITY_DEPTH / 2 + 1;
    let odds = PARITY_DEPTH.div_ceil(2);
    let calls = imported.calls();
    for (name, expected) in expected_calls() {
        assert_eq!(calls.get(&name), Some(&expected), "calls of {name}");
    }
    let arc = |caller: &str, callee: &str| {
        imported
            .arc_calls()
            .get(&(caller.to_owned(), callee.to_owned()))
            .copied()
    };
    assert_eq!(arc("main", "f"), Some(F_CALLS));
    assert_eq!(arc("f", "g"), Some(F_CALLS * G_PER_F));
    assert_eq!(arc("main", "even"), Some(PARITY_ROUNDS));
    assert_eq!(arc("even", "odd"), Some(PARITY_ROUNDS * odds));
    assert_eq!(arc("odd", "even"), Some(PARITY_ROUNDS * (evens - 1)));
    assert_eq!(arc("main", "fact"), Some(FACT_ROUNDS));
    assert_eq!(arc("fact", "fact"), Some(FACT_ROUNDS * (FACT_DEPTH - 1)));

    let graph = imported.call_graph.as_ref().unwrap();
    let entry = |name: &str| graph.entries.iter().find(|e| e.name == name).unwrap();
    assert_eq!(
        entry("fact").self_calls,
        Some(FACT_ROUNDS * (FACT_DEPTH - 1))
    );
    // even and odd form gprof's cycle: entered 100 times, 1,000 calls inside.
    let cycle = graph.entries.iter().find(|e| e.whole_cycle).unwrap();
    assert_eq!(cycle.calls, Some(PARITY_ROUNDS));
    assert_eq!(cycle.self_calls, Some(PARITY_ROUNDS * (evens + odds - 1)));
    let mut members: Vec<&str> = cycle.children.iter().map(|m| m.name.as_str()).collect();
    members.sort_unstable();
    assert_eq!(members, ["even", "odd"]);
    assert_eq!(entry("even").cycle, cycle.cycle);
    // main is gprof's spontaneous root and holds the whole run.
    let main = entry("main");
    assert!(main.parents.is_empty() && main.percent > 99.0, "{main:?}");

    // The flat profile's times add up, and it has every counted function.
    let flat = imported.flat.as_ref().unwrap();
    let self_sum: f64 = flat.rows.iter().map(|r| r.self_seconds).sum();
    assert!(flat.total_seconds > 0.0);
    assert!((self_sum - flat.total_seconds).abs() < 0.005 * flat.rows.len() as f64);
    assert!(
        flat.samples > 0
            && flat
                .rows
                .iter()
                .all(|r| r.inclusive_samples >= r.self_samples)
    );
}

#[test]
#[ignore = "needs gcc and gprof"]
fn real_gprof_output_gives_the_programs_call_counts() {
    let dir = Scratch::new("gprof-import");
    let (brief, full) = gprof_of_loops(&dir.0);
    let imported = gprof_import::parse(&brief).unwrap_or_else(|e| panic!("{e}\n{brief}"));
    check(&imported);
    // With the explanations, the same profile.
    let with_explanations = gprof_import::parse(&full).unwrap_or_else(|e| panic!("{e}\n{full}"));
    assert_eq!(with_explanations, imported);
    // Through a file, as `rtprof record --import` will read it.
    let path = dir.0.join("gprof.txt");
    std::fs::write(&path, &brief).unwrap();
    assert_eq!(gprof_import::read(&path).unwrap(), imported);
}
