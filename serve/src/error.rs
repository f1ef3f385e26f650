//! Errors: [`ApiError`] is what a request gets back (a status code and a JSON
//! `{"error": ...}`); [`ServeError`] is why the server could not start.

use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};

/// A refused or failed request: its status code and a message saying what to do.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ApiError {
    pub status: StatusCode,
    pub message: String,
    /// The line of an NFF error, for the page to point at.
    pub line: Option<usize>,
}

impl ApiError {
    pub fn new(status: StatusCode, message: impl Into<String>) -> Self {
        ApiError {
            status,
            message: message.into(),
            line: None,
        }
    }

    /// 400: the request itself is malformed (a path outside the data directory).
    pub fn bad_request(message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, message)
    }

    /// 403: a state-changing request without this server's token, or from elsewhere.
    pub fn forbidden(message: impl Into<String>) -> Self {
        Self::new(StatusCode::FORBIDDEN, message)
    }

    /// 404: no such job or file.
    pub fn not_found(message: impl Into<String>) -> Self {
        Self::new(StatusCode::NOT_FOUND, message)
    }

    /// 409: the request conflicts with the state (cancelling a finished job).
    pub fn conflict(message: impl Into<String>) -> Self {
        Self::new(StatusCode::CONFLICT, message)
    }

    /// 422: well-formed but invalid parameters or scene.
    pub fn invalid(message: impl Into<String>) -> Self {
        Self::new(StatusCode::UNPROCESSABLE_ENTITY, message)
    }

    /// 500: the server failed (a file it could not write).
    pub fn internal(message: impl Into<String>) -> Self {
        Self::new(StatusCode::INTERNAL_SERVER_ERROR, message)
    }
}

impl std::fmt::Display for ApiError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({})", self.message, self.status)
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let mut body = serde_json::json!({ "error": self.message });
        if let Some(line) = self.line {
            body["line"] = line.into();
        }
        (self.status, Json(body)).into_response()
    }
}

/// Why the server could not start or stopped with an error.
#[derive(Debug, thiserror::Error)]
pub enum ServeError {
    #[error("cannot {action} {path}: {message}")]
    Io {
        action: &'static str,
        path: std::path::PathBuf,
        message: String,
    },
    #[error(
        "cannot listen on {address}: {message} (choose another --port, or 0 for any free port)"
    )]
    Bind { address: String, message: String },
    /// An outside tracer's definition (`--tracer FILE`, `--peers`) that cannot be used:
    /// the file, line and column, and what is wrong.
    #[error("{0}")]
    Tracer(runner::RunError),
    #[error("{0}")]
    Other(String),
}

impl ServeError {
    pub fn io(action: &'static str, path: &std::path::Path, e: &std::io::Error) -> Self {
        ServeError::Io {
            action,
            path: path.to_path_buf(),
            message: e.to_string(),
        }
    }
}
