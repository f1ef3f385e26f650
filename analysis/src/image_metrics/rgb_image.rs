//! The image type the metrics work on: 8-bit interleaved RGB, loaded from any format the
//! `image` crate decodes, plus its Rec. 601 luma (grayscale) view.

use std::path::Path;

use crate::error::MetricsError;

/// Interleaved 8-bit RGB pixels, row 0 at the top, `3 * width * height` bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RgbImage {
    pub width: u32,
    pub height: u32,
    pub data: Vec<u8>,
}

impl RgbImage {
    /// Wraps `data`, refusing empty images and a length that does not match the size.
    pub fn new(width: u32, height: u32, data: Vec<u8>) -> Result<Self, MetricsError> {
        let image = Self {
            width,
            height,
            data,
        };
        image.validate()?;
        Ok(image)
    }

    /// Decodes an image file (format sniffed from its content) and converts it to RGB8.
    pub fn load(path: &Path) -> Result<Self, MetricsError> {
        let load_error = |source| MetricsError::Load {
            path: path.to_path_buf(),
            source,
        };
        let decoded = image::ImageReader::open(path)
            .and_then(|reader| reader.with_guessed_format())
            .map_err(|e| load_error(image::ImageError::IoError(e)))?
            .decode()
            .map_err(load_error)?
            .into_rgb8();
        Self::new(decoded.width(), decoded.height(), decoded.into_raw())
    }

    /// Number of pixels (not bytes).
    pub fn pixel_count(&self) -> u64 {
        u64::from(self.width) * u64::from(self.height)
    }

    /// Rec. 601 luma `0.299 R + 0.587 G + 0.114 B`, rounded, one byte per pixel.
    pub fn gray(&self) -> Vec<u8> {
        self.data
            .chunks_exact(3)
            .map(|px| luma(px[0], px[1], px[2]))
            .collect()
    }

    /// The fields are public, so code that takes an `RgbImage` re-checks it rather than
    /// trusting that it came from `new`.
    pub(crate) fn validate(&self) -> Result<(), MetricsError> {
        let (width, height) = (self.width, self.height);
        if width == 0 || height == 0 {
            return Err(MetricsError::Empty { width, height });
        }
        let expected = 3 * self.pixel_count();
        if self.data.len() as u64 != expected {
            return Err(MetricsError::DataLength {
                width,
                height,
                expected,
                actual: self.data.len(),
            });
        }
        Ok(())
    }
}

/// Integer arithmetic in thousandths so that ties round up exactly (no float error).
pub(crate) fn luma(r: u8, g: u8, b: u8) -> u8 {
    let weighted = 299 * u32::from(r) + 587 * u32::from(g) + 114 * u32::from(b);
    // At most 255_000 + 500, so the quotient is at most 255.
    ((weighted + 500) / 1000) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_checks_length_and_emptiness() {
        assert!(RgbImage::new(2, 1, vec![0; 6]).is_ok());
        assert!(matches!(
            RgbImage::new(2, 1, vec![0; 5]),
            Err(MetricsError::DataLength {
                expected: 6,
                actual: 5,
                ..
            })
        ));
        assert!(matches!(
            RgbImage::new(0, 3, vec![]),
            Err(MetricsError::Empty { .. })
        ));
    }

    #[test]
    fn gray_uses_rec601_weights_rounded() {
        // red 0.299*255 = 76.245 -> 76; green 0.587*255 = 149.685 -> 150;
        // blue 0.114*255 = 29.07 -> 29; (2,1,0) -> 0.598 + 0.587 = 1.185 -> 1.
        let img = RgbImage::new(
            5,
            1,
            vec![255, 0, 0, 0, 255, 0, 0, 0, 255, 2, 1, 0, 255, 255, 255],
        )
        .expect("valid image");
        assert_eq!(img.gray(), vec![76, 150, 29, 1, 255]);
    }

    #[test]
    fn load_reads_a_written_png_and_reports_missing_files() {
        let dir = std::env::temp_dir().join(format!("analysis-rgb-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("tiny.png");
        let pixels = vec![1, 2, 3, 250, 251, 252];
        image::save_buffer(&path, &pixels, 2, 1, image::ExtendedColorType::Rgb8)
            .expect("write png");
        let loaded = RgbImage::load(&path).expect("load png");
        assert_eq!(loaded, RgbImage::new(2, 1, pixels).expect("valid image"));
        let missing = RgbImage::load(&dir.join("missing.png"));
        assert!(matches!(missing, Err(MetricsError::Load { .. })));
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
