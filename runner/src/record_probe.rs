//! What `rtprof record` reads from the recorded program's probe (docs/instrumenting.md):
//! the file it names in the program's environment ([`PROBE_FILE`] in the output
//! directory, through `RTPROF_PROBE_FILE`), read after the run with the probe crate's
//! reader. A program without the probe writes none, and nothing changes. From a file:
//! the exact counts (as rtprof's own [`Counts`], by the counter table's keys), the
//! probe's phases (its in-process sampler's, which then replace the phase rules'), the
//! two set side by side, and the FPGA question for the program's tests
//! ([`reports::record_fpga`]). A file that cannot be read is a message naming it, never
//! a failure of the recording: the profile from perf's samples stands.

use std::path::{Path, PathBuf};

use analysis::profile::phase_compare::{PhaseComparison, compare, intersection_time};
use analysis::profile::phase_rules::PhaseBreakdown;
use reports::record_fpga::{TEST_KINDS, TracerFpga, tracer_fpga};
use reports::record_probe::CountRow;
use rtprof_probe::format::{ProbeFile, Reason, read_file};
use serde::Serialize;
use tracer::Counts;
use tracer::counter::{COUNTERS, by_key};

use crate::error::RunError;

/// The probe file's name in the output directory.
pub const PROBE_FILE: &str = "probe.rtprof";

/// How the probe's phases are named where they are the source.
pub const PROBE_ORIGIN: &str = "the probe (the program's own phase marks)";

/// What the program's probe file gave.
#[derive(Debug, Default)]
pub enum ProbeOutcome {
    /// The program wrote no probe file (it has no probe, or did not reach its exit).
    #[default]
    Absent,
    /// Read.
    Read(Box<ProbeRecord>),
    /// Written but unreadable: the reader's message, naming the file.
    Unreadable(String),
}

impl ProbeOutcome {
    /// The record, when the file was read.
    pub fn record(&self) -> Option<&ProbeRecord> {
        match self {
            ProbeOutcome::Read(r) => Some(r),
            _ => None,
        }
    }

    /// Why the file could not be read, when it could not.
    pub fn error(&self) -> Option<&str> {
        match self {
            ProbeOutcome::Unreadable(e) => Some(e),
            _ => None,
        }
    }
}

/// A probe file read, and what is made of it.
#[derive(Debug)]
pub struct ProbeRecord {
    /// The file as read.
    pub file: ProbeFile,
    /// Its standard counters as rtprof's counts.
    pub counts: Counts,
    /// Counter keys rtprof's table does not have (a newer probe), kept out of `counts`.
    pub unknown_counters: Vec<String>,
    /// Its phases, when its sampler took any: then they are the recording's phases.
    pub phases: Option<PhaseBreakdown>,
    /// Its phases beside the phase rules' (empty without probe phases).
    pub comparison: Vec<PhaseComparison>,
    /// The FPGA question for the counted tests; `None` without tests or phase time.
    pub fpga: Option<TracerFpga>,
}

/// Removes a probe file an earlier recording left in `dir` (and the writer's
/// temporary), so that only this run's file is read; returns the path to name in the
/// program's environment, absolute (a program may change its directory before it
/// writes).
pub fn prepare(dir: &Path) -> Result<PathBuf, RunError> {
    let path = dir.join(PROBE_FILE);
    let path = std::path::absolute(&path).map_err(|e| RunError::io("resolve", &path, &e))?;
    for stale in [path.clone(), dir.join(format!("{PROBE_FILE}.tmp"))] {
        match std::fs::remove_file(&stale) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(RunError::io("remove", &stale, &e));
            }
            _ => {}
        }
    }
    Ok(path)
}

/// Reads the probe file at `path` after the run; `rule_phases` are the phase rules'
/// breakdown of the same run (compared with the probe's, and the phases of the FPGA
/// question when the probe sampled none), `cores` the machine's.
pub fn read(path: &Path, rule_phases: &PhaseBreakdown, cores: u32) -> ProbeOutcome {
    if !path.exists() {
        return ProbeOutcome::Absent;
    }
    match read_file(path) {
        Ok(file) => ProbeOutcome::Read(Box::new(ProbeRecord::new(file, rule_phases, cores))),
        Err(e) => ProbeOutcome::Unreadable(e.to_string()),
    }
}

impl ProbeRecord {
    /// What a probe file gives beside the rules' phases of the same run.
    pub fn new(file: ProbeFile, rule_phases: &PhaseBreakdown, cores: u32) -> Self {
        let (counts, unknown_counters) =
            Counts::from_keys(file.counters.iter().map(|c| (c.name.as_str(), c.value)));
        let phases = file.seconds_per_sample().map(|per_sample| {
            let counted: Vec<(String, u64)> = file
                .phases
                .iter()
                .chain(&file.user_phases)
                .map(|p| (p.name.clone(), p.self_samples))
                .collect();
            PhaseBreakdown::from_counted(PROBE_ORIGIN, &counted, file.outside, per_sample)
        });
        let comparison = phases
            .as_ref()
            .map(|p| compare(p, rule_phases))
            .unwrap_or_default();
        let shown = phases.as_ref().unwrap_or(rule_phases);
        let source = if phases.is_some() {
            "the probe"
        } else {
            "the phase rules"
        };
        let tests: Vec<(&str, u64)> = TEST_KINDS
            .iter()
            .map(|kind| {
                let n = by_key(&format!("tests.{kind}.tests")).map_or(0, |d| (d.value)(&counts));
                (*kind, n)
            })
            .collect();
        let run_seconds = shown
            .phases
            .iter()
            .map(|p| p.seconds)
            .fold(0.0, |a, b| a + b);
        let fpga = tracer_fpga(&tests, intersection_time(shown), source, run_seconds, cores);
        ProbeRecord {
            file,
            counts,
            unknown_counters,
            phases,
            comparison,
            fpga,
        }
    }

    /// The standard counters in the counter table's order, with their meanings.
    pub fn count_rows(&self) -> Vec<CountRow> {
        COUNTERS
            .iter()
            .map(|d| CountRow {
                key: d.key.to_string(),
                value: (d.value)(&self.counts),
                meaning: d.description.to_string(),
            })
            .collect()
    }

    /// The user's counters: name and total.
    pub fn user_counters(&self) -> Vec<(String, u64)> {
        self.file
            .user_counters
            .iter()
            .map(|c| (c.name.clone(), c.value))
            .collect()
    }

    /// counts-P.txt: the table `rtprof count` prints, with each count per eye ray,
    /// then the user's counters.
    pub fn counts_text(&self, title: &str) -> String {
        use reports::format::{count, quantity};
        let eye = self.counts.rays.primary;
        let mut out = format!(
            "Exact counts of {title}, by rtprof's probe inside the program ({} probe, {})\n\n",
            self.file.writer,
            reports::format::plural(self.file.threads as usize, "thread"),
        );
        let per_ray = |v: u64| quantity(v as f64 / eye as f64);
        let column: Option<(&str, &dyn Fn(u64) -> String)> =
            (eye > 0).then_some(("per eye ray", &per_ray as &dyn Fn(u64) -> String));
        out += &self.counts.to_text_with(column);
        if eye == 0 {
            out += "\n(no eye rays counted, rays.primary: no cost per eye ray)\n";
        }
        if !self.file.user_counters.is_empty() {
            out += "\nThe program's own counters:\n";
            for c in &self.file.user_counters {
                out += &format!("  {:>16}  {}", count(c.value), c.name);
                if eye > 0 {
                    out += &format!("  ({} per eye ray)", quantity(c.value as f64 / eye as f64));
                }
                out.push('\n');
            }
        }
        if !self.unknown_counters.is_empty() {
            out += &format!(
                "\nCounters this rtprof does not know (a newer probe?), left out: {}\n",
                self.unknown_counters.join(", ")
            );
        }
        out
    }

    /// How the file was written, for the summary: "exit" or "signal 2".
    pub fn reason(&self) -> String {
        match self.file.reason {
            Reason::Exit => "exit".to_string(),
            Reason::Signal(s) => format!("signal {s}"),
        }
    }
}

/// The probe's part of record.json.
#[derive(Serialize)]
pub struct ProbeSummary<'a> {
    /// The file, relative to the directory.
    pub file: &'static str,
    pub writer: &'a str,
    /// Why it was written: "exit" or "signal N".
    pub reason: String,
    pub threads: u64,
    /// Phase samples its in-process sampler took, and the CPU time they cover.
    pub samples: u64,
    pub cpu_seconds: f64,
    pub seconds_per_sample: Option<f64>,
    /// Phase ends that did not match the innermost phase (a program's marking error).
    pub unbalanced: u64,
    pub user_counters: Vec<(String, u64)>,
    pub unknown_counters: &'a [String],
}

impl ProbeRecord {
    /// Its part of record.json.
    pub fn summary(&self) -> ProbeSummary<'_> {
        ProbeSummary {
            file: PROBE_FILE,
            writer: &self.file.writer,
            reason: self.reason(),
            threads: self.file.threads,
            samples: self.file.samples,
            cpu_seconds: self.file.cpu_ns as f64 * 1e-9,
            seconds_per_sample: self.file.seconds_per_sample(),
            unbalanced: self.file.unbalanced,
            user_counters: self.user_counters(),
            unknown_counters: &self.unknown_counters,
        }
    }
}

/// The cores the software may use (what the FPGA question divides by).
pub fn cores() -> u32 {
    std::thread::available_parallelism().map_or(1, |n| n.get() as u32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use analysis::profile::phase_rules::{OUTSIDE, PhaseSource};
    use rtprof_probe::format::parse;

    /// A C probe's file: 1,000,000 sphere tests over 10,000 eye rays; 100 phase samples
    /// over 0.4 s of CPU: camera 10, closest hit 60, shading 20, outside 10.
    const FILE: &str = "rtprof.probe 1\nwriter c\npid 7\nreason exit\nthreads 1\n\
        period_ns 1000000\nsamples 100\ncpu_ns 400000000\nunbalanced 0\n\
        counter 10000 rays.primary\ncounter 1000000 tests.sphere.tests\n\
        counter 90000 tests.sphere.hits\nuser_counter 5000 scattered rays\noutside 10\n\
        phase 10 10 camera ray\nphase 60 60 closest hit\nphase 20 20 shading\n\
        phase 0 0 sphere test\nend\n";

    fn rules() -> PhaseBreakdown {
        PhaseBreakdown::from_counted("rules stand-in", &[("traversal".into(), 1)], 0, 0.1)
    }

    #[test]
    fn a_probe_file_gives_counts_phases_and_the_fpga_answer() {
        let file = parse(FILE.as_bytes()).unwrap();
        let r = ProbeRecord::new(file, &rules(), 2);
        assert_eq!(r.counts.tests.sphere.tests, 1_000_000);
        assert_eq!(r.counts.rays.primary, 10_000);
        assert!(r.unknown_counters.is_empty());
        let phases = r.phases.as_ref().unwrap();
        assert_eq!(phases.source, PhaseSource::Probe);
        assert_eq!(phases.share_of("closest hit"), 0.60);
        assert_eq!(phases.share_of(OUTSIDE), 0.10);
        // 4 ms a sample (0.4 s over 100): closest hit 60 samples = 0.24 s.
        let fpga = r.fpga.as_ref().unwrap();
        assert!((fpga.intersection_seconds - 0.24).abs() < 1e-12);
        // By hand: 1,000,000 × 3 cycles / 50 MHz = 0.06 s; 0.24 / 0.06 = 4; / 2 cores = 2.
        assert!((fpga.fpga_seconds - 1_000_000.0 * 3.0 / 50e6).abs() < 1e-15);
        assert!((fpga.one_core_speedup - 4.0).abs() < 1e-9);
        assert!((fpga.all_cores_speedup - 2.0).abs() < 1e-9);
        assert_eq!(fpga.phase_source, "the probe");
        // The comparison has the four groups.
        assert_eq!(r.comparison.iter().filter(|c| !c.detail).count(), 4);
        // counts-P.txt: the `rtprof count` table with 100 sphere tests per eye ray.
        let text = r.counts_text("rtiow");
        let line = text
            .lines()
            .find(|l| l.starts_with("tests.sphere.tests "))
            .unwrap();
        assert!(
            line.contains(" 1000000  ") && line.contains("  100  ray-sphere"),
            "{line}"
        );
        assert!(
            text.contains("5,000  scattered rays  (0.50 per eye ray)"),
            "{text}"
        );
    }

    #[test]
    fn without_phase_samples_the_rules_phases_answer_the_fpga_question() {
        let counters_only = FILE
            .replace("period_ns 1000000", "period_ns 0")
            .replace("samples 100", "samples 0")
            .replace("outside 10", "outside 0")
            .replace("phase 10 10", "phase 0 0")
            .replace("phase 60 60", "phase 0 0")
            .replace("phase 20 20", "phase 0 0");
        let file = parse(counters_only.as_bytes()).unwrap();
        let r = ProbeRecord::new(file, &rules(), 2);
        assert!(r.phases.is_none() && r.comparison.is_empty());
        let fpga = r.fpga.as_ref().unwrap();
        assert_eq!(fpga.phase_source, "the phase rules");
        assert!((fpga.intersection_seconds - 0.1).abs() < 1e-12);
    }

    #[test]
    fn a_missing_file_is_absent_and_a_bad_one_is_named() {
        let dir = std::env::temp_dir().join(format!("rtprof-probe-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = prepare(&dir).unwrap();
        assert!(matches!(read(&path, &rules(), 2), ProbeOutcome::Absent));
        // Cut short: no `end` line.
        std::fs::write(&path, &FILE[..FILE.len() / 2]).unwrap();
        let outcome = read(&path, &rules(), 2);
        let e = outcome.error().unwrap_or_default().to_string();
        assert!(e.contains(&path.display().to_string()), "{e}");
        assert!(e.contains("not a valid probe file"), "{e}");
        // Garbage bytes: a message, no panic.
        std::fs::write(&path, [0xff, 0x00, 0x17, b'\n']).unwrap();
        assert!(read(&path, &rules(), 2).error().is_some());
        // A stale file is removed before the next run; the path is absolute.
        assert_eq!(prepare(&dir).unwrap(), path);
        assert!(path.is_absolute());
        assert!(!path.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
