//! `rtprof.h` in a real C program: the brute-force sphere tracer of `tests/c/spheres.c`
//! built with the system's C compiler (`cc`, or `$CC`: a given wherever Rust links),
//! run with the probe on, and its file read by this crate's reader.
//!
//! The expected counts are computed independently (`tests/common/hand.rs`, which
//! `rtprof record`'s test of the fixture shares): eye rays and sphere tests by hand from
//! the size (W·H and W·H·32), hits by an f64 ray-sphere test of another form (closest
//! approach, not the fixture's quadratic) on the scene the fixture prints.
//! Also: the same counts on 1 and 8 threads, a program stopped by SIGINT or SIGTERM
//! leaves its counts, phases are sampled and add up, and with the probe off nothing is
//! written.

use rtprof_probe::format::{ProbeFile, Reason, read_file};
use std::io::BufRead;
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;

mod common;
use common::hand::{self, SPHERES};
use common::{fixture, scratch};

fn probed() -> &'static Path {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| fixture(&[]))
}

/// Runs the fixture with the probe writing to `file`; returns its stdout.
fn run(file: &Path, args: &[&str], hz: &str) -> String {
    let out = Command::new(probed())
        .args(args)
        .env(rtprof_probe::ENV_FILE, file)
        .env(rtprof_probe::ENV_HZ, hz)
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(out.status.success(), "{args:?}: {out:?}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn read(file: &Path) -> ProbeFile {
    read_file(file).unwrap_or_else(|e| panic!("{e}"))
}

/// The fixture's scene: (centre, radius) per sphere.
fn scene() -> Vec<([f64; 3], f64)> {
    let out = Command::new(probed())
        .arg("scene")
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let spheres = hand::parse_scene(&String::from_utf8_lossy(&out.stdout));
    assert_eq!(spheres.len() as u64, SPHERES);
    spheres
}

/// Eye rays that hit a sphere, and ray-sphere pairs that hit, for a W x H image
/// ([`hand::expected_hits`]).
fn expected_hits(width: u32, height: u32) -> (u64, u64) {
    hand::expected_hits(&scene(), width, height)
}

/// Every standard counter but these is zero.
fn only(file: &ProbeFile, nonzero: &[&str]) {
    for c in &file.counters {
        if !nonzero.contains(&c.name.as_str()) {
            assert_eq!(c.value, 0, "{}", c.name);
        }
    }
    assert_eq!(file.counters.len(), rtprof_probe::COUNTER_KEYS.len());
}

#[test]
fn counts_equal_the_hand_computation_on_1_and_8_threads() {
    let dir = scratch("counts");
    let (width, height) = (64u32, 48u32);
    let (rays_hit, hits) = expected_hits(width, height);
    // The scene is not trivial: some rays hit several spheres, most hit none.
    assert!(rays_hit > 500 && hits > rays_hit + 100, "{rays_hit} {hits}");
    let pixels = u64::from(width * height);
    let mut files = Vec::new();
    for threads in ["1", "8"] {
        let file = dir.join(format!("probe-{threads}.txt"));
        let checksum = run(&file, &["64", "48", threads, "2"], "0");
        let probe = read(&file);
        assert_eq!(probe.writer, "c");
        assert_eq!(probe.reason, Reason::Exit);
        assert_eq!(probe.counter("rays.primary"), Some(2 * pixels), "{threads}");
        assert_eq!(
            probe.counter("tests.sphere.tests"),
            Some(2 * pixels * SPHERES)
        );
        assert_eq!(probe.counter("rays.primary_hit"), Some(2 * rays_hit));
        assert_eq!(probe.counter("tests.sphere.hits"), Some(2 * hits));
        only(
            &probe,
            &[
                "rays.primary",
                "tests.sphere.tests",
                "rays.primary_hit",
                "tests.sphere.hits",
            ],
        );
        assert_eq!(probe.user_counter("fixture frames"), Some(2));
        // The main thread and the workers.
        assert_eq!(probe.threads, 1 + threads.parse::<u64>().unwrap_or(0));
        // Counters only (RTPROF_PROBE_HZ=0): no phase samples.
        assert_eq!((probe.period_ns, probe.samples), (0, 0));
        assert!(!dir.join(format!("probe-{threads}.txt.tmp")).exists());
        files.push((checksum, probe.counters, probe.user_counters));
    }
    assert_eq!(files[0], files[1], "1 and 8 threads differ");
}

#[test]
fn phases_are_sampled_from_each_thread_s_cpu_time() {
    let dir = scratch("phases");
    let file = dir.join("probe.txt");
    // About 0.5 s of CPU on two threads (the fixture tests 650 M spheres a second).
    run(&file, &["320", "240", "2", "150"], "1000");
    let probe = read(&file);
    assert_eq!(probe.period_ns, 1_000_000);
    assert_eq!(probe.unbalanced, 0);
    let sphere = probe
        .phase("sphere test")
        .cloned()
        .unwrap_or_else(|| panic!("{probe:?}"));
    let closest = probe
        .phase("closest hit")
        .cloned()
        .unwrap_or_else(|| panic!("{probe:?}"));
    // At the kernel's tick or better: 100 samples a CPU second at the least.
    let cpu = probe.cpu_ns as f64 * 1e-9;
    assert!(
        probe.samples as f64 >= 100.0 * cpu && cpu > 0.2,
        "{} samples in {cpu} s",
        probe.samples
    );
    // A sample stands for at least the period asked (the kernel's tick may stretch it).
    let per_sample = probe.seconds_per_sample().unwrap_or(0.0);
    assert!(
        (0.001..0.02).contains(&per_sample),
        "{per_sample} s a sample"
    );
    // The sphere loop is the largest phase and nests in the closest-hit query.
    for other in probe.phases.iter().filter(|p| p.name != "sphere test") {
        assert!(other.self_samples <= sphere.self_samples, "{probe:?}");
    }
    assert!(closest.total_samples >= sphere.total_samples + closest.self_samples);
    assert_eq!(sphere.self_samples, sphere.total_samples, "a leaf phase");
    let outside = probe.outside as f64 / probe.samples as f64;
    assert!(outside < 0.2, "{probe:?}");
}

/// Runs the fixture until `signal` stops it; the file must hold whole frames' counts.
fn stopped_by(signal: &str, number: u32) {
    let dir = scratch(signal);
    let file = dir.join("probe.txt");
    let mut child = Command::new(probed())
        .args(["64", "48", "1", "loop"])
        .env(rtprof_probe::ENV_FILE, &file)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("{e}"));
    let mut line = String::new();
    let stdout = child.stdout.take().unwrap_or_else(|| panic!("no stdout"));
    std::io::BufReader::new(stdout)
        .read_line(&mut line)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(line, "ready\n");
    // The shell's kill: a /bin/kill (procps) is not on every machine.
    let killed = Command::new("sh")
        .args(["-c", &format!("kill -{signal} {}", child.id())])
        .status()
        .unwrap_or_else(|e| panic!("kill: {e}"));
    assert!(killed.success());
    let status = child.wait().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status.signal(), Some(number as i32), "{status:?}");
    let probe = read(&file);
    assert_eq!(probe.reason, Reason::Signal(number));
    let rays = probe.counter("rays.primary").unwrap_or(0);
    let tests = probe.counter("tests.sphere.tests").unwrap_or(0);
    assert!(
        rays >= 64 * 48,
        "{rays} eye rays: less than the first frame"
    );
    // A ray's tests are added after its count: the stop may fall between the two.
    assert!(
        tests == rays * SPHERES || tests == (rays - 1) * SPHERES,
        "{rays} rays, {tests} tests"
    );
}

#[test]
fn a_program_stopped_by_sigterm_leaves_its_counts() {
    stopped_by("TERM", 15);
}

#[test]
fn a_program_stopped_by_sigint_leaves_its_counts() {
    stopped_by("INT", 2);
}

#[test]
fn off_writes_nothing_and_renders_the_same_as_compiled_out() {
    let dir = scratch("off");
    let args = ["40", "30", "3", "1"];
    let off = Command::new(probed())
        .args(args)
        .env_remove(rtprof_probe::ENV_FILE)
        .current_dir(&dir)
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let disabled = Command::new(fixture(&["-DRTPROF_DISABLE"]))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(off.status.success() && disabled.status.success());
    assert_eq!(off.stdout, disabled.stdout);
    let on = run(&dir.join("probe.txt"), &args, "1000");
    assert_eq!(on.as_bytes(), off.stdout);
    assert_eq!(
        std::fs::read_dir(&dir).map(|d| d.count()).unwrap_or(0),
        1,
        "only the probe that was on wrote a file"
    );
}
