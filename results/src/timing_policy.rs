//! How a run's times were measured: the timing policy written into results.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// What a recorded time covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TimeCovers {
    /// Tracing only (the SPD rules' figure); preprocessing (scene preparation and
    /// structure build) is reported apart, in `preprocessing_seconds`.
    Tracing,
    /// Preprocessing and tracing together (files of schema `/1`).
    PreprocessingAndTracing,
}

impl TimeCovers {
    /// What it covers, in words.
    pub fn describe(self) -> &'static str {
        match self {
            TimeCovers::Tracing => "tracing only",
            TimeCovers::PreprocessingAndTracing => "preprocessing and tracing",
        }
    }
}

/// The timing policy of a run: how many renders were timed and how their median and
/// interval were estimated.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TimingPolicy {
    /// Timed renders per scene and variant, at least.
    pub min_repeats: u32,
    /// More renders were timed, up to `max_repeats`, until this many seconds were
    /// measured.
    pub min_seconds: f64,
    pub max_repeats: u32,
    /// Bootstrap resamples of the median's confidence interval.
    pub bootstrap_resamples: u32,
    /// The interval's confidence (0.95).
    pub confidence: f64,
    /// The bootstrap's seed (the same samples always give the same interval).
    pub seed: u64,
    pub covers: TimeCovers,
    /// The variants of a scene were timed in rounds (one render of each per round,
    /// and the calibration kernel), so that a change of load hits them alike.
    #[serde(default)]
    pub interleaved: bool,
}
