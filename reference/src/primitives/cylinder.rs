//! Finite open cylinder (no caps), in the perpendicular form.
//!
//! With `f = O - B` (B the base), the unit axis `a`, and the parts of `f` and `d`
//! perpendicular to the axis, `f⊥ = f - (f·a) a` and `d⊥ = d - (d·a) a`, the ray meets
//! the infinite cylinder where `|f⊥ + t d⊥|² = r²`:
//! `A t² + 2 h t + c = 0` with `A = d⊥·d⊥`, `h = f⊥·d⊥`, `c = f⊥·f⊥ - r²`.
//! As for the sphere, the discriminant is formed without subtracting squares of the
//! distance: `Δ = h² - A c = A (r² - |g|²)` with `g = f⊥ - (h / A) d⊥`, the axis's
//! offset from the ray's closest approach in the plane across the axis. The hit is kept
//! when its axial coordinate `m = f·a + t (d·a)` lies in `(0, L)`.

use super::Axis;
use crate::quadratic;
use crate::ray::{Hit, Ray};
use glam::DVec3;

/// An open cylinder; a negative radius shows only the inside wall.
#[derive(Clone, Debug, PartialEq)]
pub struct Cylinder {
    pub axis: Axis,
    /// The radius as written (negative: inside visible).
    pub radius: f64,
}

impl Cylinder {
    /// Whether only the inside wall is visible.
    pub fn inside_visible(&self) -> bool {
        self.radius < 0.0
    }

    /// The first visible intersection in `(t_min, t_max)`, with its axial coordinate.
    /// The smaller root enters the infinite cylinder (outer wall), the larger leaves it
    /// (inner wall); inside-only keeps the larger alone. A ray along the axis (`A = 0`)
    /// never crosses the wall.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let (f_perp, f_along) = self.axis.split(ray.origin - self.axis.base);
        let (d_perp, d_along) = self.axis.split(ray.dir);
        let a = d_perp.length_squared();
        if !(a > 0.0) {
            return None;
        }
        let half_b = f_perp.dot(d_perp);
        let r_sq = self.radius * self.radius;
        let closest = f_perp - (half_b / a) * d_perp;
        let disc = a * (r_sq - closest.length_squared());
        let c = f_perp.length_squared() - r_sq;
        let roots = quadratic::roots(a, half_b, c, disc)?;
        let first = usize::from(self.inside_visible());
        roots[first..].iter().find_map(|&t| {
            let m = f_along + t * d_along;
            (t > t_min && t < t_max && m > 0.0 && m < self.axis.length).then_some(Hit { t, m })
        })
    }

    /// The visible side's unit normal at `hit` along `ray`: the radial direction
    /// `f⊥ + t d⊥` from the axis (outward; inward when only the inside is visible).
    pub fn normal(&self, ray: &Ray, hit: &Hit) -> DVec3 {
        let (f_perp, _) = self.axis.split(ray.origin - self.axis.base);
        let (d_perp, _) = self.axis.split(ray.dir);
        let n = (f_perp + hit.t * d_perp).normalize();
        if self.inside_visible() { -n } else { n }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Radius 1 around the z axis from z = 0 to z = 4.
    fn upright(radius: f64) -> Cylinder {
        Cylinder {
            axis: Axis::new(DVec3::ZERO, DVec3::new(0.0, 0.0, 4.0)),
            radius,
        }
    }

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::toward(DVec3::from_array(o), DVec3::from_array(d))
    }

    #[test]
    fn side_hit_at_the_hand_computed_distance_and_height() {
        // From (-5, 0, 2) along +x: the wall at x = -1 (t = 4, m = 2); inside only: x = 1.
        let r = ray([-5.0, 0.0, 2.0], [1.0, 0.0, 0.0]);
        assert_eq!(
            upright(1.0).intersect(&r, 0.0, f64::INFINITY),
            Some(Hit { t: 4.0, m: 2.0 })
        );
        assert_eq!(
            upright(1.0).normal(&r, &Hit { t: 4.0, m: 2.0 }),
            DVec3::new(-1.0, 0.0, 0.0)
        );
        let inner = upright(-1.0);
        assert_eq!(
            inner.intersect(&r, 0.0, f64::INFINITY),
            Some(Hit { t: 6.0, m: 2.0 })
        );
        assert_eq!(
            inner.normal(&r, &Hit { t: 6.0, m: 2.0 }),
            DVec3::new(-1.0, 0.0, 0.0)
        );
    }

    #[test]
    fn slanted_ray_through_the_open_end_hits_the_inner_wall() {
        // From (0, 0, 6) toward (1, 0, 2) (direction (1, 0, -4)/√17): it passes the open
        // top at z = 4 (x = 0.5, inside) and meets the wall x = 1 at z = 2, t = √17.
        let r = ray([0.0, 0.0, 6.0], [1.0, 0.0, -4.0]);
        let hit = upright(1.0).intersect(&r, 0.0, f64::INFINITY);
        let hit = hit.unwrap_or(Hit {
            t: f64::NAN,
            m: f64::NAN,
        });
        assert!((hit.t - 17f64.sqrt()).abs() < 1e-14, "{hit:?}");
        assert!((hit.m - 2.0).abs() < 1e-14, "{hit:?}");
        // Beyond the base (m < 0) and above the top (m > L) there is no wall.
        let r = ray([-5.0, 0.0, -1.0], [1.0, 0.0, 0.0]);
        assert_eq!(upright(1.0).intersect(&r, 0.0, f64::INFINITY), None);
        let r = ray([-5.0, 0.0, 4.5], [1.0, 0.0, 0.0]);
        assert_eq!(upright(1.0).intersect(&r, 0.0, f64::INFINITY), None);
    }

    #[test]
    fn rays_along_the_axis_tangent_or_zero_radius_miss() {
        let along = ray([0.5, 0.0, -3.0], [0.0, 0.0, 1.0]);
        assert_eq!(upright(1.0).intersect(&along, 0.0, f64::INFINITY), None);
        let tangent = ray([-5.0, 1.0, 2.0], [1.0, 0.0, 0.0]);
        assert_eq!(upright(1.0).intersect(&tangent, 0.0, f64::INFINITY), None);
        let through = ray([-5.0, 0.0, 2.0], [1.0, 0.0, 0.0]);
        assert_eq!(upright(0.0).intersect(&through, 0.0, f64::INFINITY), None);
    }

    #[test]
    fn a_thin_far_cylinder_is_hit_exactly_where_the_geometry_says() {
        // Radius 0.01 along y, 1000 units down +z: rays at x = 0.0099 hit at
        // 1000 - sqrt(r² - x²), at x = 0.0101 miss.
        let c = Cylinder {
            axis: Axis::new(DVec3::new(0.0, -1.0, 1000.0), DVec3::new(0.0, 1.0, 1000.0)),
            radius: 0.01,
        };
        let r = ray([0.0099, 0.0, 0.0], [0.0, 0.0, 1.0]);
        let t = c
            .intersect(&r, 0.0, f64::INFINITY)
            .map_or(f64::NAN, |h| h.t);
        let want = 1000.0 - (1e-4f64 - 0.0099 * 0.0099).sqrt();
        assert!((t - want).abs() < 1e-12, "{t} vs {want}");
        let r = ray([0.0101, 0.0, 0.0], [0.0, 0.0, 1.0]);
        assert_eq!(c.intersect(&r, 0.0, f64::INFINITY), None);
    }
}
