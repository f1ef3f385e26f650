//! The report's charts, drawn once with `plotters` (SVG backend) and embedded by both
//! renderers. Each [`Chart`] carries its SVG and that SVG's size.
//!
//! The SVG backend writes text as SVG `<text>` elements, so no font files are needed:
//! the viewer (browser, typst) picks the font. Every chart but the small per-variant
//! histogram has a title inside the SVG, axis titles with units, and category labels
//! drawn here (rotated when they would not fit side by side), so long names never
//! overlap. Function names are shortened to their last two `::` segments.
//!
//! | id | function | data | thesis |
//! |---|---|---|---|
//! | `calls` | [`calls_chart`] | `profile.baseline.flat[].calls` | fig. 51 |
//! | `self-seconds` | [`self_seconds_chart`] | `profile.baseline.flat[].self_seconds` | fig. 52 |
//! | `quality-speed` | [`quality_speed_chart`] | every scene × variant: `speedup`, `quality.rms` | — |
//! | `sw-hw-times` | [`sw_hw_times_chart`] | `scenes[].hardware`: `software_seconds`, `seconds` | fig. 49 |
//! | `hw-speedup` | [`hw_speedup_chart`] | `scenes[].hardware.speedup` | fig. 50 |
//! | `time-vs-primitives` | [`time_vs_primitives_chart`] | baseline `samples` of the `balls`/`cylinder`/`both` scenes, hardware `seconds` | fig. 47, 48 |
//! | `device-utilization` | [`device_utilization_chart`] | `hardware.devices` | — |
//! | `histogram` | [`histogram_chart`] | `histogram` of baseline and the variant with the largest RMS | fig. 35-37 |
//! | `scene-histogram` | [`scene_histograms`] | one scene's `histogram`s that differ from baseline's | — |
//! | `variant-histogram` | [`variant_histogram`] | one variant's `histogram`, for an image grid cell | — |
//! | `roofline` | [`roofline_chart`] | every scene × variant: `efficiency`; `peak` | — |
//! | `bvh-histograms` | [`bvh_histograms`] | one scene's `bvh_quality`: depth and leaf-size histograms | — |
//!
//! [`all`] gives the first eight and the roofline, those the data allows; a chart that
//! fails to draw is replaced by a small SVG that says so.
//!
//! Files: `frame.rs` (backend, title, axes, grid, legend, failure SVG), `scale.rs`
//! (ranges, ticks), `marks.rs` (placed texts, reference lines, whiskers, legend keys),
//! `bars.rs` (bar layout, horizontal bar charts), `categories.rs` (charts over named
//! categories), `style.rs` (sizes, fonts, colours), `data.rs` (the results fields the
//! charts read), `numbers.rs` (number and name formatting); one file per group of
//! charts: `profile.rs`, `quality.rs`, `hardware.rs`, `timing.rs`, `histogram.rs`,
//! `roofline.rs`, `bvh.rs`.

mod bars;
mod bvh;
mod categories;
mod data;
mod frame;
mod hardware;
mod histogram;
mod marks;
mod numbers;
mod profile;
mod quality;
mod roofline;
mod scale;
mod scaling;
mod style;
mod timing;

pub use bvh::bvh_histograms;
pub use hardware::{device_utilization_chart, hw_speedup_chart, sw_hw_times_chart};
pub use histogram::{CELL_SIZE, histogram_chart, scene_histograms, variant_histogram};
pub use numbers::{format_number, short_name};
pub use profile::{calls_chart, self_seconds_chart};
pub use quality::quality_speed_chart;
pub use roofline::roofline_chart;
pub use scaling::scaling_chart;
pub use timing::time_vs_primitives_chart;

use crate::results::Results;

/// One chart: a stable id (for anchors and file names), a title, a caption saying what
/// it shows and where the thesis has it, the SVG document and its size in pixels (the
/// SVG's own `width` and `height`).
#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    pub id: &'static str,
    pub title: String,
    pub caption: String,
    pub svg: String,
    pub width: u32,
    pub height: u32,
}

/// A chart that could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum ChartError {
    #[error("chart '{chart}' could not be drawn: {message}")]
    Draw {
        chart: &'static str,
        message: String,
    },
}

/// Every chart the data allows, in report order.
pub fn all(results: &Results) -> Vec<Chart> {
    [
        calls_chart(results),
        self_seconds_chart(results),
        quality_speed_chart(results),
        sw_hw_times_chart(results),
        hw_speedup_chart(results),
        time_vs_primitives_chart(results),
        device_utilization_chart(results),
        histogram_chart(results),
        roofline_chart(results),
    ]
    .into_iter()
    .flatten()
    .collect()
}

#[cfg(test)]
mod tests;
