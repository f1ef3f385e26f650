//! A fresh results.json, made by running a tiny suite through the runner library,
//! validates against the checked-in JSON Schema (`docs/results.schema.json`); the
//! same value with a required field removed, or a value of the wrong type, does not.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use results::Results;
use results::json_schema::SCHEMA_PATH;
use runner::definition::SuiteDef;
use runner::suite::{RunContext, Suite};
use serde_json::{Value, json};

/// Two small built-in scenes (spheres, cylinders: the hardware model runs on both),
/// the reference and one variant, one timed render each.
const TINY_SUITE: &str = r#"
name = "schema-test"
size = [32, 24]
repeats = 1
min_seconds = 0
variants = ["baseline", "bvh"]
scenes = ["balls1", "cylinder2"]
extra_size = [32, 24]
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

fn run_tiny_suite() -> Results {
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
    };
    let results = suite.run(&ctx).unwrap();
    std::fs::remove_dir_all(&out).ok();
    results
}

#[test]
fn a_fresh_results_file_validates_against_the_checked_in_schema() {
    let results = run_tiny_suite();
    // The run is what was asked for: the test checks real content, not an empty run.
    assert_eq!(results.schema, results::SCHEMA);
    assert_eq!(results.scenes.len(), 2, "failures: {:?}", results.failures);
    for scene in &results.scenes {
        assert_eq!(scene.variants.len(), 2, "{}", scene.name);
        assert_eq!((scene.width, scene.height), (32, 24));
    }
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
