//! Outside tracers measured beside rtprof's variants: each prepared once (its scene
//! written in the format it reads, one untimed run that checks it works, warms the
//! caches and gives its picture and its probe's counts, and for a noisy tracer one run
//! at its converged samples per pixel), then timed in the variant job's interleaved
//! rounds, one run at a time, like the built-in variants.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use analysis::{Estimate, RgbImage};
use results::VariantName;
use tracer::{Counts, RenderOptions, Scene};

use super::definition::TracerDef;
use super::identity::ProgramIdentity;
use super::run::{OutsideRun, RunEnd, RunPlan, Shading, run_once};
use super::scene_file::write_scene;
use crate::error::RunError;

/// The outside tracers of a measurement and where their files go.
#[derive(Clone, Copy, Debug)]
pub struct OutsideJobs<'a> {
    pub defs: &'a [TracerDef],
    /// A directory of their own: each tracer's scene file and runs in `NAME/`.
    pub dir: &'a Path,
    /// Samples per pixel of the timed runs (`{spp}`): the caller's, else each
    /// definition's own, else 1.
    pub spp: Option<u32>,
}

impl OutsideJobs<'_> {
    /// No outside tracer.
    pub fn none() -> OutsideJobs<'static> {
        OutsideJobs {
            defs: &[],
            dir: Path::new(""),
            spp: None,
        }
    }
}

/// An outside tracer ready to be timed.
pub struct Prepared {
    pub def: TracerDef,
    pub identity: Option<ProgramIdentity>,
    scene_file: Option<PathBuf>,
    runs: PathBuf,
    pub width: u32,
    pub height: u32,
    pub threads: usize,
    pub spp: u32,
    pub shading: Shading,
    /// The untimed first run.
    pub first: OutsideRun,
    /// The picture at the definition's converged samples per pixel (noisy tracers).
    pub converged: Option<RgbImage>,
}

/// A run's end as the runner's error.
fn run_error(def: &TracerDef, end: RunEnd) -> RunError {
    match end {
        RunEnd::Stopped => RunError::Stopped,
        RunEnd::Failed(failure) => RunError::Outside {
            tracer: def.name.clone(),
            failure,
        },
    }
}

/// Writes `def`'s scene into `jobs.dir/NAME/`, runs it once untimed (and once at its
/// converged samples per pixel when it is noisy), at the size and shading of `options`.
pub fn prepare(
    def: &TracerDef,
    scene: &Scene,
    options: &RenderOptions,
    threads: usize,
    jobs: &OutsideJobs<'_>,
    stop: &AtomicBool,
) -> Result<Prepared, RunError> {
    let home = jobs.dir.join(&def.name);
    let scene_file = write_scene(scene, def.scene, &home, (options.width, options.height))
        .map_err(|failure| RunError::Outside {
            tracer: def.name.clone(),
            failure,
        })?;
    let spp = jobs.spp.or(def.spp).unwrap_or(1);
    let runs = home.join("run");
    let (width, height) = (options.width, options.height);
    let shading = Shading::of(options);
    let plan = RunPlan {
        def,
        scene_file: scene_file.as_deref(),
        width,
        height,
        threads,
        spp,
        shading,
    };
    let first = run_once(&plan, &runs, stop).map_err(|e| run_error(def, e))?;
    let converged = match def.converged_spp {
        Some(spp) => {
            let plan = RunPlan { spp, ..plan };
            let run = run_once(&plan, &home.join("converged"), stop);
            Some(run.map_err(|e| run_error(def, e))?.image)
        }
        None => None,
    };
    Ok(Prepared {
        def: def.clone(),
        // The program as its command expands ({rtprof} is this binary).
        identity: super::run::command_line(&plan, &runs)
            .ok()
            .and_then(|line| ProgramIdentity::of(line.first()?)),
        scene_file,
        runs,
        width,
        height,
        threads,
        spp,
        shading,
        first,
        converged,
    })
}

impl Prepared {
    fn plan(&self) -> RunPlan<'_> {
        RunPlan {
            def: &self.def,
            scene_file: self.scene_file.as_deref(),
            width: self.width,
            height: self.height,
            threads: self.threads,
            spp: self.spp,
            shading: self.shading,
        }
    }

    /// One run, timed by its definition's source.
    pub fn run(&self, stop: &AtomicBool) -> Result<OutsideRun, RunError> {
        run_once(&self.plan(), &self.runs, stop).map_err(|e| run_error(&self.def, e))
    }

    /// What results record about it: its definition's facts and the program that ran.
    pub fn record(&self) -> results::OutsideTracer {
        let def = &self.def;
        results::OutsideTracer {
            definition: def.file.clone(),
            command: def.command.clone(),
            scene_format: match def.scene {
                super::SceneFormat::Nff => "nff",
                super::SceneFormat::Pov => "pov",
                super::SceneFormat::Tachyon => "tachyon",
                super::SceneFormat::Own => "own",
            }
            .to_string(),
            time_covers: def.time.covers(),
            whole_process: def.time.whole_process(),
            deterministic: def.deterministic,
            spp: self.spp,
            conventions: def.conventions.clone(),
            program: self.identity.as_ref().map(|p| results::Program {
                path: p.path.display().to_string(),
                bytes: p.bytes,
                build_id: p.build_id.clone(),
            }),
            likeness: None,
            noise: None,
        }
    }

    /// Its exact counts, when its probe wrote them (rtprof's counters by their keys).
    pub fn counts(&self) -> Option<Counts> {
        let probe = self.first.probe.as_ref()?;
        (!probe.counters.is_empty())
            .then(|| Counts::from_keys(probe.counters.iter().map(|c| (c.name.as_str(), c.value))).0)
    }
}

/// An outside tracer measured.
pub struct OutsideMeasurement {
    pub name: VariantName,
    pub prepared: Prepared,
    /// Seconds of each timed run, by its definition's source.
    pub samples: Vec<f64>,
    /// CPU seconds of each timed run (the kernel's account of the process).
    pub cpu_samples: Vec<f64>,
    pub time: Estimate,
    /// The last timed run's picture.
    pub image: RgbImage,
}

impl OutsideMeasurement {
    /// What results record about it, its picture judged: against `truth` (the f64
    /// reference's picture, else the reference variant's) for likeness when it drew
    /// rtprof's scene at the same frame, and against its own converged run for noise.
    pub fn record(&self, truth: Option<&RgbImage>) -> Result<results::OutsideTracer, RunError> {
        let mut record = self.prepared.record();
        let same_frame = |other: &RgbImage| {
            self.prepared.def.scene != super::SceneFormat::Own
                && (other.width, other.height) == (self.image.width, self.image.height)
        };
        if let Some(truth) = truth.filter(|t| same_frame(t)) {
            record.likeness = Some(analysis::likeness(&self.image, truth)?);
        }
        if let (Some(converged), Some(spp)) =
            (&self.prepared.converged, self.prepared.def.converged_spp)
        {
            let error = analysis::noise_error(&self.image, converged)?;
            record.noise = Some(results::Noise {
                converged_spp: spp,
                rel_mse: error.rel_mse,
                mse: error.mse,
                efficiency: analysis::efficiency(error.rel_mse, self.time.median),
                flip: analysis::flip_mean(&self.image, converged).ok(),
            });
        }
        Ok(record)
    }
}
