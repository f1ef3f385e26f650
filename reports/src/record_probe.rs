//! What the probe adds to the report of `rtprof record` (report.html, report.pdf): the
//! exact counts with their cost per eye ray, the probe's phases beside the phase
//! rules', the FPGA question for the program ([`crate::record_fpga`]), and the program
//! set beside the thesis's profile (table 6), by phase and by operation. Plain data in
//! ([`ProbeReport`]), sections out; [`crate::record_report`] places them.

use analysis::profile::phase_compare::{INTERSECTION_PHASES, PhaseComparison};
use analysis::profile::phase_rules::PhaseBreakdown;
use serde::Serialize;

use crate::document::{Block, Cell, Column, Inline, Section, Table, Tone};
use crate::format;
use crate::record_fpga::{TracerFpga, faster_or_slower};
use crate::results::thesis_profile::{TABLE_6, TABLE_6_EYE_RAYS, TABLE_6_SCENE};

/// One standard counter as the probe counted it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CountRow {
    /// The counter table's key (`tests.sphere.tests`).
    pub key: String,
    pub value: u64,
    /// What it counts (the counter table's description).
    pub meaning: String,
}

/// The probe's part of a recorded run's report.
pub struct ProbeReport<'a> {
    /// The probe file's name beside the report.
    pub file: &'a str,
    /// The probe that wrote it (`c`, `rust`) and the threads that used it.
    pub writer: &'a str,
    pub threads: u64,
    /// Every standard counter, in the counter table's order.
    pub counts: &'a [CountRow],
    /// The user's counters: name and total.
    pub user_counters: &'a [(String, u64)],
    /// The probe's phases, when it sampled any: then they are the report's phases.
    pub phases: Option<&'a PhaseBreakdown>,
    /// The probe's phases beside the rules' ([`analysis::profile::phase_compare`]).
    pub comparison: &'a [PhaseComparison],
    pub fpga: Option<&'a TracerFpga>,
}

impl ProbeReport<'_> {
    /// A counter's value by key (0 when absent).
    pub fn count(&self, key: &str) -> u64 {
        self.counts
            .iter()
            .find(|c| c.key == key)
            .map_or(0, |c| c.value)
    }
}

fn section(id: &str, heading: &str, blocks: Vec<Block>) -> Section {
    Section {
        id: id.to_string(),
        heading: heading.to_string(),
        blocks,
        ..Section::default()
    }
}

/// The exact counts: the counters with a value, per eye ray, and the user's counters.
pub fn counts_section(p: &ProbeReport) -> Section {
    let eye = p.count("rays.primary");
    let mut t = Table::new(vec![
        Column::text("counter"),
        Column::number("count"),
        Column::number("per eye ray"),
        Column::text("meaning").grow(),
    ])
    .dense()
    .caption(format!(
        "Counted by the program itself through rtprof's probe ({}, {} threads); counters \
         left at zero are not listed (counts-*.txt has every one: zero is \"none\" or \
         \"not counted\").",
        p.file, p.threads
    ));
    for c in p.counts.iter().filter(|c| c.value > 0) {
        t.rows.push(vec![
            Cell::text(c.key.clone()).code(),
            Cell::count(c.value),
            if eye > 0 {
                let v = c.value as f64 / eye as f64;
                Cell::number(format::quantity(v), v)
            } else {
                Cell::dash()
            },
            Cell::text(c.meaning.clone()),
        ]);
    }
    for (name, value) in p.user_counters {
        t.rows.push(vec![
            Cell::text(name.clone()),
            Cell::count(*value),
            if eye > 0 {
                let v = *value as f64 / eye as f64;
                Cell::number(format::quantity(v), v)
            } else {
                Cell::dash()
            },
            Cell::text("the program's own counter").tone(Tone::Muted),
        ]);
    }
    let mut blocks = Vec::new();
    if t.rows.is_empty() {
        blocks.push(Block::empty(
            "The probe wrote its file but every counter is zero: the program counted nothing.",
        ));
    } else {
        blocks.push(Block::Table(t));
    }
    section("record-counts", "Exact counts (the probe)", blocks)
}

/// The probe's phases beside the rules', group by group.
pub fn comparison_section(rows: &[PhaseComparison]) -> Section {
    let mut t = Table::new(vec![
        Column::text("work"),
        Column::number("probe"),
        Column::number("rules"),
        Column::number("difference").detail("points"),
        Column::text("probe's phases · rules' phases").grow(),
    ])
    .dense()
    .caption(
        "The same run, its time by the program's own phase marks (the probe, sampled inside \
         it) and by the phase rules (perf's samples, by function name), over groups of work \
         both can name; an indented row is a phase both name inside its group.",
    );
    for r in rows {
        let d = r.difference_points();
        t.rows.push(vec![
            Cell::text(if r.detail {
                format!("    {}", r.name)
            } else {
                r.name.clone()
            })
            .tone(if r.detail { Tone::Muted } else { Tone::Neutral }),
            Cell::number(format::percent(100.0 * r.probe, 1), r.probe),
            Cell::number(format::percent(100.0 * r.rules, 1), r.rules),
            Cell::number(format::fixed(d, 1), d).tone(if d.abs() > 5.0 {
                Tone::Warning
            } else {
                Tone::Neutral
            }),
            Cell::text(format!(
                "{} · {}",
                none_if_empty(&r.probe_phases),
                none_if_empty(&r.rule_phases)
            )),
        ]);
    }
    section(
        "record-phase-comparison",
        "The probe's phases beside the phase rules'",
        vec![Block::Table(t)],
    )
}

fn none_if_empty(v: &[String]) -> String {
    if v.is_empty() {
        "none".to_string()
    } else {
        v.join(", ")
    }
}

/// Would the thesis's FPGA pay off for this program's intersection work?
pub fn fpga_section(program: &str, a: &TracerFpga) -> Section {
    let mut t = Table::new(vec![
        Column::text("software on"),
        Column::number("software").detail("intersection phases"),
        Column::number("FPGA").detail("the counted tests"),
        Column::number("FPGA against the software"),
    ])
    .dense()
    .caption(format!(
        "{} at {} cycles a test with {} unit at {}: {} × {} / {} = {}.",
        a.tests_text(),
        a.cycles_per_test,
        a.units,
        format::megahertz(a.clock_hz),
        format::count(a.total_tests),
        a.cycles_per_test,
        format::megahertz(a.clock_hz),
        format::seconds(a.fpga_seconds),
    ));
    for (side, software, fpga, speedup) in a.rows() {
        t.rows.push(vec![
            Cell::text(side),
            Cell::number(format::seconds(software), software),
            Cell::number(format::seconds(fpga), fpga),
            Cell::number(faster_or_slower(speedup), speedup).tone(if speedup >= 1.0 {
                Tone::Good
            } else {
                Tone::Bad
            }),
        ]);
    }
    section(
        "record-fpga",
        "Would the thesis's FPGA pay off for this program?",
        vec![
            Block::text(a.sentence(program)),
            Block::Table(t),
            Block::heading("What this takes for granted"),
            Block::List {
                items: a.assumptions(),
            },
        ],
    )
}

/// One row of table 6 beside the recorded program.
#[derive(Clone, Debug, PartialEq)]
pub struct Table6Beside {
    pub thesis_name: &'static str,
    pub thesis_percent: f64,
    pub thesis_per_ray: f64,
    /// The program's share (percent) of the same phase, when the row is a phase (as
    /// [`TABLE_6`] maps it) and the program has samples in it.
    pub percent: Option<f64>,
    /// The program's calls per eye ray, when the probe counted the row's counter.
    pub per_ray: Option<f64>,
}

/// Table 6's rows of intersection work, and the vector operations its tests call.
const TABLE_6_INTERSECTION: &[&str] = &[
    "Intersection test",
    "Sphere Intersection test",
    "Cylinder Intersection test",
    "Polygon Intersection test",
    "Plane Intersection test",
];
const TABLE_6_TEST_OPERATIONS: &[&str] = &["Vector -", "Vector dotPoint"];

/// The intersection work in both: table 6's intersection rows (percent), the same with
/// the subtractions and dot products its tests call (they are gprof rows of their own
/// there), and the program's intersection phases (percent), if it has any.
pub fn intersection_beside(phases: &PhaseBreakdown) -> (f64, f64, Option<f64>) {
    let sum = |names: &[&str]| -> f64 {
        TABLE_6
            .iter()
            .filter(|r| names.contains(&r.thesis_name))
            .map(|r| r.percent)
            .sum()
    };
    let thesis = sum(TABLE_6_INTERSECTION);
    let with_operations = thesis + sum(TABLE_6_TEST_OPERATIONS);
    let ours: f64 = phases
        .phases
        .iter()
        .filter(|p| INTERSECTION_PHASES.contains(&p.phase.as_str()))
        .map(|p| 100.0 * p.share)
        .sum();
    (thesis, with_operations, (ours > 0.0).then_some(ours))
}

/// Table 6's rows with the program's phase shares and counts per eye ray.
pub fn table6_beside(phases: &PhaseBreakdown, probe: Option<&ProbeReport>) -> Vec<Table6Beside> {
    let eye = probe.map_or(0, |p| p.count("rays.primary"));
    TABLE_6
        .iter()
        .map(|row| Table6Beside {
            thesis_name: row.thesis_name,
            thesis_percent: row.percent,
            thesis_per_ray: row.calls / TABLE_6_EYE_RAYS as f64,
            percent: row
                .phase
                .map(|phase| 100.0 * phases.share_of(phase))
                .filter(|p| *p > 0.0),
            per_ray: probe
                .map(|p| p.count(row.counter))
                .filter(|&n| n > 0 && eye > 0)
                .map(|n| n as f64 / eye as f64),
        })
        .collect()
}

/// The program beside the thesis's table 6, by phase and by operation.
pub fn table6_section(
    program: &str,
    phases: &PhaseBreakdown,
    probe: Option<&ProbeReport>,
) -> Section {
    let rows = table6_beside(phases, probe);
    let (thesis, with_operations, ours) = intersection_beside(phases);
    let mut t = Table::new(vec![
        Column::text("table 6 row"),
        Column::number("thesis % self"),
        Column::number(format!("{program} % self")),
        Column::number("thesis calls").detail("per eye ray"),
        Column::number(format!("{program} calls")).detail("per eye ray"),
    ])
    .dense()
    .caption(format!(
        "Table 6 is gprof's flat profile of the thesis's C++ tracer ({TABLE_6_SCENE}); \
         there each vector operation is a function of its own, so its tests' shares leave \
         out the subtractions and dot products they call, where {program}'s phases hold \
         the operations inlined into them. A share is given only where the row is a phase \
         of the same work (a primitive kind's test, shading) and {program} has samples in \
         it; calls per eye ray only where the probe counted them."
    ));
    let share_cell = |p: Option<f64>| match p {
        Some(p) => Cell::number(format::fixed(p, 2), p),
        None => Cell::dash(),
    };
    t.rows.push(vec![
        Cell::text("all intersection work").hover(
            "Table 6: Intersection test, the sphere, cylinder, polygon and plane tests; in \
             brackets with Vector - and Vector dotPoint, which the tests call. The program: \
             its query, traversal and test phases.",
        ),
        Cell::number(format::fixed(thesis, 2), thesis).detail(format!(
            "{} with Vector - and dotPoint",
            format::fixed(with_operations, 2)
        )),
        share_cell(ours),
        Cell::dash(),
        Cell::dash(),
    ]);
    for r in &rows {
        t.rows.push(vec![
            Cell::text(r.thesis_name),
            Cell::number(format::fixed(r.thesis_percent, 2), r.thesis_percent),
            share_cell(r.percent),
            Cell::number(format::quantity(r.thesis_per_ray), r.thesis_per_ray),
            match r.per_ray {
                Some(n) => Cell::number(format::quantity(n), n),
                None => Cell::dash(),
            },
        ]);
    }
    let mut opening = vec![Inline::text(format!(
        "The thesis's tracer spends {} of its time in intersection work ({} with the \
         vector operations its tests call)",
        format::percent(thesis, 1),
        format::percent(with_operations, 1)
    ))];
    opening.push(Inline::text(match ours {
        Some(p) => format!(
            "; {program} spends {} in its intersection phases.",
            format::percent(p, 1)
        ),
        None => format!("; {program} has no intersection phase with samples."),
    }));
    section(
        "record-table6",
        "Beside the thesis's profile (table 6)",
        vec![Block::Paragraph { content: opening }, Block::Table(t)],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn probe_phases() -> PhaseBreakdown {
        PhaseBreakdown::from_counted(
            "the probe",
            &[
                ("closest hit".into(), 30),
                ("sphere test".into(), 40),
                ("shading".into(), 20),
            ],
            10,
            0.01,
        )
    }

    #[test]
    fn table_6_rows_take_the_program_s_phases_and_counts_per_eye_ray() {
        let counts = [
            ("rays.primary", 100),
            ("tests.sphere.tests", 3_200),
            ("ops.dot", 0),
        ]
        .map(|(k, v)| CountRow {
            key: k.into(),
            value: v,
            meaning: String::new(),
        });
        let phases = probe_phases();
        let probe = ProbeReport {
            file: "probe.rtprof",
            writer: "c",
            threads: 1,
            counts: &counts,
            user_counters: &[],
            phases: Some(&phases),
            comparison: &[],
            fpga: None,
        };
        let rows = table6_beside(&phases, Some(&probe));
        let row = |n: &str| rows.iter().find(|r| r.thesis_name == n).unwrap();
        // By hand: sphere test 40 of 100 samples; 3,200 tests over 100 eye rays.
        let sphere = row("Sphere Intersection test");
        assert_eq!(sphere.percent, Some(40.0));
        assert_eq!(sphere.per_ray, Some(32.0));
        assert_eq!(row("Shading").percent, Some(20.0));
        // No samples, no count: blank, not zero.
        assert_eq!(row("Cylinder Intersection test").percent, None);
        assert_eq!(row("Vector dotPoint").per_ray, None);
        assert_eq!(row("Vector dotPoint").percent, None);
        // Table 6: 4.22352e9 sphere tests over 640 × 480 eye rays = 13,748.4 a ray.
        assert!((sphere.thesis_per_ray - 4.22352e9 / 307_200.0).abs() < 1e-9);
        // The intersection work: 12.00 + 15.15 + 21.12 + 0.01 + 0.02 = 48.30 in table 6,
        // + 7.55 + 21.91 = 77.76 with its tests' operations; the program's closest hit
        // and sphere test, 30 + 40 = 70.
        let (thesis, with_ops, ours) = intersection_beside(&phases);
        assert!((thesis - 48.30).abs() < 1e-9, "{thesis}");
        assert!((with_ops - 77.76).abs() < 1e-9, "{with_ops}");
        assert!((ours.unwrap() - 70.0).abs() < 1e-9);
        let s = table6_section("rtiow", &phases, Some(&probe));
        assert_eq!(s.id, "record-table6");
        let Block::Table(t) = &s.blocks[1] else {
            panic!("no table")
        };
        assert_eq!(t.rows.len(), 1 + TABLE_6.len());
        assert_eq!(t.rows[0][2].text, "70.00");
        let counts_table = counts_section(&probe);
        let Block::Table(c) = &counts_table.blocks[0] else {
            panic!("no counts table")
        };
        // The zero counter is left out; 3,200 tests are 32.0 per eye ray.
        assert_eq!(c.rows.len(), 2);
        assert_eq!(c.rows[1][2].text, "32.0");
    }
}
