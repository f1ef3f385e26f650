//! What a job would cost, said before Run: the scene's primitive count and, when its
//! baseline (every job's reference, a brute-force render) would be slow, how long one
//! render takes by `runner::estimate::brute_force`, the estimate `rtprof render` prints.

use std::collections::HashMap;
use std::path::Path;

use reports::format;
use runner::scene_input::SceneInput;
use serde::Serialize;
use tracer::{Limits, RenderOptions, Sampling, ShadingMode, VariantSet};

use crate::catalogue::Catalogue;
use crate::error::ApiError;

/// The estimate as the page shows it.
#[derive(Clone, Debug, Serialize)]
pub struct Estimate {
    pub primitives: u64,
    /// "91 primitives".
    pub primitives_text: String,
    /// One render of baseline (brute force) at the size: "about 2 min", or `None` when
    /// it takes under `runner::estimate::WORTH_A_NOTE` or the scene is small.
    pub brute_force: Option<String>,
    /// The sentence for the page.
    pub text: String,
}

/// The estimate of `?scene=ID&width=W&height=H` (`&threads=N`).
pub fn of_query(
    catalogue: &Catalogue,
    query: &HashMap<String, String>,
) -> Result<Estimate, ApiError> {
    let scene_id = query
        .get("scene")
        .ok_or_else(|| ApiError::invalid("give ?scene=ID&width=W&height=H (no scene)"))?;
    let number = |key: &str| -> Result<Option<u64>, ApiError> {
        query
            .get(key)
            .map(|v| {
                v.parse::<u64>()
                    .map_err(|_| ApiError::invalid(format!("{key} '{v}' is not a whole number")))
            })
            .transpose()
    };
    let (width, height) = match (number("width")?, number("height")?) {
        (Some(w), Some(h)) => (w, h),
        _ => return Err(ApiError::invalid("give ?scene=ID&width=W&height=H")),
    };
    let limits = Limits::default();
    limits
        .check_size(width, height)
        .map_err(|e| ApiError::invalid(format!("size {width}x{height}: {e}")))?;
    let threads = number("threads")?
        .map(runner::pool::check_threads)
        .transpose()
        .map_err(|e| ApiError::invalid(e.to_string()))?;
    let entry = catalogue.resolve(scene_id)?;
    let input = SceneInput::parse(&entry, Path::new("/nonexistent/rtprof-serve"))
        .map_err(|e| ApiError::invalid(e.to_string()))?;
    let scene = input
        .load(&limits)
        .map_err(|e| ApiError::invalid(e.to_string()))?;
    // The checks above keep both sides within the limits, far below u32::MAX.
    let (w, h) = (
        u32::try_from(width).unwrap_or(u32::MAX),
        u32::try_from(height).unwrap_or(u32::MAX),
    );
    let options = RenderOptions::new(w, h, Sampling::PixelCenters, ShadingMode::Color);
    // A job's timed renders run on one thread unless it asks for more.
    let threads = threads.or(Some(1));
    let estimate = runner::estimate::brute_force(&scene, &options, &VariantSet::default(), threads)
        .map_err(|e| ApiError::internal(e.to_string()))?;
    let primitives = scene.primitive_count() as u64;
    let primitives_text = reports::page_values::primitives(primitives);
    let slow = estimate.filter(|e| e.seconds > runner::estimate::WORTH_A_NOTE.as_secs_f64());
    let brute_force = slow.map(|e| format::rough_duration(e.seconds));
    let size = format::size(w, h);
    let text = match (&estimate, &brute_force) {
        (_, Some(time)) => format!(
            "{primitives_text}; one brute-force render of baseline at {size}: {time} (a job renders it several times; bvh is usually far faster)"
        ),
        (Some(_), None) => format!(
            "{primitives_text}; one brute-force render of baseline at {size}: under {}",
            format::seconds(runner::estimate::WORTH_A_NOTE.as_secs_f64())
        ),
        (None, None) => format!(
            "{primitives_text}: under {} primitives, brute force is quick",
            format::count(runner::estimate::MANY_PRIMITIVES as u64)
        ),
    };
    Ok(Estimate {
        primitives,
        primitives_text,
        brute_force,
        text,
    })
}
