//! The FPGA question for a tracer rtprof did not write (`rtprof record` with the probe):
//! would the thesis's pipeline do the program's intersection work faster than the
//! program does it?
//!
//! The FPGA side is the probe's counted primitive tests at the thesis pipeline's rate:
//! one intersection unit takes a primitive every 3 cycles (the minimum-distance
//! block's hold, [`hwmodel::design::Design::cycles_per_primitive`]; eq. 49's 3n cycles a
//! pixel) at the thesis's 50 MHz ([`THESIS_CLOCK_HZ`]). The software side is the
//! measured CPU time of the program's intersection phases (queries, traversal and
//! tests: [`analysis::profile::phase_compare::INTERSECTION_PHASES`]), on one core as
//! measured and on all the machine's cores assuming perfect scaling (an upper bound
//! for the software). [`TracerFpga::assumptions`] lists what the comparison takes for
//! granted; the report and phases-P.txt print them beside the figures.

use hwmodel::design::Design;
use hwmodel::frame_timing::THESIS_CLOCK_HZ;
use serde::Serialize;

use crate::format;

/// Primitive kinds the thesis's intersection unit tests (its selector: sphere or
/// cylinder); the probe's other kinds are costed at the same cycles, said as an
/// assumption.
pub const PIPELINE_KINDS: &[&str] = &["sphere", "cylinder"];

/// The primitive-test counters, by kind (`tests.KIND.tests`). The plane test is left
/// out: it is the first step of every polygon and patch test, not a test of its own.
pub const TEST_KINDS: &[&str] = &["sphere", "cylinder", "cone", "polygon", "patch", "triangle"];

/// The thesis pipeline's time for a recorded tracer's tests against the tracer's own.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TracerFpga {
    /// Tests counted, per kind with any (`("sphere", 1234)`), in [`TEST_KINDS`] order.
    pub tests: Vec<(String, u64)>,
    pub total_tests: u64,
    /// Counted kinds the thesis's unit has no test for.
    pub kinds_not_in_pipeline: Vec<String>,
    /// Cycles a test holds the unit, intersection units, clock (the thesis's design).
    pub cycles_per_test: u32,
    pub units: u32,
    pub clock_hz: f64,
    /// `total_tests × cycles_per_test / units / clock_hz`.
    pub fpga_seconds: f64,
    /// The program's intersection phases: their CPU seconds and names.
    pub intersection_seconds: f64,
    pub intersection_phases: Vec<String>,
    /// Where the phases come from ("the probe", "the phase rules").
    pub phase_source: String,
    /// The program's CPU seconds in all phases (the whole run the phases cover).
    pub run_seconds: f64,
    /// Cores of the machine the software may use.
    pub cores: u32,
    /// Software time over FPGA time: above 1 the FPGA is faster. One core: the
    /// intersection phases' CPU time; all cores: that over `cores`.
    pub one_core_speedup: f64,
    pub all_cores_speedup: f64,
    /// The whole run on one core with its intersection phases' time replaced by the
    /// FPGA's (Amdahl: the rest of the work stays in software).
    pub whole_run_speedup: f64,
}

/// The answer from the counted tests per kind (`("sphere", n)`, any order), the
/// intersection phases' CPU seconds and names, the run's CPU seconds and the cores;
/// `None` without tests or without intersection time to set them against.
pub fn tracer_fpga(
    tests: &[(&str, u64)],
    intersection: (f64, Vec<String>),
    phase_source: &str,
    run_seconds: f64,
    cores: u32,
) -> Option<TracerFpga> {
    let (intersection_seconds, intersection_phases) = intersection;
    let counted: Vec<(String, u64)> = TEST_KINDS
        .iter()
        .filter_map(|kind| {
            let n: u64 = tests
                .iter()
                .filter(|(k, _)| k == kind)
                .map(|(_, n)| n)
                .sum();
            (n > 0).then(|| (kind.to_string(), n))
        })
        .collect();
    let total_tests: u64 = counted.iter().map(|(_, n)| n).sum();
    if total_tests == 0 || intersection_seconds <= 0.0 || !intersection_seconds.is_finite() {
        return None;
    }
    let design = Design::thesis();
    let cycles_per_test = design.cycles_per_primitive();
    let units = design.units.max(1);
    // The unit takes a test every `cycles_per_test` cycles; K units share the tests.
    let cycles = total_tests.div_ceil(u64::from(units)) * u64::from(cycles_per_test);
    let fpga_seconds = cycles as f64 / THESIS_CLOCK_HZ;
    let cores = cores.max(1);
    let run_seconds = run_seconds.max(intersection_seconds);
    Some(TracerFpga {
        kinds_not_in_pipeline: counted
            .iter()
            .filter(|(k, _)| !PIPELINE_KINDS.contains(&k.as_str()))
            .map(|(k, _)| k.clone())
            .collect(),
        tests: counted,
        total_tests,
        cycles_per_test,
        units,
        clock_hz: THESIS_CLOCK_HZ,
        fpga_seconds,
        one_core_speedup: intersection_seconds / fpga_seconds,
        all_cores_speedup: intersection_seconds / f64::from(cores) / fpga_seconds,
        whole_run_speedup: run_seconds / (run_seconds - intersection_seconds + fpga_seconds),
        intersection_seconds,
        intersection_phases,
        phase_source: phase_source.to_string(),
        run_seconds,
        cores,
    })
}

/// "4.00× faster" or "2.50× slower": a speed-up (above 1) or slow-down as words, so
/// that a slow-down reads as its factor, not as "0.40×".
pub fn faster_or_slower(speedup: f64) -> String {
    if speedup >= 1.0 {
        format!("{} faster", format::speedup(speedup))
    } else {
        format!("{} slower", format::speedup(1.0 / speedup))
    }
}

impl TracerFpga {
    /// The tests as words: "1,234 sphere tests and 56 cylinder tests".
    pub fn tests_text(&self) -> String {
        let parts: Vec<String> = self
            .tests
            .iter()
            .map(|(kind, n)| format!("{} {kind} tests", format::count(*n)))
            .collect();
        format::join_list(&parts)
    }

    /// The answer in two sentences.
    pub fn sentence(&self, program: &str) -> String {
        format!(
            "On the thesis's pipeline ({} intersection unit, {} cycles a test, {}), {program}'s {} would take {}; its intersection phases ({}, by {}) took {} of CPU. The FPGA would be {} than one core and {} than all {} cores (perfect scaling, an upper bound for the software); the whole run, its other work left in software, would be {} on one core.",
            self.units,
            self.cycles_per_test,
            format::megahertz(self.clock_hz),
            self.tests_text(),
            format::seconds(self.fpga_seconds),
            format::join_list(&self.intersection_phases),
            self.phase_source,
            format::seconds(self.intersection_seconds),
            faster_or_slower(self.one_core_speedup),
            faster_or_slower(self.all_cores_speedup),
            self.cores,
            faster_or_slower(self.whole_run_speedup),
        )
    }

    /// The rows of the comparison: (side, software seconds, FPGA seconds, speed-up).
    pub fn rows(&self) -> [(String, f64, f64, f64); 2] {
        [
            (
                "one core".to_string(),
                self.intersection_seconds,
                self.fpga_seconds,
                self.one_core_speedup,
            ),
            (
                format!("all {} cores", self.cores),
                self.intersection_seconds / f64::from(self.cores),
                self.fpga_seconds,
                self.all_cores_speedup,
            ),
        ]
    }

    /// What the comparison takes for granted, one sentence each.
    pub fn assumptions(&self) -> Vec<String> {
        let mut out = vec![
            format!(
                "The pipeline runs the {} tests the probe counted, at {} cycles each with {} unit and {} (eq. 49: a pixel every 3n cycles for n primitives); its fill, a few hundred cycles a frame, and the scene's upload are left out.",
                format::count(self.total_tests),
                self.cycles_per_test,
                self.units,
                format::megahertz(self.clock_hz),
            ),
            "The pipeline is given the program's tests and nothing else: the program's traversal (which chose those tests) is free to it. The thesis's pipeline has no acceleration structure; it tests every primitive for every eye ray.".to_string(),
            format!(
                "The software time is the CPU time of the intersection phases ({}, by {}): on one core as measured (CPU time summed over the program's threads), on all {} cores divided by {} (perfect scaling: an upper bound for the software).",
                format::join_list(&self.intersection_phases),
                self.phase_source,
                self.cores,
                self.cores,
            ),
        ];
        if !self.kinds_not_in_pipeline.is_empty() {
            out.push(format!(
                "The thesis's unit tests spheres and cylinders only; the {} tests are costed at the same {} cycles.",
                format::join_list(&self.kinds_not_in_pipeline),
                self.cycles_per_test,
            ));
        }
        out
    }

    /// The answer as text lines (phases-P.txt, the summary): the sentence, the two
    /// rows, the assumptions.
    pub fn text(&self, program: &str) -> String {
        let mut out = format!("{}\n\n", self.sentence(program));
        out += &format!(
            "{:<14}  {:>12}  {:>12}  FPGA against the software\n",
            "software on", "software", "FPGA"
        );
        for (side, software, fpga, speedup) in self.rows() {
            out += &format!(
                "{side:<14}  {:>12}  {:>12}  {}\n",
                format::seconds(software),
                format::seconds(fpga),
                faster_or_slower(speedup),
            );
        }
        out += "\nAssumptions:\n";
        for a in self.assumptions() {
            out += &format!("- {a}\n");
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fpga_seconds_are_the_tests_at_3_cycles_and_50_mhz() {
        // By hand: 1,000,000 sphere tests × 3 cycles / 50,000,000 Hz = 0.06 s.
        let want = 1_000_000.0 * 3.0 / 50.0e6;
        assert_eq!(want, 0.06);
        let a = tracer_fpga(
            &[("sphere", 1_000_000), ("cylinder", 0)],
            (0.24, vec!["closest hit".into()]),
            "the probe",
            0.5,
            2,
        )
        .unwrap();
        assert!((a.fpga_seconds - want).abs() < 1e-15, "{}", a.fpga_seconds);
        assert_eq!(a.tests, [("sphere".to_string(), 1_000_000)]);
        // Software 0.24 s on one core: 0.24 / 0.06 = 4×; on two cores 0.12 / 0.06 = 2×.
        assert!((a.one_core_speedup - 4.0).abs() < 1e-12);
        assert!((a.all_cores_speedup - 2.0).abs() < 1e-12);
        // The whole run: 0.5 s becomes 0.5 - 0.24 + 0.06 = 0.32 s, 1.5625× faster.
        assert!((a.whole_run_speedup - 0.5 / 0.32).abs() < 1e-12);
        assert!(a.kinds_not_in_pipeline.is_empty());
        let s = a.sentence("rtiow");
        assert!(
            s.contains("1,000,000 sphere tests would take 60.0 ms"),
            "{s}"
        );
        assert!(s.contains("4.00× faster than one core"), "{s}");
        assert!(s.contains("2.00× faster than all 2 cores"), "{s}");
        assert!(s.contains("would be 1.56× faster on one core"), "{s}");
    }

    #[test]
    fn a_slower_fpga_says_slower_and_other_kinds_are_named() {
        // 50,000,000 triangle tests: 3 s at 50 MHz against 0.6 s of software.
        let a = tracer_fpga(
            &[("triangle", 50_000_000)],
            (0.6, vec!["traversal".into(), "triangle test".into()]),
            "the phase rules",
            1.0,
            4,
        )
        .unwrap();
        assert!((a.fpga_seconds - 3.0).abs() < 1e-12);
        let s = a.sentence("pbrt");
        assert!(s.contains("5.00× slower than one core"), "{s}");
        assert!(s.contains("20.0× slower than all 4 cores"), "{s}");
        assert_eq!(a.kinds_not_in_pipeline, ["triangle"]);
        assert!(
            a.assumptions()
                .iter()
                .any(|l| l.contains("the triangle tests are costed"))
        );
        let text = a.text("pbrt");
        assert!(
            text.lines()
                .any(|l| l.starts_with("one core") && l.ends_with("5.00× slower")),
            "{text}"
        );
    }

    #[test]
    fn no_tests_or_no_intersection_time_gives_no_answer() {
        assert!(tracer_fpga(&[("sphere", 0)], (1.0, vec![]), "p", 1.0, 2).is_none());
        assert!(tracer_fpga(&[("sphere", 10)], (0.0, vec![]), "p", 1.0, 2).is_none());
    }
}
