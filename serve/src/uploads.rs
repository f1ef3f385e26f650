//! Uploaded NFF scenes: checked with the tracer's own parser and limits (an error names
//! the line), kept as `scenes/NAME.nff` in the data directory, named by the user with
//! a plain name (never a path).

use axum::http::StatusCode;
use tracer::Limits;

use crate::catalogue::{Catalogue, SceneEntry, UPLOAD_PREFIX, check_name};
use crate::error::ApiError;

/// Checks `bytes` as the NFF scene `name` and keeps it. Refused: a bad name (422), a
/// name already taken (409: uploads are never replaced, since earlier jobs name them),
/// a body that is not UTF-8 text or does not parse within the default limits (422,
/// with the line).
pub fn save(catalogue: &Catalogue, name: &str, bytes: &[u8]) -> Result<SceneEntry, ApiError> {
    check_name(name)?;
    let file = format!("{name}.nff");
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        ApiError {
            line: Some(line),
            ..ApiError::invalid(format!(
                "{file}:{line}: not a text file (invalid UTF-8); NFF scenes are plain ASCII"
            ))
        }
    })?;
    let scene =
        tracer::nff::parse_nff_with_limits(text, &file, &Limits::default()).map_err(|e| {
            ApiError {
                line: Some(e.line),
                ..ApiError::invalid(e.to_string())
            }
        })?;
    let path = catalogue.upload_path(name);
    if path.exists() {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!("a scene named '{name}' is already uploaded: choose another name"),
        ));
    }
    std::fs::create_dir_all(catalogue.uploads_dir())
        .and_then(|()| tracer::image_io::write_atomically(&path, bytes))
        .map_err(|e| ApiError::internal(format!("cannot keep the scene: {e}")))?;
    Ok(SceneEntry::new(
        format!("{UPLOAD_PREFIX}{name}"),
        "uploaded",
        "other".into(),
        scene.primitive_count() as u64,
    ))
}
