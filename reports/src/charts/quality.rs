//! Image error against speed-up: one point per scene and variant, with the thesis's
//! RMS bands.

use plotters::prelude::*;

use super::Chart;
use super::data::{rms, rms_bands, speedup, variant_name, variant_place};
use super::frame::render;
use super::marks::{Dashed, Key, Place, keyed};
use super::scale::{Axis, Ticks, finite_positive};
use super::style::{GUIDE, GUIDE_TEXT, HEIGHT, WIDTH, variant_colour};
use crate::results::{Results, VariantResult};

/// Speed-up against image error, one point per scene × variant.
pub fn quality_speed_chart(results: &Results) -> Option<Chart> {
    let points: Vec<(&VariantResult, f64, f64)> = results
        .scenes
        .iter()
        .flat_map(|s| &s.variants)
        .filter_map(|v| {
            let error = rms(v).filter(|r| *r >= 0.0)?;
            finite_positive(speedup(v)).then_some((v, speedup(v), error))
        })
        .collect();
    if points.is_empty() {
        return None;
    }
    // One series per variant, in order of first appearance.
    let mut series: Vec<&VariantResult> = Vec::new();
    for (v, _, _) in &points {
        if !series.iter().any(|s| variant_name(s) == variant_name(v)) {
            series.push(v);
        }
    }
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
    let (lo, hi) = (lo.min(1.0) * 0.8, hi.max(1.0) * 1.25);
    let rms_max = points.iter().map(|p| p.2).fold(20.0, f64::max) * 1.12;
    let guide = |dash| Dashed {
        colour: GUIDE,
        width: 1,
        dash,
        gap: dash,
    };
    Some(render(
        "quality-speed",
        "Image error against speed-up".to_string(),
        "One point per scene and variant: speed-up over baseline (log scale) against the RMS error of the image; dashed lines are the thesis's bands (table 2: below 15 visually identical, 15-50 similar, 50-85 notable changes).".to_string(),
        (WIDTH, HEIGHT),
        move |canvas| {
            let x = Axis::log((lo, hi), "×", Some(30), "speed-up over baseline (×, log scale)", 46);
            let y = Axis::linear(0.0, rms_max, Ticks::Numbers, "RMS error against baseline (gray levels)", 56);
            let mut plot = canvas.plot(x, y)?;
            for (limit, name) in rms_bands().filter(|(limit, _)| *limit < rms_max) {
                plot.dashed([(lo, limit), (hi, limit)], Dashed { gap: 4, ..guide(6) })?;
                plot.text(&format!("{name} below"), (lo, limit), Place::BelowRight, GUIDE_TEXT)?;
            }
            plot.dashed([(1.0, 0.0), (1.0, rms_max)], guide(3))?;
            for first in &series {
                let colour = variant_colour(variant_place(results, first));
                let name = variant_name(first);
                let anno = plot.chart.draw_series(
                    points
                        .iter()
                        .filter(|p| variant_name(p.0) == name)
                        .map(|p| Circle::new((p.1, p.2), 5, colour.mix(0.85).filled())),
                )?;
                keyed(anno, name, Key::Dot(colour));
            }
            plot.legend(SeriesLabelPosition::UpperRight)
        },
    ))
}
