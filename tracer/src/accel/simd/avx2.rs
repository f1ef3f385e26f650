//! The SIMD lanes' first stage in AVX registers: which lanes of a chunk may hit, as a
//! bit per lane, for the chunk loop of the pass compiled with AVX2. A chunk that some
//! lane passes is then computed again in lane arithmetic for the rest of its test
//! (handing the registers over through arrays measured slower).
//!
//! Most chunks stop at the first stage (on SPD rings nine in ten cylinder chunks and
//! nearly every sphere chunk), so its code is the loop's. Left to the compiler, the
//! lane loop came out with shuffles between the structure-of-arrays rows and a branch
//! per lane when a condition short-circuited; written here, it is the arithmetic and
//! one mask. The operations are the portable first stage's
//! ([`super::sphere_first_stage`], [`super::cylinder_first_stage`]) in the same order,
//! each rounded alone (no fused multiply-add), so the bits are the same: the tests
//! compare them lane by lane, non-finite inputs included.

use super::{CylinderLanes, SphereLanes};
use crate::primitives::QUICK_MISS_FRACTION;
use std::arch::x86_64::{
    __m256, _CMP_GE_OQ, _CMP_GT_OQ, _mm256_add_ps, _mm256_and_ps, _mm256_cmp_ps, _mm256_load_ps,
    _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_setzero_ps, _mm256_sub_ps,
    _mm256_xor_ps,
};

/// `a·x + b·y + c·z`, summed left to right as the portable code does.
///
/// # Safety
/// The CPU must have AVX.
#[inline(always)]
unsafe fn dot(a: __m256, x: __m256, b: __m256, y: __m256, c: __m256, z: __m256) -> __m256 {
    // SAFETY: the caller guarantees AVX.
    unsafe {
        _mm256_add_ps(
            _mm256_add_ps(_mm256_mul_ps(a, x), _mm256_mul_ps(b, y)),
            _mm256_mul_ps(c, z),
        )
    }
}

/// `disc >= -(scale · 2⁻¹⁶)` per lane ([`crate::primitives::quick_miss_margin`]): all
/// bits set where it holds (false for a NaN, as in Rust).
///
/// # Safety
/// The CPU must have AVX.
#[inline(always)]
unsafe fn may_hit(disc: __m256, scale: __m256) -> __m256 {
    // SAFETY: the caller guarantees AVX.
    unsafe {
        let margin = _mm256_mul_ps(scale, _mm256_set1_ps(QUICK_MISS_FRACTION));
        // Negation flips the sign bit, as `-x` does.
        let neg_margin = _mm256_xor_ps(margin, _mm256_set1_ps(-0.0));
        _mm256_cmp_ps::<_CMP_GE_OQ>(disc, neg_margin)
    }
}

/// A bit per lane of the chunk whose sphere may be hit by the ray from `origin` along
/// `dir`: [`super::sphere_first_stage`]'s `passed`.
///
/// # Safety
/// The CPU must have AVX.
#[inline(always)]
pub(super) unsafe fn sphere_first_stage_mask(
    l: &SphereLanes,
    origin: [f32; 3],
    dir: [f32; 3],
) -> u32 {
    // SAFETY: the caller guarantees AVX; the rows are 32-byte aligned (a 32-byte aligned
    // struct of 32-byte rows) and 8 floats long.
    unsafe {
        let [ox, oy, oz] = origin.map(|x| _mm256_set1_ps(x));
        let [dx, dy, dz] = dir.map(|x| _mm256_set1_ps(x));
        let vx = _mm256_sub_ps(ox, _mm256_load_ps(l.cx.as_ptr()));
        let vy = _mm256_sub_ps(oy, _mm256_load_ps(l.cy.as_ptr()));
        let vz = _mm256_sub_ps(oz, _mm256_load_ps(l.cz.as_ptr()));
        let half_b = dot(dx, vx, dy, vy, dz, vz);
        let oo = dot(vx, vx, vy, vy, vz, vz);
        // crate::primitives::sphere_first_disc: half_b² - (|Voc|² - r²).
        let radius_sq = _mm256_load_ps(l.radius_sq.as_ptr());
        let disc = _mm256_sub_ps(_mm256_mul_ps(half_b, half_b), _mm256_sub_ps(oo, radius_sq));
        _mm256_movemask_ps(may_hit(disc, oo)) as u32
    }
}

/// A bit per lane of the chunk whose cylinder may be hit by the ray from `origin` along
/// `dir`: [`super::cylinder_first_stage`]'s `passed`.
///
/// # Safety
/// The CPU must have AVX.
#[inline(always)]
pub(super) unsafe fn cylinder_first_stage_mask(
    l: &CylinderLanes,
    origin: [f32; 3],
    dir: [f32; 3],
) -> u32 {
    // SAFETY: as for the spheres.
    unsafe {
        let [ox, oy, oz] = origin.map(|x| _mm256_set1_ps(x));
        let [dx, dy, dz] = dir.map(|x| _mm256_set1_ps(x));
        let vx = _mm256_sub_ps(ox, _mm256_load_ps(l.bx.as_ptr()));
        let vy = _mm256_sub_ps(oy, _mm256_load_ps(l.by.as_ptr()));
        let vz = _mm256_sub_ps(oz, _mm256_load_ps(l.bz.as_ptr()));
        let ax = _mm256_load_ps(l.ax.as_ptr());
        let ay = _mm256_load_ps(l.ay.as_ptr());
        let az = _mm256_load_ps(l.az.as_ptr());
        let rv = dot(dx, ax, dy, ay, dz, az);
        let ov = dot(vx, ax, vy, ay, vz, az);
        let ro = dot(dx, vx, dy, vy, dz, vz);
        let oo = dot(vx, vx, vy, vy, vz, vz);
        let a = _mm256_sub_ps(_mm256_set1_ps(1.0), _mm256_mul_ps(rv, rv));
        let half_b = _mm256_sub_ps(ro, _mm256_mul_ps(rv, ov));
        let radius_sq = _mm256_load_ps(l.radius_sq.as_ptr());
        let cc = _mm256_sub_ps(_mm256_sub_ps(oo, _mm256_mul_ps(ov, ov)), radius_sq);
        let disc = _mm256_sub_ps(_mm256_mul_ps(half_b, half_b), _mm256_mul_ps(a, cc));
        let axis_crossed = _mm256_cmp_ps::<_CMP_GT_OQ>(a, _mm256_setzero_ps());
        _mm256_movemask_ps(_mm256_and_ps(may_hit(disc, oo), axis_crossed)) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::super::{LANES, cylinder_first_stage, sphere_first_stage};
    use super::*;
    use crate::accel::cpu_has_avx2_fma;

    /// A bit per lane that passed, from the portable first stage.
    fn mask(passed: &[bool; LANES]) -> u32 {
        passed
            .iter()
            .enumerate()
            .fold(0, |m, (i, &p)| m | u32::from(p) << i)
    }

    /// Values that stress the comparisons: ordinary ones at several scales, zeros of both
    /// signs, the infinities, a NaN and the -inf of a zero radius's square.
    fn value(state: &mut u32) -> f32 {
        *state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        let unit = (*state >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0;
        match *state % 23 {
            0 => 0.0,
            1 => -0.0,
            2 => f32::INFINITY,
            3 => f32::NEG_INFINITY,
            4 => f32::NAN,
            5..=9 => unit * 1e-3,
            10..=14 => unit * 1e3,
            _ => unit * 4.0,
        }
    }

    #[test]
    fn the_avx_first_stage_passes_the_portable_lanes_bit_for_bit() {
        assert!(
            cpu_has_avx2_fma(),
            "this test needs a CPU with AVX2 and FMA"
        );
        let mut state = 11u32;
        let (mut sphere_lanes, mut cylinder_lanes) = (0u32, 0u32);
        for round in 0..20_000 {
            let mut v = || value(&mut state);
            // Near-unit directions most of the time, as the tracer's rays, and any
            // values in one round of five.
            let origin = [v(), v(), v()];
            let dir = if round % 5 == 0 {
                [v(), v(), v()]
            } else {
                let d = [v().clamp(-1.0, 1.0), v().clamp(-1.0, 1.0), 1.0];
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                d.map(|x| x / n)
            };
            let mut row = || std::array::from_fn::<f32, LANES, _>(|_| v());
            let sphere = SphereLanes {
                cx: row(),
                cy: row(),
                cz: row(),
                radius_sq: row().map(|r| if r < -100.0 { f32::NEG_INFINITY } else { r * r }),
                inside: [0.0; LANES],
            };
            // SAFETY: the assertion above.
            let avx = unsafe { sphere_first_stage_mask(&sphere, origin, dir) };
            let portable = mask(&sphere_first_stage(&sphere, origin, dir).passed);
            assert_eq!(avx, portable, "{sphere:?} {origin:?} {dir:?}");
            sphere_lanes += portable.count_ones();
            let cylinder = CylinderLanes {
                bx: row(),
                by: row(),
                bz: row(),
                ax: row(),
                ay: row(),
                az: row(),
                radius_sq: row().map(|r| r * r),
                length: row(),
                inside: [0.0; LANES],
            };
            // SAFETY: the assertion above.
            let avx = unsafe { cylinder_first_stage_mask(&cylinder, origin, dir) };
            let portable = mask(&cylinder_first_stage(&cylinder, origin, dir).passed);
            assert_eq!(avx, portable, "{cylinder:?} {origin:?} {dir:?}");
            cylinder_lanes += portable.count_ones();
        }
        // Both outcomes were exercised, not only misses.
        assert!(
            sphere_lanes > 5_000 && cylinder_lanes > 5_000,
            "{sphere_lanes} {cylinder_lanes}"
        );
    }
}
