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

/// The fewest rounds two sets must share for their ratio to be taken round by round.
/// A median of fewer ratios is known no better than their spread (the bootstrap
/// interval of two is just the two), and the first rounds need not be typical: a slow
/// reference on a small frame (baseline at 16×16, 2 rounds) pairs only the first two of
/// a fast variant's 17 renders, and Embree's first two there took 0.010-0.011 s of CPU
/// where the other 15 took 0.012-0.017 s, which moved its ratio by half between runs.
pub const MIN_PAIRED_ROUNDS: usize = 5;

/// The ratio of two sets of samples timed in rounds, `a / b`, as the sets its
/// interval is bootstrapped from ([`Ratio::of`]).
#[derive(Clone, Debug, PartialEq)]
pub enum Ratio {
    /// The per-round ratios (at least [`MIN_PAIRED_ROUNDS`]); the ratio is their median.
    PerRound(Vec<f64>),
    /// Too few shared rounds: the ratio is the median of all of `a`'s samples over the
    /// median of all of `b`'s.
    OfMedians(Vec<f64>, Vec<f64>),
}

impl Ratio {
    /// `a / b`: per round when the sets share at least [`MIN_PAIRED_ROUNDS`] rounds
    /// (or are the same samples: the reference against itself is 1 in every round),
    /// otherwise of the two sets' medians, each over all its (finite) samples.
    pub fn of(a: &[f64], b: &[f64]) -> Ratio {
        let per_round = paired_ratios(a, b);
        if per_round.len() >= MIN_PAIRED_ROUNDS || a == b {
            return Ratio::PerRound(per_round);
        }
        let finite = |s: &[f64]| s.iter().copied().filter(|x| x.is_finite()).collect();
        Ratio::OfMedians(finite(a), finite(b))
    }

    fn sets(&self) -> Vec<&[f64]> {
        match self {
            Ratio::PerRound(r) => vec![r],
            Ratio::OfMedians(a, b) => vec![a, b],
        }
    }

    /// The ratio from the medians of [`Ratio::sets`], in order.
    fn value(&self, medians: &[f64]) -> f64 {
        match self {
            Ratio::PerRound(_) => medians[0],
            Ratio::OfMedians(..) => medians[0] / medians[1],
        }
    }

    /// The ratio with its interval; `None` when a set is empty.
    pub fn estimate(&self) -> Option<Estimate> {
        of_medians(&self.sets(), |m| self.value(m))
    }

    /// `new / old`, with its interval (the gate's change of a relative time).
    pub fn change(new: &Ratio, old: &Ratio) -> Option<Estimate> {
        let split = new.sets().len();
        let sets: Vec<&[f64]> = new.sets().into_iter().chain(old.sets()).collect();
        of_medians(&sets, |m| new.value(&m[..split]) / old.value(&m[split..]))
    }
}

/// The speed-up of `variant` over `reference`, reference / variant ([`Ratio::of`]: the
/// median of the per-round ratios, or with too few shared rounds the ratio of the
/// medians), with its interval.
pub fn speedup(reference: &[f64], variant: &[f64]) -> Option<Estimate> {
    Ratio::of(reference, variant).estimate()
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

    #[test]
    fn with_too_few_shared_rounds_a_ratio_is_of_the_medians_of_all_samples() {
        // A slow reference timed twice; a fast variant whose first two renders were
        // atypically quick (as Embree's first CPU samples at 16×16).
        let reference = [60.0, 56.0];
        let variant = [10.0, 10.0, 15.0, 15.0, 14.0, 16.0, 15.0];
        let ratio = Ratio::of(&variant, &reference);
        assert_eq!(
            ratio,
            Ratio::OfMedians(variant.to_vec(), reference.to_vec())
        );
        // By hand: median 15 over median 58.
        let e = ratio.estimate().unwrap();
        assert!((e.median - 15.0 / 58.0).abs() < 1e-12, "{e:?}");
        // The interval holds both the first rounds' ratio and the later ones'.
        assert!(
            e.low <= 10.0 / 58.0 + 1e-12 && e.high >= 15.0 / 56.0,
            "{e:?}"
        );
        // Pairing would have given the first two rounds only: 10/60 and 10/56.
        assert!(
            paired_ratios(&variant, &reference)
                .iter()
                .all(|r| *r < 0.18)
        );
        // A run with the same medians is no change, whichever form either side takes.
        let later = Ratio::of(&[15.0; 5], &[58.0; 5]);
        assert!(matches!(later, Ratio::PerRound(_)));
        let change = Ratio::change(&later, &ratio).unwrap();
        assert!((change.median - 1.0).abs() < 1e-12, "{change:?}");
        assert!(change.low < 1.0 && change.high > 1.0, "{change:?}");
        // The reference against itself is exactly 1, interval and all.
        let itself = Ratio::of(&reference, &reference).estimate().unwrap();
        assert_eq!([itself.low, itself.median, itself.high], [1.0; 3]);
        // A sample that is not a number is left out, not a reason to give up.
        let with_nan = Ratio::of(&[15.0, f64::NAN], &[58.0]);
        assert_eq!(with_nan, Ratio::OfMedians(vec![15.0], vec![58.0]));
    }
}
