//! A program held just before its `exec`: forked, its process id known, waiting on a
//! pipe. A profiler attaches to that id (its events follow the `exec` and are
//! inherited by the threads and processes the program starts), then the program is
//! released and runs as itself, a child of the caller: its exit status and CPU time
//! are the caller's to read, not the profiler's.
//!
//! std's spawn returns only once the `exec` happened (it reports exec errors through a
//! pipe of its own), so it runs on a thread while the forked child, in `pre_exec`,
//! sends its id and blocks reading the release pipe.

use std::os::fd::{AsRawFd, FromRawFd, OwnedFd};
use std::os::unix::process::CommandExt;
use std::process::Child;
use std::thread::JoinHandle;

use crate::{Launch, LaunchError, Running};

/// A forked program waiting to `exec` ([`Launch::start_held`]).
#[derive(Debug)]
pub struct Held {
    pid: u32,
    name: String,
    time_limit: Option<std::time::Duration>,
    release: OwnedFd,
    spawn: JoinHandle<std::io::Result<Child>>,
}

fn pipe() -> Result<(OwnedFd, OwnedFd), std::io::Error> {
    let mut fds = [0; 2];
    // SAFETY: fds is a two-int array, as pipe2 wants.
    if unsafe { libc::pipe2(fds.as_mut_ptr(), libc::O_CLOEXEC) } != 0 {
        return Err(std::io::Error::last_os_error());
    }
    // SAFETY: both descriptors were just opened and are owned by nobody else.
    Ok(unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) })
}

impl Launch {
    /// Forks the program and holds it before its `exec` until [`Held::release`].
    pub fn start_held(&self) -> Result<Held, LaunchError> {
        let name = self.name();
        let start_error = |e: std::io::Error| LaunchError::Start {
            program: name.clone(),
            message: e.to_string(),
        };
        let (mut command, _) = self.command()?;
        let (pid_read, pid_write) = pipe().map_err(start_error)?;
        let (release_read, release_write) = pipe().map_err(start_error)?;
        let (pid_w, release_r) = (pid_write.as_raw_fd(), release_read.as_raw_fd());
        let (pid_r, release_w) = (pid_read.as_raw_fd(), release_write.as_raw_fd());
        // SAFETY: between fork and exec the closure makes only async-signal-safe
        // calls (close, getpid, write, read) on descriptors that stay open in the
        // child until its exec (they are close-on-exec).
        unsafe {
            command.pre_exec(move || {
                // The parent's ends: the release pipe must see end-of-file when the
                // parent drops its writer, so the child holds no writer of its own.
                libc::close(release_w);
                libc::close(pid_r);
                let pid = libc::getpid().to_ne_bytes();
                libc::write(pid_w, pid.as_ptr().cast(), pid.len());
                let mut byte = 0u8;
                if libc::read(release_r, (&raw mut byte).cast(), 1) == 1 {
                    Ok(())
                } else {
                    Err(std::io::Error::from_raw_os_error(libc::ECANCELED))
                }
            });
        }
        // The child's ends stay open here until the fork is done (closed earlier,
        // their numbers could be reused before the fork); after it, a failed spawn
        // closes the id pipe's last writer, which the read below sees.
        let spawn = std::thread::spawn(move || {
            let spawned = command.spawn();
            drop((pid_write, release_read));
            spawned
        });
        let mut pid = [0u8; 4];
        let mut file = std::fs::File::from(pid_read);
        if std::io::Read::read_exact(&mut file, &mut pid).is_err() {
            // The fork itself failed: the spawn thread has the error.
            let e = match spawn.join() {
                Ok(Err(e)) => LaunchError::from_spawn(&name, &e),
                _ => start_error(std::io::Error::other("the program never started")),
            };
            return Err(e);
        }
        let pid = u32::try_from(i32::from_ne_bytes(pid)).map_err(|_| {
            start_error(std::io::Error::other(
                "the forked child sent a bad process id",
            ))
        })?;
        Ok(Held {
            pid,
            name,
            time_limit: self.time_limit,
            release: release_write,
            spawn,
        })
    }
}

impl Held {
    /// The process id the program will run under.
    pub fn pid(&self) -> u32 {
        self.pid
    }

    /// Lets it `exec` and run.
    pub fn release(self) -> Result<Running, LaunchError> {
        let mut file = std::fs::File::from(self.release);
        let wrote = std::io::Write::write_all(&mut file, &[1]);
        drop(file);
        let spawned = self.spawn.join().map_err(|_| LaunchError::Start {
            program: self.name.clone(),
            message: "the thread starting it panicked".into(),
        })?;
        match (wrote, spawned) {
            (_, Err(e)) => Err(LaunchError::from_spawn(&self.name, &e)),
            (Err(e), Ok(_)) => Err(LaunchError::Start {
                program: self.name,
                message: e.to_string(),
            }),
            (Ok(()), Ok(child)) => Ok(Running::new(child.id(), self.name, self.time_limit)),
        }
    }

    /// Ends it without running it (the profiler could not attach): the child sees
    /// the release pipe close and exits before its `exec`.
    pub fn abandon(self) {
        drop(self.release);
        if let Ok(Ok(mut child)) = self.spawn.join() {
            // Not expected (no exec without a release), but never leave it running.
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{End, Launch, Stream};
    use std::sync::atomic::AtomicBool;

    #[test]
    fn a_held_program_runs_only_when_released_with_the_pid_it_had() {
        let dir = std::env::temp_dir().join(format!("launch-held-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("pid.txt");
        let mut l = Launch::new("sh", ["-c", "echo $$"]);
        l.stdout = Stream::File(out.clone());
        let held = l.start_held().unwrap();
        let pid = held.pid();
        std::thread::sleep(std::time::Duration::from_millis(50));
        assert_eq!(
            std::fs::read_to_string(&out).unwrap(),
            "",
            "ran before release"
        );
        let done = held
            .release()
            .unwrap()
            .wait(&AtomicBool::new(false))
            .unwrap();
        assert_eq!(done.end, End::Exited(0));
        assert_eq!(
            std::fs::read_to_string(&out).unwrap().trim(),
            pid.to_string()
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_abandoned_program_never_runs() {
        let dir = std::env::temp_dir().join(format!("launch-abandon-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let marker = dir.join("ran");
        let l = Launch::new("touch", [marker.as_os_str()]);
        l.start_held().unwrap().abandon();
        assert!(!marker.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
