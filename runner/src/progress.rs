//! Progress of long work, reported to whoever runs it (the binary draws bars on
//! stderr; tests and a future web UI observe the same calls). The runner itself
//! prints nothing.

/// What the timing loop's own count counts ([`Progress::within`]).
pub const TIMED: &str = "timed renders";
/// What the sampler's own count counts.
pub const SAMPLES: &str = "samples";

/// Receives progress. Every method has a do-nothing default.
pub trait Progress: Sync {
    /// A stage of `total` steps begins (`total` 0: a spinner of unknown length).
    fn begin(&self, _stage: &str, _total: u64) {}
    /// What is being done now.
    fn message(&self, _text: &str) {}
    /// `steps` more steps of the stage are done.
    fn advance(&self, _steps: u64) {}
    /// The work the last message named is `done` of `total` `what` along ("timed
    /// renders", "samples"): its own count, finer than the stage's steps. `total` may
    /// be revised as the work learns how much it needs (more renders for a fast
    /// scene); `done` never goes back, and the last call of a finished piece of work
    /// has `done == total`. A new message starts other work.
    fn within(&self, _what: &str, _done: u64, _total: u64) {}
    /// The stage is over.
    fn end(&self) {}
    /// Something the user should know (e.g. a render repeated to gather samples).
    fn note(&self, _text: &str) {}
}

/// Progress nobody watches.
pub struct Silent;

impl Progress for Silent {}
