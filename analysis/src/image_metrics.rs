//! Method 1 of the thesis: comparing two renders pixel by pixel (RMS with its verbal
//! band, PSNR, SSIM, difference statistics) and grayscale intensity histograms; and for
//! the pictures of outside renderers, Monte Carlo noise against a converged run
//! (relMSE, efficiency), NVIDIA's FLIP, and whether a picture shows the same scene
//! drawn with the same conventions at all (likeness).

mod band;
mod edges;
mod flip;
mod heat_map;
mod likeness;
mod noise;
mod rgb_image;
mod ssim;
#[cfg(test)]
mod test_scenes;

use serde::{Deserialize, Serialize};

pub use band::Band;
pub use flip::{FLIP_MAX_PIXELS, FLIP_PIXELS_PER_DEGREE, flip_mean};
pub use heat_map::difference_heat_map;
pub use likeness::{
    Likeness, LikenessMeasures, Mismatch, SAME_SCENE_MIN_EDGE_AGREEMENT, SAME_TONES_MAX_RMS,
    likeness,
};
pub use noise::{NoiseError, REL_MSE_EPSILON, efficiency, noise_error};
pub use rgb_image::RgbImage;

use crate::error::MetricsError;

/// Everything [`compare`] measures about a pair of same-sized images.
///
/// `psnr` is `f64::INFINITY` for identical images; JSON has no infinity, so it is
/// written as `null` there and `null` reads back as infinity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    pub width: u32,
    pub height: u32,
    /// Root mean square of the channel differences, 0-255 scale.
    pub rms: f64,
    pub band: Band,
    /// `20 log10(255 / rms)` in dB.
    #[serde(with = "infinite_as_null")]
    pub psnr: f64,
    /// Mean SSIM of the luma images (11x11 Gaussian window, see the `ssim` module).
    pub ssim: f64,
    pub max_abs_diff: u8,
    /// Mean absolute channel difference.
    pub mean_abs_diff: f64,
    /// Pixels where at least one channel differs.
    pub differing_pixels: u64,
    /// Gray (luma) histograms of the two images, 256 bins each.
    pub histogram_a: Vec<u64>,
    pub histogram_b: Vec<u64>,
    /// Histogram of the per-channel absolute differences (3 entries per pixel).
    pub diff_histogram: Vec<u64>,
}

/// Compares `a` with `b`; they must have the same size.
pub fn compare(a: &RgbImage, b: &RgbImage) -> Result<Comparison, MetricsError> {
    check_same_size(a, b)?;
    let mut diff_histogram = vec![0u64; 256];
    let mut sum_sq = 0u64;
    let mut sum_abs = 0u64;
    for (&x, &y) in a.data.iter().zip(&b.data) {
        let d = x.abs_diff(y);
        diff_histogram[usize::from(d)] += 1;
        sum_abs += u64::from(d);
        sum_sq += u64::from(d) * u64::from(d);
    }
    let differing_pixels = a
        .data
        .chunks_exact(3)
        .zip(b.data.chunks_exact(3))
        .filter(|(pa, pb)| pa != pb)
        .count() as u64;
    let values = a.data.len() as f64;
    let rms = (sum_sq as f64 / values).sqrt();
    let (width, height) = (a.width as usize, a.height as usize);
    Ok(Comparison {
        width: a.width,
        height: a.height,
        rms,
        band: Band::of(rms),
        // rms == 0 gives 255 / 0 = +inf, whose log is +inf: the documented value.
        psnr: 20.0 * (255.0 / rms).log10(),
        ssim: ssim::mean_ssim(&a.gray(), &b.gray(), width, height),
        max_abs_diff: diff_histogram.iter().rposition(|&n| n > 0).unwrap_or(0) as u8,
        mean_abs_diff: sum_abs as f64 / values,
        differing_pixels,
        histogram_a: gray_histogram(a).to_vec(),
        histogram_b: gray_histogram(b).to_vec(),
        diff_histogram,
    })
}

/// Number of pixels at each Rec. 601 luma level.
pub fn gray_histogram(img: &RgbImage) -> [u64; 256] {
    let mut bins = [0u64; 256];
    for level in img.gray() {
        bins[usize::from(level)] += 1;
    }
    bins
}

/// Both images must be well formed and of equal size before they are walked in step.
fn check_same_size(a: &RgbImage, b: &RgbImage) -> Result<(), MetricsError> {
    a.validate()?;
    b.validate()?;
    if (a.width, a.height) != (b.width, b.height) {
        return Err(MetricsError::SizeMismatch {
            a_width: a.width,
            a_height: a.height,
            b_width: b.width,
            b_height: b.height,
        });
    }
    Ok(())
}

/// Serde adapter: infinite PSNR as JSON `null`, since JSON numbers must be finite.
mod infinite_as_null {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
        if value.is_infinite() {
            serializer.serialize_none()
        } else {
            serializer.serialize_some(value)
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(deserializer)?.unwrap_or(f64::INFINITY))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prng::SplitMix64;

    /// A non-saturated textured image (all values in 40..=210) so offsets do not clip.
    fn textured(width: u32, height: u32) -> RgbImage {
        let mut data = Vec::new();
        for y in 0..height {
            for x in 0..width {
                data.push((40 + (x * 5 + y * 3) % 130) as u8);
                data.push((60 + (x * y) % 120) as u8);
                data.push((80 + ((x / 4 + y / 4) % 2) * 100) as u8);
            }
        }
        RgbImage::new(width, height, data).expect("valid image")
    }

    fn offset(img: &RgbImage, by: u8) -> RgbImage {
        let data = img.data.iter().map(|&v| v + by).collect();
        RgbImage::new(img.width, img.height, data).expect("valid image")
    }

    fn with_noise(img: &RgbImage, amplitude: i32, seed: u64) -> RgbImage {
        let mut rng = SplitMix64::new(seed);
        let span = (2 * amplitude + 1) as usize;
        let data = img
            .data
            .iter()
            .map(|&v| (i32::from(v) + rng.below(span) as i32 - amplitude).clamp(0, 255) as u8)
            .collect();
        RgbImage::new(img.width, img.height, data).expect("valid image")
    }

    #[test]
    fn identical_images_are_a_perfect_match() {
        let img = textured(24, 17);
        let c = compare(&img, &img).expect("same size");
        assert_eq!(c.rms, 0.0);
        assert!((c.ssim - 1.0).abs() < 1e-12, "ssim {}", c.ssim);
        assert!(c.psnr.is_infinite() && c.psnr > 0.0);
        assert_eq!(c.band, Band::VisuallyIdentical);
        assert_eq!(c.max_abs_diff, 0);
        assert_eq!(c.differing_pixels, 0);
        assert_eq!(c.histogram_a, c.histogram_b);
    }

    #[test]
    fn infinite_psnr_round_trips_through_json_as_null() {
        let img = textured(4, 4);
        let c = compare(&img, &img).expect("same size");
        let json = serde_json::to_value(&c).expect("serialize");
        assert!(json["psnr"].is_null());
        assert_eq!(json["band"], "visually_identical");
        let back: Comparison = serde_json::from_value(json).expect("deserialize");
        assert_eq!(back, c);
    }

    #[test]
    fn constant_offset_of_ten_gives_rms_ten() {
        let img = textured(20, 20);
        let c = compare(&img, &offset(&img, 10)).expect("same size");
        assert_eq!(c.rms, 10.0);
        // 20 log10(25.5), computed independently.
        assert!((c.psnr - 28.130_803_608_679_106).abs() < 1e-9);
        assert_eq!(c.band, Band::VisuallyIdentical);
        assert_eq!((c.max_abs_diff, c.mean_abs_diff), (10, 10.0));
        assert_eq!(c.differing_pixels, 400);
        // All 3 * 400 channel differences are exactly 10.
        assert_eq!(c.diff_histogram[10], 1200);
        assert_eq!(c.diff_histogram.iter().sum::<u64>(), 1200);
    }

    #[test]
    fn constant_offsets_land_in_the_expected_bands() {
        let img = textured(12, 12);
        for (by, band) in [
            (14, Band::VisuallyIdentical),
            (15, Band::Similar),
            (50, Band::NotableChanges),
            (60, Band::NotableChanges),
        ] {
            let c = compare(&img, &offset(&img, by)).expect("same size");
            assert_eq!(c.rms, f64::from(by));
            assert_eq!(c.band, band, "offset {by}");
        }
        let black = RgbImage::new(2, 2, vec![0; 12]).expect("valid image");
        let c = compare(&black, &offset(&black, 85)).expect("same size");
        assert_eq!(c.band, Band::Different);
    }

    #[test]
    fn rms_of_a_tiny_pair_matches_hand_arithmetic() {
        let a = RgbImage::new(2, 1, vec![10, 20, 30, 40, 50, 60]).expect("valid image");
        let b = RgbImage::new(2, 1, vec![20, 13, 31, 40, 50, 60]).expect("valid image");
        // Differences 10, -7, 1, 0, 0, 0: squares 100 + 49 + 1 = 150, mean 150 / 6 = 25,
        // RMS = 5. Absolute differences sum to 18, mean 3. Only pixel 0 differs.
        let c = compare(&a, &b).expect("same size");
        assert_eq!(c.rms, 5.0);
        assert_eq!(c.mean_abs_diff, 3.0);
        assert_eq!(c.max_abs_diff, 10);
        assert_eq!(c.differing_pixels, 1);
        assert!((c.psnr - 34.151_403_521_958_73).abs() < 1e-9); // 20 log10(51)
    }

    #[test]
    fn inverted_image_has_low_ssim() {
        let img = textured(32, 32);
        let inverted = RgbImage::new(32, 32, img.data.iter().map(|&v| 255 - v).collect())
            .expect("valid image");
        let c = compare(&img, &inverted).expect("same size");
        assert!(c.ssim < 0.1, "ssim {}", c.ssim);
    }

    #[test]
    fn ssim_falls_as_noise_rises() {
        let img = textured(40, 30);
        let ssims: Vec<f64> = [5, 20, 60]
            .iter()
            .map(|&amp| {
                compare(&img, &with_noise(&img, amp, 42))
                    .expect("same size")
                    .ssim
            })
            .collect();
        assert!(
            ssims[0] < 1.0 && ssims[0] > ssims[1] && ssims[1] > ssims[2],
            "{ssims:?}"
        );
    }

    #[test]
    fn gray_histogram_counts_hand_made_pixels() {
        // Luma: red 76, green 150, blue 29, red 76.
        let img = RgbImage::new(2, 2, vec![255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 0, 0])
            .expect("valid image");
        let bins = gray_histogram(&img);
        assert_eq!((bins[76], bins[150], bins[29]), (2, 1, 1));
        assert_eq!(bins.iter().sum::<u64>(), 4);
    }

    #[test]
    fn histograms_sum_to_the_pixel_count() {
        let img = textured(23, 11);
        let c = compare(&img, &with_noise(&img, 30, 1)).expect("same size");
        assert_eq!(c.histogram_a.iter().sum::<u64>(), 23 * 11);
        assert_eq!(c.histogram_b.iter().sum::<u64>(), 23 * 11);
        assert_eq!(c.diff_histogram.iter().sum::<u64>(), 3 * 23 * 11);
    }

    #[test]
    fn mismatched_sizes_are_an_error_naming_both() {
        let a = textured(4, 3);
        let b = textured(3, 4);
        let err = compare(&a, &b).expect_err("sizes differ");
        assert_eq!(err.to_string(), "image sizes differ: 4x3 vs 3x4");
        // A hand-built image with a wrong data length is refused, not indexed past.
        let broken = RgbImage {
            width: 4,
            height: 3,
            data: vec![0; 5],
        };
        assert!(matches!(
            compare(&a, &broken),
            Err(MetricsError::DataLength { .. })
        ));
    }
}
