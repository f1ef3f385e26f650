//! The SPD's portable random numbers: `lib_gauss_rand` of `libvec.c`.
//!
//! A Gaussian deviate (mean 0, variance 1) made by the polar Box–Muller method from a
//! tiny linear congruential generator (`Numerical Recipes` GASDEV with M = 134456,
//! A = 8121, C = 28411). It is a pure function of its seed: `mount` hashes the grid
//! position into the seed, so the same mountain comes out everywhere. Integer steps and
//! the floating-point expression order are the C's, so the values are the C's.

/// Modulus `M1`.
const M1: i64 = 134_456;
/// Multiplier `IA1`.
const IA1: i64 = 8121;
/// Increment `IC1`.
const IC1: i64 = 28_411;

/// `lib_gauss_rand(iseed)`. Seeds should be below 134456 (the C's requirement to avoid
/// repetition); any non-negative seed below 2^40 stays exact in i64 here.
pub fn gauss_rand(seed: i64) -> f64 {
    let mut ix2 = seed;
    let (v1, r) = loop {
        let ix1 = (IC1 + ix2 * IA1) % M1;
        ix2 = (IC1 + ix1 * IA1) % M1;
        // `ix * 2.0 * RM1` with the macro `RM1` = `1.0/M1` unparenthesised in the C:
        // ((ix * 2.0) * 1.0) / M1.
        let v1 = ix1 as f64 * 2.0 * 1.0 / M1 as f64 - 1.0;
        let v2 = ix2 as f64 * 2.0 * 1.0 / M1 as f64 - 1.0;
        let r = v1 * v1 + v2 * v2;
        if r < 1.0 {
            break (v1, r);
        }
    };
    let fac = (-2.0 * r.ln() / r).sqrt();
    v1 * fac
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deterministic_and_roughly_standard_normal() {
        assert_eq!(gauss_rand(21).to_bits(), gauss_rand(21).to_bits());
        let samples: Vec<f64> = (0..20_000).map(|s| gauss_rand(s + 21)).collect();
        let n = samples.len() as f64;
        let mean = samples.iter().sum::<f64>() / n;
        let var = samples.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
        assert!(mean.abs() < 0.05, "{mean}");
        assert!((var - 1.0).abs() < 0.1, "{var}");
    }

    #[test]
    fn first_value_by_hand() {
        // Seed 0: ix1 = 28411, ix2 = (28411 + 28411*8121) % 134456 = 53559.
        let ix1 = 28_411.0_f64;
        let ix2 = ((28_411 + 28_411 * 8121) % 134_456) as f64;
        let v1 = ix1 * 2.0 / 134_456.0 - 1.0;
        let v2 = ix2 * 2.0 / 134_456.0 - 1.0;
        let r = v1 * v1 + v2 * v2;
        assert!(r < 1.0);
        let expected = v1 * (-2.0 * r.ln() / r).sqrt();
        assert!((gauss_rand(0) - expected).abs() < 1e-15);
    }
}
