//! The JSON Schema of results.json: the checked-in `docs/results.schema.json` is the
//! one the types give (regenerate it with
//! `RTPROF_BLESS=1 cargo test -p results --test json_schema`), it validates real files
//! (a `/2` file of main, a `/1` file upgraded), and what it requires is what serde
//! requires: a field it may omit reads, one it must have does not.

use std::path::PathBuf;

use results::Results;
use results::json_schema::{SCHEMA_PATH, results_schema_text};
use serde_json::{Value, json};

const V2_MAIN: &str = include_str!("data/v2-main-972ba80/results.json");
const V1_MAIN: &str = include_str!("data/v1-main-d19ee0e/results.json");

/// The command that rewrites the checked-in schema.
const BLESS: &str = "RTPROF_BLESS=1 cargo test -p results --test json_schema";

fn schema_file() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(SCHEMA_PATH)
}

/// The checked-in schema, compiled.
fn validator() -> jsonschema::Validator {
    let text = std::fs::read_to_string(schema_file())
        .unwrap_or_else(|e| panic!("{SCHEMA_PATH}: {e}; generate it with `{BLESS}`"));
    let schema: Value = serde_json::from_str(&text).unwrap();
    jsonschema::validator_for(&schema).unwrap_or_else(|e| panic!("{SCHEMA_PATH}: {e}"))
}

/// Every validation error of `value`, one per line, with its JSON pointer.
fn errors(validator: &jsonschema::Validator, value: &Value) -> Vec<String> {
    validator
        .iter_errors(value)
        .map(|e| format!("{}: {e}", e.instance_path()))
        .collect()
}

#[test]
fn the_checked_in_schema_is_the_one_the_types_give() {
    let generated = results_schema_text();
    let path = schema_file();
    if std::env::var_os("RTPROF_BLESS").is_some_and(|v| v == "1") {
        // Written beside and renamed, so that an interrupted run leaves the old file.
        let tmp = path.with_extension("json.tmp");
        std::fs::write(&tmp, &generated).unwrap();
        std::fs::rename(&tmp, &path).unwrap();
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "{SCHEMA_PATH} is not the schema of the results types (they changed?): \
         regenerate it with `{BLESS}` and commit it"
    );
    // It is a schema (draft 2020-12, which it names), and a self-contained one.
    let schema: Value = serde_json::from_str(&checked_in).unwrap();
    assert_eq!(
        schema["$schema"],
        json!("https://json-schema.org/draft/2020-12/schema")
    );
    assert!(jsonschema::meta::is_valid(&schema));
    assert!(!checked_in.contains("\"$ref\": \"http"));
}

#[test]
fn a_v2_file_of_main_validates() {
    let value: Value = serde_json::from_str(V2_MAIN).unwrap();
    assert_eq!(value["schema"], json!("rtprof.results/2"));
    // It lacks fields /3 added (optional in the schema as in serde).
    assert!(value["suite"].get("noise_threshold").is_none());
    assert!(value["scenes"][0].get("calibration").is_none());
    assert!(value["scenes"][0]["variants"][1].get("verdict").is_none());
    let errors = errors(&validator(), &value);
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

#[test]
fn a_v1_file_read_and_written_as_v3_validates() {
    let results = Results::from_json(V1_MAIN).unwrap();
    let value = serde_json::to_value(&results).unwrap();
    assert_eq!(value["schema"], json!(results::SCHEMA));
    let errors = errors(&validator(), &value);
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

/// A JSON pointer and a change that makes the value wrong there.
type Breakage = (&'static str, fn(&mut Value));

#[test]
fn wrong_files_fail_validation_at_their_path() {
    let validator = validator();
    let good: Value = serde_json::from_str(V2_MAIN).unwrap();
    let cases: [Breakage; 7] = [
        ("", |v| {
            v.as_object_mut().unwrap().remove("scenes");
        }),
        ("/scenes/0/variants/1/time", |v| {
            v["scenes"][0]["variants"][1]["time"]
                .as_object_mut()
                .unwrap()
                .remove("median");
        }),
        ("/scenes/0/width", |v| v["scenes"][0]["width"] = json!("32")),
        ("/scenes/0/width", |v| v["scenes"][0]["width"] = json!(-1)),
        ("/schema", |v| v["schema"] = json!("criterion/1")),
        // An optional value is an `anyOf` (it or null): the error is the option's.
        ("/scenes/0/variants/1/quality", |v| {
            v["scenes"][0]["variants"][1]["quality"]["band"] = json!("very_different")
        }),
        ("/suite/variants/1", |v| {
            v["suite"]["variants"][1] = json!("BVH")
        }),
    ];
    for (pointer, break_it) in cases {
        let mut value = good.clone();
        break_it(&mut value);
        let errors = errors(&validator, &value);
        assert!(
            errors
                .iter()
                .any(|e| e.starts_with(&format!("{pointer}: "))),
            "{pointer}: {errors:?}"
        );
        // serde refuses it too (the schema says what rtprof reads).
        assert!(
            Results::from_json(&value.to_string()).is_err(),
            "{pointer} read"
        );
    }
}

/// Removes each field of the object at `pointer` in turn: the schema must accept the
/// value exactly when serde reads it.
fn required_as_serde_requires(validator: &jsonschema::Validator, good: &Value, pointer: &str) {
    let fields: Vec<String> = good
        .pointer(pointer)
        .and_then(Value::as_object)
        .unwrap_or_else(|| panic!("no object at {pointer}"))
        .keys()
        .cloned()
        .collect();
    assert!(fields.len() >= 2, "{pointer}");
    for field in fields {
        let mut value = good.clone();
        value
            .pointer_mut(pointer)
            .and_then(Value::as_object_mut)
            .unwrap()
            .remove(&field);
        let serde_reads = serde_json::from_value::<Results>(value.clone()).is_ok();
        assert_eq!(
            validator.is_valid(&value),
            serde_reads,
            "{pointer}/{field}: schema and serde disagree (serde reads it: {serde_reads})"
        );
    }
}

#[test]
fn the_schema_requires_what_serde_requires() {
    let validator = validator();
    // A /3 file (the /1 file upgraded: every field present, incl. the profile's).
    let mut good = serde_json::to_value(Results::from_json(V1_MAIN).unwrap()).unwrap();
    // Fields of /3 that the /1 file cannot fill, so that their removal is tried too.
    good["suite"]["noise_threshold"] = json!(0.1);
    good["scenes"][0]["variants"][1]["verdict"] = json!("faster");
    good["scenes"][0]["variants"][1]["speedup_interval"] = json!([1.1, 1.3]);
    good["scenes"][0]["calibration"] = json!({
        "time": {"median": 0.01, "low": 0.009, "high": 0.011},
        "samples": [0.01]
    });
    assert!(validator.is_valid(&good));
    for pointer in [
        "",
        "/machine",
        "/build",
        "/suite",
        "/suite/timing",
        "/scenes/0",
        "/scenes/0/calibration",
        "/scenes/0/variants/1",
        "/scenes/0/variants/1/quality",
        "/scenes/0/hardware",
        "/hardware",
        "/hardware/devices/0",
        "/hardware/blocks/0",
        "/hardware/blocks/0/model",
        "/hardware/blocks/0/error_pct",
    ] {
        required_as_serde_requires(&validator, &good, pointer);
    }
    // The profile's rows (the /2 file of main has one).
    let v2: Value = serde_json::from_str(V2_MAIN).unwrap();
    assert!(validator.is_valid(&v2));
    for pointer in ["/profile", "/profile/baseline", "/profile/baseline/flat/0"] {
        required_as_serde_requires(&validator, &v2, pointer);
    }
}
