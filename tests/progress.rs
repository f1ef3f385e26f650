//! Progress as a user sees it: the suite's bar (scene i of N, variant, elapsed and
//! remaining time) when RTPROF_PROGRESS forces it into a pipe, nothing in a pipe by
//! default, and the note before a long brute-force render.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn rtprof(args: &[&str], progress: Option<&str>) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rtprof"));
    command.args(args).env_remove("RTPROF_PROGRESS");
    if let Some(value) = progress {
        command.env("RTPROF_PROGRESS", value);
    }
    command
        .output()
        .unwrap_or_else(|e| panic!("cannot run rtprof: {e}"))
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A scratch directory unique to one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-progress-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Two scenes × two variants at 32x24, one repeat, a small profile.
const TINY_SUITE: &str = r#"
name = "tiny"
size = [32, 24]
repeats = 1
min_seconds = 0
variants = ["baseline", "bvh"]
scenes = ["balls1", "cylinder2"]
extra_size = [32, 24]
profile_size = [32, 24]
profile_frequency = 1000
profile_samples = 50
hardware_repeats = 1
"#;

/// Runs the tiny suite with RTPROF_PROGRESS set to `progress` (or unset): its stderr.
fn tiny_suite(test: &str, progress: Option<&str>) -> String {
    let dir = scratch(test);
    let suite = dir.join("suite.toml");
    std::fs::write(&suite, TINY_SUITE).unwrap();
    let out_dir = dir.join("out");
    let out = rtprof(
        &[
            "suite",
            suite.to_str().unwrap(),
            "-o",
            out_dir.to_str().unwrap(),
            "--no-pdf",
        ],
        progress,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(out_dir.join("results.json").is_file());
    stderr(&out)
}

#[test]
fn forced_progress_shows_the_steps_the_scene_and_the_times() {
    let text = tiny_suite("forced", Some("always"));
    let bars: Vec<&str> = text.lines().filter(|l| l.contains("elapsed")).collect();
    assert!(!bars.is_empty(), "no progress lines:\n{text}");
    assert!(
        bars.iter().any(|l| l.trim_start().starts_with("scenes [")
            && (l.contains(" 2/4 ") || l.contains(" 4/4 "))
            && l.contains("remaining)")),
        "no scenes bar with steps and remaining time:\n{text}"
    );
    assert!(
        bars.iter()
            .any(|l| l.contains("balls1") || l.contains("cylinder2")),
        "no scene named:\n{text}"
    );
    // Plain lines: no cursor movement or line clearing in a pipe.
    assert!(!text.contains('\x1b'), "escape codes in a pipe:\n{text:?}");
    // Each fits 100 columns.
    assert!(bars.iter().all(|l| l.chars().count() <= 100), "{bars:#?}");
}

#[test]
fn progress_is_absent_from_a_pipe_by_default_and_when_turned_off() {
    for (test, value) in [("default", None), ("never", Some("never"))] {
        let text = tiny_suite(test, value);
        assert!(
            !text.contains("elapsed") && !text.contains("remaining") && !text.contains("/4 "),
            "{value:?}: progress in a pipe:\n{text}"
        );
    }
}

/// Generates a sphereflake of 7,381 spheres in `dir`.
fn flake(dir: &Path) -> String {
    let path = dir.join("flake.nff");
    let out = rtprof(
        &[
            "scene",
            "gen",
            "sphereflake:4",
            "-o",
            path.to_str().unwrap(),
        ],
        None,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    path.display().to_string()
}

#[test]
fn a_long_brute_force_render_says_how_long_and_suggests_bvh() {
    let dir = scratch("note");
    let scene = flake(&dir);
    let image = dir.join("flake.png");
    // Big enough for minutes of brute force: read the note, then stop the render.
    let mut child = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args([
            "render",
            &scene,
            "--size",
            "1600x1200",
            "--threads",
            "1",
            "-o",
        ])
        .arg(&image)
        .env("RTPROF_PROGRESS", "never")
        .stderr(Stdio::piped())
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    let mut first = String::new();
    let pipe = child.stderr.take().unwrap();
    BufReader::new(pipe).read_line(&mut first).unwrap();
    child.kill().unwrap();
    child.wait().unwrap();
    let rest = first.strip_prefix("note: brute force over 7,381 primitives at 1600×1200: about ");
    let time = rest.and_then(|r| {
        r.trim_end()
            .strip_suffix("; --variant bvh is usually far faster")
    });
    // "40 s", "2 min", "3 h": a whole number and a unit.
    let (number, unit) = time
        .and_then(|t| t.split_once(' '))
        .unwrap_or_else(|| panic!("{first}"));
    assert!(
        number.parse::<u64>().is_ok() && ["s", "min", "h"].contains(&unit),
        "{first}"
    );
    // The BVH, or a size that renders in an instant: no note.
    for args in [
        vec!["render", &scene, "--size", "32x24", "--variant", "bvh"],
        vec!["render", &scene, "--size", "8x6"],
    ] {
        let mut args = args;
        let png = dir.join("small.png");
        args.extend(["-o", png.to_str().unwrap()]);
        let out = rtprof(&args, None);
        assert!(out.status.success(), "{}", stderr(&out));
        assert!(
            !stderr(&out).contains("note:"),
            "{args:?}: {}",
            stderr(&out)
        );
    }
}
