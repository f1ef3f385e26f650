//! The sizes an NFF scene and its render may ask for, refused before anything is
//! allocated; each error names the limit to raise.

use crate::color::Rgb;

/// Sizes refused before allocating, each raisable by setting its field. The defaults
/// are generous for real scenes; every error names the field to raise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Largest accepted width or height, in pixels (default 16,384).
    pub max_side: u32,
    /// Largest accepted width × height (default 64 Mi pixels).
    pub max_pixels: u64,
    /// Largest framebuffer, [`Limits::FRAMEBUFFER_BYTES_PER_PIXEL`] bytes per pixel
    /// (default 1 GiB).
    pub max_framebuffer_bytes: u64,
    /// Largest vertex count of one `p` or `pp` (default 65,536).
    pub max_polygon_vertices: u64,
    /// Most primitives in one scene, all kinds together (default 10 million).
    pub max_primitives: u64,
    /// Ceiling of the settable maximum ray-tree depth,
    /// [`RenderOptions::max_depth`](crate::RenderOptions::max_depth) (default 64: a
    /// transmitting scene can double its rays per level, and every level is a stack
    /// frame of the recursive shader).
    pub max_ray_depth: u32,
    /// Largest scene file or text, in bytes (default 1 GiB).
    pub max_file_bytes: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_side: 16_384,
            max_pixels: 64 * 1024 * 1024,
            max_framebuffer_bytes: 1 << 30,
            max_polygon_vertices: 1 << 16,
            max_primitives: 10_000_000,
            max_ray_depth: 64,
            max_file_bytes: 1 << 30,
        }
    }
}

/// How an error names the limit it hit.
pub(super) fn raise_hint(field: &str) -> String {
    format!(
        "limit {field}: raise it with rtprof's --{} or tracer::Limits::{field}",
        field.replace('_', "-")
    )
}

impl Limits {
    /// Bytes of framebuffer per pixel: one f32 RGB triple.
    pub const FRAMEBUFFER_BYTES_PER_PIXEL: u64 = std::mem::size_of::<Rgb>() as u64;

    /// Checks an image size against the side, pixel and framebuffer limits; the error
    /// says which limit to raise.
    pub fn check_size(&self, width: u64, height: u64) -> Result<(), String> {
        if width == 0 || height == 0 {
            return Err(format!("image size {width}x{height} must be positive"));
        }
        if width > u64::from(self.max_side) || height > u64::from(self.max_side) {
            return Err(format!(
                "image size {width}x{height} exceeds the limit of {} pixels per side ({})",
                self.max_side,
                raise_hint("max_side")
            ));
        }
        let pixels = width.saturating_mul(height);
        if pixels > self.max_pixels {
            return Err(format!(
                "image size {width}x{height} ({pixels} pixels) exceeds the limit of {} pixels ({})",
                self.max_pixels,
                raise_hint("max_pixels")
            ));
        }
        let bytes = pixels.saturating_mul(Self::FRAMEBUFFER_BYTES_PER_PIXEL);
        if bytes > self.max_framebuffer_bytes {
            return Err(format!(
                "image size {width}x{height} needs a framebuffer of {bytes} bytes ({} per pixel), over the limit of {} bytes ({})",
                Self::FRAMEBUFFER_BYTES_PER_PIXEL,
                self.max_framebuffer_bytes,
                raise_hint("max_framebuffer_bytes")
            ));
        }
        Ok(())
    }

    /// Checks a maximum ray-tree depth (the eye ray is depth 1) against the ceiling.
    pub fn check_ray_depth(&self, depth: u32) -> Result<(), String> {
        if depth == 0 {
            return Err(
                "maximum ray depth 0: it must be at least 1 (the eye ray is depth 1)".into(),
            );
        }
        if depth > self.max_ray_depth {
            return Err(format!(
                "maximum ray depth {depth} exceeds the limit of {} ({})",
                self.max_ray_depth,
                raise_hint("max_ray_depth")
            ));
        }
        Ok(())
    }

    /// Checks the size of a scene file or text, in bytes.
    pub fn check_file_size(&self, bytes: u64) -> Result<(), String> {
        if bytes > self.max_file_bytes {
            return Err(format!(
                "{bytes} bytes, over the limit of {} bytes for a scene ({})",
                self.max_file_bytes,
                raise_hint("max_file_bytes")
            ));
        }
        Ok(())
    }
}
