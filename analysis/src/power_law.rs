//! Power laws `y = a · x^b` fitted by least squares on log-log axes: how a cost grows
//! with scene size (the exponent `b`: 1 for brute force's tests per ray, near 0 for a
//! good hierarchy) and where an unmeasured point would lie.

/// `y = coefficient · x^exponent`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerLaw {
    pub coefficient: f64,
    pub exponent: f64,
}

impl PowerLaw {
    /// Fits `(x, y)` points with `x, y > 0` (others are ignored) by least squares of
    /// `ln y` on `ln x`. `None` with fewer than two usable points or a single `x`.
    pub fn fit(points: &[(f64, f64)]) -> Option<PowerLaw> {
        let logs: Vec<(f64, f64)> = points
            .iter()
            .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
            .map(|(x, y)| (x.ln(), y.ln()))
            .collect();
        if logs.len() < 2 {
            return None;
        }
        let n = logs.len() as f64;
        let mean_x = logs.iter().map(|p| p.0).sum::<f64>() / n;
        let mean_y = logs.iter().map(|p| p.1).sum::<f64>() / n;
        let sxx: f64 = logs.iter().map(|p| (p.0 - mean_x).powi(2)).sum();
        if sxx.is_nan() || sxx <= 0.0 {
            return None;
        }
        let sxy: f64 = logs.iter().map(|p| (p.0 - mean_x) * (p.1 - mean_y)).sum();
        let exponent = sxy / sxx;
        Some(PowerLaw {
            coefficient: (mean_y - exponent * mean_x).exp(),
            exponent,
        })
    }

    /// The law's value at `x`.
    pub fn at(&self, x: f64) -> f64 {
        self.coefficient * x.powf(self.exponent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_power_laws_are_recovered() {
        let points: Vec<(f64, f64)> = [1.0, 10.0, 100.0, 1000.0]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x * x))
            .collect();
        let law = PowerLaw::fit(&points).unwrap();
        assert!((law.exponent - 2.0).abs() < 1e-12, "{law:?}");
        assert!((law.coefficient - 3.0).abs() < 1e-9, "{law:?}");
        assert!((law.at(10_000.0) - 3e8).abs() < 1e-1);
        // A constant cost has exponent 0.
        let flat = PowerLaw::fit(&[(10.0, 5.0), (1e6, 5.0)]).unwrap();
        assert!(flat.exponent.abs() < 1e-12);
    }

    #[test]
    fn unusable_points_give_no_law() {
        assert_eq!(PowerLaw::fit(&[(10.0, 1.0)]), None);
        assert_eq!(PowerLaw::fit(&[(10.0, 1.0), (10.0, 2.0)]), None);
        assert_eq!(PowerLaw::fit(&[(0.0, 1.0), (-1.0, 2.0), (5.0, 0.0)]), None);
    }
}
