//! Per-thread sampling timers from `perf_event_open`: a software cpu-clock event on
//! each thread that runs the profiled work, overflowing every `1e9 / frequency` ns of
//! that thread's CPU time and sending SIGPROF to that thread (`F_SETOWN_EX` with
//! `F_OWNER_TID`, `O_ASYNC`, `F_SETSIG`). The signal is the one pprof's `setitimer`
//! sends, so the same handlers (pprof's, with the phase probe's in front) take the
//! stacks. The cpu-clock event runs on an hrtimer, not on the kernel's tick, so it
//! delivers thousands of signals a CPU second, and it needs no PMU (it works in VMs).
//!
//! The events are opened disabled, on every thread first (so that a run takes perf on
//! all threads or on none), enabled once the handlers are in place, and disabled and
//! closed at the end. Threads the caller does not name are not sampled under perf.

use std::collections::BTreeSet;
use std::os::fd::{AsRawFd, FromRawFd, OwnedFd};
use std::sync::{Mutex, PoisonError};

use perf_event_open_sys as sys;

// From <asm-generic/fcntl.h>: the libc crate does not define these for glibc targets.
const F_SETSIG: libc::c_int = 10;
const F_SETOWN_EX: libc::c_int = 15;
const F_OWNER_TID: libc::c_int = 0;

/// `struct f_owner_ex`: who gets an fd's signals.
#[repr(C)]
struct OwnerEx {
    kind: libc::c_int,
    pid: libc::pid_t,
}

/// Runs a function once on each thread that will run the profiled work (the calling
/// thread gets its event anyway), e.g. for a rayon pool
/// `&|open: &(dyn Fn() + Sync)| pool.broadcast(|_| open())`.
#[derive(Clone, Copy)]
pub struct WorkThreads<'a>(pub &'a dyn Fn(&(dyn Fn() + Sync)));

impl std::fmt::Debug for WorkThreads<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("WorkThreads(..)")
    }
}

/// Why the perf timer cannot run here.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("perf_event_open cannot sample this thread: {reason}")]
pub struct PerfUnavailable {
    pub reason: String,
}

impl PerfUnavailable {
    fn os(what: &str, error: std::io::Error) -> Self {
        let hint = match error.raw_os_error() {
            Some(libc::EACCES | libc::EPERM) => match paranoid_level() {
                Some(level) => format!(
                    " (kernel.perf_event_paranoid is {level}; a seccomp filter or a missing CAP_PERFMON also refuse it)"
                ),
                None => " (a seccomp filter or a missing CAP_PERFMON refuse it)".to_string(),
            },
            Some(libc::ENOENT | libc::EOPNOTSUPP) => {
                " (the kernel has no software cpu-clock event)".to_string()
            }
            Some(libc::ENOSYS) => " (the kernel has no perf events)".to_string(),
            _ => String::new(),
        };
        PerfUnavailable {
            reason: format!("{what}: {error}{hint}"),
        }
    }
}

/// /proc/sys/kernel/perf_event_paranoid, for the error message.
fn paranoid_level() -> Option<i32> {
    std::fs::read_to_string("/proc/sys/kernel/perf_event_paranoid")
        .ok()?
        .trim()
        .parse()
        .ok()
}

/// One thread's cpu-clock event (disabled until [`ThreadClocks::enable`]).
struct ThreadClock {
    fd: OwnedFd,
    tid: libc::pid_t,
}

/// The events of all the work's threads.
pub(crate) struct ThreadClocks {
    clocks: Vec<ThreadClock>,
}

/// Sampling period in ns of CPU time for `frequency` Hz (at least 1).
pub fn period_ns(frequency: i32) -> u64 {
    1_000_000_000 / u64::try_from(frequency).unwrap_or(1).max(1)
}

impl ThreadClocks {
    /// Opens a disabled event on the calling thread and on each of `threads`, every
    /// `period_ns` ns of the thread's CPU time, signalling `signal` to that thread. Any
    /// thread that gets none fails the whole set (the opened ones are closed).
    pub(crate) fn open(
        period_ns: u64,
        signal: libc::c_int,
        threads: Option<WorkThreads<'_>>,
    ) -> Result<Self, PerfUnavailable> {
        let opened = Mutex::new(Vec::new());
        let open_here = || {
            let clock = open_on_this_thread(period_ns, signal);
            opened
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .push(clock);
        };
        open_here();
        if let Some(WorkThreads(each)) = threads {
            each(&open_here);
        }
        let mut tids = BTreeSet::new();
        let mut clocks = Vec::new();
        for clock in opened.into_inner().unwrap_or_else(PoisonError::into_inner) {
            let clock = clock?;
            // The calling thread may be one of the pool's: one event per thread (a
            // second would double its samples); the duplicate is closed here.
            if tids.insert(clock.tid) {
                clocks.push(clock);
            }
        }
        Ok(ThreadClocks { clocks })
    }

    /// Threads with an event.
    pub(crate) fn threads(&self) -> usize {
        self.clocks.len()
    }

    /// Starts every event (the signal handlers must be in place).
    pub(crate) fn enable(&self) -> Result<(), PerfUnavailable> {
        for clock in &self.clocks {
            // SAFETY: an ioctl on an fd we own; ENABLE takes no pointer.
            if unsafe { sys::ioctls::ENABLE(clock.fd.as_raw_fd(), 0) } != 0 {
                let error = std::io::Error::last_os_error();
                self.disable();
                return Err(PerfUnavailable::os("cannot enable the event", error));
            }
        }
        Ok(())
    }

    /// Stops every event; closing them (drop) follows.
    pub(crate) fn disable(&self) {
        for clock in &self.clocks {
            // SAFETY: as in `enable`. A failure leaves an event that closing ends.
            unsafe { sys::ioctls::DISABLE(clock.fd.as_raw_fd(), 0) };
        }
    }
}

impl Drop for ThreadClocks {
    fn drop(&mut self) {
        // Disabled before the fds close, so no signal of ours follows the run's end.
        self.disable();
    }
}

/// A disabled cpu-clock event on the calling thread that sends `signal` to it every
/// `period_ns` ns of its CPU time.
fn open_on_this_thread(
    period_ns: u64,
    signal: libc::c_int,
) -> Result<ThreadClock, PerfUnavailable> {
    let mut attr = sys::bindings::perf_event_attr {
        size: std::mem::size_of::<sys::bindings::perf_event_attr>() as u32,
        type_: sys::bindings::PERF_TYPE_SOFTWARE,
        config: u64::from(sys::bindings::PERF_COUNT_SW_CPU_CLOCK),
        ..Default::default()
    };
    attr.__bindgen_anon_1.sample_period = period_ns.max(1);
    // A wakeup, and so a signal, at every overflow.
    attr.__bindgen_anon_2.wakeup_events = 1;
    attr.set_disabled(1);
    attr.set_exclude_hv(1);
    // Kernel time counts like setitimer's ITIMER_PROF (the signal lands on the user
    // code that made the call); where the paranoia level forbids it, user time only.
    let mut fd = perf_event_open(&mut attr);
    if fd
        .as_ref()
        .is_err_and(|e| matches!(e.raw_os_error(), Some(libc::EACCES | libc::EPERM)))
    {
        attr.set_exclude_kernel(1);
        fd = perf_event_open(&mut attr);
    }
    let fd = fd.map_err(|e| PerfUnavailable::os("perf_event_open", e))?;
    // SAFETY: gettid has no preconditions.
    let tid = unsafe { libc::gettid() };
    let owner = OwnerEx {
        kind: F_OWNER_TID,
        pid: tid,
    };
    let raw = fd.as_raw_fd();
    // SAFETY: fcntls on an fd we own; F_SETOWN_EX reads a `struct f_owner_ex`, which
    // `owner` is and which outlives the call.
    let set = |result: libc::c_int, what: &str| {
        if result == -1 {
            Err(PerfUnavailable::os(what, std::io::Error::last_os_error()))
        } else {
            Ok(result)
        }
    };
    set(
        unsafe { libc::fcntl(raw, F_SETOWN_EX, &owner as *const OwnerEx) },
        "F_SETOWN_EX",
    )?;
    // SAFETY: as above; F_SETSIG takes a signal number.
    set(unsafe { libc::fcntl(raw, F_SETSIG, signal) }, "F_SETSIG")?;
    // SAFETY: as above.
    let flags = set(unsafe { libc::fcntl(raw, libc::F_GETFL) }, "F_GETFL")?;
    // SAFETY: as above.
    set(
        unsafe { libc::fcntl(raw, libc::F_SETFL, flags | libc::O_ASYNC) },
        "O_ASYNC",
    )?;
    Ok(ThreadClock { fd, tid })
}

/// The system call for the calling thread on any CPU, close-on-exec.
fn perf_event_open(attr: &mut sys::bindings::perf_event_attr) -> std::io::Result<OwnedFd> {
    // SAFETY: `attr` is a complete perf_event_attr with its size set; pid 0 and cpu -1
    // name the calling thread on any CPU; no group.
    let fd = unsafe {
        sys::perf_event_open(attr, 0, -1, -1, sys::bindings::PERF_FLAG_FD_CLOEXEC.into())
    };
    if fd < 0 {
        return Err(std::io::Error::last_os_error());
    }
    // SAFETY: a new fd that nothing else owns.
    Ok(unsafe { OwnedFd::from_raw_fd(fd) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_period_is_a_billion_ns_over_the_frequency() {
        assert_eq!(period_ns(4000), 250_000);
        assert_eq!(period_ns(1000), 1_000_000);
        assert_eq!(period_ns(3), 333_333_333);
        // Nonsense rates do not divide by zero.
        assert_eq!(period_ns(0), 1_000_000_000);
        assert_eq!(period_ns(-5), 1_000_000_000);
    }
}
