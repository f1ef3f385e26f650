//! How a program ended, as data: its exit code, the signal that killed it, or that the
//! caller stopped it (time limit, Ctrl-C); with its wall and CPU time.

use std::time::Duration;

/// The end of a program's run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum End {
    /// It exited by itself with this code (0: success).
    Exited(i32),
    /// A signal it did not catch killed it (a crash, or `kill` from outside).
    Signalled(i32),
    /// It ran past the time limit and was stopped.
    TimedOut,
    /// The caller's stop flag was set (Ctrl-C) and it was stopped.
    Stopped,
}

impl End {
    /// It ran to its end and said it succeeded.
    pub fn success(&self) -> bool {
        *self == End::Exited(0)
    }
}

impl std::fmt::Display for End {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            End::Exited(code) => write!(f, "exited with code {code}"),
            End::Signalled(signal) => write!(f, "was killed by signal {}", signal_name(*signal)),
            End::TimedOut => f.write_str("ran past its time limit and was stopped"),
            End::Stopped => f.write_str("was stopped (interrupted)"),
        }
    }
}

/// A program's end with what it cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Finished {
    pub end: End,
    pub wall: Duration,
    /// User + system CPU time of the program and of the processes it started and
    /// waited for (the kernel's account, `wait4`'s rusage).
    pub cpu: Duration,
}

/// `SIGSEGV (11)`, or the number alone for a signal without a usual name.
pub fn signal_name(signal: i32) -> String {
    let name = match signal {
        libc::SIGHUP => "SIGHUP",
        libc::SIGINT => "SIGINT",
        libc::SIGQUIT => "SIGQUIT",
        libc::SIGILL => "SIGILL",
        libc::SIGTRAP => "SIGTRAP",
        libc::SIGABRT => "SIGABRT",
        libc::SIGBUS => "SIGBUS",
        libc::SIGFPE => "SIGFPE",
        libc::SIGKILL => "SIGKILL",
        libc::SIGUSR1 => "SIGUSR1",
        libc::SIGSEGV => "SIGSEGV",
        libc::SIGUSR2 => "SIGUSR2",
        libc::SIGPIPE => "SIGPIPE",
        libc::SIGALRM => "SIGALRM",
        libc::SIGTERM => "SIGTERM",
        libc::SIGXCPU => "SIGXCPU",
        libc::SIGSYS => "SIGSYS",
        _ => return signal.to_string(),
    };
    format!("{name} ({signal})")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_say_what_happened() {
        assert_eq!(End::Exited(3).to_string(), "exited with code 3");
        assert_eq!(
            End::Signalled(libc::SIGSEGV).to_string(),
            "was killed by signal SIGSEGV (11)"
        );
        assert_eq!(signal_name(64), "64");
        assert!(End::Exited(0).success() && !End::Exited(1).success());
    }
}
