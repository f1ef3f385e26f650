//! The analysis stages of rtprof: they turn measurements (images, timings, sampled
//! call stacks) into figures (image-quality metrics, confidence intervals, gprof
//! tables, flamegraphs). Plain data in, plain data out; nothing here renders (the
//! sampler runs a closure it is given).
//!
//! Modules:
//! - [`image_metrics`]: method 1 of the thesis, pixel comparison of two renders (RMS
//!   and its verbal band, PSNR, SSIM, difference statistics, heat map) and grayscale
//!   histograms; for outside renderers' pictures, Monte Carlo noise (pbrt's relMSE and
//!   efficiency), mean FLIP, and likeness (same scene and conventions, same scene with
//!   other conventions, or another picture);
//! - [`ppm_text`]: method 2 of the thesis, histograms from the plain-text PPM (P3) form,
//!   with a P3 writer and parser;
//! - [`timing`]: median run time with a seeded percentile-bootstrap interval;
//! - [`power_law`]: `y = a x^b` fitted on log-log axes (how costs grow with scene size);
//! - [`verdict`]: the one rule that labels a time change faster, slower or within noise;
//! - [`profile`]: the sampling profiler (pprof) and what is made of its stacks: gprof
//!   flat profile and call graph, folded stacks, flamegraphs, Amdahl projections;
//! - [`error`]: the error types of the above.

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod error;
pub mod image_metrics;
pub mod linear_fit;
pub mod power_law;
pub mod ppm_text;
mod prng;
pub mod profile;
pub mod timing;
pub mod verdict;

pub use error::{MetricsError, StatsError};
pub use image_metrics::{
    Band, Comparison, Likeness, LikenessMeasures, Mismatch, NoiseError, RgbImage, compare,
    difference_heat_map, efficiency, flip_mean, gray_histogram, likeness, noise_error,
};
pub use ppm_text::{MAX_P3_PIXELS, P3Histograms, p3_histograms, parse_p3, to_p3};
pub use timing::{Estimate, median, median_with_bootstrap};
pub use verdict::{NOISE_THRESHOLD, Verdict};
