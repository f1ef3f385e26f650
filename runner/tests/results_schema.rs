//! A fresh results.json, made by running a tiny suite through the runner library,
//! validates against the checked-in JSON Schema (`docs/results.schema.json`); the
//! same value with a required field removed, or a value of the wrong type, does not.
//! The same run's analysis fields (roofline, rays per second, SIMD lanes, BVH quality,
//! per-pixel maps, error against the f64 reference) are checked against independent
//! expectations.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use results::Results;
use results::json_schema::SCHEMA_PATH;
use runner::definition::SuiteDef;
use runner::suite::{RunContext, Suite};
use serde_json::{Value, json};

/// Two small built-in scenes (spheres, cylinders: the hardware model runs on both),
/// the reference and two variants, one timed render each; per-pixel maps of balls4.
const TINY_SUITE: &str = r#"
name = "schema-test"
size = [32, 24]
repeats = 1
min_seconds = 0
variants = ["baseline", "bvh", "simd"]
scenes = ["balls4", "cylinder2"]
pixel_stats = ["balls4"]
extra_size = [32, 24]
profile_scene = "one-sphere"
profile_size = [32, 24]
profile_frequency = 1000
profile_samples = 20
hardware_repeats = 1
"#;

fn validator() -> jsonschema::Validator {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(SCHEMA_PATH);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{SCHEMA_PATH}: {e}"));
    jsonschema::validator_for(&serde_json::from_str(&text).unwrap()).unwrap()
}

/// Every validation error of `value`: its JSON pointer and message.
fn errors(validator: &jsonschema::Validator, value: &Value) -> Vec<String> {
    validator
        .iter_errors(value)
        .map(|e| format!("{}: {e}", e.instance_path()))
        .collect()
}

/// The tiny suite's results and the directory it wrote them to.
fn run_tiny_suite() -> (Results, PathBuf) {
    let out = std::env::temp_dir().join(format!("rtprof-results-schema-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let def = SuiteDef::parse(TINY_SUITE, "tiny.toml").unwrap();
    let suite = Suite::prepare(def, false, &out, None).unwrap();
    let stop = AtomicBool::new(false);
    let ctx = RunContext {
        out: &out,
        threads: Some(2),
        progress: &runner::progress::Silent,
        stop: &stop,
        pdf: runner::report_files::Pdf::Write,
    };
    let results = suite.run(&ctx).unwrap();
    (results, out)
}

#[test]
fn a_fresh_results_file_validates_against_the_checked_in_schema() {
    let (results, out) = run_tiny_suite();
    analysis_fields_hold(&results, &out);
    std::fs::remove_dir_all(&out).ok();
    // The run is what was asked for: the test checks real content, not an empty run.
    assert_eq!(results.schema, results::SCHEMA);
    assert_eq!(results.scenes.len(), 2, "failures: {:?}", results.failures);
    for scene in &results.scenes {
        assert_eq!(scene.variants.len(), 3, "{}", scene.name);
        assert_eq!((scene.width, scene.height), (32, 24));
    }
    // The named profile scene, though not among the suite's scenes, with its counts:
    // one sphere, so every eye ray runs a sphere test (and shadow rays more).
    let profile = results.profile.as_ref().expect("a profile");
    assert_eq!(profile.scene, "one-sphere");
    let counts = &profile.baseline.counts;
    assert_eq!(counts["rays.primary"], 32 * 24);
    assert!(counts["tests.sphere.tests"] >= counts["rays.primary"]);
    let value = serde_json::to_value(&results).unwrap();
    let validator = validator();
    let found = errors(&validator, &value);
    assert!(found.is_empty(), "{}", found.join("\n"));
    // rtprof reads it back too (the file is what other tools and rtprof both read).
    let text = serde_json::to_string_pretty(&results).unwrap();
    Results::from_json(&text).unwrap_or_else(|e| panic!("read back: {e}"));

    // A required field removed: refused at the object that lacks it.
    let mut broken = value.clone();
    broken["scenes"][1]["variants"][1]["time"]
        .as_object_mut()
        .unwrap()
        .remove("median");
    let found = errors(&validator, &broken);
    assert!(
        found
            .iter()
            .any(|e| e.starts_with("/scenes/1/variants/1/time: ") && e.contains("median")),
        "{found:?}"
    );
    // A value of the wrong type: refused at its own place.
    let mut broken = value.clone();
    broken["suite"]["threads"] = json!("two");
    let found = errors(&validator, &broken);
    assert!(
        found.iter().any(|e| e.starts_with("/suite/threads: ")),
        "{found:?}"
    );
    // A whole section missing.
    let mut broken = value;
    broken.as_object_mut().unwrap().remove("machine");
    assert!(!validator.is_valid(&broken));
}

/// The flops of a flattened count map, by the documented table (a dot product is 3
/// multiplies and 2 adds, …; a box test 6 subtractions and 6 multiplies).
fn flops_by_hand(counts: &std::collections::BTreeMap<String, u64>) -> u64 {
    let n = |key: &str| counts.get(key).copied().unwrap_or(0);
    3 * (n("ops.add") + n("ops.sub") + n("ops.scale"))
        + 5 * n("ops.dot")
        + 9 * n("ops.cross")
        + 10 * n("ops.normalize")
        + n("ops.sqrt")
        + n("ops.pow")
        + 12 * n("accel.nodes_visited")
}

/// Roofline, ray rates, lanes, BVH quality and per-pixel maps of the tiny suite.
/// A PNG the suite wrote, as the image metrics read images.
fn read_png(path: &std::path::Path) -> analysis::RgbImage {
    let rgb = image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8();
    analysis::RgbImage::new(rgb.width(), rgb.height(), rgb.into_raw()).unwrap()
}

fn analysis_fields_hold(results: &Results, out: &std::path::Path) {
    let peak = results.peak.as_ref().expect("the suite measures the peaks");
    assert!(peak.peak_gflops > 0.0 && peak.bandwidth_gbs > 0.0 && peak.cache_bandwidth_gbs > 0.0);
    for scene in &results.scenes {
        // The f64 reference's picture is on disk, and each variant's error against it
        // is the error of its own PNG against that picture (recomputed here); bvh and
        // simd give baseline's picture, so their error is baseline's.
        let truth = scene.f64_reference.as_ref().expect("the f64 reference ran");
        let truth_image = read_png(&out.join(&truth.image));
        let base_truth = scene.variants[0].vs_f64_reference.clone();
        for v in &scene.variants {
            let q = v
                .vs_f64_reference
                .as_ref()
                .expect("error against the f64 reference");
            let image = read_png(&out.join(v.image.as_ref().unwrap()));
            let again = analysis::compare(&truth_image, &image).unwrap();
            assert_eq!(q.rms, again.rms, "{} {}", scene.name, v.variant);
            assert_eq!(Some(q), base_truth.as_ref(), "{} {}", scene.name, v.variant);
        }
        for v in &scene.variants {
            let what = format!("{} {}", scene.name, v.variant);
            let e = v.efficiency.as_ref().expect("efficiency");
            assert_eq!(e.flops, flops_by_hand(&v.counts), "{what}");
            assert!(e.bytes_moved > 0, "{what}");
            let achieved = e.flops as f64 / v.time.median / 1e9;
            assert!((e.achieved_gflops / achieved - 1.0).abs() < 1e-9, "{what}");
            assert!(
                e.achieved_gflops <= peak.peak_gflops,
                "{what}: {e:?} above {peak:?}"
            );
            let r = v.ray_rates.as_ref().expect("ray rates");
            let shares = [
                r.eye_fraction,
                r.secondary_fraction,
                r.shadow_fraction,
                r.other_fraction,
                r.idle_fraction,
            ];
            assert!(
                shares.iter().all(|s| (0.0..=1.0).contains(s)),
                "{what}: {r:?}"
            );
            assert!(
                (shares.iter().sum::<f64>() - 1.0).abs() < 1e-9,
                "{what}: {r:?}"
            );
            let rays = [
                "rays.primary",
                "rays.shadow",
                "rays.reflection",
                "rays.refraction",
            ]
            .iter()
            .map(|k| v.counts[*k])
            .sum::<u64>();
            let all = rays as f64 / v.time.median / 1e6;
            assert!((r.all_mrays_per_s / all - 1.0).abs() < 1e-9, "{what}");
            let lanes = v.counts["accel.lanes_issued"];
            match v.lane_utilization {
                Some(u) => {
                    assert!(v.variant == "simd");
                    let by_hand = v.counts["accel.lanes_active"] as f64 / lanes as f64;
                    assert!((u - by_hand).abs() < 1e-12 && u > 0.0 && u <= 1.0);
                }
                None => assert_eq!(lanes, 0, "{what}"),
            }
        }
        // Both builders studied (the frame is small); their trees hold every primitive.
        let builders: Vec<&str> = scene
            .bvh_quality
            .iter()
            .map(|q| q.builder.as_str())
            .collect();
        assert_eq!(builders, ["binned_sah", "midpoint"], "{}", scene.name);
        for q in &scene.bvh_quality {
            let held: u64 = q
                .leaf_size_histogram
                .iter()
                .enumerate()
                .map(|(s, n)| s as u64 * n)
                .sum();
            assert_eq!(held, scene.primitives);
            assert!(q.sah_cost > 0.0 && q.epo >= 0.0);
        }
        // The binned SAH tree is the bvh variant's: its counted render measured the same.
        let bvh = scene
            .variants
            .iter()
            .find(|v| v.variant == "bvh")
            .expect("bvh");
        let rays: u64 = [
            "rays.primary",
            "rays.shadow",
            "rays.reflection",
            "rays.refraction",
        ]
        .iter()
        .map(|k| bvh.counts[*k])
        .sum();
        let nodes = bvh.counts["accel.nodes_visited"] as f64 / rays as f64;
        assert!((scene.bvh_quality[0].measured_nodes_per_ray - nodes).abs() < 1e-9);
    }
    // Per-pixel maps of balls4's three variants, summing to each variant's counts.
    let balls = &results.scenes[0];
    assert_eq!(balls.pixel_maps.len(), 3);
    for maps in &balls.pixel_maps {
        let v = balls
            .variants
            .iter()
            .find(|v| v.variant == maps.variant)
            .expect("variant");
        for map in maps.maps.iter().filter(|m| m.key.starts_with("tests.")) {
            assert_eq!(map.sum, v.counts[&map.key], "{} {}", maps.variant, map.key);
            for file in [&map.npy, &map.png] {
                assert!(out.join(&maps.directory).join(file).is_file(), "{file}");
            }
        }
        assert!(maps.maps.iter().any(|m| m.key == "time.ns"));
    }
}
