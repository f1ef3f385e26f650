//! Finite cylinder without caps (thesis ch. 1.3):
//! `a = 1 - (R·V)²`, `b = 2((R·Voc) - (R·V)(Voc·V))`, `c = |Voc|² - (Voc·V)² - r²`,
//! bounded by `0 < m < |Ct - Cb|` with `m = d (R·V) + Voc·V`; `N = normalize(P - (Cb + m V))`.
//!
//! As for the sphere, the thesis's discriminant `(b/2)² - a c` cancels for a thin or far
//! cylinder, so it screens out certain misses ([`quick_miss_margin`]) and is used as it
//! is only when clearly positive ([`first_stage_suffices`]: `disc a² ≥ |Voc|²/2⁸`).
//! Otherwise Lagrange's identity gives it without cancellation: with `u` and `w` the
//! parts of `Voc` and `R` across the axis, `(u·w)² - |w|²|u|² = -|u × w|²`, and `u × w`
//! lies along the axis with length `|V·(Voc × R)|`, so `disc = a r² - (V·(Voc × R))²`.

use super::{
    GeometryError, first_stage_suffices, ordered_roots, quick_miss_margin, test_radius_sq,
};
use crate::counter::{Counter, NoCount, Stat};
use crate::ray::Ray;
use crate::vec3::Vec3;

/// An open cylinder from `base` to `apex`. A negative radius shows only the inside.
#[derive(Clone, Debug, PartialEq)]
pub struct Cylinder {
    pub base: Vec3,
    pub apex: Vec3,
    /// The radius as written in the scene (negative: inside visible).
    pub radius: f32,
    pub material: u32,
    /// Unit axis from base to apex.
    pub axis: Vec3,
    /// Distance from base to apex (the thesis's Mmax).
    pub length: f32,
    /// `eye - base`, set by [`crate::variants::eye_space`] for the `bounded` variant.
    pub eye_offset: Vec3,
    radius_sq: f32,
}

impl Cylinder {
    /// Builds a cylinder; fails when base and apex coincide.
    pub fn new(base: Vec3, apex: Vec3, radius: f32, material: u32) -> Result<Self, GeometryError> {
        let (axis, length) = unit_axis(base, apex)?;
        Ok(Self {
            base,
            apex,
            radius,
            material,
            axis,
            length,
            eye_offset: Vec3::ZERO,
            radius_sq: test_radius_sq(radius),
        })
    }

    /// The squared radius the intersection test uses (-inf for a zero radius: never hit).
    pub fn radius_sq(&self) -> f32 {
        self.radius_sq
    }

    /// Whether only the inside wall is visible (negative radius).
    pub fn inside_visible(&self) -> bool {
        self.radius < 0.0
    }

    /// First visible intersection in `(t_min, t_max)` as `(t, m)`.
    ///
    /// Counts one `sub` and four `dot`; when the second stage runs (a hit near the rim
    /// or a near miss) one `cross` and one `dot` more; and when the ray meets the
    /// infinite cylinder one `sqrt`.
    #[inline(always)]
    pub fn intersect<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        t_max: f32,
        c: &mut C,
    ) -> Option<(f32, f32)> {
        c.tally(Stat::CylinderTest);
        let AxialTerms {
            voc,
            rv,
            ov,
            ro,
            oo,
        } = AxialTerms::new(ray, self.base, self.eye_offset, self.axis, c);
        let a = 1.0 - rv * rv;
        let half_b = ro - rv * ov;
        let cc = oo - ov * ov - self.radius_sq;
        // a = 0: the ray runs parallel to the axis and never crosses the wall. A zero
        // radius (radius² = -inf) gives -inf or NaN: never hit.
        let quick = half_b * half_b - a * cc;
        if !(quick >= -quick_miss_margin(oo)) || a <= 0.0 {
            return None;
        }
        let disc = if first_stage_suffices(quick, a, oo) {
            quick
        } else {
            let normal_to_both = c.cross(voc, ray.dir);
            let triple = c.dot(self.axis, normal_to_both);
            let exact = a * self.radius_sq - triple * triple;
            // (A kept first stage is positive: no test.)
            if !(exact > 0.0) {
                return None;
            }
            exact
        };
        let root = c.sqrt(disc);
        let roots = ordered_roots(a, half_b, root);
        // With a > 0 the smaller root enters the infinite cylinder (outside wall) and
        // the larger leaves it (inside wall), so "inside visible" keeps only the latter.
        let first = usize::from(self.inside_visible());
        for &t in &roots[first..] {
            if t > t_min && t < t_max {
                let m = ov + t * rv;
                if m > 0.0 && m < self.length {
                    c.tally(Stat::CylinderHit);
                    return Some((t, m));
                }
            }
        }
        None
    }

    /// The visible side's normal at surface point `p` with axial coordinate `m`.
    #[inline]
    pub fn normal<C: Counter>(&self, p: Vec3, m: f32, c: &mut C) -> Vec3 {
        let along = c.scale(self.axis, m);
        let on_axis = c.add(self.base, along);
        let radial = c.sub(p, on_axis);
        let n = c.normalize(radial);
        if self.inside_visible() {
            n.flipped()
        } else {
            n
        }
    }
}

/// The dot products a ray-quadric test around an axis needs, with `Voc = O - base`:
/// `R·V`, `Voc·V`, `R·Voc` and `Voc·Voc` (one `sub`, four `dot`), and `Voc` itself.
pub(super) struct AxialTerms {
    pub voc: Vec3,
    pub rv: f32,
    pub ov: f32,
    pub ro: f32,
    pub oo: f32,
}

impl AxialTerms {
    #[inline(always)]
    pub fn new<C: Counter, const FROM_EYE: bool>(
        ray: &Ray<FROM_EYE>,
        base: Vec3,
        eye_offset: Vec3,
        axis: Vec3,
        c: &mut C,
    ) -> Self {
        let voc = ray.offset_from(base, eye_offset, c);
        Self {
            voc,
            rv: c.dot(ray.dir, axis),
            ov: c.dot(voc, axis),
            ro: c.dot(ray.dir, voc),
            oo: c.dot(voc, voc),
        }
    }
}

/// Unit axis and length from `base` to `apex` (build time, not counted).
pub(super) fn unit_axis(base: Vec3, apex: Vec3) -> Result<(Vec3, f32), GeometryError> {
    let c = &mut NoCount;
    let d = c.sub(apex, base);
    let length_sq = c.dot(d, d);
    let length = c.sqrt(length_sq);
    if !(length > 0.0) || !length.is_finite() {
        return Err(GeometryError::ZeroLengthAxis);
    }
    Ok((c.scale(d, 1.0 / length), length))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::Count;

    fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
        Ray {
            origin: Vec3::from_array(o),
            dir: Vec3::from_array(d),
        }
    }

    fn z_cylinder(radius: f32) -> Cylinder {
        // Axis along +z from z = 0 to z = 2.
        Cylinder::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0), radius, 0)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn hits_side_wall_at_hand_computed_distance() {
        let cyl = z_cylinder(1.0);
        // From x = -5 at height z = 1 along +x: wall at x = -1, t = 4, m = 1.
        let mut c = Count::default();
        let hit = cyl.intersect(
            &ray([-5.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            0.0,
            f32::INFINITY,
            &mut c,
        );
        assert_eq!(hit, Some((4.0, 1.0)));
        // Voc = (-5, 0, 1): a = 1, b/2 = -5, c = 26 - 1 - 1, so the first stage's
        // discriminant 25 - 24 = 1 is above |Voc|²/2⁸ = 26/256 and is kept: no `cross`,
        // no fifth `dot`.
        assert_eq!(
            (
                c.get(Stat::Sub),
                c.get(Stat::Dot),
                c.get(Stat::Cross),
                c.get(Stat::Sqrt)
            ),
            (1, 4, 0, 1)
        );
        let n = cyl.normal(Vec3::new(-1.0, 0.0, 1.0), 1.0, &mut NoCount);
        assert_eq!(n.to_array(), [-1.0, 0.0, 0.0]);
    }

    #[test]
    fn body_bounds_reject_hits_beyond_the_ends() {
        let cyl = z_cylinder(1.0);
        // Above the top (z = 2.5) and below the base (z = -0.1): the infinite cylinder is
        // hit but 0 < m < 2 fails.
        for z in [2.5, -0.1] {
            assert_eq!(
                cyl.intersect(
                    &ray([-5.0, 0.0, z], [1.0, 0.0, 0.0]),
                    0.0,
                    100.0,
                    &mut NoCount
                ),
                None
            );
        }
        // Parallel to the axis, inside: never crosses the wall.
        assert_eq!(
            cyl.intersect(
                &ray([0.5, 0.0, -5.0], [0.0, 0.0, 1.0]),
                0.0,
                100.0,
                &mut NoCount
            ),
            None
        );
    }

    #[test]
    fn open_end_shows_the_inner_wall() {
        let cyl = z_cylinder(1.0);
        // Enter through the open top at 45°: from (-1.1, 0, 2.2) along (1, 0, -1)/sqrt2 the
        // outer wall x = -1 is met at z = 2.1, above the top, so it is skipped; the
        // inner wall x = +1 is met after 2.1 units of x: t = 2.1 sqrt2, z = m = 0.1.
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let r = ray([-1.1, 0.0, 2.2], [h, 0.0, -h]);
        let (t, m) = cyl
            .intersect(&r, 0.0, 100.0, &mut NoCount)
            .unwrap_or((f32::NAN, f32::NAN));
        assert!((t - 2.1 * 2f32.sqrt()).abs() < 1e-5, "t = {t}");
        assert!((m - 0.1).abs() < 1e-5, "m = {m}");
    }

    #[test]
    fn oblique_axis_distance_and_counts() {
        // Axis from (1,1,1) along (1,1,0)/sqrt2, length 4sqrt2 ; radius 0.5. A ray down -z
        // through the axis point (3,3,·) hits the top of the wall at z = 1.5: t = 8.5.
        let cyl = Cylinder::new(Vec3::new(1.0, 1.0, 1.0), Vec3::new(5.0, 5.0, 1.0), 0.5, 0)
            .unwrap_or_else(|e| panic!("{e}"));
        let mut c = Count::default();
        let hit = cyl.intersect(&ray([3.0, 3.0, 10.0], [0.0, 0.0, -1.0]), 0.0, 100.0, &mut c);
        let (t, m) = hit.unwrap_or((f32::NAN, f32::NAN));
        assert!(
            (t - 8.5).abs() < 1e-5 && (m - 2.0 * 2f32.sqrt()).abs() < 1e-5,
            "t = {t}, m = {m}"
        );
        assert_eq!(
            (
                c.get(Stat::Sub),
                c.get(Stat::Dot),
                c.get(Stat::Cross),
                c.get(Stat::Sqrt)
            ),
            (1, 5, 1, 1),
            "Voc, R·V, Voc·V, R·Voc, Voc·Voc; then (the first stage's 81 - 80.75 is below \
             |Voc|²/2⁸ = 89/256) V·(Voc × R); one sqrt"
        );
        assert_eq!(
            (c.get(Stat::CylinderTest), c.get(Stat::CylinderHit)),
            (1, 1)
        );
    }

    #[test]
    fn a_thin_far_cylinder_is_hit_where_the_thesis_discriminant_cancels() {
        // Radius 0.05 along y, 1000 away on the z axis; rays along +z at offset x.
        let cyl = Cylinder::new(
            Vec3::new(0.0, -1.0, 1000.0),
            Vec3::new(0.0, 1.0, 1000.0),
            0.05,
            0,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let along_z = |x: f32| ray([x, 0.0, 0.0], [0.0, 0.0, 1.0]);
        // Hand-computed: offset 0.03 meets the wall at z = 1000 - √(0.0025 - 0.0009) = 999.96.
        let (t, m) = cyl
            .intersect(&along_z(0.03), 0.0, f32::INFINITY, &mut NoCount)
            .unwrap_or((f32::NAN, f32::NAN));
        assert!(
            (t - 999.96).abs() < 1e-4 && (m - 1.0).abs() < 1e-6,
            "t = {t}, m = {m}"
        );
        assert!(
            cyl.intersect(&along_z(0.049), 0.0, f32::INFINITY, &mut NoCount)
                .is_some()
        );
        assert!(
            cyl.intersect(&along_z(0.051), 0.0, f32::INFINITY, &mut NoCount)
                .is_none()
        );
        // The thesis's discriminant at offset 0.03 is lost in |Voc|²'s rounding.
        let (a, half_b, cc) = (1.0f32, -1000.0f32, (1.0e6f32 + 0.0009 + 1.0) - 1.0 - 0.0025);
        assert_eq!(half_b * half_b - a * cc, 0.0);
    }

    #[test]
    fn negative_radius_shows_only_the_inner_wall() {
        let cyl = z_cylinder(-1.0);
        let hit = cyl.intersect(
            &ray([-5.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            0.0,
            100.0,
            &mut NoCount,
        );
        assert_eq!(hit, Some((6.0, 1.0)));
        let n = cyl.normal(Vec3::new(1.0, 0.0, 1.0), 1.0, &mut NoCount);
        assert_eq!(n.to_array(), [-1.0, 0.0, 0.0], "inner wall faces the axis");
    }

    #[test]
    fn zero_length_axis_is_an_error() {
        assert_eq!(
            Cylinder::new(Vec3::ZERO, Vec3::ZERO, 1.0, 0),
            Err(GeometryError::ZeroLengthAxis)
        );
    }
}
