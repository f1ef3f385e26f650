//! Schema `rtprof.results/1`, as rtprof wrote it up to commit d19ee0e, and its
//! upgrade to the current schema.
//!
//! Differences from `/2`: enumerations are free strings (the RMS band in its human
//! wording, `"visually similar"` in older test files; the hardware row kind as
//! `"IP core"`), hardware figures are `[u64; 6]` arrays in the column order latency,
//! LE, comb, regs, mem bits, mult; a failed hardware job names the variant
//! `"hardware"`, a failed profile the scene `"profile"`; times cover preprocessing
//! and tracing together and the timing policy is `repeats` and `min_seconds` only.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::error::ResultsError;
use crate::hardware as v2hw;
use crate::schema as v2;
use crate::timing_policy::{TimeCovers, TimingPolicy};
use crate::variant_name::VariantName;

pub use crate::schema::SCHEMA_V1 as SCHEMA;

/// What rtprof's suite used while it wrote `/1` files (src/cli/suite.rs at d19ee0e):
/// the defaults an upgraded file's timing policy records.
pub const MAX_REPEATS: u32 = 100;
pub const BOOTSTRAP_RESAMPLES: u32 = 2000;
pub const CONFIDENCE: f64 = 0.95;
pub const SEED: u64 = 0x5eed;

pub use crate::hardware::DeviceUse;
pub use crate::schema::{AmdahlRow, Build, CriterionEstimate, FlatRow, InstructionCount, Machine};
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

pub use crate::schema::Estimate;

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

/// A `/1` band word as `analysis::Band`: the human wording rtprof wrote, and the
/// schema documentation's `"visually similar"`.
fn band(word: &str, path: &str) -> Result<v2::Band, ResultsError> {
    match word {
        "visually identical" => Ok(v2::Band::VisuallyIdentical),
        "similar" | "visually similar" => Ok(v2::Band::Similar),
        "notable changes" => Ok(v2::Band::NotableChanges),
        "different" => Ok(v2::Band::Different),
        other => Err(ResultsError::invalid(
            path,
            format!(
                "'{other}' is not a band (visually identical, similar, notable changes, different)"
            ),
        )),
    }
}

fn family(word: &str, path: &str) -> Result<v2::SceneFamily, ResultsError> {
    use v2::SceneFamily as F;
    match word {
        "balls" => Ok(F::Balls),
        "cylinder" => Ok(F::Cylinder),
        "both" => Ok(F::Both),
        "spd" => Ok(F::Spd),
        "generated" => Ok(F::Generated),
        // `extra`: a scene of a `--scenes DIR` other than spd; its source names the file.
        "other" | "extra" => Ok(F::Other),
        other => Err(ResultsError::invalid(
            path,
            format!("'{other}' is not a scene family"),
        )),
    }
}

fn variant(name: &str, path: &str) -> Result<VariantName, ResultsError> {
    VariantName::parse(name).map_err(|e| ResultsError::invalid(path, e.to_string()))
}

fn hw_kind(word: &str, path: &str) -> Result<v2hw::HwRowKind, ResultsError> {
    match word {
        "IP core" => Ok(v2hw::HwRowKind::IpCore),
        "composite" => Ok(v2hw::HwRowKind::Composite),
        "block" => Ok(v2hw::HwRowKind::Block),
        other => Err(ResultsError::invalid(
            path,
            format!("'{other}' is not a row kind (IP core, composite, block)"),
        )),
    }
}

fn hw_row(row: HwRow, path: &str) -> Result<v2hw::HwRow, ResultsError> {
    Ok(v2hw::HwRow {
        kind: hw_kind(&row.kind, &format!("{path}.kind"))?,
        name: row.name,
        model: v2hw::HwFigures::from_columns(row.model),
        thesis: row.thesis.map(v2hw::HwFigures::from_columns),
        error_pct: row.error_pct.map(|e| v2hw::HwErrors {
            latency: e[0],
            le: e[1],
            comb: e[2],
            regs: e[3],
            mem_bits: e[4],
            mult: e[5],
        }),
    })
}

fn profile(p: Profile, path: &str) -> Result<v2::Profile, ResultsError> {
    Ok(v2::Profile {
        variant: variant(&p.variant, &format!("{path}.variant"))?,
        samples: p.samples,
        seconds_per_sample: p.seconds_per_sample,
        flat: p.flat,
        flat_text: p.flat_text,
        callgraph_text: p.callgraph_text,
        flame_svg: p.flame_svg,
        amdahl: p.amdahl,
        // Not recorded before /3: calls are totals over the sampled renders.
        renders: None,
        samples_asked: None,
        timer: None,
        cpu_seconds: None,
        counts: Default::default(),
        view: v2::ProfileView::Native,
        second_view: None,
        exports: Vec::new(),
    })
}

fn variant_result(v: VariantResult, path: &str) -> Result<v2::VariantResult, ResultsError> {
    let quality = match v.quality {
        Some(q) => Some(v2::Quality {
            band: band(&q.band, &format!("{path}.quality.band"))?,
            rms: q.rms,
            psnr: q.psnr,
            ssim: q.ssim,
            max_abs_diff: q.max_abs_diff,
        }),
        None => None,
    };
    Ok(v2::VariantResult {
        variant: variant(&v.variant, &format!("{path}.variant"))?,
        time: v.time,
        samples: v.samples,
        cpu_samples: Vec::new(),
        // `/1` times include it; it was not measured apart.
        preprocessing_seconds: None,
        speedup: Some(v.speedup),
        speedup_interval: None,
        verdict: None,
        counts: v.counts,
        image: v.image,
        heat_map: v.heat_map,
        quality,
        vs_f64_reference: None,
        histogram: v.histogram,
        lane_utilization: None,
        efficiency: None,
        ray_rates: None,
        outside: None,
    })
}

fn scene(s: SceneResult, path: &str) -> Result<v2::SceneResult, ResultsError> {
    let hardware = match s.hardware {
        Some(h) => Some(v2hw::SceneHardware {
            emulator_band: band(&h.emulator_band, &format!("{path}.hardware.emulator_band"))?,
            primitives: h.primitives,
            cycles: h.cycles,
            seconds: h.seconds,
            fits: h.fits,
            fit_state: None,
            software_seconds: h.software_seconds,
            speedup: h.speedup,
            peer: None,
            emulator_rms: h.emulator_rms,
            emulator_image: h.emulator_image,
            software_image: h.software_image,
        }),
        None => None,
    };
    Ok(v2::SceneResult {
        family: family(&s.family, &format!("{path}.family"))?,
        variants: s
            .variants
            .into_iter()
            .enumerate()
            .map(|(i, v)| variant_result(v, &format!("{path}.variants[{i}]")))
            .collect::<Result<_, _>>()?,
        name: s.name,
        source: s.source,
        primitives: s.primitives,
        primitive_counts: s.primitive_counts,
        width: s.width,
        height: s.height,
        spd: s.spd,
        hardware,
        calibration: None,
        yardstick: None,
        published: None,
        memory: None,
        bvh_quality: Vec::new(),
        pixel_maps: Vec::new(),
        f64_reference: None,
        threads: None,
    })
}

fn failure(f: Failure, path: &str) -> Result<v2::Failure, ResultsError> {
    Ok(match f.variant.as_deref() {
        Some("hardware") => v2::Failure {
            scene: Some(f.scene),
            part: v2::FailedPart::Hardware,
            message: f.message,
        },
        Some(name) => v2::Failure {
            part: v2::FailedPart::Variant(variant(name, &format!("{path}.variant"))?),
            scene: Some(f.scene),
            message: f.message,
        },
        None if f.scene == "profile" => v2::Failure {
            scene: None,
            part: v2::FailedPart::Profile,
            message: f.message,
        },
        None => v2::Failure {
            scene: Some(f.scene),
            part: v2::FailedPart::Scene,
            message: f.message,
        },
    })
}

impl Results {
    /// The same run in the current schema. Fields `/1` did not have get: the timing
    /// policy of the suite that wrote `/1` files ([`MAX_REPEATS`], …) with
    /// `covers: preprocessing_and_tracing`, and `preprocessing_seconds: None`.
    pub fn upgrade(self) -> Result<v2::Results, ResultsError> {
        let hardware = match self.hardware {
            Some(h) => Some(v2hw::HardwareResult {
                ops: h
                    .ops
                    .into_iter()
                    .enumerate()
                    .map(|(i, r)| hw_row(r, &format!("hardware.ops[{i}]")))
                    .collect::<Result<_, _>>()?,
                blocks: h
                    .blocks
                    .into_iter()
                    .enumerate()
                    .map(|(i, r)| hw_row(r, &format!("hardware.blocks[{i}]")))
                    .collect::<Result<_, _>>()?,
                family: h.family,
                devices: h.devices,
                synthesis: None,
                rtl_clock: None,
                upload: None,
            }),
            None => None,
        };
        let profile = match self.profile {
            Some(p) => Some(v2::ProfileResult {
                baseline: profile(p.baseline, "profile.baseline")?,
                best: match p.best {
                    Some(b) => Some(profile(b, "profile.best")?),
                    None => None,
                },
                scene: p.scene,
                width: p.width,
                height: p.height,
                diff_flame_svg: p.diff_flame_svg,
                diff_shrunk_flame_svg: None,
            }),
            None => None,
        };
        let suite = v2::SuiteInfo {
            variants: self
                .suite
                .variants
                .iter()
                .enumerate()
                .map(|(i, v)| variant(v, &format!("suite.variants[{i}]")))
                .collect::<Result<_, _>>()?,
            timing: TimingPolicy {
                min_repeats: self.suite.repeats,
                min_seconds: self.suite.min_seconds,
                max_repeats: MAX_REPEATS,
                bootstrap_resamples: BOOTSTRAP_RESAMPLES,
                confidence: CONFIDENCE,
                seed: SEED,
                covers: TimeCovers::PreprocessingAndTracing,
                interleaved: false,
            },
            noise_threshold: None,
            shard: None,
            name: self.suite.name,
            quick: self.suite.quick,
            threads: self.suite.threads,
            wall_seconds: self.suite.wall_seconds,
        };
        Ok(v2::Results {
            schema: v2::SCHEMA.to_string(),
            created: self.created,
            command: self.command,
            machine: self.machine,
            build: self.build,
            suite,
            scenes: self
                .scenes
                .into_iter()
                .enumerate()
                .map(|(i, s)| scene(s, &format!("scenes[{i}]")))
                .collect::<Result<_, _>>()?,
            profile,
            hardware,
            failures: self
                .failures
                .into_iter()
                .enumerate()
                .map(|(i, f)| failure(f, &format!("failures[{i}]")))
                .collect::<Result<_, _>>()?,
            criterion: self.criterion,
            instructions: self.instructions,
            peak: None,
            outside_profiles: Vec::new(),
        })
    }
}
