//! The ranges and sizes a results file is held to, checked on read
//! ([`crate::validate`]; a larger file is refused before it is parsed).

/// Largest results file, bytes. The suite's files are well under a megabyte per
/// scene; this keeps reading (and everything after it) bounded.
pub const MAX_FILE_BYTES: usize = 64 << 20;
/// Longest plausible time, seconds (about 32 years). No render or suite takes
/// longer, and a bound this far below `f64::MAX` keeps every sum, ratio and chart
/// axis computed from times finite.
pub const MAX_SECONDS: f64 = 1e9;
/// Largest ratio of two times (speed-ups, Amdahl projections): times are at least
/// nanoseconds and at most [`MAX_SECONDS`].
pub const MAX_RATIO: f64 = 1e18;
/// Largest count (exact counters, cycles, resources, calls): 2^53, so that every
/// consumer's `f64` arithmetic on it is exact.
pub const MAX_COUNT: u64 = 1 << 53;
/// Timed repeats of one scene and variant: the suite takes at most 1000 (its
/// `repeats` limit; `min_seconds` adds up to 100).
pub const MAX_SAMPLES: usize = 1000;
/// Scenes of one run.
pub const MAX_SCENES: usize = 4096;
/// Variants of one run (and of one scene).
pub const MAX_VARIANTS: usize = 64;
/// Rows of any other list: profile rows, hardware rows, devices, failures,
/// benchmarks, counters of one result.
pub const MAX_ROWS: usize = 10_000;
/// Longest name, label, path or date.
pub const MAX_NAME: usize = 4096;
/// Longest free text (the command line, a failure's message).
pub const MAX_TEXT: usize = 65_536;
/// A percentage error of the hardware model against the thesis (the thesis's
/// smallest non-zero figure is 4; no model figure comes near 10^9 of it).
pub const MAX_ERROR_PCT: f64 = 1e9;
/// Worker threads and logical cores.
pub const MAX_THREADS: u32 = 1 << 16;
/// Bootstrap resamples of one interval.
pub const MAX_RESAMPLES: u32 = 10_000_000;
/// Largest possible RMS and per-channel difference on the 0-255 scale.
pub const MAX_RMS: f64 = 255.0;
/// PSNR of two 8-bit images that differ at all is below 200 dB (one unit in one
/// channel of 2^26 pixels is about 125 dB).
pub const MAX_PSNR_DB: f64 = 1000.0;
