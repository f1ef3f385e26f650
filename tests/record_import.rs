//! `rtprof record --import FILE`: a recording made elsewhere — by `perf record` run
//! directly, or GNU gprof's text output of a `-pg` build — read into rtprof's files.
//! The tests that need perf or gprof (and a C compiler) are ignored in a bare `cargo
//! test`; `.ci/run` runs them with `--ignored`. Bad input needs neither.

mod record_common;

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};

use analysis::profile::gprof_import;
use record_common::{folded, hot_program, leaf, record_json, rtprof, scratch, share, stderr};

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// `rtprof record --import FILE -o DIR` with `env` set.
fn import(file: &Path, dir: &Path, env: &[(&str, &str)]) -> Output {
    rtprof(
        &[
            "record",
            "--import",
            file.to_str().unwrap_or_default(),
            "-o",
            dir.to_str().unwrap_or_default(),
        ],
        env,
    )
}

fn run(command: &mut Command) -> Output {
    let out = command
        .output()
        .unwrap_or_else(|e| panic!("cannot run {command:?}: {e}"));
    assert!(out.status.success(), "{command:?}: {}", stderr(&out));
    out
}

#[test]
fn what_is_no_recording_exits_2_naming_the_file() {
    let dir = scratch("import-bad");
    let cases: [(&str, &[u8], &str); 5] = [
        ("empty", b"", "the file is empty"),
        (
            "notes.txt",
            b"Some notes.\nNot gprof's output.\n",
            "not a perf.data file or gprof output",
        ),
        // perf's magic, then not a header: cut short
        ("short.data", b"PERFILE2\x68\0\0\0", "truncated"),
        // perf's magic, then 200 bytes of text where the header's sizes should be
        (
            "garbage.data",
            &[b"PERFILE2".as_slice(), &[b'x'; 200]].concat(),
            "damaged header",
        ),
        (
            "gmon.out",
            b"gmon\x01\0\0\0\0\0\0\0",
            "gprof -b PROG gmon.out",
        ),
    ];
    for (name, bytes, says) in cases {
        let file = dir.join(name);
        std::fs::write(&file, bytes).unwrap_or_else(|e| panic!("{e}"));
        let out = import(&file, &dir.join("out"), &[]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(&file.display().to_string()), "{name}: {err}");
        assert!(err.contains(says), "{name}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "one line: {err}");
    }
    assert!(!dir.join("out").exists(), "nothing written");
    let missing = dir.join("no-such.data");
    let out = import(&missing, &dir.join("out"), &[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("no-such.data"), "{}", stderr(&out));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn import_and_a_command_exclude_each_other() {
    for args in [
        &["record", "--import", "perf.data", "--", "true"][..],
        &["record", "--import", "perf.data", "--freq", "100"][..],
        &["record", "-o", "x"][..],
    ] {
        let out = rtprof(args, &[]);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).contains("usage:"),
            "{args:?}: {}",
            stderr(&out)
        );
    }
}

/// A C program whose functions are called a known number of times: main calls f 1,000
/// times, f calls g every 27th time (37 times: i % 27 == 26 for i < 1,000) and leaf
/// every time, h calls g 5 times, g calls leaf once (1,042 calls of leaf), and r
/// calls itself 10 times below main's one call. leaf does the work.
const COUNTED: &str = r#"
static volatile unsigned long sink;
static volatile int depth;
__attribute__((noinline)) void leaf(long n) {
    unsigned long x = sink;
    for (long i = 0; i < n; i++) x = x * 6364136223846793005UL + 1;
    sink = x;
}
__attribute__((noinline)) void g(void) { leaf(20000); }
__attribute__((noinline)) void f(int i) {
    if (i % 27 == 26) g();
    leaf(200000);
}
__attribute__((noinline)) void h(void) { for (int i = 0; i < 5; i++) g(); }
__attribute__((noinline)) void r(int n) { if (n > 0) { r(n - 1); depth++; } }
int main(void) {
    for (int i = 0; i < 1000; i++) f(i);
    h();
    r(10);
    return 0;
}
"#;

/// Calls of each function by construction (`r`: main's one, not its own 10).
const CALLS: [(&str, u64); 5] = [("f", 1000), ("g", 42), ("h", 1), ("leaf", 1042), ("r", 1)];
/// Calls along each arc by construction.
const ARCS: [(&str, &str, u64); 8] = [
    ("main", "f", 1000),
    ("main", "h", 1),
    ("main", "r", 1),
    ("f", "g", 37),
    ("f", "leaf", 1000),
    ("h", "g", 5),
    ("g", "leaf", 42),
    ("r", "r", 10),
];

/// Calls per function in rtprof's flat text: the table's `calls` column and the rows
/// below the noise floor (`calls  name`).
fn flat_calls(text: &str) -> BTreeMap<String, u64> {
    let mut calls = BTreeMap::new();
    for line in text.lines() {
        let tokens: Vec<&str> = line.split_whitespace().collect();
        let (count, name) = match tokens.as_slice() {
            // %, cumulative, self, calls, self/call, total/call, name
            [_, _, _, count, _, _, name] => (count, name),
            [count, name] => (count, name),
            _ => continue,
        };
        if let Ok(n) = count.parse::<u64>() {
            calls.insert((*name).to_string(), n);
        }
    }
    calls
}

#[test]
#[ignore = "needs gprof"]
fn gprof_s_exact_call_counts_come_through() {
    let dir = scratch("import-gprof");
    let source = dir.join("counted.c");
    std::fs::write(&source, COUNTED).unwrap_or_else(|e| panic!("{e}"));
    let exe = dir.join("counted");
    run(Command::new("cc")
        .args(["-O1", "-pg", "-fno-inline", "-o"])
        .arg(&exe)
        .arg(&source));
    // gmon.out goes to the working directory.
    run(Command::new(&exe).current_dir(&dir));
    for (flags, stem) in [(&["-b"][..], "brief"), (&[][..], "full")] {
        let out = run(Command::new("gprof")
            .args(flags)
            .arg(&exe)
            .arg(dir.join("gmon.out")));
        let text_file = dir.join(format!("{stem}.txt"));
        std::fs::write(&text_file, &out.stdout).unwrap_or_else(|e| panic!("{e}"));
        let out_dir = dir.join(format!("r-{stem}"));
        let out = import(&text_file, &out_dir, &[]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        assert!(
            stdout(&out).contains("calls counted by -pg"),
            "{}",
            stdout(&out)
        );

        let flat = std::fs::read_to_string(out_dir.join(format!("flat-{stem}.txt")))
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(flat.contains("Read from gprof's output"), "{flat}");
        let found = flat_calls(&flat);
        for (name, calls) in CALLS {
            assert_eq!(found.get(name), Some(&calls), "{name} in\n{flat}");
        }

        let graph_text = std::fs::read_to_string(out_dir.join(format!("callgraph-{stem}.txt")))
            .unwrap_or_else(|e| panic!("{e}"));
        // rtprof's text of gprof's graph is in gprof's layout: gprof's reader reads it.
        let graph = gprof_import::parse(&graph_text)
            .unwrap_or_else(|e| panic!("{e}\n{graph_text}"))
            .call_graph
            .unwrap_or_else(|| panic!("no call graph in\n{graph_text}"));
        let entry = |name: &str| {
            graph
                .entries
                .iter()
                .find(|e| e.name == name)
                .unwrap_or_else(|| panic!("no {name} in\n{graph_text}"))
        };
        for (name, calls) in CALLS {
            assert_eq!(entry(name).calls, Some(calls), "{name}");
        }
        assert_eq!(entry("r").self_calls, Some(10), "{graph_text}");
        for (caller, callee, calls) in ARCS {
            let arc = entry(caller)
                .children
                .iter()
                .find(|c| c.name == callee)
                .unwrap_or_else(|| panic!("no {caller} -> {callee} in\n{graph_text}"));
            assert_eq!(arc.calls, Some(calls), "{caller} -> {callee}");
        }
        assert!(
            graph_text.contains("  1000/1042        leaf ["),
            "{graph_text}"
        );
        assert!(
            graph_text.contains("    37/42          g ["),
            "{graph_text}"
        );

        let json = record_json(&out_dir);
        assert_eq!(json["format"], "gprof", "{json}");
        assert_eq!(json["command"], serde_json::Value::Null);
        assert_eq!(json["calls"]["leaf"], 1042, "{json}");
        let files: Vec<&str> = json["files"]
            .as_array()
            .map(|a| a.iter().filter_map(|f| f.as_str()).collect())
            .unwrap_or_default();
        let amdahl = format!("amdahl-{stem}.txt");
        assert_eq!(
            files,
            [
                format!("flat-{stem}.txt").as_str(),
                &format!("callgraph-{stem}.txt"),
                &amdahl,
                "record.json"
            ]
        );
        assert!(!out_dir.join(format!("flame-{stem}.svg")).exists());
        // leaf (all the self time) and f (99.5 % with leaf under it) are the whole run
        // by the table's rule; g, with 4-6 % propagated from its 42 calls of leaf, leads.
        let amdahl = std::fs::read_to_string(out_dir.join(&amdahl)).unwrap_or_default();
        assert!(amdahl.contains("\ng "), "{amdahl}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `perf record -g -o DIR/perf.data` of the hot program with `HOME` at `home` (perf
/// keeps its copies of the recorded files by build id in `home/.debug`).
fn perf_record(exe: &Path, data: &Path, home: &Path, extra: &[&str]) {
    std::fs::create_dir_all(home).unwrap_or_else(|e| panic!("{e}"));
    run(Command::new("perf")
        .env("HOME", home)
        .args(["record", "-q", "-F", "4000"])
        .args(extra)
        .arg("-o")
        .arg(data)
        .arg("--")
        .arg(exe));
}

fn hot_share(out_dir: &Path) -> f64 {
    let stacks = folded(out_dir, "hot");
    share(&stacks, |s| ["hot", "step"].contains(&leaf(s)))
}

#[test]
#[ignore = "needs perf"]
fn a_perf_data_recorded_by_perf_itself_is_imported() {
    let dir = scratch("import-perf");
    let exe = hot_program(&dir);
    let home = dir.join("home");
    let data = dir.join("x").join("perf.data");
    std::fs::create_dir_all(dir.join("x")).unwrap_or_else(|e| panic!("{e}"));
    perf_record(&exe, &data, &home, &["-g"]);
    let home_env = home.to_str().unwrap_or_default();
    let out_dir = dir.join("r");
    let out = import(&data, &out_dir, &[("HOME", home_env)]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let hot = hot_share(&out_dir);
    eprintln!("{}\nhot {:.1} %", stdout(&out), hot * 100.0);
    assert!(hot >= 0.80, "hot {hot}");
    let json = record_json(&out_dir);
    assert_eq!(json["format"], "perf.data", "{json}");
    assert_eq!(json["imported"], data.display().to_string());
    assert_eq!(json["command"], serde_json::Value::Null);
    assert_eq!(json["program"], "hot");
    assert_eq!(json["call_graph"], "fp");
    // cpu-clock at 4,000 Hz: the periods add up to the CPU time, about 1/4,000 s each.
    assert!(
        json["event"]
            .as_str()
            .is_some_and(|e| e.starts_with("cpu-clock")),
        "{json}"
    );
    assert_eq!(json["cpu_seconds_from"], "periods");
    let rate = json["samples_per_cpu_second"].as_f64().unwrap_or(0.0);
    assert!((3000.0..=4500.0).contains(&rate), "{json}");
    assert!(
        json["perf_command"][1] == "record",
        "perf's command line from the header: {json}"
    );
    assert_eq!(json["missing_files"].as_array().map(Vec::len), Some(0));
    for file in [
        "flame-hot.svg",
        "profile-hot.pb.gz",
        "modules.txt",
        "phases-hot.txt",
        "report.html",
        "report.pdf",
        "amdahl-hot.txt",
    ] {
        assert!(out_dir.join(file).is_file(), "{file}");
    }
    assert!(!out_dir.join("perf.data").exists());
    // One run of an outside program, not a render.
    for text in ["flat-hot.txt", "callgraph-hot.txt"] {
        let text = std::fs::read_to_string(out_dir.join(text)).unwrap_or_default();
        assert!(text.contains("per run"), "{text}");
        assert!(!text.contains("render"), "{text}");
    }

    // The binary gone from its path: perf's copy by build id names it.
    let moved = dir.join("hot.moved");
    std::fs::rename(&exe, &moved).unwrap_or_else(|e| panic!("{e}"));
    let cached = dir.join("r-cached");
    let out = import(&data, &cached, &[("HOME", home_env)]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(hot_share(&cached) >= 0.80);
    // Nor in the cache: the file is named, its samples have no symbol.
    let empty = dir.join("empty-home");
    std::fs::create_dir_all(&empty).unwrap_or_else(|e| panic!("{e}"));
    let bare = dir.join("r-bare");
    let out = import(
        &data,
        &bare,
        &[("HOME", empty.to_str().unwrap_or_default())],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains(&format!("  {}: cannot read it", exe.display())),
        "{text}"
    );
    assert!(text.contains("perf archive"), "{text}");
    let json = record_json(&bare);
    assert_eq!(json["missing_files"][0]["path"], exe.display().to_string());
    let module = &json["modules"][0];
    assert_eq!(module["module"], "hot", "{json}");
    assert_eq!(module["no_symbol"], module["samples"], "{json}");
    // Another build at the path: refused, not misread.
    run(Command::new("cc")
        .args(["-O0", "-g", "-o"])
        .arg(&exe)
        .arg(dir.join("hot.c")));
    let out = import(
        &data,
        &dir.join("r-other"),
        &[("HOME", empty.to_str().unwrap_or_default())],
    );
    assert!(stdout(&out).contains("another build"), "{}", stdout(&out));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf"]
fn a_dwarf_recording_is_unwound_here() {
    let dir = scratch("import-dwarf");
    let exe = hot_program(&dir);
    let data = dir.join("perf.data");
    perf_record(&exe, &data, &dir.join("home"), &["--call-graph", "dwarf"]);
    let out_dir = dir.join("r");
    let home = dir.join("home");
    let out = import(
        &data,
        &out_dir,
        &[("HOME", home.to_str().unwrap_or_default())],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(hot_share(&out_dir) >= 0.80);
    assert_eq!(record_json(&out_dir)["call_graph"], "dwarf");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf"]
fn a_truncated_perf_data_exits_2_naming_the_file() {
    let dir = scratch("import-cut");
    let exe = hot_program(&dir);
    let data = dir.join("perf.data");
    perf_record(&exe, &data, &dir.join("home"), &["-g"]);
    let bytes = std::fs::read(&data).unwrap_or_else(|e| panic!("{e}"));
    let cut = dir.join("cut.data");
    for length in [9, 60, 104, 500, bytes.len() / 2, bytes.len() - 1] {
        std::fs::write(&cut, &bytes[..length]).unwrap_or_else(|e| panic!("{e}"));
        let out = import(&cut, &dir.join("r"), &[]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{length} bytes: {err}");
        assert!(err.contains(&cut.display().to_string()), "{err}");
        assert!(err.contains("truncated"), "{length} bytes: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
