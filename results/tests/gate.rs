//! The regression gate on synthetic results: a 20 % slow-down with tight intervals
//! fails, identical runs pass, a changed count fails; results round-trip through serde.

use std::collections::BTreeMap;

use results::gate::{Verdict, compare_runs};
use results::{
    Build, Estimate, Machine, Results, SCHEMA, SceneFamily, SceneResult, SuiteInfo, TimeCovers,
    TimingPolicy, VariantName, VariantResult,
};

fn name(v: &str) -> VariantName {
    VariantName::parse(v).expect("a tracer variant")
}

fn variant(name: &str, median: f64, spread: f64, dots: u64) -> VariantResult {
    let mut counts = BTreeMap::new();
    counts.insert("ops.dot".to_string(), dots);
    counts.insert("rays.primary".to_string(), 307_200);
    VariantResult {
        variant: self::name(name),
        time: Estimate {
            median,
            low: median - spread,
            high: median + spread,
        },
        samples: vec![median - spread, median, median + spread],
        preprocessing_seconds: Some(0.001),
        speedup: Some(1.0),
        speedup_interval: None,
        verdict: None,
        counts,
        image: None,
        heat_map: None,
        quality: None,
        histogram: vec![0; 256],
    }
}

fn results(baseline_s: f64, bvh_s: f64, dots: u64) -> Results {
    Results {
        schema: SCHEMA.to_string(),
        created: "2026-11-21T00:00:00Z".into(),
        command: "rtprof suite".into(),
        machine: Machine {
            cpu_model: "test cpu".into(),
            cores: 2,
            os: "Linux".into(),
            hostname: "host".into(),
        },
        build: Build {
            rtprof_version: "0.1.0".into(),
            rustc: "rustc 1.95.0".into(),
            git_commit: "abc".into(),
            profile: "release".into(),
        },
        suite: SuiteInfo {
            name: "test".into(),
            quick: true,
            threads: 2,
            variants: vec![name("baseline"), name("bvh")],
            timing: TimingPolicy {
                min_repeats: 3,
                min_seconds: 0.0,
                max_repeats: 100,
                bootstrap_resamples: 2000,
                confidence: 0.95,
                seed: 1,
                covers: TimeCovers::Tracing,
                interleaved: false,
            },
            wall_seconds: 1.0,
            noise_threshold: None,
            shard: None,
        },
        scenes: vec![SceneResult {
            name: "balls3".into(),
            source: "builtin".into(),
            family: SceneFamily::Balls,
            primitives: 3,
            primitive_counts: BTreeMap::new(),
            width: 64,
            height: 48,
            spd: false,
            variants: vec![
                variant("baseline", baseline_s, 0.01 * baseline_s, dots),
                variant("bvh", bvh_s, 0.01 * bvh_s, dots / 2),
            ],
            hardware: None,
            calibration: None,
        }],
        profile: None,
        hardware: None,
        failures: Vec::new(),
        criterion: Vec::new(),
        instructions: Vec::new(),
    }
}

#[test]
fn twenty_percent_slower_with_tight_intervals_fails() {
    let old = results(1.0, 0.2, 1000);
    let new = results(1.2, 0.2, 1000);
    let gate = compare_runs(&old, &new, 0.05);
    assert!(gate.failed());
    let base = &gate.entries[0];
    assert_eq!(base.verdict, Verdict::Slower);
    assert!((base.change - 0.2).abs() < 1e-12);
    assert_eq!(gate.entries[1].verdict, Verdict::Unchanged);
    assert!(gate.to_text().contains("SLOWER"));
}

#[test]
fn identical_runs_pass_and_a_slow_down_inside_the_threshold_passes() {
    let old = results(1.0, 0.2, 1000);
    assert!(!compare_runs(&old, &old, 0.05).failed());
    // 3 % slower: the intervals (±1 %) do not clear 5 %.
    let new = results(1.03, 0.2, 1000);
    let gate = compare_runs(&old, &new, 0.05);
    assert!(!gate.failed());
    assert_eq!(gate.entries[0].verdict, Verdict::Unchanged);
    // 20 % faster is reported, and passes.
    let faster = results(0.8, 0.2, 1000);
    let gate = compare_runs(&old, &faster, 0.05);
    assert_eq!(gate.entries[0].verdict, Verdict::Faster);
    assert!(!gate.failed());
}

#[test]
fn a_changed_count_fails_even_when_the_time_is_equal() {
    let old = results(1.0, 0.2, 1000);
    let new = results(1.0, 0.2, 1001);
    let gate = compare_runs(&old, &new, 0.05);
    assert!(gate.failed());
    assert_eq!(
        gate.entries[0].count_changes,
        vec![("ops.dot".to_string(), 1000, 1001)]
    );
    assert!(gate.to_text().contains("COUNTS CHANGED"));
}

#[test]
fn results_round_trip_through_serde_and_the_schema_is_checked() {
    let r = results(1.0, 0.2, 1000);
    let text = serde_json::to_string_pretty(&r).unwrap();
    assert_eq!(Results::from_json(&text).unwrap(), r);
    let other = text.replace(SCHEMA, "rtprof.results/0");
    let err = Results::from_json(&other).unwrap_err().to_string();
    assert!(err.contains("rtprof.results/0"), "{err}");
    assert!(Results::from_json("{").is_err());
}

#[test]
fn scenes_in_one_run_only_are_listed_not_failed() {
    let old = results(1.0, 0.2, 1000);
    let mut new = results(1.0, 0.2, 1000);
    new.scenes[0].variants.pop();
    let gate = compare_runs(&old, &new, 0.05);
    assert!(!gate.failed());
    assert_eq!(gate.unmatched, vec!["balls3/bvh (old)".to_string()]);
}
