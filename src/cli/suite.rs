//! `rtprof suite`: the main job. Renders every scene of a suite with every variant
//! (timing repeats, exact counts, images and their error against baseline), runs the
//! hardware model and emulator where the scene allows, profiles the heaviest scene,
//! and writes `results.json`, `report.html` and `report.pdf`. With `--baseline` it
//! then gates the run against an earlier one.
//!
//! Stages are joined by plain data (the `results` crate): measurement here, analysis in
//! `analysis`, reporting in `reports`. A failing scene is recorded and skipped; the
//! rest of the run stands.

use super::profile::Job;
use super::scene_args::thread_pool;
use analysis::{
    Band, RgbImage, compare, difference_heat_map, gray_histogram, median_with_bootstrap,
};
use anyhow::{Context, Result, bail};
use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::device::{demand, fit, largest_units};
use hwmodel::hw_scene::HwScene;
use hwmodel::library::Library;
use hwmodel::pipeline::frame_timing;
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use reports::slug;
use results::{
    AmdahlRow, Build, DeviceUse, Estimate, FailedPart, Failure, FlatRow, HardwareResult, HwRow,
    Machine, Profile, ProfileResult, Quality, Results, SCHEMA, SceneFamily, SceneHardware,
    SceneResult, SuiteInfo, TimeCovers, TimingPolicy, VariantName, VariantResult,
};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tracer::image_io::{encode_png_rgb8, write_atomically};
use tracer::{
    Count, NoCount, RenderOptions, Sampling, Scene, ShadingMode, VariantSet, parse_nff,
    render_variant,
};

/// The default suite, embedded.
const DEFAULT_SUITE: &str = include_str!("../../scenes/suite.toml");

#[derive(clap::Args, Debug)]
pub struct SuiteArgs {
    /// Suite definition (TOML; default: the embedded suite, scenes/suite.toml).
    suite: Option<PathBuf>,
    /// Output directory.
    #[arg(short, long, value_name = "DIR", default_value = "rtprof-suite")]
    output: PathBuf,
    /// The CI-sized run: smaller images, fewer scenes and repeats.
    #[arg(long)]
    quick: bool,
    /// Compare with an earlier results.json: exit 1 on a significant slow-down or any
    /// changed count.
    #[arg(long, value_name = "RESULTS.json")]
    baseline: Option<PathBuf>,
    /// Slow-down the gate tolerates beyond the intervals, in percent.
    #[arg(long, value_name = "PCT", default_value_t = 5.0,
          value_parser = parse_threshold)]
    threshold: f64,
    /// Add every .nff file of this directory (e.g. ../shared/spd).
    #[arg(long, value_name = "DIR")]
    scenes: Option<PathBuf>,
    /// Worker threads for the renders (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    threads: Option<u16>,
    #[command(flatten)]
    benchmarks: super::report::BenchmarkDirs,
}

pub(super) fn parse_threshold(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(p) if p.is_finite() && (0.0..=1000.0).contains(&p) => Ok(p),
        _ => Err(format!("'{text}' is not a percentage between 0 and 1000")),
    }
}

/// The most timed renders of one scene and variant, whatever `min_seconds` asks.
const MAX_REPEATS: usize = 100;
/// The bootstrap of every time's interval: resamples, confidence and seed.
const BOOTSTRAP_RESAMPLES: usize = 2000;
const CONFIDENCE: f64 = 0.95;
const BOOTSTRAP_SEED: u64 = 0x5eed;

fn default_profile_seconds() -> f64 {
    super::profile::MIN_SAMPLED.as_secs_f64()
}

/// A suite definition (scenes/suite.toml).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuiteDef {
    pub name: String,
    pub size: [u32; 2],
    pub repeats: u32,
    /// Keep repeating a timed render (beyond `repeats`, up to [`MAX_REPEATS`]) until
    /// this much time is measured: a 10 ms render needs more than three samples.
    #[serde(default)]
    pub min_seconds: f64,
    pub variants: Vec<String>,
    pub scenes: Vec<String>,
    pub extra_size: [u32; 2],
    pub profile_size: [u32; 2],
    pub profile_frequency: i32,
    /// Least sampled seconds per profile (a faster render is repeated).
    #[serde(default = "default_profile_seconds")]
    pub profile_seconds: f64,
    pub hardware_repeats: u32,
    pub quick: Option<QuickDef>,
}

/// Overrides for `--quick`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuickDef {
    pub size: Option<[u32; 2]>,
    pub repeats: Option<u32>,
    pub min_seconds: Option<f64>,
    pub variants: Option<Vec<String>>,
    pub scenes: Option<Vec<String>>,
    pub extra_size: Option<[u32; 2]>,
    pub profile_size: Option<[u32; 2]>,
    pub profile_seconds: Option<f64>,
    pub hardware_repeats: Option<u32>,
}

impl SuiteDef {
    /// Parses a definition and checks it, with and without its `[quick]` overrides
    /// (`file` names it in errors).
    pub fn parse(text: &str, file: &str) -> Result<Self> {
        let def: SuiteDef = toml::from_str(text).map_err(|e| anyhow::anyhow!("{file}: {e}"))?;
        def.check(file)?;
        def.clone()
            .quick()
            .check(file)
            .with_context(|| format!("{file}: in [quick]"))?;
        Ok(def)
    }

    fn check(&self, file: &str) -> Result<()> {
        if self.repeats == 0 || self.repeats > 1000 {
            bail!("{file}: repeats must be 1 to 1000");
        }
        if !(0.0..=60.0).contains(&self.min_seconds) {
            bail!("{file}: min_seconds must be 0 to 60");
        }
        if !(0.0..=600.0).contains(&self.profile_seconds) {
            bail!("{file}: profile_seconds must be 0 to 600");
        }
        if self.variants.first().map(String::as_str) != Some("baseline") {
            bail!("{file}: the first variant must be baseline (the reference)");
        }
        for v in &self.variants {
            VariantSet::parse(v).with_context(|| format!("{file}: variant '{v}'"))?;
        }
        for size in [self.size, self.extra_size, self.profile_size] {
            tracer::Limits::default()
                .check_size(u64::from(size[0]), u64::from(size[1]))
                .map_err(|e| anyhow::anyhow!("{file}: {e}"))?;
        }
        Ok(())
    }

    /// The definition with the `[quick]` overrides applied.
    pub fn quick(mut self) -> Self {
        if let Some(q) = self.quick.take() {
            self.size = q.size.unwrap_or(self.size);
            self.repeats = q.repeats.unwrap_or(self.repeats);
            self.min_seconds = q.min_seconds.unwrap_or(self.min_seconds);
            self.variants = q.variants.unwrap_or(self.variants);
            self.scenes = q.scenes.unwrap_or(self.scenes);
            self.extra_size = q.extra_size.unwrap_or(self.extra_size);
            self.profile_size = q.profile_size.unwrap_or(self.profile_size);
            self.profile_seconds = q.profile_seconds.unwrap_or(self.profile_seconds);
            self.hardware_repeats = q.hardware_repeats.unwrap_or(self.hardware_repeats);
        }
        self
    }
}

/// A scene to run: its name, where it came from, its text.
struct SceneSpec {
    name: String,
    source: String,
    family: SceneFamily,
    text: String,
    size: (u32, u32),
}

fn resolve_scene(entry: &str, size: (u32, u32), base: &Path) -> Result<SceneSpec> {
    if let Some((kind, param)) = entry.split_once(':') {
        let n: u32 = param
            .parse()
            .with_context(|| format!("scene '{entry}': '{param}' is not a number"))?;
        let text = match kind {
            "sphereflake" => tracer::generators::sphereflake(n)?,
            "lattice" => tracer::generators::lattice(n)?,
            _ => bail!("scene '{entry}': unknown generator '{kind}' (sphereflake, lattice)"),
        };
        return Ok(SceneSpec {
            name: format!("{kind}{n}"),
            source: "generated".into(),
            family: SceneFamily::Generated,
            text,
            size,
        });
    }
    if let Some(b) = tracer::builtin_scenes::find(entry) {
        return Ok(SceneSpec {
            name: b.name.to_string(),
            source: "builtin".into(),
            family: SceneFamily::of_builtin(b.name),
            text: b.text.to_string(),
            size,
        });
    }
    let path = base.join(entry);
    let text = std::fs::read_to_string(&path).with_context(|| {
        format!(
            "scene '{entry}': not a built-in name and cannot read {}",
            path.display()
        )
    })?;
    Ok(SceneSpec {
        name: path
            .file_stem()
            .map_or_else(|| entry.to_string(), |s| s.to_string_lossy().into_owned()),
        source: path.display().to_string(),
        family: SceneFamily::Other,
        text,
        size,
    })
}

fn extra_scenes(dir: &Path, size: (u32, u32)) -> Result<Vec<SceneSpec>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("--scenes {}: cannot read the directory", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("nff")))
        .collect();
    files.sort();
    if files.is_empty() {
        bail!("--scenes {}: no .nff files there", dir.display());
    }
    let spd = dir.file_name().is_some_and(|n| n == "spd");
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            Ok(SceneSpec {
                name: path
                    .file_stem()
                    .map_or_else(String::new, |s| s.to_string_lossy().into_owned()),
                source: path.display().to_string(),
                family: if spd {
                    SceneFamily::Spd
                } else {
                    SceneFamily::Other
                },
                text,
                size,
            })
        })
        .collect()
}

/// Flattens the counter JSON to `"ops.dot": n` pairs.
fn flatten_counts(counts: &tracer::Counts) -> BTreeMap<String, u64> {
    fn walk(prefix: &str, v: &serde_json::Value, out: &mut BTreeMap<String, u64>) {
        match v {
            serde_json::Value::Object(map) => {
                for (k, v) in map {
                    let key = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    walk(&key, v, out);
                }
            }
            serde_json::Value::Number(n) => {
                if let Some(n) = n.as_u64() {
                    out.insert(prefix.to_string(), n);
                }
            }
            _ => {}
        }
    }
    let mut out = BTreeMap::new();
    if let Ok(v) = serde_json::to_value(counts) {
        walk("", &v, &mut out);
    }
    out
}

fn estimate(samples: &[f64]) -> Result<Estimate> {
    Ok(median_with_bootstrap(
        samples,
        BOOTSTRAP_RESAMPLES,
        CONFIDENCE,
        BOOTSTRAP_SEED,
    )?)
}

/// The timing policy the suite's times follow, as results.json records it.
fn timing_policy(def: &SuiteDef) -> TimingPolicy {
    TimingPolicy {
        min_repeats: def.repeats,
        min_seconds: def.min_seconds,
        max_repeats: MAX_REPEATS as u32,
        bootstrap_resamples: BOOTSTRAP_RESAMPLES as u32,
        confidence: CONFIDENCE,
        seed: BOOTSTRAP_SEED,
        covers: TimeCovers::Tracing,
    }
}

/// Seconds of one timed render's two phases.
struct Phases {
    preprocessing: f64,
    tracing: f64,
}

impl<C> From<&tracer::VariantRender<C>> for Phases {
    fn from(r: &tracer::VariantRender<C>) -> Self {
        Phases {
            preprocessing: r.preprocessing.as_secs_f64(),
            tracing: r.tracing.as_secs_f64(),
        }
    }
}

/// The timed repeats of one job: tracing and preprocessing seconds of each.
struct Timed {
    tracing: Vec<f64>,
    preprocessing: Vec<f64>,
}

/// The suite's staging directory, `<output>/.rtprof-suite-<pid>.partial`: removed
/// with whatever is left in it when dropped (after an error, a panic or Ctrl-C).
struct Staging {
    dir: PathBuf,
}

impl Staging {
    fn create(output: &Path) -> Result<Self> {
        let dir = output.join(format!(".rtprof-suite-{}.partial", std::process::id()));
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("cannot create {}", dir.display()))?;
        Ok(Staging { dir })
    }

    /// Moves every staged file to the same place under `output` (one rename each,
    /// replacing the previous run's file).
    fn publish(&self, output: &Path) -> Result<()> {
        let mut pending = vec![self.dir.clone()];
        while let Some(dir) = pending.pop() {
            let entries = std::fs::read_dir(&dir)
                .with_context(|| format!("cannot read {}", dir.display()))?;
            for entry in entries {
                let path = entry
                    .with_context(|| format!("cannot read {}", dir.display()))?
                    .path();
                if path.is_dir() {
                    pending.push(path);
                    continue;
                }
                let rel = path.strip_prefix(&self.dir).unwrap_or(&path);
                let target = output.join(rel);
                if let Some(parent) = target.parent() {
                    std::fs::create_dir_all(parent)
                        .with_context(|| format!("cannot create {}", parent.display()))?;
                }
                std::fs::rename(&path, &target)
                    .with_context(|| format!("cannot move {} into place", target.display()))?;
            }
        }
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        // Best effort: a leftover directory is named as partial and harmless.
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The error for a suite stopped by Ctrl-C after `done` of `total` scenes.
fn interrupted(output: &Path, done: usize, total: usize) -> anyhow::Error {
    let previous = if output.join("report.html").is_file() {
        format!(
            "the previous results and reports in {} are intact",
            output.display()
        )
    } else {
        format!("nothing was written to {}", output.display())
    };
    super::Interrupted(format!(
        "interrupted after {done} of {total} scenes; this run's outputs were discarded and {previous}"
    ))
    .into()
}

/// Writes `bytes` at `dir/rel` (atomically) and returns `rel`.
fn save(dir: &Path, rel: &str, bytes: &[u8]) -> Result<String> {
    let path = dir.join(rel);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("cannot create {}", parent.display()))?;
    }
    write_atomically(&path, bytes).with_context(|| format!("cannot write {}", path.display()))?;
    Ok(rel.to_string())
}

fn save_png(dir: &Path, rel: &str, img: &RgbImage) -> Result<String> {
    let bytes = encode_png_rgb8(img.width, img.height, &img.data).map_err(anyhow::Error::msg)?;
    save(dir, rel, &bytes)
}

struct Runner<'a> {
    def: &'a SuiteDef,
    out: &'a Path,
    pool: rayon::ThreadPool,
    one_thread: rayon::ThreadPool,
    bars: MultiProgress,
}

impl Runner<'_> {
    fn bar(&self, len: u64, what: &str) -> ProgressBar {
        let bar = self.bars.add(ProgressBar::new(len));
        bar.set_style(
            ProgressStyle::with_template("{prefix:>10} [{bar:30}] {pos}/{len} {msg} ({elapsed})")
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> "),
        );
        bar.set_prefix(what.to_string());
        bar
    }

    /// Every variant on one scene.
    fn run_scene(
        &self,
        spec: &SceneSpec,
        bar: &ProgressBar,
        failures: &mut Vec<Failure>,
    ) -> Result<SceneResult> {
        let scene = parse_nff(&spec.text, &spec.source)?;
        let (width, height) = spec.size;
        let options = RenderOptions::new(width, height, Sampling::PixelCenters, ShadingMode::Color);
        let mut variants: Vec<VariantResult> = Vec::new();
        let mut baseline_image: Option<RgbImage> = None;
        let mut baseline_median: Option<f64> = None;
        for name in &self.def.variants {
            bar.set_message(format!("{} {name}", spec.name));
            match self.run_variant(spec, &scene, &options, name, baseline_image.as_ref()) {
                Ok((mut v, image)) => {
                    if v.variant.is_reference() {
                        baseline_median = Some(v.time.median);
                        baseline_image = Some(image);
                    }
                    v.speedup = baseline_median
                        .map(|b| b / v.time.median)
                        .filter(|s| s.is_finite());
                    variants.push(v);
                }
                Err(e) => failures.push(Failure {
                    scene: Some(spec.name.clone()),
                    // The suite's variants were checked when it was read.
                    part: VariantName::parse(name).map_or(FailedPart::Scene, FailedPart::Variant),
                    message: format!("{e:#}"),
                }),
            }
            bar.inc(1);
        }
        let hardware = match HwScene::from_scene(&scene) {
            Ok(hw) => match self.run_hardware(spec, &scene, &hw) {
                Ok(h) => Some(h),
                Err(e) => {
                    failures.push(Failure {
                        scene: Some(spec.name.clone()),
                        part: FailedPart::Hardware,
                        message: format!("{e:#}"),
                    });
                    None
                }
            },
            Err(_) => None, // polygons etc.: the hardware cannot render it; not a failure
        };
        let mut primitive_counts = BTreeMap::new();
        for (kind, n) in [
            ("spheres", scene.spheres.len()),
            ("cylinders", scene.cylinders.len()),
            ("cones", scene.cones.len()),
            ("polygons", scene.polygons.len()),
            ("patches", scene.patches.len()),
        ] {
            primitive_counts.insert(kind.to_string(), n as u64);
        }
        Ok(SceneResult {
            name: spec.name.clone(),
            source: spec.source.clone(),
            family: spec.family,
            primitives: scene.primitive_count() as u64,
            primitive_counts,
            width,
            height,
            spd: false,
            variants,
            hardware,
        })
    }

    /// The phases of `repeats` runs of `render`, more while less than `min_seconds` of
    /// tracing is measured (at most [`MAX_REPEATS`]).
    fn timed_n(&self, repeats: u32, mut render: impl FnMut() -> Result<Phases>) -> Result<Timed> {
        let mut timed = Timed {
            tracing: Vec::with_capacity(repeats as usize),
            preprocessing: Vec::with_capacity(repeats as usize),
        };
        while timed.tracing.len() < repeats as usize
            || (timed.tracing.iter().sum::<f64>() < self.def.min_seconds
                && timed.tracing.len() < MAX_REPEATS)
        {
            if super::interrupt::requested() {
                anyhow::bail!("interrupted");
            }
            let phases = render()?;
            timed.tracing.push(phases.tracing);
            timed.preprocessing.push(phases.preprocessing);
        }
        Ok(timed)
    }

    /// [`Self::timed_n`] with the suite's `repeats`.
    fn timed(&self, render: impl FnMut() -> Result<Phases>) -> Result<Timed> {
        self.timed_n(self.def.repeats, render)
    }

    fn run_variant(
        &self,
        spec: &SceneSpec,
        scene: &Scene,
        options: &RenderOptions,
        name: &str,
        baseline: Option<&RgbImage>,
    ) -> Result<(VariantResult, RgbImage)> {
        let set = VariantSet::parse(name)?;
        // The counted render first: it also warms caches and the thread pool up for
        // the timed ones.
        let counted = self
            .pool
            .install(|| render_variant::<Count>(scene, options, &set, &|_| {}))?;
        let mut frame = None;
        let timed = self.timed(|| {
            let out = self
                .pool
                .install(|| render_variant::<NoCount>(scene, options, &set, &|_| {}))?;
            let phases = Phases::from(&out);
            frame = Some(out.rendered.frame);
            Ok(phases)
        })?;
        let counts = counted
            .rendered
            .counts()
            .map(|c| flatten_counts(&c))
            .unwrap_or_default();
        let frame = frame.context("no render ran")?;
        let image = RgbImage {
            width: frame.width,
            height: frame.height,
            data: frame.to_rgb8(),
        };
        let stem = format!("images/{}-{}", slug(&spec.name), slug(name));
        let image_rel = save_png(self.out, &format!("{stem}.png"), &image)?;
        let variant = VariantName::of(&set);
        let (quality, heat_map) = match baseline {
            Some(base) if !variant.is_reference() => {
                let c = compare(base, &image)?;
                let heat = difference_heat_map(base, &image)?;
                let heat_rel = save_png(self.out, &format!("{stem}-diff.png"), &heat)?;
                (
                    Some(Quality {
                        rms: c.rms,
                        band: c.band,
                        psnr: c.psnr.is_finite().then_some(c.psnr),
                        ssim: c.ssim,
                        max_abs_diff: u32::from(c.max_abs_diff),
                    }),
                    Some(heat_rel),
                )
            }
            _ => (None, None),
        };
        let histogram = gray_histogram(&image).to_vec();
        Ok((
            VariantResult {
                variant,
                time: estimate(&timed.tracing)?,
                samples: timed.tracing,
                preprocessing_seconds: analysis::median(&timed.preprocessing),
                speedup: None,
                counts,
                image: Some(image_rel),
                heat_map,
                quality,
                histogram,
            },
            image,
        ))
    }

    /// Model time, emulator image, and the software on the same job.
    fn run_hardware(&self, spec: &SceneSpec, scene: &Scene, hw: &HwScene) -> Result<SceneHardware> {
        let (width, height) = spec.size;
        let lib = Library::cyclone_iv_e();
        let pipeline = Pipeline::build(&lib, &Design::thesis());
        let n = hw.primitive_count() as u64;
        let timing = frame_timing(&pipeline, n, width, height, 50e6);
        let device = lib.devices[0].clone();
        let fits = fit(&lib, &device, demand(&lib, &pipeline, n, width, height)).fits;
        let emulated = hwmodel::emulator::render(hw, width, height);
        let emu_img = RgbImage {
            width,
            height,
            data: emulated.to_rgb8(),
        };
        let options = RenderOptions::new(
            width,
            height,
            Sampling::PixelCenters,
            ShadingMode::DiffuseOnly,
        );
        let set = VariantSet::parse("baseline")?;
        let mut frame = None;
        let timed = self.timed_n(self.def.hardware_repeats.max(1), || {
            let out = self
                .one_thread
                .install(|| render_variant::<NoCount>(scene, &options, &set, &|_| {}))?;
            let phases = Phases::from(&out);
            frame = Some(out.rendered.frame);
            Ok(phases)
        })?;
        let frame = frame.context("no software render ran")?;
        let sw_img = RgbImage {
            width: frame.width,
            height: frame.height,
            data: frame.to_rgb8(),
        };
        let c = compare(&sw_img, &emu_img)?;
        let stem = format!("images/{}", slug(&spec.name));
        let software_seconds = estimate(&timed.tracing)?;
        Ok(SceneHardware {
            primitives: n,
            cycles: timing.cycles,
            seconds: timing.seconds,
            fits,
            speedup: software_seconds.median / timing.seconds,
            software_seconds,
            emulator_rms: c.rms,
            emulator_band: Band::of(c.rms),
            emulator_image: Some(save_png(self.out, &format!("{stem}-hw.png"), &emu_img)?),
            software_image: Some(save_png(
                self.out,
                &format!("{stem}-sw-diffuse.png"),
                &sw_img,
            )?),
        })
    }

    /// Profiles the heaviest scene, baseline and the best variant whose picture stays
    /// visually identical.
    fn run_profile(
        &self,
        specs: &[SceneSpec],
        results: &[SceneResult],
    ) -> Result<Option<ProfileResult>> {
        let Some(heaviest) = results
            .iter()
            .filter_map(|s| Some((s, s.variants.iter().find(|v| v.variant.is_reference())?)))
            .max_by(|a, b| a.1.time.median.total_cmp(&b.1.time.median))
            .map(|(s, _)| s)
        else {
            return Ok(None);
        };
        let best = heaviest
            .variants
            .iter()
            .filter(|v| !v.variant.is_reference())
            .filter(|v| {
                v.quality
                    .as_ref()
                    .is_some_and(|q| q.band == Band::VisuallyIdentical)
            })
            .max_by(|a, b| {
                let s = |v: &VariantResult| v.speedup.unwrap_or(f64::NEG_INFINITY);
                s(a).total_cmp(&s(b))
            })
            .map(|v| v.variant.clone());
        let Some(spec) = specs.iter().find(|s| s.name == heaviest.name) else {
            return Ok(None);
        };
        let scene = parse_nff(&spec.text, &spec.source)?;
        let [w, h] = self.def.profile_size;
        let path = PathBuf::from(&spec.source);
        let job = Job {
            scene: &scene,
            options: RenderOptions::new(w, h, Sampling::PixelCenters, ShadingMode::Color),
            pool: thread_pool(None)?,
            frequency: self.def.profile_frequency,
            path: &path,
            min_sampled: std::time::Duration::from_secs_f64(self.def.profile_seconds),
        };
        let dir = "profile";
        let base = job.profile("baseline")?;
        let title = format!("{} ({w}x{h}, baseline)", spec.name);
        let baseline = self.save_profile(dir, &base, &title)?;
        let (best_profile, diff) = match &best {
            Some(name) => {
                let p = job.profile(name)?;
                let title = format!("{} ({w}x{h}, {name})", spec.name);
                let saved = self.save_profile(dir, &p, &title)?;
                let diff_title =
                    format!("{}: baseline → {name} (red grew, blue shrank)", spec.name);
                let svg = analysis::profile::folded::differential_svg(
                    &base.folded,
                    &p.folded,
                    &diff_title,
                )?;
                let rel = save(self.out, &format!("{dir}/flame-diff.svg"), svg.as_bytes())?;
                (Some(saved), Some(rel))
            }
            None => (None, None),
        };
        Ok(Some(ProfileResult {
            scene: spec.name.clone(),
            width: w,
            height: h,
            baseline,
            best: best_profile,
            diff_flame_svg: diff,
        }))
    }

    fn save_profile(
        &self,
        dir: &str,
        p: &super::profile::VariantProfile,
        title: &str,
    ) -> Result<Profile> {
        let v = slug(&p.variant);
        let flat_text = save(
            self.out,
            &format!("{dir}/flat-{v}.txt"),
            p.flat_text.as_bytes(),
        )?;
        let callgraph_text = save(
            self.out,
            &format!("{dir}/callgraph-{v}.txt"),
            p.call_graph_text.as_bytes(),
        )?;
        save(
            self.out,
            &format!("{dir}/folded-{v}.txt"),
            p.folded.as_bytes(),
        )?;
        let svg = analysis::profile::folded::flamegraph_svg(&p.folded, title)?;
        let flame_svg = save(self.out, &format!("{dir}/flame-{v}.svg"), svg.as_bytes())?;
        Ok(Profile {
            variant: VariantName::parse(&p.variant)?,
            samples: p.samples,
            seconds_per_sample: p.seconds_per_sample,
            flat: p
                .flat
                .rows
                .iter()
                .map(|r| FlatRow {
                    name: r.name.clone(),
                    percent: r.percent,
                    self_seconds: r.self_seconds,
                    total_seconds: r.self_seconds + r.children_seconds,
                    calls: r.calls,
                })
                .collect(),
            flat_text,
            callgraph_text,
            flame_svg,
            amdahl: p
                .amdahl
                .iter()
                .map(|a| AmdahlRow {
                    name: a.name.clone(),
                    fraction: a.fraction,
                    speedup_2x: a.speedup_2x,
                    speedup_10x: a.speedup_10x,
                    speedup_limit: a.speedup_limit,
                })
                .collect(),
        })
    }
}

/// Tables 7 and 8 and the thesis design's fit on every device (7 primitives, 640x480).
fn hardware_tables() -> HardwareResult {
    let lib = Library::cyclone_iv_e();
    let t = hwmodel::table::tables(&lib, &Design::thesis());
    let mut devices = Vec::new();
    for family in Library::embedded() {
        let pipeline = Pipeline::build(&family, &Design::thesis());
        let d = demand(&family, &pipeline, 7, 640, 480);
        for device in &family.devices {
            let f = fit(&family, device, d);
            devices.push(DeviceUse {
                device: device.name.clone(),
                validated: f.validated,
                le: f.used.le,
                le_capacity: device.le,
                mult: f.used.mult,
                mult_capacity: device.mult,
                soft_mult_elements: f.soft_mult_elements,
                mem_bits: f.used.mem_bits,
                mem_capacity: device.mem_bits,
                plls: f.plls,
                pll_capacity: device.plls,
                fits: f.fits,
                largest_units: largest_units(&family, device, &Design::thesis(), 7, 640, 480),
            });
        }
    }
    HardwareResult {
        family: lib.family.clone(),
        ops: t.ops.iter().map(HwRow::from_model_row).collect(),
        blocks: t.blocks.iter().map(HwRow::from_model_row).collect(),
        devices,
    }
}

fn first_line(path: &str, prefix: &str) -> Option<String> {
    std::fs::read_to_string(path).ok()?.lines().find_map(|l| {
        l.strip_prefix(prefix)
            .map(|rest| rest.trim_start_matches([' ', '\t', ':']).trim().to_string())
    })
}

fn machine() -> Machine {
    let read = |p: &str| {
        std::fs::read_to_string(p)
            .ok()
            .map(|s| s.trim().to_string())
    };
    Machine {
        cpu_model: first_line("/proc/cpuinfo", "model name").unwrap_or_else(|| "unknown".into()),
        cores: std::thread::available_parallelism().map_or(1, |n| n.get() as u32),
        os: match (
            read("/proc/sys/kernel/ostype"),
            read("/proc/sys/kernel/osrelease"),
        ) {
            (Some(a), Some(b)) => format!("{a} {b}"),
            _ => std::env::consts::OS.to_string(),
        },
        hostname: read("/proc/sys/kernel/hostname").unwrap_or_else(|| "unknown".into()),
    }
}

fn build_info() -> Build {
    Build {
        rtprof_version: env!("CARGO_PKG_VERSION").to_string(),
        rustc: env!("RTPROF_RUSTC").to_string(),
        git_commit: env!("RTPROF_GIT_COMMIT").to_string(),
        profile: if cfg!(debug_assertions) {
            "debug"
        } else {
            "release"
        }
        .to_string(),
    }
}

/// The command line that reproduces this run.
fn command_line() -> String {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .map(|a| {
            if a.chars()
                .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+".contains(c))
            {
                a
            } else {
                format!("'{}'", a.replace('\'', r"'\''"))
            }
        })
        .collect();
    format!("rtprof {}", args.join(" "))
}

pub fn run(args: &SuiteArgs) -> Result<()> {
    let started = Instant::now();
    let (text, file) = match &args.suite {
        Some(path) => (
            std::fs::read_to_string(path)
                .with_context(|| format!("cannot read suite {}", path.display()))?,
            path.display().to_string(),
        ),
        None => (
            DEFAULT_SUITE.to_string(),
            "suite.toml (embedded)".to_string(),
        ),
    };
    let mut def = SuiteDef::parse(&text, &file)?;
    if args.quick {
        def = def.quick();
    }
    // Read the old results first: a bad --baseline should fail before the work.
    let old = match &args.baseline {
        Some(path) => Some(Results::read_file(path)?),
        None => None,
    };
    let base_dir = args
        .suite
        .as_ref()
        .and_then(|p| p.parent().map(Path::to_path_buf))
        .unwrap_or_default();
    let size = (def.size[0], def.size[1]);
    let mut specs: Vec<SceneSpec> = def
        .scenes
        .iter()
        .map(|s| resolve_scene(s, size, &base_dir))
        .collect::<Result<_>>()?;
    if let Some(dir) = &args.scenes {
        specs.extend(extra_scenes(dir, (def.extra_size[0], def.extra_size[1]))?);
    }
    std::fs::create_dir_all(&args.output)
        .with_context(|| format!("cannot create {}", args.output.display()))?;
    // Everything is written to a staging directory inside the output and moved into
    // place at the end: an interrupted or failed run leaves the previous one whole.
    let staging = Staging::create(&args.output)?;
    super::interrupt::install();

    let runner = Runner {
        def: &def,
        out: &staging.dir,
        pool: thread_pool(args.threads)?,
        one_thread: thread_pool(Some(1))?,
        bars: MultiProgress::new(),
    };
    let threads = runner.pool.current_num_threads() as u32;
    let created = results::rfc3339_utc(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs()),
    );
    let bar = runner.bar((specs.len() * def.variants.len()) as u64, "scenes");
    let mut failures = Vec::new();
    let mut scenes = Vec::new();
    for (done, spec) in specs.iter().enumerate() {
        if super::interrupt::requested() {
            bar.finish_and_clear();
            return Err(interrupted(&args.output, done, specs.len()));
        }
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let mut local = Vec::new();
            let r = runner.run_scene(spec, &bar, &mut local);
            (r, local)
        }));
        match outcome {
            Ok((Ok(result), local)) => {
                failures.extend(local);
                scenes.push(result);
            }
            Ok((Err(e), local)) => {
                failures.extend(local);
                failures.push(Failure {
                    scene: Some(spec.name.clone()),
                    part: FailedPart::Scene,
                    message: format!("{e:#}"),
                });
            }
            Err(_) => failures.push(Failure {
                scene: Some(spec.name.clone()),
                part: FailedPart::Scene,
                message: "internal error (panic) while running this scene; please report it".into(),
            }),
        }
    }
    bar.finish_and_clear();

    let spinner = runner.bar(2, "profile");
    spinner.set_message("heaviest scene");
    let profile = match runner.run_profile(&specs, &scenes) {
        Ok(p) => p,
        Err(e) => {
            failures.push(Failure {
                scene: None,
                part: FailedPart::Profile,
                message: format!("{e:#}"),
            });
            None
        }
    };
    spinner.finish_and_clear();

    let mut results = Results {
        schema: SCHEMA.to_string(),
        created,
        command: command_line(),
        machine: machine(),
        build: build_info(),
        suite: SuiteInfo {
            name: def.name.clone(),
            quick: args.quick,
            threads,
            variants: def
                .variants
                .iter()
                .map(|v| VariantName::parse(v))
                .collect::<Result<_, _>>()?,
            timing: timing_policy(&def),
            wall_seconds: started.elapsed().as_secs_f64(),
        },
        scenes,
        profile,
        hardware: Some(hardware_tables()),
        failures,
        criterion: Vec::new(),
        instructions: Vec::new(),
    };
    args.benchmarks.add_to(&mut results, true)?;
    let json = serde_json::to_string_pretty(&results)?;
    save(&staging.dir, "results.json", json.as_bytes())?;
    super::report::write_reports(
        &[reports::Run {
            label: results.machine.hostname.clone(),
            results: results.clone(),
            base_dir: staging.dir.clone(),
        }],
        &staging.dir,
    )?;
    if super::interrupt::requested() {
        return Err(interrupted(&args.output, specs.len(), specs.len()));
    }
    staging.publish(&args.output)?;
    eprintln!(
        "suite '{}': {} scenes × {} variants in {:.1} s; {} failure{}; wrote {}/{{results.json, report.html, report.pdf}}",
        def.name,
        results.scenes.len(),
        def.variants.len(),
        started.elapsed().as_secs_f64(),
        results.failures.len(),
        if results.failures.len() == 1 { "" } else { "s" },
        args.output.display()
    );
    for f in &results.failures {
        eprintln!("  failed: {}: {}", f.place(), f.message);
    }
    if let Some(old) = old {
        let gate = results::gate::compare_runs(&old, &results, args.threshold / 100.0);
        let text = gate.to_text();
        print!("{text}");
        save(&args.output, "gate.txt", text.as_bytes())?;
        if gate.failed() {
            return Err(super::CheckFailed("the regression gate failed".into()).into());
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_suite_parses_and_its_quick_form_is_smaller() {
        let def = SuiteDef::parse(DEFAULT_SUITE, "suite.toml").unwrap();
        assert_eq!(def.variants[0], "baseline");
        let quick = def.clone().quick();
        assert!(quick.size[0] * quick.size[1] < def.size[0] * def.size[1]);
        assert!(quick.scenes.len() < def.scenes.len());
        for s in &def.scenes {
            resolve_scene(s, (8, 8), Path::new(".")).unwrap();
        }
    }

    #[test]
    fn bad_suites_are_refused_with_the_file_name() {
        let bad = DEFAULT_SUITE.replace("\"baseline\", \"simd\"", "\"simd\", \"baseline\"");
        let err = SuiteDef::parse(&bad, "x.toml").unwrap_err().to_string();
        assert!(err.contains("x.toml") && err.contains("baseline"), "{err}");
        let err = SuiteDef::parse("name = 1", "y.toml")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("y.toml"), "{err}");
        // The [quick] overrides are checked too.
        let bad = DEFAULT_SUITE.replace("min_seconds = 0.02", "min_seconds = -1");
        let err = format!("{:#}", SuiteDef::parse(&bad, "z.toml").unwrap_err());
        assert!(
            err.contains("[quick]") && err.contains("min_seconds"),
            "{err}"
        );
        assert_eq!(SceneFamily::of_builtin("balls7"), SceneFamily::Balls);
        assert_eq!(SceneFamily::of_builtin("ballsX"), SceneFamily::Other);
    }
}
