//! `rtprof record --import FILE`: a recording made elsewhere read into the files a
//! live `rtprof record` writes, as far as the recording holds what they need.
//!
//! - **perf.data** (told by its magic, `PERFILE2`), recorded by `perf record -g` or
//!   `--call-graph dwarf`: read by the reader a live recording uses
//!   ([`analysis::profile::perf_data::read_perf_data`]) into the same sample model and
//!   written by the same writer: flat profile, call graph, folded stacks, flamegraph,
//!   Amdahl table, pprof, speedscope, the module table, record.json. What a live
//!   recording measures itself is taken from the file: the program's CPU time from
//!   the samples' periods (see [`analysis::profile::perf_data::CpuTimeSource`]), no
//!   exit status. Names come from the files at the paths perf recorded, or perf's
//!   copies by build id (`~/.debug`); those found in neither are listed.
//! - **GNU gprof's text output** (`gprof -b PROG gmon.out`, or without `-b`): read by
//!   [`analysis::profile::gprof_import`] into the flat profile and call graph with
//!   gprof's exact call counts; written are those two texts, the Amdahl table (from
//!   gprof's self and propagated time) and record.json. gprof gives callers and
//!   callees, not stacks: no folded stacks, flamegraph, pprof or speedscope file is
//!   made from it (they would invent stacks), and it names no modules.
//!
//! Anything else is bad input naming the file, never a panic.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};

use analysis::profile::amdahl::{amdahl_table, amdahl_text};
use analysis::profile::flat::FlatProfile;
use analysis::profile::gprof_import::{self, GprofFileError, GprofImportError, ImportedGprof};
use analysis::profile::perf_data::header::has_magic;
use analysis::profile::perf_data::{PerfProfile, read_perf_data};
use reports::format;
use results::ProfileView;
use serde::Serialize;

use crate::error::RunError;
use crate::profile_files::{ProfileToSave, ViewToSave, save_profile_files};
use crate::profile_job::ViewProfile;
use crate::record::{CallGraph, RecordSettings, frame_pointer_caveat};
use crate::record_diff::{Baseline, read_baseline, save_record_differential};
use crate::record_files::{
    dir_label, modules_text, phases_summary, save_phases, saved_flamegraph, top_functions_text,
    write_report,
};
use crate::report_files::Pdf;
use crate::staging::save;
use analysis::profile::phase_rules::{PhaseBreakdown, PhaseRules};
use reports::record_report::RecordReport;

/// Rows of the Amdahl table (as `rtprof profile`'s).
const AMDAHL_ROWS: usize = 10;
/// Larger than any gprof text: a file this big that is not perf.data is refused
/// before it is read whole.
const MAX_TEXT_BYTES: u64 = 256 << 20;
/// The magic of gprof's binary profile data.
const GMON_MAGIC: &[u8; 4] = b"gmon";
const ELF_MAGIC: &[u8; 4] = b"\x7fELF";

/// A recording read from a file.
pub enum Imported {
    // Boxed: the profile's views make it far larger than gprof's tables.
    Perf(Box<PerfImport>),
    Gprof(GprofImport),
}

/// A perf.data recorded elsewhere and its native-symbol view.
pub struct PerfImport {
    pub source: PathBuf,
    /// The program (the process with the most samples), or the file's name.
    pub name: String,
    pub perf: PerfProfile,
    pub view: ViewProfile,
    /// The samples by phase of ray tracing, by the phase rules.
    pub phases: PhaseBreakdown,
    /// The earlier record `--baseline` named.
    pub baseline: Option<Baseline>,
}

/// gprof's flat profile and call graph.
pub struct GprofImport {
    pub source: PathBuf,
    /// The file's name without its extension (gprof's text does not name the program).
    pub name: String,
    pub gprof: ImportedGprof,
}

/// `record.json` of an imported recording: where it came from and what it holds.
#[derive(Serialize)]
pub struct ImportSummary<'a> {
    /// The file read.
    pub imported: String,
    /// `perf.data` or `gprof`.
    pub format: &'static str,
    /// Always null: no program ran here.
    pub command: Option<Vec<String>>,
    pub program: &'a str,
    #[serde(flatten)]
    pub figures: ImportFigures<'a>,
    /// Every file written, relative to the directory.
    pub files: Vec<String>,
    /// Files a live recording writes that this one cannot, and why.
    pub not_written: BTreeMap<&'static str, &'static str>,
}

/// What each kind of recording tells.
#[derive(Serialize)]
#[serde(untagged)]
pub enum ImportFigures<'a> {
    Perf {
        /// perf's own command line, from the file's header.
        perf_command: &'a [String],
        event: &'a str,
        /// Samples per second asked (`-F`), or the period (`-c`).
        frequency: Option<u64>,
        period: Option<u64>,
        call_graph: CallGraph,
        samples: u64,
        cpu_seconds: f64,
        /// How `cpu_seconds` was found (`periods`, `frequency`, `span`).
        cpu_seconds_from: analysis::profile::perf_data::CpuTimeSource,
        cpu_seconds_note: &'static str,
        /// From the first sample to the last.
        span_seconds: f64,
        seconds_per_sample: f64,
        samples_per_cpu_second: f64,
        lost_samples: u64,
        /// Samples of a second sampling event, left out.
        other_event_samples: u64,
        processes: usize,
        modules: &'a [analysis::profile::perf_data::coverage::ModuleCoverage],
        /// Files with samples that named nothing, and why.
        missing_files: &'a [analysis::profile::perf_data::MissingFile],
        /// The samples by phase of ray tracing, by the phase rules.
        phases: &'a PhaseBreakdown,
    },
    Gprof {
        seconds_per_sample: f64,
        total_seconds: f64,
        functions: usize,
        /// gprof's exact calls per function (its flat profile's `calls`).
        calls: BTreeMap<String, u64>,
    },
}

/// Why `path` is neither kind, for the error.
fn not_a_recording(path: &Path, why: &str) -> RunError {
    RunError::Input(format!(
        "{}: not a perf.data file or gprof output ({why})",
        path.display()
    ))
}

/// `rtprof record --import`: reads `file`, writes its files under `--output` (or
/// [`Imported::default_dir`]) and returns the summary to print. A perf.data's samples
/// get phases by `--phases` (or the built-in rules) and differentials from `--baseline`.
pub fn import_into(file: &Path, settings: &RecordSettings) -> Result<String, RunError> {
    let rules = crate::record::phase_rules(settings.phases.as_deref())?;
    let baseline = settings
        .baseline
        .as_deref()
        .map(read_baseline)
        .transpose()?;
    let output = settings.output.as_deref();
    let mut imported = import(file, &rules)?;
    if let (Imported::Perf(p), Some(b)) = (&mut imported, baseline) {
        p.baseline = Some(b);
    }
    let dir = output.map_or_else(|| imported.default_dir(), Path::to_path_buf);
    let summary = imported.save(&dir, settings.pdf.choice())?;
    Ok(imported.to_text(&dir, &summary))
}

/// Reads `path`: a perf.data (by its magic) or gprof's text output.
pub fn import(path: &Path, rules: &PhaseRules) -> Result<Imported, RunError> {
    let io = |e: std::io::Error| RunError::io("read", path, &e);
    let mut file = std::fs::File::open(path).map_err(io)?;
    let length = file.metadata().map_err(io)?.len();
    let mut head = Vec::with_capacity(8);
    file.by_ref().take(8).read_to_end(&mut head).map_err(io)?;
    drop(file);
    if head.is_empty() {
        return Err(not_a_recording(path, "the file is empty"));
    }
    if has_magic(&head) {
        return import_perf(path, rules);
    }
    if head.starts_with(GMON_MAGIC) {
        return Err(not_a_recording(
            path,
            "it is gprof's binary gmon.out: give gprof's text output, gprof -b PROG gmon.out > prof.txt",
        ));
    }
    if head.starts_with(ELF_MAGIC) {
        return Err(not_a_recording(
            path,
            "it is a program or library (ELF), not a recording",
        ));
    }
    if length > MAX_TEXT_BYTES {
        return Err(not_a_recording(
            path,
            "no PERFILE2 magic, and too large for gprof's text output",
        ));
    }
    match gprof_import::read(path) {
        Ok(gprof) => Ok(Imported::Gprof(GprofImport {
            source: path.to_path_buf(),
            name: file_stem(path),
            gprof,
        })),
        Err(GprofFileError::Whole {
            error: GprofImportError::NothingFound,
            ..
        }) => Err(not_a_recording(
            path,
            "no PERFILE2 magic at its start, and neither gprof's \"Flat profile:\" nor its call graph's heading in it",
        )),
        Err(e) => Err(RunError::Input(e.to_string())),
    }
}

fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map_or_else(|| "import".into(), |s| s.to_string_lossy().into_owned())
}

fn import_perf(path: &Path, rules: &PhaseRules) -> Result<Imported, RunError> {
    let perf = read_perf_data(path).map_err(|e| RunError::Input(e.to_string()))?;
    if perf.samples.total() == 0 {
        return Err(RunError::Input(format!(
            "{}: no samples in this recording (perf was stopped before it wrote any, or its event never fired)",
            path.display()
        )));
    }
    let name = perf
        .recording
        .program
        .clone()
        .filter(|p| !p.is_empty())
        .unwrap_or_else(|| file_stem(path));
    let view = ViewProfile::of_run(ProfileView::Native, perf.samples.clone(), &name);
    let phases = rules.classify(&perf.samples, &perf.sources);
    Ok(Imported::Perf(Box::new(PerfImport {
        source: path.to_path_buf(),
        name,
        perf,
        view,
        phases,
        baseline: None,
    })))
}

impl Imported {
    /// The program's name, or the file's: names the files (`flat-NAME.txt`).
    pub fn name(&self) -> &str {
        match self {
            Imported::Perf(p) => &p.name,
            Imported::Gprof(g) => &g.name,
        }
    }

    /// Where the files go without `-o`: `record-NAME`.
    pub fn default_dir(&self) -> PathBuf {
        PathBuf::from(format!("record-{}", self.name()))
    }

    /// Writes the files under `dir` and record.json; a perf.data's report.pdf as `pdf`
    /// says (a gprof text gets no report).
    pub fn save(&self, dir: &Path, pdf: Pdf) -> Result<ImportSummary<'_>, RunError> {
        let summary = match self {
            Imported::Perf(p) => p.save(dir, pdf)?,
            Imported::Gprof(g) => g.save(dir)?,
        };
        let json =
            serde_json::to_string_pretty(&summary).map_err(|e| RunError::Profile(e.to_string()))?;
        save(dir, "record.json", json.as_bytes())?;
        Ok(summary)
    }

    /// What the command prints.
    pub fn to_text(&self, dir: &Path, summary: &ImportSummary) -> String {
        let mut out = match self {
            Imported::Perf(p) => p.to_text(),
            Imported::Gprof(g) => g.to_text(),
        };
        for (files, why) in &summary.not_written {
            out += &format!("\nnot written: {files} ({why})");
        }
        if !summary.not_written.is_empty() {
            out.push('\n');
        }
        out += &format!(
            "\nwrote {}/{{{}}}\n",
            dir.display(),
            summary.files.join(", ")
        );
        out
    }
}

impl PerfImport {
    fn call_graph(&self) -> CallGraph {
        if self.perf.dwarf {
            CallGraph::Dwarf
        } else {
            CallGraph::Fp
        }
    }

    fn cpu_seconds(&self) -> f64 {
        self.perf.sampled_seconds
    }

    fn save(&self, dir: &Path, pdf: Pdf) -> Result<ImportSummary<'_>, RunError> {
        let title = format!("{} (imported from {})", self.name, self.source.display());
        let saved = save_profile_files(
            dir,
            "",
            &ProfileToSave {
                stem: &self.name,
                title: &title,
                wall_seconds: self.perf.recording.span_seconds,
                sampled: format!(
                    "one run of {}, recorded by perf elsewhere ({})",
                    self.name,
                    self.source.display()
                ),
                views: vec![ViewToSave {
                    view: &self.view,
                    suffix: "",
                }],
            },
        )?;
        let mut files = Vec::new();
        for v in &saved.views {
            files.extend([
                v.flat_text.clone(),
                v.callgraph_text.clone(),
                v.flame_svg.clone(),
            ]);
        }
        // Written beside the flamegraph, not named by the results' view entry.
        files.push(format!("folded-{}.txt", results::slug(&self.name)));
        files.extend(saved.exports.iter().cloned());
        let modules = &self.perf.modules;
        let modules_json =
            serde_json::to_string_pretty(modules).map_err(|e| RunError::Profile(e.to_string()))?;
        files.push(save(dir, "modules.txt", modules_text(modules).as_bytes())?);
        files.push(save(dir, "modules.json", modules_json.as_bytes())?);
        if let Some(baseline) = &self.baseline {
            let (grown, shrunk) = save_record_differential(
                dir,
                &self.name,
                &self.view.folded,
                self.cpu_seconds(),
                &dir_label(dir),
                baseline,
            )?;
            files.extend([grown, shrunk]);
        }
        let caveat = frame_pointer_caveat(self.call_graph(), modules);
        files.push(save_phases(
            dir,
            &self.name,
            &title,
            &self.phases,
            caveat.as_deref(),
        )?);
        files.extend(pdf.files().iter().map(|f| f.to_string()));
        files.push("record.json".into());
        let end = format!("imported from {}", self.source.display());
        let samples = self.perf.samples.total();
        write_report(
            dir,
            pdf,
            &RecordReport {
                program: &self.name,
                command: &self.perf.recording.perf_command.join(" "),
                end: &end,
                success: true,
                cpu_seconds: self.cpu_seconds(),
                wall_seconds: self.perf.recording.span_seconds,
                samples,
                frequency: self
                    .perf
                    .recording
                    .frequency
                    .map_or(0, |f| u32::try_from(f).unwrap_or(u32::MAX)),
                call_graph: self.call_graph().describe(),
                lost_samples: self.perf.lost,
                processes: self.perf.processes,
                flat: &self.view.flat,
                phases: &self.phases,
                modules,
                flamegraph: saved_flamegraph(dir, &saved),
                files: &files,
                caveat,
                // A recording made elsewhere has no probe file beside it.
                probe: None,
                probe_error: None,
            },
        )?;
        let recording = &self.perf.recording;
        Ok(ImportSummary {
            imported: self.source.display().to_string(),
            format: "perf.data",
            command: None,
            program: &self.name,
            figures: ImportFigures::Perf {
                perf_command: &recording.perf_command,
                event: &recording.event,
                frequency: recording.frequency,
                period: recording.period,
                call_graph: self.call_graph(),
                samples,
                cpu_seconds: self.cpu_seconds(),
                cpu_seconds_from: self.perf.cpu_seconds_from,
                cpu_seconds_note: self.perf.cpu_seconds_from.describe(),
                span_seconds: recording.span_seconds,
                seconds_per_sample: self.perf.samples.seconds_per_sample,
                samples_per_cpu_second: samples as f64 / self.cpu_seconds().max(1e-9),
                lost_samples: self.perf.lost,
                other_event_samples: recording.other_event_samples,
                processes: self.perf.processes,
                modules,
                missing_files: &self.perf.missing_files,
                phases: &self.phases,
            },
            files,
            not_written: BTreeMap::from([(
                "perf.data, perf.log",
                "the recording stays where it is; no perf ran here",
            )]),
        })
    }

    fn to_text(&self) -> String {
        let recording = &self.perf.recording;
        let mut out = format!(
            "{} (imported{}): {} samples of {}, {} of CPU from {}, call stacks by {}\n",
            self.source.display(),
            if recording.perf_command.is_empty() {
                String::new()
            } else {
                format!(", recorded by: {}", recording.perf_command.join(" "))
            },
            format::count(self.perf.samples.total()),
            recording.event,
            format::seconds(self.cpu_seconds()),
            self.perf.cpu_seconds_from.describe(),
            if self.perf.dwarf {
                "DWARF unwinding"
            } else {
                "frame pointers"
            },
        );
        if self.perf.lost > 0 {
            out += &format!(
                "perf lost {} samples (its buffers were full)\n",
                format::count(self.perf.lost)
            );
        }
        if recording.other_event_samples > 0 {
            out += &format!(
                "{} samples of other events left out: only {} is read\n",
                format::count(recording.other_event_samples),
                recording.event
            );
        }
        out += &top_functions_text(&self.view.flat);
        out += &phases_summary(
            &self.phases,
            frame_pointer_caveat(self.call_graph(), &self.perf.modules).as_deref(),
        );
        out.push('\n');
        out += &modules_text(&self.perf.modules);
        out += &missing_files_text(&self.perf.missing_files);
        out
    }
}

/// The files of the recording that named nothing, and where rtprof looks.
pub fn missing_files_text(missing: &[analysis::profile::perf_data::MissingFile]) -> String {
    if missing.is_empty() {
        return String::new();
    }
    let mut out = format!(
        "\n{} of the recording gave no names (their samples count as without a symbol):\n",
        format::plural(missing.len(), "file")
    );
    for m in missing {
        out += &format!("  {}: {}\n", m.path, m.problem);
    }
    out += "Symbols are read from the files at the paths perf recorded, when they are the build \
            that was recorded, or from perf's copies by build id in ~/.debug (run `perf archive` \
            where it was recorded and unpack its tarball into ~/.debug here), with debug \
            packages' files from /usr/lib/debug/.build-id.\n";
    out
}

impl GprofImport {
    fn save(&self, dir: &Path) -> Result<ImportSummary<'_>, RunError> {
        let stem = results::slug(&self.name);
        let mut files = Vec::new();
        let flat = self.gprof.flat.as_ref();
        if let Some(flat) = flat {
            files.push(save(
                dir,
                &format!("flat-{stem}.txt"),
                flat.to_text().as_bytes(),
            )?);
        }
        if let Some(graph) = &self.gprof.call_graph {
            files.push(save(
                dir,
                &format!("callgraph-{stem}.txt"),
                graph.to_text().as_bytes(),
            )?);
        }
        if let Some(flat) = flat {
            files.push(save(
                dir,
                &format!("amdahl-{stem}.txt"),
                gprof_amdahl_text(flat).as_bytes(),
            )?);
        }
        files.push("record.json".into());
        let no_stacks = "gprof's output has callers and callees, not call stacks";
        let mut not_written = BTreeMap::from([
            ("folded stacks, flamegraph, pprof, speedscope", no_stacks),
            ("modules", "gprof's output names no modules"),
        ]);
        if flat.is_none() {
            not_written.insert(
                "flat profile, Amdahl table",
                "the file has no flat profile (gprof -q)",
            );
        }
        if self.gprof.call_graph.is_none() {
            not_written.insert("call graph", "the file has no call graph (gprof -p)");
        }
        let seconds_per_sample = flat.map_or(0.0, |f| f.seconds_per_sample);
        let total_seconds = flat
            .map(|f| f.total_seconds)
            .or_else(|| self.gprof.call_graph.as_ref().map(|g| g.total_seconds))
            .unwrap_or(0.0);
        let functions = flat.map_or_else(
            || {
                self.gprof
                    .call_graph
                    .as_ref()
                    .map_or(0, |g| g.entries.iter().filter(|e| !e.whole_cycle).count())
            },
            |f| f.rows.len(),
        );
        Ok(ImportSummary {
            imported: self.source.display().to_string(),
            format: "gprof",
            command: None,
            program: &self.name,
            figures: ImportFigures::Gprof {
                seconds_per_sample,
                total_seconds,
                functions,
                calls: self.gprof.calls(),
            },
            files,
            not_written,
        })
    }

    fn to_text(&self) -> String {
        let mut out = format!("{} (imported gprof output): ", self.source.display(),);
        match &self.gprof.flat {
            Some(flat) => {
                out += &format!(
                    "{} functions, {} sampled at {} a sample; calls counted by -pg\n",
                    format::count(flat.rows.len() as u64),
                    format::seconds(flat.total_seconds),
                    format::seconds(flat.seconds_per_sample),
                );
                out += &top_functions_text(flat);
            }
            None => out += "a call graph without a flat profile; calls counted by -pg\n",
        }
        out
    }
}

/// The Amdahl table of gprof's flat profile, saying where its shares come from.
fn gprof_amdahl_text(flat: &FlatProfile) -> String {
    format!(
        "From gprof's output: \"alone\" is gprof's sampled self time; \"with callees\" adds the\n\
         time gprof propagated to each function from its callees in proportion to call\n\
         counts (as if every call of a function cost the same).\n\n{}",
        amdahl_text(&amdahl_table(flat, AMDAHL_ROWS))
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("rtprof-import-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn refused(bytes: &[u8], says: &str) {
        let dir = scratch(says.split_whitespace().next().unwrap_or("x"));
        let path = dir.join("input");
        std::fs::write(&path, bytes).unwrap();
        let Err(err) = import(&path, &PhaseRules::builtin().unwrap()) else {
            panic!("{says}: imported")
        };
        let text = err.to_string();
        assert!(text.starts_with(&path.display().to_string()), "{text}");
        assert!(text.contains(says), "{text}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn what_is_neither_is_refused_naming_the_file() {
        refused(b"", "the file is empty");
        refused(b"hello\nworld\n", "not a perf.data file or gprof output");
        refused(b"gmon\x01\0\0\0", "gmon.out");
        refused(b"\x7fELF\x02\x01\x01", "ELF");
        refused(b"PERFILE2", "truncated");
        refused(b"PERFILE2 and then some text that is not a header at all, long enough to fill it: 0123456789012345678901234567890123456789", "damaged");
    }

    #[test]
    fn gprof_output_is_read_with_its_calls() {
        let dir = scratch("gprof");
        let path = dir.join("prof.txt");
        std::fs::write(
            &path,
            "Flat profile:\n\nEach sample counts as 0.01 seconds.\n  %   cumulative   self              self     total           \n time   seconds   seconds    calls  ms/call  ms/call  name    \n 80.00      0.08     0.08     1000     0.08     0.08  f\n 20.00      0.10     0.02       37     0.54     0.54  g\n\n",
        )
        .unwrap();
        let Ok(imported) = import(&path, &PhaseRules::builtin().unwrap()) else {
            panic!("not read")
        };
        assert_eq!(imported.name(), "prof");
        let out = dir.join("out");
        let summary = imported.save(&out, Pdf::Write).unwrap();
        assert_eq!(
            summary.files,
            ["flat-prof.txt", "amdahl-prof.txt", "record.json"]
        );
        let ImportFigures::Gprof { calls, .. } = &summary.figures else {
            panic!("not gprof")
        };
        assert_eq!(calls.get("f"), Some(&1000));
        assert_eq!(calls.get("g"), Some(&37));
        let flat = std::fs::read_to_string(out.join("flat-prof.txt")).unwrap();
        assert!(flat.contains("Read from gprof's output"), "{flat}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
