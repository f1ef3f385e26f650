//! `results`: the contract between an rtprof suite and everything that reads its
//! output. This crate defines ONLY the serde types of `rtprof.results/N` (the current
//! schema [`SCHEMA`], `rtprof.results/3`, in [`schema`] and [`hardware`]; `/2` is read
//! with the same types, `/1` from [`v1`], read and upgraded), their validation on read
//! ([`Results::from_json`]),
//! the regression gate ([`gate`]), and the JSON Schema derived from the types
//! ([`json_schema`], checked in as `docs/results.schema.json`).
//!
//! Other crates' types appear here only where the contract is theirs: variant names
//! are checked with `tracer`'s variant set, the RMS band and the estimate are
//! `analysis`'s, the hardware tables' figures are `hwmodel`'s.

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod bvh_quality;
pub mod change;
pub mod created;
pub mod efficiency;
mod error;
pub mod gate;
pub mod hardware;
pub mod json_schema;
pub mod limits;
pub mod outside;
pub mod pixel_stats;
mod read;
pub mod scaling;
pub mod schema;
pub mod thesis_profile;
pub mod timing_policy;
pub mod v1;
pub mod validate;
pub mod variant_name;

pub use analysis::verdict::NOISE_THRESHOLD;
pub use bvh_quality::BvhQuality;
pub use created::rfc3339_utc;
pub use hardware::{
    DeviceUse, HardwareResult, HwColumn, HwErrors, HwFigures, HwRow, HwRowKind, RtlClock,
    SceneHardware, SoftwarePeer, SynthBlock, Synthesis, Upload,
};
pub use outside::{Noise, OutsideProfile, OutsideTracer, Program};
pub use pixel_stats::{PixelMap, PixelStats, VariantPixelMaps};
pub use read::{FileError, ResultsError};
pub use schema::*;
pub use timing_policy::{TimeCovers, TimingPolicy};
pub use variant_name::{OUTSIDE_PREFIX, VariantName};

/// An id- and file-name-safe form of a name (ASCII letters, digits and '-'; the rest
/// become '_'): the runner names the files beside results.json with it, the reports
/// their anchors.
pub fn slug(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}
