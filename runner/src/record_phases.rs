//! `phases-P.txt` of `rtprof record`: the recorded program's time by phase of ray
//! tracing (by the phase rules, [`analysis::profile::phase_rules`], or by the program's
//! probe when it wrote one, beside the rules'), what each phase would buy by Amdahl's
//! law, what each rule classified and what no rule did.

use analysis::profile::amdahl::speedup;
use analysis::profile::phase_compare::PhaseComparison;
use analysis::profile::phase_rules::PhaseBreakdown;
use reports::format;

/// The phases by the rules as text: the table, Amdahl per phase, the rules, the
/// unclassified frames.
pub fn phases_text(title: &str, b: &PhaseBreakdown) -> String {
    let mut out = format!(
        "Phases of {title}, by {}\n\
         A sample's phase is that of the innermost frame of its stack a rule matches\n\
         (inlined functions are frames of their own); rules classified {} of {} samples.\n\n",
        b.origin,
        format::percent(100.0 * b.classified_share(), 1),
        format::count(b.samples),
    );
    out += &phase_table(b);
    out += &amdahl_text(b);
    out += &rules_text(b);
    out
}

/// The phases by the probe as text: its table, the rules' beside it group by group,
/// Amdahl per phase, then the rules' own breakdown and what each rule classified.
pub fn probe_phases_text(
    title: &str,
    probe: &PhaseBreakdown,
    rules: &PhaseBreakdown,
    comparison: &[PhaseComparison],
) -> String {
    let per_sample = if probe.samples > 0 {
        probe.phases.iter().map(|p| p.seconds).sum::<f64>() / probe.samples as f64
    } else {
        0.0
    };
    let mut out = format!(
        "Phases of {title}, by {}\n\
         A sample's phase is the innermost phase the program had marked when the probe's\n\
         sampler (inside the program, on each thread's CPU time) took it: {} samples, one\n\
         every {} of CPU; {} of them in a marked phase.\n\n",
        probe.origin,
        format::count(probe.samples),
        format::seconds(per_sample),
        format::percent(100.0 * probe.classified_share(), 1),
    );
    out += &phase_table(probe);
    out += &format!(
        "\nBeside {}\n\
         (perf's {} samples of the same run, by function name), over groups of work both\n\
         can name (an indented row is a phase both name inside its group):\n\n",
        rules.origin,
        format::count(rules.samples),
    );
    out += &comparison_table(comparison);
    out += &amdahl_text(probe);
    out += &format!(
        "\nThe same run by {}: rules classified {} of {} samples.\n\n",
        rules.origin,
        format::percent(100.0 * rules.classified_share(), 1),
        format::count(rules.samples),
    );
    out += &phase_table(rules);
    out += &rules_text(rules);
    out
}

/// The probe's and the rules' shares side by side, with the difference in points.
pub fn comparison_table(rows: &[PhaseComparison]) -> String {
    let width = rows
        .iter()
        .map(|r| r.name.chars().count() + if r.detail { 2 } else { 0 })
        .max()
        .unwrap_or(4)
        .max(4);
    let mut out = format!(
        "{:<width$}  {:>7}  {:>7}  {:>10}  probe's phases · rules' phases\n",
        "work", "probe", "rules", "difference"
    );
    let list = |v: &[String]| {
        if v.is_empty() {
            "none".to_string()
        } else {
            v.join(", ")
        }
    };
    for r in rows {
        let name = if r.detail {
            format!("  {}", r.name)
        } else {
            r.name.clone()
        };
        out += &format!(
            "{name:<width$}  {:>7}  {:>7}  {:>10}  {} · {}\n",
            format::percent(100.0 * r.probe, 1),
            format::percent(100.0 * r.rules, 1),
            format!("{} pt", format::fixed(r.difference_points(), 1)),
            list(&r.probe_phases),
            list(&r.rule_phases),
        );
    }
    out
}

/// Amdahl's law per phase: the whole run's speed-up if the phase became 2×, 10× or
/// infinitely faster.
fn amdahl_text(b: &PhaseBreakdown) -> String {
    let mut out = String::from(
        "\nWhole-run speed-up (Amdahl's law) if a phase became 2x, 10x or infinitely faster:\n\n",
    );
    out += &format!(
        "{:<width$}  {:>7}  {:>7}  {:>7}  {:>8}\n",
        "phase",
        "share",
        "2x",
        "10x",
        "infinite",
        width = name_width(b),
    );
    for p in b.phases.iter().filter(|p| !b.is_rest(&p.phase)) {
        out += &format!(
            "{:<width$}  {:>7}  {:>7}  {:>7}  {:>8}\n",
            p.phase,
            format::percent(100.0 * p.share, 1),
            format::speedup(speedup(p.share, 2.0)),
            format::speedup(speedup(p.share, 10.0)),
            format::speedup(speedup(p.share, f64::INFINITY)),
            width = name_width(b),
        );
    }
    out
}

/// What each rule classified, and the frames no rule matched.
fn rules_text(b: &PhaseBreakdown) -> String {
    let mut out = String::from(
        "\nWhat each rule classified (a frame takes the first rule that matches it):\n\n",
    );
    for r in &b.rules {
        out += &format!(
            "rule {} (line {}) -> {}: {} samples ({})\n    {}\n",
            r.rule,
            r.line,
            r.phase,
            format::count(r.samples),
            format::percent(100.0 * r.samples as f64 / b.samples.max(1) as f64, 1),
            r.patterns,
        );
        for (f, n) in r.functions.iter().take(5) {
            out += &format!("    {:>9}  {f}\n", format::count(*n));
        }
    }
    if b.unclassified > 0 {
        out += &format!(
            "\nNo rule matched {} ({}); their innermost frames (write a rule with\n\
             `rtprof record --phases FILE` to give them a phase):\n",
            format::plural(b.unclassified as usize, "sample"),
            format::percent(100.0 * (1.0 - b.classified_share()), 1),
        );
        for (f, n) in &b.unclassified_frames {
            out += &format!("    {:>9}  {f}\n", format::count(*n));
        }
    }
    out
}

/// The phase table alone (the summary prints it): samples, share and its 95 %
/// interval, CPU seconds.
pub fn phase_table(b: &PhaseBreakdown) -> String {
    let width = name_width(b);
    let mut out = format!(
        "{:<width$}  {:>9}  {:>7}  {:>17}  {:>9}\n",
        "phase", "samples", "share", "95 % interval", "CPU"
    );
    for p in &b.phases {
        out += &format!(
            "{:<width$}  {:>9}  {:>7}  {:>17}  {:>9}\n",
            p.phase,
            format::count(p.samples),
            format::percent(100.0 * p.share, 1),
            format!(
                "{} - {}",
                format::percent(100.0 * p.interval.low, 1),
                format::percent(100.0 * p.interval.high, 1)
            ),
            format::seconds(p.seconds),
        );
    }
    out
}

fn name_width(b: &PhaseBreakdown) -> usize {
    b.phases
        .iter()
        .map(|p| p.phase.chars().count())
        .max()
        .unwrap_or(5)
        .max(5)
}

#[cfg(test)]
mod tests {
    use super::*;
    use analysis::profile::phase_rules::PhaseRules;
    use analysis::profile::{Stack, StackSamples};
    use std::collections::BTreeMap;

    #[test]
    fn the_text_gives_shares_amdahl_rules_and_what_stayed_unclassified() {
        let samples = StackSamples {
            stacks: vec![
                Stack {
                    frames: vec!["main".into(), "bvh_node::hit".into(), "sphere::hit".into()],
                    count: 3,
                },
                Stack {
                    frames: vec!["main".into(), "bvh_node::hit".into()],
                    count: 1,
                },
                Stack {
                    frames: vec!["main".into(), "memcpy".into()],
                    count: 1,
                },
            ],
            seconds_per_sample: 0.01,
        };
        let b = PhaseRules::builtin()
            .unwrap()
            .classify(&samples, &BTreeMap::new());
        let text = phases_text("rtiow", &b);
        // By hand: sphere 3 of 5 = 60 %, 0.03 s; traversal 20 %; 20 % unclassified.
        let line = |start: &str| {
            text.lines()
                .find(|l| l.starts_with(start))
                .unwrap_or_else(|| panic!("no {start} line in\n{text}"))
                .to_string()
        };
        assert!(
            text.contains("rules classified 80.0 % of 5 samples"),
            "{text}"
        );
        let sphere = line("sphere test ");
        assert!(
            sphere.contains("60.0 %") && sphere.contains("30.0 ms"),
            "{sphere}"
        );
        // Amdahl: the sphere test 2x faster gives 1 / (0.4 + 0.3) = 1.43x; free 2.5x.
        assert!(
            text.lines().any(|l| l.starts_with("sphere test")
                && l.contains("1.43×")
                && l.contains("2.50×")),
            "{text}"
        );
        assert!(
            line(analysis::profile::phase_rules::UNCLASSIFIED).contains("20.0 %"),
            "{text}"
        );
        assert!(text.contains("No rule matched 1 sample (20.0 %)"), "{text}");
        assert!(text.contains("        1  memcpy"), "{text}");
    }

    #[test]
    fn with_the_probe_its_phases_come_first_and_the_rules_beside_them() {
        use analysis::profile::phase_compare::compare;
        use analysis::profile::phase_rules::OUTSIDE;
        let rules = PhaseRules::builtin().unwrap().classify(
            &StackSamples {
                stacks: vec![
                    Stack {
                        frames: vec!["main".into(), "bvh_node::hit".into()],
                        count: 7,
                    },
                    Stack {
                        frames: vec!["main".into(), "camera::get_ray".into()],
                        count: 3,
                    },
                ],
                seconds_per_sample: 0.001,
            },
            &BTreeMap::new(),
        );
        let probe = PhaseBreakdown::from_counted(
            "the probe",
            &[("closest hit".into(), 60), ("camera ray".into(), 30)],
            10,
            0.004,
        );
        let text = probe_phases_text("rtiow", &probe, &rules, &compare(&probe, &rules));
        assert!(
            text.starts_with("Phases of rtiow, by the probe\n"),
            "{text}"
        );
        assert!(
            text.contains("100 samples, one\nevery 4.00 ms of CPU; 90.0 %"),
            "{text}"
        );
        // Side by side, by hand: intersection 60 % (probe) against 70 % (rules).
        let row = text
            .lines()
            .find(|l| l.starts_with("intersection "))
            .unwrap_or_default();
        assert!(
            row.contains("60.0 %") && row.contains("70.0 %") && row.contains("-10.0 pt"),
            "{row}"
        );
        // Amdahl on the probe's phases, not on the samples outside them.
        assert!(
            text.lines()
                .any(|l| l.starts_with("closest hit") && l.contains("2.50×")),
            "{text}"
        );
        assert!(
            !text
                .lines()
                .any(|l| l.starts_with(OUTSIDE) && l.contains("×"))
        );
        // The rules' own breakdown follows.
        assert!(text.contains("The same run by rtprof's built-in phase rules"));
        assert!(text.contains("What each rule classified"));
    }
}
