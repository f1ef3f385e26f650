//! Sphere, after Haines et al., *Ray Tracing Gems* ch. 7 ("Precision Improvements for
//! Ray/Sphere Intersection").
//!
//! With `f = O - C` and a unit direction `d`, the ray meets the sphere where
//! `t² + 2 (f·d) t + (f·f - r²) = 0`. The textbook discriminant `(f·d)² - (f·f - r²)`
//! subtracts two numbers of size `|f|²` to get one of size `r²`: for a sphere of radius
//! 0.01 a thousand units away that loses 10 of f32's 24 bits, and all of them below
//! `r ≈ 0.03`. Here `Δ = r² - |f - (f·d) d|²`, the squared radius less the squared
//! distance from the centre to the ray, which loses only a factor `|f| / r`; the roots
//! come from [`crate::quadratic::roots`] (`q = -(b + sign(b) √Δ)`, `t₀ = c/q`, `t₁ = q`).

use crate::quadratic;
use crate::ray::{Hit, Ray};
use glam::DVec3;

/// A sphere; a negative radius shows only the inside.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    pub center: DVec3,
    /// The radius as written (negative: inside visible).
    pub radius: f64,
}

impl Sphere {
    /// Whether only the inside is visible.
    pub fn inside_visible(&self) -> bool {
        self.radius < 0.0
    }

    /// The first visible intersection in `(t_min, t_max)`: the near root unless only the
    /// inside is visible, else the far one. A tangent ray is no hit.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let f = ray.origin - self.center;
        let half_b = f.dot(ray.dir);
        let r_sq = self.radius * self.radius;
        // The centre's offset from the ray, perpendicular to it.
        let off_ray = f - half_b * ray.dir;
        let disc = r_sq - off_ray.length_squared();
        let c = f.length_squared() - r_sq;
        let [near, far] = quadratic::roots(1.0, half_b, c, disc)?;
        let inside = |t: f64| t > t_min && t < t_max;
        if !self.inside_visible() && inside(near) {
            Some(Hit::at(near))
        } else if inside(far) {
            Some(Hit::at(far))
        } else {
            None
        }
    }

    /// The visible side's unit normal at the hit `t` along `ray` (outward, inward when
    /// only the inside is visible). The radial vector is `f + t d`, relative to the
    /// centre, rather than the hit point less the centre (two large numbers).
    pub fn normal(&self, ray: &Ray, t: f64) -> DVec3 {
        let radial = (ray.origin - self.center) + t * ray.dir;
        let n = radial.normalize();
        if self.inside_visible() { -n } else { n }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::toward(DVec3::from_array(o), DVec3::from_array(d))
    }

    #[test]
    fn hits_the_near_side_at_the_hand_computed_distance() {
        // Eye at z = -5 looking +z; radius 2 at z = 3: front at z = 1, t = 6, back t = 10.
        let s = Sphere {
            center: DVec3::new(0.0, 0.0, 3.0),
            radius: 2.0,
        };
        let r = ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]);
        assert_eq!(s.intersect(&r, 0.0, f64::INFINITY), Some(Hit::at(6.0)));
        assert_eq!(s.normal(&r, 6.0), DVec3::new(0.0, 0.0, -1.0));
        // Beyond the near root's reach the far one is not hit either (t_max = 5).
        assert_eq!(s.intersect(&r, 0.0, 5.0), None);
        // From inside (t_min past the front) the back is hit.
        assert_eq!(s.intersect(&r, 7.0, f64::INFINITY), Some(Hit::at(10.0)));
        // Inside visible: the far root only, normal pointing inward (toward -z at z = 5).
        let inner = Sphere {
            radius: -2.0,
            ..s.clone()
        };
        assert_eq!(inner.intersect(&r, 0.0, f64::INFINITY), Some(Hit::at(10.0)));
        assert_eq!(inner.normal(&r, 10.0), DVec3::new(0.0, 0.0, -1.0));
    }

    #[test]
    fn off_axis_hit_matches_pythagoras_and_tangent_rays_miss() {
        // Along +x at height 1 through radius 2 at the origin: enters at x = -√3.
        let s = Sphere {
            center: DVec3::ZERO,
            radius: 2.0,
        };
        let hit = s.intersect(&ray([-10.0, 1.0, 0.0], [1.0, 0.0, 0.0]), 0.0, f64::INFINITY);
        let t = hit.map_or(f64::NAN, |h| h.t);
        assert!((t - (10.0 - 3f64.sqrt())).abs() < 1e-14, "t = {t}");
        // Height 2: tangent, no hit; height 2.001: miss.
        for y in [2.0, 2.001] {
            let r = ray([-10.0, y, 0.0], [1.0, 0.0, 0.0]);
            assert_eq!(s.intersect(&r, 0.0, f64::INFINITY), None, "y = {y}");
        }
    }

    #[test]
    fn a_small_far_sphere_is_hit_exactly_where_the_geometry_says() {
        // Radius 0.01 at distance 1000: rays at height 0.0099 hit, 0.0101 miss; the hit
        // distance is 1000 - sqrt(r² - h²).
        let s = Sphere {
            center: DVec3::new(0.0, 0.0, 1000.0),
            radius: 0.01,
        };
        for (h, hits) in [(0.0099, true), (0.0101, false), (0.0, true)] {
            let r = ray([0.0, h, 0.0], [0.0, 0.0, 1.0]);
            let got = s.intersect(&r, 0.0, f64::INFINITY);
            assert_eq!(got.is_some(), hits, "h = {h}");
            if let Some(hit) = got {
                let want = 1000.0 - (0.01f64 * 0.01 - h * h).sqrt();
                assert!((hit.t - want).abs() < 1e-12, "{} vs {want}", hit.t);
            }
        }
    }
}
