//! What a user reads when something is wrong, and the defaults every command shares:
//! whole one-line parser errors (exit 2), limit errors that name the rtprof flag,
//! default output names and one rule for `--size`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rtprof_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("cannot run rtprof: {e}"))
}

fn rtprof(args: &[&str]) -> Output {
    rtprof_in(Path::new(env!("CARGO_MANIFEST_DIR")), args)
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A scratch directory unique to one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-msg-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// One sphere, one light, at 32x24.
const SMALL: &str = "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\n\
    resolution 32 24\nl 1 1 -3\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n";

fn small_scene(dir: &Path) -> String {
    let path = dir.join("small.nff");
    std::fs::write(&path, SMALL).unwrap();
    path.display().to_string()
}

/// Exit 2 and exactly one line on stderr, which is returned.
fn one_line_exit_2(out: &Output) -> String {
    assert_eq!(out.status.code(), Some(2), "{}", stderr(out));
    let text = stderr(out);
    assert_eq!(text.lines().count(), 1, "{text}");
    text.trim_end().to_string()
}

#[test]
fn a_missing_argument_is_named() {
    let line = one_line_exit_2(&rtprof(&["render"]));
    assert_eq!(
        line,
        "rtprof: error: the following required arguments were not provided: <SCENE> \
         (usage: rtprof render <SCENE>; see --help)"
    );
}

#[test]
fn a_misspelt_command_suggests_the_right_one() {
    let line = one_line_exit_2(&rtprof(&["rendr"]));
    assert_eq!(
        line,
        "rtprof: error: unrecognized subcommand 'rendr'; \
         tip: some similar subcommands exist: 'report', 'record', 'render' \
         (usage: rtprof <COMMAND>; see --help)"
    );
}

#[test]
fn an_unknown_flag_keeps_the_tip() {
    let line = one_line_exit_2(&rtprof(&["render", "x.nff", "--outptu", "x.png"]));
    assert_eq!(
        line,
        "rtprof: error: unexpected argument '--outptu' found; \
         tip: a similar argument exists: '--output' \
         (usage: rtprof render --output <IMG> <SCENE>; see --help)"
    );
}

#[test]
fn limit_errors_name_the_flag_that_raises_them() {
    let dir = scratch("limits");
    let scene = small_scene(&dir);
    let cases: &[(&[&str], &str)] = &[
        (&["--max-primitives", "0"], "--max-primitives"),
        (&["--size", "40000x10"], "--max-side"),
        (&["--max-pixels", "100"], "--max-pixels"),
        (&["--max-file-bytes", "10"], "--max-file-bytes"),
        (&["--depth", "9", "--max-ray-depth", "8"], "--max-ray-depth"),
    ];
    for (flags, flag) in cases {
        let mut args = vec!["count", scene.as_str()];
        args.extend_from_slice(flags);
        let line = one_line_exit_2(&rtprof(&args));
        assert!(line.ends_with(&format!("(raise it with {flag})")), "{line}");
        assert!(
            !line.contains("tracer::") && !line.contains("Limits"),
            "{line}"
        );
    }
}

#[test]
fn image_writing_commands_name_their_output_after_the_scene() {
    let dir = scratch("names");
    let scene = small_scene(&dir);
    for (args, written) in [
        (vec!["render", scene.as_str()], "small.png"),
        (vec!["hw", "render", scene.as_str()], "small-hw.png"),
        (vec!["hw", "mif", scene.as_str()], "small.mif"),
        (vec!["hw", "render", "balls1"], "balls1-hw.png"),
    ] {
        let out = rtprof_in(&dir, &args);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
        assert!(dir.join(written).is_file(), "{args:?} wrote no {written}");
    }
    let png = std::fs::read(dir.join("small-hw.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn every_size_defaults_to_the_scene_resolution_and_says_so() {
    for args in [
        &["render", "--help"][..],
        &["count", "--help"],
        &["profile", "--help"],
        &["compare", "--help"],
        &["hw", "time", "--help"],
        &["hw", "render", "--help"],
    ] {
        let out = rtprof(args);
        let help = String::from_utf8_lossy(&out.stdout);
        assert!(
            help.contains("Image size WxH [default: the scene's resolution]"),
            "{args:?}: {help}"
        );
    }
    // hw time used to default to 640x480: the scene says 32x24.
    let dir = scratch("sizes");
    let scene = small_scene(&dir);
    let cycles = |extra: &[&str]| {
        let mut args = vec!["hw", "time", scene.as_str(), "--json"];
        args.extend_from_slice(extra);
        let out = rtprof(&args);
        assert!(out.status.success(), "{}", stderr(&out));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["cycles"].as_f64().unwrap()
    };
    assert_eq!(cycles(&[]), cycles(&["--size", "32x24"]));
    assert!(cycles(&["--size", "640x480"]) > 100.0 * cycles(&[]));
}
