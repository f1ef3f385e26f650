//! Reading a results file: the schema dispatch (`/2`, or `/1` upgraded) and the
//! errors that say where a file is wrong.

use std::io::Read;
use std::path::{Path, PathBuf};

use crate::schema::{Results, SCHEMA, SCHEMA_V2};
use crate::v1;
use crate::v1::SCHEMA as V1;
use crate::validate::limits::MAX_FILE_BYTES;

/// At most 64 characters of an unknown schema name, for the message.
fn truncated(text: &str) -> String {
    let mut out: String = text.chars().take(64).collect();
    if out.len() < text.len() {
        out.push('…');
    }
    out
}

/// A results file that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum ResultsError {
    /// Not JSON, or JSON of the wrong shape: where serde stopped.
    #[error("line {line}, column {column}: {message}")]
    Json {
        line: usize,
        column: usize,
        message: String,
    },
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

impl ResultsError {
    pub(crate) fn invalid(path: &str, message: impl Into<String>) -> Self {
        ResultsError::Invalid {
            path: path.to_string(),
            message: message.into(),
        }
    }
}

impl From<serde_json::Error> for ResultsError {
    fn from(e: serde_json::Error) -> Self {
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
            message,
        }
    }
}

/// A results file that cannot be read, with its name. The cause is part of the message
/// (and not a `source`), so that an error chain prints it once.
#[derive(Debug, thiserror::Error)]
#[error("{}: {error}", path.display())]
pub struct FileError {
    pub path: PathBuf,
    pub error: ResultsError,
}

/// Only the schema field, read first so that a file of another version is named as
/// such instead of failing on its first different field.
#[derive(serde::Deserialize)]
struct SchemaOnly {
    schema: Option<String>,
}

impl Results {
    /// Reads a results file of schema `/2`, or `/1` upgraded to it, and validates it
    /// ([`Results::validate`]): the file is untrusted input.
    pub fn from_json(text: &str) -> Result<Self, ResultsError> {
        if text.len() > MAX_FILE_BYTES {
            return Err(ResultsError::TooLarge(text.len()));
        }
        let head: SchemaOnly = serde_json::from_str(text)?;
        let results = match head.schema.as_deref() {
            Some(SCHEMA) => serde_json::from_str(text)?,
            Some(SCHEMA_V2) => {
                let mut results: Results = serde_json::from_str(text)?;
                results.schema = SCHEMA.to_string();
                results
            }
            Some(v1::SCHEMA) => serde_json::from_str::<v1::Results>(text)?.upgrade()?,
            Some(other) => return Err(ResultsError::Schema(truncated(other))),
            None => return Err(ResultsError::Schema("(none)".to_string())),
        };
        results.validate()?;
        Ok(results)
    }
}

impl Results {
    /// Reads and validates the results file at `path` ([`Results::from_json`]); at
    /// most [`MAX_FILE_BYTES`] are read, whatever the file's size.
    pub fn read_file(path: &Path) -> Result<Self, FileError> {
        let read = || -> Result<Self, ResultsError> {
            let mut text = String::new();
            std::fs::File::open(path)?
                .take(MAX_FILE_BYTES as u64 + 1)
                .read_to_string(&mut text)?;
            Self::from_json(&text)
        };
        read().map_err(|error| FileError {
            path: path.to_path_buf(),
            error,
        })
    }
}
