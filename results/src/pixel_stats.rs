//! The per-pixel maps of one render (`pixel-stats.json` beside the maps that
//! `rtprof count --pixel-stats DIR` writes, schema [`PIXEL_STATS_SCHEMA`]): which
//! counter each map holds, its files, unit and range, the grid the maps cover and the
//! clock that timed the samples.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The schema identifier of `pixel-stats.json`.
pub const PIXEL_STATS_SCHEMA: &str = "rtprof.pixel-stats/1";

/// The maps of one render.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PixelStats {
    pub schema: String,
    /// The scene as named on the command line (`spd:rings`, a file).
    pub scene: String,
    pub variant: String,
    /// `pixel centres` (one sample per pixel) or `SPD corners` ((W+1)×(H+1) samples).
    pub sampling: String,
    /// The sample grid every map covers, row 0 at the top.
    pub columns: u32,
    pub rows: u32,
    /// Worker threads of the renders (the counts do not depend on it).
    pub threads: u32,
    /// Smallest step of the clock that timed each sample, nanoseconds.
    pub clock_resolution_ns: f64,
    pub maps: Vec<PixelMap>,
    /// Counts that belong to no sample (the camera's set-up; the `bounded` variant's
    /// row bases), by counter key; only the non-zero ones. Each counter's map sums to
    /// the render's total minus this.
    pub frame_level: Vec<(String, u64)>,
}

/// One map: a counter (or the depth, or the time) per sample.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PixelMap {
    /// The counter's key (`tests.sphere.tests`, `accel.nodes_visited`), or
    /// `rays.secondary`, `ray_tree.depth`, `time.ns`.
    pub key: String,
    pub description: String,
    /// What one value counts, e.g. `tests per sample`.
    pub unit: String,
    /// File names, in the same directory: raw values (NumPy) and false colour.
    pub npy: String,
    pub png: String,
    /// NumPy type of the raw values (`<u8`, `<u4`, `|u1`).
    pub dtype: String,
    pub sum: u64,
    pub min: u64,
    pub max: u64,
    pub mean: f64,
}

/// Where a suite put one variant's maps of a scene, and what they hold.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct VariantPixelMaps {
    pub variant: crate::VariantName,
    /// The directory of the maps and their `pixel-stats.json`, relative to
    /// results.json; the maps' file names are relative to it.
    pub directory: String,
    pub columns: u32,
    pub rows: u32,
    pub clock_resolution_ns: f64,
    pub maps: Vec<PixelMap>,
}
