//! Why a reference render could not start.

/// A reference render refused before any ray is traced.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ReferenceError {
    /// The view defines no camera basis.
    #[error("invalid camera: {0}")]
    Camera(String),
    /// The image size or ray depth is outside the limits.
    #[error("{0}")]
    Limits(String),
}
