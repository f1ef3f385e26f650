//! The reference jobs: `rtprof render --reference` loads a scene within limits and
//! renders it once with the f64 reference renderer (the `reference` crate), timing the
//! preprocessing (parse + conversion to f64) and the tracing apart, as for the tracer;
//! `rtprof compare --variants … --reference` renders it in the comparison's pool and
//! measures each variant's image error against it ([`ImageError`]).

use std::time::{Duration, Instant};

use analysis::{RgbImage, compare};
use serde::Serialize;
use tracer::{Frame, Scene, ShadingMode};

use crate::error::RunError;
use crate::pool::{Workers, workers_for};
use crate::progress::Progress;
use crate::render_job::RenderSettings;
use crate::render_setup::RenderSetup;
use crate::scene_input::SceneInput;

/// A finished reference render with its timings.
pub struct ReferenceRender {
    pub scene: Scene,
    pub frame: Frame,
    /// Parse + conversion to f64.
    pub preprocessing: Duration,
    pub tracing: Duration,
    pub threads: usize,
}

/// Loads `input` and renders it with the reference renderer as `settings` ask (size,
/// corner sampling, threads, depth, limits; per-sample records and the BVH builder do
/// not apply). Progress counts sample rows.
pub fn render_reference(
    input: &SceneInput,
    settings: &RenderSettings,
    mode: ShadingMode,
    progress: &dyn Progress,
) -> Result<ReferenceRender, RunError> {
    let start = Instant::now();
    let scene = input.load(&settings.limits)?;
    let ref_scene = reference::RefScene::new(&scene);
    let preprocessing = start.elapsed();
    let options = settings.options(&scene, mode);
    let refuse = |e: tracer::LimitError| RunError::refused(input, &e);
    // Refused before the workers and the progress bar start.
    options
        .limits
        .check_ray_depth(options.max_depth)
        .map_err(refuse)?;
    options
        .limits
        .check_size(u64::from(options.width), u64::from(options.height))
        .map_err(refuse)?;
    let rows = options.sample_rows();
    let workers = Workers::new(workers_for(settings.threads, rows))?;
    progress.begin("tracing (f64 reference)", rows);
    let start = Instant::now();
    let frame = workers.install(|| {
        reference::render::render_converted(&ref_scene, &options, &|n| progress.advance(n))
    });
    let tracing = start.elapsed();
    progress.end();
    let frame = frame.map_err(|e| match e {
        reference::ReferenceError::Limits(e) => RunError::refused(input, &e),
        other => RunError::Render {
            context: input.to_string(),
            message: other.to_string(),
        },
    })?;
    Ok(ReferenceRender {
        scene,
        frame,
        preprocessing,
        tracing,
        threads: workers.threads(),
    })
}

impl ReferenceRender {
    /// The timing report, as the tracer's render prints it: preprocessing vs tracing,
    /// eye rays per second (the reference counts no other rays).
    pub fn timing_report(&self, input: &SceneInput) -> String {
        use reports::format::{count, fixed, plural};
        let eye_rays = u64::from(self.frame.width) * u64::from(self.frame.height);
        let secs = self.tracing.as_secs_f64().max(1e-9);
        format!(
            "{}: {}, f64 reference\npreprocessing {} s (parse + conversion), tracing {} s (with its BVH) on {}\n{} pixels, {} pixels/s",
            input,
            self.scene.summary(),
            fixed(self.preprocessing.as_secs_f64(), 3),
            fixed(self.tracing.as_secs_f64(), 3),
            plural(self.threads, "thread"),
            count(eye_rays),
            count((eye_rays as f64 / secs).round() as u64),
        )
    }
}

/// The f64 reference's picture of a comparison's scene, with the seconds it took.
pub struct ReferencePicture {
    pub image: RgbImage,
    pub seconds: f64,
}

/// Renders `setup`'s scene with its options in its pool with the reference renderer.
pub fn render_in(setup: &RenderSetup<'_>) -> Result<ReferencePicture, RunError> {
    let start = Instant::now();
    let frame = setup
        .pool
        .install(|| {
            let converted = reference::RefScene::new(setup.scene);
            reference::render::render_until(&converted, setup.options, &|_| {}, setup.stop)
        })
        .map_err(|e| match e {
            reference::ReferenceError::Cancelled => RunError::Stopped,
            e => RunError::Render {
                context: setup.name.to_string(),
                message: e.to_string(),
            },
        })?;
    let seconds = start.elapsed().as_secs_f64();
    let image = RgbImage::new(frame.width, frame.height, frame.to_rgb8())?;
    Ok(ReferencePicture { image, seconds })
}

/// How far an image is from the reference's: RMS and maximum of the 8-bit channel
/// differences, PSNR (`None` when identical: infinite).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ImageError {
    pub rms: f64,
    pub psnr: Option<f64>,
    pub max_abs_diff: u8,
}

impl ImageError {
    /// The error of `image` against `truth` (same size).
    pub fn between(truth: &RgbImage, image: &RgbImage) -> Result<Self, RunError> {
        let m = compare(truth, image)?;
        Ok(Self {
            rms: m.rms,
            psnr: m.psnr.is_finite().then_some(m.psnr),
            max_abs_diff: m.max_abs_diff,
        })
    }
}
