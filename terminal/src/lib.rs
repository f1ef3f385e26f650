//! What rtprof shows on a terminal while it works, apart from its results: progress bars
//! for the runner's long stages ([`progress`]), Ctrl-C turned into the stop flag renders
//! check ([`interrupt`]), and `RTPROF_TRACE_STARTUP`'s account of a short command's time
//! ([`startup`]), and how a command ends: its one line on stderr and its exit code
//! ([`exit`]). The binary and `serve` decide what to run; this crate only draws and
//! listens, like ripgrep's printer crate beside its thin binary.

pub mod exit;
pub mod interrupt;
pub mod progress;
pub mod startup;
