//! A least-squares line `y = a + b x` with the 95 % intervals of its intercept and slope
//! (Student's t on the residuals, m − 2 degrees of freedom), and how far the points
//! reach in x: a line is known only over the counts it was fitted on.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, StudentsT};

/// A fitted line and what is known of it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct LineFit {
    /// `a`: y at x = 0.
    pub intercept: f64,
    /// `b`.
    pub slope: f64,
    /// 95 % intervals of `a` and `b` (equal to the value with fewer than three points or
    /// points exactly on the line: nothing to estimate the scatter from).
    pub intercept_interval: [f64; 2],
    pub slope_interval: [f64; 2],
    /// Points fitted and the range of x they cover.
    pub points: usize,
    pub x_range: [f64; 2],
}

/// The confidence of the intervals.
pub const CONFIDENCE: f64 = 0.95;

impl LineFit {
    /// The least-squares line through `points`; `None` with fewer than two distinct x or
    /// a non-finite value.
    pub fn of(points: &[(f64, f64)]) -> Option<LineFit> {
        let m = points.len();
        if m < 2 || points.iter().any(|(x, y)| !x.is_finite() || !y.is_finite()) {
            return None;
        }
        let mf = m as f64;
        let mean_x = points.iter().map(|p| p.0).sum::<f64>() / mf;
        let mean_y = points.iter().map(|p| p.1).sum::<f64>() / mf;
        let sxx: f64 = points.iter().map(|p| (p.0 - mean_x).powi(2)).sum();
        if sxx <= 0.0 {
            return None;
        }
        let sxy: f64 = points.iter().map(|p| (p.0 - mean_x) * (p.1 - mean_y)).sum();
        let slope = sxy / sxx;
        let intercept = mean_y - slope * mean_x;
        let (slope_half, intercept_half) = if m > 2 {
            let residual_ss: f64 = points
                .iter()
                .map(|(x, y)| (y - intercept - slope * x).powi(2))
                .sum();
            let dof = (m - 2) as f64;
            let s2 = residual_ss / dof;
            let t = StudentsT::new(0.0, 1.0, dof)
                .map(|d| d.inverse_cdf(0.5 + CONFIDENCE / 2.0))
                .unwrap_or(f64::NAN);
            let slope_se = (s2 / sxx).sqrt();
            let intercept_se = (s2 * (1.0 / mf + mean_x * mean_x / sxx)).sqrt();
            (t * slope_se, t * intercept_se)
        } else {
            (0.0, 0.0)
        };
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.0), hi.max(p.0))
            });
        Some(LineFit {
            intercept,
            slope,
            intercept_interval: [intercept - intercept_half, intercept + intercept_half],
            slope_interval: [slope - slope_half, slope + slope_half],
            points: m,
            x_range: [lo, hi],
        })
    }

    /// y at `x`.
    pub fn at(&self, x: f64) -> f64 {
        self.intercept + self.slope * x
    }

    /// Whether `x` lies within the fitted points' range (beyond it the line is an
    /// extrapolation).
    pub fn covers(&self, x: f64) -> bool {
        x >= self.x_range[0] && x <= self.x_range[1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exact_line_is_recovered_with_no_width() {
        let f = LineFit::of(&[(1.0, 3.0), (2.0, 5.0), (4.0, 9.0)]).unwrap();
        assert!((f.intercept - 1.0).abs() < 1e-12 && (f.slope - 2.0).abs() < 1e-12);
        assert!((f.slope_interval[1] - f.slope_interval[0]).abs() < 1e-9);
        assert_eq!(f.x_range, [1.0, 4.0]);
        assert!(f.covers(3.0) && !f.covers(5.0));
        assert_eq!(f.at(10.0), 21.0);
    }

    #[test]
    fn the_slope_interval_is_the_textbook_t_interval() {
        // x = 1..5, y = 2, 5, 5, 9, 9. By hand: x̄ = 3, ȳ = 6, Sxx = 10,
        // Sxy = (-2)(-4) + (-1)(-1) + 0 + (1)(3) + (2)(3) = 18, so b = 1.8, a = 0.6.
        // Residuals: 2 - 2.4 = -0.4, 5 - 4.2 = 0.8, 5 - 6 = -1, 9 - 7.8 = 1.2,
        // 9 - 9.6 = -0.6; RSS = 0.16 + 0.64 + 1 + 1.44 + 0.36 = 3.6, s² = 1.2,
        // se(b) = √(1.2 / 10) = 0.34641; t(0.975, 3) = 3.18245: half-width 1.10245.
        let f = LineFit::of(&[(1.0, 2.0), (2.0, 5.0), (3.0, 5.0), (4.0, 9.0), (5.0, 9.0)]).unwrap();
        assert!((f.slope - 1.8).abs() < 1e-12 && (f.intercept - 0.6).abs() < 1e-12);
        let half = (f.slope_interval[1] - f.slope_interval[0]) / 2.0;
        assert!((half - 3.182446 * 0.346410).abs() < 1e-5, "{half}");
        // se(a) = √(1.2 (1/5 + 9/10)) = 1.14891: half-width 3.6563.
        let a_half = (f.intercept_interval[1] - f.intercept_interval[0]) / 2.0;
        assert!((a_half - 3.182446 * 1.148913).abs() < 1e-5, "{a_half}");
    }

    #[test]
    fn degenerate_inputs_give_none() {
        assert_eq!(LineFit::of(&[(1.0, 3.0)]), None);
        assert_eq!(LineFit::of(&[(1.0, 3.0), (1.0, 4.0)]), None);
        assert_eq!(LineFit::of(&[(1.0, f64::NAN), (2.0, 4.0)]), None);
    }
}
