//! `phases-P.txt` of `rtprof record`: the recorded program's time by phase of ray
//! tracing (by the phase rules, [`analysis::profile::phase_rules`]), what each phase
//! would buy by Amdahl's law, what each rule classified and what no rule did.

use analysis::profile::amdahl::speedup;
use analysis::profile::phase_rules::{PhaseBreakdown, UNCLASSIFIED};
use reports::format;

/// The phases as text: the table, Amdahl per phase, the rules, the unclassified frames.
/// `caveat`: what the call stacks may get wrong ([`crate::record::Recording::frame_pointer_caveat`]).
pub fn phases_text(title: &str, b: &PhaseBreakdown, caveat: Option<&str>) -> String {
    let mut out = format!(
        "Phases of {title}, by {}\n\
         A sample's phase is that of the innermost frame of its stack a rule matches\n\
         (inlined functions are frames of their own); rules classified {} of {} samples.\n\n",
        b.origin,
        format::percent(100.0 * b.classified_share(), 1),
        format::count(b.samples),
    );
    out += &phase_table(b);
    if let Some(caveat) = caveat {
        out += &format!("\nNote: {caveat}.\n");
    }
    out +=
        "\nWhole-run speed-up (Amdahl's law) if a phase became 2x, 10x or infinitely faster:\n\n";
    out += &format!(
        "{:<width$}  {:>7}  {:>7}  {:>7}  {:>8}\n",
        "phase",
        "share",
        "2x",
        "10x",
        "infinite",
        width = name_width(b),
    );
    for p in b.phases.iter().filter(|p| p.phase != UNCLASSIFIED) {
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
    out += "\nWhat each rule classified (a frame takes the first rule that matches it):\n\n";
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
        let text = phases_text("rtiow", &b, Some("a caveat"));
        assert!(text.contains("Note: a caveat."), "{text}");
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
        assert!(line(UNCLASSIFIED).contains("20.0 %"), "{text}");
        assert!(text.contains("No rule matched 1 sample (20.0 %)"), "{text}");
        assert!(text.contains("        1  memcpy"), "{text}");
    }
}
