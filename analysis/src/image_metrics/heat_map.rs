//! A false-colour picture of where two images differ, for eyeballing render artefacts.
//!
//! Ramp: black -> blue -> red -> yellow -> white, piecewise linear in four equal
//! segments (the stops sit at levels 0, 63.75, 127.5, 191.25 and 255). Luma rises
//! strictly along it, so brighter always means a larger difference, even in gray.

use super::RgbImage;
use super::check_same_size;
use crate::error::MetricsError;

const STOPS: [[u8; 3]; 5] = [
    [0, 0, 0],
    [0, 0, 255],
    [255, 0, 0],
    [255, 255, 0],
    [255, 255, 255],
];

/// Per pixel, the largest channel difference of `a` and `b` through the colour ramp,
/// scaled so that the largest difference in the image is white. Equal images give black.
pub fn difference_heat_map(a: &RgbImage, b: &RgbImage) -> Result<RgbImage, MetricsError> {
    check_same_size(a, b)?;
    let diffs: Vec<u8> = a
        .data
        .chunks_exact(3)
        .zip(b.data.chunks_exact(3))
        .map(|(pa, pb)| (0..3).map(|c| pa[c].abs_diff(pb[c])).max().unwrap_or(0))
        .collect();
    let peak = u32::from(diffs.iter().copied().max().unwrap_or(0));
    let data = diffs
        .iter()
        .flat_map(|&d| {
            // Rounded rescale of 0..=peak onto 0..=255; a zero peak means all black.
            let level = (u32::from(d) * 255 + peak / 2)
                .checked_div(peak)
                .unwrap_or(0);
            ramp(level as u8)
        })
        .collect();
    RgbImage::new(a.width, a.height, data)
}

/// The ramp colour of `level`: four equal segments between the five stops.
fn ramp(level: u8) -> [u8; 3] {
    // Position in quarter-units scaled by 255, so that level 255 lands on the last stop.
    let position = u32::from(level) * 4;
    let segment = ((position / 255) as usize).min(3);
    let within = position - segment as u32 * 255; // 0..=255 along the segment
    let (from, to) = (STOPS[segment], STOPS[segment + 1]);
    std::array::from_fn(|c| {
        let (f, t) = (u32::from(from[c]), u32::from(to[c]));
        ((f * (255 - within) + t * within + 127) / 255) as u8
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_metrics::rgb_image::luma;

    #[test]
    fn ramp_ends_black_and_white_with_rising_luma() {
        assert_eq!(ramp(0), [0, 0, 0]);
        assert_eq!(ramp(255), [255, 255, 255]);
        let lumas: Vec<u32> = (0..=255u8)
            .map(|l| {
                let [r, g, b] = ramp(l);
                299 * u32::from(r) + 587 * u32::from(g) + 114 * u32::from(b)
            })
            .collect();
        assert!(lumas.windows(2).all(|w| w[0] < w[1]), "luma must rise");
        // Rounded luma is at least non-decreasing.
        let rounded: Vec<u8> = (0..=255u8)
            .map(|l| {
                let [r, g, b] = ramp(l);
                luma(r, g, b)
            })
            .collect();
        assert!(rounded.windows(2).all(|w| w[0] <= w[1]));
    }

    #[test]
    fn equal_images_give_an_all_black_map_of_the_same_size() {
        let img = RgbImage::new(3, 2, (0..18).collect()).expect("valid image");
        let map = difference_heat_map(&img, &img).expect("same size");
        assert_eq!((map.width, map.height), (3, 2));
        assert!(map.data.iter().all(|&v| v == 0));
    }

    #[test]
    fn largest_difference_is_white_and_smaller_ones_darker() {
        let a = RgbImage::new(3, 1, vec![0; 9]).expect("valid image");
        // Max channel differences 0, 20 and 40: levels 0, 128 and 255.
        let b = RgbImage::new(3, 1, vec![0, 0, 0, 5, 20, 0, 40, 1, 1]).expect("valid image");
        let map = difference_heat_map(&a, &b).expect("same size");
        assert_eq!(&map.data[0..3], &[0, 0, 0]);
        assert_eq!(&map.data[3..6], &ramp(128));
        assert_eq!(&map.data[6..9], &[255, 255, 255]);
    }

    #[test]
    fn mismatched_sizes_are_an_error() {
        let a = RgbImage::new(2, 1, vec![0; 6]).expect("valid image");
        let b = RgbImage::new(1, 2, vec![0; 6]).expect("valid image");
        assert!(matches!(
            difference_heat_map(&a, &b),
            Err(MetricsError::SizeMismatch { .. })
        ));
    }
}
