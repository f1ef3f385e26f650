//! Which images the reports embed, and at what size.
//!
//! A default suite writes about 400 full-size PNGs (20 MB); embedding them all would
//! make a report too heavy to open or mail. The reports show the image grid of a few
//! scenes chosen from the data ([`showcase_scenes`]) and embed every picture as a
//! thumbnail ([`thumbnail`]); the full-size files stay in the run's `images/`.

use crate::results::{Results, SceneResult};
use image::codecs::png::{CompressionType, FilterType as PngFilter, PngEncoder};
use std::path::Path;

/// At most this many scenes get an image grid.
pub const SHOWCASE_SCENES: usize = 6;

/// Embedded pictures are at most this wide (a grid column is narrower on screen and
/// on A4; a reader who wants the pixels opens the file).
pub const THUMBNAIL_WIDTH: u32 = 320;

/// The scenes whose images the reports show, in the run's order: every scene when
/// there are few; otherwise the scene with the largest image difference of any variant
/// (where a reader should look), the largest scene of each family (balls, cylinders,
/// mixed, generated, SPD), then the next largest scenes.
pub fn showcase_scenes(r: &Results) -> Vec<&SceneResult> {
    let with_images: Vec<&SceneResult> =
        r.scenes.iter().filter(|s| !s.variants.is_empty()).collect();
    if with_images.len() <= SHOWCASE_SCENES {
        return with_images;
    }
    let worst_rms = |s: &SceneResult| {
        s.variants
            .iter()
            .filter_map(|v| v.quality.as_ref().map(|q| q.rms))
            .fold(0.0_f64, f64::max)
    };
    let mut chosen: Vec<usize> = Vec::new();
    if let Some((i, _)) = with_images
        .iter()
        .enumerate()
        .filter(|(_, s)| worst_rms(s) > 0.0)
        .max_by(|a, b| worst_rms(a.1).total_cmp(&worst_rms(b.1)))
    {
        chosen.push(i);
    }
    let mut by_size: Vec<usize> = (0..with_images.len()).collect();
    // Stable sort: among equal primitive counts the earlier scene wins.
    by_size.sort_by_key(|&i| std::cmp::Reverse(with_images[i].primitives));
    let family_is_shown = |chosen: &[usize], i: usize| {
        chosen
            .iter()
            .any(|&c| with_images[c].family == with_images[i].family)
    };
    for &i in &by_size {
        if chosen.len() < SHOWCASE_SCENES && !family_is_shown(&chosen, i) {
            chosen.push(i);
        }
    }
    for &i in &by_size {
        if chosen.len() < SHOWCASE_SCENES && !chosen.contains(&i) {
            chosen.push(i);
        }
    }
    chosen.sort_unstable();
    chosen.into_iter().map(|i| with_images[i]).collect()
}

/// The names of the scenes with images that [`showcase_scenes`] left out.
pub fn omitted_scenes(r: &Results) -> Vec<&str> {
    let shown = showcase_scenes(r);
    r.scenes
        .iter()
        .filter(|s| !s.variants.is_empty() && !shown.iter().any(|c| std::ptr::eq(*c, *s)))
        .map(|s| s.name.as_str())
        .collect()
}

/// A picture file read for embedding.
pub enum Picture {
    /// PNG bytes, scaled down to [`THUMBNAIL_WIDTH`] when the file was wider.
    Png(Vec<u8>),
    /// Why the file cannot be shown.
    Unusable(String),
}

/// Reads `base/rel` and returns it as a PNG no wider than [`THUMBNAIL_WIDTH`].
pub fn thumbnail(base: &Path, rel: &str) -> Picture {
    thumbnail_within(base, rel, THUMBNAIL_WIDTH)
}

/// Reads `base/rel` and returns it as a PNG no wider than `max_width`.
pub fn thumbnail_within(base: &Path, rel: &str, max_width: u32) -> Picture {
    let bytes = match std::fs::read(base.join(rel)) {
        Ok(b) => b,
        Err(e) => return Picture::Unusable(e.kind().to_string()),
    };
    if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        return Picture::Unusable("not a PNG file".to_string());
    }
    match scale_png(&bytes, max_width) {
        Ok(Some(smaller)) => Picture::Png(smaller),
        Ok(None) => Picture::Png(bytes),
        Err(why) => Picture::Unusable(why),
    }
}

/// `Some(png)` scaled to `max_width` (aspect kept) when `png` is wider; `None` when it
/// already fits.
fn scale_png(png: &[u8], max_width: u32) -> Result<Option<Vec<u8>>, String> {
    let decoded = image::load_from_memory_with_format(png, image::ImageFormat::Png)
        .map_err(|e| format!("damaged PNG: {e}"))?;
    if decoded.width() <= max_width {
        return Ok(None);
    }
    let height = ((decoded.height() as u64 * max_width as u64) / decoded.width() as u64).max(1);
    // A triangle filter averages each output pixel's whole footprint, so an isolated
    // difference in a heat map stays visible (dimmer) instead of being skipped.
    let scaled = decoded
        .resize_exact(max_width, height as u32, image::imageops::Triangle)
        .to_rgb8();
    // Gray pictures (the emulator's, the diffuse-only renders) take a third of the
    // bytes as one channel.
    let gray = scaled.pixels().all(|p| p[0] == p[1] && p[1] == p[2]);
    let mut out = Vec::new();
    // Default, not Best, compression: Best's deflate search took a third of
    // `rtprof report`'s time (typst optimised) for 1 % of the HTML report's size.
    let encoder =
        PngEncoder::new_with_quality(&mut out, CompressionType::Default, PngFilter::Adaptive);
    let result = if gray {
        image::DynamicImage::ImageRgb8(scaled)
            .to_luma8()
            .write_with_encoder(encoder)
    } else {
        scaled.write_with_encoder(encoder)
    };
    result.map_err(|e| format!("cannot encode a thumbnail: {e}"))?;
    Ok(Some(out))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(width: u32, height: u32) -> Vec<u8> {
        let img = image::RgbImage::from_fn(width, height, |x, y| {
            image::Rgb([(x % 256) as u8, (y % 256) as u8, 128])
        });
        let mut out = std::io::Cursor::new(Vec::new());
        image::DynamicImage::ImageRgb8(img)
            .write_to(&mut out, image::ImageFormat::Png)
            .unwrap();
        out.into_inner()
    }

    #[test]
    fn the_showcase_keeps_the_worst_image_and_the_largest_scenes() {
        let mut r = testkit::sample_results();
        assert!(r.scenes.len() > SHOWCASE_SCENES);
        // Make a small scene the one with the largest difference.
        let small = r.scenes.iter().position(|s| s.name == "balls2").unwrap();
        r.scenes[small].variants[1].quality.as_mut().unwrap().rms = 1000.0;
        let shown: Vec<&str> = showcase_scenes(&r)
            .iter()
            .map(|s| s.name.as_str())
            .collect();
        assert_eq!(shown.len(), SHOWCASE_SCENES);
        assert!(shown.contains(&"balls2"), "{shown:?}");
        let largest = r.scenes.iter().max_by_key(|s| s.primitives).unwrap();
        assert!(shown.contains(&largest.name.as_str()), "{shown:?}");
        // The largest of each family: balls7, cylinder7 and both7 in the sample.
        for name in ["balls7", "cylinder7", "both7"] {
            assert!(shown.contains(&name), "{name} missing from {shown:?}");
        }
        // In the run's order, and every scene is either shown or listed as omitted.
        let order: Vec<usize> = shown
            .iter()
            .map(|n| r.scenes.iter().position(|s| s.name == *n).unwrap())
            .collect();
        assert!(order.windows(2).all(|w| w[0] < w[1]));
        let with_images = r.scenes.iter().filter(|s| !s.variants.is_empty()).count();
        assert_eq!(omitted_scenes(&r).len() + shown.len(), with_images);
    }

    #[test]
    fn a_few_scenes_are_all_shown() {
        let mut r = testkit::sample_results();
        r.scenes.truncate(SHOWCASE_SCENES);
        assert_eq!(showcase_scenes(&r).len(), SHOWCASE_SCENES);
        assert!(omitted_scenes(&r).is_empty());
    }

    #[test]
    fn wide_images_shrink_to_the_thumbnail_width_with_their_aspect() {
        let small = scale_png(&png(640, 480), 320).unwrap().unwrap();
        let img = image::load_from_memory(&small).unwrap();
        assert_eq!((img.width(), img.height()), (320, 240));
        assert!(scale_png(&png(160, 120), 320).unwrap().is_none());
        assert!(scale_png(b"\x89PNG\r\n\x1a\nbroken", 320).is_err());
    }
}
