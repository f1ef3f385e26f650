//! Outside tracers as variants of `rtprof compare` (docs/tracers.md), as a user meets
//! them: rtprof's own binary run as an outside program (a real renderer whose picture
//! must equal the built-in variant's), programs that fail each way a run can, and a
//! definition that cannot be used.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rtprof(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run rtprof: {e}"))
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-outside-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

/// A small lit sphere (8 x 8 by default).
fn scene(dir: &Path) -> String {
    let path = dir.join("one.nff");
    std::fs::write(
        &path,
        "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 8 8\nl 2 3 -6\nf 1 0.5 0 1 0 1 0 1\ns 0 0 0 1.5\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    path.display().to_string()
}

/// Writes a definition named `name` whose command is `command` (TOML array items).
fn definition(dir: &Path, name: &str, command: &str, extra: &str) -> String {
    let path = dir.join(format!("{name}.toml"));
    let text = format!(
        "name = \"{name}\"\ncommand = [{command}]\nscene = \"nff\"\nimage = \"png\"\ntime = \"process\"\n{extra}"
    );
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
    path.display().to_string()
}

/// rtprof's own renderer as an outside program, drawing `{scene}` into `{output}`.
fn rtprof_as_tracer(dir: &Path, name: &str, extra: &str) -> String {
    let bin = env!("CARGO_BIN_EXE_rtprof");
    definition(
        dir,
        name,
        &format!(
            "\"{bin}\", \"render\", \"{{scene}}\", \"--size\", \"{{width}}x{{height}}\", \"--threads\", \"{{threads}}\", \"-o\", \"{{output}}\""
        ),
        extra,
    )
}

fn json(out: &Output) -> serde_json::Value {
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stdout)))
}

#[test]
fn an_outside_renderer_is_a_row_with_its_definition_and_its_picture_judged() {
    let dir = scratch("self");
    let scene = scene(&dir);
    let tracer = rtprof_as_tracer(&dir, "self", "");
    let images = dir.join("images");
    let out = rtprof(&[
        "compare",
        &scene,
        "--variants",
        "baseline,bvh",
        "--tracer",
        &tracer,
        "--repeats",
        "2",
        "--json",
        "-o",
        &images.display().to_string(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json = json(&out);
    let rows = json["variants"].as_array().cloned().unwrap_or_default();
    assert_eq!(rows.len(), 3, "{json}");
    let row = &rows[2];
    assert_eq!(row["name"], "tracer:self");
    // The NFF rtprof wrote for it parses to the same scene, and its renderer is
    // the baseline's: the same picture, bit for bit.
    assert_eq!(row["rms"], 0.0, "{row}");
    assert_eq!(row["max_abs_diff"], 0);
    // Timed like the variants (two runs at least), against the same reference.
    assert!(row["seconds"]["median"].as_f64().is_some_and(|s| s > 0.0));
    assert!(row["verdict"].is_string());
    // Its definition and the program that ran are recorded.
    let outside = &row["outside"];
    assert!(
        outside["definition"]
            .as_str()
            .is_some_and(|f| f.ends_with("self.toml"))
    );
    assert_eq!(outside["scene_format"], "nff");
    assert_eq!(outside["command"][1], "render");
    assert_eq!(outside["time_covers"], "the whole process");
    let program = outside["program"]["path"].as_str().unwrap_or_default();
    assert!(Path::new(program).ends_with("rtprof"), "{program}");
    assert!(outside["program"]["bytes"].as_u64().is_some_and(|b| b > 0));
    // An outside program counts nothing without the probe.
    assert!(row.get("counts").is_none(), "{row}");
    assert!(images.join("tracer-self.png").is_file());
    assert!(images.join("tracer-self-diff.png").is_file());
    assert!(images.join("tracers/self/scene.nff").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_failing_tracer_is_recorded_with_its_reason_and_the_others_stand() {
    let dir = scratch("failures");
    let scene = scene(&dir);
    let good = rtprof_as_tracer(&dir, "good", "");
    let sh = |name: &str, script: &str, extra: &str| {
        definition(
            &dir,
            name,
            &format!("\"sh\", \"-c\", '''{script}''', \"sh\", \"{{scene}}\", \"{{output}}\""),
            extra,
        )
    };
    let exits = sh("exits", "echo 'no licence for this scene' >&2; exit 1", "");
    let hangs = sh("hangs", "sleep 30", "time_limit = 0.5\n");
    // A real PNG of the scene, cut in half.
    let bin = env!("CARGO_BIN_EXE_rtprof");
    let truncated = sh(
        "truncated",
        &format!("{bin} render $1 -o $2.full.png && head -c 60 $2.full.png > $2"),
        "",
    );
    let missing = definition(
        &dir,
        "missing",
        "\"no-such-renderer-rtprof\", \"{scene}\", \"{output}\"",
        "",
    );
    let started = std::time::Instant::now();
    let mut args = vec![
        "compare",
        &scene,
        "--variants",
        "baseline",
        "--repeats",
        "2",
        "--json",
    ];
    for t in [&exits, &good, &hangs, &truncated, &missing] {
        args.extend(["--tracer", t.as_str()]);
    }
    let out = rtprof(&args);
    // Parts failed: exit 3, the table written, one line on stderr.
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("4 outside tracers failed"),
        "{}",
        stderr(&out)
    );
    assert!(
        started.elapsed().as_secs() < 25,
        "the hang was not stopped at its limit"
    );
    let json = json(&out);
    let rows = json["variants"].as_array().cloned().unwrap_or_default();
    let names: Vec<&str> = rows.iter().filter_map(|r| r["name"].as_str()).collect();
    assert_eq!(names, ["baseline", "tracer:good"]);
    assert_eq!(rows[1]["rms"], 0.0);
    let failed = json["failed"].as_array().cloned().unwrap_or_default();
    let kinds: Vec<(&str, &str)> = failed
        .iter()
        .map(|f| {
            (
                f["name"].as_str().unwrap_or_default(),
                f["failure"]["kind"].as_str().unwrap_or_default(),
            )
        })
        .collect();
    assert_eq!(
        kinds,
        [
            ("tracer:exits", "exited"),
            ("tracer:hangs", "timed_out"),
            ("tracer:truncated", "bad_image"),
            ("tracer:missing", "not_found"),
        ]
    );
    // Each says why, and what the program said last.
    assert_eq!(
        failed[0]["failure"]["stderr_tail"][0],
        "no licence for this scene"
    );
    assert!(
        failed[1]["failure"]["reason"]
            .as_str()
            .unwrap_or_default()
            .contains("0.5 s")
    );
    assert!(
        failed[3]["failure"]["reason"]
            .as_str()
            .unwrap_or_default()
            .contains("no-such-renderer-rtprof")
    );

    // The text form prints the table, then each failure.
    let pos = args.iter().position(|a| *a == "--json").unwrap_or(0);
    args.remove(pos);
    let out = rtprof(&args);
    assert_eq!(out.status.code(), Some(3));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("tracer:exits failed: sh exited with code 1"),
        "{text}"
    );
    assert!(text.contains("no licence for this scene"), "{text}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_definition_that_cannot_be_used_is_bad_input_naming_its_line() {
    let dir = scratch("bad-definition");
    let scene = scene(&dir);
    let bad = definition(&dir, "bad", "\"sh\", \"{scene}\", \"{outptu}\"", "");
    let out = rtprof(&[
        "compare",
        &scene,
        "--variants",
        "baseline",
        "--tracer",
        &bad,
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("bad.toml:2:"), "{err}");
    assert!(err.contains("unknown placeholder {outptu}"), "{err}");
    // Two definitions with one name.
    let a = rtprof_as_tracer(&dir, "twice", "");
    let out = rtprof(&[
        "compare",
        &scene,
        "--variants",
        "baseline",
        "--tracer",
        &a,
        "--tracer",
        &a,
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("also"), "{}", stderr(&out));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs tachyon"]
fn tachyon_the_built_in_peer_renders_an_spd_scene_beside_rtprof() {
    let spd = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/spd/tetra.nff");
    assert!(spd.is_file(), "shared/ must sit beside the project");
    let out = rtprof(&[
        "compare",
        &spd.display().to_string(),
        "--spd",
        "--size",
        "64x64",
        "--variants",
        "bvh",
        "--tracer",
        "tachyon",
        "--repeats",
        "3",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json = json(&out);
    let row = &json["variants"][1];
    assert_eq!(row["name"], "tracer:tachyon");
    // Its own printout's tracing time, read from each of its runs.
    assert!(
        row["seconds"]["median"]
            .as_f64()
            .is_some_and(|s| s > 0.0 && s < 5.0),
        "{row}"
    );
    assert!(
        row["outside"]["time_covers"]
            .as_str()
            .unwrap_or_default()
            .contains("Ray Tracing Time")
    );
    let program = &row["outside"]["program"];
    // Debian's `tachyon` is an alternative for tachyon-nox: the file itself is recorded.
    let path = program["path"].as_str().unwrap_or_default();
    assert!(path.starts_with("/usr/bin/tachyon"), "{path}");
    assert!(
        program["build_id"]
            .as_str()
            .is_some_and(|id| id.len() >= 16),
        "{program}"
    );
    // Same scene and frame: judged against rtprof's picture.
    assert!(row["rms"].as_f64().is_some(), "{row}");
}

/// RTIOW (../shared/peers/rtiow) built with the probe by scripts/rtiow-probe.sh, into a
/// fresh directory; its path.
fn build_rtiow(dir: &Path) -> PathBuf {
    let out = Command::new("bash")
        .arg(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scripts/rtiow-probe.sh"))
        .arg(dir)
        .arg("probe")
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    PathBuf::from(String::from_utf8_lossy(&out.stdout).trim())
}

#[test]
#[ignore = "needs g++ and ../shared/peers/rtiow"]
fn a_path_tracers_noise_falls_with_its_samples_per_pixel() {
    let dir = scratch("rtiow");
    let rtiow = build_rtiow(&dir.join("build"));
    let def = dir.join("rtiow.toml");
    std::fs::write(
        &def,
        format!(
            "name = \"rtiow\"\ncommand = [\"{}\", \"{{spp}}\", \"{{width}}\"]\nscene = \"own\"\nimage = \"ppm\"\noutput = \"stdout\"\ntime = \"process\"\ndeterministic = false\nconverged_spp = 256\n",
            rtiow.display()
        ),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let (width, height) = (160u64, 90u64);
    let mut noise = Vec::new();
    for spp in [4u64, 16] {
        let out = rtprof(&[
            "compare",
            "one-sphere",
            "--size",
            &format!("{width}x{height}"),
            "--variants",
            "baseline",
            "--tracer",
            &def.display().to_string(),
            "--spp",
            &spp.to_string(),
            "--repeats",
            "2",
            "--json",
        ]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let json = json(&out);
        let row = &json["variants"][1];
        // Its own probe counts one eye ray per sample: exact.
        assert_eq!(
            row["counts"]["rays"]["primary"],
            width * height * spp,
            "{row}"
        );
        let n = &row["outside"]["noise"];
        assert_eq!(n["converged_spp"], 256);
        let rel_mse = n["rel_mse"].as_f64().unwrap_or(f64::NAN);
        let efficiency = n["efficiency"].as_f64().unwrap_or(f64::NAN);
        let seconds = row["seconds"]["median"].as_f64().unwrap_or(f64::NAN);
        // Efficiency is 1 / (relMSE × time), by its definition.
        assert!((efficiency * rel_mse * seconds - 1.0).abs() < 1e-9, "{n}");
        println!(
            "rtiow {spp} spp: relMSE {rel_mse:.4}, efficiency {efficiency:.1}, {seconds:.3} s"
        );
        noise.push(rel_mse);
    }
    // Variance falls as 1/spp; the converged run's own noise (1/256) is in both:
    // (1/4 + 1/256) / (1/16 + 1/256) = 3.82.
    let ratio = noise[0] / noise[1];
    println!("rtiow relMSE 4 spp / 16 spp: {ratio:.2}");
    assert!((3.0..=5.0).contains(&ratio), "{ratio}");
    std::fs::remove_dir_all(&dir).ok();
}
