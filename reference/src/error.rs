//! Why a reference render could not start, or did not finish.

/// A reference render refused before any ray is traced, or stopped on request.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ReferenceError {
    /// The view defines no camera basis.
    #[error("invalid camera: {0}")]
    Camera(String),
    /// The image size or ray depth is outside the limits.
    #[error("{0}")]
    Limits(tracer::LimitError),
    /// The stop flag was set during the render: no frame is returned.
    #[error("cancelled: the render was stopped on request before it finished")]
    Cancelled,
}
