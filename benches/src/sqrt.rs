//! Group `sqrt`: the square-root methods of the `fast-sqrt*` variants against the
//! standard library, and inverse square roots (what `normalize` needs) against the
//! classic `0x5f3759df` trick, each over the same 4096 positive floats.
//!
//! Every benchmark maps the whole input array into an output array (so independent
//! roots can overlap in the pipeline or vectorize, as they do in a render's batches)
//! and reports elements per second.

use criterion::{BenchmarkGroup, Criterion, Throughput, measurement::WallTime};
use std::hint::black_box;
use tracer::variants::fast_sqrt::{
    BitTrickSqrt, NewtonBitTrickSqrt, SquareRoot, StdSqrt, TunedBitTrickSqrt,
};

/// Number of inputs every benchmark of the group maps.
pub const INPUT_COUNT: usize = 4096;

/// The magic constant of the classic fast inverse square root (Quake III).
pub const CLASSIC_INVERSE_SQRT_CONSTANT: u32 = 0x5f37_59df;

/// `1/sqrt(x)` for `x > 0` by the classic bit trick alone: `0x5f3759df - bits(x)/2`.
/// Relative error at most about 3.4e-2.
#[inline(always)]
pub fn classic_inverse_sqrt(x: f32) -> f32 {
    f32::from_bits(CLASSIC_INVERSE_SQRT_CONSTANT.wrapping_sub(x.to_bits() >> 1))
}

/// The classic trick followed by one Newton step `y (3/2 - x y²/2)`.
/// Relative error at most about 1.75e-3.
#[inline(always)]
pub fn classic_inverse_sqrt_newton(x: f32) -> f32 {
    let y = classic_inverse_sqrt(x);
    y * (1.5 - 0.5 * x * y * y)
}

/// The standard library's `1/sqrt(x)` (a correctly rounded root, then a division).
#[inline(always)]
pub fn std_inverse_sqrt(x: f32) -> f32 {
    #[allow(clippy::disallowed_methods)] // the reference, outside the counted tracer
    let root = x.sqrt();
    1.0 / root
}

/// 4096 deterministic positive normal floats spread over 2^-20 … 2^20 (a 64-bit LCG
/// picks exponent and mantissa), the spread a render's discriminants and squared
/// lengths cover.
pub fn inputs() -> Vec<f32> {
    let mut state = 0x853C_49E6_748F_EA9Bu64;
    (0..INPUT_COUNT)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let bits = (state >> 32) as u32;
            let exponent = 127 - 20 + (bits >> 23) % 41;
            f32::from_bits((exponent << 23) | (bits & 0x7F_FFFF))
        })
        .collect()
}

/// Maps `inputs` through `f` into `out` (same length).
#[inline(always)]
fn map_into(inputs: &[f32], out: &mut [f32], f: impl Fn(f32) -> f32) {
    for (o, &x) in out.iter_mut().zip(inputs) {
        *o = f(x);
    }
}

/// One benchmark: `f` over the whole input array.
fn bench_map(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    inputs: &[f32],
    f: impl Fn(f32) -> f32 + Copy,
) {
    let mut out = vec![0.0f32; inputs.len()];
    group.bench_function(name, |b| {
        b.iter(|| {
            map_into(black_box(inputs), &mut out, f);
            black_box(&mut out);
        })
    });
}

/// The `sqrt` group.
pub fn bench_sqrt(c: &mut Criterion) {
    let inputs = inputs();
    let mut group = c.benchmark_group("sqrt");
    group.throughput(Throughput::Elements(inputs.len() as u64));
    bench_map(&mut group, "std", &inputs, StdSqrt::sqrt);
    bench_map(&mut group, "fast-sqrt", &inputs, BitTrickSqrt::sqrt);
    bench_map(
        &mut group,
        "fast-sqrt-tuned",
        &inputs,
        TunedBitTrickSqrt::sqrt,
    );
    bench_map(
        &mut group,
        "fast-sqrt-newton",
        &inputs,
        NewtonBitTrickSqrt::sqrt,
    );
    bench_map(&mut group, "inverse-std", &inputs, std_inverse_sqrt);
    bench_map(&mut group, "inverse-classic", &inputs, classic_inverse_sqrt);
    bench_map(
        &mut group,
        "inverse-classic-newton",
        &inputs,
        classic_inverse_sqrt_newton,
    );
    group.finish();
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Largest relative error of `f` against `1/sqrt(x)` in f64 over every float in
    /// `[1, 4)`: halving the bits of `4x` lowers the result's exponent by exactly one,
    /// so the error is periodic with period 4 and this range is one whole period.
    fn max_inverse_error(f: impl Fn(f32) -> f32) -> f64 {
        (1.0f32.to_bits()..4.0f32.to_bits())
            .map(f32::from_bits)
            .map(|x| {
                #[allow(clippy::disallowed_methods)]
                let exact = 1.0 / f64::from(x).sqrt();
                ((f64::from(f(x)) - exact) / exact).abs()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn classic_inverse_sqrt_is_within_3_4_percent() {
        let error = max_inverse_error(classic_inverse_sqrt);
        assert!(error > 0.033 && error < 0.0345, "{error}");
    }

    #[test]
    fn one_newton_step_brings_it_within_1_75_thousandths() {
        let error = max_inverse_error(classic_inverse_sqrt_newton);
        assert!(error > 0.0017 && error < 0.00176, "{error}");
    }

    #[test]
    fn the_error_is_periodic_with_period_four() {
        for &x in &inputs()[..256] {
            assert_eq!(classic_inverse_sqrt(4.0 * x), 0.5 * classic_inverse_sqrt(x));
        }
    }

    #[test]
    fn inputs_are_positive_normal_and_spread_over_many_binades() {
        let inputs = inputs();
        assert_eq!(inputs.len(), INPUT_COUNT);
        assert!(inputs.iter().all(|x| x.is_normal() && *x > 0.0));
        let exponents: std::collections::BTreeSet<u32> =
            inputs.iter().map(|x| x.to_bits() >> 23).collect();
        assert_eq!(exponents.len(), 41);
        assert!((std_inverse_sqrt(4.0) - 0.5).abs() < f32::EPSILON);
    }
}
