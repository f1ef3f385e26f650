//! Reading results files: a `/1` file written by rtprof at d19ee0e (tests/data) is
//! upgraded with the right enums; mutated files are refused with the JSON path of the
//! bad value; the schema is checked.

use results::{
    Band, FailedPart, HwRowKind, Results, ResultsError, SCHEMA, SceneFamily, TimeCovers,
};
use serde_json::{Value, json};

const V1_MAIN: &str = include_str!("data/v1-main-d19ee0e/results.json");

fn v1() -> Results {
    Results::from_json(V1_MAIN).unwrap_or_else(|e| panic!("the /1 file of main: {e}"))
}

/// The /1 file upgraded and written as /2, as a JSON value to mutate.
fn v2_value() -> Value {
    serde_json::to_value(v1()).expect("serialize")
}

fn read(value: &Value) -> Result<Results, ResultsError> {
    Results::from_json(&serde_json::to_string(value).expect("serialize"))
}

/// The error message of reading `value`, which must fail.
fn refused(value: &Value) -> String {
    match read(value) {
        Ok(_) => panic!("accepted: {value}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_v1_file_of_main_is_upgraded_with_its_enums() {
    let r = v1();
    assert_eq!(r.schema, SCHEMA);
    assert_eq!(r.scenes.len(), 2);
    assert_eq!(r.scenes[0].family, SceneFamily::Balls);
    assert_eq!(r.scenes[1].family, SceneFamily::Cylinder);
    // The file's RMS values are 16.0 and 23.0, in the band written "similar" (the band
    // the issue found coloured as "different").
    for scene in &r.scenes {
        let base = r.baseline(scene).expect("baseline ran");
        assert!(base.variant.is_reference() && base.quality.is_none());
        let fast = &scene.variants[1];
        assert_eq!(fast.variant.as_str(), "fast-sqrt");
        assert!(!fast.variant.is_reference());
        let q = fast.quality.as_ref().expect("quality against baseline");
        assert!((15.0..50.0).contains(&q.rms), "{}", q.rms);
        assert_eq!(q.band, Band::Similar);
        assert_eq!(
            fast.preprocessing_seconds, None,
            "/1 did not measure it apart"
        );
        let hw = scene
            .hardware
            .as_ref()
            .expect("spheres and cylinders run on the model");
        assert_eq!(hw.emulator_band, Band::of(hw.emulator_rms));
    }
    assert_eq!(r.suite.timing.covers, TimeCovers::PreprocessingAndTracing);
    assert_eq!(r.suite.timing.min_repeats, 2);
    assert_eq!(r.suite.variants[0].as_str(), "baseline");
    // The profile job failed in that run: `/1` named the scene "profile".
    assert_eq!(r.failures.len(), 1);
    assert_eq!(r.failures[0].part, FailedPart::Profile);
    assert_eq!(r.failures[0].scene, None);
    // Table 8's primary ray block against the thesis's 62 cycles and 14 008 LEs.
    let hw = r.hardware.as_ref().expect("tables");
    let primary = &hw.blocks[0];
    assert_eq!(primary.name, "primary_ray");
    assert_eq!(primary.kind, HwRowKind::Block);
    let thesis = primary.thesis.expect("thesis figures");
    assert_eq!((thesis.latency, thesis.le, thesis.mult), (62, 14_008, 118));
    let errors = primary.error_pct.expect("errors");
    let expected = (primary.model.latency as f64 - 62.0) / 62.0 * 100.0;
    assert_eq!(errors.latency, Some(expected));
    assert_eq!(hw.ops[0].kind, HwRowKind::IpCore);
    assert!(hw.ops[0].thesis.is_none());
}

#[test]
fn the_v2_form_round_trips() {
    let r = v1();
    let text = serde_json::to_string_pretty(&r).expect("serialize");
    assert!(text.contains("\"band\": \"similar\""));
    assert!(text.contains("\"kind\": \"block\""));
    assert!(text.contains("\"covers\": \"preprocessing_and_tracing\""));
    assert_eq!(Results::from_json(&text).expect("read back"), r);
}

#[test]
fn huge_samples_are_refused_with_their_path() {
    let mut v = v2_value();
    v["scenes"][1]["variants"][0]["samples"][1] = json!(1e308);
    let e = refused(&v);
    assert_eq!(
        e,
        "scenes[1].variants[0].samples[1]: 1e308 s is beyond the plausible range (at most 1e9 s)"
    );
    // Every sample of the file, as in the report.
    let mut v = v2_value();
    for scene in v["scenes"].as_array_mut().expect("scenes") {
        for variant in scene["variants"].as_array_mut().expect("variants") {
            for s in variant["samples"].as_array_mut().expect("samples") {
                *s = json!(1e308);
            }
        }
    }
    assert!(refused(&v).starts_with("scenes[0].variants[0].samples[0]: "));
}

#[test]
fn bad_numbers_are_refused() {
    // JSON has no NaN; a string in its place is a type error at its line and column.
    let text = serde_json::to_string_pretty(&v2_value())
        .expect("serialize")
        .replacen("\"samples\": [\n", "\"samples\": [\n\"NaN\",\n", 1);
    match Results::from_json(&text) {
        Err(ResultsError::Json { line, message, .. }) => {
            assert!(line > 1 && message.contains("expected f64"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    // Beyond f64: serde_json refuses it.
    let text = serde_json::to_string(&v2_value())
        .expect("serialize")
        .replacen("\"wall_seconds\":", "\"wall_seconds\":1e400,\"x\":", 1);
    assert!(matches!(
        Results::from_json(&text),
        Err(ResultsError::Json { .. })
    ));

    let mut v = v2_value();
    v["scenes"][0]["variants"][1]["time"]["low"] = json!(-0.5);
    assert!(
        refused(&v).starts_with("scenes[0].variants[1].time.low: -0.5 s is below"),
        "{}",
        refused(&v)
    );

    let mut v = v2_value();
    let median = v["scenes"][0]["variants"][0]["time"]["median"].clone();
    v["scenes"][0]["variants"][0]["time"]["high"] = json!(median.as_f64().expect("f64") / 2.0);
    assert!(refused(&v).contains("does not hold its median"));

    let mut v = v2_value();
    v["scenes"][0]["variants"][0]["counts"]["rays.primary"] = json!(1u64 << 60);
    assert!(refused(&v).starts_with("scenes[0].variants[0].counts.\"rays.primary\": "));

    let mut v = v2_value();
    v["scenes"][0]["width"] = json!(0);
    assert!(refused(&v).contains("must be positive"));

    let mut v = v2_value();
    v["scenes"][0]["variants"][1]["quality"]["band"] = json!("different");
    assert!(refused(&v).contains("is not the band of RMS"));
}

#[test]
fn referenced_files_stay_inside_the_results_directory() {
    for (path, ok) in [
        ("images/a.png", true),
        ("./images/a.png", true),
        ("../secret.png", false),
        ("images/../../secret.png", false),
        ("/etc/passwd", false),
        ("C:\\x.png", false),
        ("", false),
    ] {
        let mut v = v2_value();
        v["scenes"][0]["variants"][0]["image"] = json!(path);
        match read(&v) {
            Ok(_) => assert!(ok, "{path} accepted"),
            Err(e) => {
                assert!(!ok, "{path}: {e}");
                assert!(e.to_string().starts_with("scenes[0].variants[0].image: "));
            }
        }
    }
}

#[test]
fn an_outside_tracers_recorded_files_stay_inside_the_results_directory() {
    // The report embeds the flat profile and the flamegraph it reads from these paths.
    let outside = json!({
        "variant": "tracer:rtiow",
        "scene": "balls",
        "width": 64,
        "height": 48,
        "command": ["./rtiow", "64"],
        "samples": 1200,
        "cpu_seconds": 0.3,
        "wall_seconds": 0.31,
        "frequency": 4000,
        "call_graph": "frame pointers",
        "directory": "profile/tracer-rtiow",
        "profile": {
            "view": "native",
            "flat": [{"name": "hit", "percent": 40.0, "self_seconds": 0.12,
                      "total_seconds": 0.2, "calls": null}],
            "flat_text": "profile/tracer-rtiow/flat-rtiow.txt",
            "callgraph_text": "profile/tracer-rtiow/callgraph-rtiow.txt",
            "flame_svg": "profile/tracer-rtiow/flame-rtiow.svg"
        },
        "folded": "profile/tracer-rtiow/folded-rtiow.txt",
        "files": ["profile/tracer-rtiow/record.json"]
    });
    let mut v = v2_value();
    v["outside_profiles"] = json!([outside.clone()]);
    read(&v).unwrap_or_else(|e| panic!("{e}"));
    for (field, expected) in [
        (&["directory"][..], "outside_profiles[0].directory: "),
        (
            &["profile", "flat_text"],
            "outside_profiles[0].profile.flat_text: ",
        ),
        (
            &["profile", "callgraph_text"],
            "outside_profiles[0].profile.callgraph_text: ",
        ),
        (
            &["profile", "flame_svg"],
            "outside_profiles[0].profile.flame_svg: ",
        ),
        (&["folded"], "outside_profiles[0].folded: "),
    ] {
        let mut bad = outside.clone();
        let mut at = &mut bad;
        for key in field {
            at = &mut at[*key];
        }
        *at = json!("../../etc/passwd");
        let mut v = v2_value();
        v["outside_profiles"] = json!([bad]);
        let e = refused(&v);
        assert!(
            e.starts_with(expected) && e.contains("leaves the results directory"),
            "{e}"
        );
    }
    let mut bad = outside.clone();
    bad["files"][0] = json!("/etc/passwd");
    v["outside_profiles"] = json!([bad]);
    assert!(refused(&v).starts_with("outside_profiles[0].files[0].path: "));
    let mut bad = outside;
    bad["profile"]["flat"][0]["percent"] = json!(140.0);
    v["outside_profiles"] = json!([bad]);
    assert!(refused(&v).starts_with("outside_profiles[0].profile.flat[0].percent: "));
}

#[test]
fn lists_are_bounded() {
    let mut v = v2_value();
    v["scenes"][0]["variants"][0]["histogram"] = json!(vec![0u64; 300]);
    assert_eq!(
        refused(&v),
        "scenes[0].variants[0].histogram: 300 bins: a gray histogram has 256 (or none)"
    );
    let mut v = v2_value();
    v["scenes"][0]["variants"][0]["samples"] = json!(vec![0.001; 1001]);
    assert!(refused(&v).contains("1001 entries, more than the 1000"));
    let mut v = v2_value();
    v["scenes"][0]["variants"][0]["histogram"][0] = json!(1_000_000);
    assert!(refused(&v).contains("more than the image's 768"));
    let mut v = v2_value();
    let first = v["scenes"][0]["variants"][0].clone();
    v["scenes"][0]["variants"]
        .as_array_mut()
        .expect("variants")
        .push(first);
    assert!(refused(&v).contains("variant 'baseline' appears twice"));
}

#[test]
fn the_schema_is_checked_and_syntax_errors_have_a_position() {
    let mut v = v2_value();
    v["schema"] = json!("rtprof.results/0");
    let e = refused(&v);
    assert!(
        e.contains("'rtprof.results/0'") && e.contains(SCHEMA),
        "{e}"
    );
    let mut v = v2_value();
    v.as_object_mut().expect("object").remove("schema");
    assert!(
        refused(&v).starts_with("not an rtprof results file (no \"schema\" field): "),
        "{}",
        refused(&v)
    );
    match Results::from_json("{\n  \"schema\": \"rtprof.results/2\",\n  oops\n}") {
        Err(ResultsError::Json { line, column, .. }) => assert_eq!((line, column), (3, 3)),
        other => panic!("{other:?}"),
    }
    // Unknown variant names are refused where they stand.
    let text = V1_MAIN.replacen("\"variant\": \"fast-sqrt\"", "\"variant\": \"warp\"", 1);
    let e = Results::from_json(&text)
        .map(|_| ())
        .expect_err("unknown variant");
    assert!(
        e.to_string()
            .starts_with("scenes[0].variants[1].variant: unknown variant 'warp'"),
        "{e}"
    );
}

#[test]
fn the_gate_notes_runs_whose_times_cover_different_things() {
    let old = v1();
    let mut new = old.clone();
    new.suite.timing.covers = TimeCovers::Tracing;
    let options = results::gate::GateOptions::default();
    let gate = results::gate::gate(&old, &new, options).unwrap();
    assert_eq!(
        gate.covers_differ,
        Some((TimeCovers::PreprocessingAndTracing, TimeCovers::Tracing))
    );
    assert!(!gate.failed());
    // A /1 file has no calibration kernel: its baselines are gated on seconds, said.
    assert!(gate.warnings.iter().any(|w| w.contains("gated on seconds")));
    assert_eq!(
        results::gate::gate(&old, &old, options)
            .unwrap()
            .covers_differ,
        None
    );
}

const V2_MAIN: &str = include_str!("data/v2-main-972ba80/results.json");

#[test]
fn a_v2_file_of_main_reads_with_its_profile_marked_as_totals_over_renders() {
    let r = Results::from_json(V2_MAIN).unwrap_or_else(|e| panic!("the /2 file of main: {e}"));
    assert_eq!(r.schema, SCHEMA);
    assert_eq!(r.build.git_commit, "972ba806ca12");
    let p = r
        .profile
        .as_ref()
        .expect("the quick suite profiles its heaviest scene");
    // /2 did not record how many renders were sampled: calls are totals over them,
    // the view is the native one, and there is no second view or export.
    for profile in std::iter::once(&p.baseline).chain(p.best.iter()) {
        assert_eq!(profile.renders, None);
        assert_eq!(profile.view, results::ProfileView::Native);
        assert!(profile.second_view.is_none() && profile.exports.is_empty());
        assert!(
            profile
                .flat
                .iter()
                .all(|row| row.inclusive_percent.is_none() && !row.noise)
        );
        assert!(profile.amdahl.iter().all(|row| row.inclusive.is_none()));
    }
    assert_eq!(p.diff_shrunk_flame_svg, None);
    // Written again it is a /3 file, and reads back the same.
    let again =
        Results::from_json(&serde_json::to_string(&r).expect("serialize")).expect("re-read");
    assert_eq!(again, r);
}
