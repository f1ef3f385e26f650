//! `reports`: the results of an rtprof suite and the reports made from them.
//!
//! Data flows one way: the suite runner fills [`results::Results`] (plain serde data,
//! schema `rtprof.results/2`, defined in the `results` crate), this crate turns it into charts (SVG), one
//! self-contained HTML file and a typeset PDF. It never renders a scene.

pub mod benchmarks;
pub mod charts;
pub mod findings;
pub mod fuzz_check;
pub mod gallery;
pub mod html;
pub mod pdf;

pub use results;
pub use results::gate;

use std::path::PathBuf;

/// One run to report: its results and the directory its relative paths start from.
#[derive(Clone, Debug)]
pub struct Run {
    /// Short label for side-by-side tables (e.g. the hostname or file name).
    pub label: String,
    pub results: results::Results,
    pub base_dir: PathBuf,
}
