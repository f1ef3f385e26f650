//! The growth study of `rtprof scaling` (`scaling.json`, schema [`SCALING_SCHEMA`]):
//! each accelerator's cost per ray against the number of primitives, over families of
//! SPD scenes generated at growing size factors, with the fitted power law per
//! accelerator. Brute force is measured only where a render stays short; beyond, its
//! points are extrapolated with its fitted law and marked so.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::{Build, Machine};

/// The schema identifier of `scaling.json`.
pub const SCALING_SCHEMA: &str = "rtprof.scaling/1";

/// One run of the growth study.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ScalingStudy {
    pub schema: String,
    pub created: String,
    pub command: String,
    pub machine: Machine,
    pub build: Build,
    pub threads: u32,
    /// The frame every point renders (pixel centres).
    pub width: u32,
    pub height: u32,
    /// Timed renders per measured point, at least (the median is kept).
    pub repeats: u32,
    /// More timed renders (up to 100) until this many seconds of tracing were
    /// measured for the point.
    #[serde(default)]
    pub min_seconds: f64,
    /// A render predicted longer than this many seconds is extrapolated, not run.
    pub budget_seconds: f64,
    pub points: Vec<ScalingPoint>,
    pub fits: Vec<ScalingFit>,
}

/// One scene size with one accelerator.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ScalingPoint {
    /// The SPD program: `balls`, `shells`, `tetra`.
    pub family: String,
    pub size_factor: u32,
    pub primitives: u64,
    /// The variant: `baseline` (brute force), `simd`, `bvh`.
    pub accelerator: String,
    /// False: extrapolated with the accelerator's fitted law (no render ran).
    pub measured: bool,
    /// Rays of every kind in one render (measured points).
    pub rays: Option<u64>,
    /// Median tracing seconds divided by the rays.
    pub seconds_per_ray: f64,
    /// Ray-primitive tests per ray (every primitive kind).
    pub tests_per_ray: Option<f64>,
    /// Acceleration-structure nodes visited per ray (0 without one).
    pub nodes_per_ray: Option<f64>,
    /// Preprocessing seconds (median): scene preparation and the structure's build.
    pub build_seconds: Option<f64>,
    /// Bytes of the acceleration structure (0: none).
    pub accelerator_bytes: Option<u64>,
    /// Bytes of the parsed scene.
    pub scene_bytes: u64,
}

/// `seconds_per_ray = coefficient · primitives^exponent`, fitted on the measured points
/// of one family and accelerator (least squares on log-log axes).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ScalingFit {
    pub family: String,
    pub accelerator: String,
    pub exponent: f64,
    pub coefficient: f64,
    /// The exponent of tests per ray, fitted the same way.
    pub tests_exponent: Option<f64>,
    /// Measured points the fit rests on.
    pub points: u32,
}
