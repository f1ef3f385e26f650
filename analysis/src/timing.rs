//! Timing statistics: the median of repeated run times and a percentile-bootstrap
//! confidence interval for it, reproducible from a seed.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::StatsError;
use crate::prng::SplitMix64;

/// A median run time with its confidence interval, all in seconds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Estimate {
    pub median: f64,
    pub low: f64,
    pub high: f64,
}

impl Estimate {
    /// The same estimate in another unit (`1e-9` turns nanoseconds into seconds).
    pub fn scaled(&self, factor: f64) -> Estimate {
        Estimate {
            median: self.median * factor,
            low: self.low * factor,
            high: self.high * factor,
        }
    }
}

/// Median of `xs` (mean of the two middle values for even lengths); `None` when `xs` is
/// empty or holds a NaN, which has no place in an ordering.
pub fn median(xs: &[f64]) -> Option<f64> {
    if xs.is_empty() || xs.iter().any(|x| x.is_nan()) {
        return None;
    }
    Some(median_of_sorted(&sorted(xs)))
}

/// Median of `samples` and the percentile bootstrap interval of the median: `resamples`
/// resamples with replacement, interval ends at the `(1 - confidence) / 2` and
/// `(1 + confidence) / 2` quantiles (linearly interpolated) of their medians.
/// The same inputs and `seed` always give the same interval.
pub fn median_with_bootstrap(
    samples: &[f64],
    resamples: usize,
    confidence: f64,
    seed: u64,
) -> Result<Estimate, StatsError> {
    if samples.is_empty() {
        return Err(StatsError::Empty);
    }
    if let Some((index, &value)) = samples.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(StatsError::NotFinite { index, value });
    }
    // Written as a positive test so that a NaN confidence is refused too.
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(StatsError::Confidence(confidence));
    }
    if resamples == 0 {
        return Err(StatsError::NoResamples);
    }
    let sorted = sorted(samples);
    let mut rng = SplitMix64::new(seed);
    let mut draw = vec![0.0; sorted.len()];
    // Capped so that an absurd request fails by running long, not by a huge allocation.
    let mut medians = Vec::with_capacity(resamples.min(1 << 20));
    for _ in 0..resamples {
        for slot in &mut draw {
            *slot = sorted[rng.below(sorted.len())];
        }
        draw.sort_unstable_by(f64::total_cmp);
        medians.push(median_of_sorted(&draw));
    }
    medians.sort_unstable_by(f64::total_cmp);
    Ok(Estimate {
        median: median_of_sorted(&sorted),
        low: quantile_of_sorted(&medians, (1.0 - confidence) / 2.0),
        high: quantile_of_sorted(&medians, (1.0 + confidence) / 2.0),
    })
}

/// The ratio `median(numerator) / median(denominator)` with its percentile bootstrap
/// interval: each resample draws both sets anew (they are independent measurements,
/// e.g. profiled and unprofiled render times). Same rules and determinism as
/// [`median_with_bootstrap`]; a zero median denominator is refused as not finite.
pub fn ratio_of_medians_with_bootstrap(
    numerator: &[f64],
    denominator: &[f64],
    resamples: usize,
    confidence: f64,
    seed: u64,
) -> Result<Estimate, StatsError> {
    // Checks both sets (emptiness, finiteness) and the parameters.
    median_with_bootstrap(numerator, 1, confidence, seed)?;
    let below = median_with_bootstrap(denominator, 1, confidence, seed)?;
    if resamples == 0 {
        return Err(StatsError::NoResamples);
    }
    if below.median <= 0.0 {
        return Err(StatsError::NotFinite {
            index: 0,
            value: f64::INFINITY,
        });
    }
    let (top, bottom) = (sorted(numerator), sorted(denominator));
    let mut rng = SplitMix64::new(seed);
    let mut draw = |set: &[f64], buffer: &mut Vec<f64>| {
        buffer.clear();
        buffer.extend((0..set.len()).map(|_| set[rng.below(set.len())]));
        buffer.sort_unstable_by(f64::total_cmp);
        median_of_sorted(buffer)
    };
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let mut ratios = Vec::with_capacity(resamples.min(1 << 20));
    for _ in 0..resamples {
        let over = draw(&bottom, &mut b);
        let ratio = draw(&top, &mut a) / over;
        if ratio.is_finite() {
            ratios.push(ratio);
        }
    }
    ratios.sort_unstable_by(f64::total_cmp);
    let median = median_of_sorted(&top) / median_of_sorted(&bottom);
    if ratios.is_empty() {
        return Ok(Estimate {
            median,
            low: median,
            high: median,
        });
    }
    Ok(Estimate {
        median,
        low: quantile_of_sorted(&ratios, (1.0 - confidence) / 2.0),
        high: quantile_of_sorted(&ratios, (1.0 + confidence) / 2.0),
    })
}

/// A statistic of the medians of several independent sample sets, with its percentile
/// bootstrap interval: each resample draws every set anew, `statistic` gets their
/// medians in order. The gate's change of a relative time, (new variant / new
/// baseline) / (old variant / old baseline), is such a statistic of four sets. Same
/// rules and determinism as [`median_with_bootstrap`]; resamples whose statistic is not
/// finite are left out.
pub fn medians_statistic_with_bootstrap(
    sets: &[&[f64]],
    statistic: impl Fn(&[f64]) -> f64,
    resamples: usize,
    confidence: f64,
    seed: u64,
) -> Result<Estimate, StatsError> {
    if sets.is_empty() {
        return Err(StatsError::Empty);
    }
    for set in sets {
        // Checks each set (emptiness, finiteness) and the parameters.
        median_with_bootstrap(set, 1, confidence, seed)?;
    }
    if resamples == 0 {
        return Err(StatsError::NoResamples);
    }
    let sorted_sets: Vec<Vec<f64>> = sets.iter().map(|s| sorted(s)).collect();
    let point: Vec<f64> = sorted_sets.iter().map(|s| median_of_sorted(s)).collect();
    let value = statistic(&point);
    let mut rng = SplitMix64::new(seed);
    let mut buffer = Vec::new();
    let mut medians = vec![0.0; sets.len()];
    let mut values = Vec::with_capacity(resamples.min(1 << 20));
    for _ in 0..resamples {
        for (slot, set) in medians.iter_mut().zip(&sorted_sets) {
            buffer.clear();
            buffer.extend((0..set.len()).map(|_| set[rng.below(set.len())]));
            buffer.sort_unstable_by(f64::total_cmp);
            *slot = median_of_sorted(&buffer);
        }
        let v = statistic(&medians);
        if v.is_finite() {
            values.push(v);
        }
    }
    if values.is_empty() {
        return Ok(Estimate {
            median: value,
            low: value,
            high: value,
        });
    }
    values.sort_unstable_by(f64::total_cmp);
    Ok(Estimate {
        median: value,
        low: quantile_of_sorted(&values, (1.0 - confidence) / 2.0),
        high: quantile_of_sorted(&values, (1.0 + confidence) / 2.0),
    })
}

fn sorted(xs: &[f64]) -> Vec<f64> {
    let mut copy = xs.to_vec();
    copy.sort_unstable_by(f64::total_cmp);
    copy
}

/// `sorted` must be non-empty and ascending.
fn median_of_sorted(sorted: &[f64]) -> f64 {
    let mid = sorted.len() / 2;
    if sorted.len() % 2 == 1 {
        sorted[mid]
    } else {
        f64::midpoint(sorted[mid - 1], sorted[mid])
    }
}

/// Linear interpolation between order statistics (Hyndman & Fan type 7); `sorted`
/// non-empty and ascending, `p` in [0, 1]. The one quantile of the workspace (the
/// bootstrap's intervals, the report's box plots).
pub fn quantile_of_sorted(sorted: &[f64], p: f64) -> f64 {
    let position = (sorted.len() - 1) as f64 * p;
    let below = position.floor() as usize;
    let above = (below + 1).min(sorted.len() - 1);
    let fraction = position - below as f64;
    sorted[below] + fraction * (sorted[above] - sorted[below])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_even_and_odd_lengths() {
        assert_eq!(median(&[3.0, 1.0, 2.0, 4.0]), Some(2.5));
        assert_eq!(median(&[5.0, 1.0, 3.0]), Some(3.0));
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[1.0, f64::NAN]), None);
    }

    #[test]
    fn a_statistic_of_several_medians_holds_its_point() {
        // (a / b) / (c / d) with constant sets: exactly (2 / 4) / (1 / 8) = 4, interval
        // collapsed on it.
        let (a, b, c, d) = ([2.0; 5], [4.0; 3], [1.0; 4], [8.0; 6]);
        let e = medians_statistic_with_bootstrap(
            &[&a, &b, &c, &d],
            |m| (m[0] / m[1]) / (m[2] / m[3]),
            500,
            0.95,
            9,
        )
        .unwrap();
        assert_eq!((e.median, e.low, e.high), (4.0, 4.0, 4.0));
        // Noisy sets: the point is the ratio of the medians, bracketed by the interval.
        let top = [1.0, 1.2, 0.9, 1.1, 1.05];
        let bottom = [2.0, 2.1, 1.9, 2.2, 1.8];
        let e = medians_statistic_with_bootstrap(&[&top, &bottom], |m| m[0] / m[1], 2000, 0.95, 3)
            .unwrap();
        assert_eq!(e.median, 1.05 / 2.0);
        assert!(e.low < e.median && e.median < e.high);
        assert!(medians_statistic_with_bootstrap(&[], |m| m[0], 10, 0.95, 1).is_err());
        assert!(medians_statistic_with_bootstrap(&[&[][..]], |m| m[0], 10, 0.95, 1).is_err());
    }

    #[test]
    fn a_ratio_of_medians_holds_its_point_and_brackets_it() {
        // Constant sets: the ratio is exact and its interval degenerate.
        let e = ratio_of_medians_with_bootstrap(&[2.0; 5], &[0.5; 7], 500, 0.95, 3).unwrap();
        assert_eq!((e.median, e.low, e.high), (4.0, 4.0, 4.0));
        // Hand-computed point: medians 1.04 and 1.0; the interval brackets it and
        // stays within the extreme ratios the samples allow (1.02/1.02 .. 1.06/0.98).
        let profiled = [1.03, 1.04, 1.05, 1.02, 1.06];
        let plain = [1.0, 0.99, 1.01, 0.98, 1.02];
        let e = ratio_of_medians_with_bootstrap(&profiled, &plain, 2000, 0.95, 7).unwrap();
        assert!((e.median - 1.04).abs() < 1e-12);
        assert!(e.low <= e.median && e.median <= e.high, "{e:?}");
        assert!(
            e.low >= 1.02 / 1.02 - 1e-12 && e.high <= 1.06 / 0.98 + 1e-12,
            "{e:?}"
        );
        assert!(ratio_of_medians_with_bootstrap(&[], &plain, 10, 0.95, 1).is_err());
        assert!(ratio_of_medians_with_bootstrap(&profiled, &[0.0], 10, 0.95, 1).is_err());
    }

    #[test]
    fn constant_samples_give_a_degenerate_interval() {
        let e = median_with_bootstrap(&[0.25; 9], 1000, 0.95, 1).expect("valid input");
        assert_eq!(
            e,
            Estimate {
                median: 0.25,
                low: 0.25,
                high: 0.25
            }
        );
        let one = median_with_bootstrap(&[1.5], 100, 0.95, 1).expect("valid input");
        assert_eq!(
            one,
            Estimate {
                median: 1.5,
                low: 1.5,
                high: 1.5
            }
        );
    }

    #[test]
    fn interval_for_one_to_hundred_and_one_surrounds_fifty_one() {
        let samples: Vec<f64> = (1..=101).map(f64::from).collect();
        let e = median_with_bootstrap(&samples, 10_000, 0.95, 7).expect("valid input");
        assert_eq!(e.median, 51.0);
        assert!(e.low <= 51.0 && 51.0 <= e.high, "{e:?}");
        assert!(1.0 <= e.low && e.high <= 101.0, "{e:?}");
        assert!(
            e.low < e.high,
            "101 distinct values must leave some spread: {e:?}"
        );
    }

    #[test]
    fn same_seed_same_interval_and_wider_confidence_nests() {
        let samples = [0.91, 1.02, 0.97, 1.3, 0.88, 1.05, 0.99, 1.12];
        let a = median_with_bootstrap(&samples, 2000, 0.9, 99).expect("valid input");
        let b = median_with_bootstrap(&samples, 2000, 0.9, 99).expect("valid input");
        assert_eq!(a, b);
        // Same seed, same bootstrap medians: a higher confidence takes outer quantiles.
        let wide = median_with_bootstrap(&samples, 2000, 0.99, 99).expect("valid input");
        assert!(wide.low <= a.low && a.high <= wide.high);
    }

    #[test]
    fn bad_input_is_an_error() {
        assert_eq!(
            median_with_bootstrap(&[], 10, 0.95, 0),
            Err(StatsError::Empty)
        );
        assert!(matches!(
            median_with_bootstrap(&[1.0, f64::NAN], 10, 0.95, 0),
            Err(StatsError::NotFinite { index: 1, .. })
        ));
        for confidence in [0.0, 1.0, f64::NAN] {
            assert!(matches!(
                median_with_bootstrap(&[1.0], 10, confidence, 0),
                Err(StatsError::Confidence(_))
            ));
        }
        assert_eq!(
            median_with_bootstrap(&[1.0], 0, 0.95, 0),
            Err(StatsError::NoResamples)
        );
    }
}
