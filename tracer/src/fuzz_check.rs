//! The check that the fuzz target (`fuzz/fuzz_targets/nff_scene.rs`) and the regression
//! test (`tests/fuzz_regressions.rs`) run on arbitrary NFF text: parse it with the
//! default [`Limits`], and when it parses, build every intersection structure (brute
//! force, SIMD lanes, BVH) and render a tiny image with each, under the variants that
//! prepare the scene or the camera differently, requiring a finite value in every pixel.
//!
//! Text that cannot be rendered must come back as an [`NffError`] naming a line of the
//! text; anything else (a render error after a successful parse, a NaN or infinite
//! pixel, an error pointing past the end of the text) is a [`Defect`]. Panics are not
//! caught: the fuzzer reports them itself.

use crate::camera::Sampling;
use crate::counter::NoCount;
use crate::nff::{Limits, NffError, parse_nff_with_limits};
use crate::render::{RenderError, RenderOptions};
use crate::shading::ShadingMode;
use crate::variants::dispatch::render_variant;
use crate::variants::set::VariantSet;

/// Width of the tiny image (the scene's own resolution is ignored: the parser has
/// already checked it against the limits, and rendering it would be slow).
pub const TINY_WIDTH: u32 = 4;
/// Height of the tiny image.
pub const TINY_HEIGHT: u32 = 3;

/// The renders run on every scene that parses: each accelerator, both sampling grids,
/// every shading mode, and the variants with their own scene preparation (`bounded`'s
/// eye offsets), camera (`ortho`), diffuse term, fill (`pixel-avg`) and every square root.
pub const RENDERS: [(&str, Sampling, ShadingMode); 7] = [
    ("baseline", Sampling::PixelCenters, ShadingMode::Color),
    ("simd", Sampling::PixelCenters, ShadingMode::Color),
    ("bvh", Sampling::SpdCorners, ShadingMode::Color),
    (
        "bvh+bounded+fast-sqrt-newton",
        Sampling::PixelCenters,
        ShadingMode::Gray,
    ),
    (
        "simd+ortho+pixel-avg+no-rsqrt-shading",
        Sampling::PixelCenters,
        ShadingMode::DiffuseOnly,
    ),
    (
        "no-rsqrt-shading+fast-sqrt",
        Sampling::SpdCorners,
        ShadingMode::Color,
    ),
    // The tuned constant also underestimates roots: "unit" vectors a little too long.
    (
        "simd+fast-sqrt-tuned",
        Sampling::PixelCenters,
        ShadingMode::Color,
    ),
];

/// What the check made of a text that is handled correctly.
#[derive(Debug)]
pub enum Outcome {
    /// The text is not a renderable scene; the error names a line of it.
    Rejected(NffError),
    /// Every render of [`RENDERS`] gave finite pixels.
    Rendered,
}

/// A bug found by the check.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Defect {
    #[error("parse error names line {line}, but the text has {lines} lines: {error}")]
    ErrorLineOutOfRange {
        error: NffError,
        line: usize,
        lines: usize,
    },
    #[error("fuzz_check::RENDERS lists a variant set that does not parse: '{variants}': {message}")]
    BadVariantSet {
        variants: &'static str,
        message: String,
    },
    #[error("the scene parsed but variants '{variants}' could not render it: {error}")]
    RenderFailed {
        variants: &'static str,
        error: RenderError,
    },
    #[error(
        "variants '{variants}' ({sampling:?}, {mode:?}) gave a wrong image: {pixels} pixels for {TINY_WIDTH}x{TINY_HEIGHT}"
    )]
    WrongSize {
        variants: &'static str,
        sampling: Sampling,
        mode: ShadingMode,
        pixels: usize,
    },
    #[error(
        "variants '{variants}' ({sampling:?}, {mode:?}) gave a non-finite pixel at ({x}, {y}): {value}"
    )]
    NonFinite {
        variants: &'static str,
        sampling: Sampling,
        mode: ShadingMode,
        x: u32,
        y: u32,
        value: String,
    },
}

/// Parses `text` (named `file` in errors) and, when it parses, renders it tiny with
/// every entry of [`RENDERS`].
pub fn parse_and_render_tiny(text: &str, file: &str) -> Result<Outcome, Defect> {
    let scene = match parse_nff_with_limits(text, file, &Limits::default()) {
        Ok(scene) => scene,
        Err(error) => {
            // `split('\n')` as the parser counts: a text ending in '\n' has an empty
            // last line, which is still a line number an error may name (end of file).
            let lines = text.split('\n').count();
            if error.line == 0 || error.line > lines {
                return Err(Defect::ErrorLineOutOfRange {
                    line: error.line,
                    lines,
                    error,
                });
            }
            return Ok(Outcome::Rejected(error));
        }
    };
    for (variants, sampling, mode) in RENDERS {
        let set = VariantSet::parse(variants).map_err(|e| Defect::BadVariantSet {
            variants,
            message: e.to_string(),
        })?;
        let options = RenderOptions::new(TINY_WIDTH, TINY_HEIGHT, sampling, mode);
        let out = render_variant::<NoCount>(&scene, &options, &set, &|_| {})
            .map_err(|error| Defect::RenderFailed { variants, error })?;
        let frame = &out.rendered.frame;
        if frame.pixels.len() != (TINY_WIDTH * TINY_HEIGHT) as usize {
            return Err(Defect::WrongSize {
                variants,
                sampling,
                mode,
                pixels: frame.pixels.len(),
            });
        }
        if let Some(at) = frame.pixels.iter().position(|p| !p.is_finite()) {
            return Err(Defect::NonFinite {
                variants,
                sampling,
                mode,
                x: at as u32 % TINY_WIDTH,
                y: at as u32 / TINY_WIDTH,
                value: format!("{:?}", frame.pixels[at]),
            });
        }
    }
    Ok(Outcome::Rendered)
}
