//! The floating-point policy of the RTL operators, as Rust: the reference the Verilog
//! (`rtl/verilog/fp_*.v`) is tested against bit for bit, and the arithmetic a
//! functional emulator must use to agree with the RTL.
//!
//! # The policy
//!
//! The operators are IEEE 754 binary32 with round to nearest, ties to even, except for
//! subnormal numbers, which they flush like the Altera ALTFP cores the thesis used:
//!
//! 1. **Subnormal inputs** (exponent field 0, fraction non-zero) are read as a zero of
//!    the same sign ([`flush`]).
//! 2. **Results**: the exact result is rounded to nearest, ties to even, to 24
//!    significant bits *with an unbounded exponent range*. If the magnitude of that
//!    rounded value is below 2⁻¹²⁶ (`f32::MIN_POSITIVE`), the result is a zero with
//!    the sign of the exact result; if it is 2¹²⁸ or more, an infinity of that sign.
//!    No operator ever returns a subnormal number.
//! 3. **Exact zeros** follow IEEE 754: `x - x = +0`, `(-0) + (-0) = -0`, products and
//!    quotients carry the XOR of the signs, `sqrt(-0) = -0`.
//! 4. **NaN**: every NaN result (a NaN input, `inf - inf`, `0 * inf`, `0 / 0`,
//!    `inf / inf`, the root of a negative non-zero number) is the canonical quiet NaN
//!    [`CANONICAL_NAN`] (`0x7FC00000`). Tests accept any NaN where the reference is NaN.
//!
//! Rule 2 differs from "compute in IEEE arithmetic, then flush subnormal results" in
//! one band only: exact magnitudes in `[2⁻¹²⁶ - 2⁻¹⁵⁰, 2⁻¹²⁶ - 2⁻¹⁵¹)`, which IEEE
//! rounds up to 2⁻¹²⁶ on the coarser subnormal grid, but which round to
//! `2⁻¹²⁶ - 2⁻¹⁵⁰` on the 24-bit grid and are therefore flushed. That is what hardware
//! does naturally (round the normalised significand, then look at the exponent). The
//! band is reachable by multiplication only: sums of two normal numbers below 2⁻¹²⁵
//! are exact, and a quotient of two 24-bit significands is never within 2⁻²⁵ of a
//! power of two without being one.
//!
//! # How the reference computes it
//!
//! `flush` the inputs, compute with Rust's `f32` operation (IEEE, correctly rounded,
//! with subnormals), then `finish` the result: NaN becomes canonical, a subnormal or
//! zero result becomes a signed zero (rule 2: an exact value that IEEE rounds to a
//! subnormal number is below `2⁻¹²⁶ - 2⁻¹⁵⁰`, so its 24-bit rounding is below 2⁻¹²⁶
//! too), and a result of exactly ±2⁻¹²⁶ is kept only if the exact value is at least
//! `2⁻¹²⁶ - 2⁻¹⁵¹` in magnitude, decided on the same operation in `f64`. That `f64`
//! value is exact for products and for sums in that range, and on the correct side of
//! the threshold for quotients (a quotient is at least 2⁻¹⁷⁵ away from the 25-bit
//! threshold, far more than half an `f64` ulp there, 2⁻¹⁸⁰).
//!
//! Overflow needs no special case: IEEE rounding to nearest overflows to infinity
//! exactly when the 24-bit rounding reaches 2¹²⁸.
//!
//! [`inv_sqrt`] is no operation of its own: it is [`div`]`(1.0, `[`sqrt`]`(a))`, two
//! policy operations, rounded twice. [`to_u8`] converts to an integer (rounding half
//! away from zero, saturating), so rules 2 to 4 have nothing to say about its result;
//! it flushes subnormal inputs like every operator.
//!
//! [`fast_sqrt`], [`select`] and the delay line are operations on bit patterns and
//! take no part in the policy.

/// The quiet NaN every NaN result is (bit pattern `0x7FC00000`).
pub const CANONICAL_NAN: u32 = 0x7FC0_0000;

/// The magnitude below which a result that IEEE rounded to ±2⁻¹²⁶ is flushed:
/// `2⁻¹²⁶ - 2⁻¹⁵¹`, the midpoint between 2⁻¹²⁶ and the largest 24-bit value below it.
const FLUSH_THRESHOLD: f64 = f64::from_bits(0x380F_FFFF_F000_0000);

/// `x` with a subnormal read as a zero of the same sign; everything else unchanged
/// (NaNs keep their bits).
pub fn flush(x: f32) -> f32 {
    if x.is_subnormal() {
        f32::from_bits(x.to_bits() & 0x8000_0000)
    } else {
        x
    }
}

/// Applies rules 2 and 4 to `ieee`, the IEEE result of an operation on flushed inputs,
/// given `exact`, the same operation in `f64` (see the module docs for why that is
/// precise enough).
fn finish(ieee: f32, exact: f64) -> f32 {
    let sign = ieee.to_bits() & 0x8000_0000;
    if ieee.is_nan() {
        f32::from_bits(CANONICAL_NAN)
    } else if ieee.is_subnormal()
        || ieee == 0.0
        || (ieee.abs() == f32::MIN_POSITIVE && exact.abs() < FLUSH_THRESHOLD)
    {
        f32::from_bits(sign)
    } else {
        ieee
    }
}

/// `a + b` under the policy (`fp_add_sub` with `sub = 0`).
pub fn add(a: f32, b: f32) -> f32 {
    let (a, b) = (flush(a), flush(b));
    finish(a + b, f64::from(a) + f64::from(b))
}

/// `a - b` under the policy (`fp_add_sub` with `sub = 1`).
pub fn sub(a: f32, b: f32) -> f32 {
    let (a, b) = (flush(a), flush(b));
    finish(a - b, f64::from(a) - f64::from(b))
}

/// `a * b` under the policy (`fp_mul`).
pub fn mul(a: f32, b: f32) -> f32 {
    let (a, b) = (flush(a), flush(b));
    finish(a * b, f64::from(a) * f64::from(b))
}

/// `a / b` under the policy (`fp_div`).
pub fn div(a: f32, b: f32) -> f32 {
    let (a, b) = (flush(a), flush(b));
    finish(a / b, f64::from(a) / f64::from(b))
}

/// `sqrt(a)` under the policy (`fp_sqrt`): a negative subnormal is -0, whose root is -0.
pub fn sqrt(a: f32) -> f32 {
    let a = flush(a);
    // The RTL's reference needs the exact IEEE root, not the counted one of the tracer.
    #[allow(clippy::disallowed_methods)]
    let root = a.sqrt();
    // The root of a positive normal number is normal: `finish` only canonicalises NaN.
    finish(root, f64::from(root))
}

/// `1 / sqrt(a)` under the policy (`fp_inv_sqrt`): exactly [`div`]`(1.0, `[`sqrt`]`(a))`,
/// each step rounded to nearest, ties to even (so the result is rounded twice, as the
/// software's normalisation computes it; it is not always the correctly rounded
/// reciprocal root). `inv_sqrt(+0) = +inf`, `inv_sqrt(-0) = -inf` (the root of -0 is
/// -0), subnormals count as zeros of their sign, `inv_sqrt(+inf) = +0`, and a NaN,
/// negative non-zero or -inf input gives [`CANONICAL_NAN`].
pub fn inv_sqrt(a: f32) -> f32 {
    div(1.0, sqrt(a))
}

/// `a` as an unsigned 8-bit integer (`fp_to_u8`, the pixel's gray value): rounded to
/// nearest, ties away from zero (`f32::round`: 127.5 gives 128, 0.5 gives 1), then
/// saturated to 0..=255 (255.5 and more, and +inf, give 255). Negative values, zeros,
/// subnormals (flushed) and NaN give 0.
///
/// For `x` in [0, 255] this is `x.round() as u8`, the rounding of
/// [`crate::emulator::to_gray8`], so `to_u8(v * 255.0) == to_gray8(v)` for every `v`.
pub fn to_u8(a: f32) -> u8 {
    // `as` saturates: NaN and negative values (-0.5 rounds to -1) to 0, 255.5 and above
    // to 255. A subnormal rounds to zero either way; flushing it says so.
    flush(a).round() as u8
}

/// `a < b` under the policy (`fp_compare`'s `lt`): subnormals are zeros, zeros are
/// equal whatever their signs, NaN compares false.
pub fn lt(a: f32, b: f32) -> bool {
    flush(a) < flush(b)
}

/// `a < b` on the low 31 bits of the patterns, as unsigned integers (`int_compare`):
/// the order of the numbers for non-negative floats, which every distance the
/// pipeline compares is (a root at or beyond the ray's start, or +∞); the sign bit is
/// not looked at.
pub fn lt_bits(a: f32, b: f32) -> bool {
    (a.to_bits() & 0x7FFF_FFFF) < (b.to_bits() & 0x7FFF_FFFF)
}

/// The signed integer `a` as a float, rounded to nearest, ties to even (`fp_from_int`).
/// Always normal or +0, so the policy has nothing to flush.
pub fn from_int(a: i32) -> f32 {
    a as f32
}

/// The thesis's bit trick `i = (i + 0x3F800000) >> 1` on the bit pattern
/// (`fp_fast_sqrt`): a 32-bit add whose carry is dropped, then a logical shift. No
/// flushing and no NaN canonicalisation: it is integer arithmetic.
pub fn fast_sqrt(a: f32) -> f32 {
    f32::from_bits(a.to_bits().wrapping_add(0x3F80_0000) >> 1)
}

/// `sel ? b : a`, bit for bit (`fp_select`).
pub fn select(sel: bool, a: f32, b: f32) -> f32 {
    if sel { b } else { a }
}

/// Whether an RTL result `got` agrees with the reference `want`: the same bits, or both
/// NaN (the RTL always returns [`CANONICAL_NAN`], the reference may carry a payload).
pub fn agrees(got: u32, want: u32) -> bool {
    got == want || (f32::from_bits(got).is_nan() && f32::from_bits(want).is_nan())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bits(x: f32) -> u32 {
        x.to_bits()
    }

    #[test]
    fn the_threshold_is_the_midpoint_below_the_smallest_normal() {
        assert_eq!(FLUSH_THRESHOLD, 2f64.powi(-126) - 2f64.powi(-151));
        assert_eq!(FLUSH_THRESHOLD.to_bits(), 0x380F_FFFF_F000_0000);
    }

    #[test]
    fn subnormal_inputs_are_zeros_of_the_same_sign() {
        assert_eq!(bits(flush(1e-40)), 0);
        assert_eq!(bits(flush(-1e-40)), 0x8000_0000);
        assert_eq!(bits(flush(f32::from_bits(1))), 0);
        assert_eq!(bits(flush(f32::from_bits(0x807F_FFFF))), 0x8000_0000);
        // Normal numbers, zeros, infinities and NaNs pass unchanged.
        for x in [
            0x0080_0000,
            0x8000_0000,
            0x7F80_0000,
            0x7FC0_0001,
            0x3F80_0000,
        ] {
            assert_eq!(bits(flush(f32::from_bits(x))), x);
        }
        // A subnormal operand counts as zero.
        assert_eq!(bits(add(1.0, 1e-40)), bits(1.0));
        assert_eq!(bits(mul(-1e-40, 3.0)), 0x8000_0000);
        assert_eq!(bits(div(1.0, -1e-40)), 0xFF80_0000);
        assert_eq!(bits(sqrt(-1e-40)), 0x8000_0000);
        assert!(!lt(-1e-40, 1e-40));
        assert!(!lt(1e-40, 0.0));
    }

    #[test]
    fn ordinary_arithmetic_is_ieee() {
        assert_eq!(bits(add(0.1, 0.2)), 0x3E99_999A);
        // A tie: 0.3f - 0.1f is exactly halfway between 0x3E4CCCCD and 0x3E4CCCCE.
        assert_eq!(bits(sub(0.3, 0.1)), 0x3E4C_CCCE);
        assert_eq!(bits(mul(0.1, 3.0)), 0x3E99_999A);
        assert_eq!(bits(div(1.0, 3.0)), 0x3EAA_AAAB);
        assert_eq!(bits(sqrt(2.0)), 0x3FB5_04F3);
        assert_eq!(bits(from_int(16_777_217)), bits(16_777_216.0));
        assert_eq!(bits(from_int(16_777_219)), bits(16_777_220.0));
        assert_eq!(bits(from_int(i32::MIN)), 0xCF00_0000);
        assert_eq!(bits(from_int(i32::MAX)), 0x4F00_0000);
        assert_eq!(bits(from_int(0)), 0);
        // Ties to even: 1 + 2^-24 is halfway between 1 and 1 + 2^-23.
        assert_eq!(bits(add(1.0, f32::from_bits(0x3380_0000))), bits(1.0));
        assert_eq!(
            bits(add(
                f32::from_bits(0x3F80_0001),
                f32::from_bits(0x3380_0000)
            )),
            0x3F80_0002
        );
    }

    #[test]
    fn tiny_results_are_flushed_with_their_sign() {
        let min = f32::MIN_POSITIVE;
        assert_eq!(bits(mul(min, 0.5)), 0);
        assert_eq!(bits(mul(-min, 0.5)), 0x8000_0000);
        assert_eq!(bits(div(min, -3.0)), 0x8000_0000);
        let next = f32::from_bits(0x0080_0001);
        assert_eq!(bits(sub(next, min)), 0); // 2^-149, exact but subnormal
        assert_eq!(bits(sub(min, next)), 0x8000_0000);
        // Exact cancellation is +0, (-0) + (-0) is -0.
        assert_eq!(bits(sub(1.5, 1.5)), 0);
        assert_eq!(bits(add(-0.0, -0.0)), 0x8000_0000);
        assert_eq!(bits(add(-0.0, 0.0)), 0);
        // Overflow to infinity keeps the sign.
        assert_eq!(bits(mul(f32::MAX, -2.0)), 0xFF80_0000);
        assert_eq!(bits(add(f32::MAX, f32::MAX)), 0x7F80_0000);
    }

    #[test]
    fn the_band_below_the_smallest_normal_is_flushed() {
        // An exact product in [2^-126 - 2^-150, 2^-126 - 2^-151): IEEE rounds it up to
        // 2^-126 on the subnormal grid, the 24-bit rounding gives 2^-126 - 2^-150,
        // below the smallest normal: flushed.
        let (a, b) = band_product();
        assert_eq!(a * b, f32::MIN_POSITIVE);
        let exact = f64::from(a) * f64::from(b);
        assert!(exact < FLUSH_THRESHOLD && exact >= 2f64.powi(-126) - 2f64.powi(-150));
        assert_eq!(bits(mul(a, b)), 0);
        assert_eq!(bits(mul(-a, b)), 0x8000_0000);
        // An exact 2^-126 stays, and so does a product just above it:
        // (1 - 2^-24)(1 + 2^-23) 2^-126 = (1 + 2^-24 - 2^-47) 2^-126 rounds to 2^-126.
        let half = f32::from_bits(0x3F00_0000);
        assert_eq!(mul(half, f32::from_bits(0x0100_0000)), f32::MIN_POSITIVE);
        let (a, b) = (f32::from_bits(0x3F7F_FFFF), f32::from_bits(0x0080_0001));
        assert_eq!(mul(a, b), f32::MIN_POSITIVE);
    }

    /// A product in the band. Significands ma = 2^23 + k and mb (integers in
    /// [2^23, 2^24)) with ma * mb in [2^47 - 2^23, 2^47 - 2^22); a = ma * 2^-24 (in
    /// [0.5, 1)) and b = mb * 2^-149 (in [2^-126, 2^-125)), so that 2^47 maps to 2^-126.
    fn band_product() -> (f32, f32) {
        for k in 1u64..(1 << 23) {
            let ma = (1u64 << 23) + k;
            let mb = ((1u64 << 47) - (1u64 << 23)).div_ceil(ma);
            if mb < (1 << 24) && ma * mb < (1u64 << 47) - (1u64 << 22) {
                let a = f32::from_bits((126 << 23) | (ma as u32 & 0x7F_FFFF));
                let b = f32::from_bits((1 << 23) | (mb as u32 & 0x7F_FFFF));
                return (a, b);
            }
        }
        unreachable!("the band is reachable")
    }

    #[test]
    fn nan_results_are_canonical() {
        let nan = f32::from_bits(0xFFC0_1234);
        for r in [
            add(nan, 1.0),
            sub(f32::INFINITY, f32::INFINITY),
            mul(0.0, f32::NEG_INFINITY),
            div(0.0, -0.0),
            div(f32::INFINITY, f32::INFINITY),
            sqrt(-1.0),
            sqrt(f32::NEG_INFINITY),
        ] {
            assert_eq!(bits(r), CANONICAL_NAN);
        }
        assert!(!lt(nan, 1.0) && !lt(1.0, nan));
        assert!(!lt(-0.0, 0.0));
        assert!(lt(f32::NEG_INFINITY, -f32::MAX));
        assert_eq!(bits(sqrt(-0.0)), 0x8000_0000);
        assert_eq!(bits(sqrt(f32::INFINITY)), 0x7F80_0000);
    }

    #[test]
    fn inv_sqrt_is_a_root_then_a_reciprocal() {
        assert_eq!(bits(inv_sqrt(4.0)), bits(0.5));
        assert_eq!(bits(inv_sqrt(0.25)), bits(2.0));
        assert_eq!(bits(inv_sqrt(1.0)), bits(1.0));
        // sqrt(2) = 0x3FB504F3 (1.41421354), 1 / that = 0.707106769 = 0x3F3504F3.
        assert_eq!(bits(inv_sqrt(2.0)), 0x3F35_04F3);
        // 2^-126 (the smallest normal): root 2^-63, reciprocal 2^63.
        assert_eq!(bits(inv_sqrt(f32::MIN_POSITIVE)), 0x5F00_0000);
        assert_eq!(bits(inv_sqrt(0.0)), 0x7F80_0000);
        assert_eq!(bits(inv_sqrt(-0.0)), 0xFF80_0000);
        assert_eq!(bits(inv_sqrt(1e-40)), 0x7F80_0000); // subnormal: +0
        assert_eq!(bits(inv_sqrt(-1e-40)), 0xFF80_0000); // -0
        assert_eq!(bits(inv_sqrt(f32::INFINITY)), 0);
        for x in [-1.0, f32::NEG_INFINITY, f32::from_bits(0x7F80_0001)] {
            assert_eq!(bits(inv_sqrt(x)), CANONICAL_NAN);
        }
    }

    #[test]
    fn to_u8_rounds_half_away_from_zero_and_saturates() {
        assert_eq!(to_u8(127.5), 128);
        assert_eq!(to_u8(126.5), 127);
        assert_eq!(to_u8(0.5), 1);
        assert_eq!(to_u8(f32::from_bits(0x3EFF_FFFF)), 0); // just below 0.5
        assert_eq!(to_u8(0.0), 0);
        assert_eq!(to_u8(1e-40), 0);
        assert_eq!(to_u8(1.0), 1);
        assert_eq!(to_u8(254.49), 254);
        assert_eq!(to_u8(254.5), 255);
        assert_eq!(to_u8(255.0), 255);
        assert_eq!(to_u8(255.49), 255);
        assert_eq!(to_u8(255.5), 255);
        assert_eq!(to_u8(300.0), 255);
        assert_eq!(to_u8(f32::MAX), 255);
        assert_eq!(to_u8(f32::INFINITY), 255);
        assert_eq!(to_u8(-0.4), 0);
        assert_eq!(to_u8(-0.5), 0);
        assert_eq!(to_u8(-1.0), 0);
        assert_eq!(to_u8(f32::NEG_INFINITY), 0);
        assert_eq!(to_u8(f32::NAN), 0);
        assert_eq!(to_u8(-f32::NAN), 0);
    }

    #[test]
    fn to_u8_of_the_scaled_gray_value_is_to_gray8() {
        use crate::emulator::to_gray8;
        let mut values = vec![
            -1.0,
            -0.0,
            0.0,
            1e-40,
            1.0,
            1.5,
            1e30,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        // Around every rounding boundary (k + 0.5) / 255, a few ulps either side.
        for k in 0..=255u32 {
            let v = (k as f32 + 0.5) / 255.0;
            values.extend((0..9).map(|d| f32::from_bits(v.to_bits() + d - 4)));
        }
        // A sweep of [0, 1] and a little beyond.
        values.extend((0..0x3F90_0000u32).step_by(4099).map(f32::from_bits));
        for v in values {
            assert_eq!(to_u8(v * 255.0), to_gray8(v), "{v:e}");
            // Scaled with the policy's multiplier, as the pipeline would.
            assert_eq!(to_u8(mul(v, 255.0)), to_gray8(v), "{v:e}");
        }
    }

    #[test]
    fn fast_sqrt_is_the_integer_trick() {
        assert_eq!(bits(fast_sqrt(1.0)), bits(1.0));
        assert_eq!(bits(fast_sqrt(4.0)), bits(2.0));
        // 2.0: (0x40000000 + 0x3F800000) >> 1 = 0x3FC00000 = 1.5 (true root 1.414).
        assert_eq!(bits(fast_sqrt(2.0)), 0x3FC0_0000);
        // The carry out of the add is dropped: -4.0 = 0xC0800000, + 0x3F800000 = 2^32.
        assert_eq!(bits(fast_sqrt(-4.0)), 0);
        assert_eq!(bits(fast_sqrt(-1.0)), 0x7F80_0000);
        assert_eq!(bits(select(true, 1.0, 2.0)), bits(2.0));
        assert_eq!(bits(select(false, 1.0, 2.0)), bits(1.0));
        assert!(agrees(CANONICAL_NAN, 0xFFC0_0001));
        assert!(!agrees(0, 0x8000_0000));
    }

    #[test]
    fn the_integer_compare_orders_every_distance_as_the_float_compare_does() {
        // Distances are +0, positive normals (the policy flushes the rest) or +∞. Every
        // exponent, mantissas at both ends and in between, against each other.
        let mut values = vec![0.0f32, f32::MIN_POSITIVE, f32::MAX, f32::INFINITY, 1.0];
        for exponent in 1..255u32 {
            for mantissa in [0u32, 1, 0x40_0000, 0x7F_FFFF, 0x12_3457] {
                values.push(f32::from_bits(exponent << 23 | mantissa));
            }
        }
        for &a in &values {
            for &b in &values {
                assert_eq!(lt_bits(a, b), lt(a, b), "{a:e} < {b:e}");
            }
        }
        // A negative zero counts as +0 (the sign bit is not compared).
        assert!(!lt_bits(-0.0, 0.0) && !lt_bits(0.0, -0.0) && lt_bits(-0.0, 1.0));
    }
}
