//! `reports`: the results of an rtprof suite and the reports made from them.
//!
//! Data flows one way: the suite runner fills [`results::Results`] (schema
//! `rtprof.results/3`, the `results` crate); [`document::build`] turns the runs into
//! one report [`document::Document`] (sections of paragraphs, tables of typed cells,
//! charts, image grids, flamegraphs, notes), with the section builders of
//! [`sections`], the charts of [`charts`] and the numbers written by [`format`](mod@format).
//! Renderers only lay the document out: [`html`] (one self-contained file), [`pdf`]
//! (typst, with the template `templates/report.typ`) and [`text`] (tables on a
//! terminal). Per-pixel counter maps leave as NumPy arrays ([`npy`]) and as
//! false-colour pictures with a legend ([`pixel_maps`]); flamegraph SVGs are made
//! static for print by [`flame_static`]. This crate never renders a scene.

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod charts;
pub mod document;
pub mod exports;
pub mod findings;
pub mod flame_static;
pub mod format;
pub mod fuzz_check;
pub mod gallery;
pub mod gate_text;
pub mod html;
pub mod markup;
pub mod npy;
pub mod page_values;
pub mod pdf;
pub mod pixel_maps;
mod print;
pub mod record_fpga;
pub mod record_probe;
pub mod record_report;
pub mod scaling_text;
pub mod sections;
pub mod table_format;
pub mod text;

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

pub use results::slug;
