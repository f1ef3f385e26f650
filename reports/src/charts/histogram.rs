//! Gray-level histograms (thesis fig. 35-37): several variants' step lines over one
//! another ([`histogram_chart`], [`scene_histograms`]), and one variant's histogram as a
//! small filled chart for an image grid's cell ([`variant_histogram`]). All on a log
//! count axis with empty bins at the bottom.

use plotters::prelude::*;

use super::Chart;
use super::data::{gray_histogram, is_reference, reference, rms, variant_name, variant_place};
use super::frame::render;
use super::marks::{Key, keyed};
use super::scale::{Axis, Ticks};
use super::style::{HEIGHT, WIDTH, variant_colour};
use crate::results::{Results, SceneResult, VariantResult};

/// The count an empty bin is drawn at (below 1, the smallest non-empty count).
const EMPTY: f64 = 0.8;
/// Size of [`variant_histogram`]: a pixel per gray level.
pub const CELL_SIZE: (u32, u32) = (256, 82);
const CELL_FILL: RGBColor = RGBColor(85, 85, 85);
const CELL_BACKGROUND: RGBColor = RGBColor(250, 250, 250);
const CELL_BORDER: RGBColor = RGBColor(204, 204, 204);

/// The histogram chart of [`all`](super::all): the scene and variant with the largest
/// RMS error, over baseline's.
pub fn histogram_chart(results: &Results) -> Option<Chart> {
    let (scene, variant, error) = results
        .scenes
        .iter()
        .flat_map(|s| s.variants.iter().map(move |v| (s, v)))
        .filter(|(_, v)| gray_histogram(v).is_some())
        .filter_map(|(s, v)| rms(v).map(|e| (s, v, e)))
        .max_by(|a, b| a.2.total_cmp(&b.2))?;
    let base = reference(results, scene)?;
    let caption = format!(
        "Thesis fig. 35-37. Gray-level histograms of {} rendered by baseline and by {} (the largest RMS error of the run, {error:.1}); log scale, empty bins drawn at the bottom.",
        scene.name,
        variant_name(variant),
    );
    overlaid(
        results,
        scene,
        &[base, variant],
        ("histogram", caption),
        (WIDTH, HEIGHT),
    )
}

/// Gray histograms of one scene: baseline and every variant whose histogram differs
/// from it (the figure under a scene's images).
pub fn scene_histograms(results: &Results, scene: &SceneResult) -> Option<Chart> {
    let base = reference(results, scene)?;
    let mut shown = vec![base];
    shown.extend(
        scene
            .variants
            .iter()
            .filter(|v| !is_reference(v) && gray_histogram(v).is_some_and(|h| h != base.histogram)),
    );
    let hidden: Vec<&str> = scene
        .variants
        .iter()
        .filter(|v| !is_reference(v) && !shown.iter().any(|s| variant_name(s) == variant_name(v)))
        .map(variant_name)
        .collect();
    let caption = if hidden.is_empty() {
        format!("Gray-level histograms of {}.", scene.name)
    } else {
        format!(
            "Gray-level histograms of {}; not drawn, because their histogram equals baseline's: {}.",
            scene.name,
            hidden.join(", ")
        )
    };
    overlaid(
        results,
        scene,
        &shown,
        ("scene-histogram", caption),
        (640, 300),
    )
}

/// One variant's gray histogram, [`CELL_SIZE`] pixels: a gray area on a framed light
/// background, without text (the grid cell names the variant), for image grids. `None`
/// when the variant has no histogram or every bin is empty.
pub fn variant_histogram(scene: &SceneResult, variant: &VariantResult) -> Option<Chart> {
    let bins = gray_histogram(variant)?;
    let top = bins.iter().copied().max().filter(|m| *m > 0)? as f64;
    let outline = steps(bins);
    Some(render(
        "variant-histogram",
        format!(
            "Gray histogram of {} rendered by {}",
            scene.name,
            variant_name(variant)
        ),
        "Gray levels 0-255 left to right; pixels on a log scale, empty bins at the bottom."
            .to_string(),
        CELL_SIZE,
        move |canvas| {
            let (w, h) = (CELL_SIZE.0 as i32, CELL_SIZE.1 as i32);
            let page = [(0, 0), (w, h)];
            // The border's stroke is centred on the last pixel row and column.
            let frame = [(0, 0), (w - 1, h - 1)];
            canvas
                .root
                .draw(&Rectangle::new(page, CELL_BACKGROUND.filled()))?;
            let mut plot = canvas.bare_plot(0.0..256.0, (EMPTY..top).log_scale())?;
            let area = [(0.0, EMPTY)]
                .into_iter()
                .chain(outline)
                .chain([(256.0, EMPTY)]);
            plot.chart
                .draw_series([Polygon::new(area.collect::<Vec<_>>(), CELL_FILL.filled())])?;
            canvas
                .root
                .draw(&Rectangle::new(frame, CELL_BORDER.stroke_width(1)))?;
            Ok(())
        },
    ))
}

/// The step outline of a histogram: for each bin its two upper corners, empty bins at
/// [`EMPTY`].
fn steps(bins: &[u64]) -> impl Iterator<Item = (f64, f64)> + '_ {
    bins.iter().enumerate().flat_map(|(bin, count)| {
        let y = (*count as f64).max(EMPTY);
        [(bin as f64, y), (bin as f64 + 1.0, y)]
    })
}

/// Step lines of the 256-bin gray histograms of `variants` of `scene` over one another
/// (those without a histogram left out), log y; `None` when every bin is empty.
fn overlaid(
    results: &Results,
    scene: &SceneResult,
    variants: &[&VariantResult],
    (id, caption): (&'static str, String),
    size: (u32, u32),
) -> Option<Chart> {
    let lines: Vec<(&str, RGBColor, &[u64], u32)> = variants
        .iter()
        .filter_map(|v| {
            let colour = variant_colour(variant_place(results, v));
            let width = if is_reference(v) { 2 } else { 1 };
            gray_histogram(v).map(|bins| (variant_name(v), colour, bins, width))
        })
        .collect();
    let max = lines
        .iter()
        .flat_map(|l| l.2.iter().copied())
        .max()
        .filter(|m| *m > 0)?;
    let hi = 10f64.powf((max as f64).log10().ceil()).max(10.0);
    Some(render(
        id,
        format!("Gray histograms of {}", scene.name),
        caption,
        size,
        move |canvas| {
            let x = Axis::linear(0.0, 256.0, Ticks::Whole, "gray level (0-255)", 46);
            let y = Axis::log((EMPTY, hi), "", None, "pixels (log scale)", 56);
            let mut plot = canvas.plot(x, y)?;
            for (name, colour, bins, width) in &lines {
                let anno = plot
                    .chart
                    .draw_series(LineSeries::new(steps(bins), colour.stroke_width(*width)))?;
                keyed(anno, name, Key::Line(*colour));
            }
            plot.legend(SeriesLabelPosition::UpperRight)
        },
    ))
}
