//! Finite cone (truncated, no caps) between a base and an apex radius.
//!
//! The radius grows linearly along the axis, `r(m) = rb + k m` with `k = (ra - rb) / L`.
//! Substituting the ray into `|P - Q(m)|² = r(m)²` gives the cylinder's quadratic with
//! `(1 + k²)` weighting the axial terms:
//! `a = 1 - (1+k²)(R·V)²`, `b/2 = R·Voc - (1+k²)(R·V)(Voc·V) - rb k (R·V)`,
//! `c = |Voc|² - (1+k²)(Voc·V)² - 2 rb k (Voc·V) - rb²`. Unlike the cylinder, `a` may be
//! zero or negative (rays steeper than the cone's half-angle), so roots are ordered
//! explicitly. The outward normal is `normalize((P - Q) - k r(m) V)`.
//!
//! As for the sphere and the cylinder, that discriminant screens out certain misses
//! ([`quick_miss_margin`]) and is used as it is only when clearly positive
//! ([`first_stage_suffices`], with the margin's scale). Otherwise it is computed
//! without cancellation: with
//! `u`, `w` the parts of `Voc` and `R` across the axis and `s0 = rb + k (Voc·V)`,
//! `s1 = k (R·V)` the radius terms, `(b/2)² - a c = |s0 w - s1 u|² - |u × w|²`, where
//! `s0 w - s1 u = s0 R - s1 Voc - (s0 (R·V) - s1 (Voc·V)) V` and `|u × w| = |V·(Voc × R)|`
//! (the cylinder's identity), both squares of vectors computed directly.

use super::cylinder::{AxialTerms, unit_axis};
use super::{GeometryError, first_stage_suffices, ordered_roots, quick_miss_margin};
use crate::counter::{Counter, Stat};
use crate::ray::Ray;
use crate::vec3::Vec3;

/// An open truncated cone. Both radii negative: only the inside is visible.
#[derive(Clone, Debug, PartialEq)]
pub struct Cone {
    pub base: Vec3,
    pub apex: Vec3,
    /// Base radius as written in the scene.
    pub base_radius: f32,
    /// Apex radius as written in the scene.
    pub apex_radius: f32,
    pub material: u32,
    /// Unit axis from base to apex.
    pub axis: Vec3,
    /// Distance from base to apex.
    pub length: f32,
    /// `eye - base`, set by [`crate::variants::eye_space`] for the `bounded` variant.
    pub eye_offset: Vec3,
    rb: f32,
    slope: f32,
    axial_weight: f32,
}

impl Cone {
    /// Builds a cone; fails when base and apex coincide.
    pub fn new(
        base: Vec3,
        base_radius: f32,
        apex: Vec3,
        apex_radius: f32,
        material: u32,
    ) -> Result<Self, GeometryError> {
        let (axis, length) = unit_axis(base, apex)?;
        let rb = base_radius.abs();
        let slope = (apex_radius.abs() - rb) / length;
        Ok(Self {
            base,
            apex,
            base_radius,
            apex_radius,
            material,
            axis,
            length,
            eye_offset: Vec3::ZERO,
            rb,
            slope,
            axial_weight: 1.0 + slope * slope,
        })
    }

    /// Whether only the inside is visible (both radii negative).
    pub fn inside_visible(&self) -> bool {
        self.base_radius < 0.0 && self.apex_radius < 0.0
    }

    /// First visible intersection in `(t_min, t_max)` as `(t, m)`.
    ///
    /// Counts one `sub` and four `dot`; when the second stage runs (a hit near the rim
    /// or a near miss) three `scale`, two `sub`, one `cross` and two `dot` more; and
    /// when the ray meets the infinite cone one `sqrt`.
    #[inline(always)]
    pub fn intersect<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        t_max: f32,
        c: &mut C,
    ) -> Option<(f32, f32)> {
        c.tally(Stat::ConeTest);
        let AxialTerms {
            voc,
            rv,
            ov,
            ro,
            oo,
        } = AxialTerms::new(ray, self.base, self.eye_offset, self.axis, c);
        let (k, w, rb) = (self.slope, self.axial_weight, self.rb);
        let a = 1.0 - w * rv * rv;
        let half_b = ro - w * rv * ov - rb * k * rv;
        let cc = oo - w * ov * ov - 2.0 * rb * k * ov - rb * rb;
        let roots = if a == 0.0 {
            if half_b == 0.0 {
                return None;
            }
            let t = -cc / (2.0 * half_b);
            [t, t]
        } else {
            // The cancelling terms are bounded by w² (|Voc|² + rb²) (|a| ≤ w, |c| ≤ 2 w (…)).
            let scale = w * w * (oo + rb * rb);
            let quick = half_b * half_b - a * cc;
            if !(quick >= -quick_miss_margin(scale)) {
                return None;
            }
            let disc = if first_stage_suffices(quick, a, scale) {
                quick
            } else {
                let (s0, s1) = (rb + k * ov, k * rv);
                let (dir_part, offset_part) = (c.scale(ray.dir, s0), c.scale(voc, s1));
                let radial = c.sub(dir_part, offset_part);
                let axial = c.scale(self.axis, s0 * rv - s1 * ov);
                let g = c.sub(radial, axial);
                let normal_to_both = c.cross(voc, ray.dir);
                let triple = c.dot(self.axis, normal_to_both);
                let exact = c.dot(g, g) - triple * triple;
                // (A kept first stage is positive: no test.)
                if !(exact > 0.0) {
                    return None;
                }
                exact
            };
            ordered_roots(a, half_b, c.sqrt(disc))
        };
        for t in roots {
            if t > t_min && t < t_max {
                let m = ov + t * rv;
                if m > 0.0 && m < self.length && self.side_visible(ro, rv, t, m) {
                    c.tally(Stat::ConeHit);
                    return Some((t, m));
                }
            }
        }
        None
    }

    /// Whether the side of the surface the ray meets at `(t, m)` is visible: always for
    /// a two-sided cone; for an inside-only cone when the outward normal faces away from
    /// the ray (its dot with the ray direction, from scalars already computed, is > 0).
    #[inline(always)]
    fn side_visible(&self, ro: f32, rv: f32, t: f32, m: f32) -> bool {
        if !self.inside_visible() {
            return true;
        }
        let radius = self.rb + self.slope * m;
        ro + t - m * rv - self.slope * radius * rv > 0.0
    }

    /// The visible side's normal at surface point `p` with axial coordinate `m`.
    #[inline]
    pub fn normal<C: Counter>(&self, p: Vec3, m: f32, c: &mut C) -> Vec3 {
        let along = c.scale(self.axis, m);
        let on_axis = c.add(self.base, along);
        let radial = c.sub(p, on_axis);
        let radius = self.rb + self.slope * m;
        let tilt = c.scale(self.axis, self.slope * radius);
        let outward = c.sub(radial, tilt);
        let n = c.normalize(outward);
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

    /// A 45° cone: radius 1 at z = 0 narrowing to a point at z = 1.
    fn pointed() -> Cone {
        Cone::new(Vec3::ZERO, 1.0, Vec3::new(0.0, 0.0, 1.0), 0.0, 0)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn side_hit_and_normal_of_a_45_degree_cone() {
        let cone = pointed();
        // At z = 0.5 the radius is 0.5: from x = -5 along +x the wall is at x = -0.5.
        let hit = cone.intersect(
            &ray([-5.0, 0.0, 0.5], [1.0, 0.0, 0.0]),
            0.0,
            100.0,
            &mut NoCount,
        );
        assert_eq!(hit, Some((4.5, 0.5)));
        let n = cone.normal(Vec3::new(-0.5, 0.0, 0.5), 0.5, &mut NoCount);
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let [x, y, z] = n.to_array();
        assert!(
            (x + h).abs() < 1e-6 && y.abs() < 1e-6 && (z - h).abs() < 1e-6,
            "n = {n:?}"
        );
    }

    #[test]
    fn the_second_stage_runs_only_when_the_first_is_not_clearly_positive() {
        // The 45° cone: k = -1, weight 2, rb = 1; rays along +x at z = 0.5 (radius 0.5)
        // from x0: Voc = (x0, 0, 0.5), a = 1, b/2 = x0, c = x0² + 0.25 - 0.5 + 1 - 1, so
        // the first stage's discriminant is 0.25 against a scale of 4 (x0² + 1.25).
        let count = |x0: f32| {
            let mut c = Count::default();
            let hit =
                pointed().intersect(&ray([x0, 0.0, 0.5], [1.0, 0.0, 0.0]), 0.0, 100.0, &mut c);
            assert_eq!(hit, Some((-0.5 - x0, 0.5)));
            [Stat::Sub, Stat::Dot, Stat::Scale, Stat::Cross, Stat::Sqrt].map(|s| c.get(s))
        };
        // x0 = -1.5: 0.25 ≥ 14/2⁸, kept.
        assert_eq!(count(-1.5), [1, 4, 0, 0, 1]);
        // x0 = -5: 0.25 < 105/2⁸, recomputed: s0 R, s1 Voc, their difference, the axial
        // part and its removal, Voc × R, V·(Voc × R) and |g|².
        assert_eq!(count(-5.0), [1 + 2, 4 + 2, 3, 1, 1]);
    }

    #[test]
    fn steep_ray_with_negative_a_hits_from_above() {
        // Straight down at x = 0.25: a = 1 - 2 = -1 < 0; the wall is at z = 0.75.
        let hit = pointed().intersect(
            &ray([0.25, 0.0, 5.0], [0.0, 0.0, -1.0]),
            0.0,
            100.0,
            &mut NoCount,
        );
        let (t, m) = hit.unwrap_or((f32::NAN, f32::NAN));
        assert!(
            (t - 4.25).abs() < 1e-5 && (m - 0.75).abs() < 1e-5,
            "t = {t}, m = {m}"
        );
    }

    #[test]
    fn misses_outside_the_body() {
        let cone = pointed();
        // Above the apex and beside the cone.
        assert_eq!(
            cone.intersect(
                &ray([-5.0, 0.0, 1.5], [1.0, 0.0, 0.0]),
                0.0,
                100.0,
                &mut NoCount
            ),
            None
        );
        assert_eq!(
            cone.intersect(
                &ray([-5.0, 2.0, 0.5], [1.0, 0.0, 0.0]),
                0.0,
                100.0,
                &mut NoCount
            ),
            None
        );
    }

    #[test]
    fn equal_radii_reduce_to_the_cylinder() {
        let cone = Cone::new(Vec3::ZERO, 1.0, Vec3::new(0.0, 0.0, 2.0), 1.0, 0)
            .unwrap_or_else(|e| panic!("{e}"));
        let hit = cone.intersect(
            &ray([-5.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            0.0,
            100.0,
            &mut NoCount,
        );
        assert_eq!(hit, Some((4.0, 1.0)));
    }

    #[test]
    fn inside_only_cone_skips_the_outer_wall() {
        let cone = Cone::new(Vec3::ZERO, -1.0, Vec3::new(0.0, 0.0, 1.0), -0.0001, 0)
            .unwrap_or_else(|e| panic!("{e}"));
        let (t, _) = cone
            .intersect(
                &ray([-5.0, 0.0, 0.5], [1.0, 0.0, 0.0]),
                0.0,
                100.0,
                &mut NoCount,
            )
            .unwrap_or((f32::NAN, 0.0));
        assert!((t - 5.5).abs() < 1e-3, "far wall at x = +0.5, t = {t}");
    }

    #[test]
    fn coincident_ends_are_an_error() {
        let p = Vec3::new(1.0, 2.0, 3.0);
        assert_eq!(
            Cone::new(p, 1.0, p, 0.5, 0),
            Err(GeometryError::ZeroLengthAxis)
        );
    }
}
