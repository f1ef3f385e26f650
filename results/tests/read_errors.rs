//! The messages of reading a file that is no rtprof results file, or one of the wrong
//! shape: JSON of another kind says what it is, another tool's schema is named, and a
//! missing field or a wrong type names its JSON path (in each schema's branch: `/3`,
//! `/2`, `/1`).

use results::{Results, ResultsError};
use serde_json::{Value, json};

const V2_MAIN: &str = include_str!("data/v2-main-972ba80/results.json");
const V1_MAIN: &str = include_str!("data/v1-main-d19ee0e/results.json");

fn message(text: &str) -> String {
    match Results::from_json(text) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn json_that_is_not_a_results_file_says_so() {
    let not = |what: &str| format!("not an rtprof results file (no \"schema\" field): {what}");
    assert_eq!(
        message(r#"{"foo": 1}"#),
        not("a JSON object with the fields foo")
    );
    assert_eq!(message("[1, {\"schema\": 2}]"), not("a JSON array"));
    assert_eq!(message("{}"), not("an empty JSON object"));
    assert_eq!(message("\"results\""), not("a JSON string"));
    assert_eq!(message("4.5"), not("a JSON number"));
    assert_eq!(message("null"), not("JSON null"));
    // criterion's estimates.json (target/criterion/<id>/new/estimates.json).
    let estimate = r#"{"confidence_interval":{"confidence_level":0.95,"lower_bound":1.0,"upper_bound":2.0},"point_estimate":1.5,"standard_error":0.1}"#;
    let criterion = format!(
        r#"{{"mean":{estimate},"median":{estimate},"median_abs_dev":{estimate},"slope":null,"std_dev":{estimate}}}"#
    );
    assert_eq!(
        message(&criterion),
        not(
            "a JSON object with the fields mean, median, median_abs_dev, slope, std_dev \
             (criterion's estimates.json?)"
        )
    );
    // Many fields: the first six, and an ellipsis; names on one line.
    assert_eq!(
        message(r#"{"a":1,"b":2,"c":3,"d":4,"e\nf":5,"g":6,"h":7}"#),
        not("a JSON object with the fields a, b, c, d, e\\nf, g, …")
    );
    assert!(matches!(
        Results::from_json("[]"),
        Err(ResultsError::NotResults(_))
    ));
}

#[test]
fn another_schema_is_named() {
    let reads = "(rtprof reads rtprof.results/3, rtprof.results/2 and rtprof.results/1)";
    assert_eq!(
        message(r#"{"schema": "criterion/1", "mean": 1}"#),
        format!("schema 'criterion/1' is not an rtprof results schema {reads}")
    );
    assert_eq!(
        message(r#"{"schema": 3}"#),
        format!("schema 3 is not an rtprof results schema {reads}")
    );
    assert_eq!(
        message(r#"{"schema": {"$id": "x"}}"#),
        format!("schema {{\"$id\":\"x\"}} is not an rtprof results schema {reads}")
    );
    // An rtprof schema of another version: rebuild it.
    let e = message(r#"{"schema": "rtprof.results/9"}"#);
    assert!(
        e.starts_with("results schema 'rtprof.results/9' is none of rtprof.results/3"),
        "{e}"
    );
    // Not JSON at all: the position of the syntax error.
    assert_eq!(
        message("{\"schema\": \"rtprof.results/3\",\n oops}"),
        "line 2, column 2: key must be a string"
    );
}

/// The error of reading `value`, which must be a [`ResultsError::Json`]: its path and
/// its whole message.
fn json_error(value: &Value) -> (String, String) {
    match Results::from_json(&serde_json::to_string(value).unwrap()) {
        Err(e @ ResultsError::Json { .. }) => {
            let ResultsError::Json { ref path, .. } = e else {
                unreachable!()
            };
            (path.clone(), e.to_string())
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn hand_written_files_of_the_wrong_shape_name_the_path() {
    // A field missing at the top level: no path, the field named.
    assert_eq!(
        message(r#"{"schema": "rtprof.results/3", "created": "2026-01-01T00:00:00Z"}"#),
        "line 1, column 65: missing field `command`"
    );
    // A wrong type names its field.
    assert_eq!(
        message(r#"{"schema": "rtprof.results/3", "created": 5}"#),
        "line 1, column 43: created: invalid type: integer `5`, expected a string"
    );
    assert_eq!(
        message(
            r#"{"schema": "rtprof.results/2", "created": "", "command": "", "machine": {"cpu_model": "x", "cores": "four"}}"#
        ),
        "line 1, column 106: machine.cores: invalid type: string \"four\", expected u32"
    );
    assert_eq!(
        message(r#"{"schema": "rtprof.results/1", "created": "", "command": "", "scenes": [{}]}"#),
        "line 1, column 74: scenes[0]: missing field `name`"
    );
}

#[test]
fn real_files_of_the_wrong_shape_name_the_path_in_each_schema() {
    // /2 as it is.
    let mut v2: Value = serde_json::from_str(V2_MAIN).unwrap();
    v2["scenes"][0]["variants"][1]["time"]
        .as_object_mut()
        .unwrap()
        .remove("median");
    let (path, text) = json_error(&v2);
    assert_eq!(path, "scenes[0].variants[1].time");
    assert!(
        text.ends_with(": scenes[0].variants[1].time: missing field `median`"),
        "{text}"
    );

    // /3: the same file as the current schema; a count's key with a dot is quoted.
    let mut v3: Value = serde_json::from_str(V2_MAIN).unwrap();
    v3["schema"] = json!(results::SCHEMA);
    v3["scenes"][2]["variants"][0]["counts"]["rays.primary"] = json!(-1);
    let (path, text) = json_error(&v3);
    assert_eq!(path, "scenes[2].variants[0].counts.\"rays.primary\"");
    assert!(
        text.ends_with(
            ": scenes[2].variants[0].counts.\"rays.primary\": invalid value: integer `-1`, expected u64"
        ),
        "{text}"
    );
    let mut v3: Value = serde_json::from_str(V2_MAIN).unwrap();
    v3["schema"] = json!(results::SCHEMA);
    v3["profile"]["baseline"]["flat"][3]["percent"] = json!("12 %");
    let (path, _) = json_error(&v3);
    assert_eq!(path, "profile.baseline.flat[3].percent");

    // /1, read through its own types.
    let mut v1: Value = serde_json::from_str(V1_MAIN).unwrap();
    v1["scenes"][1]["variants"][0]["samples"][1] = json!("fast");
    let (path, text) = json_error(&v1);
    assert_eq!(path, "scenes[1].variants[0].samples[1]");
    assert!(
        text.ends_with(
            ": scenes[1].variants[0].samples[1]: invalid type: string \"fast\", expected f64"
        ),
        "{text}"
    );
}
