//! The command line as a user meets it: exit codes, messages, outputs.

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

fn spd(name: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/spd")
        .join(format!("{name}.nff"));
    assert!(
        path.is_file(),
        "{} missing: shared/ must sit beside the project",
        path.display()
    );
    path.display().to_string()
}

/// A scratch directory unique to one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtprof-cli-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

const VIEW: &str = "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 8 8\n";

#[test]
fn malformed_scenes_exit_2_with_file_and_line_and_never_panic() {
    let dir = scratch("malformed");
    // (scene text, line the error must name)
    let cases: &[(&str, usize)] = &[
        ("s 0 0 0\n", 8),                                    // missing number
        ("s 0 0 x 1\n", 8),                                  // not a number
        ("s 0 0 NaN 1\n", 8),                                // NaN
        ("s 0 0 -inf 1\n", 8),                               // infinity
        ("cube 0 0 0 1\n", 8),                               // unknown keyword
        ("p 2\n0 0 0\n1 0 0\n", 8),                          // < 3 vertices
        ("p 3\n0 0 0\n0 0 0\n1 1 1\n", 8),                   // degenerate
        ("p 4000000000\n", 8),                               // absurd count
        ("p 4\n0 0 0\n1 0 0\n1 1 0\n", 11),                  // truncated
        ("c\n0 0 0 1\n0 0 0 1\n", 8),                        // zero-length axis
        ("pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0\n", 11), // short patch line
        ("f 1 1 1\n", 8),                                    // short material
        ("l 1 2 3 4\n", 8),                                  // bad light
        ("b 0 0 0 0\n", 8),                                  // extra number
        ("s 0 0 0 1 # ok\ns 1 2\n", 9),                      // after a comment
    ];
    let view_cases: &[(&str, usize)] = &[
        ("s 0 0 0 1\n", 1), // no v block
        (
            "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle 45\nresolution 100000000 100000000\n",
            6,
        ), // absurd size
        (
            "v\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle 45\nresolution 0 480\n",
            6,
        ), // non-positive
        (
            "v\nfrom 0 0 0\nat 0 0 1\nup 0 0 1\nangle 45\nresolution 8 8\n",
            1,
        ), // up parallel
    ];
    let all = cases
        .iter()
        .map(|(body, line)| (format!("{VIEW}{body}"), *line))
        .chain(
            view_cases
                .iter()
                .map(|(text, line)| (text.to_string(), *line)),
        );
    let mut n = 0;
    for (i, (text, line)) in all.enumerate() {
        let path = dir.join(format!("bad{i}.nff"));
        std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{e}"));
        for command in ["render", "count"] {
            let out = rtprof(
                &[command, path.to_str().unwrap_or_default(), "-o", "x.png"]
                    [..if command == "render" { 4 } else { 2 }],
            );
            let err = stderr(&out);
            assert_eq!(out.status.code(), Some(2), "case {i} {text:?}: {err}");
            assert!(
                err.contains(&format!("bad{i}.nff:{line}:")),
                "case {i}: expected line {line} in: {err}"
            );
            assert!(!err.contains("panicked"), "case {i}: {err}");
            assert_eq!(
                err.trim().lines().count(),
                1,
                "case {i}: one-line error expected: {err}"
            );
        }
        n += 1;
    }
    assert!(n >= 15);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn command_line_misuse_exits_2() {
    let dir = scratch("misuse");
    let rings = spd("rings");
    let cases: Vec<Vec<String>> = vec![
        vec!["render".into(), "no/such/file.nff".into()],
        vec!["render".into(), dir.display().to_string()],
        vec![
            "count".into(),
            rings.clone(),
            "--variant".into(),
            "warp-drive".into(),
        ],
        vec![
            "count".into(),
            rings.clone(),
            "--size".into(),
            "12by12".into(),
        ],
        vec![
            "count".into(),
            rings.clone(),
            "--size".into(),
            "0x10".into(),
        ],
        vec![
            "count".into(),
            rings.clone(),
            "--threads".into(),
            "0".into(),
        ],
        vec![
            "render".into(),
            rings.clone(),
            "-o".into(),
            dir.join("x.jpg").display().to_string(),
        ],
        vec!["render".into(), rings.clone(), "--no-such-flag".into()],
        // Variants that make the same choice cannot combine.
        vec![
            "render".into(),
            rings.clone(),
            "--variant".into(),
            "bvh,embree".into(),
        ],
        vec![
            "count".into(),
            rings.clone(),
            "--variant".into(),
            "baseline+ortho".into(),
        ],
        // compare: one image, a missing image, a scene without --variants.
        vec!["compare".into(), dir.join("a.png").display().to_string()],
        vec![
            "compare".into(),
            dir.join("a.png").display().to_string(),
            dir.join("b.png").display().to_string(),
        ],
        vec![
            "compare".into(),
            rings.clone(),
            "--variants".into(),
            "baseline,fast-sqrt+fast-sqrt-tuned".into(),
        ],
    ];
    // Files that cannot be read as scenes: not UTF-8, a path through a regular file, a
    // dangling symbolic link, an empty directory given to --scenes.
    let not_text = dir.join("binary.nff");
    std::fs::write(&not_text, [0xff, 0xfe, 0x00, 0x9f, b'\n']).unwrap();
    let dangling = dir.join("dangling.nff");
    let _ = std::fs::remove_file(&dangling);
    std::os::unix::fs::symlink(dir.join("nowhere.nff"), &dangling).unwrap();
    let suite_with_bad_variant = dir.join("bad-variant.toml");
    std::fs::write(
        &suite_with_bad_variant,
        "name = \"x\"\nsize = [8, 8]\nrepeats = 1\nvariants = [\"baseline\", \"warp-drive\"]\nscenes = [\"balls1\"]\nextra_size = [8, 8]\nprofile_size = [8, 8]\nprofile_frequency = 100\nhardware_repeats = 1\n",
    )
    .unwrap();
    let path = |p: &Path| p.display().to_string();
    let more: Vec<Vec<String>> = vec![
        vec!["render".into(), path(&not_text)],
        vec!["count".into(), format!("{rings}/inside.nff")],
        vec!["render".into(), path(&dangling)],
        vec![
            "suite".into(),
            path(&suite_with_bad_variant),
            "-o".into(),
            path(&dir.join("s")),
        ],
        vec![
            "suite".into(),
            "--quick".into(),
            "--scenes".into(),
            path(&dir.join("no-such-dir")),
        ],
        vec!["report".into(), path(&dir)],
        vec![
            "gate".into(),
            path(&dir.join("old.json")),
            path(&dir.join("new.json")),
        ],
        vec!["hw".into(), "time".into(), "no-such-scene".into()],
        vec!["warp".into()],
        vec!["render".into()],
        vec![
            "render".into(),
            rings.clone(),
            "--size".into(),
            "99999999x99999999".into(),
        ],
    ];
    for args in cases.into_iter().chain(more) {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = rtprof(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        // One line, saying it is an error (clap's multi-line usage is folded into it).
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("rtprof: error: "), "{args:?}: {err}");
    }
    // Help is not an error.
    let out = rtprof(&["render", "--help"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stdout).contains("Usage: rtprof render"));
    std::fs::remove_dir_all(&dir).ok();
}

/// The `Commands:` list of a help text: each command's name and one-line description.
fn commands_listed(help: &str) -> Vec<(String, String)> {
    help.lines()
        .skip_while(|line| line.trim() != "Commands:")
        .skip(1)
        .take_while(|line| line.starts_with("  "))
        .filter_map(|line| {
            let (name, description) = line.trim().split_once(' ')?;
            Some((name.to_string(), description.trim().to_string()))
        })
        .filter(|(name, _)| name != "help")
        .collect()
}

#[test]
fn every_command_s_help_opens_with_the_line_its_parent_lists() {
    // The arguments of each command are built only when it runs (clap's `defer`); what
    // they flatten in must not replace the command's own description.
    let mut pending = vec![Vec::<String>::new()];
    let mut seen = 0;
    while let Some(path) = pending.pop() {
        let mut args: Vec<&str> = path.iter().map(String::as_str).collect();
        args.push("-h");
        let out = rtprof(&args);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {}", stderr(&out));
        let help = String::from_utf8_lossy(&out.stdout).into_owned();
        for (name, description) in commands_listed(&help) {
            let mut sub = path.clone();
            sub.push(name);
            let mut sub_args: Vec<&str> = sub.iter().map(String::as_str).collect();
            sub_args.push("-h");
            let out = rtprof(&sub_args);
            let sub_help = String::from_utf8_lossy(&out.stdout).into_owned();
            assert_eq!(
                sub_help.lines().next().unwrap_or_default(),
                description,
                "{sub_args:?}"
            );
            seen += 1;
            pending.push(sub);
        }
    }
    // rtprof's 13 commands, hw's 7 and scene's 2.
    assert!(seen >= 22, "only {seen} commands listed");
}

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn one_and_two_threads_give_byte_identical_images_and_counts() {
    let dir = scratch("threads");
    let rings = spd("rings");
    let mut images = Vec::new();
    let mut counts = Vec::new();
    for threads in ["1", "2"] {
        for ext in ["png", "ppm"] {
            let img = dir.join(format!("rings{threads}.{ext}"));
            let out = rtprof(&[
                "render",
                &rings,
                "--size",
                "24x18",
                "--threads",
                threads,
                "-o",
                img.to_str().unwrap_or_default(),
            ]);
            assert!(out.status.success(), "{}", stderr(&out));
            images.push(read(&img));
        }
        let out = rtprof(&[
            "count",
            &rings,
            "--size",
            "24x18",
            "--threads",
            threads,
            "--json",
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        counts.push(out.stdout);
    }
    assert_eq!(images[0], images[2], "PNG differs between 1 and 2 threads");
    assert_eq!(images[1], images[3], "PPM differs between 1 and 2 threads");
    assert!(images[1].starts_with(b"P6\n24 18\n255\n"));
    assert_eq!(images[1].len(), 13 + 24 * 18 * 3);
    assert_eq!(&images[0][1..4], b"PNG");
    assert_eq!(counts[0], counts[1]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn count_json_uses_the_counter_names_and_spd_corner_rays() {
    let out = rtprof(&["count", &spd("tetra"), "--spd", "--size", "16x16", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(json["rays"]["primary"], 17 * 17);
    for group in ["ops", "calls", "tests", "rays", "accel"] {
        assert!(json[group].is_object(), "missing {group}");
    }
    for key in [
        "dot",
        "sub",
        "add",
        "cross",
        "scale",
        "normalize",
        "sqrt",
        "pow",
    ] {
        assert!(json["ops"][key].is_u64(), "ops.{key}");
    }
    for key in [
        "trace",
        "intersect",
        "shade",
        "color_contribution",
        "primary_ray_setup",
    ] {
        assert!(json["calls"][key].is_u64(), "calls.{key}");
    }
    for kind in ["sphere", "cylinder", "cone", "polygon", "patch", "plane"] {
        assert!(
            json["tests"][kind]["tests"].is_u64() && json["tests"][kind]["hits"].is_u64(),
            "tests.{kind}"
        );
    }
    for key in [
        "primary",
        "primary_hit",
        "shadow",
        "shadow_blocked",
        "reflection",
        "refraction",
    ] {
        assert!(json["rays"][key].is_u64(), "rays.{key}");
    }
    assert!(json["accel"]["nodes_visited"].is_u64() && json["accel"]["leaves_visited"].is_u64());
    // tetra: 4096 triangles, brute force.
    assert!(json["tests"]["polygon"]["tests"].as_u64().unwrap_or(0) >= 4096 * 17 * 17);

    let table = rtprof(&["count", &spd("tetra"), "--size", "8x8"]);
    let text = String::from_utf8_lossy(&table.stdout);
    assert!(
        text.lines()
            .next()
            .is_some_and(|l| l.starts_with("name") && l.ends_with("calls  meaning")),
        "{text}"
    );
    // Each row: the key, the value, and the counter table's description of it.
    assert!(
        text.lines().any(|l| {
            let cells: Vec<&str> = l.split_whitespace().collect();
            cells.len() > 2 && cells[0] == "rays.primary" && cells[1] == "64" && cells[2] == "eye"
        }),
        "{text}"
    );
    assert!(
        text.lines()
            .any(|l| l.starts_with("tests.polygon.hits ") && l.contains("inside the outline")),
        "{text}"
    );
}

#[test]
fn render_writes_an_image_and_reports_the_time_split() {
    let dir = scratch("render");
    let img = dir.join("jacks.png");
    let out = rtprof(&[
        "render",
        &spd("jacks"),
        "--size",
        "32x32",
        "--diffuse-only",
        "-o",
        img.to_str().unwrap_or_default(),
    ]);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("preprocessing") && err.contains("tracing") && err.contains("rays/s"),
        "{err}"
    );
    assert!(read(&img).len() > 100);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn render_reference_writes_the_f64_picture_and_refuses_a_variant() {
    let dir = scratch("render-reference");
    let scene = dir.join("one.nff");
    std::fs::write(
        &scene,
        format!(
            "{VIEW}l 2 3 -6\nf 1 0.5 0 1 0.3 20 0 1\ns 0 0 0 1.5\np 3\n-3 -2 2\n3 -2 2\n0 3 2\n"
        ),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let scene = scene.display().to_string();
    let img = |name: &str| dir.join(name).display().to_string();
    let out = rtprof(&[
        "render",
        &scene,
        "--reference",
        "--threads",
        "2",
        "-o",
        &img("r2.png"),
    ]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains("f64 reference") && err.contains("tracing"),
        "{err}"
    );
    // Deterministic: one thread or two, the same bytes.
    let out = rtprof(&[
        "render",
        &scene,
        "--reference",
        "--threads",
        "1",
        "-o",
        &img("r1.png"),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(read(&dir.join("r1.png")), read(&dir.join("r2.png")));
    // A large sphere and a triangle: the f32 tracer draws the same picture.
    let out = rtprof(&["render", &scene, "-o", &img("base.png")]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let out = rtprof(&["compare", &img("r1.png"), &img("base.png"), "--json"]);
    let json: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    assert!(json["rms"].as_f64().is_some_and(|rms| rms < 0.1), "{json}");
    // The reference is no variant: both at once is a usage error.
    let out = rtprof(&[
        "render",
        &scene,
        "--reference",
        "--variant",
        "bvh",
        "-o",
        &img("x.png"),
    ]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--reference") && err.contains("--variant"),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    let help = rtprof(&["render", "--help"]);
    assert!(String::from_utf8_lossy(&help.stdout).contains("--reference"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn compare_reports_metrics_of_two_images_and_of_variants() {
    let dir = scratch("compare");
    let scene = dir.join("one.nff");
    std::fs::write(
        &scene,
        format!("{VIEW}l 2 3 -6\nf 1 0.5 0 1 0 1 0 1\ns 0 0 0 1.5\n"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let scene = scene.display().to_string();
    let a = dir.join("a.png").display().to_string();
    let b = dir.join("b.ppm").display().to_string();
    for (img, variant) in [(&a, "baseline"), (&b, "bvh")] {
        let out = rtprof(&["render", &scene, "--variant", variant, "-o", img]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    }
    let diff = dir.join("diff.png");
    let out = rtprof(&[
        "compare",
        &a,
        &b,
        "--json",
        "-o",
        &diff.display().to_string(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(json["rms"], 0.0);
    assert_eq!(json["ssim"], 1.0);
    assert!(json["psnr"].is_null(), "identical images: infinite PSNR");
    // Method 2 (histograms from the P3 text) agrees with method 1 (binary image).
    assert_eq!(json["p3_histograms_a"]["gray"], json["histogram_a"]);
    let pixels: u64 = json["histogram_b"]
        .as_array()
        .map(|bins| bins.iter().filter_map(|v| v.as_u64()).sum())
        .unwrap_or(0);
    assert_eq!(pixels, 64);
    assert!(diff.is_file());

    let out = rtprof(&[
        "compare",
        &scene,
        "--variants",
        "baseline,bvh,pixel-avg",
        "--repeats",
        "2",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    let rows = json["variants"].as_array().cloned().unwrap_or_default();
    assert_eq!(rows.len(), 3);
    assert_eq!(rows[0]["name"], "baseline");
    // The reference against itself: every per-round ratio is exactly 1.
    assert_eq!(rows[0]["speedup"]["median"], 1.0);
    assert!(rows[0]["verdict"].is_null());
    assert!(rows[1]["verdict"].is_string());
    for row in &rows {
        for key in [
            "seconds", "speedup", "rms", "band", "psnr", "ssim", "counts",
        ] {
            assert!(row.get(key).is_some(), "{key} missing in {row}");
            assert!(row["speedup"]["low"].as_f64() <= row["speedup"]["median"].as_f64());
        }
        let s = &row["seconds"];
        assert!(s["low"].as_f64() <= s["median"].as_f64());
        assert!(s["median"].as_f64() <= s["high"].as_f64());
    }
    assert_eq!(rows[1]["counts"]["rays"], rows[0]["counts"]["rays"]);
    assert_eq!(rows[1]["rms"], 0.0);
    assert_eq!(rows[1]["band"], rows[0]["band"]);
    assert_eq!(rows[2]["counts"]["rays"]["primary"], 32);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn compare_against_the_f64_reference_gives_each_variant_its_error() {
    let dir = scratch("compare-reference");
    let out_dir = dir.join("images");
    let out = rtprof(&[
        "compare",
        "spd:jacks",
        "--variants",
        "baseline,fast-sqrt",
        "--reference",
        "--size",
        "24x24",
        "--repeats",
        "1",
        "--json",
        "-o",
        &out_dir.display().to_string(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        json["f64_reference"]["seconds"].as_f64().is_some(),
        "{json}"
    );
    let rows = json["variants"].as_array().cloned().unwrap_or_default();
    assert_eq!(rows.len(), 2);
    let error = |i: usize, key: &str| rows[i]["vs_f64_reference"][key].clone();
    // fast-sqrt's 6 % square roots move hits off the surfaces: further from the truth
    // than the baseline.
    let (base, fast) = (error(0, "rms").as_f64(), error(1, "rms").as_f64());
    assert!(base.is_some_and(|b| fast.is_some_and(|f| f > b)), "{json}");
    assert!(
        error(1, "max_abs_diff").as_u64().is_some_and(|m| m > 0),
        "{json}"
    );
    for name in [
        "f64-reference.png",
        "baseline-vs-f64.png",
        "fast-sqrt-vs-f64.png",
    ] {
        assert!(out_dir.join(name).is_file(), "{name} missing");
    }
    // The table has the columns; without --reference neither the columns nor the key.
    let table = rtprof(&[
        "compare",
        "spd:jacks",
        "--variants",
        "baseline",
        "--reference",
        "--size",
        "16x16",
        "--repeats",
        "1",
    ]);
    let text = String::from_utf8_lossy(&table.stdout);
    assert!(
        text.contains("vs f64") && text.contains("f64 reference"),
        "{text}"
    );
    let plain = rtprof(&[
        "compare",
        "spd:jacks",
        "--variants",
        "baseline",
        "--size",
        "16x16",
        "--repeats",
        "1",
        "--json",
    ]);
    let json: serde_json::Value =
        serde_json::from_slice(&plain.stdout).unwrap_or_else(|e| panic!("{e}"));
    assert!(json.get("f64_reference").is_none());
    assert!(json["variants"][0].get("vs_f64_reference").is_none());
    // --reference needs --variants.
    let out = rtprof(&["compare", "a.png", "b.png", "--reference"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn variants_lists_every_variant_with_measured_sqrt_errors() {
    let out = rtprof(&["variants", "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    let list = json.as_array().cloned().unwrap_or_default();
    let names: Vec<&str> = list.iter().filter_map(|v| v["name"].as_str()).collect();
    for name in [
        "baseline",
        "fast-sqrt",
        "fast-sqrt-tuned",
        "fast-sqrt-newton",
        "bounded",
        "ortho",
        "no-rsqrt-shading",
        "pixel-avg",
        "simd",
        "bvh",
    ] {
        assert!(names.contains(&name), "{name} missing: {names:?}");
    }
    let fast = list.iter().find(|v| v["name"] == "fast-sqrt");
    let max = fast
        .and_then(|v| v["sqrt_max_rel_error"].as_f64())
        .unwrap_or(0.0);
    // (3/2)/sqrt(2) - 1, the analytic worst case of the thesis's bit trick.
    assert!((max - 0.060_660_17).abs() < 1e-6, "{max}");
}

/// `rtprof profile` on SPD rings at 24x18 with `RTPROF_SAMPLER` set to `sampler`.
fn profile_with_sampler(sampler: &str, out_dir: &std::path::Path, json: bool) -> Output {
    let rings = spd("rings");
    let out_dir = out_dir.display().to_string();
    let mut args = vec![
        "profile",
        &rings,
        "--size",
        "24x18",
        "--threads",
        "2",
        "--min-samples",
        "40",
        "-o",
        &out_dir,
    ];
    if json {
        args.push("--json");
    }
    Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .env("RTPROF_SAMPLER", sampler)
        .args(&args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run rtprof: {e}"))
}

#[test]
fn profile_says_which_timer_sampled_and_refuses_an_unknown_one() {
    let dir = scratch("profile-timer");
    let out = profile_with_sampler("setitimer", &dir.join("text"), false);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text
        .lines()
        .find(|l| l.starts_with("sampled with "))
        .unwrap_or_else(|| panic!("no timer line in\n{text}"));
    // setitimer's own default rate is asked; the rate it got is a whole number.
    let rate = line
        .strip_prefix("sampled with setitimer: ")
        .and_then(|rest| rest.strip_suffix(" samples per CPU second (asked 1,000 Hz)"))
        .unwrap_or_else(|| panic!("{line}"));
    let rate: u64 = rate
        .replace(',', "")
        .parse()
        .unwrap_or_else(|e| panic!("{line}: {e}"));
    assert!((1..=1100).contains(&rate), "{line}");

    let out = profile_with_sampler("setitimer", &dir.join("json"), true);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(json["profile"]["timer"], "setitimer");
    assert_eq!(json["profile"]["frequency"], 1000);
    assert_eq!(json["frequency"], 1000);

    let out = profile_with_sampler("fastest", &dir.join("junk"), false);
    assert_ne!(out.status.code(), Some(0));
    let err = stderr(&out);
    assert!(
        err.contains("RTPROF_SAMPLER=\"fastest\" names no timer: use auto, perf or setitimer"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs perf_event_open"]
fn profile_with_perf_asks_4000_hz_and_gets_at_least_1000() {
    let dir = scratch("profile-perf");
    let out = profile_with_sampler("perf", &dir, true);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    let p = &json["profile"];
    assert_eq!(p["timer"], "perf cpu-clock");
    assert_eq!(p["frequency"], 4000);
    let rate = p["samples"].as_f64().unwrap_or(0.0) / p["cpu_seconds"].as_f64().unwrap_or(1.0);
    eprintln!("rtprof profile under perf: {rate:.0} samples per CPU second");
    assert!(rate >= 1000.0, "{p}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn profile_writes_both_views_exports_and_json_with_calls_per_render() {
    let dir = scratch("profile");
    let rings = spd("rings");
    let out_dir = dir.join("prof");
    let out = rtprof(&[
        "profile",
        &rings,
        "--size",
        "10x8",
        "--threads",
        "1",
        // A 10x8 render takes ~12 ms of CPU here (~50 samples at 4,000 a CPU
        // second): 400 samples need ~8 renders, so it repeats even when a busy
        // machine makes each render several times slower.
        "--min-samples",
        "400",
        "--diff-with",
        "bvh",
        "--json",
        "-o",
        &out_dir.display().to_string(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    // One naming scheme: <kind>-<variant>[-native].<ext>.
    for f in [
        "flat-baseline.txt",
        "callgraph-baseline.txt",
        "folded-baseline.txt",
        "flame-baseline.svg",
        "flat-baseline-native.txt",
        "callgraph-baseline-native.txt",
        "folded-baseline-native.txt",
        "flame-baseline-native.svg",
        "amdahl-baseline.txt",
        "profile-baseline.pb.gz",
        "profile-baseline-native.pb.gz",
        "speedscope-baseline.json",
        "flat-bvh.txt",
        "flame-bvh.svg",
        "flame-diff-baseline-bvh.svg",
        "flame-diff-baseline-bvh-shrunk.svg",
    ] {
        let path = out_dir.join(f);
        assert!(path.is_file(), "{} missing", path.display());
    }
    let text = |f: &str| String::from_utf8_lossy(&read(&out_dir.join(f))).into_owned();
    let flat = text("flat-baseline.txt");
    let rows =
        analysis::profile::gprof_text::parse_flat_text(&flat).unwrap_or_else(|e| panic!("{e}"));
    assert!(!rows.is_empty());
    let entries =
        analysis::profile::gprof_text::parse_call_graph_text(&text("callgraph-baseline.txt"))
            .unwrap_or_else(|e| panic!("{e}"));
    assert!(!entries.is_empty());
    let svg = text("flame-baseline.svg");
    assert!(svg.contains("<svg") && svg.trim_end().ends_with("</svg>"));
    // The phase view names the tests by kind, whatever was inlined.
    assert!(
        svg.contains("sphere test") && svg.contains("cylinder test"),
        "phases missing"
    );

    let json: serde_json::Value =
        serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}"));
    let count = rtprof(&["count", &rings, "--size", "10x8", "--json"]);
    let counts: serde_json::Value =
        serde_json::from_slice(&count.stdout).unwrap_or_else(|e| panic!("{e}"));
    // The render is repeated to gather samples; calls stay those of one render.
    let renders = json["profile"]["renders"].as_u64().unwrap();
    assert!(
        renders > 1,
        "a 10x8 render should need repeating: {renders}"
    );
    assert!(flat.contains(&format!("{renders} renders sampled; calls are per render")));
    let calls_of = |view: &str, name: &str| {
        json["profile"][view]["flat"]["rows"]
            .as_array()
            .and_then(|rows| rows.iter().find(|r| r["name"] == name))
            .and_then(|r| r["calls"].as_u64())
    };
    let spheres = counts["tests"]["sphere"]["tests"].as_u64();
    let cylinders = counts["tests"]["cylinder"]["tests"].as_u64();
    assert_eq!(calls_of("phases", "sphere test"), spheres);
    assert_eq!(calls_of("phases", "cylinder test"), cylinders);
    // Phases on most stacks: every traced ray's query, every shaded hit.
    assert_eq!(
        calls_of("phases", "closest hit"),
        counts["calls"]["trace"].as_u64()
    );
    assert_eq!(
        calls_of("phases", "shading"),
        counts["calls"]["shade"].as_u64()
    );
    // The files the results point at carry the same calls as the JSON.
    let saved = &json["files"]["baseline"];
    assert_eq!(saved["renders"].as_u64(), Some(renders));
    let row = saved["flat"]
        .as_array()
        .and_then(|rows| rows.iter().find(|r| r["name"] == "sphere test"))
        .unwrap_or_else(|| panic!("no sphere test row in {saved}"));
    assert_eq!(row["calls"].as_u64(), spheres);
    assert_eq!(json["diff"]["variant"], "bvh");
    assert!(
        json["profile"]["phases"]["amdahl"]
            .as_array()
            .is_some_and(|a| !a.is_empty())
    );
    std::fs::remove_dir_all(&dir).ok();
}

fn bench_scene(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("{name}.nff"))
        .display()
        .to_string()
}

fn json(out: &Output) -> serde_json::Value {
    assert!(out.status.success(), "{}", stderr(out));
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("not JSON: {e}"))
}

#[test]
fn hw_time_follows_equation_49_for_one_to_seven_spheres() {
    for n in 1..=7u32 {
        let v = json(&rtprof(&[
            "hw",
            "time",
            &bench_scene(&format!("balls{n}")),
            "--json",
        ]));
        assert_eq!(v["primitives"], n);
        assert_eq!(v["units"], 1);
        assert_eq!(v["clock_hz"], 50e6);
        let seconds = v["seconds"].as_f64().unwrap();
        let eq49 = 640.0 * 480.0 * 3.0 * f64::from(n) / 50e6;
        assert!(
            (seconds / eq49 - 1.0).abs() < 0.005,
            "n={n}: {seconds} vs {eq49}"
        );
        assert_eq!(v["cycles"].as_f64().unwrap() / 50e6, seconds);
        assert_eq!(v["fits"], true);
        for key in ["le", "mult", "mem_bits", "plls"] {
            assert!(v["utilization"][key].as_f64().unwrap() > 0.0, "{key}");
        }
    }
}

#[test]
fn hw_time_what_ifs_show_the_thesis_design_beside_them() {
    // Built-in scene names work as well as paths.
    let v = json(&rtprof(&[
        "hw",
        "time",
        "both5",
        "--units",
        "5",
        "--fast-sqrt",
        "--device",
        "5CGXFC9",
        "--json",
    ]));
    assert_eq!(v["units"], 5);
    assert_eq!(v["device_validated"], false);
    // 5 primitives on 5 units: 3 cycles per pixel instead of 15.
    assert_eq!(v["cycles_per_pixel"], 3);
    assert_eq!(v["thesis_design"]["cycles_per_pixel"], 15);
    let ratio = v["thesis_design"]["seconds"].as_f64().unwrap() / v["seconds"].as_f64().unwrap();
    assert!((ratio - 5.0).abs() < 0.01, "{ratio}");
    // A faster clock divides the time.
    let slow = json(&rtprof(&["hw", "time", "balls2", "--json"]));
    let fast = json(&rtprof(&[
        "hw", "time", "balls2", "--clock", "100", "--json",
    ]));
    assert_eq!(slow["cycles"], fast["cycles"]);
    assert!(
        (slow["seconds"].as_f64().unwrap() / fast["seconds"].as_f64().unwrap() - 2.0).abs() < 1e-9
    );
}

#[test]
fn hw_time_warns_when_a_design_fits_only_on_paper() {
    // The thesis's design on its board: about three quarters of the LEs (the thesis
    // routed 78 %), within the 85 % routing headroom; but its memories take 350 of the
    // 432 M9K blocks (the frame buffer alone 300: 307,200 bytes in 1K × 9 blocks), 81 %,
    // above the 80 % block rule. It fits on paper only, and the thesis built it.
    let v = json(&rtprof(&["hw", "time", "balls7", "--json"]));
    assert_eq!(v["fits"], true);
    assert_eq!(v["fit_state"], "fits_on_paper");
    assert_eq!(v["fit"]["state"], "fits_on_paper");
    assert_eq!(v["fit"]["routing_headroom"], 0.85);
    assert_eq!(
        v["fit"]["above_headroom"],
        serde_json::json!(["mem_blocks"])
    );
    assert_eq!(
        (
            v["fit"]["mem_blocks"].as_u64(),
            v["fit"]["mem_block_capacity"].as_u64()
        ),
        (Some(350), Some(432))
    );
    let le = v["utilization"]["le"].as_f64().unwrap();
    assert!(le > 0.7 && le < 0.85, "{le}");
    // All three optimizations buy a second intersection unit that fills the device
    // (about 99 % of its LEs): it fits on paper, above both headrooms.
    let what_if = [
        "hw",
        "time",
        "balls7",
        "--ortho",
        "--no-rsqrt-shading",
        "--fast-sqrt",
        "--units",
        "2",
    ];
    let v = json(&rtprof(&[&what_if[..], &["--json"]].concat()));
    let le = v["utilization"]["le"].as_f64().unwrap();
    assert!(le > 0.85 && le <= 1.0, "{le}");
    assert_eq!(v["fits"], true);
    assert_eq!(v["fit_state"], "fits_on_paper");
    assert_eq!(
        v["fit"]["above_headroom"],
        serde_json::json!(["le", "mem_blocks"])
    );
    assert_eq!(v["largest_units"], 2);
    assert_eq!(v["thesis_design"]["fit_state"], "fits_on_paper");
    // The text says so in a warning line for each design, with each rule's headroom.
    let out = rtprof(&what_if);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    let warnings: Vec<&str> = text
        .lines()
        .filter(|l| l.trim_start().starts_with("warning:"))
        .collect();
    assert_eq!(warnings.len(), 2, "{text}");
    assert!(
        warnings[1].contains("logic elements at")
            && warnings[1].contains("(headroom 85 %)")
            && warnings[1].contains("memory blocks at")
            && warnings[1].contains("(headroom 80 %)"),
        "{text}"
    );
    assert!(
        text.contains("on paper only (le > 85 %, mem_blocks > 80 %)"),
        "{text}"
    );
    assert!(text.contains("RAM blocks"), "{text}");
    // A second unit alone does not fit at all: no headroom warning, a "no".
    let v = json(&rtprof(&["hw", "time", "balls7", "--units", "2", "--json"]));
    assert_eq!(v["fits"], false);
    assert_eq!(v["fit_state"], "does_not_fit");
}

#[test]
fn hw_table_json_names_the_blocks_and_gives_errors() {
    let v = json(&rtprof(&["hw", "table", "--json"]));
    let blocks = v["blocks"].as_array().unwrap();
    let names: Vec<&str> = blocks.iter().map(|b| b["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        ["primary_ray", "intersection", "min_distance", "shading"]
    );
    assert_eq!(blocks[1]["thesis"]["latency"], 136);
    assert!(blocks[1]["error_pct"]["latency"].as_f64().unwrap().abs() <= 10.0);
    let text = rtprof(&["hw", "table", "--detail"]);
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("Table 7") && text.contains("Table 8") && text.contains("delay lines"));
}

#[test]
fn hw_render_and_mif_refuse_unsupported_primitives_and_write_files() {
    let dir = scratch("hw");
    let png = dir.join("both3.png");
    let out = rtprof(&[
        "hw",
        "render",
        &bench_scene("both3"),
        "-o",
        png.to_str().unwrap(),
        "--size",
        "64x48",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(&read(&png)[1..4], b"PNG");
    let mif = dir.join("both3.mif");
    let out = rtprof(&[
        "hw",
        "mif",
        &bench_scene("both3"),
        "-o",
        mif.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(read(&mif)).unwrap();
    assert!(
        text.contains("WIDTH=32;") && text.contains("DEPTH=27;"),
        "{text}"
    );
    // SPD rings has polygons: refused, with a message naming them; exit 2.
    for cmd in [
        vec!["hw", "render", &spd("rings"), "-o", png.to_str().unwrap()],
        vec!["hw", "mif", &spd("rings"), "-o", mif.to_str().unwrap()],
        vec!["hw", "time", &spd("rings")],
    ] {
        let out = rtprof(&cmd);
        assert_eq!(out.status.code(), Some(2), "{cmd:?}");
        assert!(stderr(&out).contains("polygon"), "{}", stderr(&out));
    }
    let v = json(&rtprof(&[
        "hw",
        "time",
        &spd("rings"),
        "--ignore-unsupported",
        "--json",
    ]));
    assert_eq!(v["primitives"], 8400);
    assert!(v["ignored"].as_str().unwrap().contains("polygon"));
    // Unknown device: exit 2, the known ones listed.
    let out = rtprof(&["hw", "table", "--device", "XC7A35T"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("EP4CE115"));
}

const TINY_SUITE: &str = r#"
name = "tiny"
size = [32, 24]
repeats = 2
variants = ["baseline", "bvh"]
scenes = ["balls2", "both3"]
extra_size = [16, 12]
profile_size = [32, 24]
profile_frequency = 500
hardware_repeats = 1
"#;

#[test]
fn an_interrupted_suite_keeps_the_previous_results_and_reports() {
    let dir = scratch("interrupt");
    let out_dir = dir.join("out");
    let tiny = dir.join("tiny.toml");
    std::fs::write(&tiny, TINY_SUITE).unwrap();
    let out = rtprof(&[
        "suite",
        tiny.to_str().unwrap(),
        "-o",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let before: Vec<Vec<u8>> = ["results.json", "report.html", "report.pdf"]
        .iter()
        .map(|f| read(&out_dir.join(f)))
        .collect();
    // A suite that needs well over a minute (2 s measured per scene and variant): it is
    // still rendering its first scenes when Ctrl-C (SIGINT) arrives.
    let long = dir.join("long.toml");
    std::fs::write(
        &long,
        TINY_SUITE
            .replace("repeats = 2", "repeats = 2\nmin_seconds = 2.0")
            .replace("scenes = [\"balls2\", \"both3\"]", "scenes = [\"balls1\", \"balls2\", \"balls3\", \"balls4\", \"balls5\", \"balls6\", \"balls7\", \"both1\", \"both2\", \"both3\", \"both4\", \"both5\", \"both6\", \"both7\", \"cylinder1\", \"cylinder2\", \"cylinder3\", \"cylinder4\", \"cylinder5\", \"cylinder6\", \"cylinder7\"]"),
    )
    .unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_rtprof"))
        .args([
            "suite",
            long.to_str().unwrap(),
            "-o",
            out_dir.to_str().unwrap(),
        ])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let out = child.wait_with_output().unwrap();
    let message = stderr(&out);
    assert_eq!(out.status.code(), Some(130), "{message}");
    assert!(
        message.contains("interrupted after") && message.contains("intact"),
        "{message}"
    );
    for (f, bytes) in ["results.json", "report.html", "report.pdf"]
        .iter()
        .zip(&before)
    {
        assert!(read(&out_dir.join(f)) == *bytes, "{f} changed");
    }
    let leftovers: Vec<_> = std::fs::read_dir(&out_dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".partial"))
        .collect();
    assert!(leftovers.is_empty(), "staging left behind: {leftovers:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn suite_writes_results_and_reports_and_the_gate_sets_the_exit_code() {
    let dir = scratch("suite");
    let suite = dir.join("tiny.toml");
    std::fs::write(&suite, TINY_SUITE).unwrap();
    let first = dir.join("first");
    let out = rtprof(&[
        "suite",
        suite.to_str().unwrap(),
        "-o",
        first.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    for f in ["results.json", "report.html", "report.pdf"] {
        assert!(first.join(f).is_file(), "{f} missing");
    }
    let results_path = first.join("results.json");
    let text = String::from_utf8(read(&results_path)).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["schema"], "rtprof.results/3");
    assert_eq!(v["scenes"].as_array().unwrap().len(), 2);
    // The hardware runs on these sphere/cylinder scenes; counts are exact.
    assert!(v["scenes"][0]["hardware"]["emulator_rms"].as_f64().unwrap() <= 15.0);
    assert_eq!(
        v["scenes"][0]["variants"][0]["counts"]["rays.primary"],
        32 * 24
    );

    // Same program, same counts: the gate passes. Time is taken out of the question by a
    // wide threshold (these renders take microseconds, where scheduler noise alone can
    // move a relative time several-fold); the files it writes are there.
    // `--no-pdf` leaves report.pdf out (typesetting it is most of this tiny run's time)
    // and removes one an earlier run left: it would describe other results.
    let second = dir.join("second");
    std::fs::create_dir_all(&second).unwrap();
    std::fs::copy(first.join("report.pdf"), second.join("report.pdf")).unwrap();
    let out = rtprof(&[
        "suite",
        suite.to_str().unwrap(),
        "-o",
        second.to_str().unwrap(),
        "--baseline",
        results_path.to_str().unwrap(),
        "--threshold",
        "1000",
        "--no-pdf",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    for f in [
        "gate.txt",
        "gate.md",
        "variants.csv",
        "summary.md",
        "report.html",
    ] {
        assert!(second.join(f).is_file(), "{f} missing");
    }
    assert!(!second.join("report.pdf").exists(), "a stale report.pdf");
    assert!(
        stderr(&out).contains("{results.json, report.html, variants.csv, summary.md}"),
        "{}",
        stderr(&out)
    );
    // A baseline whose counts differ: exit 1, the changed counter named.
    let doctored = dir.join("doctored.json");
    std::fs::write(
        &doctored,
        text.replacen("\"rays.primary\": 768", "\"rays.primary\": 769", 1),
    )
    .unwrap();
    let out = rtprof(&[
        "suite",
        suite.to_str().unwrap(),
        "-o",
        second.to_str().unwrap(),
        "--baseline",
        doctored.to_str().unwrap(),
        "--threshold",
        "1000",
        "--no-pdf",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(String::from_utf8_lossy(&out.stdout).contains("rays.primary"));
    let gate = String::from_utf8(read(&second.join("gate.txt"))).unwrap();
    assert!(gate.contains("rays.primary"), "{gate}");

    // `rtprof gate` on files made from this run: every variant's samples set to
    // `seconds` ±1 % per round, the yardstick's and the calibration kernel's to a
    // tenth of that; `slow` scales bvh's.
    let with_times = |seconds: f64, slow: f64| {
        let mut v = v.clone();
        let round = |m: f64| serde_json::json!([m * 0.99, m, m * 1.01, m]);
        for scene in v["scenes"].as_array_mut().unwrap() {
            let kernel = seconds / 10.0;
            scene["calibration"] = serde_json::json!({
                "time": {"median": kernel, "low": kernel, "high": kernel},
                "samples": round(kernel),
                "cpu_samples": round(kernel)
            });
            scene["yardstick"] = serde_json::json!({
                "width": 8, "height": 6,
                "time": {"median": kernel, "low": kernel, "high": kernel},
                "samples": round(kernel),
                "cpu_samples": round(kernel)
            });
            for variant in scene["variants"].as_array_mut().unwrap() {
                let m = if variant["variant"] == "bvh" {
                    seconds * slow
                } else {
                    seconds
                };
                variant["samples"] = round(m);
                variant["cpu_samples"] = round(m);
                variant["time"] =
                    serde_json::json!({"median": m, "low": m * 0.99, "high": m * 1.01});
            }
        }
        v
    };
    let gate_file = |name: &str, v: &serde_json::Value| {
        let path = dir.join(name);
        std::fs::write(&path, serde_json::to_string(v).unwrap()).unwrap();
        path
    };
    let old = gate_file("old.json", &with_times(0.010, 1.0));
    // A machine 1.5x slower on every render and on the kernel: not a regression.
    let busier = gate_file("busier.json", &with_times(0.015, 1.0));
    let slower = gate_file("slower.json", &with_times(0.010, 1.3));
    let mut recounted = with_times(0.010, 1.0);
    recounted["scenes"][1]["variants"][1]["counts"]["ops.dot"] = serde_json::json!(1);
    let recounted = gate_file("recounted.json", &recounted);
    let mut other_threads = with_times(0.010, 1.0);
    other_threads["suite"]["threads"] = serde_json::json!(7);
    let other_threads = gate_file("threads.json", &other_threads);
    let gate = |new: &Path| {
        rtprof(&["gate", old.to_str().unwrap(), new.to_str().unwrap()])
            .status
            .code()
    };
    assert_eq!(gate(&old), Some(0), "identical runs pass");
    assert_eq!(gate(&busier), Some(0), "a uniformly slower machine passes");
    assert_eq!(
        gate(&slower),
        Some(1),
        "bvh 20 % slower relative to baseline fails"
    );
    assert_eq!(gate(&recounted), Some(1), "a changed count fails");
    let out = rtprof(&[
        "gate",
        old.to_str().unwrap(),
        other_threads.to_str().unwrap(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(2),
        "not comparable: {}",
        stderr(&out)
    );
    assert!(stderr(&out).contains("not comparable"), "{}", stderr(&out));
    assert!(stderr(&out).contains("threads"), "{}", stderr(&out));
    let out = rtprof(&[
        "gate",
        old.to_str().unwrap(),
        slower.to_str().unwrap(),
        "--threshold",
        "35",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "30 % is inside a 35 % threshold"
    );
    // Every format carries the verdict.
    for (format, slower_label) in [
        ("text", "slower"),
        ("markdown", "**slower**"),
        ("csv", ",slower,"),
        ("json", "\"verdict\": \"slower\""),
    ] {
        let out = rtprof(&[
            "gate",
            old.to_str().unwrap(),
            slower.to_str().unwrap(),
            "--format",
            format,
        ]);
        assert_eq!(out.status.code(), Some(1), "{format}");
        let printed = String::from_utf8_lossy(&out.stdout);
        assert!(printed.contains(slower_label), "{format}: {printed}");
    }
    assert_eq!(gate(&suite), Some(2), "not a results file");

    // Two results files: the report has the side-by-side comparison.
    let both = dir.join("both");
    let out = rtprof(&[
        "report",
        results_path.to_str().unwrap(),
        second.join("results.json").to_str().unwrap(),
        "-o",
        both.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let html = String::from_utf8(read(&both.join("report.html"))).unwrap();
    assert!(html.contains("id=\"comparison\""), "no comparison section");
    assert_eq!(&read(&both.join("report.pdf"))[..4], b"%PDF");
    // Not a results file: exit 2.
    let out = rtprof(&["report", suite.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));

    // Benchmark figures added to a saved run: criterion's estimates and gungraun's
    // instruction counts, in the harnesses' own file layouts.
    let target = dir.join("target");
    for (id, ns, instructions) in [("std", 1175.0, 6330), ("fast-sqrt-newton", 815.0, 11451)] {
        let run = target.join("criterion/sqrt").join(id).join("new");
        std::fs::create_dir_all(&run).unwrap();
        std::fs::write(
            run.join("benchmark.json"),
            format!(r#"{{"group_id":"sqrt","function_id":"{id}","full_id":"sqrt/{id}"}}"#),
        )
        .unwrap();
        let stat = format!(
            r#"{{"confidence_interval":{{"confidence_level":0.95,"lower_bound":{},"upper_bound":{}}},"point_estimate":{ns},"standard_error":1.0}}"#,
            ns * 0.99,
            ns * 1.01
        );
        std::fs::write(
            run.join("estimates.json"),
            format!(r#"{{"mean":{stat},"median":{stat}}}"#),
        )
        .unwrap();
        let function = id.replace('-', "_");
        let counted = target.join(format!("gungraun/benches/instructions/g/sqrt.{function}"));
        std::fs::create_dir_all(&counted).unwrap();
        std::fs::write(
            counted.join("summary.json"),
            format!(
                r#"{{"function_name":"sqrt","id":"{function}","profiles":[{{"tool":"Callgrind","data":{{"total":{{"metrics":{{"Ir":{{"values":{{"new":{instructions}}}}}}}}}}}}}]}}"#
            ),
        )
        .unwrap();
    }
    let with_benchmarks = dir.join("with-benchmarks");
    let out = rtprof(&[
        "report",
        results_path.to_str().unwrap(),
        "--criterion",
        target.join("criterion").to_str().unwrap(),
        "-o",
        with_benchmarks.to_str().unwrap(),
        "--no-pdf",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("added 2 criterion estimates"),
        "{}",
        stderr(&out)
    );
    assert!(
        stderr(&out).contains("added 2 instruction counts"),
        "{}",
        stderr(&out)
    );
    let html = String::from_utf8(read(&with_benchmarks.join("report.html"))).unwrap();
    // 11451 / 6330 = 1.81 the instructions in 815 / 1175 = 0.69 the time.
    assert!(
        html.contains("sqrt/fast-sqrt-newton executes 1.81× the instructions of sqrt/std yet takes 0.69× its time"),
        "the report does not say that instructions and time disagree"
    );
    assert!(html.contains("11,451"), "no instruction count in the table");
    // A criterion directory that is not there: exit 2, the flag named.
    let out = rtprof(&[
        "report",
        results_path.to_str().unwrap(),
        "--criterion",
        dir.join("nowhere").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--criterion"), "{}", stderr(&out));
    std::fs::remove_dir_all(&dir).ok();
}

/// `"a.b.c": n` for every number of a JSON object (the counter keys of `count --json`).
fn flatten_json(prefix: &str, value: &serde_json::Value, out: &mut Vec<(String, u64)>) {
    match value {
        serde_json::Value::Object(map) => {
            for (k, v) in map {
                let key = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                flatten_json(&key, v, out);
            }
        }
        other => out.push((
            prefix.to_string(),
            other
                .as_u64()
                .unwrap_or_else(|| panic!("{prefix}: not a count: {other}")),
        )),
    }
}

/// Every counter of `rtprof count --json` on `scene` at `size`, flattened.
fn counter_values(scene: &str, size: &str) -> Vec<(String, u64)> {
    let counts = json(&rtprof(&["count", scene, "--size", size, "--json"]));
    let mut flat = Vec::new();
    flatten_json("", &counts, &mut flat);
    flat
}

/// Profiles `scene` at `size` (baseline, one thread) and checks the `calls` column of
/// the native view's flat profile against `rtprof count`: every function the tracer's
/// counter table gives the calls of, if sampled, has exactly the counter's value (calls
/// per render, however many renders were sampled). Returns the functions that were
/// sampled and checked.
fn profile_calls_match_the_counters(test: &str, scene: &str, size: &str) -> Vec<String> {
    let dir = scratch(test);
    let out_dir = dir.join("prof");
    // 1,000 samples: `dot` takes about 3 % of brute-force balls' samples, so 200 left
    // it unsampled about once in a few thousand runs (a CI run failed so); 1,000
    // leave it unsampled with odds below 1e-12, for about a second more.
    let profile = json(&rtprof(&[
        "profile",
        scene,
        "--size",
        size,
        "--threads",
        "1",
        "--min-samples",
        "1000",
        "--json",
        "-o",
        &out_dir.display().to_string(),
    ]));
    assert!(profile["profile"]["renders"].as_u64().unwrap() >= 1);
    let flat =
        String::from_utf8_lossy(&read(&out_dir.join("flat-baseline-native.txt"))).into_owned();
    let rows =
        analysis::profile::gprof_text::parse_flat_text(&flat).unwrap_or_else(|e| panic!("{e}"));
    // Rows below the noise floor are listed apart, with their calls.
    let noise =
        analysis::profile::gprof_text::parse_flat_noise(&flat).unwrap_or_else(|e| panic!("{e}"));
    let calls_of = |name: &str| {
        rows.iter()
            .find(|r| r.name == name)
            .map(|r| r.calls)
            .or_else(|| noise.iter().find(|r| r.name == name).map(|r| r.calls))
    };
    let counts: std::collections::BTreeMap<String, u64> =
        counter_values(scene, size).into_iter().collect();
    let mut expected: Vec<(&str, u64)> = Vec::new();
    for def in tracer::COUNTERS {
        let value = counts.get(def.key).copied();
        let value = value.unwrap_or_else(|| panic!("{} not in count --json", def.key));
        expected.extend(def.functions.iter().map(|&f| (f, value)));
    }
    // The derived entries of the table, computed here from the JSON values.
    let secondary = counts["calls.trace"] - counts["rays.primary"];
    assert_eq!(tracer::counter::DERIVED_CALLS.len(), 1);
    expected.push(("Shader::trace", secondary));
    let mut checked = Vec::new();
    for (function, value) in expected {
        match calls_of(function) {
            Some(calls) if value > 0 => {
                assert_eq!(calls, Some(value), "{function} in {flat}");
                checked.push(function.to_string());
            }
            // A function never called is never sampled.
            Some(_) => panic!("{function} sampled but its counter is 0"),
            None => {}
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    checked
}

#[test]
fn a_renamed_function_cannot_blank_the_calls_column() {
    // balls: thousands of spheres, brute force: the sphere test and its dot products
    // take nearly every sample, so both must show their exact calls.
    let checked = profile_calls_match_the_counters("renamed", &spd("balls"), "24x18");
    for function in ["Sphere::intersect", "dot"] {
        assert!(
            checked.iter().any(|f| f == function),
            "{function} has no calls: checked {checked:?}"
        );
    }
}

#[test]
fn every_counter_appears_everywhere() {
    let dir = scratch("every-counter");
    let scene = bench_scene("primitives");
    let counts = counter_values(&scene, "16x12");
    assert_eq!(counts.len(), tracer::COUNTERS.len());

    // The listing of `rtprof count`: one line per counter, key, value, then the
    // counter table's description.
    let listing = rtprof(&["count", &scene, "--size", "16x12"]);
    assert!(listing.status.success(), "{}", stderr(&listing));
    let listing = String::from_utf8_lossy(&listing.stdout).into_owned();
    for (key, value) in &counts {
        let description = tracer::COUNTERS
            .iter()
            .find(|d| d.key == key.as_str())
            .map_or("", |d| d.description);
        assert!(
            listing.lines().any(|l| {
                let mut words = l.split_whitespace();
                words.next() == Some(key.as_str())
                    && words.next() == Some(value.to_string().as_str())
                    && words.collect::<Vec<_>>().join(" ") == description
            }),
            "{key} = {value} not listed:\n{listing}"
        );
    }

    // results.json of a suite that renders the same scene at the same size.
    let suite = dir.join("counters.toml");
    std::fs::write(
        &suite,
        format!(
            "name = \"counters\"\nsize = [16, 12]\nrepeats = 1\nvariants = [\"baseline\"]\n\
             scenes = [{scene:?}]\nextra_size = [16, 12]\nprofile_size = [16, 12]\n\
             profile_frequency = 500\nprofile_samples = 50\nhardware_repeats = 1\n"
        ),
    )
    .unwrap();
    let out_dir = dir.join("suite");
    let out = rtprof(&[
        "suite",
        suite.to_str().unwrap(),
        "-o",
        out_dir.to_str().unwrap(),
        "--no-pdf",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let results: serde_json::Value =
        serde_json::from_slice(&read(&out_dir.join("results.json"))).unwrap();
    let baseline = &results["scenes"][0]["variants"][0];
    assert_eq!(baseline["variant"], "baseline");
    for (key, value) in &counts {
        assert_eq!(
            baseline["counts"][key].as_u64(),
            Some(*value),
            "{key} in results.json"
        );
    }

    // The flat profile's calls, for the counted functions it sampled.
    let checked = profile_calls_match_the_counters("every-counter-profile", &scene, "16x12");
    assert!(!checked.is_empty(), "no counted function was sampled");
    std::fs::remove_dir_all(&dir).ok();
}

/// The `/1` results written by rtprof at d19ee0e (results/tests/data).
fn v1_main_results() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("results/tests/data/v1-main-d19ee0e/results.json")
}

#[test]
fn a_results_file_of_the_previous_schema_still_makes_a_report() {
    let dir = scratch("v1-report");
    let out = rtprof(&[
        "report",
        v1_main_results().to_str().unwrap(),
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let html = String::from_utf8(std::fs::read(dir.join("report.html")).unwrap()).unwrap();
    // Its fast-sqrt images are in the "similar" band, coloured as such.
    assert!(
        html.contains("<td class=\"tone-fair\">similar</td>"),
        "the similar band lost its colour"
    );
    assert!(
        !html.contains(">different</td>"),
        "nothing in this run is different"
    );
    assert_eq!(
        &std::fs::read(dir.join("report.pdf")).unwrap()[..4],
        b"%PDF"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn implausible_results_are_refused_quickly_with_where() {
    let dir = scratch("implausible");
    let text = std::fs::read_to_string(v1_main_results()).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    for scene in v["scenes"].as_array_mut().unwrap() {
        for variant in scene["variants"].as_array_mut().unwrap() {
            for sample in variant["samples"].as_array_mut().unwrap() {
                *sample = serde_json::json!(1e308);
            }
        }
    }
    let bad = dir.join("results.json");
    std::fs::write(&bad, serde_json::to_string(&v).unwrap()).unwrap();
    let started = std::time::Instant::now();
    let out = rtprof(&["report", bad.to_str().unwrap(), "-o", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out)
            .contains("scenes[0].variants[0].samples[0]: 1e308 s is beyond the plausible range"),
        "{}",
        stderr(&out)
    );
    assert!(stderr(&out).contains("results.json"), "{}", stderr(&out));
    // The cause is said once, not once per layer of the error chain.
    assert_eq!(
        stderr(&out).matches("plausible range").count(),
        1,
        "{}",
        stderr(&out)
    );
    let out = rtprof(&["gate", bad.to_str().unwrap(), bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        started.elapsed().as_secs() < 30,
        "took {:?}",
        started.elapsed()
    );
    // A syntax error names the file, line and column.
    std::fs::write(&bad, "{\n  \"schema\": \"rtprof.results/2\",\n  oops\n}").unwrap();
    let out = rtprof(&["gate", bad.to_str().unwrap(), bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("results.json: line 3, column 3: "),
        "{}",
        stderr(&out)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_suite_with_a_failed_scene_writes_the_rest_and_exits_3() {
    let dir = scratch("suite-failure");
    let bad = dir.join("bad.nff");
    std::fs::write(
        &bad,
        "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 8\ns 0 0 oops 1\n",
    )
    .unwrap();
    let suite = dir.join("one-bad.toml");
    std::fs::write(
        &suite,
        format!(
            "name = \"one-bad\"\nsize = [16, 12]\nrepeats = 1\nvariants = [\"baseline\"]\n\
             scenes = [\"balls1\", {:?}]\nextra_size = [16, 12]\nprofile_size = [16, 12]\n\
             profile_frequency = 500\nprofile_samples = 20\nhardware_repeats = 1\n",
            bad.display().to_string()
        ),
    )
    .unwrap();
    let out_dir = dir.join("suite");
    let out = rtprof(&[
        "suite",
        suite.to_str().unwrap(),
        "-o",
        out_dir.to_str().unwrap(),
        "--no-pdf",
    ]);
    // 3: some parts failed, the rest was measured and written (not 0, not 2).
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("1 part of the suite failed"),
        "{}",
        stderr(&out)
    );
    let results: serde_json::Value =
        serde_json::from_slice(&read(&out_dir.join("results.json"))).unwrap();
    assert_eq!(results["failures"].as_array().map(Vec::len), Some(1));
    assert_eq!(results["scenes"][0]["name"], "balls1");
    assert!(out_dir.join("report.html").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

/// The thread limit is the library's one rule (`runner::pool::check_threads`): 1 to 4 ×
/// the logical CPUs; beyond it every command that takes `--threads` exits 2 naming it.
#[test]
fn thread_counts_beyond_the_limit_exit_2_naming_it() {
    let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
    let max = 4 * cpus;
    let dir = scratch("threads");
    let image = dir.join("out.png");
    let image = image.to_str().unwrap();
    for args in [
        vec!["render", "balls1", "--threads", "999", "-o", image],
        vec!["count", "balls1", "--threads", "999"],
        vec!["suite", "--quick", "--threads", "999", "-o", image],
        vec!["render", "balls1", "--threads", "0", "-o", image],
    ] {
        let out = rtprof(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        let asked = args[args.iter().position(|a| *a == "--threads").unwrap() + 1];
        assert!(
            err.contains(&format!("threads {asked}: choose 1 to {max} ")),
            "{args:?}: {err}"
        );
    }
    assert!(!Path::new(image).exists(), "nothing was rendered");
    // The limit itself is accepted.
    let most = max.to_string();
    let out = rtprof(&[
        "render",
        "balls1",
        "--size",
        "8x6",
        "--threads",
        &most,
        "-o",
        image,
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A gate of two runs with no scene × variant in common refuses (exit 2) rather than
/// passing on nothing compared; `--force` does not change that.
#[test]
fn a_gate_of_runs_with_nothing_in_common_exits_2() {
    let dir = scratch("gate-nothing");
    let first = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("results/tests/data/default-suite-runs/first.json");
    let text = std::fs::read_to_string(&first).unwrap();
    let mut other: serde_json::Value = serde_json::from_str(&text).unwrap();
    for scene in other["scenes"].as_array_mut().unwrap() {
        let name = scene["name"].as_str().unwrap().to_string();
        scene["name"] = serde_json::json!(format!("other-{name}"));
    }
    let other_path = dir.join("other.json");
    std::fs::write(&other_path, serde_json::to_string(&other).unwrap()).unwrap();
    let (a, b) = (first.to_str().unwrap(), other_path.to_str().unwrap());
    for extra in [None, Some("--force")] {
        let mut args = vec!["gate", a, b];
        args.extend(extra);
        let out = rtprof(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("nothing in common"), "{err}");
        assert!(err.contains("new: other-"), "{err}");
    }
    // The same file against itself is gated (and passes).
    assert_eq!(rtprof(&["gate", a, a]).status.code(), Some(0));
    let _ = std::fs::remove_dir_all(&dir);
}
