//! Why building the Embree scene failed: Embree's error codes, the crate's error type,
//! and the error callback that keeps Embree's message for it.

use std::ffi::{CStr, c_char, c_void};
use std::sync::Mutex;

use super::ffi::*;

/// An Embree error code (`enum RTCError`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EmbreeCode {
    Unknown,
    InvalidArgument,
    InvalidOperation,
    OutOfMemory,
    UnsupportedCpu,
    Cancelled,
    /// A code this version of the bindings does not know.
    Other(u32),
}

impl EmbreeCode {
    pub(super) fn from_raw(code: u32) -> Self {
        match code {
            RTC_ERROR_INVALID_ARGUMENT => Self::InvalidArgument,
            RTC_ERROR_INVALID_OPERATION => Self::InvalidOperation,
            RTC_ERROR_OUT_OF_MEMORY => Self::OutOfMemory,
            RTC_ERROR_UNSUPPORTED_CPU => Self::UnsupportedCpu,
            RTC_ERROR_CANCELLED => Self::Cancelled,
            RTC_ERROR_UNKNOWN => Self::Unknown,
            other => Self::Other(other),
        }
    }
}

impl std::fmt::Display for EmbreeCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Unknown => write!(f, "unknown error"),
            Self::InvalidArgument => write!(f, "invalid argument"),
            Self::InvalidOperation => write!(f, "invalid operation"),
            Self::OutOfMemory => write!(f, "out of memory"),
            Self::UnsupportedCpu => write!(
                f,
                "this CPU lacks the instruction set this Embree build needs (SSE2 or better)"
            ),
            Self::Cancelled => write!(f, "cancelled"),
            Self::Other(code) => write!(f, "error code {code}"),
        }
    }
}

/// Why the Embree scene could not be built.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EmbreeError {
    #[error("could not create the Embree device: {0}")]
    Device(EmbreeCode),
    #[error("Embree failed while {step}: {code}{}", detail(.message))]
    Call {
        /// What the intersector was doing, e.g. "building the scene".
        step: &'static str,
        code: EmbreeCode,
        /// The text Embree's error callback gave, when it gave one.
        message: Option<String>,
    },
    #[error("{count} {what} exceed Embree's 32-bit primitive ids")]
    TooMany { what: &'static str, count: usize },
}

fn detail(message: &Option<String>) -> String {
    message
        .as_deref()
        .map(|m| format!(" ({m})"))
        .unwrap_or_default()
}

/// The first message of Embree's error callback since it was last read.
#[derive(Debug, Default)]
pub(super) struct ErrorLog(Mutex<Option<String>>);

impl ErrorLog {
    pub(super) fn take(&self) -> Option<String> {
        self.0.lock().ok().and_then(|mut m| m.take())
    }
}

/// Embree's error callback: keeps the first message. It may run on Embree's worker
/// threads during a commit, hence the mutex.
pub(super) unsafe extern "C" fn on_error(
    user_ptr: *mut c_void,
    _code: u32,
    message: *const c_char,
) {
    if user_ptr.is_null() || message.is_null() {
        return;
    }
    // SAFETY: `user_ptr` is the `ErrorLog` registered with the device, alive until the
    // device is released; `message` is a NUL-terminated string Embree owns for the call.
    let (log, text) = unsafe {
        (
            &*(user_ptr as *const ErrorLog),
            CStr::from_ptr(message).to_string_lossy(),
        )
    };
    if let Ok(mut slot) = log.0.lock() {
        slot.get_or_insert_with(|| text.into_owned());
    }
}
