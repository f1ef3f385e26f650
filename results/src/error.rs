//! Why a results file cannot be read: not JSON, not rtprof's, an unknown schema, too
//! large, or a value it may not hold (each said with where in the file).

use crate::limits::MAX_FILE_BYTES;
use crate::schema::{SCHEMA, SCHEMA_V1 as V1, SCHEMA_V2};

/// A results file that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum ResultsError {
    /// Not JSON, or JSON of the wrong shape: where serde stopped, and the JSON path of
    /// the value it stopped in (`scenes[0].variants[1].time`; empty for the top level
    /// and for syntax errors).
    #[error("line {line}, column {column}: {}", at_path(path, message))]
    Json {
        line: usize,
        column: usize,
        path: String,
        message: String,
    },
    /// JSON, but no rtprof results file: what it is instead.
    #[error("not an rtprof results file (no \"schema\" field): {0}")]
    NotResults(String),
    /// A `schema` field that is not rtprof's (another tool's file).
    #[error(
        "schema {0} is not an rtprof results schema (rtprof reads {SCHEMA}, {SCHEMA_V2} and {V1})"
    )]
    ForeignSchema(String),
    /// An rtprof results schema this version does not know (a newer or an older one).
    #[error(
        "results schema '{0}' is none of {SCHEMA}, {SCHEMA_V2} and {V1}: rebuild it with this rtprof version"
    )]
    Schema(String),
    #[error("{0} bytes or more: larger than a results file may be ({MAX_FILE_BYTES} bytes)")]
    TooLarge(usize),
    #[error("cannot read: {0}")]
    Io(#[from] std::io::Error),
    /// A value the file may not hold, at a JSON path (`scenes[3].variants[1].samples[7]`).
    #[error("{path}: {message}")]
    Invalid { path: String, message: String },
}

/// `path: message`, or the message alone at the top level.
fn at_path(path: &str, message: &str) -> String {
    if path.is_empty() {
        message.to_string()
    } else {
        format!("{path}: {message}")
    }
}

impl ResultsError {
    pub(crate) fn invalid(path: &str, message: impl Into<String>) -> Self {
        ResultsError::Invalid {
            path: path.to_string(),
            message: message.into(),
        }
    }

    /// serde_json's error at the JSON path `path`.
    pub(crate) fn json_at(e: &serde_json::Error, path: String) -> Self {
        // serde_json's message ends with " at line L column C"; the position is kept
        // apart so that callers can put it after the file name.
        let text = e.to_string();
        let message = match text.rfind(" at line ") {
            Some(at) => text[..at].to_string(),
            None => text,
        };
        ResultsError::Json {
            line: e.line(),
            column: e.column(),
            path,
            message,
        }
    }
}

impl From<serde_json::Error> for ResultsError {
    fn from(e: serde_json::Error) -> Self {
        Self::json_at(&e, String::new())
    }
}
