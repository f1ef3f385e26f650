//! The roots of `a t² + 2 h t + c = 0` without cancellation.
//!
//! The textbook `(-h ± √Δ) / a` subtracts two nearly equal numbers for the root near
//! zero when `|h| ≫ √Δ`; the stable form (Press et al., *Numerical Recipes* 5.6; Haines
//! et al., *Ray Tracing Gems* ch. 7) takes `q = -(h + sign(h) √Δ)`, which adds numbers of
//! one sign, and the roots `c / q` and `q / a`. The caller computes the discriminant
//! `Δ = h² - a c` in a form suited to its surface (the perpendicular forms of
//! [`crate::primitives`]), so that it does not cancel either.

/// Both roots in ascending order, given the discriminant `disc = h² - a c`; `None` when
/// `disc ≤ 0` (a tangent or a miss: no area a pixel could see) or is NaN. With `a = 0`
/// the equation is linear: one root is `-c / 2h`, the other infinite (never inside a
/// finite interval).
pub fn roots(a: f64, half_b: f64, c: f64, disc: f64) -> Option<[f64; 2]> {
    if !(disc > 0.0) {
        return None;
    }
    let q = -(half_b + disc.sqrt().copysign(half_b));
    let (t0, t1) = (c / q, q / a);
    Some(if t0 <= t1 { [t0, t1] } else { [t1, t0] })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_of_a_factored_quadratic() {
        // (t - 2)(t - 5) = t² - 7t + 10: h = -3.5, Δ = 12.25 - 10 = 2.25.
        assert_eq!(roots(1.0, -3.5, 10.0, 2.25), Some([2.0, 5.0]));
        // 2(t + 1)(t - 3) = 2t² - 4t - 6: h = -2, Δ = 4 + 12 = 16.
        assert_eq!(roots(2.0, -2.0, -6.0, 16.0), Some([-1.0, 3.0]));
        // Negative a: -(t - 1)(t - 4) = -t² + 5t - 4: h = 2.5, Δ = 6.25 - 4 = 2.25.
        assert_eq!(roots(-1.0, 2.5, -4.0, 2.25), Some([1.0, 4.0]));
    }

    #[test]
    fn the_small_root_keeps_its_digits_where_the_textbook_form_loses_them() {
        // t² - 2e8 t + 1 = 0: the small root is 1 / (1e8 + sqrt(1e16 - 1)) = 5e-9
        // to 17 digits. The textbook (h - √Δ) gives 0 or a badly rounded value.
        let (h, c) = (-1e8, 1.0);
        let disc = h * h - c;
        let [small, large] = roots(1.0, h, c, disc).unwrap_or([f64::NAN; 2]);
        assert!((small - 5e-9).abs() < 1e-24, "{small:e}");
        assert!((large - 2e8).abs() < 1e-6, "{large:e}");
        let textbook = -h - disc.sqrt();
        assert!((textbook - 5e-9).abs() > 1e-10, "{textbook:e}");
    }

    #[test]
    fn linear_case_and_misses() {
        // a = 0: 2 h t + c = 0 with h = 2, c = -8: t = 2, the other root infinite
        // (q / 0 = -inf here, first in order; no interval holds it).
        let r = roots(0.0, 2.0, -8.0, 4.0).unwrap_or([f64::NAN; 2]);
        assert_eq!(r, [f64::NEG_INFINITY, 2.0]);
        assert_eq!(roots(1.0, 0.0, 1.0, -1.0), None);
        assert_eq!(roots(1.0, 1.0, 1.0, 0.0), None);
        assert_eq!(roots(1.0, 1.0, 1.0, f64::NAN), None);
    }
}
