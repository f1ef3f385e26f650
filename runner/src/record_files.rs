//! The files of `rtprof record` and the summary it prints. The profile's files are
//! `rtprof profile`'s, written by the same function
//! ([`crate::profile_files::save_profile_files`]) and named after the command
//! (`flat-rtiow.txt`, `flame-rtiow.svg`, …); beside them:
//!
//! | file | what |
//! |---|---|
//! | `perf.data`, `perf.log` | perf's recording (`perf report -i` reads it) and its messages |
//! | `modules.txt`, `modules.json` | per module: samples, shares without a symbol or a stack, what to do |
//! | `phases-P.txt` | the time by phase of ray tracing, by the phase rules ([`crate::record_phases`]), or by the probe beside the rules', and the FPGA question |
//! | `counts-P.txt` | with a probe file: the exact counts, in `rtprof count`'s table, per eye ray ([`crate::record_probe`]) |
//! | `probe.rtprof` | the probe file the program wrote, when it has the probe |
//! | `record.json` | the command, how it ended, CPU and wall time, samples, rate, phases (and the rules' beside the probe's), counts, the FPGA answer, files |

use std::path::Path;

use analysis::profile::flat::FlatProfile;
use analysis::profile::perf_data::coverage::ModuleCoverage;
use reports::format;
use serde::Serialize;

use crate::error::RunError;
use crate::profile_files::{ProfileToSave, SavedProfile, ViewToSave, save_profile_files};
use crate::record::{CallGraph, Recording};
use crate::record_diff::save_record_differential;
use crate::record_phases::{comparison_table, phase_table, phases_text, probe_phases_text};
use crate::record_probe::{PROBE_FILE, ProbeOutcome, ProbeSummary};
use crate::report_files::Pdf;
use crate::staging::save;
use analysis::profile::phase_compare::PhaseComparison;
use analysis::profile::phase_rules::{PhaseBreakdown, PhaseSource};
use reports::record_fpga::TracerFpga;
use reports::record_probe::ProbeReport;
use reports::record_report::RecordReport;
use tracer::Counts;

/// Rows of the flat profile the summary prints (the file has them all).
const SUMMARY_ROWS: usize = 12;

/// `record.json`: what was run, how it ended, what was sampled and where it went.
#[derive(Serialize)]
pub struct RecordSummary<'a> {
    pub command: &'a [String],
    /// "exited with code 0", "was killed by signal SIGSEGV (11)", …
    pub end: String,
    pub exit_code: Option<i32>,
    pub signal: Option<i32>,
    pub success: bool,
    pub cpu_seconds: f64,
    pub wall_seconds: f64,
    pub samples: u64,
    pub samples_per_cpu_second: f64,
    pub frequency: u32,
    pub call_graph: CallGraph,
    pub seconds_per_sample: f64,
    pub lost_samples: u64,
    pub processes: usize,
    pub modules: &'a [ModuleCoverage],
    /// Where `phases` come from: the probe when it sampled phases, else the rules.
    pub phases_source: PhaseSource,
    /// The samples by phase of ray tracing: the probe's, or the phase rules'.
    pub phases: &'a PhaseBreakdown,
    /// The phase rules' breakdown of the same run (the same as `phases` without probe
    /// phases), kept to compare.
    pub rule_phases: &'a PhaseBreakdown,
    /// The probe's phases beside the rules', group by group (empty without them).
    pub phase_comparison: &'a [PhaseComparison],
    /// The probe's exact counts (`rtprof count --json`'s shape); null without a probe file.
    pub counts: Option<&'a Counts>,
    /// The probe file: who wrote it, why, its sampler's figures; null without one.
    pub probe: Option<ProbeSummary<'a>>,
    /// Why the probe file the program wrote could not be read.
    pub probe_error: Option<&'a str>,
    /// The thesis's pipeline on the counted tests against the intersection phases.
    pub fpga: Option<&'a TracerFpga>,
    /// Every file written, relative to the directory.
    pub files: Vec<String>,
}

impl Recording {
    /// Samples per CPU second taken.
    pub fn rate(&self) -> f64 {
        self.samples() as f64 / self.cpu_seconds().max(1e-9)
    }

    /// The phases shown: the probe's when it sampled any, else the phase rules'.
    pub fn shown_phases(&self) -> &PhaseBreakdown {
        self.probe
            .record()
            .and_then(|p| p.phases.as_ref())
            .unwrap_or(&self.phases)
    }

    /// phases-P.txt: by the probe beside the rules, or by the rules; then the FPGA
    /// question when the probe counted tests.
    fn phases_file(&self, title: &str) -> String {
        let probe = self.probe.record();
        let mut out = match probe.and_then(|p| p.phases.as_ref().map(|b| (p, b))) {
            Some((p, b)) => probe_phases_text(title, b, &self.phases, &p.comparison),
            None => phases_text(title, &self.phases),
        };
        if let Some(caveat) = self.frame_pointer_caveat() {
            out += &format!("\nNote: {caveat}.\n");
        }
        if let Some(fpga) = probe.and_then(|p| p.fpga.as_ref()) {
            out += "\nWould the thesis's FPGA pay off for this program?\n\n";
            out += &fpga.text(self.name());
        }
        out
    }

    /// Writes the profile's files, the module table and record.json under `dir`.
    pub fn save(&self, dir: &Path) -> Result<RecordSummary<'_>, RunError> {
        self.save_with_profile(dir).map(|(summary, _)| summary)
    }

    /// [`Recording::save`], with the profile's own files and rows (paths relative to
    /// `dir`), as a suite lists them in results.json.
    pub fn save_with_profile(
        &self,
        dir: &Path,
    ) -> Result<(RecordSummary<'_>, SavedProfile), RunError> {
        let title = format!("{} (rtprof record)", self.command.join(" "));
        let saved: SavedProfile = save_profile_files(
            dir,
            "",
            &ProfileToSave {
                stem: self.name(),
                title: &title,
                wall_seconds: self.finished.wall.as_secs_f64(),
                sampled: format!("one run of {}, {}", self.name(), self.finished.end),
                views: vec![ViewToSave {
                    view: &self.view,
                    suffix: "",
                }],
            },
        )?;
        let modules_json = serde_json::to_string_pretty(&self.perf.modules)
            .map_err(|e| RunError::Profile(e.to_string()))?;
        let mut files = Vec::new();
        for v in &saved.views {
            files.extend([
                v.flat_text.clone(),
                v.callgraph_text.clone(),
                v.flame_svg.clone(),
            ]);
        }
        // Written beside the flamegraph, not named by the results' view entry.
        files.push(format!("folded-{}.txt", results::slug(self.name())));
        files.extend(saved.exports.iter().cloned());
        files.push(save(
            dir,
            "modules.txt",
            modules_text(&self.perf.modules).as_bytes(),
        )?);
        files.push(save(dir, "modules.json", modules_json.as_bytes())?);
        files.push(save(
            dir,
            &format!("phases-{}.txt", self.name()),
            self.phases_file(&title).as_bytes(),
        )?);
        if let Some(p) = self.probe.record() {
            files.push(save(
                dir,
                &format!("counts-{}.txt", self.name()),
                p.counts_text(&title).as_bytes(),
            )?);
        }
        if !matches!(self.probe, ProbeOutcome::Absent) {
            files.push(PROBE_FILE.to_string());
        }
        if let Some(baseline) = &self.baseline {
            let (grown, shrunk) = save_record_differential(
                dir,
                self.name(),
                &self.view.folded,
                self.cpu_seconds(),
                &dir_label(dir),
                baseline,
            )?;
            files.extend([grown, shrunk]);
        }
        files.extend(["perf.data".to_string(), "perf.log".to_string()]);
        files.extend(self.pdf.files().iter().map(|f| f.to_string()));
        files.push("record.json".to_string());
        let flame = saved_flamegraph(dir, &saved);
        self.save_report(dir, flame, &files)?;
        let (exit_code, signal) = match self.finished.end {
            launch::End::Exited(code) => (Some(code), None),
            launch::End::Signalled(s) => (None, Some(s)),
            _ => (None, None),
        };
        let summary = RecordSummary {
            command: &self.command,
            end: self.finished.end.to_string(),
            exit_code,
            signal,
            success: self.finished.end.success(),
            cpu_seconds: self.cpu_seconds(),
            wall_seconds: self.finished.wall.as_secs_f64(),
            samples: self.samples(),
            samples_per_cpu_second: self.rate(),
            frequency: self.frequency,
            call_graph: self.call_graph,
            seconds_per_sample: self.perf.samples.seconds_per_sample,
            lost_samples: self.perf.lost,
            processes: self.perf.processes,
            modules: &self.perf.modules,
            phases_source: self.shown_phases().source,
            phases: self.shown_phases(),
            rule_phases: &self.phases,
            phase_comparison: self.probe.record().map_or(&[], |p| p.comparison.as_slice()),
            counts: self.probe.record().map(|p| &p.counts),
            probe: self.probe.record().map(|p| p.summary()),
            probe_error: self.probe.error(),
            fpga: self.probe.record().and_then(|p| p.fpga.as_ref()),
            files,
        };
        let json =
            serde_json::to_string_pretty(&summary).map_err(|e| RunError::Profile(e.to_string()))?;
        save(dir, "record.json", json.as_bytes())?;
        Ok((summary, saved))
    }

    /// report.html and report.pdf: where the time goes, by phase and by function.
    fn save_report(
        &self,
        dir: &Path,
        flamegraph: Option<(String, String)>,
        files: &[String],
    ) -> Result<(), RunError> {
        let command = self.command.join(" ");
        let end = self.finished.end.to_string();
        let record = self.probe.record();
        let counts = record.map(|p| p.count_rows()).unwrap_or_default();
        let user_counters = record.map(|p| p.user_counters()).unwrap_or_default();
        let probe = record.map(|p| ProbeReport {
            file: PROBE_FILE,
            writer: &p.file.writer,
            threads: p.file.threads,
            counts: &counts,
            user_counters: &user_counters,
            phases: p.phases.as_ref(),
            comparison: &p.comparison,
            fpga: p.fpga.as_ref(),
        });
        write_report(
            dir,
            self.pdf,
            &RecordReport {
                program: self.name(),
                command: &command,
                end: &end,
                success: self.finished.end.success(),
                cpu_seconds: self.cpu_seconds(),
                wall_seconds: self.finished.wall.as_secs_f64(),
                samples: self.samples(),
                frequency: self.frequency,
                call_graph: self.call_graph.describe(),
                lost_samples: self.perf.lost,
                processes: self.perf.processes,
                flat: &self.view.flat,
                phases: &self.phases,
                modules: &self.perf.modules,
                flamegraph,
                files,
                probe,
                probe_error: self.probe.error(),
                caveat: self.frame_pointer_caveat(),
            },
        )
    }

    /// The summary `rtprof record` prints: how the program ended, what was sampled,
    /// the functions with the most self time, the module table, the files.
    pub fn to_text(&self, dir: &Path, summary: &RecordSummary) -> String {
        let mut out = format!(
            "{} {}: {} samples in {} of CPU ({} wall), {} samples per CPU second (asked {} Hz), call stacks by {}\n",
            self.command.join(" "),
            self.finished.end,
            format::count(self.samples()),
            format::seconds(self.cpu_seconds()),
            format::seconds(self.finished.wall.as_secs_f64()),
            format::count(self.rate().round() as u64),
            format::count(u64::from(self.frequency)),
            self.call_graph.describe(),
        );
        if self.perf.lost > 0 {
            out += &format!(
                "perf lost {} samples (its buffers were full)\n",
                format::count(self.perf.lost)
            );
        }
        out += &top_functions_text(&self.view.flat);
        if let Some(e) = self.probe.error() {
            out += &format!(
                "\nwarning: {e}: no exact counts or probe phases; the profile from perf's samples is written\n"
            );
        }
        let shown = self.shown_phases();
        out += &match shown.source {
            PhaseSource::Rules => format!(
                "\nby phase of ray tracing ({}; rules classified {}):\n",
                shown.origin,
                format::percent(100.0 * shown.classified_share(), 1)
            ),
            PhaseSource::Probe => format!(
                "\nby phase of ray tracing ({}: {} samples inside the program, {} in a marked phase):\n",
                shown.origin,
                format::count(shown.samples),
                format::percent(100.0 * shown.classified_share(), 1)
            ),
        };
        out += &phase_table(shown);
        if let Some(caveat) = self.frame_pointer_caveat() {
            out += &format!("note: {caveat}\n");
        }
        if let Some(p) = self.probe.record() {
            if !p.comparison.is_empty() {
                out += &format!("\nbeside {} (perf's samples):\n", self.phases.origin);
                out += &comparison_table(&p.comparison);
            }
            out += &format!("\n{}\n", self.probe_counts_line(p));
            if let Some(fpga) = &p.fpga {
                out += &format!("\n{}\n", fpga.sentence(self.name()));
            }
        }
        out.push('\n');
        out += &modules_text(&self.perf.modules);
        out += &format!(
            "\nwrote {}/{{{}}}\n",
            dir.display(),
            summary.files.join(", ")
        );
        out
    }
}

impl Recording {
    /// One line of what the probe counted: the eye rays and the primitive tests.
    fn probe_counts_line(&self, p: &crate::record_probe::ProbeRecord) -> String {
        let eye = p.counts.rays.primary;
        let tests: Vec<String> = p
            .count_rows()
            .into_iter()
            .filter(|c| c.value > 0 && c.key.starts_with("tests.") && c.key.ends_with(".tests"))
            .map(|c| {
                let per_ray = if eye > 0 {
                    format!(
                        " ({} per eye ray)",
                        format::quantity(c.value as f64 / eye as f64)
                    )
                } else {
                    String::new()
                };
                // tests.sphere.tests -> "sphere tests"
                let kind = c.key.split('.').nth(1).unwrap_or_default();
                format!("{} {kind} tests{per_ray}", format::count(c.value))
            })
            .collect();
        format!(
            "the probe counted {} eye rays{}; every count in counts-{}.txt",
            format::count(eye),
            if tests.is_empty() {
                String::new()
            } else {
                format!(" and {}", format::join_list(&tests))
            },
            self.name()
        )
    }
}

/// The functions with the most self time, with their self and inclusive shares.
pub fn top_functions_text(flat: &FlatProfile) -> String {
    let mut out = String::from("\n   self  inclusive  function\n");
    for row in flat.rows.iter().take(SUMMARY_ROWS) {
        out += &format!(
            "{:>7}  {:>9}  {}\n",
            format::percent(row.percent, 1),
            format::percent(row.inclusive_percent, 1),
            row.name
        );
    }
    out
}

/// This run's name in a differential's titles: its directory's.
pub fn dir_label(dir: &Path) -> String {
    dir.file_name()
        .map_or_else(|| "this run".into(), |n| n.to_string_lossy().into_owned())
}

/// Writes `phases-NAME.txt`; returns its name.
pub fn save_phases(
    dir: &Path,
    name: &str,
    title: &str,
    phases: &PhaseBreakdown,
    caveat: Option<&str>,
) -> Result<String, RunError> {
    save(
        dir,
        &format!("phases-{name}.txt"),
        phases_with_caveat(title, phases, caveat).as_bytes(),
    )
}

/// The flamegraph just written (its SVG and file name), for the report to embed.
pub fn saved_flamegraph(dir: &Path, saved: &SavedProfile) -> Option<(String, String)> {
    let file = &saved.views.first()?.flame_svg;
    let svg = std::fs::read_to_string(dir.join(file)).ok()?;
    Some((svg, file.clone()))
}

/// Writes report.html and (unless `pdf` says to skip it, which removes an earlier
/// run's) report.pdf of a recorded (or imported) run.
pub fn write_report(dir: &Path, pdf: Pdf, report: &RecordReport) -> Result<(), RunError> {
    let doc = reports::record_report::build(report);
    save(dir, "report.html", reports::html::render(&doc).as_bytes())?;
    if pdf == Pdf::Skip {
        return pdf.remove_stale(dir);
    }
    let typeset = reports::pdf::render(&doc)
        .map_err(|e| RunError::Report(format!("cannot build report.pdf: {e}")))?;
    save(dir, "report.pdf", &typeset)?;
    Ok(())
}

/// The phases' summary lines: the table and, when it applies, the frame-pointer caveat.
pub fn phases_summary(phases: &PhaseBreakdown, caveat: Option<&str>) -> String {
    let mut out = format!(
        "\nby phase of ray tracing ({}; rules classified {}):\n",
        phases.origin,
        format::percent(100.0 * phases.classified_share(), 1)
    );
    out += &phase_table(phases);
    if let Some(caveat) = caveat {
        out += &format!("note: {caveat}\n");
    }
    out
}

/// The rules' phases text with the frame-pointer caveat, when there is one.
fn phases_with_caveat(title: &str, phases: &PhaseBreakdown, caveat: Option<&str>) -> String {
    let mut out = phases_text(title, phases);
    if let Some(caveat) = caveat {
        out += &format!("\nNote: {caveat}.\n");
    }
    out
}

/// The module table: samples per module (of the innermost frame), the shares with no
/// symbol and no stack, and the advice for large ones.
pub fn modules_text(modules: &[ModuleCoverage]) -> String {
    let total: u64 = modules.iter().map(|m| m.samples).sum();
    let width = modules
        .iter()
        .map(|m| m.module.chars().count())
        .max()
        .unwrap_or(6)
        .max(6);
    let mut out = format!(
        "{:<width$}  {:>9}  {:>7}  {:>9}  {:>8}  {:>9}\n",
        "module", "samples", "share", "no symbol", "no stack", "cut short"
    );
    for m in modules {
        out += &format!(
            "{:<width$}  {:>9}  {:>7}  {:>9}  {:>8}  {:>9}\n",
            m.module,
            format::count(m.samples),
            format::percent(100.0 * m.samples as f64 / total.max(1) as f64, 1),
            format::percent(m.percent(m.no_symbol), 1),
            format::percent(m.percent(m.no_stack), 1),
            format::percent(m.percent(m.cut_short), 1),
        );
        for advice in &m.advice {
            out += &format!("  {}: {advice}\n", m.module);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_module_table_gives_shares_and_advice() {
        let mut lib = ModuleCoverage::new(
            "libtachyon-mt-thr.so.0.0.0",
            "/usr/lib/libtachyon-mt-thr.so.0.0.0",
        );
        lib.samples = 300;
        lib.no_symbol = 270;
        lib.advise(false, 400);
        let mut exe = ModuleCoverage::new("tachyon", "/usr/bin/tachyon");
        exe.samples = 100;
        let text = modules_text(&[lib, exe]);
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[0].starts_with("module"), "{text}");
        assert!(lines[1].starts_with("libtachyon-mt-thr.so.0.0.0"), "{text}");
        assert!(
            lines[1].contains("75.0 %") && lines[1].contains("90.0 %"),
            "{text}"
        );
        assert!(lines[2].contains("-g"), "{text}");
        assert!(
            lines[3].starts_with("tachyon") && lines[3].contains("25.0 %"),
            "{text}"
        );
    }
}
