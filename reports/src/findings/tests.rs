//! The findings' unit tests, against results built by hand.
use super::*;
use testkit::sample_results;

fn find<'a>(findings: &'a [String], needle: &str) -> &'a String {
    findings
        .iter()
        .find(|f| f.contains(needle))
        .unwrap_or_else(|| panic!("no finding with '{needle}' in {findings:#?}"))
}

#[test]
fn references_are_the_family_std_then_std_then_the_first() {
    let row = |id| BenchmarkRow {
        id,
        time: None,
        instructions: None,
    };
    let rows = [
        row("sqrt/fast-sqrt"),
        row("sqrt/inverse-classic"),
        row("sqrt/inverse-std"),
        row("sqrt/std"),
        row("intersect/sphere/hit"),
        row("intersect/sphere/miss"),
    ];
    let reference = |id| reference_of(id, &rows).map(|r| r.id);
    assert_eq!(reference("sqrt/fast-sqrt"), Some("sqrt/std"));
    assert_eq!(reference("sqrt/inverse-classic"), Some("sqrt/inverse-std"));
    assert_eq!(reference("sqrt/inverse-std"), None);
    assert_eq!(reference("sqrt/std"), None);
    assert_eq!(
        reference("intersect/sphere/miss"),
        Some("intersect/sphere/hit")
    );
    assert_eq!(reference("intersect/sphere/hit"), None);
}

#[test]
fn ids_sort_with_numbers_by_value() {
    let mut ids = [
        "accel/bvh/91",
        "accel/bvh/10",
        "accel/bvh/820",
        "accel/baseline/66430",
        "accel/bvh/66430",
    ];
    ids.sort_by(|a, b| natural_order(a, b));
    assert_eq!(
        ids,
        [
            "accel/baseline/66430",
            "accel/bvh/10",
            "accel/bvh/91",
            "accel/bvh/820",
            "accel/bvh/66430"
        ]
    );
}

#[test]
fn the_measured_span_covers_every_benchmark_file() {
    let mut r = sample_results();
    assert_eq!(
        measured_span(&r),
        " (measured 2026-11-21 10:00 – 2026-11-21 10:05 UTC)"
    );
    r.instructions.clear();
    assert_eq!(measured_span(&r), " (measured 2026-11-21 10:00 UTC)");
    r.criterion.clear();
    assert_eq!(measured_span(&r), "");
}

#[test]
fn the_truth_finding_names_baselines_worst_scene_and_the_furthest_variant() {
    let mut r = sample_results();
    // Hand-set errors against the f64 reference: baseline 0 everywhere but 0.75 on
    // the second scene; one variant at 3.5 on the first.
    for (i, scene) in r.scenes.iter_mut().enumerate() {
        for v in &mut scene.variants {
            let rms = match (i, v.variant.is_reference()) {
                (1, true) => 0.75,
                (0, false) if v.variant.as_str() == "fast-sqrt" => 3.5,
                _ => 0.0,
            };
            if let Some(q) = v.vs_f64_reference.as_mut() {
                q.rms = rms;
            }
        }
    }
    let scenes = r
        .scenes
        .iter()
        .filter(|s| s.variants.iter().any(|v| v.variant.is_reference()))
        .count();
    let said = truth_finding(&r).unwrap();
    let second = &r.scenes[1].name;
    let first = &r.scenes[0].name;
    assert_eq!(
        said,
        format!(
            "Against the independent f64 reference renderer, baseline's pictures are at most RMS 0.75 off (on {second}), and the same to the 8-bit level on {} of {scenes} scenes; the variant furthest from it is fast-sqrt (RMS 3.50 on {first}).",
            scenes - 1
        )
    );
    // Without the reference, no sentence.
    for scene in &mut r.scenes {
        for v in &mut scene.variants {
            v.vs_f64_reference = None;
        }
    }
    assert_eq!(truth_finding(&r), None);
}

#[test]
fn more_instructions_in_less_time_is_called_out() {
    let r = sample_results();
    let rows = benchmark_rows(&r);
    assert_eq!(rows.len(), 3);
    assert!(
        rows.iter()
            .all(|row| row.time.is_some() && row.instructions.is_some())
    );
    let said = instruction_time_disagreements(&r);
    // 11451 / 6330 = 1.81 the instructions, 815 / 1175 = 0.69 the time.
    assert_eq!(said.len(), 1, "{said:#?}");
    assert!(said[0].starts_with("sqrt/fast-sqrt-newton executes 1.81× the instructions of sqrt/std yet takes 0.69× its time"), "{}", said[0]);
}

#[test]
fn agreeing_or_insignificant_differences_are_not_called_out() {
    let mut r = sample_results();
    // Fewer instructions and less time: they agree (5000 / 6330 = 0.79 against
    // 0.69, well within 1.5×).
    r.instructions[1].instructions = 5_000;
    let said = instruction_time_disagreements(&r);
    assert_eq!(said.len(), 1);
    assert!(
        said[0].contains("same way for all 1 benchmarks"),
        "{}",
        said[0]
    );
    // Same direction but 0.30× the instructions for 0.69× the time: off by 2.3×.
    r.instructions[1].instructions = 1_900;
    let said = instruction_time_disagreements(&r);
    assert!(
        said[0].contains("0.30× the instructions of sqrt/std and takes 0.69× its time: the instruction count alone is off by 2.3×"),
        "{said:#?}"
    );
    // More instructions, less time, but the intervals overlap: not significant.
    r.instructions[1].instructions = 11_451;
    r.criterion[0].median.high = 1200.0;
    let said = instruction_time_disagreements(&r);
    assert!(said[0].contains("same way"), "{said:#?}");
    // Nothing counted: nothing said.
    r.instructions.clear();
    assert!(instruction_time_disagreements(&r).is_empty());
}

#[test]
fn sample_findings_name_the_right_things() {
    let r = sample_results();
    let findings = headline_findings(&r);
    assert!((3..=8).contains(&findings.len()), "{findings:#?}");

    // The profile and the fastest variant are the answers' (sections::answers),
    // not findings of their own: a mean over every family hid the story.
    assert!(
        findings.iter().all(|f| !f.contains("fastest variant")),
        "{findings:#?}"
    );

    // Variants leaving the identical band: exactly those with a non-identical band.
    let f = find(&findings, "leave the");
    for variant in &r.suite.variants {
        let leaves = r
            .scenes
            .iter()
            .flat_map(|s| s.variants.iter())
            .filter(|v| &v.variant == variant)
            .any(|v| v.quality.as_ref().is_some_and(|q| q.rms >= 15.0));
        assert_eq!(
            f.contains(&format!("{variant} on")),
            leaves,
            "{variant}: {f}"
        );
    }

    // Hardware speed-up range.
    let speedups: Vec<f64> = r
        .scenes
        .iter()
        .filter_map(|s| s.hardware.as_ref().map(|h| h.speedup))
        .collect();
    let lo = speedups.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = speedups.iter().copied().fold(0.0, f64::max);
    let f = find(&findings, "speed-up over software");
    assert!(
        f.contains(&format!("{lo:.2}×")) && f.contains(&format!("{hi:.2}×")),
        "{f}"
    );

    // Device fit and the multipliers running out.
    let f = find(&findings, "EP4CE115");
    assert!(f.contains("fits") && f.contains("multipliers"), "{f}");

    // Worst table-8 error: intersection memory bits, +168.4 % in the sample (the
    // model's own figure: its delay lines in memory, with the 15-cycle divider of
    // issue 38; +154.2 % with ALTFP_DIV's 6).
    let f = find(&findings, "table 8");
    assert!(
        f.contains("+168.4 %") && f.contains("intersection") && f.contains("memory bits"),
        "{f}"
    );

    let f = find(&findings, "failed");
    assert!(
        f.starts_with("1 part of the run failed") && f.contains("rings / ortho"),
        "{f}"
    );
}

#[test]
fn empty_or_bad_data_gives_fewer_sentences_without_panicking() {
    let mut r = sample_results();
    r.scenes.clear();
    r.profile = None;
    r.hardware = None;
    r.failures.clear();
    assert!(headline_findings(&r).is_empty());

    let mut r = sample_results();
    for s in &mut r.scenes {
        for v in &mut s.variants {
            v.speedup = None;
            if let Some(q) = &mut v.quality {
                q.rms = f64::NAN;
            }
        }
    }
    let findings = headline_findings(&r);
    assert!(!findings.iter().any(|f| f.contains("NaN")), "{findings:#?}");
}

#[test]
fn geometric_mean_ignores_bad_values() {
    assert_eq!(geometric_mean([f64::NAN, -1.0]), None);
    let (m, n) = geometric_mean([2.0, 8.0, f64::INFINITY]).expect("mean");
    assert!((m - 4.0).abs() < 1e-12 && n == 2);
}

/// The EP4CE115 with `le` logic elements used, everything else as the sample's.
fn ep4ce115_at(le: u64) -> DeviceUse {
    let mut d = sample_results().hardware.expect("hardware").devices[0].clone();
    assert_eq!((d.device.as_str(), d.le_capacity), ("EP4CE115", 114_480));
    d.le = le;
    d.fits = le <= d.le_capacity;
    // The rule applied to the figures, as for a file written before `fit_state`.
    d.fit_state = None;
    d
}

#[test]
fn the_stored_fit_state_is_the_one_shown() {
    // hwmodel's verdict as the suite stored it wins over the figures' rule.
    let mut d = ep4ce115_at(83_948);
    assert_eq!(fit_state(&d), FitState::Fits);
    d.fit_state = Some(FitState::FitsOnPaper);
    assert_eq!(fit_state(&d), FitState::FitsOnPaper);
}

#[test]
fn the_device_finding_says_when_the_design_fits_only_on_paper() {
    // 83,948 of 114,480 LEs (73.3 %): within the 85 % headroom.
    let d = ep4ce115_at(83_948);
    assert_eq!(fit_state(&d), FitState::Fits);
    assert_eq!(headroom_warning_of(&d), None);
    // 113,335 LEs, 99 %: fits on paper only, with the one warning sentence.
    let d = ep4ce115_at(113_335);
    assert_eq!(fit_state(&d), FitState::FitsOnPaper);
    assert_eq!(
        headroom_warning_of(&d).as_deref(),
        Some(
            "logic elements at 99.0 % (headroom 85 %) of the device, above the routing \
             headroom: fits on paper, but a design this full rarely routes or meets \
             timing"
        )
    );
    let mut r = sample_results();
    r.hardware.as_mut().expect("hardware").devices[0] = d;
    let f = device_finding(&r).expect("a device finding");
    assert!(
        f.starts_with(
            "The thesis design fits the EP4CE115 only on paper, above the 85 % routing headroom (99 % of its logic elements"
        ),
        "{f}"
    );
    // 97,308 LEs is exactly 85 %: within. Over the device: does not fit, no warning.
    assert_eq!(fit_state(&ep4ce115_at(97_308)), FitState::Fits);
    let over = ep4ce115_at(114_481);
    assert_eq!(fit_state(&over), FitState::DoesNotFit);
    assert_eq!(headroom_warning_of(&over), None);
}
