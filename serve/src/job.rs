//! A job: what a user asked to run ([`JobRequest`], checked before it is queued), and
//! what the server knows of it ([`Job`]: status, progress, files), as the API returns
//! it and as `job.json` keeps it in the job's directory.

use serde::{Deserialize, Serialize};
use tracer::VariantSet;

use crate::catalogue::Catalogue;
use crate::error::ApiError;

/// What a job runs besides the renders (the suite's parts).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Part {
    /// Every variant rendered, counted, timed and compared with baseline (always run).
    Render,
    /// The scene sampled: gprof-format profile and flamegraphs of baseline and the
    /// fastest variant whose picture stays visually identical.
    Profile,
    /// The FPGA pipeline model (time, fit) and its emulator's image.
    Hardware,
    /// Per-pixel maps of baseline, simd and bvh.
    PixelMaps,
    /// The embedded suite's CI-sized run (`rtprof suite --quick`): every scene and
    /// variant; the job's scene and variants are ignored.
    Suite,
}

impl Part {
    pub const ALL: [Part; 5] = [
        Part::Render,
        Part::Profile,
        Part::Hardware,
        Part::PixelMaps,
        Part::Suite,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Part::Render => "render",
            Part::Profile => "profile",
            Part::Hardware => "hardware",
            Part::PixelMaps => "pixel_maps",
            Part::Suite => "suite",
        }
    }

    /// What the page says of it.
    pub fn label(self) -> &'static str {
        match self {
            Part::Render => "render and compare: counts, times, images and their difference",
            Part::Profile => "profile: gprof flat profile, call graph, flamegraphs",
            Part::Hardware => "hardware: FPGA model time and fit, emulator image",
            Part::PixelMaps => "per-pixel maps of baseline, simd and bvh",
            Part::Suite => "the whole quick suite (every scene and variant; a few minutes)",
        }
    }
}

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
    /// Worker threads (default: one per core).
    #[serde(default)]
    pub threads: Option<u16>,
    /// What to run (default: render).
    #[serde(default = "default_run")]
    pub run: Vec<Part>,
}

fn default_size() -> [u32; 2] {
    [160, 120]
}

fn default_run() -> Vec<Part> {
    vec![Part::Render]
}

/// Most worker threads a job may ask for (as the command line's `--threads`).
pub const MAX_THREADS: u16 = 1024;

impl JobRequest {
    /// The request checked and normalized: a known scene, known variants (baseline
    /// first, no repeats), a size within the tracer's limits, a sane thread count. Every
    /// refusal is a 422 saying what to change; nothing is allocated for the size.
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
        if let Some(threads) = self.threads
            && !(1..=MAX_THREADS).contains(&threads)
        {
            return Err(ApiError::invalid(format!(
                "threads {threads}: choose 1 to {MAX_THREADS}, or leave it out for one per core"
            )));
        }
        let mut variants = vec!["baseline".to_string()];
        for name in &self.variants {
            let set = VariantSet::parse(name)
                .map_err(|e| ApiError::invalid(format!("variant '{name}': {e}")))?;
            if let Some(v) = set.variants().iter().find(|v| !v.available()) {
                return Err(ApiError::invalid(format!(
                    "variant '{name}': {} is not built into this rtprof",
                    v.name()
                )));
            }
            let canonical = set.to_string();
            if !variants.contains(&canonical) {
                variants.push(canonical);
            }
        }
        if !suite {
            self.variants = variants;
        }
        Ok(self)
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
}
