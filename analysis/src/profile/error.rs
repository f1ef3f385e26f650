//! Why a profile could not be taken: the errors of the sampler and of one sampling
//! run.

use std::time::Duration;

/// Why a profile could not be taken.
#[derive(Debug, thiserror::Error)]
pub enum ProfileError {
    #[error("cannot start the sampling profiler: {0}")]
    Start(String),
    #[error("cannot build the profile report: {0}")]
    Report(String),
    #[error(
        "no samples were taken: the profiled work ran for only {0:?}; give it more work (e.g. a larger --size)"
    )]
    NoSamples(Duration),
    #[error("another sampling run is under way in this process (one at a time)")]
    Busy,
}

/// Why a repeated sampling run failed: the profiler, or one run of the work.
#[derive(Debug, thiserror::Error)]
pub enum RepeatedError<E> {
    #[error(transparent)]
    Profile(ProfileError),
    #[error("run {run} of the sampled work failed: {error}")]
    Work { run: u64, error: E },
}
