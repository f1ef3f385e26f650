//! Outside tracers recorded with perf where the suite asks (`record = true` in its
//! `[[tracers]]`, docs/tracers.md): without perf the recording is a failure of the run
//! with its reason, and the rest of the suite stands; with perf (ignored: needs perf and
//! a C compiler) the profile of a program whose hot function holds nine tenths of its
//! work by construction names that function, and its files are listed in results.json
//! and shown in the report.

mod record_common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use record_common::{folded, leaf, scratch, share, stderr};

/// A small lit sphere.
fn scene(dir: &Path) -> PathBuf {
    let path = dir.join("one.nff");
    std::fs::write(
        &path,
        "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 8 8\nl 2 3 -6\nf 1 0.5 0 1 0 1 0 1\ns 0 0 0 1.5\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    path
}

/// A one-scene suite whose one outside tracer runs `command` (TOML array items) and
/// asks to be recorded.
fn suite(dir: &Path, name: &str, command: &str) -> PathBuf {
    scene(dir);
    let path = dir.join("suite.toml");
    let text = format!(
        "name = \"record\"\nsize = [16, 16]\nrepeats = 1\nvariants = [\"baseline\"]\nscenes = [\"one.nff\"]\nextra_size = [16, 16]\nprofile_size = [24, 24]\nprofile_samples = 50\nhardware_repeats = 1\nhardware = false\nf64_reference = false\n\n[[tracers]]\nname = \"{name}\"\ncommand = [{command}]\nscene = \"nff\"\nimage = \"ppm\"\ntime = \"process\"\ntime_limit = 120\nrecord = true\n"
    );
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
    path
}

fn run_suite(suite: &Path, out: &Path, env: impl FnOnce(&mut Command)) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rtprof"));
    command
        .arg("suite")
        .arg(suite)
        .arg("--quick")
        .arg("-o")
        .arg(out)
        .arg("--no-pdf");
    env(&mut command);
    command
        .output()
        .unwrap_or_else(|e| panic!("cannot run rtprof: {e}"))
}

fn results(out: &Path) -> serde_json::Value {
    let text = std::fs::read(out.join("results.json")).unwrap_or_else(|e| panic!("{e}"));
    serde_json::from_slice(&text).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn without_perf_the_recording_is_a_failure_with_its_reason_and_the_suite_stands() {
    let dir = scratch("suite-no-perf");
    let bin = env!("CARGO_BIN_EXE_rtprof");
    let suite = suite(
        &dir,
        "self",
        &format!(
            "\"{bin}\", \"render\", \"{{scene}}\", \"--size\", \"{{width}}x{{height}}\", \"-o\", \"{{output}}\""
        ),
    );
    // perf is not on PATH (nothing is: the tracer is named by its absolute path), and
    // RTPROF_PERF does not name another.
    let empty = dir.join("empty-path");
    std::fs::create_dir_all(&empty).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let run = run_suite(&suite, &out, |c| {
        c.env("PATH", &empty).env_remove("RTPROF_PERF");
    });
    // The run's parts-failed exit, not bad input (2) nor a panic (101).
    assert_eq!(run.status.code(), Some(3), "{}", stderr(&run));
    let err = stderr(&run);
    assert!(err.contains("could not be recorded with perf"), "{err}");
    let r = results(&out);
    let failures = r["failures"].as_array().cloned().unwrap_or_default();
    assert_eq!(failures.len(), 1, "{failures:?}");
    assert_eq!(failures[0]["part"], "profile");
    assert_eq!(failures[0]["scene"], "one");
    let message = failures[0]["message"].as_str().unwrap_or_default();
    assert!(
        message.starts_with("tracer:self could not be recorded with perf: perf is not installed"),
        "{message}"
    );
    // The rest stands: the tracer timed beside baseline, rtprof's own profile, the
    // reports; nothing recorded is listed or left behind.
    let rows: Vec<&str> = r["scenes"][0]["variants"]
        .as_array()
        .unwrap_or_else(|| panic!("{r}"))
        .iter()
        .filter_map(|v| v["variant"].as_str())
        .collect();
    assert_eq!(rows, ["baseline", "tracer:self"]);
    assert!(
        r["profile"]["baseline"]["samples"]
            .as_u64()
            .is_some_and(|n| n > 0)
    );
    assert!(
        r.get("outside_profiles").is_none(),
        "{}",
        r["outside_profiles"]
    );
    assert!(!out.join("profile/tracer-self").exists());
    let report = std::fs::read_to_string(out.join("report.html")).unwrap_or_default();
    assert!(report.contains("could not be recorded with perf"));
    std::fs::remove_dir_all(&dir).ok();
}

/// A tracer whose time is about 90 % in `hot` by construction (the loops of
/// tests/record_common's program), writing a black binary PPM of the size asked.
const HOT_TRACER: &str = r#"
#include <stdio.h>
#include <stdlib.h>
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
    if (argc < 4) return 2;
    int w = atoi(argv[1]), h = atoi(argv[2]);
    hot(20000000);
    cold(20000000);
    FILE *f = fopen(argv[3], "wb");
    if (!f) return 1;
    fprintf(f, "P6\n%d %d\n255\n", w, h);
    for (long i = 0; i < 3L * w * h; i++) fputc(0, f);
    return fclose(f) != 0;
}
"#;

#[test]
#[ignore = "needs perf and a C compiler"]
fn a_tracer_the_suite_records_has_its_hot_function_named_in_its_profile() {
    let dir = scratch("suite-record");
    let source = dir.join("hotc.c");
    std::fs::write(&source, HOT_TRACER).unwrap_or_else(|e| panic!("{e}"));
    let exe = dir.join("hotc");
    let built = Command::new("cc")
        .args(["-O1", "-g", "-fno-omit-frame-pointer", "-o"])
        .arg(&exe)
        .arg(&source)
        .status()
        .unwrap_or_else(|e| panic!("cannot run cc: {e}"));
    assert!(built.success());
    let suite = suite(
        &dir,
        "hotc",
        &format!(
            "\"{}\", \"{{width}}\", \"{{height}}\", \"{{output}}\", \"{{scene}}\"",
            exe.display()
        ),
    );
    let out = dir.join("out");
    let run = run_suite(&suite, &out, |_| {});
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let r = results(&out);
    let p = &r["outside_profiles"][0];
    assert_eq!(p["variant"], "tracer:hotc", "{r}");
    // On the profile scene at the profile size, with the command as it ran.
    assert_eq!(p["scene"], "one");
    assert_eq!(
        (p["width"].as_u64(), p["height"].as_u64()),
        (Some(24), Some(24))
    );
    assert_eq!(p["command"][1], "24");
    assert!(p["samples"].as_u64().is_some_and(|n| n > 100), "{p}");
    // Every file listed is there.
    let files: Vec<&str> = p["files"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|f| f.as_str())
        .collect();
    for f in &files {
        assert!(out.join(f).is_file(), "{f} is listed but missing");
    }
    for key in ["flat_text", "callgraph_text", "flame_svg"] {
        let f = p["profile"][key].as_str().unwrap_or_default();
        assert!(files.contains(&f), "{key}: {f}");
    }
    // The hot function by construction: the innermost frame of most samples (`hot`,
    // or its inlined `step`), and the flat profile's first row by self time.
    let stacks = folded(&out.join("profile/tracer-hotc"), "hotc");
    let hot = share(&stacks, |s| matches!(leaf(s), "hot" | "step"));
    assert!(hot >= 0.8, "hot's share {hot}: {stacks:?}");
    let top = p["profile"]["flat"]
        .as_array()
        .unwrap()
        .iter()
        .max_by(|a, b| {
            a["percent"]
                .as_f64()
                .unwrap_or(0.0)
                .total_cmp(&b["percent"].as_f64().unwrap_or(0.0))
        })
        .unwrap_or_else(|| panic!("{p}"));
    assert!(
        matches!(top["name"].as_str(), Some("hot" | "step")),
        "{top}"
    );
    // The report's outside-tracers part names it and its files.
    let report = std::fs::read_to_string(out.join("report.html")).unwrap_or_default();
    assert!(report.contains("tracer:hotc recorded with perf on one"));
    assert!(report.contains(p["profile"]["flat_text"].as_str().unwrap_or("?")));
    // results.json reads back (its checks hold the recorded files' paths inside the
    // results directory) and rebuilds the same part.
    std::fs::remove_file(out.join("report.html")).unwrap_or_else(|e| panic!("{e}"));
    let again = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(["report", "--no-pdf"])
        .arg(out.join("results.json"))
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(again.status.success(), "{}", stderr(&again));
    let report = std::fs::read_to_string(out.join("report.html")).unwrap_or_default();
    assert!(report.contains("tracer:hotc recorded with perf on one"));
    std::fs::remove_dir_all(&dir).ok();
}
