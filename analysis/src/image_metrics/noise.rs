//! Monte Carlo noise: how far a path tracer's picture is from a converged (high-sample)
//! run of the same program, as relative mean squared error, and the efficiency that
//! makes runs of different lengths comparable.
//!
//! # Definition
//!
//! relMSE as pbrt-v4 computes it (`Image::MRSE` in src/pbrt/util/image.cpp, used by
//! `imgtool diff --metric MRSE` and `imgtool error` in src/pbrt/cmd/imgtool.cpp):
//! per pixel and channel `(p - r)^2 / (r + 0.01)^2`, with `p` the picture's and `r`
//! the reference's value, averaged over the pixels of each channel, and the channels
//! averaged (imgtool prints `error.Average()`). The 0.01 is added to the reference
//! *before* squaring; the other common form, `(p - r)^2 / (r^2 + 0.01)` (in denoising
//! papers' code and Mitsuba-based research scripts), weighs black pixels a hundred
//! times less. We follow pbrt's to the letter, so that a figure here is a figure `imgtool`
//! prints for the same two files. `mse` is pbrt's `Image::MSE`, `(p - r)^2` averaged the
//! same way.
//!
//! # Linear values
//!
//! The 8-bit sRGB values are decoded to linear light (IEC 61966-2-1's curve) before
//! anything is computed: pbrt reads an 8-bit PNG as `U256` pixels whose `GetChannel`
//! decodes them through the sRGB encoding (`ColorEncoding::sRGB`, the default for PNG),
//! so its relMSE of two PNGs is one of linear values; and Mitsuba's render tests
//! (src/render/tests/test_renders.py) compare linear radiance too (a per-pixel Z-test
//! on float XYZ images, not a relMSE). Linear is also where Monte Carlo estimates are
//! unbiased averages of samples, so the error falls as `1 / spp` there (the tests check
//! it); the sRGB curve would bend that law in the dark tones. Both pictures must be of
//! the same program, exposure and tone mapping: relMSE measures noise, not conventions
//! (the `likeness` module tells those apart).
//!
//! The converged picture is itself quantized to 8 bits, so relMSE has a floor of about
//! a quantization step squared over the value (well below 1e-3 for mid tones): a
//! picture cannot be judged better than that.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::RgbImage;
use super::check_same_size;
use crate::error::MetricsError;

/// pbrt-v4's `0.01` in `Sqr(vref[c] + 0.01)` (linear units, 1 = full white): it keeps
/// black reference pixels from dividing by zero.
pub const REL_MSE_EPSILON: f64 = 0.01;

/// The Monte Carlo error of a picture against a converged run of the same program.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct NoiseError {
    /// Relative mean squared error (pbrt-v4's MRSE) of the linear values.
    pub rel_mse: f64,
    /// Mean squared error of the linear values (0-1 scale).
    pub mse: f64,
}

/// relMSE and MSE of `picture` against `converged` (see the module documentation);
/// the two must have the same size.
pub fn noise_error(picture: &RgbImage, converged: &RgbImage) -> Result<NoiseError, MetricsError> {
    check_same_size(picture, converged)?;
    let linear = srgb_to_linear_table();
    let (mut sum_rel, mut sum_sq) = (0.0, 0.0);
    for (&p, &r) in picture.data.iter().zip(&converged.data) {
        let (p, r) = (linear[usize::from(p)], linear[usize::from(r)]);
        let squared = (p - r) * (p - r);
        sum_sq += squared;
        sum_rel += squared / ((r + REL_MSE_EPSILON) * (r + REL_MSE_EPSILON));
    }
    // The mean over channels of per-channel means is the mean over all values, since
    // every channel has the same number of pixels.
    let values = picture.data.len() as f64;
    Ok(NoiseError {
        rel_mse: sum_rel / values,
        mse: sum_sq / values,
    })
}

/// Efficiency of a Monte Carlo renderer: `1 / (relMSE × seconds)`, the inverse of the
/// error-time product, which stays constant as a converging renderer runs longer
/// (error ∝ 1/spp, time ∝ spp), so runs of different lengths compare. `None` when the
/// inputs or the result are not finite and positive: a zero error (a picture equal
/// to its reference) has no finite efficiency, and a time of zero or less is no
/// measurement.
pub fn efficiency(rel_mse: f64, seconds: f64) -> Option<f64> {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    if !positive(rel_mse) || !positive(seconds) {
        return None;
    }
    Some(1.0 / (rel_mse * seconds)).filter(|&e| positive(e))
}

/// The linear value of each 8-bit sRGB code (IEC 61966-2-1: linear below 0.04045,
/// a 2.4 power above).
pub(crate) fn srgb_to_linear_table() -> [f64; 256] {
    std::array::from_fn(|code| {
        let c = code as f64 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prng::SplitMix64;

    /// Linear value to the nearest 8-bit sRGB code, the inverse of the table (the
    /// renderer's side of the tests).
    fn encode(linear: f64) -> u8 {
        let v = linear.clamp(0.0, 1.0);
        let c = if v <= 0.003_130_8 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        };
        (c * 255.0).round() as u8
    }

    #[test]
    fn the_table_decodes_srgb_codes_as_published() {
        let t = srgb_to_linear_table();
        assert_eq!((t[0], t[255]), (0.0, 1.0));
        // 10/255 = 0.0392 is on the linear segment: 0.0392157 / 12.92.
        assert!((t[10] - 0.003_035_269_835_488_375).abs() < 1e-15);
        // Code 188: ((188/255 + 0.055) / 1.055)^2.4, computed by hand = 0.502886.
        assert!((t[188] - 0.502_886_458_032_568_7).abs() < 1e-12);
        assert!(t.windows(2).all(|w| w[0] < w[1]), "strictly increasing");
        for code in 0..=255u8 {
            assert_eq!(encode(t[usize::from(code)]), code);
        }
    }

    #[test]
    fn rel_mse_of_a_two_pixel_picture_matches_hand_arithmetic() {
        let converged = RgbImage::new(2, 1, vec![188, 255, 0, 0, 0, 0]).expect("valid image");
        let picture = RgbImage::new(2, 1, vec![255, 188, 0, 0, 0, 51]).expect("valid image");
        // Linear: L(188) = 0.5028865, L(255) = 1, L(51) = 0.0331048, L(0) = 0.
        // Terms (p - r)^2 / (r + 0.01)^2:
        //   (1 - 0.5028865)^2 / 0.5128865^2 = 0.9394393
        //   (0.5028865 - 1)^2 / 1.01^2      = 0.2422526
        //   0, 0, 0
        //   0.0331048^2 / 0.01^2            = 10.9592557
        // mean = 12.1409476 / 6 = 2.0234913. Squares alone: 0.4953397 / 6 = 0.0825566.
        let e = noise_error(&picture, &converged).expect("same size");
        assert!((e.rel_mse - 2.023_491_265_243_696).abs() < 1e-9, "{e:?}");
        assert!((e.mse - 0.082_556_612_130_753_81).abs() < 1e-9, "{e:?}");
    }

    #[test]
    fn identical_pictures_have_no_noise_and_no_finite_efficiency() {
        let img = RgbImage::new(3, 2, (0..18).map(|i| i * 14).collect()).expect("valid image");
        let e = noise_error(&img, &img).expect("same size");
        assert_eq!(
            e,
            NoiseError {
                rel_mse: 0.0,
                mse: 0.0
            }
        );
        assert_eq!(efficiency(e.rel_mse, 3.0), None);
    }

    #[test]
    fn efficiency_is_the_inverse_of_error_times_time() {
        assert_eq!(efficiency(0.01, 2.0), Some(50.0));
        assert_eq!(efficiency(0.25, 0.5), Some(8.0));
        for (rel_mse, seconds) in [
            (0.0, 1.0),
            (0.1, 0.0),
            (-0.1, 1.0),
            (0.1, -2.0),
            (f64::NAN, 1.0),
            (0.1, f64::INFINITY),
            // 1 / (tiny × tiny) overflows to infinity.
            (1e-200, 1e-200),
        ] {
            assert_eq!(efficiency(rel_mse, seconds), None, "{rel_mse} {seconds}");
        }
    }

    #[test]
    fn mismatched_sizes_are_an_error() {
        let a = RgbImage::new(2, 1, vec![0; 6]).expect("valid image");
        let b = RgbImage::new(1, 2, vec![0; 6]).expect("valid image");
        assert!(matches!(
            noise_error(&a, &b),
            Err(MetricsError::SizeMismatch { .. })
        ));
    }

    #[test]
    fn noise_error_round_trips_through_json() {
        let e = NoiseError {
            rel_mse: 0.0125,
            mse: 0.002,
        };
        let json = serde_json::to_string(&e).expect("serialize");
        assert_eq!(json, r#"{"rel_mse":0.0125,"mse":0.002}"#);
        assert_eq!(serde_json::from_str::<NoiseError>(&json).expect("parse"), e);
    }

    /// The true (linear, unquantized) radiance of the synthetic scene: smooth
    /// gradients between 0.05 and 0.6, different in each channel.
    fn radiance(x: u32, y: u32, c: usize, width: u32, height: u32) -> f64 {
        let (u, v) = (
            f64::from(x) / f64::from(width),
            f64::from(y) / f64::from(height),
        );
        let base = [0.05 + 0.55 * u, 0.05 + 0.55 * v, 0.05 + 0.55 * (u * v)];
        base[c]
    }

    /// A picture whose every value is the mean of `spp` independent samples
    /// `L (1 + A (2 xi - 1))`, xi uniform in [0, 1): unbiased, with the per-sample
    /// relative variance A^2 / 3, so the mean's variance is L^2 A^2 / (3 spp).
    fn monte_carlo_picture(width: u32, height: u32, spp: u32, seed: u64) -> RgbImage {
        let mut rng = SplitMix64::new(seed);
        let mut data = Vec::new();
        for y in 0..height {
            for x in 0..width {
                for c in 0..3 {
                    let l = radiance(x, y, c, width, height);
                    let sum: f64 = (0..spp)
                        .map(|_| {
                            let xi = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
                            l * (1.0 + SAMPLE_SPREAD * (2.0 * xi - 1.0))
                        })
                        .sum();
                    // At most 0.6 × 1.5 = 0.9: the encoding never clips.
                    data.push(encode(sum / f64::from(spp)));
                }
            }
        }
        RgbImage::new(width, height, data).expect("valid image")
    }

    const SAMPLE_SPREAD: f64 = 0.5;

    #[test]
    fn rel_mse_falls_fourfold_from_4_to_16_samples_per_pixel() {
        let (width, height) = (64, 64);
        let converged = RgbImage::new(
            width,
            height,
            (0..height)
                .flat_map(|y| (0..width).map(move |x| (x, y)))
                .flat_map(|(x, y)| (0..3).map(move |c| encode(radiance(x, y, c, width, height))))
                .collect(),
        )
        .expect("valid image");
        // The expected relMSE from the variance alone: the mean over values of
        // L^2 A^2 / (3 spp) / (L + 0.01)^2.
        let mut weight = 0.0;
        for y in 0..height {
            for x in 0..width {
                for c in 0..3 {
                    let l = radiance(x, y, c, width, height);
                    weight += l * l / ((l + REL_MSE_EPSILON) * (l + REL_MSE_EPSILON));
                }
            }
        }
        weight /= f64::from(3 * width * height);
        let expected = |spp: u32| weight * SAMPLE_SPREAD * SAMPLE_SPREAD / (3.0 * f64::from(spp));
        let at = |spp: u32| {
            noise_error(&monte_carlo_picture(width, height, spp, 17), &converged)
                .expect("same size")
                .rel_mse
        };
        let (four, sixteen) = (at(4), at(16));
        // 12,288 values: the sampling error of each relMSE is about 1.3 % (measured:
        // 0.1 % and 0.2 % off, ratio 4.004), 8-bit quantization adds well under 1 %;
        // 10 % is far outside both, and far from what a wrong metric gives: a ratio of
        // 1 if it ignored the samples, 2 for an RMS, and on sRGB values instead of
        // linear ones a level 4.2 times too small (0.0044 at 4 spp).
        for (spp, got) in [(4, four), (16, sixteen)] {
            let want = expected(spp);
            assert!(
                (got / want - 1.0).abs() < 0.10,
                "{spp} spp: relMSE {got}, expected {want} from the variance"
            );
        }
        let ratio = four / sixteen;
        assert!(
            (3.6..=4.4).contains(&ratio),
            "4 -> 16 spp: relMSE ratio {ratio}"
        );
    }
}
