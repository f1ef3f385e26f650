//! The in-process profiler criterion runs under `--profile-time N`: it samples the
//! benchmark with rtprof's sampler ([`analysis::profile::session::Sampling`]: pprof's
//! SIGPROF handler, driven by a perf cpu-clock timer on the benchmark's thread or by
//! setitimer, as `RTPROF_SAMPLER` and the machine allow) while one benchmark iterates
//! and, when it stops, writes
//! the stacks as `folded.txt` (Brendan Gregg's folded format, `a;b;c count`), as an
//! interactive `flamegraph.svg`, and in the exports `rtprof profile` writes
//! (`profile.pb.gz` for `go tool pprof`, `speedscope.json`), all into the benchmark's profile directory
//! (`<target dir>/criterion/<group>/<benchmark>/profile/`, created if missing).
//!
//! Plain `cargo bench` runs never call it: criterion only starts a profiler in profile
//! mode. Nothing here panics: a profiler that cannot start, a report that cannot be
//! built or a file that cannot be written prints one warning line to stderr and the
//! benchmark run goes on. Files are written to a temporary name and renamed into place,
//! so a reader never sees half a flamegraph.
//!
//! Symbols are cleaned as the project's profiler cleans them
//! ([`analysis::profile::names::clean_symbol`]) and the folded text and SVG come from
//! [`analysis::profile::folded`]; unlike `rtprof profile`, every frame is kept (criterion's
//! loop and the thread start included), since a benchmark has no single root to cut at.

use analysis::profile::export::{PprofRun, pprof_profile_gz, speedscope_json};
use analysis::profile::folded::{flamegraph_svg, folded};
use analysis::profile::sampler::{SampleOptions, root_first_names};
use analysis::profile::session::Sampling;
use analysis::profile::{Stack, StackSamples};
use criterion::profiler::Profiler;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::Duration;

/// A criterion [`Profiler`] that draws a flamegraph of each profiled benchmark.
pub struct FlameProfiler {
    /// Samples per CPU second asked of the timer; `None`: the timer's default (as
    /// `rtprof profile`: 4,000 Hz under perf cpu-clock, 1,000 asked of setitimer).
    frequency: Option<i32>,
    /// The running profile, between `start_profiling` and `stop_profiling`.
    running: Option<Sampling>,
}

impl FlameProfiler {
    /// A profiler sampling at `frequency` Hz, or at the timer's default rate.
    pub fn new(frequency: Option<i32>) -> Self {
        Self {
            frequency,
            running: None,
        }
    }
}

impl Profiler for FlameProfiler {
    fn start_profiling(&mut self, benchmark_id: &str, _benchmark_dir: &Path) {
        // A profile left over from a start without stop is dropped (its timer stops).
        self.running = None;
        // Criterion iterates on this thread: under perf it is the one sampled.
        let options = SampleOptions {
            frequency: self.frequency,
            min_samples: 0,
            ..SampleOptions::timer_default()
        };
        match Sampling::start(&options) {
            Ok(sampling) => self.running = Some(sampling),
            Err(e) => warn(benchmark_id, &format!("cannot start the profiler: {e}")),
        }
    }

    fn stop_profiling(&mut self, benchmark_id: &str, benchmark_dir: &Path) {
        let Some(running) = self.running.take() else {
            return;
        };
        // Stop sampling before the files are written.
        let stopped = match running.stop() {
            Ok(stopped) => stopped,
            Err(e) => return warn(benchmark_id, &format!("cannot build the report: {e}")),
        };
        let cpu = stopped.cpu;
        let samples = stack_samples(&stopped.report, cpu);
        if samples.total() == 0 {
            return warn(
                benchmark_id,
                "no samples were taken (give it a longer --profile-time)",
            );
        }
        if let Err(message) = write_outputs(&samples, cpu, benchmark_id, benchmark_dir) {
            warn(benchmark_id, &message);
        }
    }
}

/// The report's stacks, root first, with cleaned names; identical stacks merged.
fn stack_samples(report: &pprof::Report, cpu: Duration) -> StackSamples {
    let mut merged: BTreeMap<Vec<String>, u64> = BTreeMap::new();
    for (frames, &count) in &report.data {
        let mut names = root_first_names(frames);
        // A function split by the compiler resolves to its own name twice in a row.
        names.dedup();
        if names.is_empty() {
            continue;
        }
        *merged.entry(names).or_default() += u64::try_from(count).unwrap_or(0);
    }
    let total: u64 = merged.values().sum();
    StackSamples {
        stacks: merged
            .into_iter()
            .map(|(frames, count)| Stack { frames, count })
            .collect(),
        seconds_per_sample: if total == 0 {
            0.0
        } else {
            cpu.as_secs_f64() / total as f64
        },
    }
}

/// Writes `folded.txt`, `flamegraph.svg`, `profile.pb.gz` and `speedscope.json` into
/// `dir` (created if missing).
fn write_outputs(
    samples: &StackSamples,
    cpu: Duration,
    benchmark_id: &str,
    dir: &Path,
) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let folded_text = folded(samples);
    write_atomically(&dir.join("folded.txt"), folded_text.as_bytes())?;
    let svg = flamegraph_svg(&folded_text, benchmark_id).map_err(|e| e.to_string())?;
    write_atomically(&dir.join("flamegraph.svg"), svg.as_bytes())?;
    let run = PprofRun {
        duration: cpu,
        comments: vec![format!(
            "criterion benchmark {benchmark_id}, native symbols"
        )],
    };
    let pprof = pprof_profile_gz(samples, &run).map_err(|e| e.to_string())?;
    write_atomically(&dir.join("profile.pb.gz"), &pprof)?;
    let speedscope = speedscope_json(benchmark_id, &[("native symbols", samples)]);
    write_atomically(&dir.join("speedscope.json"), speedscope.as_bytes())
}

/// Writes `bytes` to a temporary file beside `path`, then renames it to `path`
/// ([`tracer::image_io::write_atomically`]).
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), String> {
    tracer::image_io::write_atomically(path, bytes)
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// One warning line on stderr.
fn warn(benchmark_id: &str, message: &str) {
    eprintln!("warning: flame profiler, {benchmark_id}: {message}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_are_written_atomically_into_a_new_directory() {
        let dir = std::env::temp_dir().join(format!("benches-flame-{}", std::process::id()));
        let samples = StackSamples {
            stacks: vec![
                Stack {
                    frames: vec!["main".into(), "bench".into(), "sqrt".into()],
                    count: 7,
                },
                Stack {
                    frames: vec!["main".into(), "bench".into()],
                    count: 3,
                },
            ],
            seconds_per_sample: 0.001,
        };
        let written = write_outputs(&samples, Duration::from_millis(10), "sqrt/std", &dir);
        let folded_text = std::fs::read_to_string(dir.join("folded.txt")).unwrap_or_default();
        let pprof = std::fs::read(dir.join("profile.pb.gz")).unwrap_or_default();
        let speedscope = std::fs::read_to_string(dir.join("speedscope.json")).unwrap_or_default();
        let svg = std::fs::read_to_string(dir.join("flamegraph.svg")).unwrap_or_default();
        let leftovers = std::fs::read_dir(&dir)
            .map(|entries| entries.count())
            .unwrap_or(0);
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!(written, Ok(()));
        assert_eq!(folded_text, "main;bench 3\nmain;bench;sqrt 7\n");
        assert!(svg.contains("<svg") && svg.contains("sqrt"));
        // The exports `rtprof profile` writes: a gzip stream, a speedscope file.
        assert_eq!(
            pprof.get(..2),
            Some(&[0x1f, 0x8b][..]),
            "profile.pb.gz is not gzip"
        );
        assert!(speedscope.contains("speedscope.app/file-format-schema.json"));
        assert_eq!(leftovers, 4, "no temporary file is left behind");
    }

    #[test]
    fn a_stop_without_a_start_does_nothing() {
        let dir = std::env::temp_dir().join(format!("benches-flame-none-{}", std::process::id()));
        FlameProfiler::new(None).stop_profiling("none", &dir);
        assert!(!dir.exists());
    }
}
