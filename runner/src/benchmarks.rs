//! What the benchmark harnesses saved, read back for the reports: criterion's
//! estimates (`target/criterion`) and gungraun's instruction counts
//! (`target/gungraun`).
//!
//! Both harnesses write one directory per benchmark; this module walks them and keeps
//! only the figures the reports show, as plain `results` data. It
//! reads files and nothing else: running the benchmarks is `cargo bench`'s job.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use results::{CriterionEstimate, Estimate, InstructionCount, rfc3339_utc};

/// A harness directory that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum BenchImportError {
    #[error("cannot read {path}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{path} is not a {what} file: {source}")]
    Json {
        path: PathBuf,
        what: &'static str,
        source: serde_json::Error,
    },
    #[error("{0} is not a directory")]
    NotADirectory(PathBuf),
    /// An error in a harness directory, naming the flag that sets it.
    #[error("{error} (the directory is set with {flag})")]
    FromFlag {
        flag: &'static str,
        error: Box<BenchImportError>,
    },
}

impl BenchImportError {
    fn set_with(self, flag: &'static str) -> Self {
        BenchImportError::FromFlag {
            flag,
            error: Box::new(self),
        }
    }
}

/// criterion's `new/benchmark.json` (the fields the reports use).
#[derive(Deserialize)]
struct CriterionBenchmark {
    full_id: String,
}

#[derive(Deserialize)]
struct CriterionInterval {
    lower_bound: f64,
    upper_bound: f64,
}

#[derive(Deserialize)]
struct CriterionStatistic {
    point_estimate: f64,
    confidence_interval: CriterionInterval,
}

/// criterion's `new/estimates.json` (nanoseconds per iteration).
#[derive(Deserialize)]
struct CriterionEstimates {
    mean: CriterionStatistic,
    median: CriterionStatistic,
}

impl From<&CriterionStatistic> for Estimate {
    fn from(s: &CriterionStatistic) -> Self {
        Estimate {
            median: s.point_estimate,
            low: s.confidence_interval.lower_bound,
            high: s.confidence_interval.upper_bound,
        }
    }
}

fn read_json<T: serde::de::DeserializeOwned>(
    path: &Path,
    what: &'static str,
) -> Result<T, BenchImportError> {
    let text = std::fs::read_to_string(path).map_err(|source| BenchImportError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|source| BenchImportError::Json {
        path: path.to_path_buf(),
        what,
        source,
    })
}

/// A file's modification time, RFC 3339 UTC (when the harness wrote it).
fn modified(path: &Path) -> Option<String> {
    let time = std::fs::metadata(path).ok()?.modified().ok()?;
    let secs = time.duration_since(std::time::UNIX_EPOCH).ok()?.as_secs();
    Some(rfc3339_utc(secs))
}

/// Every file named `name` under `dir`, depth first, in path order (so the result does
/// not depend on the file system's listing order).
fn find_files(dir: &Path, name: &str) -> Result<Vec<PathBuf>, BenchImportError> {
    if !dir.is_dir() {
        return Err(BenchImportError::NotADirectory(dir.to_path_buf()));
    }
    let mut found = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(current) = pending.pop() {
        let entries = std::fs::read_dir(&current).map_err(|source| BenchImportError::Io {
            path: current.clone(),
            source,
        })?;
        for entry in entries {
            let entry = entry.map_err(|source| BenchImportError::Io {
                path: current.clone(),
                source,
            })?;
            let path = entry.path();
            // `file_type` does not follow links, so a link cycle cannot loop.
            let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
            if is_dir {
                pending.push(path);
            } else if entry.file_name() == name {
                found.push(path);
            }
        }
    }
    found.sort();
    Ok(found)
}

/// The latest estimates of every benchmark under a criterion output directory
/// (`target/criterion`): each `<id>/new/` holding `benchmark.json` and
/// `estimates.json`. Earlier runs (`base/`, named baselines) are ignored. Sorted by id.
pub fn read_criterion_dir(dir: &Path) -> Result<Vec<CriterionEstimate>, BenchImportError> {
    let mut estimates = Vec::new();
    for benchmark_file in find_files(dir, "benchmark.json")? {
        let Some(run_dir) = benchmark_file.parent() else {
            continue;
        };
        if run_dir.file_name().is_none_or(|n| n != "new") {
            continue;
        }
        let benchmark: CriterionBenchmark = read_json(&benchmark_file, "criterion benchmark")?;
        let stats: CriterionEstimates =
            read_json(&run_dir.join("estimates.json"), "criterion estimates")?;
        estimates.push(CriterionEstimate {
            id: benchmark.full_id,
            mean: Estimate::from(&stats.mean),
            median: Estimate::from(&stats.median),
            measured: modified(&run_dir.join("estimates.json")),
        });
    }
    estimates.sort_by(|a, b| a.id.cmp(&b.id));
    Ok(estimates)
}

/// The criterion id of a gungraun benchmark: the function name's first `_` separates
/// the group, the bench id is the last part, and other `_` become `-`
/// (`intersect_sphere` + `hit` is `intersect/sphere/hit`, `sqrt` + `fast_sqrt` is
/// `sqrt/fast-sqrt`); `benches/benches/instructions.rs` names its benchmarks so.
pub fn gungraun_criterion_id(function: &str, bench_id: Option<&str>) -> String {
    let mut id = match function.split_once('_') {
        Some((group, rest)) => format!("{group}/{}", rest.replace('_', "-")),
        None => function.to_string(),
    };
    if let Some(bench_id) = bench_id.filter(|b| !b.is_empty()) {
        id.push('/');
        id.push_str(&bench_id.replace('_', "-"));
    }
    id
}

/// A metric of callgrind's totals in a gungraun summary (`…metrics.<name>.values.new`).
fn callgrind_total(summary: &serde_json::Value, metric: &str) -> Option<u64> {
    summary
        .get("profiles")?
        .as_array()?
        .iter()
        .find(|p| p.get("tool").and_then(|t| t.as_str()) == Some("Callgrind"))?
        .pointer(&format!("/data/total/metrics/{metric}/values/new"))?
        .as_u64()
}

/// The instruction counts of every benchmark under a gungraun output directory
/// (`target/gungraun`), read from the `summary.json` files that
/// `--save-summary=json` writes. Sorted by id.
pub fn read_gungraun_dir(dir: &Path) -> Result<Vec<InstructionCount>, BenchImportError> {
    let mut counts = Vec::new();
    for path in find_files(dir, "summary.json")? {
        let summary: serde_json::Value = read_json(&path, "gungraun summary")?;
        let function = summary.get("function_name").and_then(|f| f.as_str());
        let (Some(function), Some(instructions)) = (function, callgrind_total(&summary, "Ir"))
        else {
            return Err(BenchImportError::Json {
                path,
                what: "gungraun callgrind summary",
                source: serde::de::Error::custom("no function_name or callgrind Ir total"),
            });
        };
        let bench_id = summary.get("id").and_then(|i| i.as_str());
        counts.push(InstructionCount {
            id: gungraun_criterion_id(function, bench_id),
            instructions,
            estimated_cycles: callgrind_total(&summary, "EstimatedCycles"),
            measured: modified(&path),
        });
    }
    counts.sort_by(|a, b| a.id.cmp(&b.id));
    Ok(counts)
}

/// The harness directories of a cargo target directory, when they exist: criterion's
/// `<target>/criterion` and gungraun's `<target>/gungraun`.
pub fn harness_dirs(target: &Path) -> (Option<PathBuf>, Option<PathBuf>) {
    let existing = |name: &str| Some(target.join(name)).filter(|d| d.is_dir());
    (existing("criterion"), existing("gungraun"))
}

/// The harness directories to read: the ones given, else (when `discover`) those of
/// the cargo target directory — `$CARGO_TARGET_DIR`, else the one this binary was
/// built in, else ./target. An instructions directory not given is looked for beside
/// a given criterion directory.
pub fn resolve_dirs(
    criterion: Option<&Path>,
    instructions: Option<&Path>,
    discover: bool,
) -> (Option<PathBuf>, Option<PathBuf>) {
    let beside_criterion = || {
        criterion
            .and_then(|c| c.parent())
            .map(|target| harness_dirs(target).1)
            .unwrap_or_default()
    };
    match (criterion, instructions) {
        (Some(c), Some(i)) => (Some(c.to_path_buf()), Some(i.to_path_buf())),
        (Some(c), None) => (Some(c.to_path_buf()), beside_criterion()),
        (None, Some(i)) => (None, Some(i.to_path_buf())),
        (None, None) if discover => match target_dir() {
            Some(target) => harness_dirs(&target),
            None => (None, None),
        },
        (None, None) => (None, None),
    }
}

/// The cargo target directory whose harness output to pick up, if one exists.
fn target_dir() -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os("CARGO_TARGET_DIR") {
        return Some(PathBuf::from(dir));
    }
    // <target>/<profile>/rtprof
    let built_in = std::env::current_exe()
        .ok()
        .and_then(|exe| Some(exe.parent()?.parent()?.to_path_buf()));
    built_in
        .into_iter()
        .chain([PathBuf::from("target")])
        .find(|t| t.join("criterion").is_dir() || t.join("gungraun").is_dir())
}

// Where the benchmark harnesses saved their figures (`cargo bench -p benches`); with
// the `clap` feature, the --criterion and --instructions flags of `suite` and `report`.
// (A plain comment: clap would take a doc comment as the about of those commands.)
#[derive(Clone, Debug, Default)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct BenchmarkDirs {
    /// Add criterion's estimates (mean, median, 95 % intervals) from this directory,
    /// e.g. target/criterion [suite default: <target dir>/criterion when present].
    // The angle brackets are for `--help` (clap reads this doc), not HTML.
    #[allow(rustdoc::invalid_html_tags)]
    #[cfg_attr(feature = "clap", arg(long, value_name = "DIR"))]
    pub criterion: Option<std::path::PathBuf>,
    /// Add gungraun's instruction counts from this directory [default: `gungraun`
    /// beside the criterion directory, when present].
    #[cfg_attr(feature = "clap", arg(long, value_name = "DIR"))]
    pub instructions: Option<std::path::PathBuf>,
}

impl BenchmarkDirs {
    /// Refuses a given directory that does not exist, before any long work.
    pub fn check(&self) -> Result<(), BenchImportError> {
        check_dirs(self.criterion.as_deref(), self.instructions.as_deref())
    }

    /// Reads the benchmark figures into `results` (replacing any it had); the lines say
    /// what it added. `discover` looks in the cargo target directory when none is given.
    pub fn add_to(
        &self,
        results: &mut results::Results,
        discover: bool,
    ) -> Result<Vec<String>, BenchImportError> {
        let (criterion, instructions) = (self.criterion.as_deref(), self.instructions.as_deref());
        add_to_results(results, criterion, instructions, discover)
    }
}

/// Refuses a given harness directory that is not a directory (before a long run).
pub fn check_dirs(
    criterion: Option<&Path>,
    instructions: Option<&Path>,
) -> Result<(), BenchImportError> {
    for (flag, dir) in [("--criterion", criterion), ("--instructions", instructions)] {
        if let Some(dir) = dir.filter(|d| !d.is_dir()) {
            return Err(BenchImportError::NotADirectory(dir.to_path_buf()).set_with(flag));
        }
    }
    Ok(())
}

/// Reads the benchmark figures of the harness directories (see [`resolve_dirs`]) into
/// `results`, replacing any it had; returns one line per directory read, saying what
/// was added.
pub fn add_to_results(
    results: &mut results::Results,
    criterion: Option<&Path>,
    instructions: Option<&Path>,
    discover: bool,
) -> Result<Vec<String>, BenchImportError> {
    let (criterion, instructions) = resolve_dirs(criterion, instructions, discover);
    let mut added = Vec::new();
    if let Some(dir) = criterion {
        results.criterion = read_criterion_dir(&dir).map_err(|e| e.set_with("--criterion"))?;
        added.push(format!(
            "added {} criterion estimates from {}",
            results.criterion.len(),
            dir.display()
        ));
    }
    if let Some(dir) = instructions {
        results.instructions = read_gungraun_dir(&dir).map_err(|e| e.set_with("--instructions"))?;
        added.push(format!(
            "added {} instruction counts from {}",
            results.instructions.len(),
            dir.display()
        ));
    }
    Ok(added)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scratch directory removed on drop.
    struct Scratch(PathBuf);
    impl Scratch {
        fn new(name: &str) -> Self {
            let dir = std::env::temp_dir()
                .join(format!("rtprof-bench-import-{name}-{}", std::process::id()));
            let _ = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).unwrap();
            Scratch(dir)
        }
        fn write(&self, rel: &str, text: &str) {
            let path = self.0.join(rel);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, text).unwrap();
        }
    }
    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    fn criterion_estimates(mean: [f64; 3], median: [f64; 3]) -> String {
        let stat = |[point, low, high]: [f64; 3]| {
            format!(
                r#"{{"confidence_interval":{{"confidence_level":0.95,"lower_bound":{low},"upper_bound":{high}}},"point_estimate":{point},"standard_error":1.0}}"#
            )
        };
        format!(
            r#"{{"mean":{},"median":{},"median_abs_dev":{},"slope":null,"std_dev":{}}}"#,
            stat(mean),
            stat(median),
            stat([1.0, 0.5, 1.5]),
            stat([2.0, 1.0, 3.0])
        )
    }

    #[test]
    fn criterion_new_estimates_are_read_and_old_runs_ignored() {
        let dir = Scratch::new("criterion");
        dir.write(
            "sqrt/std/new/benchmark.json",
            r#"{"group_id":"sqrt","function_id":"std","value_str":null,"throughput":{"Elements":4096},"full_id":"sqrt/std","directory_name":"sqrt/std","title":"sqrt/std"}"#,
        );
        dir.write(
            "sqrt/std/new/estimates.json",
            &criterion_estimates([1087.4, 1083.4, 1091.4], [1085.0, 1080.0, 1090.0]),
        );
        // The previous run (`base/`) must not appear as a second benchmark.
        dir.write("sqrt/std/base/benchmark.json", r#"{"full_id":"sqrt/std"}"#);
        dir.write(
            "sqrt/std/base/estimates.json",
            &criterion_estimates([9.0, 8.0, 10.0], [9.0, 8.0, 10.0]),
        );
        dir.write(
            "intersect/sphere/hit/new/benchmark.json",
            r#"{"full_id":"intersect/sphere/hit"}"#,
        );
        dir.write(
            "intersect/sphere/hit/new/estimates.json",
            &criterion_estimates([5.5, 5.0, 6.0], [5.4, 5.1, 5.9]),
        );
        let got = read_criterion_dir(&dir.0).unwrap();
        let ids: Vec<&str> = got.iter().map(|c| c.id.as_str()).collect();
        assert_eq!(ids, ["intersect/sphere/hit", "sqrt/std"]);
        let std = &got[1];
        assert_eq!(
            (std.mean.median, std.mean.low, std.mean.high),
            (1087.4, 1083.4, 1091.4)
        );
        assert_eq!(
            (std.median.median, std.median.low, std.median.high),
            (1085.0, 1080.0, 1090.0)
        );
    }

    #[test]
    fn a_broken_criterion_file_is_an_error_naming_it() {
        let dir = Scratch::new("broken");
        dir.write("sqrt/std/new/benchmark.json", r#"{"full_id":"sqrt/std"}"#);
        dir.write("sqrt/std/new/estimates.json", "{\"mean\": 3}");
        let err = read_criterion_dir(&dir.0).unwrap_err().to_string();
        assert!(err.contains("estimates.json"), "{err}");
        assert!(read_criterion_dir(&dir.0.join("missing")).is_err());
    }

    #[test]
    fn gungraun_ids_map_to_the_criterion_ids() {
        assert_eq!(
            gungraun_criterion_id("intersect_sphere", Some("hit")),
            "intersect/sphere/hit"
        );
        assert_eq!(
            gungraun_criterion_id("sqrt", Some("fast_sqrt_tuned")),
            "sqrt/fast-sqrt-tuned"
        );
        assert_eq!(gungraun_criterion_id("sqrt", None), "sqrt");
    }

    #[test]
    fn gungraun_summaries_give_callgrind_totals() {
        let dir = Scratch::new("gungraun");
        let summary = |function: &str, id: &str, ir: u64| {
            format!(
                r#"{{"function_name":"{function}","id":"{id}","group":"g","version":"7","profiles":[{{"tool":"Callgrind","data":{{"parts":[],"total":{{"metrics":{{"Ir":{{"values":{{"new":{ir}}}}},"EstimatedCycles":{{"values":{{"new":{}}}}}}}}}}}}}]}}"#,
                ir * 2
            )
        };
        dir.write(
            "benches/instructions/square_roots/sqrt.std/summary.json",
            &summary("sqrt", "std", 6330),
        );
        dir.write(
            "benches/instructions/ray_primitive_tests/intersect_sphere.miss/summary.json",
            &summary("intersect_sphere", "miss", 38),
        );
        dir.write("benches/instructions/other/callgrind.out", "not json");
        let got = read_gungraun_dir(&dir.0).unwrap();
        assert!(
            got.iter()
                .all(|c| c.measured.as_ref().is_some_and(|m| m.ends_with('Z')))
        );
        assert_eq!(
            got,
            [
                InstructionCount {
                    id: "intersect/sphere/miss".to_string(),
                    instructions: 38,
                    estimated_cycles: Some(76),
                    measured: got[0].measured.clone(),
                },
                InstructionCount {
                    id: "sqrt/std".to_string(),
                    instructions: 6330,
                    estimated_cycles: Some(12660),
                    measured: got[1].measured.clone(),
                },
            ]
        );
        dir.write(
            "benches/instructions/x/y.z/summary.json",
            r#"{"profiles":[]}"#,
        );
        assert!(read_gungraun_dir(&dir.0).is_err());
    }
}
