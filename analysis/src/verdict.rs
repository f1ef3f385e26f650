//! The one rule that labels a comparison of two times: **faster**, **slower** or
//! **within noise**. The terminal tables, results.json, the HTML and PDF reports and
//! the regression gate all label changes with [`judge`], so they cannot disagree.
//!
//! A change is the ratio of the new time to the old one, with an interval (for
//! example the bootstrap interval of a ratio of medians). It is a change only when
//! both hold:
//! - its size exceeds the noise threshold (`ratio > 1 + t` for slower,
//!   `ratio < 1 / (1 + t)` for faster: symmetric in log scale, so 2× slower and 2×
//!   faster are the same size of change), and
//! - its interval excludes "no change" (the whole interval lies above 1, or below 1).
//!
//! The threshold is the run-to-run noise of rtprof's relative times, measured on a
//! shared two-core machine (docs/gate.md): a change smaller than what two runs of
//! the same binary show can never be called a change. Counts are exact: they are not
//! judged here; any changed count is a change.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::timing::Estimate;

/// The default noise threshold (a fraction): above the largest run-to-run change of a
/// relative CPU time whose interval excluded no change, 19.6 %, in five back-to-back
/// default-suite runs of one binary on a shared, heavily loaded two-core machine
/// (docs/gate.md has the measurement).
pub const NOISE_THRESHOLD: f64 = 0.20;

/// A noise threshold as the command line gives it, in percent (`--threshold 20`):
/// a number from 0 to 1000.
pub fn parse_threshold_percent(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(p) if p.is_finite() && (0.0..=1000.0).contains(&p) => Ok(p),
        _ => Err(format!("'{text}' is not a percentage between 0 and 1000")),
    }
}

/// What a comparison of two times says.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Significantly less time than the reference.
    Faster,
    /// Significantly more time than the reference.
    Slower,
    /// Not distinguishable from no change.
    WithinNoise,
}

impl Verdict {
    /// Every verdict, for legends and tests.
    pub const ALL: [Verdict; 3] = [Verdict::Faster, Verdict::Slower, Verdict::WithinNoise];

    /// The label every output prints: "faster", "slower", "within noise".
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Faster => "faster",
            Verdict::Slower => "slower",
            Verdict::WithinNoise => "within noise",
        }
    }
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.label())
    }
}

/// Labels a time ratio `new / old` (median and interval) against `threshold` (a
/// fraction, e.g. 0.10). A ratio that is not a finite positive number is within noise:
/// nothing can be said of it.
pub fn judge(ratio: &Estimate, threshold: f64) -> Verdict {
    let Estimate { median, low, high } = *ratio;
    if !(median.is_finite() && median > 0.0 && low.is_finite() && high.is_finite()) {
        return Verdict::WithinNoise;
    }
    let t = threshold.max(0.0);
    if median > 1.0 + t && low > 1.0 {
        Verdict::Slower
    } else if median < 1.0 / (1.0 + t) && high < 1.0 {
        Verdict::Faster
    } else {
        Verdict::WithinNoise
    }
}

/// Labels a speed-up `old / new` (the reciprocal of a time ratio) by the same rule: a
/// speed-up of 2× with interval [1.8, 2.2] is faster.
pub fn judge_speedup(speedup: &Estimate, threshold: f64) -> Verdict {
    judge(&reciprocal(speedup), threshold)
}

/// `1 / x` of an estimate (its interval ends swap).
pub fn reciprocal(x: &Estimate) -> Estimate {
    Estimate {
        median: 1.0 / x.median,
        low: 1.0 / x.high,
        high: 1.0 / x.low,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn e(median: f64, low: f64, high: f64) -> Estimate {
        Estimate { median, low, high }
    }

    #[test]
    fn a_change_must_exceed_the_threshold_and_exclude_no_change() {
        // 25 % slower, interval [1.20, 1.31]: slower at a 10 % threshold.
        assert_eq!(judge(&e(1.25, 1.20, 1.31), 0.10), Verdict::Slower);
        // The same median with an interval that reaches 1: within noise.
        assert_eq!(judge(&e(1.25, 0.99, 1.60), 0.10), Verdict::WithinNoise);
        // 5 % slower with a tight interval: below the threshold, within noise.
        assert_eq!(judge(&e(1.05, 1.04, 1.06), 0.10), Verdict::WithinNoise);
        // 1/1.25 = 0.8: 25 % faster, interval below 1.
        assert_eq!(judge(&e(0.80, 0.76, 0.84), 0.10), Verdict::Faster);
        // 0.92 is not past 1/1.1 = 0.909: within noise.
        assert_eq!(judge(&e(0.92, 0.90, 0.94), 0.10), Verdict::WithinNoise);
        // Just past it on both sides.
        assert_eq!(judge(&e(0.905, 0.90, 0.91), 0.10), Verdict::Faster);
        assert_eq!(judge(&e(1.101, 1.05, 1.2), 0.10), Verdict::Slower);
    }

    #[test]
    fn a_zero_threshold_leaves_only_the_interval() {
        assert_eq!(judge(&e(1.01, 1.005, 1.02), 0.0), Verdict::Slower);
        assert_eq!(judge(&e(1.01, 0.995, 1.02), 0.0), Verdict::WithinNoise);
    }

    #[test]
    fn speedups_are_judged_as_the_reciprocal_time_ratio() {
        // A 1.01× speed-up with an interval reaching below 1 is within noise, not green.
        assert_eq!(
            judge_speedup(&e(1.01, 0.97, 1.05), NOISE_THRESHOLD),
            Verdict::WithinNoise
        );
        // 2× [1.8, 2.2] is faster; 0.5× [0.45, 0.55] slower.
        assert_eq!(judge_speedup(&e(2.0, 1.8, 2.2), 0.10), Verdict::Faster);
        assert_eq!(judge_speedup(&e(0.5, 0.45, 0.55), 0.10), Verdict::Slower);
        let r = reciprocal(&e(2.0, 1.6, 2.5));
        assert_eq!((r.median, r.low, r.high), (0.5, 0.4, 0.625));
    }

    #[test]
    fn thresholds_are_percentages_from_0_to_1000() {
        assert_eq!(parse_threshold_percent(" 20 "), Ok(20.0));
        assert_eq!(parse_threshold_percent("0"), Ok(0.0));
        for bad in ["-1", "1000.5", "nan", "inf", "twenty"] {
            assert!(parse_threshold_percent(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn what_cannot_be_judged_is_within_noise() {
        assert_eq!(judge(&e(f64::NAN, 1.0, 2.0), 0.1), Verdict::WithinNoise);
        assert_eq!(judge(&e(2.0, f64::NAN, 3.0), 0.1), Verdict::WithinNoise);
        assert_eq!(judge(&e(0.0, 0.0, 0.0), 0.1), Verdict::WithinNoise);
        assert_eq!(
            judge_speedup(&e(f64::INFINITY, 1.0, f64::INFINITY), 0.1),
            Verdict::WithinNoise
        );
    }

    #[test]
    fn labels_and_serde_names() {
        let labels: Vec<&str> = Verdict::ALL.iter().map(|v| v.label()).collect();
        assert_eq!(labels, ["faster", "slower", "within noise"]);
        assert_eq!(
            serde_json::to_string(&Verdict::WithinNoise).unwrap(),
            "\"within_noise\""
        );
    }
}
