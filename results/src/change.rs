//! Changes of time with their intervals, from the samples a results file keeps: a
//! variant's speed-up over the reference within one run, and the gate's change of a
//! relative time between two runs. Every interval is a seeded percentile bootstrap of
//! medians ([`analysis::timing::medians_statistic_with_bootstrap`]), every label comes
//! from the one verdict rule ([`analysis::verdict`]).

use analysis::timing::medians_statistic_with_bootstrap;
use analysis::verdict::judge_speedup;

use crate::schema::{Estimate, Results, SceneResult};

/// Bootstrap resamples of a change's interval: 2,000 keep the ends stable to about 1 %
/// of the interval's width and a gate of a few hundred entries under a second.
pub const RESAMPLES: usize = 2_000;
/// 95 % intervals, as every interval of rtprof.
pub const CONFIDENCE: f64 = 0.95;
/// The bootstrap seed: the same files always give the same intervals and verdicts.
pub const SEED: u64 = 0x5EED_C4A6;

/// A statistic of the medians of `sets` with its interval; `None` when a set is empty
/// or holds a value that is not a finite number.
pub fn of_medians(sets: &[&[f64]], statistic: impl Fn(&[f64]) -> f64) -> Option<Estimate> {
    medians_statistic_with_bootstrap(sets, statistic, RESAMPLES, CONFIDENCE, SEED).ok()
}

/// Ratios `a[j] / b[j]` of samples timed in the same round `j` (a suite times a
/// scene's variants and the calibration kernel in rounds, and keeps each one's samples
/// in round order, all starting at the first round): a change of load between rounds
/// cancels out of each ratio. Pairs up to the shorter set; non-finite ratios are left out.
pub fn paired_ratios(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter()
        .zip(b)
        .map(|(x, y)| x / y)
        .filter(|r| r.is_finite())
        .collect()
}

/// The speed-up of `variant` over `reference`: the median of the per-round ratios
/// reference / variant, with its interval.
pub fn speedup(reference: &[f64], variant: &[f64]) -> Option<Estimate> {
    of_medians(&[&paired_ratios(reference, variant)], |m| m[0])
}

/// Fills every variant's speed-up over its scene's reference, its interval and its
/// verdict at `threshold`, and records the threshold in the suite
/// ([`fill_scene_speedups`] for each scene).
pub fn fill_speedups(results: &mut Results, threshold: f64) {
    results.suite.noise_threshold = Some(threshold);
    for scene in &mut results.scenes {
        fill_scene_speedups(scene, threshold);
    }
}

/// Fills the speed-ups, intervals and verdicts of one scene's variants (the reference
/// itself gets no verdict; without a reference, nothing).
pub fn fill_scene_speedups(scene: &mut SceneResult, threshold: f64) {
    let reference = scene
        .variants
        .iter()
        .find(|v| v.variant.is_reference())
        .map(|v| v.samples.clone());
    for v in &mut scene.variants {
        let estimate = reference.as_deref().and_then(|r| speedup(r, &v.samples));
        v.speedup = estimate.map(|e| e.median).filter(|s| s.is_finite());
        v.speedup_interval = estimate.map(|e| [e.low, e.high]);
        v.verdict = match estimate {
            Some(e) if !v.variant.is_reference() => Some(judge_speedup(&e, threshold)),
            _ => None,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_speedup_is_the_median_of_the_per_round_ratios() {
        // Round 3 ran on a busy machine (both 1.5× longer): its ratio is still 2.
        let reference = [2.0, 2.1, 3.0, 2.05, 1.9];
        let variant = [1.0, 1.0, 1.5, 1.0, 1.0];
        assert_eq!(
            paired_ratios(&reference, &variant),
            [2.0, 2.1, 2.0, 2.05, 1.9]
        );
        let e = speedup(&reference, &variant).unwrap();
        assert_eq!(e.median, 2.0);
        assert!(e.low <= 2.0 && e.high >= 2.0);
        assert!(e.low >= 1.9 && e.high <= 2.1);
        // A faster variant has more rounds: the pairs stop at the shorter set.
        assert_eq!(paired_ratios(&[4.0, 4.0], &[1.0, 2.0, 3.0]), [4.0, 2.0]);
        assert!(speedup(&[], &variant).is_none());
        assert!(speedup(&reference, &[f64::NAN]).is_none());
    }
}
