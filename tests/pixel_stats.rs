//! `rtprof count --pixel-stats DIR`: the maps on disk, read back with an NPY reader
//! written here from NumPy's format description, sum to the counters `count --json`
//! prints for the same render.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Standard output and standard error of a run that must succeed.
fn rtprof_out_err(args: &[&str]) -> (String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args(args)
        .env("RTPROF_PROGRESS", "never")
        .output()
        .unwrap_or_else(|e| panic!("cannot run rtprof: {e}"));
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

fn rtprof(args: &[&str]) -> String {
    rtprof_out_err(args).0
}

fn rtprof_stderr(args: &[&str]) -> String {
    rtprof_out_err(args).1
}

fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-pixels-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// An NPY file (version 1.0): its dtype, shape and values widened to u64.
fn read_npy(path: &Path) -> (String, (usize, usize), Vec<u64>) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[..6], b"\x93NUMPY");
    assert_eq!((bytes[6], bytes[7]), (1, 0));
    let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let data = &bytes[10 + header_len..];
    assert_eq!((10 + header_len) % 64, 0, "header padded to 64 bytes");
    let header = std::str::from_utf8(&bytes[10..10 + header_len]).unwrap_or_else(|e| panic!("{e}"));
    assert!(header.ends_with('\n') && header.contains("'fortran_order': False"));
    let field = |name: &str| {
        let start = header
            .find(name)
            .unwrap_or_else(|| panic!("{name} in {header}"))
            + name.len();
        header[start..]
            .trim_start_matches([':', ' ', '\''])
            .to_string()
    };
    let descr: String = field("'descr'")
        .chars()
        .take_while(|&c| c != '\'')
        .collect();
    let shape = field("'shape'");
    let inside: String = shape
        .trim_start_matches('(')
        .chars()
        .take_while(|&c| c != ')')
        .collect();
    let dims: Vec<usize> = inside
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().parse().unwrap_or_else(|e| panic!("{s}: {e}")))
        .collect();
    let width = match descr.as_str() {
        "<u8" => 8,
        "<u4" => 4,
        "|u1" => 1,
        other => panic!("unexpected dtype {other}"),
    };
    let values = data
        .chunks_exact(width)
        .map(|c| {
            let mut b = [0u8; 8];
            b[..width].copy_from_slice(c);
            u64::from_le_bytes(b)
        })
        .collect::<Vec<_>>();
    assert_eq!(values.len(), dims[0] * dims[1]);
    (descr, (dims[0], dims[1]), values)
}

fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let be = |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    (be(16), be(20))
}

#[test]
fn pixel_maps_sum_to_the_printed_counters() {
    let dir = scratch("sums");
    let dir_arg = dir.to_string_lossy().into_owned();
    let args = ["count", "spd:balls:2", "--variant", "bvh", "--size", "12x8"];
    let json: serde_json::Value = serde_json::from_str(&rtprof(&[&args[..], &["--json"]].concat()))
        .unwrap_or_else(|e| panic!("{e}"));
    rtprof(&[&args[..], &["--pixel-stats", &dir_arg]].concat());
    let at = |key: &str| -> u64 {
        key.split('.')
            .fold(&json, |v, k| &v[k])
            .as_u64()
            .unwrap_or_else(|| panic!("{key} in count --json"))
    };
    for key in [
        "tests.sphere.tests",
        "tests.polygon.tests",
        "accel.nodes_visited",
        "accel.leaves_visited",
        "rays.shadow",
    ] {
        let (descr, shape, values) = read_npy(&dir.join(format!("{key}.npy")));
        assert_eq!(descr, "<u8");
        assert_eq!(shape, (8, 12), "rows, columns");
        assert_eq!(values.iter().sum::<u64>(), at(key), "{key}");
        let (w, h) = png_size(&dir.join(format!("{key}.png")));
        assert!(w >= 256 && h > 8 * w / 12, "{key}.png is {w}x{h}");
    }
    let (_, _, secondary) = read_npy(&dir.join("rays.secondary.npy"));
    assert_eq!(
        secondary.iter().sum::<u64>(),
        at("rays.reflection") + at("rays.refraction")
    );
    let (descr, _, depth) = read_npy(&dir.join("ray_tree.depth.npy"));
    assert_eq!(descr, "|u1");
    assert!(depth.iter().all(|&d| (1..=5).contains(&d)));
    let (descr, _, time) = read_npy(&dir.join("time.ns.npy"));
    assert_eq!(descr, "<u4");
    assert!(time.iter().any(|&t| t > 0));
    // The dot product is counted outside the samples only for the camera's set-up.
    let (_, _, dots) = read_npy(&dir.join("ops.dot.npy"));
    assert!(dots.iter().sum::<u64>() <= at("ops.dot"));
    let meta: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("pixel-stats.json")).unwrap_or_else(|e| panic!("{e}")),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(meta["schema"], "rtprof.pixel-stats/1");
    assert_eq!(
        (meta["columns"].as_u64(), meta["rows"].as_u64()),
        (Some(12), Some(8))
    );
    let listed: Vec<&str> = meta["maps"]
        .as_array()
        .unwrap_or_else(|| panic!("maps"))
        .iter()
        .filter_map(|m| m["key"].as_str())
        .collect();
    assert!(listed.contains(&"accel.nodes_visited") && listed.contains(&"time.ns"));
    // No map of work the render did not do: balls has no cones.
    assert!(!listed.contains(&"tests.cone.tests"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn count_states_lane_utilization_and_bvh_quality() {
    // balls1 is one sphere (and no cylinder): every chunk of 8 lanes holds 1 sphere.
    let simd = rtprof_stderr(&["count", "balls1", "--variant", "simd", "--size", "8x8"]);
    assert!(
        simd.contains("simd lanes: ") && simd.contains("(12.5 %)"),
        "{simd}"
    );
    let bvh = rtprof_stderr(&["count", "spd:balls:2", "--variant", "bvh", "--size", "8x8"]);
    assert!(
        bvh.contains("bvh (binned_sah builder): ")
            && bvh.contains("SAH cost")
            && bvh.contains("end-point overlap "),
        "{bvh}"
    );
    assert!(bvh.contains("bvh leaves by depth (root 1): "), "{bvh}");
    let midpoint = rtprof_stderr(&[
        "count",
        "spd:balls:2",
        "--variant",
        "bvh",
        "--size",
        "8x8",
        "--bvh-builder",
        "midpoint",
    ]);
    assert!(midpoint.contains("bvh (midpoint builder): "), "{midpoint}");
    // The midpoint split makes a leaf per primitive: 91 spheres and the floor, 92
    // leaves of 1.
    assert!(midpoint.contains("by size: 1:92"), "{midpoint}");
    assert!(
        bvh.contains("bvh per ray, measured / predicted: boxes "),
        "{bvh}"
    );
    let brute = rtprof_stderr(&["count", "balls1", "--size", "4x4"]);
    assert!(
        !brute.contains("bvh") && !brute.contains("simd lanes"),
        "{brute}"
    );
}

/// `--diffuse-only` (the thesis hardware's shading: the first light's Lambert term and
/// nothing else; the mode issue 37's peer race loses in) reaches `count` and its maps:
/// the same eye rays as full shading and no other ray, where full shading on balls
/// (three lights, reflective spheres) traces shadow and reflection rays; and the maps,
/// rendered the same way, still sum to the counters.
#[test]
fn diffuse_only_counts_and_maps_agree_and_trace_no_secondary_rays() {
    let dir = scratch("diffuse");
    let dir_arg = dir.to_string_lossy().into_owned();
    let base = ["count", "spd:balls:2", "--variant", "bvh", "--size", "12x8"];
    let counts = |extra: &[&str]| -> serde_json::Value {
        serde_json::from_str(&rtprof(&[&base[..], extra, &["--json"]].concat()))
            .unwrap_or_else(|e| panic!("{e}"))
    };
    let at = |json: &serde_json::Value, key: &str| -> u64 {
        key.split('.')
            .fold(json, |v, k| &v[k])
            .as_u64()
            .unwrap_or_else(|| panic!("{key} in count --json"))
    };
    let full = counts(&[]);
    let diffuse = counts(&["--diffuse-only"]);
    assert!(at(&full, "rays.reflection") > 0);
    assert!(at(&full, "rays.shadow") > at(&full, "rays.primary"));
    assert_eq!(
        at(&diffuse, "rays.reflection") + at(&diffuse, "rays.refraction"),
        0
    );
    assert_eq!(at(&diffuse, "rays.shadow"), 0);
    assert_eq!(at(&diffuse, "rays.primary"), at(&full, "rays.primary"));
    assert!(at(&diffuse, "accel.nodes_visited") < at(&full, "accel.nodes_visited"));
    rtprof(&[&base[..], &["--diffuse-only", "--pixel-stats", &dir_arg]].concat());
    for key in [
        "accel.nodes_visited",
        "accel.leaves_visited",
        "tests.sphere.tests",
    ] {
        let (_, _, values) = read_npy(&dir.join(format!("{key}.npy")));
        assert_eq!(values.iter().sum::<u64>(), at(&diffuse, key), "{key}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
