//! The JSON Schema of `results.json` (draft 2020-12), derived from the serde types of
//! [`crate::schema`] with `schemars`, so that other tools can read results without
//! Rust. The copy checked in as `docs/results.schema.json` is tested to match it
//! (`results/tests/json_schema.rs`; `RTPROF_BLESS=1` rewrites it).
//!
//! The schema describes what rtprof reads (serde's deserialization): fields with a
//! default (`/3`'s additions, every `Option`) are not required, so `/2` files validate
//! too; `/1` files are read through [`crate::v1`] and are not covered.

use crate::schema::{Results, SCHEMA};

/// Where the schema is checked in, relative to the workspace root.
pub const SCHEMA_PATH: &str = "docs/results.schema.json";

/// The JSON Schema of [`Results`], as JSON.
pub fn results_schema() -> serde_json::Value {
    let mut schema = schemars::schema_for!(Results);
    // The type's name ("Results") says little to a reader of the file alone.
    schema.insert(
        "title".to_string(),
        format!("rtprof results.json ({SCHEMA})").into(),
    );
    schema.to_value()
}

/// [`results_schema`] as the checked-in file spells it: pretty JSON with a trailing
/// newline.
pub fn results_schema_text() -> String {
    let mut text = serde_json::to_string_pretty(&results_schema()).unwrap_or_default();
    text.push('\n');
    text
}
