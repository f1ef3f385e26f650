//! Ctrl-C for long commands (the suite, a render, a profile): the first Ctrl-C asks the
//! command to stop; renders read the flag before each sample row, so it takes effect
//! within a row's time, and the command discards its partial outputs and leaves the
//! previous ones intact; a second Ctrl-C exits at once (outputs are written to a
//! temporary file and renamed, so even then nothing is left half-written).
//!
//! Only commands that check the flag [`install`] returns install the handler; the
//! others keep the default Ctrl-C behaviour.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Installs the handler (once per process; later calls do nothing) and returns the
/// flag it sets, for the runner to check.
pub fn install() -> &'static AtomicBool {
    // An error means a handler is already installed, which is what we want.
    let _ = ctrlc::set_handler(|| {
        if REQUESTED.swap(true, Ordering::SeqCst) {
            eprintln!("\nrtprof: interrupted again; exiting now");
            std::process::exit(130);
        }
        eprintln!("\nrtprof: interrupted; stopping (Ctrl-C again to exit now)");
    });
    &REQUESTED
}
