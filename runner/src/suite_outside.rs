//! The suite's outside tracers (docs/tracers.md): each measurement into the results
//! entry rtprof's variants have (its picture and heat map saved, judged against the
//! scene's reference variant and the f64 reference when it draws the same scene at
//! the same frame), and a failed one into the run's failures, the reason and the
//! program's last lines of standard error kept.

use std::path::Path;

use analysis::{RgbImage, compare, difference_heat_map, gray_histogram};
use results::{FailedPart, Failure, VariantName, VariantResult};

use crate::collect::quality;
use crate::error::RunError;
use crate::outside::OutsideMeasurement;
use crate::outside::SceneFormat;
use crate::staging::save_png;

/// An outside tracer's results entry; `stem` is its images' path without extension
/// (relative to `out`), `reference` the picture of the scene's reference variant.
pub(crate) fn outside_result(
    out: &Path,
    stem: &str,
    m: OutsideMeasurement,
    reference: Option<&RgbImage>,
    truth: Option<&RgbImage>,
) -> Result<VariantResult, RunError> {
    let image_rel = save_png(out, &format!("{stem}.png"), &m.image)?;
    let same_frame = |other: &RgbImage| {
        m.prepared.def.scene != SceneFormat::Own
            && (other.width, other.height) == (m.image.width, m.image.height)
    };
    let (quality_vs_reference, heat_map) = match reference {
        Some(base) if same_frame(base) => {
            let heat = difference_heat_map(base, &m.image)?;
            let heat_rel = save_png(out, &format!("{stem}-diff.png"), &heat)?;
            (Some(quality(&compare(base, &m.image)?)), Some(heat_rel))
        }
        _ => (None, None),
    };
    let vs_f64_reference = match truth {
        Some(truth) if same_frame(truth) => Some(quality(&compare(truth, &m.image)?)),
        _ => None,
    };
    // Judged against the truth where the f64 reference ran, else the reference variant.
    let outside = m.record(truth.or(reference))?;
    let counts = m
        .prepared
        .counts()
        .map(|c| crate::collect::count_map(&c))
        .unwrap_or_default();
    Ok(VariantResult {
        variant: m.name,
        time: m.time,
        samples: m.samples,
        cpu_samples: m.cpu_samples,
        // Its preparation is in its time or not, as its definition says.
        preprocessing_seconds: None,
        // Filled for the whole run by results::change::fill_speedups.
        speedup: None,
        speedup_interval: None,
        verdict: None,
        counts,
        image: Some(image_rel),
        heat_map,
        quality: quality_vs_reference,
        vs_f64_reference,
        histogram: gray_histogram(&m.image).to_vec(),
        lane_utilization: None,
        efficiency: None,
        ray_rates: None,
        outside: Some(outside),
    })
}

/// A failed outside tracer as one of the run's failures: stopped runs stop the suite.
pub(crate) fn outside_failure(scene: &str, error: RunError) -> Result<Failure, RunError> {
    let (tracer, message) = match error {
        RunError::Stopped => return Err(RunError::Stopped),
        RunError::Outside { tracer, failure } => (tracer, failure.describe()),
        other => ("?".to_string(), other.to_string()),
    };
    let part = VariantName::outside(&tracer).map_or(FailedPart::Scene, FailedPart::Variant);
    Ok(Failure {
        scene: Some(scene.to_string()),
        part,
        message: format!("tracer {tracer}: {message}"),
    })
}
