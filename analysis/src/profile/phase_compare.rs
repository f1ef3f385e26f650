//! Two breakdowns of one run by phase set side by side: the probe's (the program's own
//! phase marks) and the phase rules' (names of the sampled frames).
//!
//! The two name the same work differently. A program marks what it chooses: RTIOW's
//! probe patch marks the closest-hit query as one phase, BVH walk and sphere tests
//! inside it, where the rules tell the walk (`bvh_node::hit`, `aabb::hit`) from the test
//! (`sphere::hit`). So the shares are compared over **groups of work** each side can
//! express: the camera's rays; the intersection queries (every query, traversal and
//! primitive-test phase); shading; and everything else (set-up, output, the samples in
//! no phase). Within a group, a phase both sides name gets a row of its own too, when
//! the group holds more than that phase on either side.

use serde::Serialize;

use super::phase_rules::PhaseBreakdown;

/// The phases of intersection work, by either side's names: the probe's query phases
/// (a closest-hit or shadow query's own time is its traversal and tests, unless the
/// program marked those inside it), traversal, and each primitive kind's test.
pub const INTERSECTION_PHASES: &[&str] = &[
    "closest hit",
    "shadow query",
    "traversal",
    "sphere test",
    "cylinder test",
    "cone test",
    "polygon test",
    "patch test",
    "triangle test",
    "other primitive tests",
];

/// The groups of work compared, in order; the last, `everything else`, takes every
/// phase the others do not name (and the samples in no phase).
pub const GROUPS: &[(&str, &[&str])] = &[
    ("camera ray", &["camera ray"]),
    ("intersection", INTERSECTION_PHASES),
    ("shading", &["shading", "reflection/refraction set-up"]),
];

/// The group that takes the phases no other group names.
pub const OTHER_GROUP: &str = "everything else";

/// One row of the comparison: a group of work, or a phase both sides name within one.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PhaseComparison {
    /// The group (`intersection`) or, for a detail row, the phase (`sphere test`).
    pub name: String,
    /// A phase inside the group above it, not a group.
    pub detail: bool,
    /// Shares of all samples (0-1): the probe's and the rules'.
    pub probe: f64,
    pub rules: f64,
    /// The phases with samples that make each side's share.
    pub probe_phases: Vec<String>,
    pub rule_phases: Vec<String>,
}

impl PhaseComparison {
    /// Probe minus rules, in percentage points.
    pub fn difference_points(&self) -> f64 {
        100.0 * (self.probe - self.rules)
    }
}

/// The group a phase belongs to (its name in [`GROUPS`], or [`OTHER_GROUP`]).
pub fn group_of(phase: &str) -> &'static str {
    GROUPS
        .iter()
        .find(|(_, phases)| phases.contains(&phase))
        .map_or(OTHER_GROUP, |(group, _)| group)
}

/// The phases of `b` with samples in `group`, and their summed share.
fn in_group<'a>(b: &'a PhaseBreakdown, group: &str) -> (f64, Vec<&'a str>) {
    let phases: Vec<&str> = b
        .phases
        .iter()
        .filter(|p| group_of(&p.phase) == group)
        .map(|p| p.phase.as_str())
        .collect();
    let share = b
        .phases
        .iter()
        .filter(|p| group_of(&p.phase) == group)
        .map(|p| p.share)
        // From +0: an empty sum of floats is -0, which prints as "-0.0 %".
        .fold(0.0, |a, b| a + b);
    (share, phases)
}

/// The probe's and the rules' shares, group by group (see the module's doc).
pub fn compare(probe: &PhaseBreakdown, rules: &PhaseBreakdown) -> Vec<PhaseComparison> {
    let mut rows = Vec::new();
    let names = GROUPS.iter().map(|(g, _)| *g).chain([OTHER_GROUP]);
    for group in names {
        let (p_share, p_phases) = in_group(probe, group);
        let (r_share, r_phases) = in_group(rules, group);
        let owned = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        rows.push(PhaseComparison {
            name: group.to_string(),
            detail: false,
            probe: p_share,
            rules: r_share,
            probe_phases: owned(&p_phases),
            rule_phases: owned(&r_phases),
        });
        // The rest rows are no phase of the work: never a detail of their own.
        let both: Vec<&str> = p_phases
            .iter()
            .filter(|p| r_phases.contains(p) && !probe.is_rest(p) && !rules.is_rest(p))
            .copied()
            .collect();
        if p_phases.len() > 1 || r_phases.len() > 1 {
            for phase in both {
                rows.push(PhaseComparison {
                    name: phase.to_string(),
                    detail: true,
                    probe: probe.share_of(phase),
                    rules: rules.share_of(phase),
                    probe_phases: vec![phase.to_string()],
                    rule_phases: vec![phase.to_string()],
                });
            }
        }
    }
    rows
}

/// The intersection phases of `b` with samples: their CPU seconds and names.
pub fn intersection_time(b: &PhaseBreakdown) -> (f64, Vec<String>) {
    let phases: Vec<_> = b
        .phases
        .iter()
        .filter(|p| INTERSECTION_PHASES.contains(&p.phase.as_str()))
        .collect();
    (
        phases.iter().map(|p| p.seconds).fold(0.0, |a, b| a + b),
        phases.iter().map(|p| p.phase.clone()).collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::phase_rules::{OUTSIDE, PhaseRules};
    use crate::profile::{Stack, StackSamples};
    use std::collections::BTreeMap;

    /// RTIOW's shape: the probe marks camera ray, closest hit (walk and tests inside)
    /// and shading; the rules tell the walk from the test.
    fn rtiow() -> (PhaseBreakdown, PhaseBreakdown) {
        let probe = PhaseBreakdown::from_counted(
            "probe",
            &[
                ("camera ray".into(), 10),
                ("closest hit".into(), 62),
                ("shading".into(), 20),
            ],
            8,
            0.004,
        );
        let stack = |frames: &str, count| Stack {
            frames: frames.split(';').map(str::to_string).collect(),
            count,
        };
        let samples = StackSamples {
            stacks: vec![
                stack("main;camera::render;camera::get_ray", 12),
                stack("main;camera::ray_color;bvh_node::hit;aabb::hit", 40),
                stack("main;camera::ray_color;bvh_node::hit;sphere::hit", 20),
                stack("main;camera::ray_color;lambertian::scatter", 18),
                stack("main;write_color", 4),
                stack("main;memcpy", 6),
            ],
            seconds_per_sample: 0.001,
        };
        let rules = PhaseRules::builtin()
            .unwrap()
            .classify(&samples, &BTreeMap::new());
        (probe, rules)
    }

    #[test]
    fn groups_add_the_phases_each_side_names() {
        let (probe, rules) = rtiow();
        let rows = compare(&probe, &rules);
        let row = |name: &str| rows.iter().find(|r| r.name == name).unwrap();
        // By hand: intersection is the probe's closest hit, 62 of 100, against the
        // rules' traversal 40 + sphere test 20 of 100.
        let i = row("intersection");
        assert!((i.probe - 0.62).abs() < 1e-12 && (i.rules - 0.60).abs() < 1e-12);
        assert!((i.difference_points() - 2.0).abs() < 1e-9);
        assert_eq!(i.probe_phases, ["closest hit"]);
        assert_eq!(i.rule_phases, ["traversal", "sphere test"]);
        assert!((row("camera ray").rules - 0.12).abs() < 1e-12);
        assert!((row("shading").probe - 0.20).abs() < 1e-12);
        // Everything else: the probe's 8 outside; the rules' image output 4 and 6
        // unclassified.
        let other = row(OTHER_GROUP);
        assert!((other.probe - 0.08).abs() < 1e-12 && (other.rules - 0.10).abs() < 1e-12);
        assert_eq!(other.probe_phases, [OUTSIDE]);
        // No phase both sides name inside a group of several: no detail rows.
        assert!(rows.iter().all(|r| !r.detail), "{rows:?}");
        // Each side's groups add up to the whole.
        let sum = |f: fn(&PhaseComparison) -> f64| rows.iter().map(f).sum::<f64>();
        assert!((sum(|r| r.probe) - 1.0).abs() < 1e-12);
        assert!((sum(|r| r.rules) - 1.0).abs() < 1e-12);
        // The intersection time: the probe's closest hit, 62 × 4 ms.
        let (seconds, phases) = intersection_time(&probe);
        assert!((seconds - 0.248).abs() < 1e-12);
        assert_eq!(phases, ["closest hit"]);
    }

    #[test]
    fn a_phase_both_sides_name_inside_a_group_gets_its_own_row() {
        let (_, rules) = rtiow();
        // The fixture's shape: the sphere loop marked inside the closest-hit query.
        let probe = PhaseBreakdown::from_counted(
            "probe",
            &[("closest hit".into(), 5), ("sphere test".into(), 80)],
            15,
            0.004,
        );
        let rows = compare(&probe, &rules);
        let at = rows.iter().position(|r| r.name == "intersection").unwrap();
        let detail = &rows[at + 1];
        assert!(detail.detail);
        assert_eq!(detail.name, "sphere test");
        assert!((detail.probe - 0.80).abs() < 1e-12 && (detail.rules - 0.20).abs() < 1e-12);
        assert_eq!(group_of("reflection/refraction set-up"), "shading");
        assert_eq!(group_of("bvh build"), OTHER_GROUP);
        // A group neither side has: +0, not -0 (which would print "-0.0 %").
        let shading = rows.iter().find(|r| r.name == "shading").unwrap();
        assert!(shading.probe.is_sign_positive() && shading.probe == 0.0);
    }
}
