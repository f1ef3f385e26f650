//! The results file, `results.json`, schema `rtprof.results/3`.
//!
//! Everything a report shows is here, so a report can be rebuilt from the file alone
//! (`rtprof report results.json`) and two machines' files can be set side by side.
//! Images are PNG files next to `results.json`, referenced by relative path.
//! Counts are flattened to `"ops.dot": n` pairs so the regression gate can compare any
//! two files without knowing the counter layout. Every enumeration has one spelling
//! (snake case); `/2` files read as they are (the fields `/3` added have defaults: a
//! `/2` profile's calls are totals over its sampled renders, `renders` is unknown) and
//! `/1` files are read through [`crate::v1`].

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use analysis::profile::timer::Timer;
pub use analysis::{Band, Estimate, Verdict};

use crate::bvh_quality::BvhQuality;
pub use crate::efficiency::{Bound, CodeKind, Efficiency, MachinePeak, RayRates, Roof};
use crate::hardware::{HardwareResult, SceneHardware};
use crate::pixel_stats::VariantPixelMaps;
use crate::timing_policy::TimingPolicy;
use crate::variant_name::VariantName;

/// The schema identifier written in every file.
pub const SCHEMA: &str = "rtprof.results/3";
/// The previous schema, read with the same types (its profiles lack what `/3` added).
pub const SCHEMA_V2: &str = "rtprof.results/2";
/// The first schema, read with its own types ([`crate::v1`]) and upgraded.
pub const SCHEMA_V1: &str = "rtprof.results/1";

/// A whole suite run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Results {
    /// Always [`SCHEMA`] (files of [`SCHEMA_V2`] read as they are).
    #[schemars(
        description = "The schema identifier: rtprof.results/3 (rtprof.results/2 files have the same form, without /3's optional fields).",
        extend("enum" = [SCHEMA, SCHEMA_V2])
    )]
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
    /// The machine's measured compute and bandwidth peaks (the roofline's roofs).
    #[serde(default)]
    pub peak: Option<MachinePeak>,
    /// Outside tracers recorded with perf on the profile scene, where the suite asked
    /// (`record = true` in its `[[tracers]]`); absent when none was.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub outside_profiles: Vec<crate::OutsideProfile>,
}

/// The machine the run was made on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Machine {
    pub cpu_model: String,
    /// Logical CPUs.
    pub cores: u32,
    pub os: String,
    pub hostname: String,
}

/// The build that ran.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Build {
    pub rtprof_version: String,
    pub rustc: String,
    pub git_commit: String,
    /// `release` or `debug`.
    pub profile: String,
}

/// What was run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SuiteInfo {
    pub name: String,
    pub quick: bool,
    pub threads: u32,
    /// The variants in the order they ran; the first is the reference.
    pub variants: Vec<VariantName>,
    /// How every time of the run was measured and what it covers.
    pub timing: TimingPolicy,
    /// Wall time of the whole suite, seconds.
    pub wall_seconds: f64,
    /// The noise threshold (a fraction) of the file's verdicts ([`analysis::verdict`]);
    /// `None` in files written before verdicts were recorded.
    #[serde(default)]
    pub noise_threshold: Option<f64>,
    /// The share of the suite's scenes this file holds (`rtprof suite --shard I/N`);
    /// `None` for a whole run, and for a merge of shards (`rtprof merge`).
    #[serde(default)]
    pub shard: Option<Shard>,
}

/// One of `count` deterministic shares of a suite's scenes: shard `index` (1-based)
/// holds the scenes at the 0-based positions `p` of the suite's scene order with
/// `p % count == index - 1`, each with all its variants.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct Shard {
    /// 1 to `count`.
    pub index: u32,
    /// How many shards the suite was split into.
    pub count: u32,
}

impl Shard {
    /// Whether the scene at 0-based `position` of the suite's order belongs to this shard.
    pub fn holds(self, position: usize) -> bool {
        let (i, n) = (self.index as usize, self.count as usize);
        i >= 1 && n > 0 && position % n == i - 1
    }

    /// The 0-based position in the suite's order of this shard's `j`-th scene.
    pub fn position(self, j: usize) -> usize {
        j * self.count as usize + (self.index as usize).saturating_sub(1)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// Which test bench a scene belongs to.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum SceneFamily {
    /// The thesis's `ballsN` scenes.
    Balls,
    /// The thesis's `cylinderN` scenes.
    Cylinder,
    /// The thesis's `bothN` scenes (spheres and cylinders).
    Both,
    /// A Standard Procedural Database scene (`--scenes DIR` with DIR named `spd`).
    Spd,
    /// Made by a generator (`sphereflake:N`, `lattice:N`).
    Generated,
    /// Anything else (a built-in outside the test benches, an NFF file).
    Other,
}

impl SceneFamily {
    /// The three test benches of the thesis, in its order.
    pub const TEST_BENCHES: [SceneFamily; 3] =
        [SceneFamily::Balls, SceneFamily::Cylinder, SceneFamily::Both];

    /// The family's name as the file spells it.
    pub fn name(self) -> &'static str {
        match self {
            SceneFamily::Balls => "balls",
            SceneFamily::Cylinder => "cylinder",
            SceneFamily::Both => "both",
            SceneFamily::Spd => "spd",
            SceneFamily::Generated => "generated",
            SceneFamily::Other => "other",
        }
    }

    /// The test-bench family of a built-in scene's name: `balls7` is `Balls`, a name
    /// without the family's number is `Other`.
    pub fn of_builtin(name: &str) -> SceneFamily {
        for family in Self::TEST_BENCHES {
            if let Some(rest) = name.strip_prefix(family.name())
                && !rest.is_empty()
                && rest.chars().all(|c| c.is_ascii_digit())
            {
                return family;
            }
        }
        SceneFamily::Other
    }
}

impl std::fmt::Display for SceneFamily {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// One scene and every variant run on it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SceneResult {
    pub name: String,
    /// `builtin`, `generated` or the file's path.
    pub source: String,
    pub family: SceneFamily,
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
    /// The calibration kernel, timed once per round between this scene's renders: the
    /// gate's yardstick of the scene's root variant in files without [`Self::yardstick`].
    /// `None` in older files.
    #[serde(default)]
    pub calibration: Option<Calibration>,
    /// The f64 reference renderer on this scene at a smaller frame, timed once per round
    /// between this scene's renders: the gate divides the scene's root variant (baseline,
    /// or bvh where baseline did not run) by it (docs/gate.md). `None` in older files.
    #[serde(default)]
    pub yardstick: Option<Yardstick>,
    /// The ray statistics the SPD publishes for this scene, when it is a classic SPD
    /// scene rendered as the figures were (512 × 512, corner rays, depth 5): each
    /// variant's counts can be read against them. `None` otherwise and in older files.
    #[serde(default)]
    pub published: Option<PublishedRays>,
    /// What the scene's renders hold in memory. `None` in older files.
    #[serde(default)]
    pub memory: Option<MemoryUse>,
    /// The BVH of each build strategy, when the suite studied it on this scene.
    #[serde(default)]
    pub bvh_quality: Vec<BvhQuality>,
    /// Per-pixel maps of the variants that wrote them (suite option `pixel_stats`).
    #[serde(default)]
    pub pixel_maps: Vec<VariantPixelMaps>,
    /// The independent f64 reference renderer's picture of the scene, the ground truth
    /// each variant's [`VariantResult::vs_f64_reference`] is measured against (suite
    /// option `f64_reference`). `None` when it did not run, and in older files.
    #[serde(default)]
    pub f64_reference: Option<F64Reference>,
    /// Worker threads of this scene's renders when not the suite's (`suite.threads`):
    /// the SPD's small frames render on one thread (`[spd] small_on_one_thread`).
    /// `None`: the suite's, and in older files.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub threads: Option<u32>,
}

/// The f64 reference's render of a scene, at the scene's size, sampling and shading.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct F64Reference {
    /// The image, relative to results.json.
    pub image: String,
    /// Wall time of the one render (hierarchy build and tracing), seconds.
    pub seconds: f64,
}

/// Ray counts a reference publishes for a scene (the SPD's `Readme.txt` table).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PublishedRays {
    /// Where the figures come from.
    pub source: String,
    pub primary: u64,
    pub primary_hit: u64,
    pub reflection: u64,
    pub refraction: u64,
    pub shadow: u64,
    /// The agreement the source expects of a classical tracer (0.10: within 10 %).
    pub tolerance: f64,
}

/// Bytes a scene's render holds: the parsed scene, the largest acceleration structure
/// any variant built, and the framebuffer (12 bytes a pixel); their sum is the peak the
/// tracer's own data reach (the process adds its code and the run's images).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MemoryUse {
    pub scene_bytes: u64,
    /// The largest acceleration structure among the variants (0: brute force only).
    pub accelerator_bytes: u64,
    pub framebuffer_bytes: u64,
    /// scene + accelerator + framebuffer.
    pub peak_bytes: u64,
    /// The BVH's bytes per primitive, when a variant built one.
    pub bvh_bytes_per_primitive: Option<f64>,
}

/// A render of the scene by the f64 reference renderer (its own code: no line of the
/// tracer's renderer, intersectors or shading), at a smaller frame, timed on the same
/// threads and in the same rounds as the variants' renders: the same kind of work as
/// theirs, so load that slows memory-bound rendering slows it alike.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Yardstick {
    /// The frame it rendered (the scene's divided by [`Yardstick::DIVISOR`] per side).
    pub width: u32,
    pub height: u32,
    /// Median and interval of its tracing time, seconds.
    pub time: Estimate,
    /// Tracing seconds of each round.
    pub samples: Vec<f64>,
    /// Process CPU seconds of each round.
    pub cpu_samples: Vec<f64>,
}

impl Yardstick {
    /// The yardstick's frame is the scene's divided by this per side (a sixteenth of the
    /// pixels: the f64 renderer takes a few times bvh's time per pixel, so a round costs
    /// a fraction of one accelerated render more).
    pub const DIVISOR: u32 = 4;
}

/// A fixed amount of arithmetic (independent of the tracer's code), timed on the same
/// threads as the renders it was interleaved with.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Calibration {
    /// Median and interval, seconds.
    pub time: Estimate,
    /// Every timed run, seconds.
    pub samples: Vec<f64>,
    /// Process CPU seconds of every timed run (empty in older files).
    #[serde(default)]
    pub cpu_samples: Vec<f64>,
}

/// One variant on one scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct VariantResult {
    pub variant: VariantName,
    /// Tracing time (median and interval over the repeats), seconds; what it covers
    /// is [`SuiteInfo::timing`]'s `covers`.
    pub time: Estimate,
    /// Every timed repeat, seconds, in round order: sample j of every variant of the
    /// scene (and of its calibration kernel) was timed in round j.
    pub samples: Vec<f64>,
    /// Process CPU seconds (all threads) of each timed render, preprocessing included,
    /// in the same order: what the gate compares, as it does not grow while the machine
    /// runs other work (empty in older files).
    #[serde(default)]
    pub cpu_samples: Vec<f64>,
    /// Scene preparation and structure build (camera space, SIMD lanes, BVH) before
    /// tracing, seconds: the median over the repeats. `None` in files whose times
    /// include it (`/1`).
    pub preprocessing_seconds: Option<f64>,
    /// Baseline time / this time: the median of the per-round ratios, or with too few
    /// shared rounds (and in older files) the ratio of the medians
    /// ([`crate::change::Ratio`]); None when baseline did not run on the scene.
    pub speedup: Option<f64>,
    /// 95 % bootstrap interval of `speedup`; `None` in older files.
    #[serde(default)]
    pub speedup_interval: Option<[f64; 2]>,
    /// The speed-up's verdict against baseline (faster, slower, within noise) at the
    /// suite's `noise_threshold`; `None` for baseline itself and in older files.
    #[serde(default)]
    pub verdict: Option<Verdict>,
    /// Exact counts, flattened (`ops.dot`, `rays.primary`, …).
    pub counts: BTreeMap<String, u64>,
    /// The image, relative to results.json.
    pub image: Option<String>,
    /// Difference heat map against baseline, relative to results.json.
    pub heat_map: Option<String>,
    /// Image metrics against baseline (None for baseline itself).
    pub quality: Option<Quality>,
    /// Image metrics against the f64 reference's picture ([`SceneResult::f64_reference`]),
    /// baseline's own included: how far each picture is from the truth, not only from
    /// baseline's. `None` when the reference did not run, and in older files.
    #[serde(default)]
    pub vs_f64_reference: Option<Quality>,
    /// Gray histogram (256 bins) of the image; empty when there is no image.
    pub histogram: Vec<u64>,
    /// `accel.lanes_active / accel.lanes_issued` for the SIMD batches (`simd` only).
    #[serde(default)]
    pub lane_utilization: Option<f64>,
    /// The render as a point of the roofline model. `None` in older files.
    #[serde(default)]
    pub efficiency: Option<Efficiency>,
    /// Time and rays per second by ray kind. `None` in older files.
    #[serde(default)]
    pub ray_rates: Option<RayRates>,
    /// An outside tracer's definition and program (`None`: one of rtprof's variants).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outside: Option<crate::OutsideTracer>,
}

/// Image error against baseline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Quality {
    pub rms: f64,
    /// The thesis's band for `rms`.
    pub band: Band,
    /// dB; None when the images are identical (infinite).
    pub psnr: Option<f64>,
    pub ssim: f64,
    pub max_abs_diff: u32,
}

/// One function (or phase) of a flat profile.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct FlatRow {
    pub name: String,
    /// Share of the samples with this function running (self), percent.
    pub percent: f64,
    pub self_seconds: f64,
    /// Self plus everything it calls.
    pub total_seconds: f64,
    /// Exact calls from the counters per render, when counted (`/2`: over all renders).
    pub calls: Option<u64>,
    /// Share of the samples with this function anywhere on the stack, percent.
    #[serde(default)]
    pub inclusive_percent: Option<f64>,
    /// 95 % intervals of the self and inclusive shares, percent (binomial, Wilson).
    #[serde(default)]
    pub self_interval: Option<[f64; 2]>,
    #[serde(default)]
    pub inclusive_interval: Option<[f64; 2]>,
    /// Too few samples to tell the share from zero.
    #[serde(default)]
    pub noise: bool,
    /// Only ever the outermost frame of its stacks (a thread's root: its whole work).
    #[serde(default)]
    pub root: bool,
}

/// One row of the Amdahl table: the whole run's speed-up if one function became
/// faster, alone (self time) and with everything it calls (inclusive time).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AmdahlRow {
    pub name: String,
    /// Fraction of the time in this function itself.
    pub fraction: f64,
    /// Whole-program speed-up if it became 2x, 10x and infinitely faster.
    pub speedup_2x: f64,
    pub speedup_10x: f64,
    pub speedup_limit: f64,
    /// The same for the function with everything it calls (`/2` files: none).
    #[serde(default)]
    pub inclusive: Option<AmdahlFigures>,
}

/// A fraction of the time and the speed-ups if it ran 2x, 10x, infinitely faster.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AmdahlFigures {
    pub fraction: f64,
    pub speedup_2x: f64,
    pub speedup_10x: f64,
    pub speedup_limit: f64,
}

/// What a profile's function identities are.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ProfileView {
    /// The tracer's own record of the phase each thread was in (camera ray, traversal,
    /// sphere test, …), read at each sample: independent of inlining.
    Phases,
    /// Native symbols from the binary's debug info: what the compiler made of the code.
    #[default]
    Native,
}

/// One view of a profile: its rows and files.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ProfileViewFiles {
    pub view: ProfileView,
    pub flat: Vec<FlatRow>,
    pub flat_text: String,
    pub callgraph_text: String,
    pub flame_svg: String,
}

/// A sampled profile of one scene and variant.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Profile {
    pub variant: VariantName,
    pub samples: u64,
    pub seconds_per_sample: f64,
    /// Renders sampled (calls are per render); `None` in `/2` files, whose calls are
    /// totals over all sampled renders.
    #[serde(default)]
    pub renders: Option<u64>,
    /// Samples the asked rate would have given in the sampled CPU time.
    #[serde(default)]
    pub samples_asked: Option<u64>,
    /// The timer that sent the sampling signals ("perf cpu-clock": per-thread perf
    /// events; "setitimer": the kernel's tick); `None` in files from before it was
    /// recorded (setitimer then).
    #[serde(default)]
    pub timer: Option<Timer>,
    /// CPU seconds sampled (all threads).
    #[serde(default)]
    pub cpu_seconds: Option<f64>,
    /// Exact counts of one render of the profiled frame, flattened (`ops.dot`,
    /// `rays.primary`, …): the calls of every operation, timed or not. Empty in older
    /// files.
    #[serde(default)]
    pub counts: BTreeMap<String, u64>,
    /// The view of `flat`, the texts and the flamegraph (`/2` files: native).
    #[serde(default)]
    pub view: ProfileView,
    pub flat: Vec<FlatRow>,
    /// gprof-layout texts, relative to results.json.
    pub flat_text: String,
    pub callgraph_text: String,
    /// Flamegraph SVG, relative to results.json.
    pub flame_svg: String,
    pub amdahl: Vec<AmdahlRow>,
    /// The other view (native symbols beside the phases).
    #[serde(default)]
    pub second_view: Option<ProfileViewFiles>,
    /// Exports for other tools (pprof protobuf, speedscope JSON), relative paths.
    #[serde(default)]
    pub exports: Vec<String>,
}

impl Profile {
    /// The bottleneck a headline names: the row with the most self time (the work that
    /// costs by itself; a primitive test's self share is its inclusive share), leaving
    /// out the whole-run frames (at least
    /// [`analysis::profile::flat::WHOLE_RUN_PERCENT`] of the samples, and threads'
    /// roots: the render's outermost frames) and noise; the rule of
    /// [`analysis::profile::flat::bottleneck`]. `None` for profiles without inclusive
    /// shares (`/2` files), where whole-run frames cannot be told.
    pub fn bottleneck(&self) -> Option<&FlatRow> {
        self.candidates().max_by(|a, b| {
            let inclusive = |r: &FlatRow| r.inclusive_percent.unwrap_or(0.0);
            a.percent
                .total_cmp(&b.percent)
                .then_with(|| inclusive(a).total_cmp(&inclusive(b)))
                .then_with(|| b.name.cmp(&a.name))
        })
    }

    /// The row with the largest inclusive share short of the whole run: a parent's share
    /// holds the work it calls (the rule of [`analysis::profile::flat::largest_inclusive`]).
    pub fn largest_inclusive(&self) -> Option<&FlatRow> {
        self.candidates()
            .filter_map(|r| Some((r, r.inclusive_percent?)))
            .max_by(|a, b| a.1.total_cmp(&b.1).then_with(|| b.0.name.cmp(&a.0.name)))
            .map(|(r, _)| r)
    }

    /// Rows that may headline: with an inclusive share short of the whole run, not noise,
    /// not a thread's root.
    fn candidates(&self) -> impl Iterator<Item = &FlatRow> {
        self.flat.iter().filter(|r| {
            r.inclusive_percent
                .is_some_and(|p| p < analysis::profile::flat::WHOLE_RUN_PERCENT)
                && !r.noise
                && !r.root
        })
    }
}

/// The profile section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ProfileResult {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub baseline: Profile,
    pub best: Option<Profile>,
    /// Differential flamegraph baseline → best (what grew), relative to results.json.
    pub diff_flame_svg: Option<String>,
    /// The same the other way (what shrank or vanished), on the baseline's frames.
    #[serde(default)]
    pub diff_shrunk_flame_svg: Option<String>,
}

/// The part of a suite run that failed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FailedPart {
    /// The scene as a whole (it could not be read, or its run stopped).
    Scene,
    /// One variant on the scene.
    Variant(VariantName),
    /// The hardware model and emulator on the scene.
    Hardware,
    /// The profile of the heaviest scene.
    Profile,
    /// The f64 reference's render of the scene.
    F64Reference,
}

impl std::fmt::Display for FailedPart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FailedPart::Scene => f.write_str("scene"),
            FailedPart::Variant(name) => write!(f, "{name}"),
            FailedPart::Hardware => f.write_str("hardware"),
            FailedPart::Profile => f.write_str("profile"),
            FailedPart::F64Reference => f.write_str("f64 reference"),
        }
    }
}

/// Something that failed; the run went on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Failure {
    /// The scene it happened on (for the profile: the scene profiled, when known).
    pub scene: Option<String>,
    pub part: FailedPart,
    pub message: String,
}

impl Failure {
    /// Where it failed, for a reader: `balls3 / bvh`, `balls3 / hardware`, `profile`.
    pub fn place(&self) -> String {
        match (&self.scene, &self.part) {
            (Some(scene), FailedPart::Scene) => scene.clone(),
            (Some(scene), part) => format!("{scene} / {part}"),
            (None, part) => part.to_string(),
        }
    }
}

/// One criterion benchmark's estimates (nanoseconds).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct CriterionEstimate {
    pub id: String,
    pub mean: Estimate,
    pub median: Estimate,
    /// When it was measured (the estimates file's time, RFC 3339 UTC).
    #[serde(default)]
    pub measured: Option<String>,
}

/// One benchmark's instruction count under valgrind (deterministic, unlike time).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
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
    /// The reference (baseline) result of a scene, if it ran.
    pub fn baseline<'a>(&self, scene: &'a SceneResult) -> Option<&'a VariantResult> {
        scene.variants.iter().find(|v| v.variant.is_reference())
    }
}
