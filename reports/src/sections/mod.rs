//! The section builders: each turns the runs into one or a few [`Section`]s of the
//! document (see [`crate::document::SECTIONS`] for the order).
//!
//! | file | sections |
//! |---|---|
//! | `answers.rs` | answers (where the time goes, what the optimizations buy and cost, whether the FPGA pays off) |
//! | `fpga_answer.rs` | the break-even behind the third answer |
//! | `profile.rs` | the profile chapter (flat profile, charts, flamegraphs, Amdahl); profile-details |
//! | `variants.rs` | the variants chapter (the scene × variant matrix); variants-by-scene |
//! | `peer.rs` | the variants chapter's sentence on the peer, Embree in both its modes |
//! | `hardware.rs` | the hardware chapter (tables 7 and 8, the optimizations costed, device fit, software against hardware) |
//! | `synthesis.rs` | hardware-synthesis (the generated RTL through Yosys, inside the hardware chapter) |
//! | `images.rs` | the images chapter |
//! | `summary.rs` | summary (findings, machine, scenes, runs) |
//! | `ray_rates.rs` | ray-rates |
//! | `roofline.rs` | roofline |
//! | `pixel_maps.rs` | pixel-maps |
//! | `scaling.rs` | time-vs-primitives, spd |
//! | `bvh_quality.rs` | bvh-quality |
//! | `benchmarks.rs` | criterion |
//! | `closing.rs` | failures, reproduce |
//! | `comparison.rs` | comparison (several runs) |
//!
//! The builders of sections that only some results files can fill (the comparison,
//! ray-rates, roofline, pixel-maps, bvh-quality) return `None` when the data lack
//! them: an older file's report leaves them out rather than showing them empty.
//!
//! [`Section`]: crate::document::Section

pub(crate) mod access;
pub mod answers;
pub(crate) mod benchmarks;
pub(crate) mod bvh_quality;
pub(crate) mod closing;
pub(crate) mod comparison;
pub mod family_groups;
pub mod fpga_answer;
pub mod hardware;
pub mod images;
pub mod outside_tracers;
pub(crate) mod peer;
pub(crate) mod peer_yardstick;
pub(crate) mod pixel_maps;
pub(crate) mod profile;
pub(crate) mod ray_rates;
pub(crate) mod roofline;
pub(crate) mod scaling;
pub(crate) mod summary;
pub mod synthesis;
pub mod variants;

/// Pictures per row of an image grid (A4 and a laptop screen both fit six).
pub(crate) const GRID_COLUMNS: usize = 6;
