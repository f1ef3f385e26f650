//! Error types of the analysis crate: one enum for image input and metrics, one for
//! timing statistics.

use std::path::PathBuf;

/// Why an image could not be built, loaded, parsed or compared.
#[derive(Debug, thiserror::Error)]
pub enum MetricsError {
    #[error("image has no pixels ({width}x{height})")]
    Empty { width: u32, height: u32 },
    #[error("{width}x{height} RGB image needs {expected} bytes but has {actual}")]
    DataLength {
        width: u32,
        height: u32,
        expected: u64,
        actual: usize,
    },
    #[error("image sizes differ: {a_width}x{a_height} vs {b_width}x{b_height}")]
    SizeMismatch {
        a_width: u32,
        a_height: u32,
        b_width: u32,
        b_height: u32,
    },
    #[error("cannot load image {}", path.display())]
    Load {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error("plain PPM, line {line}: {problem}")]
    P3 { line: usize, problem: String },
    #[error("plain PPM of {width}x{height} exceeds the limit of {limit} pixels")]
    TooLarge { width: u64, height: u64, limit: u64 },
    #[error("FLIP takes images of at most {limit} pixels, not {width}x{height}")]
    FlipTooLarge { width: u32, height: u32, limit: u64 },
}

/// Why timing statistics could not be computed.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum StatsError {
    #[error("no samples")]
    Empty,
    #[error("sample {index} is not finite ({value})")]
    NotFinite { index: usize, value: f64 },
    #[error("confidence must lie strictly between 0 and 1, got {0}")]
    Confidence(f64),
    #[error("at least one bootstrap resample is needed")]
    NoResamples,
}
