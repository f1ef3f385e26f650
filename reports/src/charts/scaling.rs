//! The growth study's chart: time per ray against primitives, log-log, one line per
//! family and accelerator (colour: accelerator; the family's name and the fitted
//! exponent in the legend), extrapolated stretches dashed.

use plotters::prelude::*;

use super::Chart;
use super::frame::render;
use super::marks::{Dashed, Key, Place, keyed};
use super::scale::{Axis, log_range};
use super::style::{HEIGHT, PALETTE, WIDTH};
use crate::results::scaling::{ScalingPoint, ScalingStudy};

/// Time per ray against primitive count for every family and accelerator.
pub fn scaling_chart(study: &ScalingStudy) -> Option<Chart> {
    let usable = |p: &&ScalingPoint| p.seconds_per_ray.is_finite() && p.seconds_per_ray > 0.0;
    let points: Vec<&ScalingPoint> = study.points.iter().filter(usable).collect();
    let (x_lo, x_hi) = log_range(points.iter().map(|p| p.primitives as f64))?;
    let (y_lo, y_hi) = log_range(points.iter().map(|p| p.seconds_per_ray * 1e9))?;
    let mut accelerators: Vec<&str> = Vec::new();
    for p in &points {
        if !accelerators.contains(&p.accelerator.as_str()) {
            accelerators.push(&p.accelerator);
        }
    }
    let series: Vec<(String, String)> = study
        .fits
        .iter()
        .map(|f| (f.family.clone(), f.accelerator.clone()))
        .collect();
    let exponent = |family: &str, accel: &str| {
        study
            .fits
            .iter()
            .find(|f| f.family == family && f.accelerator == accel)
            .map(|f| f.exponent)
    };
    Some(render(
        "scaling",
        "Time per ray against scene size".to_string(),
        "Tracing time per ray (ns, log scale) against the primitives of SPD scenes generated at growing size factors, one line per scene family and accelerator; b is the fitted exponent (time per ray ∝ N^b); dashed: extrapolated with that law, not measured.".to_string(),
        (WIDTH, HEIGHT + 60),
        move |canvas| {
            let x = Axis::log((x_lo, x_hi), "", Some(30), "primitives in the scene (log scale)", 46);
            let y = Axis::log((y_lo, y_hi * 3.0), "", Some(30), "time per ray (ns, log scale)", 64);
            let mut plot = canvas.plot(x, y)?;
            for (family, accel) in &series {
                let colour = PALETTE[accelerators.iter().position(|a| a == accel).unwrap_or(0) % PALETTE.len()];
                let mine: Vec<&&ScalingPoint> = points
                    .iter()
                    .filter(|p| &p.family == family && &p.accelerator == accel)
                    .collect();
                let measured: Vec<(f64, f64)> = mine
                    .iter()
                    .filter(|p| p.measured)
                    .map(|p| (p.primitives as f64, p.seconds_per_ray * 1e9))
                    .collect();
                let label = match exponent(family, accel) {
                    Some(b) => format!("{accel} · {family} (b = {b:.2})"),
                    None => format!("{accel} · {family}"),
                };
                let anno = plot
                    .chart
                    .draw_series(LineSeries::new(measured.clone(), colour.stroke_width(2)))?;
                keyed(anno, &label, Key::Line(colour));
                plot.chart.draw_series(
                    measured.iter().map(|&(x, y)| Circle::new((x, y), 3, colour.filled())),
                )?;
                // From the last measured point on through the extrapolated ones.
                let mut extrapolated: Vec<(f64, f64)> = measured.last().copied().into_iter().collect();
                extrapolated.extend(
                    mine.iter()
                        .filter(|p| !p.measured)
                        .map(|p| (p.primitives as f64, p.seconds_per_ray * 1e9)),
                );
                // The family's name at the line's end: the colours tell accelerators.
                if let Some(&end) = extrapolated.last() {
                    plot.text(family, end, Place::Right, colour)?;
                }
                if extrapolated.len() > 1 {
                    plot.dashed(
                        extrapolated,
                        Dashed {
                            colour,
                            width: 2,
                            dash: 6,
                            gap: 4,
                        },
                    )?;
                }
            }
            plot.legend(SeriesLabelPosition::UpperLeft)
        },
    ))
}
