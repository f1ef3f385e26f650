//! Why a program could not be run, naming it.

use std::path::PathBuf;

/// A program that could not be started or waited for.
#[derive(Debug, thiserror::Error)]
pub enum LaunchError {
    #[error("command not found: {program}")]
    NotFound { program: String },
    #[error("cannot run {program}: {reason}")]
    NotExecutable { program: String, reason: String },
    #[error("cannot start {program}: {message}")]
    Start { program: String, message: String },
    #[error("cannot open {} for {program}'s output: {message}", path.display())]
    Output {
        program: String,
        path: PathBuf,
        message: String,
    },
    #[error("waiting for {program} failed: {message}")]
    Wait { program: String, message: String },
}

impl LaunchError {
    /// std's spawn error, as one of ours.
    pub(crate) fn from_spawn(program: &str, e: &std::io::Error) -> Self {
        let program = program.to_string();
        match e.kind() {
            std::io::ErrorKind::NotFound => LaunchError::NotFound { program },
            std::io::ErrorKind::PermissionDenied => LaunchError::NotExecutable {
                program,
                reason: "permission denied".into(),
            },
            _ if e.raw_os_error() == Some(libc::ENOEXEC) => LaunchError::NotExecutable {
                program,
                reason: "not a program this system can run (exec format error)".into(),
            },
            _ => LaunchError::Start {
                program,
                message: e.to_string(),
            },
        }
    }
}
