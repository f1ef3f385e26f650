//! The few C library calls the runtime needs, declared here so that the crate has no
//! dependency: Linux with glibc on x86-64 and AArch64, whose structure layouts below
//! are those of `<signal.h>` and `<time.h>` there (the crate's tests exercise each).

use std::ffi::{c_char, c_int, c_long, c_void};

pub const SIGINT: c_int = 2;
pub const SIGTERM: c_int = 15;
pub const SIGPROF: c_int = 27;

pub const SA_RESTART: c_int = 0x1000_0000;
pub const SA_NODEFER: c_int = 0x4000_0000;
pub const SA_RESETHAND: c_int = 0x8000_0000_u32 as c_int;

/// `SIG_DFL`: the default action.
pub const SIG_DFL: usize = 0;

pub const CLOCK_THREAD_CPUTIME_ID: c_int = 3;
pub const SIGEV_THREAD_ID: c_int = 4;

pub const O_WRONLY: c_int = 0o1;
pub const O_CREAT: c_int = 0o100;
pub const O_TRUNC: c_int = 0o1000;
pub const O_CLOEXEC: c_int = 0o2000000;

pub const EINTR: c_int = 4;

#[cfg(target_arch = "x86_64")]
pub const SYS_GETTID: c_long = 186;
#[cfg(target_arch = "aarch64")]
pub const SYS_GETTID: c_long = 178;

/// `struct sigaction` (glibc): handler, mask (1024 bits), flags, restorer.
#[repr(C)]
pub struct SigAction {
    pub handler: usize,
    pub mask: [u64; 16],
    pub flags: c_int,
    pub restorer: usize,
}

/// `struct sigevent` (64 bytes): value, signal, notification, thread id, padding.
#[repr(C)]
pub struct SigEvent {
    pub value: usize,
    pub signo: c_int,
    pub notify: c_int,
    pub thread_id: c_int,
    pub pad: [c_int; 11],
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct Timespec {
    pub sec: i64,
    pub nsec: i64,
}

#[repr(C)]
pub struct ITimerSpec {
    pub interval: Timespec,
    pub value: Timespec,
}

unsafe extern "C" {
    pub fn sigaction(signal: c_int, act: *const SigAction, old: *mut SigAction) -> c_int;
    pub safe fn raise(signal: c_int) -> c_int;
    pub fn timer_create(clock: c_int, event: *mut SigEvent, timer: *mut *mut c_void) -> c_int;
    pub fn timer_settime(
        timer: *mut c_void,
        flags: c_int,
        new: *const ITimerSpec,
        old: *mut ITimerSpec,
    ) -> c_int;
    pub fn clock_gettime(clock: c_int, time: *mut Timespec) -> c_int;
    pub fn open(path: *const c_char, flags: c_int, ...) -> c_int;
    pub fn write(fd: c_int, buf: *const c_void, count: usize) -> isize;
    pub safe fn close(fd: c_int) -> c_int;
    pub fn rename(old: *const c_char, new: *const c_char) -> c_int;
    pub fn unlink(path: *const c_char) -> c_int;
    pub safe fn getpid() -> c_int;
    pub safe fn syscall(number: c_long, ...) -> c_long;
    pub safe fn atexit(callback: extern "C" fn()) -> c_int;
    pub safe fn __errno_location() -> *mut c_int;
}

/// The calling thread's CPU time in nanoseconds (0 if the clock fails).
pub fn thread_cpu_ns() -> u64 {
    let mut time = Timespec { sec: 0, nsec: 0 };
    // SAFETY: `time` is a valid timespec to write; async-signal-safe.
    if unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut time) } != 0 {
        return 0;
    }
    (time.sec as u64)
        .saturating_mul(1_000_000_000)
        .saturating_add(time.nsec as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_structures_have_the_c_sizes() {
        assert_eq!(std::mem::size_of::<SigAction>(), 152);
        assert_eq!(std::mem::size_of::<SigEvent>(), 64);
        assert_eq!(std::mem::size_of::<ITimerSpec>(), 32);
    }

    #[test]
    fn the_thread_clock_runs() {
        let before = thread_cpu_ns();
        let mut x = 1u64;
        for i in 0..2_000_000u64 {
            x = std::hint::black_box(x.wrapping_mul(i | 1));
        }
        assert!(thread_cpu_ns() > before, "{x}");
        assert!(syscall(SYS_GETTID) > 0);
        assert_eq!(getpid() as u32, std::process::id());
    }
}
