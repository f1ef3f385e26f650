//! Sphere: `d² + 2 (R·Voc) d + (|Voc|² - r²) = 0` (thesis ch. 1.3), `N = normalize(P - C)`.
//!
//! The thesis's discriminant `(R·Voc)² - (|Voc|² - r²)` cancels when the sphere is small
//! and far (`|Voc| ≫ r`): its rounding error grows with `|Voc|²` while the answer is of
//! the order of `r²`, so a sphere of radius 0.1 at distance 1000 is noise. The test runs
//! in two stages (Haines, Günther and Akenine-Möller, "Precision Improvements for
//! Ray/Sphere Intersection", Ray Tracing Gems, 2019, ch. 7):
//! 1. the thesis's discriminant, trusted to say "certainly a miss" when it lies below
//!    a margin of `|Voc|²/2¹⁶` ([`sphere_may_hit`]; most tests end here, at the
//!    thesis's cost), and kept as it is when it lies above `|Voc|²/2⁸`
//!    ([`first_stage_suffices`]: then it is accurate to well under the secondary rays'
//!    offset, and a hit costs only the `sqrt` more);
//! 2. in between (a ray near the rim, or a small or far sphere: the discriminant is at
//!    most `r²`), `r² - |Voc - (R·Voc) R|²`, the squared radius less the squared
//!    distance from the centre to the ray, computed from the perpendicular vector: no
//!    cancellation.
//!
//! The roots stay `-(R·Voc) ± √disc`: the near root of a sphere ahead adds two terms of
//! one sign, and the far root is needed only from inside or on the surface, where
//! `|R·Voc| ≤ r`, so neither cancels more than the inputs' rounding.

use super::{first_stage_suffices, sphere_first_disc, sphere_may_hit, test_radius_sq};
use crate::counter::{Counter, Stat};
use crate::ray::Ray;
use crate::vec3::Vec3;

/// A sphere. A negative NFF radius means only the inside is visible.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    /// The radius as written in the scene (negative: inside visible).
    pub radius: f32,
    pub material: u32,
    /// `eye - center`, set by [`crate::variants::eye_space`] for the `bounded` variant.
    pub eye_offset: Vec3,
    radius_sq: f32,
}

impl Sphere {
    /// Builds a sphere; `radius` keeps its NFF sign.
    pub fn new(center: Vec3, radius: f32, material: u32) -> Self {
        Self {
            center,
            radius,
            material,
            eye_offset: Vec3::ZERO,
            radius_sq: test_radius_sq(radius),
        }
    }

    /// The squared radius the intersection test uses (-inf for a zero radius: never hit).
    pub fn radius_sq(&self) -> f32 {
        self.radius_sq
    }

    /// Whether only the inside of the sphere is visible (negative radius).
    pub fn inside_visible(&self) -> bool {
        self.radius < 0.0
    }

    /// Distance to the first visible intersection in `(t_min, t_max)`.
    ///
    /// Counts one `sub` and two `dot`; when the second stage runs (a hit near the rim
    /// or a near miss) one `scale`, one `sub` and one `dot` more; and when the ray
    /// meets the sphere one `sqrt`.
    #[inline(always)]
    pub fn intersect<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        t_max: f32,
        c: &mut C,
    ) -> Option<f32> {
        c.tally(Stat::SphereTest);
        let voc = ray.offset_from(self.center, self.eye_offset, c);
        let half_b = c.dot(ray.dir, voc);
        let oo = c.dot(voc, voc);
        // Stage 1. A zero-radius sphere (radius² = -inf, see `test_radius_sq`) ends here.
        let quick = sphere_first_disc(half_b, oo, self.radius_sq);
        if !sphere_may_hit(quick, oo) {
            return None;
        }
        let disc = if first_stage_suffices(quick, 1.0, oo) {
            quick
        } else {
            // Stage 2: the centre's offset across the ray.
            let along = c.scale(ray.dir, half_b);
            let across = c.sub(voc, along);
            let exact = self.radius_sq - c.dot(across, across);
            // A tangent ray (disc = 0) is never hit: it has no area that a pixel could
            // see, and the normal would be undefined. (A kept first stage is positive.)
            if exact <= 0.0 {
                return None;
            }
            exact
        };
        let root = c.sqrt(disc);
        let near = -half_b - root;
        let far = -half_b + root;
        let t = if !self.inside_visible() && near > t_min && near < t_max {
            near
        } else if far > t_min && far < t_max {
            far
        } else {
            return None;
        };
        c.tally(Stat::SphereHit);
        Some(t)
    }

    /// The visible side's normal at surface point `p`: outward, or inward when
    /// only the inside is visible.
    #[inline]
    pub fn normal<C: Counter>(&self, p: Vec3, c: &mut C) -> Vec3 {
        let radial = c.sub(p, self.center);
        let n = c.normalize(radial);
        if self.inside_visible() {
            n.flipped()
        } else {
            n
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::{Count, NoCount};

    fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
        Ray {
            origin: Vec3::from_array(o),
            dir: Vec3::from_array(d),
        }
    }

    #[test]
    fn hits_front_of_unit_sphere_at_hand_computed_distance() {
        // Eye at z = -5 looking +z at a sphere of radius 2 at (0, 0, 3): front at z = 1.
        let s = Sphere::new(Vec3::new(0.0, 0.0, 3.0), 2.0, 0);
        let t = s.intersect(
            &ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]),
            0.0,
            f32::INFINITY,
            &mut NoCount,
        );
        assert_eq!(t, Some(6.0));
        let n = s.normal(Vec3::new(0.0, 0.0, 1.0), &mut NoCount);
        assert_eq!(n.to_array(), [0.0, 0.0, -1.0]);
    }

    #[test]
    fn off_axis_hit_matches_pythagoras() {
        // Ray along +x at height y = 1 through a sphere of radius 2 at the origin:
        // enters at x = -sqrt(3), so t = 10 - sqrt(3) from x = -10.
        let s = Sphere::new(Vec3::ZERO, 2.0, 0);
        let t = s
            .intersect(
                &ray([-10.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
                0.0,
                f32::INFINITY,
                &mut NoCount,
            )
            .unwrap_or(f32::NAN);
        assert!((t - (10.0 - 3f32.sqrt())).abs() < 1e-5, "t = {t}");
    }

    #[test]
    fn misses_and_interval_limits() {
        let s = Sphere::new(Vec3::ZERO, 1.0, 0);
        assert_eq!(
            s.intersect(
                &ray([-5.0, 1.5, 0.0], [1.0, 0.0, 0.0]),
                0.0,
                100.0,
                &mut NoCount
            ),
            None
        );
        // Sphere behind the origin of the ray.
        assert_eq!(
            s.intersect(
                &ray([5.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
                0.0,
                100.0,
                &mut NoCount
            ),
            None
        );
        // Hit beyond t_max (a shadow ray stopping at the light) does not count.
        assert_eq!(
            s.intersect(
                &ray([-5.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
                0.0,
                3.0,
                &mut NoCount
            ),
            None
        );
        // From inside, the far wall is hit.
        assert_eq!(
            s.intersect(
                &ray([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
                0.0,
                100.0,
                &mut NoCount
            ),
            Some(1.0)
        );
    }

    #[test]
    fn negative_radius_shows_only_the_inside() {
        let s = Sphere::new(Vec3::ZERO, -1.0, 0);
        let t = s.intersect(
            &ray([-5.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
            0.0,
            100.0,
            &mut NoCount,
        );
        assert_eq!(
            t,
            Some(6.0),
            "the near (outer) wall is invisible; the far wall's inside is hit"
        );
        assert_eq!(
            s.normal(Vec3::new(1.0, 0.0, 0.0), &mut NoCount).to_array(),
            [-1.0, 0.0, 0.0]
        );
    }

    #[test]
    fn a_small_far_sphere_is_hit_where_the_thesis_discriminant_cancels() {
        // Radius 0.1 at distance 1000 on the z axis, rays along +z at a lateral offset.
        let s = Sphere::new(Vec3::new(0.0, 0.0, 1000.0), 0.1, 0);
        let along_z = |x: f32| ray([x, 0.0, 0.0], [0.0, 0.0, 1.0]);
        // In f32, |Voc|² = 1e6 + x² rounds to 1e6 (its ulp is 0.0625), so the thesis's
        // b² - (|Voc|² - r²) is exactly 0 for every offset: the sphere would vanish.
        let voc = Vec3::new(-0.05, 0.0, -1000.0);
        let half_b = NoCount.dot(Vec3::new(0.0, 0.0, 1.0), voc);
        let textbook = half_b * half_b - (NoCount.dot(voc, voc) - 0.01);
        assert_eq!(textbook, 0.0);
        // Hand-computed: offset 0.05 meets the sphere at z = 1000 - √(0.01 - 0.0025).
        // The first stage's discriminant (0) is far below 10⁶/2⁸: the second stage
        // runs, (R·Voc) R, Voc - (R·Voc) R and its square.
        let mut c = Count::default();
        let t = s
            .intersect(&along_z(0.05), 0.0, f32::INFINITY, &mut c)
            .unwrap_or(f32::NAN);
        assert_eq!(
            (c.get(Stat::Sub), c.get(Stat::Dot), c.get(Stat::Scale)),
            (2, 3, 1)
        );
        let expected = 1000.0 - 0.0075f64.sqrt();
        assert!(
            (f64::from(t) - expected).abs() < 1e-4,
            "t = {t}, expected {expected}"
        );
        // Just inside and just outside the rim (radius 0.1).
        assert!(
            s.intersect(&along_z(0.099), 0.0, f32::INFINITY, &mut NoCount)
                .is_some()
        );
        assert!(
            s.intersect(&along_z(0.101), 0.0, f32::INFINITY, &mut NoCount)
                .is_none()
        );
        // Far outside: the first stage says "miss" with the thesis's operations only.
        let mut c = Count::default();
        assert!(
            s.intersect(&along_z(5.0), 0.0, f32::INFINITY, &mut c)
                .is_none()
        );
        assert_eq!((c.get(Stat::Dot), c.get(Stat::Scale)), (2, 0));
    }

    #[test]
    fn exact_counts_of_one_ray_against_one_sphere() {
        let s = Sphere::new(Vec3::new(0.0, 0.0, 3.0), 2.0, 0);
        let mut c = Count::default();
        s.intersect(
            &ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]),
            0.0,
            f32::INFINITY,
            &mut c,
        );
        // b = R·Voc = -8, |Voc|² = 64: the first stage's b² - (|Voc|² - r²) = 4 is above
        // 64/2⁸, so it is kept and the second stage does not run.
        assert_eq!(
            (
                c.get(Stat::Sub),
                c.get(Stat::Dot),
                c.get(Stat::Scale),
                c.get(Stat::Sqrt)
            ),
            (1, 2, 0, 1),
            "hit: O - C, R·Voc and Voc·Voc; one sqrt"
        );
        assert_eq!((c.get(Stat::SphereTest), c.get(Stat::SphereHit)), (1, 1));

        let mut miss = Count::default();
        s.intersect(
            &ray([0.0, 5.0, -5.0], [0.0, 0.0, 1.0]),
            0.0,
            f32::INFINITY,
            &mut miss,
        );
        assert_eq!(
            (
                miss.get(Stat::Sub),
                miss.get(Stat::Dot),
                miss.get(Stat::Sqrt)
            ),
            (1, 2, 0)
        );
        assert_eq!(
            (miss.get(Stat::SphereTest), miss.get(Stat::SphereHit)),
            (1, 0)
        );
    }
}
