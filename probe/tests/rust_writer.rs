//! The crate's own recorder in a Rust program: the C fixture's sphere tracer ported to
//! Rust (same scene, camera and test), run in a child process (this test binary again,
//! `child_render`, with the probe's environment), must write the same counts as the C
//! fixture with `rtprof.h`: the two probes have one meaning. Also on 1 and 8 threads,
//! with phases sampled, and when stopped by SIGTERM.

#![cfg(feature = "enabled")] // the recorder compiled out writes nothing to compare

use rtprof_probe::format::{ProbeFile, Reason, read_file};
use rtprof_probe::{Counter, Phase, count, in_phase};
use std::os::unix::process::ExitStatusExt;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

mod common;
use common::{fixture, scratch};

const CHILD: &str = "RTPROF_PROBE_TEST_CHILD";
const READY: &str = "RTPROF_PROBE_TEST_READY";

/// The fixture's scene (tests/c/spheres.c, `build_scene`).
fn scene() -> [[f64; 4]; 32] {
    let mut scene = [[0.0; 4]; 32];
    for (k, s) in scene.iter_mut().enumerate() {
        *s = [
            -3.5 + 1.0 * (k % 8) as f64 + 0.15 * (k % 3) as f64,
            -1.6 + 1.05 * (k / 8) as f64 - 0.1 * (k % 5) as f64,
            -4.5 - 0.17 * ((k * 7) % 32) as f64,
            0.45 + 0.06 * (k % 7) as f64,
        ];
    }
    scene
}

/// One row, as the fixture renders it, instrumented with the crate.
fn render_row(scene: &[[f64; 4]; 32], width: u32, height: u32, j: u32) -> f64 {
    let aspect = f64::from(height) / f64::from(width);
    let mut sum = 0.0;
    for i in 0..width {
        let d = in_phase(Phase::CAMERA_RAY, || {
            let x = 2.0 * (f64::from(i) + 0.5) / f64::from(width) - 1.0;
            let y = (1.0 - 2.0 * (f64::from(j) + 0.5) / f64::from(height)) * aspect;
            let length = (x * x + y * y + 1.0).sqrt();
            count(Counter::RAYS_PRIMARY, 1);
            [x / length, y / length, -1.0 / length]
        });
        let (nearest, hits) = in_phase(Phase::CLOSEST_HIT, || {
            let (nearest, hits) = in_phase(Phase::SPHERE_TEST, || {
                let mut best = (1e30, usize::MAX);
                let mut hits = 0;
                for (k, s) in scene.iter().enumerate() {
                    let b = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];
                    let c = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - s[3] * s[3];
                    let disc = b * b - c;
                    if disc >= 0.0 {
                        let root = disc.sqrt();
                        let t = if b - root > 1e-9 { b - root } else { b + root };
                        if t > 1e-9 {
                            hits += 1;
                            if t < best.0 {
                                best = (t, k);
                            }
                        }
                    }
                }
                (best.1, hits)
            });
            count(Counter::TESTS_SPHERE_TESTS, 32);
            count(Counter::TESTS_SPHERE_HITS, hits);
            (nearest, hits)
        });
        if nearest != usize::MAX {
            count(Counter::RAYS_PRIMARY_HIT, 1);
            sum += in_phase(Phase::SHADING, || nearest as f64 * 1e-3) + hits as f64;
        }
    }
    sum
}

/// The child: renders when the parent asked (`W,H,THREADS,FRAMES`, FRAMES 0 = until
/// killed), else does nothing.
#[test]
fn child_render() {
    let Ok(spec) = std::env::var(CHILD) else {
        return;
    };
    let v: Vec<u32> = spec.split(',').filter_map(|x| x.parse().ok()).collect();
    let (width, height, threads, frames) = (v[0], v[1], v[2], v[3]);
    const FRAMES: Counter = Counter::user(0);
    rtprof_probe::declare_counter(FRAMES, "fixture frames");
    rtprof_probe::declare_phase(Phase::user(0), "fixture setup");
    in_phase(Phase::user(0), || count(FRAMES, u64::from(frames.max(1))));
    let scene = scene();
    std::thread::scope(|s| {
        for index in 0..threads {
            let scene = &scene;
            s.spawn(move || {
                let mut frame = 0;
                while frames == 0 || frame < frames {
                    for j in (index..height).step_by(threads as usize) {
                        std::hint::black_box(render_row(scene, width, height, j));
                    }
                    if frames == 0 && frame == 0 && index == 0 {
                        let ready = std::env::var_os(READY).unwrap_or_default();
                        std::fs::write(ready, "ready").unwrap_or_else(|e| panic!("{e}"));
                    }
                    frame += 1;
                }
            });
        }
    });
}

fn child(file: &Path, spec: &str, hz: &str) -> Command {
    let mut command = Command::new(std::env::current_exe().unwrap_or_default());
    command
        .args(["--exact", "child_render", "--test-threads=1", "--quiet"])
        .env(CHILD, spec)
        .env(rtprof_probe::ENV_FILE, file)
        .env(rtprof_probe::ENV_HZ, hz);
    command
}

fn read(file: &Path) -> ProbeFile {
    read_file(file).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_rust_probe_writes_what_the_c_probe_writes_for_the_same_program() {
    let dir = scratch("rust-writer");
    let c_file = dir.join("c.txt");
    let status = Command::new(fixture(&[]))
        .args(["64", "48", "3", "2"])
        .env(rtprof_probe::ENV_FILE, &c_file)
        .env(rtprof_probe::ENV_HZ, "0")
        .stdout(std::process::Stdio::null())
        .status()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(status.success());
    let c = read(&c_file);
    let mut runs = Vec::new();
    for threads in [1, 8] {
        let file = dir.join(format!("rust-{threads}.txt"));
        let out = child(&file, &format!("64,48,{threads},2"), "0")
            .output()
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(out.status.success(), "{out:?}");
        let rust = read(&file);
        assert_eq!(rust.writer, "rust");
        assert_eq!(rust.reason, Reason::Exit);
        assert_eq!(rust.threads, 1 + threads);
        assert_eq!(rust.counters, c.counters, "{threads} threads");
        assert_eq!(rust.user_counters, c.user_counters);
        assert_eq!(rust.counter("rays.primary"), Some(2 * 64 * 48));
        assert_eq!(
            rust.phases.iter().map(|p| &p.name).collect::<Vec<_>>(),
            c.phases.iter().map(|p| &p.name).collect::<Vec<_>>()
        );
        assert_eq!(rust.user_phases.len(), 1);
        assert_eq!(rust.user_phases[0].name, "fixture setup");
        runs.push(rust.counters);
    }
    assert_eq!(runs[0], runs[1]);
}

#[test]
fn the_rust_probe_samples_phases() {
    let dir = scratch("rust-phases");
    let file = dir.join("probe.txt");
    // Long enough for a hundred samples at the kernel's tick.
    let out = child(&file, "320,240,2,120", "1000")
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(out.status.success(), "{out:?}");
    let probe = read(&file);
    assert_eq!(probe.period_ns, 1_000_000);
    assert_eq!(probe.unbalanced, 0);
    assert!(probe.samples >= 50, "{probe:?}");
    let sphere = probe.phase("sphere test").map_or(0, |p| p.self_samples);
    let closest = probe.phase("closest hit").map_or(0, |p| p.total_samples);
    assert!(sphere > 0 && closest >= sphere, "{probe:?}");
    assert!(probe.outside * 5 < probe.samples, "{probe:?}");
}

#[test]
fn a_rust_program_stopped_by_sigterm_leaves_its_counts() {
    let dir = scratch("rust-sigterm");
    let file = dir.join("probe.txt");
    let ready = dir.join("ready");
    let mut running = child(&file, "64,48,2,0", "1000")
        .env(READY, &ready)
        .spawn()
        .unwrap_or_else(|e| panic!("{e}"));
    let start = Instant::now();
    while !ready.exists() {
        assert!(start.elapsed() < Duration::from_secs(60), "no first frame");
        std::thread::sleep(Duration::from_millis(10));
    }
    // The shell's kill: a /bin/kill (procps) is not on every machine.
    let killed = Command::new("sh")
        .args(["-c", &format!("kill -TERM {}", running.id())])
        .status()
        .unwrap_or_else(|e| panic!("kill: {e}"));
    assert!(killed.success());
    let status = running.wait().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status.signal(), Some(15), "{status:?}");
    let probe = read(&file);
    assert_eq!(probe.reason, Reason::Signal(15));
    let rays = probe.counter("rays.primary").unwrap_or(0);
    let tests = probe.counter("tests.sphere.tests").unwrap_or(0);
    assert!(rays >= 64 * 48, "{rays}");
    // Two threads: each may have counted its ray and not yet its tests.
    assert!(
        tests <= rays * 32 && tests + 2 * 32 >= rays * 32,
        "{rays} {tests}"
    );
}
