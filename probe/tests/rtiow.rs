//! The worked example of docs/instrumenting.md: Ray Tracing: The Next Week
//! (`../shared/peers/rtiow`, C++) patched with the probe by `scripts/rtiow-probe.sh`,
//! against the same program patched with plain global atomic counters instead
//! (`scripts/rtiow/count.patch`): eye rays, sphere tests and hits must be equal, and the
//! pictures of the probed, counted and plain builds identical (the probe changes
//! nothing the program computes). RTIOW is single-threaded, so there is no thread
//! count to vary. Needs g++ and rtprof's repository around the crate; .ci/run runs it.

use rtprof_probe::format::read_file;
use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::{probe_dir, scratch};

fn build(dir: &Path, kind: &str) -> PathBuf {
    let script = probe_dir().join("../scripts/rtiow-probe.sh");
    let out = Command::new("bash")
        .arg(&script)
        .arg(dir)
        .arg(kind)
        .output()
        .unwrap_or_else(|e| panic!("{}: {e}", script.display()));
    assert!(
        out.status.success(),
        "{kind}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    PathBuf::from(String::from_utf8_lossy(&out.stdout).trim())
}

/// Runs `program SAMPLES WIDTH`; returns (picture, stderr).
fn run(program: &Path, args: &[&str], env: &[(&str, &Path)]) -> (Vec<u8>, String) {
    let mut command = Command::new(program);
    command.args(args).env_remove(rtprof_probe::ENV_FILE);
    for (k, v) in env {
        command.env(k, v);
    }
    let out = command.output().unwrap_or_else(|e| panic!("{e}"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (
        out.stdout,
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `name value` pairs of the count patch's last line.
fn independent(stderr: &str) -> Vec<(String, u64)> {
    let line = stderr
        .lines()
        .find_map(|l| l.rsplit('\r').next()?.strip_prefix("rtiow count: "))
        .unwrap_or_else(|| panic!("no count line in {stderr:?}"));
    let words: Vec<&str> = line.split(' ').collect();
    words
        .chunks(2)
        .map(|p| (p[0].to_string(), p[1].parse().unwrap_or(u64::MAX)))
        .collect()
}

#[test]
#[ignore = "needs g++ and ../shared/peers/rtiow (.ci/run runs it)"]
fn rtiow_s_probe_counts_equal_an_independent_count() {
    let dir = scratch("rtiow");
    let probe = build(&dir, "probe");
    let count = build(&dir, "count");
    let plain = build(&dir, "plain");
    let args = ["2", "160"];
    let file = dir.join("probe.txt");
    let (probed_picture, _) = run(&probe, &args, &[(rtprof_probe::ENV_FILE, &file)]);
    let (counted_picture, stderr) = run(&count, &args, &[]);
    let (plain_picture, _) = run(&plain, &args, &[]);
    let (off_picture, _) = run(&probe, &args, &[]);
    assert!(plain_picture.starts_with(b"P3\n160 90\n255\n"));
    assert!(probed_picture == plain_picture && counted_picture == plain_picture);
    assert!(off_picture == plain_picture);
    let probe = read_file(&file).unwrap_or_else(|e| panic!("{e}"));
    let counts = independent(&stderr);
    let by = |k: &str| counts.iter().find(|(n, _)| n == k).map(|(_, v)| *v);
    // 160 x 90 pixels, 2 samples each: the eye rays by hand as well.
    assert_eq!(by("eye_rays"), Some(160 * 90 * 2));
    assert_eq!(probe.counter("rays.primary"), by("eye_rays"));
    assert_eq!(probe.counter("tests.sphere.tests"), by("sphere_tests"));
    assert_eq!(probe.counter("tests.sphere.hits"), by("sphere_hits"));
    assert!(by("sphere_tests").unwrap_or(0) > 10 * 160 * 90 * 2);
    // Every traced ray is an eye ray or a scattered one; a ray scattered at the depth
    // limit (50 bounces, inside glass) is not traced.
    let scattered = probe.user_counter("scattered rays").unwrap_or(0);
    let traced = probe.counter("calls.trace").unwrap_or(0);
    assert!(traced <= 160 * 90 * 2 + scattered && traced + 100 > 160 * 90 * 2 + scattered);
    assert_eq!(probe.threads, 1);
    assert_eq!(probe.unbalanced, 0);
}
