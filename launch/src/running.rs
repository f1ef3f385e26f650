//! A started program, waited for with `wait4` (std's wait gives no CPU time) under a
//! time limit and a stop flag: past either it gets SIGTERM, and SIGKILL if it has not
//! ended after a grace period.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::{End, Finished, LaunchError};

/// How often the wait looks at the flag and the clock: short beside any run worth
/// profiling, long enough to cost nothing.
const POLL: Duration = Duration::from_millis(5);
/// Time a stopped program gets to end on SIGTERM before SIGKILL.
const GRACE: Duration = Duration::from_secs(2);

/// A program that was started and has not been waited for.
#[derive(Debug)]
pub struct Running {
    pid: u32,
    name: String,
    time_limit: Option<Duration>,
    started: Instant,
}

impl Running {
    pub(crate) fn new(pid: u32, name: String, time_limit: Option<Duration>) -> Self {
        Running {
            pid,
            name,
            time_limit,
            started: Instant::now(),
        }
    }

    /// Its process id (it stays its own until [`Running::wait`] reaps it).
    pub fn pid(&self) -> u32 {
        self.pid
    }

    /// Sends `signal` to it. The process has not been reaped, so the id is still its.
    pub fn signal(&self, signal: i32) {
        let Ok(pid) = libc::pid_t::try_from(self.pid) else {
            return;
        };
        // SAFETY: kill has no memory effects; the pid is our unreaped child's.
        unsafe { libc::kill(pid, signal) };
    }

    /// Its end if it has ended (reaped then), without waiting; `None` while it runs.
    pub fn poll(&self) -> Result<Option<Finished>, LaunchError> {
        let pid = libc::pid_t::try_from(self.pid).map_err(|_| self.wait_error("bad pid"))?;
        self.reap(pid, None)
    }

    /// Reaps it if it has ended; `asked` is why the caller stopped it, if it did.
    fn reap(&self, pid: libc::pid_t, asked: Option<&End>) -> Result<Option<Finished>, LaunchError> {
        let mut status = 0;
        // SAFETY: an all-zero rusage is valid; wait4 writes into it.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        // SAFETY: pointers to live locals; WNOHANG returns at once.
        let got = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        if got == pid {
            let end = match asked {
                Some(why) => why.clone(),
                None if libc::WIFSIGNALED(status) => End::Signalled(libc::WTERMSIG(status)),
                None => End::Exited(libc::WEXITSTATUS(status)),
            };
            return Ok(Some(Finished {
                end,
                wall: self.started.elapsed(),
                cpu: cpu_time(&usage),
            }));
        }
        if got < 0 {
            let e = std::io::Error::last_os_error();
            if e.kind() != std::io::ErrorKind::Interrupted {
                return Err(self.wait_error(&e.to_string()));
            }
        }
        Ok(None)
    }

    /// Asks it to stop as Ctrl-C would (SIGINT).
    pub fn interrupt(&self) {
        self.signal(libc::SIGINT);
    }

    /// Kills it (SIGKILL).
    pub fn kill(&self) {
        self.signal(libc::SIGKILL);
    }

    /// Waits for it to end. When `stop` is set or the time limit passes, it is asked
    /// to end (SIGTERM), then killed (SIGKILL) after a grace period; its end then
    /// says why ([`End::Stopped`], [`End::TimedOut`]).
    pub fn wait(self, stop: &AtomicBool) -> Result<Finished, LaunchError> {
        let pid = libc::pid_t::try_from(self.pid).map_err(|_| self.wait_error("bad pid"))?;
        let mut asked: Option<(End, Instant)> = None;
        loop {
            let why = match &asked {
                Some((why, _)) => Some(why.clone()),
                None => stop.load(Ordering::Relaxed).then_some(End::Stopped),
            };
            if let Some(mut done) = self.reap(pid, why.as_ref())? {
                // The terminal's Ctrl-C reaches the program and us at once; it may die
                // of it before our handler has set the flag: it was stopped all the same.
                if why.is_none()
                    && done.end == End::Signalled(libc::SIGINT)
                    && flag_within(stop, HANDLER_DELAY)
                {
                    done.end = End::Stopped;
                }
                return Ok(done);
            }
            match &asked {
                None => {
                    let why = if stop.load(Ordering::Relaxed) {
                        Some(End::Stopped)
                    } else if self.time_limit.is_some_and(|t| self.started.elapsed() > t) {
                        Some(End::TimedOut)
                    } else {
                        None
                    };
                    if let Some(why) = why {
                        self.signal(libc::SIGTERM);
                        asked = Some((why, Instant::now()));
                    }
                }
                Some((_, since)) if since.elapsed() > GRACE => self.signal(libc::SIGKILL),
                Some(_) => {}
            }
            std::thread::sleep(POLL);
        }
    }

    fn wait_error(&self, message: &str) -> LaunchError {
        LaunchError::Wait {
            program: self.name.clone(),
            message: message.to_string(),
        }
    }
}

/// Longest our SIGINT handler may lag behind the program's death by the same signal.
const HANDLER_DELAY: Duration = Duration::from_millis(500);

/// Whether `flag` is set now or becomes set within `limit`.
fn flag_within(flag: &AtomicBool, limit: Duration) -> bool {
    let start = Instant::now();
    loop {
        if flag.load(Ordering::Relaxed) {
            return true;
        }
        if start.elapsed() >= limit {
            return false;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn cpu_time(usage: &libc::rusage) -> Duration {
    let tv = |t: libc::timeval| {
        Duration::from_secs(u64::try_from(t.tv_sec).unwrap_or(0))
            + Duration::from_micros(u64::try_from(t.tv_usec).unwrap_or(0))
    };
    tv(usage.ru_utime) + tv(usage.ru_stime)
}

#[cfg(test)]
mod tests {
    use crate::{End, Launch, Stream};
    use std::sync::atomic::AtomicBool;
    use std::time::Duration;

    fn sh(script: &str) -> Launch {
        let mut l = Launch::new("sh", ["-c", script]);
        l.stdout = Stream::Null;
        l
    }

    #[test]
    fn exit_codes_and_signals_are_reported() {
        let stop = AtomicBool::new(false);
        let done = sh("exit 3").start().unwrap().wait(&stop).unwrap();
        assert_eq!(done.end, End::Exited(3));
        let done = sh("kill -SEGV $$").start().unwrap().wait(&stop).unwrap();
        assert_eq!(done.end, End::Signalled(libc::SIGSEGV));
    }

    #[test]
    fn a_program_killed_by_sigint_as_the_flag_is_set_was_stopped() {
        // The flag set 50 ms after the program died of SIGINT (our handler running
        // late): stopped. Never set: killed by the signal.
        let stop = AtomicBool::new(false);
        let done = std::thread::scope(|scope| {
            let running = sh("kill -INT $$").start().unwrap();
            scope.spawn(|| {
                std::thread::sleep(Duration::from_millis(150));
                stop.store(true, std::sync::atomic::Ordering::Relaxed);
            });
            std::thread::sleep(Duration::from_millis(100));
            running.wait(&stop).unwrap()
        });
        assert_eq!(done.end, End::Stopped);
        let unset = AtomicBool::new(false);
        let done = sh("kill -INT $$").start().unwrap().wait(&unset).unwrap();
        assert_eq!(done.end, End::Signalled(libc::SIGINT));
    }

    #[test]
    fn cpu_time_of_a_busy_child_is_measured() {
        let stop = AtomicBool::new(false);
        let busy = "i=0; while [ $i -lt 200000 ]; do i=$((i+1)); done";
        let done = sh(busy).start().unwrap().wait(&stop).unwrap();
        assert!(done.end.success());
        assert!(done.cpu > Duration::from_millis(20), "{:?}", done.cpu);
        assert!(
            done.cpu <= done.wall + Duration::from_millis(20),
            "{done:?}"
        );
    }

    #[test]
    fn a_time_limit_and_the_stop_flag_end_the_program() {
        let stop = AtomicBool::new(false);
        let mut slow = sh("sleep 5");
        slow.time_limit = Some(Duration::from_millis(100));
        let done = slow.start().unwrap().wait(&stop).unwrap();
        assert_eq!(done.end, End::TimedOut);
        assert!(done.wall < Duration::from_secs(3), "{:?}", done.wall);
        let stopped = AtomicBool::new(true);
        let done = sh("sleep 5").start().unwrap().wait(&stopped).unwrap();
        assert_eq!(done.end, End::Stopped);
    }

    #[test]
    fn a_missing_program_is_named() {
        let err = Launch::new("rtprof-no-such-command", ["x"])
            .start()
            .unwrap_err();
        assert_eq!(err.to_string(), "command not found: rtprof-no-such-command");
    }
}
