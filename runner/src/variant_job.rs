//! The variant job: one variant set on one scene, measured the one way rtprof
//! measures: a counted render first (exact counts; it also warms caches and the
//! thread pool up), then the timed uncounted renders under the timing policy. The
//! last timed frame is the variant's image.

use std::sync::atomic::AtomicBool;

use analysis::RgbImage;
use tracer::{Count, Counts, NoCount, RenderOptions, Scene, VariantSet, render_variant};

use crate::error::RunError;
use crate::timing::{TimingPolicy, measure};

/// A measured variant.
pub struct VariantMeasurement {
    pub variants: VariantSet,
    /// Tracing seconds of each timed render.
    pub samples: Vec<f64>,
    /// Median and interval of `samples`.
    pub time: analysis::Estimate,
    /// Median preprocessing seconds (reported apart from the time).
    pub preprocessing: f64,
    /// Exact counts of one render.
    pub counts: Counts,
    /// The picture.
    pub image: RgbImage,
}

/// Where and how to render.
pub struct RenderSetup<'a> {
    pub scene: &'a Scene,
    /// The scene's name in messages.
    pub name: &'a str,
    pub options: &'a RenderOptions,
    pub pool: &'a rayon::ThreadPool,
    pub stop: &'a AtomicBool,
}

impl RenderSetup<'_> {
    /// Counts, times and pictures `set`.
    pub fn measure(
        &self,
        set: &VariantSet,
        policy: &TimingPolicy,
    ) -> Result<VariantMeasurement, RunError> {
        let fail = |e: tracer::RenderError| RunError::render(self.name, &e);
        let counted = self
            .pool
            .install(|| render_variant::<Count>(self.scene, self.options, set, &|_| {}))
            .map_err(fail)?;
        let counts = counted.rendered.counts().ok_or_else(|| RunError::Render {
            context: self.name.to_string(),
            message: "the counted render returned no counts".into(),
        })?;
        let measured = measure(policy, self.stop, || {
            self.pool
                .install(|| render_variant::<NoCount>(self.scene, self.options, set, &|_| {}))
                .map_err(fail)
        })?;
        let frame = &measured.last.rendered.frame;
        let image = RgbImage::new(frame.width, frame.height, frame.to_rgb8())?;
        Ok(VariantMeasurement {
            variants: set.clone(),
            samples: measured.samples,
            time: measured.time,
            preprocessing: measured.preprocessing,
            counts,
            image,
        })
    }
}
