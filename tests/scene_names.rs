//! Every command takes the scene names `rtprof scene list` prints: SPD databases at any
//! size factor (`spd:rings`, `spd:balls:2`), built-in scenes and generators, besides
//! files. Renders are small; the expectations are hand-computed from the SPD's rules.

use std::path::PathBuf;
use std::process::{Command, Output};

fn rtprof(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(args)
        .env("RTPROF_PROGRESS", "never")
        .output()
        .unwrap_or_else(|e| panic!("cannot run rtprof: {e}"))
}

fn ok(args: &[&str]) -> String {
    ok_with_stderr(args).0
}

/// Standard output and standard error of a run that must succeed.
fn ok_with_stderr(args: &[&str]) -> (String, String) {
    let out = rtprof(args);
    assert!(
        out.status.success(),
        "rtprof {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-names-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

/// Width and height from a PNG's IHDR chunk (bytes 16-23, big-endian).
fn png_size(path: &std::path::Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let word =
        |at: usize| u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    (word(16), word(20))
}

#[test]
fn render_takes_an_spd_name() {
    let dir = scratch("render");
    let image = dir.join("r.png");
    let (_, stderr) = ok_with_stderr(&[
        "render",
        "spd:rings",
        "--size",
        "16x12",
        "--variant",
        "bvh",
        "-o",
        image.to_str().unwrap(),
    ]);
    assert_eq!(png_size(&image), (16, 12));
    // The memory it held: 16 x 12 pixels of three f32 = 2,304 bytes = 2.2 KiB.
    let memory = stderr
        .lines()
        .find(|l| l.starts_with("memory: scene "))
        .unwrap_or_else(|| panic!("no memory line in {stderr}"));
    assert!(memory.contains("+ framebuffer 2.2 KiB ="), "{memory}");
    assert!(memory.contains("process peak resident"), "{memory}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn count_takes_an_spd_name_with_a_size_factor() {
    // SPD balls at size factor 2: 1 + 9 + 81 = 91 spheres and the ground polygon.
    // Brute force tests every sphere at every closest-hit query; a shadow query may
    // stop at its first blocker.
    let json = ok(&["count", "spd:balls:2", "--size", "8x8", "--json"]);
    let counts: serde_json::Value = serde_json::from_str(&json).unwrap_or_else(|e| panic!("{e}"));
    let get = |path: &[&str]| {
        path.iter()
            .fold(&counts, |v, k| &v[*k])
            .as_u64()
            .unwrap_or_else(|| panic!("{path:?} missing in {json}"))
    };
    assert_eq!(get(&["rays", "primary"]), 64);
    let closest =
        get(&["rays", "primary"]) + get(&["rays", "reflection"]) + get(&["rays", "refraction"]);
    let queries = get(&["calls", "intersect"]);
    assert_eq!(queries, closest + get(&["rays", "shadow"]));
    let sphere_tests = get(&["tests", "sphere", "tests"]);
    assert!(
        (91 * closest..=91 * queries).contains(&sphere_tests),
        "{sphere_tests} sphere tests for {closest} closest-hit and {queries} queries"
    );
}

#[test]
fn profile_takes_an_spd_name() {
    let dir = scratch("profile");
    let out = dir.join("p");
    ok(&[
        "profile",
        "spd:tetra",
        "--size",
        "16x16",
        "--min-samples",
        "10",
        "-o",
        out.to_str().unwrap(),
    ]);
    let flat =
        std::fs::read_to_string(out.join("flat-baseline.txt")).unwrap_or_else(|e| panic!("{e}"));
    assert!(flat.contains("Flat profile"), "{flat}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn compare_takes_an_spd_name() {
    let json = ok(&[
        "compare",
        "spd:gears",
        "--variants",
        "baseline,bvh",
        "--size",
        "8x8",
        "--repeats",
        "1",
        "--format",
        "json",
    ]);
    let report: serde_json::Value = serde_json::from_str(&json).unwrap_or_else(|e| panic!("{e}"));
    let text = report.to_string();
    assert!(text.contains("\"bvh\""), "{text}");
    assert!(
        text.contains("spd:gears:4"),
        "the scene is named as it was generated: {text}"
    );
}

#[test]
fn scene_gen_writes_an_spd_database_at_a_size_factor() {
    // spd:tetra at size factor 1: one subdivision of the tetrahedron, 4 triangles.
    let by_flag = ok(&["scene", "gen", "spd:tetra", "--size-factor", "1"]);
    let by_name = ok(&["scene", "gen", "spd:tetra:1"]);
    assert_eq!(by_flag, by_name);
    let triangles = by_flag.lines().filter(|l| l.trim() == "p 3").count();
    assert_eq!(triangles, 4, "{by_flag}");
    let dir = scratch("gen");
    let file = dir.join("tetra.nff");
    ok(&["scene", "gen", "spd:tetra:1", "-o", file.to_str().unwrap()]);
    assert_eq!(std::fs::read_to_string(&file).unwrap_or_default(), by_name);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn scene_list_names_every_scene_with_its_primitives() {
    let list = ok(&["scene", "list"]);
    // Correct plurals; SPD counts from the SPD's formulas (balls: 7381 spheres + 1 polygon).
    assert!(
        list.lines()
            .any(|l| l.starts_with("  balls1 ") && l.ends_with(" 1 primitive")),
        "{list}"
    );
    assert!(
        list.lines()
            .any(|l| l.starts_with("  balls2 ") && l.ends_with(" 2 primitives")),
        "{list}"
    );
    assert!(
        list.lines()
            .any(|l| l.contains("spd:balls ") && l.contains("7,382 primitives")),
        "{list}"
    );
    for name in [
        "balls", "gears", "jacks", "lattice", "mount", "rings", "sample", "shells", "sombrero",
        "teapot", "tetra", "tree",
    ] {
        assert!(
            list.contains(&format!("spd:{name} ")),
            "spd:{name} missing from\n{list}"
        );
    }
    // Every name the list prints resolves (cheap ones are generated for real).
    for name in [
        "both3",
        "one-sphere",
        "spd:jacks",
        "spd:sample",
        "sphereflake:1",
        "lattice:2",
    ] {
        let text = ok(&["scene", "gen", name]);
        assert!(text.lines().any(|l| l.starts_with('v')), "{name}: {text}");
    }
}

#[test]
fn bad_scene_names_exit_2_with_what_is_wrong() {
    for (args, expected) in [
        (&["render", "spd:nope"][..], "unknown SPD scene 'nope'"),
        (
            &["count", "spd:balls:9"][..],
            "size factor 9 is out of range: use 1 to 6",
        ),
        (
            &["scene", "gen", "spd:rings", "--size-factor", "0"][..],
            "size factor 0 is out of range",
        ),
        (
            &["scene", "gen", "balls3", "--size-factor", "2"][..],
            "--size-factor is for spd:NAME scenes",
        ),
    ] {
        let out = rtprof(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}
