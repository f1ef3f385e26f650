//! Render time against primitive count: box plots of the timed repeats per test-bench
//! family, with the hardware model's time (thesis fig. 47, 48).

use analysis::timing::quantile_of_sorted;
use plotters::prelude::*;

use super::Chart;
use super::bars::Slots;
use super::categories::{Categories, category_chart};
use super::data::{finite_hardware_times, reference, time_samples};
use super::marks::{Dashed, Key, cap, keyed, stem};
use super::scale::{Axis, finite_positive, tight_log_range};
use super::style::{INK, PALETTE};
use crate::results::{Results, SceneFamily};

/// The test-bench families, in drawing order.
const FAMILIES: [SceneFamily; 3] = SceneFamily::TEST_BENCHES;
/// The test-bench primitive counts.
const COUNTS: std::ops::RangeInclusive<u64> = 1..=7;
/// The families' boxes at a count.
const BOX_SLOTS: Slots = Slots {
    groups: FAMILIES.len(),
    span: 0.76,
    gap: 0.05,
};

/// Box-plot statistics with Tukey whiskers (the farthest sample within 1.5 IQR).
#[derive(Debug, PartialEq)]
struct BoxStats {
    low_whisker: f64,
    q1: f64,
    median: f64,
    q3: f64,
    high_whisker: f64,
    outliers: Vec<f64>,
}

/// The box of the finite positive `samples`, if there are any.
fn box_stats(samples: &[f64]) -> Option<BoxStats> {
    let mut s: Vec<f64> = samples
        .iter()
        .copied()
        .filter(|v| finite_positive(*v))
        .collect();
    if s.is_empty() {
        return None;
    }
    s.sort_by(f64::total_cmp);
    let [q1, median, q3] = [0.25, 0.5, 0.75].map(|p| quantile_of_sorted(&s, p));
    let iqr = q3 - q1;
    let fences = q1 - 1.5 * iqr..=q3 + 1.5 * iqr;
    let (inside, outliers): (Vec<f64>, Vec<f64>) = s.into_iter().partition(|v| fences.contains(v));
    Some(BoxStats {
        low_whisker: inside.first().copied().unwrap_or(q1),
        q1,
        median,
        q3,
        high_whisker: inside.last().copied().unwrap_or(q3),
        outliers,
    })
}

/// Baseline render time against primitive count, box plots per test-bench family, with
/// the hardware model's time (thesis fig. 47, 48).
pub fn time_vs_primitives_chart(results: &Results) -> Option<Chart> {
    // (family, count, box)
    let mut boxes: Vec<(usize, u64, BoxStats)> = Vec::new();
    for (f, family) in FAMILIES.iter().enumerate() {
        for count in COUNTS {
            let samples: Vec<f64> = results
                .scenes
                .iter()
                .filter(|s| s.family == *family && s.primitives == count)
                .filter_map(|s| reference(results, s))
                .flat_map(time_samples)
                .collect();
            if let Some(stats) = box_stats(&samples) {
                boxes.push((f, count, stats));
            }
        }
    }
    if boxes.is_empty() {
        return None;
    }
    let hardware = finite_hardware_times(results, COUNTS);
    let values = boxes
        .iter()
        .flat_map(|(_, _, b)| {
            [b.low_whisker, b.high_whisker]
                .into_iter()
                .chain(b.outliers.iter().copied())
        })
        .chain(hardware.iter().map(|h| h.1));
    let (lo, hi) = tight_log_range(values)?;
    let counts = Categories::fitted(
        COUNTS.map(|n| n.to_string()).collect(),
        1.0,
        "primitives in the scene",
    );
    Some(category_chart(
        (
            "time-vs-primitives",
            "Render time against primitive count".to_string(),
            "Thesis fig. 47, 48. Boxes: the timed repeats of the baseline render of the test-bench scenes (balls: spheres, cylinder: cylinders, both: mixed), quartiles and whiskers at 1.5 IQR; line: the hardware model's frame time, which depends on the count only (eq. 49). Log scale.".to_string(),
        ),
        counts,
        // Room above the boxes for the legend.
        Axis::log((lo, hi * 4.0), "", Some(30), "render time (s, log scale)", 64),
        move |plot| {
            for (f, family) in FAMILIES.iter().enumerate() {
                let colour = PALETTE[f];
                let mine: Vec<(usize, &BoxStats)> = boxes
                    .iter()
                    .filter(|b| b.0 == f)
                    .map(|(_, count, b)| (*count as usize, b))
                    .collect();
                if mine.is_empty() {
                    continue;
                }
                let anno = plot.chart.draw_series(mine.iter().map(|(count, b)| {
                    let (x0, x1) = BOX_SLOTS.extent(*count, f);
                    Rectangle::new([(x0, b.q1), (x1, b.q3)], colour.mix(0.35).filled())
                }))?;
                keyed(anno, family.name(), Key::Box(colour));
                plot.chart.draw_series(mine.iter().flat_map(|(count, b)| {
                    box_outline(BOX_SLOTS.extent(*count, f), b, colour)
                }))?;
                plot.chart.draw_series(mine.iter().flat_map(|(count, b)| {
                    let x = BOX_SLOTS.centre(*count, f);
                    b.outliers.iter().map(move |v| Circle::new((x, *v), 3, colour.stroke_width(1)))
                }))?;
            }
            if !hardware.is_empty() {
                let line = Dashed { colour: INK, width: 2, dash: 6, gap: 4 };
                let anno = plot.dashed(hardware.iter().map(|(n, s)| (*n as f64, *s)), line)?;
                keyed(anno, "hardware model (eq. 49)", Key::Line(INK));
                plot.chart.draw_series(hardware.iter().map(|(n, s)| Circle::new((*n as f64, *s), 3, INK.filled())))?;
            }
            plot.legend(SeriesLabelPosition::UpperLeft)
        },
    ))
}

/// The lines of a box from `x0` to `x1`: frame, median (bold) and whiskers with caps.
fn box_outline(
    (x0, x1): (f64, f64),
    b: &BoxStats,
    colour: RGBColor,
) -> Vec<PathElement<(f64, f64)>> {
    let x = (x0 + x1) / 2.0;
    let thin = colour.stroke_width(1);
    let frame = vec![(x0, b.q1), (x1, b.q1), (x1, b.q3), (x0, b.q3), (x0, b.q1)];
    vec![
        PathElement::new(frame, thin),
        PathElement::new(vec![(x0, b.median), (x1, b.median)], colour.stroke_width(2)),
        stem(x, (b.q3, b.high_whisker), thin),
        stem(x, (b.q1, b.low_whisker), thin),
        cap(x, b.high_whisker, thin),
        cap(x, b.low_whisker, thin),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boxes_follow_tukey() {
        let mut samples: Vec<f64> = (1..=9).map(f64::from).collect();
        samples.push(25.0);
        samples.push(f64::NAN);
        let b = box_stats(&samples).expect("a box");
        assert_eq!((b.q1, b.median, b.q3), (3.25, 5.5, 7.75));
        // Fences at -3.5 and 14.5: 25 is an outlier, 9 the top whisker.
        assert_eq!((b.low_whisker, b.high_whisker), (1.0, 9.0));
        assert_eq!(b.outliers, vec![25.0]);
        assert_eq!(box_stats(&[f64::NAN, -1.0]), None);
    }
}
