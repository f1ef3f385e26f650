//! What the tests of `rtprof record` share (tests/record.rs, tests/record_import.rs):
//! running rtprof, scratch directories, a C program whose hot function holds nine
//! tenths of its work by construction, and readers of the files a recording writes.
// Each test crate that includes this module uses a part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn rtprof(args: &[&str], env: &[(&str, &str)]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(args)
        .envs(env.iter().copied())
        .output()
        .unwrap_or_else(|e| panic!("cannot run rtprof: {e}"))
}

pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A scratch directory unique to one test.
pub fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-record-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

/// A C program whose time is, by construction, about 90 % in `hot` (nine times the
/// loop of `cold`), with `step` forced inline into `hot`; it exits with `argv[1]`'s
/// code, or kills itself with SIGSEGV when `argv[1]` is `segv`.
pub const PROGRAM: &str = r#"
#include <signal.h>
#include <stdlib.h>
#include <string.h>
static volatile unsigned long sink;
static inline __attribute__((always_inline)) unsigned long step(unsigned long x) {
    return x * 2862933555777941757UL + 3037000493UL;
}
__attribute__((noinline)) void hot(long n) {
    unsigned long x = sink;
    for (long i = 0; i < 9 * n; i++) x = step(x);
    sink = x;
}
__attribute__((noinline)) void cold(long n) {
    unsigned long x = sink;
    for (long i = 0; i < n; i++) x = x * 6364136223846793005UL + 1;
    sink = x;
}
int main(int argc, char **argv) {
    long n = 20000000;
    hot(n);
    cold(n);
    if (argc > 1 && strcmp(argv[1], "segv") == 0) raise(SIGSEGV);
    return argc > 1 ? atoi(argv[1]) : 0;
}
"#;

/// Compiles [`PROGRAM`] with frame pointers and debug info into `dir/hot`. At -O1, as
/// at -O2 with gcc 12, `hot` and `cold` are leaves without a frame of their own, so
/// the kernel's walk goes from them to `main`'s caller; -O1 keeps `step` as an inlined
/// subroutine in the debug info (-O2 folds it into the loop).
pub fn hot_program(dir: &Path) -> PathBuf {
    let source = dir.join("hot.c");
    std::fs::write(&source, PROGRAM).unwrap_or_else(|e| panic!("{e}"));
    let exe = dir.join("hot");
    let status = Command::new("cc")
        .args(["-O1", "-g", "-fno-omit-frame-pointer", "-o"])
        .arg(&exe)
        .arg(&source)
        .status()
        .unwrap_or_else(|e| panic!("cannot run cc: {e}"));
    assert!(status.success(), "cc failed");
    exe
}

/// Samples per innermost frame and per whole folded stack, from the folded file.
pub fn folded(dir: &Path, stem: &str) -> Vec<(String, u64)> {
    let text = std::fs::read_to_string(dir.join(format!("folded-{stem}.txt")))
        .unwrap_or_else(|e| panic!("{e}"));
    text.lines()
        .filter_map(|l| {
            let (stack, n) = l.rsplit_once(' ')?;
            Some((stack.to_string(), n.parse().ok()?))
        })
        .collect()
}

/// The innermost frame of a folded stack, the kernel's left out.
pub fn leaf(stack: &str) -> &str {
    stack.split(';').rfind(|f| *f != "[kernel]").unwrap_or("")
}

pub fn share(stacks: &[(String, u64)], keep: impl Fn(&str) -> bool) -> f64 {
    let total: u64 = stacks.iter().map(|s| s.1).sum();
    let kept: u64 = stacks.iter().filter(|s| keep(&s.0)).map(|s| s.1).sum();
    kept as f64 / total.max(1) as f64
}

pub fn record_json(dir: &Path) -> serde_json::Value {
    let text = std::fs::read(dir.join("record.json")).unwrap_or_else(|e| panic!("{e}"));
    serde_json::from_slice(&text).unwrap_or_else(|e| panic!("{e}"))
}
