//! The suite: every scene of a definition with every variant (counts, timed renders,
//! images and their error against the reference variant and the f64 reference
//! renderer's picture), the hardware model and emulator
//! where the scene allows, and a profile of the heaviest scene; collected into one
//! [`Results`]. A failing scene or variant is recorded and skipped; the rest stands.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use analysis::{compare, difference_heat_map, gray_histogram};
use hwmodel::device::FitState;
use hwmodel::hw_scene::HwScene;
use results::{
    Calibration, CodeKind, F64Reference, FailedPart, Failure, MachinePeak, Results, SCHEMA,
    SceneHardware, SceneResult, Shard, SuiteInfo, VariantName, VariantResult, slug,
};
use tracer::{BvhBuilder, RenderOptions, Sampling, Scene, ShadingMode, VariantSet, parse_nff};

use crate::bvh_study;
use crate::collect::{count_map, quality};
use crate::definition::SuiteDef;
use crate::error::RunError;
use crate::hardware_job::{hardware_tables, run_hardware};
use crate::machine::{build_info, command_line, machine, now_rfc3339};
use crate::machine_peak::{PeakPlan, measure_peak};
use crate::pixel_maps::{MapsContext, record_maps, write_maps};
use crate::pool::thread_pool;
use crate::progress::Progress;
use crate::ray_rates::ray_rates;
use crate::reference_job;
use crate::render_setup::RenderSetup;
use crate::scene_facts::{efficiency, memory_use, published_rays};
use crate::scenes::{SceneSpec, extra_scenes, resolve_scene};
use crate::staging::save_png;
use crate::variant_job::VariantMeasurement;

mod profile;
mod tracers;

/// A suite ready to run: its definition and its resolved scenes.
pub struct Suite {
    pub def: SuiteDef,
    pub quick: bool,
    pub scenes: Vec<SceneSpec>,
    /// The scene to profile when the definition names one (`profile_scene`).
    pub profile_scene: Option<SceneSpec>,
    /// The share of the scenes this run holds ([`Suite::with_shard`]); `None`: all.
    pub shard: Option<Shard>,
    /// The outside tracers run beside the variants (the definition's `[[tracers]]`,
    /// `--tracer`, `--peers`).
    pub tracers: Vec<crate::outside::TracerDef>,
    /// Built-in peers `--peers` asked for that are not installed.
    pub missing_peers: Vec<String>,
    /// The outside tracers also recorded with perf on the profile scene (by name: the
    /// definition's `[[tracers]]` entries with `record = true`).
    pub recorded: Vec<String>,
}

/// Where a suite's work happens.
pub struct RunContext<'a> {
    /// Directory the images, profiles and flamegraphs are written to.
    pub out: &'a Path,
    /// Threads of the timed renders (default: the definition's `timing_threads`, one).
    /// The untimed work uses one worker per core.
    pub threads: Option<u16>,
    pub progress: &'a dyn Progress,
    /// Set when the user asks the run to stop; checked before every render.
    pub stop: &'a AtomicBool,
    /// Whether report.pdf is written (the outside tracers' recordings' too).
    pub pdf: crate::report_files::Pdf,
}

impl Suite {
    /// What a finished run says: scenes, variants, time, failures (one line each) and
    /// where its files are.
    pub fn summary(
        &self,
        results: &Results,
        seconds: f64,
        output: &Path,
        pdf: crate::report_files::Pdf,
    ) -> String {
        let failures = results.failures.len();
        let mut text = format!(
            "suite '{}': {} scenes × {} variants in {seconds:.1} s; {failures} failure{}; wrote {}/{{results.json, {}, variants.csv, summary.md}}\n",
            self.def.name,
            results.scenes.len(),
            self.def.variants.len(),
            if failures == 1 { "" } else { "s" },
            output.display(),
            pdf.documents()
        );
        if !self.tracers.is_empty() {
            let names: Vec<&str> = self.tracers.iter().map(|t| t.name.as_str()).collect();
            text += &format!("  outside tracers: {}\n", names.join(", "));
        }
        for name in &self.missing_peers {
            text += &format!(
                "  {name} is not installed, so it did not run (docs/tracers.md: built-in peers)\n"
            );
        }
        for f in &results.failures {
            text += &format!("  failed: {}: {}\n", f.place(), f.message);
        }
        text
    }

    /// What the run's failures mean for its exit, when it had any: "N parts failed".
    pub fn failures_message(results: &Results) -> Option<String> {
        match results.failures.len() {
            0 => None,
            1 => Some(
                "1 part of the suite failed (listed above); the rest is in the results and reports"
                    .into(),
            ),
            n => Some(format!(
                "{n} parts of the suite failed (listed above); the rest is in the results and reports"
            )),
        }
    }

    /// Resolves the scenes of `def` (relative paths from `base_dir`) and, when given,
    /// every NFF file of `extra_dir`: a missing scene fails here, before any work.
    pub fn prepare(
        def: SuiteDef,
        quick: bool,
        base_dir: &Path,
        extra_dir: Option<&Path>,
    ) -> Result<Self, RunError> {
        let def = if quick { def.quick() } else { def };
        let size = (def.size[0], def.size[1]);
        let mut scenes: Vec<SceneSpec> = def
            .scenes
            .iter()
            .map(|s| resolve_scene(s, size, base_dir))
            .collect::<Result<_, _>>()?;
        if let Some(spd) = &def.spd {
            for entry in &spd.scenes {
                scenes.extend(SceneSpec::spd_pair(entry, spd, base_dir)?);
            }
        }
        if let Some(dir) = extra_dir {
            scenes.extend(extra_scenes(dir, (def.extra_size[0], def.extra_size[1]))?);
        }
        let profile_size = (def.profile_size[0], def.profile_size[1]);
        let profile_scene = def
            .profile_scene
            .as_deref()
            .map(|entry| resolve_scene(entry, profile_size, base_dir))
            .transpose()?;
        let tracers = def
            .tracers
            .iter()
            .enumerate()
            .map(|(i, entry)| entry.resolve(&def.name, base_dir, i))
            .collect::<Result<Vec<_>, _>>()?;
        let recorded = (def.tracers.iter().zip(&tracers))
            .filter(|(entry, _)| entry.record())
            .map(|(_, t)| t.name.clone())
            .collect();
        let suite = Suite {
            def,
            quick,
            scenes,
            profile_scene,
            shard: None,
            tracers: Vec::new(),
            missing_peers: Vec::new(),
            recorded,
        };
        suite.with_tracers(tracers)
    }

    /// Keeps only `shard`'s scenes (each with all its variants: a scene's variants are
    /// compared within one process); `None` keeps them all. An empty share is refused.
    pub fn with_shard(mut self, shard: Option<Shard>) -> Result<Self, RunError> {
        let Some(shard) = shard else {
            return Ok(self);
        };
        let total = self.scenes.len();
        self.scenes = crate::shard::select(std::mem::take(&mut self.scenes), shard);
        if self.scenes.is_empty() {
            return Err(RunError::Input(format!(
                "shard {shard} holds no scene: the suite has {total} scene{}, so at most {total} shards",
                if total == 1 { "" } else { "s" }
            )));
        }
        self.shard = Some(shard);
        Ok(self)
    }

    /// Renders per progress step count: every scene's variants and outside tracers.
    pub fn steps(&self) -> u64 {
        self.scenes
            .iter()
            .map(|s| {
                let tracers = if s.runs_tracers() {
                    self.tracers.len()
                } else {
                    0
                };
                (s.variants_in(&self.def).len() + tracers) as u64
            })
            .sum()
    }

    /// Runs everything. Stopping returns [`RunError::StoppedAfter`] with the scenes done.
    pub fn run(&self, ctx: &RunContext<'_>) -> Result<Results, RunError> {
        let started = Instant::now();
        let created = now_rfc3339();
        // Untimed work on every core; the timed renders and the machine's peak (the roof
        // they are placed under) on the timed threads.
        let pool = thread_pool(None)?;
        let timed = thread_pool(Some(ctx.threads.unwrap_or(self.def.timing_threads)))?;
        let one_thread = thread_pool(Some(1))?;
        ctx.progress.begin("machine", 0);
        ctx.progress
            .message("measuring the FMA and memory bandwidth peaks");
        let plan = if self.quick {
            PeakPlan::QUICK
        } else {
            PeakPlan::FULL
        };
        let peak = match measure_peak(&timed, plan, ctx.stop) {
            Ok(peak) => peak,
            Err(e) => {
                ctx.progress.end();
                return Err(match e {
                    RunError::Stopped => RunError::StoppedAfter {
                        done: 0,
                        total: self.scenes.len(),
                    },
                    e => e,
                });
            }
        };
        ctx.progress.end();
        // The outside tracers' scene files and runs: a directory of the run's own.
        let tracer_dir =
            std::env::temp_dir().join(format!("rtprof-tracers-{}", std::process::id()));
        let runner = SceneRunner {
            def: &self.def,
            tracers: &self.tracers,
            tracer_dir: &tracer_dir,
            ctx,
            pool: &pool,
            timed: &timed,
            one_thread: &one_thread,
            peak: &peak,
        };
        ctx.progress.begin("scenes", self.steps());
        let mut failures = Vec::new();
        let mut scenes = Vec::new();
        let total = self.scenes.len();
        for (done, spec) in self.scenes.iter().enumerate() {
            if ctx.stop.load(Ordering::SeqCst) {
                ctx.progress.end();
                return Err(RunError::StoppedAfter { done, total });
            }
            let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                let mut local = Vec::new();
                let r = runner.run_scene(spec, (done, total), &mut local);
                (r, local)
            }));
            match outcome {
                Ok((Ok(result), local)) => {
                    failures.extend(local);
                    scenes.push(result);
                }
                Ok((Err(RunError::Stopped), _)) => {
                    ctx.progress.end();
                    return Err(RunError::StoppedAfter { done, total });
                }
                Ok((Err(e), local)) => {
                    failures.extend(local);
                    failures.push(failure(Some(&spec.name), FailedPart::Scene, &e));
                }
                Err(_) => failures.push(Failure {
                    scene: Some(spec.name.clone()),
                    part: FailedPart::Scene,
                    message: "internal error (panic) while running this scene; please report it"
                        .into(),
                }),
            }
        }
        ctx.progress.end();

        ctx.progress.begin("profile", 0);
        ctx.progress.message("heaviest scene");
        // A named profile scene is profiled once: by the whole run, or by shard 1.
        let named = match self.shard {
            Some(shard) if shard.index != 1 => None,
            _ => self.profile_scene.as_ref(),
        };
        let chosen = runner.profile_choice(&self.scenes, &scenes, named);
        let profiled = chosen
            .as_ref()
            .map(|(spec, best)| runner.profile_spec(spec, best.clone()));
        // The outside tracers the suite records, on the same scene (failures recorded).
        let recorded =
            chosen.map(|(spec, _)| runner.record_tracers(spec, &self.recorded, &mut failures));
        // Scratch only: the pictures and profiles that matter were saved with the results.
        let _ = std::fs::remove_dir_all(&tracer_dir);
        let (profile, outside_profiles) = match (profiled.transpose(), recorded.transpose()) {
            (Err(RunError::Stopped), _) | (_, Err(_)) => {
                ctx.progress.end();
                return Err(RunError::StoppedAfter { done: total, total });
            }
            (Err(e), Ok(o)) => {
                failures.push(failure(None, FailedPart::Profile, &e));
                (None, o.unwrap_or_default())
            }
            (Ok(p), Ok(o)) => (p.flatten(), o.unwrap_or_default()),
        };
        ctx.progress.end();

        let policy = self.def.timing();
        Ok(Results {
            schema: SCHEMA.to_string(),
            created,
            command: command_line(),
            machine: machine(),
            build: build_info(),
            suite: SuiteInfo {
                name: self.def.name.clone(),
                quick: self.quick,
                threads: timed.current_num_threads() as u32,
                variants: self
                    .def
                    .variants
                    .iter()
                    .map(|v| VariantName::parse(v))
                    .chain(self.tracers.iter().map(|t| VariantName::outside(&t.name)))
                    .collect::<Result<_, _>>()?,
                timing: policy.record(),
                wall_seconds: started.elapsed().as_secs_f64(),
                noise_threshold: Some(results::NOISE_THRESHOLD),
                shard: self.shard,
            },
            scenes,
            profile,
            hardware: Some(hardware_tables()),
            failures,
            criterion: Vec::new(),
            instructions: Vec::new(),
            peak: Some(peak),
            outside_profiles,
        })
    }
}

/// Frames up to this many pixels get the BVH study (the SPD scenes' small runs and the
/// quick suite's scenes): two builders, each counted and timed again.
const BVH_STUDY_PIXELS: u64 = 128 * 128;

/// The variants whose per-pixel maps the suite writes.
const MAPPED_VARIANTS: [&str; 3] = ["baseline", "simd", "bvh"];

fn failure(scene: Option<&str>, part: FailedPart, e: &RunError) -> Failure {
    Failure {
        scene: scene.map(str::to_string),
        part,
        message: e.to_string(),
    }
}

/// A variant's result and its picture, or why there is none.
type VariantOutcome = Result<(VariantResult, analysis::RgbImage), RunError>;

struct SceneRunner<'a> {
    def: &'a SuiteDef,
    /// Outside tracers, and the directory of their scene files and runs.
    tracers: &'a [crate::outside::TracerDef],
    tracer_dir: &'a Path,
    ctx: &'a RunContext<'a>,
    /// Every core: counted renders, pictures, the f64 reference, the profile.
    pool: &'a rayon::ThreadPool,
    /// The timed renders' threads ([`SuiteDef::timing_threads`]).
    timed: &'a rayon::ThreadPool,
    one_thread: &'a rayon::ThreadPool,
    peak: &'a MachinePeak,
}

impl SceneRunner<'_> {
    /// Every variant on one scene, then the hardware job.
    fn run_scene(
        &self,
        spec: &SceneSpec,
        position: (usize, usize),
        failures: &mut Vec<Failure>,
    ) -> Result<SceneResult, RunError> {
        let scene = parse_nff(&spec.text, &spec.source).map_err(|e| RunError::Scene {
            scene: spec.name.clone(),
            message: e.to_string(),
        })?;
        let (width, height) = spec.size;
        let sampling = if spec.spd_sampling {
            Sampling::SpdCorners
        } else {
            Sampling::PixelCenters
        };
        let options = RenderOptions::new(width, height, sampling, ShadingMode::Color);
        // The scene's timed renders run on the timed pool (the SPD's small frames on one
        // thread whatever it is).
        let pool = if spec.one_thread {
            self.one_thread
        } else {
            self.timed
        };
        let setup = RenderSetup {
            scene: &scene,
            name: &spec.name,
            options: &options,
            pool,
            counting_pool: self.pool,
            stop: self.ctx.stop,
        };
        let doing = |what: &str| {
            self.ctx.progress.message(&format!(
                "{}/{} {}: {what}",
                position.0 + 1,
                position.1,
                spec.name
            ));
        };
        let names = spec.variants_in(self.def);
        let sets: Vec<VariantSet> = names
            .iter()
            .map(|name| VariantSet::parse(name))
            .collect::<Result<_, _>>()?;
        let timed = |done, total| {
            self.ctx
                .progress
                .within(crate::progress::TIMED, done, total)
        };
        let tracer_home = self.tracer_dir.join(slug(&spec.name));
        let outside = crate::outside::OutsideJobs {
            defs: if spec.runs_tracers() {
                self.tracers
            } else {
                &[]
            },
            dir: &tracer_home,
            spp: None,
        };
        let mut measured =
            setup.measure_all(&sets, &outside, &self.def.timing(), true, &doing, &timed)?;
        let truth = self.f64_reference(spec, &setup, &doing, failures)?;
        let mut variants: Vec<VariantResult> = Vec::new();
        let memory = memory_use(&scene, &measured.variants);
        // The `bvh` variant's counts and time, for the BVH quality of a large frame.
        let bvh_measured = names
            .iter()
            .zip(&measured.variants)
            .find(|(name, _)| name.as_str() == "bvh")
            .and_then(|(_, m)| m.as_ref().ok())
            .map(|m| (m.counts, m.time.median));
        // The reference variant's picture first (the others are compared with it), then
        // every other variant's images, metrics and files on the pool, in parallel:
        // nothing renders meanwhile, and each is a second of single-threaded work on a
        // large frame (PNG encoding, SSIM, heat maps).
        let truth_image = truth.as_ref().map(|(_, image)| image);
        let outside_measured = std::mem::take(&mut measured.outside);
        let mut outcomes: Vec<Option<VariantOutcome>> =
            (0..measured.variants.len()).map(|_| None).collect();
        let mut pending: Vec<(usize, Result<VariantMeasurement, RunError>)> =
            measured.variants.into_iter().enumerate().collect();
        let reference_at = pending.iter().position(|(_, m)| {
            m.as_ref()
                .is_ok_and(|m| VariantName::of(&m.variants).is_reference())
        });
        let mut reference: Option<analysis::RgbImage> = None;
        if let Some(at) = reference_at {
            let (index, m) = pending.remove(at);
            let result = m.and_then(|m| self.variant_result(spec, &scene, m, None, truth_image));
            if let Ok((_, image)) = &result {
                reference = Some(image.clone());
            }
            outcomes[index] = Some(result);
        }
        let done: Vec<(usize, VariantOutcome)> = self.pool.install(|| {
            use rayon::prelude::*;
            pending
                .into_par_iter()
                .map(|(index, m)| {
                    let result = m.and_then(|m| {
                        self.variant_result(spec, &scene, m, reference.as_ref(), truth_image)
                    });
                    (index, result)
                })
                .collect()
        });
        for (index, result) in done {
            outcomes[index] = Some(result);
        }
        for (name, outcome) in names.iter().zip(outcomes) {
            let Some(result) = outcome else { continue };
            match result {
                Ok((v, _)) => variants.push(v),
                Err(RunError::Stopped) => return Err(RunError::Stopped),
                Err(e) => {
                    // The suite's variant names were checked when it was read.
                    let part =
                        VariantName::parse(name).map_or(FailedPart::Scene, FailedPart::Variant);
                    failures.push(failure(Some(&spec.name), part, &e));
                }
            }
            self.ctx.progress.advance(1);
        }
        tracers::push_outside_results(
            self.ctx,
            &spec.name,
            outside_measured,
            (reference.as_ref(), truth_image),
            &mut variants,
            failures,
        )?;
        let bvh_quality = self.bvh_quality(&setup, &sets, bvh_measured, &doing, failures)?;
        let pixel_maps = self.pixel_maps(spec, &setup, &sets, &doing, failures)?;
        let calibration = measured.calibration.map(|k| Calibration {
            time: k.time,
            samples: k.samples,
            cpu_samples: k.cpu_samples,
        });
        let yardstick = measured
            .yardstick
            .map(|((width, height), k)| results::Yardstick {
                width,
                height,
                time: k.time,
                samples: k.samples,
                cpu_samples: k.cpu_samples,
            });
        let hardware = match HwScene::from_scene(&scene) {
            Ok(_) if !self.def.hardware => None,
            Ok(hw) => match self.run_hardware(spec, &scene, &hw) {
                Ok(h) => Some(h),
                Err(RunError::Stopped) => return Err(RunError::Stopped),
                Err(e) => {
                    failures.push(failure(Some(&spec.name), FailedPart::Hardware, &e));
                    None
                }
            },
            Err(_) => None, // polygons etc.: the hardware cannot render it; not a failure
        };
        let primitive_counts: BTreeMap<String, u64> = [
            ("spheres", scene.spheres.len()),
            ("cylinders", scene.cylinders.len()),
            ("cones", scene.cones.len()),
            ("polygons", scene.polygons.len()),
            ("patches", scene.patches.len()),
        ]
        .into_iter()
        .map(|(kind, n)| (kind.to_string(), n as u64))
        .collect();
        let mut result = SceneResult {
            name: spec.name.clone(),
            source: spec.source.clone(),
            family: spec.family,
            primitives: scene.primitive_count() as u64,
            primitive_counts,
            width,
            height,
            spd: spec.spd_sampling,
            variants,
            hardware,
            calibration,
            yardstick,
            published: published_rays(spec, &options),
            memory,
            bvh_quality,
            pixel_maps,
            f64_reference: truth.map(|(t, _)| t),
            threads: (spec.one_thread && self.timed.current_num_threads() != 1).then_some(1),
        };
        results::change::fill_scene_speedups(&mut result, results::NOISE_THRESHOLD);
        Ok(result)
    }

    /// The BVH study of both builders, when the scene ran `bvh` on a frame small
    /// enough ([`BVH_STUDY_PIXELS`]); a builder that fails is recorded and skipped. On a
    /// larger frame, the `bvh` variant's own tree with its measured counts and time.
    fn bvh_quality(
        &self,
        setup: &RenderSetup,
        sets: &[VariantSet],
        bvh_measured: Option<(tracer::Counts, f64)>,
        doing: &dyn Fn(&str),
        failures: &mut Vec<Failure>,
    ) -> Result<Vec<results::BvhQuality>, RunError> {
        let ran_bvh = sets
            .iter()
            .any(|s| s.config().accel == tracer::Accelerator::Bvh);
        let pixels = u64::from(setup.options.width) * u64::from(setup.options.height);
        if !ran_bvh {
            return Ok(Vec::new());
        }
        if pixels > BVH_STUDY_PIXELS {
            return Ok(bvh_measured
                .map(|(counts, seconds)| {
                    doing("bvh quality");
                    bvh_study::quality(setup, BvhBuilder::BinnedSah, &counts, seconds)
                })
                .into_iter()
                .collect());
        }
        let mut studies = Vec::new();
        for builder in BvhBuilder::ALL {
            doing(&format!("bvh {builder}"));
            match bvh_study::study(setup, builder, &self.def.timing()) {
                Ok(q) => studies.push(q),
                Err(RunError::Stopped) => return Err(RunError::Stopped),
                Err(e) => failures.push(failure(Some(setup.name), FailedPart::Scene, &e)),
            }
        }
        Ok(studies)
    }

    /// Per-pixel maps of baseline, simd and bvh, when the suite asks for them on this
    /// scene (`pixel_stats`), under `pixel-stats/SCENE/VARIANT/`.
    fn pixel_maps(
        &self,
        spec: &SceneSpec,
        setup: &RenderSetup,
        sets: &[VariantSet],
        doing: &dyn Fn(&str),
        failures: &mut Vec<Failure>,
    ) -> Result<Vec<results::VariantPixelMaps>, RunError> {
        if !self.def.pixel_stats.contains(&spec.name) {
            return Ok(Vec::new());
        }
        let mut all = Vec::new();
        for set in sets
            .iter()
            .filter(|s| MAPPED_VARIANTS.contains(&s.to_string().as_str()))
        {
            doing(&format!("maps of {set}"));
            let directory = format!(
                "pixel-stats/{}/{}",
                slug(&spec.name),
                slug(&set.to_string())
            );
            let written = record_maps(setup, set).and_then(|maps| {
                let context = MapsContext {
                    scene: &spec.name,
                    variant: &set.to_string(),
                    sampling: setup.options.sampling,
                    threads: setup.pool.current_num_threads(),
                    clock_resolution_ns: tracer::pixel_stats::clock_resolution().as_secs_f64()
                        * 1e9,
                };
                write_maps(&self.ctx.out.join(&directory), &maps, &context)
            });
            match written {
                Ok(stats) => all.push(results::VariantPixelMaps {
                    variant: VariantName::of(set),
                    directory,
                    columns: stats.columns,
                    rows: stats.rows,
                    clock_resolution_ns: stats.clock_resolution_ns,
                    maps: stats.maps,
                }),
                Err(RunError::Stopped) => return Err(RunError::Stopped),
                Err(e) => failures.push(failure(
                    Some(&spec.name),
                    FailedPart::Variant(VariantName::of(set)),
                    &e,
                )),
            }
        }
        Ok(all)
    }

    /// The f64 reference's picture of the scene (suite option `f64_reference`), saved
    /// beside the variants' images; a failure is recorded and the scene goes on.
    fn f64_reference(
        &self,
        spec: &SceneSpec,
        setup: &RenderSetup,
        doing: &dyn Fn(&str),
        failures: &mut Vec<Failure>,
    ) -> Result<Option<(F64Reference, analysis::RgbImage)>, RunError> {
        if !self.def.f64_reference {
            return Ok(None);
        }
        doing("f64 reference");
        let rendered = reference_job::render_in(setup).and_then(|picture| {
            let path = format!("images/{}-f64-reference.png", slug(&spec.name));
            let image = save_png(self.ctx.out, &path, &picture.image)?;
            let truth = F64Reference {
                image,
                seconds: picture.seconds,
            };
            Ok((truth, picture.image))
        });
        match rendered {
            Ok(truth) => Ok(Some(truth)),
            Err(RunError::Stopped) => Err(RunError::Stopped),
            Err(e) => {
                failures.push(failure(Some(&spec.name), FailedPart::F64Reference, &e));
                Ok(None)
            }
        }
    }

    /// One measured variant: its image saved, compared with the reference variant's
    /// and with the f64 reference's (`truth`).
    fn variant_result(
        &self,
        spec: &SceneSpec,
        scene: &Scene,
        m: VariantMeasurement,
        reference: Option<&analysis::RgbImage>,
        truth: Option<&analysis::RgbImage>,
    ) -> Result<(VariantResult, analysis::RgbImage), RunError> {
        let variant = VariantName::of(&m.variants);
        let out = self.ctx.out;
        let stem = format!(
            "images/{}-{}",
            slug(&spec.name),
            slug(&m.variants.to_string())
        );
        let image_rel = save_png(out, &format!("{stem}.png"), &m.image)?;
        let (quality, heat_map) = match reference {
            Some(base) if !variant.is_reference() => {
                let c = compare(base, &m.image)?;
                let heat = difference_heat_map(base, &m.image)?;
                let heat_rel = save_png(out, &format!("{stem}-diff.png"), &heat)?;
                (Some(quality(&c)), Some(heat_rel))
            }
            _ => (None, None),
        };
        let vs_f64_reference = match truth {
            Some(truth) => Some(crate::collect::quality(&compare(truth, &m.image)?)),
            None => None,
        };
        let histogram = gray_histogram(&m.image).to_vec();
        let lanes = &m.counts.accel;
        let lane_utilization =
            (lanes.lanes_issued > 0).then(|| lanes.lanes_active as f64 / lanes.lanes_issued as f64);
        let accel = m.variants.config().accel;
        let simd = accel == tracer::Accelerator::Simd;
        let code = CodeKind::of_accelerator(accel);
        // Embree's work is uncounted: its flops would be a few shading operations.
        let efficiency = accel
            .counts_its_work()
            .then(|| efficiency(&m.counts, scene, (simd, code), m.time.median, self.peak));
        let ray_rates = m
            .query_shares
            .map(|shares| ray_rates(&shares, &m.counts.rays, m.time.median));
        Ok((
            VariantResult {
                variant,
                time: m.time,
                samples: m.samples,
                cpu_samples: m.cpu_samples,
                preprocessing_seconds: Some(m.preprocessing),
                // Filled for the whole run by results::change::fill_speedups.
                speedup: None,
                speedup_interval: None,
                verdict: None,
                counts: count_map(&m.counts),
                image: Some(image_rel),
                heat_map,
                quality,
                vs_f64_reference,
                histogram,
                lane_utilization,
                efficiency,
                ray_rates,
                outside: None,
            },
            m.image,
        ))
    }

    /// Model time, emulator image, and the software on the same job.
    fn run_hardware(
        &self,
        spec: &SceneSpec,
        scene: &Scene,
        hw: &HwScene,
    ) -> Result<SceneHardware, RunError> {
        let m = run_hardware(
            scene,
            hw,
            &spec.name,
            spec.size,
            self.one_thread,
            self.pool,
            &self.def.hardware_timing(),
            self.ctx.stop,
        )?;
        let out = self.ctx.out;
        let stem = format!("images/{}", slug(&spec.name));
        let software_seconds = m.software.time;
        Ok(SceneHardware {
            primitives: m.primitives,
            cycles: m.timing.cycles,
            seconds: m.timing.seconds,
            fits: m.fit_state.is_some_and(|s| s != FitState::DoesNotFit),
            fit_state: m.fit_state,
            speedup: software_seconds.median / m.timing.seconds,
            peer: Some(results::SoftwarePeer {
                variant: VariantName::parse(crate::hardware_job::PEER_VARIANT)?,
                one_thread: m.peer_one_thread.time,
                all_threads: m.peer_all_threads.time,
                threads: m.peer_threads as u32,
            }),
            software_seconds,
            emulator_rms: m.comparison.rms,
            emulator_band: m.comparison.band,
            emulator_image: Some(save_png(out, &format!("{stem}-hw.png"), &m.emulator_image)?),
            software_image: Some(save_png(
                out,
                &format!("{stem}-sw-diffuse.png"),
                &m.software_image,
            )?),
        })
    }
}
