//! How a command ends when it neither succeeds nor meets bad input: its exit code and
//! message.

/// An end that is neither success nor bad input (exit 2), with its exit code.
#[derive(Debug)]
pub struct Outcome {
    pub exit_code: u8,
    pub message: String,
}

impl Outcome {
    /// A check that ran and failed (the regression gate).
    pub const CHECK_FAILED: u8 = 1;
    /// Some parts of a suite failed; the rest was measured and written.
    pub const PARTS_FAILED: u8 = 3;
    /// Stopped by Ctrl-C: 128 + SIGINT, as a shell reports it.
    pub const INTERRUPTED: u8 = 130;

    pub fn new(exit_code: u8, message: impl Into<String>) -> Self {
        let message = message.into();
        Outcome { exit_code, message }
    }
}

impl std::fmt::Display for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Outcome {}
