//! The regression gate on synthetic results: relative times (variant ÷ baseline,
//! baseline ÷ calibration kernel) survive a uniformly slower machine, a 25 % slow-down
//! of one variant fails, a changed count fails, runs that cannot be compared are
//! refused; results round-trip through serde.

use std::collections::BTreeMap;

use results::gate::{GateOptions, Measure, gate};
use results::{
    Build, Calibration, Estimate, Machine, Results, SCHEMA, SceneFamily, SceneResult, SuiteInfo,
    TimeCovers, TimingPolicy, VariantName, VariantResult, Verdict,
};

fn name(v: &str) -> VariantName {
    VariantName::parse(v).expect("a tracer variant")
}

/// Twelve samples around `median`, about ±1 % in a fixed pattern of 256ths (exact in
/// binary, so that a file round-trips exactly; their median is `median`).
fn samples(median: f64) -> Vec<f64> {
    [
        -2.5, -2.0, -1.25, -0.75, -0.25, 0.0, 0.0, 0.25, 0.75, 1.25, 2.0, 2.5,
    ]
    .iter()
    .map(|k| median * (1.0 + k / 256.0))
    .collect()
}

fn estimate(median: f64) -> Estimate {
    Estimate {
        median,
        low: median * 0.995,
        high: median * 1.005,
    }
}

fn variant(name: &str, median: f64, dots: u64) -> VariantResult {
    let mut counts = BTreeMap::new();
    counts.insert("ops.dot".to_string(), dots);
    counts.insert("rays.primary".to_string(), 307_200);
    VariantResult {
        variant: self::name(name),
        time: estimate(median),
        samples: samples(median),
        cpu_samples: samples(median),
        preprocessing_seconds: Some(0.001),
        speedup: Some(1.0),
        speedup_interval: None,
        verdict: None,
        counts,
        image: None,
        heat_map: None,
        quality: None,
        vs_f64_reference: None,
        histogram: vec![0; 256],
        lane_utilization: None,
        efficiency: None,
        ray_rates: None,
    }
}

/// A run of balls3 with baseline and bvh, and the calibration kernel at `kernel_s`.
fn run(baseline_s: f64, bvh_s: f64, kernel_s: f64, dots: u64) -> Results {
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
            quick: false,
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
                interleaved: true,
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
                variant("baseline", baseline_s, dots),
                variant("bvh", bvh_s, dots / 2),
            ],
            hardware: None,
            calibration: Some(Calibration {
                time: estimate(kernel_s),
                samples: samples(kernel_s),
                cpu_samples: samples(kernel_s),
            }),
            published: None,
            memory: None,
            bvh_quality: Vec::new(),
            pixel_maps: Vec::new(),
            f64_reference: None,
            threads: None,
        }],
        profile: None,
        hardware: None,
        failures: Vec::new(),
        criterion: Vec::new(),
        instructions: Vec::new(),
        peak: None,
    }
}

fn default_gate(old: &Results, new: &Results) -> results::gate::GateReport {
    gate(old, new, GateOptions::default()).expect("comparable runs")
}

#[test]
fn identical_runs_pass_with_every_entry_within_noise() {
    let old = run(1.0, 0.2, 0.01, 1000);
    let g = default_gate(&old, &old);
    assert!(!g.failed());
    assert_eq!(g.entries.len(), 2);
    assert!(g.entries.iter().all(|e| e.verdict == Verdict::WithinNoise));
    assert_eq!(g.entries[0].measure, Measure::RelativeToCalibration);
    assert_eq!(g.entries[1].measure, Measure::RelativeToReference);
    // The relative times: 1.0 / 0.01 = 100 and 0.2 / 1.0 = 0.2, changed by exactly 1.
    assert_eq!(g.entries[0].old.median, 100.0);
    assert_eq!(g.entries[1].new.median, 0.2);
    assert_eq!(g.entries[1].change.median, 1.0);
}

#[test]
fn a_scene_run_without_baseline_is_gated_against_the_calibration_kernel() {
    // The suite's SPD scenes at full size run bvh alone: bvh ÷ kernel, not seconds, so
    // a machine twice as slow on the second run (kernel too) is no regression.
    let only_bvh = |mut r: Results| {
        r.scenes[0].variants.retain(|v| v.variant.as_str() == "bvh");
        r
    };
    let old = only_bvh(run(1.0, 0.2, 0.01, 1000));
    let new = only_bvh(run(2.0, 0.4, 0.02, 1000));
    let g = default_gate(&old, &new);
    assert_eq!(g.entries.len(), 1);
    assert_eq!(g.entries[0].measure, Measure::RelativeToCalibration);
    // 0.2 / 0.01 = 20 in both runs.
    assert_eq!(g.entries[0].old.median, 20.0);
    assert_eq!(g.entries[0].change.median, 1.0);
    assert!(!g.failed());
}

#[test]
fn a_machine_half_as_fast_on_the_second_run_is_not_a_regression() {
    // Every time (renders and kernel) 1.5× longer: the relative times do not move.
    let old = run(1.0, 0.2, 0.01, 1000);
    let new = run(1.5, 0.3, 0.015, 1000);
    let g = default_gate(&old, &new);
    assert!(!g.failed(), "{g:?}");
    for e in &g.entries {
        assert!((e.change.median - 1.0).abs() < 1e-9, "{e:?}");
        assert_eq!(e.verdict, Verdict::WithinNoise);
    }
}

#[test]
fn one_variant_25_percent_slower_fails_and_faster_passes() {
    let old = run(1.0, 0.2, 0.01, 1000);
    let new = run(1.0, 0.25, 0.01, 1000);
    let g = default_gate(&old, &new);
    assert!(g.failed());
    let bvh = &g.entries[1];
    assert_eq!(bvh.verdict, Verdict::Slower);
    assert!((bvh.change.median - 1.25).abs() < 1e-9);
    assert!(bvh.change.low > 1.0);
    assert_eq!(g.entries[0].verdict, Verdict::WithinNoise);
    // The same variant 25 % faster is reported and passes.
    let faster = run(1.0, 0.16, 0.01, 1000);
    let g = default_gate(&old, &faster);
    assert_eq!(g.entries[1].verdict, Verdict::Faster);
    assert!(!g.failed());
    // 5 % slower with ±1 % samples: inside the noise threshold.
    let g = default_gate(&old, &run(1.0, 0.21, 0.01, 1000));
    assert_eq!(g.entries[1].verdict, Verdict::WithinNoise);
    assert!(!g.failed());
}

#[test]
fn the_baseline_is_gated_against_the_calibration_kernel() {
    // Baseline 25 % slower while the kernel (the machine) is unchanged: slower; bvh
    // moved with baseline, so its relative time is unchanged… and is 20 % faster relative.
    let old = run(1.0, 0.2, 0.01, 1000);
    let new = run(1.25, 0.25, 0.01, 1000);
    let g = default_gate(&old, &new);
    assert_eq!(g.entries[0].verdict, Verdict::Slower);
    assert_eq!(g.entries[1].verdict, Verdict::WithinNoise);
    assert!(g.failed());
}

#[test]
fn a_count_changed_by_one_fails_even_when_the_time_is_equal() {
    let old = run(1.0, 0.2, 0.01, 1000);
    let new = run(1.0, 0.2, 0.01, 1001);
    let g = default_gate(&old, &new);
    assert!(g.failed());
    let change = &g.entries[0].count_changes;
    assert_eq!(change.len(), 1);
    assert_eq!(
        (change[0].counter.as_str(), change[0].old, change[0].new),
        ("ops.dot", 1000, 1001)
    );
}

#[test]
fn runs_that_cannot_be_compared_are_refused_unless_forced() {
    let old = run(1.0, 0.2, 0.01, 1000);
    let mut new = old.clone();
    new.suite.threads = 1;
    new.machine.cpu_model = "other cpu".into();
    new.scenes[0].width = 32;
    let err = gate(&old, &new, GateOptions::default())
        .unwrap_err()
        .to_string();
    assert!(err.contains("2 threads against 1"), "{err}");
    assert!(
        err.contains("machine 'test cpu' (2 CPUs) against 'other cpu' (2 CPUs)"),
        "{err}"
    );
    assert!(err.contains("balls3 at 64x48 against 32x48"), "{err}");
    assert!(err.contains("--force"), "{err}");
    let forced = GateOptions {
        force: true,
        ..GateOptions::default()
    };
    let g = gate(&old, &new, forced).unwrap();
    assert_eq!(g.forced_over.len(), 3);
    let mut other = old.clone();
    other.suite.name = "mine".into();
    assert!(gate(&old, &other, GateOptions::default()).is_err());
}

#[test]
fn quick_runs_and_files_without_calibration_are_gated_with_a_warning() {
    let mut old = run(1.0, 0.2, 0.01, 1000);
    old.suite.quick = true;
    old.scenes[0].calibration = None;
    let mut new = old.clone();
    new.scenes[0].calibration = None;
    let g = default_gate(&old, &new);
    assert!(g.warnings.iter().any(|w| w.contains("--quick")));
    assert!(
        g.warnings
            .iter()
            .any(|w| w.contains("1 entry gated on seconds"))
    );
    assert_eq!(g.entries[0].measure, Measure::Seconds);
}

#[test]
fn an_instruction_count_that_grows_beyond_one_percent_fails() {
    let count = |n: u64| results::InstructionCount {
        id: "sqrt/fast-sqrt".into(),
        instructions: n,
        estimated_cycles: None,
        measured: None,
    };
    let mut old = run(1.0, 0.2, 0.01, 1000);
    old.instructions = vec![count(10_000)];
    let mut new = old.clone();
    new.instructions = vec![count(10_050)];
    assert!(!default_gate(&old, &new).failed());
    new.instructions = vec![count(10_200)];
    let g = default_gate(&old, &new);
    assert!(g.failed());
    assert!((g.instructions[0].change - 0.02).abs() < 1e-12);
}

#[test]
fn results_round_trip_through_serde_and_the_schema_is_checked() {
    let r = run(1.0, 0.25, 0.015625, 1000);
    let text = serde_json::to_string_pretty(&r).unwrap();
    assert_eq!(Results::from_json(&text).unwrap(), r);
    let other = text.replace(SCHEMA, "rtprof.results/0");
    let err = Results::from_json(&other).unwrap_err().to_string();
    assert!(err.contains("rtprof.results/0"), "{err}");
    assert!(Results::from_json("{").is_err());
}

#[test]
fn scenes_in_one_run_only_are_listed_not_failed() {
    let old = run(1.0, 0.2, 0.01, 1000);
    let mut new = old.clone();
    new.scenes[0].variants.pop();
    let g = default_gate(&old, &new);
    assert!(!g.failed());
    assert_eq!(g.unmatched, vec!["balls3/bvh (old)".to_string()]);
}
