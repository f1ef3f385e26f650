//! Ray-primitive intersection tests, one primitive per file.
//!
//! Each test counts itself (`tests.<kind>.tests` on entry, `.hits` when it reports an
//! intersection inside the ray's interval) next to the code it counts. A test returns
//! only the distance (and, for quadrics, the axial coordinate); the surface normal is
//! computed afterwards for the closest hit alone (the thesis's "hit body").

mod cone;
mod cylinder;
mod edge_slabs;
mod patch;
mod plane;
mod polygon;
mod sphere;

pub use cone::Cone;
pub use cylinder::Cylinder;
pub use patch::Patch;
pub use plane::PlanarOutline;
pub use polygon::Polygon;
pub use sphere::Sphere;

/// Why a primitive could not be built from its description.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeometryError {
    #[error("a polygon needs at least 3 vertices, found {0}")]
    TooFewVertices(usize),
    #[error("the first three polygon vertices are collinear or coincident (no plane normal)")]
    DegeneratePolygon,
    #[error("the cone/cylinder base and apex coincide (zero-length axis)")]
    ZeroLengthAxis,
    /// The 1-based vertex whose normal is the zero vector.
    #[error("the normal of vertex {0} has zero length")]
    ZeroNormal(usize),
    #[error("patch has {vertices} vertices but {normals} normals")]
    NormalCountMismatch { vertices: usize, normals: usize },
}

/// The squared radius a quadric test uses: `radius²`, or -inf when that is zero (a zero
/// radius, or one whose square underflows). A point or a line has no area to see, but
/// rounding can make its discriminant slightly positive and report a hit whose normal
/// is undefined; -inf makes every discriminant -inf (or NaN), never a hit, with no
/// extra test in the intersection loop.
pub(crate) fn test_radius_sq(radius: f32) -> f32 {
    let sq = radius * radius;
    if sq > 0.0 { sq } else { f32::NEG_INFINITY }
}

/// `2⁻¹⁶`: see [`quick_miss_margin`].
pub(crate) const QUICK_MISS_FRACTION: f32 = 1.0 / 65536.0;

/// The margin below which a quadric test's first-stage (the thesis's) discriminant
/// certainly means a miss, for `scale` bounding the terms that cancel in it (`|Voc|²` for
/// the sphere and the cylinder, weighted by the slope for the cone). Those terms carry
/// rounding errors of a few ulps of `scale` (about 10 ε·scale for the sphere's products
/// and sums, ε = 2⁻²⁴); the margin is 2⁻¹⁶·scale = 256 ε·scale, well above any of them,
/// so no hit is ever rejected, and a power of two, so the product is exact. Tests that
/// pass this stage (hits and near misses) compute the discriminant again without
/// cancellation, unless it is far from zero ([`first_stage_suffices`]).
#[inline(always)]
pub(crate) fn quick_miss_margin(scale: f32) -> f32 {
    scale * QUICK_MISS_FRACTION
}

/// The sphere test's first stage: whether the thesis's discriminant `disc`
/// ([`sphere_first_disc`]) may show a hit, i.e. lies above
/// `-`[`quick_miss_margin`]`(|Voc|²)`. Either side's rounding (a few ulps of `|Voc|²`)
/// is far inside the margin. A zero radius (`r² = -inf`, so `disc = -inf`) and a NaN
/// say no. Every path (scalar, lanes, packs) calls this one function, so their
/// decisions agree bit for bit.
#[inline(always)]
pub(crate) fn sphere_may_hit(disc: f32, oo: f32) -> bool {
    disc >= -quick_miss_margin(oo)
}

/// `2⁻⁸`: see [`first_stage_suffices`].
const TRUSTED_FRACTION: f32 = 1.0 / 256.0;

/// Whether a quadric test's first-stage (the thesis's) discriminant `disc` of
/// `a t² + 2 half_b t + c = 0` is accurate enough to take the roots from, so that the
/// second stage can be skipped: `disc a² > 2⁻⁸ scale`, `scale` as for
/// [`quick_miss_margin`]. Strictly greater, so a kept `disc` is positive (even where
/// the product underflows) and the caller needs no test of its sign.
///
/// Error bound (ε = 2⁻²⁴, first order): the first stage's `disc` is off by at most
/// `δ = k ε scale + 2 ε disc`, with `k ≈ 12` for the sphere (7 from `(R·Voc)²`, 3 from
/// `|Voc|²`, 2 from the sums) and `k < 100` for the cylinder and the cone (a
/// componentwise worst case over their longer sums; independent roundings mostly
/// cancel). A root `(-half_b ± √disc)/a` is then off by `δ/(2 |a| √disc)`, which the
/// rule bounds by `(k/2) ε √scale / √2⁻⁸ = 8 k ε √scale` plus an ulp of `√disc`: at
/// most `96 ε |Voc| ≈ 6e-6 |Voc|` for the sphere and `5e-5 √scale` for the others,
/// below the `1e-4` (relative) offset that keeps secondary rays off their surface (the
/// tests below check these bounds against f64 roots).
/// Where the thesis's discriminant fails (small or far quadrics, rays near the rim)
/// `disc` is small against `scale` and the second stage runs. A NaN `disc` says
/// no. Every path (scalar, lanes, packs) calls this one function, so their
/// choices, and thus their pictures, agree bit for bit.
#[inline(always)]
pub(crate) fn first_stage_suffices(disc: f32, a: f32, scale: f32) -> bool {
    disc * (a * a) > scale * TRUSTED_FRACTION
}

/// The sphere test's first-stage (the thesis's) discriminant `(R·Voc)² - (|Voc|² - r²)`,
/// for [`sphere_may_hit`] and [`first_stage_suffices`]. In this order `|Voc|² - r²` is
/// ready with `(R·Voc)²`, so a kept discriminant's square root waits for no more
/// operations than in the thesis's test.
#[inline(always)]
pub(crate) fn sphere_first_disc(half_b: f32, oo: f32, radius_sq: f32) -> f32 {
    half_b * half_b - (oo - radius_sq)
}

/// The two roots of `a t² + 2 half_b t + c = 0` in ascending order, given the square
/// root of the discriminant `half_b² - a c`. `a` must not be zero.
#[inline(always)]
pub(crate) fn ordered_roots(a: f32, half_b: f32, root: f32) -> [f32; 2] {
    let t1 = (-half_b - root) / a;
    let t2 = (-half_b + root) / a;
    if t1 <= t2 { [t1, t2] } else { [t2, t1] }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::{Count, Counter, NoCount, Stat};
    use crate::ray::Ray;
    use crate::vec3::Vec3;

    /// The unit roundoff ε = 2⁻²⁴ of the error bounds.
    const EPS: f64 = f32::EPSILON as f64 / 2.0;

    /// A fixed pseudo-random sequence in [-1, 1).
    struct Lcg(u32);

    impl Lcg {
        fn next(&mut self) -> f32 {
            self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (self.0 >> 8) as f32 / (1u32 << 23) as f32 - 1.0
        }

        fn vec(&mut self, scale: f32) -> Vec3 {
            Vec3::new(
                self.next() * scale,
                self.next() * scale,
                self.next() * scale,
            )
        }
    }

    fn f64s(v: Vec3) -> [f64; 3] {
        v.to_array().map(f64::from)
    }

    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    /// The distance from `t` to the nearer root of `a t² + 2 half_b t + c = 0` (f64).
    fn root_error(t: f32, a: f64, half_b: f64, c: f64) -> f64 {
        let root = (half_b * half_b - a * c).max(0.0).sqrt();
        let t = f64::from(t);
        [(-half_b - root) / a, (-half_b + root) / a]
            .map(|r| (t - r).abs())
            .into_iter()
            .fold(f64::INFINITY, f64::min)
    }

    /// A ray from a random point at up to `reach` from `target`'s neighbourhood towards
    /// a random point within `spread` of `target`.
    fn ray_towards(g: &mut Lcg, target: Vec3, spread: f32, reach: f32) -> Ray {
        let origin = NoCount.add(target, g.vec(reach));
        let aim = NoCount.add(target, g.vec(spread));
        Ray {
            origin,
            dir: NoCount.normalize(NoCount.sub(aim, origin)),
        }
    }

    // Each test below checks the bound of `first_stage_suffices` on the hits that keep
    // the first stage's discriminant (no second-stage operation counted), against the
    // f64 roots of the same quadratic (from the test's own f32 `Voc`, so that only the
    // discriminant's and the roots' arithmetic is measured), and that the rule was
    // exercised both ways.

    #[test]
    fn a_kept_sphere_discriminant_is_within_its_bound() {
        let mut g = Lcg(11);
        let (mut kept, mut recomputed) = (0, 0);
        for _ in 0..20_000 {
            let center = g.vec(100.0);
            let radius = (g.next() + 1.0) * 10.0 + 0.01;
            let s = Sphere::new(center, radius, 0);
            let ray = ray_towards(&mut g, center, radius, 8.0 * radius);
            let mut c = Count::default();
            let Some(t) = s.intersect(&ray, 0.0, f32::INFINITY, &mut c) else {
                continue;
            };
            if c.get(Stat::Scale) > 0 {
                recomputed += 1;
                continue;
            }
            kept += 1;
            let voc = f64s(NoCount.sub(ray.origin, center));
            let dir = f64s(ray.dir);
            let r_sq = f64::from(radius) * f64::from(radius);
            let err = root_error(t, dot(dir, dir), dot(dir, voc), dot(voc, voc) - r_sq);
            let bound = 96.0 * EPS * dot(voc, voc).sqrt() + 4.0 * EPS * f64::from(t.abs());
            assert!(
                err <= bound,
                "{s:?} {ray:?}: t = {t}, off by {err} > {bound}"
            );
        }
        assert!(kept > 1000 && recomputed > 1000, "{kept} {recomputed}");
    }

    #[test]
    fn a_kept_cylinder_discriminant_is_within_its_bound() {
        let mut g = Lcg(12);
        let (mut kept, mut recomputed) = (0, 0);
        for _ in 0..20_000 {
            let middle = g.vec(100.0);
            let radius = (g.next() + 1.0) * 10.0 + 0.01;
            let half = NoCount.scale(NoCount.normalize(g.vec(1.0)), 2.0 * radius);
            let base = NoCount.sub(middle, half);
            let Ok(cyl) = Cylinder::new(base, NoCount.add(middle, half), radius, 0) else {
                continue;
            };
            let ray = ray_towards(&mut g, middle, radius, 8.0 * radius);
            let mut c = Count::default();
            let Some((t, _)) = cyl.intersect(&ray, 0.0, f32::INFINITY, &mut c) else {
                continue;
            };
            if c.get(Stat::Cross) > 0 {
                recomputed += 1;
                continue;
            }
            kept += 1;
            let voc = f64s(NoCount.sub(ray.origin, base));
            let (dir, axis) = (f64s(ray.dir), f64s(cyl.axis));
            let (rv, ov) = (dot(dir, axis), dot(voc, axis));
            let a = dot(dir, dir) - rv * rv;
            let half_b = dot(dir, voc) - rv * ov;
            let cc = dot(voc, voc) - ov * ov - f64::from(radius) * f64::from(radius);
            let err = root_error(t, a, half_b, cc);
            let bound = 800.0 * EPS * dot(voc, voc).sqrt() + 4.0 * EPS * f64::from(t.abs());
            assert!(
                err <= bound,
                "{cyl:?} {ray:?}: t = {t}, off by {err} > {bound}"
            );
        }
        assert!(kept > 1000 && recomputed > 1000, "{kept} {recomputed}");
    }

    #[test]
    fn a_kept_cone_discriminant_is_within_its_bound() {
        let mut g = Lcg(13);
        let (mut kept, mut recomputed) = (0, 0);
        for _ in 0..20_000 {
            let middle = g.vec(100.0);
            let (rb, ra) = ((g.next() + 1.0) * 10.0 + 0.01, (g.next() + 1.0) * 10.0);
            let half = NoCount.scale(NoCount.normalize(g.vec(1.0)), 2.0 * (rb + ra));
            let base = NoCount.sub(middle, half);
            let Ok(cone) = Cone::new(base, rb, NoCount.add(middle, half), ra, 0) else {
                continue;
            };
            let ray = ray_towards(&mut g, middle, rb.max(ra), 8.0 * rb.max(ra));
            let mut c = Count::default();
            let Some((t, _)) = cone.intersect(&ray, 0.0, f32::INFINITY, &mut c) else {
                continue;
            };
            if c.get(Stat::Cross) > 0 {
                recomputed += 1;
                continue;
            }
            kept += 1;
            // The cone's own f32 slope, as its constructor computes it.
            let k = f64::from((ra - rb) / cone.length);
            let (rb, w) = (f64::from(rb), 1.0 + k * k);
            let voc = f64s(NoCount.sub(ray.origin, base));
            let (dir, axis) = (f64s(ray.dir), f64s(cone.axis));
            let (rv, ov, oo) = (dot(dir, axis), dot(voc, axis), dot(voc, voc));
            let a = dot(dir, dir) - w * rv * rv;
            let half_b = dot(dir, voc) - w * rv * ov - rb * k * rv;
            let cc = oo - w * ov * ov - 2.0 * rb * k * ov - rb * rb;
            let err = root_error(t, a, half_b, cc);
            let scale = w * w * (oo + rb * rb);
            let bound = 800.0 * EPS * scale.sqrt() + 4.0 * EPS * f64::from(t.abs());
            assert!(
                err <= bound,
                "{cone:?} {ray:?}: t = {t}, off by {err} > {bound}"
            );
        }
        assert!(kept > 1000 && recomputed > 1000, "{kept} {recomputed}");
    }
}
