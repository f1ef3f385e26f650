//! The section builders: each turns the runs into one or a few [`Section`]s of the
//! document (see [`crate::document::SECTIONS`] for the order).
//!
//! | file | sections |
//! |---|---|
//! | `summary.rs` | summary (findings, machine, scenes, runs) |
//! | `profile.rs` | profile, profile-charts, flamegraphs, amdahl |
//! | `variants.rs` | variants |
//! | `images.rs` | images |
//! | `hardware.rs` | hardware-tables, device-utilization, sw-hw |
//! | `scaling.rs` | time-vs-primitives, spd |
//! | `benchmarks.rs` | criterion |
//! | `closing.rs` | failures, reproduce |
//! | `comparison.rs` | comparison (several runs) |
//!
//! [`Section`]: crate::document::Section

pub(crate) mod access;
pub(crate) mod benchmarks;
pub(crate) mod closing;
pub(crate) mod comparison;
pub mod hardware;
pub(crate) mod images;
pub(crate) mod profile;
pub(crate) mod scaling;
pub(crate) mod summary;
pub(crate) mod variants;

/// Pictures per row of an image grid (A4 and a laptop screen both fit six).
pub(crate) const GRID_COLUMNS: usize = 6;
