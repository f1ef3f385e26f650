//! The sampling error of a profile's shares. A function's share of the samples is a
//! binomial proportion (each sample lands in the function or not), so its 95 %
//! interval is the Wilson score interval (Wilson 1927), which stays inside [0, 1] and
//! keeps its coverage for the small counts of rarely sampled functions, where the
//! textbook `p ± 1.96 √(p(1−p)/n)` interval collapses to a point at 0.
//!
//! # The noise floor
//! A share is *below the noise floor* when the lower end of its 95 % interval, as a
//! number of samples (`n × low`), is under half a sample: the data are then consistent
//! with a true count that rounds to zero samples, and the function's time cannot be
//! told from none. With the Wilson interval this means at most one sample for any run
//! of more than a few dozen samples (1 sample: `n × low` ≈ 0.18; 2 samples: ≈ 0.55).

use serde::{Deserialize, Serialize};

/// The standard normal quantile for a two-sided 95 % interval (Φ⁻¹(0.975)).
pub const Z_95: f64 = 1.959_963_984_540_054;

/// A confidence interval of a share, in the unit of the share it bounds (a fraction
/// from [`wilson_interval`]; percent in the flat profile's rows).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShareInterval {
    pub low: f64,
    pub high: f64,
}

impl ShareInterval {
    /// The same interval with both ends multiplied by `factor` (100 for percent).
    pub fn scaled(self, factor: f64) -> ShareInterval {
        ShareInterval {
            low: self.low * factor,
            high: self.high * factor,
        }
    }

    /// Whether `value` lies inside the interval (ends included).
    pub fn contains(self, value: f64) -> bool {
        (self.low..=self.high).contains(&value)
    }
}

/// Wilson score interval of the proportion `successes / trials` at normal quantile `z`
/// ([`Z_95`] for 95 %), as fractions in [0, 1]. With no trials nothing is known: [0, 1].
pub fn wilson_interval(successes: u64, trials: u64, z: f64) -> ShareInterval {
    if trials == 0 {
        return ShareInterval {
            low: 0.0,
            high: 1.0,
        };
    }
    let n = trials as f64;
    let k = successes.min(trials) as f64;
    let p = k / n;
    let z2 = z * z;
    let denominator = 1.0 + z2 / n;
    let centre = (p + z2 / (2.0 * n)) / denominator;
    let half_width = z / denominator * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    // At k = 0 and k = n the formula gives exactly 0 and 1; rounding must not move them.
    let low = if successes == 0 {
        0.0
    } else {
        (centre - half_width).max(0.0)
    };
    let high = if successes >= trials {
        1.0
    } else {
        (centre + half_width).min(1.0)
    };
    ShareInterval { low, high }
}

/// Whether `successes` of `trials` samples are below the noise floor (see the module
/// documentation): the 95 % interval's lower end is under half a sample. No trials:
/// nothing was measured, so yes.
pub fn below_noise_floor(successes: u64, trials: u64) -> bool {
    trials == 0 || wilson_interval(successes, trials, Z_95).low * (trials as f64) < 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rounded(x: f64) -> f64 {
        (x * 1e4).round() / 1e4
    }

    #[test]
    fn wilson_matches_newcombe_1998_worked_examples() {
        // R. G. Newcombe, "Two-sided confidence intervals for the single proportion:
        // comparison of seven methods", Statistics in Medicine 17 (1998) 857-872: the
        // worked examples for method 3 (score interval without continuity correction)
        // give 81/263 -> 0.2553-0.3662, 15/148 -> 0.0624-0.1605, 0/20 -> 0-0.1611 and
        // 1/29 -> 0.0061-0.1718.
        for (k, n, low, high) in [
            (81, 263, 0.2553, 0.3662),
            (15, 148, 0.0624, 0.1605),
            (0, 20, 0.0, 0.1611),
            (1, 29, 0.0061, 0.1718),
        ] {
            let interval = wilson_interval(k, n, Z_95);
            assert_eq!(
                (rounded(interval.low), rounded(interval.high)),
                (low, high),
                "{k}/{n}"
            );
        }
    }

    #[test]
    fn wilson_is_symmetric_and_bounded() {
        // k/n and (n-k)/n mirror each other about 1/2.
        let a = wilson_interval(30, 100, Z_95);
        let b = wilson_interval(70, 100, Z_95);
        assert!((a.low - (1.0 - b.high)).abs() < 1e-12 && (a.high - (1.0 - b.low)).abs() < 1e-12);
        // 50/100: centred on 0.5 with half-width 1.96/(2 sqrt(100 + 1.96^2)) = 0.09617.
        let half = wilson_interval(50, 100, Z_95);
        assert!((half.high - 0.5 - Z_95 / (2.0 * (100.0 + Z_95 * Z_95).sqrt())).abs() < 1e-12);
        assert_eq!(wilson_interval(10, 10, Z_95).high, 1.0);
        assert_eq!(
            wilson_interval(0, 0, Z_95),
            ShareInterval {
                low: 0.0,
                high: 1.0
            }
        );
        // More successes than trials (bad input) is read as all of them.
        assert_eq!(wilson_interval(12, 10, Z_95).high, 1.0);
        assert!(a.scaled(100.0).contains(30.0) && !a.scaled(100.0).contains(40.0));
    }

    #[test]
    fn noise_floor_is_at_most_one_sample_in_a_long_run() {
        // n x low for 1 of 1000 = 0.1765 (< 0.5), for 2 of 1000 = 0.5486 (>= 0.5),
        // computed from the Wilson formula by hand.
        assert!(below_noise_floor(0, 1000));
        assert!(below_noise_floor(1, 1000));
        assert!(!below_noise_floor(2, 1000));
        assert!(below_noise_floor(1, 30_000) && !below_noise_floor(2, 30_000));
        assert!(below_noise_floor(0, 0));
        let low = wilson_interval(1, 1000, Z_95).low;
        assert!((low * 1000.0 - 0.17655).abs() < 1e-4);
    }
}
