//! `rtprof scaling`: the growth study's files and figures, on a tiny plan.

use std::process::Command;

#[test]
fn a_small_study_writes_json_csv_markdown_and_the_chart() {
    let dir = std::env::temp_dir().join(format!("rtprof-scaling-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args([
            "scaling",
            "--family",
            "balls:1-2",
            "--family",
            "tetra:2-4:2",
            "--size",
            "8x8",
            "--repeats",
            "1",
        ])
        .args(["--format", "json", "-o"])
        .arg(&dir)
        .env("RTPROF_PROGRESS", "never")
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let study: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(study["schema"], "rtprof.scaling/1");
    let points = study["points"].as_array().map_or(0, Vec::len);
    // Two families of two sizes, three accelerators each.
    assert_eq!(points, 2 * 2 * 3);
    // balls:2 has 1 + 9 + 81 spheres and the ground polygon; tetra:4 has 4^4 triangles.
    let primitives: Vec<u64> = study["points"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|p| p["primitives"].as_u64())
        .collect();
    assert!(
        primitives.contains(&92) && primitives.contains(&256),
        "{primitives:?}"
    );
    assert_eq!(study["fits"].as_array().map_or(0, Vec::len), 2 * 3);
    let read = |name: &str| {
        std::fs::read_to_string(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
    };
    let saved: serde_json::Value =
        serde_json::from_str(&read("scaling.json")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(saved, study, "the file is what was printed");
    let csv = read("scaling.csv");
    assert!(
        csv.starts_with("family,size_factor,primitives,accelerator,measured,"),
        "{csv}"
    );
    assert_eq!(csv.lines().count(), 1 + points);
    assert!(read("scaling.md").contains("| family |"));
    let svg = read("scaling.svg");
    assert!(
        svg.contains("<svg") && svg.contains("bvh · balls (b = "),
        "{svg}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_bad_family_exits_2_and_says_the_form() {
    let out = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(["scaling", "--family", "balls:6-1"])
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("expected SPD:FROM-TO[:STEP]"));
}
