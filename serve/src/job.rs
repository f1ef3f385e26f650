//! A job: what a user asked to run ([`JobRequest`], checked before it is queued), and
//! what the server knows of it ([`Job`]: status, progress, files), as the API returns
//! it and as `job.json` keeps it in the job's directory.

use serde::{Deserialize, Serialize};
use tracer::VariantSet;

use reports::format;

use crate::catalogue::{Catalogue, Part};
use crate::error::ApiError;

/// The request of `POST /api/jobs`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobRequest {
    /// A scene id of `GET /api/scenes` (`balls3`, `spd:balls:2`, `upload:NAME`).
    #[serde(default)]
    pub scene: String,
    /// Variants (names or combinations such as `bvh+simd`); baseline is always run.
    #[serde(default)]
    pub variants: Vec<String>,
    /// Image width and height.
    #[serde(default = "default_size")]
    pub size: [u32; 2],
    /// Threads of the timed renders (default: one, as in the suite; the untimed work uses
    /// every core); at most `runner::pool::max_threads`.
    /// Read as any whole number, so that a count too large for a thread pool is
    /// refused by the one rule with its message rather than by the JSON reader.
    #[serde(default)]
    pub threads: Option<u64>,
    /// What to run (default: render).
    #[serde(default = "default_run")]
    pub run: Vec<Part>,
    /// Outside tracers run beside the variants (docs/tracers.md), each by the name of
    /// a definition the server loaded at start (`tachyon` or `tracer:tachyon`); never
    /// a command or a path (refused with a 400).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tracers: Vec<String>,
}

fn default_size() -> [u32; 2] {
    [160, 120]
}

fn default_run() -> Vec<Part> {
    vec![Part::Render]
}

impl JobRequest {
    /// The request checked and normalized: a known scene, known variants (baseline
    /// first, no repeats), a size within the tracer's limits, a sane thread count, and
    /// outside tracers the server loaded at start. Every refusal is a 422 saying what to
    /// change (a tracer that is not one of the loaded ones: a 400); nothing is allocated
    /// for the size.
    pub fn checked(mut self, catalogue: &Catalogue) -> Result<Self, ApiError> {
        if !self.run.contains(&Part::Render) {
            self.run.insert(0, Part::Render);
        }
        self.run.dedup();
        let suite = self.run.contains(&Part::Suite);
        if suite {
            // The suite runs its own scenes, variants and sizes.
            self.run = vec![Part::Render, Part::Suite];
            self.variants.clear();
            self.scene = String::new();
            self.size = default_size();
        } else {
            catalogue.resolve(&self.scene)?;
        }
        let [width, height] = self.size;
        let limits = tracer::Limits::default();
        limits
            .check_size(u64::from(width), u64::from(height))
            .map_err(|e| ApiError::invalid(format!("size {width}x{height}: {e}")))?;
        if let Some(threads) = self.threads {
            runner::pool::check_threads(threads).map_err(|e| ApiError::invalid(e.to_string()))?;
        }
        // One run per distinct set: `simd+bvh` and `bvh+simd` are the same variant (the
        // first spelling is kept).
        let key = |set: &VariantSet| {
            let mut names: Vec<&str> = set.variants().iter().map(|v| v.name()).collect();
            names.sort_unstable();
            names
        };
        let mut variants = vec!["baseline".to_string()];
        let mut seen = vec![key(&VariantSet::default())];
        for name in &self.variants {
            if name.contains(',') {
                return Err(ApiError::invalid(format!(
                    "variant '{name}': give each variant as its own entry (combine with '+')"
                )));
            }
            let set = VariantSet::parse(name)
                .map_err(|e| ApiError::invalid(format!("variant '{name}': {e}")))?;
            if let Some(v) = set.variants().iter().find(|v| !v.available()) {
                return Err(ApiError::invalid(format!(
                    "variant '{name}': {} is not built into this rtprof",
                    v.name()
                )));
            }
            if !seen.contains(&key(&set)) {
                seen.push(key(&set));
                variants.push(set.to_string());
            }
        }
        if !suite {
            self.variants = variants;
        }
        // Normalized to the loaded tracers' own names, each once, in the server's order.
        self.tracers = catalogue
            .tracers_named(&self.tracers)?
            .into_iter()
            .map(|t| t.name)
            .collect();
        Ok(self)
    }

    /// The checked thread count as the runner takes it.
    pub fn thread_count(&self) -> Result<Option<u16>, ApiError> {
        self.threads
            .map(runner::pool::check_threads)
            .transpose()
            .map_err(|e| ApiError::invalid(e.to_string()))
    }

    /// Whether the job runs `part`.
    pub fn runs(&self, part: Part) -> bool {
        self.run.contains(&part)
    }
}

/// Where a job is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JobStatus {
    Queued,
    Running,
    Done,
    /// It ran and failed (an error, a crash); partial outputs under `partial/`.
    Failed,
    /// Stopped by the user; partial outputs under `partial/`.
    Cancelled,
    /// The server stopped (or was killed) while it was queued or running.
    Interrupted,
}

impl JobStatus {
    /// Whether the job will not change any more.
    pub fn is_final(self) -> bool {
        !matches!(self, JobStatus::Queued | JobStatus::Running)
    }
}

/// How far a running job is.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct JobProgress {
    /// The runner's stage (`machine`, `scenes`, `profile`) or `reports`.
    pub stage: String,
    pub done: u64,
    pub total: u64,
    /// What is being done now.
    pub message: String,
    /// The whole job's share done, 0 to 1 (an estimate of the stages' weights).
    pub fraction: f64,
    /// The work the message names, in its own count (the timed renders, the
    /// profiler's samples), when the runner counts it.
    #[serde(default)]
    pub within: Option<Within>,
}

/// A count inside a stage's step: `done` of `total` `what` ("timed renders").
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Within {
    pub what: String,
    pub done: u64,
    pub total: u64,
}

impl Within {
    /// The share done, 0 to 1; `None` for a count of nothing.
    pub fn fraction(&self) -> Option<f64> {
        (self.total > 0).then(|| self.done.min(self.total) as f64 / self.total as f64)
    }
}

/// The stages a job goes through, in order, and what the page calls them.
pub const STAGES: [(&str, &str); 4] = [
    ("machine", "measuring the machine's peaks"),
    ("scenes", "rendering, counting and timing"),
    ("profile", "profiling"),
    ("reports", "writing the reports"),
];

impl JobProgress {
    /// The share of what the line says is under way: the work's own count when the
    /// runner counts it (timing 4 of 12 renders, 150 of 300 samples), else the stage's
    /// steps (the scenes' variants); `None` while neither is counted (the page shows an
    /// indeterminate bar rather than a made-up share).
    pub fn stage_fraction(&self) -> Option<f64> {
        self.within.as_ref().and_then(Within::fraction).or_else(|| {
            (self.total > 0).then(|| self.done.min(self.total) as f64 / self.total as f64)
        })
    }

    /// "step 2 of 4: rendering, counting and timing (1 of 3 variants done): 1/1 balls3:
    /// timing 3 variants".
    pub fn line(&self) -> String {
        let Some(at) = STAGES.iter().position(|(key, _)| *key == self.stage) else {
            return match self.message.is_empty() {
                true => self.stage.clone(),
                false => format!("{}: {}", self.stage, self.message),
            };
        };
        let mut line = format!(
            "step {} of {}: {}",
            format::count(at as u64 + 1),
            format::count(STAGES.len() as u64),
            STAGES[at].1
        );
        if self.total > 0 {
            let what = match self.stage.as_str() {
                "scenes" => "scene × variant runs",
                _ => "steps",
            };
            line.push_str(&format!(
                " ({} of {} {what} done)",
                format::count(self.done.min(self.total)),
                format::count(self.total)
            ));
        }
        if !self.message.is_empty() {
            line.push_str(": ");
            line.push_str(&self.message);
        }
        if let Some(w) = self.within.as_ref().filter(|w| w.total > 0) {
            line.push_str(&format!(
                " ({} of {} {})",
                format::count(w.done.min(w.total)),
                format::count(w.total),
                w.what
            ));
        }
        line
    }
}

/// A job's figures as the page shows them, written by `reports::format` (the page
/// formats no number itself). Rebuilt for every answer; never read back.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct JobText {
    /// "2026-11-27 20:11:25 UTC".
    pub created: String,
    pub started: Option<String>,
    pub finished: Option<String>,
    /// How long it ran ("3 min 05 s"), or has been running; `None` without a start.
    pub elapsed: Option<String>,
    /// "160×120".
    pub size: String,
    /// The timed renders' threads: "1 thread", "4 threads".
    pub threads: String,
    /// "balls3", or "the quick suite".
    pub scene: String,
    /// "baseline, bvh", or "every variant".
    pub variants: String,
    /// The progress line of a queued or running job (see [`JobProgress::line`]).
    pub progress: String,
    /// The current stage's own share, 0 to 1, for the page's bar (`None`: unknown).
    pub stage_fraction: Option<f64>,
}

/// A job as the API returns it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Job {
    pub id: String,
    pub request: JobRequest,
    pub status: JobStatus,
    /// RFC 3339 UTC.
    pub created: String,
    pub started: Option<String>,
    pub finished: Option<String>,
    pub progress: JobProgress,
    pub error: Option<String>,
    /// The job's files, relative to its directory (results.json, report.html, images,
    /// `partial/...` for a job that did not finish).
    #[serde(default)]
    pub files: Vec<String>,
    /// Seconds since the Unix epoch at its start and end, for its duration (older
    /// job.json files have none).
    #[serde(default)]
    pub started_unix: Option<u64>,
    #[serde(default)]
    pub finished_unix: Option<u64>,
    /// Its figures written for the page ([`Job::with_text`]).
    #[serde(default)]
    pub text: JobText,
}

/// Seconds since the Unix epoch now.
pub fn unix_now() -> u64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs())
}

impl Job {
    /// The job with [`Job::text`] written as of now.
    pub fn with_text(mut self) -> Job {
        let request = &self.request;
        let suite = request.runs(Part::Suite);
        let end = match self.status.is_final() {
            true => self.finished_unix,
            false => Some(unix_now()),
        };
        let elapsed = match (self.started_unix, end) {
            (Some(start), Some(end)) => Some(format::elapsed(end.saturating_sub(start))),
            _ => None,
        };
        let active = !self.status.is_final();
        self.text = JobText {
            created: format::timestamp(&self.created),
            started: self.started.as_deref().map(format::timestamp),
            finished: self.finished.as_deref().map(format::timestamp),
            elapsed,
            size: format::size(request.size[0], request.size[1]),
            threads: format::kind_count(request.threads.unwrap_or(1), "threads"),
            scene: match suite {
                true => "the quick suite".to_string(),
                false => request.scene.clone(),
            },
            variants: {
                let own = match suite {
                    true => vec!["every variant".to_string()],
                    false => request.variants.clone(),
                };
                let outside = request.tracers.iter().map(|t| format!("tracer:{t}"));
                own.into_iter()
                    .chain(outside)
                    .collect::<Vec<_>>()
                    .join(", ")
            },
            progress: match active {
                true => self.progress.line(),
                false => String::new(),
            },
            stage_fraction: self.progress.stage_fraction().filter(|_| active),
        };
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn catalogue() -> Catalogue {
        Catalogue::new(std::path::PathBuf::from("/nonexistent/uploads"), 1024)
    }

    fn request(scene: &str, variants: &[&str]) -> JobRequest {
        JobRequest {
            scene: scene.into(),
            variants: variants.iter().map(|v| v.to_string()).collect(),
            size: [16, 12],
            threads: None,
            run: vec![Part::Profile],
            tracers: Vec::new(),
        }
    }

    #[test]
    fn requests_are_normalized_baseline_first_without_repeats() {
        let r = request("balls3", &["simd+bvh", "bvh", "baseline", "bvh+simd"])
            .checked(&catalogue())
            .unwrap();
        // The reference first, each set once (in its first spelling).
        assert_eq!(r.variants, ["baseline", "simd+bvh", "bvh"]);
        assert_eq!(r.run, [Part::Render, Part::Profile]);
        // The suite runs its own scenes and variants.
        let mut suite = request("", &["bvh"]);
        suite.run = vec![Part::Suite, Part::Hardware];
        let suite = suite.checked(&catalogue()).unwrap();
        assert_eq!((suite.scene.as_str(), suite.variants.len()), ("", 0));
        assert_eq!(suite.run, [Part::Render, Part::Suite]);
    }

    #[test]
    fn bad_requests_say_what_to_change() {
        let message = |r: JobRequest| r.checked(&catalogue()).unwrap_err().message;
        assert!(message(request("", &[])).contains("no scene"));
        assert!(message(request("balls99", &[])).contains("unknown scene 'balls99'"));
        assert!(message(request("/etc/passwd", &[])).contains("unknown scene"));
        assert!(message(request("upload:../x", &[])).contains("not a scene name"));
        assert!(message(request("upload:missing", &[])).contains("upload it first"));
        assert!(message(request("spd:balls:99", &[])).contains("out of range"));
        assert!(message(request("balls3", &["warp"])).contains("variant 'warp'"));
        assert!(message(request("balls3", &["bvh,simd"])).contains("its own entry"));
        let mut big = request("balls3", &[]);
        big.size = [1 << 20, 2];
        assert!(message(big).contains("size 1048576x2"));
        let (max, _) = runner::pool::max_threads();
        for bad in [0, u64::from(max) + 1, 999 + u64::from(max), 1 << 40] {
            let mut threads = request("balls3", &[]);
            threads.threads = Some(bad);
            let said = message(threads);
            assert!(
                said.starts_with(&format!("threads {bad}: choose 1 to {max} ")),
                "{said}"
            );
        }
        let mut most = request("balls3", &[]);
        most.threads = Some(u64::from(max));
        assert_eq!(
            most.checked(&catalogue()).unwrap().thread_count().unwrap(),
            Some(max)
        );
    }

    #[test]
    fn the_line_and_the_bar_follow_the_work_under_way() {
        let mut p = JobProgress {
            stage: "scenes".into(),
            done: 1,
            total: 4,
            message: "1/1 balls3: timing 3 variants".into(),
            ..JobProgress::default()
        };
        assert_eq!(p.stage_fraction(), Some(0.25));
        p.within = Some(Within {
            what: "timed renders".into(),
            done: 1_234,
            total: 4_000,
        });
        assert_eq!(
            p.line(),
            "step 2 of 4: rendering, counting and timing (1 of 4 scene × variant runs done): \
             1/1 balls3: timing 3 variants (1,234 of 4,000 timed renders)"
        );
        // The bar shows what the line's last count says: 1,234 / 4,000.
        assert_eq!(p.stage_fraction(), Some(0.3085));
    }
}
