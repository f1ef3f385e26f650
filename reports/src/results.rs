//! The results file, `results.json`: schema `rtprof.results/1`.
//!
//! Everything a report shows is here, so a report can be rebuilt from the file alone
//! (`rtprof report results.json`) and two machines' files can be set side by side.
//! Images are PNG files next to `results.json`, referenced by relative path.
//! Counts are flattened to `"ops.dot": n` pairs so the regression gate can compare any
//! two files without knowing the counter layout.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// The schema identifier written in every file.
pub const SCHEMA: &str = "rtprof.results/1";

/// A whole suite run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// Always [`SCHEMA`].
    pub schema: String,
    /// When the run started, RFC 3339 UTC.
    pub created: String,
    /// The command that reproduces this run.
    pub command: String,
    pub machine: Machine,
    pub build: Build,
    pub suite: SuiteInfo,
    pub scenes: Vec<SceneResult>,
    /// Profile of the heaviest scene (baseline and the best variant).
    pub profile: Option<ProfileResult>,
    /// The FPGA model: tables 7 and 8, device fit.
    pub hardware: Option<HardwareResult>,
    /// Parts of the run that failed; the rest of the results stand.
    pub failures: Vec<Failure>,
    /// Criterion estimates picked up from a `target/criterion` directory, if any.
    #[serde(default)]
    pub criterion: Vec<CriterionEstimate>,
    /// Instruction counts picked up from gungraun's summaries (`target/gungraun`), if
    /// any; their ids match the criterion benchmark doing the same work.
    #[serde(default)]
    pub instructions: Vec<InstructionCount>,
}

/// The machine the run was made on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Machine {
    pub cpu_model: String,
    /// Logical CPUs.
    pub cores: u32,
    pub os: String,
    pub hostname: String,
}

/// The build that ran.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Build {
    pub rtprof_version: String,
    pub rustc: String,
    pub git_commit: String,
    /// `release` or `debug`.
    pub profile: String,
}

/// What was run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SuiteInfo {
    pub name: String,
    pub quick: bool,
    /// Timed renders per scene and variant (at least).
    pub repeats: u32,
    /// More renders were timed, up to 100, until this many seconds were measured.
    #[serde(default)]
    pub min_seconds: f64,
    pub threads: u32,
    pub variants: Vec<String>,
    /// Wall time of the whole suite, seconds.
    pub wall_seconds: f64,
}

/// Median and 95 % bootstrap interval.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    pub median: f64,
    pub low: f64,
    pub high: f64,
}

impl Estimate {
    /// The same estimate in another unit (`1e-9` turns nanoseconds into seconds).
    pub fn scaled(&self, factor: f64) -> Estimate {
        Estimate {
            median: self.median * factor,
            low: self.low * factor,
            high: self.high * factor,
        }
    }
}

/// One scene and every variant run on it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneResult {
    pub name: String,
    /// `builtin`, `generated` or the file's path.
    pub source: String,
    /// `balls`, `cylinder`, `both`, `spd`, `generated` or `other`.
    pub family: String,
    /// Primitives of every kind.
    pub primitives: u64,
    /// Per kind: `spheres`, `cylinders`, `cones`, `polygons`, `patches`.
    pub primitive_counts: BTreeMap<String, u64>,
    pub width: u32,
    pub height: u32,
    /// SPD corner sampling.
    pub spd: bool,
    pub variants: Vec<VariantResult>,
    /// The hardware model and emulator on this scene (spheres and cylinders only).
    pub hardware: Option<SceneHardware>,
}

/// One variant on one scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VariantResult {
    pub variant: String,
    /// Tracing time (median and interval over the repeats), seconds.
    pub time: Estimate,
    /// Every timed repeat, seconds.
    pub samples: Vec<f64>,
    /// Baseline median / this median.
    pub speedup: f64,
    /// Exact counts, flattened (`ops.dot`, `rays.primary`, …).
    pub counts: BTreeMap<String, u64>,
    /// The image, relative to results.json.
    pub image: Option<String>,
    /// Difference heat map against baseline, relative to results.json.
    pub heat_map: Option<String>,
    /// Image metrics against baseline (None for baseline itself).
    pub quality: Option<Quality>,
    /// Gray histogram (256 bins) of the image.
    pub histogram: Vec<u64>,
}

/// Image error against baseline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Quality {
    pub rms: f64,
    /// The thesis's band: `visually identical`, `visually similar`, …
    pub band: String,
    /// dB; None when the images are identical (infinite).
    pub psnr: Option<f64>,
    pub ssim: f64,
    pub max_abs_diff: u32,
}

/// The FPGA model and emulator on one scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneHardware {
    pub primitives: u64,
    pub cycles: u64,
    pub seconds: f64,
    pub fits: bool,
    /// Software time of the same job (baseline, diffuse-only gray), seconds.
    pub software_seconds: Estimate,
    /// Software seconds / hardware seconds.
    pub speedup: f64,
    /// RMS between the emulator's image and the software's diffuse-only render.
    pub emulator_rms: f64,
    pub emulator_band: String,
    /// Emulator image, relative to results.json.
    pub emulator_image: Option<String>,
    /// Software diffuse-only image, relative to results.json.
    pub software_image: Option<String>,
}

/// One function of a flat profile.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FlatRow {
    pub name: String,
    pub percent: f64,
    pub self_seconds: f64,
    pub total_seconds: f64,
    /// Exact calls from the counters, when counted.
    pub calls: Option<u64>,
}

/// One row of the Amdahl table.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AmdahlRow {
    pub name: String,
    /// Fraction of the time in this function.
    pub fraction: f64,
    /// Whole-program speed-up if it became 2x, 10x and infinitely faster.
    pub speedup_2x: f64,
    pub speedup_10x: f64,
    pub speedup_limit: f64,
}

/// A sampled profile of one scene and variant.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Profile {
    pub variant: String,
    pub samples: u64,
    pub seconds_per_sample: f64,
    pub flat: Vec<FlatRow>,
    /// gprof-layout texts, relative to results.json.
    pub flat_text: String,
    pub callgraph_text: String,
    /// Flamegraph SVG, relative to results.json.
    pub flame_svg: String,
    pub amdahl: Vec<AmdahlRow>,
}

/// The profile section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProfileResult {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub baseline: Profile,
    pub best: Option<Profile>,
    /// Differential flamegraph baseline → best, relative to results.json.
    pub diff_flame_svg: Option<String>,
}

/// One row of tables 7 or 8: the model's figures, the thesis's, the errors (%).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HwRow {
    pub name: String,
    /// `IP core`, `composite` or `block`.
    pub kind: String,
    /// latency, le, comb, regs, mem_bits, mult.
    pub model: [u64; 6],
    pub thesis: Option<[u64; 6]>,
    pub error_pct: Option<[Option<f64>; 6]>,
}

/// Device utilization of the thesis design.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DeviceUse {
    pub device: String,
    pub validated: bool,
    pub le: u64,
    pub le_capacity: u64,
    pub mult: u64,
    pub mult_capacity: u64,
    pub soft_mult_elements: u64,
    pub mem_bits: u64,
    pub mem_capacity: u64,
    pub plls: u32,
    pub pll_capacity: u32,
    pub fits: bool,
    pub largest_units: Option<u32>,
}

/// The FPGA model's tables and fit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HardwareResult {
    pub family: String,
    pub ops: Vec<HwRow>,
    pub blocks: Vec<HwRow>,
    pub devices: Vec<DeviceUse>,
}

/// Something that failed; the run went on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Failure {
    pub scene: String,
    pub variant: Option<String>,
    pub message: String,
}

/// One criterion benchmark's estimates (nanoseconds).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CriterionEstimate {
    pub id: String,
    pub mean: Estimate,
    pub median: Estimate,
    /// When it was measured (the estimates file's time, RFC 3339 UTC).
    #[serde(default)]
    pub measured: Option<String>,
}

/// One benchmark's instruction count under valgrind (deterministic, unlike time).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct InstructionCount {
    /// The id of the criterion benchmark that does the same work (`sqrt/fast-sqrt`).
    pub id: String,
    /// Instructions executed (callgrind's `Ir`).
    pub instructions: u64,
    /// Callgrind's cycle estimate from its cache simulation, when it ran one.
    #[serde(default)]
    pub estimated_cycles: Option<u64>,
    /// When it was counted (the summary file's time, RFC 3339 UTC).
    #[serde(default)]
    pub measured: Option<String>,
}

impl Results {
    /// Reads a results file, checking the schema.
    pub fn from_json(text: &str) -> Result<Self, ResultsError> {
        let value: serde_json::Value = serde_json::from_str(text)?;
        match value.get("schema").and_then(|s| s.as_str()) {
            Some(SCHEMA) => Ok(serde_json::from_value(value)?),
            Some(other) => Err(ResultsError::Schema(other.to_string())),
            None => Err(ResultsError::Schema("(none)".to_string())),
        }
    }

    /// The baseline result of a scene, if it ran.
    pub fn baseline<'a>(&self, scene: &'a SceneResult) -> Option<&'a VariantResult> {
        scene.variants.iter().find(|v| v.variant == "baseline")
    }
}

/// Seconds since the epoch as RFC 3339 UTC (civil-from-days, no time-zone crate).
pub fn rfc3339_utc(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// A results file that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum ResultsError {
    #[error("not a results file: {0}")]
    Json(#[from] serde_json::Error),
    #[error("results schema '{0}' is not {SCHEMA}: rebuild it with this rtprof version")]
    Schema(String),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rfc3339_matches_known_instants() {
        assert_eq!(rfc3339_utc(0), "1970-01-01T00:00:00Z");
        // 2000-02-29 12:34:56 UTC (a leap day) = 951827696.
        assert_eq!(rfc3339_utc(951_827_696), "2000-02-29T12:34:56Z");
        // 2026-11-21 00:00:00 UTC = 1795219200.
        assert_eq!(rfc3339_utc(1_795_219_200), "2026-11-21T00:00:00Z");
    }
}
