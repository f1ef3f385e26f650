//! `rtprof-probe`: exact counts and phase times from inside a Rust ray tracer, for
//! `rtprof record`. The Rust twin of the C/C++ header `rtprof.h` (shipped with this
//! crate): the same ids, the same semantics, the same output file.
//!
//! ```
//! use rtprof_probe::{Counter, Phase, count, phase};
//!
//! const REFITS: Counter = Counter::user(0);
//! rtprof_probe::declare_counter(REFITS, "bvh refits");
//!
//! let _shading = phase(Phase::SHADING); // ends when dropped; phases nest
//! count(Counter::RAYS_SHADOW, 1);
//! count(REFITS, 1);
//! ```
//!
//! Off unless the environment variable [`ENV_FILE`] names the file to write (rtprof
//! sets it): every call is then one relaxed load of a global flag and one predictable
//! branch. Without the default feature `enabled`, every call compiles to nothing.
//!
//! When on, counters are per thread (each thread adds only to its own block,
//! registered once), summed at exit and on SIGINT or SIGTERM, and written to a
//! temporary file renamed over the named one. Phase times come from a per-thread
//! CPU-time timer whose SIGPROF handler reads the thread's phase stack ([`ENV_HZ`]
//! samples per CPU second, default 1000, 0 = no phases). The recorder runs on Linux with
//! glibc (x86-64, AArch64); elsewhere it stays off.
//!
//! [`format`](mod@format) is the file format's one home: the writers' lines and the reader
//! ([`format::read_file`], [`format::parse`]), which refuses a truncated or hostile file
//! with the line and byte of the fault and never panics.

#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod format;
mod ids;

pub use format::{ENV_FILE, ENV_HZ, FORMAT_LINE, ProbeFile};
pub use ids::{COUNTER_KEYS, PHASE_NAMES};

#[cfg(all(
    feature = "enabled",
    target_os = "linux",
    target_env = "gnu",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]
mod runtime;
#[cfg(all(
    feature = "enabled",
    target_os = "linux",
    target_env = "gnu",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]
mod sys;

/// The recorder's entry points, or nothing where it does not run.
#[cfg(not(all(
    feature = "enabled",
    target_os = "linux",
    target_env = "gnu",
    any(target_arch = "x86_64", target_arch = "aarch64")
)))]
mod runtime {
    #[inline(always)]
    pub(crate) fn enabled() -> bool {
        false
    }
    #[inline(always)]
    pub(crate) fn count(_: u16, _: u64) {}
    #[inline(always)]
    pub(crate) fn phase_begin(_: u8) {}
    #[inline(always)]
    pub(crate) fn phase_end(_: u8) {}
    pub(crate) fn declare(_: bool, _: usize, _: &str) {}
    pub(crate) fn flush() {}
}

/// Number of user counter ids ([`Counter::user`]).
pub const USER_COUNTERS: u16 = 64;
/// Number of user phase ids ([`Phase::user`]).
pub const USER_PHASES: u8 = 32;

/// A counter id: a standard one (`Counter::RAYS_PRIMARY`, a row of rtprof's counter
/// table, ids 0..) or a user's ([`Counter::user`], ids 64..128), as in `rtprof.h`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Counter(u16);

impl Counter {
    /// User counter `k` (0 to 63); name it with [`declare_counter`].
    pub const fn user(k: u16) -> Counter {
        assert!(k < USER_COUNTERS, "user counters are 0 to 63");
        Counter(64 + k)
    }

    /// The id (the value of the same counter in `rtprof.h`).
    pub const fn id(self) -> u16 {
        self.0
    }

    /// A standard counter's key in rtprof's counter table (`rays.primary`).
    pub fn key(self) -> Option<&'static str> {
        COUNTER_KEYS.get(usize::from(self.0)).copied()
    }
}

/// A phase id: a standard one (`Phase::SPHERE_TEST`, ids 1..) or a user's
/// ([`Phase::user`], ids 32..64), as in `rtprof.h`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Phase(u8);

impl Phase {
    /// User phase `k` (0 to 31); name it with [`declare_phase`].
    pub const fn user(k: u8) -> Phase {
        assert!(k < USER_PHASES, "user phases are 0 to 31");
        Phase(32 + k)
    }

    /// The id (the value of the same phase in `rtprof.h`).
    pub const fn id(self) -> u8 {
        self.0
    }

    /// A standard phase's name (`sphere test`).
    pub fn name(self) -> Option<&'static str> {
        PHASE_NAMES
            .get(usize::from(self.0).wrapping_sub(1))
            .copied()
    }
}

/// Whether the probe records (reads the environment on the first call).
#[inline(always)]
pub fn enabled() -> bool {
    runtime::enabled()
}

/// Adds `n` to counter `id` on the calling thread.
#[inline(always)]
pub fn count(id: Counter, n: u64) {
    runtime::count(id.0, n);
}

/// Enters phase `id` on the calling thread (phases nest; end it with [`phase_end`]).
#[inline(always)]
pub fn phase_begin(id: Phase) {
    runtime::phase_begin(id.0);
}

/// Leaves phase `id`, the innermost one (a mismatch is counted as `unbalanced`).
#[inline(always)]
pub fn phase_end(id: Phase) {
    runtime::phase_end(id.0);
}

/// Enters phase `id` until the returned guard is dropped.
#[inline(always)]
pub fn phase(id: Phase) -> PhaseScope {
    phase_begin(id);
    PhaseScope(id)
}

/// Runs `f` in phase `id`.
#[inline(always)]
pub fn in_phase<R>(id: Phase, f: impl FnOnce() -> R) -> R {
    let _scope = phase(id);
    f()
}

/// A phase that ends when dropped ([`phase`]).
#[must_use = "the phase ends when the scope is dropped"]
#[derive(Debug)]
pub struct PhaseScope(Phase);

impl Drop for PhaseScope {
    #[inline(always)]
    fn drop(&mut self) {
        phase_end(self.0);
    }
}

/// Names user counter `id` in the output (at most 63 bytes; any time, any thread).
pub fn declare_counter(id: Counter, name: &str) {
    if let Some(index) = id.0.checked_sub(64) {
        runtime::declare(true, usize::from(index), name);
    }
}

/// Names user phase `id` in the output.
pub fn declare_phase(id: Phase, name: &str) {
    if let Some(index) = id.0.checked_sub(32) {
        runtime::declare(false, usize::from(index), name);
    }
}

/// Writes the file now and never again (for a program that ends by `_exit` or
/// `abort`; a normal exit writes it anyway).
pub fn flush() {
    runtime::flush();
}
