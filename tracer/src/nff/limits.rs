//! The sizes an NFF scene and its render may ask for ([`Limits`]), refused before
//! anything is allocated; each error names the limit to raise. The defaults
//! ([`Limits::DEFAULT`]) are generous for real scenes. With the `clap` feature the
//! limits are also the command line's `--max-*` flags, declared here once.

use crate::color::Rgb;

// Sizes refused before allocating, each raisable by setting its field. The defaults
// (`Limits::DEFAULT`) are generous for real scenes; every error names the field to
// raise. With the `clap` feature these are also the command line's flags (the field
// `max_side` is `--max-side`), so a limit, its default and its help live here only.
// (A plain comment: clap would take a doc comment as the about of every command that
// flattens these flags.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(
    feature = "clap",
    command(next_help_heading = "Limits (raise them for very large inputs)")
)]
pub struct Limits {
    /// Largest image width or height, pixels.
    #[cfg_attr(feature = "clap", arg(long, value_name = "PIXELS", default_value_t = Limits::DEFAULT.max_side))]
    pub max_side: u32,
    /// Largest image, width x height, pixels.
    #[cfg_attr(feature = "clap", arg(long, value_name = "PIXELS", default_value_t = Limits::DEFAULT.max_pixels))]
    pub max_pixels: u64,
    /// Largest framebuffer, bytes (12 a pixel: one f32 RGB triple).
    #[cfg_attr(feature = "clap", arg(long, value_name = "BYTES", default_value_t = Limits::DEFAULT.max_framebuffer_bytes))]
    pub max_framebuffer_bytes: u64,
    /// Most vertices of one polygon or patch.
    #[cfg_attr(feature = "clap", arg(long, value_name = "N", default_value_t = Limits::DEFAULT.max_polygon_vertices))]
    pub max_polygon_vertices: u64,
    /// Most primitives in a scene, all kinds together.
    #[cfg_attr(feature = "clap", arg(long, value_name = "N", default_value_t = Limits::DEFAULT.max_primitives))]
    pub max_primitives: u64,
    /// Ceiling of the ray-tree depth (a transmitting scene can double its rays per
    /// level, and every level is a stack frame of the recursive shader).
    #[cfg_attr(feature = "clap", arg(long, value_name = "N", default_value_t = Limits::DEFAULT.max_ray_depth))]
    pub max_ray_depth: u32,
    /// Largest scene file or text, bytes.
    #[cfg_attr(feature = "clap", arg(long, value_name = "BYTES", default_value_t = Limits::DEFAULT.max_file_bytes))]
    pub max_file_bytes: u64,
}

impl Limits {
    /// The defaults: 16,384 pixels a side, 64 Mi pixels, a 1 GiB framebuffer, 65,536
    /// vertices a polygon, 10 million primitives, depth 64, 1 GiB of scene.
    pub const DEFAULT: Limits = Limits {
        max_side: 16_384,
        max_pixels: 64 * 1024 * 1024,
        max_framebuffer_bytes: 1 << 30,
        max_polygon_vertices: 1 << 16,
        max_primitives: 10_000_000,
        max_ray_depth: 64,
        max_file_bytes: 1 << 30,
    };
}

impl Default for Limits {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// One of the [`Limits`], named by its field. Errors carry it, so that a front end
/// can say how to raise it in its own terms (rtprof: the flag its field declares).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    MaxSide,
    MaxPixels,
    MaxFramebufferBytes,
    MaxPolygonVertices,
    MaxPrimitives,
    MaxRayDepth,
    MaxFileBytes,
}

impl Limit {
    /// Every limit, in the order of [`Limits`]'s fields.
    pub const ALL: [Limit; 7] = [
        Limit::MaxSide,
        Limit::MaxPixels,
        Limit::MaxFramebufferBytes,
        Limit::MaxPolygonVertices,
        Limit::MaxPrimitives,
        Limit::MaxRayDepth,
        Limit::MaxFileBytes,
    ];

    /// The field of [`Limits`] that sets it (with the `clap` feature, also the id of
    /// the flag that does).
    pub fn field(self) -> &'static str {
        match self {
            Limit::MaxSide => "max_side",
            Limit::MaxPixels => "max_pixels",
            Limit::MaxFramebufferBytes => "max_framebuffer_bytes",
            Limit::MaxPolygonVertices => "max_polygon_vertices",
            Limit::MaxPrimitives => "max_primitives",
            Limit::MaxRayDepth => "max_ray_depth",
            Limit::MaxFileBytes => "max_file_bytes",
        }
    }

    /// How an error names it, at the end of its message: `(limit
    /// tracer::Limits::max_side)`. The one text a front end replaces with its own
    /// way to raise the limit.
    pub fn hint(self) -> String {
        format!("(limit tracer::Limits::{})", self.field())
    }
}

/// A size the [`Limits`] refuse: over one of them (`limit`), or impossible whatever
/// the limits (a zero size or depth: `limit` is `None`).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{message}{}", limit.map(|l| format!(" {}", l.hint())).unwrap_or_default())]
pub struct LimitError {
    pub limit: Option<Limit>,
    pub message: String,
}

impl LimitError {
    fn over(limit: Limit, message: String) -> Self {
        LimitError {
            limit: Some(limit),
            message,
        }
    }

    fn impossible(message: String) -> Self {
        LimitError {
            limit: None,
            message,
        }
    }
}

impl Limits {
    /// Bytes of framebuffer per pixel: one f32 RGB triple.
    pub const FRAMEBUFFER_BYTES_PER_PIXEL: u64 = std::mem::size_of::<Rgb>() as u64;

    /// Checks an image size against the side, pixel and framebuffer limits; the error
    /// says which limit to raise.
    pub fn check_size(&self, width: u64, height: u64) -> Result<(), LimitError> {
        if width == 0 || height == 0 {
            return Err(LimitError::impossible(format!(
                "image size {width}x{height} must be positive"
            )));
        }
        if width > u64::from(self.max_side) || height > u64::from(self.max_side) {
            return Err(LimitError::over(
                Limit::MaxSide,
                format!(
                    "image size {width}x{height} exceeds the limit of {} pixels per side",
                    self.max_side
                ),
            ));
        }
        let pixels = width.saturating_mul(height);
        if pixels > self.max_pixels {
            return Err(LimitError::over(
                Limit::MaxPixels,
                format!(
                    "image size {width}x{height} ({pixels} pixels) exceeds the limit of {} pixels",
                    self.max_pixels
                ),
            ));
        }
        let bytes = pixels.saturating_mul(Self::FRAMEBUFFER_BYTES_PER_PIXEL);
        if bytes > self.max_framebuffer_bytes {
            return Err(LimitError::over(
                Limit::MaxFramebufferBytes,
                format!(
                    "image size {width}x{height} needs a framebuffer of {bytes} bytes ({} per pixel), over the limit of {} bytes",
                    Self::FRAMEBUFFER_BYTES_PER_PIXEL,
                    self.max_framebuffer_bytes
                ),
            ));
        }
        Ok(())
    }

    /// Checks a maximum ray-tree depth (the eye ray is depth 1) against the ceiling.
    pub fn check_ray_depth(&self, depth: u32) -> Result<(), LimitError> {
        if depth == 0 {
            return Err(LimitError::impossible(
                "maximum ray depth 0: it must be at least 1 (the eye ray is depth 1)".into(),
            ));
        }
        if depth > self.max_ray_depth {
            return Err(LimitError::over(
                Limit::MaxRayDepth,
                format!(
                    "maximum ray depth {depth} exceeds the limit of {}",
                    self.max_ray_depth
                ),
            ));
        }
        Ok(())
    }

    /// Checks the size of a scene file or text, in bytes.
    pub fn check_file_size(&self, bytes: u64) -> Result<(), LimitError> {
        if bytes > self.max_file_bytes {
            return Err(LimitError::over(
                Limit::MaxFileBytes,
                format!(
                    "{bytes} bytes, over the limit of {} bytes for a scene",
                    self.max_file_bytes
                ),
            ));
        }
        Ok(())
    }
}
