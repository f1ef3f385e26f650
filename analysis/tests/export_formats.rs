//! The exports read back: the pprof profile decoded (gzip, then protobuf with pprof-rs's
//! codec) gives the functions, samples and totals it was built from; the speedscope
//! file validates against speedscope's published schema (tests/data) and its
//! profiles give back the samples; and, with Go installed, `go tool pprof` reads the
//! pprof file.

use analysis::profile::export::{
    PprofRun, SPEEDSCOPE_SCHEMA, pprof_profile_gz, sample_nanoseconds, speedscope_json,
};
use analysis::profile::{Stack, StackSamples};
use flate2::read::GzDecoder;
use pprof::protos::{Message, Profile};
use serde_json::Value;
use std::collections::BTreeMap;
use std::io::Read;
use std::time::Duration;

/// A hand-built profile: a phase view with nested phases, names with spaces and
/// characters JSON must escape.
fn phase_view() -> StackSamples {
    let stack = |frames: &[&str], count| Stack {
        frames: frames.iter().map(|f| f.to_string()).collect(),
        count,
    };
    StackSamples {
        stacks: vec![
            stack(&["camera ray", "closest hit", "sphere test"], 120),
            stack(&["camera ray", "closest hit", "cylinder test"], 700),
            stack(
                &["camera ray", "shading", "shadow query", "sphere test"],
                30,
            ),
            stack(&["camera ray", "shading"], 50),
            stack(&["pixel \"fill\"\\"], 1),
        ],
        seconds_per_sample: 0.004_1,
    }
}

fn native_view() -> StackSamples {
    StackSamples {
        stacks: vec![
            Stack {
                frames: vec![
                    "tracer::render".into(),
                    "tracer::Cylinder::intersect".into(),
                ],
                count: 850,
            },
            Stack {
                frames: vec!["tracer::render".into(), "powf".into()],
                count: 51,
            },
        ],
        seconds_per_sample: 0.004_1,
    }
}

fn decode(gz: &[u8]) -> Profile {
    let mut bytes = Vec::new();
    GzDecoder::new(gz).read_to_end(&mut bytes).unwrap();
    Profile::decode(bytes.as_slice()).unwrap()
}

#[test]
fn the_pprof_profile_decodes_to_the_stacks_it_was_built_from() {
    let samples = phase_view();
    let run = PprofRun {
        duration: Duration::from_millis(1234),
        comments: vec!["view: phases".into()],
    };
    let gz = pprof_profile_gz(&samples, &run).unwrap();
    assert_eq!(&gz[..2], &[0x1f, 0x8b], "not gzip");
    let profile = decode(&gz);
    let s = |i: i64| profile.string_table[i as usize].as_str();
    assert_eq!(s(0), "");
    let types: Vec<(&str, &str)> = profile
        .sample_type
        .iter()
        .map(|t| (s(t.ty), s(t.unit)))
        .collect();
    assert_eq!(types, [("samples", "count"), ("cpu", "nanoseconds")]);
    assert_eq!(profile.duration_nanos, 1_234_000_000);
    assert_eq!(profile.period, 4_100_000);
    assert_eq!(
        profile.comment.iter().map(|&c| s(c)).collect::<Vec<_>>(),
        ["view: phases"]
    );

    // One function per distinct frame name, each with its own location.
    let names: BTreeMap<u64, &str> = profile.function.iter().map(|f| (f.id, s(f.name))).collect();
    let mut distinct: Vec<&str> = samples
        .stacks
        .iter()
        .flat_map(|st| st.frames.iter().map(String::as_str))
        .collect();
    distinct.sort();
    distinct.dedup();
    let mut exported: Vec<&str> = names.values().copied().collect();
    exported.sort();
    assert_eq!(exported, distinct);
    let location_function: BTreeMap<u64, u64> = profile
        .location
        .iter()
        .map(|l| {
            assert_eq!(l.line.len(), 1);
            (l.id, l.line[0].function_id)
        })
        .collect();
    assert_eq!(location_function.len(), names.len());

    // Each sample: its stack leaf first, its count, its CPU nanoseconds.
    assert_eq!(profile.sample.len(), samples.stacks.len());
    for (sample, stack) in profile.sample.iter().zip(&samples.stacks) {
        let leaf_first: Vec<&str> = sample
            .location_id
            .iter()
            .map(|l| names[&location_function[l]])
            .collect();
        let expected: Vec<&str> = stack.frames.iter().rev().map(String::as_str).collect();
        assert_eq!(leaf_first, expected);
        let nanos = (stack.count as f64 * 0.0041 * 1e9).round() as i64;
        assert_eq!(sample.value, [stack.count as i64, nanos]);
    }
    // Totals: 901 samples, 901 x 4.1 ms of CPU.
    let total = |i: usize| profile.sample.iter().map(|x| x.value[i]).sum::<i64>();
    assert_eq!(total(0), 901);
    assert_eq!(total(1), 3_694_100_000);
    assert_eq!(sample_nanoseconds(901, 0.0041), 3_694_100_000);
}

/// Validates `value` against the JSON Schema node `schema` of `root`, for the keywords
/// speedscope's schema uses (checked by the caller): $ref to a definition, type,
/// enum, properties, required, items, anyOf.
fn validate(root: &Value, schema: &Value, value: &Value, at: &str) -> Result<(), String> {
    if let Some(reference) = schema.get("$ref").and_then(Value::as_str) {
        let name = reference
            .strip_prefix("#/definitions/")
            .ok_or_else(|| format!("unsupported $ref {reference}"))?;
        return validate(root, &root["definitions"][name], value, at);
    }
    if let Some(any) = schema.get("anyOf").and_then(Value::as_array) {
        let errors: Vec<String> = any
            .iter()
            .filter_map(|s| validate(root, s, value, at).err())
            .collect();
        if errors.len() == any.len() {
            return Err(format!("{at}: matches none of anyOf: {errors:?}"));
        }
    }
    if let Some(ty) = schema.get("type").and_then(Value::as_str) {
        let ok = match ty {
            "object" => value.is_object(),
            "array" => value.is_array(),
            "string" => value.is_string(),
            "number" => value.is_number(),
            other => return Err(format!("unsupported type {other}")),
        };
        if !ok {
            return Err(format!("{at}: {value} is not of type {ty}"));
        }
    }
    if let Some(allowed) = schema.get("enum").and_then(Value::as_array)
        && !allowed.contains(value)
    {
        return Err(format!("{at}: {value} is not one of {allowed:?}"));
    }
    if let Some(required) = schema.get("required").and_then(Value::as_array) {
        for key in required.iter().filter_map(Value::as_str) {
            if value.get(key).is_none() {
                return Err(format!("{at}: required {key} is missing"));
            }
        }
    }
    if let (Some(properties), Some(object)) = (
        schema.get("properties").and_then(Value::as_object),
        value.as_object(),
    ) {
        for (key, property) in properties {
            if let Some(v) = object.get(key) {
                validate(root, property, v, &format!("{at}.{key}"))?;
            }
        }
    }
    if let (Some(items), Some(array)) = (schema.get("items"), value.as_array()) {
        for (i, item) in array.iter().enumerate() {
            validate(root, items, item, &format!("{at}[{i}]"))?;
        }
    }
    Ok(())
}

/// Every keyword in the schema: the validator above must know them all.
fn keywords(schema: &Value, into: &mut Vec<String>) {
    match schema {
        Value::Object(map) => {
            for (key, value) in map {
                into.push(key.clone());
                if key == "properties" || key == "definitions" {
                    // Names of properties or definitions, not keywords.
                    for sub in value.as_object().into_iter().flat_map(|m| m.values()) {
                        keywords(sub, into);
                    }
                } else if key != "enum" && key != "required" {
                    keywords(value, into);
                }
            }
        }
        Value::Array(items) => items.iter().for_each(|v| keywords(v, into)),
        _ => {}
    }
}

fn speedscope_schema() -> Value {
    serde_json::from_str(include_str!("data/speedscope-file-format-schema.json")).unwrap()
}

#[test]
fn the_validator_knows_every_keyword_of_the_schema_and_rejects_bad_files() {
    let schema = speedscope_schema();
    let mut used = Vec::new();
    keywords(&schema, &mut used);
    let known = [
        "$schema",
        "definitions",
        "$ref",
        "anyOf",
        "type",
        "enum",
        "properties",
        "required",
        "items",
        "title",
    ];
    for keyword in &used {
        assert!(
            known.contains(&keyword.as_str()),
            "schema keyword {keyword} not validated"
        );
    }
    // The validator can fail: files the schema rejects.
    let good: Value = serde_json::from_str(&speedscope_json("x", &[("p", &phase_view())])).unwrap();
    assert_eq!(validate(&schema, &schema, &good, "$"), Ok(()));
    let broken = |edit: &dyn Fn(&mut Value)| {
        let mut bad = good.clone();
        edit(&mut bad);
        validate(&schema, &schema, &bad, "$")
    };
    assert!(broken(&|v| v["$schema"] = "https://example.invalid/".into()).is_err());
    assert!(broken(&|v| v["profiles"][0]["unit"] = "minutes".into()).is_err());
    assert!(broken(&|v| v["profiles"][0]["samples"][0][0] = "camera ray".into()).is_err());
    assert!(
        broken(&|v| {
            v["profiles"][0].as_object_mut().unwrap().remove("weights");
        })
        .is_err()
    );
    assert!(
        broken(&|v| {
            v["shared"]["frames"][0]
                .as_object_mut()
                .unwrap()
                .remove("name");
        })
        .is_err()
    );
}

#[test]
fn the_speedscope_file_follows_the_published_schema_and_gives_back_the_samples() {
    let (phases, native) = (phase_view(), native_view());
    let text = speedscope_json(
        "lattice5 baseline",
        &[("phases", &phases), ("native symbols", &native)],
    );
    let file: Value = serde_json::from_str(&text).unwrap();
    let schema = speedscope_schema();
    validate(&schema, &schema, &file, "$").unwrap_or_else(|e| panic!("{e}"));

    assert_eq!(file["$schema"], SPEEDSCOPE_SCHEMA);
    assert_eq!(file["name"], "lattice5 baseline");
    assert_eq!(file["activeProfileIndex"], 0);
    assert!(file["exporter"].as_str().unwrap().starts_with("rtprof "));
    let frames: Vec<&str> = file["shared"]["frames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    // Shared frames: each name once, across both profiles.
    let mut unique = frames.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), frames.len());

    let profiles = file["profiles"].as_array().unwrap();
    assert_eq!(profiles.len(), 2);
    for (profile, (name, samples)) in profiles
        .iter()
        .zip([("phases", &phases), ("native symbols", &native)])
    {
        assert_eq!(profile["type"], "sampled");
        assert_eq!(profile["name"], name);
        assert_eq!(profile["unit"], "seconds");
        assert_eq!(profile["startValue"], 0.0);
        let stacks = profile["samples"].as_array().unwrap();
        let weights: Vec<f64> = profile["weights"]
            .as_array()
            .unwrap()
            .iter()
            .map(|w| w.as_f64().unwrap())
            .collect();
        assert_eq!(stacks.len(), weights.len());
        assert_eq!(stacks.len(), samples.stacks.len());
        let end = profile["endValue"].as_f64().unwrap();
        let sum: f64 = weights.iter().sum();
        assert!(
            (end - sum).abs() <= 1e-12 * sum,
            "endValue {end} != sum of weights {sum}"
        );
        // The whole profile is the CPU time of all its samples.
        let cpu = samples.total() as f64 * samples.seconds_per_sample;
        assert!((end - cpu).abs() <= 1e-12 * cpu, "endValue {end} != {cpu}");
        for ((stack, weight), original) in stacks.iter().zip(&weights).zip(&samples.stacks) {
            let names: Vec<&str> = stack
                .as_array()
                .unwrap()
                .iter()
                .map(|i| {
                    let i = i.as_u64().unwrap() as usize;
                    assert!(i < frames.len(), "frame index {i} out of range");
                    frames[i]
                })
                .collect();
            assert_eq!(names, original.frames, "root first");
            // serde_json reads floats to within an ulp or so (no float_roundtrip).
            let expected = original.count as f64 * samples.seconds_per_sample;
            assert!(
                (weight - expected).abs() <= 1e-12 * expected,
                "{weight} != {expected}"
            );
        }
    }
}

/// `go tool pprof` (Debian's golang-go) reads the file and lists the frames.
#[test]
#[ignore = "needs go (golang-go)"]
fn go_tool_pprof_reads_the_profile() {
    let dir = std::env::temp_dir().join(format!("rtprof-pprof-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("profile.pb.gz");
    let samples = phase_view();
    std::fs::write(
        &path,
        pprof_profile_gz(&samples, &PprofRun::default()).unwrap(),
    )
    .unwrap();
    let out = std::process::Command::new("go")
        .args(["tool", "pprof", "-top"])
        .arg(&path)
        .env("HOME", &dir)
        .output()
        .unwrap_or_else(|e| panic!("cannot run go: {e}"));
    let _ = std::fs::remove_dir_all(&dir);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "go tool pprof failed: {}{stdout}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("3694.10ms total"), "{stdout}");
    // Flat and cumulative times as computed by hand from the stacks (4.1 ms a sample):
    // cylinder test 700 samples = 2870 ms, 77.69 % of 3694.1 ms; sphere test
    // 120 + 30 = 615 ms; shading 50 self, 80 with its shadow query (328 ms).
    let row = |name: &str| -> Vec<String> {
        let line = stdout
            .lines()
            .find(|l| l.trim_end().ends_with(name))
            .unwrap_or_else(|| panic!("no row for {name} in:\n{stdout}"));
        line.split_whitespace()
            .take(5)
            .map(str::to_string)
            .collect()
    };
    assert_eq!(
        row("cylinder test"),
        ["2870ms", "77.69%", "77.69%", "2870ms", "77.69%"]
    );
    assert_eq!(row("sphere test")[0], "615ms");
    assert_eq!(row("shading")[0], "205ms");
    assert_eq!(row("shading")[3], "328ms");
    assert_eq!(row("closest hit")[3], "3362ms");
}
