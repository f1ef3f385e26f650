//! Finite open cone (truncated, no caps), in the perpendicular form.
//!
//! The radius grows linearly along the axis, `r(m) = r_b + k m` with
//! `k = (|r_a| - |r_b|) / L`. Along the ray, `m(t) = f·a + t (d·a)`, so the radius at the
//! ray's axial position is `ρ₀ + ρ₁ t` with `ρ₀ = r_b + k (f·a)` and `ρ₁ = k (d·a)`, and
//! the ray meets the infinite cone where `|f⊥ + t d⊥|² = (ρ₀ + ρ₁ t)²`:
//! `A = d⊥·d⊥ - ρ₁²`, `h = f⊥·d⊥ - ρ₀ρ₁`, `c = f⊥·f⊥ - ρ₀²`. By Lagrange's identity the
//! discriminant is `Δ = h² - A c = |ρ₀ d⊥ - ρ₁ f⊥|² - |f⊥ × d⊥|²`: two squared lengths
//! of vectors formed directly, no difference of squared distances. `A` may be zero or
//! negative (a ray steeper than the cone's half-angle meets both nappes); the stable
//! roots ([`crate::quadratic::roots`]) handle both, and between the base and the apex
//! the radius `r(m)` is never negative, so the other nappe is never inside `(0, L)`.

use super::Axis;
use crate::quadratic;
use crate::ray::{Hit, Ray};
use glam::DVec3;

/// An open truncated cone; both radii negative shows only the inside.
#[derive(Clone, Debug, PartialEq)]
pub struct Cone {
    pub axis: Axis,
    /// The base radius as written.
    pub base_radius: f64,
    /// The apex radius as written.
    pub apex_radius: f64,
}

impl Cone {
    /// Whether only the inside is visible (both radii negative; mixed signs are read
    /// as a two-sided cone of the radii's magnitudes).
    pub fn inside_visible(&self) -> bool {
        self.base_radius < 0.0 && self.apex_radius < 0.0
    }

    /// The slope `k`: the radius gained per unit of axis.
    fn slope(&self) -> f64 {
        (self.apex_radius.abs() - self.base_radius.abs()) / self.axis.length
    }

    /// The first visible intersection in `(t_min, t_max)` with its axial coordinate,
    /// roots in ascending order. An inside-only cone shows a hit only where its outward
    /// normal faces away from the ray.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let f = ray.origin - self.axis.base;
        let (f_perp, f_along) = self.axis.split(f);
        let (d_perp, d_along) = self.axis.split(ray.dir);
        let k = self.slope();
        let rho0 = self.base_radius.abs() + k * f_along;
        let rho1 = k * d_along;
        let a = d_perp.length_squared() - rho1 * rho1;
        let half_b = f_perp.dot(d_perp) - rho0 * rho1;
        let c = f_perp.length_squared() - rho0 * rho0;
        let disc = (rho0 * d_perp - rho1 * f_perp).length_squared()
            - f_perp.cross(d_perp).length_squared();
        let roots = quadratic::roots(a, half_b, c, disc)?;
        roots.into_iter().find_map(|t| {
            let m = f_along + t * d_along;
            let hit = Hit { t, m };
            let visible = !self.inside_visible() || self.outward(ray, &hit).dot(ray.dir) > 0.0;
            (t > t_min && t < t_max && m > 0.0 && m < self.axis.length && visible).then_some(hit)
        })
    }

    /// The outward (not normalized) normal at `hit`: the radial vector from the axis,
    /// tilted back along the axis by the slope, `(f⊥ + t d⊥) - k r(m) a`.
    fn outward(&self, ray: &Ray, hit: &Hit) -> DVec3 {
        let (f_perp, _) = self.axis.split(ray.origin - self.axis.base);
        let (d_perp, _) = self.axis.split(ray.dir);
        let radial = f_perp + hit.t * d_perp;
        let k = self.slope();
        let radius = self.base_radius.abs() + k * hit.m;
        radial - (k * radius) * self.axis.dir
    }

    /// The visible side's unit normal at `hit` (NaN at the tip of a pointed cone, where
    /// there is none).
    pub fn normal(&self, ray: &Ray, hit: &Hit) -> DVec3 {
        let n = self.outward(ray, hit).normalize();
        if self.inside_visible() { -n } else { n }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::toward(DVec3::from_array(o), DVec3::from_array(d))
    }

    /// A 45° cone: radius 1 at z = 0 narrowing to a point at z = 1.
    fn pointed(base_radius: f64, apex_radius: f64) -> Cone {
        Cone {
            axis: Axis::new(DVec3::ZERO, DVec3::new(0.0, 0.0, 1.0)),
            base_radius,
            apex_radius,
        }
    }

    #[test]
    fn side_hit_and_normal_of_a_45_degree_cone() {
        // At height 0.5 the radius is 0.5: from x = -5 along +x, t = 4.5, outward
        // normal (-1, 0, 1)/√2.
        let cone = pointed(1.0, 0.0);
        let r = ray([-5.0, 0.0, 0.5], [1.0, 0.0, 0.0]);
        let hit = cone.intersect(&r, 0.0, f64::INFINITY);
        assert_eq!(hit, Some(Hit { t: 4.5, m: 0.5 }));
        let n = cone.normal(&r, &Hit { t: 4.5, m: 0.5 });
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((n - DVec3::new(-h, 0.0, h)).length() < 1e-15, "{n}");
        // A negative zero is not negative: mixed signs read as two-sided.
        assert!(!pointed(-1.0, -0.0).inside_visible());
        // Inside only (both radii negative): the outer wall at x = -0.625 faces the ray
        // and is skipped; the inner one at x = 0.625 (t = 5.625) is shown.
        let inner = Cone {
            apex_radius: -0.25,
            ..pointed(-1.0, 0.0)
        };
        // Radius 1 - 0.75 m: at m = 0.5 it is 0.625.
        let hit = inner.intersect(&r, 0.0, f64::INFINITY);
        let t = hit.map_or(f64::NAN, |h| h.t);
        assert!((t - 5.625).abs() < 1e-14, "{hit:?}");
    }

    #[test]
    fn ray_down_the_axis_meets_the_tip_region_of_a_widening_cone() {
        // Radius 0 at the base z = 0, 2 at z = 2 (half-angle 45°); from (0.5, 0, 5)
        // straight down: |x| = m gives m = 0.5, t = 4.5, on the inside (normal (1,0,-1)/√2
        // outward, ray going down: seen from inside, two-sided so shown).
        let cone = Cone {
            axis: Axis::new(DVec3::ZERO, DVec3::new(0.0, 0.0, 2.0)),
            base_radius: 0.0,
            apex_radius: 2.0,
        };
        let r = ray([0.5, 0.0, 5.0], [0.0, 0.0, -1.0]);
        let hit = cone.intersect(&r, 0.0, f64::INFINITY);
        assert_eq!(hit, Some(Hit { t: 4.5, m: 0.5 }));
        // A ray parallel to a generator (A = 0) meets the surface once: from (-4, 0, 1)
        // along (1, 0, 1)/√2, x = -4 + s, z = 1 + s meets x = -z at s = 1.5, z = 2.5:
        // beyond the apex end, so no hit.
        let r = ray([-4.0, 0.0, 1.0], [1.0, 0.0, 1.0]);
        assert_eq!(cone.intersect(&r, 0.0, f64::INFINITY), None);
        // Along (1, 0, 1)/√2 from (-1, 0, 0.5): x = -1 + s, z = 0.5 + s with |x| = z
        // at s = 0.25: t = 0.25 √2, m = 0.75 (A = 0, the linear root).
        let r = ray([-1.0, 0.0, 0.5], [1.0, 0.0, 1.0]);
        let hit = cone.intersect(&r, 0.0, f64::INFINITY);
        let hit = hit.unwrap_or(Hit {
            t: f64::NAN,
            m: f64::NAN,
        });
        assert!((hit.t - 0.25 * 2f64.sqrt()).abs() < 1e-14, "{hit:?}");
        assert!((hit.m - 0.75).abs() < 1e-14, "{hit:?}");
    }

    #[test]
    fn a_cone_that_is_a_cylinder_agrees_with_the_cylinder_formula() {
        // Radii 1 and 1 + 1e-9 over length 4: the wall at x = -1 from x = -5.
        let cone = Cone {
            axis: Axis::new(DVec3::ZERO, DVec3::new(0.0, 0.0, 4.0)),
            base_radius: 1.0,
            apex_radius: 1.0 + 1e-9,
        };
        let r = ray([-5.0, 0.0, 2.0], [1.0, 0.0, 0.0]);
        let t = cone
            .intersect(&r, 0.0, f64::INFINITY)
            .map_or(f64::NAN, |h| h.t);
        assert!((t - (4.0 - 0.5e-9)).abs() < 1e-13, "{t}");
    }
}
