//! Writing frames as PNG or binary PPM (P6), chosen by file extension, atomically:
//! the image goes to a temporary file beside the target and is renamed into place,
//! so a reader never sees half an image.

use crate::render::Frame;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Image file formats rtprof writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Ppm,
}

/// Why an image could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    #[error("cannot tell the image format of {0}: use a .png or .ppm extension")]
    UnknownExtension(String),
    #[error("cannot write {path}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot encode {path}: {message}")]
    Encode { path: String, message: String },
}

impl ImageFormat {
    /// The format named by `path`'s extension (case-insensitive).
    pub fn from_path(path: &Path) -> Result<Self, ImageError> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("png") => Ok(Self::Png),
            Some("ppm") => Ok(Self::Ppm),
            _ => Err(ImageError::UnknownExtension(path.display().to_string())),
        }
    }
}

/// The frame as a binary PPM (P6) file.
pub fn encode_ppm(frame: &Frame) -> Vec<u8> {
    encode_ppm_rgb8(frame.width, frame.height, &frame.to_rgb8())
}

/// Interleaved 8-bit RGB as a binary PPM (P6) file.
pub fn encode_ppm_rgb8(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
    let mut out = format!("P6\n{width} {height}\n255\n").into_bytes();
    out.extend_from_slice(rgb);
    out
}

/// The frame as a PNG file (8-bit RGB).
pub fn encode_png(frame: &Frame) -> Result<Vec<u8>, String> {
    encode_png_rgb8(frame.width, frame.height, &frame.to_rgb8())
}

/// Interleaved 8-bit RGB as a PNG file.
pub fn encode_png_rgb8(width: u32, height: u32, rgb: &[u8]) -> Result<Vec<u8>, String> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(rgb, width, height, image::ExtendedColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(out)
}

/// Writes `frame` to `path` in the format its extension names, atomically.
pub fn write_image(path: &Path, frame: &Frame) -> Result<(), ImageError> {
    write_rgb8(path, frame.width, frame.height, &frame.to_rgb8())
}

/// Writes interleaved 8-bit RGB to `path` in the format its extension names,
/// atomically.
pub fn write_rgb8(path: &Path, width: u32, height: u32, rgb: &[u8]) -> Result<(), ImageError> {
    let bytes = match ImageFormat::from_path(path)? {
        ImageFormat::Ppm => encode_ppm_rgb8(width, height, rgb),
        ImageFormat::Png => {
            encode_png_rgb8(width, height, rgb).map_err(|message| ImageError::Encode {
                path: path.display().to_string(),
                message,
            })?
        }
    };
    write_atomically(path, &bytes).map_err(|source| ImageError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// Writes `bytes` to a temporary file beside `path`, then renames it over `path`.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let temp = temp_path(path);
    let result = (|| {
        let mut file = std::fs::File::create(&temp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        std::fs::rename(&temp, path)
    })();
    if result.is_err() {
        std::fs::remove_file(&temp).ok();
    }
    result
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    #[test]
    fn ppm_header_and_pixels() {
        let frame = Frame {
            width: 2,
            height: 1,
            pixels: vec![Rgb::new(1.0, 0.0, 0.5), Rgb::new(2.0, -1.0, 0.25)],
        };
        let ppm = encode_ppm(&frame);
        assert_eq!(&ppm[..11], b"P6\n2 1\n255\n");
        assert_eq!(&ppm[11..], &[255, 0, 128, 255, 0, 64]);
    }

    #[test]
    fn format_from_extension() {
        assert_eq!(
            ImageFormat::from_path(Path::new("a/b.PNG")).ok(),
            Some(ImageFormat::Png)
        );
        assert_eq!(
            ImageFormat::from_path(Path::new("b.ppm")).ok(),
            Some(ImageFormat::Ppm)
        );
        assert!(ImageFormat::from_path(Path::new("b.jpg")).is_err());
        assert!(ImageFormat::from_path(Path::new("b")).is_err());
    }
}
