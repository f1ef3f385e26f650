//! `rtprof.h` itself: its ids are this crate's (read back from the header's text), it
//! compiles without a warning under `-Wall -Wextra -pedantic` as C99 and C++11 with GCC
//! and Clang (on and compiled out), and two translation units share one state (the
//! header's weak definitions), C and C++ alike.
//!
//! `cc` is a given wherever Rust links; g++, clang and clang++ are not, so the test
//! that needs them is ignored here and run by .ci/run after it installs them.

use rtprof_probe::format::read_file;
use rtprof_probe::{COUNTER_KEYS, Counter, PHASE_NAMES, Phase};
use std::path::{Path, PathBuf};
use std::process::Command;

fn probe_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn header() -> String {
    std::fs::read_to_string(probe_dir().join("rtprof.h")).unwrap_or_else(|e| panic!("{e}"))
}

/// `(IDENT, value)` of the enum `name` of the header.
fn enum_items(text: &str, name: &str) -> Vec<(String, usize)> {
    let start = text
        .find(&format!("enum {name} {{"))
        .unwrap_or_else(|| panic!("no enum {name}"));
    let body = &text[start..start + text[start..].find("};").unwrap_or(0)];
    body.lines()
        .filter_map(|l| {
            let (ident, rest) = l.trim().split_once(" = ")?;
            let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
            Some((ident.to_string(), digits.parse().ok()?))
        })
        .filter(|(ident, _)| !ident.starts_with("RTPROF_STANDARD"))
        .collect()
}

/// The quoted strings of the macro `name`.
fn macro_strings(text: &str, name: &str) -> Vec<String> {
    let start = text
        .find(&format!("#define {name}"))
        .unwrap_or_else(|| panic!("no {name}"));
    let body = &text[start..];
    let end = ["\n#", "\n/*"]
        .iter()
        .filter_map(|m| body.find(m))
        .min()
        .unwrap_or(body.len());
    body[..end]
        .split('"')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

#[test]
fn the_header_s_ids_are_the_crate_s() {
    let text = header();
    let counters = enum_items(&text, "rtprof_counter");
    assert_eq!(counters.len(), COUNTER_KEYS.len());
    assert_eq!(macro_strings(&text, "RTPROF_I_COUNTER_KEYS"), COUNTER_KEYS);
    for (index, (ident, id)) in counters.iter().enumerate() {
        // RTPROF_RAYS_PRIMARY is rays.primary, in the crate's order.
        assert_eq!(*id, index, "{ident}");
        let key = COUNTER_KEYS[index].to_uppercase().replace('.', "_");
        assert_eq!(*ident, format!("RTPROF_{key}"));
    }
    let phases = enum_items(&text, "rtprof_phase");
    assert_eq!(phases.len(), PHASE_NAMES.len());
    assert_eq!(macro_strings(&text, "RTPROF_I_PHASE_NAMES"), PHASE_NAMES);
    for (i, (_, id)) in phases.iter().enumerate() {
        assert_eq!(*id, i + 1);
    }
    // The crate's constants carry the header's values.
    assert_eq!(Counter::RAYS_PRIMARY.key(), Some("rays.primary"));
    assert!(text.contains(&format!(
        "RTPROF_RAYS_PRIMARY = {},",
        Counter::RAYS_PRIMARY.id()
    )));
    assert!(text.contains(&format!(
        "RTPROF_PHASE_SPHERE_TEST = {},",
        Phase::SPHERE_TEST.id()
    )));
    assert_eq!(Phase::SPHERE_TEST.name(), Some("sphere test"));
    assert!(text.contains("#define RTPROF_USER_COUNTER(k) (64 + (k))"));
    assert_eq!(Counter::user(5).id(), 69);
    assert!(text.contains("#define RTPROF_USER_PHASE(k) (32 + (k))"));
    assert_eq!(Phase::user(1).id(), 33);
    assert!(text.contains(&format!(
        "#define RTPROF_FORMAT \"{}\"",
        rtprof_probe::FORMAT_LINE
    )));
    assert!(text.contains(&format!(
        "#define RTPROF_ENV_FILE \"{}\"",
        rtprof_probe::ENV_FILE
    )));
    assert!(text.contains(&format!(
        "#define RTPROF_ENV_HZ \"{}\"",
        rtprof_probe::ENV_HZ
    )));
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("header-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

/// Builds every_macro (C or C++) and other_unit with `compiler` in `standard`, warnings
/// as errors; returns the program.
fn build(dir: &Path, compiler: &str, cxx: bool, defines: &[&str]) -> PathBuf {
    let c = probe_dir().join("tests/c");
    let out = dir.join(format!(
        "every-{compiler}{}",
        defines.join("").replace(['-', '='], "_")
    ));
    let flags = ["-Wall", "-Wextra", "-pedantic", "-Werror", "-O1", "-I"];
    let mut objects = Vec::new();
    // The second unit is always C; with C++ it is compiled by the matching C compiler.
    let c_compiler = match compiler {
        "g++" => "gcc",
        "clang++" => "clang",
        other => other,
    };
    for (tool, std, source) in [
        (
            compiler,
            if cxx { "-std=c++11" } else { "-std=c99" },
            c.join(if cxx {
                "every_macro.cc"
            } else {
                "every_macro.c"
            }),
        ),
        (c_compiler, "-std=c99", c.join("other_unit.c")),
    ] {
        let object = dir.join(format!(
            "{}-{tool}{}.o",
            source
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("unit"),
            defines.join("").replace(['-', '='], "_")
        ));
        let output = Command::new(tool)
            .arg(std)
            .args(flags)
            .arg(probe_dir())
            .args(defines)
            .arg("-c")
            .arg(&source)
            .arg("-o")
            .arg(&object)
            .output()
            .unwrap_or_else(|e| panic!("cannot run {tool}: {e}"));
        assert!(
            output.status.success() && output.stderr.is_empty(),
            "{tool} {std} {defines:?} {}:\n{}",
            source.display(),
            String::from_utf8_lossy(&output.stderr)
        );
        objects.push(object);
    }
    let status = Command::new(compiler)
        .args(&objects)
        .arg("-pthread")
        .arg("-o")
        .arg(&out)
        .status()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(status.success(), "{compiler}: linking failed");
    out
}

/// Runs the program with the probe on and off and checks the counts of both units.
fn check_program(dir: &Path, program: &Path, cxx: bool) {
    let file = dir.join(format!(
        "{}.txt",
        program.file_name().and_then(|n| n.to_str()).unwrap_or("p")
    ));
    let on = Command::new(program)
        .env(rtprof_probe::ENV_FILE, &file)
        .status()
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(on.code(), Some(0), "{}", program.display());
    let probe = read_file(&file).unwrap_or_else(|e| panic!("{e}"));
    // 10 in main's unit, 7 in the other one.
    assert_eq!(probe.counter("calls.trace"), Some(17));
    assert_eq!(probe.counter("calls.shade"), Some(if cxx { 5 } else { 0 }));
    assert_eq!(probe.user_counter("main's own"), Some(20));
    // Counted but never named: the writer names it by its number.
    assert_eq!(probe.user_counter("counter 5"), Some(1));
    assert!(probe.phase("outer").is_some(), "{probe:?}");
    assert_eq!(probe.unbalanced, 1);
    assert_eq!(probe.threads, 1);
    let off = Command::new(program)
        .env_remove(rtprof_probe::ENV_FILE)
        .status()
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(off.code(), Some(3), "RTPROF_ENABLED() is 0 when off");
}

/// Compiled out, the program runs without the probe whatever the environment.
fn check_disabled(dir: &Path, program: &Path) {
    let file = dir.join("disabled.txt");
    let status = Command::new(program)
        .env(rtprof_probe::ENV_FILE, &file)
        .status()
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status.code(), Some(3));
    assert!(!file.exists());
}

#[test]
fn the_header_compiles_cleanly_as_c99_with_cc_and_two_units_share_one_state() {
    let dir = scratch("cc");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let program = build(&dir, &cc, false, &[]);
    check_program(&dir, &program, false);
    let disabled = build(&dir, &cc, false, &["-DRTPROF_DISABLE"]);
    check_disabled(&dir, &disabled);
}

#[test]
#[ignore = "needs g++, clang and clang++ (.ci/run installs them)"]
fn the_header_compiles_cleanly_under_gcc_and_clang_as_c99_and_cxx11() {
    let dir = scratch("all");
    for (compiler, cxx) in [
        ("gcc", false),
        ("g++", true),
        ("clang", false),
        ("clang++", true),
    ] {
        let program = build(&dir, compiler, cxx, &[]);
        check_program(&dir, &program, cxx);
        let disabled = build(&dir, compiler, cxx, &["-DRTPROF_DISABLE"]);
        check_disabled(&dir, &disabled);
    }
}
