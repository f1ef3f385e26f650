//! `rtprof suite --shard I/N` and `rtprof merge`: two shards merged give the same
//! scenes, variants and counts as one unsharded run; bad shards and parts are refused.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn rtprof(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run rtprof: {e}"))
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs rtprof and insists on exit 0.
fn ok(args: &[&str]) -> Output {
    let out = rtprof(args);
    assert!(
        out.status.success(),
        "rtprof {args:?} failed: {}",
        stderr(&out)
    );
    out
}

/// A scratch directory unique to one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-shard-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

/// A tiny suite: three built-in scenes, baseline and bvh, 32x24.
const SUITE: &str = r#"
name = "tiny"
size = [32, 24]
repeats = 1
min_seconds = 0.0
variants = ["baseline", "bvh"]
scenes = ["balls1", "cylinder2", "both3"]
extra_size = [32, 24]
profile_size = [32, 24]
profile_frequency = 1000
profile_samples = 50
hardware_repeats = 1
"#;

fn read(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// (scene, [(variant, counts)]) in file order.
fn scenes_variants_counts(results: &Value) -> Vec<(String, Vec<(String, Value)>)> {
    let scenes = results["scenes"].as_array().expect("scenes");
    scenes
        .iter()
        .map(|s| {
            let variants = s["variants"].as_array().expect("variants");
            let variants = variants
                .iter()
                .map(|v| (v["variant"].to_string(), v["counts"].clone()))
                .collect();
            (s["name"].as_str().expect("name").to_string(), variants)
        })
        .collect()
}

fn p(path: &Path) -> String {
    path.display().to_string()
}

#[test]
fn two_shards_merged_equal_the_unsharded_run() {
    let dir = scratch("merge");
    let suite = dir.join("suite.toml");
    std::fs::write(&suite, SUITE).unwrap();
    let (whole, one, two, merged) = (
        dir.join("whole"),
        dir.join("part-1"),
        dir.join("part-2"),
        dir.join("merged"),
    );
    // The parts' PDFs are not what this test checks; the merge's is.
    ok(&["suite", &p(&suite), "-o", &p(&whole), "--no-pdf"]);
    ok(&[
        "suite",
        &p(&suite),
        "--shard",
        "1/2",
        "-o",
        &p(&one),
        "--no-pdf",
    ]);
    ok(&[
        "suite",
        &p(&suite),
        "--shard",
        "2/2",
        "-o",
        &p(&two),
        "--no-pdf",
    ]);

    // Shard 1 holds positions 0 and 2, shard 2 position 1; each says which it is.
    let names = |v: &Value| -> Vec<String> {
        scenes_variants_counts(v)
            .into_iter()
            .map(|(n, _)| n)
            .collect()
    };
    let (r1, r2) = (
        read(&one.join("results.json")),
        read(&two.join("results.json")),
    );
    assert_eq!(names(&r1), ["balls1", "both3"]);
    assert_eq!(names(&r2), ["cylinder2"]);
    assert_eq!(
        r1["suite"]["shard"],
        serde_json::json!({"index": 1, "count": 2})
    );
    assert_eq!(
        r2["suite"]["shard"],
        serde_json::json!({"index": 2, "count": 2})
    );

    // A part may be a directory or its results.json, in any order.
    let out = ok(&[
        "merge",
        &p(&two.join("results.json")),
        &p(&one),
        "-o",
        &p(&merged),
    ]);
    assert!(
        stderr(&out).contains("merged shards 1/2, 2/2: 3 scenes × 2 variants"),
        "{}",
        stderr(&out)
    );
    let (w, m) = (
        read(&whole.join("results.json")),
        read(&merged.join("results.json")),
    );
    let expected = scenes_variants_counts(&w);
    assert_eq!(expected.len(), 3);
    assert!(
        expected
            .iter()
            .all(|(_, v)| v.len() == 2 && v.iter().all(|(_, c)| c["rays.primary"] == 32 * 24))
    );
    assert_eq!(scenes_variants_counts(&m), expected);
    assert_eq!(m["suite"]["variants"], w["suite"]["variants"]);
    assert!(m["suite"]["shard"].is_null());
    assert!(m["profile"].is_object(), "the merged run has no profile");
    for f in ["report.html", "report.pdf"] {
        assert!(merged.join(f).is_file(), "{f}");
    }

    // Every file the merged results reference is in the merged directory.
    let mut referenced = Vec::new();
    for scene in m["scenes"].as_array().unwrap() {
        for v in scene["variants"].as_array().unwrap() {
            referenced.extend(v["image"].as_str().map(str::to_string));
            referenced.extend(v["heat_map"].as_str().map(str::to_string));
        }
        referenced.extend(
            scene["hardware"]["emulator_image"]
                .as_str()
                .map(str::to_string),
        );
    }
    referenced.extend(
        m["profile"]["baseline"]["flame_svg"]
            .as_str()
            .map(str::to_string),
    );
    // Per scene: two images, bvh's heat map, the emulator's image; and the flamegraph.
    assert_eq!(referenced.len(), 3 * 4 + 1, "{referenced:?}");
    for rel in &referenced {
        assert!(merged.join(rel).is_file(), "{rel} is missing");
    }

    // One shard alone merges with a warning; a whole run is not a shard.
    let out = ok(&["merge", &p(&one), "-o", &p(&dir.join("half")), "--no-pdf"]);
    assert!(
        stderr(&out).contains("warning: shard 2/2 missing"),
        "{}",
        stderr(&out)
    );
    let out = rtprof(&["merge", &p(&one), &p(&whole), "-o", &p(&dir.join("bad"))]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("is not a shard"), "{}", stderr(&out));
    assert_eq!(stderr(&out).lines().count(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_shards_are_one_line_errors_with_exit_2() {
    let dir = scratch("bad");
    let suite = dir.join("suite.toml");
    std::fs::write(&suite, SUITE).unwrap();
    for (shard, says) in [
        ("0/2", "the index must be 1 to 2"),
        ("3/2", "the index must be 1 to 2"),
        ("x", "'x' is not a shard I/N"),
        ("1/1001", "the count must be 1 to 1000"),
        // Three scenes cannot fill four shards.
        ("4/4", "shard 4/4 holds no scene: the suite has 3 scenes"),
    ] {
        let out = rtprof(&[
            "suite",
            &p(&suite),
            "--shard",
            shard,
            "-o",
            &p(&dir.join("out")),
        ]);
        assert_eq!(out.status.code(), Some(2), "{shard}: {}", stderr(&out));
        let text = stderr(&out);
        assert_eq!(text.lines().count(), 1, "{shard}: {text}");
        assert!(text.contains(says), "{shard}: {text}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The timed renders' threads: one when neither the definition (the tiny suite has no
/// `timing_threads`) nor the command line says, as many as `--threads` asks otherwise;
/// recorded as `suite.threads`, the machine's peak measured on the same threads (the
/// roof the timed renders are set under), and said so in summary.md.
#[test]
fn the_timed_renders_run_on_one_thread_unless_asked() {
    let dir = scratch("timed-threads");
    let suite = dir.join("suite.toml");
    std::fs::write(&suite, SUITE).unwrap();
    for (asked, expected, says) in [
        (None, 1, "timed on 1 thread"),
        (Some("2"), 2, "timed on 2 threads"),
    ] {
        let out = dir.join(format!("out-{expected}"));
        let (suite_arg, out_arg) = (p(&suite), p(&out));
        let mut args = vec!["suite", &suite_arg, "-o", &out_arg, "--no-pdf"];
        if let Some(n) = asked {
            args.extend(["--threads", n]);
        }
        ok(&args);
        let r = read(&out.join("results.json"));
        assert_eq!(r["suite"]["threads"], expected, "{asked:?}");
        assert_eq!(r["peak"]["threads"], expected, "{asked:?}");
        let summary = std::fs::read_to_string(out.join("summary.md")).unwrap();
        assert!(summary.contains(says), "{asked:?}: {summary}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
