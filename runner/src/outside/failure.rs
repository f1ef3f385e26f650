//! Why an outside tracer's run failed, as data results and tables keep: the kind, one
//! line of reason, and the last lines of the program's standard error.

use serde::{Deserialize, Serialize};

/// Why a run failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FailureKind {
    /// The program is not there, or cannot be run.
    NotFound,
    /// It exited with a code other than 0.
    Exited,
    /// A signal killed it.
    Killed,
    /// It ran past its time limit.
    TimedOut,
    /// It wrote no image.
    NoImage,
    /// Its image cannot be read (truncated, or not the format its definition says).
    BadImage,
    /// Its image is not the size asked.
    WrongSize,
    /// Its time is not where its definition says (no match of the pattern, no probe).
    NoTime,
    /// Its scene file could not be written, or the run's directory made.
    Setup,
}

/// A failed run: why, in one line, and the last lines of the program's standard error.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, thiserror::Error)]
#[error("{reason}")]
pub struct Failure {
    pub kind: FailureKind,
    pub reason: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stderr_tail: Vec<String>,
}

impl Failure {
    pub(crate) fn new(kind: FailureKind, reason: impl Into<String>) -> Self {
        Failure {
            kind,
            reason: reason.into(),
            stderr_tail: Vec::new(),
        }
    }

    /// The reason and the standard error's tail, as a message prints them.
    pub fn describe(&self) -> String {
        let mut out = self.reason.clone();
        if !self.stderr_tail.is_empty() {
            out += "; its standard error ended:";
            for line in &self.stderr_tail {
                out += "\n    ";
                out += line;
            }
        }
        out
    }
}
