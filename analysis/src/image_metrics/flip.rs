//! NVIDIA's FLIP (LDR-FLIP; Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström and
//! Fairchild, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020): a
//! per-pixel perceptual error in [0, 1] from colour differences (HyAB in a
//! Hunt-adjusted L*a*b*, after contrast-sensitivity filtering) and edge and point
//! differences, for 8-bit sRGB pictures. [`flip_mean`] is the mean of that error map,
//! the figure FLIP's own tool prints first.
//!
//! # Where it comes from
//!
//! The `nv-flip` crate (0.1.2, gfx-rs/nv-flip-rs; MIT OR Apache-2.0 OR Zlib, and
//! NVIDIA's BSD-3-Clause for the C++ it compiles) binds NVIDIA's own C++ implementation.
//! It is the wgpu project's, whose test suite compares its frames with it. Checked before adopting it (2026-11):
//! - kept: its last change is from August 2023 (three releases in 2023), so it is
//!   finished rather than maintained. It wraps FLIP as of v1.2; later versions changed
//!   the packaging (one header from v1.3, Python on PyPI) and, in v1.3, the output
//!   slightly ("changing the order of some transforms", FLIP's version list), so a
//!   figure here may differ from current FLIP's in its last digits. The algorithm is
//!   the paper's, and the crate is one small file of bindings, so a dormant crate is a
//!   small risk; the tests hold its figures to values computed by hand from the
//!   paper's formulas, so a change would show.
//! - builds here: from crates.io like every dependency; its only build dependency, `cc`,
//!   was already in the workspace; it needs a C++ compiler, which the machines have
//!   (g++, as for the probe's C tests).
//! - cost: a cold build of the two crates took 4-7 s with the C++ at opt-level 1 (2.5 s
//!   at 0, 13 s at 3), on one core, beside the rest of the build. The C++ builds at
//!   opt-level 1 in both profiles (root Cargo.toml, docs/build-times.md): an 800x600
//!   comparison took 1.4-2.1 s at 0 and 0.15-0.23 s at 1.
//!
//! # Limits
//!
//! The bindings compute the buffer size in `u32` and assert on it, so images above
//! [`FLIP_MAX_PIXELS`] are refused with an error before they reach them. FLIP judges
//! what a viewer sees: the viewing setup is FLIP's default, 67 pixels per degree (a
//! 0.7 m wide 4K monitor seen from 0.7 m).

use super::RgbImage;
use super::check_same_size;
use crate::error::MetricsError;

/// FLIP's standard viewing setup: 0.7 m from a 0.7 m wide monitor of 3840 pixels,
/// `0.7 × (3840 / 0.7) × π / 180 ≈ 67` pixels per degree of visual angle.
pub const FLIP_PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// The largest image [`flip_mean`] takes: the bindings size the RGB buffer as a `u32`
/// count of bytes.
pub const FLIP_MAX_PIXELS: u64 = u32::MAX as u64 / 3;

/// Mean LDR-FLIP error of `test` against `reference` at [`FLIP_PIXELS_PER_DEGREE`]:
/// 0 for identical images, up to 1 for the largest perceptible difference.
pub fn flip_mean(test: &RgbImage, reference: &RgbImage) -> Result<f64, MetricsError> {
    check_same_size(test, reference)?;
    if test.pixel_count() > FLIP_MAX_PIXELS {
        return Err(MetricsError::FlipTooLarge {
            width: test.width,
            height: test.height,
            limit: FLIP_MAX_PIXELS,
        });
    }
    let (width, height) = (test.width, test.height);
    let reference = nv_flip::FlipImageRgb8::with_data(width, height, &reference.data);
    let test = nv_flip::FlipImageRgb8::with_data(width, height, &test.data);
    let error_map = nv_flip::flip(reference, test, FLIP_PIXELS_PER_DEGREE).to_vec();
    // Summed in f64: an f32 sum of millions of small errors loses digits.
    let sum: f64 = error_map.iter().map(|&e| f64::from(e)).sum();
    Ok(sum / error_map.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_metrics::test_scenes::{discs, uniform, with_noise};

    #[test]
    fn the_viewing_setup_is_flips_standard_67_pixels_per_degree() {
        let ppd = 0.7 * (3840.0 / 0.7) * std::f64::consts::PI / 180.0;
        assert!((ppd - 67.02).abs() < 0.01);
        assert_eq!(FLIP_PIXELS_PER_DEGREE, 67.0);
    }

    #[test]
    fn identical_pictures_have_no_flip_error() {
        let scene = discs(48, 40, [30, 40, 60]);
        assert_eq!(flip_mean(&scene, &scene).expect("same size"), 0.0);
    }

    /// Two uniform images have no edges or points, so FLIP is its colour term alone,
    /// and the contrast-sensitivity filters (normalized to sum 1) leave a uniform
    /// image as it is. The expected values were computed by hand from the paper's
    /// formulas: sRGB decoded, to XYZ (the sRGB matrix) and L*a*b* (white = RGB 1,1,1),
    /// a* and b* scaled by 0.01 L* (Hunt), HyAB = |dL| + sqrt(da^2 + db^2), raised to
    /// q_c = 0.7; cmax is that distance from green to blue, 41.2776; then the paper's
    /// remapping with p_c = 0.4, p_t = 0.95:
    /// - black to white: HyAB 100, 100^0.7 = 25.1189 > p_c cmax = 16.5110, so
    ///   0.95 + (25.1189 - 16.5110) / (41.2776 - 16.5110) × 0.05 = 0.96738;
    /// - grey 128 to grey 140: L* 53.585 to 58.250, 4.665^0.7 = 2.9390 < 16.5110, so
    ///   0.95 / 16.5110 × 2.9390 = 0.16910.
    ///
    /// The C++ carries its matrices to more digits, hence the tolerance.
    #[test]
    fn uniform_pictures_give_the_hand_computed_colour_difference() {
        let black = uniform(16, 12, [0, 0, 0]);
        let white = uniform(16, 12, [255, 255, 255]);
        let got = flip_mean(&white, &black).expect("same size");
        assert!((got - 0.967_378).abs() < 2e-4, "black/white {got}");
        let grey =
            flip_mean(&uniform(16, 12, [140; 3]), &uniform(16, 12, [128; 3])).expect("same size");
        assert!((grey - 0.169_102).abs() < 2e-4, "grey 128/140 {grey}");
    }

    #[test]
    fn flip_rises_with_the_noise_of_the_picture() {
        let scene = discs(64, 48, [30, 40, 60]);
        let errors: Vec<f64> = [4, 16, 48]
            .iter()
            .map(|&amplitude| {
                flip_mean(&with_noise(&scene, amplitude, 5), &scene).expect("same size")
            })
            .collect();
        assert!(
            0.0 < errors[0] && errors[0] < errors[1] && errors[1] < errors[2] && errors[2] < 1.0,
            "{errors:?}"
        );
    }

    #[test]
    fn mismatched_sizes_are_an_error_not_a_panic() {
        let a = uniform(4, 3, [0; 3]);
        let b = uniform(3, 4, [0; 3]);
        assert!(matches!(
            flip_mean(&a, &b),
            Err(MetricsError::SizeMismatch { .. })
        ));
    }
}
