//! The roofline chart (Williams, Waterman and Patterson, 2009): every render as a point
//! of attained GFLOP/s against arithmetic intensity (flops per byte read), log-log,
//! under the machine's roof: the lower of its measured compute peak and its bandwidth
//! times the intensity. One colour per variant; the scenes share the plot, so a
//! variant's cloud shows how its intensity and speed move with the scene.

use std::cell::Cell;

use plotters::coord::ranged1d::Ranged;
use plotters::prelude::*;

use super::Chart;
use super::data::{RooflinePoint, machine_peak, roofline_points, variant_name, variant_place};
use super::frame::{DrawResult, Plot, render};
use super::marks::{Dashed, Key, Place, keyed};
use super::scale::{Axis, log_range, tight_log_range};
use super::style::{GUIDE, GUIDE_TEXT, HEIGHT, INK, WIDTH, variant_colour};
use crate::format;
use crate::results::{MachinePeak, Results, VariantResult};

/// DRAM's roof: a second, dashed ink, so that it reads as the lesser limit.
const DRAM: RGBColor = RGBColor(110, 110, 110);

/// Where the chart puts its data: the axes' ranges and the plot's pixel edges, so a
/// test can tell where a point must be drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct RooflineScale {
    /// Flop/byte at the left and right edges.
    pub intensity: (f64, f64),
    /// GFLOP/s at the bottom and top edges.
    pub gflops: (f64, f64),
    /// Pixel columns of the left and right edges.
    pub columns: (f64, f64),
    /// Pixel rows of the top and bottom edges.
    pub rows: (f64, f64),
}

/// Attained GFLOP/s against arithmetic intensity for every render with a roofline
/// point, under the roof when the run measured the machine's peaks.
pub fn roofline_chart(results: &Results) -> Option<Chart> {
    roofline_with_scale(results).map(|(chart, _)| chart)
}

/// [`roofline_chart`] and the scale it was drawn at.
pub(super) fn roofline_with_scale(results: &Results) -> Option<(Chart, RooflineScale)> {
    let points = roofline_points(results);
    if points.is_empty() {
        return None;
    }
    let peak = machine_peak(results).cloned();
    // Both ridges in view: where the L1 and the DRAM slopes meet the peak.
    let ridges: Vec<f64> = peak
        .iter()
        .flat_map(|p| [p.ridge_intensity(), p.peak_gflops / p.bandwidth_gbs])
        .collect();
    // Each axis from the decade below the data (plotters labels a log axis from its
    // first power of ten on) to just past the data and the roofs' bends.
    let span = |values: Vec<f64>| -> Option<(f64, f64)> {
        let (lo, _) = log_range(values.iter().copied())?;
        let (_, hi) = tight_log_range(values)?;
        Some((lo, hi))
    };
    let (x_lo, x_hi) = span(points.iter().map(|p| p.intensity).chain(ridges).collect())?;
    // Twice the peak: room above the roof for its label.
    let top = peak.as_ref().map(|p| p.peak_gflops * 2.0);
    let (y_lo, y_hi) = span(points.iter().map(|p| p.gflops).chain(top).collect())?;
    let mut series: Vec<&VariantResult> = Vec::new();
    for p in &points {
        if !series
            .iter()
            .any(|s| variant_name(s) == variant_name(p.variant))
        {
            series.push(p.variant);
        }
    }
    let caption = match &peak {
        Some(_) => {
            "One point per scene and variant: the counted floating-point operations over the median tracing time, against the flops per byte the render asks of the memory system, wherever they are found (the cache-aware roofline). The roof is the lower of the machine's compute peak (FMA kernel) and its L1 bandwidth (STREAM triad within the cache) times the intensity; left of the dotted ridge a render is bandwidth-bound, right of it compute-bound. Dashed: the DRAM bandwidth's roof; a point above it read most of its records from the caches."
        }
        None => {
            "One point per scene and variant: the counted floating-point operations over the median tracing time, against the flops per byte the render is estimated to read. The machine's peaks were not measured in this run: no roof."
        }
    };
    let scale = Cell::new(RooflineScale::default());
    let drawn = &scale;
    let chart = render(
        "roofline",
        "Roofline: attained GFLOP/s against arithmetic intensity".to_string(),
        caption.to_string(),
        (WIDTH, HEIGHT + 40),
        move |canvas| {
            let x = Axis::log(
                (x_lo, x_hi),
                "",
                Some(30),
                "arithmetic intensity (flop/byte, log scale)",
                46,
            );
            let y = Axis::log(
                (y_lo, y_hi),
                "",
                Some(30),
                "attained GFLOP/s (log scale)",
                56,
            );
            let mut plot = canvas.plot(x, y)?;
            let (columns, rows) = plot.chart.plotting_area().get_pixel_range();
            drawn.set(RooflineScale {
                intensity: (x_lo, x_hi),
                gflops: (y_lo, y_hi),
                columns: (f64::from(columns.start), f64::from(columns.end - 1)),
                rows: (f64::from(rows.start), f64::from(rows.end - 1)),
            });
            if let Some(peak) = &peak {
                draw_roof(&mut plot, peak, y_lo)?;
            }
            for first in &series {
                let colour = variant_colour(variant_place(results, first));
                let name = variant_name(first);
                let mine = points.iter().filter(|p| variant_name(p.variant) == name);
                let anno = plot.chart.draw_series(mine.map(|p: &RooflinePoint| {
                    Circle::new((p.intensity, p.gflops), 4, colour.mix(0.85).filled())
                }))?;
                keyed(anno, name, Key::Dot(colour));
            }
            // The lower right is high intensity at low speed, where renders rarely
            // are (the ray tracer's intensities lie far left of DRAM's ridge, which
            // the axis reaches); the upper left holds the steep L1 roof's label.
            plot.legend(SeriesLabelPosition::LowerRight)
        },
    );
    Some((chart, scale.get()))
}

/// The roofs with their labels: compute peak and the bandwidth that bounds the
/// render's bytes (L1's, solid), DRAM's slope dashed below it when it was measured
/// apart, and the ridge where the solid roofs meet, faint.
fn draw_roof<X, Y>(plot: &mut Plot<'_, '_, X, Y>, peak: &MachinePeak, y_lo: f64) -> DrawResult
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let (x_lo, x_hi) = (plot.chart.x_range().start, plot.chart.x_range().end);
    let bandwidth = peak.roof_bandwidth_gbs();
    let ridge = peak.ridge_intensity();
    // A sloped roof enters the plot at its left edge or through its floor.
    let entry = |gbs: f64| x_lo.max(y_lo / gbs);
    let start = entry(bandwidth);
    let roof = [
        (start, bandwidth * start),
        (ridge, peak.peak_gflops),
        (x_hi, peak.peak_gflops),
    ];
    plot.chart
        .draw_series(LineSeries::new(roof, INK.stroke_width(2)))?;
    plot.text(
        &format!("peak {} GFLOP/s", format::significant(peak.peak_gflops)),
        (ridge, peak.peak_gflops),
        Place::AboveRight,
        INK,
    )?;
    let cache = peak.cache_bandwidth_gbs > 0.0;
    let slope_label = |level: &str, gbs: f64| format!("{level}{} GB/s", format::significant(gbs));
    // A third of the way up the slope, on its empty side.
    let at = start * (ridge / start).powf(0.35);
    plot.text(
        &slope_label(if cache { "L1 " } else { "" }, bandwidth),
        (at, bandwidth * at),
        Place::AboveLeft,
        INK,
    )?;
    if cache && peak.bandwidth_gbs < bandwidth {
        // DRAM's slope up to where it meets the peak: a render above it read most of
        // its records from the caches.
        let dram_ridge = peak.peak_gflops / peak.bandwidth_gbs;
        let from = entry(peak.bandwidth_gbs);
        let to = dram_ridge.min(x_hi);
        plot.dashed(
            [
                (from, peak.bandwidth_gbs * from),
                (to, peak.bandwidth_gbs * to),
            ],
            Dashed {
                colour: DRAM,
                width: 2,
                dash: 6,
                gap: 4,
            },
        )?;
        let at = from * (to / from).powf(0.75);
        plot.text(
            &slope_label("DRAM ", peak.bandwidth_gbs),
            (at, peak.bandwidth_gbs * at),
            Place::AboveLeft,
            DRAM,
        )?;
    }
    plot.dashed(
        [(ridge, y_lo), (ridge, peak.peak_gflops)],
        Dashed {
            colour: GUIDE,
            width: 1,
            dash: 3,
            gap: 3,
        },
    )?;
    plot.text(
        &format!("ridge {} flop/byte", format::significant(ridge)),
        (ridge, y_lo),
        Place::AboveRight,
        GUIDE_TEXT,
    )
}
