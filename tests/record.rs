//! `rtprof record -- CMD` as a user meets it: programs rtprof did not write, profiled
//! under Linux perf. The tests that need perf (and a C compiler) are ignored in a bare
//! `cargo test`; `.ci/run` installs linux-perf and runs them with `--ignored`.

mod record_common;

use record_common::{folded, hot_program, leaf, record_json, rtprof, scratch, share, stderr};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `rtprof record FLAGS -o OUT_DIR -- EXE`.
fn record_program(flags: &[&str], out_dir: &Path, exe: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .arg("record")
        .args(flags)
        .arg("-o")
        .arg(out_dir)
        .arg("--")
        .arg(exe)
        .output()
        .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_missing_command_exits_2_and_is_named() {
    let dir = scratch("missing");
    let out = rtprof(
        &[
            "record",
            "-o",
            dir.join("r").to_str().unwrap_or_default(),
            "--",
            "rtprof-no-such-tracer",
            "scene.nff",
        ],
        &[],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("command not found: rtprof-no-such-tracer"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "one line: {err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn perf_missing_names_the_package_and_the_variable() {
    let dir = scratch("no-perf");
    let out = rtprof(
        &[
            "record",
            "-o",
            dir.join("r").to_str().unwrap_or_default(),
            "--",
            "true",
        ],
        &[("RTPROF_PERF", "/nonexistent/perf")],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("linux-perf") && err.contains("RTPROF_PERF"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// perf 6.1's refusal, word for word as it printed it on this machine when run as
/// `nobody` to attach to another user's process (perf_event_paranoid 2).
const PERF_REFUSAL: &str = "Error:
Access to performance monitoring and observability operations is limited.
Consider adjusting /proc/sys/kernel/perf_event_paranoid setting to open
access to performance monitoring and observability operations for processes
without CAP_PERFMON, CAP_SYS_PTRACE or CAP_SYS_ADMIN Linux capability.
More information can be found at 'Perf events and tool security' document:
https://www.kernel.org/doc/html/latest/admin-guide/perf-security.html
perf_event_paranoid setting is 2:
";

#[test]
fn perf_refused_names_the_setting_and_the_program_never_runs() {
    // A stand-in perf that refuses as perf does (its message, exit 255): rtprof must
    // name the setting and its value, exit 2, and never release the program.
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch("refused");
    let perf = dir.join("perf");
    std::fs::write(
        &perf,
        format!("#!/bin/sh\ncat >&2 <<'END'\n{PERF_REFUSAL}END\nexit 255\n"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    std::fs::set_permissions(&perf, std::fs::Permissions::from_mode(0o755))
        .unwrap_or_else(|e| panic!("{e}"));
    let marker = dir.join("ran");
    let out = rtprof(
        &[
            "record",
            "-o",
            dir.join("r").to_str().unwrap_or_default(),
            "--",
            "touch",
            marker.to_str().unwrap_or_default(),
        ],
        &[("RTPROF_PERF", perf.to_str().unwrap_or_default())],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let err = stderr(&out);
    let paranoid = std::fs::read_to_string("/proc/sys/kernel/perf_event_paranoid")
        .map(|s| s.trim().to_string())
        .unwrap_or_else(|_| "unreadable".into());
    assert!(
        err.contains(&format!("perf_event_paranoid is {paranoid}")) && err.contains("CAP_PERFMON"),
        "{err}"
    );
    assert!(
        !marker.exists(),
        "the program must not run when perf cannot sample it"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_command_is_required_after_the_separator() {
    let out = rtprof(&["record"], &[]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
}

#[test]
#[ignore = "needs perf"]
fn the_hot_function_of_a_c_program_takes_its_share() {
    let dir = scratch("hot");
    let exe = hot_program(&dir);
    let out_dir = dir.join("r");
    let out = record_program(&[], &out_dir, &exe);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let stacks = folded(&out_dir, "hot");
    // The leaf is `hot` or its inlined `step`, with a caller below it.
    let hot = share(&stacks, |s| ["hot", "step"].contains(&leaf(s)));
    let cold = share(&stacks, |s| leaf(s) == "cold");
    let with_caller = share(&stacks, |s| {
        s.contains("__libc_start_call_main;hot") || s.contains("main;hot")
    });
    eprintln!("hot {:.1} %, cold {:.1} %", hot * 100.0, cold * 100.0);
    assert!(hot >= 0.80, "hot {hot}: {stacks:?}");
    assert!(cold > 0.02 && cold < 0.2, "cold {cold}");
    assert!(with_caller >= 0.80, "callers found: {stacks:?}");
    assert!(
        stacks.iter().any(|s| s.0.ends_with("hot;step")),
        "the inlined step shows as its own frame: {stacks:?}"
    );
    let json = record_json(&out_dir);
    assert_eq!(json["exit_code"], 0);
    let rate = json["samples_per_cpu_second"].as_f64().unwrap_or(0.0);
    assert!(rate >= 1000.0, "{json}");
    let hot_module = &json["modules"][0];
    assert_eq!(hot_module["module"], "hot", "{json}");
    assert_eq!(hot_module["no_symbol"], 0, "{json}");
    for file in [
        "flat-hot.txt",
        "callgraph-hot.txt",
        "flame-hot.svg",
        "profile-hot.pb.gz",
    ] {
        assert!(out_dir.join(file).is_file(), "{file}");
    }
    // One run of an outside program, not one of rtprof's renders.
    for file in ["flat-hot.txt", "callgraph-hot.txt"] {
        let text = std::fs::read_to_string(out_dir.join(file)).unwrap_or_default();
        assert!(
            text.contains("1 run of the program sampled; seconds are per run"),
            "{text}"
        );
        assert!(!text.contains("render"), "{file}: {text}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf"]
fn the_processes_a_command_starts_are_sampled() {
    let dir = scratch("children");
    let exe = hot_program(&dir);
    let out_dir = dir.join("r");
    // sh runs the program as its child (twice, so that sh cannot exec it in place).
    let script = format!("{0} && {0}", exe.display());
    let out = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(["record", "-o"])
        .arg(&out_dir)
        .args(["--", "sh", "-c", &script])
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let stacks = folded(&out_dir, "sh");
    let hot = share(&stacks, |s| ["hot", "step"].contains(&leaf(s)));
    assert!(hot >= 0.80, "hot {hot}: {stacks:?}");
    assert_eq!(record_json(&out_dir)["processes"], 3);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf"]
fn no_pdf_leaves_out_report_pdf_and_removes_an_earlier_one() {
    let dir = scratch("no-pdf");
    let exe = hot_program(&dir);
    let out_dir = dir.join("r");
    let listed = |out_dir: &Path| -> Vec<String> {
        record_json(out_dir)["files"]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|f| f.as_str().map(String::from))
                    .collect()
            })
            .unwrap_or_default()
    };
    for (flags, pdf) in [(&[][..], true), (&["--no-pdf"][..], false)] {
        let out = record_program(flags, &out_dir, &exe);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        assert!(out_dir.join("report.html").is_file());
        // The second run's report.pdf would otherwise be the first run's.
        assert_eq!(out_dir.join("report.pdf").is_file(), pdf, "{flags:?}");
        let files = listed(&out_dir);
        assert!(files.iter().any(|f| f == "report.html"), "{files:?}");
        assert_eq!(files.iter().any(|f| f == "report.pdf"), pdf, "{files:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf"]
fn a_failing_command_keeps_its_profile_and_exits_4() {
    let dir = scratch("fails");
    let exe = hot_program(&dir);
    for (arg, code, signal, says) in [
        ("3", Some(3), None, "exited with code 3"),
        ("segv", None, Some(11), "SIGSEGV"),
    ] {
        let out_dir = dir.join(arg);
        let out = Command::new(env!("CARGO_BIN_EXE_rtprof"))
            .args(["record", "-o"])
            .arg(&out_dir)
            .arg("--")
            .arg(&exe)
            .arg(arg)
            .output()
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(out.status.code(), Some(4), "{}", stderr(&out));
        assert!(stderr(&out).contains(says), "{}", stderr(&out));
        let json = record_json(&out_dir);
        assert_eq!(json["exit_code"].as_i64(), code.map(i64::from), "{json}");
        assert_eq!(json["signal"].as_i64(), signal.map(i64::from), "{json}");
        assert_eq!(json["success"], false);
        let stacks = folded(&out_dir, "hot");
        assert!(share(&stacks, |s| ["hot", "step"].contains(&leaf(s))) >= 0.8);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf"]
fn rtprof_render_as_an_outside_program_shows_its_intersection_tests() {
    let dir = scratch("own");
    let out_dir = dir.join("r");
    let image = dir.join("rings.png");
    let out = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(["record", "--call-graph", "dwarf", "-o"])
        .arg(&out_dir)
        .args([
            "--",
            env!("CARGO_BIN_EXE_rtprof"),
            "render",
            "spd:rings",
            "--threads",
            "1",
        ])
        .args(["--size", "40x30", "-o"])
        .arg(&image)
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(image.is_file());
    let stacks = folded(&out_dir, "rtprof");
    // Each sample to the innermost intersection test on its stack, inlined frames
    // included.
    let kind = |s: &str| {
        s.split(';')
            .rev()
            .find_map(|f| {
                if f.contains("Cylinder::intersect") {
                    Some("cylinder")
                } else if f.contains("Sphere::intersect") {
                    Some("sphere")
                } else {
                    None
                }
            })
            .unwrap_or("other")
    };
    let cylinder = share(&stacks, |s| kind(s) == "cylinder");
    let sphere = share(&stacks, |s| kind(s) == "sphere");
    eprintln!(
        "cylinder {:.1} %, sphere {:.1} %",
        cylinder * 100.0,
        sphere * 100.0
    );
    // SPD rings: as many cylinders as spheres, and a cylinder test costs about twice
    // a sphere test (rtprof profile's phases: 66 % and 33 % at 96x72).
    assert!(cylinder > sphere && sphere > 0.1, "{stacks:?}");
    assert!(
        stacks
            .iter()
            .any(|s| s.0.contains("main") && kind(&s.0) == "cylinder"),
        "DWARF unwinding reaches main"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A phase's self share (percent) in a gprof-layout flat profile: the first row, of
/// the table with shares first, whose name is `phase`.
fn flat_share(text: &str, phase: &str) -> f64 {
    text.lines()
        .filter(|l| l.trim_end().ends_with(&format!("  {phase}")))
        .find_map(|l| l.split_whitespace().next()?.parse::<f64>().ok())
        .unwrap_or(0.0)
}

#[test]
#[ignore = "needs perf"]
fn the_phase_rules_agree_with_rtprof_s_own_phases() {
    // rtprof render as an outside program: by the built-in rules (innermost matching
    // frame, inlined frames included), its sphere- and cylinder-test shares within 5
    // points of `rtprof profile`'s phases (the tracer's own phase probe) on the same
    // render. The BVH variant: its traversal is a phase of its own in both views.
    let dir = scratch("phases");
    let render = [
        "spd:rings",
        "--variant",
        "bvh",
        "--threads",
        "1",
        "--size",
        "480x360",
    ];
    let out_dir = dir.join("r");
    let out = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(["record", "--call-graph", "dwarf", "-o"])
        .arg(&out_dir)
        .args(["--", env!("CARGO_BIN_EXE_rtprof"), "render"])
        .args(render)
        .arg("-o")
        .arg(dir.join("rings.png"))
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json = record_json(&out_dir);
    let rules = |phase: &str| {
        json["phases"]["phases"]
            .as_array()
            .and_then(|a| a.iter().find(|p| p["phase"] == phase))
            .and_then(|p| p["share"].as_f64())
            .unwrap_or(0.0)
            * 100.0
    };
    let profile_dir = dir.join("p");
    let mut args = vec!["profile"];
    args.extend(render);
    let profile_dir_text = profile_dir.display().to_string();
    args.extend(["-o", &profile_dir_text]);
    let out = rtprof(&args, &[]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let flat =
        std::fs::read_to_string(profile_dir.join("flat-bvh.txt")).unwrap_or_else(|e| panic!("{e}"));
    for phase in ["cylinder test", "sphere test"] {
        let (by_rules, own) = (rules(phase), flat_share(&flat, phase));
        eprintln!("{phase}: rules {by_rules:.1} %, rtprof profile {own:.1} %");
        assert!(
            (by_rules - own).abs() <= 5.0,
            "{phase}: rules {by_rules:.1} % against {own:.1} %\n{flat}"
        );
    }
    // The cylinder test is most of the tests' time (as many cylinders as spheres, and
    // the rays reach the cylinders): not a pass by two zeros.
    assert!(rules("cylinder test") > 5.0, "{json}");
    let phases = std::fs::read_to_string(out_dir.join("phases-rtprof.txt"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(phases.contains("rules classified"), "{phases}");
    let report =
        std::fs::read_to_string(out_dir.join("report.html")).unwrap_or_else(|e| panic!("{e}"));
    assert!(report.contains("Where the time goes in rtprof"));
    assert!(out_dir.join("report.pdf").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_bad_phase_rules_file_is_refused_before_the_program_runs() {
    // Read before perf is looked for: no perf needed.
    let dir = scratch("bad-rules");
    let rules = dir.join("rules.toml");
    std::fs::write(&rules, "[[rule]]\nphase = \"x\"\nsymbol = ['(']\n")
        .unwrap_or_else(|e| panic!("{e}"));
    let marker = dir.join("ran");
    let out = rtprof(
        &[
            "record",
            "--phases",
            &rules.display().to_string(),
            "--",
            "touch",
            &marker.display().to_string(),
        ],
        &[],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains(&format!("{}:3: bad pattern", rules.display())),
        "{}",
        stderr(&out)
    );
    assert!(!marker.exists(), "the program must not run");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf and tachyon (Debian tachyon-bin-nox)"]
fn tachyon_s_renderer_is_named_as_a_library_without_symbols() {
    let dir = scratch("tachyon");
    let out_dir = dir.join("r");
    let balls = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/spd/balls.nff");
    let out = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(["record", "-o"])
        .arg(&out_dir)
        .args(["--", "tachyon"])
        .arg(&balls)
        .args([
            "-numthreads",
            "1",
            "-res",
            "96",
            "96",
            "-format",
            "PPM",
            "-o",
        ])
        .arg(dir.join("t.ppm"))
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json = record_json(&out_dir);
    let modules = json["modules"].as_array().cloned().unwrap_or_default();
    // Debian's Tachyon renders in libtachyon-mt-*.so, which exports only its rt_* API.
    let lib = modules
        .iter()
        .find(|m| {
            m["module"]
                .as_str()
                .is_some_and(|n| n.starts_with("libtachyon"))
        })
        .unwrap_or_else(|| panic!("no libtachyon module: {json}"));
    let samples = lib["samples"].as_f64().unwrap_or(0.0);
    let total = json["samples"].as_f64().unwrap_or(1.0);
    assert!(
        samples / total > 0.5,
        "the renderer's library holds most samples: {json}"
    );
    assert!(
        lib["no_symbol"].as_f64().unwrap_or(0.0) / samples > 0.9,
        "{lib}"
    );
    assert!(
        lib["advice"][0].as_str().is_some_and(|a| a.contains("-g")),
        "{lib}"
    );
    assert!(stderr(&out).contains("libtachyon"), "the summary names it");
    // The report renders, names the library and its share without symbols.
    let report =
        std::fs::read_to_string(out_dir.join("report.html")).unwrap_or_else(|e| panic!("{e}"));
    let no_symbol = 100.0 * lib["no_symbol"].as_f64().unwrap_or(0.0) / samples;
    let module = lib["module"].as_str().unwrap_or("?");
    assert!(report.contains(module), "report.html names {module}");
    assert!(
        report.contains(&format!("{no_symbol:.1} %")),
        "report.html gives {no_symbol:.1} % without symbols"
    );
    assert!(out_dir.join("report.pdf").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf"]
fn ctrl_c_stops_the_program_and_keeps_what_was_sampled() {
    use std::os::unix::process::CommandExt;
    let dir = scratch("ctrl-c");
    let out_dir = dir.join("r");
    // In a process group of its own, as a shell runs a foreground job: Ctrl-C is
    // SIGINT to the whole group (rtprof and the program; perf has its own group).
    let child = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(["record", "-o"])
        .arg(&out_dir)
        .args(["--", "sh", "-c", "while :; do :; done"])
        .process_group(0)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("{e}"));
    // Until perf runs (its file exists) and the program has run a while: on a busy
    // machine rtprof itself may take a second to start, and perf another to attach
    // (one run in six failed here with a one-second wait while other tests ran).
    let started = std::time::Instant::now();
    while !out_dir.join("perf.data").is_file() && started.elapsed().as_secs() < 30 {
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    std::thread::sleep(std::time::Duration::from_millis(3000));
    let group = format!("-{}", child.id());
    let status = Command::new("kill")
        .args(["-INT", "--", &group])
        .status()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(status.success());
    let out = child.wait_with_output().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.status.code(), Some(130), "{}", stderr(&out));
    assert!(stderr(&out).contains("interrupted"), "{}", stderr(&out));
    let json = record_json(&out_dir);
    assert!(json["samples"].as_u64().unwrap_or(0) > 100, "{json}");
    assert!(out_dir.join("flame-sh.svg").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf"]
fn a_baseline_record_gives_the_differential_flamegraphs() {
    let dir = scratch("baseline");
    let exe = hot_program(&dir);
    let (before, after) = (dir.join("before"), dir.join("after"));
    let exe_text = exe.display().to_string();
    for (out_dir, baseline) in [(&before, None), (&after, Some(&before))] {
        let mut args = vec![
            "record".to_string(),
            "-o".into(),
            out_dir.display().to_string(),
        ];
        if let Some(b) = baseline {
            args.extend(["--baseline".into(), b.display().to_string()]);
        }
        args.extend(["--".into(), exe_text.clone(), "0".into()]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = rtprof(&args, &[]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    }
    let json = record_json(&after);
    let files: Vec<&str> = json["files"]
        .as_array()
        .map(|a| a.iter().filter_map(|f| f.as_str()).collect())
        .unwrap_or_default();
    for file in [
        "flame-diff-before-after.svg",
        "flame-diff-before-after-shrunk.svg",
    ] {
        assert!(files.contains(&file), "{file} in {files:?}");
        let svg = std::fs::read_to_string(after.join(file)).unwrap_or_else(|e| panic!("{e}"));
        // The same program twice: both drawings name its hot function, per run.
        assert!(svg.contains("hot") && svg.contains("per run"), "{file}");
    }
    // A directory that is no record: refused before the program runs.
    let out = rtprof(
        &[
            "record",
            "--baseline",
            &dir.display().to_string(),
            "--",
            &exe_text,
            "0",
        ],
        &[],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("folded-*.txt"), "{}", stderr(&out));
    std::fs::remove_dir_all(&dir).ok();
}
