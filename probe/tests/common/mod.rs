//! Helpers of the probe's integration tests: scratch directories and the C fixture
//! built with the system's C compiler.

#![allow(dead_code)] // each test file uses a part

use std::path::PathBuf;
use std::process::Command;

pub mod hand;

pub fn probe_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh directory for one test's files.
pub fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("probe-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// Compiles the fixture once per `defines` (e.g. `-DRTPROF_DISABLE`).
pub fn fixture(extra: &[&str]) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c_fixture-bin");
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let name = format!("spheres{}", extra.join("").replace(['-', '='], "_"));
    let out = dir.join(name);
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let status = Command::new(&cc)
        .args([
            "-std=c99",
            "-O2",
            "-g",
            "-pthread",
            "-Wall",
            "-Wextra",
            "-pedantic",
            "-Werror",
        ])
        .args(extra)
        .arg("-I")
        .arg(probe_dir())
        .arg(probe_dir().join("tests/c/spheres.c"))
        .arg("-o")
        .arg(&out)
        .arg("-lm")
        .status()
        .unwrap_or_else(|e| panic!("cannot run the C compiler {cc}: {e}"));
    assert!(status.success(), "{cc} failed to build the fixture");
    out
}
